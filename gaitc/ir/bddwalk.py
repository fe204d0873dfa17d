"""Reading answers off BDDs: canonical assignments and evaluation by a walk from the root.

Shared by the solver's extraction (:mod:`gaitc.solver.strategy`) and the runtime of symbolic
controllers (:mod:`gaitc.sim.symbolic_view`), so that both pick the very same move: the
smallest assignment in the manager's variable order.  Works on any ``dd.cudd`` manager.
"""

from __future__ import annotations

import itertools
import operator
from collections.abc import Callable, Collection, Mapping, Sequence
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from dd.cudd import BDD, Function

State = tuple[int, ...]


def all_assignments(bdd: BDD, u: Function, bits: Sequence[str]) -> list[State]:
    """Every assignment to ``bits`` (a superset of ``u``'s support), sorted."""
    if u == bdd.false:
        return []
    out = {tuple(int(a[b]) for b in bits) for a in bdd.pick_iter(u, care_vars=set(bits))}
    return sorted(out)


def first_assignment(bdd: BDD, u: Function, bits: Sequence[str],
                     rank: Mapping[str, int] | None = None) -> State | None:
    """The smallest assignment to ``bits`` inside ``u`` (None if empty), in ``bits`` order.

    Smallest with the bits compared in ``rank`` order (default: as listed), the first bit
    most significant.  When the manager's order agrees, a walk from the root that takes the
    0-branch whenever it is not empty finds it in one step per level; otherwise each bit is
    fixed in turn by a cofactor, so the answer never depends on the current BDD order.
    ``u`` must not depend on variables outside ``bits``.
    """
    false = bdd.false
    if u == false:
        return None
    ordered = list(bits) if rank is None else sorted(bits, key=rank.__getitem__)
    levels = [bdd.level_of_var(b) for b in ordered]
    if any(a > b for a, b in itertools.pairwise(levels)):
        chosen: dict[str, int] = {}
        for bit in ordered:
            low = bdd.let({bit: False}, u)
            chosen[bit] = int(low == false)
            u = bdd.let({bit: True}, u) if chosen[bit] else low
        if u != bdd.true:
            raise ValueError("smallest: the function depends on bits outside those chosen")
        return tuple(chosen[b] for b in bits)
    wanted = set(bits)
    found: dict[str, int] = {}
    while (var := u.var) is not None:
        if var not in wanted:
            raise ValueError(f"smallest: {var!r} is not among the bits to choose")
        low, high = (~u.low, ~u.high) if u.negated else (u.low, u.high)
        if low != false:
            u = low
        else:
            found[var] = 1
            u = high
    return tuple(found.get(b, 0) for b in bits)


def cofactor(bdd: BDD, values: dict[str, bool], u: Function) -> Function:
    """``u`` with the variables ``values`` assigns set to their values; ``u`` itself when
    it assigns none (dd would log that call as one without effect)."""
    return bdd.let(values, u) if values else u


class Cofactors:
    """The cofactors of one BDD ``u`` at assignments to the variables ``fixed``, remembered
    by the values of those of ``u``'s support: an extraction asks for the same few at
    thousands of states (a move cost over one leg's health, a goal over one region), and a
    cofactor costs a cube and a CUDD call (about 20-30 microseconds) where the lookup costs
    one tuple.  At most ``limit`` of them are kept (then the memory starts again)."""

    def __init__(self, bdd: BDD, u: Function, fixed: Collection[str], limit: int = 100_000) -> None:
        self.bdd, self.u, self.limit = bdd, u, limit
        self.names = tuple(sorted(bdd.support(u) & set(fixed)))
        self.key: Callable[[Mapping[str, bool]], Any] = (
            operator.itemgetter(*self.names) if self.names else lambda _: ())
        self.known: dict[Any, Function] = {}

    def at(self, values: Mapping[str, bool]) -> Function:
        """``u`` with the variables ``fixed`` set to their ``values`` (which has them all)."""
        key = self.key(values)
        found = self.known.get(key)
        if found is None:
            if len(self.known) >= self.limit:
                self.known.clear()
            found = self.known[key] = cofactor(self.bdd, {n: values[n] for n in self.names},
                                               self.u)
        return found


def holds_at(u: Function, values: Mapping[str, bool]) -> bool:
    """Whether ``u`` is true at ``values`` (which assigns every variable of its support)."""
    negated = False
    while u.var is not None:
        negated ^= u.negated
        u = u.high if values[u.var] else u.low
    return bool((u == u.bdd.true) != negated)
