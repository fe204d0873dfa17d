"""Run one fuzz case in-process and judge it against the three properties of issue 9.

(a) no internal error: exit 70, a traceback, or an exception escaping ``main`` other than
gaitc's own error family; (b) every ``file:line:col`` naming an input file points at a
line that exists, and the line echoed under it is that line as ``source_lines`` counts
(tabs shown as spaces, as the printer does); (c) the run ends within its limit.  Kinds that
write files add (d): nothing outside the fuzz folder changes (``escaped``, :mod:`fuzz_targets`).
"""

from __future__ import annotations

import contextlib
import io
import re
import time
from dataclasses import dataclass, field
from pathlib import Path

from gaitc.diagnostics import GaitcError, source_lines, without_bom

LOCATION = re.compile(r"(\d+):(\d+): ")
OUTCOMES = ("accepted", "user error", "other exit", "internal", "past limit", "wrong line",
            "escaped")


@dataclass
class Verdict:
    """What one run did: its exit code, time, and every broken property."""

    command: str
    code: int
    seconds: float
    problems: list[str] = field(default_factory=list)

    @property
    def outcome(self) -> str:
        """The worst of :data:`OUTCOMES` that applies."""
        for kind in ("internal", "escaped", "past limit", "wrong line"):
            if any(p.startswith(kind) for p in self.problems):
                return kind
        if self.code in (0, 3, 5):
            return "accepted"
        return "user error" if self.code == 1 else "other exit"


def _as_shown(line: str) -> str:
    """A source line as a message quotes it: a tab as a space, any other C0 or C1 control
    character (and DEL) as '?', so that no file sends escape sequences to the terminal."""
    return "".join(" " if c == "\t" else "?" if ord(c) < 0x20 or 0x7F <= ord(c) <= 0x9F
                   else c for c in line)


def location_problems(stderr: str, files: dict[str, bytes]) -> list[str]:
    """Property (b) for every message in ``stderr`` that names one of ``files``."""
    problems: list[str] = []
    out = stderr.split("\n")  # only \n: the echoed line may hold U+2028 (\x0c, \x85 show as ?)
    for number, message in enumerate(out):
        for name, data in files.items():
            if not message.startswith(f"{name}:"):
                continue
            m = LOCATION.match(message, len(name) + 1)
            if m is None:
                continue
            line, column = int(m.group(1)), int(m.group(2))
            lines = source_lines(without_bom(data.decode("utf-8", errors="replace")))
            if not 1 <= line <= max(len(lines), 1):
                problems.append(f"wrong line: {message[:120]!r} but the file has "
                                f"{len(lines)} lines")
                continue
            if not lines:
                continue
            expected = "    " + _as_shown(lines[line - 1])
            shown = out[number + 1] if number + 1 < len(out) else ""
            if shown != expected and not _excerpt_of(shown[4:], expected[4:], column):
                problems.append(f"wrong line: {message[:120]!r} shows {shown[:80]!r}, "
                                f"line {line} is {expected[:80]!r}")
            elif not 1 <= column <= len(lines[line - 1]) + 1:
                problems.append(f"wrong line: {message[:120]!r}: column {column} of a line "
                                f"of {len(lines[line - 1])} characters")
    return problems


def _excerpt_of(shown: str, full: str, column: int) -> bool:
    """Whether ``shown`` is a cut of the long line ``full`` (one screen line, "..." where it
    was cut) that holds the character at ``column``."""
    from gaitc.diagnostics import EXCERPT

    if len(full) <= EXCERPT or len(shown) > EXCERPT:
        return False
    # A line that itself starts with "..." shows them uncut: try the shown text both ways.
    heads = (True, False) if shown.startswith("...") else (False,)
    for head in heads:
        inner = shown[3 if head else 0:]
        if inner.endswith("...") and len(full) > EXCERPT:
            inner = inner[:-3]
        if not inner:
            continue
        start = 0 if not head else 1
        while (start := full.find(inner, start)) >= 0:  # a repetitive line may hold it twice
            if start < column <= start + len(inner) + 1:
                return True
            start += 1
    return False


def run_command(command: str, argv: list[str], files: dict[str, bytes],
                limit: float) -> Verdict:
    """Run ``gaitc argv`` in-process (output captured) and judge it."""
    from gaitc.cli import main

    err, out = io.StringIO(), io.StringIO()
    start = time.perf_counter()
    code = -1
    problems: list[str] = []
    try:
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            code = main(argv)
    except GaitcError as escaped:  # allowed by (a), though main should have printed it
        code = 1
        err.write(str(escaped))
    except Exception as escaped:  # property (a) broken
        problems.append(f"internal: {type(escaped).__name__} escaped main: {escaped}"[:300])
    seconds = time.perf_counter() - start
    text = err.getvalue()
    if code == 70 or "Traceback" in text or "internal error" in text:
        first = next((ln for ln in text.splitlines() if "internal" in ln), text[:200])
        problems.append(f"internal: exit {code}: {first[:300]}")
    if seconds > limit:
        problems.append(f"past limit: {seconds:.1f} s, the limit is {limit:g} s")
    problems.extend(location_problems(text, files))
    return Verdict(command, code, seconds, problems)


def write_mutant(folder: Path, suffix: str, data: bytes) -> Path:
    """The mutant as the file the commands read (one fixed name per kind and folder)."""
    path = folder / f"mutant{suffix}"
    path.write_bytes(data)
    return path
