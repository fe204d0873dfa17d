"""The active/passive model (thesis 4.1.2, 4.2.2) on silicone6: constraints, momentum,
friction, symmetry, and a brute-force search for a forward cycle."""

from __future__ import annotations

import itertools
import math
import re
from pathlib import Path

import numpy as np
import pytest

from gaitc.models.active_passive.description import parse_active_passive
from gaitc.models.active_passive.model import ActivePassiveModel, Step, settle_time, step_response
from gaitc.models.active_passive.statics import normal_loads
from gaitc.models.motion import MotionModel, Pose2D, ValveState

ROBOT = Path(__file__).resolve().parents[2] / "specs" / "robots" / "silicone6.yaml"
TOL = 1e-9  # mm or rad


def valves(bits: str) -> ValveState:
    """silicone6 valves: middle right, middle left, RL, RR, FL, FR."""
    return tuple(b == "1" for b in bits)


def mirror(state: ValveState) -> ValveState:
    right, left, rl, rr, fl, fr = state
    return (left, right, rr, rl, fr, fl)


@pytest.fixture(scope="module")
def model() -> ActivePassiveModel:
    return ActivePassiveModel.from_robot_file(ROBOT, steps=4)


@pytest.fixture(scope="module")
def frictionless() -> ActivePassiveModel:
    text = re.sub(r"friction: [0-9.]+", "friction: 0", ROBOT.read_text())
    return ActivePassiveModel(parse_active_passive(text, str(ROBOT)), steps=16, cache=False)


SEQUENCE = ["000000", "001001", "010110", "100110", "111111", "001000", "000000"]


def _check_rest(model: ActivePassiveModel, x: np.ndarray, vertices: np.ndarray) -> None:
    assert vertices[:, 2].min() >= -TOL  # no vertex below the ground
    assert vertices[:, 2].min() <= TOL  # and the robot rests on it
    for (low, high), value in zip(model.kinematics.bounds(), x, strict=True):
        assert low is None or value >= low - TOL
        assert high is None or value <= high + TOL


def test_the_model_is_a_motion_model(model: ActivePassiveModel) -> None:
    checked: MotionModel = model
    assert checked.name == "active-passive"
    with pytest.raises(ValueError, match="has 6 entries, not 2"):
        model.transition((True, False), (False, False), 6.0)


def test_vented_robot_lies_flat(model: ActivePassiveModel) -> None:
    rest = model.steady(valves("000000"))
    np.testing.assert_allclose(rest.x, 0.0, atol=1e-6)
    heights = rest.posture.vertices[0, :, 2]
    assert heights.min() == pytest.approx(0.0, abs=TOL)


def test_constraints_hold_at_every_step_of_a_valve_sequence(model: ActivePassiveModel) -> None:
    for a, b in itertools.pairwise(SEQUENCE):
        start = model.steady(valves(a))
        _check_rest(model, start.x, start.posture.vertices[0])
        steps = model.simulate(valves(a), valves(b), 6.0)
        assert steps and steps[-1].time == 6.0
        for step in steps:
            _check_rest(model, step.rest.x, step.rest.posture.vertices[0])
            assert step.rest.converged


def test_legs_down_lift_the_body_by_their_curl(model: ActivePassiveModel) -> None:
    rest = model.steady(valves("001111"))
    # every leg curls 80 mm at 0.0196 1/mm: its tip ends r(1 - cos κL) below the leg's base,
    # which sits 8 mm above the bottom of the blocks, and the lowest corner of the 16 mm
    # section there hangs 8 cos κL lower still; the body stays level
    radius = 1 / 0.0196
    bend = 80 / radius
    drop = radius * (1 - math.cos(bend)) + 8 * math.cos(bend)
    assert rest.x[0] == pytest.approx(drop - 8, abs=1e-6)
    np.testing.assert_allclose(rest.x[1:], 0.0, atol=1e-6)


