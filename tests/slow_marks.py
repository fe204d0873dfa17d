"""The test functions tests/slow_tests.txt names, which tests/conftest.py marks ``slow``
(the list is written by tools/slow_tests.py from measured times)."""

from __future__ import annotations

from pathlib import Path
from typing import Final

#: The functions the quick run leaves out, one ``path::function`` a line.
SLOW_LIST: Final = Path(__file__).resolve().parent / "slow_tests.txt"


def listed_slow() -> frozenset[str]:
    """The ``path::function`` names of tests/slow_tests.txt (comments and blanks left out)."""
    lines = SLOW_LIST.read_text(encoding="utf-8").splitlines()
    return frozenset(line.strip() for line in lines
                     if line.strip() and not line.lstrip().startswith("#"))
