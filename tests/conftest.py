"""Shared pytest options (``--update-golden`` rewrites tests/golden/ from the current
output), the ``slow`` mark of the functions listed in tests/slow_tests.txt (written by
tools/slow_tests.py from measured times), and the fixtures several test files use: the
two-leg shuttle spec ``tiny_spec`` (specs/shuttle_2leg.gait, copied to a temporary folder)
and its session ``tiny``, and ``live_slugs``, the real SLUGS binary for the
``slugs``-marked family tests."""

from __future__ import annotations

import os
from pathlib import Path

import pytest
from fake_board import TINY
from slow_marks import listed_slow

from gaitc.api.simulation import Session, session


def pytest_collection_modifyitems(config: pytest.Config, items: list[pytest.Item]) -> None:
    """Mark ``slow`` every case of the functions tests/slow_tests.txt names."""
    slow = listed_slow()
    for item in items:
        if item.nodeid.split("[", 1)[0] in slow:
            item.add_marker(pytest.mark.slow)


def pytest_addoption(parser: pytest.Parser) -> None:
    parser.addoption(
        "--update-golden",
        action="store_true",
        default=False,
        help="rewrite the golden files in tests/golden/ from the current output",
    )


@pytest.fixture()
def tiny_spec(tmp_path: Path) -> Path:
    path = tmp_path / "tiny.gait"
    path.write_text(TINY, encoding="utf-8")
    return path


@pytest.fixture()
def tiny(tiny_spec: Path) -> Session:
    loaded = session(str(tiny_spec), None)
    assert loaded is not None
    return loaded


@pytest.fixture()
def live_slugs() -> str:
    """The real SLUGS binary ($SLUGS or on PATH); the test is skipped without one."""
    from slugs_bridge.runner import find_slugs

    binary = find_slugs(os.environ.get("SLUGS"))
    if binary is None or Path(binary).name != "slugs":
        pytest.skip("no slugs binary on PATH or in $SLUGS")
    return binary
