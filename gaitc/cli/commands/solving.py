"""The commands that make or read controllers: ``synth``, ``counter`` and ``verify``.

Each parses its options (the solver's are :mod:`gaitc.cli.commands.deciding`'s, shared with
``check``), calls :func:`gaitc.synthesize`, :func:`gaitc.tolerate`,
:func:`gaitc.counterstrategy` or :func:`gaitc.verify` (:mod:`gaitc.api.solving`) and prints.
"""

from __future__ import annotations

import argparse
import sys
from typing import Any

import gaitc
from gaitc.api.isolation import run_limited
from gaitc.api.modes import FORM_CHOICES, ControllerKind, EncodingName, Form, form_choice
from gaitc.api.solving import (
    MAX_NODES,
    VerificationReport,
    read_once,
    recorded_encoding,
    tables_hint,
)
from gaitc.cli.commands.arguments import (
    add_prefer,
    output_file,
    positive_count,
    positive_whole,
    semantics_of,
)
from gaitc.cli.commands.deciding import (
    EXIT_CODES,
    Unasked,
    hard_limits,
    options_of,
    solver_args,
    solver_arguments,
)
from gaitc.cli.exitcodes import ExitCode
from gaitc.cli.reporting import document, print_json
from gaitc.cli.status import progress_display
from gaitc.diagnostics import UsageError


def _json(p: argparse.ArgumentParser) -> None:
    """``--json``: one object printed instead of the text."""
    p.add_argument("--json", action="store_true",
                   help="print one JSON object instead of the text (docs/json.md)")


def register(sub: Any) -> None:
    fmt = argparse.RawDescriptionHelpFormatter
    p = sub.add_parser(
        "synth",
        help="synthesize and verify a controller",
        description="Synthesize an explicit controller (JSON, docs/controller-format.md), then "
        "prove it with the independent verifier.",
        epilog=EXIT_CODES,
        formatter_class=fmt,
    )
    p.add_argument("spec", metavar="SPEC")
    p.add_argument("-o", "--output", required=True, metavar="FILE", type=output_file)
    p.add_argument("--no-verify", action="store_true", help="skip the verification step")
    _json(p)
    p.add_argument("--form", choices=FORM_CHOICES, default=None,
                   help="the controller's form: explicit (every node listed), symbolic "
                   "(BDDs; simulate, drive, verify and render map read it), compact "
                   "(decision diagrams over the robot's words: regions, gaits, leg health, "
                   "hazards, proved on every state; 'render policy' prints them as rules, "
                   "'codegen' turns them into C for a host or the valve board), or auto "
                   "(default: explicit unless it would pass --max-nodes nodes, then "
                   "symbolic); docs/controller-format.md")
    p.add_argument("--symbolic", action="store_true", help="the same as --form symbolic")
    p.add_argument("--compact", action="store_true", help="the same as --form compact")
    p.add_argument("--max-nodes", type=positive_count, default=MAX_NODES, metavar="N",
                   help=f"keep the controller symbolic when the explicit automaton would pass "
                   f"N nodes (default {MAX_NODES:,})")
    p.add_argument("--tolerate", type=positive_whole, metavar="K",
                   help="plan for up to K surprises (steps on which the environment breaks "
                   "its safety assumptions, e.g. a leg failing while not in use): report the "
                   "most it survives and the assumption that limits it, and write the "
                   "controller for that many (in any form; docs/background/tolerance.md)")
    p.add_argument("--breakable", metavar="KIND",
                   help="with --tolerate: only these assumptions may break: unused (a leg not "
                   "in use keeps its health), wear (a leg in use loses at most one level a "
                   "step), cache (a cache restores every leg), hazard, hazard-wear, or the "
                   "rule of an assumption of the spec (default: every one)")
    add_prefer(p)
    solver_arguments(p)
    p.set_defaults(run=run_synth)

    p = sub.add_parser(
        "counter",
        help="the environment's winning strategy of an unrealizable spec",
        description="Write the environment's counter-strategy (JSON) of an unrealizable SPEC.",
        epilog=EXIT_CODES,
        formatter_class=fmt,
    )
    p.add_argument("spec", metavar="SPEC")
    p.add_argument("-o", "--output", required=True, metavar="FILE", type=output_file)
    _json(p)
    solver_arguments(p)
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
    _json(p)
    solver_arguments(p, solver=False)
    p.set_defaults(run=run_verify)


