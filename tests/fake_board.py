"""A fake valve board for the tests: a thread on a local TCP port (``socket://`` URL) that
speaks the gaitc line protocol v2, or misbehaves on purpose (garbage, refusals, silence, a
dropped link, a trickle of bytes, a flood), and records every command it receives.
"""

from __future__ import annotations

import contextlib
import socket
import threading
from collections.abc import Iterator
from pathlib import Path

TINY = (Path(__file__).resolve().parent.parent / "specs" / "shuttle_2leg.gait").read_text(
    encoding="utf-8")  # two legs, two valves: short runs on the simulated board


class FakeBoard:
    """A valve board on a local TCP port speaking the gaitc line protocol."""

    def __init__(self, valves: int = 8, mode: str = "ok", silent_after: int = 10**6,
                 health: str = "2,2", region: str = "-", proto: str = " proto=2") -> None:
        self.valves = valves
        self.proto = proto
        self.mode = mode
        self.silent_after = silent_after
        self.health = health
        self.region = region
        self.received: list[str] = []
        self.server = socket.create_server(("127.0.0.1", 0))
        self.url = f"socket://127.0.0.1:{self.server.getsockname()[1]}"
        self.thread = threading.Thread(target=self._serve, daemon=True)
        self.thread.start()

    def reply(self, line: str) -> str | None:
        if len(self.received) > self.silent_after:
            return None
        if line == "PING":
            return f"PONG fake-1.0{self.proto} valves={self.valves}"
        if self.mode == "garbage":
            return "#@!~ 0x7f"
        if line == "HB":
            return "OK"
        if line.startswith("V "):
            if self.mode == "refuse":
                return "ERR pressure rail empty"
            return "OK" if len(line) == 2 + self.valves else "ERR bad length"
        if line == "S":
            return f"S h={self.health} hazard=- region={self.region}"
        return "ERR unknown command"

    def _serve(self) -> None:
        conn, _ = self.server.accept()
        conn.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
        # the host may hang up while a reply is on its way (a lost link, a test's close)
        with contextlib.suppress(OSError), conn, conn.makefile("rwb") as stream:
            for raw in stream:
                line = raw.decode("ascii").strip()
                self.received.append(line)
                if self.mode == "drop" and len(self.received) > self.silent_after:
                    return  # the link drops: the connection closes
                if self.mode in ("trickle", "flood") and line.startswith("V "):
                    self._babble(conn)
                    continue
                answer = self.reply(line)
                if answer is not None:
                    stream.write(answer.encode("ascii") + b"\n")
                    stream.flush()

    def _babble(self, conn: socket.socket) -> None:
        with contextlib.suppress(OSError):  # the host may hang up first
            if self.mode == "flood":  # 2 MB without an end of line
                conn.sendall(b"x" * 2_000_000)
                return
            for _ in range(4):  # one byte every 0.3 s, never a line
                conn.sendall(b"O")
                threading.Event().wait(0.3)

    def commands(self, prefix: str) -> list[str]:
        return [c for c in self.received if c.startswith(prefix)]

    def close(self) -> None:
        self.server.close()


def tracked_boards() -> Iterator[type[FakeBoard]]:
    """For a fixture: a FakeBoard class whose boards are all closed afterwards."""
    boards: list[FakeBoard] = []

    class Tracked(FakeBoard):
        def __init__(self, *args: object, **kwargs: object) -> None:
            super().__init__(*args, **kwargs)  # type: ignore[arg-type]
            boards.append(self)

    yield Tracked
    for board in boards:
        board.close()


def wait_for(board: FakeBoard, count: int) -> None:
    """Let the board thread record ``count`` commands (the last vent has no reply read)."""
    for _ in range(200):
        if len(board.received) >= count:
            return
        threading.Event().wait(0.01)
