"""The controller node's observations under fuzzing: a mutant is a few lines, each one
``leg_health`` or ``hazards`` message (``TOPIC OFFSET NAME=VALUE ...``, the stamp OFFSET
seconds from now), handed to the node's subscription callbacks (:func:`exchange`) or
published to it over a real graph.  An oracle written apart from the node's checks says
which messages are bad; the node must never raise, and must vent exactly once for each bad
message (and never for a good one).
"""

from __future__ import annotations

import math
import time
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

from fuzz_oracle import Verdict

from gaitc.ros.topics import HAZARDS, LEG_HEALTH

LEGS = " ".join(f"L{i}=3" for i in range(1, 9))
EXCHANGES: tuple[tuple[str, bytes], ...] = (
    ("start.txt", f"hazards +0 blue=0 red=0\nleg_health +0 {LEGS}\n".encode()),
    ("worn.txt", b"hazards +0.01 blue=1 red=0\nleg_health +0.01 L1=3 L2=2 L3=1 L4=3 L5=3 "
                 b"L6=2 L7=3 L8=1\nleg_health +0.02 L1=2 L2=2 L3=1 L4=3 L5=3 L6=2 L7=3 L8=1\n"
                 b"hazards +0.02 blue=0 red=1\n"),
    ("order.txt", f"leg_health +0 {LEGS}\nhazards +0 red=0 blue=0\n"
                  f"leg_health -0.5 {LEGS}\n".encode()),
    ("odd.txt", b"leg_health +0 L8=1 L7=1 L6=1 L5=1 L4=1 L3=1 L2=1 L1=1\n"
                b"hazards +0 blue=0.0 red=1e0\nleg_health +2 L1=3\nhazards -3 blue=0\n"),
)
STALE_AFTER = 1.0
LIMIT_OFFSET = 1.0e6  # seconds: stamps stay inside builtin_interfaces/Time


@dataclass(frozen=True)
class Observation:
    """One message of a mutant: its topic, stamp offset (s) and (name, value) pairs."""

    topic: str
    offset: float
    pairs: tuple[tuple[str, float], ...]


def _number(word: str) -> float:
    try:
        return float(word)
    except ValueError:
        return math.nan


def parse(data: bytes) -> list[Observation]:
    """The messages of a mutant (any bytes: what does not parse becomes odd values)."""
    found = []
    for line in data.decode("utf-8", errors="replace").splitlines():
        words = line.replace("\x00", "").split()
        if not words:
            continue
        topic = HAZARDS.name if words[0] == HAZARDS.name else LEG_HEALTH.name
        offset = _number(words[1]) if len(words) > 1 else 0.0
        if not math.isfinite(offset):
            offset = LIMIT_OFFSET
        offset = max(-LIMIT_OFFSET, min(LIMIT_OFFSET, offset))
        # off the edge of staleness, so that the oracle's clock and the node's agree
        if abs(abs(offset) - STALE_AFTER) < 0.01:
            offset = math.copysign(STALE_AFTER + 0.02, offset)
        pairs = tuple((name, _number(value)) for name, _, value in
                      (w.partition("=") for w in words[2:]))
        found.append(Observation(topic, offset, pairs))
    return found


def message(seen: Observation, now: int) -> tuple[Any, int]:
    """The rclpy message of ``seen`` stamped relative to ``now``, and its stamp (ns)."""
    from gaitc.ros.topics import health_message

    at = max(0, now + int(seen.offset * 1e9))
    built = health_message((), at)  # a JointState, for either topic
    built.name = [name for name, _ in seen.pairs]
    built.position = [value for _, value in seen.pairs]
    return built, at


@dataclass
class Oracle:
    """Which observations are bad, decided apart from :mod:`gaitc.ros.observation`."""

    full: Mapping[str, int]
    hazards: Sequence[str]
    last: int | None = None
    health: dict[int, bool] = field(default_factory=dict)
    hazard: dict[int, bool] = field(default_factory=dict)

    def bad(self, seen: Observation, at: int, now: int) -> bool:
        names = [n for n, _ in seen.pairs]
        values = [v for _, v in seen.pairs]
        limit = int(STALE_AFTER * 1e9)
        if at == 0 or abs(now - at) > limit or (self.last is not None and at <= self.last):
            return True
        if seen.topic == HAZARDS.name:
            if not self.hazards or sorted(names) != sorted(self.hazards):
                return True
            if any(v not in (0.0, 1.0) for v in values) or values.count(1.0) > 1:
                return True
            self.hazard[at] = True
        else:
            if sorted(names) != sorted(self.full):
                return True
            for name, value in seen.pairs:
                if not (math.isfinite(value) and value == int(value)
                        and 1 <= value <= self.full[name]):
                    return True
            self.health[at] = True
        if at in self.health and (not self.hazards or at in self.hazard):
            self.last = at
            for pending in (self.health, self.hazard):
                for old in [s for s in pending if s <= at]:
                    del pending[old]
        else:
            for pending in (self.health, self.hazard):
                while len(pending) > 8:
                    del pending[min(pending)]
        return False


@dataclass
class Tally:
    """What an exchange did: messages, the bad ones, the vents."""

    messages: int = 0
    bad: int = 0
    vents: int = 0


def exchange(data: bytes, node: Any, tally: Tally | None = None,
             limit: float = 2.0) -> Verdict:
    """Hand each message of ``data`` to ``node``'s callbacks (its intake fresh): none may
    raise, and the node vents for exactly the bad ones, saying why on /diagnostics."""
    from gaitc.ros.observation import Intake

    node.intake = Intake(node.domain.full, tuple(node.domain.hazard_regions),
                         STALE_AFTER)
    oracle = Oracle(node.domain.full, tuple(node.domain.hazard_regions))
    counts = tally if tally is not None else Tally()
    problems: list[str] = []
    start = time.perf_counter()
    code = 0
    now = time.time_ns()  # one time for the mutant: equal offsets, equal stamps (a pair)
    for seen in parse(data):
        built, at = message(seen, now)
        expected = oracle.bad(seen, at, time.time_ns())
        before = node.vents
        try:
            (node.on_hazards if seen.topic == HAZARDS.name else node.on_health)(built)
        except Exception as err:  # the property: nothing escapes the callback
            problems.append(f"internal: {type(err).__name__}: {err} on {seen}")
            continue
        counts.messages += 1
        counts.bad += expected
        counts.vents += node.vents - before
        if node.vents - before != int(expected):
            problems.append(f"escaped: vented {node.vents - before} time(s) for a "
                            f"{'bad' if expected else 'good'} observation {seen}")
        elif expected:
            code = 1
            if node.status.level != 2 or not node.status.message.startswith(
                    f"bad observation: {seen.topic}: "):
                problems.append(f"escaped: /diagnostics did not say why: {node.status}")
    seconds = time.perf_counter() - start
    if seconds > limit:
        problems.append(f"past limit: {seconds:.1f} s")
    return Verdict("ros observations", code, seconds, problems)
