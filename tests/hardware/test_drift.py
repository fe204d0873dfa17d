"""How a gait missed its region (issue 51): drifted, fell short, went too far, the wrong way.

:func:`gaitc.hw.localisation.deviation` on constructed courses, then ``gaitc drive --backend
physics`` on small specs whose gaits drift sideways or overshoot, with the message word for
word and located at the gait in the .gait file.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from gaitc.api.simulation import session
from gaitc.cli import main
from gaitc.hw.backend import Course, HardwareError, SensorReading
from gaitc.hw.driver import Driver, bind_primitives
from gaitc.hw.localisation import Miss, RegionMap, compass, deviation
from gaitc.hw.simulated import SimulatedRobot
from gaitc.sim.environments import RandomEnvironment

ROOT = Path(__file__).resolve().parents[2]
RADIAL8 = str(ROOT / "specs" / "robots" / "radial8.yaml")

# radial8 on 2 x 2 cells: the east gait fires L3 after L6 and L4, and L3 pulls the chassis
# about 20 mm south a cycle (see tests/data/softmodels/radial8_miswired.gait)
DRIFTING = """\
robot "radial8 drifting"
legs L1..L8 health 2
gait west uses L2, L8 moves west valves 00000001, 01000000
gait east uses L3, L4, L6 moves east valves 00000100, 00010000, 00100000
grid 2 x 2 cells a, b, c, d
cache a
start a
visit a, b infinitely often
"""
# the shuttle of tests/data/softmodels/radial8_shuttle.gait with a third cell east of b
LONG = """\
robot "radial8 long shuttle"
legs L1..L8 health 2
gait east uses L4, L6 moves east valves 00000100, 00010000
gait west uses L2, L8 moves west valves 00000001, 01000000
grid 1 x 3 cells a, b, c
cache a
start a
visit a, b infinitely often
"""


def _grid() -> RegionMap:
    """2 x 2 cells of 100 mm: a (north-west), b, c, d (south-east)."""
    def square(x: float, y: float) -> tuple[tuple[float, float], ...]:
        return ((x, y), (x + 100, y), (x + 100, y + 100), (x, y + 100))

    return RegionMap({"a": square(0, 100), "b": square(100, 100), "c": square(0, 0),
                      "d": square(100, 0)})


def _reached(regions: RegionMap, found: str, expected: str) -> tuple[float, float]:
    (fx, fy), (ex, ey) = regions.centre(found), regions.centre(expected)
    return fx - ex, fy - ey


def test_compass_words() -> None:
    assert [compass(1, 0), compass(0, 1), compass(-1, 0), compass(0, -1)] == \
        ["east", "north", "west", "south"]
    assert [compass(1, 1), compass(-1, -1), compass(1, -0.3)] == \
        ["north-east", "south-west", "east"]


@pytest.mark.parametrize(("moved", "found", "miss", "side", "beside"), [
    ((101.3, -92.7), "d", Miss.DRIFTED, "south", "south"),  # far enough, but south of b
    ((61.8, -56.4), "d", Miss.DRIFTED, "south", "south"),  # short of 100 mm, yet into d
    ((24.8, -1.4), "a", Miss.SHORT, "south", "west"),
    ((45.0, -44.0), "c", Miss.SHORT, "south", "south-west"),  # both: behind comes first
    ((0.0, -20.0), "c", Miss.WRONG_WAY, "south", "south-west"),
    ((-30.0, 5.0), "a", Miss.WRONG_WAY, "north", "west"),
    ((0.3, -0.2), "a", Miss.STILL, "south", "west"),
    ((0.0, 0.0), "a", Miss.STILL, "", "west"),
])
def test_a_miss_splits_the_motion_along_and_across_the_move(
        moved: tuple[float, float], found: str, miss: Miss, side: str, beside: str) -> None:
    regions = _grid()
    course = Course(moved, (100.0, 0.0))  # from a to b, east
    off = deviation(course, _reached(regions, found, "b"))
    assert (off.miss, off.side, off.beside) == (miss, side, beside)
    assert off.along == pytest.approx(moved[0]) and off.across == pytest.approx(moved[1])
    assert off.length == pytest.approx(100.0)


def test_across_is_to_the_left_of_the_move_whichever_way_it_goes() -> None:
    regions = _grid()
    # from b to d, south: drifting east is to the move's left
    off = deviation(Course((30.0, -110.0), (0.0, -100.0)), _reached(regions, "b", "d"))
    assert off.miss is Miss.SHORT and off.beside == "north"
    assert off.along == pytest.approx(110.0) and off.across == pytest.approx(30.0)
    assert off.side == "east"
    # from d to c, west, ending in a: drifted north, to the move's right
    off = deviation(Course((-95.0, 70.0), (-100.0, 0.0)), _reached(regions, "a", "c"))
    assert (off.miss, off.side, off.beside) == (Miss.DRIFTED, "north", "north")
    assert off.across == pytest.approx(-70.0)
    # from a to d, south-east on a map of its own: a motion that stops short of d's centre
    off = deviation(Course((60.0, -80.0), (100.0, -100.0)), (-100.0, 0.0))
    assert off.miss is Miss.SHORT and off.side == "south-west" and off.beside == "west"


def test_a_motion_past_the_region_went_too_far() -> None:
    regions = RegionMap({name: ((x, 0), (x + 100, 0), (x + 100, 100), (x, 100))
                         for name, x in (("a", 0), ("b", 100), ("c", 200))})
    off = deviation(Course((201.8, -6.2), (100.0, 0.0)), _reached(regions, "c", "b"))
    assert (off.miss, off.side, off.beside) == (Miss.FAR, "south", "east")
    assert off.error == pytest.approx(1.76, abs=0.01)


def _drive(spec: Path, cycles: int, capsys: pytest.CaptureFixture[str]) -> str:
    code = main(["drive", str(spec), "--backend", "physics", "--robot", RADIAL8, "--steps",
                 "4", "--cycles", str(cycles), "--cell-size", "100"])
    err = capsys.readouterr().err
    assert code == 1, err
    return err


def test_a_gait_that_drifts_into_the_next_cell_is_named_as_drifting(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """Five cycles carry the robot 101.3 mm east, past b's western edge, and 92.7 mm south,
    into d: it went far enough and drifted (it was reported as 'not far enough: 101.3 mm
    along the 100.0 mm', at a pseudo-file named after the backend)."""
    spec = tmp_path / "drifting.gait"
    spec.write_text(DRIFTING, encoding="utf-8")
    err = _drive(spec, 5, capsys)
    assert err.splitlines()[-4:] == [
        f"{spec}:4:1: error: step 2: localisation reports region d but the controller expects "
        "b after gait east: gait east drifted: it moved the chassis 137.3 mm (101.3 mm east, "
        "92.7 mm south), 101.3 mm along the 100.0 mm from a to b, enough to reach b, but "
        "92.7 mm south of that line (a direction error of 42 deg), which put it in d, south "
        "of b; stopped with all valves vented",
        "    gait east uses L3, L4, L6 moves east valves 00000100, 00010000, 00100000",
        "    " + "^" * 72,
        "  hint: the gait's motion has a sideways part that carried the robot out of the "
        "region: choose a primitive closer to the move ('gaitc gaits ROBOT --direction D' "
        "ranks each direction's valve sequences), or give the regions room across the move "
        "(--cell-size MM, or a --map)"]
    assert "<physics model" not in err and "not far enough" not in err
    # three cycles: 61.8 mm east is short of b's centre but inside b's column; still drift
    err = _drive(spec, 3, capsys)
    assert "gait east drifted: it moved the chassis 83.7 mm (61.8 mm east, 56.4 mm south), " \
        "61.8 mm along the 100.0 mm from a to b, enough to reach b, but 56.4 mm south of " \
        "that line (a direction error of 42 deg), which put it in d, south of b;" in err


def test_a_gait_that_falls_short_or_goes_too_far_says_which(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    spec = tmp_path / "long.gait"
    spec.write_text(LONG, encoding="utf-8")
    err = _drive(spec, 1, capsys)
    assert f"{spec}:3:1: error: step 2: localisation reports region a but the controller " \
        "expects b after gait east: gait east went the right way (a direction error of 3 " \
        "deg) but not far enough: it moved the chassis 24.8 mm (24.8 mm east, 1.4 mm south), " \
        "24.8 mm along the 100.0 mm from a to b and 1.4 mm south of that line, so it fell " \
        "short and is in a, west of b; stopped with all valves vented\n" in err
    assert "repeat each gait with --cycles N" in err
    err = _drive(spec, 9, capsys)
    assert f"{spec}:3:1: error: step 2: localisation reports region c but the controller " \
        "expects b after gait east: gait east went the right way (a direction error of 2 " \
        "deg) but too far: it moved the chassis 201.9 mm (201.8 mm east, 6.2 mm south), " \
        "201.8 mm along the 100.0 mm from a to b and 6.2 mm south of that line, so it " \
        "passed b and is in c, east of b; stopped with all valves vented\n" in err
    assert "run fewer cycles" in err and "repeat each gait" not in err


def test_a_gait_whose_valves_stay_shut_did_not_move_the_robot(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """It was reported as going the wrong way (a direction error of 180 deg)."""
    spec = tmp_path / "shut.gait"
    spec.write_text(LONG.replace("valves 00000100, 00010000", "valves 00000000, 00000000"),
                    encoding="utf-8")
    err = _drive(spec, 1, capsys)
    assert f"{spec}:3:1: error: step 2: localisation reports region a but the controller " \
        "expects b after gait east: gait east did not move the robot: the chassis moved 0.0 " \
        "mm of the 100.0 mm from a to b; its primitive (inline) runs 00000000, 00000000; " \
        "stopped with all valves vented\n" in err
    assert "wrong way" not in err


class _Stuck(SimulatedRobot):
    """The simulated robot whose localisation always reports region ``b``."""

    def read_sensors(self) -> SensorReading:
        reading = super().read_sensors()
        return SensorReading(reading.health, reading.hazard, "b")


def test_a_robot_off_its_region_without_a_course_is_an_error_at_the_spec(
        tmp_path: Path) -> None:
    """Without a measured course (a board and a tracker), the error still names the step
    and is located at the gait, or at the spec's start for the first reading."""
    spec = tmp_path / "shuttle.gait"

    def error(start: str) -> HardwareError:
        text = (ROOT / "specs" / "shuttle_2leg.gait").read_text(encoding="utf-8")
        spec.write_text(text.replace("start a", f"start {start}"), encoding="utf-8")
        again = session(str(spec), None)
        assert again is not None
        robot = _Stuck(again.strategy, again.domain, again.monitor, RandomEnvironment(1), 2)
        driver = Driver(again.strategy, again.domain, again.monitor,
                        bind_primitives(again.model, str(tmp_path)), robot)
        run = driver.run(6)
        assert isinstance(run.error, HardwareError)
        return run.error

    found = error("a")
    assert (str(found.span), found.message) == (
        f"{spec}:10:1", "step 0: localisation reports region b but the controller expects a at "
        "the start: the robot is not in the region the spec starts it in; stopped with all "
        "valves vented")
    assert found.hint == "put the robot in a before the run, or check the localisation map"
    found = error("b")  # step 1 of the run goes west from b to a; the robot is still in b
    assert (str(found.span), found.message) == (
        f"{spec}:7:1", "step 1: localisation reports region b but the controller expects a "
        "after gait west: the gait did not get there; stopped with all valves vented")
