"""The ``gaitc`` command line: parse arguments, dispatch to a command module, print errors.

The exit codes are :class:`gaitc.cli.exitcodes.ExitCode`; ``gaitc --help`` lists them.
"""

from __future__ import annotations

import argparse
import os
import signal
import sys
import threading
import traceback
from collections.abc import Sequence
from typing import Final

from gaitc.cli import reporting
from gaitc.cli.exitcodes import ExitCode, exit_code_help
from gaitc.diagnostics import GaitcError, UsageError, render_error
from gaitc.diagnostics.teardown import quiet_cudd_teardown

#: Options whose values may start with a minus sign (``--direction -y``, ``--goal -10,0``):
#: argparse would take such a value for an option, so :func:`attach_signed_values` joins it.
SIGNED_VALUES: Final = ("--direction", "--goal")


def attach_signed_values(argv: Sequence[str]) -> list[str]:
    """``argv`` with ``--direction -y`` written ``--direction=-y`` (and so for every option
    of :data:`SIGNED_VALUES`), up to a ``--`` that ends the options."""
    out: list[str] = []
    k = 0
    while k < len(argv):
        word = argv[k]
        if word == "--":
            out += argv[k:]
            break
        if word in SIGNED_VALUES and k + 1 < len(argv) and argv[k + 1].startswith("-") \
                and argv[k + 1] != "--":
            out.append(f"{word}={argv[k + 1]}")
            k += 2
            continue
        out.append(word)
        k += 1
    return out


class _Parser(argparse.ArgumentParser):
    commands: tuple[str, ...] = ()  # the subcommands' names (the top-level parser's)

    def error(self, message: str) -> None:  # type: ignore[override]
        raise UsageError(message, hint=_did_you_mean(message))


def _did_you_mean(message: str) -> str | None:
    """For argparse's "invalid choice: 'sytnh' (choose from ...)", the nearest choice."""
    import difflib
    import re

    found = re.search(r"invalid choice: '([^']*)' \(choose from (.*)\)", message)
    if found is None:
        return None
    choices = re.findall(r"'([^']*)'", found.group(2))
    close = difflib.get_close_matches(found.group(1), choices, n=1, cutoff=0.6)
    return f"did you mean '{close[0]}'?" if close else None


