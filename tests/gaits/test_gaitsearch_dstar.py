"""D* Lite (gaitc.search.dstar): the same costs as A* from scratch after edge changes and after
the start moves, on hand-made and random gait graphs."""

from __future__ import annotations

import heapq
import math

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from test_gaitsearch_search import EDGES, GOAL, graphs, model, pairs, skewed_graphs

from gaitc.search.astar import astar
from gaitc.search.cells import Lattice
from gaitc.search.dstar import DStarLite
from gaitc.search.goals import Goal
from gaitc.search.transitions import Step, compose


def cheapest_from(lattice: Lattice, node: int) -> float | None:
    """Uniform-cost search from any node to a goal node (a cycle leaves the root first)."""
    dist = {node: 0.0}
    heap = [(0.0, node)]
    done: set[int] = set()
    while heap:
        d, u = heapq.heappop(heap)
        if u in done:
            continue
        if u != lattice.root and lattice.is_goal(u):
            return d
        done.add(u)
        edges, keys = lattice.successors(u)
        for e, v in zip(edges, keys, strict=True):
            c = d + lattice.cost(e)
            if c < dist.get(v, math.inf):
                dist[v] = c
                heapq.heappush(heap, (c, v))
    return None


def test_dstar_finds_the_hand_made_shortest_cycles_through_changes() -> None:
    m = model()
    planner = DStarLite(Lattice(m, 0, GOAL, size=1.0, angle=1.0))
    first = planner.compute()
    assert first is not None and pairs(m, first.edges) == [(0, 8), (8, 0)]
    assert math.isclose(first.cost, 2.0)
    # the robot turns but steps only 10 mm: the turning cycle now misses the goal
    planner.update_transition(m.find(8, 0) or 0, Step(0.0, -10.0, -90.0))
    second = planner.compute()
    assert second is not None and pairs(m, second.edges) == [(0, 5), (5, 0)]
    assert math.isclose(second.cost, 2.05)
    # the robot cannot make 0 -> 5: the three-step cycle is left
    planner.update_transition(m.find(0, 5) or 0, None)
    third = planner.compute()
    assert third is not None and pairs(m, third.edges) == [(0, 1), (1, 2), (2, 0)]
    fresh = astar(Lattice(m.copy(), 0, GOAL, size=1.0, angle=1.0))
    assert fresh is not None and math.isclose(fresh.cost, third.cost)


def test_dstar_replans_from_where_the_robot_got() -> None:
    m = model(EDGES)
    lattice = Lattice(m, 0, GOAL, size=1.0, angle=1.0)
    planner = DStarLite(lattice)
    route = planner.compute()
    assert route is not None
    # the robot takes 0 -> 5 but gets only 10 mm: from there 14 mm misses the goal, so the
    # rest of the cycle is 5 -> 0 -> 1 -> 2 -> 0 ... or whatever is cheapest from (10, 0)
    edge = route.edges[0]
    planner.update_transition(edge, Step(10.0, 0.0, 0.0))
    x, y, h = compose(0.0, 0.0, 0.0, m.step(edge))
    node = lattice.pack(int(m.dst[edge]), round(x), round(y), round(h))
    planner.move_start(node)
    rest = planner.compute()
    expected = cheapest_from(Lattice(m.copy(), 0, GOAL, size=1.0, angle=1.0), node)
    assert (rest is None) == (expected is None)
    if rest is not None and expected is not None:
        assert math.isclose(rest.cost, expected)
        assert rest.nodes[0] == node


def _check(case, goal: Goal, size: float, angle: float, radius: float) -> None:  # type: ignore[no-untyped-def]
    rows, changes = case
    m = model(rows)
    lattice = Lattice(m, 0, goal, size, angle, radius=radius)
    planner = DStarLite(lattice, budget=10**7)
    planner.compute()
    for row, motion in changes:
        edge = int(np.nonzero(m.original == row)[0][0])
        planner.update_transition(edge, None if motion is None else Step(*motion))
        got = planner.compute()
        fresh = astar(Lattice(m.copy(), 0, goal, size, angle, radius=radius), 10**7)
        assert (got is None) == (fresh is None)
        if got is not None and fresh is not None:
            assert math.isclose(got.cost, fresh.cost, abs_tol=1e-9)
            assert int(m.src[got.edges[0]]) == 0 and int(m.dst[got.edges[-1]]) == 0
            assert all(m.alive[e] for e in got.edges)


