"""Constant-curvature kinematics of every leg for many valve states at once (thesis 2.4.1).

Sign convention: chassis frame x forward, y left, z up.  A leg's frame has its axis z'
along the unbent leg (yaw about z, then pitch below the xy-plane), x' perpendicular to
it pointing up/outward, y' = z' × x'.  A leg bent with curvature κ in the plane at angle
φ (from x' towards y', plus the leg's roll) has its point at arc length s at
``((1 - cos κs)/κ · cos φ, (1 - cos κs)/κ · sin φ, sin(κs)/κ)``, written with sinc so it
is continuous as κ → 0.  A leg with a ``parent`` hangs from the parent's tip frame, which
is the chassis frame carried by the parent's bending.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from gaitc.gaitgraph.robot import Leg, Robot

Array = NDArray[np.float64]
_SAMPLES = 8  # points per leg for its centre of mass


def valve_string(state: int, count: int) -> str:
    """Valve state as text: character i is chamber i (``1`` = pressurised)."""
    return "".join("1" if (state >> i) & 1 else "0" for i in range(count))


def valve_int(text: str) -> int:
    """Inverse of :func:`valve_string`."""
    return sum(1 << i for i, ch in enumerate(text) if ch == "1")


def leg_shapes(robot: Robot, states: NDArray[np.int64]) -> tuple[Array, Array]:
    """Curvature κ and bending angle φ of each leg, arrays of shape (states, legs).

    κ is the length of the vector sum of the rest shape and the open chambers'
    (κ_c cos φ_c, κ_c sin φ_c); a measured ``table`` entry overrides the sum.
    """
    n = len(states)
    kappa = np.zeros((n, len(robot.legs)))
    phi = np.zeros((n, len(robot.legs)))
    for j, leg in enumerate(robot.legs):
        vx = np.full(n, leg.rest[0] * np.cos(leg.rest[1]))
        vy = np.full(n, leg.rest[0] * np.sin(leg.rest[1]))
        pattern = np.zeros(n, dtype=np.int64)
        for c, chamber in enumerate(leg.chambers):
            bit = (states >> (leg.first_valve + c)) & 1
            vx += bit * chamber.curvature * np.cos(chamber.angle)
            vy += bit * chamber.curvature * np.sin(chamber.angle)
            pattern |= bit << c
        k = np.hypot(vx, vy)
        a = np.where(k > 1e-12, np.arctan2(vy, vx), 0.0)
        for text, tk, tphi in leg.table:
            hit = pattern == valve_int(text)
            k = np.where(hit, tk, k)
            a = np.where(hit, tphi, a)
        kappa[:, j] = k
        phi[:, j] = a + leg.roll
    return kappa, phi


def arc_point(kappa: Array, phi: Array, s: float | Array) -> Array:
    """Point at arc length ``s`` in the leg frame; broadcasts, adds a last axis of size 3."""
    half = kappa * s / 2.0
    sinc_half = np.sinc(half / np.pi)  # sin(h)/h, 1 at h = 0
    lateral = s * np.sin(half) * sinc_half  # (1 - cos κs)/κ
    axial = s * np.sinc(kappa * s / np.pi)  # sin(κs)/κ
    return np.stack([lateral * np.cos(phi), lateral * np.sin(phi), axial], axis=-1)


def arc_rotation(kappa: Array, phi: Array, length: float) -> Array:
    """Rotation of the tip frame relative to the base frame: Rz(φ) Ry(κL) Rz(-φ)."""
    theta = kappa * length
    c, s = np.cos(theta), np.sin(theta)
    cp, sp = np.cos(phi), np.sin(phi)
    out = np.empty((*np.shape(kappa), 3, 3))
    out[..., 0, 0] = cp * cp * c + sp * sp
    out[..., 0, 1] = cp * sp * (c - 1.0)
    out[..., 0, 2] = cp * s
    out[..., 1, 0] = cp * sp * (c - 1.0)
    out[..., 1, 1] = sp * sp * c + cp * cp
    out[..., 1, 2] = sp * s
    out[..., 2, 0] = -cp * s
    out[..., 2, 1] = -sp * s
    out[..., 2, 2] = c
    return out


def leg_basis(leg: Leg) -> Array:
    """Columns x', y', z' of the unbent leg frame in its parent frame."""
    cy, sy = np.cos(leg.yaw), np.sin(leg.yaw)
    cp, sp = np.cos(leg.pitch), np.sin(leg.pitch)
    z = np.array([cp * cy, cp * sy, -sp])
    x = np.array([sp * cy, sp * sy, cp])
    return np.stack([x, np.cross(z, x), z], axis=1)


