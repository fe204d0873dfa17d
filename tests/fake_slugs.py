#!/usr/bin/env python3
"""A stand-in for the ``slugs`` binary that imitates its command-line contract for tests.

It checks options and file-name order the way SLUGS's ``src/main.cpp`` does, prints the banner
and a ``RESULT:`` line on stderr (exit code 0 for both verdicts), and answers only for the
specifications recorded in ``tests/data/slugs_recorded`` (matched section by section, so
the text gaitc emits for a recorded spec finds its recording).
``FAKE_SLUGS_BEHAVIOUR`` selects a failure: ``sleep``, ``no-result``, ``crash``,
``signal``, ``garbage``.
"""

from __future__ import annotations

import json
import os
import signal
import sys
import time
from pathlib import Path

RECORDED = Path(__file__).resolve().parent / "data" / "slugs_recorded"
KNOWN = {
    "--explicitStrategy", "--symbolicStrategy", "--jsonOutput", "--sysInitRoboticsSemantics",
    "--counterStrategy", "--simpleRecovery", "--fixedPointRecycling", "--biasForAction",
}
# sorted option string -> (task, semantics)
COMBINATIONS = {
    "": ("check", "default"),
    "--sysInitRoboticsSemantics": ("check", "robotics"),
    "--explicitStrategy": ("text", "default"),
    "--explicitStrategy --jsonOutput": ("synth", "default"),
    "--explicitStrategy --jsonOutput --sysInitRoboticsSemantics": ("synth", "robotics"),
    "--counterStrategy": ("counter", "default"),
    "--counterStrategy --sysInitRoboticsSemantics": ("counter", "robotics"),
}


def fail(message: str) -> int:
    print(f"Error: {message}", file=sys.stderr)
    return 1


def sections(text: str) -> dict[str, list[str]]:
    """Section name -> its formula lines: the same spec whatever the section order or spacing."""
    out: dict[str, list[str]] = {}
    current = ""
    for raw in text.splitlines():
        line = " ".join(raw.split())
        if line.startswith("["):
            current = line
            out.setdefault(current, [])
        elif line and not line.startswith("#"):
            out.setdefault(current, []).append(line)
    return {name: lines for name, lines in out.items() if lines}


def recording(text: str) -> str | None:
    for path in sorted(RECORDED.glob("*.slugsin")):
        if sections(path.read_text(encoding="utf-8")) == sections(text):
            return path.stem
    return None


def check_variables(text: str) -> str | None:
    """The first undeclared variable, as SLUGS reports it (only plain prefix lines)."""
    section, declared = "", set()
    for number, raw in enumerate(text.splitlines(), 1):
        line = raw.strip()
        if not line or line.startswith("#"):
            continue
        if line.startswith("["):
            section = line
            continue
        if section in ("[INPUT]", "[OUTPUT]"):
            declared.add(line)
            continue
        for token in line.split():
            name = token.rstrip("'")
            if token not in "!&|^10$?" and not token.isdigit() and name not in declared:
                return (f"Error reading line {number} from the input file. The variable "
                        f"{token} has not been found.")
    return None


def main(argv: list[str]) -> int:
    print("SLUGS: SmaLl bUt complete Gr(1) Synthesis tool (fake for gaitc tests).",
          file=sys.stderr)
    options = sorted({a for a in argv if a.startswith("-")})
    files = [a for a in argv if not a.startswith("-")]
    for option in options:
        if option not in KNOWN:
            return fail(f"Parameter '{option}' is unknown.")
    combination = COMBINATIONS.get(" ".join(options))
    if combination is None:
        return fail("the chosen option combination is not permissible.")
    task, semantics = combination
    limit = 1 if task == "check" else 2
    if len(files) > limit:
        return fail("You provided too many file names!")
    if not files:
        return fail("Cannot open input file")
    if task == "counter":  # the output file name comes first
        output, source = (files[0], files[1]) if len(files) == 2 else ("", files[0])
    else:
        source, output = files[0], (files[1] if len(files) == 2 else "")
    try:
        text = Path(source).read_text(encoding="utf-8")
    except OSError:
        return fail("Cannot open input file")
    behaviour = os.environ.get("FAKE_SLUGS_BEHAVIOUR", "")
    if behaviour == "sleep":
        time.sleep(60)
    if behaviour == "signal":
        os.kill(os.getpid(), signal.SIGKILL)
    if behaviour == "crash":
        print("Segmentation fault (core dumped)", file=sys.stderr)
        return 139
    problem = check_variables(text)
    if problem is not None:
        return fail(problem)
    name = recording(text)
    if name is None:
        return fail("the fake slugs has no recording for this specification")
    verdicts = json.loads((RECORDED / "index.json").read_text(encoding="utf-8"))[name]
    realizable = verdicts[semantics] == "realizable"
    if behaviour == "no-result":
        return 0
    verdict = "realizable" if realizable else "unrealizable"
    print(f"RESULT: Specification is {verdict}.", file=sys.stderr)
    answer: Path | None = None
    if task == "synth" and realizable:
        answer = RECORDED / f"{name}.{semantics}.json"
    elif task == "counter" and not realizable:
        answer = RECORDED / f"{name}.{semantics}.counter.txt"
    if answer is not None:
        body = "{not json" if behaviour == "garbage" else answer.read_text(encoding="utf-8")
        if output:
            Path(output).write_text(body, encoding="utf-8")
        else:
            sys.stdout.write(body)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
