"""A change of the robot's environment: a leg fails, loses levels or is repaired, a hazard
set switches.

The environment of a ``.gait`` spec sets the legs' health levels and the active hazard set
(thesis chapter 3: the inputs of eqs. 3.4-3.6 and 3.8-3.9).  Every front end that speaks
of what the environment did or may do uses these four types and their words: ``simulate
--violate STEP:EVENT`` and the player's "break an assumption" moves (a surprise, parsed by
:func:`parse_changes`, the one parser), the player's environment moves
(:func:`between`), the surprises the player offers, the board's recovery classes
(:mod:`gaitc.compact.recovery`) and explain's freedoms (:mod:`gaitc.analysis.freedoms`).
Adding a kind of change is one dataclass here, its words in :func:`parse_changes`, and the
``match`` branches mypy then asks for (each ends in :func:`unreachable`).

The words are the player's: ``fail L5``, ``degrade L3``, ``degrade L3 by 2``, ``repair
L2``, ``repair L2 to level 3``, ``switch spill on``, ``switch spill off``.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Final, TypeAlias

from gaitc.diagnostics import UsageError
from gaitc.ir.formula import unreachable

#: An example of each kind of change, for help texts.
EXAMPLES: Final = ("'fail L5', 'degrade L3', 'degrade L3 by 2', 'repair L2', "
                   "'repair L2 to level 3', 'switch spill on', 'switch spill off'")
#: What :func:`parse_changes` accepts, for its error message.
FORMS: Final = ("'fail LEG'", "'degrade LEG'", "'degrade LEG by N'", "'repair LEG'",
                "'repair LEG to level N'", "'switch HAZARD on'", "'switch HAZARD off'")


@dataclass(frozen=True)
class LegFails:
    """The leg drops to its lowest level, 1 (failed)."""

    leg: str

    def words(self) -> str:
        return f"fail {self.leg}"

    def told(self) -> str:
        return f"{self.leg} fails"


@dataclass(frozen=True)
class LegWears:
    """The leg loses ``levels`` health levels (never below 1)."""

    leg: str
    levels: int = 1

    def words(self) -> str:
        return f"degrade {self.leg}" if self.levels == 1 else \
            f"degrade {self.leg} by {self.levels}"

    def told(self) -> str:
        return f"{self.leg} loses a level" if self.levels == 1 else \
            f"{self.leg} loses {self.levels} levels"


@dataclass(frozen=True)
class LegRepaired:
    """The leg is repaired: to full health (``level`` None), or up to ``level``."""

    leg: str
    level: int | None = None

    def words(self) -> str:
        return f"repair {self.leg}" if self.level is None else \
            f"repair {self.leg} to level {self.level}"

    def told(self) -> str:
        return f"{self.leg} is repaired" if self.level is None else \
            f"{self.leg} goes up to level {self.level}"


@dataclass(frozen=True)
class HazardSwitch:
    """Hazard set ``hazard`` switches on (``on``) or off.  One set is active at a time:
    switching one on switches the active one off."""

    hazard: str
    on: bool

    def words(self) -> str:
        return f"switch {self.hazard} {'on' if self.on else 'off'}"

    def told(self) -> str:
        return f"hazard {self.hazard} switches {'on' if self.on else 'off'}"


#: A change of the environment.
Change: TypeAlias = LegFails | LegWears | LegRepaired | HazardSwitch
#: A change of one leg.
LegChange: TypeAlias = LegFails | LegWears | LegRepaired


def words(changes: Sequence[Change]) -> str:
    """Several changes made at one step, in the words :func:`parse_changes` reads back."""
    return ", ".join(c.words() for c in changes)


def subject(change: Change) -> str:
    """What ``change`` changes: its leg, or ``the hazard``."""
    match change:
        case LegFails(leg) | LegWears(leg) | LegRepaired(leg):
            return leg
        case HazardSwitch():
            return "the hazard"
        case _:
            unreachable(change)


def conflict(a: Change, b: Change) -> bool:
    """Whether ``a`` and ``b`` cannot happen at one step: both change one leg, or both
    switch a hazard set on, or both switch the same set."""
    if isinstance(a, HazardSwitch) and isinstance(b, HazardSwitch):
        return a.hazard == b.hazard or (a.on and b.on)
    return subject(a) == subject(b)


def leg_level(change: LegChange, level: int, full: int) -> int:
    """The leg's level after ``change`` from ``level`` (its full health ``full``)."""
    match change:
        case LegFails():
            return 1
        case LegWears(_, levels):
            return max(1, level - levels)
        case LegRepaired(_, to):
            return full if to is None else to
        case _:
            unreachable(change)


