"""How late ``--timeout`` returns, per command (issue 38): whole processes, worst of N runs.

Every command that can run long takes ``--timeout``: ``check``, ``synth``, ``counter``,
``explain``, ``lint`` (the search behind a valve primitive) and ``resilience`` (this one
with two worker processes, ``--jobs 2``).  Each runs here on an input that takes far longer
than the limit: thesis robot A with 100 health levels a leg (realizable; for ``counter``
its unrealizable twin without caches, where legs that wear out are never restored), a
formula nested 100,001 deep (the parser's work counts too), and a robot file (a fuzz
mutant, tests/data/limits/slow_primitive_robot.yaml) whose primitive search takes 20 s.
The table gives the limit, the exit code, and the wall seconds past the
limit, median and worst of the runs; the promise is a second.
Run: .venv/bin/python bench/bench_timeouts.py [--quick] [--limit S] [--runs N]
"""

from __future__ import annotations

import argparse
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
GAITC = [sys.executable, "-m", "gaitc"]


def inputs(folder: Path) -> dict[str, Path]:
    """The long inputs, written into ``folder``."""
    robot = (ROOT / "specs" / "thesis_robot_a.gait").read_text(encoding="utf-8")
    long = folder / "robot_a_h100.gait"
    long.write_text(robot.replace("health 3", "health 100"), encoding="utf-8")
    lost = folder / "robot_a_h100_no_caches.gait"
    lost.write_text("".join(line for line in robot.replace("health 3", "health 100")
                            .splitlines(keepends=True) if not line.startswith("cache")),
                    encoding="utf-8")
    deep = folder / "deep.structuredslugs"
    depth = 100_001
    deep.write_text("[INPUT]\na\n[OUTPUT]\nb\n[SYS_TRANS]\n" + "(" * depth + "b"
                    + ")" * depth + "\n", encoding="utf-8")
    slow = folder / "slow_primitive.gait"
    robot = ROOT / "tests" / "data" / "limits" / "slow_primitive_robot.yaml"
    slow.write_text(f'legs L1..L8 health 2\ngait north_a uses L6, L8 moves north primitive '
                    f'"{robot}" direction +y\ngrid 2 x 1\nstart r0\n', encoding="utf-8")
    return {"long": long, "lost": lost, "deep": deep, "slow": slow}


def runs(files: dict[str, Path]) -> list[tuple[str, list[str]]]:
    return [
        ("check", ["check", str(files["long"])]),
        ("synth", ["synth", str(files["long"]), "-o", str(files["long"].with_suffix(".json"))]),
        ("counter", ["counter", str(files["lost"]), "-o",
                     str(files["lost"].with_suffix(".counter.json"))]),
        ("explain", ["explain", str(files["long"])]),
        ("resilience --jobs 2", ["resilience", "--jobs", "2", str(files["long"])]),
        ("check (nested 100,001)", ["check", str(files["deep"])]),
        ("lint (primitive search)", ["lint", str(files["slow"])]),
    ]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="one run per command")
    parser.add_argument("--limit", type=float, default=2.0, help="the --timeout given")
    parser.add_argument("--runs", type=int, default=5)
    args = parser.parse_args()
    count = 1 if args.quick else args.runs
    print(f"{'command':<24} {'limit s':>7} {'exit':>5} {'past, median':>13} {'worst':>7}")
    with tempfile.TemporaryDirectory() as folder:
        files = inputs(Path(folder))
        for name, words in runs(files):
            past, codes = [], set()
            for _ in range(count):
                began = time.perf_counter()
                done = subprocess.run([*GAITC, *words, "--timeout", f"{args.limit:g}"],
                                      capture_output=True, check=False)
                past.append(time.perf_counter() - began - args.limit)
                codes.add(done.returncode)
            print(f"{name:<24} {args.limit:7.1f} {'/'.join(map(str, sorted(codes))):>5} "
                  f"{statistics.median(past):13.2f} {max(past):7.2f}", flush=True)
    print("past: wall seconds of the whole process beyond the limit (negative: it ended "
          "before the limit, with an answer or an error of the input)")


if __name__ == "__main__":
    main()
