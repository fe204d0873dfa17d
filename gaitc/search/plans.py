"""The gait a chapter 5 search returns: its transitions, predicted displacement, search cost.

A :class:`GaitPlan` prints itself as a table (``repr``), draws itself in a notebook
(``_repr_svg_``: explored cells, the trajectory, the goal) and writes sorted JSON.
"""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from typing import Any

from gaitc.search.drawing import plan_svg
from gaitc.search.goals import Goal
from gaitc.search.transitions import Step, TransitionModel, compose


@dataclass(frozen=True)
class PlanStep:
    """One transition of a gait: from pose ``source`` to ``target`` (valves of the target)."""

    edge: int
    source: int
    target: int
    valves: str
    dx: float
    dy: float
    rotation: float
    slip: float


@dataclass(frozen=True)
class GaitPlan:
    """A gait cycle from the start pose back to it, found by ``method`` for ``goal``."""

    robot: str
    method: str
    goal: Goal
    start: int
    start_valves: str
    steps: tuple[PlanStep, ...]
    displacement: tuple[float, float, float]  # predicted per cycle: mm, mm, degrees
    expanded: int  # lattice nodes expanded (A*, LPA*) or MCTS iterations
    seconds: float
    explored: tuple[tuple[float, float], ...] = field(default=(), repr=False, compare=False)
    cell: tuple[float, float] = (2.0, 2.0)  # lattice size (mm) and angle (deg)
    graph: tuple[int, int, int] = (0, 0, 0)  # valve states, poses, transitions searched
    groups: tuple[int, ...] = ()  # chambers per leg (valve states are printed by leg)

    @property
    def edges(self) -> tuple[int, ...]:
        return tuple(s.edge for s in self.steps)

    @property
    def valves(self) -> tuple[str, ...]:
        """The valve sequence: the start state, then the target of every step but the last."""
        return (self.start_valves, *(s.valves for s in self.steps[:-1]))

    @property
    def reached(self) -> bool:
        return self.goal.reached(*self.displacement)

    def trajectory(self) -> list[tuple[float, float, float]]:
        """Predicted chassis poses (x, y, heading) after each transition, from the origin."""
        out = [(0.0, 0.0, 0.0)]
        for s in self.steps:
            out.append(compose(*out[-1], _step(s)))
        return out

    def by_leg(self, valves: str) -> str:
        """A valve state with a space between the chambers of consecutive legs."""
        if sum(self.groups) != len(valves):
            return valves
        parts, at = [], 0
        for n in self.groups:
            parts.append(valves[at : at + n])
            at += n
        return " ".join(parts)

    def table(self) -> str:
        x, y, th = self.displacement
        far, turn = self.goal.error(x, y, th)
        lines = [
            f"{self.method} gait for {self.robot}: goal {self.goal} within "
            f"{self.goal.tolerance:g} mm, {self.goal.angle_tolerance:g} deg",
            f"{'step':>4}  {'dx mm':>8} {'dy mm':>8} {'rot deg':>8} {'slip mm':>8}  valves",
            f"{0:>4}  {'':>8} {'':>8} {'':>8} {'':>8}  {self.by_leg(self.start_valves)}",
        ]
        for i, s in enumerate(self.steps, 1):
            lines.append(
                f"{i:>4}  {s.dx:8.1f} {s.dy:8.1f} {s.rotation:8.2f} {s.slip:8.2f}  "
                f"{self.by_leg(s.valves)}"
            )
        lines.append(
            f"per cycle: {x:.1f} mm, {y:.1f} mm, {th:.2f} deg ({len(self.steps)} transitions; "
            f"{far:.1f} mm and {turn:.1f} deg from the goal)"
        )
        return "\n".join(lines)

    def __repr__(self) -> str:
        return self.table()

    def _repr_svg_(self) -> str:
        return plan_svg(self)

    def to_dict(self) -> dict[str, Any]:
        return {
            "robot": self.robot,
            "method": str(self.method),
            "goal": {
                "dx": _r(self.goal.dx),
                "dy": _r(self.goal.dy),
                "dtheta": _r(self.goal.dtheta),
                "tolerance": _r(self.goal.tolerance),
                "angle_tolerance": _r(self.goal.angle_tolerance),
            },
            "start": {"pose": self.start, "valves": self.start_valves},
            "valves": list(self.valves),
            "transitions": [
                {
                    "edge": s.edge,
                    "source": s.source,
                    "target": s.target,
                    "dx": _r(s.dx),
                    "dy": _r(s.dy),
                    "rotation": _r(s.rotation),
                    "slip": _r(s.slip),
                }
                for s in self.steps
            ],
            "displacement": [_r(v) for v in self.displacement],
            "reached": self.reached,
            "expanded": self.expanded,
            "units": {"length": "mm", "angle": "deg"},
        }

    def to_json(self) -> str:
        """Sorted keys, numbers rounded to 0.001, no timings: the same run, the same bytes."""
        return json.dumps(self.to_dict(), indent=2, sort_keys=True) + "\n"


def _r(x: float) -> float:
    value = round(x, 3)
    return 0.0 if value == 0 else value


def _step(s: PlanStep) -> Step:
    return Step(s.dx, s.dy, s.rotation)


def make_plan(
    model: TransitionModel,
    robot: str,
    method: str,
    goal: Goal,
    *, start: int,
    edges: tuple[int, ...],
    expanded: int,
    seconds: float,
    explored: tuple[tuple[float, float], ...] = (),
    cell: tuple[float, float] = (2.0, 2.0),
) -> GaitPlan:
    """A plan from transition rows, with the motions the model predicts now."""
    steps = []
    x = y = h = 0.0
    for e in edges:
        step = model.step(e)
        target = int(model.dst[e])
        steps.append(
            PlanStep(

                edge=e,
                source=int(model.src[e]),
                target=target,
                valves=model.labels[target],
                dx=step.dx,
                dy=step.dy,
                rotation=step.rotation,
                slip=float(model.slip[e]),
            )
        )
        x, y, h = compose(x, y, h, step)
    return GaitPlan(

        robot=robot,
        method=method,
        goal=goal,
        start=start,
        start_valves=model.labels[start],
        steps=tuple(steps),
        displacement=(x, y, h),
        expanded=expanded,
        seconds=seconds,
        explored=explored,
        cell=cell,
        groups=model.groups,
    )
