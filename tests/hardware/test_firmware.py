"""The real valve-board firmware in simavr (issue 14): board-side safety and full drives.

The suite builds ``firmware/gaitboard.c`` with avr-gcc and runs the image in the harness
(``gaitboard-sim`` on libsimavr), whose pin record is the ground truth: every valve pin
change with its simulated time.  Checks: the board vents on its own within the watchdog
period when the host dies (SIGKILL) and at once on SIGTERM/SIGHUP (the host vents), when the
pty closes, on garbage, an oversized line and a malformed command, and after a hang (the
hardware watchdog); heartbeats hold a valve state; full ``gaitc drive --backend serial``
runs put exactly each gait's valve sequence on the pins and vent between steps.
Marked ``firmware``; skipped without gcc-avr, avr-libc or libsimavr-dev.
"""

from __future__ import annotations

import itertools
import json
import signal
import subprocess
import sys
import time
from collections.abc import Callable, Iterator
from pathlib import Path

import pytest
import serial

from gaitc.api.simulation import session
from gaitc.cli import main
from gaitc.hw.driver import bind_primitives
from gaitc.hw.firmware import Image, SimulatedBoard, build, missing_tools, vented_after
from gaitc.hw.sensing import FIGURE_3_5_DEPTHS
from gaitc.hw.serial_board import SerialValveBoard
from gaitc.sim.run import Step, read_jsonl

pytestmark = [
    pytest.mark.firmware,
    pytest.mark.skipif(bool(missing_tools()), reason="the AVR toolchain or libsimavr is missing "
                       "(apt-get install gcc-avr avr-libc simavr libsimavr-dev libsimavrparts1)"),
]

ROOT = Path(__file__).resolve().parents[2]
RADIAL8 = ROOT / "specs" / "radial8_patrol.gait"
TINY = (Path(__file__).resolve().parents[2] / "specs" / "shuttle_2leg.gait").read_text(
    encoding="utf-8")  # two legs, two valves: short runs on the simulated board
WATCHDOG_MS = 500  # the firmware's default
LOOP_MS = 10.0  # one firmware loop, a reply in progress included (115200 baud, ~90 bytes)
VENTED = "00000000"


# ---------------------------------------------------------------------------- fixtures
@pytest.fixture(scope="module")
def image(tmp_path_factory: pytest.TempPathFactory) -> Image:
    return build(tmp_path_factory.mktemp("firmware"))


@pytest.fixture()
def board(image: Image, tmp_path: Path) -> Iterator[SimulatedBoard]:
    with SimulatedBoard(image, tmp_path / "pins.jsonl") as sim:
        yield sim


@pytest.fixture(scope="module")
def tiny(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, Path]:
    folder = tmp_path_factory.mktemp("tiny")
    spec, controller = folder / "tiny.gait", folder / "tiny.json"
    spec.write_text(TINY, encoding="utf-8")
    assert main(["synth", str(spec), "-o", str(controller)]) == 0
    return spec, controller


def wait_until(ready: Callable[[], bool], seconds: float) -> None:
    end = time.monotonic() + seconds
    while not ready():
        assert time.monotonic() < end, "timed out"
        time.sleep(0.01)


def state_at(record: list[tuple[float, str]], t_ms: float) -> str:
    return [v for t, v in record if t <= t_ms][-1]


def port(board: SimulatedBoard) -> serial.Serial:
    link = serial.Serial(board.port, 115200, timeout=1.0)
    link.write(b"PING\n")
    assert link.readline().startswith(b"PONG gaitboard/2.0 proto=2 valves=8")
    return link


def ask(link: serial.Serial, line: bytes) -> bytes:
    link.write(line)
    answer: bytes = link.readline()
    return answer


def drive(spec: Path, controller: Path, board: SimulatedBoard, *extra: str
          ) -> subprocess.Popen[str]:
    argv = [sys.executable, "-m", "gaitc", "drive", str(spec), str(controller), "--backend",
            "serial", "--port", board.port, *extra]
    return subprocess.Popen(argv, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            cwd=ROOT)


def collapse(states: list[str]) -> list[str]:
    return [s for i, s in enumerate(states) if i == 0 or states[i - 1] != s]


