"""The valve-board firmware: building its image and running it in the simavr harness.

The C sources are package data in ``board/`` beside this module (``firmware/`` in the repository
links there): ``gaitboard.c`` is the firmware of an ATmega328P valve board (protocol v2,
docs/hardware.md), built with avr-gcc and avr-libc; ``harness.c`` is ``gaitboard-sim``, a small
program on libsimavr that runs the real image in real time, gives its UART as a pseudo-terminal,
takes waveguide (ADC) values on a control channel and records every valve pin change with its
simulated time.
"""

from __future__ import annotations

import json
import os
import select
import shutil
import subprocess
import time
from dataclasses import dataclass
from pathlib import Path
from types import TracebackType

from gaitc.diagnostics import GaitcError, Span
from gaitc.diagnostics.files import make_folder

SOURCES = Path(__file__).resolve().parent / "board"
MCU = "atmega328p"
F_CPU = 16_000_000
AVR_FLAGS = ("-mmcu=" + MCU, f"-DF_CPU={F_CPU}UL", "-Os", "-std=gnu99", "-Wall", "-Wextra",
             "-Werror")
HOST_FLAGS = ("-O2", "-Wall", "-Wextra", "-Werror")
SIMAVR_HEADER = Path("/usr/include/simavr/sim_avr.h")
START_TIMEOUT = 10.0  # seconds for the harness to boot the image and print its pty


class FirmwareError(GaitcError, RuntimeError):
    """The firmware or its simulator could not be built or started."""


def _where(what: str) -> Span:
    return Span(f"<{what}>", 1, 1)


@dataclass(frozen=True)
class Image:
    """A built firmware: the ELF image, its Intel HEX for a programmer, the harness."""

    elf: Path
    hex: Path
    simulator: Path | None  # None when libsimavr is not installed


def missing_tools(simulator: bool = True) -> list[str]:
    """The Debian packages still needed to build the image (and the simulator): empty when
    everything is there."""
    missing = []
    if shutil.which("avr-gcc") is None or shutil.which("avr-objcopy") is None:
        missing.append("gcc-avr")
    if not Path("/usr/lib/avr/include/avr/io.h").exists() and shutil.which("avr-gcc"):
        missing.append("avr-libc")
    if simulator:
        if shutil.which("gcc") is None:
            missing.append("gcc")
        if not SIMAVR_HEADER.exists():
            missing.append("libsimavr-dev")
    return missing


def run_tool(argv: list[str], what: str) -> str:
    """Run a toolchain program; its standard output, or :class:`FirmwareError` saying what
    failed (the last lines of its errors) or that it is not installed."""
    try:
        done = subprocess.run(argv, capture_output=True, text=True, check=False)
    except OSError as err:
        raise FirmwareError(f"cannot run {argv[0]}: {err}", _where(what),
                            "install the toolchain: apt-get install gcc-avr avr-libc simavr "
                            "libsimavr-dev libsimavrparts1 (scripts/setup.sh does it)") from None
    if done.returncode != 0:
        detail = (done.stderr or done.stdout).strip().splitlines()
        raise FirmwareError(f"{what} failed: " + (" | ".join(detail[-5:]) or "no output"),
                            _where(what))
    return done.stdout


def build(out_dir: str | Path, simulator: bool = True) -> Image:
    """Build ``gaitboard.elf`` and ``gaitboard.hex`` (and ``gaitboard-sim`` when
    ``simulator``) into ``out_dir``; raise :class:`FirmwareError` saying what is missing."""
    need = missing_tools(simulator)
    if need:
        raise FirmwareError(f"cannot build the firmware: missing {', '.join(need)}",
                            _where("firmware build"),
                            "on Debian: apt-get install gcc-avr avr-libc simavr libsimavr-dev "
                            "libsimavrparts1 (scripts/setup.sh does it when run as root)")
    if not (SOURCES / "gaitboard.c").exists():
        raise FirmwareError(f"the firmware sources are not in {SOURCES}",
                            _where("firmware build"),
                            "run gaitc from a checkout of the repository (pip install -e .)")
    out = Path(out_dir)
    make_folder(out)
    elf, hexfile = out / "gaitboard.elf", out / "gaitboard.hex"
    run_tool(["avr-gcc", *AVR_FLAGS, "-o", str(elf), str(SOURCES / "gaitboard.c")],
         "avr-gcc gaitboard.c")
    run_tool(["avr-objcopy", "-O", "ihex", "-R", ".eeprom", str(elf), str(hexfile)],
         "avr-objcopy gaitboard.elf")
    sim = None
    if simulator:
        sim = out / "gaitboard-sim"
        run_tool(["gcc", *HOST_FLAGS, "-o", str(sim), str(SOURCES / "harness.c"), "-lsimavr",
              "-lm"],
             "gcc harness.c (libsimavr)")
    return Image(elf, hexfile, sim)


