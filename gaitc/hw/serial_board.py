"""A valve board on a serial line (pyserial URL: a device, ``socket://``, ``loop://``).

Line protocol v2 (ASCII, one command a line, one answer line each; docs/hardware.md):
``PING`` → ``PONG <firmware> proto=2 valves=<n> [legs= contacts= wd= reset= monitor=]``;
``V <bits>`` → ``OK``; ``HB`` (heartbeat) → ``OK``; ``W <ms>`` → ``OK wd=<ms>``; ``S`` →
``S a=<adc,..> lo=<adc,..> c=<bits>`` (graded into health levels by :mod:`gaitc.hw.sensing`) or ``S
h=<levels>`` (a board that grades legs itself), with ``hazard=`` and ``region=``; any
refusal is ``ERR <text>``.  A board whose controller carries recovery tables also sends
``R <outcome> k=<goals kept> ...`` (:func:`parse_outcome`).  The board vents on its own
when no valid command arrives for its watchdog period, so the host sends a heartbeat while
valves are open.  Every read is bounded in bytes and by a deadline of ``timeout`` seconds;
garbled replies are retried, and every valve is vented on close and on any error.  Messages
say whether a vent was acknowledged or only the board's watchdog is left to vent.
"""

from __future__ import annotations

import contextlib
import time
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any, TypeVar

import serial

from gaitc.core.modes import Outcome
from gaitc.hw.backend import Backend, HardwareError, SensorReading, where
from gaitc.hw.sensing import HealthSensing, LegCalibration
from gaitc.sim.environments import Move

PROTOCOL = 2
FIRMWARE_PREFIX = "PONG"
MAX_REPLY = 256  # bytes in one reply line, its \n included; a longer one is garbled
MAX_DRAIN = 4096  # stale bytes thrown away before a command, at most
MAX_DIGITS = 6  # in a number of a reply
MAX_VALVES = 32  # a V command must fit the board's 48-character line
ADC_FULL = 1023  # a 10-bit converter
POLL = 0.02  # seconds of one port read inside a deadline
DEFAULT_WATCHDOG_MS = 500
T = TypeVar("T")


def link_errors() -> tuple[type[BaseException], ...]:
    """What the port raises when the board goes away: pyserial's error, the OS's, and on
    POSIX termios's, which is no OSError (``flush`` drains with ``tcdrain``, and a
    vanished pseudo-terminal makes that fail with EIO)."""
    found: tuple[type[BaseException], ...] = (serial.SerialException, OSError)
    with contextlib.suppress(ImportError):
        import termios  # lazy: POSIX only

        found += (termios.error,)
    return found


def _count(text: str) -> int | None:
    """A reply's number: ASCII digits only (``str.isdigit`` takes ``²`` and ``٣``), short."""
    if not (text.isascii() and text.isdigit()) or len(text) > MAX_DIGITS:
        return None
    return int(text)


class Garbled(Exception):
    """A reply that does not fit the protocol (internal: retried, then a HardwareError)."""


@dataclass(frozen=True)
class BoardInfo:
    """What the board says of itself at the handshake."""

    firmware: str
    protocol: int
    valves: int
    legs: int | None = None
    contacts: int | None = None
    watchdog_ms: int | None = None
    reset: str | None = None
    #: a board running a generated controller: whether it checks the spec's assumptions
    #: (None: no controller linked, or a firmware that does not say)
    monitor: bool | None = None


_PONG_NUMBERS = ("proto", "valves", "legs", "contacts", "wd")


def parse_pong(line: str) -> BoardInfo:
    """``PONG gaitboard/2.0 proto=2 valves=8 legs=8 contacts=4 wd=500 reset=power``; a
    v1 board (``PONG <firmware> valves=<n>``) parses as protocol 1."""
    words = line.split()
    if len(words) < 3 or words[0] != FIRMWARE_PREFIX:
        raise Garbled(line)
    fields: dict[str, str] = {}
    for word in words[2:]:
        key, sep, value = word.partition("=")
        if not sep or not value or key in fields or key not in (*_PONG_NUMBERS, "reset",
                                                                 "monitor"):
            raise Garbled(line)
        fields[key] = value
    numbers = {key: _count(fields[key]) for key in _PONG_NUMBERS if key in fields}
    if None in numbers.values() or "valves" not in numbers:
        raise Garbled(line)
    valves = numbers["valves"]
    if valves is None or valves < 1 or fields.get("monitor", "0") not in ("0", "1"):
        raise Garbled(line)
    monitor = None if "monitor" not in fields else fields["monitor"] == "1"
    return BoardInfo(words[1], numbers.get("proto") or 1, valves, numbers.get("legs"),
                     numbers.get("contacts"), numbers.get("wd"), fields.get("reset"),
                     monitor=monitor)


