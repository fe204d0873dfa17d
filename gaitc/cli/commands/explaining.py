"""``gaitc explain``: why a spec is unrealizable and what would fix it (:func:`gaitc.explain`).

Prints the kind of failure, a minimal core as compiler notes, the environment's freedoms, a
play and verified repairs; ``--json`` prints one object; ``--out`` saves the play as a run.
"""

from __future__ import annotations

import argparse
import sys
from typing import Any

import gaitc
from gaitc.api.modes import EncodingName
from gaitc.cli.commands.arguments import positive_seconds, run_file, semantics_of
from gaitc.cli.exitcodes import ExitCode, exit_code_help
from gaitc.cli.reporting import document, print_json
from gaitc.diagnostics import UsageError

EPILOG = exit_code_help({
    ExitCode.OK: "the spec is realizable and passed the sanity checks",
    ExitCode.UNREALIZABLE: "the spec is unrealizable (the explanation says why)",
    ExitCode.WARNING: "the spec is realizable, but a sanity check warns",
}, codes=(ExitCode.OK, ExitCode.USER, ExitCode.USAGE, ExitCode.UNREALIZABLE, ExitCode.SOLVER,
          ExitCode.WARNING))


def register(sub: Any) -> None:
    p = sub.add_parser(
        "explain", help="explain why a spec is unrealizable, and how to repair it",
        description="For an unrealizable SPEC: the kind of failure, a minimal core of its "
        "statements, the environment's freedoms it needs, a play it wins and verified "
        "one-edit repairs. For a realizable SPEC: sanity checks (satisfiable and "
        "well-separated assumptions, no vacuous goal, no unused part).",
        epilog=EPILOG, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("spec", metavar="SPEC")
    p.add_argument("--json", action="store_true",
                   help="print one JSON object (docs/json.md)")
    p.add_argument("--no-repairs", action="store_true", help="skip the search for repairs")
    p.add_argument("--timeout", type=positive_seconds, metavar="SECONDS",
                   help="stop the whole analysis after this long (exit 4)")
    p.add_argument("--out", metavar="FILE", type=run_file, help="save the play as .jsonl (draw it "
                   "with 'gaitc render map SPEC --run FILE') or .csv (a table)")
    p.add_argument("--encoding", choices=EncodingName.values(), default=EncodingName.ONEHOT.value)
    p.add_argument("--robotics-semantics", action="store_true",
                   help="SLUGS's --sysInitRoboticsSemantics")
    p.set_defaults(run=run_explain)


def exit_code(why: Any) -> ExitCode:
    if not why.realizable:
        return ExitCode.UNREALIZABLE
    return ExitCode.WARNING if why.warnings else ExitCode.OK


def run_explain(args: argparse.Namespace) -> int:
    spec = gaitc.load(args.spec, args.encoding)
    why = gaitc.explain(spec, semantics_of(args), args.timeout, not args.no_repairs)
    if args.out:
        if why.run is None:
            raise UsageError("there is no play to save: "
                             + ("the spec is realizable" if why.realizable
                                else "plays are told in robot terms for .gait specs only"))
        from gaitc.api.runs import save_run

        save_run(why.run, args.out)
    if args.json:
        print_json(document("explain", why.to_json()))
    else:
        print("\n".join(why.lines()))
        if args.out:
            print(f"wrote the play to {args.out}", file=sys.stderr)
    return exit_code(why)
