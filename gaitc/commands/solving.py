"""The solving commands: ``check``, ``synth``, ``counter`` and ``verify``.

Each loads a spec with :func:`gaitc.loading.load_spec`, runs the embedded solver
(:mod:`solver.synthesis`) or SLUGS (:mod:`slugs_bridge.runner`), and, for ``synth``,
proves the result with the independent checker (:mod:`verifier.strategy`).
"""

from __future__ import annotations

import argparse
import json
import resource
import sys
import time
from typing import Any

from diagnostics import GaitcError, SolverError, UsageError, render_error
from diagnostics.files import write_atomically
from gaitc.exitcodes import EXIT_OK, EXIT_SOLVER, EXIT_UNREALIZABLE, EXIT_USER
from gaitc.loading import Spec, load
from gr1.controller import Controller, controller_to_json, load_controller
from gr1.spec import GR1Spec
from ltlcompiler.encoding import ENCODINGS
from solver.game import Progress

EXIT_CODES = """exit codes:
  0  every spec is realizable (check), the controller was written / verified
  1  an input file is wrong (syntax, names, malformed controller) or verification failed
  2  the command line is wrong
  3  a spec is unrealizable (check, synth) or realizable (counter)
  4  the solver could not finish (timeout, memory limit, SLUGS failure)
"""


def _common(p: argparse.ArgumentParser, solver: bool = True) -> None:
    p.add_argument(
        "--robotics-semantics",
        action="store_true",
        help="every initial state allowed by env_init and sys_init must be winning "
        "(SLUGS --sysInitRoboticsSemantics); default: for every allowed input some output",
    )
    p.add_argument(
        "--encoding",
        choices=ENCODINGS,
        default="onehot",
        help="encoding of .gait specs (default onehot)",
    )
    if not solver:
        return
    p.add_argument("--solver", choices=("embedded", "slugs"), default="embedded")
    p.add_argument("--slugs", metavar="PATH", help="the SLUGS binary (else $SLUGS or PATH)")
    p.add_argument("--timeout", type=float, metavar="SECONDS", help="stop after this long")
    p.add_argument(
        "--memory-limit", type=int, metavar="MB", help="stop when the solver needs more memory"
    )


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
    p.add_argument("--json", action="store_true", help="one JSON object per file")
    _common(p)
    p.set_defaults(run=run_check)

    p = sub.add_parser(
        "synth",
        help="synthesize and verify a controller",
        description="Synthesize an explicit controller (JSON, docs/controller-format.md), then "
        "prove it with the independent verifier.",
        epilog=EXIT_CODES,
        formatter_class=fmt,
    )
    p.add_argument("spec", metavar="SPEC")
    p.add_argument("-o", "--output", required=True, metavar="FILE")
    p.add_argument("--no-verify", action="store_true", help="skip the verification step")
    _common(p)
    p.set_defaults(run=run_synth)

    p = sub.add_parser(
        "counter",
        help="the environment's winning strategy of an unrealizable spec",
        description="Write the environment's counter-strategy (JSON) of an unrealizable SPEC.",
        epilog=EXIT_CODES,
        formatter_class=fmt,
    )
    p.add_argument("spec", metavar="SPEC")
    p.add_argument("-o", "--output", required=True, metavar="FILE")
    _common(p)
    p.set_defaults(run=run_counter)

    p = sub.add_parser(
        "verify",
        help="prove that a controller realizes a spec",
        description="Check a controller (or counter-strategy) against SPEC independently of "
        "the solver. The semantics default to the one recorded in the controller file.",
        epilog=EXIT_CODES,
        formatter_class=fmt,
    )
    p.add_argument("spec", metavar="SPEC")
    p.add_argument("controller", metavar="CONTROLLER")
    _common(p, solver=False)
    p.set_defaults(run=run_verify)


# ---------------------------------------------------------------- helpers
def _semantics(args: argparse.Namespace) -> str:
    return "robotics" if args.robotics_semantics else "default"


def _progress() -> Progress | None:
    if not sys.stderr.isatty():
        return None

    def show(message: str) -> None:
        print(f"gaitc: {message}", file=sys.stderr, flush=True)

    return show


def _limit_memory(args: argparse.Namespace) -> None:
    mb = getattr(args, "memory_limit", None)
    if mb is None:
        return
    if mb <= 0:
        raise UsageError("--memory-limit must be a positive number of megabytes")
    limit = mb * 1024 * 1024
    try:
        _, hard = resource.getrlimit(resource.RLIMIT_AS)
        resource.setrlimit(resource.RLIMIT_AS, (limit, hard))
    except (ValueError, OSError) as err:
        raise UsageError(f"cannot set a memory limit of {mb} MB: {err}") from None


def _slugsin(spec: GR1Spec) -> str:
    from gr1.bitblast import bitblast
    from slugs_bridge.slugsin import emit_slugsin

    return emit_slugsin(bitblast(spec))


def _options(args: argparse.Namespace) -> Any:
    from solver.symbolic import Options

    return Options(memory_mb=getattr(args, "memory_limit", None))


def _decide(loaded: Spec, args: argparse.Namespace) -> tuple[bool, float]:
    semantics = _semantics(args)
    if args.solver == "slugs":
        from slugs_bridge.runner import run_slugs_check

        result = run_slugs_check(
            _slugsin(loaded.gr1), semantics=semantics, timeout=args.timeout, slugs=args.slugs
        )
        return result.realizable, result.seconds
    from solver import synthesis

    checked = synthesis.check(loaded.gr1, semantics, args.timeout, _progress(), _options(args))
    return checked.realizable, checked.seconds


