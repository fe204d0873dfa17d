"""The gait graph from a dynamic model (thesis 4.2.2, "Generating the gait graph").

Every valve state is a node, at its steady state; every ordered pair of valve states is
an edge whose motion (displacement and rotation, in the body frame of the start) the model
predicts by simulating the transition for one control period.  Gaits are then found with
the ideas of thesis Algorithm 1 (section 2.3, :mod:`gaitc.gaitgraph.cycles`): a driving edge
closest in angle to the requested direction, edges weighted ``(1 - cos α)^4`` against its
translation, the cheapest path back closing the cycle (small graphs also try every
two-state cycle, the shape of the thesis's primitives); cycles are ranked by forward
progress minus lateral drift minus body length times rotation.

Unlike the kinematic graph of chapter 2, the motion here comes from friction, so a robot
that walks by friction (the radial robot of section 3.4) gets forward gaits.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Sequence
from dataclasses import dataclass

import networkx as nx

from gaitc.gaitgraph.cycles import within_heading
from gaitc.models.motion import IDENTITY, MotionModel, Pose2D, ValveState

ZERO_MOTION = 0.5  # mm: edges that move less are "still" (reset) edges, as in chapter 2
PAIR_LIMIT = 64  # graphs with at most this many states also try every two-state cycle


def valve_states(count: int, max_open: int) -> list[ValveState]:
    """Valve states with at most ``max_open`` valves open, fewest open first."""
    out: list[ValveState] = []
    for k in range(min(max_open, count) + 1):
        for chosen in itertools.combinations(range(count), k):
            out.append(tuple(i in chosen for i in range(count)))
    return out


def valve_text(state: ValveState) -> str:
    return "".join("1" if v else "0" for v in state)


@dataclass(frozen=True)
class ModelGraph:
    """Nodes are valve states; ``motion[(a, b)]`` is the predicted body-frame motion."""

    model: str
    states: tuple[ValveState, ...]
    motion: dict[tuple[ValveState, ValveState], Pose2D]
    period: float


def build_graph(model: MotionModel, states: Sequence[ValveState], period: float) -> ModelGraph:
    """Simulate every transition between ``states`` (in one batch when the model can)."""
    pairs = [(a, b) for a in states for b in states if a != b]
    batch = getattr(model, "transitions", None)
    if callable(batch):
        poses: list[Pose2D] = list(batch(pairs, period))
    else:
        poses = [model.transition(a, b, period) for a, b in pairs]
    return ModelGraph(model.name, tuple(states), dict(zip(pairs, poses, strict=True)), period)


@dataclass(frozen=True)
class ModelGait:
    """A cycle of valve states with the predicted motion of each transition."""

    states: tuple[ValveState, ...]
    steps: tuple[Pose2D, ...]  # steps[i] goes from states[i] to states[i + 1 mod n]
    net: Pose2D  # per cycle, in the body frame at states[0]
    score: float

    @property
    def valves(self) -> tuple[str, ...]:
        return tuple(valve_text(s) for s in self.states)


def cycle_motion(steps: Sequence[Pose2D]) -> Pose2D:
    """The net body-frame motion of a sequence of transitions (an SE(2) product)."""
    net = IDENTITY
    for step in steps:
        net = net.compose(step)
    return net


def _angle(pose: Pose2D, ux: float, uy: float) -> float:
    norm = math.hypot(pose.x, pose.y)
    if norm == 0.0:
        return math.pi
    return math.acos(max(-1.0, min(1.0, (pose.x * ux + pose.y * uy) / norm)))


def find_gaits(
    graph: ModelGraph,
    direction: tuple[float, float],
    body_length: float,
    candidates: int = 8,
) -> list[ModelGait]:
    """Forward gaits towards the unit vector ``direction`` (body frame), best first."""
    ux, uy = direction
    moving = [
        (
            round(_angle(p, ux, uy), 9),
            -round(math.hypot(p.x, p.y), 6),
            graph.states.index(a),
            graph.states.index(b),
        )
        for (a, b), p in graph.motion.items()
        if math.hypot(p.x, p.y) > ZERO_MOTION and _angle(p, ux, uy) < math.pi / 2
    ]
    moving.sort()
    cycles: list[tuple[ValveState, ...]] = []
    for _, _, i, j in moving[:candidates]:
        u, v = graph.states[i], graph.states[j]
        path = _close(graph, u, v)
        if path is not None:
            cycles.append((u, *path[:-1]))
    if len(graph.states) <= PAIR_LIMIT:  # small graphs: every two-state cycle as well
        cycles.extend(itertools.combinations(graph.states, 2))
    return _rank(graph, cycles, direction, body_length)


def _close(graph: ModelGraph, u: ValveState, v: ValveState) -> list[ValveState] | None:
    """The cheapest path from ``v`` back to ``u`` without the driving edge (Algorithm 1)."""
    t = graph.motion[(u, v)]
    tx, ty = t.x / math.hypot(t.x, t.y), t.y / math.hypot(t.x, t.y)
    g = nx.DiGraph()
    for (a, b), p in graph.motion.items():
        if (a, b) == (u, v):
            continue
        if math.hypot(p.x, p.y) <= ZERO_MOTION:
            weight = 1e-2
        else:
            alpha = _angle(p, tx, ty)
            weight = 1e-4 if alpha < 1e-9 else (1.0 - math.cos(alpha)) ** 4
        g.add_edge(a, b, weight=weight)
    try:
        path: list[ValveState] = nx.dijkstra_path(g, v, u, weight="weight")
    except (nx.NetworkXNoPath, nx.NodeNotFound):
        return None
    return path


def _rank(
    graph: ModelGraph,
    cycles: list[tuple[ValveState, ...]],
    direction: tuple[float, float],
    body_length: float,
) -> list[ModelGait]:
    ux, uy = direction
    seen: set[tuple[ValveState, ...]] = set()
    out = []
    for states in cycles:
        k = states.index(min(states))
        canon = states[k:] + states[:k]
        if canon in seen:
            continue
        seen.add(canon)
        steps = tuple(
            graph.motion[(a, b)] for a, b in zip(canon, canon[1:] + canon[:1], strict=True)
        )
        net = cycle_motion(steps)
        along = net.x * ux + net.y * uy
        lateral = -net.x * uy + net.y * ux
        score = along - abs(lateral) - body_length * abs(net.theta)
        if along > ZERO_MOTION and within_heading(along, lateral):
            out.append(ModelGait(canon, steps, net, score))
    out.sort(key=lambda g: (-round(g.score, 6), len(g.states), g.states))
    return out


def gait_rows(gaits: Sequence[ModelGait], legs: Sequence[str], limit: int = 10) -> str:
    """The table ``gaitc gaits --model`` prints: predicted motion per cycle and sequence."""
    lines = [f"{'rank':>4}  {'dx mm':>8} {'dy mm':>8} {'rot deg':>8}  valve sequence (open legs)"]
    for rank, g in enumerate(gaits[:limit], 1):
        names = " | ".join(
            "+".join(leg for leg, on in zip(legs, s, strict=True) if on) or "-" for s in g.states
        )
        lines.append(
            f"{rank:>4}  {g.net.x:8.1f} {g.net.y:8.1f} {math.degrees(g.net.theta):8.2f}  "
            f"{' | '.join(g.valves)}  ({names})"
        )
    return "\n".join(lines)
