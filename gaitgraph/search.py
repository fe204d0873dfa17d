"""Gait search (thesis sections 2.3 and 2.5): grow the gait graph, then find gait cycles.

Methods: ``full`` enumeration, ``random`` batches of 100 valve states with a search after
each (2.5.1), and ``reset``: only zero-motion edges around e*, unit weights (2.5.2, in
:mod:`gaitgraph.resets`).  The cycles themselves come from :mod:`gaitgraph.cycles`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from gaitgraph.cycles import GaitCycle, driving_edges, synthesize
from gaitgraph.graph import GaitGraph, full_graph, random_states
from gaitgraph.resets import reset_gaits, stance_variants
from gaitgraph.robot import Robot

METHODS = ("full", "random", "reset")


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
            gaits, around = reset_gaits(graph, drivers, direction, budget)
            result = SearchResult(method, around, gaits, len(graph.states))
        if gaits or len(graph.states) >= min(max_states, total):
            return result
        start = len(graph)
        graph.add_states(random_states(robot, rng, 100, graph.states))
        if method == "reset":
            graph.add_states(stance_variants(graph, start))
