"""What a generated clause says about the robot's world: its role (issue 61).

The front end (:mod:`ltlcompiler.lowering`) writes every clause of a ``.gait`` spec with a
display label (:attr:`gaitc.ir.spec.Origin.rule`, for people) and one of these roles, a
small closed set of typed values.  Every consumer that needs the meaning (tolerance's
breakable pieces, explain's core, mechanism and variants, the goal titles of progress
messages) matches on the role, never on the label's words, and handles the kinds with a
``match`` that ends in :func:`gaitc.ir.formula.unreachable`, so mypy names each place a new kind
must be handled.  Clauses of SLUGS specs, and those an analysis adds itself, have no role.

The kinds follow the thesis's encoding (chapter 3): the exclusions and initial values
that only fix the state's shape, the map's moves (eq. 3.3), a failed leg's gaits off
(eq. 3.4), the legs a gait wears or spares (eq. 3.5), an active hazard's effect on the
legs of the gait in it (eq. 3.9, graded: eq. 3.5 with k levels for 1), a cache's
restoration (eq. 3.6), a goal (eq. 3.7) and a formula of the user's own.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TypeAlias

from gaitc.ir.formula import unreachable


@dataclass(frozen=True)
class Shape:
    """An exclusion or initial value that only fixes the state's shape: exactly one
    region, gait or health level; at most one hazard set; the start region and gait."""


@dataclass(frozen=True)
class StartHealth:
    """Leg ``leg`` starts at its declared health level."""

    leg: str


@dataclass(frozen=True)
class Moves:
    """The map's moves out of ``region`` (eq. 3.3)."""

    region: str


@dataclass(frozen=True)
class LegFailure:
    """Once leg ``leg`` has failed, the gaits that use it are off (eq. 3.4)."""

    leg: str


@dataclass(frozen=True)
class Spares:
    """Under gait ``gait``, which wears no leg, every leg keeps its health (eq. 3.5)."""

    gait: str


@dataclass(frozen=True)
class Wears:
    """Under gait ``gait`` outside caches and active hazards, each of ``legs`` may lose
    one level and the other legs keep theirs (eq. 3.5)."""

    gait: str
    legs: tuple[str, ...]


@dataclass(frozen=True)
class Fails:
    """What an active hazard region does to the legs of the gait in it: fails every one
    (eq. 3.9)."""

    def lost(self, level: int) -> int:
        """The most levels a leg at ``level`` loses there: all but one."""
        return level - 1

    @property
    def words(self) -> str:
        return "fails the legs"


@dataclass(frozen=True)
class WearsUpTo:
    """What a graded hazard region does (``wears k``): each leg of the gait may lose up to
    ``levels`` levels, never going below level 1, the environment choosing how many (eq. 3.5
    with k for 1; ``wears 1`` is the normal wear, and ``wears`` h - 1 or more lets the
    environment pick any level down to failed, which is not "fails": it may also spare the
    leg)."""

    levels: int

    def lost(self, level: int) -> int:
        """The most levels a leg at ``level`` loses there."""
        return min(self.levels, level - 1)

    @property
    def words(self) -> str:
        return f"wears the legs by up to {self.levels} level{'s' if self.levels != 1 else ''}"


#: What an active hazard region does to the legs of the gait in it (issue 61: a type, where
#: an optional number stood for it in eight modules).
Harm: TypeAlias = Fails | WearsUpTo


def graded_levels(harm: Harm) -> int | None:
    """The levels a graded hazard wears (``wears k``), None for one that fails the legs;
    the readers that ask only this go through here, so a new kind of harm is named by mypy
    in this ``match``."""
    match harm:
        case Fails():
            return None
        case WearsUpTo(levels):
            return levels
        case _:
            unreachable(harm)


@dataclass(frozen=True)
class HazardEffect:
    """Under gait ``gait`` in an active region of hazard ``hazard``, ``legs`` suffer
    ``harm`` (they fail, eq. 3.9, or lose up to k levels, a graded hazard), and the other
    legs keep theirs."""

    hazard: str
    gait: str
    legs: tuple[str, ...]
    harm: Harm


@dataclass(frozen=True)
class Restores:
    """In cache ``cache`` every leg is restored to full health (eq. 3.6)."""

    cache: str


@dataclass(frozen=True)
class Goal:
    """A goal of the task (eq. 3.7), ``title`` its words ("visit r11")."""

    title: str


@dataclass(frozen=True)
class UserClause:
    """An assumption or guarantee the user wrote (``assumption``: which of the two)."""

    assumption: bool


#: Every role a clause of a ``.gait`` spec can have.
ClauseRole: TypeAlias = (Shape | StartHealth | Moves | LegFailure | Spares | Wears | HazardEffect
                   | Restores | Goal | UserClause)