Grader = Callable[[dict[str, float], dict[str, float]], Mapping[str, int]]


def _adc(text: str, legs: Sequence[str], line: str) -> dict[str, float]:
    values = [_count(v) for v in text.split(",")]
    if len(values) < len(legs) or any(v is None or v > ADC_FULL for v in values):
        raise Garbled(line)
    return {leg: float(v) for leg, v in zip(legs, values, strict=False) if v is not None}


def parse_sensors(line: str, legs: Sequence[str], grade: Grader | None = None) -> SensorReading:
    """``S h=3,3,2 hazard=- region=r12`` (levels graded by the board) or ``S a=1023,512
    lo=330,512 c=..`` (each leg's waveguide now and its lowest in its last actuation, graded
    here by ``grade``, which is called only once the whole line is valid) → a reading."""
    words = line.split()
    if not words or words[0] != "S":
        raise Garbled(line)
    fields: dict[str, str] = {}
    for word in words[1:]:
        key, sep, value = word.partition("=")
        if (not sep or key not in ("h", "a", "lo", "c", "hazard", "region") or key in fields
                or not value):
            raise Garbled(line)
        fields[key] = value
    if "h" in fields:
        levels = [_count(v) for v in fields["h"].split(",")]
        if len(levels) != len(legs):
            raise Garbled(line)
        if None in levels:
            raise Garbled(line)
    elif "a" in fields and "lo" in fields and grade is not None:
        now, lowest = _adc(fields["a"], legs, line), _adc(fields["lo"], legs, line)
        if "c" in fields and set(fields["c"]) - {"0", "1"}:
            raise Garbled(line)
        graded = grade(now, lowest)
        levels = [graded[leg] for leg in legs]
    else:
        raise Garbled(line)
    hazard = fields.get("hazard", "-")
    region = fields.get("region", "-")
    return SensorReading(tuple((leg, v) for leg, v in zip(legs, levels, strict=True)
                               if v is not None),
                         None if hazard == "-" else hazard, None if region == "-" else region)


def parse_channels(text: str, span_name: str = "--channels") -> tuple[int, ...]:
    """``"3,2,1,0"`` → (3, 2, 1, 0): robot valve i drives board channel ``channels[i]``."""
    try:
        channels = tuple(int(part) for part in text.split(","))
    except ValueError:
        raise HardwareError(f"valve channel map {text!r} is not a comma-separated list of "
                            "board channel numbers", where(span_name),
                            "write e.g. --channels 0,1,2,3,4,5,6,7") from None
    return channels


