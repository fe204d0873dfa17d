"""Output paths and recordings that used to end in an internal error (issue 38): a link
that points to itself, a file name too long, a file where a folder should be, a full
device, and CSV rows the csv module cannot read. Each is now one line naming the path or
the file and line, with the usage (2) or user (1) exit code."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from gaitc.cli import main

ROOT = Path(__file__).resolve().parents[2]
PATROL = str(ROOT / "specs" / "patrol_2x2.gait")
ONE_LEG = ROOT / "tests" / "data" / "softmodels" / "one_leg.yaml"


def _last(capsys: pytest.CaptureFixture[str]) -> str:
    return capsys.readouterr().err.strip().splitlines()[0]


def test_a_link_to_itself(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    loop = tmp_path / "loop.json"
    loop.symlink_to(loop)
    assert main(["synth", PATROL, "-o", str(loop)]) == 2
    assert _last(capsys) == (f"gaitc: usage error: argument -o/--output: cannot write "
                             f"'{loop}': the symbolic link points to itself")


def test_a_name_too_long(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    name = tmp_path / ("x" * 300 + ".json")
    assert main(["synth", PATROL, "-o", str(name)]) == 2
    assert _last(capsys).endswith(f"cannot write '{name}': the file name is too long for "
                                  "the file system")


def test_a_file_where_the_drawings_go(tmp_path: Path,
                                      capsys: pytest.CaptureFixture[str]) -> None:
    taken = tmp_path / "existing.txt"
    taken.write_text("mine", encoding="utf-8")
    robot = str(ROOT / "specs" / "robots" / "symmetric6.yaml")
    assert main(["gaits", robot, "--svg", str(taken)]) == 2
    assert _last(capsys) == (f"gaitc: usage error: cannot write into '{taken}': it is a "
                             "file, not a folder")
    assert taken.read_text(encoding="utf-8") == "mine"


@pytest.mark.skipif(not os.path.exists("/dev/full"), reason="needs /dev/full")
def test_a_full_device(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["synth", PATROL, "-o", "/dev/full"]) == 2
    assert _last(capsys) == "gaitc: usage error: cannot write '/dev/full': No space left on device"


def test_a_field_over_the_csv_limit(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    big = tmp_path / "legs.csv"
    big.write_text("leg,cycle,level,intensity\nL1,1,2," + "9" * 140_000 + "\n",
                   encoding="utf-8")
    assert main(["calibrate", str(big), "-o", str(tmp_path / "out.sensing.yaml")]) == 1
    assert _last(capsys) == (f"{big}:2:1: error: line 2 is not a CSV row: field larger than "
                             "field limit (131072)")
    assert not (tmp_path / "out.sensing.yaml").exists()


def test_a_carriage_return_inside_a_line(tmp_path: Path,
                                         capsys: pytest.CaptureFixture[str]) -> None:
    curve = tmp_path / "curv.csv"
    curve.write_bytes(b"time,curvature\n0.0,0.01\n0.1,0.0\r2\n")
    robot = tmp_path / "one_leg.yaml"
    robot.write_bytes(ONE_LEG.read_bytes())
    assert main(["characterize", str(robot), "L1", "--curvature", str(curve)]) == 1
    assert _last(capsys) == (f"{curve}:3:1: error: line 3 is not a CSV row: a carriage "
                             "return (\\r) inside the line")
    assert robot.read_bytes() == ONE_LEG.read_bytes()


# ---------------------------------------------------------------- issue 48
@pytest.mark.skipif(not os.path.isdir("/proc/self"), reason="needs /proc")
def test_an_output_folder_that_takes_no_file(tmp_path: Path,
                                             capsys: pytest.CaptureFixture[str]) -> None:
    compact = tmp_path / "patrol.compact.json"
    assert main(["synth", PATROL, "--compact", "-o", str(compact)]) == 0
    capsys.readouterr()
    assert main(["codegen", PATROL, str(compact), "--target", "c", "-o", "/proc/self"]) == 2
    assert _last(capsys) == ("gaitc: usage error: cannot write into '/proc/self': no file can "
                             "be made in it")


def test_an_examples_folder_name_too_long(tmp_path: Path,
                                          capsys: pytest.CaptureFixture[str]) -> None:
    folder = tmp_path / ("x" * 300)
    assert main(["examples", str(folder)]) == 2
    assert _last(capsys) == (f"gaitc: usage error: cannot copy the examples into '{folder}': "
                             "the file name is too long for the file system")


def test_examples_force_replaces_a_link_and_never_writes_its_target(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    folder, victim = tmp_path / "ex", tmp_path / "precious.txt"
    folder.mkdir()
    victim.write_text("precious\n", encoding="utf-8")
    victim.chmod(0o640)
    link = folder / "patrol_2x2.gait"
    link.symlink_to(victim)
    assert main(["examples", str(folder)]) == 2  # a link counts as a file that exists
    assert _last(capsys) == (f"gaitc: usage error: '{link}' exists; copy the examples into a "
                             "new folder, or replace 1 existing file(s) with --force")
    assert main(["examples", str(folder), "--force"]) == 0
    assert victim.read_text(encoding="utf-8") == "precious\n"
    assert victim.stat().st_mode & 0o777 == 0o640
    assert not link.is_symlink()
    assert link.read_bytes() == (ROOT / "gaitc" / "examples" / "patrol_2x2.gait").read_bytes()
    dangling = folder / "shuttle_2leg.gait"
    dangling.unlink()
    dangling.symlink_to(tmp_path / "made-through-the-link.gait")
    assert main(["examples", str(folder), "--force"]) == 0
    assert not (tmp_path / "made-through-the-link.gait").exists()
    assert not dangling.is_symlink()


def test_examples_refuse_a_linked_subfolder(tmp_path: Path,
                                            capsys: pytest.CaptureFixture[str]) -> None:
    folder, elsewhere = tmp_path / "ex", tmp_path / "elsewhere"
    folder.mkdir()
    elsewhere.mkdir()
    (folder / "robots").symlink_to(elsewhere)
    assert main(["examples", str(folder), "--force"]) == 2
    assert _last(capsys) == (f"gaitc: usage error: cannot copy the examples into "
                             f"'{folder / 'robots'}': it is a symbolic link or a file, not a "
                             "folder; remove it or choose another folder")
    assert list(elsewhere.iterdir()) == [] and list(folder.iterdir()) == [folder / "robots"]


def test_a_nul_in_an_output_folder_is_a_usage_error(tmp_path: Path,
                                                    capsys: pytest.CaptureFixture[str]) -> None:
    """Only a caller in Python can pass a NUL (fuzz campaign of issue 48)."""
    bad = str(tmp_path / "a\0b")
    assert main(["examples", bad]) == 2
    assert "a file name cannot hold a NUL byte" in capsys.readouterr().err
    controller = tmp_path / "c.json"
    spec = str(Path(__file__).resolve().parents[2] / "specs" / "patrol_2x2.gait")
    assert main(["synth", spec, "--compact", "-o", str(controller)]) == 0
    capsys.readouterr()
    assert main(["codegen", spec, str(controller), "--target", "c", "-o", bad]) == 2
    assert "a file name cannot hold a NUL byte" in capsys.readouterr().err


def test_json_output_stays_utf8_for_a_path_of_other_bytes(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    import json

    spec = str(Path(__file__).resolve().parents[2] / "specs" / "patrol_2x2.gait")
    out = os.fsdecode(os.fsencode(str(tmp_path)) + b"/\xff.structuredslugs")
    assert main(["compile", spec, "-o", out, "--json"]) == 0
    line = capsys.readouterr().out
    line.encode("utf-8")  # no lone surrogate left to print
    assert json.loads(line)["output"] == out
