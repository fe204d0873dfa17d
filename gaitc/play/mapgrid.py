"""The map on a grid of cells, for the player: as text for a terminal, as SVG for a notebook.

A cell is ``@name+*!``: ``@`` where the robot is, ``+`` a cache, ``*`` a goal (the next one
is styled), ``~`` a hazard region and ``!`` one whose hazard is on. Regions sit on their
grid cells, else on the cells their edges' compass directions give
(:func:`gaitc.sim.placement.directed_cells`), else in reading order of the spring layout
the picture uses. Every cell of the text map takes the same number of characters, so each
grid column is a column of text; a map wider than the room it has (:meth:`MapGrid.fit`)
labels its cells with their shortest unambiguous names (:func:`short_names`), which the
legend spells out. Lines are lists of ``(text, style)`` pieces; a front end maps the style
names (:data:`STYLES`) to its colours or drops them. :meth:`MapGrid.svg` draws the same
cells as SVG with the colours of ``gaitc render map`` and needs no Graphviz, so a notebook
redraws it at every step.
"""

from __future__ import annotations

import math
import re
from collections.abc import Collection, Sequence
from dataclasses import dataclass
from html import escape

from gaitc.sim.domain import model_goals
from gaitc.sim.placement import directed_cells, positions
from ltlcompiler.model import Model

#: Fill colours of the SVG cells, after gaitc.sim.map_view (cache green, hazard red when on).
FILLS = {"robot": "#1f3a93", "hazard_on": "#fcbba1", "hazard": "#fff3c4", "cache": "#b8e3b0",
         "goal": "#f3e5f5", "next_goal": "#e1bee7", "visited": "#e3f2fd", "": "#ffffff"}
SVG_CELL = 64  # pixels a cell
WORDS = re.compile(r"[^\W\d_]+|\d+|[\W_]+")  # a name's words, numbers and the rest

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


def shared_start(names: Collection[str]) -> str:
    """The start that all ``names`` share, shorter than each of them ("" for one name)."""
    if len(set(names)) < 2:
        return ""
    first, last = min(names), max(names)  # what these two share, all the names between do
    size = next((i for i, (a, b) in enumerate(zip(first, last, strict=False)) if a != b),
                len(first))
    return first[:min(size, min(len(n) for n in names) - 1)]


@dataclass(frozen=True)
class ShortNames:
    """Labels for the cells of a map too wide for their names, and the legend's key to them."""

    labels: dict[str, str]  # name -> label
    key: tuple[str, ...]  # what the labels stand for, a phrase each


def _unique_starts(rests: dict[str, str]) -> dict[str, str]:
    """Each name's rest cut to its shortest start that begins no other rest (whole when
    the rest begins another)."""
    out = {}
    for name, rest in rests.items():
        others = [other for other in rests.values() if other != rest]
        out[name] = next((rest[:k] for k in range(1, len(rest))
                          if not any(other.startswith(rest[:k]) for other in others)), rest)
    return out


def _word_cuts(rests: dict[str, str]) -> tuple[int, dict[str, str]] | None:
    """The fewest letters each word of a rest may keep with the rests still apart (numbers
    kept whole, the rest dropped), and the labels so cut; None when no cut keeps them apart."""
    longest = max((len(rest) for rest in rests.values()), default=0)
    for letters in range(1, longest):
        cut = {name: "".join(run[:letters] if run[0].isalpha() else
                             run if run[0].isdigit() else "" for run in WORDS.findall(rest))
               for name, rest in rests.items()}
        if all(cut.values()) and len(set(cut.values())) == len(cut):
            return letters, cut
    return None


def _longest(labels: dict[str, str]) -> int:
    return max((len(label) for label in labels.values()), default=0)


