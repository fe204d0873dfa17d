"""Chapter 5 searches (gaitsearch): A*, LPA* and MCTS on hand-made gait graphs."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from gaitc.search.astar import astar, astar_counted
from gaitc.search.cells import Lattice
from gaitc.search.goals import Goal
from gaitc.search.lpa import LifelongPlanner
from gaitc.search.lpa_arrays import ArrayLifelongPlanner, lifelong
from gaitc.search.mcts import MonteCarloPlanner
from gaitc.search.transitions import Step, TransitionModel, compose

ROBOTS = Path(__file__).resolve().parents[2] / "specs" / "robots"

# (source, target, dx, dy, rotation deg, slip mm); pose 0 is the start
EDGES = [
    (0, 1, 10.0, 0.0, 0.0, 0.0),  # three steps of 10 mm: a correct but long cycle
    (1, 2, 10.0, 0.0, 0.0, 0.0),
    (2, 0, 10.0, 0.0, 0.0, 0.0),
    (0, 5, 15.0, 0.0, 0.0, 1.0),  # two steps, 1 mm slip: 29 mm, within the tolerance
    (5, 0, 14.0, 0.0, 0.0, 0.0),
    (0, 6, 30.0, 0.0, 0.0, 0.0),  # right distance, then a sideways step: misses
    (6, 0, 0.0, 20.0, 0.0, 0.0),
    (0, 8, 10.0, 0.0, 90.0, 0.0),  # turn left, then (0, -20) in the turned frame is +x
    (8, 0, 0.0, -20.0, -90.0, 0.0),
]
GOAL = Goal(30.0, 0.0, 0.0, tolerance=2.0, angle_tolerance=2.0)
# the dict planner and the array planner are the same LPA*: every LPA* test runs both
PLANNERS = pytest.mark.parametrize("planner_class", [LifelongPlanner, ArrayLifelongPlanner])
Planner = type[LifelongPlanner] | type[ArrayLifelongPlanner]


def model(edges: list[tuple[int, int, float, float, float, float]] = EDGES) -> TransitionModel:
    cols = list(zip(*edges, strict=True))
    return TransitionModel(
        max(max(cols[0]), max(cols[1])) + 1,
        np.array(cols[0]),
        np.array(cols[1]),
        np.array(cols[2]),
        np.array(cols[3]),
        np.array(cols[4]),
        np.array(cols[5]),
    )


def pairs(m: TransitionModel, edges: tuple[int, ...]) -> list[tuple[int, int]]:
    return [(int(m.src[e]), int(m.dst[e])) for e in edges]


def lattice(m: TransitionModel) -> Lattice:
    return Lattice(m, 0, GOAL, size=1.0, angle=1.0)


def test_astar_composes_motions_in_the_turned_frame() -> None:
    m = model()
    route = astar(lattice(m))
    assert route is not None
    assert pairs(m, route.edges) == [(0, 8), (8, 0)]
    assert math.isclose(route.cost, 2.0)


@PLANNERS
def test_lpa_finds_the_same_and_repairs_after_changes(planner_class: Planner) -> None:
    m = model()
    planner = planner_class(lattice(m))
    first = planner.compute()
    assert first is not None and pairs(m, first.edges) == [(0, 8), (8, 0)]
    # the robot turns but steps only 10 mm: the turning cycle now misses the goal
    planner.update_transition(m.find(8, 0) or 0, Step(0.0, -10.0, -90.0))
    second = planner.compute()
    assert second is not None and pairs(m, second.edges) == [(0, 5), (5, 0)]
    assert math.isclose(second.cost, 2.05)
    # the robot cannot make 0 -> 5: the three-step cycle is left
    planner.update_transition(m.find(0, 5) or 0, None)
    third = planner.compute()
    assert third is not None and pairs(m, third.edges) == [(0, 1), (1, 2), (2, 0)]
    assert planner.expanded < third.expanded + 10
    fresh = astar(lattice(m))
    assert fresh is not None and math.isclose(fresh.cost, third.cost)


@PLANNERS
def test_no_route_when_no_cycle_reaches_the_goal(planner_class: Planner) -> None:
    m = model([(0, 1, 5.0, 5.0, 0.0, 0.0), (1, 0, 5.0, 5.0, 0.0, 0.0)])  # drifts to +y
    assert astar(Lattice(m, 0, GOAL, 1.0, 1.0, radius=40.0)) is None
    assert planner_class(Lattice(m, 0, GOAL, 1.0, 1.0, radius=40.0)).compute() is None


def test_mcts_finds_the_exact_two_step_cycle_and_is_deterministic() -> None:
    found = []
    for _ in range(2):
        tree = MonteCarloPlanner(model(), 0, GOAL, horizon=4, seed=3)
        best = tree.run(300)
        assert best is not None
        found.append((best.edges, tree.iterations, sorted(tree.candidates)))
    m = model()
    assert pairs(m, found[0][0]) == [(0, 8), (8, 0)]
    assert found[0] == found[1]
    other = MonteCarloPlanner(model(), 0, GOAL, horizon=4, seed=4)
    other.run(300)
    assert other.best() is not None


def test_mcts_prunes_a_branch_observed_to_differ() -> None:
    m = model()
    tree = MonteCarloPlanner(m, 0, GOAL, horizon=4, seed=1)
    tree.run(300)
    edge = m.find(8, 0) or 0
    assert edge in tree.by_edge
    pruned = tree.observe(edge, Step(0.0, -10.0, -90.0), rollouts=4)
    assert pruned >= 1
    best = tree.best()
    assert best is not None and pairs(m, best.edges) == [(0, 5), (5, 0)]
    # the pruned branch was rebuilt from its parent with the new motion
    rebuilt = [n for n in tree.by_edge.get(edge, []) if not n.pruned and n.depth == 2]
    assert rebuilt
    for n in rebuilt:  # (10, 0) turning left, then (0, -10) in the turned frame: +10 in x
        assert math.isclose(n.x, 20.0) and math.isclose(n.y, 0.0, abs_tol=1e-9)


@st.composite
def graphs(draw: st.DrawFn) -> tuple[list[tuple[int, int, float, float, float, float]], list]:  # type: ignore[type-arg]
    n = draw(st.integers(3, 6))
    steps = st.sampled_from([-10.0, 0.0, 5.0, 10.0, 15.0])
    turns = st.sampled_from([0.0, 0.0, 90.0, -90.0])
    edges = {}
    for _ in range(draw(st.integers(n, 3 * n))):
        a, b = draw(st.integers(0, n - 1)), draw(st.integers(0, n - 1))
        if a != b:
            edges[(a, b)] = (draw(steps), draw(steps), draw(turns), draw(st.sampled_from([0, 1])))
    for a in range(n):  # every pose can get home and be reached
        edges.setdefault((a, (a + 1) % n), (10.0, 0.0, 0.0, 0))
    rows = [(a, b, *v) for (a, b), v in sorted(edges.items())]
    changes = draw(
        st.lists(
            st.tuples(
                st.integers(0, len(rows) - 1), st.one_of(st.none(), st.tuples(steps, steps, turns))
            ),
            min_size=1,
            max_size=6,
        )
    )
    return rows, changes


@PLANNERS
@settings(max_examples=50, deadline=None)
@given(graphs())
def test_lpa_after_changes_costs_what_astar_from_scratch_costs(planner_class, case) -> None:  # type: ignore[no-untyped-def]
    rows, changes = case
    goal = Goal(20.0, 0.0, 0.0, 2.0, 2.0)
    m = model(rows)
    planner = planner_class(Lattice(m, 0, goal, 5.0, 90.0, radius=40.0), budget=50_000)
    planner.compute()
    for row, motion in changes:
        edge = int(np.nonzero(m.original == row)[0][0])
        planner.update_transition(edge, None if motion is None else Step(*motion))
        got = planner.compute()
        fresh = astar(Lattice(m.copy(), 0, goal, 5.0, 90.0, radius=40.0))
        assert (got is None) == (fresh is None)
        if got is not None and fresh is not None:
            assert math.isclose(got.cost, fresh.cost, abs_tol=1e-9)
            # the route is a cycle of live edges from the start reaching the goal
            assert int(m.src[got.edges[0]]) == 0 and int(m.dst[got.edges[-1]]) == 0
            assert all(m.alive[e] for e in got.edges)
            x = y = h = 0.0
            for e in got.edges:
                x, y, h = compose(x, y, h, m.step(e))
            assert math.hypot(x - 20.0, y) <= 2.0 + 1e-9  # steps are multiples of the cell
    # no claim on expansions here: a change that cuts the route off makes LPA* retract every
    # node it had settled while A* from scratch stops at once (found by this test)


@PLANNERS
def test_lpa_repairs_expand_fewer_nodes_than_astar_on_the_symmetric_robot(
    planner_class: Planner,
) -> None:
    from gaitc.gaitgraph.graph import GaitGraph, random_states
    from gaitc.gaitgraph.robot import load_robot

    robot = load_robot(ROBOTS / "symmetric6.yaml")
    graph = GaitGraph(robot)
    graph.add_states([0, *random_states(robot, np.random.default_rng(0), 299, {0})])
    m = TransitionModel.from_graph(graph)
    goal = Goal(40.0, 0.0)
    planner = planner_class(Lattice(m, 0, goal))
    route = planner.compute()
    rng = np.random.default_rng(5)
    repairs = scratch = 0
    for _ in range(12):  # what the online loop does: the route's transitions, re-measured
        assert route is not None
        e = int(route.edges[int(rng.integers(len(route.edges)))])
        s = m.step(e)
        planner.update_transition(e, Step(s.dx * 1.1 + 1.0, s.dy * 0.9, s.rotation + 0.5))
        route = planner.compute()
        repairs += planner.expanded
        fresh, count = astar_counted(Lattice(m.copy(), 0, goal))
        scratch += count
        assert (route is None) == (fresh is None)
        assert route is None or fresh is None or math.isclose(route.cost, fresh.cost)
    assert repairs < scratch


@st.composite
def skewed_graphs(
    draw: st.DrawFn,
) -> tuple[list[tuple[int, int, float, float, float, float]], list]:  # type: ignore[type-arg]
    """Motions that are no multiple of the cell: every step snaps."""
    n = draw(st.integers(3, 5))
    step = st.floats(-12, 12, allow_nan=False)
    turn = st.floats(-40, 40, allow_nan=False)
    edges = {}
    for _ in range(draw(st.integers(n, 3 * n))):
        a, b = draw(st.integers(0, n - 1)), draw(st.integers(0, n - 1))
        if a != b:
            edges[(a, b)] = (draw(step), draw(step), draw(turn), draw(st.floats(0, 2)))
    for a in range(n):
        edges.setdefault((a, (a + 1) % n), (7.0, 1.0, 3.0, 0.0))
    rows = [(a, b, *v) for (a, b), v in sorted(edges.items())]
    motion = st.one_of(st.none(), st.tuples(step, step, turn))
    changes = draw(st.lists(st.tuples(st.integers(0, len(rows) - 1), motion), max_size=6))
    return rows, changes


@PLANNERS
@settings(max_examples=30, deadline=None)
@given(skewed_graphs())
def test_lpa_matches_astar_when_every_step_snaps(planner_class, case) -> None:  # type: ignore[no-untyped-def]
    rows, changes = case
    goal = Goal(15.0, 0.0, 0.0, 3.0, 10.0)
    m = model(rows)
    planner = planner_class(Lattice(m, 0, goal, 3.0, 10.0, radius=25.0), budget=10**7)
    planner.compute()
    for row, motion in changes:
        edge = int(np.nonzero(m.original == row)[0][0])
        planner.update_transition(edge, None if motion is None else Step(*motion))
        got = planner.compute()
        fresh = astar(Lattice(m.copy(), 0, goal, 3.0, 10.0, radius=25.0), 10**7)
        assert (got is None) == (fresh is None)
        if got is not None and fresh is not None:
            assert math.isclose(got.cost, fresh.cost, abs_tol=1e-9)


@PLANNERS
def test_lpa_takes_the_cheaper_of_parallel_transitions(planner_class: Planner) -> None:
    # two transitions 0 -> 1 with the same motion (one lattice target) but different slip
    rows = [
        (0, 1, 10.0, 0.0, 0.0, 2.0),
        (0, 1, 10.0, 0.0, 0.0, 0.0),
        (1, 0, 10.0, 0.0, 0.0, 0.0),
    ]
    m = model(rows)
    goal = Goal(20.0, 0.0, 0.0, 2.0, 2.0)
    planner = planner_class(Lattice(m, 0, goal, 5.0, 90.0, radius=40.0))
    route = planner.compute()
    assert route is not None and math.isclose(route.cost, 2.0)
    cheap = route.edges[0]
    assert m.slip[cheap] == 0.0
    planner.update_transition(cheap, None)  # the cheap one is gone: the slipping one is left
    route = planner.compute()
    assert route is not None and math.isclose(route.cost, 2.1)
    fresh = astar(Lattice(m.copy(), 0, goal, 5.0, 90.0, radius=40.0))
    assert fresh is not None and math.isclose(fresh.cost, route.cost)


def test_lifelong_takes_the_array_planner_for_dense_graphs_only() -> None:
    assert isinstance(lifelong(lattice(model()), 100), LifelongPlanner)
    n = 12  # every pose to every other: 11 transitions per pose
    rows = [(a, b, 5.0, 0.0, 0.0, 0.0) for a in range(n) for b in range(n) if a != b]
    assert isinstance(lifelong(lattice(model(rows)), 100, dense=11), ArrayLifelongPlanner)
    assert isinstance(lifelong(lattice(model(rows)), 100, dense=12), LifelongPlanner)
