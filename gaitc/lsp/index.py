"""Where each name of a ``.gait`` file is declared and used: the editor's symbol index.

Built from the syntax tree alone (:mod:`ltlcompiler.syntax`), so it exists as soon as a
file parses, even when the checker rejects it. Every leg, gait, region and hazard set is
one :class:`Symbol` with its declaration and every mention (``uses``, edges, caches,
hazards, ``start``, ``visit`` and the bare names of formulas). A name declared by a range
(``L1..L8``, ``cells r0..r19``) or by a grid without names is declared at the range: such
a name cannot be renamed on its own. Beside the names, the facts the checker decides
places by: each leg's health, the grid's cells and the blocked ones (the regions that are
free are those the checker accepts wherever a region is required).
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass, field

from gaitc.diagnostics import GaitcError, Span
from gaitc.diagnostics.choices import Choice
from gaitc.ir.formula import IntVar, Var, unreachable, walk
from gaitc.ir.traversal import Node
from ltlcompiler import syntax as s
from ltlcompiler.names import expand


class Kind(Choice):
    """What a name stands for (legs, gaits, regions and hazards share one namespace)."""

    LEG = "leg"
    GAIT = "gait"
    REGION = "region"
    HAZARD = "hazard set"


@dataclass(frozen=True)
class Mention:
    """One occurrence of a name: where, and whether it is the declaration."""

    span: Span
    declaration: bool = False
    ranged: bool = False  # the span is a range or a grid standing for several names
    role: str = ""  # what the mention says: "uses", "cache", "hazard", "start", "goal", ...


@dataclass
class Symbol:
    name: str
    kind: Kind
    mentions: list[Mention] = field(default_factory=list)

    @property
    def declaration(self) -> Mention | None:
        return next((m for m in self.mentions if m.declaration), None)

    def roles(self) -> set[str]:
        return {m.role for m in self.mentions}


class Index:
    """The symbols of one syntax tree; :meth:`at` finds the one under a position."""

    def __init__(self, tree: s.SpecFile) -> None:
        self.tree = tree
        self.symbols: dict[str, Symbol] = {}
        self._pending: list[tuple[str, Mention, Kind | None]] = []
        self.health: dict[str, int] = {}  # each leg's health levels
        self.cells: dict[tuple[int, int], str] = {}  # the grid's cells by (row, column)
        self._blocks: list[s.RegionRef] = []
        for statement in tree.statements:
            self._statement(statement)
        for name, mention, kind in self._pending:
            self._mention(name, mention, kind)
        #: The blocked cells: obstacles, refused by the checker wherever a region is named.
        self.blocked: set[str] = {name for name in map(self._cell_name, self._blocks)
                                  if name in self.cells.values()}

    # ------------------------------------------------------------------ building
    def _declare(self, item: s.NameItem | s.Name, kind: Kind, role: str = "") -> None:
        try:
            names = expand(item)
        except GaitcError:
            return
        ranged = isinstance(item, s.NameRange)
        for name in names:
            if name.span is None or name.text in self.symbols:
                continue
            self.symbols[name.text] = Symbol(name.text, kind, [
                Mention(name.span, declaration=True, ranged=ranged, role=role)])

    def _use(self, item: s.NameItem | s.RegionRef, kind: Kind | None, role: str) -> None:
        if isinstance(item, s.Cell) or item.span is None:
            return
        try:
            names = expand(item)
        except GaitcError:
            return
        for name in names:
            if name.span is not None:
                self._pending.append((name.text, Mention(
                    name.span, ranged=isinstance(item, s.NameRange), role=role), kind))

    def _mention(self, name: str, mention: Mention, kind: Kind | None) -> None:
        symbol = self.symbols.get(name)
        if symbol is None:
            return  # an undeclared name: the checker reports it
        if kind is not None and symbol.kind is not kind:
            return
        symbol.mentions.append(mention)

    def _statement(self, st: s.Statement) -> None:
        """The declarations and mentions of one statement: a ``match`` over every statement
        kind, so mypy reports a kind added to :data:`ltlcompiler.syntax.Statement` and not
        handled here."""
        match st:
            case s.RobotDecl():
                pass  # the robot's name is no symbol
            case s.LegsDecl():
                for item in st.legs:
                    self._declare(item, Kind.LEG)
                    for name in _names_of(item):
                        self.health.setdefault(name, st.health)
            case s.GaitDecl():
                self._declare(st.name, Kind.GAIT, "correction" if st.correction else "")
                for item in st.legs or ():
                    self._use(item, Kind.LEG, "uses")
                for arrow in st.transitions:
                    self._use(arrow.source, Kind.REGION, "move")
                    self._use(arrow.target, Kind.REGION, "move")
            case s.GridDecl():
                if st.cells is None and st.span is not None:
                    for i in range(max(0, min(st.rows * st.cols, 10_000))):
                        self._declare(s.Name(f"r{i}", span=st.span), Kind.REGION)
                        self.symbols[f"r{i}"].mentions[0] = Mention(st.span, True, True)
                for item in st.cells or ():
                    self._declare(item, Kind.REGION)
                self._grid(st)
            case s.RegionDecl():
                for item in st.names:
                    self._declare(item, Kind.REGION)
            case s.BlockDecl():
                self._blocks.extend(st.cells)
                for ref in st.cells:
                    self._use(ref, Kind.REGION, "block")
            case s.EdgeDecl():
                self._use(st.source, Kind.REGION, "edge")
                self._use(st.target, Kind.REGION, "edge")
                for gait in st.gaits:
                    self._use(gait, Kind.GAIT, "edge")
            case s.CacheDecl():
                for ref in st.regions:
                    self._use(ref, Kind.REGION, "cache")
            case s.HazardDecl():
                self._declare(st.name, Kind.HAZARD)
                for ref in st.regions:
                    self._use(ref, Kind.REGION, f"hazard {st.name.text}")
            case s.StartDecl():
                self._use(st.region, Kind.REGION, "start")
                for init in st.health:
                    self._use(init.legs, Kind.LEG, "start")
            case s.VisitDecl():
                for ref in st.regions:
                    self._use(ref, Kind.REGION, "goal")
            case s.AssumeDecl():
                self._formula(st.formula, "assume")
            case s.GuaranteeDecl():
                self._formula(st.formula, "guarantee")
            case _:
                unreachable(st)

    def _grid(self, st: s.GridDecl) -> None:
        """The cells of the first grid, row-major as the checker names them."""
        count = st.rows * st.cols
        if self.cells or st.cols < 1 or not 0 < count <= 10_000:
            return
        names = ([f"r{i}" for i in range(count)] if st.cells is None else
                 [name for item in st.cells for name in _names_of(item)])
        if len(names) == count:
            self.cells = {divmod(i, st.cols): name for i, name in enumerate(names)}

    def _cell_name(self, ref: s.RegionRef) -> str:
        if isinstance(ref, s.Cell):
            return self.cells.get((ref.row, ref.col), "")
        return ref.text

    def _formula(self, formula: Node, role: str) -> None:
        for name, span in _formula_names(formula):
            self._pending.append((name, Mention(span, role=role), None))

    # ------------------------------------------------------------------ queries
    def at(self, line: int, column: int, word: str = "") -> tuple[Symbol, Mention] | None:
        """The symbol mentioned at 1-based ``line``, ``column``; inside a range
        (``L1..L8``) the one named ``word``, the word under the cursor."""
        ranged: tuple[Symbol, Mention] | None = None
        for symbol in self.symbols.values():
            for mention in symbol.mentions:
                if not _contains(mention.span, line, column):
                    continue
                if not mention.ranged:
                    return symbol, mention
                if ranged is None or symbol.name == word:
                    ranged = (symbol, mention)
        return ranged

    def of_kind(self, kind: Kind) -> list[str]:
        return [name for name, symbol in self.symbols.items() if symbol.kind is kind]

    def free_regions(self) -> list[str]:
        """The regions that are not blocked cells, in declaration order."""
        return [name for name in self.of_kind(Kind.REGION) if name not in self.blocked]

    def named_as(self, role: str, outside: range = range(0)) -> set[str]:
        """The names mentioned with ``role`` (``cache``, ``goal``; ``hazard`` takes those of
        every hazard set) on a line not in ``outside``."""
        return {symbol.name for symbol in self.symbols.values() for m in symbol.mentions
                if (m.role == role or m.role.startswith(role + " "))
                and m.span.line not in outside}


def _names_of(item: s.NameItem) -> list[str]:
    """The names an item of a list stands for (none for a range the checker refuses)."""
    try:
        return [name.text for name in expand(item)]
    except GaitcError:
        return []


def _contains(span: Span, line: int, column: int) -> bool:
    end_line = span.end_line if span.end_line is not None else span.line
    end_column = span.end_column if span.end_column is not None else span.column
    if not span.line <= line <= end_line:
        return False
    if line == span.line and column < span.column:
        return False
    return not (line == end_line and column > end_column + 1)


def _formula_names(formula: Node) -> Iterator[tuple[str, Span]]:
    """The names a formula mentions (``Var``, ``IntVar``), with their spans, in the order
    they are written: :func:`gaitc.ir.formula.walk` is iterative, so a formula nested as
    deep as the parser allows (``MAX_NESTING``) needs no recursion here either."""
    for node in walk(formula):
        if isinstance(node, (Var, IntVar)) and node.span is not None:
            yield node.name, node.span
