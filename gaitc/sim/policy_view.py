"""Drawing controllers as rules: the projected controller (:mod:`gaitc.sim.policy`) as small
multiples on the map, one table per region the controller is in (its rules: when, which
gait towards which region, how many decisions), with an arrow per region move and its gaits;
and a compact controller's rule tables (:mod:`gaitc.compact.rules`), one table per goal.

Each region table sits where :func:`gaitc.sim.placement.positions` puts its region on the map
(grid cells, compass directions, else the seeded spring layout), the map stretched so tables
do not overlap: on a grid each column is as wide and each row as tall as its largest table,
elsewhere every cell is as large as the largest.  Regions the controller never leaves are
small dashed boxes; regions are marked as on the map (cache, hazard set, goal, start).

Pictures stay readable at their natural size: long conditions wrap inside their cell, and
a map whose tables would spread wider than :data:`MAX_WIDTH` inches is drawn as rows of
tables in map order instead (the arrows still join them), so no picture is scaled down.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING

import pydot

from gaitc.sim.domain import Domain
from gaitc.sim.graphics import Picture, html
from gaitc.sim.placement import positions
from gaitc.sim.policy import Policy, Rule

if TYPE_CHECKING:
    from gaitc.compact.rules import RuleTables

MAX_GAITS_ON_EDGE = 4
CHAR_WIDTH, ROW_HEIGHT, GAP = 0.08, 0.24, 0.9  # inches, at the tables' 10 pt font
SMALL = (1.2, 0.5)  # a dashed box
#: The widest picture drawn on the map, in inches (1,440 px at Graphviz's 96 dpi); wider
#: maps are drawn as rows of tables of at most this width
MAX_WIDTH = 15.0
WHEN_WRAP, WHAT_WRAP = 44, 36  # characters per line in a region table's cells
RULE_WRAP, MOVE_WRAP = 60, 28  # the same in a compact controller's tables
FONT = "10"  # points: never scaled down


def wrap(text: str, width: int) -> list[str]:
    """``text`` in lines of at most ``width`` characters, broken after its commas (a part
    longer than ``width`` gets a line of its own); joined again they give ``text``."""
    lines: list[str] = []
    for part in text.split(", "):
        if lines and len(lines[-1]) + 2 + len(part) <= width:
            lines[-1] += ", " + part
        else:
            if lines:
                lines[-1] += ","
            lines.append(part)
    return lines or [""]


def _cell(lines: Sequence[str], extra: str = "") -> str:
    """A left-aligned HTML-like table cell of ``lines``."""
    body = "".join(f'{html(line)}<BR ALIGN="LEFT"/>' for line in lines)
    return f'<TD ALIGN="LEFT" BALIGN="LEFT"{extra}>{body}</TD>'


def _rule_lines(rule: Rule) -> tuple[list[str], list[str]]:
    return wrap(rule.when(), WHEN_WRAP), wrap(rule.what(), WHAT_WRAP)


def _sizes(policy: Policy) -> dict[str, tuple[float, float]]:
    """An upper estimate of each region table's width and height in inches."""
    out = {}
    for region in policy.regions:
        cells = [_rule_lines(r) for r in policy.rules if r.region == region]
        chars = max(max(map(len, when)) + max(map(len, what)) for when, what in cells) + 6
        lines = sum(max(len(when), len(what)) for when, what in cells)
        out[region] = (max(chars, 40) * CHAR_WIDTH, (lines + 2) * ROW_HEIGHT + 0.2)
    return out


def _stretch(cells: dict[str, float], sizes: dict[str, float]) -> dict[str, float]:
    """Centres along one axis: cells in order, each band as wide as its largest table."""
    bands = sorted(set(cells.values()))
    width = {b: max((sizes[r] for r, c in cells.items() if c == b), default=0.0) for b in bands}
    centre, edge = {}, 0.0
    for b in bands:
        centre[b] = edge + width[b] / 2
        edge += width[b] + GAP
    return {r: centre[c] for r, c in cells.items()}


