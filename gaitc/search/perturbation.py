"""Model mismatch for the physics backend: the spring-damper robot with scaled parameters.

The online loop (thesis 5.2.3, Algorithm 2) learns only where the robot moves otherwise than
predicted.  The model gait graph of the physics backend is built from the robot file's
spring-damper model (chapter 4, eq. 4.1); executing with that same model leaves only the
difference of start states.  :func:`perturbed` gives the robot the walker executes with:
each limb's stiffness matrices and each of its four friction contacts scaled by its own
seeded factor drawn uniformly from [1 - F, 1 + F] (static and kinetic coefficient by the same
factor, so stiction stays at least kinetic friction), as a real robot differs from its
estimated parameters (models.md).
"""

from __future__ import annotations

import dataclasses

import numpy as np

from gaitc.diagnostics import UsageError
from gaitc.models.spring_damper.description import (
    Coefficients,
    Limb,
    SpringDamperRobot,
    ToeFriction,
)

_CONTACTS = ("heel", "outward", "inward", "lateral")


def perturbed(robot: SpringDamperRobot, scale: float, seed: int) -> SpringDamperRobot:
    """``robot`` with stiffness and friction scaled limb by limb (``scale`` F in [0, 1))."""
    if not 0 <= scale < 1:
        raise UsageError(f"the model mismatch must lie in [0, 1), not {scale:g}")
    if scale == 0:
        return robot
    rng = np.random.default_rng([seed, 4])
    limbs = tuple(_limb(limb, rng, scale) for limb in robot.limbs)
    return dataclasses.replace(robot, limbs=limbs)


def _factor(rng: np.random.Generator, scale: float) -> float:
    return float(rng.uniform(1.0 - scale, 1.0 + scale))


def _limb(limb: Limb, rng: np.random.Generator, scale: float) -> Limb:
    k = _factor(rng, scale)
    stiffness = tuple(
        (pattern, tuple(tuple(k * v for v in row) for row in matrix))
        for pattern, matrix in limb.stiffness
    )
    contacts = {}
    for name in _CONTACTS:
        c: Coefficients = getattr(limb.friction, name)
        f = _factor(rng, scale)
        contacts[name] = Coefficients(c.static * f, c.kinetic * f)
    return dataclasses.replace(limb, stiffness=stiffness, friction=ToeFriction(**contacts))