class SerialValveBoard(Backend):
    """The valve board behind a pyserial URL, speaking the gaitc line protocol v2."""

    def __init__(self, url: str, valve_count: int, legs: Sequence[str], baudrate: int = 115200,
                 *, timeout: float = 1.0, retries: int = 2,
                 channels: Sequence[int] | None = None,
                 levels: Mapping[str, int] | None = None,
                 calibration: Mapping[str, LegCalibration] | None = None) -> None:
        super().__init__(valve_count)
        self.url = url
        self.name = f"serial board {url}"
        self.legs = tuple(legs)
        self.baudrate = baudrate
        self.timeout = timeout
        self.retries = retries
        self.channels = tuple(channels) if channels is not None else None
        self.sensing = HealthSensing(levels, calibration) if levels else None
        self.in_use: tuple[str, ...] = ()  # the legs the step's gait pressurised
        self.in_cache = False
        self.info: BoardInfo | None = None
        self.firmware = ""
        self.board_valves = 0
        self.state = ""  # the last valve state the board acknowledged
        self.vent_acknowledged = True
        self.link_lost = False  # the last vent got no answer at all
        self._port: Any = None

    @property
    def watchdog_ms(self) -> int:
        """The board's watchdog period (its own report, else the firmware default)."""
        reported = self.info.watchdog_ms if self.info is not None else None
        return reported or DEFAULT_WATCHDOG_MS

    def safety_note(self) -> str:
        if self.vent_acknowledged:
            return "all valves vented"
        known = "link lost" if self.link_lost else "the vent was not acknowledged"
        return f"{known}; the board's watchdog vents within {self.watchdog_ms} ms"

    # ------------------------------------------------------------------ connection
    def open(self) -> None:
        try:
            self._port = serial.serial_for_url(self.url, baudrate=self.baudrate, timeout=POLL,
                                               write_timeout=self.timeout)
        except (serial.SerialException, ValueError, OSError) as err:
            raise HardwareError(
                f"cannot open the valve board at {self.url}: {err}", where(self.name),
                "check --port (a device such as /dev/ttyUSB0, or socket://HOST:PORT) and that "
                "the board is plugged in") from None
        try:
            info = self.info = self._ask("PING", parse_pong)
            self.firmware, self.board_valves = info.firmware, info.valves
            self._check_board(info)
            self._check_channels()
        except BaseException:
            self._shut()
            raise

    def _check_board(self, info: BoardInfo) -> None:
        if info.protocol != PROTOCOL:
            raise HardwareError(
                f"the board ({info.firmware}) speaks protocol v{info.protocol}; this gaitc "
                f"speaks v{PROTOCOL}", where(self.name),
                "flash the current firmware (gaitc firmware build, docs/hardware.md)")
        if info.valves > MAX_VALVES:
            raise HardwareError(f"the board claims {info.valves} valves; protocol v2 drives "
                                f"at most {MAX_VALVES}", where(self.name))
        if info.legs is not None and self.sensing and info.legs < len(self.legs):
            raise HardwareError(f"the spec has {len(self.legs)} legs but the board "
                                f"({info.firmware}) senses {info.legs}", where(self.name))

    def _check_channels(self) -> None:
        if self.channels is None:
            if self.valve_count != self.board_valves:
                raise HardwareError(
                    f"the robot has {self.valve_count} valves but the board "
                    f"({self.firmware}) drives {self.board_valves}", where(self.name),
                    "give a valve channel map (--channels) from robot valves to board channels")
            return
        if len(self.channels) != self.valve_count:
            raise HardwareError(
                f"the valve channel map lists {len(self.channels)} channels but the robot has "
                f"{self.valve_count} valves", where(self.name))
        bad = [c for c in self.channels if not 0 <= c < self.board_valves]
        if bad or len(set(self.channels)) != len(self.channels):
            raise HardwareError(
                f"the valve channel map {','.join(map(str, self.channels))} needs distinct "
                f"channels in 0..{self.board_valves - 1} (the board drives "
                f"{self.board_valves})", where(self.name))

    def close(self) -> None:
        if self._port is None:
            return
        try:
            self._vent_quietly()
        finally:
            self._shut()

    def _shut(self) -> None:
        port, self._port = self._port, None
        if port is not None:
            with contextlib.suppress(Exception):  # a dead link must not mask the first error
                port.close()

    # ------------------------------------------------------------------ commands
    def board_state(self, valves: str) -> str:
        """The board's valve string for a robot valve state (through the channel map)."""
        if self.channels is None:
            return valves
        bits = ["0"] * self.board_valves
        for value, channel in zip(valves, self.channels, strict=True):
            bits[channel] = value
        return "".join(bits)

    def apply(self, valves: str) -> None:
        self.check_valves(valves)
        board = self.board_state(valves)
        self._guarded(f"V {board}", _expect_ok)
        self.state = board

    def step_context(self, in_use: tuple[str, ...], in_cache: bool) -> None:
        self.in_use, self.in_cache = in_use, in_cache

    def accepted(self, move: Move) -> None:
        if self.sensing is not None:  # grade the next reading from the controller's levels
            self.sensing.levels.update(move.state.health)

    def read_sensors(self) -> SensorReading:
        sensing = self.sensing
        grade = None if sensing is None else (
            lambda now, low: sensing.update(now, low, self.in_use, self.in_cache))
        reading: SensorReading = self._guarded("S", lambda line: parse_sensors(line, self.legs,
                                                                               grade))
        return reading

    def wait(self, seconds: float) -> None:
        """Let ``seconds`` pass; while a valve is open, send a heartbeat every quarter of the
        board's watchdog period so that the board keeps the state."""
        end = time.monotonic() + max(0.0, seconds)
        beat = self.watchdog_ms / 4000.0
        while True:
            left = end - time.monotonic()
            if left <= 0:
                return
            time.sleep(min(left, beat) if "1" in self.state else left)
            if "1" in self.state and end - time.monotonic() > 0:
                self._guarded("HB", _expect_ok)

    def _guarded(self, command: str, parse: Callable[[str], T]) -> T:
        """Run one command; on any failure vent every valve before the error propagates."""
        if self._port is None:
            raise HardwareError("the valve board is not open", where(self.name))
        try:
            return self._ask(command, parse)
        except HardwareError as err:
            self._vent_quietly()
            raise HardwareError(f"{err.message}; {self.safety_note()}", err.span,
                                err.hint) from None
        except BaseException:
            self._vent_quietly()
            raise

    def _vent_quietly(self) -> None:
        """Best effort: send the all-vented state once; record whether the board said OK."""
        self.vent_acknowledged, self.link_lost = False, True
        if self._port is None or self.board_valves == 0:
            return
        try:
            self._drain()
            self._port.write(f"V {'0' * self.board_valves}\n".encode("ascii"))
            self._port.flush()
            answer = self._read_line(time.monotonic() + self.timeout)
        except Exception:  # the board may be gone; venting must never mask the first error
            return
        self.link_lost = not answer
        if answer.strip() == b"OK":
            self.vent_acknowledged = True
            self.state = "0" * self.board_valves

    def _drain(self) -> None:
        """Throw away stale input: at most MAX_DRAIN bytes, so a babbling board cannot stall."""
        dropped = 0
        while dropped < MAX_DRAIN:
            waiting = min(self._port.in_waiting, MAX_DRAIN - dropped)
            if waiting <= 0:
                return
            dropped += len(self._port.read(waiting))

    def _read_line(self, deadline: float) -> bytes:
        """One line, its ``\\n`` included, of at most MAX_REPLY bytes, read by ``deadline``;
        shorter when the board is silent, longer lines are cut at MAX_REPLY."""
        line = bytearray()
        while len(line) < MAX_REPLY and time.monotonic() < deadline:
            want = max(1, min(self._port.in_waiting, MAX_REPLY - len(line)))
            line += self._port.read(want)
            end = line.find(b"\n")
            if end >= 0:
                return bytes(line[:end + 1])
        return bytes(line)

    def _ask(self, command: str, parse: Callable[[str], T]) -> T:
        """Send ``command`` and parse the reply; retry garbled or missing replies."""
        problem = ""
        verb = command.split()[0]
        for _attempt in range(self.retries + 1):
            try:
                self._drain()
                self._port.write(f"{command}\n".encode("ascii"))
                self._port.flush()
                raw = self._read_line(time.monotonic() + self.timeout)  # bounded both ways
            except link_errors() as err:
                raise HardwareError(f"lost the valve board at {self.url}: {err}",
                                    where(self.name)) from None
            if len(raw) >= MAX_REPLY and not raw.endswith(b"\n"):
                problem = (f"garbled answer to '{verb}': longer than {MAX_REPLY} bytes "
                           "without an end of line")
                continue
            if not raw.endswith(b"\n"):
                problem = (f"no answer to '{verb}' within {self.timeout:g} s" if not raw
                           else f"incomplete answer {raw[:40]!r} to '{verb}' within "
                           f"{self.timeout:g} s")
                continue
            line = raw.decode("ascii", errors="replace").strip()
            if line.startswith("ERR"):
                raise HardwareError(f"the board refused '{command}': {line[3:].strip()}",
                                    where(self.name))
            try:
                return parse(line)
            except Garbled:
                problem = f"garbled answer {line[:80]!r} to '{verb}'"
        hint = ("check the baud rate (--baud) and the cable" if "garbled" in problem
                else "check that the board is powered and running gaitc firmware")
        raise HardwareError(f"valve board at {self.url}: {problem} "
                            f"(after {self.retries + 1} attempts)",
                            where(self.name), hint)


