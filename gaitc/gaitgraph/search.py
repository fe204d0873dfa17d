"""Gait search (thesis sections 2.3 and 2.5): grow the gait graph, then find gait cycles.

Methods: ``full`` enumeration, ``random`` batches of 100 valve states with a search after
each (2.5.1), and ``reset``: only zero-motion edges around e*, unit weights (2.5.2, in
:mod:`gaitc.gaitgraph.resets`).  The cycles themselves come from :mod:`gaitc.gaitgraph.cycles`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from gaitc.core.modes import SearchMethod
from gaitc.diagnostics import UsageError
from gaitc.gaitgraph.cycles import GaitCycle, driving_edges, synthesize
from gaitc.gaitgraph.graph import GaitGraph, full_graph, random_states
from gaitc.gaitgraph.resets import reset_gaits, stance_variants
from gaitc.gaitgraph.robot import Robot

#: The kinematic graph's methods (thesis 2.5), the direction searches of
#: :class:`~gaitc.core.modes.SearchMethod` that build the graph themselves.
METHODS = (SearchMethod.FULL, SearchMethod.RANDOM, SearchMethod.RESET)
FULL_LIMIT = 16  # chambers the full search enumerates at most (2^16 valve states)


@dataclass(frozen=True)
class SearchResult:
    method: str
    graph: GaitGraph
    gaits: list[GaitCycle]
    states_added: int
    limit_reached: bool = False  # stopped at ``max_states`` before trying every valve state


def search(
    robot: Robot,
    direction: tuple[float, float],
    method: SearchMethod | str = SearchMethod.RESET,
    seed: int = 0,
    max_states: int = 10_000,
    candidates: int = 8,
    budget: int = 1500,
) -> SearchResult:
    """Run one of :data:`METHODS` and return the graph it built and the ranked gaits.

    ``random`` adds batches of 100 random valve states and searches after each batch;
    ``reset`` does the same until steady driving edges exist, then searches around them.
    No method adds more than ``max_states`` valve states: ``full`` refuses a robot with
    more (a :class:`~gaitc.diagnostics.UsageError`), the others stop there and say so in
    :attr:`SearchResult.limit_reached`.
    """
    method = SearchMethod.parse(method, "kinematic search method")
    rng = np.random.default_rng(seed)
    total = 1 << robot.valve_count
    if method == SearchMethod.FULL:
        if total > max_states and robot.valve_count <= FULL_LIMIT:  # beyond: full_graph says
            raise UsageError(
                f"the full search enumerates all 2^{robot.valve_count} = {total} valve states "
                f"of robot {robot.name}, more than --max-states {max_states}; raise "
                f"--max-states to {total} or use --method random or reset")
        graph = full_graph(robot, FULL_LIMIT)
        return SearchResult(
            method, graph, synthesize(graph, direction, candidates), len(graph.states)
        )
    graph = GaitGraph(robot)
    if total <= min(max_states, 256):
        graph.add_states(range(total))
    tried: set[int] = set()
    while True:
        if method == SearchMethod.RANDOM:
            gaits = synthesize(graph, direction, candidates) if len(graph) else []
            result = SearchResult(method, graph, gaits, len(graph.states))
        else:
            drivers = [
                d for d in driving_edges(graph, direction, candidates, True) if d not in tried
            ]
            tried.update(drivers)
            gaits, around = reset_gaits(graph, drivers, direction, budget)
            result = SearchResult(method, around, gaits, len(graph.states))
        if gaits or len(graph.states) >= min(max_states, total):
            limited = not gaits and len(graph.states) < total
            return SearchResult(result.method, result.graph, result.gaits,
                                result.states_added, limited)
        start = len(graph)
        batch = min(100, max_states - len(graph.states))
        graph.add_states(random_states(robot, rng, batch, graph.states))
        if method == SearchMethod.RESET:
            room = max(0, max_states - len(graph.states))
            graph.add_states([s for s in stance_variants(graph, start)
                              if s not in graph.states][:room])
