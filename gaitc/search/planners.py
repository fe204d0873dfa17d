"""One interface over the chapter 5 searches, as the online loop uses them: :class:`Planner`.

:class:`HybridPlanner` runs A* from scratch after every change (``astar``), repairs with
LPA* (``lpa``) or with D* Lite (``dstar``), which also re-plans from wherever the robot got;
:class:`TreePlanner` is the MCTS of 5.2.4.  Both answer :meth:`~Planner.plan` with a
:class:`~gaitc.search.plans.GaitPlan` and take what the robot did through
:meth:`~Planner.observe`; which method makes which planner is said once, in
:mod:`gaitc.search.registry`.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, replace
from typing import Protocol

from gaitc.core.modes import SearchMethod
from gaitc.diagnostics import SolverError
from gaitc.search.astar import Route, SearchBudgetExceeded, astar
from gaitc.search.cells import Lattice
from gaitc.search.dstar import DStarLite
from gaitc.search.goals import Goal
from gaitc.search.lpa_arrays import lifelong
from gaitc.search.mcts import MonteCarloPlanner, TreeNode
from gaitc.search.plans import GaitPlan, make_plan
from gaitc.search.transitions import Step, TransitionModel


class SearchLimitError(SolverError):
    """A search used up its expansion budget without finding a gait."""


@dataclass(frozen=True)
class Settings:
    """Knobs of the searches; the defaults are those of ``gaitc gaits`` and ``gaitc learn``."""

    cell: float = 2.0  # mm
    cell_angle: float = 2.0  # degrees, must divide 360
    slip_cost: float = 0.05  # extra cost per mm of slip of a transition
    budget: int = 200_000  # lattice expansions per search (A*, LPA*)
    iterations: int = 2000  # MCTS iterations for the first plan
    horizon: int = 12  # MCTS: longest cycle
    rollouts: int = 1  # MCTS: new rollouts from each pruned branch's parent (Algorithm 3)
    seed: int = 0


class Planner(Protocol):
    """What every chapter 5 planner offers the searches and the online loop."""

    method: SearchMethod
    model: TransitionModel
    robot: str
    start: int
    goal: Goal
    settings: Settings
    expanded: int  # expansions (MCTS: iterations) of the last search

    @property
    def replans_from_anywhere(self) -> bool:
        """It re-plans from the pose the robot reached after each transition
        (:meth:`HybridPlanner.replan_from`, D* Lite), not only between cycles."""
        ...

    def plan(self, explored: bool = True) -> GaitPlan | None:
        """Search (or repair the last search) and return the gait; None: no gait."""
        ...

    def observe(self, edge: int, step: Step | None, differs: bool = True) -> None:
        """What the robot did on transition ``edge`` (None: it could not make it)."""
        ...

    def set_budget(self, budget: int) -> None:
        """Expansions each later search (or repair) may take."""
        ...


class HybridPlanner:
    """Hybrid graph search on the lattice: A* each time, LPA* repairs (``lpa``), or D* Lite
    (``dstar``), which also re-plans from wherever the robot got after each transition."""

    def __init__(
        self,
        model: TransitionModel,
        robot: str,
        start: int,
        goal: Goal,
        settings: Settings,
        method: SearchMethod = SearchMethod.LPA,
        aim: Goal | None = None,
    ) -> None:
        self.model, self.robot, self.start, self.goal = model, robot, start, goal
        self.settings, self.method = settings, method
        # the lattice's goal cells may be a tighter disc than the goal (``aim``), so that a
        # route's continuous displacement, snapped cell by cell, still lands in the goal
        self.lattice = Lattice(
            model, start, aim or goal, settings.cell, settings.cell_angle, settings.slip_cost
        )
        self.lpa = lifelong(self.lattice, settings.budget) if method is SearchMethod.LPA else None
        self.dstar = (DStarLite(self.lattice, settings.budget) if method is SearchMethod.DSTAR
                      else None)
        self.expanded = 0

    @property
    def replans_from_anywhere(self) -> bool:
        return self.dstar is not None

    def set_budget(self, budget: int) -> None:
        """Expansions each later search (or repair) may take."""
        self.settings = replace(self.settings, budget=budget)
        for engine in (self.lpa, self.dstar):
            if engine is not None:
                engine.budget = budget

    def plan(self, explored: bool = True) -> GaitPlan | None:
        """Search (or repair) and return the gait; ``explored`` adds the explored cells."""
        began = time.perf_counter()
        try:
            if self.lpa is not None:
                route = self.lpa.compute()
            elif self.dstar is not None:
                self.dstar.move_start(self.lattice.root)
                route = self.dstar.compute()
            else:
                self.lattice.refresh_bounds()
                route = astar(self.lattice, self.settings.budget)
        except SearchBudgetExceeded as err:
            raise SearchLimitError(
                f"no gait for goal {self.goal} within {err.expanded} node expansions "
                f"({self.method})",
                None,
                "raise --budget, coarsen --cell or loosen --tolerance",
            ) from None
        seconds = time.perf_counter() - began
        if route is None:
            return None
        self.expanded = route.expanded
        return self._plan(route, seconds, explored)

    def _plan(self, route: Route, seconds: float, with_cells: bool) -> GaitPlan:
        lattice = self.lattice
        explored = []
        if with_cells:
            search = self.lpa or self.dstar
            nodes = route.explored if search is None else search.explored()
            explored = sorted({lattice.centre(n)[1:3] for n in nodes})
        return make_plan(

            model=self.model,
            robot=self.robot,
            method=self.method,
            goal=self.goal,
            start=self.start,
            edges=route.edges,
            expanded=route.expanded,
            seconds=seconds,
            explored=tuple(explored),
            cell=(self.settings.cell, self.settings.cell_angle),
        )

    def observe(self, edge: int, step: Step | None, differs: bool = True) -> None:
        """What the robot did on transition ``edge`` (``None``: it could not make it);
        ``differs`` only matters to MCTS, which prunes on a real difference."""
        if self.lpa is not None:
            self.lpa.update_transition(edge, step)
        elif self.dstar is not None:
            self.dstar.update_transition(edge, step)
        elif step is None:
            self.model.remove(edge)
        else:
            self.model.set_motion(edge, step)

    def replan_from(
        self, pose: int, x: float, y: float, heading: float, budget: int
    ) -> tuple[int, ...] | None:
        """D* Lite: the rest of the cycle from pose ``pose`` at the measured displacement
        (x, y mm, heading deg) since the cycle began; () when that is a goal cell, None when
        no route is left, the robot is off the lattice or ``budget`` expansions did not
        settle the new start (the search resumes from there at the next call)."""
        if self.dstar is None:
            raise ValueError("replan_from is D* Lite's (method dstar)")
        lattice = self.lattice
        ix, iy = round(x / lattice.size), round(y / lattice.size)
        if ix * ix + iy * iy > lattice.radius**2 / lattice.size**2:
            return None
        node = lattice.pack(pose, ix, iy, round(heading / lattice.angle))
        self.dstar.move_start(node)
        self.dstar.budget = budget
        try:
            route = self.dstar.compute()
        except SearchBudgetExceeded:
            return None
        finally:
            self.dstar.budget = self.settings.budget
        return None if route is None else route.edges


class TreePlanner:
    """MCTS (5.2.4): the best cycle of the tree's rollouts; pruning on observed changes."""

    method = SearchMethod.MCTS
    replans_from_anywhere = False

    def __init__(
        self, model: TransitionModel, robot: str, start: int, goal: Goal, settings: Settings
    ) -> None:
        self.model, self.robot, self.start, self.goal = model, robot, start, goal
        self.settings = settings
        self.tree = MonteCarloPlanner(model, start, goal, settings.horizon, settings.seed)
        self.expanded = 0
        self._ran = False

    def set_budget(self, budget: int) -> None:
        """Kept for the interface: the tree grows by ``settings.iterations``, not by a
        budget of expansions."""
        self.settings = replace(self.settings, budget=budget)

    def plan(self, explored: bool = True) -> GaitPlan | None:
        began = time.perf_counter()
        before = self.tree.iterations
        if not self._ran:
            self.tree.run(self.settings.iterations)
            self._ran = True
        best = self.tree.best()
        seconds = time.perf_counter() - began
        self.expanded = self.tree.iterations - before
        if best is None:
            return None
        cells = sorted({(n.x, n.y) for n in _nodes(self.tree.root)}) if explored else []
        plan = make_plan(

            model=self.model,
            robot=self.robot,
            method=self.method,
            goal=self.goal,
            start=self.start,
            edges=best.edges,
            expanded=self.tree.iterations,
            seconds=seconds,
            explored=tuple(cells),
        )
        return replace(plan, cell=(0.0, 0.0))

    def observe(self, edge: int, step: Step | None, differs: bool = True) -> None:
        self.tree.observe(edge, step, self.settings.rollouts, differs or step is None)


def _nodes(root: TreeNode, limit: int = 20_000) -> list[TreeNode]:
    out: list[TreeNode] = []
    stack = [root]
    while stack and len(out) < limit:
        node = stack.pop()
        out.append(node)
        stack.extend(node.children[e] for e in sorted(node.children))
    return out
