"""The interface every valve-board backend implements, the sensor reading, hardware errors.

A backend applies valve states (thesis section 2.2: one Boolean per pneumatic chamber, open
to the rail or vented) and reports what the robot senses: each leg's health level (from the
waveguide curvature thresholds of thesis section 3.4.2), the active hazard and the region.
"""

from __future__ import annotations

import contextlib
import math
import signal
import threading
from abc import ABC, abstractmethod
from collections.abc import Iterator, Sequence
from dataclasses import dataclass
from types import FrameType, TracebackType

from gaitc.diagnostics import GaitcError, Span
from gaitc.sim.environments import Move


class HardwareError(GaitcError, RuntimeError):
    """The valve board or the robot failed: port missing, no answer, protocol error, timeout."""


class Interrupted(KeyboardInterrupt):
    """SIGTERM or SIGHUP arrived during a drive: handled as Ctrl-C is (vent, keep the run)."""

    def __init__(self, name: str) -> None:
        super().__init__(name)
        self.name = name


@contextlib.contextmanager
def interrupt_on_signals() -> Iterator[None]:
    """While inside, SIGTERM and SIGHUP raise :class:`Interrupted` (in the main thread)."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return

    def interrupt(signum: int, frame: FrameType | None) -> None:
        raise Interrupted(signal.Signals(signum).name)

    kept = {sig: signal.signal(sig, interrupt) for sig in (signal.SIGTERM, signal.SIGHUP)}
    try:
        yield
    finally:
        for sig, handler in kept.items():
            signal.signal(sig, handler)


@dataclass(frozen=True)
class SensorReading:
    """What the robot senses before the controller's next move."""

    health: tuple[tuple[str, int], ...]  # (leg, level) in leg order; 1 = failed
    hazard: str | None  # the active hazard set, None when no hazard is active
    region: str | None  # the region the localisation reports, None when unknown


def is_valve_state(valves: str) -> bool:
    """True when ``valves`` is a non-empty string of 0/1 characters."""
    return bool(valves) and set(valves) <= {"0", "1"}


def level_from_waveguide(extension: float, thresholds: Sequence[float]) -> int:
    """The health level of a leg from its normalised waveguide extension (thesis 3.4.2).

    ``thresholds`` are descending, one per level above 1: with ``(0.8, 0.3)`` an extension
    of at least 0.8 is level 3 (healthy), at least 0.3 level 2 (degraded), below it level 1.
    """
    level = len(thresholds) + 1
    for threshold in thresholds:
        if extension >= threshold:
            return level
        level -= 1
    return 1


@dataclass(frozen=True)
class Course:
    """The last gait's chassis motion (mm, world frame) against the move it was to make,
    from the centre of its start region to the centre of the region expected."""

    moved: tuple[float, float]
    wanted: tuple[float, float]

    @property
    def error(self) -> float:
        """The angle between the motion and the move, degrees in [0, 180]."""
        (mx, my), (wx, wy) = self.moved, self.wanted
        if math.hypot(mx, my) < 1e-9 or math.hypot(wx, wy) < 1e-9:
            return 180.0
        turn = math.degrees(math.atan2(my, mx) - math.atan2(wy, wx))
        return abs((turn + 180.0) % 360.0 - 180.0)

    @property
    def progress(self) -> float:
        """How far (mm) the motion went along the move."""
        (mx, my), (wx, wy) = self.moved, self.wanted
        length = math.hypot(wx, wy)
        return 0.0 if length < 1e-9 else (mx * wx + my * wy) / length


#: A gait whose motion is this many degrees or more off its move went the wrong way
#: (rather than too short).
WRONG_WAY = 45.0


class Backend(ABC):
    """A valve board plus sensors; a context manager that vents every valve when it closes."""

    name = "backend"

    def __init__(self, valve_count: int) -> None:
        self.valve_count = valve_count

    @property
    def vented(self) -> str:
        """The valve state with every chamber vented."""
        return "0" * self.valve_count

    @abstractmethod
    def open(self) -> None:
        """Connect to the board (handshake); raise :class:`HardwareError` when it fails."""

    @abstractmethod
    def close(self) -> None:
        """Vent every valve (best effort) and disconnect; safe to call twice."""

    @abstractmethod
    def apply(self, valves: str) -> None:
        """Set one valve state: a 0/1 string with one character per robot valve."""

    @abstractmethod
    def read_sensors(self) -> SensorReading:
        """The current health levels, hazard and region."""

    @abstractmethod
    def wait(self, seconds: float) -> None:
        """Let ``seconds`` pass between valve states (a simulation may skip it)."""

    def step_context(self, in_use: tuple[str, ...], in_cache: bool) -> None:
        """Before a reading: the legs the step's gait used and whether the robot is in a
        cache, for a backend that grades health from its sensors (the default ignores it)."""
        del in_use, in_cache

    def accepted(self, move: Move) -> None:
        """The input the controller took for the last reading (it may stand for a reading that
        broke an assumption, see ``--on-violation``): a backend that keeps state syncs it."""
        del move

    def safety_note(self) -> str:
        """What is known of the valves after the last vent (for messages)."""
        return "all valves vented"

    def course(self, source: str, target: str) -> Course | None:
        """Where the chassis went during the last gait, against the move from region
        ``source`` to region ``target``, for a backend that knows the chassis pose and the
        regions' places (the default: unknown)."""
        del source, target
        return None

    def vent(self) -> None:
        """Vent every valve."""
        self.apply(self.vented)

    def check_valves(self, valves: str) -> None:
        """Reject a valve state of the wrong shape before it reaches the board."""
        if not is_valve_state(valves):
            raise HardwareError(f"valve state {valves!r} is not a string of 0 and 1",
                                where(self.name))
        if len(valves) != self.valve_count:
            raise HardwareError(
                f"valve state {valves} has {len(valves)} valves but the robot has "
                f"{self.valve_count}", where(self.name),
                "check the gait's primitive against the robot file")

    def __enter__(self) -> Backend:
        self.open()
        return self

    def __exit__(self, kind: type[BaseException] | None, error: BaseException | None,
                 trace: TracebackType | None) -> None:
        self.close()


def where(name: str) -> Span:
    """The span of a hardware error: the backend (port) name, since no file is involved."""
    return Span(f"<{name}>", 1, 1)
