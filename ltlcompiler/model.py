"""The checked robot-and-task model: what a .gait file means once names are resolved.

The semantic checker builds a :class:`Model` from the syntax tree; the lowering turns
it into a :class:`~gaitc.ir.spec.GR1Spec` (thesis eqs. 3.3-3.9).  The simulator
and renderer read it to decode controller states into regions, gaits and health.

Atoms of user formulas (``Model.assumptions``/``guarantees``) use one namespace:
``Var(region)`` is "the robot is in region", ``Var(gait)`` "gait is selected",
``Var(hazard)`` "hazard set is active", and ``Compare(op, IntVar(leg), IntConst(k))``
compares a leg's health level (1 = failed, ``health`` = full).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from enum import Enum
from typing import Final

from gaitc.diagnostics import Span
from gaitc.ir.formula import Expr
from gaitc.ir.roles import Fails, Harm

NO_GAIT = "noGait"


class GaitKind(Enum):
    MOVE = "move"  # uses legs; may degrade them (eq. 3.5)
    CORRECTION = "correction"  # orientation adjustment: uses no health (section 3.4.1)
    NONE = "none"  # the implicit noGait


class Section(Enum):
    """Where a free-form formula goes: init, trans (□) or liveness (□◇)."""

    INIT = "init"
    TRANS = "trans"
    LIVENESS = "liveness"


@dataclass(frozen=True)
class Leg:
    """A leg, its number of health levels and the level it starts at."""

    name: str
    health: int  # number of health levels h_i; 1 = permanently failed
    initial: int  # initial health level (default: health, i.e. full)
    span: Span | None = field(default=None, compare=False, repr=False)
    initial_span: Span | None = field(default=None, compare=False, repr=False)  # L1 = 2


@dataclass(frozen=True)
class Primitive:
    """The valve sequence bound to a gait: inline, or synthesised from a robot file."""

    valves: tuple[str, ...] = ()  # inline valve states, each a string of 0/1 per chamber
    robot: str | None = None  # path of a robot YAML file (relative to the .gait file)
    direction: str | None = None  # requested direction for synthesis, e.g. "+x"
    method: str | None = None  # gait-graph method: full | random | reset
    span: Span | None = field(default=None, compare=False, repr=False)


@dataclass(frozen=True)
class Gait:
    """A gait: its kind, the legs it uses and, when known, its valve primitive."""

    name: str
    kind: GaitKind
    legs: tuple[str, ...]  # L_G(g), sorted in declaration order of legs
    span: Span | None = field(default=None, compare=False, repr=False)
    primitive: Primitive | None = None
    # the legs in the order the gait names them: the order its actuators fire (thesis 3.4.1)
    fired: tuple[str, ...] = field(default=(), compare=False)

    @property
    def firing_order(self) -> tuple[str, ...]:
        """The legs in the order they are pressurised: as the gait names them."""
        return self.fired or self.legs

    def valve_mismatch(self, pressed: Sequence[str], source: str) -> tuple[str, str] | None:
        """Why valves that pressurise the legs ``pressed`` cannot run this gait as the
        health reasoning has it, with the remedy, or None.  A move gait's valves must
        pressurise exactly the legs it uses, a correction gait's none (it wears no leg,
        eq. 3.5), so the board never fires a leg the reasoning takes as idle.  ``source``
        says where the valves come from ("inline", a robot file's gait)."""
        if self.kind is GaitKind.CORRECTION:
            if not pressed:
                return None
            return (f"correction gait {self.name} wears no leg, but its primitive ({source}) "
                    f"pressurises {', '.join(pressed)}", CORRECTION_HINT)
        if set(pressed) == set(self.legs):
            return None
        return (f"gait {self.name} uses {', '.join(self.legs) or 'no legs'} but its primitive "
                f"({source}) pressurises {', '.join(pressed) or 'no legs'}", MOVE_HINT)

    def idle_fired(self, pressed: Sequence[str], source: str) -> tuple[str, str] | None:
        """:meth:`valve_mismatch` when the valves pressurise a leg this gait does not use
        (any leg, for a correction gait), which would wear a leg the health reasoning
        takes as idle: no command may take such a gait.  Firing fewer legs than the gait
        uses only moves it less than planned (``lint`` reports it, and a drive's
        localisation), so that alone is None here."""
        if all(leg in self.legs for leg in pressed):
            return None
        return self.valve_mismatch(pressed, source)


#: The remedies of :meth:`Gait.valve_mismatch`'s two cases.
MOVE_HINT: Final = "the spec's leg-to-gait map drives the health reasoning; make them agree"
CORRECTION_HINT: Final = ("a correction gait wears no leg (thesis 3.4.1): its valves may move "
                          "the body, not a leg; make it a move gait that uses the legs, or "
                          "change its valves")


@dataclass(frozen=True)
class Region:
    """A region of the map (a grid cell when ``row`` and ``col`` are set)."""

    name: str
    row: int | None = None  # grid coordinates when the region is a grid cell
    col: int | None = None
    span: Span | None = field(default=None, compare=False, repr=False)


@dataclass(frozen=True)
class Transition:
    """(source, target) ∈ τ with D_τ(source, target) = gaits; self-loops included."""

    source: str
    target: str
    gaits: tuple[str, ...]
    span: Span | None = field(default=None, compare=False, repr=False)
    # the compass direction of an explicit ``edge A -> B north`` (for drawing the map only)
    direction: str | None = field(default=None, compare=False, repr=False)


@dataclass(frozen=True)
class Hazard:
    """A hazard set, the regions it covers when active and what it does to the legs."""

    name: str
    regions: tuple[str, ...]  # F_T(t)
    span: Span | None = field(default=None, compare=False, repr=False)
    harm: Harm = field(default_factory=Fails)

    @property
    def effect(self) -> str:
        """What an active region does to the legs of a gait, in words: "fails the legs" or
        "wears the legs by up to 2 levels" (the words of the lowering, the map and docs)."""
        return self.harm.words


@dataclass(frozen=True)
class UserFormula:
    """A free-form assume/guarantee, already checked to be GR(1); ``formula`` may contain Next."""

    section: Section
    formula: Expr
    span: Span | None = field(default=None, compare=False, repr=False)


@dataclass(frozen=True)
class Model:
    """A robot, its map and its task, every name resolved (see the module's docstring)."""

    name: str
    legs: tuple[Leg, ...]
    gaits: tuple[Gait, ...]  # includes noGait, last
    regions: tuple[Region, ...]
    transitions: tuple[Transition, ...]  # sorted by (region order of source, of target)
    caches: tuple[str, ...]
    hazards: tuple[Hazard, ...]
    start: str
    goals: tuple[UserFormula, ...]  # sys liveness from goal statements (□◇ region ...)
    assumptions: tuple[UserFormula, ...]
    guarantees: tuple[UserFormula, ...]
    grid: tuple[int, int] | None = None  # (rows, columns) when declared with a grid
    file: str = field(default="", compare=False)
    start_span: Span | None = field(default=None, compare=False, repr=False)
    cache_spans: tuple[Span | None, ...] = field(default=(), compare=False, repr=False)

    def leg(self, name: str) -> Leg:
        return next(leg for leg in self.legs if leg.name == name)

    def gait(self, name: str) -> Gait:
        return next(g for g in self.gaits if g.name == name)

    def gaits_using(self, leg: str) -> tuple[str, ...]:
        """G_L(leg): the gaits that use ``leg``."""
        return tuple(g.name for g in self.gaits if leg in g.legs)
