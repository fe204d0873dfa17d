"""Lifelong Planning A* over the hybrid lattice (Koenig, Likhachev and Furcy 2004; thesis 5.2.2).

The online loop of Algorithm 2 replaces a transition's predicted motion with the one the
robot really made, or removes a transition the robot could not make.  In the lattice that
moves (or deletes) the edge of that transition out of every node of its source pose, so
:meth:`LifelongPlanner.update_transition` touches only those nodes and repairs g/rhs from
there instead of searching again.  Several goal nodes (every cell within the tolerance) are
joined by zero-cost edges to one virtual goal.  Keys are [min(g, rhs) + h; min(g, rhs)].
"""

from __future__ import annotations

import heapq
import math
from collections import defaultdict

import numpy as np

from gaitsearch.astar import Route, SearchBudgetExceeded
from gaitsearch.cells import Lattice
from gaitsearch.transitions import Step

GOAL = -1  # the virtual goal node
_INF = math.inf


class LifelongPlanner:
    """LPA* from the lattice's root to its goal cells; call :meth:`compute` for a route."""

    def __init__(self, lattice: Lattice, budget: int = 200_000) -> None:
        self.lattice = lattice
        self.budget = budget
        self.root = lattice.root
        self.g: dict[int, float] = {}
        self.rhs: dict[int, float] = {self.root: 0.0}
        # predecessors (u, edge, cost) of every generated node; the goal edges are -1
        self.pred: dict[int, list[tuple[int, int, float]]] = defaultdict(list)
        self.parent: dict[int, tuple[int, int]] = {}  # the predecessor rhs came from
        self.by_pose: dict[int, list[int]] = defaultdict(list)  # nodes whose edges are known
        self._h: dict[int, float] = {}
        self._heap: list[tuple[float, float, int]] = []
        self._queued: dict[int, tuple[float, float]] = {}
        self.expanded = 0  # expansions of the last compute()
        self.total_expanded = 0
        self._known: set[int] = set()
        self._push(self.root)

    # -- LPA* primitives -------------------------------------------------------------
    def h(self, node: int) -> float:
        if node == GOAL:
            return 0.0
        value = self._h.get(node)
        if value is None:
            value = self._h[node] = self.lattice.heuristic(node)
        return value

    def key(self, node: int) -> tuple[float, float]:
        best = min(self.g.get(node, _INF), self.rhs.get(node, _INF))
        return best + self.h(node), best

    def _push(self, node: int) -> None:
        if self.g.get(node, _INF) != self.rhs.get(node, _INF):
            k = self.key(node)
            if math.isfinite(k[0]):
                self._queued[node] = k
                heapq.heappush(self._heap, (k[0], k[1], node))
                return
        self._queued.pop(node, None)

    def _top(self) -> tuple[float, float, int] | None:
        while self._heap:
            k1, k2, node = self._heap[0]
            if self._queued.get(node) == (k1, k2):
                return k1, k2, node
            heapq.heappop(self._heap)
        return None

    def _cost(self, edge: int) -> float:
        return 0.0 if edge < 0 else self.lattice.cost(edge)

    def _recompute(self, node: int) -> None:
        if node != self.root:
            get = self.g.get
            best, arg = _INF, None
            for u, e, c in self.pred[node]:
                value = get(u, _INF) + c
                if value < best:
                    best, arg = value, (u, e)
            self.rhs[node] = best
            if arg is None:
                self.parent.pop(node, None)
            else:
                self.parent[node] = arg
        self._push(node)

    def _relax(self, node: int, value: float, u: int, e: int) -> None:
        if node != self.root and value < self.rhs.get(node, _INF):
            self.rhs[node] = value
            self.parent[node] = (u, e)
            self._push(node)

    def _through(self, node: int, u: int) -> bool:
        """Whether ``node``'s rhs came from ``u``."""
        came = self.parent.get(node)
        return came is not None and came[0] == u

    def _successors(self, node: int) -> list[tuple[int, int]]:
        """(edge, target) of ``node``; generating them the first time records the preds."""
        lattice = self.lattice
        edges, keys = lattice.successors(node)
        out = list(zip(edges, keys, strict=True))
        if len(keys) > 48:  # heuristics of a large fan-out at once
            fresh = [k for k in keys if k not in self._h]
            if fresh:
                values = lattice.heuristics(np.array(fresh, dtype=np.int64)).tolist()
                self._h.update(zip(fresh, values, strict=True))
        if node != self.root and lattice.is_goal(node):
            out.append((-1, GOAL))
        pose = node >> 48
        if node not in self._known:
            self._known.add(node)
            self.by_pose[pose].append(node)
            for e, v in out:
                self.pred[v].append((node, e, self._cost(e)))
        return out

    def compute(self) -> Route | None:
        """ComputeShortestPath; the cheapest route, or None when the goal is unreachable.

        Raises :class:`SearchBudgetExceeded` after ``budget`` expansions in one call.
        """
        self.expanded = 0
        g, rhs = self.g, self.rhs
        while True:
            top = self._top()
            goal_key = self.key(GOAL)
            # ties with the goal's key are expanded too: the zero-cost goal edges would
            # otherwise let an underconsistent goal cell hide behind an equal key
            if top is None or (
                (top[0], top[1]) > goal_key and rhs.get(GOAL, _INF) == g.get(GOAL, _INF)
            ):
                break
            heapq.heappop(self._heap)
            u = top[2]
            del self._queued[u]
            self.expanded += 1
            if self.expanded > self.budget:
                self.total_expanded += self.expanded
                raise SearchBudgetExceeded(self.budget)
            if u == GOAL:
                if g.get(u, _INF) > rhs.get(u, _INF):
                    g[u] = rhs[u]
                else:
                    g[u] = _INF
                    self._recompute(u)
                continue
            if g.get(u, _INF) > rhs.get(u, _INF):
                g[u] = base = rhs[u]
                for e, v in self._successors(u):
                    self._relax(v, base + self._cost(e), u, e)
            else:
                g[u] = _INF
                for _e, v in self._successors(u):
                    if self._through(v, u):
                        self._recompute(v)
                self._recompute(u)
        self.total_expanded += self.expanded
        return self.route()

    def route(self) -> Route | None:
        """The current cheapest route, following each node's rhs back to the root."""
        g = self.g
        if g.get(GOAL, _INF) == _INF:
            return None
        nodes: list[int] = []
        edges: list[int] = []
        v = GOAL
        while v != self.root:
            came = self.parent.get(v)
            if came is None or len(nodes) > len(g):  # cannot happen on consistent values
                return None
            u, e = came
            if v != GOAL:
                nodes.append(v)
                edges.append(e)
            v = u
        nodes.append(self.root)
        return Route(
            tuple(reversed(nodes)),
            tuple(reversed(edges)),
            g[GOAL],
            self.expanded,
        )

    def explored(self) -> frozenset[int]:
        """Every node with a finite g (the cells the search has settled)."""
        return frozenset(n for n, v in self.g.items() if n != GOAL and v < _INF)

    # -- changes of the gait graph -----------------------------------------------------
    def update_transition(self, edge: int, step: Step | None) -> None:
        """Give transition ``edge`` a new motion (``None``: the robot cannot make it), then
        repair: every known node of its source pose gets its edge moved to the new target.
        Call :meth:`compute` afterwards for the repaired route."""
        lattice, model = self.lattice, self.lattice.model
        nodes = self.by_pose.get(int(model.src[edge]), [])
        before = [lattice.successor(u, edge) for u in nodes]
        if step is None:
            model.remove(edge)
        else:
            model.set_motion(edge, step)
        if step is not None and lattice.cover(edge):
            self._rekey()
        cost = self._cost(edge)
        for u, old in zip(nodes, before, strict=True):
            new = lattice.successor(u, edge)
            if new == old:
                continue
            if old is not None:
                self.pred[old].remove((u, edge, cost))
                if self.parent.get(old) == (u, edge):
                    self._recompute(old)
            if new is not None:
                self.pred[new].append((u, edge, cost))
                self._relax(new, self.g.get(u, _INF) + cost, u, edge)

    def _rekey(self) -> None:
        """The heuristic's step bounds grew: recompute h and every queued key."""
        self._h.clear()
        queued = list(self._queued)
        self._queued.clear()
        self._heap.clear()
        for node in queued:
            self._push(node)
