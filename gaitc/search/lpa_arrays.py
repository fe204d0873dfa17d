"""Lifelong Planning A* with numpy arrays, for lattices whose nodes have hundreds of edges.

The algorithm is :mod:`gaitc.search.lpa`'s, Koenig, Likhachev and Furcy's 2004 LPA* (thesis
5.2.2: UpdateVertex, ComputeShortestPath, and the edge repair of Algorithm 2's online loop);
what differs is the data layout, because a pose of a 10,000-state gait graph has about 430
transitions and the dict-and-tuple planner spends its time in Python loops over them.  Nodes
get dense numbers with g, rhs, h and the rhs-giving predecessor in numpy arrays, successor
lists are arrays, an expansion relaxes its successors (or, when underconsistent, finds
those whose rhs came through it) in a few array operations, and predecessors are found in
:class:`~gaitc.search.incoming.IncomingEdges`.  Each array call costs microseconds, so on
sparse graphs (a few edges per pose) :mod:`gaitc.search.lpa` is faster; :func:`lifelong`
picks one.  The priority queue is the same binary heap of (k1, k2, flag, node) tuples with
lazy deletion.
"""

from __future__ import annotations

import heapq
import math
import struct
from collections import defaultdict

import numpy as np

from gaitc.search.astar import Route, SearchBudgetExceeded
from gaitc.search.cells import Lattice
from gaitc.search.incoming import IncomingEdges
from gaitc.search.lpa import GOAL, LifelongPlanner, route_settled
from gaitc.search.transitions import Ints, Step

_GOAL, _ROOT = 0, 1  # dense numbers
_INF = math.inf
_NONE = np.zeros(0, np.int64)
# a queue entry (k1, k2, flag, node) as bytes that sort like the tuple (big-endian; k1, k2
# are never negative, so their IEEE bits sort like the numbers); bytes are not tracked by
# Python's cycle collector, which otherwise walks millions of queued tuples when it runs
_ENTRY = struct.Struct(">ddBQ")
_RECORD = np.dtype([("k1", ">f8"), ("k2", ">f8"), ("flag", "u1"), ("node", ">u8")])


DENSE = 100  # edges per pose from which :func:`lifelong` takes the array planner


