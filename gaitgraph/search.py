"""Gait synthesis (thesis Algorithm 1, sections 2.3 and 2.5): driving edge, cycle, ranking.

A gait is a cycle in the gait graph through a driving edge e* chosen closest to the
requested direction.  Other edges weigh (1 - cos α)^4 (α: angle to t*; 0.0001 when
α = 0, 0.01 for zero-motion edges); e* is removed and the shortest path from its
target back to its source closes the cycle.  Methods: ``full`` enumeration, ``random``
batches of 100 valve states with a search after each (2.5.1), and ``reset``: only
zero-motion edges around e*, unit weights, found by A* over one-leg changes (2.5.2).
"""

from __future__ import annotations

import heapq
import itertools
import math
from dataclasses import dataclass
from typing import Any

import networkx as nx
import numpy as np

from gaitgraph.graph import GaitGraph, Motion, PoseKey, full_graph, random_states
from gaitgraph.kinematics import body_length, forward, leg_shapes
from gaitgraph.motion import Edges, Ints, pair_edges
from gaitgraph.poses import PoseTable, stable_poses
from gaitgraph.robot import Robot
from slugs_bridge.diagnostics import Span, SpecSemanticError

METHODS = ("full", "random", "reset")
_NAMED = {"+x": 0.0, "-x": 180.0, "+y": 90.0, "-y": 270.0}


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
        keys = _shape_keys(graph.robot, graph.poses.state)
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
    cycles that do not move forward are dropped, duplicates (same poses) merged."""
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
        if along > graph_epsilon:
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


@dataclass(frozen=True)
class SearchResult:
    method: str
    graph: GaitGraph
    gaits: list[GaitCycle]
    states_added: int


def search(
    robot: Robot,
    direction: tuple[float, float],
    method: str = "reset",
    seed: int = 0,
    max_states: int = 10_000,
    candidates: int = 8,
    budget: int = 1500,
) -> SearchResult:
    """Run one of :data:`METHODS` and return the graph it built and the ranked gaits.

    ``random`` adds batches of 100 random valve states and searches after each batch;
    ``reset`` does the same until steady driving edges exist, then searches around them.
    """
    rng = np.random.default_rng(seed)
    total = 1 << robot.valve_count
    if method == "full":
        graph = full_graph(robot)
        return SearchResult(
            method, graph, synthesize(graph, direction, candidates), len(graph.states)
        )
    graph = GaitGraph(robot)
    if robot.valve_count <= 8:
        graph.add_states(range(total))
    tried: set[int] = set()
    while True:
        if method == "random":
            gaits = synthesize(graph, direction, candidates) if len(graph) else []
            result = SearchResult(method, graph, gaits, len(graph.states))
        else:
            drivers = [
                d for d in driving_edges(graph, direction, candidates, True) if d not in tried
            ]
            tried.update(drivers)
            gaits, around = _reset_gaits(graph, drivers, direction, budget)
            result = SearchResult(method, around, gaits, len(graph.states))
        if gaits or len(graph.states) >= min(max_states, total):
            return result
        start = len(graph)
        graph.add_states(random_states(robot, rng, 100, graph.states))
        if method == "reset":
            graph.add_states(_stance_variants(graph, start))


# ---------------------------------------------------------------- search around one edge


def _shape_keys(robot: Robot, states: Ints) -> np.ndarray[Any, np.dtype[np.int64]]:
    kappa, phi = leg_shapes(robot, states)
    x = np.round(kappa * np.cos(phi) * 1e6).astype(np.int64)
    y = np.round(kappa * np.sin(phi) * 1e6).astype(np.int64)
    out: np.ndarray[Any, np.dtype[np.int64]] = x * 1_000_003 + y
    return out


def _leg_patterns(robot: Robot) -> list[list[int]]:
    """For each leg, one chamber pattern per distinct shape (the smallest)."""
    result = []
    for j, leg in enumerate(robot.legs):
        pats = np.arange(1 << len(leg.chambers), dtype=np.int64)
        keys = _shape_keys(robot, pats << leg.first_valve)[:, j]
        _, first = np.unique(keys, return_index=True)
        result.append(sorted(int(pats[i]) for i in first))
    return result


def _reset_gaits(
    seed_graph: GaitGraph, drivers: list[int], direction: tuple[float, float], budget: int
) -> tuple[list[GaitCycle], GaitGraph]:
    cycles: list[tuple[GaitCycle, GaitGraph]] = []
    for d in drivers:
        found = _search_around(seed_graph, d, budget)
        if found is not None:
            cycles.append(found)
    ranked = rank([c for c, _ in cycles], direction, body_length(seed_graph.robot))
    if not ranked:
        return [], GaitGraph(seed_graph.robot, zero_only=True)
    best = next(g for c, g in cycles if c.keys == ranked[0].keys)
    return ranked, best


def _search_around(
    seed: GaitGraph, driving: int, budget: int, batch: int = 24
) -> tuple[GaitCycle, GaitGraph] | None:
    """Best-first search from e*'s target back to its source over zero-motion edges; each
    step changes one leg's chambers.  Priority: depth + 2 × (legs whose shape differs from
    the source's); ``batch`` poses are expanded together to share the vectorised work."""
    robot = seed.robot
    u0, v0 = int(seed.edges.src[driving]), int(seed.edges.dst[driving])
    graph = GaitGraph(robot, zero_only=True)
    patterns = _leg_patterns(robot)
    ends = seed.poses.take(np.array([u0, v0], dtype=np.int64))
    canon = np.array([_canonical(robot, int(s), patterns) for s in ends.state], dtype=np.int64)
    graph.add_poses(
        PoseTable(canon, ends.mask, ends.xy, ends.z, ends.cg, ends.rotation, ends.height),
        link=False,
    )
    graph.states.update(int(s) for s in graph.poses.state)
    graph.add_edges(_relabel(seed.edges, driving, 0, 1))
    goal = _shape_keys(robot, graph.poses.state[:1])[0]
    far = [int(x) for x in (_shape_keys(robot, graph.poses.state) != goal).sum(axis=1)]
    dist = {1: 0}
    frontier = [(2 * far[1], 0, 1)]
    done: set[int] = set()
    expanded = 0
    while frontier and expanded < budget and 0 not in dist:
        group: list[tuple[int, int]] = []
        while frontier and len(group) < batch:
            _, depth, pose = heapq.heappop(frontier)
            if pose not in done and pose != 0:
                done.add(pose)
                group.append((pose, depth))
        expanded += len(group)
        near = {p: _neighbours(robot, int(graph.poses.state[p]), patterns) for p, _ in group}
        fresh = sorted(set().union(*near.values()) - graph.states)
        if fresh:
            graph.states.update(fresh)
            start = len(graph.poses)
            graph.add_poses(stable_poses(robot, forward(robot, fresh)), link=False)
            keys = _shape_keys(robot, graph.poses.state[start:])
            far.extend(int(x) for x in (keys != goal).sum(axis=1))
        rows_of: dict[int, list[int]] = {}
        for row, state in enumerate(graph.poses.state.tolist()):
            rows_of.setdefault(state, []).append(row)
        src = [p for p, _ in group for s in sorted(near[p]) for _ in rows_of.get(s, [])]
        dst = [r for p, _ in group for s in sorted(near[p]) for r in rows_of.get(s, [])]
        edges = pair_edges(
            robot, graph.poses, np.array(src, np.int64), np.array(dst, np.int64), True
        )
        graph.add_edges(edges)
        depth_of = dict(group)
        for a, b in zip(edges.src.tolist(), edges.dst.tolist(), strict=False):
            if a in depth_of and depth_of[a] + 1 < dist.get(b, budget + 1):
                dist[b] = depth_of[a] + 1
                heapq.heappush(frontier, (dist[b] + 2 * far[b], dist[b], b))
    if 0 not in dist:
        return None
    cycle = close_cycle(graph, graph.to_networkx(), 0, unit_weights=True)
    return None if cycle is None else (cycle, graph)


