"""Drawings: SVG top views of poses (legs, contacts, contact polygon, CG) and the gait graph.

Top views are written as plain SVG text; the gait graph (or a window of it around a gait)
goes through pydot, rendered by Graphviz's ``dot`` when it is installed, else kept as .dot.
"""

from __future__ import annotations

import shutil
from pathlib import Path

import numpy as np
import pydot

from gaitgraph.cycles import GaitCycle
from gaitgraph.graph import GaitGraph, PoseKey
from gaitgraph.kinematics import Array, forward, leg_polyline, valve_int
from gaitgraph.poses import support_planes
from gaitgraph.robot import Robot


def _hull(points: list[tuple[float, float]]) -> list[tuple[float, float]]:
    """Convex hull, counter-clockwise (Andrew's monotone chain)."""
    pts = sorted(set(points))
    if len(pts) < 3:
        return pts

    def turn(o: tuple[float, float], a: tuple[float, float], b: tuple[float, float]) -> float:
        return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])

    lower: list[tuple[float, float]] = []
    upper: list[tuple[float, float]] = []
    for p in pts:
        while len(lower) >= 2 and turn(lower[-2], lower[-1], p) <= 0:
            lower.pop()
        lower.append(p)
    for p in reversed(pts):
        while len(upper) >= 2 and turn(upper[-2], upper[-1], p) <= 0:
            upper.pop()
        upper.append(p)
    return lower[:-1] + upper[:-1]


def pose_svg(robot: Robot, key: PoseKey, title: str = "") -> str:
    """Top view of one pose, levelled onto its support plane (x right, y up)."""
    valves, contacts = key
    geo = forward(robot, [valve_int(valves)])
    table = support_planes(robot, geo)
    names = robot.contact_names
    mask = sum(1 << names.index(c) for c in contacts)
    rows = np.nonzero(table.mask == mask)[0]
    rot: Array = table.rotation[rows[0]] if len(rows) else np.eye(3)
    legs = [leg_polyline(geo, 0, j, leg.length) @ rot.T for j, leg in enumerate(robot.legs)]
    outline = [rot @ np.array([x, y, 0.0]) for x, y in robot.outline]
    feet = geo.contacts[0] @ rot.T
    cg = rot @ geo.cg[0]
    xs = [p[0] for line in legs for p in line] + [p[0] for p in outline] + [float(cg[0])]
    ys = [p[1] for line in legs for p in line] + [p[1] for p in outline] + [float(cg[1])]
    pad, scale = 20.0, 2.0
    x0, y1 = min(xs) - pad, max(ys) + pad
    width, height = (max(xs) - min(xs) + 2 * pad) * scale, (max(ys) - min(ys) + 2 * pad) * scale

    def pt(x: float, y: float) -> str:
        return f"{(x - x0) * scale:.1f},{(y1 - y) * scale:.1f}"

    out = [
        f'<svg xmlns="http://www.w3.org/2000/svg" width="{width:.0f}" height="{height + 20:.0f}">',
        f'<text x="4" y="{height + 14:.0f}" font-family="monospace" font-size="11">'
        f"{title} {valves} on {', '.join(contacts)}</text>",
    ]
    if outline:
        poly = " ".join(pt(p[0], p[1]) for p in outline)
        out.append(f'<polygon points="{poly}" fill="#ddd" stroke="#555"/>')
    hull = _hull(
        [(float(feet[names.index(c)][0]), float(feet[names.index(c)][1])) for c in contacts]
    )
    if len(hull) >= 3:
        poly = " ".join(pt(x, y) for x, y in hull)
        out.append(f'<polygon points="{poly}" fill="none" stroke="black" stroke-dasharray="4,3"/>')
    for leg, line in zip(robot.legs, legs, strict=False):
        path = " ".join(pt(p[0], p[1]) for p in line)
        out.append(f'<polyline points="{path}" fill="none" stroke="#36c" stroke-width="4"/>')
        tip = line[-1]
        out.append(
            f'<text x="{(tip[0] - x0) * scale + 5:.1f}" y="{(y1 - tip[1]) * scale:.1f}" '
            f'font-size="10">{leg.name}</text>'
        )
    for c in contacts:
        p = feet[names.index(c)]
        out.append(
            f'<circle cx="{(p[0] - x0) * scale:.1f}" cy="{(y1 - p[1]) * scale:.1f}" '
            'r="6" fill="none" stroke="red" stroke-width="2"/>'
        )
    out.append(
        f'<circle cx="{(cg[0] - x0) * scale:.1f}" cy="{(y1 - cg[1]) * scale:.1f}" '
        'r="4" fill="green"/>'
    )
    out.append("</svg>")
    return "\n".join(out) + "\n"


def graph_dot(graph: GaitGraph, gait: GaitCycle | None = None, window: int | None = 1) -> pydot.Dot:
    """The gait graph, or with ``gait`` and ``window`` only poses within ``window`` edges of
    the gait; the gait's poses and transitions are drawn in red."""
    nodes = set(range(len(graph)))
    on_gait = set(gait.poses) if gait is not None else set()
    gait_edges = set()
    if gait is not None:
        gait_edges = {(m.source, m.target) for m in gait.motions}
        if window is not None:
            nodes = set(on_gait)
            for _ in range(window):
                near = {
                    int(b)
                    for a, b in zip(graph.edges.src, graph.edges.dst, strict=False)
                    if int(a) in nodes
                }
                near |= {
                    int(a)
                    for a, b in zip(graph.edges.src, graph.edges.dst, strict=False)
                    if int(b) in nodes
                }
                nodes |= near
    dot = pydot.Dot("gait_graph", graph_type="digraph", rankdir="LR")
    for n in sorted(nodes):
        valves, contacts = graph.key(n)
        color = "red" if n in on_gait else "black"
        dot.add_node(
            pydot.Node(
                str(n),
                label=f'"{valves}\\n{" ".join(contacts)}"',
                shape="box",
                color=color,
                fontname="monospace",
            )
        )
    for i in range(len(graph.edges)):
        m = graph.motion(i)
        if m.source in nodes and m.target in nodes:
            red = (m.source, m.target) in gait_edges
            dot.add_edge(
                pydot.Edge(
                    str(m.source),
                    str(m.target),
                    color="red" if red else "gray",
                    label=f'"{m.dx:.0f},{m.dy:.0f}"',
                    fontsize="8",
                )
            )
    return dot


def write_drawings(
    robot: Robot, graph: GaitGraph, gaits: list[GaitCycle], directory: str
) -> list[str]:
    """Write the graph drawing and a top view of each pose of each gait; returns the paths."""
    out = Path(directory)
    out.mkdir(parents=True, exist_ok=True)
    written = []
    best = gaits[0] if gaits and all(p < len(graph) for p in gaits[0].poses) else None
    dot = graph_dot(graph, best, 1 if best is not None else None)
    if shutil.which("dot") is not None:
        path = out / "gait-graph.svg"
        dot.write(str(path), format="svg")
    else:
        path = out / "gait-graph.dot"
        path.write_text(dot.to_string(), encoding="utf-8")
    written.append(str(path))
    for rank, gait in enumerate(gaits, 1):
        for i, key in enumerate(gait.keys):
            p = out / f"gait{rank}-pose{i}.svg"
            p.write_text(pose_svg(robot, key, f"gait {rank} pose {i}:"), encoding="utf-8")
            written.append(str(p))
    return written
