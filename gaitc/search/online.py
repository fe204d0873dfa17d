"""The online loop of thesis Algorithms 2 (hybrid graph search) and 3 (MCTS).

Synthesize a gait, run it on the robot, estimate each executed transition's displacement,
give it to the search (LPA* repairs, MCTS prunes and rolls out again), and repeat until every
transition of the returned gait has been executed and its prediction is the robot's own
measured mean.  Finally the learned gait is run ``verify`` more cycles and its measured
displacement per cycle compared with the goal.
"""

from __future__ import annotations

import json
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from gaitc.core.modes import BackendKind, SearchMethod
from gaitc.diagnostics import GaitcError
from gaitc.gaitgraph.robot import Robot
from gaitc.search.backends import open_session
from gaitc.search.cycles import Point, run_cycle, whole_cycle
from gaitc.search.drawing import learning_svg
from gaitc.search.goal_search import goal_for
from gaitc.search.goals import Goal
from gaitc.search.planners import Planner, SearchLimitError, Settings
from gaitc.search.plans import GaitPlan
from gaitc.search.stepwise import replanning_cycle
from gaitc.search.transitions import Step, TransitionModel
from gaitc.search.walker import Mismatch, SimulatedWalker

if TYPE_CHECKING:
    from gaitc.search.backends import Walker
    from gaitc.search.growth import Grower


@dataclass(frozen=True)
class Iteration:
    """One pass of the loop: the gait tried, what it was predicted and measured to do."""

    index: int
    edges: tuple[int, ...]
    valves: tuple[str, ...]
    predicted: tuple[float, float, float]
    executed: tuple[float, float, float] | None  # None: the cycle broke off
    completed: int  # transitions executed as planned
    newly_explored: int
    changed: int  # transitions whose prediction moved by more than the change threshold
    failed: int | None  # the transition the robot did not make as planned
    plan_seconds: float = field(compare=False)
    update_seconds: float = field(compare=False)
    path: tuple[Point, ...] = field(default=(), compare=False, repr=False)


@dataclass(frozen=True)
class Learned:
    """Result of :func:`learn_gait`: the first and final plans and every iteration."""

    first: GaitPlan
    final: GaitPlan | None
    iterations: tuple[Iteration, ...]
    converged: bool
    executed: tuple[float, float, float] | None  # mean measured displacement per cycle
    verify_cycles: int
    stopped: str  # converged, no gait, search budget or iteration limit
    changed: tuple[tuple[Point, Point], ...] = field(default=(), repr=False)

    @property
    def error(self) -> tuple[float, float] | None:
        """Distance (mm) and angle (deg) of the executed displacement from the goal."""
        if self.executed is None:
            return None
        return self.first.goal.error(*self.executed)

    def summary(self) -> str:
        state = "converged" if self.converged else f"did not converge ({self.stopped})"
        lines = [f"{self.first.method}: {state} after {len(self.iterations)} iterations"]
        if self.final is not None and self.executed is not None and self.error is not None:
            x, y, th = self.executed
            lines.append(
                f"learned gait: {len(self.final.steps)} transitions; executed {x:.1f} mm, "
                f"{y:.1f} mm, {th:.2f} deg per cycle (mean of {self.verify_cycles}); "
                f"{self.error[0]:.1f} mm, {self.error[1]:.1f} deg from the goal"
            )
        return "\n".join(lines)

    def __repr__(self) -> str:
        return self.summary()

    def _repr_svg_(self) -> str:
        final = self.final or self.first
        return learning_svg(self.first, final, [it.path for it in self.iterations], self.changed)

    def to_json(self) -> str:
        """The log: every iteration (no timings, so a seeded run gives the same bytes)."""
        doc: dict[str, Any] = {
            "method": str(self.first.method),
            "robot": self.first.robot,
            "goal": self.first.to_dict()["goal"],
            "converged": self.converged,
            "stopped": self.stopped,
            "iterations": [
                {
                    "index": it.index,
                    "edges": list(it.edges),
                    "valves": list(it.valves),
                    "predicted": [_r(v) for v in it.predicted],
                    "executed": None if it.executed is None else [_r(v) for v in it.executed],
                    "completed": it.completed,
                    "newly_explored": it.newly_explored,
                    "changed": it.changed,
                    "failed": it.failed,
                }
                for it in self.iterations
            ],
            "final": None if self.final is None else self.final.to_dict(),
            "executed": None if self.executed is None else [_r(v) for v in self.executed],
            "verify_cycles": self.verify_cycles,
        }
        return json.dumps(doc, indent=2, sort_keys=True) + "\n"


def _r(x: float) -> float:
    value = round(x, 3)
    return 0.0 if value == 0 else value


def _valves(model: TransitionModel, start: int, edges: tuple[int, ...]) -> tuple[str, ...]:
    return (model.labels[start], *(model.labels[int(model.dst[e])] for e in edges[:-1]))


