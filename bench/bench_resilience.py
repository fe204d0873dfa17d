"""Benchmark of the failure-set question of ``gaitc resilience`` (issue 11): every subset of
legs failed from the start, answered three ways, side by side.

parametric: one game with a rigid cap per leg; lattice: one solver call per variant,
pruned by monotonicity; brute: one call per subset. Target: thesis robot A (all 256 subsets
of its 8 legs) under 10 s with the parametric method.

    python bench/bench_resilience.py [SPEC ...]
"""

from __future__ import annotations

import functools
import itertools
import sys
import time
from pathlib import Path

import gaitc
from analysis.lattice import fatal_sets
from analysis.parametric import winning_caps
from analysis.pool import Pool
from analysis.variants import with_failed
from ltlcompiler.model import Model

ROOT = Path(__file__).resolve().parent.parent
DEFAULT = [ROOT / "specs" / "thesis_robot_a.gait", ROOT / "specs" / "thesis_robot_b.gait"]
TARGET_SECONDS = 10.0


def _fatal(pool: Pool, model: Model, sets: list[frozenset[str]]) -> list[bool]:
    return [not ok for ok in pool.models([with_failed(model, s) for s in sets])]


def main() -> None:
    paths = [Path(p) for p in sys.argv[1:]] or DEFAULT
    print(f"{'spec':<24}{'legs':>5}{'subsets':>9}  {'method':<11}{'calls':>7}{'seconds':>9}"
          f"{'peak nodes':>12}  minimal fatal sets")
    for path in paths:
        spec = gaitc.load(path, "binary")
        model = spec.model
        assert model is not None
        legs = [leg.name for leg in model.legs if leg.health > 1]
        subsets = 2 ** len(legs)
        rows = []
        t = time.perf_counter()
        domains = {leg.name: ((1, leg.health) if leg.health > 1 else (1,)) for leg in model.legs}
        result = winning_caps(model, "binary", domains)
        rows.append(("parametric", 1, time.perf_counter() - t, str(result.peak_nodes)))
        with Pool("binary") as pool:
            t = time.perf_counter()
            found = fatal_sets(legs, functools.partial(_fatal, pool, model))
            rows.append(("lattice", pool.calls, time.perf_counter() - t, "-"))
            before = pool.calls
            t = time.perf_counter()
            variants = [with_failed(model, c) for n in range(len(legs) + 1)
                        for c in itertools.combinations(legs, n)]
            pool.models(variants)
            rows.append(("brute", pool.calls - before, time.perf_counter() - t, "-"))
        for method, calls, seconds, peak in rows:
            print(f"{path.name:<24}{len(model.legs):>5}{subsets:>9}  {method:<11}{calls:>7}"
                  f"{seconds:>9.2f}{peak:>12}  {len(found.minimal_fatal)}", flush=True)
        verdict = "meets" if rows[0][2] < TARGET_SECONDS else "MISSES"
        print(f"{'':<24}parametric {verdict} the {TARGET_SECONDS:.0f} s target", flush=True)


if __name__ == "__main__":
    main()