def short_names(names: Collection[str]) -> ShortNames:
    """The shortest unambiguous labels of ``names``, which first lose their
    :func:`shared_start`: the shorter of each name cut to its shortest start that begins no
    other name (a name that begins another stays whole), and each name's words cut to as
    few letters as keep the labels apart (numbers kept whole, ``_`` and the like dropped:
    ``westroom_12`` is ``w12``)."""
    shared = shared_start(names)
    rests = {name: name[len(shared):] for name in sorted(names)}
    key = [f"names less {shared!r}"] if shared else []
    labels = _unique_starts(rests)
    cuts = _word_cuts(rests)
    if cuts is not None and _longest(cuts[1]) < _longest(labels):
        letters, labels = cuts
        example = next((n for n, rest in rests.items() if len(WORDS.findall(rest)) > 1), None)
        if example is not None:  # how the words make a label
            key.append(f"{labels[example]}: {rests[example]}")
        words = {run: run[:letters] for rest in rests.values() for run in WORDS.findall(rest)
                 if run[0].isalpha() and len(run) > letters}
        key += [f"{short}: {word}" for word, short in words.items()]
    else:
        key += [f"{label}: {rests[name]}" for name, label in labels.items()
                if label != rests[name]]
    return ShortNames(labels, tuple(key))


class MapGrid:
    """The map of one model, drawn again for each state of a play."""

    def __init__(self, model: Model) -> None:
        self.model = model
        self.cells = cells(model)
        self.goals = {r for g in model_goals(model) for r in g.regions}
        self.hazard_of = {r: h.name for h in model.hazards for r in h.regions}
        self.rows = 1 + max((r for r, _ in self.cells.values()), default=0)
        self.cols = 1 + max((c for _, c in self.cells.values()), default=0)
        self._at = {cell: name for name, cell in self.cells.items()}
        self._flags = max((len(self._marks(name, None)) for name in self.cells), default=0)
        self.short = short_names(self.cells)
        self.labels = {name: name for name in self.cells}  # as drawn in the text map
        self.gap = 1  # blank columns after each cell's marks

    @property
    def abbreviated(self) -> bool:
        """Whether the text map labels its cells with their short names."""
        return any(label != name for name, label in self.labels.items())

    @property
    def width(self) -> int:
        """The characters each cell takes in the text map: the robot's mark, the longest
        label, the most marks a cell has and the gap."""
        longest = max((len(label) for label in self.labels.values()), default=1)
        return 1 + longest + self._flags + self.gap

    def fit(self, room: int) -> bool:
        """Draw the rows in ``room`` characters if they fit: the cells' names with a blank
        after each cell, else without it, else their short names with the blank, else
        without it (which may not fit either: a front end then scrolls); whether the labels
        are the short names."""
        names = {name: name for name in self.cells}
        for labels, gap in ((names, 1), (names, 0), (self.short.labels, 1),
                            (self.short.labels, 0)):
            self.labels, self.gap = dict(labels), gap
            if self.cols * self.width <= room:
                break
        return self.abbreviated

    def legend(self) -> list[str]:
        """The legend's lines: the marks, then what the short names stand for, as wide as
        the map's rows (or as the marks' lines, when the map is narrower)."""
        out = LEGEND.splitlines()
        if not self.abbreviated:
            return out
        room = max(self.cols * self.width, *(len(line) for line in out))
        line = ""
        for phrase in self.short.key:
            if line and len(line) + 2 + len(phrase) > room:
                out.append(line)
                line = phrase
            else:
                line = f"{line}  {phrase}" if line else phrase
        return [*out, line] if line else out

    def _marks(self, name: str, hazard: str | None) -> str:
        """The marks of a cell after its name: cache, goal, hazard region (on or off)."""
        flags = ""
        if name in self.model.caches:
            flags += "+"
        if name in self.goals:
            flags += "*"
        danger = self.hazard_of.get(name)
        if danger is not None:
            flags += "!" if danger == hazard else "~"
        return flags

    def _cell(self, name: str, robot: str | None, hazard: str | None,
              next_goal: Collection[str], visited: Collection[str]) -> Piece:
        danger = self.hazard_of.get(name)
        text = ("@" if name == robot else " ") + self.labels[name] + self._marks(name, hazard)
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
            _, style = self._cell(name, None, hazard, next_goal, visited)
            border = "#c0392b" if style == "hazard_on" else "#888888"
            out.append(f'<rect x="{x}" y="{y}" width="{size - 2}" height="{size - 2}" rx="4" '
                       f'fill="{FILLS[style]}" stroke="{border}"/>')
            out.append(f'<text x="{x + 5}" y="{y + 15}" font-size="12">{escape(name)}</text>')
            marks = self._marks(name, hazard)
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
