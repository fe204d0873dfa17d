"""Sensing of actuator health (thesis 3.4.2, issue 14): calibration and classification on
synthetic waveguide curves of known level, hysteresis against noise, the sensing file,
``gaitc calibrate``, and ``--on-violation stop|hold|worst`` of ``gaitc drive``.
"""

from __future__ import annotations

import itertools
from pathlib import Path

import pytest
from recordings import recorded

from gaitc.api.simulation import session
from gaitc.cli import main
from gaitc.hw.driver import Driver, bind_primitives
from gaitc.hw.sensing import (
    FIGURE_3_5_DEPTHS,
    CalibrationError,
    Cycle,
    HealthSensing,
    LegCalibration,
    calibrate,
    confusion,
    curve_feature,
    grade,
    read_cycles,
    read_sensing,
    synthetic_cycle,
    write_sensing,
)
from gaitc.hw.simulated import SimulatedRobot
from gaitc.sim.scenario import ScriptedEnvironment, load_scenario

LEGS = ("L1", "L2", "L3")
#: Two legs of three levels on a three-cell corridor (shared with test_drive_surprises).
SPEC3 = (Path(__file__).resolve().parents[1] / "data" / "surprises" / "three_levels.gait"
         ).read_text(encoding="utf-8")


# ---------------------------------------------------------------------------- features
def test_the_feature_is_the_depth_of_the_normalised_dip() -> None:
    for depth in FIGURE_3_5_DEPTHS:
        assert curve_feature(synthetic_cycle(depth, rest=512.0)) == pytest.approx(depth,
                                                                                   abs=1e-9)
    assert curve_feature(()) == 0.0
    assert curve_feature([0.0, 0.0, 0.0]) == 0.0  # no light at rest: no feature


def test_grade_moves_one_threshold_at_a_time_with_hysteresis() -> None:
    cal = LegCalibration((0.48, 0.18), 0.05)
    assert [grade(cal, 3, f) for f in (0.6, 0.44, 0.42, 0.2, 0.12, 0.0)] == [3, 3, 2, 2, 1, 1]
    assert [grade(cal, 1, f) for f in (0.2, 0.24, 0.5, 0.54)] == [1, 2, 2, 3]
    assert grade(cal, 2, 0.5) == 2 and grade(cal, 2, 0.16) == 2  # inside the margins


# ---------------------------------------------------------------------------- calibration
def test_calibration_separates_the_levels_and_classifies_fresh_cycles() -> None:
    calibration = calibrate(recorded(seed=1, noise=12.0))
    for cal in calibration.values():
        assert cal.levels == 3
        assert 0.36 < cal.thresholds[0] < 0.58 and 0.07 < cal.thresholds[1] < 0.30
        assert 0 < cal.hysteresis < 0.1
    matrix = confusion(calibration, recorded(seed=2, noise=12.0))
    assert matrix == [[45, 0, 0], [0, 27, 0], [0, 0, 9]]


def test_heavy_noise_confuses_only_neighbouring_levels() -> None:
    calibration = calibrate(recorded(seed=1, noise=12.0))
    matrix = confusion(calibration, recorded(seed=2, noise=100.0))
    assert matrix[0][2] == 0 and matrix[2][0] == 0  # never healthy for inoperable
    assert 0.9 * 81 <= sum(matrix[i][i] for i in range(3)) < 81  # noise now costs a few


def test_noise_near_a_threshold_does_not_flap_the_level() -> None:
    calibration = calibrate(recorded(seed=1, noise=12.0))
    cal = calibration["L1"]
    threshold = cal.thresholds[0]
    sensing = HealthSensing({"L1": 3}, {"L1": cal})
    hysteresis_free = HealthSensing({"L1": 3}, {"L1": LegCalibration(cal.thresholds, 0.0)})
    levels, free = [], []
    for i in range(200):  # an actuator right at the healthy/degraded border, with noise
        depth = threshold + ((i * 37) % 11 - 5) / 250  # ±0.02 from cycle to cycle
        samples = synthetic_cycle(depth, 700.0, 12.0, seed=5000 + i)
        low = 700.0 * (1 - curve_feature(samples, 700.0))  # the cycle's filtered lowest
        now = {"L1": 700.0}
        levels.append(sensing.update(now, {"L1": low}, ("L1",), in_cache=False)["L1"])
        free.append(hysteresis_free.update(now, {"L1": low}, ("L1",), in_cache=False)["L1"])
    flaps = sum(a != b for a, b in itertools.pairwise(levels))
    assert cal.hysteresis > 0.02 and flaps <= 1  # at most one step down, never back and forth
    assert sum(a != b for a, b in itertools.pairwise(free)) > 10  # the control


def test_levels_of_legs_not_in_use_hold_and_a_cache_resets() -> None:
    sensing = HealthSensing({"L1": 3, "L2": 3})
    now = {"L1": 800.0, "L2": 800.0}
    assert sensing.update(now, {"L1": 560.0, "L2": 790.0}, ("L1",), False) == {"L1": 2,
                                                                                 "L2": 3}
    assert sensing.update(now, {"L1": 790.0, "L2": 790.0}, (), False) == {"L1": 2, "L2": 3}
    assert sensing.update(now, {"L1": 790.0, "L2": 790.0}, ("L1",), True) == {"L1": 3, "L2": 3}


