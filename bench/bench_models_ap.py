"""Benchmark of the active/passive model (thesis 4.1.2) on silicone6: speed as tables.

Target from issue 15: at least 100× real time at the thesis's 6 s control period, that is
one valve transition (6 s of robot time) in under 60 ms.  Transitions are simulated afresh
(no transition cache); the steady states of the 64 valve states are solved first and
timed separately, as a gait graph (section 4.2.2, "Generating the gait graph") needs them
once.  Also prints the forward cycle found by brute force over salamander-like states.
Run: ``.venv/bin/python bench/bench_models_ap.py [--quick]``.
"""

from __future__ import annotations

import argparse
import itertools
import time
from pathlib import Path

import numpy as np

from softmodels.active_passive import ActivePassiveModel
from softmodels.motion import Pose2D, ValveState

ROBOT = Path(__file__).resolve().parent.parent / "specs" / "robots" / "silicone6.yaml"
PERIOD = 6.0  # s, the controller period of thesis chapter 4


def _state(index: int) -> ValveState:
    return tuple(bool(index >> (5 - i) & 1) for i in range(6))


def bench_speed(pairs: int, step_counts: list[int]) -> None:
    rng = np.random.default_rng(0)
    chosen = [tuple(int(v) for v in rng.choice(64, 2, replace=False)) for _ in range(pairs)]
    print(f"silicone6, {pairs} random valve transitions of {PERIOD:g} s each (uncached)")
    print(
        f"{'steps':>6} {'steady s':>9} {'per trans ms':>13} {'trans/s':>8} "
        f"{'real time x':>12} {'solver iters':>13}  target"
    )
    for steps in step_counts:
        model = ActivePassiveModel.from_robot_file(ROBOT, steps=steps)
        t0 = time.perf_counter()
        for i in range(64):
            model.steady(_state(i))
        t1 = time.perf_counter()
        iterations = 0
        for a, b in chosen:
            for step in model.simulate(_state(a), _state(b), PERIOD):
                iterations += step.rest.iterations
        t2 = time.perf_counter()
        per = (t2 - t1) / pairs
        print(
            f"{steps:>6} {t1 - t0:9.2f} {per * 1e3:13.1f} {1 / per:8.1f} {PERIOD / per:12.1f} "
            f"{iterations / pairs:13.1f}  >= 100x"
        )
    print()


def bench_forward(steps: int) -> None:
    states = [m + legs for m in ("10", "01") for legs in ("1001", "0110")]
    model = ActivePassiveModel.from_robot_file(ROBOT, steps=steps)
    found: list[tuple[float, Pose2D, tuple[str, ...]]] = []
    t0 = time.perf_counter()
    for k in (2, 3):
        for cycle in itertools.permutations(states, k):
            if cycle[0] == min(cycle):
                pose = model.cycle([tuple(c == "1" for c in s) for s in cycle], PERIOD)
                found.append((pose.x, pose, cycle))
    found.sort(key=lambda item: -item[0])
    print(
        f"silicone6 two- and three-state cycles over {len(states)} salamander-like states "
        f"({steps} steps per transition, {time.perf_counter() - t0:.1f} s)"
    )
    print(f"{'cycle (valves R L RL RR FL FR)':<34} {'x mm':>7} {'y mm':>7} {'turn deg':>9}")
    for _, pose, cycle in found[:5]:
        print(f"{' -> '.join(cycle):<34} {pose.x:7.2f} {pose.y:7.2f} {np.degrees(pose.theta):9.2f}")
    print()


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--quick", action="store_true", help="fewer transitions")
    args = parser.parse_args()
    bench_speed(10 if args.quick else 40, [4, 8] if args.quick else [2, 4, 8])
    bench_forward(4 if args.quick else 8)


if __name__ == "__main__":
    main()
