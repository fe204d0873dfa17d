"""Independent proof of a recovering controller's surprise handling (issue 52).

A compact controller with recovery tables (:mod:`gaitc.compact.recovery`) answers, besides
the inputs ρe allows, inputs that break ρe: a *recovery* move back into a state from which
its own play wins every goal, or the *entry* into a fallback that pursues fewer goals.  The
intermittent-violation reading of Ehlers and Topcu ("Resilience to intermittent assumption
violations in reactive synthesis", HSCC 2014) is what is proved here, on the closed loop of
:mod:`gaitc.verifier.symbolic` (its goal counter and fixpoints, Emerson and Lei, LICS 1986):

* the states reachable with ordinary moves and any number of recoveries, R*, from the
  controller's initial states;
* on R*: every input ρe allows has a move and every move keeps ρs; where the flag says a
  surprise is recoverable, the recovery move keeps ρs; and no state of R* starts a run of
  ordinary moves that meets every environment goal infinitely often but misses a system
  goal (so each recovery lands where the controller's own play wins: in its W);
* for each fallback, the same from the states its entries reach from R*, with its goals.

What W the solver computed is not used: the proof is of the controller's own moves.  Which
surprises the flags cover (that none recoverable is missed) is a property of the solver's
W; the tests compare it with :class:`gaitc.sim.recovery.Fallback` on every surprise.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

from gaitc.ir.bddfile import SymbolicController, materialize
from gaitc.ir.spec import GR1Spec, Semantics
from gaitc.verifier.strategy import MAX_PROBLEMS, VerificationReport
from gaitc.verifier.symbolic import _fair_avoiding, _Loop, _reachable

if TYPE_CHECKING:
    from dd.cudd import BDD, Function


@dataclass(frozen=True)
class FallbackRelations:
    """One fallback as BDDs of the verifier's manager: the goals it keeps (indices into the
    spec's □◇ guarantees), where it applies (s, x'), its entry moves (s, x', y') and per kept
    goal its move relation and goal function."""

    kept: tuple[int, ...]
    applies: Function
    entry: Function
    strategies: Sequence[Function]
    goals: Sequence[Function]


@dataclass(frozen=True)
class RecoveryRelations:
    """The surprise handling as BDDs: the recoverable flag (s, x'), the recovery moves
    (s, x', y') and the fallbacks, tried in order."""

    recoverable: Function
    recover: Function
    assumed: Function  # the assumption monitor (s, x'): must be ρe wherever a run can be
    fallbacks: Sequence[FallbackRelations] = field(default_factory=tuple)


def verify_recovery(spec: GR1Spec, ctrl: SymbolicController,
                    relations_of: Callable[[BDD], RecoveryRelations],
                    valid_inputs: Callable[[BDD], Function],
                    semantics: Semantics | None = None) -> VerificationReport:
    """Prove the surprise handling of ``ctrl`` (its ordinary moves, as
    :func:`gaitc.compact.controller.to_symbolic` gives them) with the relations
    ``relations_of(bdd)`` builds; ``valid_inputs(bdd)`` is the next inputs a sensor can
    report (every field at one of its values).  See the module text."""
    chosen = semantics or ctrl.semantics
    loop = _Loop(spec, ctrl)
    b = loop.bdd
    roots = materialize(b, ctrl)
    rel = relations_of(b)
    in_range = valid_inputs(b)
    rho_e, rho_s = loop.section("env_trans"), loop.section("sys_trans")
    theta = loop.section("env_init") & loop.section("sys_init")
    start = roots["sys_init"] & roots["winning"]
    if chosen == Semantics.ROBOTICS:
        init = roots["env_init"] & start & theta
    else:
        init = b.exist(set(loop.logic.outputs), roots["env_init"]) & start & theta
    init &= loop.counter(0)
    problems: list[str] = []
    all_goals = [u for _, u in loop.logic.clauses("sys_liveness")] or [b.true]
    surprise = ~rho_e & in_range
    normal, recovering = b.false, b.false
    for g, relation in enumerate(roots["strategies"]):
        advance = loop.advance(g, roots["goals"])
        normal |= loop.counter(g) & relation & rho_e & advance
        recovering |= loop.counter(g) & rel.recoverable & surprise & rel.recover & advance
    reach = _reachable(loop, init, normal | recovering)
    problems += _play(loop, reach, roots["strategies"], normal, all_goals, "")
    problems += _monitor(loop, reach & in_range, rel.assumed, "")
    if reach & rel.recoverable & surprise & rel.recover & ~rho_s != b.false:
        problems.append("a recovery move from a reachable state violates sys_trans")
    if reach & rel.recoverable & surprise & ~b.exist(loop.post_out, rel.recover) != b.false:
        problems.append("a surprise the flag calls recoverable has no recovery move")
    left = reach & surprise & ~rel.recoverable
    for fb in rel.fallbacks:
        here = left & fb.applies
        left &= ~fb.applies
        what = f" (fallback to goals {', '.join(str(j + 1) for j in fb.kept)})"
        if here & fb.entry & ~rho_s != b.false:
            problems.append(f"an entry move{what} violates sys_trans")
        if here & ~b.exist(loop.post_out, fb.entry) != b.false:
            problems.append(f"a surprise{what} has no entry move")
        landed = loop.image(b.exist(set(loop.g), here & fb.entry), b.true) & loop.counter(0)
        k_normal = b.false
        for g, relation in enumerate(fb.strategies):
            k_normal |= loop.counter(g) & relation & rho_e & loop.advance(g, list(fb.goals))
        k_reach = _reachable(loop, landed, k_normal)
        kept = [all_goals[j] for j in fb.kept]
        problems += _play(loop, k_reach, fb.strategies, k_normal, kept, what)
        problems += _monitor(loop, k_reach & in_range, rel.assumed, what)
    count = int(b.count(reach, nvars=len(loop.pre)))
    shown = problems[:MAX_PROBLEMS]
    return VerificationReport(ok=not shown, problems=tuple(shown), nodes=count,
                              semantics=chosen, symbolic=True)


def _play(loop: _Loop, reach: Function, strategies: Sequence[Function], edges: Function,
          goals: Sequence[Function], what: str) -> list[str]:
    """Completeness, safety and every goal of ``goals`` on the ordinary play from ``reach``."""
    b = loop.bdd
    rho_e, rho_s = loop.section("env_trans"), loop.section("sys_trans")
    inputs_ok = b.exist(loop.post_out, rho_e)
    problems = []
    for g, relation in enumerate(strategies):
        here = reach & loop.counter(g)
        offered = b.exist(loop.post_out, relation)
        if here & b.exist(loop.post_in, inputs_ok & ~offered) != b.false:
            problems.append(f"goal {g + 1}{what}: a state reachable with recoveries has an "
                            "input the assumptions allow but no move")
        if here & b.exist(loop.post_in | loop.post_out, relation & rho_e & ~rho_s) != b.false:
            problems.append(f"goal {g + 1}{what}: a move from a state reachable with "
                            "recoveries violates sys_trans")
    env_goals = loop.goals("env_liveness")
    moves = reach & edges
    for k, goal in enumerate(goals):
        if _fair_avoiding(loop, moves & ~goal, env_goals, reach) != b.false:
            problems.append(f"a state reachable with recoveries{what} starts a run that "
                            "satisfies every environment liveness assumption infinitely "
                            f"often but never goal {k + 1} of those pursued")
    return problems


def _monitor(loop: _Loop, here: Function, assumed: Function, what: str) -> list[str]:
    """The monitor must tell ρe from a surprise on every state a run can be in."""
    rho_e = loop.section("env_trans")
    if here & ((assumed & ~rho_e) | (rho_e & ~assumed)) != loop.bdd.false:
        return [f"the assumption monitor differs from env_trans on a state reachable with "
                f"recoveries{what}"]
    return []
