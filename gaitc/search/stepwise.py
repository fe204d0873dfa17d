"""The online loop's cycle with per-transition updates, for D* Lite (``--method dstar``).

Algorithm 2 updates the graph after a whole cycle.  Here each transition's measured motion
goes to the search as soon as the robot has made it, the search start moves to the lattice
node the robot really reached (its pose, in the cell of its measured displacement since the
cycle began), and D* Lite (Koenig and Likhachev 2002) re-plans the rest of the cycle from
there.  The cycle is over when the robot stands in its start pose in a goal cell (or when the plan
it carries on with, after a re-plan that ran out of its budget, ends).
"""

from __future__ import annotations

import time
from typing import TYPE_CHECKING

from gaitc.search.cycles import Cycle, Point, observe_step
from gaitc.search.planners import HybridPlanner, Planner
from gaitc.search.transitions import Step, compose

if TYPE_CHECKING:
    from gaitc.search.backends import Walker

SLACK = 8  # transitions a cycle may take beyond twice its plan before it is given up
STEP_BUDGET = 2_000  # expansions of one re-plan; beyond, the cycle keeps its old plan


def replanning_cycle(
    planner: Planner,
    walker: Walker,
    edges: tuple[int, ...],
    measured: dict[int, list[Step]],
    threshold: float,
    changed: list[tuple[Point, Point]],
) -> Cycle:
    """Run ``edges`` from the rest pose, re-planning the rest after every transition."""
    if not isinstance(planner, HybridPlanner) or planner.dstar is None:
        raise ValueError("a re-planning cycle needs D* Lite (method dstar)")
    model = planner.model
    walker.reset()
    walked = 0.0
    pose = (0.0, 0.0, 0.0)
    path = [pose]
    tried: list[int] = []
    cycle = Cycle((), path, None)
    rest: tuple[int, ...] | None = edges
    limit = 2 * len(edges) + SLACK
    while rest and len(tried) < limit:
        e = rest[0]
        began = time.perf_counter()
        walker.apply(model.labels[int(model.dst[e])])
        walked += time.perf_counter() - began
        out = walker.last
        tried.append(e)
        if out is None or out.edge != e or out.measured is None:
            observe_step(
                planner=planner,
                edge=e,
                step=None,
                measured=measured,
                threshold=threshold,
                changed=changed,
                at=pose,
                reached=None,
                cycle=cycle,
            )
            rest = None
            break
        reached = compose(*pose, out.measured)
        observe_step(
            planner=planner,
            edge=e,
            step=out.measured,
            measured=measured,
            threshold=threshold,
            changed=changed,
            at=pose,
            reached=reached,
            cycle=cycle,
        )
        pose = reached
        path.append(pose)
        before = rest[1:]
        rest = planner.replan_from(int(model.dst[e]), *pose, STEP_BUDGET)
        if rest is None and planner.dstar.expanded > STEP_BUDGET:
            rest = before  # the re-plan ran out of time: carry on as planned
    cycle.edges = tuple(tried)
    if rest == () and int(model.dst[tried[-1]]) == planner.start:  # back in the start pose
        cycle.executed = pose
    cycle.walking, cycle.tried = walked, len(tried)
    return cycle
