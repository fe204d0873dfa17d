"""Minimal unrealizable cores: a smallest set of the spec's guarantees that still loses.

The units (:mod:`gaitc.analysis.units`) of the system's sections are reduced with ddmin
(:mod:`gaitc.analysis.ddmin`) under the test "these guarantees, the structural clauses and all
the assumptions are unrealizable". Dropping guarantees only frees the system, so the test is
monotone and the result is a core: unrealizable as it is, realizable without any one of its
units. The same search over the environment's units gives the assumptions that matter.
"""

from __future__ import annotations

from gaitc.analysis.ddmin import ddmin
from gaitc.analysis.oracle import Oracle
from gaitc.analysis.units import GUARANTEE_SECTIONS, Unit, keep_only, units
from gaitc.ir.spec import GR1Spec


def guarantee_core(spec: GR1Spec, oracle: Oracle, keep: tuple[Unit, ...] = ()
                   ) -> tuple[Unit, ...]:
    """A 1-minimal set of guarantee units that, with all assumptions, is unrealizable.

    ``spec`` must be unrealizable. An empty core means that the structural clauses alone
    (one region and one gait at a time) already lose. With ``keep`` (say the goal the
    explanation is about), the core is sought among those that hold those units: ddmin
    runs over the others with ``keep`` always in; a unit of ``keep`` that the result does
    not need is then dropped, so the core stays 1-minimal either way.
    """
    every = units(spec, GUARANTEE_SECTIONS)
    candidates = tuple(u for u in every if u not in keep)

    def loses(kept: tuple[Unit, ...]) -> bool:
        return not oracle.realizable(keep_only(spec, kept, GUARANTEE_SECTIONS))

    if loses(()):
        return ()
    if not keep:
        return ddmin(every, loses)
    found = ddmin(candidates, lambda kept: loses(keep + kept))  # the spec loses: all in
    core = [*keep, *found]
    for unit in keep:  # each kept unit must be needed too
        rest = tuple(u for u in core if u != unit)
        if loses(rest):
            core = list(rest)
    return tuple(u for u in every if u in core)


def variant_without(spec: GR1Spec, core: tuple[Unit, ...], dropped: Unit | None) -> GR1Spec:
    """The spec with the guarantees of ``core`` minus ``dropped`` (for checking a core)."""
    kept = tuple(u for u in core if u != dropped)
    return keep_only(spec, kept, GUARANTEE_SECTIONS)
