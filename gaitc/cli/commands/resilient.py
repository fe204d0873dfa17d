"""``gaitc resilience``: which failures a task survives (:func:`gaitc.resilience`).

Prints one table per question, or ``--json``; ``-o`` draws the legs coloured by how
critical each is (svg, png, pdf or dot).
"""

from __future__ import annotations

import argparse
import sys
from typing import Any

import gaitc
from gaitc.api.answers import METHODS, terminal_progress
from gaitc.api.modes import EncodingName
from gaitc.cli.commands.arguments import (
    output_file,
    positive_count,
    positive_seconds,
    positive_whole,
    semantics_of,
)
from gaitc.cli.exitcodes import ExitCode, exit_code_help
from gaitc.cli.reporting import document, print_json
from gaitc.diagnostics import UsageError

EPILOG = exit_code_help({
    ExitCode.OK: "the report was printed (the task is realizable with no failure)",
    ExitCode.UNREALIZABLE: "the task is unrealizable even with no failure",
}, codes=(ExitCode.OK, ExitCode.USER, ExitCode.USAGE, ExitCode.UNREALIZABLE, ExitCode.SOLVER))


def register(sub: Any) -> None:
    p = sub.add_parser(
        "resilience", help="which leg failures, health levels, caches and hazards a task "
        "survives or needs",
        description="For the .gait SPEC: minimal fatal and maximal survivable sets of legs "
        "failed for good (health 1), single points of failure, the legs each direction depends on; "
        "the largest k such that any k legs may break during the run; the least uniform "
        "health and the Pareto front of per-leg health; essential caches, cache placements "
        "and hazard sets survived alone; the most surprises (broken assumptions) survived.",
        epilog=EPILOG, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("spec", metavar="SPEC")
    p.add_argument("--json", action="store_true",
                   help="print one JSON object (docs/json.md)")
    p.add_argument("--method", choices=METHODS, default="parametric",
                   help="parametric: one game with rigid per-leg parameters; lattice: one "
                   "solver call per variant (default parametric)")
    p.add_argument("--health-bound", type=int, metavar="B",
                   help="health levels 1..B for every leg in the front (default: each leg "
                   "within its own declared levels)")
    p.add_argument("--place-caches", type=positive_count, metavar="K",
                   help="search the sets of K regions where caches make the task realizable")
    p.add_argument("--tolerate", type=positive_whole, default=2, metavar="K",
                   help="the most surprises (broken safety assumptions, as synth --tolerate) "
                   "searched (default 2)")
    p.add_argument("--jobs", type=int, default=1, metavar="N",
                   help="check variants in N local processes")
    p.add_argument("--dask", metavar="ADDRESS",
                   help="check variants on a Dask distributed scheduler (tcp://HOST:PORT)")
    p.add_argument("--encoding", choices=EncodingName.values(), default=EncodingName.BINARY.value,
                   help="encoding of the spec (default binary: the parametric games use "
                   "integers)")
    p.add_argument("-o", "--output", metavar="PICTURE", type=output_file,
                   help="draw the legs coloured by criticality (.svg, .png, .pdf, .dot)")
    p.add_argument("--robotics-semantics", action="store_true")
    p.add_argument("--timeout", type=positive_seconds, metavar="SECONDS",
                   help="stop the analysis (its workers too) this many seconds after it "
                   "starts, with exit 4")
    p.set_defaults(run=run_resilience)


def run_resilience(args: argparse.Namespace) -> int:
    if args.jobs < 1:
        raise UsageError("--jobs must be at least 1")
    spec = gaitc.load(args.spec, args.encoding)
    report = gaitc.resilience(spec, method=args.method, health_bound=args.health_bound,
                              place_caches=args.place_caches, semantics=semantics_of(args),
                              jobs=args.jobs, dask=args.dask, tolerate=args.tolerate,
                              progress=terminal_progress("resilience"), timeout=args.timeout,
                              encoding=args.encoding)
    if args.output:
        fmt = report.picture().save(args.output)
        print(f"wrote {args.output} ({fmt})", file=sys.stderr)
    if args.json:
        print_json(document("resilience", report.to_json()))
    else:
        print("\n".join(report.lines()))
    return ExitCode.OK if report.realizable else ExitCode.UNREALIZABLE