# ---------------------------------------------------------------- commands
def _solve(args: argparse.Namespace, kind: ControllerKind
           ) -> tuple[gaitc.Spec, gaitc.Synthesis]:
    options_of(args)  # a memory limit too small fails here, before the fork

    def work() -> tuple[gaitc.Spec, gaitc.Synthesis]:
        spec = gaitc.load(args.spec, args.encoding)
        with progress_display(args.verbose) as progress:
            if kind == ControllerKind.COUNTERSTRATEGY:
                return spec, gaitc.counterstrategy(spec, **solver_args(args, progress))
            return spec, gaitc.synthesize(spec, verify=not args.no_verify, form=_form(args),
                                          max_nodes=args.max_nodes, prefer=args.prefer,
                                          **solver_args(args, progress))

    return run_limited(work, hard_limits(args))


def run_synth(args: argparse.Namespace) -> int:
    if args.tolerate is not None:
        return _run_tolerate(args)
    if args.breakable is not None:
        raise UsageError("--breakable says which assumptions --tolerate K plans for; give "
                         "--tolerate K too")
    _, found = _solve(args, ControllerKind.STRATEGY)
    if args.json:
        return _synth_json(args, found)
    if found.controller is None:
        print(f"{args.spec}: unrealizable ({found.seconds:.2f} s); no controller written")
        print("  hint: 'gaitc counter' shows how the environment wins", file=sys.stderr)
        return ExitCode.UNREALIZABLE
    if found.report is not None and not found.report.ok:
        print(f"{args.spec}: realizable ({found.seconds:.2f} s), but the controller failed "
              f"verification; {args.output} was not written")
        return _print_report(found.report)
    found.save(args.output)  # only a verified controller (or one --no-verify asked for)
    print(
        f"{args.spec}: realizable ({found.seconds:.2f} s); wrote {args.output} "
        f"({found.size})"
    )
    _hint_tables(args.output)
    if found.separation is not None:
        print(f"  note: {found.separation}")
    if found.report is None:
        return ExitCode.OK
    return _print_report(found.report)


def _form(args: argparse.Namespace) -> Form | None:
    """The form ``--form``, ``--symbolic`` or ``--compact`` asks for (None: auto); two of
    them naming different forms is a :class:`UsageError`."""
    asked = [(f"--form {args.form}", form_choice(args.form))] if args.form is not None else []
    asked += [(f"--{form}", form) for form in (Form.SYMBOLIC, Form.COMPACT)
              if getattr(args, str(form))]
    if len({form for _, form in asked}) > 1:
        raise UsageError(f"{' and '.join(flag for flag, _ in asked)} are two forms of the "
                         "controller: give one")
    return asked[0][1] if asked else None


#: What ``synth --tolerate`` says when it chose the binary encoding itself.
TOLERATE_ENCODING_NOTE = ("synth --tolerate: solving in the binary encoding, whose counter "
                          "game is several times faster than one-hot's (the controller "
                          "records it; --encoding onehot keeps one-hot)")


def _tolerate(args: argparse.Namespace) -> gaitc.Tolerance:
    """``synth --tolerate K``: the tolerance report and its controller (gaitc.tolerate)."""
    options_of(args)  # a memory limit too small fails here, before the fork
    if args.solver != "embedded":
        raise UsageError("--tolerate solves a game of its own with the embedded solver; drop "
                         "--solver slugs")
    form = _form(args)
    if args.prefer is not None:
        raise UsageError("--prefer does not apply with --tolerate: the controller keeps every "
                         "winning move of the game with surprises")

    encoding = args.encoding
    if isinstance(encoding, Unasked) and str(args.spec).endswith(".gait"):
        # issue 59: a six-legged robot's --tolerate 1 took over 300 s one-hot, 38 s binary
        encoding = EncodingName.BINARY
        print(f"note: {TOLERATE_ENCODING_NOTE}", file=sys.stderr)

    def work() -> gaitc.Tolerance:
        spec = gaitc.load(args.spec, encoding)
        with progress_display(args.verbose) as progress:
            return gaitc.tolerate(spec, args.tolerate, semantics_of(args),
                                  breakable=args.breakable, form=form,
                                  max_nodes=args.max_nodes,
                                  verify=not args.no_verify, options=options_of(args),
                                  timeout=args.timeout, progress=progress)

    return run_limited(work, hard_limits(args))


