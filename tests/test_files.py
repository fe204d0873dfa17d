"""Result files get the mode an ordinary file gets (diagnostics/files.py)."""

from __future__ import annotations

import os
import stat
from collections.abc import Iterator
from pathlib import Path

import pytest

from diagnostics.files import write_atomically
from gaitc.cli import main


@pytest.fixture
def umask() -> Iterator[None]:
    old = os.umask(0o022)
    yield
    os.umask(old)


def _mode(path: Path) -> int:
    return stat.S_IMODE(path.stat().st_mode)


@pytest.mark.usefixtures("umask")
def test_new_files_follow_the_umask(tmp_path: Path) -> None:
    write_atomically(tmp_path / "a.txt", "x")
    assert _mode(tmp_path / "a.txt") == 0o644
    os.umask(0o077)
    write_atomically(tmp_path / "b.txt", "x")
    assert _mode(tmp_path / "b.txt") == 0o600


@pytest.mark.usefixtures("umask")
def test_a_replaced_file_keeps_its_mode(tmp_path: Path) -> None:
    target = tmp_path / "c.txt"
    target.write_text("old", encoding="utf-8")
    target.chmod(0o640)
    write_atomically(target, "new")
    assert _mode(target) == 0o640 and target.read_text(encoding="utf-8") == "new"


@pytest.mark.usefixtures("umask")
def test_commands_write_ordinary_files(tmp_path: Path) -> None:
    out = tmp_path / "patrol.structuredslugs"
    assert main(["compile", "specs/patrol_2x2.gait", "-o", str(out)]) == 0
    controller = tmp_path / "patrol.json"
    assert main(["synth", "specs/patrol_2x2.gait", "-o", str(controller)]) == 0
    assert _mode(out) == 0o644 and _mode(controller) == 0o644
