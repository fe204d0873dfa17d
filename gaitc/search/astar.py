"""A* over the hybrid lattice (thesis 5.2.2, after Hart, Nilsson and Raphael 1968).

From the start pose in the origin cell to the start pose in a cell within the goal's
tolerance: the result is a cycle of the gait graph whose predicted net displacement is the
goal.  Each reached node keeps only its cheapest control history (its parent edge).
"""

from __future__ import annotations

import heapq
import math
from dataclasses import dataclass, field

import numpy as np

from gaitc.search.cells import Lattice


@dataclass(frozen=True)
class Route:
    """A path of the lattice: nodes from the root to a goal node and the edges between."""

    nodes: tuple[int, ...]
    edges: tuple[int, ...]
    cost: float
    expanded: int  # node expansions of the search (or of the repair) that found it
    explored: frozenset[int] = field(default=frozenset(), compare=False, repr=False)


class SearchBudgetExceeded(Exception):
    """The search expanded ``budget`` nodes without reaching the goal."""

    def __init__(self, expanded: int) -> None:
        super().__init__(f"no gait within {expanded} node expansions")
        self.expanded = expanded


def astar(lattice: Lattice, budget: int = 200_000) -> Route | None:
    """Cheapest route to the goal, or None when none exists in the lattice.

    Raises :class:`SearchBudgetExceeded` after ``budget`` expansions.  Ties are broken by the
    larger g, then the smaller node number, so the result is deterministic.
    """
    return astar_counted(lattice, budget)[0]


def astar_counted(lattice: Lattice, budget: int = 200_000) -> tuple[Route | None, int]:
    """:func:`astar` and the number of nodes it expanded (also when there is no route)."""
    root = lattice.root
    g: dict[int, float] = {root: 0.0}
    parent: dict[int, tuple[int, int]] = {}
    heap = [(lattice.heuristic(root), 0.0, root)]
    closed: set[int] = set()
    while heap:
        _f, _neg_g, node = heapq.heappop(heap)
        if node in closed:
            continue
        if node != root and lattice.is_goal(node):
            return _route(node, parent, g[node], len(closed), closed), len(closed)
        closed.add(node)
        if len(closed) > budget:
            raise SearchBudgetExceeded(budget)
        base = g[node]
        edges, keys = lattice.successors(node)
        costs = [base + lattice.cost_list[e] for e in edges]
        hs = lattice.heuristics(np.array(keys, dtype=np.int64)).tolist()
        for e, v, cost, h in zip(edges, keys, costs, hs, strict=True):
            if cost < g.get(v, math.inf) and v not in closed and h < math.inf:
                g[v] = cost
                parent[v] = (node, e)
                heapq.heappush(heap, (cost + h, -cost, v))
    return None, len(closed)


def _route(
    goal: int, parent: dict[int, tuple[int, int]], cost: float, expanded: int, closed: set[int]
) -> Route:
    nodes, edges = [goal], []
    while goal in parent:
        goal, e = parent[goal]
        nodes.append(goal)
        edges.append(e)
    return Route(tuple(reversed(nodes)), tuple(reversed(edges)), cost, expanded, frozenset(closed))
