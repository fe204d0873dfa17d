"""Surprises: environment events that may break the spec's assumptions, and their words.

A surprise is written in the player's move words (:mod:`gaitc.play.words`): ``fail L5``,
``degrade L3``, ``degrade L3 by 2``, ``repair L2``, ``switch spill on``, ``switch spill off``.
``simulate --violate STEP:EVENT`` makes the environment perform one at a step whatever the
assumptions ρe say.  :func:`broken_words` tells a move that breaks ρe in the robot's terms
("L5 failed while not in use (eq. 3.5, line 23)"): what changed that the clause forbids,
with the clause's equation and source line, the detection half of issue 52; the recovery
half is :mod:`gaitc.sim.recovery`.
"""

from __future__ import annotations

import re
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

from gaitc.core.changes import (
    Change,
    HazardSwitch,
    LegFails,
    LegRepaired,
    LegWears,
    active_after,
    between,
    conflict,
    leg_level,
    parse_changes,
    subject,
)
from gaitc.core.changes import words as change_words_of
from gaitc.core.modes import Outcome
from gaitc.diagnostics import Span, UsageError
from gaitc.ir.formula import unreachable
from gaitc.sim.domain import Domain, State
from gaitc.sim.monitor import Violation

_EQUATION = re.compile(r"^(eq\. [0-9.]+|mutex|init)")


#: The note of an event that broke no assumption (``simulate --violate``, ``drive``).
ALLOWED_NOTE = "allowed: the assumptions allow this event; the controller answered it"


@dataclass(frozen=True)
class Surprise:
    """One event of a run that the environment performed (``violations`` in run files and
    ``--json``): the step, the event in move words, the first assumption it broke in the
    robot's words with the clause's rule and source, and what became of the run."""

    step: int
    event: str
    assumption: str | None  # None: the event broke no assumption
    clause: str | None = None  # the broken clause's rule
    line: str | None = None  # file:line:col of the clause, when it has a source
    outcome: Outcome = Outcome.ALLOWED
    kept: tuple[str, ...] = ()  # the goals still pursued
    lost: tuple[str, ...] = ()  # the goals given up
    note: str = ""  # the outcome in words

    def words(self) -> str:
        """The surprise as the run report prints it."""
        head = f"step {self.step}: {self.event}"
        if self.assumption:
            head = f"step {self.step}: {self.assumption}"
        return f"{head}; {self.note}" if self.note else head

    def to_json(self) -> dict[str, Any]:
        return {"step": self.step, "event": self.event, "assumption": self.assumption,
                "clause": self.clause, "line": self.line, "outcome": str(self.outcome),
                "goals_kept": list(self.kept), "goals_lost": list(self.lost),
                "note": self.note}

    @classmethod
    def from_json(cls, data: Any) -> Surprise:
        """A surprise read back from a run file (KeyError/TypeError/ValueError on a bad one)."""
        def text(key: str) -> str | None:
            return None if data.get(key) is None else str(data[key])

        return cls(int(data["step"]), str(data["event"]), text("assumption"),
                   clause=text("clause"), line=text("line"), outcome=Outcome(data["outcome"]),
                   kept=tuple(str(g) for g in data.get("goals_kept", ())),
                   lost=tuple(str(g) for g in data.get("goals_lost", ())),
                   note=str(data.get("note", "")))


@dataclass(frozen=True)
class Event:
    """What the environment does at one step: one or more changes
    (:mod:`gaitc.core.changes`: legs failing, losing levels or repaired, a hazard set
    switched), with the words they were given in (by default the changes' own)."""

    changes: tuple[Change, ...]
    text: str | None = None

    @property
    def words(self) -> str:
        return self.text if self.text is not None else change_words_of(self.changes)

    def apply(self, state: State, domain: Domain) -> State:
        """The state after the event: the legs' levels and the hazard changed, the robot's
        region and gait as they were (the robot has not answered yet)."""
        return self.onto(state, state, domain)

    def onto(self, base: State, now: State, domain: Domain) -> State:
        """``base`` (what the environment would do anyway at ``now``) with the event's own
        changes: a failed leg at level 1, a degraded one ``lost`` levels below its level at
        ``now``, a repaired one at full health (or the level named), the hazard switched;
        everything else as in ``base``."""
        levels = dict(base.health)
        old = dict(now.health)
        for change in self.changes:
            if not isinstance(change, HazardSwitch):
                levels[change.leg] = leg_level(change, old[change.leg], domain.full[change.leg])
        hazard = active_after(self.changes, base.hazard)
        return State(base.region, base.gait, tuple((leg, levels[leg]) for leg in domain.legs),
                     hazard)