def simulator_argv(image: Image, record: str | Path | None = None,
                   watchdog_ms: int | None = None, adc_mv: int | None = None,
                   depth: float | None = None, noise_mv: float | None = None) -> list[str]:
    """The command line that runs ``image`` in the harness: ``adc_mv`` each waveguide's
    at-rest millivolts, ``depth`` how far a bent leg dims it, ``noise_mv`` added noise."""
    if image.simulator is None:
        raise FirmwareError("the firmware was built without its simulator",
                            _where("firmware simulate"))
    argv = [str(image.simulator), str(image.elf)]
    if record is not None:
        argv += ["--record", str(record)]
    if watchdog_ms is not None:
        argv += ["--watchdog-ms", str(watchdog_ms)]
    if adc_mv is not None:
        argv += ["--adc", str(adc_mv)]
    if depth is not None:
        argv += ["--depth", f"{depth:g}"]
    if noise_mv is not None:
        argv += ["--noise", f"{noise_mv:g}"]
    return argv


class SimulatedBoard:
    """The harness running in the background: its pty path and its control channel.

    A context manager; ``stop()`` ends the harness.  ``set_adc`` and ``set_contact`` change
    the inputs, ``time_ms()`` is the simulated time, ``record()`` reads the pin record.
    """

    def __init__(self, image: Image, record: str | Path, watchdog_ms: int | None = None,
                 adc_mv: int | None = None, depth: float | None = None,
                 noise_mv: float | None = None) -> None:
        self.record_path = Path(record)
        argv = simulator_argv(image, record, watchdog_ms, adc_mv, depth, noise_mv)
        self.process = subprocess.Popen(argv, stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                                        stderr=subprocess.PIPE)
        self.port = self._line(START_TIMEOUT)
        if not self.port.startswith("/dev/"):
            self.stop()
            raise FirmwareError(f"the simulator did not start: {self.port or self._errors()}",
                                _where("firmware simulate"))

    def _line(self, timeout: float) -> str:
        assert self.process.stdout is not None
        fd = self.process.stdout.fileno()
        deadline = time.monotonic() + timeout
        data = b""
        while not data.endswith(b"\n"):
            left = deadline - time.monotonic()
            if left <= 0 or not select.select([fd], [], [], left)[0]:
                return data.decode("ascii", "replace")
            chunk = os.read(fd, 1)
            if not chunk:
                break
            data += chunk
        return data.decode("ascii", "replace").strip()

    def _errors(self) -> str:
        if self.process.poll() is None or self.process.stderr is None:
            return "no pty path"
        return self.process.stderr.read().decode("utf-8", "replace").strip() or "no output"

    def _send(self, command: str) -> None:
        assert self.process.stdin is not None
        self.process.stdin.write(command.encode("ascii") + b"\n")
        self.process.stdin.flush()

    def set_adc(self, channel: int, millivolts: int) -> None:
        """Waveguide input ``channel`` now reads ``millivolts`` (0..5000)."""
        self._send(f"adc {channel} {millivolts}")

    def set_depth(self, leg: int, depth: float) -> None:
        """Leg ``leg`` dims its waveguide by the fraction ``depth`` when fully bent."""
        self._send(f"depth {leg} {depth:g}")

    def set_wear(self, leg: int, depths: list[float]) -> None:
        """Leg ``leg``'s next actuation cycles dim its waveguide by ``depths``, one per cycle
        (the last stays): a progressively damaged actuator, as in Figure 3.5."""
        self._send(f"wear {leg} " + " ".join(f"{d:g}" for d in depths))

    def set_contact(self, index: int, touching: bool) -> None:
        """Contact input ``index`` touches the ground (or not)."""
        self._send(f"contact {index} {int(touching)}")

    def time_ms(self) -> float:
        """The board's simulated time in milliseconds."""
        self._send("time")
        answer = self._line(5.0)
        if not answer.startswith("t_ms="):
            raise FirmwareError(f"the simulator did not tell its time: {answer!r}",
                                _where("firmware simulate"))
        return float(answer[len("t_ms="):])

    def record(self) -> list[tuple[float, str]]:
        """The valve pin changes so far: (simulated ms, valve string)."""
        return read_record(self.record_path)

    def stop(self) -> None:
        """End the harness (SIGTERM, then SIGKILL) and wait for it."""
        if self.process.poll() is None:
            self.process.terminate()
            try:
                self.process.wait(5)
            except subprocess.TimeoutExpired:
                self.process.kill()
                self.process.wait()
        for stream in (self.process.stdin, self.process.stdout, self.process.stderr):
            if stream is not None:
                stream.close()

    def __enter__(self) -> SimulatedBoard:
        return self

    def __exit__(self, kind: type[BaseException] | None, error: BaseException | None,
                 trace: TracebackType | None) -> None:
        self.stop()


def read_record(path: str | Path) -> list[tuple[float, str]]:
    """A pin record (JSON lines ``{"t_ms": ..., "valves": ...}``) as (ms, valves) pairs; a
    last line still being written is left out."""
    rows = []
    for line in Path(path).read_text(encoding="ascii").splitlines():
        try:
            entry = json.loads(line)
        except json.JSONDecodeError:
            continue
        rows.append((float(entry["t_ms"]), str(entry["valves"])))
    return rows


def vented_after(record: list[tuple[float, str]], t_ms: float) -> float | None:
    """How long after ``t_ms`` every valve was vented for good: 0 when they already were, None
    when a valve is still open at the end of the record."""
    if not record or "1" in record[-1][1]:
        return None
    opened = [i for i, (_, valves) in enumerate(record) if "1" in valves]
    if not opened:
        return 0.0
    return max(0.0, record[opened[-1] + 1][0] - t_ms)
