"""Benchmark: what the move preferences (issue 13) change in long runs.

For thesis robot A (binary encoding), the hazard patrol and the forklift yard of tests/data,
with and without preferences: controller size and synthesis seconds, then 10,000
adversarial and 10,000 random steps, with per 100 steps the moves into (or within) a
region of the active hazard set with a leg-wearing gait, and the health levels lost; and
the longest wait between two visits of a goal (no goal may be starved).  Target:
active-hazard entries down by at least 90% wherever the spec allows a detour, the longest
wait not longer.

Usage: python bench/bench_preferences.py [--steps N] [--spec FILE --encoding E]
"""

from __future__ import annotations

import argparse
import itertools
import time
from pathlib import Path

import gaitc
from gaitc.sim.environments import AdversarialEnvironment, Environment, RandomEnvironment
from gaitc.sim.run import Run

ROOT = Path(__file__).resolve().parent.parent
SPECS = ((ROOT / "specs" / "thesis_robot_a.gait", "binary"),
         (ROOT / "tests" / "data" / "hazard_patrol.gait", "onehot"),
         # a forklift that comes and goes beside a spill that may stay (issue 60)
         (ROOT / "tests" / "data" / "hazards" / "yard.gait", "onehot"))


def measures(run: Run, hazards: dict[str, set[str]], caches: set[str]) -> tuple[int, int, int]:
    """Active-hazard entries, health levels lost, and the longest wait for any goal."""
    entries = sum(1 for s in run.steps if s.hazard is not None and s.legs_used
                  and s.region in hazards.get(s.hazard, set()) and s.region not in caches)
    lost = 0
    for before, after in itertools.pairwise(run.steps):
        lost += sum(max(0, level - after.level(leg)) for leg, level in before.health)
    labels = {g for s in run.steps for g in s.goals}
    if run.summary is not None:
        labels |= {g for g, _ in run.summary.goal_visits}
    wait = 0
    for label in labels:
        seen = [s.index for s in run.steps if label in s.goals]
        marks = [0, *seen, len(run.steps) - 1]
        wait = max(wait, *(b - a for a, b in itertools.pairwise(marks)))
    return entries, lost, wait


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--steps", type=int, default=10_000)
    parser.add_argument("--spec", help="one .gait spec instead of the two default ones")
    parser.add_argument("--encoding", default="onehot", choices=("onehot", "binary"))
    args = parser.parse_args()
    specs = [(Path(args.spec), args.encoding)] if args.spec else list(SPECS)
    print(f"{'spec':<18}{'prefer':<8}{'nodes':>7}{'synth s':>9}  {'environment':<14}"
          f"{'entries/100':>12}{'lost/100':>10}{'longest wait':>13}")
    for path, encoding in specs:
        spec = gaitc.load(path, encoding)
        assert spec.model is not None
        hazards = {h.name: set(h.regions) for h in spec.model.hazards}
        caches = set(spec.model.caches)
        for prefer in ("none", None):
            started = time.perf_counter()
            found = gaitc.synthesize(spec, prefer=prefer)
            seconds = time.perf_counter() - started
            if found.controller is None or not found.verified:
                raise SystemExit(f"{path}: no verified controller")
            bound = gaitc.session(spec, found)
            assert bound is not None
            envs: list[Environment] = [AdversarialEnvironment(), RandomEnvironment(1)]
            for env in envs:
                run = gaitc.simulate(bound, env=env, steps=args.steps)
                assert run.summary is not None and run.summary.guarantees_held
                entries, lost, wait = measures(run, hazards, caches)
                per = 100 / args.steps
                print(f"{path.stem:<18}{prefer or 'default':<8}{len(found.controller.nodes):>7}"
                      f"{seconds:>9.1f}  {env.name.split(' --')[0]:<14}{entries * per:>12.2f}"
                      f"{lost * per:>10.2f}{wait:>13}", flush=True)


if __name__ == "__main__":
    main()
