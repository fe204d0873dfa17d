"""The terminal player under fuzzing: a mutant is a screen size and the keys a user presses.

:func:`keys_of` reads the bytes: the first two are the width (1-200) and height (1-60),
each further byte a key (:data:`NAMED` for the bytes above 127, the character itself for
printable ones, a control key below). :func:`drive` plays the keys in ``PlayApp`` on the
2 x 2 patrol under Textual's pilot, headless, then quits, and judges the run like
:mod:`fuzz_oracle` does: nothing escapes the app, it ends, the play is saved whole.
"""

from __future__ import annotations

import asyncio
import contextlib
import io
import os
import tempfile
import time
from collections.abc import Iterator, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from fuzz_mutate import Chooser, mutate
from fuzz_oracle import Verdict

ROOT = Path(__file__).resolve().parent.parent
SPEC = ROOT / "specs" / "patrol_2x2.gait"
OUT = "fuzz.run.jsonl"  # the --out of the play, in a folder of its own
MAX_KEYS = 200  # keys of one mutant, at most (the rest is not played)
KEY_WAIT = 10.0  # seconds the app may take to handle one key
IDLE_SLEEP = 0.001  # seconds of each sleep while the pilot waits for the app to be idle
MAX_DIGITS = 3  # a longer run of digit keys loses its further digits (see keys_of)
WIDTHS, HEIGHTS = 200, 60
#: The keys of the bytes 128-255 (each byte's key is NAMED[(byte - 128) % len(NAMED)]):
#: what the app binds that is not a character, Textual's own keys, and some it ignores.
NAMED: tuple[str, ...] = (
    "up", "down", "left", "right", "pageup", "pagedown", "home", "end", "enter", "escape",
    "tab", "shift+tab", "backspace", "delete", "insert", "space", "ctrl+q", "ctrl+c",
    "ctrl+p", "ctrl+home", "ctrl+end", "shift+up", "shift+down", "f1", "f10", "ctrl+left",
    "ctrl+right", "ctrl+a", "ctrl+e", "ctrl+k", "ctrl+u", "ctrl+w",
)
#: Control bytes with a key of their own; any other below 32 is ctrl and a letter.
CONTROL = {0x09: "tab", 0x0A: "enter", 0x0D: "enter", 0x1B: "escape", 0x08: "backspace",
           0x7F: "backspace", 0x00: "ctrl+space", 0x11: "ctrl+q", 0x03: "ctrl+c"}
#: Characters typed as another: a path typed at the save prompt stays a name in the play's
#: own folder (no separator, nothing a shell would expand).
TYPED_AS = {"/": "-", "\\": "_"}


def _character_key(character: str) -> str:
    from textual.keys import _character_to_key

    return _character_to_key(character)


def key_of(byte: int) -> str:
    """The key one byte (after the first two) stands for."""
    if byte >= 0x80:
        return NAMED[(byte - 0x80) % len(NAMED)]
    if byte in CONTROL:
        return CONTROL[byte]
    if byte < 0x20:
        return f"ctrl+{chr(0x60 + byte)}"
    return _character_key(TYPED_AS.get(chr(byte), chr(byte)))


def size_of(data: bytes) -> tuple[int, int]:
    """The screen (width, height) of a mutant: 80 x 24 when its bytes are missing."""
    width = 1 + data[0] % WIDTHS if len(data) > 0 else 80
    height = 1 + data[1] % HEIGHTS if len(data) > 1 else 24
    return width, height


def keys_of(data: bytes, most: int = MAX_KEYS) -> list[str]:
    """The keys of a mutant, at most ``most``. A digit after :data:`MAX_DIGITS`
    digits in a row is dropped: the pilots play as many steps as asked, a hundred
    thousand a second or so, and a number of ten digits would only measure that."""
    keys: list[str] = []
    digits = 0
    for byte in data[2:]:
        key = key_of(byte)
        digits = digits + 1 if key.isdigit() else 0
        if digits > MAX_DIGITS:
            continue
        keys.append(key)
        if len(keys) == most:
            break
    return keys


def bytes_of(width: int, height: int, keys: list[str]) -> bytes:
    """The bytes that :func:`size_of` and :func:`keys_of` read back as these (for seeds)."""
    table = {key_of(b): b for b in range(255, -1, -1)}  # the first byte of each key wins
    return bytes([width - 1, height - 1, *(table[key] for key in keys)])


