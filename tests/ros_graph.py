"""What the ROS 2 tests share: the skip without the ``ros`` extra, a ROS domain of each
test process's own with discovery kept on this machine, the specs' controllers, and a
test node that publishes observations and listens to the controller's topics."""

from __future__ import annotations

import os
import queue
import time
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

import gaitc
from gaitc.diagnostics import UsageError

ROOT = Path(__file__).resolve().parent.parent
ROBOT_A = ROOT / "specs" / "thesis_robot_a.gait"  # 8 legs, hazard sets blue and red
RADIAL8 = ROOT / "specs" / "radial8_patrol.gait"  # 8 legs, gaits bound to valve primitives


def missing_extra() -> str | None:
    """Why the ROS 2 tests cannot run here (the ros extra is missing), or None."""
    from gaitc.ros.topics import require

    try:
        require()
    except UsageError as err:
        return err.message
    return None


MISSING = missing_extra()
needs_ros = pytest.mark.skipif(MISSING is not None, reason=f"{MISSING}")


def domain_id(second: bool = False) -> int:
    """A ROS domain of this test process's own: 60 + the xdist worker's number (gw3: 63),
    59 without xdist, so that workers running at once never hear each other; ``second``:
    another one, 20 higher, for a graph that must not hear the first."""
    worker = os.environ.get("PYTEST_XDIST_WORKER", "")
    first = 60 + int(worker[2:]) if worker.startswith("gw") and worker[2:].isdigit() else 59
    return first + 20 if second else first


def ros_environment(second: bool = False) -> dict[str, str]:
    """The environment variables that keep a ROS 2 graph on this machine, in its domain."""
    return {"ROS_DOMAIN_ID": str(domain_id(second)),
            "ROS_AUTOMATIC_DISCOVERY_RANGE": "LOCALHOST"}


@pytest.fixture()
def ros_domain(monkeypatch: pytest.MonkeyPatch) -> Iterator[dict[str, str]]:
    """This process's domain and localhost discovery, for in-process nodes and children."""
    env = ros_environment()
    for key, value in env.items():
        monkeypatch.setenv(key, value)
    yield env


def controller(spec: Path, folder: Path) -> Path:
    """A controller of ``spec`` synthesized into ``folder`` (not proved again: the tests
    that prove controllers are elsewhere)."""
    made = gaitc.synthesize(gaitc.load(spec), verify=False)
    assert made.controller is not None
    path = folder / f"{spec.stem}.controller.json"
    made.save(path)
    return path


class Probe:
    """A test node in ``graph``: publishes observations and collects the controller's gaits
    and /diagnostics statuses."""

    def __init__(self, graph: Any, hazards: bool = True) -> None:
        from rclpy.node import Node

        from gaitc.ros.topics import DIAGNOSTICS, GAIT, HAZARDS, LEG_HEALTH, qos, status_of

        self.node = Node("gaitc_test_probe", context=graph.context)
        self.health = self.node.create_publisher(LEG_HEALTH.message_class, LEG_HEALTH.name,
                                                 qos(LEG_HEALTH))
        self.hazards = (self.node.create_publisher(HAZARDS.message_class, HAZARDS.name,
                                                   qos(HAZARDS)) if hazards else None)
        self.gaits: queue.Queue[str] = queue.Queue()
        self.statuses: list[Any] = []
        self.node.create_subscription(GAIT.message_class, GAIT.name,
                                      lambda m: self.gaits.put(m.data), qos(GAIT))
        self.node.create_subscription(
            DIAGNOSTICS.message_class, DIAGNOSTICS.name,
            lambda m: self.statuses.append(status_of(m)), qos(DIAGNOSTICS))
        graph.add(self.node)

    def connected(self, timeout: float = 10.0) -> bool:
        from gaitc.ros.graph import wait_until

        return wait_until(lambda: self.health.get_subscription_count() > 0 and (
            self.hazards is None or self.hazards.get_subscription_count() > 0), timeout)

    def gait(self, timeout: float = 5.0) -> str:
        return self.gaits.get(timeout=timeout)

    def step(self, index: int, timeout: float = 5.0) -> Any:
        """The status of step ``index`` (waiting up to ``timeout`` s), or None."""
        return self._first(lambda s: s.value("step") == str(index) and not s.value("stopped"),
                           timeout)

    def stopped(self, timeout: float = 5.0) -> Any:
        """The first status that says the controller stopped (waiting up to ``timeout`` s)."""
        return self._first(lambda s: bool(s.value("stopped")), timeout)

    def _first(self, wanted: Any, timeout: float) -> Any:
        end = time.monotonic() + timeout
        while time.monotonic() < end:
            found = next((s for s in list(self.statuses) if s is not None and wanted(s)), None)
            if found is not None:
                return found
            time.sleep(0.01)
        return None
