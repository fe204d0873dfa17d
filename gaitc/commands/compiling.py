"""``gaitc lint`` and ``gaitc compile``: check a .gait file, or lower it to a SLUGS/LTL text.

``compile`` runs parse, check, lowering (thesis eqs. 3.3-3.9) and one emitter; warnings go
to stderr in the standard layout, and the output file is replaced atomically.
"""

from __future__ import annotations

import argparse
import sys
from typing import Any

import gaitc
from diagnostics import Diagnostic, UsageError, render_diagnostic
from diagnostics.files import write_atomically
from gaitc.emission import FORMATS, emit, output_format
from gaitc.exitcodes import ExitCode
from gaitc.loading import load
from ltlcompiler.encoding import ENCODINGS


def register(subparsers: Any) -> None:
    lint = subparsers.add_parser(
        "lint", help="check a .gait file and print its warnings",
        description="Parse and check SPEC, lower it in both encodings, print warnings. "
        "Exit 0 when there is no error (warnings allowed), 1 on an error.")
    lint.add_argument("spec", metavar="SPEC", help="a .gait file")
    lint.add_argument("--primitives", action="store_true",
                      help="report gaits without a valve primitive even when no gait binds one "
                      "(by default they are reported once any gait of the spec binds one)")
    lint.add_argument("--deep", action="store_true",
                      help="also solve the spec and run the sanity checks of 'gaitc explain' "
                      "(exit 3 if unrealizable, 5 on a sanity warning)")
    lint.set_defaults(run=run_lint)

    comp = subparsers.add_parser(
        "compile", help="compile a .gait file to structuredslugs, slugsin or LTL text",
        description="Compile SPEC to a GR(1) specification (thesis eqs. 3.3-3.9). "
        "Exit 0 on success, 1 on an error in SPEC, 2 on a bad command line.")
    comp.add_argument("spec", metavar="SPEC", help="a .gait file")
    comp.add_argument("-o", "--output", default="-", metavar="OUT",
                      help="output file, '-' for stdout (default); replaced atomically")
    comp.add_argument("--format", choices=FORMATS, default=None,
                      help="output format (default: from the suffix of OUT, .slugsin or .ltl, "
                      "else structuredslugs)")
    comp.add_argument("--encoding", choices=ENCODINGS, default="onehot",
                      help="onehot: a proposition per region/gait/health level (the thesis); "
                      "binary: integer variables (default onehot)")
    comp.set_defaults(run=run_compile)


def _warn(diagnostics: list[Diagnostic]) -> None:
    for diag in diagnostics:
        print(render_diagnostic(diag), file=sys.stderr)


def run_lint(args: argparse.Namespace) -> int:
    diagnostics = list(gaitc.lint(args.spec, args.primitives))
    _warn(diagnostics)
    if any(d.severity == "error" for d in diagnostics):
        return ExitCode.USER
    if not args.deep:
        return ExitCode.OK
    why = gaitc.explain(gaitc.load(args.spec, kind=".gait"), repairs=False)
    if not why.realizable:
        print(f"{args.spec}: unrealizable ({why.kind} failure); 'gaitc explain' says why",
              file=sys.stderr)
        return ExitCode.UNREALIZABLE
    for warning in why.warnings:
        print(f"{args.spec}: warning: {warning.message}", file=sys.stderr)
    return ExitCode.WARNING if why.warnings else ExitCode.OK


def compile_text(path: str, fmt: str = "structuredslugs", encoding: str = "onehot"
                 ) -> tuple[str, list[Diagnostic]]:
    """The text of the .gait file at ``path`` compiled to ``fmt``, plus the warnings."""
    if fmt not in FORMATS:
        raise UsageError(f"unknown format '{fmt}': use one of {', '.join(FORMATS)}")
    spec = load(path, encoding, kind=".gait")
    return emit(spec, fmt), list(spec.diagnostics)


def run_compile(args: argparse.Namespace) -> int:
    fmt = output_format(args.output, args.format)
    text, diagnostics = compile_text(args.spec, fmt, args.encoding)
    _warn(diagnostics)
    if args.output == "-":
        sys.stdout.write(text)
        sys.stdout.flush()
    else:
        write_atomically(args.output, text)
    return 0
