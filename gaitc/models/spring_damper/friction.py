"""Coulomb friction with stiction at the end-effector contacts (thesis 4.1.3 and 3.4).

The spring-damper model has one contact per limb, its end effector (section 4.1.3).  Each
foot's coefficients depend on the direction it would slide, in the limb frame: outward
(the toe's high-friction pad), inward (the low-friction band) and sideways, blended as
``μ = μ_± cos²α + μ_lat sin²α``; while the limb is vented the heel carries the load, so the
coefficients move from the heel's to the toe's with the limb's activation (section 3.4:
"the heel provides a low friction contact point while the actuator is at rest").

With a massless foot, the ground force that holds it still is the stick force H (the
spring-damper force of eq. 4.1 with the foot at rest).  The foot sticks while |H| ≤ μ_s N
(μ_k N once it slides); otherwise it slides along −H with speed (|H| − μ_k N)/b, so that
the ground force is −μ_k N in the sliding direction.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from gaitc.models.spring_damper.description import Limb

Array = NDArray[np.float64]


@dataclass(frozen=True)
class FrictionTable:
    """Every limb's coefficients as (n,) arrays: static and kinetic for each direction."""

    heel: tuple[Array, Array]
    outward: tuple[Array, Array]
    inward: tuple[Array, Array]
    lateral: tuple[Array, Array]

    @classmethod
    def of(cls, limbs: tuple[Limb, ...]) -> FrictionTable:
        def column(part: str) -> tuple[Array, Array]:
            pairs = [getattr(limb.friction, part) for limb in limbs]
            return (
                np.array([p.static for p in pairs], dtype=float),
                np.array([p.kinetic for p in pairs], dtype=float),
            )

        return cls(column("heel"), column("outward"), column("inward"), column("lateral"))

    def coefficients(self, along: Array, across: Array, activation: Array) -> tuple[Array, Array]:
        """Static and kinetic coefficients for unit slide directions in the limb frames.

        ``along`` and ``across`` (..., n) are the direction's outward and left components,
        ``activation`` (..., n) in [0, 1]."""
        c2, s2 = along * along, across * across
        out = along >= 0.0
        a = np.minimum(np.maximum(activation, 0.0), 1.0)
        pairs = []
        for k in (0, 1):
            toe = np.where(out, self.outward[k], self.inward[k]) * c2 + self.lateral[k] * s2
            pairs.append((1.0 - a) * self.heel[k] + a * toe)
        return pairs[0], pairs[1]


@dataclass(frozen=True)
class Contact:
    """The result of the friction law at every foot for one time step, (..., n) arrays."""

    force_x: Array  # tangential ground force on each foot (= on the chassis), N
    force_y: Array
    slip_x: Array  # sliding velocity of each foot, m/s (zero while stuck)
    slip_y: Array
    sliding: NDArray[np.bool_]


def coulomb(
    hold_x: Array,
    hold_y: Array,
    normal: Array,
    damping: Array,
    cos: Array,
    sin: Array,
    activation: Array,
    *, table: FrictionTable,
    was_sliding: NDArray[np.bool_],
) -> Contact:
    """Coulomb friction with stiction for massless feet; every argument is (..., n).

    ``hold_x``, ``hold_y`` are the world-frame tangential force that would hold each foot
    still, ``normal`` the normal loads (zero off the ground), ``damping`` b of eq. 4.1,
    ``cos``, ``sin`` the world direction of every limb's outward axis.
    """
    magnitude = np.hypot(hold_x, hold_y)
    safe = np.where(magnitude > 0.0, magnitude, 1.0)
    ux, uy = -hold_x / safe, -hold_y / safe  # the way the spring pushes the foot
    mu_s, mu_k = table.coefficients(ux * cos + uy * sin, uy * cos - ux * sin, activation)
    on = normal > 0.0
    limit = np.where(was_sliding, mu_k, mu_s) * normal
    sliding = (magnitude > limit) & on
    kinetic = mu_k * normal
    speed = np.where(sliding, (magnitude - kinetic) / damping, 0.0)
    force_x = np.where(sliding, -kinetic * ux, np.where(on, hold_x, 0.0))
    force_y = np.where(sliding, -kinetic * uy, np.where(on, hold_y, 0.0))
    return Contact(force_x, force_y, ux * speed, uy * speed, sliding)
