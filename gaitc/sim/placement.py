"""Where the map draws each region: grid cells where declared, else the compass directions
of explicit edges (``edge G <-> I north`` puts I one cell above G), else a seeded spring
layout for the regions that no direction places.

The directions are laid out as a constraint layout on integer cells: a breadth-first walk
from each unplaced region along its directed edges (both ways), skipping an edge whose
cell is taken or contradicts an earlier placement; the spring layout then places the rest
with the placed regions pinned.
"""

from __future__ import annotations

from collections import deque

import networkx as nx

from ltlcompiler.model import Model

#: (row, column) step of each direction; row 0 is north, as in a grid.
STEPS = {"north": (-1, 0), "south": (1, 0), "east": (0, 1), "west": (0, -1)}


def directed_cells(model: Model) -> dict[str, tuple[int, int]]:
    """Integer (row, column) cells of the regions that explicit edge directions place."""
    links: dict[str, list[tuple[str, tuple[int, int]]]] = {r.name: [] for r in model.regions}
    for t in model.transitions:
        if t.direction is None or t.source == t.target or t.direction not in STEPS:
            continue
        dr, dc = STEPS[t.direction]
        links[t.source].append((t.target, (dr, dc)))
        links[t.target].append((t.source, (-dr, -dc)))
    cells: dict[str, tuple[int, int]] = {}
    taken: set[tuple[int, int]] = set()
    offset = 0
    for region in model.regions:
        if region.name in cells or not links[region.name]:
            continue
        component = _walk(region.name, links, (0, offset), taken)
        cells.update(component)
        taken.update(component.values())
        offset = max(c for _, c in taken) + 2
    return cells


def _walk(start: str, links: dict[str, list[tuple[str, tuple[int, int]]]],
          origin: tuple[int, int], taken: set[tuple[int, int]]) -> dict[str, tuple[int, int]]:
    """Cells of the regions reached from ``start`` along directed edges."""
    placed = {start: origin}
    used = set(taken) | {origin}
    queue = deque([start])
    while queue:
        here = queue.popleft()
        row, col = placed[here]
        for there, (dr, dc) in links[here]:
            cell = (row + dr, col + dc)
            if there in placed or cell in used:
                continue  # contradicting or crowded: the first placement stands
            placed[there] = cell
            used.add(cell)
            queue.append(there)
    return placed


def positions(model: Model, cell: float) -> dict[str, tuple[float, float]]:
    """Region centres in inches (``cell`` inches between neighbouring cells, north up)."""
    if all(r.row is not None and r.col is not None for r in model.regions):
        return {r.name: (float(r.col or 0) * cell, -float(r.row or 0) * cell)
                for r in model.regions}
    fixed = {r.name: (float(r.col or 0), -float(r.row or 0)) for r in model.regions
             if r.row is not None and r.col is not None}
    if not fixed:
        fixed = {name: (float(c), -float(r)) for name, (r, c) in directed_cells(model).items()}
    regions = [r.name for r in model.regions]
    if len(fixed) == len(regions):
        return {name: (x * cell, y * cell) for name, (x, y) in fixed.items()}

    graph = nx.Graph()
    graph.add_nodes_from(regions)
    graph.add_edges_from((t.source, t.target) for t in model.transitions
                         if t.source != t.target)
    layout = nx.spring_layout(graph, pos=fixed or None, fixed=list(fixed) or None, seed=7,
                              k=1.2 if fixed else None, scale=None if fixed else 1.0)
    span = 1.0 if fixed else max(1.0, len(regions) ** 0.5)
    return {name: (round(float(layout[name][0]) * span * cell, 3),
                   round(float(layout[name][1]) * span * cell, 3)) for name in regions}
