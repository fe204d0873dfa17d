"""The simulated robot as a ROS 2 node beside the controller node (``gaitc ros --sim``): it
plays the environment of ``simulate`` (random, adversarial or scripted, with planned
``--violate`` events) and talks to the controller only through the topics.

Like :class:`~gaitc.hw.simulated.SimulatedRobot`, it steps a copy of the controller, so that
its environment sees what ``simulate``'s does (the moves the controller has, and after a
surprise those of the fallback strategy, :mod:`gaitc.sim.recovery`); each step it publishes
the legs' levels and the hazard of that step, waits for the controller node's gait and
checks it against its copy's.  The controller node decides on its own, from the messages.
"""

from __future__ import annotations

import queue
import time
from collections import Counter
from collections.abc import Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from gaitc.core.modes import SurprisePolicy
from gaitc.hw.backend import HardwareError
from gaitc.ir.spec import Semantics
from gaitc.ros.graph import wait_until
from gaitc.ros.topics import (
    DIAGNOSTICS,
    ERROR,
    GAIT,
    HAZARDS,
    LEG_HEALTH,
    hazards_message,
    health_message,
    qos,
    status_of,
)
from gaitc.sim.domain import Domain, State
from gaitc.sim.environments import Environment
from gaitc.sim.events import Event
from gaitc.sim.jumps import forced
from gaitc.sim.monitor import Monitor
from gaitc.sim.recovery import Fallback
from gaitc.sim.run import Run
from gaitc.sim.simulator import Simulator, SurpriseOptions, Verdicts

if TYPE_CHECKING:
    from gaitc.ros.graph import Graph
    from gaitc.sim.strategy import StrategyView


@dataclass(frozen=True)
class RobotOptions:
    """How the simulated robot runs: the events it performs whatever the assumptions say
    (by step); the recovery games (shared with the controller node, which then finds each
    game the robot's copy solved; None: its own); the controller's policy and semantics
    after a surprise (its copy follows the controller node); how long it waits for each
    gait (s); its node's name."""

    planned: Mapping[int, Event]
    games: Fallback | None = None  # recovery games shared with the controller node
    on_surprise: SurprisePolicy = SurprisePolicy.RECOVER
    semantics: Semantics = Semantics.DEFAULT
    wait: float = 5.0
    name: str = "gaitc_sim_robot"


class ControllerStopped(Exception):
    """The controller node reported that it stopped (on /diagnostics): the robot stops too."""


