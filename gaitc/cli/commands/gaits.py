"""``gaitc gaits``: gait primitives for a robot file (thesis chapters 2, 4 and 5).

The work lives in :func:`gaitc.gaits` (:mod:`gaitc.api.gaits`); this module turns the
options into :class:`~gaitc.api.gaits.GaitOptions`, prints the result, writes the gaits file
and the drawings.
"""

from __future__ import annotations

import argparse
import sys
from typing import Any

from gaitc.cli.commands.arguments import output_file
from gaitc.cli.reporting import document, print_json


def register(subparsers: Any) -> None:
    p = subparsers.add_parser(
        "gaits",
        help="synthesise gaits for a robot description (gait graph, thesis ch. 2)",
        description="Build the gait graph of ROBOT.yaml, synthesise gaits towards a direction, "
        "print them as a table and write them as JSON.",
    )
    search_arguments(p)
    p.add_argument("-o", "--output", metavar="gaits.json", type=output_file,
                   help="write the gaits as JSON")
    p.add_argument("--svg", metavar="DIR", help="write the gait graph and pose top views here")
    p.add_argument("--json", action="store_true",
                   help="print the search and its gaits as one JSON object (docs/json.md)")
    p.set_defaults(run=run)


def search_arguments(p: argparse.ArgumentParser) -> None:
    """The robot file and search options, shared by ``gaits`` and ``render gaits``."""
    from gaitc.api.gaits import model_choices
    from gaitc.api.modes import SearchMethod
    from gaitc.cli.commands.learning import goal_arguments

    p.add_argument("robot", metavar="ROBOT.yaml")
    p.add_argument("--direction", default="+x", help="+x, -x, +y, -y or an angle in degrees")
    p.add_argument(
        "--method", choices=SearchMethod.values(), default=None,
        help="chapter 2 (default): full for at most 12 chambers and --max-states valve "
        "states, else random; astar, lpa, dstar, mcts: chapter 5 searches toward --goal")
    p.add_argument("--seed", type=int, default=0,
                   help="seed of the random and reset searches and of chapter 5's (default 0)")
    p.add_argument("--max-states", type=int, default=10_000, help="valve states to try at most")
    p.add_argument(
        "--model", choices=model_choices(),
        help="the gait graph to search: by default the chapter 4 model the robot file's "
        "'model:' section declares (thesis 4.2.2, docs/models.md), else the kinematic graph "
        "of chapter 2; 'kinematic' asks for that one whatever the file declares")
    p.add_argument("--max-open", type=int, default=1, metavar="N",
                   help="a model's gait graph: valve states with at most N valves open (1)")
    p.add_argument("--legs", metavar="L1,L2", type=_legs,
                   help="a model's gait graph: only gaits that pressurise exactly these legs, "
                   "the first one first (what a .gait primitive clause of a gait that uses "
                   "them finds)")
    goal_arguments(p)


def _legs(text: str) -> tuple[str, ...]:
    legs = tuple(leg.strip() for leg in text.split(","))
    if not all(legs):
        raise argparse.ArgumentTypeError(f"leg names separated by commas, got {text!r}")
    return legs


def options_of(args: argparse.Namespace) -> Any:
    """The :class:`~gaitc.api.gaits.GaitOptions` of ``gaits`` and ``render gaits``."""
    from gaitc.api.gaits import GaitOptions
    from gaitc.api.modes import SearchMethod
    from gaitc.cli.commands.learning import search_of

    return GaitOptions(direction=args.direction,
                       method=None if args.method is None else SearchMethod.parse(args.method),
                       model=args.model, max_open=args.max_open, seed=args.seed,
                       max_states=args.max_states, search=search_of(args),
                       legs=args.legs)


def run_render(args: argparse.Namespace) -> int:
    """``gaitc render gaits``: search, then draw the gait graph and each gait's poses."""
    args.svg, args.output, args.json = args.output_dir, None, False
    return run(args)


def run(args: argparse.Namespace) -> int:
    import gaitc

    found = gaitc.gaits(args.robot, options_of(args))
    written: list[str] = []
    if args.output and found.save(args.output):
        written.append(args.output)
    drawn = found.draw(args.svg) if args.svg else []
    if args.json:
        print_json(document("gaits", {**found.to_json(), "written": written + drawn}))
        return 0 if found.found else 1
    print(found)
    for hint in found.hints:
        print(f"  {hint}", file=sys.stderr)
    for path in drawn:
        print(f"wrote {path}")
    return 0 if found.found else 1
