"""Growing the gait graph online: when the robot's removals leave no gait, add valve states.

The first search grows the graph by batches of random valve states (thesis 2.5.1) until it
finds a gait.  In the online loop a transition the robot cannot make is removed, and the
removals can leave no cycle that reaches the goal.  Then :class:`Grower` adds the next
batch, carries every transition the loop has already learned (its measured motion, or its
removal) over to the larger graph, and starts a fresh search there; batches are added until
a gait is found or ``max_states`` are in.  Poses and transitions are appended by
:meth:`gaitc.gaitgraph.graph.GaitGraph.add_states`, so those of the smaller graph keep their
meaning (a transition is known by its source and target pose).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from gaitc.gaitgraph.graph import GaitGraph
from gaitc.gaitgraph.robot import Robot
from gaitc.search.goals import Goal
from gaitc.search.planners import Planner, Settings
from gaitc.search.plans import GaitPlan
from gaitc.search.transitions import Step, TransitionModel
from gaitc.search.walker import SimulatedWalker

if TYPE_CHECKING:
    from gaitc.search.registry import GoalSearch


class Grower:
    """The rest of the batches of the first search's graph, to add when the loop needs them."""

    def __init__(
        self,
        robot: Robot,
        order: list[int],
        added: int,
        batch: int,
        entry: GoalSearch,
        goal: Goal,
        settings: Settings,
    ) -> None:
        self.robot, self.order, self.batch = robot, order, batch
        self.entry, self.goal, self.settings = entry, goal, settings
        self.graph = GaitGraph(robot)
        self.added = 0
        while self.added < added:  # the same batches as the first search, in its order
            self.graph.add_states(self.order[self.added : self.added + batch])
            self.added = min(len(self.order), self.added + batch)
        self.grown = 0  # batches added by the loop

    def grow(
        self, planner: Planner, walker: SimulatedWalker, measured: dict[int, list[Step]]
    ) -> tuple[Planner, GaitPlan, dict[int, list[Step]]] | None:
        """Add batches until a search over the larger graph finds a gait; the new planner,
        its plan and ``measured`` renumbered (the walker is grown in place).  None when
        every batch is in and there is still no gait."""
        old = planner.model
        while self.added < len(self.order):
            self.graph.add_states(self.order[self.added : self.added + self.batch])
            self.added = min(len(self.order), self.added + self.batch)
            self.grown += 1
            fresh = TransitionModel.from_graph(self.graph)
            predicted = fresh.copy()
            rows: dict[int, int] = {}
            for r in range(len(old)):
                k = fresh.find(int(old.src[r]), int(old.dst[r]))
                if k is None:  # cannot happen: the smaller graph's edges are all kept
                    continue
                rows[r] = k
                if old.alive[r]:
                    fresh.set_motion(k, old.step(r))
                else:
                    fresh.remove(k)
            nxt = self.entry.planner(fresh, planner.robot, planner.start, self.goal,
                                     self.settings)
            plan = nxt.plan()
            if plan is None:
                continue
            walker.grow(predicted, rows, self.grown)
            return nxt, plan, {rows[e]: steps for e, steps in measured.items() if e in rows}
        return None