class RobotNode:
    """The simulated robot in ``graph``: publishes observations, subscribes to the gait."""

    def __init__(self, graph: Graph, strategy: StrategyView, domain: Domain, monitor: Monitor,
                 environment: Environment, options: RobotOptions, spec_file: str = "") -> None:
        # lazy: the ros extra (rclpy) may be missing; gaitc ros then names the extra
        from rclpy.node import Node

        self.strategy, self.domain, self.monitor = strategy, domain, monitor
        self.environment = environment
        self.options = options
        self.spec_file = spec_file
        self.node = node = Node(options.name, context=graph.context)
        self.health = node.create_publisher(LEG_HEALTH.message_class, LEG_HEALTH.name,
                                            qos(LEG_HEALTH))
        self.hazards = (node.create_publisher(HAZARDS.message_class, HAZARDS.name, qos(HAZARDS))
                        if domain.hazard_regions else None)
        self.gait_subscription = node.create_subscription(GAIT.message_class, GAIT.name,
                                                          self._on_gait, qos(GAIT))
        node.create_subscription(DIAGNOSTICS.message_class, DIAGNOSTICS.name,
                                 self._on_diagnostics, qos(DIAGNOSTICS))
        self._gaits: queue.Queue[str] = queue.Queue()
        self.controller_stopped = ""  # what the controller said when it stopped
        self.note = ""  # how the robot's run ended, in words
        self.sent: Counter[str] = Counter()  # messages published, by topic
        self._last_stamp = 0
        graph.add(node)

    def _on_gait(self, message: Any) -> None:
        self._gaits.put(str(message.data))

    def _on_diagnostics(self, message: Any) -> None:
        status = status_of(message)
        if status is not None and status.level == ERROR and status.value("stopped"):
            self.controller_stopped = status.message

    def connected(self) -> bool:
        """Whether the controller node subscribes to the observations and publishes gaits."""
        ready = self.health.get_subscription_count() > 0 and (
            self.hazards is None or self.hazards.get_subscription_count() > 0)
        return ready and self.gait_subscription.get_publisher_count() > 0

    def observe(self, index: int, state: State) -> None:
        """Publish step ``index``'s observation of ``state``, then wait for the controller's
        gait of that step and check it."""
        self.publish(state)
        gait = self._next_gait()
        if gait != state.gait:
            raise HardwareError(f"step {index}: the controller node commanded gait {gait}, "
                                f"but the simulated robot's copy of the controller runs "
                                f"{state.gait}")

    def publish(self, state: State) -> None:
        """Publish the observation of ``state`` (the hazards first, with the same stamp)."""
        at = max(time.time_ns(), self._last_stamp + 1)
        self._last_stamp = at
        if self.hazards is not None:
            self.hazards.publish(hazards_message(tuple(self.domain.hazard_regions),
                                                 state.hazard, at))
            self.sent[HAZARDS.name] += 1
        self.health.publish(health_message(state.health, at))
        self.sent[LEG_HEALTH.name] += 1

    def _next_gait(self) -> str:
        end = time.monotonic() + self.options.wait
        while True:
            try:
                return self._gaits.get(timeout=0.02)
            except queue.Empty:
                if self.controller_stopped:
                    raise ControllerStopped(self.controller_stopped) from None
                if time.monotonic() > end:
                    raise HardwareError(f"the controller node sent no gait in "
                                        f"{self.options.wait:g} s") from None

    def run(self, steps: int, connect: float = 15.0) -> Run | None:
        """Play ``steps`` steps against the controller node (after waiting up to ``connect``
        s for it); the copy's run, or None when the controller stopped first."""
        if not wait_until(self.connected, connect):
            raise HardwareError(f"the controller node did not appear in {connect:g} s")
        opts = self.options
        surprises = SurpriseOptions(dict(opts.planned), opts.on_surprise, opts.semantics,
                                    opts.games)
        copy = _Copy(self, self.strategy, self.domain, self.monitor)
        try:
            run = copy.run(self.environment, steps, self.spec_file, surprises)
        except ControllerStopped as stopped:
            self.note = f"the controller node stopped: {stopped}"
            return None
        if run.error is not None and run.steps:
            # the stop policy refused an event: the robot performed it all the same
            step = len(run.steps)
            event = opts.planned.get(step)
            if event is not None:
                last = run.steps[-1].node
                request = forced(copy, last, event)
                self.publish(copy.after(last, dict(zip(copy.strategy.inputs, request.inputs,
                                                       strict=True))))
                self.note = (f"performed '{event.words}' at step {step}, which breaks an "
                             f"assumption; the controller stops (--on-surprise stop)")
                return run
        self.note = f"played {max(0, len(run.steps) - 1)} steps"
        return run


class _Copy(Simulator):
    """The robot's copy of the controller: each step checked is observed by the robot."""

    def __init__(self, owner: RobotNode, strategy: StrategyView, domain: Domain,
                 monitor: Monitor) -> None:
        super().__init__(strategy, domain, monitor)
        self.owner = owner

    def observe(self, verdicts: Verdicts, index: int, before: tuple[int, ...] | None,
                values: tuple[int, ...]) -> None:
        super().observe(verdicts, index, before, values)
        state = self.domain.decode(dict(zip(self.monitor.variables, values, strict=True)))
        self.owner.observe(index, state)
