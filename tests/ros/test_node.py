"""The controller node in a real ROS 2 graph: ``gaitc ros SPEC CONTROLLER`` in a process of
its own, and a test node in this one that plays the robot.  A bad observation (an unknown
leg, a level out of range, a stale stamp), a silent robot (the watchdog) and SIGINT/SIGTERM
each stop the node with every valve vented (the no-gait, the reason on /diagnostics),
without a traceback; a signal within a second (issue 62)."""

from __future__ import annotations

import os
import re
import signal
import subprocess
import sys
import time
from collections.abc import Iterator
from pathlib import Path

import pytest
from ros_graph import ROBOT_A, Probe, controller, ros_domain

import gaitc
from gaitc.ros.graph import Graph
from gaitc.ros.topics import hazards_message, health_message

__all__ = ["ros_domain"]


@pytest.fixture(scope="module")
def robot_a(tmp_path_factory: pytest.TempPathFactory) -> Path:
    return controller(ROBOT_A, tmp_path_factory.mktemp("controllers"))


@pytest.fixture(scope="module")
def start_state(robot_a: Path) -> tuple[tuple[tuple[str, int], ...], str | None]:
    """The legs' levels and the hazard of a run's first step (an allowed first input)."""
    first = gaitc.simulate(ROBOT_A, robot_a, steps=1).steps[0]
    return first.health, first.hazard


class Node:
    """``gaitc ros`` as a child process (SIGINT at its default), ended by the test."""

    def __init__(self, argv: list[str], env: dict[str, str]) -> None:
        self.proc = subprocess.Popen(
            [sys.executable, "-m", "gaitc", "ros", *argv], env={**os.environ, **env},
            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
            preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))

    def ready(self) -> str:
        """Wait for the node's 'ready' log line (its participant is up: a test node made
        after it is discovered at once); the lines before it."""
        assert self.proc.stderr is not None
        lines = []
        while self.proc.poll() is None:
            line = self.proc.stderr.readline()
            lines.append(line)
            if "ready: waiting for observations on /leg_health, /hazards" in line:
                break
        return "".join(lines)

    def finish(self, timeout: float) -> tuple[int, str, str]:
        out, err = self.proc.communicate(timeout=timeout)
        return self.proc.returncode, out, err

    def end(self) -> None:
        if self.proc.poll() is None:
            self.proc.kill()
            self.proc.communicate()


@pytest.fixture()
def graph(ros_domain: dict[str, str]) -> Iterator[list[Graph]]:
    """The test's graph, made by :func:`started` once the node is ready."""
    made: list[Graph] = []
    yield made
    for graph in made:
        graph.close()


def started(robot_a: Path, graph: list[Graph], env: dict[str, str], *options: str
            ) -> tuple[Node, Probe]:
    node = Node([str(ROBOT_A), str(robot_a), "--rate", "0", *options], env)
    before = node.ready()
    assert "Traceback" not in before, before
    graph.append(Graph())
    probe = Probe(graph[0])
    if not probe.connected(20.0):
        node.end()
        pytest.fail(f"the controller node did not subscribe: {node.finish(5)}")
    return node, probe


def observe(probe: Probe, health: tuple[tuple[str, int], ...], hazard: str | None,
            at: int | None = None) -> None:
    stamp = time.time_ns() if at is None else at
    assert probe.hazards is not None
    probe.hazards.publish(hazards_message(("blue", "red"), hazard, stamp))
    probe.health.publish(health_message(health, stamp))


BAD = {  # the change, the stamp's shift (s), the message (a pattern)
    "unknown leg": (lambda h: (*h[:-1], ("L9", 3)), 0.0,
                    re.escape("leg_health: unknown leg 'L9'; the spec has L1, L2, L3, L4, L5, "
                              "L6, L7, L8")),
    "level out of range": (lambda h: (*h[:-1], (h[-1][0], 7)), 0.0,
                           re.escape("leg_health: leg L8 has health level 7, outside 1..3")),
    # both messages are stale; either may arrive first (two topics keep no order between them)
    "stale stamp": (lambda h: h, -5.0,
                    r"(hazards|leg_health): stale reading, stamped 5\.\d+ s ago \(more than 1 s\)"),
}


@pytest.mark.parametrize("kind", sorted(BAD))
def test_a_bad_observation_is_reported_and_every_valve_vented(
        kind: str, robot_a: Path, graph: list[Graph], ros_domain: dict[str, str],
        start_state: tuple[tuple[tuple[str, int], ...], str | None]) -> None:
    node, probe = started(robot_a, graph, ros_domain)
    try:
        health, hazard = start_state
        observe(probe, health, hazard)
        probe.gait()  # step 0's (robot A starts with the no-gait)
        assert probe.step(0) is not None
        change, shift, words = BAD[kind]
        observe(probe, change(health), hazard, time.time_ns() + int(shift * 1e9))
        assert probe.gait() == "noGait"
        stopped = probe.stopped()
        assert stopped is not None and stopped.level == 2
        assert re.match(f"bad observation: {words}", stopped.message), stopped.message
        code, out, err = node.finish(10)
    finally:
        node.end()
    assert code == 1, err
    assert "Traceback" not in err and re.search(f"gaitc: error: {words}", err), err
    assert "node: bad observation" in out


def test_the_watchdog_stops_a_node_whose_robot_went_silent(
        robot_a: Path, graph: list[Graph], ros_domain: dict[str, str],
        start_state: tuple[tuple[tuple[str, int], ...], str | None]) -> None:
    node, probe = started(robot_a, graph, ros_domain, "--watchdog", "0.5")
    try:
        observe(probe, *start_state)
        probe.gait()
        assert probe.step(0) is not None
        assert probe.gait(timeout=5) == "noGait"
        stopped = probe.stopped()
        assert stopped is not None and stopped.message.startswith(
            "watchdog: no observation for 0.5 s"), stopped.message
        code, _, err = node.finish(10)
    finally:
        node.end()
    assert code == 1 and "gaitc: error: watchdog: no observation for 0.5 s" in err, err


@pytest.mark.parametrize("signum", [signal.SIGTERM, signal.SIGINT], ids=["SIGTERM", "SIGINT"])
def test_a_signal_vents_and_ends_the_node_within_a_second(
        signum: signal.Signals, robot_a: Path, graph: list[Graph], ros_domain: dict[str, str],
        start_state: tuple[tuple[tuple[str, int], ...], str | None]) -> None:
    node, probe = started(robot_a, graph, ros_domain)
    try:
        observe(probe, *start_state)
        probe.gait()
        assert probe.step(0) is not None
        sent = time.monotonic()
        node.proc.send_signal(signum)
        code, out, err = node.finish(5)
        took = time.monotonic() - sent
        assert probe.gait(timeout=2) == "noGait"
    finally:
        node.end()
    assert code == 0, err
    assert took < 1.0, f"the node took {took:.2f} s to end"
    stopped = probe.stopped()
    assert stopped is not None and stopped.message == (
        f"interrupted ({signum.name}); stopped with every valve vented")
    assert "Traceback" not in err and "interrupted" in out