def expected_pins(spec: Path, run_file: Path, pad: int) -> list[str]:
    """The board states a run must show: vented, each step's gait sequence then a vent."""
    loaded = session(str(spec), None)
    assert loaded is not None
    prims = bind_primitives(loaded.model, str(spec.parent))
    states = [VENTED]
    for step in read_jsonl(str(run_file)).steps:
        seq = prims[step.gait].states if step.gait in prims else ()
        states += [s + "0" * pad for s in seq] + [VENTED]
    return collapse(states)


# ---------------------------------------------------------------------------- the board
def test_build_writes_the_image_and_cli(tmp_path: Path, capsys: pytest.CaptureFixture[str]
                                        ) -> None:
    assert main(["firmware", "build", "-o", str(tmp_path), "--no-simulator"]) == 0
    printed = capsys.readouterr().out.split()
    assert printed == [str(tmp_path / "gaitboard.elf"), str(tmp_path / "gaitboard.hex")]
    assert (tmp_path / "gaitboard.hex").read_text(encoding="ascii").startswith(":")


def test_cli_simulate_prints_the_pty_first_and_records_the_pins(tmp_path: Path) -> None:
    record = tmp_path / "pins.jsonl"
    sim = subprocess.Popen([sys.executable, "-m", "gaitc", "firmware", "simulate", "--record",
                            str(record), "--watchdog-ms", "200"], stdout=subprocess.PIPE,
                           stdin=subprocess.PIPE, text=True, cwd=ROOT)
    try:
        assert sim.stdout is not None
        pty = sim.stdout.readline().strip()
        assert pty.startswith("/dev/pts/")
        link = serial.Serial(pty, 115200, timeout=1.0)
        assert b" wd=200 " in ask(link, b"PING\n")
        assert ask(link, b"V 01000000\n") == b"OK\r\n"
        time.sleep(0.4)  # silence: the board vents after 200 ms
        lines = record.read_text(encoding="ascii").splitlines()
        assert [json.loads(line)["valves"] for line in lines] == [VENTED, "01000000", VENTED]
    finally:
        sim.terminate()
        sim.wait(10)
    assert main(["firmware", "simulate", "--watchdog-ms", "20"]) == 2


def test_valve_command_sets_the_pins_and_errors_vent(board: SimulatedBoard) -> None:
    link = port(board)
    assert ask(link, b"V 10100001\n") == b"OK\r\n"
    time.sleep(0.1)  # the pressurised legs bend and dim their waveguides to 40 %
    answer = ask(link, b"S\n").decode("ascii").split()
    assert answer[0] == "S" and answer[3] == "c=0000"
    now = [int(v) for v in answer[1].removeprefix("a=").split(",")]
    assert [round(v / 818, 1) for v in now] == [0.4, 1, 0.4, 1, 1, 1, 1, 0.4]
    assert board.record()[-1][1] == "10100001"
    assert ask(link, b"V 1x100001\n").startswith(b"ERR V needs 8 valve bits; vented")
    assert board.record()[-1][1] == VENTED
    assert ask(link, b"V 01\n").startswith(b"ERR")
    assert ask(link, b"FLY\n") == b"ERR unknown command; vented\r\n"


@pytest.mark.parametrize(("junk", "answer"), [
    (b"\x00\xff\x1b[2J garbage\n", b"ERR malformed byte; vented\r\n"),
    (b"V " + b"1" * 200 + b"\n", b"ERR line too long; vented\r\n"),
])
def test_garbage_and_an_oversized_line_vent_at_once(board: SimulatedBoard, junk: bytes,
                                                    answer: bytes) -> None:
    link = port(board)
    assert ask(link, b"V 11111111\n") == b"OK\r\n"
    t0 = board.time_ms()
    assert ask(link, junk) == answer
    delay = vented_after(board.record(), t0)
    assert delay is not None and delay < 30  # the bytes' transfer time, then one loop


