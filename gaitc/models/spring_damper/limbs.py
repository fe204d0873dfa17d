"""The limb maps of thesis section 4.1.1 as arrays over all limbs: f_e, f_m, K_q, frames.

Each chain is planar, in the vertical plane of its limb frame (x outward from the mount,
z up): the tangent starts ``pitch`` below x and turns down by κ per unit length in each
segment (constant curvature), so f_e is a sum of circular arcs.  f_m takes the chord
midpoints of the segments, weighted by length.  Limbs with fewer segments are padded with
zero-length segments, so every map is one vectorised expression.
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from gaitc.models.motion import ValveState
from gaitc.models.spring_damper.description import SpringDamperRobot

Array = NDArray[np.float64]


@dataclass(frozen=True)
class LimbArrays:
    """Everything the integrator needs about the limbs, padded to S segments each."""

    names: tuple[str, ...]
    length: Array  # (n, S) m
    rest: Array  # (n, S) vented curvature, 1/m
    full: Array  # (n, S) pressurised curvature, 1/m
    real: NDArray[np.bool_]  # (n, S) the segment exists
    frequency: Array  # (n, S) ω_n, rad/s
    damping_ratio: Array  # (n, S)
    valve: NDArray[np.int64]  # (n, S) index into the valve state (-1 for padding)
    pitch: Array  # (n,)
    yaw: Array  # (n,)
    offset: Array  # (n, 3) limb origins in the chassis frame
    damping: Array  # (n,) b, N·s/m
    table: Array  # (n, 2^S, 3, 3) stiffness per steady-state pattern, limb frame
    bits: Array  # (2^S, S) the patterns
    inertia: float  # yaw moment of inertia at the vented steady state, kg·m²
    max_length: float

    @classmethod
    def of(cls, robot: SpringDamperRobot) -> LimbArrays:
        limbs = robot.limbs
        n, s = len(limbs), max([len(limb.segments) for limb in limbs] + [1])
        shape = (n, s)
        length, rest, full = np.zeros(shape), np.zeros(shape), np.ones(shape)
        real = np.zeros(shape, dtype=bool)
        freq, zeta = np.ones(shape), np.ones(shape)
        valve = -np.ones(shape, dtype=np.int64)
        bits = np.array(list(itertools.product((0.0, 1.0), repeat=s)))
        table = np.zeros((n, len(bits), 3, 3))
        for i, limb in enumerate(limbs):
            for j, seg in enumerate(limb.segments):
                length[i, j], rest[i, j], full[i, j] = seg.length, seg.rest_curvature, seg.curvature
                real[i, j] = True
                freq[i, j], zeta[i, j] = limb.dynamics.frequency, limb.dynamics.damping_ratio
                valve[i, j] = limb.valves[j]
            matrices = dict(limb.stiffness)
            for p, pattern in enumerate(bits):
                own = pattern[: len(limb.segments)]
                if pattern[len(limb.segments) :].any():
                    continue  # a padding segment is never active: weight zero
                key = "" if "" in matrices else "".join("1" if b else "0" for b in own)
                table[i, p] = np.array(matrices[key])
        arrays = cls(
            names=tuple(limb.name for limb in limbs),
            length=length,
            rest=rest,
            full=full,
            real=real,
            frequency=freq,
            damping_ratio=zeta,
            valve=valve,
            pitch=np.array([limb.pitch for limb in limbs]),
            yaw=np.array([limb.yaw for limb in limbs]),
            offset=np.array([limb.position for limb in limbs]).reshape(n, 3),
            damping=np.array([limb.damping for limb in limbs]),
            table=table,
            bits=bits,
            inertia=0.0,
            max_length=float(length.sum(axis=1).max(initial=0.0)) or 1.0,
        )
        masses = np.array([limb.mass for limb in limbs])
        centres = arrays.to_world(arrays.centre_of_mass(rest), np.zeros(3), 0.0)
        radius2 = float(np.max(np.sum(arrays.offset[:, :2] ** 2, axis=1), initial=0.0))
        inertia = (
            float(masses @ np.sum(centres[:, :2] ** 2, axis=1)) + 0.5 * robot.chassis_mass * radius2
        )
        object.__setattr__(arrays, "inertia", max(inertia, 1e-9))
        return arrays

    def targets(self, valves: ValveState) -> Array:
        """The steady-state curvature of every segment under ``valves``, (n, S)."""
        state = np.array([bool(v) for v in valves] + [False])
        on = state[self.valve] & self.real
        out: Array = np.where(on, self.full, self.rest)
        return out

    def fraction(self, kappa: Array) -> Array:
        """Each segment's curvature from vented (0) to pressurised (1), clipped; (..., n, S)."""
        f = np.minimum(np.maximum((kappa - self.rest) / (self.full - self.rest), 0.0), 1.0)
        out: Array = np.where(self.real, f, 0.0)
        return out

    def activation(self, fraction: Array) -> Array:
        """How far each limb is from vented to pressurised, averaged over its segments."""
        out: Array = fraction.sum(axis=-1) / np.maximum(self.real.sum(axis=1), 1)
        return out

    def chain(self, kappa: Array) -> tuple[Array, Array]:
        """f_e: the unloaded end effectors' x and z in their limb frames, (..., n) each."""
        turn = kappa * self.length
        half = 0.5 * turn
        middle = -self.pitch[:, None] - np.cumsum(turn, axis=-1) + half
        chord = self.length * np.sinc(half / np.pi)
        x: Array = (chord * np.cos(middle)).sum(axis=-1)
        z: Array = (chord * np.sin(middle)).sum(axis=-1)
        return x, z

    def centre_of_mass(self, kappa: Array) -> Array:
        """f_m: the limb centre of mass in its limb frame, (n, 3) (chord midpoints)."""
        turn = kappa * self.length
        half = 0.5 * turn
        middle = -self.pitch[:, None] - np.cumsum(turn, axis=-1) + half
        chord = self.length * np.sinc(half / np.pi)
        dx, dz = chord * np.cos(middle), chord * np.sin(middle)
        ox = np.cumsum(dx, axis=1) - 0.5 * dx
        oz = np.cumsum(dz, axis=1) - 0.5 * dz
        total = np.maximum(self.length.sum(axis=1), 1e-12)
        return np.stack(
            [
                (ox * self.length).sum(axis=1) / total,
                np.zeros(len(dx)),
                (oz * self.length).sum(axis=1) / total,
            ],
            axis=1,
        )

    def stiffness_local(self, fraction: Array) -> Array:
        """K_q in the limb frames, multilinear between the steady states (section 4.2.1).

        ``fraction`` is (..., n, S); the result (..., n, 9) holds each matrix row by row."""
        f = fraction[..., None, :]
        weights = np.prod(np.where(self.bits > 0, f, 1.0 - f), axis=-1)
        out: Array = np.einsum(
            "...np,npk->...nk", weights, self.table.reshape(len(self.names), -1, 9)
        )
        return out

    def to_world(self, local: Array, position: Array, theta: float) -> Array:
        """Limb-frame points (n, 3) in the world frame, chassis at ``position``, yaw ``theta``."""
        c, s = np.cos(theta), np.sin(theta)
        o = self.offset
        phi = theta + self.yaw
        cp, sp = np.cos(phi), np.sin(phi)
        out = np.empty((len(o), 3))
        out[:, 0] = position[0] + c * o[:, 0] - s * o[:, 1] + cp * local[:, 0] - sp * local[:, 1]
        out[:, 1] = position[1] + s * o[:, 0] + c * o[:, 1] + sp * local[:, 0] + cp * local[:, 1]
        out[:, 2] = position[2] + o[:, 2] + local[:, 2]
        return out
