"""The first k steps of a controller: the automaton restricted to the nodes a run can be in
after at most k moves from an initial node, drawn in the robot's words.

A breadth-first search from the initial nodes (in node order) to depth k, capped at a
number of nodes; each drawn node says its region, gait, leg health, hazard and the goal it
pursues, each edge what the environment changed (:func:`gaitc.sim.automaton_view.input_change`).
Edges out of the last layer are cut, and the view says how many nodes and edges of the
whole automaton it leaves out.  Works on symbolic controllers too: their nodes are found by
expanding them (:mod:`gaitc.sim.symbolic_view`), so only the part drawn is ever computed.
"""

from __future__ import annotations

import pydot

from gaitc.sim.automaton_view import input_change
from gaitc.sim.domain import Domain, State
from gaitc.sim.graphics import Picture
from gaitc.sim.policy import band, goal_label
from gaitc.sim.strategy import Strategy
from gaitc.sim.view import StrategyView, reachable

DEFAULT_STEPS = 3
DEFAULT_CAP = 40


def health_words(domain: Domain, state: State) -> str:
    """The legs that are not healthy ("L2 degraded (2), L5 failed"), or "all legs healthy"."""
    parts = []
    for leg, level in state.health:
        kind = band(level, domain.full[leg])
        if kind == "degraded":
            parts.append(f"{leg} degraded ({level})")
        elif kind == "failed":
            parts.append(f"{leg} failed")
    return ", ".join(parts) if parts else "all legs healthy"


class StepsView(Picture):
    """The drawn first ``steps`` steps: ``depth`` maps each drawn node to its step,
    ``edges`` lists the drawn moves."""

    def __init__(
        self,
        graph: pydot.Dot,
        depth: dict[int, int],
        edges: tuple[tuple[int, int], ...],
        steps: int,
        notes: tuple[str, ...],
    ) -> None:
        super().__init__(graph, notes)
        self.depth = depth
        self.edges = edges
        self.steps = steps


def steps_view(
    strategy: StrategyView, domain: Domain, steps: int = DEFAULT_STEPS, cap: int = DEFAULT_CAP
) -> StepsView:
    """Draw the nodes of ``strategy`` within ``steps`` moves of an initial node (at most
    ``cap`` of them) and the moves between them, with a note of what was cut."""
    depth, capped = reachable(strategy, steps, cap)
    order = sorted(depth, key=lambda n: (depth[n], n))
    states = {n: domain.node_state(strategy, n) for n in order}
    graph = pydot.Dot("steps", graph_type="digraph", rankdir="LR", fontname="Helvetica")
    graph.set_node_defaults(
        shape="box",
        style="rounded,filled",
        fillcolor="#f4f6fb",
        fontname="Helvetica",
        fontsize="11",
    )
    graph.set_edge_defaults(fontname="Helvetica", fontsize="9", color="#555555")
    graph.add_node(pydot.Node("start", shape="point", width="0.12", label=""))
    frontier = 0
    edges: list[tuple[int, int]] = []
    for node in order:
        st = states[node]
        goal = goal_label(domain, strategy.ranks[node])
        label = (
            f"n{node} · step {depth[node]}\n{st.region} · {st.gait}\n"
            f"{'hazard ' + st.hazard if st.hazard else 'no hazard'}\n"
            f"{health_words(domain, st)}\n→ {goal}"
        )
        drawn = pydot.Node(f"n{node}", label=label)
        if depth[node] == 0:
            drawn.set("peripheries", "2")
        succs = strategy.successors[node] if depth[node] < steps else ()
        if depth[node] >= steps or any(s not in depth for s in succs):
            drawn.set("style", "rounded,filled,dashed")
            frontier += 1
        graph.add_node(drawn)
        edges.extend((node, s) for s in succs if s in depth)
    for node in sorted(strategy.initial):
        if node in depth:
            graph.add_edge(pydot.Edge("start", f"n{node}"))
    labels: dict[tuple[int, int], str] = {}
    for src, dst in edges:
        labels[(src, dst)] = input_change(states[src], states[dst])
    for src, dst in sorted(set(edges)):
        graph.add_edge(pydot.Edge(f"n{src}", f"n{dst}", label=labels[(src, dst)]))
    drawn_edges = tuple(sorted(set(edges)))
    notes = [_summary(strategy, depth, drawn_edges, steps, capped, cap)]
    if frontier:
        notes.append(
            f"{frontier} node{'s' if frontier != 1 else ''} with moves beyond the "
            "view (dashed border)"
        )
    return StepsView(graph, depth, drawn_edges, steps, tuple(notes))


def _summary(
    strategy: StrategyView,
    depth: dict[int, int],
    edges: tuple[tuple[int, int], ...],
    steps: int,
    capped: bool,
    cap: int,
) -> str:
    shown = (
        f"the first {steps} step{'s' if steps != 1 else ''} from "
        f"{len(set(strategy.initial))} initial node"
        f"{'s' if len(set(strategy.initial)) != 1 else ''}: {len(depth)} nodes, "
        f"{len(edges)} edges"
    )
    if capped:
        shown += f" (stopped at the node cap {cap}: raise --max-nodes to see the whole layer)"
    if isinstance(strategy, Strategy):
        total_edges = sum(len(set(s)) for s in strategy.successors)
        shown += (
            f"; cut {len(strategy) - len(depth)} of {len(strategy)} nodes and "
            f"{total_edges - len(edges)} of {total_edges} edges"
        )
    else:
        shown += "; the controller is symbolic, so its whole size is not known"
    return shown
