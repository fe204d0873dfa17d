"""``gaitc ros --sim``: the controller node and a simulated robot node talk over real ROS 2
topics, every topic goes to an MCAP file, and the gaits recorded are those of ``gaitc
simulate`` with the same environment, seed, steps and violations, step by step (issue 62),
on robot A (hazard sets) and on the 8-leg radial robot (valve primitives)."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from collections import Counter
from pathlib import Path

import pytest
from ros_graph import RADIAL8, ROBOT_A, controller, ros_domain

import gaitc
from gaitc.api.ros import RosOptions, SimulatedRobot, ros
from gaitc.ros.recording import read
from gaitc.ros.topics import status_of

__all__ = ["ros_domain"]

TWO_EVENTS = {ROBOT_A: ("40:fail L1", "120:degrade L3,switch blue on"),
              RADIAL8: ("40:fail L1", "120:degrade L3 by 2")}


@pytest.fixture(scope="module")
def controllers(tmp_path_factory: pytest.TempPathFactory) -> dict[Path, Path]:
    folder = tmp_path_factory.mktemp("controllers")
    return {spec: controller(spec, folder) for spec in (ROBOT_A, RADIAL8)}


def recorded(path: Path) -> tuple[list[str], Counter[str], list[object]]:
    """The gaits, the messages by topic and the controller's statuses of a recording."""
    messages = list(read(path))
    gaits = [m.message.data for m in messages if m.topic == "/gait"]
    statuses = [status_of(m.message) for m in messages if m.topic == "/diagnostics"]
    return gaits, Counter(m.topic for m in messages), statuses


@pytest.mark.parametrize(("spec", "env", "violate"), [
    (ROBOT_A, "random", False),
    (RADIAL8, "random", True),
], ids=["robot_a-random", "radial8-random-two-events"])
def test_the_recording_is_the_simulation_step_by_step(
        spec: Path, env: str, violate: bool, controllers: dict[Path, Path], tmp_path: Path,
        ros_domain: dict[str, str]) -> None:
    events = TWO_EVENTS[spec] if violate else ()
    mcap = tmp_path / "run.mcap"
    ran = ros(spec, controllers[spec], RosOptions(record=mcap),
              SimulatedRobot(env, seed=7, violate=events, steps=200))
    assert ran.run is not None and ran.run.error is None, ran.stopped
    assert ran.robot == "played 200 steps"
    simulated = gaitc.simulate(spec, controllers[spec], env=env, steps=200, seed=7,
                               violate=events)
    expected = [s.gait for s in simulated.steps]
    assert len(expected) == 201
    assert [s.gait for s in ran.run.steps] == expected
    gaits, counts, statuses = recorded(mcap)
    assert gaits == [*expected, "noGait"]  # each step's gait, then the vent at the end
    assert counts["/leg_health"] == 201 and counts["/target_region"] == 201
    if spec == ROBOT_A:
        assert counts["/hazards"] == 201 and "/valves" not in counts
    else:
        assert counts["/valves"] == 202 and "/hazards" not in counts
    if violate:
        assert [(s.step, s.outcome.value) for s in ran.run.surprises] == [
            (s.step, s.outcome.value) for s in simulated.surprises]
        surprised = [s for s in statuses if s is not None and s.value("surprises") == "2"]
        assert surprised and surprised[-1].value("last surprise") == \
            simulated.surprises[-1].outcome.value
    last = statuses[-1]
    assert last is not None and last.level == 2 and last.message == \
        "finished 200 steps; every valve vented"


@pytest.mark.slow  # robot A's recovery games: about 15 s of CPU in each process
def test_the_command_with_two_events_on_robot_a_is_simulate_json(
        controllers: dict[Path, Path], tmp_path: Path, ros_domain: dict[str, str]) -> None:
    """The command line, as the issue says it: ``gaitc ros ... --sim`` beside ``gaitc
    simulate ... --json`` (run at the same time: robot A's recovery games take seconds)."""
    words = [str(ROBOT_A), str(controllers[ROBOT_A]), "--env", "adversarial", "--steps", "200"]
    for event in TWO_EVENTS[ROBOT_A]:
        words += ["--violate", event]
    mcap = tmp_path / "run.mcap"
    env = {**os.environ, **ros_domain}
    node = subprocess.Popen([sys.executable, "-m", "gaitc", "ros", *words, "--sim", "--record",
                             str(mcap), "--quiet"], env=env, stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True)
    try:
        simulated = subprocess.run([sys.executable, "-m", "gaitc", "simulate", *words,
                                    "--json"], env=env, capture_output=True, text=True,
                                   timeout=120, check=False)
        out, err = node.communicate(timeout=120)
    finally:
        if node.poll() is None:
            node.kill()
            node.wait()
    assert node.returncode == 0, err
    assert "simulated robot: played 200 steps" in out
    document = json.loads(simulated.stdout)
    expected = [s["gait"] for s in document["steps"]]
    assert len(expected) == 201 and len(document["violations"]) == 2
    gaits, _, _ = recorded(mcap)
    assert gaits == [*expected, "noGait"]


def test_a_run_file_replayed_under_remapped_names(tmp_path: Path, ros_domain: dict[str, str]
                                                  ) -> None:
    """``--env scripted RUN.jsonl`` plays a run file's inputs again, and ``--ros-args -r``
    moves a topic for every node of the command, the recorder too."""
    spec = ROBOT_A.parent / "patrol_2x2.gait"
    played = gaitc.simulate(spec, steps=8, seed=4)
    file = tmp_path / "run.jsonl"
    from gaitc.api.runs import save_run

    save_run(played, str(file))
    mcap = tmp_path / "again.mcap"
    ran = ros(spec, None, RosOptions(record=mcap, ros_args=("-r", "gait:=/robot/gait_cmd")),
              SimulatedRobot(f"scripted:{file}"))
    assert ran.run is not None and ran.robot == "played 8 steps"
    messages = list(read(mcap))
    assert "/gait" not in {m.topic for m in messages}
    assert [m.message.data for m in messages if m.topic == "/robot/gait_cmd"] == [
        *(s.gait for s in played.steps), "noGait"]


@pytest.mark.parametrize("form", ["explicit", "symbolic", "compact"])
def test_every_controller_form_runs_on_the_node(form: str, tmp_path: Path,
                                                ros_domain: dict[str, str]) -> None:
    """Each form through its run view (:mod:`gaitc.forms`), on the two-leg shuttle with its
    valves; L2 failing unused at step 3 leaves the robot one goal (degraded)."""
    spec = ROBOT_A.parent / "shuttle_2leg.gait"
    made = gaitc.synthesize(gaitc.load(spec), form=form, verify=False)
    path = tmp_path / f"{form}.json"
    made.save(path)
    mcap = tmp_path / "run.mcap"
    ran = ros(spec, path, RosOptions(record=mcap),
              SimulatedRobot("random", seed=2, violate=("3:fail L2",), steps=12))
    simulated = gaitc.simulate(spec, path, env="random", steps=12, seed=2,
                               violate=["3:fail L2"])
    assert ran.run is not None
    assert [s.gait for s in ran.run.steps] == [s.gait for s in simulated.steps]
    gaits, counts, statuses = recorded(mcap)
    assert gaits[:len(simulated.steps)] == [s.gait for s in simulated.steps]
    assert counts["/valves"] == counts["/gait"]
    degraded = next(s for s in statuses if s is not None and s.value("surprises") == "1")
    assert (degraded.value("last surprise"), degraded.value("goals lost")) == (
        "degraded", "visit a")
