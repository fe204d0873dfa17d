"""Growing the gait graph online (gaitc.search.growth): removals that leave no gait add the
next batch of valve states instead of stopping the loop."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from gaitc.gaitgraph.graph import GaitGraph, random_states
from gaitc.gaitgraph.robot import load_robot
from gaitc.search import Mismatch, Settings, learn_gait
from gaitc.search.goals import Goal
from gaitc.search.transitions import TransitionModel
from gaitc.search.walker import SimulatedWalker

ROBOT = str(Path(__file__).resolve().parents[2] / "specs" / "robots" / "symmetric6.yaml")
# 30 % of the transitions cannot be made: the first gait's first transition is one of them
ROBOT_CASE = (Goal(40, 0), Mismatch(0.2, 0.2, 0.3, 1), Settings(seed=1))


def test_without_growth_the_loop_stops_with_no_gait() -> None:
    goal, mismatch, settings = ROBOT_CASE
    run = learn_gait(ROBOT, goal, "lpa", mismatch, settings, max_states=400)
    assert not run.converged and run.stopped == "no gait"


def test_with_growth_the_loop_converges_on_a_larger_graph() -> None:
    goal, mismatch, settings = ROBOT_CASE
    lines: list[str] = []
    run = learn_gait(
        ROBOT, goal, "lpa", mismatch, settings, max_states=400, progress=lines.append, grow=True
    )
    assert run.converged and run.final is not None and run.error is not None
    assert "no gait left: the gait graph grew to 300 states" in lines
    assert run.first.graph[0] == 200  # the first search found its gait with 200 states
    # the goal's tolerance plus 3 mm for snapping and noise, as for the other loop tests
    assert run.error[0] <= 8.0 and run.error[1] <= 8.0
    assert run.iterations[0].failed is not None


def test_the_walker_keeps_the_truth_of_known_transitions() -> None:
    robot = load_robot(ROBOT)
    graph = GaitGraph(robot)
    graph.add_states([0, *random_states(robot, np.random.default_rng(0), 99, {0})])
    small = TransitionModel.from_graph(graph)
    walker = SimulatedWalker(small.copy(), 0, 24, (), Mismatch(0.2, 0.0, 0.3, 4))
    before = [walker.true_step(e) for e in range(len(small))]
    feasible = walker.feasible.copy()
    graph.add_states(random_states(robot, np.random.default_rng(1), 100, set(graph.states)))
    large = TransitionModel.from_graph(graph)
    rows = {r: large.find(int(small.src[r]), int(small.dst[r])) for r in range(len(small))}
    assert all(k is not None for k in rows.values())
    walker.grow(large, {r: k for r, k in rows.items() if k is not None}, 1)
    assert len(walker.true_dx) == len(large) > len(small)
    for r, k in rows.items():
        assert k is not None
        assert walker.true_step(k) == before[r]
        assert walker.feasible[k] == feasible[r]
