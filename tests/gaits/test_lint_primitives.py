"""``gaitc lint`` pairs each gait with its valve primitive (issue 5) through the CLI."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest

import gaitc
from gaitc.cli import main

SPECS = Path(__file__).resolve().parents[2] / "specs"


@pytest.fixture
def radial(tmp_path: Path) -> Path:
    shutil.copytree(SPECS / "robots", tmp_path / "robots")
    spec = tmp_path / "radial8_patrol.gait"
    shutil.copy(SPECS / "radial8_patrol.gait", spec)
    return spec


def test_bound_primitives_agree_with_the_gaits(radial: Path, capsys: pytest.CaptureFixture[str]
                                               ) -> None:
    assert main(["lint", str(radial)]) == 0
    assert "error" not in capsys.readouterr().err


def test_a_primitive_searches_the_model_for_the_gaits_legs(
    radial: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """Issue 49: no stored gait of L6 and L7 goes north, but the robot file's spring-damper
    model has one; before, the clause took another stored gait and lint said it pressurised
    other legs."""
    text = radial.read_text(encoding="utf-8")
    radial.write_text(text.replace("gait north_a uses L6, L8", "gait north_a uses L6, L7"),
                      encoding="utf-8")
    assert main(["lint", str(radial)]) == 0
    assert "error" not in capsys.readouterr().err


def test_legs_the_model_cannot_move_that_way_are_an_error(
    radial: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    text = radial.read_text(encoding="utf-8")
    radial.write_text(text.replace("gait north_a uses L6, L8", "gait north_a uses L2, L3"),
                      encoding="utf-8")
    assert main(["lint", str(radial)]) == 1
    err = capsys.readouterr().err
    assert (f"{radial}:16:38: error: gait north_a: no gait of legs L2, L3 moves towards +y "
            "in robots/radial8.yaml's spring-damper model; legs L8, L6 do") in err


def test_inline_valves_with_the_wrong_legs_are_an_error(
    radial: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    text = radial.read_text(encoding="utf-8")
    radial.write_text(text.replace("valves 00010000, 10000000", "valves 00010000, 01000000"),
                      encoding="utf-8")
    assert main(["lint", str(radial)]) == 1
    assert "south_c" in capsys.readouterr().err


def test_unbound_gaits_are_reported_once_one_gait_binds_a_primitive(
    radial: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    text = radial.read_text(encoding="utf-8")
    radial.write_text(text.replace(' primitive "robots/radial8.yaml" direction -x', "", 1),
                      encoding="utf-8")
    assert main(["lint", str(radial)]) == 0
    err = capsys.readouterr().err
    assert "warning: gait west_a has no primitive" in err


def test_specs_without_primitives_stay_quiet_unless_asked(
    capsys: pytest.CaptureFixture[str]
) -> None:
    spec = str(SPECS / "patrol_2x2.gait")
    assert main(["lint", spec]) == 0
    assert "primitive" not in capsys.readouterr().err
    assert main(["lint", "--primitives", spec]) == 0
    assert capsys.readouterr().err.count("has no primitive") == 4


@pytest.mark.parametrize("name", ["patrol_2x2.gait", "thesis_robot_a.gait"])
def test_the_suggested_valves_are_readable_and_pass_lint(
    name: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    import re

    spec = tmp_path / name
    shutil.copy(SPECS / name, spec)
    assert main(["lint", "--primitives", str(spec)]) == 0
    err = capsys.readouterr().err
    hints = re.findall(r"^  hint: add valves ([01, ]+) \(", err, re.MULTILINE)
    gaits = re.findall(r"warning: gait (\w+) has no primitive", err)
    assert len(hints) == len(gaits) > 0
    assert "\\" not in err
    lines = spec.read_text(encoding="utf-8").splitlines()
    for gait, valves in zip(gaits, hints, strict=True):
        at = next(i for i, t in enumerate(lines) if t.startswith(f"gait {gait} "))
        lines[at] += f" valves {valves}"
    spec.write_text("\n".join(lines) + "\n", encoding="utf-8")
    assert main(["lint", "--primitives", str(spec)]) == 0
    assert capsys.readouterr().err == ""


def test_suggested_valves_keep_the_declared_firing_order() -> None:
    """Issue 34: ``uses L2, L1`` fires L2 first, so the suggestion pressurises L2 first, and
    gaits that fire the same legs in opposite orders get different suggestions."""
    text = ("legs L1..L2 health 2\ngait north uses L1, L2 moves north\n"
            "gait south uses L2, L1 moves south\ngrid 2 x 1\nstart r0\n")
    hints = {d.message.split()[1]: d.hint for d in gaitc.lint(
        gaitc.parse(text, name="order.gait"), primitives=True)}
    assert hints["north"] is not None and hints["north"].startswith(
        "add valves 10, 01 (L1, then L2 pressurised")
    assert hints["south"] is not None and hints["south"].startswith(
        "add valves 01, 10 (L2, then L1 pressurised")


def test_two_directions_with_one_valve_sequence_are_a_warning() -> None:
    text = ("legs L1..L2 health 2\ngait north uses L1, L2 moves north valves 10, 01\n"
            "gait south uses L2, L1 moves south valves 10, 01\ngrid 2 x 1\nstart r0\n")
    found = [d for d in gaitc.lint(gaitc.parse(text, name="same.gait"))
             if "same valve sequence" in d.message]
    assert [(d.severity, d.message) for d in found] == [(
        "warning", "gaits north and south move the robot differently but run the same valve "
        "sequence (10, 01): the robot cannot do both")]
    assert found[0].span is not None and found[0].span.line == 3
    # the same sequence in the same direction is two names for one gait: no warning
    twin = text.replace("moves south", "moves north")
    assert not [d for d in gaitc.lint(gaitc.parse(twin, name="twin.gait"))
                if "same valve sequence" in d.message]