def _typed(text: str) -> list[str]:
    return [_character_key(c) for c in text]


EXCHANGES: tuple[tuple[str, bytes], ...] = (
    ("standard.keys", bytes_of(80, 24, [
        "1", "down", "down", "enter", "2", "up", "1", "u", "u", "r", "question_mark",
        "escape", "a", *_typed("20"), "enter", "g", *_typed("3"), "enter", "n", "5", "enter",
        "u", "s", "enter", "1", "pagedown", "pageup", "home", "end", "enter", "q"])),
    ("tiny.keys", bytes_of(20, 3, [
        "1", "pageup", "pagedown", "home", "end", "up", "down", "pageup", "enter", "2",
        "question_mark", "escape", "u", "r", "g", "escape", "tab", "shift+tab", "ctrl+p",
        "pagedown", "pageup", "3", "q"])),
    ("one.keys", bytes_of(1, 1, [
        "1", "1", "pagedown", "enter", "a", "9", "enter", "question_mark", "u", "s",
        *_typed("x.csv"), "enter", "r", "ctrl+c", "q"])),
    ("wide.keys", bytes_of(200, 60, [
        "2", "n", *_typed("999"), "enter", "g", *_typed("-1"), "enter", "r", "r", "end",
        "enter", "g", *_typed("no"), "enter", "a", "escape", "q"])),
    ("prompts.keys", bytes_of(80, 24, [
        "1", "s", *_typed("my play.run.jsonl"), "enter", "1", "2", "s", *_typed("bad"),
        "enter", "s", *_typed(".."), "enter", "a", *_typed("0"), "enter", "n",
        "backspace", "enter", "g", *_typed("99"), "enter", "tab", "enter", "ctrl+q"])),
    ("help.keys", bytes_of(40, 12, [
        "question_mark", "question_mark", "1", "question_mark", "ctrl+p", "escape",
        "ctrl+c", "f1", "tab", "tab", "space", "enter", "delete", "insert", "left", "right",
        "shift+up", "ctrl+end", "u", "u", "u", "r", "q"])),
)

def mutate_play(seed: bytes, chooser: Chooser, donors: Sequence[bytes] = ()) -> bytes:
    """A mutant of a seed (:func:`fuzz_mutate.mutate`), on another screen one time in two
    (the byte mutations seldom reach the two bytes of the size)."""
    data = mutate(seed, chooser, donors)
    if chooser.randint(0, 1):
        data = bytes([chooser.randint(0, 255), chooser.randint(0, 255)]) + data[2:]
    return data


_SESSION: list[Any] = []  # the patrol's player session, built once a process


def _player() -> Any:
    """A new play of the 2 x 2 patrol (its controller is synthesized once)."""
    import gaitc
    from gaitc.play.player import Player

    if not _SESSION:
        _SESSION.append(gaitc.player(SPEC).session)
    return Player(_SESSION[0])


@dataclass
class PlayerRun:
    """One session: its verdict, the screen, the keys pressed and the play saved."""

    verdict: Verdict
    size: tuple[int, int]
    keys: list[str] = field(default_factory=list)  # the keys pressed, in order
    steps: int = 0  # the play's steps when the app ended
    saved: str | None = None
    output: str = ""  # what the app printed (Textual's traceback of an error)


@contextlib.contextmanager
def _quick_idle() -> Iterator[None]:
    """Textual's pilot waits for the app to be idle after each key, in sleeps of 20 ms,
    twice a key; sleeps of :data:`IDLE_SLEEP` make a key about five times cheaper (each
    key is still handled to the end before the next, as :meth:`Pilot.press` waits for
    the screen). Textual's own value is put back afterwards."""
    from textual import _wait

    granularity, idle = _wait.SLEEP_GRANULARITY, _wait.SLEEP_IDLE
    _wait.SLEEP_GRANULARITY, _wait.SLEEP_IDLE = IDLE_SLEEP, IDLE_SLEEP / 10
    try:
        yield
    finally:
        _wait.SLEEP_GRANULARITY, _wait.SLEEP_IDLE = granularity, idle


