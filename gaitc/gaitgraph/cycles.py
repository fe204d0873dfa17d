"""Gait cycles (thesis Algorithm 1, section 2.3): driving edge, closing cycle, ranking.

A gait is a cycle in the gait graph through a driving edge e* chosen closest to the
requested direction.  Other edges weigh (1 - cos α)^4 (α: angle to t*; 0.0001 when
α = 0, 0.01 for zero-motion edges); e* is removed and the shortest path from its
target back to its source closes the cycle.  The searches that grow the graph
and call this module are in :mod:`gaitc.gaitgraph.search`.
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass
from typing import Any

import networkx as nx
import numpy as np

from gaitc.diagnostics import Span, SpecSemanticError
from gaitc.gaitgraph.graph import GaitGraph, Motion, PoseKey
from gaitc.gaitgraph.kinematics import body_length, shape_keys
from gaitc.gaitgraph.motion import Edges

_NAMED = {"+x": 0.0, "-x": 180.0, "+y": 90.0, "-y": 270.0}

#: The most a gait's net motion per cycle may turn from the direction asked for and still
#: count as a gait towards it (degrees). At 30 degrees a gait drifts at most 0.58 cells
#: sideways per cell forward, so a few steps along a corridor stay in it; a gait further
#: off moves the robot another way than the map's, and is not offered (issue 60: one 85
#: degrees off was ranked first).
MAX_HEADING_DEG = 30.0


def within_heading(along: float, lateral: float) -> bool:
    """Whether a net motion ``along`` the direction asked for, with ``lateral`` drift, is
    forward and within :data:`MAX_HEADING_DEG` of it."""
    return along > 0 and math.degrees(math.atan2(abs(lateral), along)) <= MAX_HEADING_DEG


def parse_direction(text: str, span: Span | None = None) -> tuple[float, float]:
    """``+x``, ``-x``, ``+y``, ``-y`` or an angle in degrees from +x, as a unit vector."""
    angle = _NAMED.get(text.strip())
    if angle is None:
        try:
            angle = float(text.strip().removesuffix("deg"))
        except ValueError:
            raise SpecSemanticError(
                f"unknown direction {text!r}", span, "use +x, -x, +y, -y or an angle in degrees"
            ) from None
    rad = math.radians(angle)
    return math.cos(rad), math.sin(rad)


@dataclass(frozen=True)
class GaitCycle:
    """A synthesised gait: poses p0..p(n-1), returning to p0, with predicted motion."""

    poses: tuple[int, ...]
    keys: tuple[PoseKey, ...]
    motions: tuple[Motion, ...]  # motions[i] goes from poses[i] to poses[i+1 mod n]
    displacement: tuple[float, float]  # net per cycle, mm, frame of p0
    rotation: float  # net per cycle, degrees
    slip: float  # largest slip of any transition, mm
    score: float

    @property
    def valves(self) -> tuple[str, ...]:
        return tuple(k[0] for k in self.keys)


def compose(motions: list[Motion]) -> tuple[float, float, float]:
    """Net planar motion (x, y, θ degrees) of a sequence of transitions (SE(2) product)."""
    x = y = th = 0.0
    for m in motions:
        c, s = math.cos(th), math.sin(th)
        x, y = x + c * m.dx - s * m.dy, y + s * m.dx + c * m.dy
        th += math.radians(m.rotation)
    return x, y, math.degrees(th)


def _angles(edges: Edges, ux: float, uy: float) -> np.ndarray[Any, np.dtype[np.float64]]:
    norm = np.hypot(edges.dx, edges.dy)
    cos = (edges.dx * ux + edges.dy * uy) / np.where(norm > 0, norm, 1.0)
    out: np.ndarray[Any, np.dtype[np.float64]] = np.arccos(np.clip(cos, -1.0, 1.0))
    return out


def driving_edges(
    graph: GaitGraph, direction: tuple[float, float], count: int, steady: bool = False
) -> list[int]:
    """The ``count`` moving edges closest in angle to ``direction`` (ties: longer, less slip).

    ``steady`` keeps only condition-1 edges between poses on equally tilted support planes:
    zero-motion resets cannot undo a tilt or a change of height, so other edges cannot
    close a reset cycle.
    """
    e = graph.edges
    ok = np.hypot(e.dx, e.dy) > graph.robot.settings.zero_motion
    alpha = np.round(_angles(e, *direction), 9)
    ok &= alpha < math.pi / 2
    if steady:
        rot = graph.poses.rotation
        ok &= (e.condition == 1) & (np.abs(rot[e.src] - rot[e.dst]).max(axis=(1, 2)) < 1e-6)
        height = graph.poses.height
        ok &= np.abs(height[e.src] - height[e.dst]) < graph.robot.settings.contact_tolerance
    changed = np.zeros(len(e), dtype=np.int64)
    if steady:
        keys = shape_keys(graph.robot, graph.poses.state)
        changed = (keys[e.src] != keys[e.dst]).sum(axis=1)
    order = np.lexsort((e.dst, e.src, e.slip, -np.round(np.hypot(e.dx, e.dy), 6), changed, alpha))
    return [int(i) for i in order if ok[i]][:count]


def edge_weights(graph: GaitGraph, driving: int) -> np.ndarray[Any, np.dtype[np.float64]]:
    """Algorithm 1 weights relative to the driving edge's translation t*."""
    e = graph.edges
    alpha = _angles(e, float(e.dx[driving]), float(e.dy[driving]))
    w = (1.0 - np.cos(alpha)) ** 4
    w = np.where(alpha < 1e-9, 1e-4, w)
    still = np.hypot(e.dx, e.dy) <= graph.robot.settings.zero_motion
    out: np.ndarray[Any, np.dtype[np.float64]] = np.where(still, 1e-2, w)
    return out


