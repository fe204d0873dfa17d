"""A controller file is read once per command (issue 61): the encoding the file records and
the controller itself come from one reading, whatever the command and the form."""

from __future__ import annotations

import sys
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

import gaitc
from gaitc.cli import main
from gaitc.diagnostics import files

ROOT = Path(__file__).resolve().parents[2]
SHUTTLE = ROOT / "specs" / "shuttle_2leg.gait"


@pytest.fixture
def reads(monkeypatch: pytest.MonkeyPatch) -> Iterator[list[str]]:
    """The paths read through ``read_input``, wherever a module bound the name."""
    original = files.read_input
    seen: list[str] = []

    def counted(path: Any, *args: Any, **kwargs: Any) -> bytes:
        seen.append(str(path))
        return original(path, *args, **kwargs)

    for module in list(sys.modules.values()):
        if getattr(module, "read_input", None) is original:
            monkeypatch.setattr(module, "read_input", counted)
    yield seen


@pytest.mark.parametrize("form", ["explicit", "symbolic", "compact"])
def test_each_command_reads_the_controller_file_once(
        form: str, tmp_path: Path, reads: list[str], capsys: pytest.CaptureFixture[str]) -> None:
    controller = tmp_path / f"shuttle.{form}.json"
    gaitc.synthesize(gaitc.load(SHUTTLE, "binary"), form=form).save(controller)
    commands = {
        "verify": ["verify", str(SHUTTLE), str(controller)],
        "simulate": ["simulate", str(SHUTTLE), str(controller), "--steps", "5", "--quiet"],
        "drive": ["drive", str(SHUTTLE), str(controller), "--steps", "3", "--quiet"],
    }
    for name, words in commands.items():
        reads.clear()
        assert main(words) == 0, (name, capsys.readouterr())
        assert reads.count(str(controller)) == 1, (name, reads)
    capsys.readouterr()
    reads.clear()
    played = gaitc.player(SHUTTLE, controller)
    assert played.choices() and reads.count(str(controller)) == 1, reads
