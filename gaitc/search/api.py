"""What the CLI and notebooks call to plan: :func:`plan_gait` (and :func:`first_planner`,
which :func:`gaitc.search.online.learn_gait` starts from).

The gait graph comes from :mod:`gaitc.gaitgraph` (thesis chapter 2): every valve state of a small
robot, else batches of 100 random valve states (2.5.1) with the vented state first, and a
search after each batch until one reaches the goal or ``max_states`` are in.
"""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np

from gaitc.diagnostics import UsageError
from gaitc.gaitgraph.graph import GaitGraph, random_states
from gaitc.gaitgraph.robot import Robot, RobotFileError, load_robot
from gaitc.search.goals import Goal, parse_goal
from gaitc.search.planners import METHODS, Planner, Settings, make_planner
from gaitc.search.plans import GaitPlan
from gaitc.search.transitions import TransitionModel

FULL_CHAMBERS = 12  # robots with at most this many chambers get every valve state


def start_pose(graph: GaitGraph) -> int:
    """The robot at rest: the pose of the all-vented valve state with the most contacts."""
    rows = np.nonzero(graph.poses.state == 0)[0]
    if not len(rows):
        robot = graph.robot
        raise RobotFileError(
            f"robot {robot.name} has no stable pose with every chamber vented, where the "
            "chapter 5 searches start",
            robot.legs[0].span,
            "check the legs' rest shapes",
        )
    counts = [int(graph.poses.mask[r]).bit_count() for r in rows]
    return int(rows[int(np.argmax(counts))])


def graph_batches(robot: Robot, seed: int, max_states: int) -> list[int] | None:
    """None for a full graph, else the random valve states in the order they are added."""
    total = 1 << robot.valve_count
    if robot.valve_count <= FULL_CHAMBERS and total <= max_states:
        return None
    rng = np.random.default_rng(seed)
    return [0, *random_states(robot, rng, max_states - 1, {0})]


def _robot(robot: Robot | str | Path) -> Robot:
    return robot if isinstance(robot, Robot) else load_robot(robot)


def goal_for(goal: Goal | str) -> Goal:
    value = parse_goal(goal) if isinstance(goal, str) else goal
    if value.reached(0.0, 0.0, 0.0):
        raise UsageError(
            f"--goal {value} is within the tolerance of standing still; a gait must move"
        )
    return value


def check_method(method: str) -> None:
    if method not in METHODS:
        raise UsageError(f"unknown search method {method!r}; use one of {', '.join(METHODS)}")


def first_planner(
    robot: Robot | str | Path,
    goal: Goal | str,
    method: str = "lpa",
    settings: Settings | None = None,
    max_states: int = 10_000,
    batch: int = 100,
) -> tuple[Planner, Robot, GaitPlan | None]:
    """Grow the gait graph batch by batch until ``method`` finds a gait that reaches the
    goal; the planner of that graph (or of the last one), the robot and the plan."""
    check_method(method)
    if max_states < 1:
        raise UsageError("--max-states must be at least 1")
    bot, target = _robot(robot), goal_for(goal)
    settings = settings or Settings()
    order = graph_batches(bot, settings.seed, max_states)
    graph = GaitGraph(bot)
    if order is None:
        graph.add_states(range(1 << bot.valve_count))
        order = []
    added = 0
    while True:
        if order:
            graph.add_states(order[added : added + batch])
            added = min(len(order), added + batch)
        start = start_pose(graph)
        model = TransitionModel.from_graph(graph)
        planner = make_planner(method, model, bot.name, start, target, settings)
        plan = planner.plan()
        if plan is not None:
            plan = dataclasses.replace(plan, graph=(len(graph.states), len(graph), len(model)))
        # a lattice route reaches the goal's cells by construction (its continuous
        # displacement may still miss by the snapping, which the plan reports); an MCTS
        # cycle is only as good as its rollouts
        found = plan is not None and (plan.reached or method != "mcts")
        if found or added >= len(order):
            return planner, bot, plan


def plan_gait(
    robot: Robot | str | Path,
    goal: Goal | str,
    method: str = "lpa",
    settings: Settings | None = None,
    max_states: int = 10_000,
    batch: int = 100,
) -> GaitPlan | None:
    """A gait cycle from the rest pose whose predicted displacement per cycle is ``goal``.

    ``method`` is ``astar``, ``lpa`` (hybrid graph search, thesis 5.2.2) or ``mcts``
    (5.2.4).  The graph grows by ``batch`` random valve states (all of them for a robot of
    at most 12 chambers) until a search finds a gait; returns it, else the last graph's
    plan (MCTS: its best cycle, which misses the goal), else None.  ``GaitPlan.reached``
    says whether the continuous predicted displacement is within the tolerance.  Raises
    :class:`~gaitc.search.planners.SearchLimitError` when a search runs out of budget.
    """
    return first_planner(robot, goal, method, settings, max_states, batch)[2]
