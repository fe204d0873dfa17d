"""Benchmark of ``gaitc explain``: the two thesis tasks of issue 10 (target 30 s each), the
shipped unrealizable specs, and an 8-leg lab robot of issue 34 (target 20 s), each beside
the time of a plain ``check``.

Robot B without its caches, and the robot A task with every leg at health 2; the lab robot
has health 2 or 3, twelve two-leg gaits, a 3 x 5 grid, two caches and two hazard sets.
Prints, per part of the explanation of the thesis tasks, the solver calls and the seconds
("counter" is the counter-strategy of the whole environment, which explain avoids by taking
the play from the environment restricted to the freedoms it needs), then one table of
``check`` against ``explain`` for every task.

    python bench/bench_explain.py            # everything
    python bench/bench_explain.py --quick    # the table only, without the thesis parts
"""

from __future__ import annotations

import sys
import time
from collections.abc import Callable
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

import gaitc
from bench.families.lab8 import GAITS
from gaitc.analysis import core, failure, freedoms, repairs
from gaitc.analysis.oracle import Oracle

ROOT = Path(__file__).resolve().parent.parent
TARGET_SECONDS = 30.0
LAB_TARGET_SECONDS = 20.0

#: The 8-leg robot of issue 34: the bench lies past hazard set spill, and fumes covers c1.
LAB_ROBOT = ('robot "lab8"\nlegs L1..L8 health {health}\n' + GAITS.replace("{", "{{")
             + """grid 3 x 5 cells dock, a1, a2, a3, a4, b0, b1, b2, b3, b4, c0, c1, c2, c3, bench
cache dock, b0
hazard spill: a3, b3
hazard fumes: c1
start dock
visit bench, dock infinitely often
""")


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
        ("freedoms", lambda: freedoms.needed_freedoms(spec, oracle)),
        ("counter", lambda: oracle.counterstrategy(spec.gr1)),  # every freedom
        ("repairs", lambda: repairs.repairs(model, spec.text, spec.path, encoding, oracle, [])),
    ]


def table_tasks() -> list[tuple[str, str, float]]:
    """Every task of the check-against-explain table, with its target in seconds."""
    out = [(name, text, TARGET_SECONDS) for name, text in tasks()]
    for folder in (ROOT / "specs", ROOT / "tests" / "data" / "explain"):
        for path in sorted(folder.glob("*.gait")):
            text = path.read_text(encoding="utf-8")
            if not gaitc.check(gaitc.parse(text, name=path.name)).realizable:
                out.append((path.name, text, TARGET_SECONDS))
    out += [(f"lab8 health {h}", LAB_ROBOT.format(health=h), LAB_TARGET_SECONDS)
            for h in (2, 3)]
    return out


def table() -> None:
    print(f"\n{'task':<34}{'check s':>9}{'explain s':>11}{'calls':>7}{'repairs':>9}  target")
    for name, text, target in table_tasks():
        spec = gaitc.parse(text, name=name if name.endswith(".gait") else f"{name}.gait")
        t = time.perf_counter()
        gaitc.check(spec)
        checked = time.perf_counter() - t
        t = time.perf_counter()
        why = gaitc.explain(spec)
        whole = time.perf_counter() - t
        verdict = "meets" if whole < target else "MISSES"
        print(f"{name:<34}{checked:>9.2f}{whole:>11.2f}{why.solver_calls:>7}"
              f"{len(why.repairs):>9}  {verdict} {target:.0f} s", flush=True)


def main() -> None:
    if "--quick" not in sys.argv:
        parts()
    table()


def parts() -> None:
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
