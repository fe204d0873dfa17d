"""Transitions between stable poses (thesis 2.2.2): Kabsch fit, conditions 1 and 2, slip.

The feet shared by two poses stay put on the ground, so the chassis moves by the planar
rigid motion that best maps the shared feet of the post-transition pose (levelled) onto
those of the pre-transition pose: rotation from the 2-D Kabsch algorithm (closed form,
never a reflection), translation from the centroid displacement.  Slip is the largest
distance a shared foot is left from its old place.  Pairs are matched in blocks of equal
contact sets, pruned by the pairwise distances of the shared feet (a rigid motion keeps
them, so slip ≤ ε needs every distance to agree within 2ε).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from gaitc.gaitgraph.kinematics import Array
from gaitc.gaitgraph.poses import PoseTable, bits, inside_hull
from gaitc.gaitgraph.robot import Robot

Ints = NDArray[np.int64]


def kabsch_2d(source: Array, target: Array) -> tuple[Array, Array, Array]:
    """Best proper rotation θ and translation t with ``R(θ) source + t ≈ target``.

    ``source`` and ``target`` have shape (m, q, 2); returns θ (m,), t (m, 2) and the
    residual distance of every point (m, q).  A single point gives θ = 0.
    """
    cs, ct = source.mean(axis=1), target.mean(axis=1)
    s, t = source - cs[:, None], target - ct[:, None]
    num = (s[..., 0] * t[..., 1] - s[..., 1] * t[..., 0]).sum(axis=1)
    den = (s[..., 0] * t[..., 0] + s[..., 1] * t[..., 1]).sum(axis=1)
    theta = np.arctan2(num, den)
    c, sn = np.cos(theta), np.sin(theta)
    rot_cs = np.stack([c * cs[:, 0] - sn * cs[:, 1], sn * cs[:, 0] + c * cs[:, 1]], axis=1)
    trans = ct - rot_cs
    moved = rotate(source, theta) + trans[:, None]
    return theta, trans, np.linalg.norm(moved - target, axis=-1)


def rotate(points: Array, theta: Array) -> Array:
    """Rotate (m, q, 2) or (m, 2) points by per-row angles θ (m,)."""
    c, s = np.cos(theta), np.sin(theta)
    if points.ndim == 3:
        c, s = c[:, None], s[:, None]
    return np.stack(
        [c * points[..., 0] - s * points[..., 1], s * points[..., 0] + c * points[..., 1]], axis=-1
    )


@dataclass(frozen=True)
class Edges:
    """Transitions as arrays: chassis motion (dx, dy, rotation) in the source pose's frame."""

    src: Ints
    dst: Ints
    dx: Array
    dy: Array
    rot: Array  # radians, counter-clockwise
    slip: Array  # mm
    condition: Ints  # 1 or 2 (the first that holds)
    shared: Ints  # mask of the shared contact points

    def __len__(self) -> int:
        return len(self.src)

    @staticmethod
    def concat(parts: list[Edges]) -> Edges:
        if not parts:
            z, f = np.zeros(0, np.int64), np.zeros(0)
            return Edges(
                src=z,
                dst=z,
                dx=f,
                dy=f,
                rot=f,
                slip=f,
                condition=z,
                shared=z,
            )
        return Edges(*(np.concatenate([getattr(p, k) for p in parts]) for k in _FIELDS))

    def take(self, rows: Ints) -> Edges:
        return Edges(*(getattr(self, k)[rows] for k in _FIELDS))


_FIELDS = ("src", "dst", "dx", "dy", "rot", "slip", "condition", "shared")


def _distances(xy: Array) -> Array:
    q = xy.shape[1]
    iu, ju = np.triu_indices(q, 1)
    out: Array = np.linalg.norm(xy[:, iu] - xy[:, ju], axis=-1)
    return out


def _window_pairs(key_a: Array, key_b: Array, width: float) -> tuple[Ints, Ints]:
    """All (i, j) with |key_a[i] - key_b[j]| <= width, by sorting ``key_b``."""
    order = np.argsort(key_b, kind="stable")
    keys = key_b[order]
    lo = np.searchsorted(keys, key_a - width, "left")
    hi = np.searchsorted(keys, key_a + width, "right")
    counts = hi - lo
    ia = np.repeat(np.arange(len(key_a)), counts)
    starts = np.repeat(np.cumsum(counts) - counts, counts)
    ib = order[lo[ia] + np.arange(len(ia)) - starts]
    return ia.astype(np.int64), ib.astype(np.int64)


