"""Search around a single driving edge (thesis 2.5.2): only zero-motion "reset" edges.

Best-first search from the driving edge's target back to its source, changing one leg's
chambers per step; plus the stance-variant proposals that give the reset method its
candidate driving edges.
"""

from __future__ import annotations

import heapq

import numpy as np

from gaitc.gaitgraph.cycles import GaitCycle, close_cycle, rank
from gaitc.gaitgraph.graph import GaitGraph
from gaitc.gaitgraph.kinematics import body_length, forward, shape_keys
from gaitc.gaitgraph.motion import Edges, pair_edges
from gaitc.gaitgraph.poses import PoseTable, stable_poses
from gaitc.gaitgraph.robot import Robot


def _leg_patterns(robot: Robot) -> list[list[int]]:
    """For each leg, one chamber pattern per distinct shape (the smallest)."""
    result = []
    for j, leg in enumerate(robot.legs):
        pats = np.arange(1 << len(leg.chambers), dtype=np.int64)
        keys = shape_keys(robot, pats << leg.first_valve)[:, j]
        _, first = np.unique(keys, return_index=True)
        result.append(sorted(int(pats[i]) for i in first))
    return result


def reset_gaits(
    seed_graph: GaitGraph, drivers: list[int], direction: tuple[float, float], budget: int
) -> tuple[list[GaitCycle], GaitGraph]:
    cycles: list[tuple[GaitCycle, GaitGraph]] = []
    for d in drivers:
        found = search_around(seed_graph, d, budget)
        if found is not None:
            cycles.append(found)
    ranked = rank([c for c, _ in cycles], direction, body_length(seed_graph.robot))
    if not ranked:
        return [], GaitGraph(seed_graph.robot, zero_only=True)
    best = next(g for c, g in cycles if c.keys == ranked[0].keys)
    return ranked, best


def search_around(
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
    goal = shape_keys(robot, graph.poses.state[:1])[0]
    far = [int(x) for x in (shape_keys(robot, graph.poses.state) != goal).sum(axis=1)]
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
            keys = shape_keys(robot, graph.poses.state[start:])
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


def stance_variants(graph: GaitGraph, start: int, limit: int = 25) -> set[int]:
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
    keys = shape_keys(robot, np.array([state], dtype=np.int64))[0]
    out = state
    for j, (leg, pats) in enumerate(zip(robot.legs, patterns, strict=False)):
        width = len(leg.chambers)
        cands = np.array([p << leg.first_valve for p in pats], dtype=np.int64)
        same = [
            p for p, k in zip(pats, shape_keys(robot, cands)[:, j], strict=False) if k == keys[j]
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

        src=np.array([src]),
        dst=np.array([dst]),
        dx=one.dx,
        dy=one.dy,
        rot=one.rot,
        slip=one.slip,
        condition=one.condition,
        shared=one.shared,
    )
