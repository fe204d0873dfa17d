"""The kind of failure of an unrealizable spec, decided by solving sub-games.

* ``initial``: the system cannot even choose a legal initial state for some initial input
  the assumptions allow (its transition rules and goals removed, it still loses);
* ``safety``: without its goals it still loses: the environment can force it into a state
  with no legal move;
* ``liveness``: it keeps its transition rules for ever but the environment can keep it
  from some goal; each goal is tested alone, and the goals that are lost alone are named
  (when none is, only their combination is lost).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Final, Literal, get_args

from gaitc.analysis.oracle import Oracle
from gaitc.ir.spec import GR1Spec

Kind = Literal["initial", "safety", "liveness"]
KINDS: Final[tuple[Kind, ...]] = get_args(Kind)


@dataclass(frozen=True)
class Failure:
    """Why the system loses: the kind, and the goals (indices into ``sys_liveness``) that
    the environment can keep it from, each tested alone."""

    kind: Kind
    blocked_goals: tuple[int, ...] = ()


def without_goals(spec: GR1Spec) -> GR1Spec:
    """The safety game of ``spec``: the system only has to keep its transition rules."""
    return spec.with_sections(sys_liveness=())


def initial_only(spec: GR1Spec) -> GR1Spec:
    """The initial game: the system only has to pick an initial state (ρs and goals off)."""
    return spec.with_sections(sys_trans=(), sys_liveness=())


def with_one_goal(spec: GR1Spec, goal: int) -> GR1Spec:
    return spec.with_sections(sys_liveness=(spec.sys_liveness[goal],))


def classify(spec: GR1Spec, oracle: Oracle) -> Failure:
    """The :class:`Failure` of an unrealizable ``spec``."""
    if not oracle.realizable(initial_only(spec)):
        return Failure("initial")
    if not oracle.realizable(without_goals(spec)):
        return Failure("safety")
    blocked = tuple(j for j in range(len(spec.sys_liveness))
                    if not oracle.realizable(with_one_goal(spec, j)))
    return Failure("liveness", blocked)
