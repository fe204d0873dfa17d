"""Benchmark of the spring-damper model (thesis 4.1.1): speed as model steps per second.

Real-time factor = simulated seconds / wall seconds.  A transition holds its valves for the
thesis's 6 s control period; the model stops integrating once the robot is at rest, so
"per period" counts the full 6 s and "integrated" only the steps actually taken.  Target
(issue 15): at least 100x real time at the 6 s control period.  Robots: radial8 (eight
legs) and a six-leg radial variant with radial8's limb parameters (the chapter 4 six-leg
silicone robot hangs its front legs on a spine, which the spring-damper reader does not
support; its model is the active/passive one).
Run: ``.venv/bin/python bench/bench_models.py [--quick]``.
"""

from __future__ import annotations

import argparse
import math
import time
from pathlib import Path

from gaitc.models.gait_graph import build_graph, valve_states
from gaitc.models.spring_damper.description import parse_spring_damper
from gaitc.models.spring_damper.model import SpringDamperModel

ROBOTS = Path(__file__).resolve().parent.parent / "specs" / "robots"
PERIOD = 6.0


def radial(legs: int) -> str:
    """radial8's file with its legs replaced by ``legs`` legs evenly around the chassis."""
    text = (ROBOTS / "radial8.yaml").read_text(encoding="utf-8")
    if legs == 8:
        return text
    head, rest = text.split("legs:\n", 1)
    tail = rest[rest.index("gaits:") :]
    model = tail[tail.index("model:") :]
    rows = []
    for i in range(legs):
        yaw = 360.0 * i / legs
        x, y = 50 * math.cos(math.radians(yaw)), 50 * math.sin(math.radians(yaw))
        rows.append(f"  - {{name: L{i + 1}, mount: [{x:.3f}, {y:.3f}, 0], yaw: {yaw:g}}}\n")
    model = (
        model[: model.index("    limbs:")]
        + "    limbs:\n"
        + "".join(f"      - {{name: L{i + 1}}}\n" for i in range(legs))
    )
    return (
        head.replace("robot: radial8", f"robot: radial{legs}") + "legs:\n" + "".join(rows) + model
    )


def bench(legs: int, repeats: int) -> None:
    robot = parse_spring_damper(radial(legs), f"radial{legs}")
    vented = (False,) * legs
    one = tuple(i == 0 for i in range(legs))
    rows = []
    for label, start, end in (("extend one leg", vented, one), ("vent it", one, vented)):
        best, steps = math.inf, 0
        for _ in range(repeats):
            model = SpringDamperModel(robot)
            model.steady_state(start)
            before = model.steps
            t0 = time.perf_counter()
            model.transition(start, end, PERIOD)
            best = min(best, time.perf_counter() - t0)
            steps = model.steps - before
        rows.append((label, 1, steps, best))
    model = SpringDamperModel(robot)
    states = valve_states(legs, 1)
    model.steady_states(states)
    before = model.steps
    t0 = time.perf_counter()
    graph = build_graph(model, states, PERIOD)
    wall = time.perf_counter() - t0
    rows.append(("gait graph (batch)", len(graph.motion), model.steps - before, wall))
    print(
        f"radial{legs}: {legs} legs, time step {robot.time_step * 1000:g} ms, period {PERIOD:g} s"
    )
    print(
        f"{'run':<20} {'transitions':>11} {'steps':>9} {'seconds':>8} {'steps/s':>10} "
        f"{'RTF integrated':>14} {'RTF per period':>14}  target"
    )
    for label, count, steps, wall in rows:
        integrated = steps * robot.time_step / wall
        per_period = count * PERIOD / wall
        print(
            f"{label:<20} {count:>11} {steps:>9} {wall:8.3f} {steps / wall:10.0f} "
            f"{integrated:14.1f} {per_period:14.1f}  >= 100"
        )
    print()


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--quick", action="store_true", help="one repeat instead of three")
    args = parser.parse_args()
    for legs in (8, 6):
        bench(legs, 1 if args.quick else 3)


if __name__ == "__main__":
    main()
