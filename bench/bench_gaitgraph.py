"""Benchmark of the gait graph (thesis chapter 2): build times as tables.

Targets from issue 5: the full graph of the six-chamber robot (64 valve states) in under
1 s; 10,000 random valve states of a 24-chamber robot with all transitions in under 30 s.
Run: ``.venv/bin/python bench/bench_gaitgraph.py [--quick]``.
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

import numpy as np

from gaitc.gaitgraph.graph import GaitGraph, full_graph, random_states
from gaitc.gaitgraph.kinematics import forward
from gaitc.gaitgraph.poses import stable_poses
from gaitc.gaitgraph.robot import load_robot

ROBOTS = Path(__file__).resolve().parent.parent / "specs" / "robots"


def bench_full() -> None:
    robot = load_robot(ROBOTS / "silicone6.yaml")
    best = float("inf")
    for _ in range(3):
        start = time.perf_counter()
        graph = full_graph(robot)
        best = min(best, time.perf_counter() - start)
    print("full gait graph, six-chamber silicone robot")
    print(f"{'states':>8} {'poses':>8} {'edges':>10} {'seconds':>8}  target")
    print(f"{64:>8} {len(graph):>8} {len(graph.edges):>10} {best:8.3f}  < 1 s")
    print()


def bench_growth(sizes: list[int]) -> None:
    robot = load_robot(ROBOTS / "symmetric6.yaml")
    print("random valve states, symmetric six-leg robot (24 chambers), all transitions")
    print(f"{'states':>8} {'poses':>8} {'edges':>10} {'poses s':>8} {'edges s':>8} {'total s':>8}")
    for n in sizes:
        rng = np.random.default_rng(0)
        states = random_states(robot, rng, n, set())
        t0 = time.perf_counter()
        poses = stable_poses(robot, forward(robot, states))
        t1 = time.perf_counter()
        graph = GaitGraph(robot)
        graph.states.update(states)
        graph.add_poses(poses)
        t2 = time.perf_counter()
        print(
            f"{n:>8} {len(poses):>8} {len(graph.edges):>10} {t1 - t0:8.2f} {t2 - t1:8.2f} "
            f"{t2 - t0:8.2f}"
        )
    print("target: 10000 states in < 30 s")
    print()


def bench_batches(total: int) -> None:
    robot = load_robot(ROBOTS / "symmetric6.yaml")
    rng = np.random.default_rng(0)
    graph = GaitGraph(robot)
    print("incremental batches of 100 (random method, section 2.5.1)")
    print(f"{'states':>8} {'poses':>8} {'edges':>10} {'seconds':>8}")
    start = time.perf_counter()
    while len(graph.states) < total:
        graph.add_states(random_states(robot, rng, 100, graph.states))
        if len(graph.states) % (total // 5) == 0:
            elapsed = time.perf_counter() - start
            print(f"{len(graph.states):>8} {len(graph):>8} {len(graph.edges):>10} {elapsed:8.2f}")
    print()


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--quick", action="store_true", help="smaller sizes")
    args = parser.parse_args()
    bench_full()
    sizes = [250, 500, 1000, 2000] if args.quick else [500, 1000, 2000, 5000, 10_000]
    bench_growth(sizes)
    bench_batches(1000 if args.quick else 2000)


if __name__ == "__main__":
    main()
