"""Drawing the projected controller (:mod:`gaitc.sim.policy`): small multiples on the map, one
table per region the controller is in (its rules: when, which gait towards which region,
how many decisions), and an arrow per region move the controller makes, with its gaits.

Each table sits where :func:`gaitc.sim.placement.positions` puts its region on the map (grid
cells, compass directions, else the seeded spring layout), the map stretched so tables do
not overlap: on a grid each column is as wide and each row as tall as its largest table,
elsewhere every cell is as large as the largest.  Regions the controller never leaves are
small dashed boxes; regions are marked as on the map (cache, hazard set, goal, start).
"""

from __future__ import annotations

import pydot

from gaitc.sim.domain import Domain
from gaitc.sim.graphics import Picture, html
from gaitc.sim.placement import positions
from gaitc.sim.policy import Policy

MAX_GAITS_ON_EDGE = 4
CHAR_WIDTH, ROW_HEIGHT, GAP = 0.08, 0.24, 0.9  # inches, at the tables' 10 pt font
SMALL = (1.2, 0.5)  # a dashed box


def _sizes(policy: Policy) -> dict[str, tuple[float, float]]:
    """An upper estimate of each region table's width and height in inches."""
    out = {}
    for region in policy.regions:
        rows = [r for r in policy.rules if r.region == region]
        chars = max(len(r.when()) + len(r.what()) for r in rows) + 6
        out[region] = (max(chars, 40) * CHAR_WIDTH, (len(rows) + 2) * ROW_HEIGHT + 0.2)
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


def _layout(policy: Policy, domain: Domain, drawn: list[str]) -> dict[str, tuple[float, float]]:
    size = _sizes(policy)
    full = {r: size.get(r, SMALL) for r in drawn}
    cells = positions(domain.model, 1.0)
    on_grid = all(
        float(cells[r][0]).is_integer() and float(cells[r][1]).is_integer() for r in drawn
    )
    if on_grid:
        xs = _stretch({r: cells[r][0] for r in drawn}, {r: full[r][0] for r in drawn})
        ys = _stretch({r: -cells[r][1] for r in drawn}, {r: full[r][1] for r in drawn})
        return {r: (xs[r], -ys[r]) for r in drawn}
    cw = max(w for w, _ in full.values()) + GAP
    ch = max(h for _, h in full.values()) + GAP
    return {r: (cells[r][0] * cw, cells[r][1] * ch) for r in drawn}


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
    graph.set_node_defaults(shape="plaintext", fontname="Helvetica", fontsize="10")
    graph.set_edge_defaults(fontname="Helvetica", fontsize="9", color="#555555")
    gaits: dict[tuple[str, str], set[str]] = {}
    targets: set[str] = set()
    drawn: list[str] = []
    for region in policy.regions:
        rows = [r for r in policy.rules if r.region == region]
        cells = "".join(
            f'<TR><TD ALIGN="LEFT">{html(rule.when())}</TD>'
            f'<TD ALIGN="LEFT">{html(rule.what())}</TD></TR>'
            for rule in rows
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
    place = _layout(policy, domain, drawn)
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
    return Picture(graph, (policy.summary(), *policy.notes))
