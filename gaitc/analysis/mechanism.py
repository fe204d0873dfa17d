"""How an explanation's parts connect: the lost goal, the core and the freedoms, in robot words.

``gaitc explain`` names a goal the environment can keep the robot from, a core of
guarantees that cannot be met together, the environment's freedoms it needs, and a play.
Each is true on its own; this module says how they make one story, from the model alone:

* a leg whose failure rule (eq. 3.4) is in the core closes the directions whose every gait
  uses it ("both gaits that move west (west_a, west_b) use A5");
* a freedom to wear that leg down (eq. 3.5) or a hazard that fails or wears legs (eqs.
  3.8-3.9) is how the environment gets it to fail;
* in the play, where the leg fails and whether the lost goal can still be reached from
  there on the map with the gaits left (a breadth-first search over the region graph τ).
"""

from __future__ import annotations

from collections import deque
from collections.abc import Iterable, Sequence

from gaitc.analysis.freedoms import Freedom
from gaitc.analysis.units import Unit
from gaitc.analysis.variants import gait_families
from gaitc.core.changes import HazardSwitch, LegWears
from gaitc.ir.roles import LegFailure
from gaitc.sim.run import Run
from ltlcompiler.model import GaitKind, Model

#: Legs of the core told one by one; the others share a sentence.
MAX_LEGS_TOLD = 3


def core_legs(core: Iterable[Unit]) -> tuple[str, ...]:
    """The legs whose failure rule (eq. 3.4: its gaits are off once it fails) is in the core."""
    return tuple(u.role.leg for u in core if isinstance(u.role, LegFailure))


def _names(items: Sequence[str]) -> str:
    return items[0] if len(items) == 1 else ", ".join(items[:-1]) + " and " + items[-1]


def closed_directions(model: Model, leg: str) -> list[tuple[str, tuple[str, ...]]]:
    """The directions (or explicit-edge gaits) every gait of which uses ``leg``."""
    return [(direction, gaits) for direction, gaits in gait_families(model).items()
            if gaits and all(leg in model.gait(g).legs for g in gaits)]


def reachable(model: Model, start: str, failed: Iterable[str]) -> set[str]:
    """The regions the robot can reach from ``start`` with the gaits that use no leg of
    ``failed`` (health apart: a gait whose legs still work may move)."""
    broken = set(failed)
    usable = {g.name for g in model.gaits
              if g.kind is not GaitKind.MOVE or not set(g.legs) & broken}
    out: dict[str, list[str]] = {}
    for t in model.transitions:
        if t.source != t.target and set(t.gaits) & usable:
            out.setdefault(t.source, []).append(t.target)
    seen = {start}
    queue = deque([start])
    while queue:
        here = queue.popleft()
        for there in out.get(here, ()):
            if there not in seen:
                seen.add(there)
                queue.append(there)
    return seen


def _legs_entering(model: Model, hazard: str) -> set[str]:
    """The legs of the gaits that move into a cell of ``hazard``."""
    cells = set(next(h for h in model.hazards if h.name == hazard).regions)
    return {leg for t in model.transitions if t.target in cells
            for g in t.gaits for leg in model.gait(g).legs}


def _direction_text(direction: str, gaits: tuple[str, ...], leg: str) -> str:
    where = (f"moves {direction}" if not direction.startswith("gait ")
             else f"takes the edges of {direction.removeprefix('gait ')}")
    if len(gaits) == 1:
        return f"the only gait that {where} ({gaits[0]}) uses {leg}"
    both = "both" if len(gaits) == 2 else f"all {len(gaits)}"
    return f"{both} gaits that {where.replace('moves', 'move').replace('takes', 'take')} " \
           f"({', '.join(gaits)}) use {leg}"


def connection(model: Model, core: Sequence[Unit], freedoms: Sequence[Freedom],
               goal_regions: Sequence[str], goal: str | None, run: Run | None) -> list[str]:
    """Sentences that tie the core's legs, the environment's freedoms and the play to the
    lost ``goal`` (its regions ``goal_regions``); empty when the core names no leg."""
    lines: list[str] = []
    legs = list(dict.fromkeys(core_legs(core)))
    for leg in legs[:MAX_LEGS_TOLD]:
        closed = closed_directions(model, leg)
        said = "; ".join(_direction_text(d, g, leg) for d, g in closed) if closed else \
            f"the gaits {_names(model.gaits_using(leg))} use {leg}"
        worn = [f.gait for f in freedoms if f.change == LegWears(leg)]
        if worn:
            said += f"; the environment may wear {leg} down under {_names(worn)}"
        lines.append(said)
    if len(legs) > MAX_LEGS_TOLD:
        rest = legs[MAX_LEGS_TOLD:]
        lines.append(f"likewise {_names(rest)}, whose failure turns off "
                     f"{_names(sorted({g for x in rest for g in model.gaits_using(x)}))}")
    for f in freedoms:
        if not isinstance(f.change, HazardSwitch):
            continue
        hazard = next(h for h in model.hazards if h.name == f.change.hazard)
        touched = [x for x in legs if x in _legs_entering(model, hazard.name)]
        whose = f" ({_names(touched)} among them)" if touched else ""
        effect = hazard.effect
        lines.append(f"hazard set {hazard.name}, when on, {effect} of the gait in use in "
                     f"{_names(list(hazard.regions))}{whose}")
    if run is not None and run.steps and goal is not None and goal_regions:
        lines += _in_the_play(model, run, legs, goal, goal_regions)
    return lines


def _in_the_play(model: Model, run: Run, legs: Sequence[str], goal: str,
                 goal_regions: Sequence[str]) -> list[str]:
    """Where the core's legs fail in the play, and what the robot can reach after."""
    failed_at: dict[str, int] = {}
    for step in run.steps:
        for leg in step.failed:
            failed_at.setdefault(leg, step.index)
    last = run.steps[-1]
    dead = [leg for leg, level in last.health if level == 1]
    shown = [leg for leg in legs if leg in dead] or dead
    if not shown:
        return []
    where = last.region
    can = reachable(model, where, dead)
    goal = _names(list(goal_regions)) if len(goal_regions) <= 3 else goal
    if set(goal_regions) & can:
        return [f"when {_names(shown)} {'has' if len(shown) == 1 else 'have'} failed, the "
                f"robot in {where} can still reach {goal} on the map, but not keep its legs "
                "working on the way: the environment wins on the way there"]
    steps = [f"step {failed_at[leg]}" for leg in shown if leg in failed_at]
    when = f" (the play: {', '.join(steps)})" if steps else ""
    return [f"when {_names(shown)} {'fails' if len(shown) == 1 else 'fail'}{when}, the robot "
            f"cannot get from {where} to {goal}: no path of the map avoids the gaits that "
            f"use {_names(shown)}"]
