"""Drawing the map: regions (grid or explicit graph) with caches, hazard sets, goals and start;
a run's path with step numbers and degrade/fail marks, and a leg-health timeline beside it
(the look of thesis figure 3.7); the spec view adds τ with its gaits and the gait map.
"""

from __future__ import annotations

from collections.abc import Sequence
from itertools import pairwise
from typing import TYPE_CHECKING

import pydot

from gaitc.diagnostics import UsageError
from gaitc.sim.domain import model_goals
from gaitc.sim.graphics import Picture, html
from gaitc.sim.placement import positions
from ltlcompiler.model import NO_GAIT, Model

if TYPE_CHECKING:
    from gaitc.sim.run import Run, Step

CELL = 1.6  # inches between grid cells
HAZARD_COLOURS = (("#c6dbef", "#2171b5"), ("#fcbba1", "#cb181d"), ("#dadaeb", "#6a51a3"),
                  ("#fdd0a2", "#d94801"), ("#c7e9c0", "#238b45"))
CACHE_FILL = "#b8e3b0"
HEALTHY, DEGRADED, FAILED, IN_USE = "#5b9bd5", "#f2c94c", "#d64541", "#1a9850"
PATH, PATH_DEGRADE, PATH_FAIL = "#1f3a93", "#e67e22", "#c0392b"
DEFAULT_MAX_STEPS = 30


def _positions(model: Model) -> dict[str, tuple[float, float]]:
    """Region centres in inches (:func:`gaitc.sim.placement.positions`)."""
    return positions(model, CELL)


def _graph(name: str) -> pydot.Dot:
    graph = pydot.Dot(name, graph_type="digraph", layout="neato", splines="true",
                      overlap="true", outputorder="edgesfirst", fontname="Helvetica")
    graph.set_node_defaults(fontname="Helvetica", fontsize="11")
    graph.set_edge_defaults(fontname="Helvetica", fontsize="9")
    return graph


def _region_nodes(graph: pydot.Dot, model: Model, pos: dict[str, tuple[float, float]],
                  active: dict[str, list[int]] | None = None) -> None:
    goals = {r for g in model_goals(model) for r in g.regions}
    colour = {h.name: HAZARD_COLOURS[i % len(HAZARD_COLOURS)]
              for i, h in enumerate(model.hazards)}
    hazard_of = {r: h.name for h in model.hazards for r in h.regions}
    for region in model.regions:
        name = region.name
        marks = []
        fill, border, width = "#ffffff", "#888888", "1"
        if name in model.caches:
            fill = CACHE_FILL
            marks.append('<FONT COLOR="#1b7837">● cache</FONT>')
        if name in hazard_of:
            light, strong = colour[hazard_of[name]]
            fill = light
            marks.append(f'<FONT COLOR="{strong}">▦ {html(hazard_of[name])}</FONT>')
            if active and active.get(hazard_of[name]):
                border, width = strong, "3"
        if name in goals:
            marks.append('<FONT COLOR="#b8860b">◆ goal</FONT>')
        if name == model.start:
            marks.append("▶ start")
            width = "3" if width == "1" else width
            border = "#000000" if border == "#888888" else border
        label = f"<<B>{html(name)}</B>" + "".join(
            f'<BR/><FONT POINT-SIZE="8">{m}</FONT>' for m in marks) + ">"
        x, y = pos[name]
        graph.add_node(pydot.Node(
            name, label=label, shape="box", style="filled", fillcolor=fill, color=border,
            penwidth=width, width="1.0", height="1.0", fixedsize="true", pos=f"{x},{y}!"))


def _bounds(pos: dict[str, tuple[float, float]]) -> tuple[float, float, float, float]:
    xs = [p[0] for p in pos.values()]
    ys = [p[1] for p in pos.values()]
    return min(xs), max(xs), min(ys), max(ys)