def learn(
    planner: Planner,
    walker: Walker,
    plan: GaitPlan | None = None,
    max_iterations: int = 40,
    *, verify: int = 5,
    threshold: float = 0.5,
    progress: Callable[[str], None] | None = None,
    grower: Grower | None = None,
) -> Learned:
    """Algorithms 2 and 3 with ``planner`` on ``walker``; ``threshold`` (mm and deg) is the
    change in a prediction that counts as "observed to differ".  With ``grower`` (the
    simulated walker only), a graph left without a gait grows instead of stopping."""
    model = planner.model
    measured: dict[int, list[Step]] = {}
    iterations: list[Iteration] = []
    changed: list[tuple[Point, Point]] = []
    began = time.perf_counter()
    plan = plan or planner.plan()
    plan_seconds = plan.seconds if plan is not None else time.perf_counter() - began
    if plan is None:
        raise _no_gait(planner.goal)
    first, converged, stopped = plan, False, "iteration limit"
    with walker:
        for index in range(1, max_iterations + 1):
            if all(e in measured for e in plan.edges):
                converged = True
                break
            began = time.perf_counter()
            if planner.replans_from_anywhere:

                cycle = replanning_cycle(planner, walker, plan.edges, measured, threshold, changed)
            else:
                cycle = whole_cycle(planner, walker, plan.edges, measured, threshold, changed)
            iterations.append(
                Iteration(

                    index=index,
                    edges=cycle.edges,
                    valves=_valves(model, plan.start, cycle.edges),
                    predicted=plan.displacement,
                    executed=cycle.executed,
                    completed=cycle.completed,
                    newly_explored=cycle.fresh,
                    changed=cycle.moved,
                    failed=cycle.failed,
                    plan_seconds=plan_seconds,
                    update_seconds=time.perf_counter() - began - cycle.walking,
                    path=tuple((p[0], p[1]) for p in cycle.path),
                )
            )
            if progress is not None:
                progress(_line(iterations[-1], cycle.tried))
            began = time.perf_counter()
            try:
                nxt = planner.plan(explored=False)
            except SearchLimitError:
                nxt, stopped = None, "search budget"
            grown = None
            sim = isinstance(walker, SimulatedWalker)
            if nxt is None and grower is not None and stopped != "search budget" and sim:
                grown = grower.grow(planner, walker, measured)  # type: ignore[arg-type]
            if grown is not None and grower is not None:
                planner, nxt, measured = grown
                model = planner.model
                if progress is not None:
                    progress(f"no gait left: the gait graph grew to {grower.added} states")
            plan_seconds = time.perf_counter() - began
            if nxt is None:
                stopped = "no gait" if stopped != "search budget" else stopped
                plan = None
                break
            plan = nxt
        if plan is not None and not converged:
            converged = all(e in measured for e in plan.edges)
        if converged:
            stopped = "converged"
        final_executed = _verify(walker, model, plan, verify) if plan is not None else None
    if plan is not None:
        plan = planner.plan()  # the same gait (nothing changed), with the explored cells
    return Learned(

        first=first,
        final=plan,
        iterations=tuple(iterations),
        converged=converged,
        executed=final_executed,
        verify_cycles=verify,
        stopped=stopped,
        changed=tuple(changed),
    )


def _verify(
    walker: Walker, model: TransitionModel, plan: GaitPlan, cycles: int
) -> tuple[float, float, float] | None:
    runs = []
    for _ in range(cycles):
        _, _, executed = run_cycle(walker, model, plan.edges)
        if executed is None:
            return None
        runs.append(executed)
    if not runs:
        return None
    n = len(runs)
    return (sum(r[0] for r in runs) / n, sum(r[1] for r in runs) / n, sum(r[2] for r in runs) / n)


def _line(it: Iteration, tried: int) -> str:
    x, y, th = it.predicted
    done = (
        "broke off"
        if it.executed is None
        else (f"executed {it.executed[0]:.1f}, {it.executed[1]:.1f} mm, {it.executed[2]:.1f} deg")
    )
    return (
        f"iteration {it.index}: {len(it.edges)} transitions predicted {x:.1f}, {y:.1f} mm, "
        f"{th:.1f} deg; {done} ({it.completed}/{tried}); {it.newly_explored} newly explored, "
        f"{it.changed} changed; plan {it.plan_seconds * 1000:.1f} ms, "
        f"update {it.update_seconds * 1000:.1f} ms"
    )


class NoGaitError(GaitcError, RuntimeError):
    """The gait graph has no cycle to start learning from (the CLI exits with 1)."""


def _no_gait(goal: Goal) -> Exception:
    return NoGaitError(
        f"no gait for goal {goal} in the gait graph",
        None,
        "loosen --tolerance or allow more --max-states",
    )


def learn_gait(
    robot: Robot | str,
    goal: Goal | str,
    method: SearchMethod | str = SearchMethod.LPA,
    mismatch: Mismatch | None = None,
    settings: Settings | None = None,
    *, max_states: int = 10_000,
    max_iterations: int = 40,
    verify: int = 5,
    progress: Callable[[str], None] | None = None,
    backend: BackendKind = BackendKind.SIM,
    predictions: str | None = None,
    max_open: int = 1,
    grow: bool = False,
) -> Learned:
    """Learn a gait (``gaitc learn``): the first plan over ``predictions`` (``model``: the
    chapter 4 model's gait graph, the default where the robot file has one; ``kinematic``:
    :func:`~gaitc.search.registry.plan_gait`'s graph), then the loop of :func:`learn` on
    ``backend`` (``sim``: the simulated robot with ``mismatch``; ``physics``: the
    spring-damper model, with ``mismatch.noise`` on every measurement).  ``grow``: when the
    robot's removals leave no gait, add the kinematic graph's next batch of valve states
    (:mod:`gaitc.search.growth`) instead of stopping."""
    session = open_session(

        robot=robot,
        goal=goal_for(goal),
        method=method,
        backend=backend,
        predictions=predictions,
        mismatch=mismatch,
        settings=settings,
        max_states=max_states,
        max_open=max_open,
    )
    grower = session.grower if grow else None
    return learn(
        session.planner,
        session.walker,
        session.plan,
        max_iterations,
        verify=verify,
        progress=progress,
        grower=grower,
    )