def _layout(policy: Policy, domain: Domain, drawn: list[str]
            ) -> tuple[dict[str, tuple[float, float]], bool]:
    """Each table's centre in inches, and whether the map was too wide to follow (the tables
    are then rows in map order, each map row starting a new one, each at most
    :data:`MAX_WIDTH` wide)."""
    size = _sizes(policy)
    full = {r: size.get(r, SMALL) for r in drawn}
    cells = positions(domain.model, 1.0)
    on_grid = all(
        float(cells[r][0]).is_integer() and float(cells[r][1]).is_integer() for r in drawn
    )
    if on_grid:
        xs = _stretch({r: cells[r][0] for r in drawn}, {r: full[r][0] for r in drawn})
        ys = _stretch({r: -cells[r][1] for r in drawn}, {r: full[r][1] for r in drawn})
        place = {r: (xs[r], -ys[r]) for r in drawn}
    else:
        cw = max(w for w, _ in full.values()) + GAP
        ch = max(h for _, h in full.values()) + GAP
        place = {r: (cells[r][0] * cw, cells[r][1] * ch) for r in drawn}
    left = min(place[r][0] - full[r][0] / 2 for r in drawn)
    right = max(place[r][0] + full[r][0] / 2 for r in drawn)
    if right - left <= MAX_WIDTH:
        return place, False
    order = sorted(drawn, key=lambda r: (-cells[r][1], cells[r][0]))
    bands = {r: -cells[r][1] if on_grid else 0.0 for r in drawn}
    return _rows(order, bands, full), True


def _rows(order: list[str], bands: dict[str, float], size: dict[str, tuple[float, float]]
          ) -> dict[str, tuple[float, float]]:
    """Tables left to right in ``order``, a new row (downwards) for each new band (a map
    row) and whenever the next table would pass :data:`MAX_WIDTH`."""
    rows: list[list[str]] = [[]]
    width = 0.0
    for region in order:
        w = size[region][0]
        if rows[-1] and (width + GAP + w > MAX_WIDTH or bands[region] != bands[rows[-1][0]]):
            rows.append([])
            width = 0.0
        width += (GAP if rows[-1] else 0.0) + w
        rows[-1].append(region)
    place, top = {}, 0.0
    for row in rows:
        height = max(size[r][1] for r in row)
        x = 0.0
        for region in row:
            w = size[region][0]
            place[region] = (x + w / 2, top - height / 2)
            x += w + GAP
        top -= height + GAP
    return place


def _marks(domain: Domain, region: str) -> str:
    model = domain.model
    marks = []
    if region in model.caches:
        marks.append("cache")
    marks += [f"hazard {h}" for h, regions in domain.hazard_regions.items() if region in regions]
    if any(region in g.regions for g in domain.goals):
        marks.append("goal")
    if region == model.start:
        marks.append("start")
    return f" ({', '.join(marks)})" if marks else ""


