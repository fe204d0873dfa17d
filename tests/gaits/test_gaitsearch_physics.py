"""The chapter 5 online loop on the chapter 4 physics backend (gaitc.search.physics_walker),
with predictions from the spring-damper model's gait graph (gaitc.search.predictions)."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from gaitc.cli import main
from gaitc.diagnostics import UsageError
from gaitc.models.spring_damper.description import load_spring_damper
from gaitc.search import Mismatch, Settings, learn_gait
from gaitc.search.backends import default_predictions
from gaitc.search.goals import Goal
from gaitc.search.perturbation import perturbed
from gaitc.search.physics_walker import PhysicsWalker
from gaitc.search.predictions import has_model, model_transitions
from gaitc.search.transitions import compose

ROBOTS = Path(__file__).resolve().parents[2] / "specs" / "robots"
RADIAL = str(ROBOTS / "radial8.yaml")
FINE = Settings(cell=1.0, cell_angle=1.0)
# executed against the final plan's prediction: the model graph starts every transition from
# a steady state, the walker from wherever the last one left the feet, plus 0.2 mm noise
AGREE = 2.0


def test_model_predictions_are_the_model_gait_graph() -> None:
    found = model_transitions(RADIAL)
    model = found.model
    assert model.poses == 9 and len(model) == 72  # at most one valve open, every pair
    assert model.labels[found.start] == "00000000"
    edge = model.find(found.start, model.labels.index("00001000"))
    assert edge is not None
    # pressurising L5 (pointing along -x) pushes the chassis along +x
    step = model.step(edge)
    assert step.dx == pytest.approx(20.1, abs=0.1) and abs(step.dy) < 1e-6
    assert has_model(RADIAL) and not has_model(ROBOTS / "symmetric6.yaml")
    assert default_predictions(RADIAL) == "model"
    assert default_predictions(str(ROBOTS / "symmetric6.yaml")) == "kinematic"


def test_the_walker_from_rest_measures_the_prediction() -> None:
    found = model_transitions(RADIAL)
    walker = PhysicsWalker(found.model, found.start, found.loaded)
    with walker:
        walker.apply("00001000")
        first = walker.last
        walker.apply("00000000")
        walker.apply("00001000")
        again = walker.last
    assert first is not None and first.measured is not None and first.edge is not None
    predicted = found.model.step(first.edge)
    # the first transition starts from the steady state, as the prediction does
    assert first.measured.dx == pytest.approx(predicted.dx, abs=1e-6)
    assert first.measured.dy == pytest.approx(predicted.dy, abs=1e-6)
    # the second stroke of L5 starts from the feet the first cycle left: not the same motion
    assert again is not None and again.measured is not None
    assert again.measured != first.measured
    assert walker.transitions == 3


@pytest.mark.parametrize(
    ("goal", "method"), [((20.0, 0.0), "lpa"), ((10.0, 0.0), "lpa"), ((0.0, 20.0), "mcts")]
)
def test_the_loop_converges_on_the_physics_backend(goal: tuple[float, float], method: str) -> None:
    run = learn_gait(RADIAL, Goal(*goal), method, Mismatch(seed=1), FINE, backend="physics")
    assert run.converged and run.stopped == "converged"
    assert run.final is not None and run.executed is not None and run.error is not None
    distance, angle = run.error
    assert distance <= 5.0 and angle <= 5.0  # the goal's tolerance
    x, y, th = run.executed
    px, py, pth = run.final.displacement
    assert math.hypot(x - px, y - py) <= AGREE and abs(th - pth) <= AGREE


def test_executed_strokes_differ_from_steady_state_predictions() -> None:
    """10 mm along +x is no single stroke (one leg moves the chassis 20 mm): the gait is a
    diagonal stroke and a second leg's stroke, and the second starts from where the first
    left the feet, not from a steady state, so its measured motion differs from the
    prediction by more than the loop's 0.5 mm threshold."""
    run = learn_gait(RADIAL, Goal(10, 0), "lpa", Mismatch(seed=1), FINE, backend="physics")
    assert len(run.iterations[0].edges) == 3
    assert sum(it.changed for it in run.iterations) > 0


def test_the_physics_log_is_deterministic() -> None:
    runs = [
        learn_gait(RADIAL, Goal(20, 0), "lpa", Mismatch(seed=3), FINE, backend="physics")
        for _ in range(2)
    ]
    assert runs[0].to_json() == runs[1].to_json()


def test_sim_backend_can_search_the_model_graph() -> None:
    run = learn_gait(RADIAL, Goal(20, 0), "lpa", Mismatch(0.2, 0.2, seed=2), FINE)
    assert run.converged and run.final is not None
    assert all(len(v) == 8 for v in run.final.valves)


