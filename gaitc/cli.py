"""The ``gaitc`` command line: parse arguments, dispatch to a command module, print errors.

Exit codes (shared by every subcommand unless its help says otherwise):
0 success, 1 a user error in an input file, 2 a usage error, 3 unrealizable
(``check``/``synth``), 4 the solver could not finish (timeout, memory, SLUGS failure),
70 an internal error (a bug in gaitc; ``GAITC_DEBUG=1`` shows the traceback).
"""

from __future__ import annotations

import argparse
import os
import sys
import traceback
from collections.abc import Sequence

from diagnostics import GaitcError, SolverError, UsageError, render_error
from gaitc.commands import COMMAND_MODULES
from gaitc.exitcodes import EXIT_INTERNAL, EXIT_OK, EXIT_SOLVER, EXIT_USAGE, EXIT_USER


class _Parser(argparse.ArgumentParser):
    def error(self, message: str) -> None:  # type: ignore[override]
        raise UsageError(message)


def build_parser() -> argparse.ArgumentParser:
    parser = _Parser(
        prog="gaitc",
        description="Compile .gait robot specifications to GR(1), synthesize and run controllers.",
    )
    from gaitc import __version__

    parser.add_argument("--version", action="version", version=f"gaitc {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=_Parser)
    for module in COMMAND_MODULES:
        module.register(sub)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    """Run gaitc with ``argv`` (default: ``sys.argv[1:]``) and return the exit code."""
    parser = build_parser()
    try:
        args = parser.parse_args(list(sys.argv[1:] if argv is None else argv))
        if getattr(args, "run", None) is None:
            parser.print_help(sys.stderr)
            return EXIT_USAGE
        code: int = args.run(args)
        return code
    except UsageError as err:
        print(f"gaitc: usage error: {err.message}", file=sys.stderr)
        return EXIT_USAGE
    except GaitcError as err:
        print(render_error(err), file=sys.stderr)
        return EXIT_SOLVER if isinstance(err, SolverError) else EXIT_USER
    except KeyboardInterrupt:
        print("gaitc: interrupted", file=sys.stderr)
        return 130
    except BrokenPipeError:
        return EXIT_OK
    except Exception as err:  # a bug in gaitc, not in the user's input
        if os.environ.get("GAITC_DEBUG"):
            traceback.print_exc()
        print(
            f"gaitc: internal error: {type(err).__name__}: {err}\n"
            "  this is a bug in gaitc, not in your input; please report it with the command "
            "line and files (GAITC_DEBUG=1 prints the traceback)",
            file=sys.stderr,
        )
        return EXIT_INTERNAL


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
