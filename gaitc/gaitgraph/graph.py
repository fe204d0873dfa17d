"""The gait graph G = (V, E) of thesis 2.3: stable poses as nodes, transitions as edges.

:class:`GaitGraph` grows by whole valve states (ADDSTATE of Algorithm 1, batched and
vectorised): each new state's stable poses are added and linked to every earlier pose.
Poses are numbered in insertion order; :meth:`GaitGraph.to_networkx` gives a DiGraph.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass

import networkx as nx
import numpy as np

from gaitc.gaitgraph.kinematics import forward, valve_string
from gaitc.gaitgraph.motion import Edges, transitions
from gaitc.gaitgraph.poses import PoseTable, contact_names, stable_poses
from gaitc.gaitgraph.robot import Robot, RobotFileError

PoseKey = tuple[str, tuple[str, ...]]  # (valve state, contact points)


@dataclass(frozen=True)
class Motion:
    """One transition's predicted chassis motion, in the frame of its source pose."""

    source: int
    target: int
    dx: float
    dy: float
    rotation: float  # degrees, counter-clockwise
    slip: float
    condition: int


class GaitGraph:
    """A growing gait graph for one robot; ``zero_only`` admits reset edges only (2.5.2)."""

    def __init__(self, robot: Robot, zero_only: bool = False) -> None:
        self.robot = robot
        self.zero_only = zero_only
        self.states: set[int] = set()
        self.poses = PoseTable.concat([], len(robot.contact_names))
        self.edges = Edges.concat([])

    def __len__(self) -> int:
        return len(self.poses)

    def add_states(self, states: Iterable[int]) -> int:
        """Add valve states not yet in the graph with their poses and transitions.

        Returns the number of poses added.
        """
        fresh = sorted({int(s) for s in states} - self.states)
        if not fresh:
            return 0
        self.states.update(fresh)
        table = stable_poses(self.robot, forward(self.robot, fresh))
        return self.add_poses(table)

    def add_poses(self, table: PoseTable, link: bool = True) -> int:
        """Append poses; with ``link``, add their transitions to all earlier poses."""
        start = len(self.poses)
        self.poses = PoseTable.concat([self.poses, table], len(self.robot.contact_names))
        if link:
            new = transitions(self.robot, self.poses, start, self.zero_only)
            self.edges = Edges.concat([self.edges, new])
        return len(table)

    def add_edges(self, edges: Edges) -> None:
        """Append precomputed transitions between poses already in the graph."""
        self.edges = Edges.concat([self.edges, edges])

    def key(self, pose: int) -> PoseKey:
        """The (valve string, contact names) of pose number ``pose``."""
        state = int(self.poses.state[pose])
        mask = int(self.poses.mask[pose])
        return valve_string(state, self.robot.valve_count), contact_names(self.robot, mask)

    def find(self, state: int, mask: int) -> int | None:
        hit = np.nonzero((self.poses.state == state) & (self.poses.mask == mask))[0]
        return int(hit[0]) if len(hit) else None

    def motion(self, edge: int) -> Motion:
        e = self.edges
        return Motion(
            int(e.src[edge]),
            int(e.dst[edge]),
            float(e.dx[edge]),
            float(e.dy[edge]),
            float(np.degrees(e.rot[edge])),
            float(e.slip[edge]),
            int(e.condition[edge]),
        )

    def to_networkx(self) -> nx.DiGraph:
        """Nodes are pose numbers (attributes ``valves``, ``contacts``); each edge carries
        ``index`` (its row in :attr:`edges`), ``dx``, ``dy``, ``rotation`` (deg), ``slip``."""
        g = nx.DiGraph()
        for pose in range(len(self.poses)):
            valves, contacts = self.key(pose)
            g.add_node(pose, valves=valves, contacts=contacts)
        e = self.edges
        rot = np.degrees(e.rot)
        g.add_edges_from(
            (
                int(e.src[i]),
                int(e.dst[i]),
                {
                    "index": i,
                    "dx": float(e.dx[i]),
                    "dy": float(e.dy[i]),
                    "rotation": float(rot[i]),
                    "slip": float(e.slip[i]),
                },
            )
            for i in range(len(e))
        )
        return g


def full_graph(robot: Robot, limit: int = 16) -> GaitGraph:
    """Every valve state of a small robot (at most ``limit`` chambers)."""
    if robot.valve_count > limit:

        raise RobotFileError(
            f"robot {robot.name} has {robot.valve_count} chambers: 2^{robot.valve_count} "
            f"valve states are too many to enumerate",
            robot.legs[0].span,
            hint="use --method random or --method reset",
        )
    graph = GaitGraph(robot)
    graph.add_states(range(1 << robot.valve_count))
    return graph


def random_states(
    robot: Robot, rng: np.random.Generator, count: int, exclude: set[int]
) -> list[int]:
    """``count`` distinct random valve states not in ``exclude`` (fewer if none are left)."""
    total = 1 << robot.valve_count
    want = min(count, total - len(exclude))
    out: list[int] = []
    seen = set(exclude)
    while len(out) < want:
        draw = rng.integers(0, total, size=2 * (want - len(out)) + 8, dtype=np.int64)
        for s in draw.tolist():
            if s not in seen:
                seen.add(s)
                out.append(s)
                if len(out) == want:
                    break
    return out
