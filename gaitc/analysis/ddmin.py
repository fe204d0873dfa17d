"""Delta debugging: a 1-minimal subset that still fails a monotone test.

Zeller and Hildebrandt, "Simplifying and isolating failure-inducing input", IEEE TSE 28(2),
2002 (the ddmin algorithm). Here the "failure" is a property of a set of spec parts, such as
"these guarantees with all assumptions are unrealizable"; the result keeps the property and
loses it when any single element is dropped (every answer is checked by the caller's test).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import TypeVar

T = TypeVar("T")


def ddmin(items: Sequence[T], fails: Callable[[tuple[T, ...]], bool]) -> tuple[T, ...]:
    """A subsequence of ``items`` on which ``fails`` holds and which is 1-minimal.

    ``fails(tuple(items))`` must hold. ``fails`` is called on subsequences (in the original
    order); the algorithm is iterative, so long inputs need no deep recursion.
    """
    current = tuple(items)
    n = 2
    while len(current) >= 2:
        chunks = _split(current, n)
        reduced = False
        for chunk in chunks:  # reduce to a subset
            if fails(chunk):
                current, n, reduced = chunk, 2, True
                break
        if not reduced:
            for i in range(len(chunks)):  # reduce to a complement
                rest = tuple(x for j, c in enumerate(chunks) if j != i for x in c)
                if fails(rest):
                    current, n, reduced = rest, max(n - 1, 2), True
                    break
        if not reduced:
            if n >= len(current):
                break
            n = min(len(current), 2 * n)
    if len(current) == 1 and fails(()):
        return ()
    return current


def _split(items: tuple[T, ...], n: int) -> list[tuple[T, ...]]:
    size, extra = divmod(len(items), n)
    out: list[tuple[T, ...]] = []
    start = 0
    for i in range(n):
        end = start + size + (1 if i < extra else 0)
        if end > start:
            out.append(items[start:end])
        start = end
    return out
