"""D* Lite over the hybrid lattice (Koenig and Likhachev, *D* Lite*, AAAI 2002; thesis 5.2.2).

LPA* (:mod:`gaitc.search.lpa`) searches forward from the cycle's start, so its g values are
costs *from* that start and are only of use while the start stays put.  D* Lite searches
backward from the goal, so its g values are costs *to* the goal: after every single
transition the robot makes, the search start moves to the lattice node the robot really
reached (its pose, in the cell of its measured displacement since the cycle began) and the
rest of the cycle is re-planned from there, repairing only what the change touched.  The key
modifier k_m keeps queued keys valid as the start moves (the paper's Figure 3).

Backward search needs the predecessors of a node.  The lattice's successors are propagated
from cell centres, so for each incoming transition of a node's pose there is (up to
rounding, which is checked against the forward rule) one source cell: the node's cell
centre minus the transition's motion turned into the source heading.  All goal cells feed a
virtual goal by zero-cost edges, as in LPA*.  The heuristic between two nodes is the largest
of the hops between their poses, their distance over the longest step and their turn over
the largest rotation: each is a lower bound that obeys the triangle inequality, as D* Lite
needs.

On graphs small enough for walk tables (:data:`gaitc.search.cells.WALK_EDGES`) the
heuristic from the start is sharper: the fewest transitions whose longest walk from the
start's pose to a node's pose (:meth:`Lattice.walks_with`) spans their distance, the bound
that keeps A* and LPA* small toward far goals (the backward search, from about a hundred
goal cells, ran out of its budget without it: asymmetric6's goals at (60, 0) and (0, 50)).
That bound holds for one start only, so when the robot moves the table is built for its
new pose and every queued key is made afresh (k_m back to zero) instead of growing k_m,
which is the same search with a new consistent heuristic.
"""

from __future__ import annotations

import bisect
import heapq
import math
from collections import defaultdict

import numpy as np

from gaitc.search.astar import Route, SearchBudgetExceeded
from gaitc.search.cells import Lattice
from gaitc.search.transitions import Step

GOAL = -1  # the virtual goal node
_INF = math.inf
_AROUND = [(x, y) for x in (-1, 0, 1) for y in (-1, 0, 1)]
_TIE = 1e-6  # cells: how near half a cell a shift counts as a rounding tie


