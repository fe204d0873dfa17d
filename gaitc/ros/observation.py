"""Reading the robot's observations: each ``leg_health`` and ``hazards`` message checked
against the spec (known names, levels in range, a fresh stamp) and paired by stamp into
one reading, the environment's input of a step.

A message that fails a check raises :class:`~gaitc.hw.backend.HardwareError` naming what
is wrong; the node reports it on ``/diagnostics`` and stops with every valve vented.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

from gaitc.hw.backend import HardwareError
from gaitc.ros.topics import HAZARDS, LEG_HEALTH, nanoseconds

#: Pending halves of a pair kept at most (older ones are dropped).
PENDING = 8


@dataclass(frozen=True)
class Reading:
    """One observation: its stamp (ns), each leg's level in the spec's leg order, and the
    hazard set that is on (None: none)."""

    stamp: int
    health: tuple[tuple[str, int], ...]
    hazard: str | None


class Intake:
    """Checks observation messages and pairs ``leg_health`` with ``hazards`` by stamp.

    ``full`` gives each leg's number of levels (in the spec's leg order), ``hazards`` the
    spec's hazard sets (none: a ``leg_health`` message alone is a reading), ``stale_after``
    the largest age (and lead) of a stamp, in seconds."""

    def __init__(self, full: Mapping[str, int], hazards: Sequence[str],
                 stale_after: float) -> None:
        self.full = dict(full)
        self.hazard_sets = tuple(hazards)
        self.stale_after = int(stale_after * 1e9)
        self.last: int | None = None  # the stamp of the last reading made
        self._health: dict[int, tuple[tuple[str, int], ...]] = {}
        self._hazard: dict[int, str | None] = {}

    def health(self, message: Any, now: int) -> Reading | None:
        """A ``leg_health`` message received at ``now`` ns: the reading it completes."""
        at = self._stamp(message, now, LEG_HEALTH.name)
        levels = self._named(message, tuple(self.full), LEG_HEALTH.name, "leg")
        health = []
        for leg in self.full:
            value = levels[leg]
            if not math.isfinite(value) or value != int(value) or not (
                    1 <= value <= self.full[leg]):
                raise HardwareError(f"{LEG_HEALTH.name}: leg {leg} has health level "
                                    f"{_number(value)}, outside 1..{self.full[leg]}")
            health.append((leg, int(value)))
        self._health[at] = tuple(health)
        return self._paired(at)

    def hazards(self, message: Any, now: int) -> Reading | None:
        """A ``hazards`` message received at ``now`` ns: the reading it completes."""
        if not self.hazard_sets:
            raise HardwareError(f"{HAZARDS.name}: the spec has no hazard sets")
        at = self._stamp(message, now, HAZARDS.name)
        states = self._named(message, self.hazard_sets, HAZARDS.name, "hazard set")
        bad = [f"{name} {_number(v)}" for name, v in states.items() if v not in (0.0, 1.0)]
        if bad:
            raise HardwareError(f"{HAZARDS.name}: a hazard set is 1 (on) or 0 (off), not "
                                f"{', '.join(bad)}")
        on = [name for name in self.hazard_sets if states[name] == 1.0]
        if len(on) > 1:
            raise HardwareError(f"{HAZARDS.name}: hazard sets {', '.join(on)} are on at once; "
                                "the spec has at most one on")
        self._hazard[at] = on[0] if on else None
        return self._paired(at)

    def _paired(self, at: int) -> Reading | None:
        if at not in self._health or (self.hazard_sets and at not in self._hazard):
            for pending in (self._health, self._hazard):
                while len(pending) > PENDING:
                    del pending[min(pending)]
            return None
        reading = Reading(at, self._health.pop(at), self._hazard.pop(at, None))
        self.last = at
        for pending in (self._health, self._hazard):
            for old in [s for s in pending if s <= at]:
                del pending[old]
        return reading

    def _stamp(self, message: Any, now: int, topic: str) -> int:
        at = nanoseconds(message.header.stamp)
        if at == 0:
            raise HardwareError(f"{topic}: the message has no stamp (header.stamp is 0)")
        if now - at > self.stale_after:
            raise HardwareError(f"{topic}: stale reading, stamped {(now - at) / 1e9:.3f} s "
                                f"ago (more than {self.stale_after / 1e9:g} s)")
        if at - now > self.stale_after:
            raise HardwareError(f"{topic}: the reading is stamped {(at - now) / 1e9:.3f} s "
                                "in the future; check the robot's clock")
        if self.last is not None and at <= self.last:
            raise HardwareError(f"{topic}: the reading is not newer than the last one "
                                f"(stamped {(self.last - at) / 1e9:.6f} s before it)")
        return at

    @staticmethod
    def _named(message: Any, names: tuple[str, ...], topic: str, what: str
               ) -> dict[str, float]:
        given, values = list(message.name), list(message.position)
        if len(given) != len(values):
            raise HardwareError(f"{topic}: {len(given)} names but {len(values)} positions")
        unknown = [n for n in given if n not in names]
        if unknown:
            raise HardwareError(f"{topic}: unknown {what} {_quoted(unknown[0])}; the spec has "
                                f"{', '.join(names)}")
        twice = sorted({n for n in given if given.count(n) > 1})
        if twice:
            raise HardwareError(f"{topic}: {what} {twice[0]} is named twice")
        missing = [n for n in names if n not in given]
        if missing:
            raise HardwareError(f"{topic}: no value for {what} {', '.join(missing)}")
        return {n: float(v) for n, v in zip(given, values, strict=True)}


def _number(value: float) -> str:
    return str(int(value)) if math.isfinite(value) and value == int(value) else repr(value)


def _quoted(name: str) -> str:
    shown = name if len(name) <= 40 else name[:37] + "..."
    return repr(shown)
