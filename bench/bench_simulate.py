"""Benchmark: simulate 10,000 steps of the thesis robot-A controller (target: under 2 s).

Usage: python bench/bench_simulate.py [--controller FILE] [--steps N]
Without --controller, the controller is synthesized once (binary encoding, about 1-2
minutes) and cached in the system's temporary directory.
"""

from __future__ import annotations

import argparse
import hashlib
import tempfile
import time
from pathlib import Path

import gaitc
from gaitc.sim.environments import AdversarialEnvironment, Environment, RandomEnvironment

ROOT = Path(__file__).resolve().parent.parent
SPEC = ROOT / "specs" / "thesis_robot_a.gait"
TARGET_SECONDS = 2.0


def cached_controller(spec: Path, encoding: str) -> Path:
    digest = hashlib.sha256(spec.read_bytes()).hexdigest()[:16]
    path = Path(tempfile.gettempdir()) / f"gaitc-bench-{spec.stem}-{encoding}-{digest}.json"
    if not path.exists():
        print(f"synthesizing {spec.name} ({encoding}) once; cached in {path}")
        found = gaitc.synthesize(gaitc.load(spec, encoding))
        if found.controller is None:
            raise SystemExit(f"{spec}: unrealizable")
        found.save(path)
    return path


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--controller", help="controller JSON of specs/thesis_robot_a.gait")
    parser.add_argument("--encoding", default="binary", choices=("onehot", "binary"))
    parser.add_argument("--steps", type=int, default=10_000)
    args = parser.parse_args()
    controller = args.controller or str(cached_controller(SPEC, args.encoding))
    started = time.perf_counter()
    loaded = gaitc.session(SPEC, controller, args.encoding)
    assert loaded is not None
    print(f"loaded {len(loaded.strategy)} controller nodes in "
          f"{time.perf_counter() - started:.2f} s")
    environments: list[Environment] = [RandomEnvironment(1), AdversarialEnvironment()]
    print(f"{'environment':<18}{'steps':>8}{'seconds':>10}{'cpu s':>8}{'steps/s':>10}  spec held")
    worst = 0.0
    for env in environments:
        wall, cpu = time.perf_counter(), time.process_time()
        run = gaitc.simulate(loaded, env=env, steps=args.steps)
        wall, cpu = time.perf_counter() - wall, time.process_time() - cpu
        worst = max(worst, cpu)
        held = run.summary is not None and run.summary.assumptions_held \
            and run.summary.guarantees_held and run.error is None
        print(f"{env.name:<18}{args.steps:>8}{wall:>10.2f}{cpu:>8.2f}"
              f"{args.steps / wall:>10.0f}  {'yes' if held else 'NO'}")
    verdict = "meets" if worst < TARGET_SECONDS else "MISSES"
    print(f"slowest run {worst:.2f} cpu s: {verdict} the {TARGET_SECONDS:.0f} s target (judged "
          "on cpu time, which a busy shared machine does not inflate; compare the seconds column)")


if __name__ == "__main__":
    main()