def _expect_ok(line: str) -> None:
    if line != "OK":
        raise Garbled(line)


@dataclass(frozen=True)
class BoardOutcome:
    """An ``R`` line of a board whose controller carries recovery tables (``codegen
    --recover``): what a step did whatever the inputs (allowed, recovered, degraded,
    stopped), the goals still pursued (bit j for goal j + 1), and, as the board says, the
    step (``s=``, running alone) or the move, goal and field values (``m= g= o=``, the
    answer to ``C r``)."""

    outcome: Outcome
    kept: int
    step: int | None = None
    move: int | None = None
    goal: int | None = None
    values: str | None = None


_R_KEYS = ("k", "s", "m", "g", "o")


def parse_outcome(line: str) -> BoardOutcome:
    """``R recovered k=3 s=12`` or ``R degraded k=2 m=4 g=0 o=0a12``; anything else is
    :class:`Garbled`.  Boards without recovery tables never send it (protocol v2 is
    otherwise unchanged)."""
    words = line.split()
    if len(words) < 3 or words[0] != "R" or words[1] not in [str(o) for o in Outcome]:
        raise Garbled(line)
    fields: dict[str, str] = {}
    for word in words[2:]:
        key, sep, value = word.partition("=")
        if not sep or not value or key in fields or key not in _R_KEYS:
            raise Garbled(line)
        fields[key] = value
    numbers = {key: _count(fields[key]) for key in ("k", "s", "m", "g") if key in fields}
    kept = numbers.get("k")
    if kept is None or None in numbers.values():
        raise Garbled(line)
    values = fields.get("o")
    if values is not None and not (values.isascii() and values.isalnum()):
        raise Garbled(line)
    return BoardOutcome(Outcome(words[1]), kept, numbers.get("s"), numbers.get("m"),
                        numbers.get("g"), values)
