"""Shared pytest options (``--update-golden`` rewrites tests/golden/ from the current
output) and the fixtures several test files use: the two-leg shuttle spec ``tiny_spec``
(specs/shuttle_2leg.gait, copied to a temporary folder) and its session ``tiny``, and
``live_slugs``, the real SLUGS binary for the ``slugs``-marked family tests."""

from __future__ import annotations

import os
from pathlib import Path

import pytest
from fake_board import TINY

from gaitc.api.simulation import Session, session


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
