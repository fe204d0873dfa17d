"""Benchmark: what recovering from a broken assumption costs (issue 52).

For each spec, a run of N steps without surprises is set beside runs where one leg fails
while not in use (every leg in turn): the seconds of synthesis, of the first surprise of a
run (it solves the spec's game without the care set, and the goal-dropped games when the
state is lost), of a later surprise (the games solved already), and the outcomes.

Usage: python bench/bench_recovery.py [--quick] [--steps N]
"""

from __future__ import annotations

import argparse
import statistics
import time
from collections import Counter
from pathlib import Path

import gaitc
from gaitc.sim.environments import RandomEnvironment
from gaitc.sim.events import plan
from gaitc.sim.recovery import Fallback
from gaitc.sim.simulator import SurpriseOptions, simulate

ROOT = Path(__file__).resolve().parent.parent
QUICK = ("shuttle_2leg", "thesis_robot_a", "radial8_patrol")
FULL = (*QUICK, "thesis_robot_b", "radial12_patrol")


def bench(name: str, steps: int) -> str:
    path = ROOT / "specs" / f"{name}.gait"
    started = time.perf_counter()
    bound = gaitc.session(path)
    synth = time.perf_counter() - started
    assert bound is not None
    domain = bound.domain
    started = time.perf_counter()
    plain = simulate(bound.strategy, domain, bound.monitor, RandomEnvironment(1), steps)
    plain_s = time.perf_counter() - started
    shared = Fallback(bound.spec.gr1, domain)
    first: list[float] = []
    later: list[float] = []
    outcomes: Counter[str] = Counter()
    for leg in domain.legs:
        k = next((k for k in range(1, len(plain.steps)) if leg not in plain.steps[k - 1].legs_used
                  and plain.steps[k - 1].region not in domain.model.caches
                  and plain.steps[k - 1].level(leg) > 1), None)
        if k is None:
            continue
        fresh = not first
        started = time.perf_counter()
        options = SurpriseOptions(plan([f"{k}:fail {leg}"], domain), fallback=shared)
        run = simulate(bound.strategy, domain, bound.monitor, RandomEnvironment(1), steps,
                       surprises=options)
        spent = time.perf_counter() - started - plain_s * len(run.steps) / len(plain.steps)
        (first if fresh else later).append(max(0.0, spent))
        outcomes.update(str(s.outcome) for s in run.surprises)
    told = ", ".join(f"{n} {o}" for o, n in sorted(outcomes.items()))
    later_ms = statistics.median(later) * 1000 if later else float("nan")
    return (f"{name:<18}{len(domain.legs):>5}{synth:>9.2f}{plain_s:>10.2f}"
            f"{first[0] if first else float('nan'):>10.2f}{later_ms:>10.1f}  {told}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="the small specs only")
    parser.add_argument("--steps", type=int, default=200)
    args = parser.parse_args()
    print(f"{'spec':<18}{'legs':>5}{'synth s':>9}{'run s':>10}{'1st surp':>10}"
          f"{'later ms':>10}  outcomes (one leg failing while unused, each leg)")
    for name in QUICK if args.quick else FULL:
        print(bench(name, args.steps), flush=True)
    print(f"run s: {args.steps} steps without a surprise; 1st surp: the extra seconds of the "
          "run with the first surprise (its games solved); later ms: the median extra time "
          "of a run whose games were solved by an earlier one")


if __name__ == "__main__":
    main()
