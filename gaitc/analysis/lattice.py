"""Monotone searches over sets and vectors, with as few oracle calls as monotonicity allows.

Failures only hurt: if the task survives the failure of a set of legs it survives every
subset, and if a set is fatal so is every superset. The searches test candidates level by
level (a whole level at a time, so that a caller may test them in parallel), skip every
candidate that a known answer decides, and derive the rest of the lattice from the minimal
fatal sets. Health is the same upside down: more levels only help.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass

#: Tests many candidates at once (possibly in parallel); returns one bool per candidate.
Batch = Callable[[list[frozenset[str]]], list[bool]]


@dataclass(frozen=True)
class SetLattice:
    """The answer of :func:`fatal_sets`: sets are sorted tuples of element names."""

    minimal_fatal: tuple[tuple[str, ...], ...]
    maximal_survivable: tuple[tuple[str, ...], ...]
    tested: int


def _sorted_sets(sets: Sequence[frozenset[str]], order: Sequence[str]
                 ) -> tuple[tuple[str, ...], ...]:
    rank = {name: i for i, name in enumerate(order)}
    items = [tuple(sorted(s, key=rank.__getitem__)) for s in sets]
    return tuple(sorted(items, key=lambda t: (len(t), [rank[x] for x in t])))


def fatal_sets(elements: Sequence[str], fatal: Batch, max_size: int | None = None
               ) -> SetLattice:
    """Minimal fatal and maximal survivable subsets of ``elements`` under a monotone test.

    Level k tests only the k-sets with no fatal subset and all of whose (k-1)-subsets
    survived; ``max_size`` stops early (the maximal survivable sets are then those found
    up to that size).
    """
    limit = len(elements) if max_size is None else min(max_size, len(elements))
    minimal: list[frozenset[str]] = []
    survivors: set[frozenset[str]] = {frozenset()}
    tested = 1
    if fatal([frozenset()])[0]:
        return SetLattice(((),), (), tested)
    level: list[frozenset[str]] = [frozenset()]
    for _ in range(limit):
        candidates = sorted({s | {e} for s in level for e in elements if e not in s},
                            key=lambda s: sorted(elements.index(x) for x in s))
        candidates = [c for c in candidates
                      if all(c - {e} in survivors for e in c)
                      and not any(m <= c for m in minimal)]
        if not candidates:
            break
        answers = fatal(candidates)
        tested += len(candidates)
        level = []
        for candidate, is_fatal in zip(candidates, answers, strict=True):
            if is_fatal:
                minimal.append(candidate)
            else:
                survivors.add(candidate)
                level.append(candidate)
    maximal = [s for s in survivors if not any(s < t for t in survivors)]
    return SetLattice(_sorted_sets(minimal, elements), _sorted_sets(maximal, elements),
                      tested)


@dataclass(frozen=True)
class VectorFront:
    """Minimal good vectors within ``bound`` (each coordinate ``1..bound``)."""

    minimal: tuple[tuple[int, ...], ...]
    tested: int


MAX_VECTORS = 200_000  # the vector searches enumerate the box; beyond this, refuse


def _below(a: tuple[int, ...], b: tuple[int, ...]) -> bool:
    return all(x <= y for x, y in zip(a, b, strict=True))


def minimal_vectors(bounds: Sequence[int], good: Callable[[tuple[int, ...]], bool]
                    ) -> VectorFront:
    """The minimal vectors of an upward-closed set of vectors whose coordinate ``i`` ranges
    over ``1..bounds[i]`` (a uniform bound, or each leg's own levels).

    Vectors are visited smallest sum first; one that no answer so far decides is tested,
    then pushed down greedily to a minimal good vector (if good) or up to a maximal bad one
    (if bad). Every later vector above a minimal good or below a maximal bad one is
    decided without a call (the dualisation of Fredman and Khachiyan's setting, solved
    greedily: the calls grow with the size of the front, not of the box).
    """
    size = len(bounds)
    if math.prod(bounds) > MAX_VECTORS:
        raise ValueError(f"{math.prod(bounds):,} vectors are too many to search; lower the "
                         "bound")
    goods: list[tuple[int, ...]] = []
    bads: list[tuple[int, ...]] = []
    tested = 0

    def known(v: tuple[int, ...]) -> bool | None:
        if any(_below(g, v) for g in goods):
            return True
        if any(_below(v, b) for b in bads):
            return False
        return None

    def ask(v: tuple[int, ...]) -> bool:
        nonlocal tested
        answer = known(v)
        if answer is None:
            tested += 1
            answer = good(v)
        return answer

    def step(v: tuple[int, ...], i: int, by: int) -> tuple[int, ...]:
        return (*v[:i], v[i] + by, *v[i + 1:])

    for v in sorted(itertools.product(*(range(1, b + 1) for b in bounds)),
                    key=lambda w: (sum(w), w)):
        if known(v) is not None:
            continue
        if ask(v):
            for i in range(size):
                while v[i] > 1 and ask(step(v, i, -1)):
                    v = step(v, i, -1)
            goods.append(v)
        else:
            for i in range(size):
                while v[i] < bounds[i] and not ask(step(v, i, 1)):
                    v = step(v, i, 1)
            bads.append(v)
    return VectorFront(tuple(sorted(set(goods))), tested)


def minimal_of(vectors: frozenset[tuple[int, ...]] | set[tuple[int, ...]]
               ) -> tuple[tuple[int, ...], ...]:
    """The minimal elements of an upward-closed set given in full (one decrement each)."""
    out = []
    for v in vectors:
        if not any((*v[:i], v[i] - 1, *v[i + 1:]) in vectors for i in range(len(v))):
            out.append(v)
    return tuple(sorted(out))


def subsets_of_size(elements: Sequence[str], size: int) -> list[frozenset[str]]:
    return [frozenset(c) for c in itertools.combinations(elements, size)]
