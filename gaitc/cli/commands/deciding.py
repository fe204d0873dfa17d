"""The deciding command, ``check``, and the solver options every solving command shares.

``check`` parses its options, calls :func:`gaitc.check` (:mod:`gaitc.api.deciding`) in a
limited process and prints one verdict per spec; it loads nothing of controllers, their
forms or their proofs (tests/codebase/test_startup_imports.py).  ``synth``, ``counter`` and
``verify`` (:mod:`gaitc.cli.commands.solving`) take the same solver options from here.
"""

from __future__ import annotations

import argparse
import functools
import sys
import time
from typing import TYPE_CHECKING, Any

import gaitc
from gaitc.api.deciding import SOLVERS
from gaitc.api.isolation import HardLimits, run_limited, solver_options
from gaitc.api.modes import EncodingName
from gaitc.cli.commands.arguments import positive_megabytes, positive_seconds, semantics_of
from gaitc.cli.exitcodes import ExitCode, exit_code_help
from gaitc.cli.reporting import diagnostic_json, document, error_json, exit_code_of, print_json
from gaitc.cli.status import progress_display
from gaitc.diagnostics import (
    Diagnostic,
    GaitcError,
    UsageError,
    render_diagnostic,
    render_error,
)

if TYPE_CHECKING:
    from gaitc.api.progress import Progress

EXIT_CODES = exit_code_help({
    ExitCode.OK: "every spec is realizable (check), the controller was written / verified",
    ExitCode.USER: "an input file is wrong (syntax, names, malformed controller) or "
    "verification failed",
    ExitCode.UNREALIZABLE: "a spec is unrealizable (check, synth) or realizable (counter)",
})


class Unasked(str):
    """An option's default, told apart from the same value given on the command line (a
    command may choose another value when the user did not ask for one)."""

    __slots__ = ()


def solver_arguments(p: argparse.ArgumentParser, solver: bool = True) -> None:
    """The semantics and encoding options, and with ``solver`` the solver, its limits and
    ``--verbose`` (``verify`` runs no solver)."""
    p.add_argument(
        "--robotics-semantics",
        action="store_true",
        help="every initial state allowed by env_init and sys_init must be winning "
        "(SLUGS --sysInitRoboticsSemantics); default: for every allowed input some output",
    )
    p.add_argument(
        "--encoding",
        choices=EncodingName.values(),
        default=Unasked(EncodingName.ONEHOT.value) if solver else None,
        help="encoding of .gait specs (default onehot"
        + ("; synth --tolerate: binary" if solver
           else "; verify: the one recorded in the controller file") + ")",
    )
    if not solver:
        return
    p.add_argument("--solver", choices=SOLVERS, default="embedded")
    p.add_argument("--slugs", metavar="PATH", help="the SLUGS binary (else $SLUGS or PATH)")
    p.add_argument("--timeout", type=positive_seconds, metavar="SECONDS",
                   help="stop after this long (exit 4; the solver is killed at most "
                   "half a second later)")
    p.add_argument("--memory-limit", type=positive_megabytes, metavar="MB",
                   help="the most memory the solver process may take (exit 4 when it needs "
                   "more)")
    p.add_argument("--verbose", action="store_true",
                   help="print each stage of the solve on a line of its own, with the "
                   "solver's figures (rounds, BDD sizes); on a terminal a status line "
                   "shows the stage and the time elapsed")


def register(sub: Any) -> None:
    fmt = argparse.RawDescriptionHelpFormatter
    p = sub.add_parser(
        "check",
        help="decide realizability of specs",
        description="Decide whether a controller exists for each SPEC (.gait, .slugsin, "
        ".structuredslugs); prints 'FILE: realizable (0.12 s)' per file.",
        epilog=EXIT_CODES,
        formatter_class=fmt,
    )
    p.add_argument("specs", nargs="+", metavar="SPEC")
    p.add_argument("--json", action="store_true",
                   help="one JSON object per file (docs/json.md)")
    solver_arguments(p)
    p.set_defaults(run=run_check)


def hard_limits(args: argparse.Namespace) -> HardLimits:
    """The limits the solver's process runs under (``--timeout``, ``--memory-limit``)."""
    return HardLimits(args.timeout, getattr(args, "memory_limit", None))


def options_of(args: argparse.Namespace) -> Any:
    """The embedded solver's options (CUDD's share of ``--memory-limit``)."""
    return solver_options(getattr(args, "memory_limit", None))


def solver_args(args: argparse.Namespace, progress: Progress | None) -> dict[str, Any]:
    """The keyword arguments the solving functions of the facade share, from ``args``."""
    return {"semantics": semantics_of(args), "solver": args.solver, "timeout": args.timeout,
            "slugs": args.slugs, "options": options_of(args), "progress": progress}


def run_check(args: argparse.Namespace) -> int:
    worst = ExitCode.OK
    for path in args.specs:
        started = time.monotonic()
        record: dict[str, Any] = {"file": path, "semantics": semantics_of(args),
                                  "solver": args.solver, "engine": None, "error": None,
                                  "warnings": []}
        try:
            options_of(args)  # a memory limit too small fails here, before the fork
            verdict, warnings = run_limited(functools.partial(_check_one, path, args),
                                            hard_limits(args))
            record.update(verdict.to_json(), file=path, warnings=[
                diagnostic_json(w) for w in warnings])
            for warning in warnings:
                print(render_diagnostic(warning), file=sys.stderr)
            code = ExitCode.OK if verdict.realizable else ExitCode.UNREALIZABLE
        except UsageError:
            raise
        except GaitcError as err:
            record.update(verdict="error", error=error_json(err))
            code = exit_code_of(err)
            print(render_error(err), file=sys.stderr)
        record.setdefault("seconds", round(time.monotonic() - started, 3))
        if args.json:
            print_json(document("check", record))
        elif record["verdict"] != "error":
            print(f"{path}: {record['verdict']} ({record['seconds']:.2f} s)", flush=True)
        worst = max(worst, code, key=_SEVERITY.index)
    return worst


def _check_one(path: str, args: argparse.Namespace
               ) -> tuple[gaitc.Verdict, tuple[Diagnostic, ...]]:
    """Load and decide one spec (in the limited child process when there are limits; CUDD's
    share of the memory limit is what is left once the spec is loaded), and check that it
    is well-separated (its warnings)."""
    spec = gaitc.load(path, args.encoding)
    with progress_display(args.verbose) as progress:
        verdict = gaitc.check(spec, separation=True, **solver_args(args, progress))
    separated = verdict.separation or gaitc.separation(spec)  # SLUGS decided: check here
    return verdict, separated.warnings()


_SEVERITY = (ExitCode.OK, ExitCode.UNREALIZABLE, ExitCode.USER, ExitCode.SOLVER)