# ---------------------------------------------------------------- commands
def run_check(args: argparse.Namespace) -> int:
    _limit_memory(args)
    worst = EXIT_OK
    for path in args.specs:
        started = time.monotonic()
        record: dict[str, Any] = {"file": path, "semantics": _semantics(args)}
        try:
            loaded = load(path, args.encoding)
            realizable, seconds = _decide(loaded, args)
            record.update(
                verdict="realizable" if realizable else "unrealizable",
                seconds=round(seconds, 3),
                solver=args.solver,
            )
            code = EXIT_OK if realizable else EXIT_UNREALIZABLE
        except MemoryError:
            err: GaitcError = SolverError("synthesis ran out of memory (see --memory-limit)")
            record.update(verdict="error", error=str(err))
            code = EXIT_SOLVER
            print(render_error(err), file=sys.stderr)
        except UsageError:
            raise
        except GaitcError as err:
            record.update(verdict="error", error=str(err))
            code = EXIT_SOLVER if isinstance(err, SolverError) else EXIT_USER
            print(render_error(err), file=sys.stderr)
        record.setdefault("seconds", round(time.monotonic() - started, 3))
        if args.json:
            print(json.dumps(record, sort_keys=True), flush=True)
        elif record["verdict"] != "error":
            print(f"{path}: {record['verdict']} ({record['seconds']:.2f} s)", flush=True)
        worst = max(worst, code, key=_severity)
    return worst


def _severity(code: int) -> int:
    return {EXIT_OK: 0, EXIT_UNREALIZABLE: 1, EXIT_USER: 2, EXIT_SOLVER: 3}.get(code, 4)


def _with_source(c: Controller, loaded: Spec, solver: str) -> Controller:
    from dataclasses import replace

    return replace(c, source=loaded.source(), solver=solver)


def _solve(
    args: argparse.Namespace, loaded: Spec, semantics: str, kind: str
) -> tuple[Controller | None, float]:
    """Run the chosen solver for a ``strategy`` or a ``counterstrategy``; (automaton, seconds).

    The automaton is None when the spec has no such winner (unrealizable for a strategy,
    realizable for a counter-strategy).
    """
    started = time.monotonic()
    automaton: Controller | None = None
    try:
        if args.solver == "slugs":
            from slugs_bridge import runner

            wanted_realizable = kind == "strategy"
            run = runner.run_slugs_synth if wanted_realizable else runner.run_slugs_counter
            result = run(
                _slugsin(loaded.gr1), semantics=semantics, timeout=args.timeout, slugs=args.slugs
            )
            if result.realizable == wanted_realizable:
                if result.output is None:
                    verdict = "realizable" if result.realizable else "unrealizable"
                    raise SolverError(f"SLUGS reported {verdict} but wrote no {kind}")
                read = (runner.controller_from_slugs_json if wanted_realizable
                        else runner.counterstrategy_from_slugs_text)
                automaton = read(result.output, loaded.gr1, semantics)
        else:
            from solver import synthesis

            make = synthesis.synthesize if kind == "strategy" else synthesis.counterstrategy
            automaton = make(loaded.gr1, semantics, args.timeout, _progress(), _options(args))
    except MemoryError:
        raise SolverError("synthesis ran out of memory (see --memory-limit)") from None
    if automaton is not None:
        automaton = _with_source(automaton, loaded, args.solver)
    return automaton, time.monotonic() - started


def run_synth(args: argparse.Namespace) -> int:
    _limit_memory(args)
    semantics = _semantics(args)
    loaded = load(args.spec, args.encoding)
    controller, seconds = _solve(args, loaded, semantics, "strategy")
    if controller is None:
        print(f"{args.spec}: unrealizable ({seconds:.2f} s); no controller written")
        print("  hint: 'gaitc counter' shows how the environment wins", file=sys.stderr)
        return EXIT_UNREALIZABLE
    write_atomically(args.output, controller_to_json(controller))
    print(
        f"{args.spec}: realizable ({seconds:.2f} s); wrote {args.output} "
        f"({len(controller.nodes)} nodes)"
    )
    if args.no_verify:
        return EXIT_OK
    return _report_verification(loaded.gr1, controller, semantics)


def _report_verification(spec: GR1Spec, controller: Controller, semantics: str) -> int:
    from verifier.counterstrategy import verify_counterstrategy
    from verifier.strategy import verify

    check = verify_counterstrategy if controller.kind == "counterstrategy" else verify
    report = check(spec, controller, semantics)
    print(f"verified: {report.summary()}" if report.ok else f"NOT verified: {report.summary()}")
    for problem in report.problems:
        print(f"  - {problem}")
    return EXIT_OK if report.ok else EXIT_USER


def run_counter(args: argparse.Namespace) -> int:
    _limit_memory(args)
    semantics = _semantics(args)
    loaded = load(args.spec, args.encoding)
    counter, seconds = _solve(args, loaded, semantics, "counterstrategy")
    if counter is None:
        print(f"{args.spec}: realizable ({seconds:.2f} s); there is no counter-strategy")
        return EXIT_UNREALIZABLE
    write_atomically(args.output, controller_to_json(counter))
    print(
        f"{args.spec}: unrealizable ({seconds:.2f} s); wrote {args.output} "
        f"({len(counter.nodes)} nodes)"
    )
    return EXIT_OK


def run_verify(args: argparse.Namespace) -> int:
    loaded = load(args.spec, args.encoding)
    controller = load_controller(args.controller, loaded.gr1)
    semantics = "robotics" if args.robotics_semantics else controller.semantics
    return _report_verification(loaded.gr1, controller, semantics)
