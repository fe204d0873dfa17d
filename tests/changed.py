"""What a test checks of an event performed: the state after it has what the event names,
judged without :mod:`gaitc.core.changes`'s own arithmetic."""

from __future__ import annotations

from collections.abc import Mapping

from gaitc.core.changes import HazardSwitch, LegFails, LegRepaired, LegWears
from gaitc.sim.domain import State
from gaitc.sim.events import Event


def agrees(event: Event, now: Mapping[str, int], state: State) -> bool:
    """Whether ``state`` has what ``event`` performed when the legs were at ``now`` names:
    a failed leg at level 1, a degraded one ``k`` levels lower (at least 1), a leg repaired
    to the level named higher than before, a hazard set on (or not on)."""
    levels = dict(state.health)
    for change in event.changes:
        match change:
            case LegFails(leg):
                ok = levels[leg] == 1
            case LegWears(leg, k):
                ok = levels[leg] == max(1, now[leg] - k)
            case LegRepaired(leg, level):
                ok = levels[leg] >= now[leg] and (level is None or levels[leg] == level)
            case HazardSwitch(hazard, on):
                ok = (state.hazard == hazard) == on
        if not ok:
            return False
    return True


def legs_named(event: Event) -> bool:
    """Whether ``event`` changes a leg."""
    return any(not isinstance(c, HazardSwitch) for c in event.changes)


def hazard_named(event: Event) -> bool:
    """Whether ``event`` switches a hazard set."""
    return any(isinstance(c, HazardSwitch) for c in event.changes)
