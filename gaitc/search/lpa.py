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

from gaitc.search.astar import Route, SearchBudgetExceeded
from gaitc.search.cells import Lattice
from gaitc.search.transitions import Step

GOAL = -1  # the virtual goal node
_INF = math.inf


def route_settled(top: tuple[float, float, int, int], goal_key: tuple[float, float],
                  goal_done: bool) -> bool:
    """LPA*'s stopping test for a non-empty queue whose first entry is ``top``: the goal
    is consistent and no queued key is below its key.  With the zero-cost goal edges an
    underconsistent goal cell can sit at exactly the goal's key, so ties are expanded
    while they are underconsistent (``top[2]``: they come first among equal keys); an
    overconsistent tie cannot lower the goal."""
    key = (top[0], top[1])
    return goal_done and (key > goal_key or (key == goal_key and bool(top[2])))


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
        self._heap: list[tuple[float, float, int, int]] = []
        self._queued: dict[int, tuple[float, float, int]] = {}
        # (edge, target, cost) of nodes with a small fan-out, kept across expansions
        self._succ: dict[int, list[tuple[int, int, float]]] = {}
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
        g, rhs = self.g.get(node, _INF), self.rhs.get(node, _INF)
        if g != rhs:
            h = self._h.get(node)
            if h is None:
                h = self.h(node)
            best = g if g < rhs else rhs
            k1 = best + h
            if k1 < _INF:
                # among equal keys the underconsistent (g < rhs) come first (flag 0)
                flag = 0 if g < rhs else 1
                self._queued[node] = (k1, best, flag)
                heapq.heappush(self._heap, (k1, best, flag, node))
                return
        self._queued.pop(node, None)

    def _top(self) -> tuple[float, float, int, int] | None:
        heap, queued = self._heap, self._queued
        while heap:
            k1, k2, flag, node = top = heap[0]
            if queued.get(node) == (k1, k2, flag):
                return top
            heapq.heappop(heap)
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

    def _successors(self, node: int) -> list[tuple[int, int, float]]:
        """(edge, target, cost) of ``node``; generating them the first time records the
        predecessors (and, for a small fan-out, keeps the list for later expansions)."""
        cached = self._succ.get(node)
        if cached is not None:
            return cached
        lattice = self.lattice
        edges, keys = lattice.successors(node)
        costs = lattice.cost_list
        out = [(e, k, costs[e]) for e, k in zip(edges, keys, strict=True)]
        if len(keys) > 48:  # heuristics of a large fan-out at once
            fresh = [k for k in keys if k not in self._h]
            if fresh:
                values = lattice.heuristics(np.array(fresh, dtype=np.int64)).tolist()
                self._h.update(zip(fresh, values, strict=True))
        if node != self.root and lattice.is_goal(node):
            out.append((-1, GOAL, 0.0))
        if node not in self._known:
            self._known.add(node)
            self.by_pose[node >> 48].append(node)
            pred = self.pred
            for e, v, c in out:
                pred[v].append((node, e, c))
        if len(out) <= 48:
            self._succ[node] = out
        return out

    def compute(self) -> Route | None:
        """ComputeShortestPath; the cheapest route, or None when the goal is unreachable.

        Raises :class:`SearchBudgetExceeded` after ``budget`` expansions in one call.
        """
        self.expanded = 0
        g, rhs = self.g, self.rhs
        heap, queued = self._heap, self._queued
        while True:
            top = self._top()
            if top is None or route_settled(top, self.key(GOAL),
                                            rhs.get(GOAL, _INF) == g.get(GOAL, _INF)):
                break
            heapq.heappop(heap)
            u = top[3]
            del queued[u]
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
                relax = self._relax
                for e, v, c in self._successors(u):
                    relax(v, base + c, u, e)
            else:
                g[u] = _INF
                for _e, v, _c in self._successors(u):
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
            cached = self._succ.get(u)
            if cached is not None:
                kept = [t for t in cached if t[0] != edge]
                if new is not None:
                    kept.append((edge, new, cost))
                self._succ[u] = kept
            if old is not None:
                self.pred[old].remove((u, edge, cost))
                if self.parent.get(old) == (u, edge):
                    self._recompute(old)
            if new is not None:
                self.pred[new].append((u, edge, cost))
                self._relax(new, self.g.get(u, _INF) + cost, u, edge)

    def _rekey(self) -> None:
        """The heuristic shrank (the step bounds or the walk table grew): recompute h and
        the queued keys, of the poses whose heuristic changed when the lattice knows them."""
        poses = self.lattice.rekey_poses
        if poses is None:  # every key: the heap is rebuilt (its stale entries dropped)
            self._h.clear()
            queued = list(self._queued)
            self._queued.clear()
            self._heap.clear()
            for node in queued:
                self._push(node)
            return
        self._h = {n: v for n, v in self._h.items() if n >> 48 not in poses}
        queued = [n for n in self._queued if n != GOAL and n >> 48 in poses]
        for node in queued:
            del self._queued[node]
            self._push(node)
