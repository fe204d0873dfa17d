"""One registry of the gait searches: each :class:`~gaitc.core.modes.SearchMethod` and its entry.

Two kinds of entry, one interface (:class:`SearchEntry`: the method, a summary, and what it
can do once the robot runs its gait):

- :class:`DirectionSearch` (thesis chapter 2, and its counterpart on a chapter 4 model):
  gait cycles ranked by their displacement toward a direction, over the kinematic gait graph
  (every valve state, random batches of them, or the reset edges around a driving edge;
  :mod:`gaitc.gaitgraph.search`) or over the gait graph of the model a robot file declares
  (:mod:`gaitc.models.catalogue`), optionally of some legs only (:meth:`DirectionSearch.model`);
- :class:`GoalSearch` (chapter 5): a :class:`~gaitc.search.planners.Planner` toward a
  displacement per cycle (A*, LPA*, D* Lite, MCTS), over a growing kinematic graph or a
  model's gait graph (:mod:`gaitc.search.goal_search`), which ``gaitc learn`` then runs
  online.

``gaitc gaits``, ``gaitc learn``, ``gaitc drive``, the ``.gait`` ``primitive`` clause
(:mod:`gaitc.search.primitives`), ``gaitc lint --primitives`` and the language server all
look the method up here (:func:`entry`, :func:`direction_search`, :func:`goal_search`);
nothing else picks a search by its name.  Adding a method is a :class:`SearchMethod` member
and one entry in :data:`ENTRIES`.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from types import MappingProxyType
from typing import TYPE_CHECKING, Final

import numpy as np

from gaitc.core.modes import SearchMethod
from gaitc.diagnostics import UsageError
from gaitc.gaitgraph.search import search
from gaitc.models.catalogue import ModelSearch, sampled_states, search_gaits
from gaitc.models.gait_graph import ModelGait, cycle_motion, valve_states
from gaitc.search.goal_search import FirstPlan, first_planner, model_planner
from gaitc.search.goals import Goal
from gaitc.search.planners import HybridPlanner, Planner, Settings, TreePlanner

if TYPE_CHECKING:
    from gaitc.gaitgraph.robot import Robot
    from gaitc.gaitgraph.search import SearchResult
    from gaitc.models.catalogue import ModelSearch
    from gaitc.models.gait_graph import ModelGait
    from gaitc.models.motion import LoadedModel
    from gaitc.search.plans import GaitPlan
    from gaitc.search.predictions import ModelPredictions
    from gaitc.search.transitions import TransitionModel

#: A chapter 5 planner from (model, robot name, start pose, goal, settings, goal cells' aim).
PlannerFactory = Callable[["TransitionModel", str, int, Goal, Settings, "Goal | None"], Planner]
#: Chambers up to which the chapter 2 default (``chapter2``) takes every valve state.
FULL_CHAMBERS = 12


@dataclass(frozen=True)
class SearchEntry:
    """What every search method declares: its member, a summary, and what it can do while
    the robot runs the gait (the online loop asks these, not the planner's type)."""

    method: SearchMethod
    summary: str
    #: an observed transition updates the search in place (LPA*, D* Lite, MCTS's pruning)
    #: rather than a new search from scratch
    repairs: bool = False
    #: re-plans from the pose the robot reached after each transition (D* Lite)
    replans_from_anywhere: bool = False

    @property
    def toward_goal(self) -> bool:
        """A chapter 5 search toward a goal displacement (else toward a direction)."""
        return self.method.is_global

    @property
    def learns(self) -> bool:
        """``gaitc learn``'s online loop can run it (the chapter 5 planners)."""
        return self.toward_goal


@dataclass(frozen=True)
class DirectionSearch(SearchEntry):
    """Gait cycles toward a direction (thesis 2.3-2.5; 4.2.2 on a model's gait graph)."""

    #: :func:`gaitc.gaitgraph.search.search`'s method; None: ``full`` for a small robot
    #: (at most :data:`FULL_CHAMBERS` chambers and ``max_states`` valve states), else ``random``
    kinematic_method: SearchMethod | None = None
    #: a model's gait graph of a seeded sample of ``max_states`` valve states, not all of them
    sampled: bool = False
    #: why a model's gait graph cannot be searched this way (None: it can)
    not_on_models: str | None = None

    def graph_method(self, robot: Robot, max_states: int) -> SearchMethod:
        """The kinematic graph's method for ``robot``: ``full``, ``random`` or ``reset``."""
        if self.kinematic_method is not None:
            return self.kinematic_method
        total = 1 << robot.valve_count
        full = robot.valve_count <= FULL_CHAMBERS and total <= max_states
        return SearchMethod.FULL if full else SearchMethod.RANDOM

    def kinematic(self, robot: Robot, direction: tuple[float, float], seed: int = 0,
                  max_states: int = 10_000) -> SearchResult:
        """Gaits of the chapter 2 kinematic graph toward the unit vector ``direction``."""
        return search(robot, direction, self.graph_method(robot, max_states), seed, max_states)

    def model(self, loaded: LoadedModel, direction: tuple[float, float], *, max_open: int = 1,
              seed: int = 0, max_states: int = 10_000,
              legs: Sequence[str] | None = None) -> ModelSearch:
        """Gaits of the model's gait graph over valve states of at most ``max_open`` open
        valves.  With ``legs`` (in firing order) only their valves open, a gait must
        pressurise each of them, and it starts at the first state where ``legs[0]`` is
        pressurised (thesis 3.4.1: the gait's actuators fire in the order it names them)."""
        if self.not_on_models is not None:
            raise UsageError(self.not_on_models)
        if max_open < 1:
            raise UsageError("--max-open must be at least 1")
        count = len(loaded.valve_legs)
        limit = max_states if self.sampled else 1 << count
        if legs is None:
            states = sampled_states(count, max_open, limit, seed)
            return search_gaits(loaded, direction, max_open, states)
        found = search_gaits(loaded, direction, max_open,
                             leg_states(loaded.valve_legs, legs, max_open, limit, seed))
        gaits = [fired_first(g, loaded.valve_legs, legs[0]) for g in found.gaits
                 if set(pressurised(g, loaded.valve_legs)) == set(legs)]
        return ModelSearch(found.loaded, found.graph, gaits)


@dataclass(frozen=True)
class GoalSearch(SearchEntry):
    """A chapter 5 planner toward a displacement per cycle (thesis 5.2)."""

    make: PlannerFactory | None = None
    #: searches the (dx, dy, dθ) lattice of 5.2.2, so a route whose continuous displacement
    #: misses the goal is planned again, finer (:func:`gaitc.search.goal_search.settle`)
    lattice: bool = True

    def planner(self, model: TransitionModel, robot: str, start: int, goal: Goal,
                settings: Settings, aim: Goal | None = None) -> Planner:
        """The method's planner from pose ``start``; a lattice planner's goal cells are
        those of ``aim`` (by default the goal itself)."""
        assert self.make is not None, f"registry entry {self.method} has no planner"
        return self.make(model, robot, start, goal, settings, aim)

    def kinematic(self, robot: Robot | str | Path, goal: Goal | str,
                  settings: Settings | None = None, max_states: int = 10_000,
                  batch: int = 100) -> FirstPlan:
        """The first plan over the kinematic graph, grown batch by batch."""
        return first_planner(robot, goal, self, settings, max_states, batch)

    def model(self, path: str | Path, goal: Goal | str, settings: Settings | None = None, *,
              max_open: int = 1, model: str | None = None,
              max_states: int = 10_000) -> tuple[FirstPlan, ModelPredictions]:
        """The first plan over the gait graph of the robot file's chapter 4 model."""
        return model_planner(path, goal, self, settings, max_open=max_open, model=model,
                             max_states=max_states)


def _hybrid(method: SearchMethod) -> PlannerFactory:
    def make(model: TransitionModel, robot: str, start: int, goal: Goal, settings: Settings,
             aim: Goal | None) -> Planner:
        return HybridPlanner(model, robot, start, goal, settings, method, aim)

    return make


def _tree(model: TransitionModel, robot: str, start: int, goal: Goal, settings: Settings,
          aim: Goal | None) -> Planner:
    return TreePlanner(model, robot, start, goal, settings)


_NO_RESETS = ("--method reset searches the kinematic graph's reset edges (thesis 2.5.2); a "
              "chapter 4 model's gait graph has none: add --model kinematic, or use --method "
              "full or random")

#: Every search method's entry, one each (``tests/test_search_registry.py`` checks it).
ENTRIES: Final[tuple[SearchEntry, ...]] = (
    DirectionSearch(SearchMethod.CHAPTER2, "chapter 2's default: every valve state of a small "
                    "robot, else random batches (2.5); a model's whole gait graph"),
    DirectionSearch(SearchMethod.FULL, "every valve state (2.5)",
                    kinematic_method=SearchMethod.FULL),
    DirectionSearch(SearchMethod.RANDOM, "batches of 100 random valve states, searched after "
                    "each (2.5.1)", kinematic_method=SearchMethod.RANDOM, sampled=True),
    DirectionSearch(SearchMethod.RESET, "zero-motion edges around a driving edge (2.5.2)",
                    kinematic_method=SearchMethod.RESET, not_on_models=_NO_RESETS),
    GoalSearch(SearchMethod.ASTAR, "A* on the (dx, dy, dθ) lattice, from scratch after each "
               "change (5.2.2)", make=_hybrid(SearchMethod.ASTAR)),
    GoalSearch(SearchMethod.LPA, "LPA*: A* that repairs itself after each change (5.2.3)",
               repairs=True, make=_hybrid(SearchMethod.LPA)),
    GoalSearch(SearchMethod.DSTAR, "D* Lite: LPA* that also re-plans from wherever the robot "
               "got", repairs=True, replans_from_anywhere=True, make=_hybrid(SearchMethod.DSTAR)),
    GoalSearch(SearchMethod.MCTS, "Monte Carlo tree search over cycles, pruned on observed "
               "changes (5.2.4)", repairs=True, make=_tree, lattice=False),
)

#: The entry of each method.
SEARCHES: Final[Mapping[SearchMethod, SearchEntry]] = MappingProxyType(
    {e.method: e for e in ENTRIES})


def entry(method: SearchMethod | str) -> SearchEntry:
    """The registry entry of ``method`` (a member or its value; an unknown one is a
    :class:`UsageError` naming the accepted values)."""
    return SEARCHES[SearchMethod.parse(method, "search method")]


def direction_search(method: SearchMethod | str | None = None) -> DirectionSearch:
    """The entry of a search toward a direction (None: ``chapter2``)."""
    found = entry(method if method is not None else SearchMethod.CHAPTER2)
    if not isinstance(found, DirectionSearch):
        raise UsageError(f"--method {found.method} is a chapter 5 search toward --goal "
                         "DX,DY[,DTHETA]; toward a --direction use chapter2, full, random or "
                         "reset")
    return found


def goal_search(method: SearchMethod | str) -> GoalSearch:
    """The entry of a chapter 5 search toward a goal."""
    goals = ", ".join(e.method.value for e in ENTRIES if isinstance(e, GoalSearch))
    if method not in SearchMethod.values():
        raise UsageError(f"unknown search method {method!r}; use one of {goals}")
    found = entry(method)
    if not isinstance(found, GoalSearch):
        raise UsageError(f"--method {found.method} searches toward a direction (chapter 2); "
                         f"a goal needs a chapter 5 search: {goals}")
    return found


def plan_gait(
    robot: Robot | str | Path,
    goal: Goal | str,
    method: SearchMethod | str = SearchMethod.LPA,
    settings: Settings | None = None,
    max_states: int = 10_000,
    batch: int = 100,
) -> GaitPlan | None:
    """A gait cycle from the rest pose whose predicted displacement per cycle is ``goal``.

    ``method`` is a chapter 5 search: ``astar``, ``lpa`` (hybrid graph search, thesis
    5.2.2), ``dstar`` or ``mcts`` (5.2.4).  The kinematic graph grows by ``batch`` random
    valve states (all of them for a robot of at most 12 chambers) until a search finds a
    gait; returns it, else the last graph's plan (MCTS: its best cycle, which misses the
    goal), else None.  ``GaitPlan.reached`` says whether the continuous predicted
    displacement is within the tolerance.  Raises
    :class:`~gaitc.search.planners.SearchLimitError` when a search runs out of budget.
    """
    return goal_search(method).kinematic(robot, goal, settings, max_states, batch).plan


# -- the legs of a gait ---------------------------------------------------------------------


def legs_sentence(legs: Sequence[str], direction: str, where: str,
                  movers: Sequence[str]) -> str:
    """Why a search of some legs found nothing, and which legs do move that way."""
    others = f"legs {', '.join(movers)} do" if movers else "no legs do"
    return (f"no gait of legs {', '.join(legs) or '(none)'} moves towards {direction} in "
            f"{where}; {others}")


def leg_states(valve_legs: Sequence[str], legs: Sequence[str], max_open: int, limit: int,
               seed: int) -> list[tuple[bool, ...]]:
    """The valve states of at most ``max_open`` open valves that open only valves of
    ``legs`` (the vented state first); a seeded sample of ``limit`` of them when there are
    more."""
    mine = [i for i, leg in enumerate(valve_legs) if leg in legs]
    every: list[tuple[bool, ...]] = []
    for sub in valve_states(len(mine), max_open):
        state = [False] * len(valve_legs)
        for i, on in zip(mine, sub, strict=True):
            state[i] = on
        every.append(tuple(state))
    if len(every) <= limit:
        return every
    rng = np.random.default_rng(seed)
    chosen = sorted(rng.choice(np.arange(1, len(every)), size=limit - 1, replace=False).tolist())
    return [every[0], *(every[i] for i in chosen)]


def pressurised(gait: ModelGait, valve_legs: Sequence[str]) -> tuple[str, ...]:
    """The legs a model gait pressurises, in the order they first are."""
    out: list[str] = []
    for state in gait.states:
        for leg, on in zip(valve_legs, state, strict=True):
            if on and leg not in out:
                out.append(leg)
    return tuple(out)


def fired_first(gait: ModelGait, valve_legs: Sequence[str], leg: str) -> ModelGait:
    """``gait`` started at its first state in which ``leg`` is pressurised (the same cycle;
    the net motion is that of the new start's body frame)."""
    opened = [any(on and name == leg for name, on in zip(valve_legs, s, strict=True))
              for s in gait.states]
    k = opened.index(True) if True in opened else 0
    states = gait.states[k:] + gait.states[:k]
    steps = gait.steps[k:] + gait.steps[:k]
    return ModelGait(states, steps, cycle_motion(steps), gait.score)