def policy_view(policy: Policy, domain: Domain) -> Picture:
    """Small multiples of ``policy``: a table of rules per region, arrows for its moves."""
    graph = pydot.Dot(
        "policy",
        graph_type="digraph",
        layout="neato",
        splines="true",
        overlap="true",
        fontname="Helvetica",
    )
    graph.set_node_defaults(shape="plaintext", fontname="Helvetica", fontsize=FONT)
    graph.set_edge_defaults(fontname="Helvetica", fontsize="9", color="#555555")
    gaits: dict[tuple[str, str], set[str]] = {}
    targets: set[str] = set()
    drawn: list[str] = []
    for region in policy.regions:
        rows = [r for r in policy.rules if r.region == region]
        cells = "".join(
            f"<TR>{_cell(when)}{_cell(what)}</TR>" for when, what in map(_rule_lines, rows)
        )
        label = (
            f'<<TABLE BORDER="0" CELLBORDER="1" CELLSPACING="0" CELLPADDING="3">'
            f'<TR><TD COLSPAN="2" BGCOLOR="#dde4f0"><B>{html(region)}</B>'
            f"{html(_marks(domain, region))}</TD></TR>"
            f"<TR><TD><I>when</I></TD><TD><I>gait → next region (decisions)</I></TD></TR>"
            f"{cells}</TABLE>>"
        )
        graph.add_node(pydot.Node(region, label=label))
        drawn.append(region)
        for rule in rows:
            for move, _ in rule.moves:
                if move.target != region:
                    gaits.setdefault((region, move.target), set()).add(move.gait)
                    targets.add(move.target)
    for region in domain.regions:  # regions entered but never left within the projection
        if region in targets and region not in policy.regions:
            graph.add_node(
                pydot.Node(
                    region,
                    shape="box",
                    style="rounded,dashed",
                    label=f"{region}{_marks(domain, region)}",
                )
            )
            drawn.append(region)
    place, rowed = _layout(policy, domain, drawn)
    for node in graph.get_nodes():
        name = node.get_name().strip('"')
        if name in place:  # not the "node" defaults
            node.set("pos", f"{place[name][0]:.2f},{place[name][1]:.2f}!")
    order = {r: i for i, r in enumerate(domain.regions)}
    for (src, dst), used in sorted(
        gaits.items(), key=lambda kv: (order[kv[0][0]], order[kv[0][1]])
    ):
        names = sorted(used, key=list(domain.gait_legs).index)
        shown = ", ".join(names[:MAX_GAITS_ON_EDGE])
        if len(names) > MAX_GAITS_ON_EDGE:
            shown += f" (+{len(names) - MAX_GAITS_ON_EDGE})"
        graph.add_edge(pydot.Edge(src, dst, label=shown))
    notes = (policy.summary(), *policy.notes)
    if rowed:
        notes += (f"the tables on the map would be wider than {MAX_WIDTH:g} in: they are drawn "
                  "in rows in map order (north to south, west to east)",)
    return Picture(graph, notes)



def _rules_table(title: str, rules: Sequence[tuple[str, str, bool]]) -> str:
    """An HTML-like table: a title row, then one row per rule (when, move), the never used
    ones grey."""
    rows = []
    for when, move, used in rules:
        extra = "" if used else ' BGCOLOR="#eeeeee"'
        rows.append(f"<TR>{_cell(wrap(when, RULE_WRAP), extra)}"
                    f"{_cell(wrap(move, MOVE_WRAP), extra)}</TR>")
    return (f'<<TABLE BORDER="0" CELLBORDER="1" CELLSPACING="0" CELLPADDING="3">'
            f'<TR><TD COLSPAN="2" BGCOLOR="#dde4f0"><B>{html(title)}</B></TD></TR>'
            f"<TR><TD><I>when</I></TD><TD><I>move</I></TD></TR>{''.join(rows)}</TABLE>>")


def rules_view(tables: RuleTables) -> Picture:
    """A compact controller's rules (the ones its text lists): one table per goal (and the
    start), stacked from top to bottom, so the picture is as wide as its widest table
    however many goals and rules there are."""
    graph = pydot.Dot("rules", graph_type="digraph", rankdir="TB", fontname="Helvetica",
                      nodesep="0.3", ranksep="0.3")
    graph.set_node_defaults(shape="plaintext", fontname="Helvetica", fontsize=FONT)
    head = [f"compact controller: {tables.sizes}"]
    line = tables.reach_line()
    if line is not None:
        head.append(line)
    graph.add_node(pydot.Node("title", shape="plaintext", label="<" + "<BR/>".join(
        html(h) for h in [x for part in head for x in wrap(part, RULE_WRAP + MOVE_WRAP)])
                                                              + ">"))
    parts: list[tuple[str, tuple[tuple[str, str, bool], ...]]] = []
    start = tables.shown(tables.start)
    if start:
        parts.append(("start", tuple((r.when, r.said, r.used) for r in start)))
    for label, rules in tables.shown_goals():
        parts.append((f"pursuing {label} ({len(rules)} rule{'' if len(rules) == 1 else 's'})",
                      tuple((r.when, r.said, r.used) for r in rules)))
    previous = "title"
    for k, (title, rows) in enumerate(parts):
        graph.add_node(pydot.Node(f"table{k}", label=_rules_table(title, rows)))
        graph.add_edge(pydot.Edge(previous, f"table{k}", style="invis"))
        previous = f"table{k}"
    return Picture(graph, tuple(head))