def differences(a: State, b: State) -> int:
    """How many of the environment's parts (legs' levels, the hazard) differ in ``a`` and
    ``b``."""
    legs = sum(x != y for (_, x), (_, y) in zip(a.health, b.health, strict=True))
    return legs + int(a.hazard != b.hazard)


def performed(event: Event, now: State, allowed: Sequence[State],
              domain: Domain) -> tuple[State, int | None]:
    """The state ``event`` performed at ``now`` leaves, the rest of the environment's move
    being one the assumptions allow, so that only the event itself can break one (a hazard
    switched on in a cache still has the cache reset every leg); and the index of that move
    in ``allowed`` (the states of the moves the controller accepts at ``now``).

    The event is laid onto each allowed move (:meth:`Event.onto`); the result preferred is
    one that is allowed itself, then one the event changes least, then one closest to
    ``event.apply(now)`` (the levels and hazard as they were), then the first.  Without
    allowed moves it is ``event.apply(now)``, with no index."""
    naive = event.apply(now, domain)
    accepted = {(s.health, s.hazard) for s in allowed}
    if not allowed or (naive.health, naive.hazard) in accepted:
        return naive, None
    best: tuple[tuple[int, int, int], State] | None = None
    for rank, base in enumerate(allowed):
        state = event.onto(base, now, domain)
        broken = 0 if (state.health, state.hazard) in accepted else 1 + differences(state, base)
        key = (broken, differences(state, naive), rank)
        if best is None or key < best[0]:
            best = (key, state)
    assert best is not None
    return best[1], best[0][2]


@dataclass(frozen=True)
class Planned:
    """An event planned for a step (``--violate STEP:EVENT``)."""

    step: int
    event: Event


def parse_event(text: str, domain: Domain, where: str = "--violate") -> Event:
    """An event from the player's move words, several of them joined by commas as the
    player writes a move (``fail L1, degrade L3``), read by
    :func:`gaitc.core.changes.parse_changes`: an unknown word, leg or hazard, or two
    changes of one leg or hazard, is a :class:`UsageError` naming ``where`` and what is
    accepted."""
    return Event(parse_changes(text, domain.legs, tuple(domain.hazard_regions), where), text)


def combined(events: Sequence[Event], where: str, text: str | None = None) -> Event:
    """One event doing what each of ``events`` does at the same step (``text`` its words,
    by default theirs joined by commas); two changes that cannot happen at one step
    (:func:`gaitc.core.changes.conflict`) are a :class:`UsageError` naming ``where``."""
    words = text if text is not None else ", ".join(e.words for e in events)
    seen: list[tuple[Change, Event]] = []
    for event in events:
        for change in event.changes:
            clash = next((e for c, e in seen if conflict(c, change)), None)
            if clash is not None:
                thing = subject(change)
                thing = thing if thing == "the hazard" else f"leg {thing}"
                raise UsageError(f"{where} '{words}': '{clash.words}' and '{event.words}' "
                                 f"both change {thing}; give one of them")
            seen.append((change, event))
    return Event(tuple(c for e in events for c in e.changes), words)


def parse_planned(text: str, domain: Domain) -> Planned:
    """``STEP:EVENT`` (``12:fail L5``) as a planned event; STEP counts from 1 (step 0 is the
    first state, which the initial assumptions decide)."""
    step, sep, rest = text.partition(":")
    if not sep or not step.strip().isdigit() or int(step) < 1:
        raise UsageError(f"--violate '{text}': write STEP:EVENT with STEP a step number from 1, "
                         "e.g. --violate '12:fail L5'")
    return Planned(int(step), parse_event(rest.strip(), domain))


