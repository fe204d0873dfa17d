"""How long a whole ``gaitc check`` process takes on small specs (issue 50): start-up counts.

Each row is one command run as a fresh process, ``--runs`` times (default 10); the table
gives the fastest and the median wall-clock time, imports included, twice: with Python's
bytecode cache (``cached``: as an installed gaitc runs, its ``.pyc`` files written once, here
into a temporary ``PYTHONPYCACHEPREFIX``) and without it (``source``: every module compiled
again at each start, as under ``PYTHONDONTWRITEBYTECODE=1``).  The first rows are the floor:
a bare interpreter, ``dd.cudd`` as dd imports itself (with networkx) and as gaitc imports it
(:mod:`gaitc.ir.cuddlib`, networkx left out).  The others are ``gaitc check`` on specs of a
few variables: the random GR(1) corpus, SLUGS's examples and a small ``.gait`` (which loads
the lark grammar).  Take the minimum on a busy machine, or time the processor instead
(``--cpu``: user and system seconds of the child, which other jobs disturb less).
Run: .venv/bin/python bench/bench_startup.py [--runs N] [--cpu] [--importtime]
"""

from __future__ import annotations

import argparse
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from collections.abc import Mapping
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
PYTHON = sys.executable

#: The small specs, relative to the repository.
SPECS = (
    "tests/data/gr1_corpus/rand3_0000.slugsin",
    "tests/data/gr1_corpus/rand3_0001.slugsin",
    "tests/data/gr1_corpus/rand3_0002.structuredslugs",
    "tests/data/slugs_examples/simple_safety_example.slugsin",
    "tests/data/slugs_examples/unrealizable1.slugsin",
    "tests/data/slugs_examples/water_reservoir.structuredslugs",
    "specs/patrol_2x2.gait",
)

#: The floor every run pays: (label, code for ``python -c``).
FLOOR = (
    ("python -c pass", "pass"),
    ("import dd.cudd", "import dd.cudd"),
    ("import dd.cudd (no networkx)", "import gaitc.ir.cuddlib"),
)

#: What ``gaitc check`` exits with when it has decided (realizable, unrealizable).
DECIDED = (0, 3)


def environments(cache: str) -> dict[str, dict[str, str]]:
    """The two ways a start is timed: with the bytecode cache in ``cache``, and without."""
    cached = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}
    cached["PYTHONPYCACHEPREFIX"] = cache
    return {"cached": cached, "source": {**os.environ, "PYTHONDONTWRITEBYTECODE": "1"}}


def _cpu_of_children() -> float:
    """User and system seconds of this process's children that have ended."""
    used = resource.getrusage(resource.RUSAGE_CHILDREN)
    return used.ru_utime + used.ru_stime


def timed(command: list[str], runs: int, env: Mapping[str, str],
          cpu: bool = False) -> tuple[float, float]:
    """The fastest and the median seconds of ``runs`` runs of ``command``, wall-clock or,
    with ``cpu``, the processor's (after one run that is not counted, which fills the
    bytecode cache when there is one)."""
    clock = _cpu_of_children if cpu else time.perf_counter
    seconds = []
    for k in range(runs + 1):
        began = clock()
        done = subprocess.run(command, cwd=ROOT, stdout=subprocess.DEVNULL,
                              stderr=subprocess.PIPE, env=env, check=False)
        if k:
            seconds.append(clock() - began)
        if done.returncode not in DECIDED:
            raise SystemExit(f"{' '.join(command)} exited {done.returncode}:\n"
                             f"{done.stderr.decode(errors='replace')}")
    return min(seconds), statistics.median(seconds)


def heaviest_imports(spec: str, count: int = 15) -> list[tuple[int, str]]:
    """The ``count`` imports of ``gaitc check spec`` that take longest, cumulative
    microseconds first (``python -X importtime``)."""
    done = subprocess.run([PYTHON, "-X", "importtime", "-m", "gaitc", "check", spec],
                          cwd=ROOT, capture_output=True, text=True, check=False)
    rows = []
    for line in done.stderr.splitlines():
        parts = line.split("|")
        if len(parts) == 3 and parts[1].strip().isdigit():
            rows.append((int(parts[1]), parts[2].rstrip()))
    return sorted(rows, reverse=True)[:count]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=10, help="runs of each command")
    parser.add_argument("--cpu", action="store_true",
                        help="processor seconds (user + system) instead of wall-clock ones")
    parser.add_argument("--importtime", action="store_true",
                        help="also list the heaviest imports of the first spec")
    args = parser.parse_args()
    rows = [(label, [PYTHON, "-c", code]) for label, code in FLOOR]
    rows += [(f"check {Path(spec).name}", [PYTHON, "-m", "gaitc", "check", spec])
             for spec in SPECS if (ROOT / spec).exists()]
    width = max(len(label) for label, _ in rows)
    with tempfile.TemporaryDirectory() as cache:
        envs = environments(cache)
        head = "".join(f" {name + ' min':>11} {name + ' median':>14}" for name in envs)
        print("processor seconds (user + system)" if args.cpu else "wall-clock seconds")
        print(f"{'command':<{width}}{head}")
        for label, command in rows:
            cells = ""
            for env in envs.values():
                fastest, median = timed(command, args.runs, env, args.cpu)
                cells += f" {fastest:11.3f} {median:14.3f}"
            print(f"{label:<{width}}{cells}", flush=True)
    if args.importtime:
        print(f"\nheaviest imports of check {SPECS[0]} (cumulative ms, under -X importtime):")
        for micros, name in heaviest_imports(SPECS[0]):
            print(f"{micros / 1000:8.1f}  {name}")


if __name__ == "__main__":
    main()
