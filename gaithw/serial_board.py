"""A valve board on a serial line (pyserial URL: a device, ``socket://``, ``loop://``).

The line protocol (ASCII, one command per line, docs/hardware.md): ``PING`` → ``PONG
<firmware> valves=<n>``; ``V <bits>`` → ``OK`` or ``ERR <text>``; ``S`` → ``S h=<levels>
hazard=<name|-> region=<name|->``.  Garbled replies are retried, silence times out, and
every valve is vented on close and on any error (safety first).
"""

from __future__ import annotations

import contextlib
from collections.abc import Sequence
from typing import Any

from gaithw.backend import Backend, HardwareError, SensorReading, where

FIRMWARE_PREFIX = "PONG"
MAX_REPLY = 256  # bytes in one reply line, its \n included; a longer one is garbled
MAX_DIGITS = 6  # in a valve count or a health level of a reply


def _count(text: str) -> int | None:
    """A reply's number: ASCII digits only (``str.isdigit`` takes ``²`` and ``٣``), short."""
    if not (text.isascii() and text.isdigit()) or len(text) > MAX_DIGITS:
        return None
    return int(text)


class Garbled(Exception):
    """A reply that does not fit the protocol (internal: retried, then a HardwareError)."""


def parse_pong(line: str) -> tuple[str, int]:
    """``PONG <firmware> valves=<n>`` → (firmware, n)."""
    words = line.split()
    if len(words) != 3 or words[0] != FIRMWARE_PREFIX or not words[2].startswith("valves="):
        raise Garbled(line)
    count = _count(words[2][len("valves="):])
    if count is None or count < 1:
        raise Garbled(line)
    return words[1], count


def parse_sensors(line: str, legs: Sequence[str]) -> SensorReading:
    """``S h=3,3,2 hazard=- region=r12`` → a reading; ``-`` means none or unknown."""
    words = line.split()
    if not words or words[0] != "S":
        raise Garbled(line)
    fields: dict[str, str] = {}
    for word in words[1:]:
        key, sep, value = word.partition("=")
        if not sep or key not in ("h", "hazard", "region") or key in fields or not value:
            raise Garbled(line)
        fields[key] = value
    levels = [_count(v) for v in fields.get("h", "").split(",")]
    if len(levels) != len(legs) or None in levels:
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
    """The valve board behind a pyserial URL, speaking the gaitc line protocol."""

    def __init__(self, url: str, valve_count: int, legs: Sequence[str], baudrate: int = 115200,
                 timeout: float = 1.0, retries: int = 2,
                 channels: Sequence[int] | None = None) -> None:
        super().__init__(valve_count)
        self.url = url
        self.name = f"serial board {url}"
        self.legs = tuple(legs)
        self.baudrate = baudrate
        self.timeout = timeout
        self.retries = retries
        self.channels = tuple(channels) if channels is not None else None
        self.firmware = ""
        self.board_valves = 0
        self._port: Any = None

    # ------------------------------------------------------------------ connection
    def open(self) -> None:
        import serial

        try:
            self._port = serial.serial_for_url(self.url, baudrate=self.baudrate,
                                               timeout=self.timeout)
        except (serial.SerialException, ValueError, OSError) as err:
            raise HardwareError(
                f"cannot open the valve board at {self.url}: {err}", where(self.name),
                "check --port (a device such as /dev/ttyUSB0, or socket://HOST:PORT) and that "
                "the board is plugged in") from None
        try:
            self.firmware, self.board_valves = self._ask("PING", parse_pong)
            self._check_channels()
        except BaseException:
            self._shut()
            raise

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
            with contextlib.suppress(OSError):
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
        self._guarded(f"V {self.board_state(valves)}", _expect_ok)

    def read_sensors(self) -> SensorReading:
        reading: SensorReading = self._guarded("S", lambda line: parse_sensors(line, self.legs))
        return reading

    def wait(self, seconds: float) -> None:
        import time

        if seconds > 0:
            time.sleep(seconds)

    def _guarded(self, command: str, parse: Any) -> Any:
        """Run one command; on any failure vent every valve before the error propagates."""
        if self._port is None:
            raise HardwareError("the valve board is not open", where(self.name))
        try:
            return self._ask(command, parse)
        except HardwareError as err:
            self._vent_quietly()
            raise HardwareError(f"{err.message}; all valves vented", err.span, err.hint) from None
        except BaseException:
            self._vent_quietly()
            raise

    def _vent_quietly(self) -> None:
        """Best effort: send the all-vented state once, ignoring any failure."""
        if self._port is None or self.board_valves == 0:
            return
        try:
            self._port.reset_input_buffer()
            self._port.write(f"V {'0' * self.board_valves}\n".encode("ascii"))
            self._port.flush()
            self._port.readline(MAX_REPLY)
        except Exception:  # the board may be gone; venting must never mask the first error
            pass

    def _ask(self, command: str, parse: Any) -> Any:
        """Send ``command`` and parse the reply; retry garbled or missing replies."""
        import serial

        problem = ""
        for _attempt in range(self.retries + 1):
            try:
                self._port.reset_input_buffer()
                self._port.write(f"{command}\n".encode("ascii"))
                self._port.flush()
                raw = self._port.readline(MAX_REPLY)  # bounded: a board may babble
            except (serial.SerialException, OSError) as err:
                raise HardwareError(f"lost the valve board at {self.url}: {err}",
                                    where(self.name)) from None
            if len(raw) >= MAX_REPLY and not raw.endswith(b"\n"):
                problem = (f"garbled answer to '{command.split()[0]}': longer than "
                           f"{MAX_REPLY} bytes without an end of line")
                continue
            if not raw.endswith(b"\n"):
                problem = (f"no answer to '{command.split()[0]}' within {self.timeout:g} s"
                           if not raw else f"incomplete answer {raw!r} to '{command.split()[0]}'")
                continue
            line = raw.decode("ascii", errors="replace").strip()
            if line.startswith("ERR"):
                raise HardwareError(f"the board refused '{command}': {line[3:].strip()}",
                                    where(self.name))
            try:
                return parse(line)
            except Garbled:
                problem = f"garbled answer {line!r} to '{command.split()[0]}'"
        hint = ("check the baud rate (--baud) and the cable" if "garbled" in problem
                else "check that the board is powered and running gaitc firmware")
        raise HardwareError(f"valve board at {self.url}: {problem} "
                            f"(after {self.retries + 1} attempts)",
                            where(self.name), hint)


def _expect_ok(line: str) -> None:
    if line != "OK":
        raise Garbled(line)
