"""Tests of the hardware layer (gaithw) and ``gaitc drive``, without hardware.

The simulated robot runs the radial8 patrol end to end; the serial backend's tests, on a
fake valve board, are in test_serial_board.py, the real firmware's in test_firmware.py.
"""

from __future__ import annotations

import itertools
import json
from collections.abc import Sequence
from pathlib import Path

import pytest
from fake_board import TINY

import gaitc
from gaitc.api.simulation import Session, session
from gaitc.cli import main
from gaitc.diagnostics import SpecSemanticError
from gaitc.gaitgraph.pairing import resolve_primitive
from gaitc.hw.backend import SensorReading
from gaitc.hw.driver import Driver, applied_states, bind_primitives, valve_count
from gaitc.hw.simulated import SimulatedRobot
from gaitc.sim.environments import AdversarialEnvironment, RandomEnvironment
from gaitc.sim.run import read_jsonl
from gaitc.sim.scenario import ScriptedEnvironment, load_scenario
from ltlcompiler.model import GaitKind

ROOT = Path(__file__).resolve().parents[2]
RADIAL8 = ROOT / "specs" / "radial8_patrol.gait"



# ---------------------------------------------------------------------------- fixtures
@pytest.fixture(scope="module")
def radial8() -> Session:
    loaded = session(str(RADIAL8), None)
    assert loaded is not None
    return loaded




# ---------------------------------------------------------------------------- simulated
def test_simulated_radial8_runs_the_primitives_of_the_chosen_gaits(radial8: Session) -> None:
    prims = bind_primitives(radial8.model, str(RADIAL8.parent))
    robot = SimulatedRobot(radial8.strategy, radial8.domain, radial8.monitor,
                           AdversarialEnvironment(), valve_count(prims, 0))
    driver = Driver(radial8.strategy, radial8.domain, radial8.monitor, prims, robot)
    run = driver.run(15, str(RADIAL8))
    assert run.error is None and len(run.steps) == 16
    legs = [leg.name for leg in radial8.model.legs]
    expected = ["00000000"]  # vented when the driver starts
    executed: list[str] = []
    for step in run.steps:
        gait = radial8.model.gait(step.gait)
        if gait.kind is GaitKind.NONE:
            expected.append("00000000")
            executed.append("00000000")
            continue
        seq = resolve_primitive(gait, str(RADIAL8.parent), legs)
        assert set(seq.pressurised_legs()) == set(step.legs_used)
        expected.extend(seq.states)
        executed.extend(seq.states)
        if "1" in seq.states[-1]:
            expected.append("00000000")  # no valve stays open after its gait's step
    expected.append("00000000")  # vented on close
    assert robot.applied == expected
    assert applied_states(driver.executed) == executed
    assert [e.gait for e in driver.executed] == [s.gait for s in run.steps]
    assert any(s.gait != "noGait" for s in run.steps)


def test_simulated_health_readings_obey_the_assumptions(radial8: Session) -> None:
    prims = bind_primitives(radial8.model, str(RADIAL8.parent))
    robot = SimulatedRobot(radial8.strategy, radial8.domain, radial8.monitor,
                           RandomEnvironment(3), 8)
    run = Driver(radial8.strategy, radial8.domain, radial8.monitor, prims, robot).run(25)
    monitor = radial8.monitor
    values = [monitor.values(dict(step.values)) for step in run.steps]
    assert monitor.check_initial(values[0]) == []
    for before, after in itertools.pairwise(values):
        check = monitor.check_step(before, after)
        assert check.env_failed == () and check.sys_failed == ()
    assert [r.health for r in robot.readings] == [s.health for s in run.steps]
    assert any(s.degraded or s.failed for s in run.steps)
    assert run.summary is not None and run.summary.assumptions_held


def test_scenario_breaking_an_assumption_stops_and_vents(tiny: Session, tmp_path: Path) -> None:
    scenario = tmp_path / "s.yaml"
    scenario.write_text("steps:\n  - degrade: [L2]\n", encoding="utf-8")
    env = ScriptedEnvironment(load_scenario(str(scenario), tiny.model), tiny.strategy.inputs)
    prims = bind_primitives(tiny.model, str(tmp_path))
    robot = SimulatedRobot(tiny.strategy, tiny.domain, tiny.monitor, env, 2)
    run = Driver(tiny.strategy, tiny.domain, tiny.monitor, prims, robot).run(5)
    assert run.error is not None
    assert run.error.message.startswith("step 1 (sensed L2 2→1; no hazard): L2 failed in "
                                        "cache a (eq. 3.6, line 9): the environment breaks the "
                                        "assumption 'eq. 3.6: cache a resets")
    assert robot.applied[-1] == "00"


class _Interrupting(SimulatedRobot):
    def __init__(self, *args: object, fail_at: int, error: BaseException) -> None:
        super().__init__(*args)  # type: ignore[arg-type]
        self.fail_at = fail_at
        self.error = error

    def read_sensors(self) -> SensorReading:
        if len(self.readings) == self.fail_at:
            raise self.error
        return super().read_sensors()


def test_ctrl_c_vents_all_valves_and_keeps_the_run(tiny: Session, tmp_path: Path) -> None:
    prims = bind_primitives(tiny.model, str(tmp_path))
    robot = _Interrupting(tiny.strategy, tiny.domain, tiny.monitor, RandomEnvironment(1), 2,
                          fail_at=3, error=KeyboardInterrupt())
    run = Driver(tiny.strategy, tiny.domain, tiny.monitor, prims, robot).run(10)
    assert len(run.steps) == 3 and run.error is None
    assert run.summary is not None and run.summary.stopped is not None
    assert "interrupted" in run.summary.stopped
    assert robot.applied[-2:] == ["00", "00"] and not robot.is_open


