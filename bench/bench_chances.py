"""Benchmark and Monte Carlo check of ``gaitc chances`` (issue 63): state counts and times of
Storm's model on robot A with two health levels, its chances of 1, 5 and 10 patrols within
500 steps, and RUNS stochastic runs of the controller it writes (10,000; --quick 300) against
the 99% interval of Storm's number.  A realizable robot's chance that its assumptions hold
over 1,000 steps (with a sudden-failure rate) is checked the same way.

Usage: python bench/bench_chances.py [--quick] [--runs N] [--only-patrols | --only-assumptions]
"""

from __future__ import annotations

import argparse
import hashlib
import math
import tempfile
import time
from pathlib import Path

import gaitc
from gaitc.api.chances import ChancesOptions, chances, save_best
from gaitc.api.simulation import session, simulate
from gaitc.core.modes import EnvironmentKind
from gaitc.sim.rates import Rates, load_rates
from gaitc.sim.session import Opponent

ROOT = Path(__file__).resolve().parent.parent
SPEC = ROOT / "specs" / "thesis_robot_a_health2.gait"
RATES = ROOT / "docs" / "how-to" / "robot_a_rates.yaml"
REALIZABLE = ROOT / "specs" / "radial8_patrol.gait"


def interval(p: float, runs: int) -> float:
    return 2.576 * math.sqrt(max(p * (1 - p), 0.25 / runs) / runs)


def patrols(runs: int, steps: int, wear: float | None = None) -> None:
    clock = time.perf_counter()
    answer = chances(SPEC, rates=RATES, wear=wear, options=ChancesOptions(steps, 10))
    seconds = time.perf_counter() - clock
    out = Path(tempfile.gettempdir()) / "gaitc-bench-chances-robot-a.json"
    save_best(answer, out)
    assert answer.written is not None and answer.controller is not None
    harder = "" if wear is None else f", wear {wear:g}"
    print(f"robot A health 2, {steps} steps{harder}: MDP of {answer.best.states} states, "
          f"written controller of {len(answer.controller.nodes)} nodes, {seconds:.1f} s "
          f"({', '.join(f'{k} {v:.1f} s' for k, v in answer.seconds.items())})")
    bound = session(SPEC, out)
    env = Opponent(EnvironmentKind.STOCHASTIC, rates=str(RATES), wear=wear)
    clock = time.perf_counter()
    counts = [simulate(bound, env=env, steps=steps, seed=s).patrols() for s in range(runs)]
    print(f"{runs} runs of {steps} steps in {time.perf_counter() - clock:.1f} s")
    print(f"{'k':>3}{'best':>12}{'written':>12}{'Monte Carlo':>14}{'99% interval':>15}  agrees")
    for k in (1, 5, 10):
        p = answer.written.patrols[k - 1]
        seen = sum(c >= k for c in counts) / runs
        width = interval(p, runs)
        print(f"{k:>3}{answer.best.patrols[k - 1]:>12.6f}{p:>12.6f}{seen:>14.4f}"
              f"{width:>15.4f}  {'yes' if abs(seen - p) <= width else 'NO'}")


def assumptions(runs: int, steps: int) -> None:
    digest = hashlib.sha256(REALIZABLE.read_bytes()).hexdigest()[:16]
    ctrl = Path(tempfile.gettempdir()) / f"gaitc-bench-chances-{digest}.json"
    if not ctrl.exists():
        gaitc.synthesize(gaitc.load(REALIZABLE)).save(ctrl)
    model = gaitc.load(REALIZABLE).robot
    rates = Rates(every=0.05, fail=0.0005)
    clock = time.perf_counter()
    answer = chances(REALIZABLE, ctrl, rates=rates, options=ChancesOptions(steps, 3),
                     write=False)
    assert answer.assumptions is not None
    print(f"{REALIZABLE.name}: assumptions hold for {steps} steps with chance "
          f"{answer.assumptions.hold:.6f} ({time.perf_counter() - clock:.1f} s)")
    del model
    rates_file = Path(tempfile.gettempdir()) / "gaitc-bench-chances-rates.yaml"
    rates_file.write_text("wear: 0.05\nfail: 0.0005\n")
    load_rates(rates_file, gaitc.load(REALIZABLE).robot)
    bound = session(REALIZABLE, ctrl)
    env = Opponent(EnvironmentKind.STOCHASTIC, rates=str(rates_file))
    # a run stops at the first input that breaks an assumption (a sudden failure)
    held = sum(simulate(bound, env=env, steps=steps, seed=s, on_surprise="stop").error is None
               for s in range(runs))
    p = answer.assumptions.hold
    width = interval(p, runs)
    print(f"Monte Carlo {held / runs:.4f} over {runs} runs, 99% interval +-{width:.4f}: "
          f"{'agrees' if abs(held / runs - p) <= width else 'DISAGREES'}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="300 runs instead of 10,000")
    parser.add_argument("--runs", type=int)
    parser.add_argument("--only-assumptions", action="store_true")
    parser.add_argument("--only-patrols", action="store_true")
    args = parser.parse_args()
    runs = args.runs or (300 if args.quick else 10_000)
    if not args.only_assumptions:
        patrols(runs, 500)  # the question: wear of 1-5% per use, 500 steps
        patrols(runs, 80, 0.4)  # where the chances bite: harder wear, a tight horizon
    if not args.only_patrols:
        assumptions(runs, 1000)


if __name__ == "__main__":
    main()
