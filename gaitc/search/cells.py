"""The configuration-space lattice of hybrid graph search (thesis 5.2.2).

Planar chassis displacement (dx, dy, dθ) is cut into cells of ``size`` mm and ``angle``
degrees; a search node is a pose of the gait graph in a cell, packed in one integer.  Cell
adjacency comes from propagating the gait graph's transitions from the cell's centre, so the
graph is the same whichever path reaches a node (which LPA* needs; the thesis and Dolgov et
al.'s hybrid A* propagate from the path's own continuous state).  The heuristic is the
larger of two lower bounds on the transitions still needed: hops back to the start pose, and
distance to the goal over the longest step (both consistent).
"""

from __future__ import annotations

import bisect
import math

import numpy as np

from gaitc.diagnostics import UsageError
from gaitc.search.goals import Goal, angle_difference
from gaitc.search.transitions import Floats, Ints, TransitionModel

_OFF = 1 << 15
WALK_STEPS = 24  # longest walk the walk table covers
WALK_EDGES = 20_000  # larger graphs go without it (rebuilding it would cost more than it saves)
_MASK = (1 << 16) - 1


class Lattice:
    """Cells of ``size`` mm × ``size`` mm × ``angle`` degrees around a start pose."""

    def __init__(
        self,
        model: TransitionModel,
        start: int,
        goal: Goal,
        size: float = 2.0,
        angle: float = 2.0,
        slip_cost: float = 0.05,
        radius: float | None = None,
    ) -> None:
        if size <= 0 or angle <= 0:
            raise UsageError("the cell size and angle must be positive")
        turns = 360.0 / angle
        if abs(turns - round(turns)) > 1e-9:
            raise UsageError(f"the cell angle must divide 360 degrees, not {angle:g}")
        if not 0 <= start < model.poses:
            raise UsageError(f"start pose {start} is not a pose of the gait graph")
        self.model, self.start, self.goal = model, start, goal
        self.size, self.angle, self.turns = size, angle, round(turns)
        self.slip_cost = slip_cost
        self.costs = 1.0 + slip_cost * model.slip
        self.cost_list: list[float] = self.costs.tolist()
        if model.poses >= 1 << 15:
            raise UsageError(f"the lattice packs poses in 15 bits: {model.poses} are too many")
        self._heading = [angle_difference(it * angle, 0.0) for it in range(self.turns)]
        self._cos = [math.cos(math.radians(h)) for h in self._heading]
        self._sin = [math.sin(math.radians(h)) for h in self._heading]
        self.hops = model.hops_to(start).astype(np.float64)
        self.hops[self.hops < 0] = math.inf
        self.reach = 0.0
        self.turn = 0.0
        self._slack = size * math.sqrt(2) / 2
        # step lengths (plus the snapping slack) the walk table was built with, per edge
        self._walk_len: Floats = np.hypot(model.dx, model.dy) + self._slack
        self._walks: Floats | None = None
        self._walk_cols: list[list[float]] = []
        # the poses whose heuristic the last growth changed (None: every pose)
        self.rekey_poses: frozenset[int] | None = None
        self.refresh_bounds()
        self._build_walks()
        span = math.hypot(goal.dx, goal.dy)
        if radius is None:  # room for a cycle to swing out and come back
            radius = max(3.0 * span, span + 2.0 * self.reach)
        self.radius = radius
        if radius / size >= _OFF - 1:
            raise UsageError(
                f"the lattice would reach {radius:g} mm, too far for {size:g} mm cells",
                None,
                "use a coarser --cell or a nearer --goal",
            )
        self._cells = (radius / size) ** 2  # squared radius in cells

    def _build_walks(self) -> None:
        """The walk table: ``W[k, p]``, the longest translation (summed step lengths plus
        slack) of any walk of at most k transitions from pose p to the start pose.  The
        fewest transitions left from a node is at least the smallest k whose W reaches
        the node's distance to the goal disc (which also bounds the hops home).  Skipped
        for graphs of more than WALK_EDGES transitions (the distance bound is used)."""
        m = self.model
        if len(m) > WALK_EDGES:
            self._walks, self._walk_cols = None, []
            return
        table = self.walks_with(self.start, home=True)
        if self._walks is not None:
            moved = (self._walks != table).any(axis=0)
            self.rekey_poses = frozenset(np.nonzero(moved)[0].tolist())
        self._walks = table
        self._walk_cols = table.T.tolist()

    def walks_with(self, anchor: int, home: bool) -> Floats:
        """``W[k, p]``: the longest translation (summed step lengths plus the snapping slack,
        as the edges' bounds have them) of any walk of at most k <= WALK_STEPS live
        transitions from pose p to pose ``anchor`` (``home``), or from ``anchor`` to p."""
        m = self.model
        live = m.alive
        src, dst, length = m.src[live], m.dst[live], self._walk_len[live]
        if not home:  # walks from the anchor: the same recursion over reversed edges
            order = np.argsort(dst, kind="stable")
            src, dst, length = dst[order], src[order], length[order]
        table = np.full((WALK_STEPS + 1, m.poses), -np.inf)
        table[0, anchor] = 0.0
        exact = table[0].copy()
        # rows are sorted by (their) source pose: one maximum per pose with a live edge
        starts = np.searchsorted(src, np.arange(m.poses))
        has = starts < np.searchsorted(src, np.arange(m.poses), side="right")
        first = starts[has]
        for k in range(1, WALK_STEPS + 1):
            longer = np.full(m.poses, -np.inf)
            if len(src):
                longer[has] = np.maximum.reduceat(length + exact[dst], first)
            exact = longer
            table[k] = np.maximum(table[k - 1], exact)
        return table

    def walk_bound(self, edge: int) -> float:
        """The length (plus the snapping slack) the walk tables assume for ``edge``."""
        return float(self._walk_len[edge])

    @property
    def walking(self) -> bool:
        """Whether the graph is small enough for walk tables (:data:`WALK_EDGES`)."""
        return self._walks is not None

    def _walk_steps(self, pose: int, distance: float) -> int:
        column = self._walk_cols[pose]
        return bisect.bisect_left(column, distance)  # WALK_STEPS + 1 when none reaches

    def cover(self, edge: int) -> bool:
        """Make the step bounds cover one (changed) edge; True when they had to grow (by a
        quarter more than needed, so that a run of growing edges re-keys seldom)."""
        m = self.model
        length = math.hypot(m.dx_list[edge], m.dy_list[edge])
        reach = length + self._slack
        turn = abs(m.rot_list[edge]) + self.angle / 2
        grew = False
        self.rekey_poses = frozenset()
        if reach > self._walk_len[edge]:
            self._walk_len[edge] = 1.25 * length + self._slack
            if self._walks is not None:
                self._build_walks()
                grew = bool(self.rekey_poses)
        if reach > self.reach:
            self.reach, grew = 1.25 * reach, True
            self.rekey_poses = None
        if turn > self.turn:
            self.turn, grew = 1.25 * turn, True
            self.rekey_poses = None
        return grew

    def refresh_bounds(self) -> bool:
        """Recompute the step bounds of the heuristic; True when they grew."""
        m = self.model
        if hasattr(self, "_walks"):
            now = np.hypot(m.dx, m.dy) + self._slack
            if (now > self._walk_len).any():
                self._walk_len = np.maximum(now, self._walk_len)
                self._build_walks()
        longest, turn = self.model.largest_step()
        reach = longest + self.size * math.sqrt(2) / 2 + 1e-9
        turn = turn + self.angle / 2 + 1e-9
        grew = reach > self.reach or turn > self.turn
        self.reach, self.turn = max(reach, self.reach), max(turn, self.turn)
        return grew

    def pack(self, pose: int, ix: int, iy: int, it: int) -> int:
        return (pose << 48) | ((ix + _OFF) << 32) | ((iy + _OFF) << 16) | (it % self.turns)

    def unpack(self, node: int) -> tuple[int, int, int, int]:
        return (
            node >> 48,
            ((node >> 32) & _MASK) - _OFF,
            ((node >> 16) & _MASK) - _OFF,
            node & _MASK,
        )

    def centre(self, node: int) -> tuple[int, float, float, float]:
        """Pose, x, y (mm) and heading (degrees) of a node's cell centre."""
        pose, ix, iy, it = self.unpack(node)
        heading = angle_difference(it * self.angle, 0.0)
        return pose, ix * self.size, iy * self.size, heading

    @property
    def root(self) -> int:
        return self.pack(self.start, 0, 0, 0)

    def cost(self, edge: int) -> float:
        """One valve step plus a penalty for the slip the transition needs."""
        return self.cost_list[edge]

    def successors(self, node: int) -> tuple[list[int], list[int]]:
        """The live out-edges of ``node`` and their target nodes; edges leaving the lattice's
        disc of ``radius`` mm, and self-transitions, are dropped.  Small poses are done in plain
        Python, large ones with numpy; both give the same bits (same operations, and the
        cosines come from one table)."""
        pose, ix, iy, it = self.unpack(node)
        m = self.model
        lo, hi = int(m.offsets[pose]), int(m.offsets[pose + 1])
        if hi - lo <= 48:
            edges: list[int] = []
            targets: list[int] = []
            size, cells, turns, angle = self.size, self._cells, self.turns, self.angle
            x, y = ix * size, iy * size
            c, s, heading = self._cos[it], self._sin[it], self._heading[it]
            alive, dxs, dys, rots = m.alive_list, m.dx_list, m.dy_list, m.rot_list
            dsts = m.dst_list
            for e in range(lo, hi):
                if not alive[e]:
                    continue
                dx, dy = dxs[e], dys[e]
                tx = round((x + c * dx - s * dy) / size)
                ty = round((y + s * dx + c * dy) / size)
                if tx * tx + ty * ty > cells:
                    continue
                tt = round((heading + rots[e]) / angle) % turns
                key = (dsts[e] << 48) | ((tx + _OFF) << 32) | ((ty + _OFF) << 16) | tt
                if key != node:
                    edges.append(e)
                    targets.append(key)
            return edges, targets
        edge_array, target_array = self._successor_arrays(node)
        return edge_array.tolist(), target_array.tolist()

    def successor_arrays(self, node: int) -> tuple[Ints, Ints]:
        """:meth:`successors` as numpy arrays (the same edges and targets)."""
        pose = node >> 48
        m = self.model
        if int(m.offsets[pose + 1]) - int(m.offsets[pose]) <= 48:
            edges, targets = self.successors(node)
            return np.array(edges, dtype=np.int64), np.array(targets, dtype=np.int64)
        return self._successor_arrays(node)

    def _successor_arrays(self, node: int) -> tuple[Ints, Ints]:
        pose, ix, iy, it = self.unpack(node)
        m = self.model
        lo, hi = int(m.offsets[pose]), int(m.offsets[pose + 1])
        x, y = ix * self.size, iy * self.size
        c, s, heading = self._cos[it], self._sin[it], self._heading[it]
        sel = np.arange(lo, hi)
        sel = sel[m.alive[sel]]
        nx = np.rint((x + c * m.dx[sel] - s * m.dy[sel]) / self.size).astype(np.int64)
        ny = np.rint((y + s * m.dx[sel] + c * m.dy[sel]) / self.size).astype(np.int64)
        nt = np.rint((heading + m.rot[sel]) / self.angle).astype(np.int64) % self.turns
        ok = nx * nx + ny * ny <= self._cells
        sel, nx, ny, nt = sel[ok], nx[ok], ny[ok], nt[ok]
        packed: Ints = (m.dst[sel] << 48) | ((nx + _OFF) << 32) | ((ny + _OFF) << 16) | nt
        keep = packed != node
        return sel[keep], packed[keep]

    def _target(self, ix: int, iy: int, it: int, e: int) -> int | None:
        m = self.model
        if not m.alive_list[e]:
            return None
        x, y = ix * self.size, iy * self.size
        c, s = self._cos[it], self._sin[it]
        dx, dy = m.dx_list[e], m.dy_list[e]
        nx = round((x + c * dx - s * dy) / self.size)
        ny = round((y + s * dx + c * dy) / self.size)
        if nx * nx + ny * ny > self._cells:
            return None
        nt = round((self._heading[it] + m.rot_list[e]) / self.angle) % self.turns
        return (m.dst_list[e] << 48) | ((nx + _OFF) << 32) | ((ny + _OFF) << 16) | nt

    def successor(self, node: int, edge: int) -> int | None:
        """The target node of one edge from ``node`` (None when dead, off the lattice or a
        self-transition)."""
        _, ix, iy, it = self.unpack(node)
        key = self._target(ix, iy, it, edge)
        return None if key == node else key

    def is_goal(self, node: int) -> bool:
        pose, x, y, heading = self.centre(node)
        return pose == self.start and self.goal.reached(x, y, heading)

    def heuristics(self, nodes: Ints) -> Floats:
        """:meth:`heuristic` of many nodes at once."""
        pose = nodes >> 48
        x = (((nodes >> 32) & _MASK) - _OFF) * self.size
        y = (((nodes >> 16) & _MASK) - _OFF) * self.size
        heading = (nodes & _MASK) * self.angle
        far = np.hypot(x - self.goal.dx, y - self.goal.dy)
        turn = np.abs((heading - self.goal.dtheta + 180.0) % 360.0 - 180.0)
        slack = self.size * math.sqrt(2) / 2
        by_distance = np.maximum(0.0, far - self.goal.tolerance - slack) / self.reach
        by_turn = np.maximum(0.0, turn - self.goal.angle_tolerance - self.angle / 2) / self.turn
        out: Floats = np.maximum(self.hops[pose], np.maximum(by_distance, by_turn))
        if self._walks is not None:
            left = np.maximum(0.0, far - self.goal.tolerance - slack)
            steps = (self._walks[:, pose] < left).sum(axis=0)
            out = np.maximum(out, steps.astype(np.float64))
        return out

    def heuristic(self, node: int) -> float:
        """:meth:`heuristics` of one node (the same bits, in plain Python)."""
        goal = self.goal
        x = (((node >> 32) & _MASK) - _OFF) * self.size - goal.dx
        y = (((node >> 16) & _MASK) - _OFF) * self.size - goal.dy
        heading = angle_difference((node & _MASK) * self.angle, 0.0)
        turn = abs(angle_difference(heading, goal.dtheta))
        slack = self.size * math.sqrt(2) / 2
        by_distance = max(0.0, math.hypot(x, y) - goal.tolerance - slack) / self.reach
        by_turn = max(0.0, turn - goal.angle_tolerance - self.angle / 2) / self.turn
        hops = float(self.hops[node >> 48])
        if self._walks is None:
            return max(hops, by_distance, by_turn)
        left = max(0.0, math.hypot(x, y) - goal.tolerance - slack)
        return max(hops, by_distance, by_turn, float(self._walk_steps(node >> 48, left)))

    def bound(self, node: int) -> float:
        """The heuristic without the walk table: hops home and the distance and turn over
        the largest step (what D* Lite combines with its node-to-node bound)."""
        goal = self.goal
        _, x, y, heading = self.centre(node)
        far, turn = goal.error(x, y, heading)
        by_distance = max(0.0, far - goal.tolerance - self._slack) / self.reach
        by_turn = max(0.0, turn - goal.angle_tolerance - self.angle / 2) / self.turn
        return max(float(self.hops[node >> 48]), by_distance, by_turn)
