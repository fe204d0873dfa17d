"""Argument types shared by the commands (argparse turns their errors into usage errors)."""

from __future__ import annotations

import argparse
import math


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


def preference_list(value: str) -> tuple[str, ...]:
    """``--prefer``: a comma-separated order of the move preferences, or ``none``."""
    from diagnostics import UsageError
    from solver.preferences import preference_order

    try:
        return preference_order(value)
    except UsageError as err:
        raise argparse.ArgumentTypeError(err.message) from None


def add_prefer(parser: argparse.ArgumentParser, when: str = "") -> None:
    """The ``--prefer`` option (default: every preference, in the documented order)."""
    from solver.preferences import PREFERENCES

    parser.add_argument(
        "--prefer", type=preference_list, metavar="LIST",
        help=f"{when}the order of the move preferences among winning moves, comma-separated "
        f"(default {','.join(PREFERENCES)}; 'none': the solver's first move; "
        "docs/simulation.md)")
