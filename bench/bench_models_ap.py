"""Benchmark of the active/passive model (thesis 4.1.2) on silicone6: speed as tables.

Target from issue 15: at least 100× real time at the thesis's 6 s control period, that is
one valve transition (6 s of robot time) in under 60 ms.  The rates use the process's CPU
time (the machine is shared; the wall-clock time is shown too).  Transitions are simulated afresh
(no transition cache); the steady states of the 64 valve states are solved first and
timed separately, as a gait graph (section 4.2.2, "Generating the gait graph") needs them
once.  Also prints the forward cycle found by brute force over salamander-like states.
Run: ``.venv/bin/python bench/bench_models_ap.py [--quick]``.
"""

from __future__ import annotations

import argparse
import itertools
import math
import time
from pathlib import Path

import numpy as np

from gaitc.models.active_passive.model import ActivePassiveModel
from gaitc.models.motion import Pose2D, ValveState

ROBOT = Path(__file__).resolve().parent.parent / "specs" / "robots" / "silicone6.yaml"
PERIOD = 6.0  # s, the controller period of thesis chapter 4


def _state(index: int) -> ValveState:
    return tuple(bool(index >> (5 - i) & 1) for i in range(6))


FORWARD = ("010110", "100000", "011001")  # the best straight cycle of bench_forward


def _forward_x(model: ActivePassiveModel) -> float:
    return model.cycle([tuple(c == "1" for c in s) for s in FORWARD], PERIOD).x


def bench_speed(pairs: int, settings: list[tuple[int, int]]) -> None:
    """Speed, and agreement with fine steps: the median and largest position error over
    random transitions (the largest are paths that branch into another local minimum), and
    the forward cycle's displacement."""
    rng = np.random.default_rng(0)
    chosen = [tuple(int(v) for v in rng.choice(64, 2, replace=False)) for _ in range(pairs)]
    model = ActivePassiveModel.from_robot_file(ROBOT, cache=False)
    t0 = time.perf_counter()
    for i in range(64):
        model.steady(_state(i))
    steady = time.perf_counter() - t0
    model.steps, model.refine = 64, 0
    reference = [model.simulate(_state(a), _state(b), PERIOD)[-1].pose for a, b in chosen]
    print(
        f"silicone6: steady states of all 64 valve states in {steady:.1f} s; {pairs} random "
        f"transitions of {PERIOD:g} s each (uncached); errors against 64 even steps, whose "
        f"forward cycle {' -> '.join(FORWARD)} moves {_forward_x(model):.2f} mm"
    )
    print(
        f"{'steps':>5} {'refine':>6} {'cpu ms':>7} {'wall ms':>8} {'trans/s':>8} "
        f"{'x real time':>12} "
        f"{'solves':>7} {'err median mm':>14} {'err max mm':>11} {'forward mm':>11}  target"
    )
    for steps, refine in settings:
        model.steps, model.refine = steps, refine
        per = wall = math.inf
        for _ in range(2):  # the faster of two passes: the machine is shared
            solves = 0
            poses = []
            t1, c1 = time.perf_counter(), time.process_time()
            for a, b in chosen:
                out = model.simulate(_state(a), _state(b), PERIOD)
                solves += len(out)
                poses.append(out[-1].pose)
            per = min(per, (time.process_time() - c1) / pairs)
            wall = min(wall, (time.perf_counter() - t1) / pairs)
        err = [math.hypot(p.x - r.x, p.y - r.y) for p, r in zip(poses, reference, strict=True)]
        print(
            f"{steps:>5} {refine:>6} {per * 1e3:7.1f} {wall * 1e3:8.1f} {1 / per:8.1f} "
            f"{PERIOD / per:12.1f} "
            f"{solves / pairs:7.1f} {np.median(err):14.3f} {max(err):11.3f} "
            f"{_forward_x(model):11.2f}  >= 100x"
        )
    print()


def bench_forward(steps: int) -> None:
    """The cycles moving furthest along +x; the thesis (4.3.3) saw the robot propel itself
    forward with a brief "salamander" gait."""
    states = [m + legs for m in ("10", "01") for legs in ("0000", "1001", "0110")]
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
        f"silicone6: two- and three-state cycles over {len(states)} salamander-like states "
        f"(middle bent, no legs or a diagonal pair down; {time.perf_counter() - t0:.1f} s), "
        "displacement per cycle in the first state's frame"
    )
    print(f"{'cycle (valves R L RL RR FL FR)':<34} {'x mm':>7} {'y mm':>7} {'turn deg':>9}")
    for _, pose, cycle in found[:5]:
        print(f"{' -> '.join(cycle):<34} {pose.x:7.2f} {pose.y:7.2f} {np.degrees(pose.theta):9.2f}")
    print()


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--quick", action="store_true", help="fewer transitions")
    args = parser.parse_args()
    quick = [(4, 0), (8, 2)]
    bench_speed(
        10 if args.quick else 40,
        quick if args.quick else [(4, 0), (8, 0), (4, 2), (6, 1), (6, 2), (8, 1), (8, 2), (16, 2)],
    )
    bench_forward(8)


if __name__ == "__main__":
    main()
