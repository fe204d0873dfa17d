"""The jump a surprise makes: at one controller node, the events that would break ρe
there, the inputs an event stands for, and where the run goes after it (:class:`Jump`).
``simulate --violate`` and ``drive`` (inside :meth:`gaitc.sim.simulator.Simulator.run`)
and the player's "break an assumption" moves all jump through :func:`jump`.

The recovery decision is :meth:`gaitc.sim.recovery.Fallback.enter`, after Ehlers and
Topcu ("Resilience to intermittent assumption violations in reactive synthesis", HSCC
2014): the surprise is a jump of the game, after which the run goes on from the winning
region of all goals, of fewer goals, or towards a cache.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING

from gaitc.core.changes import Change, HazardSwitch, LegFails, LegWears
from gaitc.core.modes import Outcome
from gaitc.sim.domain import Domain, Goal
from gaitc.sim.environments import Request
from gaitc.sim.events import (
    Event,
    Surprise,
    broken_words,
    change_words,
    performed,
)
from gaitc.sim.run import Step
from gaitc.solver.progress import goal_titles

if TYPE_CHECKING:
    from gaitc.sim.recovery import Entry, Fallback
    from gaitc.sim.simulator import Simulator
    from gaitc.sim.strategy import StrategyView

#: The section of the spec whose clauses a surprise breaks (ρe).
ASSUMPTIONS = "env_trans"


@dataclass(frozen=True)
class Breaking:
    """An event the assumptions forbid at a node: its words, its inputs, and the first
    assumption it breaks in the robot's words (``L5 failed while not in use (eq. 3.5,
    line 34)``)."""

    event: Event
    request: Request
    breaks: str


def forced(sim: Simulator, node: int, event: Event) -> Request:
    """The inputs of ``event`` performed at ``node`` of ``sim``'s controller, laid onto a
    move the assumptions allow there (:func:`gaitc.sim.events.performed`), so that only
    the event itself can break an assumption; inputs the robot's state does not name are
    that move's (the node's own when it has no moves)."""
    moves = sim.moves(node)
    state, base = performed(event, sim.state(node), [m.state for m in moves], sim.domain)
    rest = (sim.strategy.valuation(node) if base is None
            else dict(zip(sim.strategy.inputs, moves[base].inputs, strict=True)))
    values = sim.domain.encode(state)
    return Request(tuple(int(values.get(name, rest[name])) for name in sim.strategy.inputs),
                   event.words)


def candidates(domain: Domain) -> list[Change]:
    """The changes a surprise may make: each leg failing and losing a level, each hazard
    set switched on and off."""
    out: list[Change] = [c for leg in domain.legs for c in (LegFails(leg), LegWears(leg))]
    out.extend(HazardSwitch(name, on) for name in domain.hazard_regions for on in (True, False))
    return out


def breaking(sim: Simulator, node: int, index: int = 0) -> tuple[Breaking, ...]:
    """The events that break an assumption at ``node`` (step ``index`` is the step they
    would be performed at, for the clause's report): for each leg ``fail L`` and ``degrade
    L``, then ``switch H on`` / ``switch H off`` for each hazard set, leaving out events
    that change nothing, those the controller accepts, and those giving the inputs of an
    event listed before them (``degrade L`` at level 2 is ``fail L``)."""
    state = sim.state(node)
    moves = sim.moves(node)
    accepted = {m.inputs for m in moves}
    allowed = [m.state for m in moves]
    values = sim.strategy.values[node]
    seen: set[tuple[int, ...]] = set()
    found: list[Breaking] = []
    for change in candidates(sim.domain):
        event = Event((change,))
        after = event.apply(state, sim.domain)
        if after == state:
            continue
        request = forced(sim, node, event)
        if request.inputs in accepted or request.inputs in seen:
            continue
        seen.add(request.inputs)
        inputs = dict(zip(sim.strategy.inputs, request.inputs, strict=True))
        failed = sim.monitor.failed_assumptions(values, inputs)
        if not failed:
            continue
        broken = [sim.monitor.violation(index, ASSUMPTIONS, i) for i in failed]
        done = sim.after(node, inputs)
        found.append(Breaking(event, request,
                              broken_words(state, done, sim.domain, broken, allowed)))
    return tuple(found)


def recover(sim: Simulator, fallback: Fallback, index: int, node: int, request: Request,
            pursuing: int) -> tuple[Surprise, Entry]:
    """Where a run goes after ``request`` at ``node`` of ``sim``'s controller broke an
    assumption at step ``index``, the robot pursuing goal ``pursuing`` (an index into the
    spec's □◇ guarantees), and the record of it (:class:`Surprise`, as ``simulate`` writes
    it): the entry into the fallback strategy that :meth:`Fallback.enter` decides."""
    names = dict(zip(sim.strategy.inputs, request.inputs, strict=True))
    values = sim.strategy.values[node]
    entry = fallback.enter(values, names, pursuing)
    before = sim.state(node)
    after = sim.after(node, names)
    broken = [sim.monitor.violation(index, ASSUMPTIONS, i)
              for i in sim.monitor.failed_assumptions(values, names)]
    allowed = [m.state for m in sim.moves(node)]
    words = broken_words(before, after, sim.domain, broken, allowed)
    first = next((v for v in broken if v.span is not None), broken[0] if broken else None)
    titles = goal_titles(sim.monitor.spec)
    kept = tuple(titles[j] for j in entry.kept)
    lost = tuple(t for j, t in enumerate(titles) if j not in entry.kept)
    change = ", ".join(change_words(before, after, sim.domain, allowed)) or "this event"
    match entry.outcome:
        case Outcome.RECOVERED:
            note = "recovered: the state is still winning; every goal is pursued"
        case Outcome.DEGRADED:
            note = (f"degraded: still pursuing {', '.join(kept)}; {', '.join(lost)} "
                    f"{'is' if len(lost) == 1 else 'are'} out of reach after {change}")
        case _:
            where = (f"heading for cache {' or '.join(entry.cache)} to stop there"
                     if entry.node is not None else "the robot stops where it is")
            note = f"stopped: no goal is reachable after {change}; {where}"
    surprise = Surprise(index, request.what or "an input outside the assumptions",
                        words or None, clause=None if first is None else first.rule,
                        line=None if first is None or first.span is None else str(first.span),
                        outcome=entry.outcome, kept=kept, lost=lost, note=note)
    return surprise, entry


@dataclass(frozen=True)
class Jump:
    """Where a run goes after a surprise: its record, and the controller, node, goals (with
    the index of the one pursued) and caches the run goes on with; ``sim`` None when the
    robot stops where it is.  Every front end that steps a controller through surprises
    (``simulate`` and ``drive`` through :meth:`gaitc.sim.simulator.Simulator.run`, the
    player) takes the same jump."""

    surprise: Surprise
    sim: Simulator | None
    node: int | None
    goals: tuple[Goal, ...]
    goal: int
    caches: tuple[str, ...]


def jump(sim: Simulator, fallback: Fallback, index: int, node: int, request: Request,
         pursuing: int, simulator: Callable[[StrategyView], Simulator]) -> Jump:
    """The jump ``request`` makes at ``node`` of ``sim``'s controller, where it broke an
    assumption at step ``index`` with the robot pursuing goal ``pursuing`` (an index into
    the spec's □◇ guarantees): :func:`recover`'s entry, with the fallback strategy run by
    ``simulator`` and the goal pursued kept when the fallback keeps it."""
    surprise, entry = recover(sim, fallback, index, node, request, pursuing)
    if entry.strategy is None or entry.node is None:
        return Jump(surprise, None, None, (), 0, entry.cache)
    goals = tuple(sim.domain.goals[j] for j in entry.kept)
    goal = entry.kept.index(pursuing) if pursuing in entry.kept else 0
    return Jump(surprise, simulator(entry.strategy), entry.node, goals, goal, entry.cache)


def entered(sim: Simulator, index: int, node: int, previous: Step | None) -> Step:
    """Step ``index`` at ``node`` of ``sim``'s controller after ``previous``, a state of
    another controller (the run jumped here after a surprise)."""
    return sim.step(index, node, previous, foreign=True)
