"""Drawings: SVG top views of poses (legs, contacts, contact polygon, CG) and the gait graph.

Top views are written as plain SVG text; the gait graph (or a window of it around a gait)
goes through pydot, rendered by Graphviz's ``dot`` when it is installed, else kept as .dot.
"""

from __future__ import annotations

import shutil
import subprocess
from collections import deque
from pathlib import Path

import numpy as np
import pydot

from gaitc.diagnostics import GaitcError
from gaitc.diagnostics.files import make_folder
from gaitc.gaitgraph.cycles import GaitCycle
from gaitc.gaitgraph.graph import GaitGraph, PoseKey
from gaitc.gaitgraph.kinematics import Array, forward, leg_polyline, valve_int
from gaitc.gaitgraph.poses import support_planes
from gaitc.gaitgraph.robot import Robot


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


#: The most poses a gait-graph drawing shows (beyond it Graphviz takes minutes and the
#: picture is a hairball); and how long Graphviz may take for one picture.
MAX_DRAWN = 40
DOT_SECONDS = 20.0


def _adjacent(graph: GaitGraph) -> dict[int, list[int]]:
    out: dict[int, list[int]] = {}
    for a, b in zip(graph.edges.src, graph.edges.dst, strict=False):
        out.setdefault(int(a), []).append(int(b))
        out.setdefault(int(b), []).append(int(a))
    return out


def drawn_poses(graph: GaitGraph, gait: GaitCycle | None, window: int | None,
                cap: int = MAX_DRAWN) -> tuple[list[int], str]:
    """The poses to draw and a note on what was left out: the gait and its ``window``-edge
    neighbourhood, else the poses nearest the first one; breadth-first, at most ``cap``."""
    if len(graph) == 0:
        return [], ""
    adjacent = _adjacent(graph)
    seeds = list(dict.fromkeys(gait.poses)) if gait is not None else [0]
    depth = {n: 0 for n in seeds}
    order = list(seeds)
    queue = deque(seeds)
    limit = window if gait is not None and window is not None else len(graph)
    while queue and len(order) < cap:
        here = queue.popleft()
        if depth[here] >= limit:
            continue
        for there in sorted(adjacent.get(here, ())):
            if there not in depth and len(order) < cap:
                depth[there] = depth[here] + 1
                order.append(there)
                queue.append(there)
    whole = len(graph) if gait is None or window is None else None
    note = ""
    if whole is not None and len(order) < whole:
        note = (f"drawing {len(order)} of {whole} poses (those nearest pose 0"
                f"{'' if gait is None else ' and the gait'}; at most {cap})")
    elif len(order) >= cap:
        note = f"drawing {cap} poses of the gait's neighbourhood (at most {cap})"
    return order, note


def _drawn_edges(graph: GaitGraph, nodes: set[int], gait_edges: set[tuple[int, int]],
                 cap: int = 2 * MAX_DRAWN) -> list[int]:
    """The transitions to draw: the gait's, then one per pose pair among the drawn poses,
    first those linking a pose to a new one, at most ``cap`` in all (the rest is noise)."""
    first: dict[tuple[int, int], int] = {}
    for i, (a, b) in enumerate(zip(graph.edges.src, graph.edges.dst, strict=False)):
        key = (int(a), int(b))
        if key[0] in nodes and key[1] in nodes and key[0] != key[1]:
            first.setdefault(key, i)
    chosen = [first[k] for k in sorted(first) if k in gait_edges]
    linked = {p for k in sorted(first) if k in gait_edges for p in k}
    rest = [k for k in sorted(first) if k not in gait_edges]
    for key in rest:  # a spanning forest first: every drawn pose gets an edge
        if len(chosen) >= cap:
            break
        if key[0] not in linked or key[1] not in linked:
            chosen.append(first[key])
            linked.update(key)
    taken = set(chosen)
    for key in rest:
        if len(chosen) >= cap:
            break
        if first[key] not in taken:
            chosen.append(first[key])
            taken.add(first[key])
    return sorted(chosen)


def graph_dot(graph: GaitGraph, gait: GaitCycle | None = None, window: int | None = 1) -> pydot.Dot:
    """The gait graph around ``gait`` (poses within ``window`` edges of it), or without a gait
    the poses nearest the first; at most :data:`MAX_DRAWN` poses (see :func:`drawn_poses`);
    the gait's poses and transitions are drawn in red."""
    order, note = drawn_poses(graph, gait, window)
    nodes = set(order)
    on_gait = set(gait.poses) if gait is not None else set()
    gait_edges = set()
    if gait is not None:
        gait_edges = {(m.source, m.target) for m in gait.motions}
    dot = pydot.Dot("gait_graph", graph_type="digraph", rankdir="LR")
    if note:
        dot.set("label", f'"{note}"')
        dot.set("labelloc", "t")
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
    for i in _drawn_edges(graph, nodes, gait_edges):
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
    make_folder(out)
    written = []
    best = gaits[0] if gaits and all(p < len(graph) for p in gaits[0].poses) else None
    dot = graph_dot(graph, best, 1 if best is not None else None)
    text = dot.to_string()
    path = out / "gait-graph.dot"
    path.write_text(text, encoding="utf-8")
    written.append(str(path))
    exe = shutil.which("dot")
    if exe is not None:
        for fmt in ("svg", "png"):
            picture = out / f"gait-graph.{fmt}"
            _render(exe, text, fmt, picture)
            written.append(str(picture))
    return written + _pose_drawings(robot, gaits, out)


def _render(exe: str, text: str, fmt: str, path: Path) -> None:
    """Run Graphviz on ``text`` with a time limit; a clear error when it is exceeded."""
    try:
        result = subprocess.run([exe, f"-T{fmt}", "-o", str(path)], input=text.encode("utf-8"),
                                capture_output=True, check=False, timeout=DOT_SECONDS)
    except subprocess.TimeoutExpired:
        raise GaitcError(f"Graphviz took more than {DOT_SECONDS:g} s to draw {path.name}; "
                         f"the graph is kept as {path.with_suffix('.dot').name}",
                         hint="draw it yourself with 'dot', or search with a smaller "
                         "--max-states") from None
    if result.returncode != 0:
        message = result.stderr.decode("utf-8", "replace").strip().splitlines()
        raise GaitcError("Graphviz failed: " + (message[0] if message else "no message"))


def _pose_drawings(robot: Robot, gaits: list[GaitCycle], out: Path) -> list[str]:
    written = []
    for rank, gait in enumerate(gaits, 1):
        for i, key in enumerate(gait.keys):
            p = out / f"gait{rank}-pose{i}.svg"
            p.write_text(pose_svg(robot, key, f"gait {rank} pose {i}:"), encoding="utf-8")
            written.append(str(p))
    return written