def build_parser(words: Sequence[str] | None = None) -> _Parser:
    """The command line's parser.  Given the command line ``words``, only the module of the
    command they name is imported and registered (the other commands' names are still
    known, in :attr:`_Parser.commands`), and ``--version`` alone registers none; without a
    command, or with an unknown one, every command is registered, for ``gaitc --help`` and
    the "did you mean" of a misspelling."""
    parser = _Parser(
        prog="gaitc",
        description="Compile .gait robot specifications to GR(1), synthesize and run controllers.",
        epilog=exit_code_help(codes=tuple(ExitCode)),
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    from gaitc import __version__
    from gaitc.cli.commands import COMMANDS, all_modules, command_module

    parser.add_argument("--version", action="version", version=f"gaitc {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=_Parser)
    chosen = _command_word(words) if words is not None else None
    bare = chosen is None and words is not None and "--version" in words
    if chosen in COMMANDS or bare:
        # argparse takes the first word that is no option for the command, and the top-level
        # options take no value, so that word is ``chosen``: the parsers of the others would
        # never be used (and took 2 ms of every start to build)
        if chosen is not None:
            command_module(chosen).register(sub)
        parser.commands = tuple(COMMANDS)
    else:
        for module in all_modules():
            module.register(sub)
        parser.commands = tuple(name for name in COMMANDS if name in sub.choices)
    return parser


def _command_word(words: Sequence[str]) -> str | None:
    """The command a command line names: its first word that is not an option (the
    top-level parser's options, --help and --version, take no value); None when --help
    comes first, since the top-level help lists every command."""
    for word in words:
        if word in ("--", "-h", "--help"):
            return None
        if not word.startswith("-"):
            return word
    return None


class Terminated(BaseException):
    """SIGTERM arrived: unwind (temporary files are removed, nothing is half-written).

    A BaseException, as KeyboardInterrupt is, so that no ``except Exception`` in library
    code (networkx's generators, for one) swallows it halfway through."""


class _Signals:
    """The SIGTERM and SIGINT of one run: each raises Terminated or KeyboardInterrupt where
    the run is, and the first is recorded.

    The record lets :func:`_run` report the signal even when a library's cleanup, hit
    halfway, raised some other exception in its place; once the run has returned (disarmed)
    a signal is only recorded, so that putting the handlers back cannot fail."""

    RAISES: Final = {signal.SIGTERM: Terminated, signal.SIGINT: KeyboardInterrupt}

    def __init__(self) -> None:
        self.received: int | None = None
        self.armed = True

    def __call__(self, signum: int, frame: object) -> None:
        if self.received is None:
            self.received = signum
        if self.armed:
            raise self.RAISES[signal.Signals(signum)]

    def ending(self) -> int | None:
        """The exit code of the signal received (its line printed), or None if none came."""
        return None if self.received is None else _ended_by(self.received)


#: The exit codes of runs a signal ended (their line printed already).
SIGNAL_CODES: Final = (ExitCode.INTERRUPTED, ExitCode.TERMINATED)


def _ended_by(signum: int) -> int:
    """Print the line of a run that ``signum`` ended and return its exit code."""
    if signum == signal.SIGINT:
        print("gaitc: interrupted", file=sys.stderr)
        return ExitCode.INTERRUPTED
    print("gaitc: terminated", file=sys.stderr)
    return ExitCode.TERMINATED


def main(argv: Sequence[str] | None = None) -> int:
    """Run gaitc with ``argv`` (default: ``sys.argv[1:]``) and return the exit code."""
    quiet_cudd_teardown()
    if threading.current_thread() is not threading.main_thread():
        return _run(argv, None)
    signals = _Signals()
    previous = {signal.SIGTERM: signal.signal(signal.SIGTERM, signals)}
    # Ctrl-C only where Python's own handler has it (a background job may ignore SIGINT)
    if signal.getsignal(signal.SIGINT) is signal.default_int_handler:
        previous[signal.SIGINT] = signal.signal(signal.SIGINT, signals)
    try:
        try:
            code = _run(argv, signals)
            # a signal whose exception some code dropped (Python prints it as "Exception
            # ignored") still ends the run as that signal
            ending = None if code in SIGNAL_CODES else signals.ending()
            return code if ending is None else ending
        finally:
            signals.armed = False  # from here on a signal is only recorded
            for signum, handler in previous.items():
                signal.signal(signum, handler)
    except (Terminated, KeyboardInterrupt):  # it came after _run had returned
        return _ended_by(signals.received or signal.SIGINT)


def _parse(parser: _Parser, words: list[str]) -> argparse.Namespace:
    """``parser.parse_args(words)``, except that CONTROLLER after an option (``simulate SPEC
    --steps 9 CONTROLLER``) is taken: argparse fills an optional positional together with
    the one before it, so it would refuse the word as unrecognized."""
    try:
        args, extra = parser.parse_known_args(words)
    except UsageError as err:  # '--env random SPEC': nargs='+' took SPEC as well
        if "--env" in words and err.message.endswith("required: SPEC"):
            raise UsageError(f"{err.message} (--env took the words after it as its own; "
                             "write SPEC [CONTROLLER] before --env)") from None
        raise
    if len(extra) == 1 and not extra[0].startswith("-") and getattr(args, "controller", 0) is None:
        args.controller = extra[0]
    elif extra:
        parser.error(f"unrecognized arguments: {' '.join(extra)}")
    return args


def _run(argv: Sequence[str] | None, signals: _Signals | None) -> int:
    words = attach_signed_values(list(sys.argv[1:] if argv is None else argv))
    # --json before parsing, for usage errors; after parsing, the command's own option
    as_json, command = reporting.json_requested(words), None
    try:
        parser = build_parser(words)
        command = reporting.command_named(words, parser.commands)
        args = _parse(parser, words)
        as_json = bool(getattr(args, "json", False))
        if getattr(args, "run", None) is None:
            parser.print_help(sys.stderr)
            return ExitCode.USAGE
        code: int = args.run(args)
        return code
    except GaitcError as err:
        ending = signals.ending() if signals is not None else None
        if ending is not None:  # the error came of the signal's unwinding
            return ending
        if isinstance(err, UsageError):
            print(f"gaitc: usage error: {err.message}", file=sys.stderr)
            if err.hint:
                print(f"  hint: {err.hint}", file=sys.stderr)
        else:
            print(render_error(err), file=sys.stderr)
        if as_json:
            reporting.print_json(reporting.error_document(command, err))
        return reporting.exit_code_of(err)
    except KeyboardInterrupt:
        return _ended_by(signal.SIGINT)
    except Terminated:
        return _ended_by(signal.SIGTERM)
    except BrokenPipeError:
        return ExitCode.OK
    except Exception as err:
        # a signal's exception may land in a library's cleanup, which then fails otherwise
        ending = signals.ending() if signals is not None else None
        if ending is not None:
            return ending
        # else a bug in gaitc, not in the user's input
        if os.environ.get("GAITC_DEBUG"):
            traceback.print_exc()
        print(
            f"gaitc: internal error: {type(err).__name__}: {err}\n"
            "  this is a bug in gaitc, not in your input; please report it with the command "
            "line and files (GAITC_DEBUG=1 prints the traceback)",
            file=sys.stderr,
        )
        if as_json:
            reporting.print_json(reporting.document(command, {
                "error": reporting.internal_error_json(err)}))
        return ExitCode.INTERNAL


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
