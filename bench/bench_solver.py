"""Benchmark of ``gaitc check`` on the thesis task at growing grids and health levels.

Generates .gait texts (four legs, one gait per compass direction, a cache, two goal
corners), lowers them in both encodings, times the embedded solver end to end (lowering
included) and, when $SLUGS is set, SLUGS on the same slugsin; prints a table.
Run: .venv/bin/python bench/bench_solver.py [--quick] [--ablation]
"""

from __future__ import annotations

import argparse
import os
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from gaitc.loading import load_spec
from slugs_bridge import synthesis
from slugs_bridge.diagnostics import SolverError
from slugs_bridge.symbolic import Options

SIZES = [(4, 5), (6, 6), (10, 10), (15, 15), (20, 20), (30, 30)]
HEALTH = [2, 3, 4, 5]


def gait_text(rows: int, cols: int, health: int) -> str:
    """A thesis-style task: reach two far corners forever, the cache mid-way along the top."""
    return "\n".join(
        [
            f'robot "bench {rows}x{cols} h{health}"',
            f"legs L1..L4 health {health}",
            "gait north uses L1 moves north",
            "gait south uses L2 moves south",
            "gait east uses L3 moves east",
            "gait west uses L4 moves west",
            f"grid {rows} x {cols}",
            f"cache ({0}, {cols // 2})",
            "start (0, 0)",
            f"visit ({rows - 1}, {cols - 1}), ({rows - 1}, 0) infinitely often",
            "",
        ]
    )


def time_embedded(path: str, encoding: str, options: Options, timeout: float) -> tuple[str, float]:
    started = time.monotonic()
    try:
        spec = load_spec(path, encoding).spec
        result = synthesis.check(spec, timeout=timeout, options=options)
    except SolverError:
        return "timeout", time.monotonic() - started
    verdict = "realizable" if result.realizable else "unrealizable"
    return verdict, time.monotonic() - started


def time_slugs(path: str, encoding: str, timeout: float) -> str:
    if not os.environ.get("SLUGS"):
        return "-"
    from gaitc.commands.solving import _slugsin
    from slugs_bridge.runner import run_slugs_check

    try:
        res = run_slugs_check(_slugsin(load_spec(path, encoding).spec), timeout=timeout)
    except SolverError:
        return "timeout"
    return f"{res.seconds:.2f}"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--quick", action="store_true", help="small grids only")
    parser.add_argument("--ablation", action="store_true", help="compare solver options")
    parser.add_argument("--timeout", type=float, default=120.0)
    args = parser.parse_args()
    sizes = SIZES[:3] if args.quick else SIZES
    health = HEALTH[:2] if args.quick else HEALTH
    variants = {"default": Options()}
    if args.ablation:
        variants.update(
            {
                "no-recycle": Options(recycle=False),
                "clustered": Options(partitioned=True),
                "decl-order": Options(order="declaration"),
                "reorder": Options(reordering=True),
            }
        )
    header = f"{'grid':>7} {'H':>2} {'enc':>6} {'variant':>11} {'verdict':>12} {'s':>8}"
    print(header + f" {'slugs s':>8} {'ratio':>6}")
    with tempfile.TemporaryDirectory() as tmp:
        for rows, cols in sizes:
            for h in health:
                path = str(Path(tmp, f"g{rows}x{cols}h{h}.gait"))
                Path(path).write_text(gait_text(rows, cols, h), encoding="utf-8")
                for enc in ("onehot", "binary"):
                    for name, options in variants.items():
                        verdict, secs = time_embedded(path, enc, options, args.timeout)
                        slugs = time_slugs(path, enc, args.timeout) if name == "default" else "-"
                        ratio = f"{float(slugs) / secs:.1f}" if slugs[:1].isdigit() else "-"
                        print(
                            f"{rows:>3}x{cols:<3} {h:>2} {enc:>6} {name:>11} {verdict:>12} "
                            f"{secs:>8.2f} {slugs:>8} {ratio:>6}",
                            flush=True,
                        )


if __name__ == "__main__":
    main()
