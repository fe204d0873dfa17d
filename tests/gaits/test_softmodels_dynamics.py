"""The spring-damper model (thesis 4.1.1) against closed-form answers and energy bounds."""

from __future__ import annotations

import math
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from gaitc.models.characterization import step_response
from gaitc.models.motion import Pose2D
from gaitc.models.spring_damper.description import Coefficients, ToeFriction, load_spring_damper
from gaitc.models.spring_damper.model import SpringDamperModel

DATA = Path(__file__).parents[1] / "data" / "softmodels"
RADIAL8 = Path(__file__).parents[2] / "specs" / "robots" / "radial8.yaml"


@pytest.fixture(scope="module")
def one_limb() -> SpringDamperModel:
    return SpringDamperModel(load_spring_damper(DATA / "one_limb.yaml"))


def test_vertical_response_is_the_closed_form_second_order_solution(
    one_limb: SpringDamperModel,
) -> None:
    m, k, b, g = 0.1, 200.0, 1.0, 9.81  # kg, N/m, N·s/m: the file's 100 g, 0.2 N/mm, 0.001
    w = math.sqrt(k / m)
    zeta = b / (2 * math.sqrt(k * m))
    wd = w * math.sqrt(1 - zeta**2)
    rest = one_limb.rest_state([(False,)])
    equilibrium = 0.05 - m * g / k  # the leg is 50 mm long, straight down
    v0 = 0.05
    state = replace(
        rest,
        position=np.array([[0.0, 0.0, equilibrium]]),
        velocity=np.array([[0.0, 0.0, -v0]]),
        feet=np.zeros((1, 1, 3)),
        contact=np.ones((1, 1), dtype=bool),
    )
    target = np.stack([one_limb.arrays.targets((False,))])
    worst = 0.0
    for i in range(1, 4001):  # 0.4 s, about three periods
        state = one_limb.step(state, target)
        t = i * one_limb.dt
        exact = equilibrium - v0 / wd * math.exp(-zeta * w * t) * math.sin(wd * t)
        worst = max(worst, abs(float(state.position[0, 2]) - exact))
    amplitude = v0 / wd
    assert worst < 0.02 * amplitude


def test_curvature_follows_the_second_order_step(one_limb: SpringDamperModel) -> None:
    state = one_limb.rest_state([(False,)])
    state = replace(state, position=state.position + np.array([[0, 0, 1.0]]))  # in the air
    target = np.stack([one_limb.arrays.targets((True,))])
    times, kappa = [], []
    for i in range(1, 3001):
        state = one_limb.step(state, target)
        times.append(i * one_limb.dt)
        kappa.append(float(state.kappa[0, 0, 0]))
    exact = step_response(np.array(times), 0.0, 4.0, 30.0, 0.4)  # 0.004 1/mm = 4 1/m
    assert np.abs(np.array(kappa) - exact).max() < 0.01 * 4.0
    assert not state.contact.any()


def test_a_damped_robot_never_gains_energy() -> None:
    model = SpringDamperModel(load_spring_damper(RADIAL8))
    valves = (False, False, False, False, False, True, False, False)
    steady = model.steady_state(valves)
    kicked = replace(steady, velocity=np.array([[0.08, -0.05, 0.03]]), omega=np.array([0.6]))
    target = np.stack([model.arrays.targets(valves)])
    energies = [float(model.energy(kicked)[0])]
    state = kicked
    for _ in range(1500):
        state = model.step(state, target)
        energies.append(float(model.energy(state)[0]))
    e = np.array(energies)
    scale = e[0] - e.min()
    assert scale > 0
    assert np.max(e[1:] - np.minimum.accumulate(e)[:-1]) < 1e-3 * scale  # never rises
    assert e[-1] < e[0] - 0.9 * scale


def test_dropping_settles_on_all_feet_with_the_weight_carried() -> None:
    model = SpringDamperModel(load_spring_damper(RADIAL8))
    steady = model.steady_state((False,) * 8)
    f = model.forces(steady, steady.kappa, steady.kappa_rate)
    assert steady.contact.all()
    assert float(f.ground[0, :, 2].sum()) == pytest.approx(model.mass * 9.81, rel=5e-3)
    assert abs(float(f.ground[0, :, 0].sum())) < 1e-3


def test_transitions_compose_in_the_body_frame() -> None:
    model = SpringDamperModel(load_spring_damper(RADIAL8))
    vented = (False,) * 8
    l7 = tuple(i == 6 for i in range(8))
    push = model.transition(vented, l7, 6.0)
    assert push.y > 10.0 and abs(push.x) < 0.5  # L7 points along -y: the chassis goes +y
    back = Pose2D(1.0, 2.0, 0.5).compose(Pose2D(1.0, 2.0, 0.5).inverse())
    assert (back.x, back.y, back.theta) == pytest.approx((0.0, 0.0, 0.0), abs=1e-12)


def test_without_friction_horizontal_and_angular_momentum_are_conserved() -> None:
    robot = load_spring_damper(RADIAL8)
    none = Coefficients(0.0, 0.0)
    slippery = ToeFriction(none, none, none, none)
    limbs = tuple(replace(limb, friction=slippery) for limb in robot.limbs)
    model = SpringDamperModel(replace(robot, limbs=limbs))
    valves = (False,) * 8
    steady = model.steady_state(valves)
    kicked = replace(steady, velocity=np.array([[0.05, -0.02, 0.01]]), omega=np.array([0.3]))
    target = np.stack([model.arrays.targets(valves)])
    state = kicked
    for _ in range(500):
        state = model.step(state, target)
    assert state.velocity[0, :2] == pytest.approx([0.05, -0.02], abs=1e-9)
    assert state.omega[0] == pytest.approx(0.3, abs=1e-9)
    assert state.contact.all()  # the feet stayed on the ground and carried no shear
