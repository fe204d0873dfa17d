"""The robot file's ``model: spring_damper:`` section: values read, errors word for word."""

from __future__ import annotations

from pathlib import Path

import pytest

from gaitc.diagnostics import render_error
from gaitc.gaitgraph.robot import load_robot
from gaitc.models.fields import ModelFileError
from gaitc.models.spring_damper.description import load_spring_damper, parse_spring_damper

ROBOTS = Path(__file__).parents[2] / "specs" / "robots"
ONE_LEG = Path(__file__).parents[1] / "data" / "softmodels" / "one_leg.yaml"


def test_radial8_reads_in_si_units() -> None:
    robot = load_spring_damper(ROBOTS / "radial8.yaml")
    assert [x.name for x in robot.limbs] == [f"L{i}" for i in range(1, 9)]
    l2 = robot.limbs[1]
    assert l2.position == pytest.approx((0.035355, 0.035355, 0.0))
    assert l2.segments[0].length == pytest.approx(0.06)
    assert l2.segments[0].rest_curvature == pytest.approx(22.0)
    assert dict(l2.stiffness)["1"][2][2] == pytest.approx(250.0)
    assert l2.damping == pytest.approx(1.5)
    assert l2.friction.outward.static == 1.2 and l2.friction.inward.kinetic == 0.1
    assert l2.valves == (1,)
    assert robot.mass == pytest.approx(0.4)
    assert robot.period == 6.0


def test_every_robot_file_still_loads_for_the_gait_graph() -> None:
    for path in sorted(ROBOTS.glob("*.yaml")):
        assert load_robot(path).legs


def _error(text: str) -> str:
    with pytest.raises(ModelFileError) as info:
        parse_spring_damper(text, "r.yaml")
    return str(info.value)


BASE = ONE_LEG.read_text(encoding="utf-8")


@pytest.mark.parametrize(
    ("old", "new", "message"),
    [
        (
            "        damping: 0.0015\n",
            "        damping: -1\n",
            "r.yaml:24:18: damping of limb L1 must be positive, not -1",
        ),
        (
            "    time_step: 0.001\n",
            "    time_step: 0.001\n    gravity: high\n",
            "r.yaml:15:14: gravity must be a number",
        ),
        (
            "      - name: L1\n",
            "      - name: L9\n",
            "r.yaml:16:15: limb L9 is neither a leg nor a chassis contact of robot one_leg",
        ),
        (
            '          "1": [[0.20, 0, 0], [0, 0.12, 0], [0, 0, 0.25]]\n',
            "",
            "r.yaml:22:11: limb L1 has no stiffness matrix for the steady state '1'",
        ),
        (
            '"1": [[0.20, 0, 0], [0, 0.12, 0]',
            '"1": [[0.20, 0, 1], [0, 0.12, 0]',
            "r.yaml:23:16: stiffness of limb L1 must be a symmetric positive semi-definite matrix",
        ),
        (
            "inward: [0.15, 0.1]",
            "inward: [0.1, 0.15]",
            "r.yaml:25:69: inward friction of limb L1 must be [static, kinetic] with static >= "
            "kinetic >= 0",
        ),
        (
            "        pitch: 60\n",
            "        pitch: 60\n        stiffnes: 1\n",
            "r.yaml:18:9: unknown key 'stiffnes' in a limb",
        ),
        (
            "segments: [{length: 60, rest_curvature: 0.022, curvature: 0.008}]",
            "segments: [{length: 60, rest_curvature: 0.022, curvature: 0.022}]",
            "r.yaml:19:20: a segment of limb L1 has the same curvature pressurised as vented",
        ),
        (
            "        segments: [{length: 60, rest_curvature: 0.022, curvature: 0.008}]\n",
            "",
            "r.yaml:16:9: limb L1 has 0 segments but 1 chambers",
        ),
    ],
)
def test_errors_name_the_file_position(old: str, new: str, message: str) -> None:
    assert old in BASE
    assert _error(BASE.replace(old, new)) == message


def test_a_robot_without_the_section_says_what_to_add() -> None:
    with pytest.raises(ModelFileError) as info:
        load_spring_damper(ROBOTS / "symmetric6.yaml")
    err = info.value
    assert err.message == "robot file has no 'model' section"
    assert err.hint == "add 'model: {spring_damper: ...}' (docs/models.md lists its fields)"
    assert render_error(err).startswith(f"{ROBOTS / 'symmetric6.yaml'}:")


def test_a_leg_without_a_limb_and_a_limb_twice_are_reported() -> None:
    lines = BASE.splitlines(keepends=True)
    without_l1 = "".join(lines[:15] + lines[26:])  # drop the L1 entry (lines 16-26)
    assert _error(without_l1) == "r.yaml:16:7: leg L1 has no limb in model spring_damper"
    twice = BASE.replace("{name: skid_right,", "{name: skid_left,")
    assert _error(twice) == "r.yaml:29:9: limb skid_left is described twice"
