"""Integer comparisons as gr1c reads them: one variable against a number.

gr1c compares a variable with a number and nothing else (its ``doc/spc_format.md``).  An IR
comparison has sums on both sides, so ``left - right`` is ``Σ cᵢ·vᵢ + k`` and the atom says
``Σ cᵢ·vᵢ + k op 0``.  :func:`expand_comparison` lists the values that satisfy it, one
variable at a time: fixing the first variable at a value leaves an atom of the same kind over
the others with a new constant, so the answers are memoized by constant, and the values of
the first variable that lead to the same answer are grouped.  The last variable's values are
found without listing them (:func:`solutions`: a point, or one run by bisection, since
``c·v + k`` is monotone).  Each group of values, and the
satisfying values of the last variable, are written as runs of consecutive values (``v = c``,
``v <= b``, ``v >= a``, ``v >= a & v <= b``), or as the negation of the complement's runs
when that is shorter; a comparison of one variable with a number comes out as itself.
The result uses only such atoms, with numbers inside each variable's range.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from typing import Final

from gaitc.diagnostics import PeerFormatError
from gaitc.ir.formula import (
    FALSE,
    TRUE,
    Add,
    And,
    Compare,
    Expr,
    IntConst,
    IntVar,
    Not,
    Term,
    conj,
    disj,
    term_kind,
    unreachable,
)
from gaitc.ir.traversal import Node, fold

#: Each integer variable's inclusive range, by name.
Domains = Mapping[str, tuple[int, int]]
#: A variable of a comparison: its name and whether it is the next-state copy.
Key = tuple[str, bool]

#: The most combinations of values one comparison may range over (the product of the sizes
#: of its variables' ranges); a larger one is a PeerFormatError.
LIMIT: Final = 1 << 16

_TESTS: Final[dict[str, Callable[[int], bool]]] = {
    "=": lambda n: n == 0, "!=": lambda n: n != 0, "<": lambda n: n < 0,
    "<=": lambda n: n <= 0, ">": lambda n: n > 0, ">=": lambda n: n >= 0,
}


def linear_form(node: Compare) -> tuple[dict[Key, int], int]:
    """``(coefficients, k)`` with ``left - right = Σ coefficients[v]·v + k``; variables in
    the order they first appear, those whose coefficient cancels left out."""
    left, k_left = _sum(node.left)
    right, k_right = _sum(node.right)
    total = dict(left)
    for key, c in right.items():
        total[key] = total.get(key, 0) - c
    return {key: c for key, c in total.items() if c != 0}, k_left - k_right


def _sum(term: Term) -> tuple[dict[Key, int], int]:
    def combine(node: Node, kids: list[tuple[dict[Key, int], int]]
                ) -> tuple[dict[Key, int], int]:
        kind = term_kind(node)
        match kind:
            case IntConst():
                return {}, kind.value
            case IntVar():
                return {(kind.name, kind.primed): 1}, 0
            case Add():
                (a, ka), (b, kb) = kids
                merged = dict(a)
                for key, c in b.items():
                    merged[key] = merged.get(key, 0) + c
                return merged, ka + kb
            case _:
                unreachable(kind)

    return fold(term, combine)


def expand_comparison(node: Compare, domains: Domains, limit: int = LIMIT) -> Expr:
    """An equivalent formula over comparisons of one variable with a number in its range
    (``=``, ``!=``, ``<=``, ``>=``), given each variable's range in ``domains``.

    Equivalent on every valuation in range.  Raises
    :class:`~gaitc.diagnostics.PeerFormatError` when the variables' ranges together hold
    more than ``limit`` combinations of values.
    """
    coefficients, k = linear_form(node)
    keys = list(coefficients)
    space = 1
    for name, _ in keys:
        low, high = domains[name]
        space *= high - low + 1
    if space > limit:
        shown = ", ".join(name + ("'" if primed else "") for name, primed in keys)
        raise PeerFormatError(
            f"a comparison over {shown} ranges over {space} combinations of values, more "
            f"than the {limit} gr1c's translation lists",
            node.span,
            hint="gr1c compares a variable with a number only, so a comparison of several "
            "variables is written as the values that satisfy it; narrow the ranges",
        )
    op = node.op
    last = len(keys) - 1
    memo: dict[tuple[int, int], Expr] = {}

    def solve(index: int, constant: int) -> Expr:
        """The atom over ``keys[index:]`` with the others fixed (their sum: ``constant``)."""
        found = memo.get((index, constant))
        if found is not None:
            return found
        key = keys[index]
        low, high = domains[key[0]]
        c = coefficients[key]
        if index == last:
            result = membership(key, solutions(c, constant, op, low, high), low, high)
        else:
            groups: dict[Expr, list[int]] = {}
            for value in range(low, high + 1):
                groups.setdefault(solve(index + 1, constant + c * value), []).append(value)
            result = disj(conj(part for part in (membership(key, _runs(values), low, high),
                                                 rest) if part != TRUE)
                          for rest, values in groups.items() if rest != FALSE)
        memo[(index, constant)] = result
        return result

    if not keys:
        return TRUE if _TESTS[op](k) else FALSE
    return solve(0, k)


def solutions(c: int, k: int, op: str, low: int, high: int) -> list[tuple[int, int]]:
    """The runs of ``v`` in ``low..high`` with ``c·v + k op 0`` (``c`` not 0): one point or
    its complement for ``=``/``!=``; otherwise ``c·v + k`` is monotone in ``v``, so the
    values form one run, found by bisection."""
    if op in ("=", "!="):
        point = -k // c
        hit = c * point + k == 0 and low <= point <= high
        if op == "=":
            return [(point, point)] if hit else []
        if not hit:
            return [(low, high)]
        return [r for r in ((low, point - 1), (point + 1, high)) if r[0] <= r[1]]
    test = _TESTS[op]
    holds_low, holds_high = test(c * low + k), test(c * high + k)
    if holds_low == holds_high:
        return [(low, high)] if holds_low else []
    a, b = low, high  # test differs at a and b: find the last value like a
    while b - a > 1:
        middle = (a + b) // 2
        if test(c * middle + k) == holds_low:
            a = middle
        else:
            b = middle
    return [(low, a)] if holds_low else [(b, high)]


def membership(key: Key, runs: list[tuple[int, int]], low: int, high: int) -> Expr:
    """``v`` in the ``runs`` of consecutive values (ascending, disjoint, not adjacent, in
    ``low..high``): the runs, or the negation of the complement's runs when fewer atoms."""
    if not runs:
        return FALSE
    if runs == [(low, high)]:
        return TRUE
    outside = _complement(runs, low, high)
    if _atoms(outside, low, high) >= _atoms(runs, low, high):
        return disj(_run(key, run, low, high) for run in runs)
    if len(outside) == 1 and outside[0][0] == outside[0][1]:
        return Compare("!=", IntVar(*key), IntConst(outside[0][0]))
    return Not(disj(_run(key, run, low, high) for run in outside))


def _complement(runs: list[tuple[int, int]], low: int, high: int) -> list[tuple[int, int]]:
    out: list[tuple[int, int]] = []
    start = low
    for a, b in runs:
        if a > start:
            out.append((start, a - 1))
        start = b + 1
    if start <= high:
        out.append((start, high))
    return out


def _runs(values: list[int]) -> list[tuple[int, int]]:
    out: list[tuple[int, int]] = []
    for v in values:
        if out and out[-1][1] == v - 1:
            out[-1] = (out[-1][0], v)
        else:
            out.append((v, v))
    return out


def _atoms(runs: list[tuple[int, int]], low: int, high: int) -> int:
    return sum(1 if a in (b, low) or b == high else 2 for a, b in runs)


def _run(key: Key, run: tuple[int, int], low: int, high: int) -> Expr:
    a, b = run
    var = IntVar(*key)
    if a == b:
        return Compare("=", var, IntConst(a))
    if a == low:
        return Compare("<=", var, IntConst(b))
    if b == high:
        return Compare(">=", var, IntConst(a))
    return And((Compare(">=", var, IntConst(a)), Compare("<=", var, IntConst(b))))

