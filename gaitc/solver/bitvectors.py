"""Unsigned bit-vector arithmetic over BDDs: sums and comparisons of integer variables.

Integers are little-endian vectors of BDDs (SLUGS's encoding, see gaitc.solver.symbolic); these
are the textbook ripple-carry adder and comparator circuits.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from dd.cudd import BDD
    from dd.cudd import Function as BDDNode


def xor(u: BDDNode, v: BDDNode, bdd: BDD) -> BDDNode:
    return bdd.ite(u, ~v, v)


def add(a: list[BDDNode], b: list[BDDNode], bdd: BDD) -> list[BDDNode]:
    """Ripple-carry sum of two unsigned bit vectors; one bit wider than the longer one."""
    n = max(len(a), len(b))
    a = a + [bdd.false] * (n - len(a))
    b = b + [bdd.false] * (n - len(b))
    carry = bdd.false
    out: list[BDDNode] = []
    for x, y in zip(a, b, strict=True):
        half = xor(x, y, bdd)
        out.append(xor(half, carry, bdd))
        carry = (x & y) | (carry & half)
    out.append(carry)
    return out


def less(a: list[BDDNode], b: list[BDDNode], bdd: BDD) -> BDDNode:
    """Unsigned ``a < b`` for bit vectors of equal length (little-endian)."""
    n = max(len(a), len(b))
    a = a + [bdd.false] * (n - len(a))
    b = b + [bdd.false] * (n - len(b))
    lt = bdd.false
    for x, y in zip(a, b, strict=True):
        lt = (~x & y) | (~xor(x, y, bdd) & lt)
    return lt
