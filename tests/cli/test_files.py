"""Result files get the mode an ordinary file gets (gaitc/diagnostics/files.py)."""

from __future__ import annotations

import os
import stat
from collections.abc import Iterator
from pathlib import Path

import pytest

from gaitc.cli import main
from gaitc.diagnostics.files import write_atomically


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


def test_a_symlink_is_followed_and_kept(tmp_path: Path) -> None:
    real = tmp_path / "real.txt"
    real.write_text("old", encoding="utf-8")
    link = tmp_path / "link.txt"
    link.symlink_to(real)
    write_atomically(link, "new")
    assert link.is_symlink() and real.read_text(encoding="utf-8") == "new"


def test_devices_and_fifos_are_written_in_place(tmp_path: Path) -> None:
    import threading

    write_atomically("/dev/null", "discarded")
    assert Path("/dev/null").is_char_device()  # not replaced by a regular file
    fifo = tmp_path / "pipe"
    os.mkfifo(fifo)
    got: list[bytes] = []
    reader = threading.Thread(target=lambda: got.append(fifo.read_bytes()))
    reader.start()
    write_atomically(fifo, "through the pipe")
    reader.join(timeout=10)
    assert got == [b"through the pipe"] and stat.S_ISFIFO(fifo.stat().st_mode)


def test_a_directory_is_not_replaced(tmp_path: Path) -> None:
    from gaitc.diagnostics import UsageError

    folder = tmp_path / "out"
    folder.mkdir()
    with pytest.raises(UsageError, match="not a regular file"):
        write_atomically(folder, "x")
    assert folder.is_dir()


def test_synth_writes_only_a_verified_controller(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                 capsys: pytest.CaptureFixture[str]) -> None:
    import gaitc.forms.synthesis
    from gaitc.verifier.strategy import VerificationReport

    def failing(*_args: object, **_kwargs: object) -> VerificationReport:
        return VerificationReport(False, ("planted problem",))

    monkeypatch.setattr(gaitc.forms.synthesis, "prove", failing)  # the proof synth runs
    out = tmp_path / "c.json"
    assert main(["synth", "specs/patrol_2x2.gait", "-o", str(out)]) == 1
    assert not out.exists()
    assert "was not written" in capsys.readouterr().out


@pytest.mark.parametrize("value", ["nan", "inf", "-1", "0", "soon"])
def test_bad_timeouts_are_usage_errors(value: str) -> None:
    assert main(["check", "specs/patrol_2x2.gait", "--timeout", value]) == 2
    assert main(["explain", "specs/patrol_2x2.gait", "--timeout", value]) == 2