def test_silence_vents_within_the_watchdog_period_and_heartbeats_hold(
        board: SimulatedBoard) -> None:
    link = port(board)
    assert ask(link, b"V 00011000\n") == b"OK\r\n"
    for _ in range(12):  # 1.2 s of heartbeats: more than twice the watchdog period
        time.sleep(0.1)
        assert ask(link, b"HB\n") == b"OK\r\n"
    t0 = board.time_ms()
    assert state_at(board.record(), t0) == "00011000"
    time.sleep(0.7)
    delay = vented_after(board.record(), t0)
    assert delay is not None and delay <= WATCHDOG_MS + LOOP_MS


def test_watchdog_period_is_configurable(image: Image, tmp_path: Path) -> None:
    with SimulatedBoard(image, tmp_path / "pins.jsonl", watchdog_ms=150) as sim:
        link = serial.Serial(sim.port, 115200, timeout=1.0)
        assert b" wd=150 " in ask(link, b"PING\n")
        assert ask(link, b"W 40\n").startswith(b"ERR W needs a period")
        assert ask(link, b"W 250\n") == b"OK wd=250\r\n"
        assert ask(link, b"V 10000000\n") == b"OK\r\n"
        time.sleep(0.5)
        record = sim.record()
        assert record[-1][1] == VENTED
        assert 250 - LOOP_MS <= record[-1][0] - record[-2][0] <= 250 + LOOP_MS


def test_a_hung_firmware_is_reset_by_the_hardware_watchdog(board: SimulatedBoard) -> None:
    link = port(board)
    assert ask(link, b"V 11110000\n") == b"OK\r\n"
    t0 = board.time_ms()
    link.write(b"HANG\n")
    time.sleep(0.5)
    delay = vented_after(board.record(), t0)
    assert delay is not None and delay <= 250 + 20  # WDTO_250MS, then the reset vents
    assert b" reset=watchdog" in ask(link, b"PING\n")


def test_closing_the_pty_vents_within_the_watchdog_period(board: SimulatedBoard) -> None:
    link = port(board)
    assert ask(link, b"V 00000011\n") == b"OK\r\n"
    link.close()
    t0 = board.time_ms()
    time.sleep(0.7)
    delay = vented_after(board.record(), t0)
    assert delay is not None and delay <= WATCHDOG_MS + LOOP_MS


# ---------------------------------------------------------------------------- full drives
def test_drive_puts_each_gaits_sequence_on_the_pins(board: SimulatedBoard,
                                                     tiny: tuple[Path, Path],
                                                     tmp_path: Path) -> None:
    spec, controller = tiny
    out = tmp_path / "run.jsonl"
    host = drive(spec, controller, board, "--channels", "0,1", "--steps", "6",
                 "--step-delay", "0.6", "--out", str(out))
    stdout, stderr = host.communicate(timeout=120)
    assert host.returncode == 0, stderr
    assert "guarantees:      held at every step" in stdout
    record = board.record()
    assert collapse([v for _, v in record]) == expected_pins(spec, out, 6)
    for (t, valves), (t_next, _) in itertools.pairwise(record):
        if "1" in valves:  # held through the 0.6 s step delay by heartbeats, not longer
            assert 600 - LOOP_MS <= t_next - t <= 600 + 400


def _kill_during_a_step(spec: Path, controller: Path, board: SimulatedBoard, sig: int
                        ) -> tuple[float, subprocess.Popen[str]]:
    host = drive(spec, controller, board, "--channels", "0,1", "--steps", "50",
                 "--step-delay", "2")
    wait_until(lambda: any("1" in v for _, v in board.record()), 60)
    time.sleep(0.8)  # past the watchdog period: the host's heartbeats keep the valve open
    t0 = board.time_ms()
    assert "1" in state_at(board.record(), t0)
    host.send_signal(sig)
    return t0, host


@pytest.mark.parametrize("sig", [signal.SIGKILL, signal.SIGTERM, signal.SIGHUP],
                         ids=["SIGKILL", "SIGTERM", "SIGHUP"])
def test_host_death_vents_within_the_watchdog_period(board: SimulatedBoard,
                                                     tiny: tuple[Path, Path], sig: int) -> None:
    t0, host = _kill_during_a_step(*tiny, board, sig)
    stdout, _ = host.communicate(timeout=30)
    time.sleep(0.7)
    delay = vented_after(board.record(), t0)
    assert delay is not None and delay <= WATCHDOG_MS + LOOP_MS
    if sig != signal.SIGKILL:  # the host vents itself, as on Ctrl-C, and says so
        name = signal.Signals(sig).name
        assert host.returncode == 0 and delay < WATCHDOG_MS / 2
        assert f"interrupted ({name}); all valves vented" in stdout