@settings(max_examples=50, deadline=None)
@given(graphs())
def test_dstar_after_changes_costs_what_astar_from_scratch_costs(case) -> None:  # type: ignore[no-untyped-def]
    _check(case, Goal(20.0, 0.0, 0.0, 2.0, 2.0), 5.0, 90.0, 40.0)


@settings(max_examples=20, deadline=None)
@given(skewed_graphs())
def test_dstar_matches_astar_when_every_step_snaps(case) -> None:  # type: ignore[no-untyped-def]
    _check(case, Goal(15.0, 0.0, 0.0, 3.0, 10.0), 3.0, 10.0, 25.0)


@settings(max_examples=20, deadline=None)
@given(skewed_graphs(), st.lists(st.integers(0, 10**6), min_size=1, max_size=4))
def test_dstar_after_the_start_moves_costs_what_a_fresh_search_costs(case, picks) -> None:  # type: ignore[no-untyped-def]
    rows, changes = case
    goal = Goal(15.0, 0.0, 0.0, 3.0, 10.0)
    m = model(rows)
    lattice = Lattice(m, 0, goal, 3.0, 10.0, radius=25.0)
    planner = DStarLite(lattice, budget=10**7)
    route = planner.compute()
    for i, pick in enumerate(picks):
        if route is None or not route.edges:
            return
        if i < len(changes):  # the transition first changes, as the robot reveals
            row, motion = changes[i]
            edge = int(np.nonzero(m.original == row)[0][0])
            planner.update_transition(edge, None if motion is None else Step(*motion))
        # the robot moves one step along the current route (or to any successor)
        _edges, keys = lattice.successors(route.nodes[0])
        if not keys:
            return
        planner.move_start(keys[pick % len(keys)])
        route = planner.compute()
        fresh = Lattice(m.copy(), 0, goal, 3.0, 10.0, radius=25.0)
        expected = cheapest_from(fresh, planner.start)
        assert (route is None) == (expected is None), (route, expected)
        if route is not None and expected is not None:
            assert math.isclose(route.cost, expected, abs_tol=1e-9)


def test_the_loop_with_per_transition_updates_converges() -> None:
    from pathlib import Path

    from gaitc.search import Mismatch, Settings, learn_gait

    robot = Path(__file__).resolve().parents[2] / "specs" / "robots" / "symmetric6.yaml"
    run = learn_gait(str(robot), Goal(40, 0), "dstar", Mismatch(0.2, 0.2, seed=2), Settings(seed=2))
    assert run.converged and run.executed is not None and run.error is not None
    # the goal's tolerance plus 3 mm for snapping and noise, as for LPA* (docs/gait-search.md)
    assert run.error[0] <= 8.0 and run.error[1] <= 8.0
    # each cycle is re-planned as it goes, so a cycle may take other transitions than planned
    assert all(it.completed == len(it.edges) for it in run.iterations if it.executed)


@settings(max_examples=30, deadline=None)
@given(skewed_graphs())
def test_the_walk_table_keeps_astar_optimal(case) -> None:  # type: ignore[no-untyped-def]
    """A* and LPA* share the walk-table heuristic; a search without any heuristic checks it."""
    rows, changes = case
    goal = Goal(15.0, 0.0, 0.0, 3.0, 10.0)
    m = model(rows)
    for row, motion in changes:  # the table is built from the changed motions
        edge = int(np.nonzero(m.original == row)[0][0])
        if motion is None:
            m.remove(edge)
        else:
            m.set_motion(edge, Step(*motion))
    lattice = Lattice(m, 0, goal, 3.0, 10.0, radius=25.0)
    route = astar(lattice, 10**7)
    expected = cheapest_from(lattice, lattice.root)
    assert (route is None) == (expected is None)
    if route is not None and expected is not None:
        assert math.isclose(route.cost, expected, abs_tol=1e-9)


def test_the_walk_table_sharpens_the_heuristic() -> None:
    m = model()
    lattice = Lattice(m, 0, GOAL, size=1.0, angle=1.0)
    node = lattice.pack(0, 0, 0, 0)
    # from the origin 30 mm away: the longest step is 30 mm, but no walk home covers it in
    # one transition, so the walk table asks for two where the distance bound asks for one
    assert lattice.bound(node) <= 1.0
    assert lattice.heuristic(node) == 2.0
