"""The simulated robot, the default backend: instant valves, sensors from a gaitsim environment.

The robot shadows the controller: at each sensor reading a gaitsim environment (random,
adversarial or scripted) picks the next health levels and hazard among the inputs the
controller accepts, so the readings obey the spec's assumptions; the region follows the
controller's chosen move (the gait succeeds).  Every applied valve state is recorded.
"""

from __future__ import annotations

import time

from gaitc.hw.backend import Backend, HardwareError, SensorReading, where
from gaitc.sim.domain import Domain, Goal, State
from gaitc.sim.environments import Environment, Move
from gaitc.sim.monitor import Monitor
from gaitc.sim.simulator import Simulator
from gaitc.sim.strategy import StrategyView


class ScenarioFinished(HardwareError):
    """The simulated robot's scripted environment has no more steps."""


class SimulatedRobot(Backend):
    """A robot that obeys the spec's assumptions, driven by a gaitsim environment."""

    name = "simulated robot"

    def __init__(self, strategy: StrategyView, domain: Domain, monitor: Monitor,
                 environment: Environment, valve_count: int) -> None:
        super().__init__(valve_count)
        self.view = Simulator(strategy, domain, monitor)
        self.domain = domain
        self.environment = environment
        self.name = f"simulated robot, {environment.name}"
        self.applied: list[str] = []  # every valve state, in order
        self.readings: list[SensorReading] = []
        self.is_open = False
        self._node: int | None = None  # the controller node the robot believes it is in
        self._step = 0
        self._goal = 0  # index of the goal the robot is heading for, as the simulator tracks

    def open(self) -> None:
        self.is_open = True

    def close(self) -> None:
        if self.is_open:
            self.applied.append(self.vented)
        self.is_open = False

    def apply(self, valves: str) -> None:
        if not self.is_open:
            raise HardwareError("the simulated robot is not open", where(self.name))
        self.check_valves(valves)
        self.applied.append(valves)

    def wait(self, seconds: float) -> None:
        if seconds > 0:
            time.sleep(seconds)

    def read_sensors(self) -> SensorReading:
        node = self._node
        here = None if node is None else self.view.state(node)
        region = self.domain.model.start if here is None else here.region
        situation = self.view.situation(self._step, node, self._next_goal())
        moves = situation.moves
        request = self.environment.choose(situation)
        if request is None:
            raise ScenarioFinished("the simulated environment has no more steps",
                                   where(self.name))
        move = next((m for m in moves if m.inputs == request.inputs), None)
        sensed = self._requested(node, request.inputs) if move is None else move.state
        self._node = None if move is None else move.node
        if move is not None:
            self._advance_goal(move.state, here)
        self._step += 1
        reading = SensorReading(sensed.health, sensed.hazard, region)
        self.readings.append(reading)
        return reading

    def accepted(self, move: Move) -> None:
        self._node = move.node  # the driver may stand a move in for a refused reading

    def _next_goal(self) -> Goal | None:
        goals = self.domain.goals
        return goals[self._goal % len(goals)] if goals else None

    def _advance_goal(self, state: State, previous: State | None) -> None:
        goal = self._next_goal()
        if goal is not None and goal.label in self.domain.goals_reached(state, previous):
            self._goal += 1

    def _requested(self, node: int | None, inputs: tuple[int, ...]) -> State:
        """The state an input the controller refuses asks for (a scenario breaking a rule)."""
        strategy = self.view.strategy
        base = strategy.valuation(node if node is not None else strategy.initial[0])
        base.update(zip(strategy.inputs, inputs, strict=True))
        return self.domain.decode(base)

