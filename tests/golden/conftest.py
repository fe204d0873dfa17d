"""The ``--update-golden`` switch for tests/test_golden.py: rewrite the expected outputs.

Pytest reads command-line options only from conftests it loads at start-up, so name
this folder on the command line: ``pytest tests/golden tests/test_golden.py
--update-golden`` (or set ``GAITC_UPDATE_GOLDEN=1``).
"""

from __future__ import annotations

import pytest


def pytest_addoption(parser: pytest.Parser) -> None:
    parser.addoption("--update-golden", action="store_true", default=False,
                     help="rewrite the golden files in tests/golden/ from the current output")
