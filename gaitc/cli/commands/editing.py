"""The ``lsp`` command: the language server editors start for ``.gait`` files.

The work lives in :mod:`gaitc.lsp.server`; this module only registers the command.
"""

from __future__ import annotations

import argparse
from typing import Any

from gaitc.cli.exitcodes import ExitCode


def register(sub: Any) -> None:
    p = sub.add_parser(
        "lsp",
        help="the language server for .gait files (editors start it)",
        description="Serve the Language Server Protocol over standard input and output: "
        "diagnostics as you type, hover, go to definition, references, completion, rename, "
        "quick fixes and verified repairs, highlighting and an outline for .gait files. "
        "Editors start it (docs/editors.md); it is not meant to be run by hand.",
    )
    p.add_argument("--stdio", action="store_true",
                   help="talk over standard input and output (the default and only way)")
    p.set_defaults(run=run_lsp)


def run_lsp(args: argparse.Namespace) -> int:
    del args
    from gaitc.lsp.server import serve

    serve()
    return ExitCode.OK