def test_calibration_errors(tmp_path: Path) -> None:
    healthy = Cycle("L1", 2, synthetic_cycle(0.6))
    with pytest.raises(CalibrationError, match="levels 2 and 1 overlap"):
        calibrate([healthy, Cycle("L1", 1, synthetic_cycle(0.62))])
    with pytest.raises(CalibrationError, match=r"leg L1: no recorded cycle of level\(s\) 2"):
        calibrate([Cycle("L1", 3, synthetic_cycle(0.6)), Cycle("L1", 1, synthetic_cycle(0))])
    path = tmp_path / "legs.csv"
    for text, message in [("a,b\n", "header"), ("leg,cycle,level,intensity\nL1,1,x,3\n",
                                                  "line 2: expected"),
                          ("leg,cycle,level,intensity\nL1,1,2,3\nL1,1,3,4\n",
                           "line 3: cycle 1 of leg L1 changes its level")]:
        path.write_text(text, encoding="utf-8")
        with pytest.raises(CalibrationError, match=message):
            read_cycles(path)
    with pytest.raises(CalibrationError, match="calibrated for 2 levels but the spec gives"):
        HealthSensing({"L1": 3}, {"L1": LegCalibration((0.3,))})


def test_sensing_file_round_trip_and_cli(tmp_path: Path,
                                          capsys: pytest.CaptureFixture[str]) -> None:
    rows = ["leg,cycle,level,intensity"]
    for n, cycle in enumerate(recorded(seed=1, noise=12.0, repeats=1)):
        rows += [f"{cycle.leg},{n},{cycle.level},{v:.2f}" for v in cycle.samples]
    csv_path = tmp_path / "legs.csv"
    csv_path.write_text("\n".join(rows) + "\n", encoding="utf-8")
    assert main(["calibrate", str(csv_path)]) == 0
    out = capsys.readouterr().out
    assert "L1          9      3" in out and f"wrote {tmp_path / 'legs.sensing.yaml'}" in out
    written = read_sensing(tmp_path / "legs.sensing.yaml")
    assert written == calibrate(read_cycles(csv_path))
    write_sensing(tmp_path / "again.yaml", written)
    assert read_sensing(tmp_path / "again.yaml") == written
    (tmp_path / "bad.yaml").write_text("legs:\n  L1: {thresholds: [0.2, 0.5]}\n",
                                       encoding="utf-8")
    with pytest.raises(CalibrationError, match="descending"):
        read_sensing(tmp_path / "bad.yaml")
    csv_path.write_text("leg,cycle,level,intensity\nL1,1,0,5\n", encoding="utf-8")
    assert main(["calibrate", str(csv_path)]) == 1
    assert f"{csv_path}:2:1: error: line 2: levels run from 1 to 100" in capsys.readouterr().err


# ---------------------------------------------------------------------------- --on-violation
@pytest.mark.parametrize(("policy", "l1"), [("hold", 3), ("worst", 2)])
def test_a_reading_that_breaks_an_assumption_is_held_or_taken_at_worst(
        tmp_path: Path, policy: str, l1: int) -> None:
    spec = tmp_path / "s.gait"
    spec.write_text(SPEC3, encoding="utf-8")
    scenario = tmp_path / "jump.yaml"
    scenario.write_text("steps:\n  - {}\n  - fail: [L1]\n", encoding="utf-8")  # 3 → 1 at once
    # without move preferences the controller walks on L1 at step 1, so 'worst' may take
    # it down one level (a controller sparing L1 would leave the assumptions no loss)
    loaded = session(str(spec), None, prefer="none")
    assert loaded is not None
    prims = bind_primitives(loaded.model, str(tmp_path))

    def drive(on_violation: str) -> tuple[Driver, object]:
        env = ScriptedEnvironment(load_scenario(str(scenario), loaded.model),
                                  loaded.strategy.inputs)
        robot = SimulatedRobot(loaded.strategy, loaded.domain, loaded.monitor, env, 2)
        driver = Driver(loaded.strategy, loaded.domain, loaded.monitor, prims, robot,
                        on_violation=on_violation)
        return driver, driver.run(5)

    stopped, run = drive("stop")
    assert getattr(run, "error", None) is not None and stopped.violations == []
    driver, run = drive(policy)
    assert getattr(run, "error", "x") is None
    assert len(driver.violations) == 1 and f"{policy}: taken as L1 {l1}" in driver.violations[0]
    steps = getattr(run, "steps", [])
    assert dict(steps[2].health)["L1"] == l1
    assert run.summary.assumptions_held  # type: ignore[attr-defined]


def test_cli_on_violation(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    spec = tmp_path / "s.gait"
    spec.write_text(SPEC3, encoding="utf-8")
    scenario = tmp_path / "jump.yaml"
    scenario.write_text("steps:\n  - {}\n  - fail: [L1]\n", encoding="utf-8")
    argv = ["drive", str(spec), "--env", "scripted", str(scenario), "--prefer", "none"]
    assert main([*argv, "--on-violation", "worst"]) == 0
    out = capsys.readouterr().out
    assert "readings that broke an assumption (worst): 1" in out
    assert "worst: taken as L1 2, L2 3, hazard none" in out
    assert main(argv) == 1  # stop, the default
    assert "breaks the assumption 'eq. 3.5" in capsys.readouterr().err


@pytest.mark.parametrize("thresholds", ["[.nan, 0.2]", "[0.4, -.inf]", "[.inf, 0.2]",
                                        "[true, 0.2]"])
def test_a_sensing_file_with_a_threshold_that_is_no_finite_number_is_refused(
        tmp_path: Path, thresholds: str) -> None:
    path = tmp_path / "bad.sensing.yaml"
    path.write_text(f"legs:\n  L1:\n    thresholds: {thresholds}\n", encoding="utf-8")
    with pytest.raises(CalibrationError) as caught:
        read_sensing(path)
    assert caught.value.message == ("leg L1: thresholds must be a descending list of finite "
                                    "numbers and hysteresis a finite number >= 0")
    assert caught.value.span is not None and caught.value.span.file == str(path)