def _stance_variants(graph: GaitGraph, start: int, limit: int = 25) -> set[int]:
    """Driving-edge proposals for the reset method: for the first ``limit`` poses from
    ``start`` on, set every leg whose foot is in contact to one same chamber pattern (a
    coordinated stance stroke; legs with other chamber counts are left alone)."""
    robot = graph.robot
    names = robot.contact_names
    out: set[int] = set()
    for pose in range(start, min(len(graph), start + limit)):
        state = int(graph.poses.state[pose])
        mask = int(graph.poses.mask[pose])
        legs = [leg for leg in robot.legs if leg.foot and (mask >> names.index(leg.name)) & 1]
        widths = {len(leg.chambers) for leg in legs}
        if len(widths) != 1:
            continue
        width = widths.pop()
        for pattern in range(1 << width):
            new = state
            for leg in legs:
                new = (new & ~(((1 << width) - 1) << leg.first_valve)) | (
                    pattern << leg.first_valve
                )
            out.add(new)
    return out - graph.states


def _canonical(robot: Robot, state: int, patterns: list[list[int]]) -> int:
    """The same geometry with each leg's chambers set to its shape's representative."""
    keys = _shape_keys(robot, np.array([state], dtype=np.int64))[0]
    out = state
    for j, (leg, pats) in enumerate(zip(robot.legs, patterns, strict=False)):
        width = len(leg.chambers)
        cands = np.array([p << leg.first_valve for p in pats], dtype=np.int64)
        same = [
            p for p, k in zip(pats, _shape_keys(robot, cands)[:, j], strict=False) if k == keys[j]
        ]
        out = (out & ~(((1 << width) - 1) << leg.first_valve)) | (same[0] << leg.first_valve)
    return out


def _neighbours(robot: Robot, state: int, patterns: list[list[int]]) -> set[int]:
    out = set()
    for leg, pats in zip(robot.legs, patterns, strict=False):
        width = len(leg.chambers)
        clear = state & ~(((1 << width) - 1) << leg.first_valve)
        for p in pats:
            out.add(clear | (p << leg.first_valve))
    out.discard(state)
    return out


def _relabel(edges: Edges, row: int, src: int, dst: int) -> Edges:
    one = edges.take(np.array([row], dtype=np.int64))
    return Edges(
        np.array([src]),
        np.array([dst]),
        one.dx,
        one.dy,
        one.rot,
        one.slip,
        one.condition,
        one.shared,
    )
