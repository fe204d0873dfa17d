"""The .gait syntax tree: one frozen dataclass per statement rule of ``gait.lark``.

Names are not resolved yet (that is :mod:`ltlcompiler.checker`'s job).  Spans ride
along but do not count in equality.  Formulas are already formula IR
(:mod:`gaitc.ir.formula`) whose ``Var``/``IntVar`` names are still unchecked.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from gaitc.diagnostics import Span
from gaitc.ir.formula import Expr

_SPAN: Any = field(default=None, compare=False, repr=False, kw_only=True)


# ---------------------------------------------------------------- names and cells
@dataclass(frozen=True)
class Name:
    """One identifier as written."""

    text: str
    span: Span | None = _SPAN


@dataclass(frozen=True)
class NameRange:
    """``L1..L8``: expands to L1, L2, ..., L8 (same prefix, ascending numbers)."""

    first: Name
    last: Name
    span: Span | None = _SPAN


@dataclass(frozen=True)
class Cell:
    """``(row, col)``: a grid cell by its coordinates (0-based, row 0 is north)."""

    row: int
    col: int
    span: Span | None = _SPAN


NameItem = Name | NameRange
RegionRef = Name | Cell


# ---------------------------------------------------------------- the robot
@dataclass(frozen=True)
class RobotDecl:
    """``robot "name"``."""

    name: str
    span: Span | None = _SPAN


@dataclass(frozen=True)
class LegsDecl:
    """``legs L1..L8 health 3`` / ``leg L2 health 2``."""

    legs: tuple[NameItem, ...]
    health: int
    health_span: Span | None = field(default=None, compare=False, repr=False, kw_only=True)
    span: Span | None = _SPAN


@dataclass(frozen=True)
class Direction:
    """A compass direction: north, south, east or west."""

    name: str
    span: Span | None = _SPAN


@dataclass(frozen=True)
class Arrow:
    """``source -> target`` in a gait's explicit transition list."""

    source: RegionRef
    target: RegionRef
    span: Span | None = _SPAN


@dataclass(frozen=True)
class ValvesPrimitive:
    """``valves 1000, 0100``: inline valve states, one 0/1 character per valve."""

    states: tuple[Name, ...]  # kept as written (leading zeros matter)
    span: Span | None = _SPAN


@dataclass(frozen=True)
class RobotPrimitive:
    """``primitive "robot.yaml" direction +x method reset``."""

    robot: str
    direction: str | None
    method: Name | None
    span: Span | None = _SPAN


@dataclass(frozen=True)
class GaitDecl:
    """``[correction] gait NAME [uses legs] [moves ...] [valves ... | primitive ...]``."""

    name: Name
    correction: bool
    legs: tuple[NameItem, ...] | None  # None when there is no ``uses`` clause
    directions: tuple[Direction, ...] = ()
    transitions: tuple[Arrow, ...] = ()
    primitive: ValvesPrimitive | RobotPrimitive | None = None
    span: Span | None = _SPAN


# ---------------------------------------------------------------- the map
@dataclass(frozen=True)
class GridDecl:
    """``grid ROWS x COLS [cells r0..r19 | cells a, b, ...]``."""

    rows: int
    cols: int
    cells: tuple[NameItem, ...] | None
    span: Span | None = _SPAN


@dataclass(frozen=True)
class BlockDecl:
    """``block r1, r2``: cells of the grid that are no region."""

    cells: tuple[RegionRef, ...]
    span: Span | None = _SPAN


@dataclass(frozen=True)
class RegionDecl:
    """``region a, b`` / ``regions r1..r4``."""

    names: tuple[NameItem, ...]
    span: Span | None = _SPAN


@dataclass(frozen=True)
class EdgeDecl:
    """``edge a -> b by g1, g2`` or ``edge a <-> b east``."""

    source: RegionRef
    target: RegionRef
    both_ways: bool
    gaits: tuple[Name, ...] = ()
    direction: Direction | None = None
    span: Span | None = _SPAN


# ---------------------------------------------------------------- the task
@dataclass(frozen=True)
class CacheDecl:
    """``cache r1, r2``: the regions that hold a cache."""

    regions: tuple[RegionRef, ...]
    span: Span | None = _SPAN


@dataclass(frozen=True)
class HazardDecl:
    """``hazard fire: r2, r3`` (fails the legs) / ``hazard sand: r2, r3 wears 2`` (each leg
    in use may lose up to 2 levels): a hazard set, the regions it covers and its wear."""

    name: Name
    regions: tuple[RegionRef, ...]
    wears: int | None = None  # None: no ``wears`` clause, the hazard fails the legs at once
    wears_span: Span | None = field(default=None, compare=False, repr=False, kw_only=True)
    span: Span | None = _SPAN


@dataclass(frozen=True)
class HealthInit:
    """``L1 = 2`` in ``start r12 with L1 = 2``."""

    legs: NameItem
    value: int
    value_span: Span | None = field(default=None, compare=False, repr=False, kw_only=True)
    span: Span | None = _SPAN


@dataclass(frozen=True)
class StartDecl:
    """``start r1`` / ``start r12 with L1 = 2``."""

    region: RegionRef
    health: tuple[HealthInit, ...]
    span: Span | None = _SPAN


@dataclass(frozen=True)
class VisitDecl:
    """``visit r1, r4 infinitely often``."""

    regions: tuple[RegionRef, ...]
    span: Span | None = _SPAN


@dataclass(frozen=True)
class AssumeDecl:
    """``assume φ``: an assumption on the environment."""

    formula: Expr
    span: Span | None = _SPAN


@dataclass(frozen=True)
class GuaranteeDecl:
    """``guarantee φ``: a guarantee of the robot."""

    formula: Expr
    span: Span | None = _SPAN


Statement = (
    RobotDecl
    | LegsDecl
    | GaitDecl
    | GridDecl
    | BlockDecl
    | RegionDecl
    | EdgeDecl
    | CacheDecl
    | HazardDecl
    | StartDecl
    | VisitDecl
    | AssumeDecl
    | GuaranteeDecl
)


@dataclass(frozen=True)
class SpecFile:
    """A whole .gait file: its statements in source order."""

    statements: tuple[Statement, ...]
    file: str = field(default="", compare=False)
