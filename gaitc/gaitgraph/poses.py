"""Stable poses (thesis 2.2.1): support planes of each valve state and the CG test.

A pose is a valve state plus the set of contact points lying on a support plane (all
other points above it, the CG above it, tilt limited); it is stable when the CG projects
strictly inside the convex contact polygon.  Fewer than three or collinear contacts are
simply unstable.  Each pose is stored levelled: rotated so its support plane is z = 0.
"""

from __future__ import annotations

from dataclasses import dataclass
from itertools import combinations

import numpy as np
from numpy.typing import NDArray

from gaitc.gaitgraph.kinematics import Array, Geometry
from gaitc.gaitgraph.robot import Robot

_EPS = 1e-9


def bits(mask: int) -> list[int]:
    """Indices of the set bits of ``mask``, ascending."""
    return [i for i in range(mask.bit_length()) if (mask >> i) & 1]


def inside_hull(point: Array, xy: Array, mask: int) -> NDArray[np.bool_]:
    """Whether ``point[m]`` lies strictly inside the convex hull of ``xy[m, bits(mask)]``.

    ``point`` has shape (m, 2) and ``xy`` (m, P, 2).  Uses Carathéodory: a point is inside
    the hull of a planar set exactly when it is inside one of its triangles.  Fewer than
    three points, or collinear points, give False.
    """
    idx = bits(mask)
    result = np.zeros(len(point), dtype=bool)
    for a, b, c in combinations(idx, 3):
        pa, pb, pc = xy[:, a], xy[:, b], xy[:, c]
        d1 = _cross(pb - pa, point - pa)
        d2 = _cross(pc - pb, point - pb)
        d3 = _cross(pa - pc, point - pc)
        pos = (d1 > _EPS) & (d2 > _EPS) & (d3 > _EPS)
        neg = (d1 < -_EPS) & (d2 < -_EPS) & (d3 < -_EPS)
        result |= pos | neg
    return result


def _cross(u: Array, v: Array) -> Array:
    out: Array = u[..., 0] * v[..., 1] - u[..., 1] * v[..., 0]
    return out


def level_rotation(normal: Array) -> Array:
    """Smallest rotations taking unit normals (m, 3) with positive z onto +z (Rodrigues)."""
    v = np.cross(normal, np.array([0.0, 0.0, 1.0]))
    c = normal[:, 2]
    k = np.zeros((len(normal), 3, 3))
    k[:, 0, 1], k[:, 0, 2] = -v[:, 2], v[:, 1]
    k[:, 1, 0], k[:, 1, 2] = v[:, 2], -v[:, 0]
    k[:, 2, 0], k[:, 2, 1] = -v[:, 1], v[:, 0]
    out: Array = np.eye(3) + k + np.einsum("nij,njk->nik", k, k) / (1.0 + c)[:, None, None]
    return out


@dataclass(frozen=True)
class PoseTable:
    """Stable poses of a batch of valve states (structure of arrays, one row per pose)."""

    state: NDArray[np.int64]  # valve state of the pose
    mask: NDArray[np.int64]  # contact set as a bit mask over Robot.contact_names
    xy: Array  # (m, P, 2) levelled positions of every contact point
    z: Array  # (m, P) heights of the contact points above the support plane
    cg: Array  # (m, 2) levelled centre of gravity
    rotation: Array  # (m, 3, 3) levelling rotation (chassis frame -> ground frame)
    height: Array  # (m,) height of the chassis origin above the support plane

    def __len__(self) -> int:
        return len(self.state)

    def take(self, rows: NDArray[np.int64]) -> PoseTable:
        return PoseTable(
            self.state[rows],
            self.mask[rows],
            self.xy[rows],
            self.z[rows],
            self.cg[rows],
            self.rotation[rows],
            self.height[rows],
        )

    @staticmethod
    def concat(tables: list[PoseTable], points: int) -> PoseTable:
        if not tables:
            return PoseTable(
                np.zeros(0, np.int64),
                np.zeros(0, np.int64),
                np.zeros((0, points, 2)),
                np.zeros((0, points)),
                np.zeros((0, 2)),
                np.zeros((0, 3, 3)),
                np.zeros(0),
            )
        return PoseTable(
            np.concatenate([t.state for t in tables]),
            np.concatenate([t.mask for t in tables]),
            np.concatenate([t.xy for t in tables]),
            np.concatenate([t.z for t in tables]),
            np.concatenate([t.cg for t in tables]),
            np.concatenate([t.rotation for t in tables]),
            np.concatenate([t.height for t in tables]),
        )


def support_planes(robot: Robot, geo: Geometry) -> PoseTable:
    """Every (state, contact set) whose support plane is admissible, stable or not."""
    pts, cg = geo.contacts, geo.cg
    _n, count = pts.shape[0], pts.shape[1]
    tol = robot.settings.contact_tolerance
    min_nz = float(np.cos(np.radians(robot.settings.max_tilt)))
    rows: list[NDArray[np.int64]] = []
    masks: list[NDArray[np.int64]] = []
    normals: list[Array] = []
    weights = (1 << np.arange(count)).astype(np.int64)
    for a, b, c in combinations(range(count), 3):
        normal = np.cross(pts[:, b] - pts[:, a], pts[:, c] - pts[:, a])
        length = np.linalg.norm(normal, axis=1)
        ok = length > 1e-6
        normal = normal / np.where(ok, length, 1.0)[:, None]
        side = np.einsum("ni,ni->n", normal, cg - pts[:, a])
        normal = np.where((side < 0)[:, None], -normal, normal)
        ok &= np.abs(side) > 1e-9
        ok &= normal[:, 2] >= min_nz
        d = np.einsum("npi,ni->np", pts - pts[:, a, None], normal)
        ok &= np.all(d >= -tol, axis=1)
        mask = ((d <= tol) * weights).sum(axis=1)
        hit = np.nonzero(ok)[0]
        rows.append(hit)
        masks.append(mask[hit])
        normals.append(normal[hit])
    row = np.concatenate(rows) if rows else np.zeros(0, np.int64)
    mask = np.concatenate(masks) if masks else np.zeros(0, np.int64)
    normal = np.concatenate(normals) if normals else np.zeros((0, 3))
    _, first = np.unique(row * (1 << count) + mask, return_index=True)
    row, mask, normal = row[first], mask[first], normal[first]
    rot = level_rotation(normal)
    lifted = np.einsum("mij,mpj->mpi", rot, pts[row])
    lowest = (
        lifted[np.arange(len(row)), [bits(int(m))[0] for m in mask], 2] if len(row) else np.zeros(0)
    )
    lifted[..., 2] -= lowest[:, None]
    cg_l = np.einsum("mij,mj->mi", rot, cg[row])
    return PoseTable(
        geo.states[row], mask, lifted[..., :2], lifted[..., 2], cg_l[:, :2], rot, -lowest
    )


def stable_poses(robot: Robot, geo: Geometry) -> PoseTable:
    """The stable poses of each valve state in ``geo``, sorted by state then contact mask."""
    table = support_planes(robot, geo)
    keep = np.zeros(len(table), dtype=bool)
    for m in np.unique(table.mask):
        rows = np.nonzero(table.mask == m)[0]
        keep[rows] = inside_hull(table.cg[rows], table.xy[rows], int(m))
    rows = np.nonzero(keep)[0]
    order = np.lexsort((table.mask[rows], table.state[rows]))
    return table.take(rows[order])


def contact_names(robot: Robot, mask: int) -> tuple[str, ...]:
    """The contact points of a mask, in the robot's order."""
    names = robot.contact_names
    return tuple(names[i] for i in bits(mask))