def _timeline(steps: Sequence[Step], legs: Sequence[str], full: dict[str, int],
              hazard_colour: dict[str, str]) -> str:
    """An HTML-like table: one column per step, rows region/gait/hazard and one per leg."""
    font = '<FONT POINT-SIZE="8">{}</FONT>'
    rows = ['<TR><TD ALIGN="LEFT"><B>step</B></TD>' + "".join(
        f"<TD><B>{s.index}</B></TD>" for s in steps) + "</TR>"]
    rows.append('<TR><TD ALIGN="LEFT">region</TD>' + "".join(
        f"<TD>{font.format(html(s.region))}</TD>" for s in steps) + "</TR>")
    rows.append('<TR><TD ALIGN="LEFT">gait</TD>' + "".join(
        f"<TD>{font.format(html('·' if s.gait == NO_GAIT else s.gait))}</TD>" for s in steps)
        + "</TR>")
    rows.append('<TR><TD ALIGN="LEFT">hazard</TD>' + "".join(
        f'<TD BGCOLOR="{hazard_colour.get(s.hazard, "#ffffff")}">'
        f"{font.format(html(s.hazard or ''))}</TD>" if s.hazard else "<TD> </TD>"
        for s in steps) + "</TR>")
    for leg in legs:
        cells = []
        for s in steps:
            level = s.level(leg)
            colour = HEALTHY if level >= full.get(leg, level) else (
                FAILED if level == 1 else DEGRADED)
            text = "✗" if leg in s.failed else f"{level}↓" if leg in s.degraded else str(level)
            border = f' COLOR="{IN_USE}" BORDER="3"' if leg in s.legs_used else ' BORDER="1"'
            cells.append(f'<TD BGCOLOR="{colour}"{border} WIDTH="22">{text}</TD>')
        rows.append(f'<TR><TD ALIGN="LEFT"><B>{html(leg)}</B></TD>{"".join(cells)}</TR>')
    return ('<<TABLE BORDER="0" CELLBORDER="0" CELLSPACING="2" CELLPADDING="2">'
            + "".join(rows) + "</TABLE>>")


def _table_width(steps: Sequence[Step]) -> float:
    """A generous estimate of the timeline's width in inches (8 pt text, 22 pt cells)."""
    points = 50.0
    for s in steps:
        longest = max(len(s.region), len(s.gait), len(s.hazard or ""), len(str(s.index)) * 2)
        points += max(26.0, 5.2 * longest + 8.0)
    return points / 72.0


def _legend(model: Model, with_run: bool) -> str:
    rows = [f'<TR><TD BGCOLOR="{CACHE_FILL}" WIDTH="14"> </TD><TD ALIGN="LEFT">cache</TD></TR>',
            '<TR><TD><FONT COLOR="#b8860b">◆</FONT></TD><TD ALIGN="LEFT">goal</TD></TR>',
            '<TR><TD>▶</TD><TD ALIGN="LEFT">start</TD></TR>']
    for i, h in enumerate(model.hazards):
        light = HAZARD_COLOURS[i % len(HAZARD_COLOURS)][0]
        rows.append(f'<TR><TD BGCOLOR="{light}"> </TD><TD ALIGN="LEFT">hazard set '
                    f"{html(h.name)}: {html(h.effect)}</TD></TR>")
    if with_run:
        rows += [f'<TR><TD BGCOLOR="{HEALTHY}"> </TD><TD ALIGN="LEFT">healthy leg</TD></TR>',
                 f'<TR><TD BGCOLOR="{DEGRADED}"> </TD><TD ALIGN="LEFT">degraded</TD></TR>',
                 f'<TR><TD BGCOLOR="{FAILED}"> </TD><TD ALIGN="LEFT">failed</TD></TR>',
                 '<TR><TD>✗ ↓</TD><TD ALIGN="LEFT">this step\'s gait fails / degrades the '
                 "leg (its level drops on the next step)</TD></TR>",
                 f'<TR><TD COLOR="{IN_USE}" BORDER="3"> </TD><TD ALIGN="LEFT">leg in use'
                 "</TD></TR>",
                 f'<TR><TD><FONT COLOR="{PATH_FAIL}">→</FONT></TD><TD ALIGN="LEFT">'
                 "move whose gait fails a leg (↓ degrades one)</TD></TR>"]
    return ('<<TABLE BORDER="1" COLOR="#bbbbbb" CELLBORDER="0" CELLSPACING="2">'
            + "".join(rows) + "</TABLE>>")


