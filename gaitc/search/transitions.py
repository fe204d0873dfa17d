"""The transitions the searches propagate: the gait graph's predicted motions, per pose.

A :class:`TransitionModel` holds every gait-graph edge (thesis 2.2.2) as arrays grouped by
source pose (compressed rows), with motions that the online loop may overwrite with what the
robot really did (thesis 5.2.2) or remove when the robot did not make the transition.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from gaitc.gaitgraph.displacement import Stillness, stillness
from gaitc.gaitgraph.graph import GaitGraph
from gaitc.gaitgraph.kinematics import valve_string

Floats = NDArray[np.float64]
Ints = NDArray[np.int64]


@dataclass(frozen=True)
class Step:
    """One transition's motion in the frame of its source pose (mm, mm, degrees)."""

    dx: float
    dy: float
    rotation: float


def compose(x: float, y: float, heading: float, step: Step) -> tuple[float, float, float]:
    """The chassis pose (x, y, heading in degrees) after ``step`` from (x, y, heading)."""
    rad = math.radians(heading)
    c, s = math.cos(rad), math.sin(rad)
    return x + c * step.dx - s * step.dy, y + s * step.dx + c * step.dy, heading + step.rotation


class TransitionModel:
    """Edges of a gait graph (or hand-made ones) with mutable predicted motions.

    ``src``, ``dst`` are pose numbers; ``dx``, ``dy`` mm and ``rot`` degrees in the source
    pose's frame; ``slip`` mm.  Rows of one source pose are contiguous: ``rows(p)``.
    """

    def __init__(
        self,
        poses: int,
        src: Ints,
        dst: Ints,
        dx: Floats,
        dy: Floats,
        rot: Floats,
        slip: Floats,
        *, labels: list[str] | None = None,
    ) -> None:
        order = np.lexsort((dst, src))
        self.poses = poses
        self.src = np.asarray(src, np.int64)[order]
        self.dst = np.asarray(dst, np.int64)[order]
        self.dx = np.asarray(dx, np.float64)[order].copy()
        self.dy = np.asarray(dy, np.float64)[order].copy()
        self.rot = np.asarray(rot, np.float64)[order].copy()
        self.slip = np.asarray(slip, np.float64)[order].copy()
        self.alive = np.ones(len(self.src), dtype=bool)
        self._mirror()
        self.original = np.asarray(order, np.int64)  # row in the source arrays
        self.offsets = np.searchsorted(self.src, np.arange(poses + 1)).astype(np.int64)
        self.labels = labels or [f"p{i}" for i in range(poses)]
        self.groups: tuple[int, ...] = ()  # chambers per leg, to print valve states by leg

    def __len__(self) -> int:
        return len(self.src)

    def _mirror(self) -> None:
        """Plain lists of the arrays, for the per-edge loops of small poses."""
        self.dx_list: list[float] = self.dx.tolist()
        self.dy_list: list[float] = self.dy.tolist()
        self.rot_list: list[float] = self.rot.tolist()
        self.dst_list: list[int] = self.dst.tolist()
        self.alive_list: list[bool] = self.alive.tolist()

    @staticmethod
    def from_graph(graph: GaitGraph) -> TransitionModel:
        e = graph.edges
        count = graph.robot.valve_count
        labels = [valve_string(int(s), count) for s in graph.poses.state]
        model = TransitionModel(

            poses=len(graph),
            src=e.src,
            dst=e.dst,
            dx=e.dx,
            dy=e.dy,
            rot=np.degrees(e.rot),
            slip=e.slip,
            labels=labels,
        )
        model.groups = tuple(len(leg.chambers) for leg in graph.robot.legs)
        return model

    def stillness(self) -> Stillness:
        """Which cycles of the live transitions move the chassis
        (:mod:`gaitc.gaitgraph.displacement`)."""
        live = self.alive
        return stillness(self.poses, self.src[live].tolist(), self.dst[live].tolist(),
                         self.dx[live].tolist(), self.dy[live].tolist(),
                         self.rot[live].tolist())

    def copy(self) -> TransitionModel:
        """An independent copy (the walker keeps the original predictions)."""
        out = TransitionModel(

            poses=self.poses,
            src=self.src,
            dst=self.dst,
            dx=self.dx,
            dy=self.dy,
            rot=self.rot,
            slip=self.slip,
            labels=list(self.labels),
        )
        out.alive = self.alive.copy()
        out.alive_list = self.alive.tolist()
        out.groups = self.groups
        return out

    def rows(self, pose: int) -> range:
        return range(int(self.offsets[pose]), int(self.offsets[pose + 1]))

    def step(self, edge: int) -> Step:
        return Step(float(self.dx[edge]), float(self.dy[edge]), float(self.rot[edge]))

    def find(self, src: int, dst: int) -> int | None:
        """The row of the edge ``src`` → ``dst``, if any."""
        lo, hi = int(self.offsets[src]), int(self.offsets[src + 1])
        k = lo + int(np.searchsorted(self.dst[lo:hi], dst))
        return k if k < hi and int(self.dst[k]) == dst else None

    def set_motion(self, edge: int, step: Step) -> None:
        self.dx[edge], self.dy[edge], self.rot[edge] = step.dx, step.dy, step.rotation
        self.dx_list[edge], self.dy_list[edge], self.rot_list[edge] = (
            float(self.dx[edge]),
            float(self.dy[edge]),
            float(self.rot[edge]),
        )

    def remove(self, edge: int) -> None:
        self.alive[edge] = False
        self.alive_list[edge] = False

    def largest_step(self) -> tuple[float, float]:
        """The longest translation (mm) and largest |rotation| (deg) of any live edge."""
        if not self.alive.any():
            return 0.0, 0.0
        a = self.alive
        return float(np.hypot(self.dx[a], self.dy[a]).max()), float(np.abs(self.rot[a]).max())

    def hops_to(self, target: int) -> Ints:
        """Fewest live transitions from every pose to ``target`` (-1 when it cannot be
        reached); breadth-first by levels over the edge arrays."""
        hops = np.full(self.poses, -1, dtype=np.int64)
        hops[target] = 0
        frontier = np.zeros(self.poses, dtype=bool)
        frontier[target] = True
        level = 0
        while frontier.any():
            level += 1
            into = self.alive & frontier[self.dst]
            fresh = np.zeros(self.poses, dtype=bool)
            fresh[self.src[into]] = True
            fresh &= hops < 0
            hops[fresh] = level
            frontier = fresh
        return hops
