"""Tests of the serial valve board's host side (protocol v2, ``gaitc.hw.serial_board``) against
a fake board on a local socket: parsing, the handshake and channel checks, retries, bounded
reads, truthful vent messages, heartbeats, and ``gaitc drive --backend serial``.
"""

from __future__ import annotations

import time
from collections.abc import Iterator
from pathlib import Path

import pytest
from fake_board import FakeBoard, tracked_boards, wait_for

from gaitc.api.simulation import Session
from gaitc.cli import main
from gaitc.hw.backend import HardwareError, SensorReading, level_from_waveguide
from gaitc.hw.driver import Driver, bind_primitives
from gaitc.hw.sensing import HealthSensing
from gaitc.hw.serial_board import (
    BoardInfo,
    Garbled,
    SerialValveBoard,
    parse_pong,
    parse_sensors,
)


@pytest.fixture()
def board_factory() -> Iterator[type[FakeBoard]]:
    yield from tracked_boards()


# ---------------------------------------------------------------------------- protocol
def test_protocol_parsers() -> None:
    assert parse_pong("PONG gaitboard-2.1 valves=16") == BoardInfo("gaitboard-2.1", 1, 16)
    assert parse_pong("PONG gaitboard/2.0 proto=2 valves=8 legs=8 contacts=4 wd=500 "
                      "reset=power") == BoardInfo("gaitboard/2.0", 2, 8, 8, 4, 500, "power")
    legs = ("L1", "L2", "L3")
    sensing = HealthSensing(dict.fromkeys(legs, 3))  # default thresholds 0.4, 0.2

    def grade(now: dict[str, float], low: dict[str, float]) -> dict[str, int]:
        return sensing.update(now, low, legs, in_cache=False)

    reading = parse_sensors("S a=1000,1000,1000 lo=400,700,950 c=0000", legs, grade)
    assert reading == SensorReading((("L1", 3), ("L2", 2), ("L3", 1)), None, None)
    for bad in ("S a=1023,400", "S a=1023,400,2 lo=1,1", "S a=1,1,1 lo=1,1,1024",
                "S a=1,1,1 lo=1,1,1 c=2"):
        with pytest.raises(Garbled):  # raw values without a grader, or malformed
            parse_sensors(bad, legs, grade if "lo" in bad else None)
    reading = parse_sensors("S h=3,2 hazard=blue region=r12", ["L1", "L2"])
    assert reading == SensorReading((("L1", 3), ("L2", 2)), "blue", "r12")
    assert parse_sensors("S h=1,1 hazard=- region=-", ["L1", "L2"]).region is None
    for bad in ("S h=3 hazard=-", "S h=3,x", "X h=3,3", "S h=3,3 h=3,3", "S h=3,3 foo=1"):
        with pytest.raises(Garbled):
            parse_sensors(bad, ["L1", "L2"])
    for bad in ("PONG", "PONG v1 valves=0", "PING v1 valves=8", "PONG v1 count=8",
                "PONG v1 proto=2", "PONG v1 proto=x valves=8", "PONG v1 valves=8 valves=8"):
        with pytest.raises(Garbled):
            parse_pong(bad)


def test_level_from_waveguide() -> None:
    assert [level_from_waveguide(x, (0.8, 0.3)) for x in (1.0, 0.8, 0.5, 0.29, 0.0)] == \
        [3, 3, 2, 1, 1]


# ---------------------------------------------------------------------------- serial
def test_serial_handshake_valves_through_channel_map_and_sensors(
        board_factory: type[FakeBoard]) -> None:
    board = board_factory(valves=4, health="2,1", region="b")
    with SerialValveBoard(board.url, 2, ["L1", "L2"], timeout=1.0, channels=(3, 1)) as hw:
        assert isinstance(hw, SerialValveBoard)
        assert (hw.firmware, hw.board_valves) == ("fake-1.0", 4)
        hw.apply("10")
        hw.apply("01")
        assert hw.read_sensors() == SensorReading((("L1", 2), ("L2", 1)), None, "b")
    wait_for(board, 5)
    assert board.received[0] == "PING"
    assert board.commands("V") == ["V 0001", "V 0100", "V 0000"]


def test_serial_wrong_valve_count(board_factory: type[FakeBoard]) -> None:
    board = board_factory(valves=16)
    hw = SerialValveBoard(board.url, 8, ["L1"], timeout=1.0)
    with pytest.raises(HardwareError, match="the robot has 8 valves but the board"):
        hw.open()
    with pytest.raises(HardwareError, match="not open"):
        hw.apply("00000000")
    with pytest.raises(HardwareError, match=r"distinct channels in 0\.\.15"):
        SerialValveBoard(board_factory(valves=16).url, 2, ["L1"], channels=(0, 16)).open()


