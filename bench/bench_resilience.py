"""Benchmark of the failure-set question of ``gaitc resilience`` (issue 11): every subset of
legs failed from the start, answered three ways, side by side.

parametric: one game with a rigid cap per leg, the sets read off its BDD; lattice: one
solver call per variant, pruned by monotonicity; brute: one call per subset. The enumerating
methods are skipped where they would take hours (brute force beyond 2^10 subsets, the lattice
search beyond 12 legs). A last row per spec times the complete ``gaitc resilience`` report
(failure sets, any-time k, health front, caches, hazards). Targets: thesis robot A's failure
sets under 10 s with the parametric method, the 24-leg robot's complete report under 5 min.

    python bench/bench_resilience.py [SPEC ...]
"""

from __future__ import annotations

import functools
import itertools
import sys
import time
from pathlib import Path

import gaitc
from gaitc.analysis.lattice import fatal_sets
from gaitc.analysis.parametric import failure_sets
from gaitc.analysis.pool import Pool
from gaitc.analysis.variants import with_failed
from ltlcompiler.model import Model

ROOT = Path(__file__).resolve().parent.parent
DEFAULT = [ROOT / "specs" / f"{name}.gait" for name in
           ("thesis_robot_a", "thesis_robot_b", "radial12_patrol", "centipede24_patrol")]
TARGET_SECONDS = 10.0  # robot A's failure sets, parametric
REPORT_TARGET_SECONDS = 300.0  # the 24-leg robot's complete report
BRUTE_LIMIT = 10  # legs up to which brute force runs
LATTICE_LIMIT = 12  # legs up to which the lattice search runs


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
        found = failure_sets(model, "binary")
        rows.append(("parametric", "1", time.perf_counter() - t, f"{found.peak_nodes:,}"))
        with Pool("binary") as pool:
            if len(legs) <= LATTICE_LIMIT:
                t = time.perf_counter()
                lattice = fatal_sets(legs, functools.partial(_fatal, pool, model))
                rows.append(("lattice", str(pool.calls), time.perf_counter() - t, "-"))
                assert len(lattice.minimal_fatal) == len(found.minimal_fatal)
            if len(legs) <= BRUTE_LIMIT:
                before = pool.calls
                t = time.perf_counter()
                variants = [with_failed(model, c) for n in range(len(legs) + 1)
                            for c in itertools.combinations(legs, n)]
                pool.models(variants)
                rows.append(("brute", str(pool.calls - before), time.perf_counter() - t, "-"))
        t = time.perf_counter()
        report = gaitc.resilience(spec)
        rows.append(("report", str(report.solver_calls), time.perf_counter() - t, "-"))
        for method, calls, seconds, peak in rows:
            print(f"{path.name:<24}{len(model.legs):>5}{subsets:>9}  {method:<11}{calls:>7}"
                  f"{seconds:>9.2f}{peak:>12}  {len(found.minimal_fatal)}", flush=True)
        if path.stem == "thesis_robot_a":
            verdict = "meets" if rows[0][2] < TARGET_SECONDS else "MISSES"
            print(f"{'':<24}parametric {verdict} the {TARGET_SECONDS:.0f} s target", flush=True)
        if len(model.legs) >= 24:
            verdict = "meets" if rows[-1][2] < REPORT_TARGET_SECONDS else "MISSES"
            print(f"{'':<24}the report {verdict} the {REPORT_TARGET_SECONDS:.0f} s target",
                  flush=True)

if __name__ == "__main__":
    main()