def _path(graph: pydot.Dot, steps: Sequence[Step]) -> list[tuple[str, str, str, str]]:
    """Edges for the run: one per directed region pair, labelled with its step numbers.

    The edge into step t is the move made with step t's gait, so it carries the marks of
    the legs that gait wears out (their level drops at step t + 1, see Run.add).  A busy
    edge (more than two steps) and a pair travelled both ways, whose labels would lie on
    top of each other, get a letter at the arrow head instead; the letters and their
    steps are returned as rows (key, source, target, steps) for a side table."""
    moves: dict[tuple[str, str], list[Step]] = {}
    for before, after in pairwise(steps):
        moves.setdefault((before.region, after.region), []).append(after)
    keyed: list[tuple[str, str, str, str]] = []
    for (src, dst), taken in moves.items():
        words = [f"{s.index}{'✗' if s.failed else '↓' if s.degraded else ''}" for s in taken]
        colour = PATH_FAIL if any(s.failed for s in taken) else (
            PATH_DEGRADE if any(s.degraded for s in taken) else PATH)
        extra: dict[str, str] = {}
        if len(taken) > 2 or (src != dst and (dst, src) in moves):
            key = _key(len(keyed))
            keyed.append((key, src, dst, ", ".join(words)))
            extra = {"headlabel": key, "labeldistance": "1.6", "labelfontsize": "10"}
        else:
            extra = {"label": ", ".join(words)}
        edge = pydot.Edge(src, dst, color=colour, fontcolor=colour, penwidth="2.2",
                          arrowsize="0.8")
        for name, value in extra.items():
            edge.set(name, value)
        graph.add_edge(edge)
    return keyed