def test_a_lost_link_says_the_watchdog_vents(board: SimulatedBoard,
                                            tiny: tuple[Path, Path]) -> None:
    spec, controller = tiny
    host = drive(spec, controller, board, "--channels", "0,1", "--steps", "50",
                 "--step-delay", "2")
    wait_until(lambda: any("1" in v for _, v in board.record()), 60)
    board.stop()  # the board (and its pty) is gone
    _, stderr = host.communicate(timeout=30)
    assert host.returncode == 1
    assert "link lost; the board's watchdog vents within 500 ms" in stderr
    assert "all valves vented" not in stderr


def test_waveguide_wear_degrades_the_level_as_in_figure_3_5(board: SimulatedBoard) -> None:
    board.set_wear(0, list(FIGURE_3_5_DEPTHS))  # leg L1's actuator, damaged cycle by cycle
    legs = [f"L{i}" for i in range(1, 9)]
    levels = []
    with SerialValveBoard(board.port, 8, legs, levels=dict.fromkeys(legs, 3)) as hw:
        hw.read_sensors()
        for _ in FIGURE_3_5_DEPTHS:
            hw.apply("10000000")
            hw.wait(0.08)
            hw.vent()
            hw.wait(0.08)  # the actuator relaxes
            hw.step_context(("L1",), in_cache=False)
            levels.append(dict(hw.read_sensors().health)["L1"])
    assert levels == [3, 3, 3, 3, 3, 2, 2, 2, 1]  # cycles 1-5 healthy, 6-8 degraded, 9 failed


def expected_levels(steps: list[Step], caches: tuple[str, ...], gait_legs: dict[str, tuple[
        str, ...]], worn_from: int) -> list[dict[str, int]]:
    """Each step's levels when every actuator bends fully for its first ``worn_from - 1``
    cycles and to the degraded depth from then on: a leg the step's gait used is graded
    (degraded once worn), the others keep theirs, and a cache resets every leg."""
    level = dict(steps[0].health)
    uses = dict.fromkeys(level, 0)
    out = [dict(level)]
    for before in steps[:-1]:
        used = gait_legs.get(before.gait, ())
        for leg in used:
            uses[leg] += 1
        if before.region in caches:
            level = dict.fromkeys(level, 3)
        else:
            level.update({leg: 2 for leg in used if uses[leg] >= worn_from})
        out.append(dict(level))
    return out


def test_radial8_patrol_on_the_simulated_firmware(board: SimulatedBoard,
                                                  tmp_path: Path) -> None:
    """The full patrol on the real firmware: every actuator wears to the degraded depth on
    its third cycle; the levels sensed from the waveguides follow, the controller takes
    them, and the pins show each gait's valve sequence step by step."""
    for leg in range(8):
        board.set_wear(leg, [0.6, 0.6, 0.33])
    controller, out = tmp_path / "radial8.json", tmp_path / "run.jsonl"
    assert main(["synth", str(RADIAL8), "-o", str(controller)]) == 0
    host = drive(RADIAL8, controller, board, "--steps", "12", "--step-delay", "0.05",
                 "--out", str(out))
    stdout, stderr = host.communicate(timeout=180)
    assert host.returncode == 0, stderr
    assert "assumptions:     held at every step" in stdout
    pins = collapse([v for _, v in board.record()])
    assert pins == expected_pins(RADIAL8, out, 0)
    assert sum("1" in v for v in pins) >= 12  # two valve states per moving gait
    loaded = session(str(RADIAL8), None)
    assert loaded is not None
    steps = read_jsonl(str(out)).steps
    legs = {g.name: g.legs for g in loaded.model.gaits}
    sensed = [dict(step.health) for step in steps]
    assert sensed == expected_levels(steps, tuple(loaded.model.caches), legs, 3)
    assert any(2 in levels.values() for levels in sensed)  # some actuator did wear
