"""The map on a grid of cells, for the player: as text for a terminal, as SVG for a notebook.

A cell is ``@name+*!``: ``@`` where the robot is, ``+`` a cache, ``*`` a goal (the next one
is styled), ``~`` a hazard region and ``!`` one whose hazard is on. Regions sit on their
grid cells, else on the cells their edges' compass directions give
(:func:`gaitc.sim.placement.directed_cells`), else in reading order of the spring layout
the picture uses. Lines are lists of ``(text, style)`` pieces; a front end maps the style
names (:data:`STYLES`) to its colours or drops them. :meth:`MapGrid.svg` draws the same
cells as SVG with the colours of ``gaitc render map`` and needs no Graphviz, so a notebook
redraws it at every step.
"""

from __future__ import annotations

import math
from collections.abc import Collection, Sequence
from html import escape

from gaitc.sim.domain import model_goals
from gaitc.sim.placement import directed_cells, positions
from ltlcompiler.model import Model

#: Fill colours of the SVG cells, after gaitc.sim.map_view (cache green, hazard red when on).
FILLS = {"robot": "#1f3a93", "hazard_on": "#fcbba1", "hazard": "#fff3c4", "cache": "#b8e3b0",
         "goal": "#f3e5f5", "next_goal": "#e1bee7", "visited": "#e3f2fd", "": "#ffffff"}
SVG_CELL = 64  # pixels a cell

Piece = tuple[str, str]  # (text, style name; "" for none)
STYLES = ("robot", "hazard_on", "hazard", "cache", "goal", "next_goal", "visited", "legend")
LEGEND = "@ robot  + cache  * goal\n~ hazard region (! when on)"


def cells(model: Model) -> dict[str, tuple[int, int]]:
    """The (row, column) of every region in the text map, north up."""
    if all(r.row is not None and r.col is not None for r in model.regions):
        return {r.name: (int(r.row or 0), int(r.col or 0)) for r in model.regions}
    placed = directed_cells(model)
    if len(placed) == len(model.regions):
        low_r = min(r for r, _ in placed.values())
        low_c = min(c for _, c in placed.values())
        return {name: (r - low_r, c - low_c) for name, (r, c) in placed.items()}
    where = positions(model, 1.0)
    order = sorted(where, key=lambda name: (-round(where[name][1], 1), where[name][0]))
    width = max(1, math.ceil(math.sqrt(len(order))))
    return {name: divmod(i, width) for i, name in enumerate(order)}


class MapGrid:
    """The map of one model, drawn again for each state of a play."""

    def __init__(self, model: Model) -> None:
        self.model = model
        self.cells = cells(model)
        self.goals = {r for g in model_goals(model) for r in g.regions}
        self.hazard_of = {r: h.name for h in model.hazards for r in h.regions}
        self.width = max((len(name) for name in self.cells), default=1) + 4
        self.rows = 1 + max((r for r, _ in self.cells.values()), default=0)
        self.cols = 1 + max((c for _, c in self.cells.values()), default=0)
        self._at = {cell: name for name, cell in self.cells.items()}

    def _cell(self, name: str, robot: str | None, hazard: str | None,
              next_goal: Collection[str], visited: Collection[str]) -> Piece:
        flags = ""
        if name in self.model.caches:
            flags += "+"
        if name in self.goals:
            flags += "*"
        danger = self.hazard_of.get(name)
        if danger is not None:
            flags += "!" if danger == hazard else "~"
        text = ("@" if name == robot else " ") + name + flags
        if name == robot:
            style = "robot"
        elif danger is not None and danger == hazard:
            style = "hazard_on"
        elif name in next_goal:
            style = "next_goal"
        elif name in self.model.caches:
            style = "cache"
        elif name in self.goals:
            style = "goal"
        elif danger is not None:
            style = "hazard"
        elif name in visited:
            style = "visited"
        else:
            style = ""
        return text.ljust(self.width), style

    def lines(self, robot: str | None = None, hazard: str | None = None,
              next_goal: Collection[str] = (), visited: Collection[str] = ()
              ) -> list[list[Piece]]:
        """The map's lines with the robot in region ``robot`` and hazard set ``hazard`` on."""
        out: list[list[Piece]] = []
        for row in range(self.rows):
            line: list[Piece] = []
            for col in range(self.cols):
                name = self._at.get((row, col))
                line.append(self._cell(name, robot, hazard, next_goal, visited)
                            if name is not None else (" " * self.width, ""))
            out.append(line)
        return out

    def text(self, robot: str | None = None, hazard: str | None = None) -> str:
        """The map as plain text (no styles), for logs and tests."""
        return "\n".join("".join(t for t, _ in line).rstrip()
                         for line in self.lines(robot, hazard))

    def svg(self, robot: str | None = None, hazard: str | None = None,
            next_goal: Collection[str] = (), visited: Collection[str] = (),
            trail: Sequence[str] = ()) -> str:
        """The map as an SVG picture: a square a region with its marks, the robot as a dot
        and ``trail`` (the regions of the play, in order) as a line."""
        size = SVG_CELL
        width, height = self.cols * size + 2, self.rows * size + 2
        out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" '
               f'viewBox="0 0 {width} {height}" font-family="Helvetica, sans-serif">']
        centre: dict[str, tuple[int, int]] = {}
        for name, (row, col) in sorted(self.cells.items()):
            x, y = col * size + 1, row * size + 1
            centre[name] = (x + size // 2, y + size // 2)
            text, style = self._cell(name, None, hazard, next_goal, visited)
            border = "#c0392b" if style == "hazard_on" else "#888888"
            out.append(f'<rect x="{x}" y="{y}" width="{size - 2}" height="{size - 2}" rx="4" '
                       f'fill="{FILLS[style]}" stroke="{border}"/>')
            out.append(f'<text x="{x + 5}" y="{y + 15}" font-size="12">{escape(name)}</text>')
            marks = text.strip()[len(name):]
            if marks:
                out.append(f'<text x="{x + size - 6}" y="{y + size - 8}" font-size="12" '
                           f'text-anchor="end" fill="#555555">{escape(marks)}</text>')
        points = [centre[r] for r in trail if r in centre]
        if len(points) > 1:
            path = " ".join(f"{x},{y}" for x, y in points)
            out.append(f'<polyline points="{path}" fill="none" stroke="#1f3a93" '
                       'stroke-opacity="0.45" stroke-width="3"/>')
        if robot in centre:
            x, y = centre[robot]
            out.append(f'<circle cx="{x}" cy="{y + 6}" r="10" fill="{FILLS["robot"]}"/>')
        out.append("</svg>")
        return "\n".join(out)