def _key(index: int) -> str:
    letters = "ABCDEFGHIJKLMNOPQRSTUVWXYZ"
    return letters[index % 26] * (1 + index // 26)


def _moves_table(rows: Sequence[tuple[str, str, str, str]]) -> str:
    cells = "".join(f'<TR><TD><B>{html(k)}</B></TD><TD ALIGN="LEFT">{html(a)} → {html(b)}'
                    f'</TD><TD ALIGN="LEFT">{html(steps)}</TD></TR>' for k, a, b, steps in rows)
    return ('<<TABLE BORDER="1" COLOR="#bbbbbb" CELLBORDER="0" CELLSPACING="2">'
            '<TR><TD COLSPAN="3"><B>moves (steps)</B></TD></TR>' + cells + "</TABLE>>")


def map_view(model: Model, run: Run | None = None,
             max_steps: int = DEFAULT_MAX_STEPS) -> Picture:
    """The region map; with ``run``, its first ``max_steps`` steps and the leg timeline."""
    pos = _positions(model)
    graph = _graph("map")
    graph.set("label", html(model.name or "map"))
    graph.set("labelloc", "t")
    steps = list(run.steps[: max_steps + 1]) if run is not None else []
    active: dict[str, list[int]] = {}
    for s in steps:
        if s.hazard is not None:
            active.setdefault(s.hazard, []).append(s.index)
    _region_nodes(graph, model, pos, active)
    grid = all(r.row is not None for r in model.regions)
    if not grid:
        _transitions(graph, model, labelled=False)
    notes: list[str] = []
    x0, x1, y0, y1 = _bounds(pos)
    if steps:
        keyed = _path(graph, steps)
        if keyed:
            graph.add_node(pydot.Node(
                "moves", shape="plaintext", label=_moves_table(keyed),
                pos=f"{x1 + 0.9 + _table_width(steps) / 2:.2f},"
                    f"{y0 - 0.9 - 0.1 * len(keyed):.2f}!"))
        full = {leg.name: leg.health for leg in model.legs}
        colours = {h.name: HAZARD_COLOURS[i % len(HAZARD_COLOURS)][0]
                   for i, h in enumerate(model.hazards)}
        legs = list(run.legs) if run is not None and run.legs else [leg.name for leg in
                                                                     model.legs]
        width = _table_width(steps)
        graph.add_node(pydot.Node(
            "timeline", shape="plaintext", label=_timeline(steps, legs, full, colours),
            pos=f"{x1 + 0.9 + width / 2:.2f},{(y0 + y1) / 2:.2f}!"))
        if run is not None and len(run.steps) > len(steps):
            notes.append(f"showing steps 0..{len(steps) - 1} of {len(run.steps) - 1}")
    legend_y = y0 - 1.3 - 0.16 * (len(model.hazards) + (5 if steps else 0))
    graph.add_node(pydot.Node("legend", shape="plaintext", label=_legend(model, bool(steps)),
                              pos=f"{x0 + 0.6:.2f},{legend_y:.2f}!"))
    if notes:
        graph.set("label", html(f"{model.name or 'map'} ({notes[0]})"))
    return Picture(graph, tuple(notes))


def _transitions(graph: pydot.Dot, model: Model, labelled: bool) -> None:
    for t in model.transitions:
        if t.source == t.target:
            continue
        gaits = [g for g in t.gaits if g != NO_GAIT]
        label = "\n".join(gaits) if labelled else ""
        graph.add_edge(pydot.Edge(t.source, t.target, label=label, color="#9a9a9a",
                                  fontcolor="#555555", fontsize="8", arrowsize="0.6"))


def _gait_table(model: Model) -> str:
    legs = [leg.name for leg in model.legs]
    head = "<TR><TD><B>gait</B></TD>" + "".join(f"<TD><B>{html(x)}</B></TD>" for x in legs)
    rows = [head + "</TR>"]
    for gait in model.gaits:
        if gait.name == NO_GAIT:
            continue
        kind = " (correction)" if gait.kind.value == "correction" else ""
        cells = "".join(f'<TD BGCOLOR="{HEALTHY if x in gait.legs else "#ffffff"}"> </TD>'
                        for x in legs)
        rows.append(f'<TR><TD ALIGN="LEFT">{html(gait.name + kind)}</TD>{cells}</TR>')
    return ('<<TABLE BORDER="0" CELLBORDER="1" CELLSPACING="0" CELLPADDING="3">'
            + "".join(rows) + "</TABLE>>")


def spec_view(model: Model) -> Picture:
    """The region graph τ with the gaits of each move, and which legs each gait uses."""
    pos = _positions(model)
    graph = _graph("spec")
    graph.set("label", html(f"{model.name or 'spec'}: regions, moves and gaits"))
    graph.set("labelloc", "t")
    _region_nodes(graph, model, pos)
    _transitions(graph, model, labelled=True)
    x0, x1, y0, y1 = _bounds(pos)
    width = 1.2 + 0.3 * len(model.legs)
    graph.add_node(pydot.Node("gaits", shape="plaintext", label=_gait_table(model),
                              pos=f"{x1 + 1.0 + width / 2:.2f},{(y0 + y1) / 2:.2f}!"))
    legend_y = y0 - 1.3 - 0.16 * len(model.hazards)
    graph.add_node(pydot.Node("legend", shape="plaintext", label=_legend(model, False),
                              pos=f"{x0 + 0.6:.2f},{legend_y:.2f}!"))
    return Picture(graph)


def run_view(run: Run, max_steps: int = DEFAULT_MAX_STEPS) -> Picture:
    """A run on its map (needs ``run.model``, set by the simulator or by the caller)."""
    if run.model is None:

        raise UsageError("this run has no model attached; draw it with map_view(model, run)")
    return map_view(run.model, run, max_steps)
