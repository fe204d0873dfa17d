"""Compile-time benchmark: parse + check + lower + emit slugsin for thesis-style grids.

Each grid is the thesis task scaled up (8 legs with 3 health levels, 12 directional gaits,
two caches, two hazard sets, two goals) from 4 x 5 to 40 x 40 cells, in both encodings.
Run: ``.venv/bin/python bench/bench_compile.py [--sizes 4x5,10x10] [--repeat 3]``.
"""

from __future__ import annotations

import argparse
import time
from collections.abc import Callable
from functools import partial
from typing import TypeVar

from gaitc.api.compiling import emit
from gaitc.ir.spec import SECTIONS
from ltlcompiler.frontend import model_from_text
from ltlcompiler.lowering import lower

SIZES = ((4, 5), (8, 8), (10, 10), (16, 16), (20, 20), (30, 30), (40, 40))
GAITS = {
    "north": ((4, 6), (4, 7), (3, 6)), "east": ((2, 4), (2, 5), (1, 4)),
    "south": ((2, 8), (3, 8), (2, 7)), "west": ((6, 8), (1, 6), (5, 8)),
}
T = TypeVar("T")


def grid_spec(rows: int, cols: int) -> str:
    """The thesis patrol task on a rows x cols grid (cells r0 .. r{rows*cols-1}, row-major)."""

    def cell(r: int, c: int) -> str:
        return f"r{r * cols + c}"

    lines = [f'robot "grid {rows}x{cols}"', "legs L1..L8 health 3"]
    for direction, patterns in GAITS.items():
        for k, (a, b) in enumerate(patterns):
            lines.append(f"gait {direction}_{'abc'[k]} uses L{a}, L{b} moves {direction}")
    lines.append(f"grid {rows} x {cols}")
    mid_r, mid_c = rows // 2, cols // 2
    lines.append(f"cache {cell(0, 1)}, {cell(rows - 1, cols - 2)}")
    blue = sorted({cell(mid_r, c) for c in range(1, cols - 1, 2)})
    red = sorted({cell(r, mid_c) for r in range(1, rows - 1, 2)} - set(blue))
    lines.append(f"hazard blue: {', '.join(blue)}")
    lines.append(f"hazard red: {', '.join(red)}")
    lines.append(f"start {cell(0, 0)}")
    lines.append(f"visit {cell(rows - 1, 0)}, {cell(0, cols - 1)} infinitely often")
    return "\n".join(lines) + "\n"


def timed(fn: Callable[[], T], repeat: int) -> tuple[T, float]:
    best = float("inf")
    result: T | None = None
    for _ in range(repeat):
        start = time.perf_counter()
        result = fn()
        best = min(best, time.perf_counter() - start)
    assert result is not None
    return result, best


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--sizes", help="comma-separated RxC list (default 4x5 .. 40x40)")
    parser.add_argument("--repeat", type=int, default=1, help="best of N runs (default 1)")
    args = parser.parse_args()
    sizes = SIZES if not args.sizes else tuple(
        (int(r), int(c)) for r, c in (s.split("x") for s in args.sizes.split(",")))
    header = (f"{'grid':>7} {'regions':>7} {'encoding':>8} {'parse+check':>11} {'lower':>8} "
              f"{'emit':>8} {'total s':>8} {'clauses':>7} {'slugsin KB':>10}")
    print(header)
    print("-" * len(header))
    for rows, cols in sizes:
        text = grid_spec(rows, cols)
        (model, _), t_front = timed(partial(model_from_text, text, "bench.gait"), args.repeat)
        for encoding in ("onehot", "binary"):
            spec, t_lower = timed(partial(lower, model, encoding), args.repeat)
            out, t_emit = timed(partial(emit, spec, "slugsin"), args.repeat)
            clauses = sum(len(spec.section(s)) for s in SECTIONS)
            total = t_front + t_lower + t_emit
            print(f"{rows:>3}x{cols:<3} {rows * cols:>7} {encoding:>8} {t_front:>11.3f} "
                  f"{t_lower:>8.3f} {t_emit:>8.3f} {total:>8.3f} {clauses:>7} "
                  f"{len(out) / 1024:>10.1f}", flush=True)


if __name__ == "__main__":
    main()
