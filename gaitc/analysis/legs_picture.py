"""The resilience picture, in the style of thesis Figure 3.6 (right): the robot's legs in
their places around the chassis, labelled with index and health, coloured by how critical
each is, with the minimal fatal sets listed beside them.

Legs are placed counter-clockwise from the front (L1 points north, then 360/n degrees
apart), as the thesis numbers them; Graphviz's neato draws the pinned layout.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import pydot

from gaitc.sim.graphics import Picture, html, quote

if TYPE_CHECKING:
    from gaitc.analysis.resilience import Resilience

RADIUS = 1.6  # inches from the chassis centre to a leg
COLOURS = {  # criticality → (fill, legend)
    "single": ("#d64541", "single point of failure"),
    "pair": ("#f39c12", "in a fatal pair"),
    "set": ("#f7dc6f", "in a larger minimal fatal set"),
    "spare": ("#82c785", "in no minimal fatal set"),
    "failed": ("#bdbdbd", "already failed (health 1)"),
}


def criticality(report: Resilience, leg: str) -> str:
    """How critical ``leg`` is: the smallest minimal fatal set it belongs to."""
    if leg in report.already_failed:
        return "failed"
    sizes = [len(s) for s in report.minimal_fatal_sets if leg in s]
    if not sizes:
        return "spare"
    smallest = min(sizes)
    return "single" if smallest == 1 else "pair" if smallest == 2 else "set"


def legs_picture(report: Resilience) -> Picture:
    graph = pydot.Dot("resilience", graph_type="graph", layout="neato",
                      fontname="Helvetica", label=quote(f"{report.file}: leg criticality"),
                      labelloc="t", bgcolor="white")
    graph.set_node_defaults(fontname="Helvetica", fontsize="11")
    graph.add_node(pydot.Node("chassis", label='""', shape="circle", width="1.2",
                              style="filled", fillcolor="#eeeeee", pos='"0,0!"'))
    n = max(len(report.legs), 1)
    for index, (leg, health) in enumerate(report.legs):
        angle = math.pi / 2 + 2 * math.pi * index / n
        x, y = RADIUS * math.cos(angle), RADIUS * math.sin(angle)
        fill = COLOURS[criticality(report, leg)][0]
        label = f"<<b>{html(leg)}</b><br/>h = {health}>"
        graph.add_node(pydot.Node(quote(leg), label=label, shape="circle", width="0.75",
                                  fixedsize="true", style="filled", fillcolor=fill,
                                  pos=quote(f"{x:.2f},{y:.2f}!")))
        graph.add_edge(pydot.Edge("chassis", quote(leg), penwidth="2", color="#777777"))
    graph.add_node(pydot.Node("legend", shape="plaintext", label=_legend(report),
                              pos=quote(f"{RADIUS + 2.6:.2f},0!")))
    return Picture(graph)


def _legend(report: Resilience) -> str:
    rows = ['<tr><td colspan="2" align="left"><b>minimal fatal sets</b></td></tr>']
    shown = report.minimal_fatal_sets[:16]
    for s in shown:
        rows.append(f'<tr><td colspan="2" align="left">{{{html(", ".join(s))}}}</td></tr>')
    if len(report.minimal_fatal_sets) > len(shown):
        rows.append(f'<tr><td colspan="2" align="left">... and '
                    f'{len(report.minimal_fatal_sets) - len(shown)} more</td></tr>')
    if not report.minimal_fatal_sets:
        rows.append('<tr><td colspan="2" align="left">none</td></tr>')
    rows.append(f'<tr><td colspan="2" align="left">survives any {report.any_time_k} leg(s) '
                'breaking during the run</td></tr>')
    for fill, text in COLOURS.values():
        rows.append(f'<tr><td bgcolor="{fill}" width="14"> </td>'
                    f'<td align="left">{html(text)}</td></tr>')
    return "<<table border=\"0\" cellspacing=\"2\">" + "".join(rows) + "</table>>"