def _saved_nodes(path: Path) -> list[int]:
    """The controller node of each step of a saved play (read back as ``simulate --env
    scripted`` reads it; a CSV table, which cannot be read back, by its columns)."""
    import csv

    from gaitc.sim.run import read_jsonl

    if path.suffix.lower() == ".csv":
        return [int(row["node"]) for row in csv.DictReader(path.read_text().splitlines())]
    return [step.node for step in read_jsonl(path).steps]


def drive(data: bytes, limit: float = 30.0, most: int = MAX_KEYS) -> PlayerRun:
    """Play the keys of ``data`` (at most ``most``) on its screen, then escape, escape, q,
    q; judge the run."""
    from gaitc.diagnostics import GaitcError
    from gaitc.play.terminal import PlayApp, PlayCrash

    size, keys = size_of(data), keys_of(data, most)
    player = _player()
    problems: list[str] = []
    pressed: list[str] = []
    ended_by_keys = [False]
    here = os.getcwd()
    start = time.perf_counter()
    code = 0
    with tempfile.TemporaryDirectory() as folder:
        app = PlayApp(player, OUT)

        async def press(pilot: Any, key: str) -> None:
            """One key, handled to the end (:meth:`Pilot.press`); but once the key has
            made the app exit, the pilot stops waiting: it may wait on for the animator,
            which the ending app no longer runs, while the app's ending waits for the
            pilot (a race in Textual's pilot, seen with idle sleeps of a few ms on
            screens of 3 to 5 lines)."""
            pressed.append(key)
            task = asyncio.ensure_future(pilot.press(key))
            waited = time.perf_counter()
            while not task.done():
                await asyncio.wait({task}, timeout=0.05)
                if task.done():
                    break
                if app._exit or time.perf_counter() - waited > KEY_WAIT:
                    if not app._exit:
                        problems.append(f"past limit: the app did not handle {key!r} within "
                                        f"{KEY_WAIT:g} s")
                    task.cancel()
                    with contextlib.suppress(asyncio.CancelledError):
                        await task
                    return
            task.result()

        async def script(pilot: Any) -> None:
            for key in keys:
                if app._exit or problems or time.perf_counter() > start + limit:
                    break
                await press(pilot, key)
            for key in ("escape", "escape", "q", "q"):
                if app._exit:
                    break
                await press(pilot, key)
            ended_by_keys[0] = bool(app._exit)
            if not app._exit:
                app.exit(0)

        output = io.StringIO()
        os.chdir(folder)  # a name typed at the save prompt is a file here
        try:
            with contextlib.redirect_stdout(output), contextlib.redirect_stderr(output), \
                    _quick_idle():
                app.play(headless=True, size=size, auto_pilot=script)
        except PlayCrash as crash:
            code = 70
            problems.append(f"internal: PlayCrash: {crash}; {_last_line(output.getvalue())}")
        except Exception as err:  # anything else escaping the app
            code = 70
            problems.append(f"internal: {type(err).__name__} escaped the app: {err}"[:300])
        finally:
            os.chdir(here)
        seconds = time.perf_counter() - start
        steps = player.step + 1
        if not ended_by_keys[0] and code == 0:
            problems.append(f"internal: the app did not end on escape, escape, q, q "
                            f"(after {len(pressed)} keys)")
        saved = app.saved
        if steps and saved is None:
            problems.append(f"internal: a play of {steps} steps was not saved")
        elif saved is not None:
            path = Path(folder, saved)
            try:
                found = _saved_nodes(path)
            except (GaitcError, OSError, ValueError, KeyError) as err:
                problems.append(f"internal: the saved play {saved} cannot be read: {err}"[:300])
            else:
                if found != list(player.path):
                    problems.append(f"internal: the saved play {saved} has {len(found)} steps "
                                    f"{found[:8]}..., the play {steps} {list(player.path)[:8]}")
    if seconds > limit:
        problems.append(f"past limit: {seconds:.1f} s, the limit is {limit:g} s")
    return PlayerRun(Verdict("play", code, seconds, problems), size, pressed, steps, saved,
                     output.getvalue())


def _last_line(text: str) -> str:
    lines = [line.strip() for line in text.splitlines() if line.strip()]
    return lines[-1][:200] if lines else ""


def exchange(data: bytes, limit: float = 30.0) -> Verdict:
    """Play the keys of ``data`` in the terminal player: no exception escapes, the app
    ends, and the play is saved with every step made."""
    return drive(data, limit).verdict
