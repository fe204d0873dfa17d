"""The controller node's step latency on ROS 2 (issue 62): from an observation published to
the command received, median and p99.

A test node plays the robot: it publishes each step's observation (``hazards`` and
``leg_health``, taken from a seeded ``simulate`` run, so every one is an input the
controller accepts) and times the controller's ``gait`` for it.  The node runs in this
process (its own node and executor thread, the messages through Fast DDS) or as ``gaitc
ros`` in a process of its own; the ROS domain is the bench's own and discovery stays on this
machine.  Robot A has hazard sets (two messages an observation), the radial robot binds
valve primitives (three commands a step).
Run: .venv/bin/python bench/bench_ros.py [--quick] [--steps N]
"""

from __future__ import annotations

import argparse
import os
import signal
import statistics
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "tests"))
os.environ.setdefault("ROS_DOMAIN_ID", "58")
os.environ["ROS_AUTOMATIC_DISCOVERY_RANGE"] = "LOCALHOST"

from ros_graph import RADIAL8, ROBOT_A, Probe, controller

import gaitc
from gaitc.api.simulation import session
from gaitc.ros.graph import Graph
from gaitc.ros.node import ControllerNode, NodeOptions
from gaitc.ros.topics import hazards_message, health_message


def steps_of(spec: Path, control: Path, count: int) -> list[Any]:
    return gaitc.simulate(spec, control, steps=count, seed=11).steps


def play(probe: Probe, spec: Path, steps: list[Any]) -> list[float]:
    """Each step's latency in ms: observation published to its gait received."""
    domain = session(gaitc.load(spec), None)
    hazards = tuple(domain.domain.hazard_regions) if domain is not None else ()
    took = []
    for step in steps:
        at = time.time_ns()
        start = time.perf_counter()
        if probe.hazards is not None:
            probe.hazards.publish(hazards_message(hazards, step.hazard, at))
        probe.health.publish(health_message(step.health, at))
        gait = probe.gait(timeout=30)
        took.append((time.perf_counter() - start) * 1000)
        if gait != step.gait:
            raise SystemExit(f"{spec.name}: the node ran {gait}, the simulation {step.gait}")
    return took


def in_process(spec: Path, control: Path, steps: list[Any]) -> list[float]:
    bound = session(gaitc.load(spec), str(control))
    assert bound is not None
    from gaitc.api.ros import _primitives

    with Graph() as graph:
        node = ControllerNode(graph, bound.strategy, bound.domain, bound.monitor,
                              _primitives(bound.spec), NodeOptions(rate=0.0, watchdog=30.0,
                                                                   steps=len(steps) - 1))
        probe = Probe(graph, hazards=bool(bound.domain.hazard_regions))
        runner = threading.Thread(target=node.run, daemon=True)
        runner.start()
        assert probe.connected()
        took = play(probe, spec, steps)
        runner.join(timeout=10)
    return took


def own_process(spec: Path, control: Path, steps: list[Any]) -> list[float]:
    proc = subprocess.Popen([sys.executable, "-m", "gaitc", "ros", str(spec), str(control),
                             "--rate", "0", "--watchdog", "30", "--steps",
                             str(len(steps) - 1)], stdout=subprocess.DEVNULL,
                            stderr=subprocess.PIPE, text=True)
    try:
        assert proc.stderr is not None
        while "ready:" not in proc.stderr.readline():
            if proc.poll() is not None:
                raise SystemExit(f"gaitc ros ended: {proc.stderr.read()}")
        with Graph() as graph:
            hazards = bool(gaitc.load(spec).robot.hazards)
            probe = Probe(graph, hazards=hazards)
            assert probe.connected()
            return play(probe, spec, steps)
    finally:
        if proc.poll() is None:
            proc.send_signal(signal.SIGINT)
        proc.communicate(timeout=10)


def row(spec: Path, form: str, where: str, took: list[float]) -> str:
    ordered = sorted(took)
    p99 = ordered[min(len(ordered) - 1, int(0.99 * len(ordered)))]
    return (f"| {spec.stem} | {form} | {where} | {len(took)} | {statistics.median(took):.2f} "
            f"| {p99:.2f} | {ordered[-1]:.2f} |")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="100 steps a row")
    parser.add_argument("--steps", type=int, default=1000, help="steps a row (1000)")
    args = parser.parse_args()
    count = 100 if args.quick else args.steps
    print("| spec | controller | node | steps | median ms | p99 ms | worst ms |")
    print("|---|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as folder:
        for spec in (ROBOT_A, RADIAL8):
            control = controller(spec, Path(folder))
            symbolic = Path(folder) / f"{spec.stem}.symbolic.json"
            made = gaitc.synthesize(gaitc.load(spec), form="symbolic")
            made.save(symbolic)
            steps = steps_of(spec, control, count)
            print(row(spec, "explicit", "in process", in_process(spec, control, steps)),
                  flush=True)
            print(row(spec, "explicit", "own process", own_process(spec, control, steps)),
                  flush=True)
            steps = steps_of(spec, symbolic, count)  # the symbolic form may choose otherwise
            print(row(spec, "symbolic", "in process", in_process(spec, symbolic, steps)),
                  flush=True)


if __name__ == "__main__":
    main()
