"""Anisotropic Coulomb friction with stiction (thesis 4.1.3 and 3.4) on a one-leg robot."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from gaitc.models.spring_damper.description import Coefficients, ToeFriction, load_spring_damper
from gaitc.models.spring_damper.friction import FrictionTable, coulomb
from gaitc.models.spring_damper.model import SpringDamperModel

ONE_LEG = Path(__file__).parents[1] / "data" / "softmodels" / "one_leg.yaml"


def _cycles(model: SpringDamperModel, count: int) -> list[float]:
    """Chassis x after each extension-and-return cycle, mm, from the vented steady state."""
    state = model.steady_state((False,))
    xs = [state.pose().x]
    for _ in range(count):
        state = model.run(state, [(True,)], 6.0)
        state = model.run(state, [(False,)], 6.0)
        xs.append(state.pose().x)
    return xs


def test_the_toe_propels_the_robot_forward_every_cycle() -> None:
    model = SpringDamperModel(load_spring_damper(ONE_LEG))
    xs = _cycles(model, 3)
    steps = np.diff(xs)
    # the leg points along +x: extension pushes the chassis away from it, towards -x
    assert (steps < -10.0).all()
    assert np.allclose(steps, steps[0], atol=1.0)  # the same progress every cycle


def test_the_return_slides_on_the_band_instead_of_pulling_back() -> None:
    model = SpringDamperModel(load_spring_damper(ONE_LEG))
    out = model.transition((False,), (True,), 6.0)
    back = model.transition((True,), (False,), 6.0)
    assert out.x < -15.0
    assert 0.0 <= back.x < 0.2 * -out.x


def test_an_isotropic_toe_goes_nowhere() -> None:
    robot = load_spring_damper(ONE_LEG)
    pad = robot.limbs[0].friction.outward
    leg = robot.limbs[0]
    same = type(leg)(**{**leg.__dict__, "friction": ToeFriction(pad, pad, pad, pad)})
    model = SpringDamperModel(type(robot)(**{**robot.__dict__, "limbs": (same, *robot.limbs[1:])}))
    xs = _cycles(model, 2)
    assert abs(xs[-1] - xs[0]) < 0.25 * abs(_cycles(SpringDamperModel(robot), 2)[-1])


def _table() -> FrictionTable:
    leg = load_spring_damper(ONE_LEG).limbs[0]
    toe = ToeFriction(
        Coefficients(0.1, 0.05),
        Coefficients(1.0, 0.8),
        Coefficients(0.2, 0.1),
        Coefficients(0.5, 0.4),
    )
    return FrictionTable.of((type(leg)(**{**leg.__dict__, "friction": toe}),))


def _law(hold_x: float, activation: float, sliding: bool) -> tuple[bool, float, float]:
    """One foot along its limb's axis (world +x), normal load 1 N, b = 2 N·s/m."""
    c = coulomb(
        np.array([hold_x]),
        np.zeros(1),
        np.ones(1),
        np.array([2.0]),
        np.ones(1),
        np.zeros(1),
        np.array([activation]),
        table=_table(),
        was_sliding=np.array([sliding]),
    )
    return bool(c.sliding[0]), float(c.force_x[0]), float(c.slip_x[0])


def test_stiction_holds_below_the_static_limit_and_slides_above_it() -> None:
    # the spring pushes the foot outward (hold -0.9 N): the pad's μ_s N = 1 N holds it
    assert _law(-0.9, 1.0, False) == (False, pytest.approx(-0.9), 0.0)
    # once sliding, μ_k N = 0.8 N applies and the foot slides at (0.9 - 0.8) / b
    assert _law(-0.9, 1.0, True) == (True, pytest.approx(-0.8), pytest.approx(0.05))
    # pushed inward, the band (μ_s 0.2) gives way; the ground force is μ_k N = 0.1 N
    assert _law(0.9, 1.0, False) == (True, pytest.approx(0.1), pytest.approx(-0.4))
    # vented, the heel carries the load whichever way the foot is pushed
    assert _law(-0.9, 0.0, False)[:2] == (True, pytest.approx(-0.05))
    assert _law(0.05, 0.0, False) == (False, pytest.approx(0.05), 0.0)