def transitions(robot: Robot, poses: PoseTable, start: int, zero_only: bool = False) -> Edges:
    """Edges between each pose ``i >= start`` and each pose ``j < i``, both directions.

    Conditions (thesis 2.2.2): 1. the shared contacts alone hold the CG in both poses;
    2. the post-transition CG, carried into the pre-transition frame by the fitted motion,
    leaves the pre-transition contact polygon (the robot falls into the new, stable pose).
    At least two shared contacts are needed to fix the motion.  ``zero_only`` keeps only
    reset edges (motion below ``settings.zero_motion``), as in thesis 2.5.2.
    """
    eps = robot.settings.max_slip
    parts: list[Edges] = []
    by_mask = {int(m): np.nonzero(poses.mask == m)[0] for m in np.unique(poses.mask)}
    new_masks = sorted({int(m) for m in poses.mask[start:]})
    for m1 in new_masks:
        rows_a = by_mask[m1][by_mask[m1] >= start]
        for m2, rows_b in by_mask.items():
            shared = m1 & m2
            if shared.bit_count() < 2 or int(rows_b[0]) >= int(rows_a[-1]):
                continue
            parts.extend(_block(robot, poses, rows_a, rows_b, shared, eps, zero_only))
    edges = Edges.concat(parts)
    order = np.lexsort((edges.dst, edges.src))
    return edges.take(order)


def _block(
    robot: Robot,
    poses: PoseTable,
    rows_a: Ints,
    rows_b: Ints,
    shared: int,
    eps: float,
    zero_only: bool,
) -> list[Edges]:
    idx = bits(shared)
    xa, xb = poses.xy[rows_a][:, idx], poses.xy[rows_b][:, idx]
    da, db = _distances(xa), _distances(xb)
    ia, ib = _window_pairs(da[:, 0], db[:, 0], 2 * eps)
    keep = (rows_b[ib] < rows_a[ia]) & (poses.state[rows_b[ib]] != poses.state[rows_a[ia]])
    if da.shape[1] > 1:
        keep &= np.all(np.abs(da[ia] - db[ib]) <= 2 * eps, axis=1)
    ia, ib = ia[keep], ib[keep]
    if len(ia) == 0:
        return []
    return _evaluate(robot, poses, rows_a[ia], rows_b[ib], shared, zero_only)


def pair_edges(robot: Robot, poses: PoseTable, p: Ints, q: Ints, zero_only: bool = False) -> Edges:
    """Edges, in both directions, for explicitly given pose pairs ``(p[i], q[i])``."""
    shared = poses.mask[p] & poses.mask[q]
    parts: list[Edges] = []
    for m in np.unique(shared):
        if int(m).bit_count() < 2:
            continue
        sel = np.nonzero((shared == m) & (poses.state[p] != poses.state[q]))[0]
        parts.extend(_evaluate(robot, poses, p[sel], q[sel], int(m), zero_only))
    return Edges.concat(parts)


def _evaluate(
    robot: Robot, poses: PoseTable, p: Ints, q: Ints, shared: int, zero_only: bool
) -> list[Edges]:
    eps = robot.settings.max_slip
    idx = bits(shared)
    xa, xb = poses.xy[p][:, idx], poses.xy[q][:, idx]
    rows = np.unique(np.concatenate([p, q]))
    holds = np.zeros(len(poses), dtype=bool)  # the shared contacts alone hold the CG
    holds[rows] = inside_hull(poses.cg[rows], poses.xy[rows], shared)
    out = []
    for src, dst, xs, xt in ((p, q, xa, xb), (q, p, xb, xa)):
        # chassis motion src -> dst: the map taking dst's shared feet onto src's
        theta, trans, resid = kabsch_2d(xt, xs)
        slip = resid.max(axis=1)
        ok = slip <= eps
        if zero_only:
            limit = robot.settings.zero_motion
            ok &= (np.hypot(trans[:, 0], trans[:, 1]) <= limit) & (
                np.degrees(np.abs(theta)) <= limit
            )
        keep = np.nonzero(ok)[0]
        src, dst, theta, trans, slip = src[keep], dst[keep], theta[keep], trans[keep], slip[keep]
        cond1 = holds[src] & holds[dst]
        cond2 = np.zeros(len(src), dtype=bool)
        falls = np.nonzero(~cond1)[0]
        carried = rotate(poses.cg[dst[falls]], theta[falls]) + trans[falls]
        for m in np.unique(poses.mask[src[falls]]):
            sel = poses.mask[src[falls]] == m
            cond2[falls[sel]] = ~inside_hull(carried[sel], poses.xy[src[falls[sel]]], int(m))
        ok = cond1 | cond2
        cond = np.where(cond1, 1, 2).astype(np.int64)
        sel = np.nonzero(ok)[0]
        out.append(
            Edges(

                src=src[sel],
                dst=dst[sel],
                dx=trans[sel, 0],
                dy=trans[sel, 1],
                rot=theta[sel],
                slip=slip[sel],
                condition=cond[sel],
                shared=np.full(len(sel), shared, dtype=np.int64),
            )
        )
    return out