def test_friction_only_dissipates_and_the_robot_comes_to_rest(model: ActivePassiveModel) -> None:
    for a, b in itertools.pairwise(SEQUENCE):
        steps = model.simulate(valves(a), valves(b), 6.0)
        assert all(s.friction_power <= 1e-6 for s in steps)
        assert np.abs(steps[-1].velocity).max() < 1e-4  # mm/s, rad/s


def test_mirrored_transitions_mirror_the_motion(model: ActivePassiveModel) -> None:
    a, b = valves("001001"), valves("010110")
    p = model.transition(a, b, 6.0)
    q = model.transition(mirror(a), mirror(b), 6.0)
    assert abs(p.x) + abs(p.y) > 0.5  # something moves
    assert q.x == pytest.approx(p.x, abs=1e-4)
    assert q.y == pytest.approx(-p.y, abs=1e-4)
    assert q.theta == pytest.approx(-p.theta, abs=1e-6)


def test_a_symmetric_transition_does_not_turn(model: ActivePassiveModel) -> None:
    for a, b in [("000000", "001111"), ("001111", "110000"), ("000000", "000011")]:
        p = model.transition(valves(a), valves(b), 6.0)
        assert abs(p.y) < 1e-6 and abs(p.theta) < 1e-8


def _world_centre(model: ActivePassiveModel, step: Step, frame: Pose2D) -> np.ndarray:
    """The centre of mass after ``step`` in the frame its transition began at ``frame``."""
    m = model.kinematics.masses
    local = m @ step.rest.posture.centres[0, :, :2] / m.sum()
    pose = frame.compose(step.pose).compose(Pose2D(float(local[0]), float(local[1]), 0.0))
    return np.array([pose.x, pose.y])


def test_without_friction_momentum_is_conserved(frictionless: ActivePassiveModel) -> None:
    a, b = valves("001001"), valves("010100")
    rest = frictionless.steady(a)
    m = frictionless.kinematics.masses
    start = m @ rest.posture.centres[0, :, :2] / m.sum()
    steps = frictionless.simulate(a, b, 6.0)
    origin = Pose2D(0.0, 0.0, 0.0)
    turned = 0.0
    for step in steps:
        np.testing.assert_allclose(step.momentum, 0.0, atol=1e-6)  # linear and angular
        np.testing.assert_allclose(_world_centre(frictionless, step, origin), start, atol=1e-6)
        turned = max(turned, abs(step.pose.theta))
    assert turned > 1e-3  # the shape change alone turns the body (a "falling cat" rotation)
    back = frictionless.simulate(b, a, 6.0)
    # a reciprocal shape change retraces its path: no net rotation, the centre stays put
    total = steps[-1].pose.compose(back[-1].pose)
    assert abs(total.theta) < 1e-4
    np.testing.assert_allclose(
        _world_centre(frictionless, back[-1], steps[-1].pose), start, atol=1e-6
    )


def test_second_order_response() -> None:
    comp = ActivePassiveModel.from_robot_file(ROBOT).robot.component("RL")
    t = np.array([0.0, 1.0, 2.0])
    wn = comp.natural_frequency
    np.testing.assert_allclose(step_response(comp, t), 1 - (1 + wn * t) * np.exp(-wn * t))
    done = settle_time(comp)
    assert 1 - step_response(comp, np.array([done]))[0] <= 1e-3
    assert done == pytest.approx(9.23 / wn, rel=0.01)


def _best_forward(model: ActivePassiveModel) -> tuple[Pose2D, tuple[str, ...]]:
    """The straight cycle moving furthest along +x among every two- and three-state cycle
    over salamander-like states: the middle bent one way or the other, no legs or one
    diagonal leg pair down (displacement in the frame of the cycle's first state)."""
    states = [m + legs for m in ("10", "01") for legs in ("0000", "1001", "0110")]
    best: tuple[Pose2D, tuple[str, ...]] = (Pose2D(0.0, 0.0, 0.0), ())
    for k in (2, 3):
        for cycle in itertools.permutations(states, k):
            if cycle[0] != min(cycle):
                continue
            pose = model.cycle([valves(s) for s in cycle], 6.0)
            straight = abs(pose.theta) < 0.02 and abs(pose.y) < abs(pose.x)
            if straight and pose.x > best[0].x:
                best = (pose, cycle)
    return best