def test_physics_without_a_model_names_the_file(capsys: pytest.CaptureFixture[str]) -> None:
    robot = str(ROBOTS / "symmetric6.yaml")
    assert main(["learn", robot, "--goal", "10,0", "--backend", "physics"]) == 1
    err = capsys.readouterr().err
    assert f"{robot}:7:1: error: robot file has no 'model' section" in err


def test_physics_with_kinematic_predictions_is_a_usage_error(
    capsys: pytest.CaptureFixture[str],
) -> None:
    argv = ["learn", RADIAL, "--goal", "10,0", "--backend", "physics"]
    assert main([*argv, "--predictions", "kinematic"]) == 2
    assert "use --predictions model" in capsys.readouterr().err


def test_learn_physics_cli(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    log = tmp_path / "log.json"
    argv = ["learn", RADIAL, "--goal", "20,0", "--backend", "physics", "--cell", "1,1"]
    assert main([*argv, "--log", str(log), "--quiet"]) == 0
    out = capsys.readouterr().out
    assert out.startswith("lpa: converged after 1 iterations\n")
    assert '"valves": [\n        "00000000",\n        "00001000"\n      ]' in log.read_text()


def test_unknown_predictions_are_a_usage_error(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["learn", RADIAL, "--goal", "10,0", "--predictions", "dynamic"]) == 2
    err = capsys.readouterr().err
    assert err == "gaitc: usage error: unknown predictions 'dynamic'; use kinematic or model\n"


# the model mismatch: the walker's robot has its stiffness and friction scaled (seeded)
SLACK = 3.0  # executed against the goal: its 5 mm / 5 deg plus snapping and noise


def test_perturbed_scales_stiffness_and_friction_within_the_bound() -> None:
    robot = load_spring_damper(RADIAL)
    assert perturbed(robot, 0.0, 1) is robot
    changed = perturbed(robot, 0.3, 1)
    assert changed == perturbed(robot, 0.3, 1) and changed != perturbed(robot, 0.3, 2)
    for old, new in zip(robot.limbs, changed.limbs, strict=True):
        (_, k_old), (_, k_new) = old.stiffness[0], new.stiffness[0]
        ratio = k_new[0][0] / k_old[0][0]
        assert 0.7 <= ratio <= 1.3 and ratio != 1.0
        f_old, f_new = old.friction.outward, new.friction.outward
        assert 0.7 <= f_new.static / f_old.static <= 1.3
        assert f_new.static / f_old.static == pytest.approx(f_new.kinetic / f_old.kinetic)
    with pytest.raises(UsageError, match="must lie in"):
        perturbed(robot, 1.0, 1)


def test_a_mismatched_walker_moves_otherwise_than_predicted_from_rest() -> None:
    found = model_transitions(RADIAL)
    walker = PhysicsWalker(found.model, found.start, found.loaded, seed=2, mismatch=0.3)
    with walker:
        walker.apply("00001000")
        first = walker.last
    assert first is not None and first.measured is not None and first.edge is not None
    predicted = found.model.step(first.edge)
    assert abs(first.measured.dx - predicted.dx) > 1.0  # from rest, unlike without mismatch


@pytest.mark.parametrize(
    ("goal", "seed", "method"),
    [((20.0, 0.0), 2, "lpa"), ((40.0, 0.0), 2, "lpa"), ((0.0, 20.0), 1, "mcts")],
)
def test_the_loop_learns_a_model_mismatch(
    goal: tuple[float, float], seed: int, method: str
) -> None:
    found = model_transitions(RADIAL)
    mismatch = Mismatch(seed=seed, model=0.3)
    run = learn_gait(RADIAL, Goal(*goal), method, mismatch, FINE, backend="physics")
    assert run.converged and sum(it.changed for it in run.iterations) > 0
    assert run.final is not None and run.executed is not None and run.error is not None
    distance, angle = run.error
    assert distance <= 5.0 + SLACK and angle <= 5.0 + SLACK
    # the learned prediction is what the robot does, the model graph's was not
    x, y, th = run.executed
    px, py, pth = run.final.displacement
    assert math.hypot(x - px, y - py) <= AGREE and abs(th - pth) <= AGREE
    ox = oy = oth = 0.0
    for e in run.final.edges:
        ox, oy, oth = compose(ox, oy, oth, found.model.step(e))
    assert math.hypot(x - ox, y - oy) > AGREE or abs(th - oth) > AGREE


def test_model_mismatch_is_the_physics_backends(capsys: pytest.CaptureFixture[str]) -> None:
    argv = ["learn", RADIAL, "--goal", "20,0", "--model-mismatch", "0.3"]
    assert main(argv) == 2
    assert "is the physics backend's" in capsys.readouterr().err
    assert main([*argv, "--backend", "physics", "--cell", "1,1", "--quiet"]) == 0