def active_after(changes: Sequence[Change], active: str | None) -> str | None:
    """The hazard set active after ``changes`` when ``active`` was: the set switched on,
    else none when the active one was switched off, else as it was."""
    switches = [c for c in changes if isinstance(c, HazardSwitch)]
    on = next((c.hazard for c in switches if c.on), None)
    if on is not None:
        return on
    if any(c.hazard == active for c in switches):
        return None
    return active


def of_leg(leg: str, before: int, after: int, full: int) -> LegChange | None:
    """The change that takes ``leg`` from level ``before`` to ``after`` (None: no change)."""
    if after == before:
        return None
    if after < before:
        return LegFails(leg) if after == 1 else LegWears(leg, before - after)
    return LegRepaired(leg, None if after == full else after)


def of_hazard(before: str | None, after: str | None) -> tuple[HazardSwitch, ...]:
    """The switches that take the active hazard set from ``before`` to ``after``."""
    if before == after:
        return ()
    off = () if before is None else (HazardSwitch(before, False),)
    return off if after is None else (*off, HazardSwitch(after, True))


def between(before: Mapping[str, int], after: Mapping[str, int], full: Mapping[str, int],
            hazard_before: str | None, hazard_after: str | None) -> tuple[Change, ...]:
    """Every change from one environment (legs' levels, active hazard set) to another: the
    hazard switches first, then the legs in ``before``'s order."""
    legs = [of_leg(leg, level, after.get(leg, level), full.get(leg, level))
            for leg, level in before.items()]
    return (*of_hazard(hazard_before, hazard_after), *(c for c in legs if c is not None))


def parse_changes(text: str, legs: Sequence[str], hazards: Sequence[str],
                  where: str) -> tuple[Change, ...]:
    """The changes ``text`` names in the player's words, several joined by commas (``fail
    L1, degrade L3``).  An unknown word, leg or hazard set, an empty part, or two changes
    that cannot happen at one step (:func:`conflict`) is a :class:`UsageError` that quotes
    ``text``, names ``where`` and says what is accepted."""
    parts = [p.strip() for p in text.split(",")]
    if len(parts) > 1 and not all(parts):
        raise UsageError(f"{where} '{text}': an event is missing "
                         f"{'before' if not parts[0] else 'after'} a comma")
    out: list[Change] = []
    for part in parts:
        change = _one(part, text, legs, hazards, where)
        clash = next((c for c in out if conflict(c, change)), None)
        if clash is not None:
            thing = subject(change)
            thing = thing if thing == "the hazard" else f"leg {thing}"
            raise UsageError(f"{where} '{text}': '{clash.words()}' and '{part}' both "
                             f"change {thing}; give one of them")
        out.append(change)
    return tuple(out)


def _one(part: str, text: str, legs: Sequence[str], hazards: Sequence[str],
         where: str) -> Change:
    def leg(name: str) -> str:
        if name not in legs:
            raise UsageError(f"{where} '{text}': unknown leg '{name}'; the robot's legs are "
                             f"{', '.join(legs)}")
        return name

    match part.split():
        case ["fail", name]:
            return LegFails(leg(name))
        case ["degrade", name]:
            return LegWears(leg(name))
        case ["degrade", name, "by", count] if count.isdigit() and int(count) >= 1:
            return LegWears(leg(name), int(count))
        case ["repair", name]:
            return LegRepaired(leg(name))
        case ["repair", name, "to", "level", level] if level.isdigit() and int(level) >= 1:
            return LegRepaired(leg(name), int(level))
        case ["switch", name, ("on" | "off") as how]:
            if name not in hazards:
                known = ", ".join(hazards) if hazards else "none (the spec declares no hazard)"
                raise UsageError(f"{where} '{text}': unknown hazard set '{name}'; the spec's "
                                 f"hazard sets are {known}")
            return HazardSwitch(name, how == "on")
    raise UsageError(f"{where} '{text}': not an event; write one of {', '.join(FORMS)}, "
                     "or several joined by commas")