def test_some_valve_cycle_moves_silicone6_forward(model: ActivePassiveModel) -> None:
    pose, cycle = _best_forward(model)
    assert pose.x > 1.0, (pose, cycle)  # mm per cycle along the robot's +x
    mirrored = model.cycle([mirror(valves(s)) for s in cycle], 6.0)
    assert mirrored.x == pytest.approx(pose.x, abs=1e-4)
    assert mirrored.y == pytest.approx(-pose.y, abs=1e-4)
    # run backwards, the same states do not carry the robot forward as far
    backwards = model.cycle([valves(s) for s in reversed(cycle)], 6.0)
    assert backwards.x < pose.x - 0.5


@pytest.mark.parametrize("bits", ["011001", "100110", "001111"])
def test_height_derivatives_match_finite_differences(model: ActivePassiveModel, bits: str) -> None:
    kin = model.kinematics
    prepared = kin.prepare(model.active(valves(bits)))
    x = np.array([20.0, 0.1, -0.05, 0.2, -0.1, 0.15])  # height, roll, pitch, twist, hinges
    vz, cz, jv, jc = kin.heights(prepared, x)
    h = 1e-6
    rows = np.vstack([x, x + h * np.eye(x.size)])
    posture = kin.posture(prepared, rows)
    np.testing.assert_allclose(vz, posture.vertices[0, :, 2], atol=1e-12)
    np.testing.assert_allclose(cz, posture.centres[0, :, 2], atol=1e-12)
    fd_v = (posture.vertices[1:, :, 2] - posture.vertices[0, :, 2]).T / h
    fd_c = (posture.centres[1:, :, 2] - posture.centres[0, :, 2]).T / h
    np.testing.assert_allclose(jv, fd_v, atol=1e-4)  # mm per rad; the FD error is ~h·|p|
    np.testing.assert_allclose(jc, fd_c, atol=1e-4)
    assert np.abs(jv[:, 4]).max() > 1.0  # the rear hinge moves something


def test_normal_loads_balance_the_weight_as_evenly_as_possible() -> None:
    square = np.array([[1.0, 1.0, 0.0], [1.0, -1.0, 0.0], [-1.0, -1.0, 0.0], [-1.0, 1.0, 0.0]])
    lifted = np.array([[0.0, 0.0, 3.0]])  # above the contact tolerance: no load
    points = np.vstack([square * 50, lifted])
    even = normal_loads(points, np.zeros(3), 100.0, 0.5)
    np.testing.assert_allclose(even, [25, 25, 25, 25, 0], atol=1e-3)
    # centre 25 mm towards +x: the least-norm loads are 37.5 on the front pair, 12.5 behind
    shifted = normal_loads(points, np.array([25.0, 0.0, 10.0]), 100.0, 0.5)
    np.testing.assert_allclose(shifted, [37.5, 37.5, 12.5, 12.5, 0], atol=1e-3)
    moment = shifted @ (points[:, 0] - 25.0)
    assert abs(moment) < 1e-2 and shifted.sum() == pytest.approx(100.0)


def test_the_catalogue_entry_finds_a_forward_gait() -> None:
    from gaitc.models.active_passive.model import loaded_model
    from gaitc.models.catalogue import search_gaits

    loaded = loaded_model(ROBOT)
    assert loaded.period == 6.0 and loaded.robot == "silicone6"
    assert loaded.valve_legs == ("spine", "spine", "RL", "RR", "FL", "FR")
    assert loaded.body_length == pytest.approx(200.0)  # the legs' span when flat
    found = search_gaits(loaded, (1.0, 0.0), max_open=1)  # at most one valve open
    best = found.gaits[0]
    assert best.net.x > 5.0 and abs(best.net.y) < best.net.x / 4  # mm per cycle
    assert abs(best.net.theta) < math.radians(3)
