"""Benchmark of ``gaitc explain`` on the two thesis tasks of issue 10 (target: 30 s each).

Robot B without its caches, and the robot A task with every leg at health 2; both are
unrealizable. Prints, per part of the explanation, the solver calls and the seconds;
"counter" is the counter-strategy of the whole environment, which explain avoids by taking
the play from the environment restricted to the freedoms it needs.

    python bench/bench_explain.py
"""

from __future__ import annotations

import time
from collections.abc import Callable
from pathlib import Path

import gaitc
from gaitc.analysis import core, failure, freedoms, repairs
from gaitc.analysis.oracle import Oracle

ROOT = Path(__file__).resolve().parent.parent
TARGET_SECONDS = 30.0


def tasks() -> list[tuple[str, str]]:
    robot_b = (ROOT / "specs" / "thesis_robot_b.gait").read_text(encoding="utf-8")
    robot_a = (ROOT / "specs" / "thesis_robot_a.gait").read_text(encoding="utf-8")
    no_caches = robot_b.replace("cache r3, r14\n", "")
    health_2 = robot_a.replace("legs L1..L8 health 3", "legs L1..L8 health 2")
    assert no_caches != robot_b and health_2 != robot_a
    return [("robot B, no caches", no_caches), ("robot A, health 2", health_2)]


def _parts(spec: gaitc.Spec, oracle: Oracle) -> list[tuple[str, Callable[[], object]]]:
    model, encoding = spec.model, spec.encoding
    assert model is not None and encoding is not None
    return [
        ("verdict", lambda: oracle.realizable(spec.gr1)),
        ("kind", lambda: failure.classify(spec.gr1, oracle)),
        ("core", lambda: core.guarantee_core(spec.gr1, oracle)),
        ("freedoms", lambda: freedoms.needed_freedoms(spec.gr1, model, encoding, oracle)),
        ("counter", lambda: oracle.counterstrategy(spec.gr1)),  # every freedom
        ("repairs", lambda: repairs.repairs(model, spec.text, spec.path, encoding, oracle, [])),
    ]


def main() -> None:
    print(f"{'task':<20}{'part':<12}{'calls':>7}{'seconds':>9}")
    for name, text in tasks():
        spec = gaitc.parse(text, name=f"{name}.gait")
        oracle = Oracle()
        started = time.perf_counter()
        parts = _parts(spec, oracle)
        for part, run in parts:
            calls, t = oracle.calls, time.perf_counter()
            run()
            print(f"{name:<20}{part:<12}{oracle.calls - calls:>7}"
                  f"{time.perf_counter() - t:>9.2f}", flush=True)
        t = time.perf_counter()
        why = gaitc.explain(spec)
        whole = time.perf_counter() - t
        verdict = "meets" if whole < TARGET_SECONDS else "MISSES"
        print(f"{name:<20}{'explain':<12}{why.solver_calls:>7}{whole:>9.2f}  {verdict} the "
              f"{TARGET_SECONDS:.0f} s target (parts above: "
              f"{time.perf_counter() - started - whole:.2f} s)", flush=True)


if __name__ == "__main__":
    main()
