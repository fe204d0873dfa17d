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
