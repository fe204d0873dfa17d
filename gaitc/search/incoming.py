"""The incoming edges of the lattice nodes LPA* has generated, as sorted numpy runs.

LPA* (Koenig, Likhachev and Furcy 2004) recomputes a node's rhs as the minimum over its
predecessors; on the hybrid lattice (thesis 5.2.2) a node of a large gait graph has hundreds
of them.  Each expansion that generates a node's successors adds one chunk of (target,
source, edge) rows at once; chunks are sorted by target into runs, and runs of similar
length are merged (a log-structured store), so that the predecessors of many nodes are
found with a few binary searches and gathered in one pass, without a Python list per node.
An edge that moves to another target has its old row marked dead (:data:`DEAD`).
"""

from __future__ import annotations

import numpy as np

from gaitc.search.transitions import Ints

DEAD = -2  # the edge of a row that no longer exists (its cost slot is infinite)
_TAIL = 4096  # rows kept unsorted before they become a run


class IncomingEdges:
    """Rows (target, source, edge) with look-up by target."""

    def __init__(self, tail: int = _TAIL) -> None:
        self._limit = tail
        self._runs: list[tuple[Ints, Ints, Ints]] = []  # each sorted by target
        self._tail: list[tuple[Ints, Ints, Ints]] = []
        self._tail_rows = 0

    def __len__(self) -> int:
        return sum(len(r[0]) for r in self._runs) + self._tail_rows

    def add(self, targets: Ints, source: int, edges: Ints) -> None:
        """The edges of ``source`` into ``targets``."""
        if len(targets):
            self._tail.append(
                (targets.copy(), np.full(len(targets), source, np.int64), edges.copy())
            )
            self._tail_rows += len(targets)
            if self._tail_rows > self._limit:
                self._settle()

    def _settle(self) -> None:
        """Sort the tail into a run; merge runs while the last is at least half the one
        before (the runs shrink geometrically: few of them, each row merged O(log n) times)."""
        if self._tail:
            v, u, e = (np.concatenate(c) for c in zip(*self._tail, strict=True))
            order = np.argsort(v, kind="stable")
            self._runs.append((v[order], u[order], e[order]))
            self._tail, self._tail_rows = [], 0
        runs = self._runs
        while len(runs) >= 2 and 2 * len(runs[-1][0]) >= len(runs[-2][0]):
            b, a = runs.pop(), runs.pop()
            v, u, e = (np.concatenate((x, y)) for x, y in zip(a, b, strict=True))
            order = np.argsort(v, kind="stable")  # two sorted runs: a linear merge
            runs.append((v[order], u[order], e[order]))

    def _flat(self) -> list[tuple[Ints, Ints, Ints]]:
        """The tail as (at most) one chunk."""
        if len(self._tail) > 1:
            self._tail = [tuple(np.concatenate(c) for c in zip(*self._tail, strict=True))]  # type: ignore[list-item]
        return self._tail

    def of(self, targets: Ints) -> tuple[Ints, Ints, Ints]:
        """Every row into one of ``targets`` (distinct): (position in ``targets``, source,
        edge), dead rows included."""
        seg: list[Ints] = []
        src: list[Ints] = []
        via: list[Ints] = []
        order = np.argsort(targets)
        wanted = targets[order]
        for v, u, e in self._runs:
            lo = np.searchsorted(v, wanted)
            hi = np.searchsorted(v, wanted, side="right")
            counts = hi - lo
            total = int(counts.sum())
            if not total:
                continue
            # the row numbers lo[i] .. hi[i] - 1 of every target, in one array
            starts = np.repeat(lo - np.cumsum(counts) + counts, counts)
            rows = starts + np.arange(total)
            seg.append(np.repeat(order, counts))
            src.append(u[rows])
            via.append(e[rows])
        for v, u, e in self._flat():
            hit = np.isin(v, wanted)
            if hit.any():
                seg.append(order[np.searchsorted(wanted, v[hit])])
                src.append(u[hit])
                via.append(e[hit])
        if not seg:
            empty = np.zeros(0, np.int64)
            return empty, empty, empty
        return np.concatenate(seg), np.concatenate(src), np.concatenate(via)

    def kill(self, target: int, source: int, edge: int) -> None:
        """Mark the row (target, source, edge) dead."""
        for v, u, e in self._runs:
            lo = int(np.searchsorted(v, target))
            hi = int(np.searchsorted(v, target, side="right"))
            if lo < hi:
                hit = np.nonzero((u[lo:hi] == source) & (e[lo:hi] == edge))[0]
                e[lo + hit] = DEAD
        for v, u, e in self._flat():
            e[(v == target) & (u == source) & (e == edge)] = DEAD
