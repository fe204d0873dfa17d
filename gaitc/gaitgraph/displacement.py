"""Whether a gait graph can move the robot at all: planar potentials of its transitions.

A transition's motion is a planar rigid motion (dx, dy, rotation) in the frame of its source
pose (thesis 2.2.2 for the kinematic graph, 4.2.2 for a model's).  If every pose can be given
one chassis placement in the world such that each transition takes the placement of its
source to the placement of its target, then every cycle of the graph, composed, is the
identity: no gait exists in any direction, and searching for one is wasted time.  The check
builds the placements along a spanning forest (breadth first) and tests every edge against
them, which costs one pass over the edges (milliseconds even for the 7,768 transitions of
the eight-leg radial robot).

The kinematic model of chapter 2 is frictionless: the shared feet of a transition stay put,
so a robot whose feet keep the same places relative to each other whatever the valves do,
or whose contact changes always undo themselves, has such potentials.  That is the reason a
robot that walks by friction (thesis 3.4) has no kinematic gait and needs a chapter 4 model.
"""

from __future__ import annotations

import math
from collections import deque
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components

#: What counts as no motion: mm of translation and degrees of rotation around a cycle.
STILL_MM = 0.05
STILL_DEG = 0.05


@dataclass(frozen=True)
class Stillness:
    """The verdict of :func:`stillness`: ``moving_poses`` are the poses on some cycle that
    moves the chassis (translation above :data:`STILL_MM` or rotation above
    :data:`STILL_DEG`), ``largest`` the largest mismatch found (mm, degrees) and ``edges``
    the transitions that lie on a cycle."""

    moving_poses: frozenset[int]
    largest: tuple[float, float]
    edges: int

    @property
    def moves(self) -> bool:
        """Some cycle of the graph moves the chassis."""
        return bool(self.moving_poses)


def stillness(
    poses: int,
    src: Sequence[int],
    dst: Sequence[int],
    dx: Sequence[float],
    dy: Sequence[float],
    rotation: Sequence[float],
) -> Stillness:
    """Which cycles of the graph move the chassis (``poses`` nodes; edges ``src[i] ->
    dst[i]`` move the chassis by ``dx[i]``, ``dy[i]`` mm and ``rotation[i]`` degrees in the
    source's frame); see the module's docstring.  Only edges inside a strongly connected
    component lie on a cycle, so each component gets its own placements."""
    if not len(src):
        return Stillness(frozenset(), (0.0, 0.0), 0)
    a, b = np.asarray(src, np.int64), np.asarray(dst, np.int64)
    matrix = coo_matrix((np.ones(len(a)), (a, b)), shape=(poses, poses))
    _, component = connected_components(matrix, directed=True, connection="strong")
    inside = [i for i in range(len(a)) if component[a[i]] == component[b[i]] and a[i] != b[i]]
    out: list[list[int]] = [[] for _ in range(poses)]
    back: list[list[int]] = [[] for _ in range(poses)]
    for i in inside:
        out[src[i]].append(i)
        back[dst[i]].append(i)
    placed: list[tuple[float, float, float] | None] = [None] * poses
    for root in range(poses):
        if placed[root] is not None:
            continue
        placed[root] = (0.0, 0.0, 0.0)
        queue = deque([root])
        while queue:
            node = queue.popleft()
            x, y, heading = placed[node]  # type: ignore[misc]
            for i in out[node]:
                if placed[dst[i]] is None:
                    placed[dst[i]] = _after(x, y, heading, dx[i], dy[i], rotation[i])
                    queue.append(dst[i])
            for i in back[node]:
                if placed[src[i]] is None:
                    placed[src[i]] = _before(x, y, heading, dx[i], dy[i], rotation[i])
                    queue.append(src[i])
    worst_mm = worst_deg = 0.0
    moving: set[int] = set()
    for i in inside:
        xa, ya, ha = placed[src[i]]  # type: ignore[misc]
        xb, yb, hb = placed[dst[i]]  # type: ignore[misc]
        x, y, heading = _after(xa, ya, ha, dx[i], dy[i], rotation[i])
        mm = math.hypot(x - xb, y - yb)
        deg = abs((heading - hb + 180.0) % 360.0 - 180.0)
        worst_mm, worst_deg = max(worst_mm, mm), max(worst_deg, deg)
        if mm > STILL_MM or deg > STILL_DEG:
            moving.add(int(component[src[i]]))
    poses_moving = frozenset(p for p in range(poses) if int(component[p]) in moving)
    return Stillness(poses_moving, (worst_mm, worst_deg), len(inside))


def _after(x: float, y: float, heading: float, dx: float, dy: float,
           rotation: float) -> tuple[float, float, float]:
    rad = math.radians(heading)
    c, s = math.cos(rad), math.sin(rad)
    return x + c * dx - s * dy, y + s * dx + c * dy, heading + rotation


def _before(x: float, y: float, heading: float, dx: float, dy: float,
            rotation: float) -> tuple[float, float, float]:
    """The placement whose motion (dx, dy, rotation) ends at (x, y, heading)."""
    start = heading - rotation
    rad = math.radians(start)
    c, s = math.cos(rad), math.sin(rad)
    return x - (c * dx - s * dy), y - (s * dx + c * dy), start