class ArrayLifelongPlanner:
    """LPA* from the lattice's root to its goal cells; call :meth:`compute` for a route."""

    def __init__(self, lattice: Lattice, budget: int = 200_000) -> None:
        self.lattice = lattice
        self.budget = budget
        self.root = lattice.root
        self._index: dict[int, int] = {GOAL: _GOAL, self.root: _ROOT}
        size = 1024
        self._key = np.zeros(size, np.int64)  # packed lattice node per dense number
        self._key[_GOAL], self._key[_ROOT] = GOAL, self.root
        self._count = 2
        self._g = np.full(size, _INF)
        self._rhs = np.full(size, _INF)
        self._h = np.zeros(size)
        self._parent = np.full(size, -1, np.int64)  # the predecessor rhs came from
        self._via = np.full(size, -1, np.int64)  # and its edge
        self._rhs[_ROOT] = 0.0
        self._h[_ROOT] = float(lattice.heuristics(np.array([self.root], np.int64))[0])
        # (targets, edges) per node once generated; the goal edges are -1
        self._succ: dict[int, tuple[Ints, Ints]] = {_GOAL: (_NONE, _NONE)}
        self._incoming = IncomingEdges()
        self.by_pose: dict[int, list[int]] = defaultdict(list)  # generated nodes per pose
        # cost per edge; the negative edge numbers read the two extra slots: -2 (a dead
        # incoming row) costs infinity, -1 (a goal edge) nothing
        self._cost = np.concatenate((lattice.costs, [_INF, 0.0]))
        self._heap: list[bytes] = []
        self._queued: dict[int, bytes] = {}  # the live entry of every queued node
        self.expanded = 0  # expansions of the last compute()
        self.total_expanded = 0
        self._push(_ROOT)

    # -- dense node numbers ------------------------------------------------------------
    def _grow(self, count: int) -> None:
        size = len(self._g)
        if count <= size:
            return
        wider = max(count, 2 * size)

        def widen(a: np.ndarray, fill: float) -> np.ndarray:
            out = np.full(wider, fill, a.dtype)
            out[:size] = a
            return out

        self._g, self._rhs = widen(self._g, _INF), widen(self._rhs, _INF)
        self._h = widen(self._h, 0.0)
        self._parent, self._via = widen(self._parent, -1), widen(self._via, -1)
        self._key = widen(self._key, 0)

    def _add(self, keys: Ints) -> Ints:
        """Number the new nodes ``keys`` (distinct, unknown)."""
        first = self._count
        ids = np.arange(first, first + len(keys), dtype=np.int64)
        self._index.update(zip(keys.tolist(), ids.tolist(), strict=True))
        self._count += len(keys)
        self._grow(self._count)
        self._key[ids] = keys
        self._h[ids] = self.lattice.heuristics(keys)
        return ids

    def _ids(self, keys: Ints) -> Ints:
        """The dense numbers of ``keys``, numbering the unknown ones."""
        get = self._index.get
        ids = np.array([get(k, -1) for k in keys.tolist()], dtype=np.int64)
        fresh = ids < 0
        if fresh.any():
            unknown, where = np.unique(keys[fresh], return_inverse=True)
            ids[fresh] = self._add(unknown)[where]
        return ids

    # -- LPA* primitives -------------------------------------------------------------
    def key(self, node: int) -> tuple[float, float]:
        """[min(g, rhs) + h; min(g, rhs)] of a dense node number."""
        best = min(self._g.item(node), self._rhs.item(node))
        return best + self._h.item(node), best

    def _push(self, node: int) -> None:
        """UpdateVertex's queue part: queue ``node`` with its key when inconsistent."""
        g, rhs = self._g.item(node), self._rhs.item(node)
        if g != rhs:
            best = g if g < rhs else rhs
            k1 = best + self._h.item(node)
            if k1 < _INF:
                # among equal keys the underconsistent (g < rhs) come first (flag 0)
                flag = 0 if g < rhs else 1
                entry = self._queued[node] = _ENTRY.pack(k1, best, flag, node)
                heapq.heappush(self._heap, entry)
                return
        self._queued.pop(node, None)

    def _push_many(self, nodes: Ints) -> None:
        """:meth:`_push` of distinct nodes."""
        g, rhs = self._g[nodes], self._rhs[nodes]
        best = np.minimum(g, rhs)
        k1 = best + self._h[nodes]
        queue = (g != rhs) & (k1 < _INF)
        records = np.empty(int(queue.sum()), _RECORD)
        records["k1"], records["k2"] = k1[queue], best[queue]
        records["flag"], records["node"] = g[queue] >= rhs[queue], nodes[queue]
        packed, width = records.tobytes(), _RECORD.itemsize
        queued, heap, push = self._queued, self._heap, heapq.heappush
        for at, node in enumerate(nodes[queue].tolist()):
            entry = queued[node] = packed[at * width : (at + 1) * width]
            push(heap, entry)
        if not queue.all():
            for node in nodes[~queue].tolist():
                queued.pop(node, None)

    def _top(self) -> tuple[float, float, int, int] | None:
        heap, queued, unpack = self._heap, self._queued, _ENTRY.unpack
        while heap:
            top = unpack(heap[0])
            if queued.get(top[3]) == heap[0]:
                return top
            heapq.heappop(heap)
        return None

    def _successors(self, node: int) -> tuple[Ints, Ints]:
        """(targets, edges) of ``node``; generating them the first time records them as
        the targets' incoming edges."""
        cached = self._succ.get(node)
        if cached is not None:
            return cached
        lattice, key = self.lattice, self._key.item(node)
        edges, keys = lattice.successor_arrays(key)
        targets = self._ids(keys)
        if node != _ROOT and lattice.is_goal(key):
            targets = np.append(targets, _GOAL)
            edges = np.append(edges, -1)
        self._succ[node] = targets, edges
        self._incoming.add(targets, node, edges)
        self.by_pose[key >> 48].append(node)
        return targets, edges

    def _lower(self, node: int, base: float) -> None:
        """Expansion of an overconsistent ``node`` (g = rhs = ``base``): successors whose
        rhs the edge from it lowers take it (of parallel edges into one target, the
        cheapest is written last)."""
        targets, edges = self._successors(node)
        value = base + self._cost[edges]
        better = np.nonzero(value < self._rhs[targets])[0]
        if not len(better):
            return
        if len(better) > 1:
            better = better[np.argsort(-value[better], kind="stable")]
        lowered = targets[better]
        self._rhs[lowered] = value[better]
        self._parent[lowered] = node
        self._via[lowered] = edges[better]
        self._push_many(np.unique(lowered))

    def _recompute(self, nodes: Ints) -> None:
        """rhs = min over predecessors (g + cost) of distinct non-root ``nodes``; queue them."""
        rows, src, via = self._incoming.of(nodes)
        value = self._g[src] + self._cost[via]
        self._rhs[nodes] = _INF
        self._parent[nodes] = -1
        self._via[nodes] = -1
        keep = value < _INF
        if keep.any():
            rows, src, via, value = rows[keep], src[keep], via[keep], value[keep]
            order = np.lexsort((value, rows))
            ranked = rows[order]
            first = order[np.concatenate(([True], ranked[1:] != ranked[:-1]))]
            best = nodes[rows[first]]
            self._rhs[best] = value[first]
            self._parent[best] = src[first]
            self._via[best] = via[first]
        self._push_many(nodes)

    def compute(self) -> Route | None:
        """ComputeShortestPath; the cheapest route, or None when the goal is unreachable.

        Raises :class:`SearchBudgetExceeded` after ``budget`` expansions in one call.
        """
        self.expanded = 0
        heap, queued = self._heap, self._queued
        while True:
            top = self._top()
            if top is None or route_settled(top, self.key(_GOAL),
                                            self._rhs.item(_GOAL) == self._g.item(_GOAL)):
                break
            heapq.heappop(heap)
            u = top[3]
            del queued[u]
            self.expanded += 1
            if self.expanded > self.budget:
                self.total_expanded += self.expanded
                raise SearchBudgetExceeded(self.budget)
            g, rhs = self._g.item(u), self._rhs.item(u)
            if g > rhs:
                self._g[u] = rhs
                self._lower(u, rhs)
            else:
                # underconsistent: g = inf; the successors whose rhs came through u are
                # recomputed (u's own rhs does not depend on its g)
                self._g[u] = _INF
                targets, _edges = self._successors(u)
                through = np.unique(targets[self._parent[targets] == u])
                if len(through):
                    self._recompute(through)
                self._push(u)
        self.total_expanded += self.expanded
        return self.route()

    def route(self) -> Route | None:
        """The current cheapest route, following each node's rhs back to the root."""
        if self._g.item(_GOAL) == _INF:
            return None
        nodes: list[int] = []
        edges: list[int] = []
        v = _GOAL
        while v != _ROOT:
            u = self._parent.item(v)
            if u < 0 or len(nodes) > self._count:  # cannot happen on consistent values
                return None
            if v != _GOAL:
                nodes.append(self._key.item(v))
                edges.append(self._via.item(v))
            v = u
        nodes.append(self.root)
        return Route(
            tuple(reversed(nodes)),
            tuple(reversed(edges)),
            self._g.item(_GOAL),
            self.expanded,
        )

    def explored(self) -> frozenset[int]:
        """Every node with a finite g (the cells the search has settled)."""
        settled = np.nonzero(self._g[_ROOT : self._count] < _INF)[0] + _ROOT
        return frozenset(self._key[settled].tolist())

    # -- changes of the gait graph -----------------------------------------------------
    def update_transition(self, edge: int, step: Step | None) -> None:
        """Give transition ``edge`` a new motion (``None``: the robot cannot make it), then
        repair: every generated node of its source pose gets its edge moved to the new
        target.  Call :meth:`compute` afterwards for the repaired route."""
        lattice, model = self.lattice, self.lattice.model
        nodes = self.by_pose.get(int(model.src[edge]), [])
        if step is None:
            model.remove(edge)
        else:
            model.set_motion(edge, step)
        if step is not None and lattice.cover(edge):
            self._rekey()
        cost = self._cost.item(edge)
        for u in nodes:
            targets, edges = self._successors(u)
            at = np.nonzero(edges == edge)[0]
            old = targets.item(at[0]) if len(at) else None
            key = lattice.successor(self._key.item(u), edge)
            new = None if key is None else self._ids(np.array([key], np.int64)).item(0)
            if new == old:
                continue
            if old is not None and new is not None:
                targets[at[0]] = new
            elif old is not None:
                keep = edges != edge
                self._succ[u] = targets[keep], edges[keep]
            elif new is not None:
                self._succ[u] = np.append(targets, new), np.append(edges, edge)
            if old is not None:
                self._incoming.kill(old, u, edge)
                if self._parent.item(old) == u and self._via.item(old) == edge:
                    self._recompute(np.array([old], np.int64))
            if new is not None:
                self._incoming.add(np.array([new], np.int64), u, np.array([edge], np.int64))
                value = self._g.item(u) + cost
                if new != _ROOT and value < self._rhs.item(new):
                    self._rhs[new] = value
                    self._parent[new] = u
                    self._via[new] = edge
                    self._push(new)

    def _rekey(self) -> None:
        """The heuristic shrank (the step bounds or the walk table grew): recompute h and
        the queued keys, of the poses whose heuristic changed when the lattice knows them."""
        poses = self.lattice.rekey_poses
        ids = np.arange(_ROOT, self._count, dtype=np.int64)
        keys = self._key[ids]
        if poses is None:  # every key: the heap is rebuilt (its stale entries dropped)
            self._h[ids] = self.lattice.heuristics(keys)
            queued = list(self._queued)
            self._queued.clear()
            self._heap.clear()
            for node in queued:
                self._push(node)
            return
        if not poses:
            return
        changed = np.isin(keys >> 48, np.array(sorted(poses), np.int64))
        self._h[ids[changed]] = self.lattice.heuristics(keys[changed])
        moved = set(ids[changed].tolist())
        for node in [n for n in self._queued if n in moved]:
            del self._queued[node]
            self._push(node)


def lifelong(
    lattice: Lattice, budget: int, dense: int = DENSE
) -> LifelongPlanner | ArrayLifelongPlanner:
    """The LPA* planner for ``lattice``: the array one when poses have ``dense`` or more
    transitions on average, else the dict one."""
    model = lattice.model
    if len(model) >= dense * model.poses:
        return ArrayLifelongPlanner(lattice, budget)
    return LifelongPlanner(lattice, budget)
