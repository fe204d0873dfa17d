"""Benchmark of ``gaitc check`` on thesis-style tasks at growing grids and health levels.

Each task scales thesis robot A (bench/families/thesis.py: eight legs, three gaits per
direction, caches on a lattice of corridors, hazards off them, goals in two far corners);
every task is realizable.
Times are CPU seconds (``time.process_time``, best of ``--repeat``), lowering included; the
table also shows the verdict and CUDD's peak of live nodes, and SLUGS's time when $SLUGS is
set.  ``--ablation`` compares solver options on a few tasks (docs/design-notes.md).
Run: .venv/bin/python bench/bench_solver.py [--quick] [--ablation] [--repeat N]
"""

from __future__ import annotations

import argparse
import os
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

import gaitc
from bench.families.thesis import HEALTH, SIZES, gait_text
from gaitc.diagnostics import SolverError
from gaitc.solver.symbolic import Options

ROOT = Path(__file__).resolve().parent.parent
ABLATION = {
    "default": Options(),
    "no-care": Options(care=False),
    "occurrence": Options(order="occurrence"),
    "declaration": Options(order="declaration"),
    "reorder-once": Options(reorder_once=True),
    "reorder-dyn": Options(reordering=True),
    "no-recycle": Options(recycle=False),
    "clustered": Options(partitioned=True),
}


@dataclass
class Row:
    verdict: str
    seconds: float
    peak: int


def time_embedded(path: str, encoding: str, options: Options, timeout: float, repeat: int) -> Row:
    best: Row | None = None
    for _ in range(repeat):
        started = time.process_time()
        try:
            result = gaitc.check(gaitc.load(path, encoding), timeout=timeout, options=options)
        except SolverError:
            return Row("timeout", time.process_time() - started, 0)
        verdict = "realizable" if result.realizable else "unrealizable"
        peak = result.stats.peak_nodes if result.stats is not None else 0
        row = Row(verdict, time.process_time() - started, peak)
        best = row if best is None or row.seconds < best.seconds else best
    assert best is not None
    return best


def time_slugs(path: str, encoding: str, timeout: float) -> str:
    if not os.environ.get("SLUGS"):
        return "-"
    try:
        verdict = gaitc.check(gaitc.load(path, encoding), solver="slugs", timeout=timeout)
    except SolverError:
        return "timeout"
    return f"{verdict.seconds:.2f}"


HEADER = (
    f"{'task':>16} {'H':>2} {'enc':>6} {'variant':>12} {'verdict':>12} {'cpu s':>8} "
    f"{'peak nodes':>10} {'slugs s':>8} {'ratio':>6}"
)


def print_row(task: str, h: str, enc: str, variant: str, row: Row, slugs: str) -> None:
    ratio = f"{float(slugs) / row.seconds:.1f}" if slugs[:1].isdigit() else "-"
    print(
        f"{task:>16} {h:>2} {enc:>6} {variant:>12} {row.verdict:>12} {row.seconds:>8.2f} "
        f"{row.peak:>10} {slugs:>8} {ratio:>6}",
        flush=True,
    )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--quick", action="store_true", help="grids up to 10x10, health 2-3")
    parser.add_argument("--ablation", action="store_true", help="compare solver options")
    parser.add_argument("--timeout", type=float, default=120.0)
    parser.add_argument("--repeat", type=int, default=1, help="best of N runs")
    parser.add_argument("--grid", action="append", help="only this grid, e.g. 30x30 (repeatable)")
    parser.add_argument("--health", type=int, action="append", help="only this health level")
    args = parser.parse_args()
    sizes = SIZES[:3] if args.quick else SIZES
    if args.grid:
        sizes = [(int(r), int(c)) for r, c in (g.lower().split("x") for g in args.grid)]
    health = args.health or (HEALTH[:2] if args.quick else HEALTH)
    gaitc.load(str(ROOT / "specs" / "thesis_robot_b.gait"))  # warm up: grammar, imports
    print(HEADER)
    for name in ("thesis_robot_a", "thesis_robot_b"):
        path = str(ROOT / "specs" / f"{name}.gait")
        for enc in ("onehot", "binary"):
            variants = ABLATION if args.ablation else {"default": Options()}
            for variant, options in variants.items():
                row = time_embedded(path, enc, options, args.timeout, args.repeat)
                slugs = time_slugs(path, enc, args.timeout) if variant == "default" else "-"
                print_row(name, "-", enc, variant, row, slugs)
    with tempfile.TemporaryDirectory() as tmp:
        for rows, cols in sizes:
            for h in health:
                path = str(Path(tmp, f"g{rows}x{cols}h{h}.gait"))
                Path(path).write_text(gait_text(rows, cols, h), encoding="utf-8")
                for enc in ("onehot", "binary"):
                    ablate = args.ablation and (rows, cols, h) in ((10, 10, 2), (6, 6, 3))
                    variants = ABLATION if ablate else {"default": Options()}
                    for variant, options in variants.items():
                        row = time_embedded(path, enc, options, args.timeout, args.repeat)
                        slugs = time_slugs(path, enc, args.timeout) if variant == "default" else "-"
                        print_row(f"{rows}x{cols}", str(h), enc, variant, row, slugs)


if __name__ == "__main__":
    main()