def _run_tolerate(args: argparse.Namespace) -> int:
    outcome = _tolerate(args)
    report, found = outcome.report, outcome.synthesis
    written = found.controller is not None and (found.report is None or found.report.ok)
    if written:
        found.save(args.output)
    if args.json:
        print_json(document("synth", {**found.to_json(), "tolerance": report.to_json(),
                                      "output": args.output if written else None}))
        if found.controller is None:
            return ExitCode.UNREALIZABLE
        return ExitCode.OK if written else ExitCode.USER
    for line in report.lines():
        print(line)
    if found.controller is None or report.reached is None:
        print(f"{args.spec}: unrealizable even without surprises; no controller written")
        return ExitCode.UNREALIZABLE
    plan = f"for up to {report.reached} surprise{'s' if report.reached != 1 else ''}"
    if not written:
        print(f"{args.spec}: the controller {plan} failed verification; {args.output} was "
              "not written")
    else:
        size = found.size.removeprefix(f"{found.form}, ")
        proof = ", proved against it" if found.report is not None else ""
        print(f"{args.spec}: wrote {args.output}, the {found.form} controller {plan} "
              f"({size}); it is a controller of the spec itself{proof}")
    if found.report is None:
        return ExitCode.OK
    return _print_report(found.report)


def _hint_tables(output: str) -> None:
    """The hint of :func:`gaitc.api.solving.tables_hint`, on standard error."""
    hint = tables_hint(output)
    if hint is not None:
        print(f"  hint: {hint}", file=sys.stderr)


def _synth_json(args: argparse.Namespace, found: gaitc.Synthesis) -> int:
    """``synth --json`` and ``counter --json``: the same files written, one object printed."""
    strategy = found.kind == ControllerKind.STRATEGY
    # as without --json: synth writes only a verified controller, counter whatever it found
    verified = not strategy or found.report is None or found.report.ok
    written = found.controller is not None and verified
    if written:
        found.save(args.output)
    print_json(document("synth" if strategy else "counter",
                        {**found.to_json(), "output": args.output if written else None,
                         "tolerance": None}))
    if found.controller is None:
        if strategy:
            print("  hint: 'gaitc counter' shows how the environment wins", file=sys.stderr)
        return ExitCode.UNREALIZABLE
    return ExitCode.OK if verified else ExitCode.USER


def _print_report(report: VerificationReport) -> int:
    print(f"verified: {report.summary()}" if report.ok else f"NOT verified: {report.summary()}")
    for problem in report.problems:
        print(f"  - {problem}")
    for note in report.notes:
        print(f"  note: {note}")
    return ExitCode.OK if report.ok else ExitCode.USER


def run_counter(args: argparse.Namespace) -> int:
    _, found = _solve(args, ControllerKind.COUNTERSTRATEGY)
    if args.json:
        return _synth_json(args, found)
    if found.controller is None:
        print(f"{args.spec}: realizable ({found.seconds:.2f} s); there is no counter-strategy")
        return ExitCode.UNREALIZABLE
    found.save(args.output)
    print(
        f"{args.spec}: unrealizable ({found.seconds:.2f} s); wrote {args.output} "
        f"({len(found.controller.nodes)} nodes)"
    )
    return ExitCode.OK


def run_verify(args: argparse.Namespace) -> int:
    controller = read_once(args.controller)
    encoding = args.encoding or recorded_encoding(controller) or EncodingName.ONEHOT
    spec = gaitc.load(args.spec, encoding)
    semantics = semantics_of(args) if args.robotics_semantics else None  # None: as recorded
    report = gaitc.verify(spec, controller, semantics)
    if not args.json:
        return _print_report(report)
    print_json(document("verify", {"file": args.spec, "controller": args.controller,
                                   **report.to_json()}))
    return ExitCode.OK if report.ok else ExitCode.USER
