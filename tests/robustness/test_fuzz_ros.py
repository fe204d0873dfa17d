"""Fuzz kind ``ros`` (issue 62): malformed and out-of-range observations sent to the
controller node, CI size.  At least 1,000 bad ones go to the node's callbacks in-process
(:func:`fuzz_ros.exchange`) and a smaller slice over a real ROS 2 graph; the node never
raises, and vents exactly for the bad ones.  ``bench/fuzz.py --kinds ros`` is the long mode.
"""

from __future__ import annotations

import random
import time
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest
from fuzz_mutate import mutate
from fuzz_ros import EXCHANGES, Oracle, Tally, exchange, message, parse
from ros_graph import MISSING, ROBOT_A, Probe, ros_domain, ros_environment

__all__ = ["ros_domain"]

pytestmark = [pytest.mark.ros,
              pytest.mark.skipif(MISSING is not None, reason=f"{MISSING}")]
BAD_WANTED = 1000  # bad observations the in-process slice sends, at least


def node_of(spec: Path, graph: Any) -> Any:
    import gaitc
    from gaitc.api.simulation import session
    from gaitc.ros.node import ControllerNode, NodeOptions

    bound = session(gaitc.load(spec), None)
    assert bound is not None
    return ControllerNode(graph, bound.strategy, bound.domain, bound.monitor, None,
                          NodeOptions(rate=0.0, stale_after=1.0), spec_file=str(spec))


@pytest.fixture()
def graph(ros_domain: dict[str, str]) -> Iterator[Any]:
    from gaitc.ros.graph import Graph

    with Graph() as made:
        yield made


@pytest.fixture(scope="module")
def robot_a_node() -> Iterator[Any]:
    """Robot A's controller node (8 legs, hazard sets blue and red: the seeds' names), in a
    graph of the module's own, in a second domain (the real-graph slice must not hear its
    vents); its callbacks are called directly."""
    from gaitc.ros.graph import Graph

    with pytest.MonkeyPatch.context() as patch:
        for key, value in ros_environment(second=True).items():
            patch.setenv(key, value)
        with Graph() as made:
            yield node_of(ROBOT_A, made)


def test_the_seeds_are_good_and_bad_as_written(robot_a_node: Any) -> None:
    node = robot_a_node
    tally = Tally()
    for name, data in EXCHANGES:
        verdict = exchange(data, node, tally)
        assert not verdict.problems, (name, verdict.problems)
    # start and worn are good throughout; order's last reading is older than its first
    # pair; odd has one stamped 2 s ahead and one 3 s old
    assert (tally.messages, tally.bad, tally.vents) == (13, 3, 3)


def test_a_thousand_bad_observations_never_crash_the_node_and_each_vents(robot_a_node: Any
                                                                         ) -> None:
    node = robot_a_node
    tally = Tally()
    rng = random.Random(62)
    seeds = [d for _, d in EXCHANGES]
    problems: list[str] = []
    mutants = 0
    while tally.bad < BAD_WANTED and mutants < 20 * BAD_WANTED:
        data = mutate(seeds[rng.randint(0, len(seeds) - 1)], rng, seeds)
        mutants += 1
        verdict = exchange(data, node, tally, limit=5.0)
        problems.extend(f"{data!r}: {p}" for p in verdict.problems)
    assert not problems, problems[:5]
    assert tally.bad >= BAD_WANTED and tally.vents == tally.bad
    assert tally.messages > tally.bad  # good ones were among them, and not vented


def test_bad_observations_over_a_real_graph_each_vent(graph: Any) -> None:
    """The slice over real topics: a test node publishes mutant ``leg_health`` messages of
    the 2 x 2 patrol robot (four legs, no hazard sets) to the controller node, each once
    the one before was handled (as a robot senses once a step)."""
    from gaitc.ros.graph import wait_until

    node = node_of(ROBOT_A.parent / "patrol_2x2.gait", graph)
    probe = Probe(graph, hazards=False)
    assert probe.connected()
    oracle = Oracle(node.domain.full, ())
    rng = random.Random(7)
    seed = b"leg_health +0 L1=2 L2=2 L3=2 L4=2\n"
    sent = bad = 0
    while sent < 60:
        for seen in parse(mutate(seed, rng, [seed])):
            if seen.topic != "leg_health":
                continue
            now = time.time_ns()
            built, at = message(seen, now)
            bad += oracle.bad(seen, at, now)
            probe.health.publish(built)
            sent += 1
            assert wait_until(lambda done=sent: node.taken == done, 5.0), (node.taken, sent)
    assert bad > 0 and node.vents == bad
    gaits = []
    while not probe.gaits.empty():
        gaits.append(probe.gait())
    assert gaits.count("noGait") == bad  # each vent reached the robot's side
