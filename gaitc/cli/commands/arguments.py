"""Argument types shared by the commands (argparse turns their errors into usage errors)."""

from __future__ import annotations

import argparse
import math
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from gaitc.api.modes import Semantics


def positive_seconds(value: str) -> float:
    """A positive, finite number of seconds (``--timeout``): ``nan``, ``inf``, 0 and negative
    values are refused rather than silently ignored."""
    try:
        seconds = float(value)
    except ValueError:
        raise argparse.ArgumentTypeError(f"'{value}' is not a number of seconds") from None
    if not math.isfinite(seconds) or seconds <= 0:
        raise argparse.ArgumentTypeError(
            f"must be a positive, finite number of seconds, not {value}")
    return seconds


def probability(value: str) -> float:
    """A probability in [0, 1] (``--wear``), as a number or a percentage (``2%``)."""
    text = value.strip()
    try:
        p = float(text[:-1]) / 100 if text.endswith("%") else float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"'{value}' is not a probability") from None
    if not math.isfinite(p) or not 0.0 <= p <= 1.0:
        raise argparse.ArgumentTypeError(f"must be a probability in [0, 1], not {value}")
    return p


def positive_megabytes(value: str) -> int:
    """A positive whole number of megabytes (``--memory-limit``)."""
    try:
        mb = int(value)
    except ValueError:
        raise argparse.ArgumentTypeError(f"'{value}' is not a whole number of megabytes"
                                         ) from None
    if mb <= 0:
        raise argparse.ArgumentTypeError(f"must be a positive number of megabytes, not {value}")
    return mb


def positive_count(value: str) -> int:
    """A positive whole number (``--max-nodes``)."""
    try:
        count = int(value)
    except ValueError:
        raise argparse.ArgumentTypeError(f"'{value}' is not a whole number") from None
    if count <= 0:
        raise argparse.ArgumentTypeError(f"must be a positive whole number, not {value}")
    return count


def output_file(value: str) -> str:
    """An output file (``-o``, ``--out``) checked before any work: its folder must exist and
    be writable, and it must not be a folder; ``-`` is standard output."""
    from gaitc.diagnostics import UsageError
    from gaitc.diagnostics.files import check_writable

    if value != "-":
        try:
            check_writable(value)
        except UsageError as err:
            raise argparse.ArgumentTypeError(err.message) from None
    return value


def run_file(value: str) -> str:
    """An output run file (``--out`` of simulate, drive, explain): a writable ``.jsonl`` or
    ``.csv`` file (:func:`output_file`)."""
    from gaitc.api.runs import run_format
    from gaitc.diagnostics import UsageError

    try:
        run_format(value)
    except UsageError as err:
        raise argparse.ArgumentTypeError(err.message) from None
    return output_file(value)


def positive_whole(value: str) -> int:
    """A whole number of at least 0 (``--max-steps``, ``--steps``)."""
    try:
        count = int(value)
    except ValueError:
        raise argparse.ArgumentTypeError(f"'{value}' is not a whole number") from None
    if count < 0:
        raise argparse.ArgumentTypeError(f"must not be negative, not {value}")
    return count


def preference_list(value: str) -> tuple[str, ...]:
    """``--prefer``: a comma-separated order of the move preferences, or ``none``."""
    from gaitc.api.solving import preference_order
    from gaitc.diagnostics import UsageError

    try:
        return preference_order(value)
    except UsageError as err:
        raise argparse.ArgumentTypeError(err.message) from None


def add_prefer(parser: argparse.ArgumentParser, when: str = "") -> None:
    """The ``--prefer`` option (default: every preference, in the documented order)."""
    from gaitc.api.solving import PREFERENCES

    parser.add_argument(
        "--prefer", type=preference_list, metavar="LIST",
        help=f"{when}the order of the move preferences among winning moves, comma-separated "
        f"(default {','.join(PREFERENCES)}; 'none': the solver's first move; "
        "docs/simulation.md)")



def semantics_of(args: argparse.Namespace) -> Semantics:
    """The semantics ``--robotics-semantics`` asks for (else the default one)."""
    from gaitc.api.modes import Semantics

    return Semantics.ROBOTICS if args.robotics_semantics else Semantics.DEFAULT


def mcap_file(value: str) -> str:
    """An MCAP recording to write (``--record``, ``--mcap``): a writable ``.mcap`` file."""
    if not value.lower().endswith(".mcap"):
        raise argparse.ArgumentTypeError(f"'{value}': an MCAP recording is named FILE.mcap")
    return output_file(value)


def seconds_or_zero(value: str) -> float:
    """A finite number of at least 0 (``--rate``)."""
    try:
        number = float(value)
    except ValueError:
        raise argparse.ArgumentTypeError(f"'{value}' is not a number") from None
    if not math.isfinite(number) or number < 0:
        raise argparse.ArgumentTypeError(f"must be a finite number of at least 0, not {value}")
    return number
