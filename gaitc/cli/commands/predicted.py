"""``gaitc gaits --model``: gaits found on the motion a chapter 4 model predicts.

The work lives in :mod:`gaitc.models.catalogue`; this module adds the options to ``gaits``,
prints the predicted displacement per cycle and writes the gaits as JSON.
"""

from __future__ import annotations

import argparse
import json
import math
from typing import Any

from gaitc.diagnostics import SpecSemanticError, UsageError
from gaitc.diagnostics.files import write_atomically


def model_arguments(p: argparse.ArgumentParser) -> None:
    """``--model`` and ``--max-open`` of ``gaitc gaits``."""
    from gaitc.models.catalogue import MODELS

    p.add_argument(
        "--model",
        choices=sorted(MODELS),
        help="search the gait graph of a dynamic model (thesis 4.2.2) instead of the "
        "kinematic one; needs the robot file's 'model:' section (docs/models.md)",
    )
    p.add_argument(
        "--max-open",
        type=int,
        default=1,
        metavar="N",
        help="--model: valve states with at most N valves open (1)",
    )


def run_model_gaits(args: argparse.Namespace) -> int:
    from gaitc.gaitgraph.cycles import parse_direction
    from gaitc.models.catalogue import load_model, search_gaits
    from gaitc.models.gait_graph import gait_rows

    if args.method is not None or args.goal is not None:
        raise UsageError(
            "--model searches the model's gait graph; --method and --goal are "
            "for the kinematic searches"
        )
    if args.max_open < 1:
        raise UsageError("--max-open must be at least 1")
    try:
        direction = parse_direction(args.direction)
    except SpecSemanticError as err:
        raise UsageError(f"--direction: unknown direction {args.direction!r}") from err
    loaded = load_model(args.model, args.robot)
    found = search_gaits(loaded, direction, args.max_open)
    if getattr(args, "json", False):
        from gaitc.cli.reporting import document, print_json

        written = []
        if args.output:
            write_atomically(args.output, _json(found, args.direction))
            written.append(args.output)
        body = {**json.loads(_json(found, args.direction)), "written": written}
        print_json(document("gaits", body))
        return 0 if found.gaits else 1
    print(
        f"robot {loaded.robot}: model {args.model}, {len(found.graph.states)} valve states, "
        f"{len(found.graph.motion)} simulated transitions of {loaded.period:g} s"
    )
    if found.gaits:
        best = found.gaits[0]
        print(gait_rows(found.gaits, loaded.valve_legs))
        print(
            f"predicted displacement per cycle of gait 1: {best.net.x:.1f} mm, "
            f"{best.net.y:.1f} mm, {math.degrees(best.net.theta):.2f} deg "
            f"({len(best.states)} valve states)"
        )
    else:
        print(f"no gait towards {args.direction} found")
    if args.output:
        write_atomically(args.output, _json(found, args.direction))
    return 0 if found.gaits else 1


def _r(x: float) -> float:
    value = round(x, 3)
    return 0.0 if value == 0 else value


def _json(found: Any, direction: str) -> str:
    gaits = [
        {
            "rank": rank,
            "valves": list(g.valves),
            "transitions": [
                {"dx": _r(p.x), "dy": _r(p.y), "rotation": _r(math.degrees(p.theta))}
                for p in g.steps
            ],
            "displacement": [_r(g.net.x), _r(g.net.y)],
            "rotation": _r(math.degrees(g.net.theta)),
            "score": _r(g.score),
        }
        for rank, g in enumerate(found.gaits, 1)
    ]
    doc = {
        "robot": found.loaded.robot,
        "model": found.graph.model,
        "direction": direction,
        "period": found.graph.period,
        "valve_states": len(found.graph.states),
        "transitions": len(found.graph.motion),
        "valve_legs": list(found.loaded.valve_legs),
        "units": {"length": "mm", "angle": "deg"},
        "gaits": gaits,
    }
    return json.dumps(doc, indent=2, sort_keys=True) + "\n"
