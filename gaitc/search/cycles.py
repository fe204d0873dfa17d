"""One cycle of the online loop on the robot (thesis Algorithms 2 and 3).

:func:`run_cycle` runs a gait from the rest pose and records what the robot measured;
:func:`observe_step` gives one executed transition to the search (the mean of its
measurements, or its removal when the robot could not make it).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass
from typing import TYPE_CHECKING

from gaitc.search.planners import Planner
from gaitc.search.transitions import Step, TransitionModel, compose

if TYPE_CHECKING:
    from gaitc.search.backends import Walker

Point = tuple[float, float]


def _mean(steps: list[Step]) -> Step:
    n = len(steps)
    return Step(
        sum(s.dx for s in steps) / n,
        sum(s.dy for s in steps) / n,
        sum(s.rotation for s in steps) / n,
    )


def _differs(a: Step, b: Step, threshold: float) -> bool:
    return math.hypot(a.dx - b.dx, a.dy - b.dy) > threshold or abs(a.rotation - b.rotation) > (
        threshold
    )


def run_cycle(
    walker: Walker, model: TransitionModel, edges: tuple[int, ...]
) -> tuple[
    list[tuple[int, Step | None]],
    list[tuple[float, float, float]],
    tuple[float, float, float] | None,
]:
    """Run one cycle from the rest pose; per planned edge what was measured (None: the robot
    did not make it, and the cycle stops there), the measured chassis poses, the net
    displacement."""
    walker.reset()
    x = y = h = 0.0
    path = [(0.0, 0.0, 0.0)]
    seen: list[tuple[int, Step | None]] = []
    for e in edges:
        walker.apply(model.labels[int(model.dst[e])])
        out = walker.last
        if out is None or out.edge != e or out.measured is None:
            seen.append((e, None))
            return seen, path, None
        seen.append((e, out.measured))
        x, y, h = compose(x, y, h, out.measured)
        path.append((x, y, h))
    return seen, path, (x, y, h)


@dataclass
class Cycle:
    """What one cycle on the robot did, as the loop records it."""

    edges: tuple[int, ...]  # the transitions tried, in order
    path: list[tuple[float, float, float]]  # measured chassis poses
    executed: tuple[float, float, float] | None  # None: the cycle broke off
    completed: int = 0
    fresh: int = 0
    moved: int = 0
    failed: int | None = None
    walking: float = 0.0  # seconds spent on the robot (not counted as update time)
    tried: int = 0  # transitions the robot was asked to make


def observe_step(
    planner: Planner,
    edge: int,
    step: Step | None,
    measured: dict[int, list[Step]],
    *, threshold: float,
    changed: list[tuple[Point, Point]],
    at: tuple[float, float, float],
    reached: tuple[float, float, float] | None,
    cycle: Cycle,
) -> None:
    """Give the planner what the robot did on ``edge`` (from pose ``at`` to ``reached``):
    the mean of its measurements so far, or its removal when the robot could not make it."""
    if step is None or reached is None:
        cycle.failed = edge
        planner.observe(edge, None)
        return
    before = planner.model.step(edge)
    cycle.completed += 1
    cycle.fresh += edge not in measured
    measured.setdefault(edge, []).append(step)
    estimate = _mean(measured[edge])
    differs = _differs(before, estimate, threshold)
    if differs:
        cycle.moved += 1
        guess = compose(*at, before)
        changed.append(((guess[0], guess[1]), (reached[0], reached[1])))
    planner.observe(edge, estimate, differs)


def whole_cycle(
    planner: Planner,
    walker: Walker,
    edges: tuple[int, ...],
    measured: dict[int, list[Step]],
    threshold: float,
    changed: list[tuple[Point, Point]],
) -> Cycle:
    """Algorithm 2 and 3's cycle: run the whole gait, then give every transition over."""
    began = time.perf_counter()
    seen, path, executed = run_cycle(walker, planner.model, edges)
    cycle = Cycle(edges, path, executed, tried=len(seen))
    cycle.walking = time.perf_counter() - began
    for i, (e, step) in enumerate(seen):
        reached = path[i + 1] if i + 1 < len(path) else None
        observe_step(
            planner=planner,
            edge=e,
            step=step,
            measured=measured,
            threshold=threshold,
            changed=changed,
            at=path[i],
            reached=reached,
            cycle=cycle,
        )
    return cycle
