"""Drawing the projected controller (:mod:`gaitsim.policy`): small multiples, one table per
region the controller is in (its rules: when, which gait towards which region, how many
decisions), and an arrow per region move the controller makes, labelled with its gaits.

Laid out by Graphviz's ``dot`` (tables never overlap); regions are marked as on the map
(cache, hazard set, goal, start).
"""

from __future__ import annotations

import pydot

from gaitsim.domain import Domain
from gaitsim.graphics import Picture, html
from gaitsim.policy import Policy

MAX_GAITS_ON_EDGE = 4


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
        rankdir="LR",
        nodesep="0.4",
        ranksep="0.8",
        fontname="Helvetica",
    )
    graph.set_node_defaults(shape="plaintext", fontname="Helvetica", fontsize="10")
    graph.set_edge_defaults(fontname="Helvetica", fontsize="9", color="#555555")
    gaits: dict[tuple[str, str], set[str]] = {}
    targets: set[str] = set()
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
