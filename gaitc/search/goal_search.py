"""The chapter 5 searches toward a goal, over a growing kinematic graph (:func:`first_planner`)
or a chapter 4 model's gait graph (:func:`model_planner`).
Each takes the method's registry entry (:class:`gaitc.search.registry.GoalSearch`), which
makes its planner; :func:`gaitc.search.online.learn_gait` starts from them.

The gait graph comes from :mod:`gaitc.gaitgraph` (thesis chapter 2): every valve state of a small
robot, else batches of 100 random valve states (2.5.1) with the vented state first, and a
search after each batch until one reaches the goal or ``max_states`` are in.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from gaitc.diagnostics import UsageError
from gaitc.gaitgraph.graph import GaitGraph, random_states
from gaitc.gaitgraph.robot import Robot, RobotFileError, load_robot
from gaitc.models.catalogue import chosen_model, sampled_states
from gaitc.search.goals import Goal, parse_goal
from gaitc.search.planners import Planner, SearchLimitError, Settings
from gaitc.search.plans import GaitPlan
from gaitc.search.predictions import ModelPredictions, model_transitions
from gaitc.search.transitions import TransitionModel

if TYPE_CHECKING:
    from gaitc.search.registry import GoalSearch

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


#: Re-plans of a lattice route whose continuous displacement misses the goal: the first
#: ones aim at a tighter disc of goal cells, the last at a lattice of half the cell.
REFINEMENTS = 3
TIGHTER = 2
#: While the kinematic graph still grows, a batch's search may take this share of
#: ``--budget`` (a small graph that holds no gait would otherwise eat the whole budget), and
#: all the batches' searches together this many budgets.
BATCH_SHARE = 4
TOTAL_BUDGETS = 2


@dataclass(frozen=True)
class FirstPlan:
    """What :func:`first_planner` found: the planner of the graph it stopped at, the
    robot, the plan (None: none) and, when there is none, the reason in a sentence."""

    planner: Planner
    robot: Robot
    plan: GaitPlan | None
    reason: str | None = None


def miss(goal: Goal, plan: GaitPlan) -> float:
    """How far a plan's continuous displacement is from the goal, in tolerances (at most 1
    when it reaches the goal)."""
    far, turn = goal.error(*plan.displacement)
    return max(far / goal.tolerance, turn / goal.angle_tolerance)


def settle(
    model: TransitionModel, robot: str, start: int, goal: Goal, entry: GoalSearch,
    settings: Settings,
) -> tuple[Planner, GaitPlan | None, int]:
    """Plan on one graph; when a lattice route reaches the goal's cells but its continuous
    displacement misses the goal (each transition is propagated from a cell centre, thesis
    5.2.2), plan again, aiming at goal cells within a tolerance shrunk by the miss, then on
    a lattice of half the cell, all within ``settings.budget`` expansions.  Returns the
    planner of the best plan (one that reaches the goal when any does), the plan and the
    expansions (MCTS: iterations) spent in all.  Raises
    :class:`~gaitc.search.planners.SearchLimitError` when the first search runs out."""
    planner = entry.planner(model, robot, start, goal, settings)
    plan = planner.plan()
    if not entry.lattice or plan is None or plan.reached:
        return planner, plan, planner.expanded
    best: tuple[Planner, GaitPlan] = (planner, plan)
    spent, aim, finer = planner.expanded, goal, settings
    for round_ in range(REFINEMENTS):
        far, turn = goal.error(*plan.displacement)
        if round_ < TIGHTER:
            aim = Goal(goal.dx, goal.dy, goal.dtheta,
                       _tighter(aim.tolerance, far - goal.tolerance, finer.cell, goal.tolerance),
                       _tighter(aim.angle_tolerance, turn - goal.angle_tolerance,
                                finer.cell_angle, goal.angle_tolerance))
        else:
            finer = dataclasses.replace(settings, cell=settings.cell / 2,
                                        cell_angle=settings.cell_angle / 2)
            aim = goal
        left = settings.budget - spent
        if left <= 0:
            break
        again = entry.planner(model, robot, start, goal,
                              dataclasses.replace(finer, budget=left), aim)
        try:
            found = again.plan()
        except SearchLimitError:
            break
        spent += again.expanded
        if found is None:
            continue
        if miss(goal, found) < miss(goal, best[1]):
            best = (again, found)
        if found.reached:
            break
        plan = found
    chosen, plan = best
    chosen.set_budget(settings.budget)  # the online loop's repairs get the whole budget
    return chosen, plan, spent


def _tighter(current: float, over: float, cell: float, tolerance: float) -> float:
    """A goal disc shrunk by how far the last route went over, and half a cell more."""
    return max(tolerance / 4, current - max(over, 0.0) - cell / 2)


def _motionless(model: TransitionModel, start: int) -> bool:
    """No cycle through the start pose moves the chassis (:mod:`gaitc.gaitgraph.displacement`)."""
    return start not in model.stillness().moving_poses


def still_reason(kind: str, transitions: int) -> str:
    """The sentence for a graph with no cycle through the rest pose that moves the robot."""
    return (f"no cycle of the {kind} gait graph through the rest pose moves the chassis: "
            f"every cycle of its {transitions} transitions that passes there returns the "
            "robot to where it started, so no search toward any goal can succeed")


def first_planner(
    robot: Robot | str | Path,
    goal: Goal | str,
    entry: GoalSearch,
    settings: Settings | None = None,
    max_states: int = 10_000,
    batch: int = 100,
) -> FirstPlan:
    """Grow the kinematic gait graph batch by batch until ``entry`` finds a gait that
    reaches the goal (:func:`settle` on each graph); the planner of that graph (or of the
    last one) and the plan.  A complete graph (every valve state) with no moving cycle
    through the rest pose is answered at once, without a search; a batch whose search runs
    out of budget is followed by the next batch, and the error is raised only when the
    last one runs out too."""
    if max_states < 1:
        raise UsageError("--max-states must be at least 1")
    bot, target = _robot(robot), goal_for(goal)
    settings = settings or Settings()
    order = graph_batches(bot, settings.seed, max_states)
    graph = GaitGraph(bot)
    complete = order is None
    if order is None:
        graph.add_states(range(1 << bot.valve_count))
        order = []
    added = 0
    best: FirstPlan | None = None
    closest = math.inf
    left = TOTAL_BUDGETS * settings.budget
    while True:
        if order:
            graph.add_states(order[added : added + batch])
            added = min(len(order), added + batch)
        last = added >= len(order)
        start = start_pose(graph)
        model = TransitionModel.from_graph(graph)
        if complete and _motionless(model, start):
            planner = entry.planner(model, bot.name, start, target, settings)
            return FirstPlan(planner, bot, None, still_reason("kinematic", len(model)))
        share = settings.budget if last else max(1, settings.budget // BATCH_SHARE)
        here_settings = dataclasses.replace(settings, budget=max(1, min(share, left)))
        last = last or left <= here_settings.budget
        try:
            planner, plan, spent = settle(model, bot.name, start, target, entry,
                                          here_settings)
        except SearchLimitError as err:
            left -= here_settings.budget
            if not last:
                continue
            if best is not None:
                return best
            raise SearchLimitError(
                f"no gait for goal {target} within {settings.budget} node expansions per "
                f"search and {TOTAL_BUDGETS * settings.budget - max(left, 0)} in all, over "
                f"{len(graph.states)} valve states ({entry.method})",
                None, "raise --budget, coarsen --cell or loosen --tolerance") from err
        left -= spent
        planner.set_budget(settings.budget)
        if plan is not None:
            plan = dataclasses.replace(plan, graph=(len(graph.states), len(graph), len(model)))
        here = FirstPlan(planner, bot, plan)
        if plan is not None and miss(target, plan) < closest:  # the closest of all batches
            best, closest = here, miss(target, plan)
        if (plan is not None and plan.reached) or last:
            return best or here


def model_planner(
    path: str | Path,
    goal: Goal | str,
    entry: GoalSearch,
    settings: Settings | None = None,
    *, max_open: int = 1,
    model: str | None = None,
    max_states: int = 10_000,
) -> tuple[FirstPlan, ModelPredictions]:
    """:func:`first_planner` over the gait graph of the robot file's chapter 4 model
    (``model``, by default the one it declares; thesis 4.2.2) with valve states of at most
    ``max_open`` open valves (at most ``max_states`` of them, a seeded sample beyond), and
    the predictions it planned on."""
    if max_open < 1:
        raise UsageError("--max-open must be at least 1")
    if max_states < 1:
        raise UsageError("--max-states must be at least 1")
    bot, target = load_robot(path), goal_for(goal)
    settings = settings or Settings()
    chambers = bot.valve_count
    found = model_transitions(path, max_open, model or chosen_model(bot, None),
                              sampled_states(chambers, max_open, max_states, settings.seed))
    transitions, start, name = found.model, found.start, found.loaded.robot
    shape = (transitions.poses, transitions.poses, len(transitions))
    if _motionless(transitions, start):
        planner = entry.planner(transitions, name, start, target, settings)
        kind = f"{found.graph.model} model's"
        return FirstPlan(planner, bot, None, still_reason(kind, len(transitions))), found
    planner, plan, _ = settle(transitions, name, start, target, entry, settings)
    if plan is not None:
        plan = dataclasses.replace(plan, graph=shape)
    return FirstPlan(planner, bot, plan), found