def test_serial_rejects_a_valve_state_of_the_wrong_length(board_factory: type[FakeBoard]) -> None:
    board = board_factory(valves=8)
    with SerialValveBoard(board.url, 8, ["L1"]) as hw, \
            pytest.raises(HardwareError, match="has 4 valves but the robot has 8"):
        hw.apply("1000")
    wait_for(board, 2)
    assert board.commands("V") == ["V 00000000"]  # only the vent on close reached it


def test_serial_garbled_answers_are_retried_then_fail_vented(
        board_factory: type[FakeBoard]) -> None:
    board = board_factory(valves=8, mode="garbage")
    hw = SerialValveBoard(board.url, 8, ["L1"], timeout=1.0, retries=2)
    hw.open()
    with pytest.raises(HardwareError,
                       match=r"garbled answer .* \(after 3 attempts\); the vent was not "
                       r"acknowledged; the board's watchdog vents within 500 ms"):
        hw.apply("10000000")
    hw.close()
    wait_for(board, 6)
    assert board.commands("V") == ["V 10000000"] * 3 + ["V 00000000"] * 2


def test_serial_board_that_stops_answering_times_out_vented(
        board_factory: type[FakeBoard]) -> None:
    board = board_factory(valves=8, silent_after=2)
    hw = SerialValveBoard(board.url, 8, ["L1"], timeout=0.2, retries=1)
    hw.open()
    hw.apply("01000000")
    with pytest.raises(HardwareError, match=r"no answer to 'V' within 0.2 s") as caught:
        hw.apply("00100000")
    assert caught.value.span is not None  # the silent board acknowledged no vent: say so
    assert caught.value.message.endswith("; link lost; the board's watchdog vents within "
                                         "500 ms")
    hw.close()
    wait_for(board, 5)
    assert board.commands("V")[-1] == "V 00000000"


def test_serial_board_error_reply_and_missing_port(board_factory: type[FakeBoard]) -> None:
    board = board_factory(valves=2, mode="refuse")
    with SerialValveBoard(board.url, 2, ["L1"]) as hw, \
            pytest.raises(HardwareError, match="refused 'V 10': pressure rail empty"):
        hw.apply("10")
    with pytest.raises(HardwareError, match="cannot open the valve board at /dev/nonexistent"):
        SerialValveBoard("/dev/nonexistent-gaitc", 2, ["L1"]).open()


def test_driver_on_a_serial_board(tiny: Session, tmp_path: Path,
                                  board_factory: type[FakeBoard]) -> None:
    board = board_factory(valves=2, health="2,2")
    prims = bind_primitives(tiny.model, str(tmp_path))
    hw = SerialValveBoard(board.url, 2, tiny.domain.legs, timeout=1.0)
    run = Driver(tiny.strategy, tiny.domain, tiny.monitor, prims, hw).run(4)
    assert run.error is None and len(run.steps) == 5
    expected = ["V 00"]
    for step in run.steps:
        gait = step.gait
        expected += ["V 00"] if gait == "noGait" else [f"V {v}" for v in prims[gait].states]
    wait_for(board, 1 + len(expected) + 1 + 5)
    assert board.commands("V") == [*expected, "V 00"]
    assert len(board.commands("S")) == 5


def test_driver_stops_when_localisation_disagrees(tiny: Session, tmp_path: Path,
                                                  board_factory: type[FakeBoard]) -> None:
    board = board_factory(valves=2, health="2,2", region="b")  # the robot starts in a
    hw = SerialValveBoard(board.url, 2, tiny.domain.legs, timeout=1.0)
    run = Driver(tiny.strategy, tiny.domain, tiny.monitor,
                 bind_primitives(tiny.model, str(tmp_path)), hw).run(3)
    assert isinstance(run.error, HardwareError)
    assert "localisation reports region b but the controller expects a" in run.error.message
    assert run.steps == []


@pytest.mark.parametrize("mode", ["trickle", "flood"])
def test_a_babbling_board_is_bounded_by_the_timeout(board_factory: type[FakeBoard],
                                                    mode: str) -> None:
    board = board_factory(valves=8, mode=mode)
    hw = SerialValveBoard(board.url, 8, ["L1"], timeout=0.3, retries=2)
    hw.open()
    start = time.monotonic()
    with pytest.raises(HardwareError, match=r"the vent was not acknowledged|link lost"):
        hw.apply("10000000")
    hw.close()
    assert time.monotonic() - start < 3 * 0.3 + 2 * 0.3 + 1.0  # 3 tries, 2 vents, slack