def plan(texts: Sequence[str], domain: Domain) -> dict[int, Event]:
    """The events of several ``--violate`` options by step; events given for one step are
    performed together (:func:`combined`)."""
    by_step: dict[int, list[Event]] = {}
    for text in texts:
        planned = parse_planned(text, domain)
        by_step.setdefault(planned.step, []).append(planned.event)
    return {step: events[0] if len(events) == 1
            else combined(events, f"--violate at step {step}")
            for step, events in by_step.items()}


def equation(rule: str) -> str:
    """The equation a clause's rule cites (``eq. 3.5``), or the rule itself."""
    found = _EQUATION.match(rule)
    return found.group(1) if found else rule


def _where(violation: Violation) -> str:
    span = violation.span
    return f", line {span.line}" if isinstance(span, Span) else ""


def change_words(before: State, after: State, domain: Domain,
                 allowed: Sequence[State] = ()) -> list[str]:
    """What the environment changed from ``before`` to ``after`` that the gait of ``before``
    does not explain, in the robot's words, one per change of
    :func:`gaitc.core.changes.between` (a leg in use losing one level is told only when
    nothing else changed, a cache's reset never, a hazard switched as one of the ``allowed``
    moves switches it neither)."""
    used = set(domain.legs_used(before.gait))
    in_cache = before.region in domain.model.caches
    old = dict(before.health)
    changes = between(old, dict(after.health), domain.full, before.hazard, after.hazard)
    out: list[str] = []
    usual: list[str] = []  # what eq. 3.5 allows: a leg in use losing one level
    hazard: list[str] = []  # told after the legs
    switched = before.hazard != after.hazard and after.hazard not in {s.hazard for s in allowed}
    for change in changes:
        match change:
            case HazardSwitch(name, on):
                if switched and on == (after.hazard is not None):
                    hazard.append(f"hazard {name} switched {'on' if on else 'off'}")
            case LegRepaired(leg, level):
                if not in_cache:
                    out.append(f"{leg} was repaired outside a cache")
                elif level is not None:  # a cache's reset to full health is eq. 3.6
                    out.append(f"{leg} went up to level {level}")
            case LegFails(leg) | LegWears(leg):
                lost = old[leg] - leg_level(change, old[leg], domain.full[leg])
                what = "failed" if isinstance(change, LegFails) else (
                    "lost a level" if lost == 1 else f"lost {lost} levels")
                if in_cache:
                    out.append(f"{leg} {what} in cache {before.region}")
                elif leg not in used:
                    out.append(f"{leg} {what} while not in use")
                elif lost > 1:
                    out.append(f"{leg} dropped {lost} levels in one move"
                               + (" and failed" if isinstance(change, LegFails) else ""))
                else:
                    usual.append(f"{leg} {what}")
            case _:
                unreachable(change)
    return [*out, *hazard] or usual


def broken_words(before: State, after: State, domain: Domain,
                 broken: Sequence[Violation], allowed: Sequence[State] = ()) -> str:
    """The first broken assumption in the robot's words: what changed, then the clause's
    equation and line (``L5 failed while not in use (eq. 3.5, line 23)``); a clause that
    names no equation is quoted.  A generated clause without a source line (the one of
    "no gait") cites the line declaring the first leg that changed; ``allowed`` are the
    states of the moves the assumptions allow at ``before`` (:func:`change_words`)."""
    if not broken:
        return ""
    first = next((v for v in broken if v.span is not None), broken[0])
    changes = change_words(before, after, domain, allowed)
    tag = equation(first.rule)
    where = _where(first)
    if not where:
        changed = [leg for (leg, level), (_, new) in zip(before.health, after.health,
                                                          strict=True) if level != new]
        spans = {leg.name: leg.span for leg in domain.model.legs}
        span = spans.get(changed[0]) if changed else None
        where = f", {changed[0]} declared on line {span.line}" if span is not None else ""
    cite = f"({tag}{where})" if tag != first.rule else f"('{first.rule}'{where})"
    if not changes:
        return f"the environment broke an assumption {cite}"
    return f"{', '.join(changes)} {cite}"
