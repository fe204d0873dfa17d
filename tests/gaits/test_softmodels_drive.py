"""``gaitc drive --backend physics``: the region comes from the pose the model predicts."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from gaitc.cli import main
from gaitc.hw.backend import SensorReading
from gaitc.hw.localisation import RegionMap
from gaitc.hw.physics import PhysicsRobot, centre, region_map
from gaitc.models.motion import Pose2D
from gaitc.models.spring_damper.description import load_spring_damper
from gaitc.models.spring_damper.model import SpringDamperModel
from ltlcompiler.frontend import load_model

DATA = Path(__file__).parents[1] / "data" / "softmodels"
SHUTTLE = str(DATA / "radial8_shuttle.gait")
RADIAL8 = str(Path(__file__).parents[2] / "specs" / "robots" / "radial8.yaml")


def _poses(out: str) -> list[tuple[float, float, str]]:
    return [
        (float(x), float(y), region)
        for x, y, region in re.findall(r"x +(\S+) +y +(\S+) +heading +\S+ +(\w+)", out)
    ]


def test_enough_cycles_carry_the_chassis_from_cell_to_cell(
    capsys: pytest.CaptureFixture[str],
) -> None:
    code = main(
        [
            "drive",
            SHUTTLE,
            "--backend",
            "physics",
            "--robot",
            RADIAL8,
            "--steps",
            "4",
            "--cycles",
            "5",
            "--cell-size",
            "100",
        ]
    )
    out = capsys.readouterr().out
    assert code == 0, out
    poses = _poses(out)
    assert poses[0] == (50.0, 50.0, "a")
    assert {region for _, _, region in poses} == {"a", "b"}
    xs = [x for x, _, _ in poses]
    assert max(xs) - min(xs) > 100.0  # about five cycles of 22 mm
    assert all(abs(y - 50.0) < 10.0 for _, y, _ in poses)


def test_a_gait_that_does_not_go_far_enough_breaks_the_spec(
    capsys: pytest.CaptureFixture[str],
) -> None:
    code = main(
        [
            "drive",
            SHUTTLE,
            "--backend",
            "physics",
            "--robot",
            RADIAL8,
            "--steps",
            "4",
            "--cycles",
            "1",
            "--cell-size",
            "100",
        ]
    )
    captured = capsys.readouterr()
    assert code == 1
    assert "localisation reports region a but the controller expects b after gait east" in (
        captured.err
    )
    assert "gait east went the right way (a direction error of 3 deg) but not far enough: " \
        "it moved the chassis 24.8 mm (24.8 mm east, 1.4 mm south), 24.8 mm along the " \
        "100.0 mm from a to b" in captured.err
    assert "repeat each gait with --cycles N" in captured.err
    assert _poses(captured.out)[-1][2] == "a"


def test_a_miswired_gait_is_reported_as_going_the_wrong_way(
    capsys: pytest.CaptureFixture[str],
) -> None:
    """The east gait's valves fire L3, which moves the chassis south: the report names the
    direction error and the primitive, and does not say to repeat the gait."""
    code = main(["drive", str(DATA / "radial8_miswired.gait"), "--backend", "physics",
                 "--robot", RADIAL8, "--steps", "4", "--cycles", "1", "--cell-size", "100"])
    err = capsys.readouterr().err
    assert code == 1
    assert ("localisation reports region a but the controller expects b after gait east: "
            "gait east went the wrong way: it moved the chassis 20.0 mm (0.0 mm east, 20.0 mm "
            "south), toward -90 deg, but b lies toward 0 deg from a, a direction error of "
            "90 deg; its primitive (inline) runs 00000000, 00100000; stopped with all valves "
            "vented") in err
    assert "--cycles" not in err


def test_regions_get_positions_and_sizes() -> None:
    model, _ = load_model(SHUTTLE)
    regions = region_map(model, 100.0)
    assert regions.region_at(50.0, 50.0) == "a" and regions.region_at(150.0, 50.0) == "b"
    assert regions.region_at(250.0, 50.0) is None
    start = centre(regions, "b")
    assert (start.x, start.y) == (150.0, 50.0)
    assert isinstance(regions, RegionMap)


def test_physics_options_are_checked(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["drive", SHUTTLE, "--robot", RADIAL8]) == 2
    assert "--robot is for --backend physics" in capsys.readouterr().err


class _Sensors:
    """Stands in for the simulated robot: fixed health levels, region ignored."""

    valve_count = 8

    def __init__(self, l7_level: int) -> None:
        self.environment = type("E", (), {"name": "fixed"})()
        self.health = tuple((f"L{i}", l7_level if i == 7 else 3) for i in range(1, 9))

    def open(self) -> None: ...

    def close(self) -> None: ...

    def apply(self, valves: str) -> None: ...

    def read_sensors(self) -> SensorReading:
        return SensorReading(self.health, None, "a")


@pytest.mark.parametrize(("level", "moves"), [(3, True), (1, False)])
def test_an_inoperable_leg_does_not_move_the_robot(level: int, moves: bool) -> None:
    model = SpringDamperModel(load_spring_damper(RADIAL8))
    regions = RegionMap({"a": ((-500, -500), (500, -500), (500, 500), (-500, 500))})
    robot = PhysicsRobot(_Sensors(level), model, regions, Pose2D(0, 0, 0), 6.0)  # type: ignore[arg-type]
    robot.open()
    robot.read_sensors()
    robot.apply("00000010")  # L7 points south: extending it pushes the robot north
    robot.apply("00000000")
    assert (robot.pose.y > 15.0) is moves
    assert abs(robot.pose.y) < 0.5 or moves