@dataclass(frozen=True)
class Geometry:
    """Shapes of the robot for a batch of valve states, in the chassis frame."""

    states: NDArray[np.int64]
    kappa: Array  # (n, legs)
    phi: Array  # (n, legs)
    base: Array  # (n, legs, 3) leg base points
    axes: Array  # (n, legs, 3, 3) leg frame axes (columns) in the chassis frame
    tips: Array  # (n, legs, 3)
    cg: Array  # (n, 3)
    contacts: Array  # (n, contact points, 3): chassis contacts, then feet


def forward(robot: Robot, states: NDArray[np.int64] | list[int]) -> Geometry:
    """Steady-state geometry of ``robot`` for each valve state in ``states``."""
    st = np.asarray(states, dtype=np.int64).reshape(-1)
    n = len(st)
    kappa, phi = leg_shapes(robot, st)
    legs = len(robot.legs)
    base = np.zeros((n, legs, 3))
    axes = np.zeros((n, legs, 3, 3))
    tips = np.zeros((n, legs, 3))
    tip_rot: dict[str, tuple[Array, Array]] = {}
    mass_sum = np.zeros((n, 3)) + robot.chassis_mass * np.asarray(robot.chassis_cg)
    total = robot.chassis_mass
    s = (np.arange(_SAMPLES) + 0.5) / _SAMPLES
    for j, leg in enumerate(robot.legs):
        basis = leg_basis(leg)
        if leg.parent is None:
            q = np.broadcast_to(np.eye(3), (n, 3, 3))
            origin = np.broadcast_to(np.asarray(leg.mount), (n, 3))
        else:
            parent_q, parent_tip = tip_rot[leg.parent]
            q = parent_q
            origin = parent_tip + np.einsum("nij,j->ni", parent_q, np.asarray(leg.mount))
        a = np.einsum("nij,jk->nik", q, basis)
        local_tip = arc_point(kappa[:, j], phi[:, j], leg.length)
        tip = origin + np.einsum("nij,nj->ni", a, local_tip)
        rot = arc_rotation(kappa[:, j], phi[:, j], leg.length)
        tip_q = np.einsum("nij,njk,lk->nil", a, rot, basis)
        tip_rot[leg.name] = (tip_q, tip)
        samples = arc_point(kappa[:, j, None], phi[:, j, None], leg.length * s[None, :])
        centroid = origin + np.einsum("nij,nj->ni", a, samples.mean(axis=1))
        mass_sum += leg.mass * centroid + leg.tip_mass * tip
        total += leg.mass + leg.tip_mass
        base[:, j] = origin
        axes[:, j] = a
        tips[:, j] = tip
    cg = mass_sum / max(total, 1e-12)
    fixed = np.asarray([p for _, p in robot.contacts], dtype=float).reshape(-1, 3)
    feet = tips[:, [j for j, leg in enumerate(robot.legs) if leg.foot]]
    contacts = np.concatenate([np.broadcast_to(fixed, (n, len(fixed), 3)), feet], axis=1)
    return Geometry(
        states=st,
        kappa=kappa,
        phi=phi,
        base=base,
        axes=axes,
        tips=tips,
        cg=cg,
        contacts=contacts,
    )


def leg_polyline(
    geometry: Geometry, index: int, leg: int, length: float, points: int = 12
) -> Array:
    """Points along one leg of one state (for drawing), shape (points, 3)."""
    s = np.linspace(0.0, length, points)
    local = arc_point(geometry.kappa[index, leg], geometry.phi[index, leg], s)
    result: Array = geometry.base[index, leg] + local @ geometry.axes[index, leg].T
    return result


def body_length(robot: Robot) -> float:
    """Length along x of the robot with every valve vented (chassis outline and feet)."""
    g = forward(robot, [0])
    xs = [float(x) for x in g.contacts[0, :, 0]] + [p[0] for p in robot.outline]
    xs += [float(x) for x in g.base[0, :, 0]]
    return max(xs) - min(xs)


def shape_keys(robot: Robot, states: NDArray[np.int64]) -> NDArray[np.int64]:
    """An integer per (state, leg) that is equal exactly when the leg shapes are equal."""
    kappa, phi = leg_shapes(robot, states)
    x = np.round(kappa * np.cos(phi) * 1e6).astype(np.int64)
    y = np.round(kappa * np.sin(phi) * 1e6).astype(np.int64)
    out: NDArray[np.int64] = x * 1_000_003 + y
    return out
