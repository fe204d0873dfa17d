"""``gaitc drive`` meeting broken assumptions (issue 52): ``--on-violation recover`` and
``--violate STEP:EVENT`` on the simulated robot.

The drive's answers are checked by other means: the same event performed by ``gaitc
simulate --violate`` against the same environment gives the same steps and the same
violation objects; the steps after the surprise are checked by a fresh run monitor; the
valves run are those of the gaits of the steps, fallback strategy included.
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest

import gaitc
from gaitc.api.driving import DriveOptions, SimulatedBoard
from gaitc.cli import main
from gaitc.core.modes import Outcome, ViolationPolicy
from gaitc.hw.driver import Driver, bind_primitives
from gaitc.hw.saboteur import SurprisingRobot
from gaitc.sim.environments import RandomEnvironment
from gaitc.sim.events import plan
from gaitc.sim.monitor import Monitor
from gaitc.sim.run import read_jsonl

#: The corridor of tests/data/surprises/corridor3.gait with valves: only L1 moves east,
#: only L2 west; L1 failing while the robot goes west puts e out of reach for good.
SURPRISES = Path(__file__).resolve().parents[1] / "data" / "surprises"
CORRIDOR = (SURPRISES / "corridor3_valves.gait").read_text(encoding="utf-8")
SPEC3 = (SURPRISES / "three_levels.gait").read_text(encoding="utf-8")
DEGRADED = ("step 2: L1 failed while not in use (eq. 3.5, line 4); degraded: still pursuing "
            "visit w; visit e is out of reach after L1 failed while not in use")
BROKEN = ("    broken: eq. 3.5: under west leg L2 may lose one level, the other legs keep "
          "theirs ({spec}:4:1)")


@pytest.fixture()
def corridor(tmp_path: Path) -> Path:
    path = tmp_path / "corridor.gait"
    path.write_text(CORRIDOR, encoding="utf-8")
    return path


def test_violate_degrades_and_the_drive_goes_on(corridor: Path,
                                                capsys: pytest.CaptureFixture[str]) -> None:
    out = corridor.parent / "drive.jsonl"
    code = main(["drive", str(corridor), "--steps", "10", "--violate", "2:fail L1", "--out",
                 str(out), "--quiet"])
    text = capsys.readouterr().out
    assert code == 0
    assert text.endswith(f"surprises:\n  {DEGRADED}\n{BROKEN.format(spec=corridor)}\n")
    run = read_jsonl(out)
    (surprise,) = run.surprises
    assert surprise.outcome == Outcome.DEGRADED and surprise.event == "fail L1"
    assert surprise.kept == ("visit w",) and surprise.lost == ("visit e",)
    assert len(run.steps) == 11 and run.steps[2].level("L1") == 1
    # a fresh monitor: every guarantee kept and no assumption broken after the surprise,
    # w visited again and e never
    bound = gaitc.api.simulation.session(str(corridor))
    assert bound is not None
    names = [v.name for v in bound.spec.gr1.variables()]
    values = [tuple(dict(s.values)[n] for n in names) for s in run.steps]
    monitor = Monitor(bound.spec.gr1)
    for i in range(2, len(values)):
        found = monitor.check_step(values[i - 1], values[i])
        assert found.sys_failed == ()
        assert found.env_failed == () or i == 2
    later = [s.goals for s in run.steps[3:]]
    assert sum("w" in g for g in later) >= 3 and not any("e" in g for g in later)


def test_drive_reports_the_same_violations_as_simulate(
        corridor: Path, capsys: pytest.CaptureFixture[str]) -> None:
    argv = [str(corridor), "--steps", "8", "--violate", "2:fail L1", "--json"]
    assert main(["drive", *argv]) == 0
    driven = json.loads(capsys.readouterr().out)
    assert main(["simulate", *argv]) == 0
    simulated = json.loads(capsys.readouterr().out)
    assert driven["violations"] == simulated["violations"]
    assert [s["values"] for s in driven["steps"]] == [s["values"] for s in simulated["steps"]]
    (violation,) = driven["violations"]
    assert violation == {
        "step": 2, "event": "fail L1",
        "assumption": "L1 failed while not in use (eq. 3.5, line 4)",
        "clause": "eq. 3.5: under west leg L2 may lose one level, the other legs keep theirs",
        "line": f"{corridor}:4:1", "outcome": "degraded", "goals_kept": ["visit w"],
        "goals_lost": ["visit e"],
        "note": "degraded: still pursuing visit w; visit e is out of reach after L1 failed "
                "while not in use"}
    assert driven["substituted"] == [] and driven["backend"] == "sim"


def test_the_valves_follow_the_fallback_strategy(corridor: Path) -> None:
    """The driver runs, step by step, the gait of each step of the run, those of the
    fallback strategy after the surprise too (each gait's primitive)."""
    bound = gaitc.api.simulation.session(str(corridor))
    assert bound is not None
    prims = bind_primitives(bound.model, str(corridor.parent))
    robot = SurprisingRobot(bound.strategy, bound.domain, bound.monitor, RandomEnvironment(0),
                            2, plan(["2:fail L1"], bound.domain))
    lines: list[str] = []
    driver = Driver(bound.strategy, bound.domain, bound.monitor, prims, robot,
                    on_violation=ViolationPolicy.RECOVER, follower=robot, progress=lines.append)
    run = driver.run(8)
    assert ("step 2: fail L1 breaks an assumption; recover: the controller goes on from the "
            "state sensed") in lines  # as it happens (a serial drive prints these lines)
    assert [e.gait for e in driver.executed] == [s.gait for s in run.steps]
    for entry in driver.executed:
        want = ((robot.vented,) if entry.gait == driver.no_gait
                else prims[entry.gait].states)
        assert entry.valves == want
    assert [s.outcome for s in run.surprises] == [Outcome.DEGRADED]


def test_recover_goes_on_after_a_scripted_reading_that_breaks_an_assumption(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    spec = tmp_path / "s.gait"
    spec.write_text(SPEC3, encoding="utf-8")
    scenario = tmp_path / "jump.yaml"
    scenario.write_text("steps:\n  - {}\n  - fail: [L1]\n  - {}\n  - {}\n  - {}\n",
                        encoding="utf-8")
    argv = ["drive", str(spec), "--env", "scripted", str(scenario), "--prefer", "none"]
    assert main([*argv, "--on-violation", "recover", "--quiet"]) == 0
    out = capsys.readouterr().out
    assert out.endswith(
        "surprises:\n  step 2: L1 dropped 2 levels in one move and failed (eq. 3.5, line 3); "
        "recovered: the state is still winning; every goal is pursued\n    broken: eq. 3.5: "
        f"under east leg L1 may lose one level, the other legs keep theirs ({spec}:3:1)\n")
    assert main([*argv, "--on-violation", "recover", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    (violation,) = data["violations"]
    assert violation["event"] == "sensed L1 3→1; no hazard"
    assert violation["outcome"] == "recovered" and len(data["steps"]) == 6
    assert main(argv) == 1  # stop, the default without --violate
    assert "breaks the assumption 'eq. 3.5" in capsys.readouterr().err


def test_an_event_the_assumptions_allow_is_marked_allowed(
        corridor: Path, capsys: pytest.CaptureFixture[str]) -> None:
    # at step 1 the robot goes west on L2, which may lose a level
    assert main(["drive", str(corridor), "--steps", "4", "--violate", "2:degrade L2",
                 "--json"]) == 0
    (violation,) = json.loads(capsys.readouterr().out)["violations"]
    assert (violation["step"], violation["event"], violation["assumption"],
            violation["outcome"]) == (2, "degrade L2", None, "allowed")
    assert violation["note"] == ("allowed: the assumptions allow this event; the controller "
                                 "answered it")


def test_violate_with_stop_keeps_the_old_error(corridor: Path,
                                               capsys: pytest.CaptureFixture[str]) -> None:
    code = main(["drive", str(corridor), "--steps", "4", "--violate", "2:fail L1",
                 "--on-violation", "stop"])
    assert code == 1
    err = capsys.readouterr().err
    assert err.strip() == (
        "gaitc: error: step 2 (fail L1): L1 failed while not in use (eq. 3.5, line 4): the "
        "environment breaks the assumption 'eq. 3.5: under west leg L2 may lose one level, "
        "the other legs keep theirs'; the controller has no successor for this input")


@pytest.mark.parametrize(("extra", "message"), [
    (["--backend", "serial", "--port", "socket://localhost:1"],
     "--violate makes the simulated robot's environment perform an event; a serial board's "
     "sensors report what happens (use --backend sim or physics)"),
    (["--violate", "2:fail L9"],
     "--violate 'fail L9': unknown leg 'L9'; the robot's legs are L1, L2"),
    (["--violate", "2:degrade L1"],
     "--violate at step 2 'fail L1, degrade L1': 'fail L1' and 'degrade L1' both change "
     "leg L1; give one of them"),
    (["--on-violation", "pray"],
     "argument --on-violation: invalid choice: 'pray' (choose from 'stop', 'hold', 'worst', "
     "'recover')"),
])
def test_bad_drive_surprise_options_are_usage_errors(
        corridor: Path, extra: list[str], message: str,
        capsys: pytest.CaptureFixture[str]) -> None:
    code = main(["drive", str(corridor), "--steps", "4", "--violate", "2:fail L1", *extra])
    assert code == 2
    assert message in capsys.readouterr().err


def test_the_python_api_lists_the_surprises(corridor: Path) -> None:
    driven = gaitc.drive(corridor, board=SimulatedBoard(),
                         options=DriveOptions(steps=6, violate=("2:fail L1",)))
    assert [s.words() for s in driven.surprises] == [DEGRADED]
    assert str(driven).endswith(f"surprises:\n  {DEGRADED}\n"
                                f"{BROKEN.format(spec=corridor)}")
    assert driven.to_json()["substituted"] == []
    with pytest.raises(gaitc.UsageError, match="unknown --on-violation 'pray'"):
        gaitc.drive(corridor, options=DriveOptions(on_violation="pray"))


def test_violate_with_worst_substitutes_the_event(corridor: Path,
                                                  capsys: pytest.CaptureFixture[str]) -> None:
    """A performed event that breaks an assumption, taken at worst, is a substitution and
    not a surprise (nor an 'allowed' event)."""
    assert main(["drive", str(corridor), "--steps", "4", "--violate", "2:fail L1",
                 "--on-violation", "worst", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["violations"] == []
    assert data["substituted"] == [
        "step 2: fail L1 breaks an assumption; worst: taken as L1 3, L2 2, hazard none"]


def test_the_player_resumes_a_drive_that_recovered(tmp_path: Path,
                                                   capsys: pytest.CaptureFixture[str]) -> None:
    """A drive's run file, whose surprise is a sensed reading (no move words), is played
    again by ``gaitc play --from``: the recorded inputs are performed through the same
    recovery, to the same steps and the same surprise."""
    spec = tmp_path / "s.gait"
    spec.write_text(SPEC3, encoding="utf-8")
    controller = tmp_path / "s.json"
    scenario = tmp_path / "jump.yaml"
    scenario.write_text("steps:\n  - {}\n  - fail: [L1]\n  - {}\n  - {}\n", encoding="utf-8")
    out = tmp_path / "drive.jsonl"
    assert main(["synth", str(spec), "--prefer", "none", "-o", str(controller)]) == 0
    assert main(["drive", str(spec), str(controller), "--env", "scripted", str(scenario),
                 "--on-violation", "recover", "--out", str(out)]) == 0
    capsys.readouterr()
    driven = read_jsonl(out)
    player = gaitc.player(spec, controller, start=out)
    assert [s.values for s in player.steps] == [s.values for s in driven.steps]
    (surprise,) = player.surprises
    assert surprise == driven.surprises[0]
    assert surprise.event == "sensed L1 3→1; no hazard" and surprise.outcome == Outcome.RECOVERED
