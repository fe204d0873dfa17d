"""The serial valve board's line protocol under fuzzing: a fake port plays back replies.

:class:`ReplayPort` answers each command written to it with the next line of a reply
stream (a mutant of one of :data:`EXCHANGES`); :func:`exchange` runs the handshake, a
sensor reading and a valve state on a :class:`SerialValveBoard` over it, and judges the
run like :mod:`fuzz_oracle` does: only gaitc's errors, within the time limit.
"""

from __future__ import annotations

import time

from fuzz_oracle import Verdict

from gaitc.diagnostics import GaitcError
from gaitc.hw.serial_board import SerialValveBoard, parse_pong

LEGS = tuple(f"L{i}" for i in range(1, 9))
EXCHANGES: tuple[tuple[str, bytes], ...] = (
    ("plain.txt", b"PONG gaitc-fw-1.2 proto=2 valves=8\nS h=3,3,2,1,3,3,2,1 hazard=- "
                  b"region=r12\nOK\nOK\n"),
    ("hazard.txt", b"PONG fw proto=2 valves=8\nS hazard=blue h=1,1,1,1,1,1,1,1 region=-\n"
                   b"OK\nOK\n"),
    ("retry.txt", b"PONX fw valves=8\nPONG fw proto=2 valves=8 wd=500\nS h=0,0,0,0,0,0,0,0\r\n"
                  b"ERR valve 3 stuck\nOK\n"),
    ("raw.txt", b"PONG gaitboard/2.0 proto=2 valves=8 legs=8 contacts=4 wd=500 reset=power\r\n"
                b"S a=1023,818,400,0,1,2,3,4 lo=1,1,1,1,1,1,1,1 c=0101\r\nOK\r\nOK\r\n"),
)


class ReplayPort:
    """Just enough of a pyserial port: each write queues the next reply line."""

    def __init__(self, stream: bytes) -> None:
        self.replies = stream.split(b"\n")
        self.buffer = b""
        self.written: list[bytes] = []

    def reset_input_buffer(self) -> None:
        self.buffer = b""

    @property
    def in_waiting(self) -> int:
        return len(self.buffer)

    def read(self, size: int = 1) -> bytes:
        data, self.buffer = self.buffer[:size], self.buffer[size:]
        return data

    def write(self, data: bytes) -> int:
        self.written.append(data)
        if self.replies:
            reply = self.replies.pop(0)
            self.buffer += reply + (b"\n" if self.replies else b"")
        return len(data)

    def flush(self) -> None:
        pass

    def close(self) -> None:
        pass


def board_over(port: ReplayPort) -> SerialValveBoard:
    """A board object talking to ``port`` (no pyserial URL is opened)."""
    board = SerialValveBoard("replay://fuzz", 8, LEGS, timeout=0.01, retries=2,
                             levels=dict.fromkeys(LEGS, 3))
    board._port = port  # the fake stands in for serial_for_url
    return board


def exchange(stream: bytes, limit: float = 2.0) -> Verdict:
    """Handshake, one sensor reading, one valve state: only gaitc errors may come out."""
    port = ReplayPort(stream)
    board = board_over(port)
    start = time.perf_counter()
    code, problems = 0, []
    try:
        info = board.info = board._ask("PING", parse_pong)
        board.firmware, board.board_valves = info.firmware, info.valves
        board.read_sensors()
        board.apply("10000001")
    except GaitcError:
        code = 1
    except Exception as err:  # property (a) broken
        problems.append(f"internal: {type(err).__name__}: {err}"[:300])
        code = 70
    seconds = time.perf_counter() - start
    if seconds > limit:
        problems.append(f"past limit: {seconds:.1f} s, the limit is {limit:g} s")
    return Verdict("board", code, seconds, problems)
