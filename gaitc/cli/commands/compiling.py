"""``gaitc lint`` and ``gaitc compile``: check a spec, or lower it to a SLUGS/LTL text.

``compile`` runs parse, check, lowering (thesis eqs. 3.3-3.9) and one emitter; warnings go
to stderr in the standard layout, and the output file is replaced atomically.
"""

from __future__ import annotations

import argparse
import sys
from typing import TYPE_CHECKING, Any

import gaitc
from gaitc.api.compiling import FORMATS, OutputFormat, emit, output_format
from gaitc.api.loading import Spec, load, reader_of
from gaitc.api.modes import EncodingName
from gaitc.cli.commands.arguments import output_file, positive_seconds
from gaitc.cli.exitcodes import ExitCode
from gaitc.cli.reporting import compilation_json, document, lint_json, print_json
from gaitc.diagnostics import Diagnostic, UsageError, render_diagnostic
from gaitc.diagnostics.files import write_atomically

if TYPE_CHECKING:
    from gaitc.api.answers import Explanation


def register(subparsers: Any) -> None:
    lint = subparsers.add_parser(
        "lint", help="check a .gait file and print its warnings",
        description="Parse and check SPEC, lower it in both encodings, print warnings. "
        "Exit 0 when there is no error (warnings allowed), 1 on an error.")
    lint.add_argument("spec", metavar="SPEC", help="a .gait file (or .slugsin, "
                      ".structuredslugs: read and, with --deep, checked)")
    lint.add_argument("--primitives", action="store_true",
                      help="report gaits without a valve primitive even when no gait binds one "
                      "(by default they are reported once any gait of the spec binds one)")
    lint.add_argument("--deep", action="store_true",
                      help="also solve the spec and run the sanity checks of 'gaitc explain' "
                      "(exit 3 if unrealizable, 5 on a sanity warning)")
    lint.add_argument("--json", action="store_true",
                      help="print one JSON object (docs/json.md); warnings stay on stderr too")
    lint.add_argument("--timeout", type=positive_seconds, metavar="SECONDS",
                      help="stop after this long (exit 4): the search behind a valve primitive "
                      "bound to a robot file, and the solving of --deep")
    lint.set_defaults(run=run_lint)

    comp = subparsers.add_parser(
        "compile", help="compile a .gait file to structuredslugs, slugsin or LTL text",
        description="Compile SPEC to a GR(1) specification (thesis eqs. 3.3-3.9). "
        "Exit 0 on success, 1 on an error in SPEC, 2 on a bad command line.")
    comp.add_argument("spec", metavar="SPEC", help="a .gait file (or .slugsin, "
                      ".structuredslugs, .ltl: translated to the output format)")
    comp.add_argument("-o", "--output", default="-", metavar="OUT", type=output_file,
                      help="output file, '-' for stdout (default); replaced atomically")
    comp.add_argument("--format", choices=FORMATS, default=None,
                      help="output format (default: from the suffix of OUT: .slugsin or .txt "
                      "slugsin, .ltl LTL text, "
                      "else structuredslugs)")
    comp.add_argument("--encoding", choices=EncodingName.values(),
                      default=EncodingName.ONEHOT.value,
                      help="onehot: a proposition per region/gait/health level (the thesis); "
                      "binary: integer variables (default onehot)")
    comp.add_argument("--json", action="store_true",
                      help="print one JSON object (docs/json.md) with the sizes of the "
                      "output; with '-o -' it holds the text")
    comp.set_defaults(run=run_compile)


def _warn(diagnostics: list[Diagnostic]) -> None:
    for diag in diagnostics:
        print(render_diagnostic(diag), file=sys.stderr)


def run_lint(args: argparse.Namespace) -> int:
    diagnostics = list(gaitc.lint(args.spec, args.primitives, args.timeout))
    _warn(diagnostics)
    code, why = _lint_verdict(args, diagnostics)
    if args.json:
        print_json(document("lint", lint_json(args.spec, diagnostics, why)))
    return code


def _lint_verdict(args: argparse.Namespace, diagnostics: list[Diagnostic]
                  ) -> tuple[ExitCode, Explanation | None]:
    """The exit code of ``lint`` and, with ``--deep``, the explanation behind it."""
    if any(d.severity == "error" for d in diagnostics):
        return ExitCode.USER, None
    if not args.deep:
        return ExitCode.OK, None
    why = gaitc.explain(gaitc.load(args.spec, kind=reader_of(args.spec)), repairs=False,
                        timeout=args.timeout)
    if not why.realizable:
        print(f"{args.spec}: unrealizable ({why.kind} failure); 'gaitc explain' says why",
              file=sys.stderr)
        return ExitCode.UNREALIZABLE, why
    from gaitc.api.answers import NOT_WELL_SEPARATED

    for warning in why.warnings:
        if warning.code == NOT_WELL_SEPARATED:
            continue  # lint's own well-separation warning, above, says it with a play
        print(f"{args.spec}: warning: {warning.message}", file=sys.stderr)
    return (ExitCode.WARNING if why.warnings else ExitCode.OK), why


def compile_text(path: str, fmt: str = OutputFormat.STRUCTUREDSLUGS,
                 encoding: str = EncodingName.ONEHOT) -> tuple[str, list[Diagnostic]]:
    """The text of the .gait file at ``path`` compiled to ``fmt``, plus the warnings."""
    spec, text = _compiled(path, fmt, encoding)
    return text, list(spec.diagnostics)


def _compiled(path: str, fmt: str, encoding: str) -> tuple[Spec, str]:
    if fmt not in FORMATS:
        raise UsageError(f"unknown format '{fmt}': use one of {', '.join(FORMATS)}")
    spec = load(path, encoding, kind=reader_of(path))
    return spec, emit(spec, fmt)


def run_compile(args: argparse.Namespace) -> int:
    fmt = output_format(args.output, args.format)
    spec, text = _compiled(args.spec, fmt, args.encoding)
    _warn(list(spec.diagnostics))
    if args.output != "-":
        write_atomically(args.output, text)
    if args.json:
        print_json(document("compile", compilation_json(spec, fmt, text, args.output)))
    elif args.output == "-":
        sys.stdout.write(text)
        sys.stdout.flush()
    return 0
