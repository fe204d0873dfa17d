"""Drawing a controller automaton: nodes by region, gait and pursued goal, edges by the
environment's inputs in domain terms (health changes, hazards), initial nodes marked.

Big automata are shown as quotients (nodes merged by region and gait, or by region); the
view reports what it merged.
"""

from __future__ import annotations

from collections.abc import Iterable

import pydot

from gaitc.sim.domain import Domain, State
from gaitc.sim.graphics import Picture
from gaitc.sim.strategy import Strategy

QUOTIENTS = ("none", "region-gait", "region")
DEFAULT_MAX_NODES = 40
MAX_EDGE_LABELS = 3


def input_change(before: State | None, after: State) -> str:
    """The environment's move into ``after`` in domain terms (what changed since ``before``)."""
    parts: list[str] = []
    if before is None:
        levels = [f"{leg}={lv}" for leg, lv in after.health]
        hazard = after.hazard or "none"
        return f"start: hazard {hazard}; " + " ".join(levels)
    old = dict(before.health)
    ups = [leg for leg, lv in after.health if lv > old[leg]]
    for leg, lv in after.health:
        if lv < old[leg]:
            parts.append(f"{leg} fails" if lv == 1 else f"{leg} {old[leg]}→{lv}")
    if ups:
        parts.append("repair " + ",".join(ups) if len(ups) < len(after.health) else "repair all")
    if after.hazard != before.hazard:
        parts.append(f"hazard {after.hazard} on" if after.hazard else
                     f"hazard {before.hazard} off")
    return ", ".join(parts) if parts else "no change"


def _group_key(state: State, quotient: str) -> tuple[str, ...]:
    if quotient == "region":
        return (state.region,)
    return (state.region, state.gait)


class AutomatonView(Picture):
    """A drawn automaton; ``groups`` maps each drawn node to the controller nodes it shows."""

    def __init__(self, graph: pydot.Dot, groups: dict[str, tuple[int, ...]], quotient: str,
                 notes: tuple[str, ...]) -> None:
        super().__init__(graph, notes)
        self.groups = groups
        self.quotient = quotient


def _choose(strategy: Strategy, domain: Domain, quotient: str | None,
            max_nodes: int) -> tuple[str, list[str]]:
    notes: list[str] = []
    if quotient is not None:
        return quotient, notes
    if len(strategy) <= max_nodes:
        return "none", notes
    regions_gaits = {_group_key(domain.node_state(strategy, n), "region-gait")
                     for n in range(len(strategy))}
    chosen = "region-gait" if len(regions_gaits) <= max_nodes else "region"
    notes.append(f"the automaton has {len(strategy)} nodes, more than --max-nodes "
                 f"{max_nodes}: showing the quotient by "
                 f"{'region and gait' if chosen == 'region-gait' else 'region'} "
                 "(--quotient none draws every node)")
    return chosen, notes


def _short(labels: Iterable[str]) -> str:
    items = sorted(set(labels))
    if len(items) > MAX_EDGE_LABELS:
        return "\n".join(items[:MAX_EDGE_LABELS]) + f"\n(+{len(items) - MAX_EDGE_LABELS} more)"
    return "\n".join(items)


def automaton_view(strategy: Strategy, domain: Domain, quotient: str | None = None,
                   max_nodes: int = DEFAULT_MAX_NODES) -> AutomatonView:
    """Draw ``strategy``; ``quotient`` None picks one automatically above ``max_nodes``."""
    chosen, notes = _choose(strategy, domain, quotient, max_nodes)
    states = [domain.node_state(strategy, n) for n in range(len(strategy))]
    region_order = {r: i for i, r in enumerate(domain.regions)}
    gait_order = {g: i for i, g in enumerate(domain.gait_legs)}
    goal_labels = [g.label for g in domain.goals]

    def goal_of(node: int) -> str:
        rank = strategy.ranks[node]
        return goal_labels[rank] if 0 <= rank < len(goal_labels) else f"goal {rank}"

    members: dict[tuple[str, ...], list[int]] = {}
    for node, st in enumerate(states):
        key = (str(node),) if chosen == "none" else _group_key(st, chosen)
        members.setdefault(key, []).append(node)

    def order(key: tuple[str, ...]) -> tuple[int, ...]:
        if chosen == "none":
            return (int(key[0]),)
        return (region_order[key[0]], *(gait_order[g] for g in key[1:]))

    keys = sorted(members, key=order)
    ident = {key: f"q{i}" if chosen != "none" else f"n{key[0]}" for i, key in enumerate(keys)}
    where = {node: ident[key] for key, nodes in members.items() for node in nodes}
    initial = set(strategy.initial)

    graph = pydot.Dot("automaton", graph_type="digraph", rankdir="LR", fontname="Helvetica")
    graph.set_node_defaults(shape="box", style="rounded,filled", fillcolor="#f4f6fb",
                            fontname="Helvetica", fontsize="11")
    graph.set_edge_defaults(fontname="Helvetica", fontsize="9", color="#555555")
    graph.add_node(pydot.Node("start", shape="point", width="0.12", label=""))
    for key in keys:
        nodes = members[key]
        first = states[nodes[0]]
        if chosen == "none":
            node = nodes[0]
            label = f"n{node}\n{first.region} · {first.gait}\n→ {goal_of(node)}"
        elif chosen == "region":
            label = f"{first.region}\n{len(nodes)} node{'s' if len(nodes) > 1 else ''}"
        else:
            label = (f"{first.region} · {first.gait}\n"
                     f"{len(nodes)} node{'s' if len(nodes) > 1 else ''}")
        drawn = pydot.Node(ident[key], label=label)
        if initial.intersection(nodes):
            drawn.set("peripheries", "2")
        graph.add_node(drawn)
    for key in keys:
        if initial.intersection(members[key]):
            graph.add_edge(pydot.Edge("start", ident[key]))
    edges: dict[tuple[str, str], set[str]] = {}
    for node, st in enumerate(states):
        for succ in strategy.successors[node]:
            edges.setdefault((where[node], where[succ]), set()).add(
                input_change(st, states[succ]))
    for (src, dst), labels in sorted(edges.items(), key=lambda kv: (
            _num(kv[0][0]), _num(kv[0][1]))):
        graph.add_edge(pydot.Edge(src, dst, label=_short(labels)))
    groups = {ident[key]: tuple(members[key]) for key in keys}
    if chosen != "none":
        notes.append(f"merged {len(strategy)} nodes into {len(keys)}:")
        for key in keys:
            nodes = members[key]
            shown = ", ".join(str(n) for n in nodes[:8])
            more = f" (+{len(nodes) - 8} more)" if len(nodes) > 8 else ""
            notes.append(f"  {' · '.join(key)}: nodes {shown}{more}")
    return AutomatonView(graph, groups, chosen, tuple(notes))


def _num(ident: str) -> int:
    return int(ident[1:])
