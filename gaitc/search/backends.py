"""What the online loop runs on: the predictions searched and the robot that executes them.

``gaitc learn --backend sim`` executes on :class:`~gaitc.search.walker.SimulatedWalker` (the
predictions with a seeded mismatch), ``--backend physics`` on
:class:`~gaitc.search.physics_walker.PhysicsWalker` (the chapter 4 spring-damper model).  The
predictions come from the chapter 4 model's gait graph where the robot file has a model
(thesis 4.2.2), else from the chapter 2 kinematic graph (``predictions`` chooses).
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from gaitc.core.modes import BackendKind, SearchMethod
from gaitc.diagnostics import UsageError
from gaitc.gaitgraph.robot import Robot
from gaitc.search.goal_search import graph_batches
from gaitc.search.goals import Goal
from gaitc.search.growth import Grower
from gaitc.search.physics_walker import PhysicsWalker
from gaitc.search.planners import Planner, Settings
from gaitc.search.plans import GaitPlan
from gaitc.search.predictions import PREDICTIONS, has_model
from gaitc.search.registry import goal_search
from gaitc.search.walker import Mismatch, SimulatedWalker

#: The backends a gait search can learn on (the serial board measures no displacement).
BACKENDS = (BackendKind.SIM, BackendKind.PHYSICS)
Walker = SimulatedWalker | PhysicsWalker


@dataclass
class Session:
    """A planner with its first plan, and the walker the loop will run it on."""

    planner: Planner
    plan: GaitPlan | None
    walker: Walker
    predictions: str
    grower: Grower | None = None  # the kinematic graph's remaining batches, if any


def default_predictions(robot: Robot | str | Path) -> str:
    """``model`` when the robot file has a chapter 4 model, else ``kinematic``."""
    if isinstance(robot, Robot):
        return "kinematic"
    return "model" if has_model(robot) else "kinematic"


def open_session(
    robot: Robot | str | Path,
    goal: Goal,
    method: SearchMethod | str,
    backend: BackendKind = BackendKind.SIM,
    *, predictions: str | None = None,
    mismatch: Mismatch | None = None,
    settings: Settings | None = None,
    max_states: int = 10_000,
    max_open: int = 1,
) -> Session:
    """The first plan for ``goal`` over ``predictions`` and the walker of ``backend``."""
    entry = goal_search(method)
    settings = settings or Settings()
    mismatch = mismatch or Mismatch(seed=settings.seed)
    if backend not in BACKENDS:
        raise UsageError(f"unknown backend {backend!r}; use one of {', '.join(BACKENDS)}")
    if mismatch.model and backend != BackendKind.PHYSICS:
        raise UsageError("a model mismatch (--model-mismatch) is the physics backend's")
    # the physics backend runs the model, so a robot file without one is reported by the
    # model's reader (with the file position)
    source = predictions or ("model" if backend == BackendKind.PHYSICS
                             else default_predictions(robot))
    if source not in PREDICTIONS:
        raise UsageError(f"unknown predictions {source!r}; use kinematic or model")
    if (source == "model" or backend == BackendKind.PHYSICS) and isinstance(robot, Robot):
        raise UsageError("the chapter 4 model is read from a robot file: pass its path")
    if source == "kinematic":
        if backend == BackendKind.PHYSICS:
            raise UsageError(
                "--backend physics executes the model gait graph's valve states; the chapter 2 "
                "kinematic graph's poses (valve state and contact set) have no counterpart "
                "in the model, so use --predictions model"
            )
        first = entry.kinematic(robot, goal, settings, max_states)
        planner, bot, plan = first.planner, first.robot, first.plan
        walker: Walker = SimulatedWalker(
            planner.model.copy(),
            planner.start,
            bot.valve_count,
            tuple(leg.name for leg in bot.legs),
            mismatch,
        )
        order = graph_batches(bot, settings.seed, max_states)
        grower = None
        if order is not None and plan is not None:
            grower = Grower(bot, order, plan.graph[0], 100, entry, goal, settings)
        return Session(planner, plan, walker, source, grower)
    if max_open < 1:
        raise UsageError("--max-open must be at least 1")
    path = robot if not isinstance(robot, Robot) else ""
    first, found = entry.model(path, goal, settings, max_open=max_open, max_states=max_states)
    planner, plan, model = first.planner, first.plan, found.model
    if backend == BackendKind.PHYSICS:
        walker = PhysicsWalker(
            model.copy(), found.start, found.loaded, mismatch.noise, mismatch.seed, mismatch.model
        )
    else:
        walker = SimulatedWalker(
            model.copy(),
            found.start,
            len(found.loaded.valve_legs),
            tuple(dict.fromkeys(found.loaded.valve_legs)),
            mismatch,
        )
    return Session(planner, plan, walker, source)
