"""``gaitc lint`` and ``gaitc compile``: check a .gait file, or lower it to a SLUGS/LTL text.

``compile`` runs parse, check, lowering (thesis eqs. 3.3-3.9) and one emitter; warnings go
to stderr in the standard layout, and the output file is replaced atomically.
"""

from __future__ import annotations

import argparse
import contextlib
import os
import sys
import tempfile
from pathlib import Path
from typing import Any

from ltlcompiler.encoding import ENCODINGS
from slugs_bridge.diagnostics import Diagnostic, UsageError, render_diagnostic
from slugs_bridge.spec import GR1Spec

FORMATS = ("structuredslugs", "slugsin", "ltl")


def register(subparsers: Any) -> None:
    lint = subparsers.add_parser(
        "lint", help="check a .gait file and print its warnings",
        description="Parse and check SPEC, lower it in both encodings, print warnings. "
        "Exit 0 when there is no error (warnings allowed), 1 on an error.")
    lint.add_argument("spec", metavar="SPEC", help="a .gait file")
    lint.set_defaults(run=run_lint)

    comp = subparsers.add_parser(
        "compile", help="compile a .gait file to structuredslugs, slugsin or LTL text",
        description="Compile SPEC to a GR(1) specification (thesis eqs. 3.3-3.9). "
        "Exit 0 on success, 1 on an error in SPEC, 2 on a bad command line.")
    comp.add_argument("spec", metavar="SPEC", help="a .gait file")
    comp.add_argument("-o", "--output", default="-", metavar="OUT",
                      help="output file, '-' for stdout (default); replaced atomically")
    comp.add_argument("--format", choices=FORMATS, default="structuredslugs",
                      help="output format (default structuredslugs)")
    comp.add_argument("--encoding", choices=ENCODINGS, default="onehot",
                      help="onehot: a proposition per region/gait/health level (the thesis); "
                      "binary: integer variables (default onehot)")
    comp.set_defaults(run=run_compile)


def _warn(diagnostics: list[Diagnostic]) -> None:
    for diag in diagnostics:
        print(render_diagnostic(diag), file=sys.stderr)


def run_lint(args: argparse.Namespace) -> int:
    from ltlcompiler.frontend import load_model
    from ltlcompiler.lowering import lower

    model, diagnostics = load_model(args.spec)
    for encoding in ENCODINGS:
        lower(model, encoding)
    _warn(diagnostics)
    return 0


def compile_text(path: str, fmt: str = "structuredslugs", encoding: str = "onehot"
                 ) -> tuple[str, list[Diagnostic]]:
    """The text of the .gait file at ``path`` compiled to ``fmt``, plus the warnings."""
    from ltlcompiler.frontend import load_model
    from ltlcompiler.lowering import lower

    if fmt not in FORMATS:
        raise UsageError(f"unknown format '{fmt}': use one of {', '.join(FORMATS)}")
    model, diagnostics = load_model(path)
    return emit(lower(model, encoding), fmt), diagnostics


def emit(spec: GR1Spec, fmt: str) -> str:
    """``spec`` written in ``fmt`` (slugsin bit-blasts integer variables first)."""
    if fmt == "structuredslugs":
        from slugs_bridge.structured import emit_structuredslugs

        text: str = emit_structuredslugs(spec)
        return text
    if fmt == "slugsin":
        from slugs_bridge.slugsin import emit_slugsin

        if spec.has_integers:
            from slugs_bridge.bitblast import bitblast

            spec = bitblast(spec)
        return emit_slugsin(spec)
    from slugs_bridge.ltltext import emit_ltl

    ltl: str = emit_ltl(spec)
    return ltl


def write_atomically(path: str, text: str) -> None:
    """Replace ``path`` by ``text`` via a temporary file and a rename: never half-written."""
    target = Path(path)
    tmp: str | None = None
    try:
        fd, tmp = tempfile.mkstemp(prefix=f".{target.name}.", suffix=".tmp",
                                   dir=target.parent if str(target.parent) else ".")
        with os.fdopen(fd, "w", encoding="utf-8", newline="\n") as out:
            out.write(text)
            out.flush()
            os.fsync(out.fileno())
        os.replace(tmp, target)
        tmp = None
    except OSError as err:
        raise UsageError(f"cannot write '{path}': {err.strerror or err}") from None
    finally:
        if tmp is not None:
            with contextlib.suppress(OSError):
                os.unlink(tmp)


def run_compile(args: argparse.Namespace) -> int:
    text, diagnostics = compile_text(args.spec, args.format, args.encoding)
    _warn(diagnostics)
    if args.output == "-":
        sys.stdout.write(text)
        sys.stdout.flush()
    else:
        write_atomically(args.output, text)
    return 0
