"""The robot file's active_passive section: parsing and positioned errors (thesis 4.1.2)."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from gaitc.gaitgraph.robot import RobotFileError, load_robot
from gaitc.models.active_passive.description import load_active_passive, parse_active_passive

ROBOTS = Path(__file__).resolve().parents[2] / "specs" / "robots"

TINY = """\
robot: tiny
chassis:
  mass: 10
  contacts: {a: [0, 0, 0], b: [1, 0, 0]}
legs:
  - {name: L, mount: [0, 0, 0], length: 50, chambers: [{curvature: 0.01}]}
model:
  active_passive:
    components:
      - {name: body, mass: 10, wireframe: [[-10, -10, 0], [10, -10, 0], [10, 10, 0]]}
      - {name: leg, leg: L, length: 50, mass: 5, section: [[-5, -5], [5, -5], [5, 5]],
         states: {"0": {curvature: 0}, "1": {curvature: 0.02, angle: -90}}}
    connections:
      - {from: body, to: leg, at: [10, 0, 5], joint: {lower: -10, upper: 10}}
"""


def test_silicone6_describes_the_chapter4_robot() -> None:
    ap = load_active_passive(ROBOTS / "silicone6.yaml")
    names = [c.name for c in ap.components]
    assert names[0] == "rear_block"
    assert {"middle", "front_block", "RL", "RR", "FL", "FR"} <= set(names)
    middle = ap.component("middle")
    assert middle.valves == (0, 1) and middle.torsion is not None
    assert math.isclose(math.degrees(middle.torsion.upper), 35.0)
    assert middle.shape("10").curvature == 0.008
    assert math.isclose(math.degrees(ap.component("RL").shape("1").angle), -90.0)
    joints = [c.joint.name for c in ap.connections if c.joint is not None]
    assert joints == ["rear_hinge", "front_hinge"]
    # every parent comes before its children
    seen = {names[0]}
    for c in ap.connections:
        assert c.source in seen
        seen.add(c.target)


def test_old_robot_files_stay_valid() -> None:
    for path in sorted(ROBOTS.glob("*.yaml")):
        assert load_robot(path).legs


def test_tiny_robot_parses_with_defaults() -> None:
    ap = parse_active_passive(TINY)
    leg = ap.component("leg")
    assert leg.stations == 4 and leg.friction == (0.0, 0.0, 0.0)
    (link,) = ap.connections
    assert link.joint is not None and link.joint.name == "leg_hinge"
    assert link.axis == (0.0, 1.0, 0.0) and ap.contact_tolerance == 0.5


def test_a_file_without_the_section_is_refused_for_this_model() -> None:
    with pytest.raises(RobotFileError) as err:
        load_active_passive(ROBOTS / "radial8.yaml")
    assert str(err.value).endswith(
        "radial8.yaml:53:3: the model section has no 'active_passive' entry"
    )
    with pytest.raises(RobotFileError) as err:
        parse_active_passive(TINY.split("model:")[0])
    assert str(err.value) == "<robot>:1:1: robot file has no 'model' section"
    assert err.value.hint == "add 'model: {active_passive: ...}' (docs/models.md lists its fields)"


@pytest.mark.parametrize(
    ("old", "new", "message"),
    [
        (
            "mass: 10, wireframe",
            "mas: 10, wireframe",
            "<robot>:10:22: unknown key 'mas' in a component",
        ),
        (
            '"1": {curvature: 0.02, angle: -90}',
            '"2": {curvature: 0.02}',
            "<robot>:12:40: state '2' of leg must have 1 digits 0 or 1, one per chamber of leg L",
        ),
        (
            '"1": {curvature: 0.02, angle: -90}',
            '"0": {curvature: 0.02}',
            "<robot>:12:40: key '0' appears twice in states of leg",
        ),
        (
            "leg: L,",
            "leg: Q,",
            "<robot>:11:26: actuator leg names leg 'Q', which the robot file does not declare",
        ),
        ("to: leg", "to: foot", "<robot>:14:26: connection to unknown component 'foot'"),
        (
            "lower: -10, upper: 10",
            "lower: 10, upper: -10",
            "<robot>:14:73: joint leg_hinge: upper bound -10 is below the lower bound 10",
        ),
        ("mass: 5,", "mass: -5,", "<robot>:11:47: mass of leg must be at least 0, not -5"),
        (
            "at: [10, 0, 5]",
            "at: tip",
            "<robot>:14:35: 'at: tip' needs an actuator, and body is rigid",
        ),
        ("at: [10, 0, 5]", "at: [10, 0]", "<robot>:14:35: at must have 3 numbers, not 2"),
        (
            "      - {from: body, to: leg, at: [10, 0, 5], joint: {lower: -10, upper: 10}}\n",
            "      - {from: leg, to: body, at: tip}\n",
            "<robot>:14:9: body is the root (the first component) and cannot be mounted on another",
        ),
        (
            "length: 50, mass: 5",
            "length: 50, stations: 2.5, mass: 5",
            "<robot>:11:51: stations must be a whole number, not 2.5",
        ),
        (
            "length: 50, mass: 5",
            "length: 0, mass: 5",
            "<robot>:11:37: length of leg must be at least 1e-06, not 0",
        ),
    ],
)
def test_bad_fields_are_reported_where_they_are(old: str, new: str, message: str) -> None:
    assert old in TINY
    with pytest.raises(RobotFileError) as err:
        parse_active_passive(TINY.replace(old, new, 1))
    assert str(err.value) == message


def test_missing_pattern_and_unconnected_component() -> None:
    text = TINY.replace(', "1": {curvature: 0.02, angle: -90}', "")
    with pytest.raises(RobotFileError) as err:
        parse_active_passive(text)
    assert str(err.value) == "<robot>:12:18: states of leg miss the pattern '1'"
    text = TINY.replace(
        "      - {from: body, to: leg, at: [10, 0, 5], joint: {lower: -10, upper: 10}}\n", ""
    ).replace("    connections:\n", "    connections: []\n")
    with pytest.raises(RobotFileError) as err:
        parse_active_passive(text)
    assert str(err.value) == "<robot>:13:18: component leg is not connected to the root body"


def test_every_valved_leg_needs_a_component() -> None:
    text = TINY.replace("leg: L, ", "")
    text = text.replace(
        "length: 50, mass: 5, section: [[-5, -5], [5, -5], [5, 5]],\n"
        '         states: {"0": {curvature: 0}, "1": {curvature: 0.02, '
        "angle: -90}}}",
        "mass: 5, wireframe: [[0, 0, 0]]}",
    )
    with pytest.raises(RobotFileError) as err:
        parse_active_passive(text)
    assert str(err.value) == "<robot>:10:7: no component is driven by leg 'L'"
    assert err.value.hint == "give one actuator component 'leg: L'"