class DStarLite:
    """D* Lite from the lattice's goal cells back to a movable start (:meth:`move_start`)."""

    def __init__(self, lattice: Lattice, budget: int = 200_000) -> None:
        self.lattice = lattice
        self.budget = budget
        self.root = lattice.root
        self.start = self.root
        self._last = self.root
        self.km = 0.0
        self.g: dict[int, float] = {}
        self.rhs: dict[int, float] = {GOAL: 0.0}
        self.by_pose: dict[int, list[int]] = defaultdict(list)  # nodes with an rhs
        model = lattice.model
        # edges into each pose, from poses the start pose can reach (no other source can
        # lie on a route from the start; removals only shrink that set)
        seen = _levels(model.src, model.dst, model.alive, lattice.start, model.poses) >= 0
        order = np.argsort(model.dst, kind="stable")
        order = order[seen[model.src[order]]]
        bounds = np.searchsorted(model.dst[order], np.arange(model.poses + 1))
        self._into = [order[bounds[p] : bounds[p + 1]].tolist() for p in range(model.poses)]
        self._goals = self._goal_nodes()
        self._alive = model.alive.copy()  # hops are taken on the graph as first searched
        self._hops: dict[int, list[float]] = {}
        self._heap: list[tuple[float, float, int]] = []
        self._queued: dict[int, tuple[float, float]] = {}
        self._walks: list[list[float]] = []  # per pose, W[k] of walks from the start's pose
        self._walk_table()
        self.expanded = 0
        self.total_expanded = 0
        self._push(GOAL)

    # -- the lattice, backward -------------------------------------------------------
    def _goal_nodes(self) -> list[int]:
        lat, goal = self.lattice, self.lattice.goal
        reach = math.ceil((goal.tolerance + 1e-6) / lat.size)
        cx, cy = round(goal.dx / lat.size), round(goal.dy / lat.size)
        out = []
        for ix in range(cx - reach - 1, cx + reach + 2):
            for iy in range(cy - reach - 1, cy + reach + 2):
                if ix * ix + iy * iy > lat._cells:
                    continue
                for it in range(lat.turns):
                    node = lat.pack(lat.start, ix, iy, it)
                    if node != self.root and lat.is_goal(node):
                        out.append(node)
        return out

    def _successors(self, node: int) -> list[tuple[int, int]]:
        """(edge, target) of ``node``, the goal edge (-1) of a goal cell included."""
        edges, keys = self.lattice.successors(node)
        out = list(zip(edges, keys, strict=True))
        if node != self.root and node >> 48 == self.lattice.start and self.lattice.is_goal(node):
            out.append((-1, GOAL))
        return out

    def _sources(self, node: int, edge: int) -> list[int]:
        """The nodes from which ``edge`` leads to ``node`` (usually one, none off the disc)."""
        lat, m = self.lattice, self.lattice.model
        if not m.alive_list[edge]:
            return []
        _, ix, iy, it = lat.unpack(node)
        rot, dx, dy = m.rot_list[edge], m.dx_list[edge], m.dy_list[edge]
        heading = lat._heading[it]
        guess = round((heading - rot) / lat.angle)
        out = []
        for jt in (guess - 1, guess, guess + 1):
            jt %= lat.turns
            if round((lat._heading[jt] + rot) / lat.angle) % lat.turns != it:
                continue
            c, s = lat._cos[jt], lat._sin[jt]
            fx, fy = (c * dx - s * dy) / lat.size, (s * dx + c * dy) / lat.size
            gx, gy = ix - round(fx), iy - round(fy)
            src = int(m.src[edge])
            # a shift of exactly half a cell rounds to even: two source cells can then
            # share one target, so every neighbour is checked
            tie = abs(fx - math.floor(fx) - 0.5) < _TIE or abs(fy - math.floor(fy) - 0.5) < _TIE
            if not tie and gx * gx + gy * gy <= lat._cells:
                source = lat.pack(src, gx, gy, jt)
                if lat.successor(source, edge) == node:
                    out.append(source)
                    continue
            for jx, jy in _AROUND:  # a tie, or rounding moved the source off the guess
                jx, jy = gx + jx, gy + jy
                if jx * jx + jy * jy <= lat._cells:
                    source = lat.pack(src, jx, jy, jt)
                    if source != node and lat.successor(source, edge) == node:
                        out.append(source)
        return out

    def _predecessors(self, node: int) -> list[tuple[int, float]]:
        """(source, edge cost) of every live edge into ``node``."""
        if node == GOAL:
            return [(s, 0.0) for s in self._goals]
        costs = self.lattice.cost_list
        return [(s, costs[e]) for e in self._into[node >> 48] for s in self._sources(node, e)]

    # -- keys --------------------------------------------------------------------------
    def hops(self, pose: int) -> list[float]:
        """Fewest transitions from ``pose`` to every pose (inf: none), on the graph as it
        was first searched: removals only lengthen them, so they stay a lower bound, and
        one graph for all of them keeps the triangle inequality D* Lite's k_m needs."""
        out = self._hops.get(pose)
        if out is None:
            m = self.lattice.model
            levels = _levels(m.src, m.dst, self._alive, pose, m.poses)
            out = self._hops[pose] = [math.inf if v < 0 else float(v) for v in levels]
        return out

    def h(self, a: int, b: int) -> float:
        """Lower bound on the cost from node ``a`` to node ``b`` (or to the goal): the hops
        between their poses, their distance over the longest step, their turn over the
        largest rotation."""
        lat = self.lattice
        _, ax, ay, ah = lat.centre(a)
        if b == GOAL:
            return lat.bound(a)
        _, bx, by, bh = lat.centre(b)
        far = math.hypot(ax - bx, ay - by)
        turn = abs((ah - bh + 180.0) % 360.0 - 180.0)
        return max(self.hops(a >> 48)[b >> 48], far / lat.reach, turn / lat.turn)

    def _walk_table(self) -> None:
        """The walk table from the start's pose (none for large graphs)."""
        lat = self.lattice
        self._walks = (lat.walks_with(self.start >> 48, home=False).T.tolist()
                       if lat.walking else [])

    def from_start(self, node: int) -> float:
        """:meth:`h` from the start to ``node``, sharpened by the walk table: at least the
        fewest transitions whose longest walk from the start's pose spans the distance
        between the two cell centres (each step's bound holds its snapping slack)."""
        bound = self.h(self.start, node)
        if not self._walks or node == GOAL:
            return bound
        lat = self.lattice
        _, ax, ay, _ = lat.centre(self.start)
        _, bx, by, _ = lat.centre(node)
        steps = bisect.bisect_left(self._walks[node >> 48], math.hypot(ax - bx, ay - by))
        return max(bound, float(steps))

    def key(self, node: int) -> tuple[float, float]:
        best = min(self.g.get(node, _INF), self.rhs.get(node, _INF))
        return best + self.from_start(node) + self.km, best

    def _push(self, node: int) -> None:
        if self.g.get(node, _INF) != self.rhs.get(node, _INF):
            k = self.key(node)
            self._queued[node] = k
            heapq.heappush(self._heap, (k[0], k[1], node))
        else:
            self._queued.pop(node, None)

    def _top(self) -> tuple[float, float, int] | None:
        while self._heap:
            k1, k2, node = self._heap[0]
            if self._queued.get(node) == (k1, k2):
                return k1, k2, node
            heapq.heappop(self._heap)
        return None

    def _set_rhs(self, node: int, value: float) -> None:
        if node not in self.rhs:
            self.by_pose[node >> 48].append(node)
        self.rhs[node] = value

    def _recompute(self, node: int) -> None:
        """rhs(node) = min over its successors of c + g; requeue."""
        if node != GOAL:
            get, costs = self.g.get, self.lattice.cost_list
            best = _INF
            for e, v in self._successors(node):
                value = get(v, _INF) + (0.0 if e < 0 else costs[e])
                best = min(best, value)
            self._set_rhs(node, best)
        self._push(node)

    def _relax(self, node: int, value: float) -> None:
        if value < self.rhs.get(node, _INF):
            self._set_rhs(node, value)
            self._push(node)

    # -- D* Lite -----------------------------------------------------------------------
    def compute(self) -> Route | None:
        """ComputeShortestPath, then the route from the current start (None: no route).

        Raises :class:`SearchBudgetExceeded` after ``budget`` expansions in one call."""
        self.expanded = 0
        g, rhs = self.g, self.rhs
        while True:
            top = self._top()
            start_key = self.key(self.start)
            consistent = g.get(self.start, _INF) == rhs.get(self.start, _INF)
            # ties with the start's key are expanded too (see LPA*: zero-cost goal edges)
            if top is None or ((top[0], top[1]) > start_key and consistent):
                break
            u = top[2]
            fresh = self.key(u)
            if (top[0], top[1]) < fresh:
                self._queued[u] = fresh
                heapq.heapreplace(self._heap, (fresh[0], fresh[1], u))
                continue
            heapq.heappop(self._heap)
            del self._queued[u]
            self.expanded += 1
            if self.expanded > self.budget:
                self.total_expanded += self.expanded
                raise SearchBudgetExceeded(self.budget)
            old = g.get(u, _INF)
            if old > rhs.get(u, _INF):
                g[u] = base = rhs[u]
                for s, c in self._predecessors(u):
                    self._relax(s, base + c)
            else:
                g[u] = _INF
                for s, c in self._predecessors(u):
                    if rhs.get(s, _INF) == old + c:
                        self._recompute(s)
                self._recompute(u)
        self.total_expanded += self.expanded
        return self.route()

    def route(self) -> Route | None:
        """Greedy descent of c + g from the start to the goal."""
        g, costs = self.g, self.lattice.cost_list
        if g.get(self.start, _INF) == _INF:
            return None
        nodes, edges, v = [self.start], [], self.start
        while True:
            best: tuple[float, int, int] | None = None
            for e, w in self._successors(v):
                value = g.get(w, _INF) + (0.0 if e < 0 else costs[e])
                if value < _INF and (best is None or (value, w) < (best[0], best[2])):
                    best = (value, e, w)
            if best is None or len(nodes) > len(g) + 1:  # cannot happen on consistent values
                return None
            _, e, w = best
            if w == GOAL:
                break
            nodes.append(w)
            edges.append(e)
            v = w
        return Route(tuple(nodes), tuple(edges), g[self.start], self.expanded)

    def explored(self) -> frozenset[int]:
        """Every node with a finite g (the cells the backward search has settled)."""
        return frozenset(n for n, v in self.g.items() if n != GOAL and v < _INF)

    def move_start(self, node: int) -> None:
        """The robot is now at ``node``: k_m grows by the heuristic from the last start,
        or, with a walk table, the table is built for the new start and every key afresh."""
        if self._walks:
            if node != self.start:
                self.start = node
                self._walk_table()
                self._rekey()
            return
        self.km += self.h(self._last, node)
        self._last = self.start = node

    # -- changes of the gait graph -----------------------------------------------------
    def update_transition(self, edge: int, step: Step | None) -> None:
        """Give transition ``edge`` a new motion (``None``: remove it), then fix the rhs of
        the nodes whose edge moved: those whose rhs came through the old target, and the
        new sources of every settled node of the target pose.  :meth:`compute` repairs."""
        lattice, model = self.lattice, self.lattice.model
        cost = lattice.cost_list[edge]
        tight = []
        for u in self.by_pose.get(int(model.src[edge]), []):
            old = lattice.successor(u, edge)
            value = self.rhs.get(u, _INF)
            if old is not None and value < _INF and value == self.g.get(old, _INF) + cost:
                tight.append(u)
        if step is None:
            model.remove(edge)
        else:
            model.set_motion(edge, step)
        if step is not None:
            bound = lattice.walk_bound(edge)
            grew = lattice.cover(edge)
            if self._walks and lattice.walk_bound(edge) != bound:
                # the edge's length bound grew: walks from the start may reach farther,
                # even where the walks home (what cover reports) stayed as they were
                self._walk_table()
                grew = True
            if grew:
                self._rekey()
        for u in tight:
            self._recompute(u)
        target = int(model.dst[edge])
        for v in list(self.by_pose.get(target, [])):
            value = self.g.get(v, _INF)
            if value < _INF:
                for s in self._sources(v, edge):
                    self._relax(s, value + cost)

    def _rekey(self) -> None:
        """The heuristic's bounds changed: every queued key afresh (and k_m from zero)."""
        self.km, self._last = 0.0, self.start
        queued = list(self._queued)
        self._queued.clear()
        self._heap.clear()
        for node in queued:
            self._push(node)


def _levels(
    src: np.ndarray, dst: np.ndarray, alive: np.ndarray, start: int, poses: int
) -> np.ndarray:
    """Breadth-first levels from ``start`` over live edges (-1: unreachable)."""
    level = np.full(poses, -1, dtype=np.int64)
    level[start] = 0
    frontier = np.zeros(poses, dtype=bool)
    frontier[start] = True
    depth = 0
    while frontier.any():
        depth += 1
        fresh = np.zeros(poses, dtype=bool)
        fresh[dst[alive & frontier[src]]] = True
        frontier = fresh & (level < 0)
        level[frontier] = depth
    return level
