"""Benchmark: symbolic against explicit controllers (issue 12), side by side.

Per spec, the symbolic controller is synthesized, verified symbolically and run for
``--steps`` random steps in this process; the explicit one is synthesized by ``gaitc
synth`` in a child process under a 1 GB memory limit and ``--explicit-timeout``, and its
nodes, file size and peak memory are read back.  The hazard grids are the family of
``bench/families/hazard_grid.py``, where the explicit controller grows with N^4 nodes of
N^2 successors each while the BDDs stay small.

Usage: python bench/bench_symbolic.py [--grids 6,10,20] [--steps N] [--explicit-timeout S]
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

import gaitc
from bench.families.hazard_grid import hazard_grid_text
from gaitc.ir.bddfile import SymbolicController, symbolic_to_json
from gaitc.sim.environments import RandomEnvironment
from gaitc.solver import synthesis
from gaitc.verifier.symbolic import verify_symbolic

ROOT = Path(__file__).resolve().parent.parent
MEMORY_MB = 1024
#: ``gaitc`` in a child that prints its peak memory (KB, with its solver child) last.
_MEASURED = ("import resource, sys\nfrom gaitc.cli import main\ncode = main(sys.argv[1:])\n"
             "peak = max(resource.getrusage(w).ru_maxrss for w in "
             "(resource.RUSAGE_SELF, resource.RUSAGE_CHILDREN))\n"
             "print(peak, file=sys.stderr)\nsys.exit(code)")


@dataclass
class Row:
    name: str
    path: Path
    encoding: str


def _symbolic(row: Row, steps: int) -> list[str]:
    spec = gaitc.load(row.path, row.encoding)
    started = time.perf_counter()
    ctrl = synthesis.synthesize_controller(spec.gr1, form="symbolic")
    synth = time.perf_counter() - started
    if not isinstance(ctrl, SymbolicController):
        return ["unrealizable"] + [""] * 5
    size = len(symbolic_to_json(ctrl).encode()) / 2**20
    started = time.perf_counter()
    report = verify_symbolic(spec.gr1, ctrl)
    verify = time.perf_counter() - started
    started = time.perf_counter()
    run = gaitc.simulate(spec, ctrl, env=RandomEnvironment(1), steps=steps)
    sim = time.perf_counter() - started
    held = run.error is None and run.summary is not None and run.summary.guarantees_held
    return [f"{synth:.1f}", f"{len(ctrl.nodes):,}", f"{size:.1f}",
            f"{verify:.1f}" + ("" if report.ok else " FAILED"),
            f"{sim:.1f}" + ("" if held else " BROKEN")]


def _explicit(row: Row, timeout: float) -> list[str]:
    out = Path(tempfile.mkdtemp()) / "explicit.json"
    command = [sys.executable, "-c", _MEASURED, "synth", str(row.path), "--encoding",
               row.encoding, "--no-verify", "--max-nodes", "1000000000", "--memory-limit",
               str(MEMORY_MB), "--timeout", str(timeout), "-o", str(out)]
    started = time.perf_counter()
    done = subprocess.run(command, capture_output=True, text=True, check=False)
    seconds = time.perf_counter() - started
    lines = done.stderr.strip().splitlines()
    peak = int(lines[-1]) / 1024 if lines and lines[-1].isdigit() else float("nan")
    if done.returncode != 0:
        reason = "out of memory" if "memory" in done.stderr else (
            "time limit" if "time limit" in done.stderr else f"exit {done.returncode}")
        return [f"> {seconds:.0f} ({reason})", "", "", f"{peak:.0f}"]
    nodes = len(json.loads(out.read_text(encoding="utf-8"))["nodes"])
    size = out.stat().st_size / 2**20
    return [f"{seconds:.1f}", f"{nodes:,}", f"{size:.1f}", f"{peak:.0f}"]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--grids", default="6,10,20", help="hazard-grid sides")
    parser.add_argument("--steps", type=int, default=10_000)
    parser.add_argument("--explicit-timeout", type=float, default=900.0)
    parser.add_argument("--no-explicit", action="store_true")
    args = parser.parse_args()
    rows = [Row("robot A", ROOT / "specs" / "thesis_robot_a.gait", "onehot"),
            Row("robot A", ROOT / "specs" / "thesis_robot_a.gait", "binary"),
            Row("radial8", ROOT / "specs" / "radial8_patrol.gait", "onehot")]
    folder = Path(tempfile.mkdtemp())
    for n in (int(x) for x in args.grids.split(",") if x):
        path = folder / f"hazard_grid_{n}.gait"
        path.write_text(hazard_grid_text(n, 2), encoding="utf-8")
        rows.append(Row(f"hazard grid {n}x{n}", path, "binary"))
    head = ["spec", "enc", "sym synth s", "BDD nodes", "sym MB", "sym verify s",
            f"{args.steps} steps s", "expl synth s", "expl nodes", "expl MB", "expl peak MB"]
    print("| " + " | ".join(head) + " |")
    print("|" + "---|" * len(head))
    for row in rows:
        cells = [row.name, row.encoding, *_symbolic(row, args.steps)]
        cells += ["not run"] * 4 if args.no_explicit else _explicit(row, args.explicit_timeout)
        print("| " + " | ".join(cells) + " |", flush=True)


if __name__ == "__main__":
    main()