def close_cycle(
    graph: GaitGraph, nxg: nx.DiGraph, driving: int, unit_weights: bool = False
) -> GaitCycle | None:
    """Remove e* and find the cheapest path from its target back to its source."""
    e = graph.edges
    u, v = int(e.src[driving]), int(e.dst[driving])
    w = np.ones(len(e)) if unit_weights else edge_weights(graph, driving)

    def weight(a: int, b: int, data: dict[str, Any]) -> float | None:
        i = data["index"]
        return None if i == driving else float(w[i])

    try:
        path: list[int] = nx.dijkstra_path(nxg, v, u, weight=weight)
    except nx.NetworkXNoPath:
        return None
    rows = [driving] + [int(nxg.edges[a, b]["index"]) for a, b in itertools.pairwise(path)]
    return make_cycle(graph, [u, *path[:-1]], rows)


def make_cycle(graph: GaitGraph, poses: list[int], rows: list[int]) -> GaitCycle:
    motions = [graph.motion(i) for i in rows]
    x, y, th = compose(motions)
    return GaitCycle(
        tuple(poses),
        tuple(graph.key(p) for p in poses),
        tuple(motions),
        (x, y),
        th,
        max(m.slip for m in motions),
        0.0,
    )


def rank(cycles: list[GaitCycle], direction: tuple[float, float], length: float) -> list[GaitCycle]:
    """Score = forward displacement - |lateral drift| - body length · |rotation (rad)|;
    cycles that do not move forward within :data:`MAX_HEADING_DEG` of ``direction`` are
    dropped, duplicates (same poses) merged."""
    seen: set[tuple[int, ...]] = set()
    scored = []
    for c in cycles:
        k = c.poses.index(min(c.poses))
        canon = c.poses[k:] + c.poses[:k]
        if canon in seen:
            continue
        seen.add(canon)
        along = c.displacement[0] * direction[0] + c.displacement[1] * direction[1]
        lateral = -c.displacement[0] * direction[1] + c.displacement[1] * direction[0]
        score = along - abs(lateral) - length * abs(math.radians(c.rotation))
        if along > graph_epsilon and within_heading(along, lateral):
            scored.append(GaitCycle(**{**c.__dict__, "score": score}))
    scored.sort(key=lambda c: (-round(c.score, 6), len(c.poses), c.poses))
    return scored


graph_epsilon = 1e-6


def synthesize(
    graph: GaitGraph,
    direction: tuple[float, float],
    candidates: int = 8,
    unit_weights: bool = False,
) -> list[GaitCycle]:
    """Algorithm 1 for the best ``candidates`` driving edges, ranked."""
    nxg = graph.to_networkx()
    cycles = []
    for d in driving_edges(graph, direction, candidates):
        cycle = close_cycle(graph, nxg, d, unit_weights)
        if cycle is not None:
            cycles.append(cycle)
    return rank(cycles, direction, body_length(graph.robot))
