"""Independent check of a compact controller's assumption monitor against the spec's ρe.

A board that runs a compact controller on its own stops when its monitor (the ``assumed``
diagram) says the sensed inputs break the spec's environment assumptions.  That diagram is
part of what the controller file says, so it is proved with the rest: on every state a run
of the controller reaches (the symbolic verifier's least fixpoint,
:mod:`gaitc.verifier.symbolic`) and every input the fields can name, the monitor must equal
ρe, the conjunction of the spec's env_trans clauses, as translated by the verifier's own
:class:`~gaitc.verifier.logic.Logic`.  So the board stops at the first step that breaks an
assumption, and at no step that keeps them.  The first state where the two differ is
reported in the fields' words.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from typing import TYPE_CHECKING, Protocol

from gaitc.verifier.logic import Logic
from gaitc.verifier.symbolic import ReachCheck

if TYPE_CHECKING:
    from dd.cudd import BDD, Function


class FieldLike(Protocol):
    """What the check needs of a field (:class:`gaitc.core.vocabulary.Field` is one)."""

    @property
    def name(self) -> str: ...
    @property
    def is_input(self) -> bool: ...
    @property
    def labels(self) -> tuple[str, ...]: ...
    @property
    def bits(self) -> frozenset[str]: ...
    def cube(self, value: int, primed: bool = False) -> dict[str, bool]: ...
    def value_of(self, bits: Mapping[str, object], primed: bool = False) -> int | None: ...


def field_states(bdd: BDD, fields: Sequence[FieldLike]) -> Function:
    """Every field at one of its values, and every input at one of its next values."""
    out = bdd.true
    for f in fields:
        for primed in (False, True) if f.is_input else (False,):
            values = bdd.false
            for k in range(len(f.labels)):
                values |= bdd.cube(f.cube(k, primed))
            out &= values
    return out


def monitor_check(monitor_of: Callable[[BDD], Function], fields: Sequence[FieldLike]
                  ) -> ReachCheck:
    """The check that a monitor (``monitor_of(bdd)``, a BDD over current bits and the
    inputs' next bits) is ρe on the reachable states and every value of ``fields`` (see
    the module text), for :func:`~gaitc.verifier.symbolic.verify_symbolic`."""
    inputs = [f for f in fields if f.is_input]

    def check(logic: Logic, reached: Function) -> str | None:
        bdd = logic.bdd
        rho_e = bdd.true
        for _, u in logic.clauses("env_trans"):
            rho_e &= u
        monitor = monitor_of(bdd)
        here = reached & field_states(bdd, fields)
        differ = here & ((monitor & ~rho_e) | (rho_e & ~monitor))
        if differ == bdd.false:
            return None
        care = {b for f in fields for b in f.bits}
        care |= {b + "'" for f in inputs for b in f.bits}
        witness = next(bdd.pick_iter(differ, care_vars=care))
        now = ", ".join(f"{f.name}={_label(f, witness, False)}" for f in fields)
        chosen = ", ".join(f"{f.name}={_label(f, witness, True)}" for f in inputs)
        allowed = bdd.let(witness, monitor) == bdd.true
        return (f"the assumption monitor {'allows' if allowed else 'forbids'} what the "
                f"spec's assumptions (env_trans) {'forbid' if allowed else 'allow'}: from the "
                f"reachable state {now}, the environment choosing {chosen or 'nothing'}")

    return check


def _label(f: FieldLike, witness: dict[str, bool], primed: bool) -> str:
    value = f.value_of(witness, primed)
    return "?" if value is None else f.labels[value]
