"""``gaitc gaits``: synthesise gait primitives for a robot file (thesis chapters 2 and 5).

``--method full|random|reset`` (or ``chapter2``, the default) is the chapter 2 search of
:mod:`gaitc.gaitgraph`; ``astar``, ``lpa`` and ``mcts`` search the global frame toward ``--goal``
with :mod:`gaitc.search` (:func:`run_global`, in :mod:`gaitc.cli.commands.learning`).
"""

from __future__ import annotations

import argparse
import sys
from typing import TYPE_CHECKING, Any

from gaitc.cli.commands.arguments import output_file
from gaitc.cli.reporting import document, print_json
from gaitc.diagnostics import SpecSemanticError, UsageError
from gaitc.diagnostics.files import write_atomically

if TYPE_CHECKING:
    from gaitc.gaitgraph.robot import Robot
    from gaitc.gaitgraph.search import SearchResult


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
    from gaitc.cli.commands.predicted import model_arguments

    model_arguments(p)
    p.set_defaults(run=run)


def search_arguments(p: argparse.ArgumentParser) -> None:
    """The robot file and search options, shared by ``gaits`` and ``render gaits``."""
    p.add_argument("robot", metavar="ROBOT.yaml")
    p.add_argument("--direction", default="+x", help="+x, -x, +y, -y or an angle in degrees")
    p.add_argument(
        "--method",
        choices=("chapter2", "full", "random", "reset", "astar", "lpa", "dstar", "mcts"),
        default=None,
        help="chapter 2 (default): full for at most 12 chambers and --max-states valve "
        "states, else random; astar, lpa, dstar, mcts: chapter 5 searches toward --goal",
    )
    p.add_argument("--seed", type=int, default=0,
                   help="seed of the random and reset searches and of chapter 5's (default 0)")
    p.add_argument("--max-states", type=int, default=10_000, help="valve states to try at most")
    from gaitc.cli.commands.learning import goal_arguments

    goal_arguments(p)


def run_render(args: argparse.Namespace) -> int:
    """``gaitc render gaits``: search, then draw the gait graph and each gait's poses."""
    args.svg, args.output, args.json = args.output_dir, None, False
    return run(args)


def run(args: argparse.Namespace) -> int:
    if getattr(args, "model", None) is not None:
        from gaitc.cli.commands.predicted import run_model_gaits

        if args.seed != 0:
            raise UsageError("--seed seeds the random and reset searches; --model searches "
                             "the model's whole gait graph, without random numbers")

        return run_model_gaits(args)
    if args.method in ("astar", "lpa", "dstar", "mcts"):
        from gaitc.cli.commands.learning import run_global

        return run_global(args)
    if args.goal is not None:
        raise UsageError(
            f"--goal is for --method astar, lpa, dstar or mcts; the chapter 2 search "
            f"(--method {args.method or 'chapter2'}) takes --direction"
        )
    from gaitc.gaitgraph.cycles import parse_direction
    from gaitc.gaitgraph.drawing import write_drawings
    from gaitc.gaitgraph.report import gait_table, gaits_json
    from gaitc.gaitgraph.robot import load_robot
    from gaitc.gaitgraph.search import search

    if args.max_states < 1:
        raise UsageError("--max-states must be at least 1")
    robot = load_robot(args.robot)
    try:
        direction = parse_direction(args.direction)
    except SpecSemanticError as err:  # no file to point at: a usage error
        raise UsageError(f"--direction: unknown direction {args.direction!r}") from err
    full = robot.valve_count <= 12 and 1 << robot.valve_count <= args.max_states
    method = args.method if args.method not in (None, "chapter2") else (
        "full" if full else "random")
    if method == "full" and args.seed != 0:
        raise UsageError(f"--seed seeds the random and reset searches; the full search of "
                         f"robot {robot.name} tries every valve state, without random numbers")
    result = search(robot, direction, method, args.seed, args.max_states)
    if args.json:
        return _print_json(args, robot, result)
    print(
        f"robot {robot.name}: {robot.valve_count} chambers, method {method}, "
        f"{result.states_added} valve states, {len(result.graph)} poses, "
        f"{len(result.graph.edges)} transitions"
    )
    if result.gaits:
        print(gait_table(robot, result.gaits))
    else:
        print(f"no gait towards {args.direction} found")
        from gaitc.models.catalogue import MODELS

        print(f"  hint: the chapter 2 graph is kinematic and frictionless; a robot that walks "
              f"by friction needs a dynamic model: --model {' or '.join(sorted(MODELS))} "
              "(docs/models.md)", file=sys.stderr)
    if result.limit_reached:
        print(f"the search stopped at --max-states {args.max_states} of the "
              f"{1 << robot.valve_count} valve states")
    if args.output:
        write_atomically(args.output, gaits_json(robot, result, args.direction, args.seed))
    if args.svg:
        for path in write_drawings(robot, result.graph, result.gaits, args.svg):
            print(f"wrote {path}")
    return 0 if result.gaits else 1


def _print_json(args: argparse.Namespace, robot: Robot, result: SearchResult) -> int:
    """``gaits --json``: the same files written, the search printed as one object."""
    from gaitc.gaitgraph.drawing import write_drawings
    from gaitc.gaitgraph.report import gaits_json, search_document

    written = []
    if args.output:
        write_atomically(args.output, gaits_json(robot, result, args.direction, args.seed))
        written.append(args.output)
    if args.svg:
        written.extend(str(p) for p in write_drawings(robot, result.graph, result.gaits,
                                                      args.svg))
    body = {**search_document(robot, result, args.direction, args.seed), "written": written}
    print_json(document("gaits", body))
    return 0 if result.gaits else 1
