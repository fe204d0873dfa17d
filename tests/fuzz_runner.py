"""gaitc-run's line protocol under fuzzing: scripts of commands fed to a compiled controller.

:func:`build_program` compiles ``gaitc-run`` once per fixtures folder from the hazard
patrol's compact controller (:func:`gaitc.codegen.build.build`, ``--target c``);
:func:`exchange` feeds it a script (a mutant of one of :data:`SCRIPTS`) on standard input,
plain and with ``--names``, and judges each run: it exits 0 (no signal, no crash), answers
every line it read and ends within the limit.  The driver reads with ``fgets`` into a
:data:`LINE_BUFFER`-byte buffer, so a longer line is read, and answered, in pieces:
:func:`lines_read` counts the pieces.
"""

from __future__ import annotations

import json
import shutil
import signal
import subprocess
import time
from pathlib import Path

from fuzz_oracle import Verdict

LINE_BUFFER = 4096  # char line[4096] in gaitc/codegen/host/driver.c
# The hazard patrol's compact controller: inputs L1, L2, L3 (3 levels each) and hazard (2);
# fields region (4), gait (9), L1, L2, L3 (3 each) and hazard (2).
# The three valid scripts keep the assumptions on every step (a leg in use loses at most a
# level, the cache at nw restores every leg): gaitc-run refuses a step that breaks them.
SCRIPTS: tuple[tuple[str, bytes], ...] = (
    ("walk.txt", b"s 2 2 2 0\nx 2 2 2 0\nx 2 1 2 1\nx 2 2 2 0\nx 2 2 2 1\nx 2 2 2 0\n"
                 b"x 2 2 2 1\nx 2 2 2 0\nd\n"),
    ("accepts.txt", b"a 0 8 2 2 2 0\na 3 0 0 0 0 1\na 1 4 1 2 0 0\nx 2 2 2 0\n"
                    b"a 2 8 2 2 2 0\nx 2 2 2 1\nd\n"),
    ("restart.txt", b"s 0 0 0 0\nx 2 2 2 1\ns 1 1 1 1\nx 2 2 2 0\nx 2 2 2 1\r\n"
                    b"x  2  2  2  1  \n"),
    ("junk.txt", b"x 0 0 0 0\n\ns\nq\ns 9 9 9 9\na -1 0 0 0 0 0\ns 0 0 0 0 0\n\r\nd extra\n"
                 b"s 1 1 1 1\r\nx 256 0 0 0\nx +1 1 1 1\nx 0x1 0 0 0\na 3 8 2 2 2\nx 1 1 1"),
    ("long.txt", b"s 2 2 2 0\nx " + b"0 " * 2500 + b"\nx 2 2 2 0\n" + b"a" * 5000
                 + b"\nx 1 1 1 1\nd\n"),
)
MODES: tuple[tuple[str, ...], ...] = ((), ("--names",))


def build_program(controller: Path, folder: Path) -> Path | None:
    """``gaitc-run`` for the compact ``controller``, built into ``folder``; None without gcc."""
    if shutil.which("gcc") is None:
        return None
    from gaitc.codegen.build import build
    from gaitc.compact.controller import compact_from_dict

    ctrl = compact_from_dict(json.loads(controller.read_text(encoding="utf-8")),
                             str(controller))
    program: Path | None = build(ctrl, folder, "c", str(controller)).program
    return program


def lines_read(data: bytes) -> int:
    """How many times ``fgets(line, LINE_BUFFER, stdin)`` returns a line of ``data``: at a
    newline, or after ``LINE_BUFFER - 1`` bytes, or at the end of the input."""
    count, start = 0, 0
    while start < len(data):
        end = data.find(b"\n", start, start + LINE_BUFFER - 1)
        start = start + LINE_BUFFER - 1 if end < 0 else end + 1
        count += 1
    return count


def _signal_name(code: int) -> str:
    try:
        return signal.Signals(-code).name
    except ValueError:
        return f"signal {-code}"


def exchange(data: bytes, limit: float, program: Path) -> list[Verdict]:
    """Run ``program`` on the script ``data`` in every mode of :data:`MODES` and judge it.

    A verdict's code is the exit status, except that a clean run which answered some line
    with ``error`` counts 1, so the table tells refused scripts from accepted ones."""
    verdicts = []
    expected = lines_read(data)
    for flags in MODES:
        command = " ".join(("gaitc-run", *flags))
        start = time.perf_counter()
        problems: list[str] = []
        try:
            done = subprocess.run([str(program), *flags], input=data, capture_output=True,
                                  timeout=limit, check=False)
        except subprocess.TimeoutExpired:
            seconds = time.perf_counter() - start
            problems.append(f"past limit: {seconds:.1f} s, the limit is {limit:g} s")
            verdicts.append(Verdict(command, -1, seconds, problems))
            continue
        seconds = time.perf_counter() - start
        code = done.returncode
        answers = done.stdout.split(b"\n")
        unfinished = answers.pop()  # what follows the last newline: nothing, when whole
        if code < 0:
            problems.append(f"internal: gaitc-run ended by {_signal_name(code)} after "
                            f"{len(answers)} answers to {expected} lines")
        elif code != 0:
            problems.append(f"internal: gaitc-run exit {code}: {done.stderr[:200]!r}")
        elif len(answers) != expected or unfinished:
            problems.append(f"internal: gaitc-run gave {len(answers)} answers"
                            f"{' and a cut one' if unfinished else ''} to {expected} lines")
        if done.stderr and code == 0:
            problems.append(f"internal: gaitc-run wrote to stderr: {done.stderr[:200]!r}")
        if seconds > limit:
            problems.append(f"past limit: {seconds:.1f} s, the limit is {limit:g} s")
        if code == 0 and any(a.startswith(b"error") for a in answers):
            code = 1
        verdicts.append(Verdict(command, code, seconds, problems))
    return verdicts