def test_an_unexpected_exception_still_vents(tiny: Session, tmp_path: Path) -> None:
    prims = bind_primitives(tiny.model, str(tmp_path))
    robot = _Interrupting(tiny.strategy, tiny.domain, tiny.monitor, RandomEnvironment(1), 2,
                          fail_at=2, error=RuntimeError("sensor bus fault"))
    with pytest.raises(RuntimeError):
        Driver(tiny.strategy, tiny.domain, tiny.monitor, prims, robot).run(10)
    assert robot.applied[-1] == "00" and not robot.is_open


def test_missing_primitives_are_listed(tmp_path: Path) -> None:
    spec = tmp_path / "bare.gait"
    spec.write_text(TINY.replace(" valves 10, 00", "").replace(" valves 01, 00", ""),
                    encoding="utf-8")
    loaded = session(str(spec), None)
    assert loaded is not None
    with pytest.raises(SpecSemanticError, match=r"2 gait\(s\) have no valve primitive: "
                       r"east, west"):
        bind_primitives(loaded.model, str(tmp_path))


# ---------------------------------------------------------------------------- CLI
def test_cli_drive_sim(tiny_spec: Path, tmp_path: Path,
                       capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "run.jsonl"
    code = main(["drive", str(tiny_spec), "--env", "adversarial", "--steps", "6",
                 "--out", str(out)])
    captured = capsys.readouterr()
    assert code == 0, captured.err
    assert "guarantees:      held at every step" in captured.out
    run = read_jsonl(out)
    assert len(run.steps) == 7 and {s.gait for s in run.steps} >= {"east", "west"}
    header = json.loads(out.read_text(encoding="utf-8").splitlines()[0])
    assert header["environment"].startswith("hardware (simulated robot, adversarial")


def test_cli_drive_missing_primitives(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    spec = tmp_path / "bare.gait"
    spec.write_text(TINY.replace(" valves 01, 00", ""), encoding="utf-8")
    assert main(["drive", str(spec)]) == 1
    err = capsys.readouterr().err
    line = next(k for k, text in enumerate(TINY.splitlines(), 1) if text.startswith("gait west"))
    assert f"{spec}:{line}:1: error: cannot drive the robot: 1 gait(s) have no valve " \
           "primitive: west" in err
    assert "bind one to each gait" in err


def test_every_command_refuses_valves_that_fire_a_leg_the_gait_does_not_use(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """Issue 60: ``lint`` refused a move gait whose valves fire a leg it does not use, but
    ``check`` and ``synth`` accepted it and ``drive`` ran it: the board wore L2 while the
    health reasoning took it as idle.  Every command that reads the spec refuses it now,
    at the primitive, before any valve moves."""
    spec = tmp_path / "crossed.gait"
    spec.write_text(TINY.replace("uses L1 moves east valves 10, 00",
                                 "uses L1 moves east valves 11, 00"), encoding="utf-8")
    out = tmp_path / "run.jsonl"
    line = next(k for k, text in enumerate(TINY.splitlines(), 1) if text.startswith("gait east"))
    for command in (["check"], ["synth", "-o", str(tmp_path / "c.json")],
                    ["simulate", "--steps", "3"], ["lint"], ["drive", "--out", str(out)]):
        assert main([command[0], str(spec), *command[1:]]) == 1, command
        err = capsys.readouterr().err
        assert f"{spec}:{line}:" in err
        assert "error: gait east uses L1 but its primitive (inline) pressurises L1, L2" in err
        assert "make them agree" in err
    assert not out.exists() and not (tmp_path / "c.json").exists()


def test_drive_refuses_a_resolved_primitive_that_fires_an_idle_leg(tmp_path: Path) -> None:
    """A robot file's primitive is resolved only when the board needs it: ``drive`` checks
    what the resolver gives (here a robot file's gait on both legs for a gait using L1)."""
    from gaitc.gaitgraph.pairing import ValveSequence
    from ltlcompiler.model import Gait

    spec = tmp_path / "tiny.gait"
    spec.write_text(TINY, encoding="utf-8")
    loaded = gaitc.load(spec)
    assert loaded.model is not None

    def crossed(gait: Gait, spec_dir: str, legs: Sequence[str] | None = None) -> ValveSequence:
        if gait.name != "east":
            return resolve_primitive(gait, spec_dir, legs)
        return ValveSequence(("11", "00"), ("L1", "L2"), "robot file gait crab")

    with pytest.raises(SpecSemanticError) as caught:
        bind_primitives(loaded.model, str(tmp_path), crossed)
    assert caught.value.message == ("cannot drive the robot: gait east uses L1 but its "
                                    "primitive (robot file gait crab) pressurises L1, L2")
    assert caught.value.hint is not None and "make them agree" in caught.value.hint


def test_cli_drive_usage_errors(tiny_spec: Path, capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["drive", str(tiny_spec), "--backend", "serial"]) == 2
    assert "needs --port" in capsys.readouterr().err
    assert main(["drive", str(tiny_spec), "--port", "socket://x:1"]) == 2
    assert main(["drive", str(tiny_spec), "--steps", "-1"]) == 2