def test_a_dropped_link_says_only_the_watchdog_can_vent(board_factory: type[FakeBoard]
                                                        ) -> None:
    board = board_factory(valves=2, mode="drop", silent_after=2)
    hw = SerialValveBoard(board.url, 2, ["L1"], timeout=0.3)
    hw.open()
    hw.apply("10")
    with pytest.raises(HardwareError) as caught:
        hw.apply("01")
    assert caught.value.message.endswith("link lost; the board's watchdog vents within 500 ms")
    assert "all valves vented" not in caught.value.message
    hw.close()
    assert hw.safety_note() == "link lost; the board's watchdog vents within 500 ms"


def test_the_board_is_checked_before_any_valve_opens(board_factory: type[FakeBoard]) -> None:
    for kwargs, message in [({"valves": 999999}, "claims 999999 valves; protocol v2 drives "
                             "at most 32"), ({"proto": ""}, "speaks protocol v1; this gaitc "
                                             "speaks v2")]:
        board = board_factory(**kwargs)
        start = time.monotonic()
        with pytest.raises(HardwareError, match=message):
            SerialValveBoard(board.url, 2, ["L1"], channels=(0, 1)).open()
        assert time.monotonic() - start < 2
        wait_for(board, 1)
        assert board.commands("V") == []


def test_heartbeats_while_valves_are_open_only(tiny: Session, tmp_path: Path,
                                              board_factory: type[FakeBoard]) -> None:
    board = board_factory(valves=2, health="2,2")
    hw = SerialValveBoard(board.url, 2, tiny.domain.legs, timeout=1.0)
    run = Driver(tiny.strategy, tiny.domain, tiny.monitor,
                 bind_primitives(tiny.model, str(tmp_path)), hw, step_delay=0.3).run(2)
    assert run.error is None
    wait_for(board, len(board.received) + 1)
    state, beats = "", 0
    for command in board.received:
        if command.startswith("V "):
            state = command[2:]
        elif command == "HB":
            assert "1" in state  # a heartbeat only holds an open valve state
            beats += 1
    assert beats >= 2  # 0.3 s with a valve open: a heartbeat every 125 ms



def test_cli_drive_serial(tiny_spec: Path, board_factory: type[FakeBoard],
                          capsys: pytest.CaptureFixture[str]) -> None:
    board = board_factory(valves=2, health="2,2", region="-")
    code = main(["drive", str(tiny_spec), "--backend", "serial", "--port", board.url,
                 "--steps", "3", "--step-delay", "0"])
    out = capsys.readouterr().out
    assert code == 0
    assert "step 1: " in out and "summary: 3 steps" in out
    wait_for(board, 8)
    assert board.received[0] == "PING" and board.commands("V")[-1] == "V 00"


def test_firmware_build_says_which_packages_are_missing(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
        capsys: pytest.CaptureFixture[str]) -> None:
    import gaitc.hw.firmware

    monkeypatch.setattr(gaitc.hw.firmware.shutil, "which", lambda name: None)
    missing = gaitc.hw.firmware.missing_tools()
    assert missing[0] == "gcc-avr" and "gcc" in missing
    assert main(["firmware", "build", "-o", str(tmp_path)]) == 1
    err = capsys.readouterr().err
    assert "cannot build the firmware: missing gcc-avr" in err
    assert "apt-get install gcc-avr avr-libc simavr" in err



def test_a_pty_that_vanishes_during_a_flush_is_a_lost_link(board_factory: type[FakeBoard],
                                                            monkeypatch: pytest.MonkeyPatch
                                                            ) -> None:
    """A full test run under load (issue 38): the firmware board's pseudo-terminal went away
    while the host flushed a command, and termios.tcdrain's error, which is no OSError,
    escaped as an internal error (exit 70). It is the lost link it is."""
    import termios

    board = board_factory(valves=2)
    hw = SerialValveBoard(board.url, 2, ["L1"], timeout=0.3)
    hw.open()
    hw.apply("10")
    port = hw._port
    assert port is not None

    def vanished() -> None:
        raise termios.error(5, "Input/output error")

    monkeypatch.setattr(port, "flush", vanished)
    with pytest.raises(HardwareError) as caught:
        hw.apply("01")
    assert caught.value.message.startswith(f"lost the valve board at {board.url}: ")
    assert caught.value.message.endswith("link lost; the board's watchdog vents within 500 ms")
    hw.close()
