"""The workspace map: grid and explicit regions, blocked cells, and the transition relation τ.

Builds ``Reg``, τ and ``D_τ`` of thesis section 3.3.1 from grid, region, edge and gait
statements; noGait (and correction gaits without moves) give every region a self-loop.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field

from gaitc.diagnostics import Diagnostic, Span, SpecSemanticError
from ltlcompiler import syntax as s
from ltlcompiler.model import NO_GAIT, Region, Transition
from ltlcompiler.names import Namespace, describe, expand_all

MAX_CELLS = 10_000
STEPS = {"north": (-1, 0), "south": (1, 0), "east": (0, 1), "west": (0, -1)}
OPPOSITE = {"north": "south", "south": "north", "east": "west", "west": "east"}


@dataclass
class RegionMap:
    """Regions in declaration order (blocked cells removed) and the grid, if any."""

    regions: list[Region] = field(default_factory=list)
    grid: tuple[int, int] | None = None
    grid_span: Span | None = None
    cells: dict[tuple[int, int], str] = field(default_factory=dict)
    blocked: dict[str, Span | None] = field(default_factory=dict)

    def index(self) -> dict[str, int]:
        return {r.name: i for i, r in enumerate(self.regions)}

    def resolve(self, ref: s.RegionRef, ns: Namespace, context: str) -> str:
        """The region a name or ``(row, col)`` refers to; errors for unknown or blocked ones."""
        if isinstance(ref, s.Cell):
            name = self._cell(ref, context)
        else:
            # the hint lists the regions valid here: blocked cells are no place to name
            name = ns.require(ref, "region", context, (r.name for r in self.regions))
        if name in self.blocked:
            line = self.blocked[name]
            where = f" (line {line.line})" if line is not None else ""
            raise SpecSemanticError(
                f"region '{name}' {context} is a blocked cell{where}; blocked cells are "
                "obstacles, so unblock it or choose another region",
                ref.span,
            )
        return name

    def _cell(self, cell: s.Cell, context: str) -> str:
        if self.grid is None:
            raise SpecSemanticError(
                f"cell ({cell.row}, {cell.col}) {context} needs a grid, but no grid is "
                "declared; use a region name or add 'grid ROWS x COLS'",
                cell.span,
            )
        rows, cols = self.grid
        if (cell.row, cell.col) not in self.cells:
            raise SpecSemanticError(
                f"cell ({cell.row}, {cell.col}) is outside the {rows} x {cols} grid; rows are "
                f"0..{rows - 1} and columns are 0..{cols - 1}",
                cell.span,
            )
        return self.cells[(cell.row, cell.col)]


def add_regions(rmap: RegionMap, st: s.RegionDecl, ns: Namespace) -> None:
    """Declare the explicit regions of a ``region`` statement."""
    for name in expand_all(st.names):
        ns.declare(name, "region")
        rmap.regions.append(Region(name.text, span=name.span))


def apply_blocks(rmap: RegionMap, blocks: Sequence[s.BlockDecl], ns: Namespace, file: str) -> None:
    """Remove blocked grid cells from the regions; at least one region must remain."""
    for st in blocks:
        for ref in st.cells:
            name = rmap.resolve(ref, ns, "in block")
            if not any(r.name == name and r.row is not None for r in rmap.regions):
                raise SpecSemanticError(
                    f"only grid cells can be blocked, and '{name}' is an explicit region; "
                    "remove its declaration instead",
                    ref.span,
                )
            rmap.blocked[name] = ref.span
    rmap.regions = [r for r in rmap.regions if r.name not in rmap.blocked]
    if not rmap.regions:
        raise SpecSemanticError(
            "no regions: declare a map with 'grid ROWS x COLS' or 'region NAME, ...'",
            Span(file, 1, 1),
        )


def add_grid(rmap: RegionMap, st: s.GridDecl, ns: Namespace) -> None:
    """Declare the cells of a ``grid`` statement, row-major from the north-west."""
    if rmap.grid is not None:
        line = rmap.grid_span.line if rmap.grid_span is not None else 0
        raise SpecSemanticError(
            f"a second grid; only one grid is allowed (the first is at line {line}); "
            "use explicit regions and edges for the rest of the map",
            st.span,
        )
    if st.rows < 1 or st.cols < 1:
        raise SpecSemanticError(
            f"a grid needs at least 1 row and 1 column, not {st.rows} x {st.cols}", st.span
        )
    count = st.rows * st.cols
    if count > MAX_CELLS:
        raise SpecSemanticError(
            f"a {st.rows} x {st.cols} grid has {count} cells; at most {MAX_CELLS} are allowed",
            st.span,
        )
    if st.cells is None:
        names = [s.Name(f"r{i}", span=st.span) for i in range(count)]
    else:
        names = expand_all(st.cells)
        if len(names) != count:
            raise SpecSemanticError(
                f"a {st.rows} x {st.cols} grid has {count} cells, but {len(names)} cell names "
                "are given; list exactly one name per cell, row by row",
                st.span,
            )
    rmap.grid, rmap.grid_span = (st.rows, st.cols), st.span
    for i, name in enumerate(names):
        row, col = divmod(i, st.cols)
        ns.declare(name, "region")
        rmap.cells[(row, col)] = name.text
        rmap.regions.append(Region(name.text, row, col, span=name.span))


class _Moves:
    """Accumulates D_τ: (source, target) -> gaits, remembering the first span."""

    def __init__(self) -> None:
        self.gaits: dict[tuple[str, str], set[str]] = {}
        self.spans: dict[tuple[str, str], Span | None] = {}
        self.directions: dict[tuple[str, str], str] = {}  # compass direction of an edge

    def add(self, source: str, target: str, gait: str, span: Span | None,
            direction: str | None = None) -> None:
        key = (source, target)
        self.gaits.setdefault(key, set()).add(gait)
        self.spans.setdefault(key, span)
        if direction is not None:
            self.directions.setdefault(key, direction)


def build_transitions(
    rmap: RegionMap,
    gaits: Sequence[s.GaitDecl],
    edges: Sequence[s.EdgeDecl],
    ns: Namespace,
    diagnostics: list[Diagnostic],
) -> tuple[Transition, ...]:
    """τ with D_τ, sorted by (source, target) in region order; gaits in declaration order."""
    moves = _Moves()
    for region in rmap.regions:
        moves.add(region.name, region.name, NO_GAIT, region.span)
        for g in gaits:
            if g.correction and not g.directions and not g.transitions:
                moves.add(region.name, region.name, g.name.text, g.span)
    by_direction: dict[str, list[str]] = {d: [] for d in STEPS}
    for g in gaits:
        for d in g.directions:
            by_direction[d.name].append(g.name.text)
        for arrow in g.transitions:
            context = f"in gait {g.name.text}"
            src = rmap.resolve(arrow.source, ns, context)
            dst = rmap.resolve(arrow.target, ns, context)
            moves.add(src, dst, g.name.text, arrow.span)
    _grid_moves(rmap, by_direction, moves, diagnostics)
    _edge_moves(rmap, edges, by_direction, ns, moves, diagnostics)
    index = rmap.index()
    order = {g.name.text: i for i, g in enumerate(gaits)}
    order[NO_GAIT] = len(gaits)
    keys = sorted(moves.gaits, key=lambda k: (index[k[0]], index[k[1]]))
    return tuple(
        Transition(src, dst, tuple(sorted(moves.gaits[(src, dst)], key=order.__getitem__)),
                   span=moves.spans[(src, dst)], direction=moves.directions.get((src, dst)))
        for src, dst in keys
    )


def _grid_moves(
    rmap: RegionMap,
    by_direction: dict[str, list[str]],
    moves: _Moves,
    diagnostics: list[Diagnostic],
) -> None:
    if rmap.grid is None:
        return
    rows, cols = rmap.grid
    for direction, (dr, dc) in STEPS.items():
        if (dr and rows < 2) or (dc and cols < 2):
            continue
        if not by_direction[direction]:
            diagnostics.append(Diagnostic(
                f"no gait moves {direction}, so the grid's moves to the {direction} are never "
                "used",
                rmap.grid_span,
            ))
            continue
        for (row, col), src in rmap.cells.items():
            dst = rmap.cells.get((row + dr, col + dc))
            if dst is None or src in rmap.blocked or dst in rmap.blocked:
                continue
            for gait in by_direction[direction]:
                moves.add(src, dst, gait, rmap.grid_span)


def _edge_moves(
    rmap: RegionMap,
    edges: Sequence[s.EdgeDecl],
    by_direction: dict[str, list[str]],
    ns: Namespace,
    moves: _Moves,
    diagnostics: list[Diagnostic],
) -> None:
    declared: dict[tuple[str, str], Span | None] = {}
    for edge in edges:
        src = rmap.resolve(edge.source, ns, "in edge")
        dst = rmap.resolve(edge.target, ns, "in edge")
        pairs = [(src, dst, edge.direction.name if edge.direction else None)]
        if edge.both_ways:
            back = OPPOSITE[edge.direction.name] if edge.direction else None
            pairs.append((dst, src, back))
        for a, b, direction in pairs:
            if (a, b) in declared:
                first = declared[(a, b)]
                line = first.line if first is not None else 0
                raise SpecSemanticError(
                    f"edge {a} -> {b} is already declared at line {line}; "
                    "merge the two edge statements",
                    edge.span,
                )
            declared[(a, b)] = edge.span
            if direction is not None:
                names = by_direction[direction]
                if not names:
                    diagnostics.append(Diagnostic(
                        f"no gait moves {direction}, so edge {a} -> {b} is never usable",
                        edge.direction.span if edge.direction else edge.span,
                    ))
            else:
                names = [_edge_gait(g, ns) for g in edge.gaits]
            for gait in names:
                moves.add(a, b, gait, edge.span, direction)


def _edge_gait(name: s.Name, ns: Namespace) -> str:
    if name.text == NO_GAIT:
        raise SpecSemanticError(
            "noGait keeps the robot in place and cannot label an edge; name a moving gait",
            name.span,
        )
    return ns.require(name, "gait", "in edge", (g for g in ns.of_kind("gait") if g != NO_GAIT))


def reachable(start: str, transitions: Sequence[Transition]) -> set[str]:
    """Regions reachable from ``start`` along τ (any gait)."""
    succ: dict[str, list[str]] = {}
    for t in transitions:
        succ.setdefault(t.source, []).append(t.target)
    seen, stack = {start}, [start]
    while stack:
        for nxt in succ.get(stack.pop(), ()):
            if nxt not in seen:
                seen.add(nxt)
                stack.append(nxt)
    return seen


def describe_regions(rmap: RegionMap) -> str:
    return describe(r.name for r in rmap.regions)
