"""The saboteur: a simulated robot that surprises its controller (``drive --violate``,
``--on-violation recover``): it reads the driver's controller, not a copy of it, and
performs planned events.

:class:`~gaitc.hw.simulated.SimulatedRobot` shadows the controller it was built with; after
a surprise the driver goes on with a fallback strategy (:mod:`gaitc.sim.recovery`, after
Ehlers and Topcu, HSCC 2014), which that copy does not know.  :class:`SurprisingRobot` is
told the driver's situation before each reading (:class:`gaitc.hw.driver.Follower`), so its
environment chooses among the moves of the controller the driver runs now, and at a step of
``planned`` it performs the event whatever the assumptions say: the legs' levels and the
hazard change as the event says, the rest of the reading is a move the assumptions allow
(:func:`gaitc.sim.events.performed`, as ``simulate --violate`` does) and the robot stays
where the last gait took it.
"""

from __future__ import annotations

from collections.abc import Mapping

from gaitc.hw.backend import SensorReading, where
from gaitc.hw.simulated import ScenarioFinished, SimulatedRobot
from gaitc.sim.domain import Domain
from gaitc.sim.environments import Environment, Situation
from gaitc.sim.events import Event, performed
from gaitc.sim.monitor import Monitor
from gaitc.sim.strategy import StrategyView


class SurprisingRobot(SimulatedRobot):
    """A simulated robot that follows the driver's situation and performs ``planned``
    events (by step, counted as the run's steps: reading k is step k)."""

    def __init__(self, strategy: StrategyView, domain: Domain, monitor: Monitor,
                 environment: Environment, valve_count: int,
                 planned: Mapping[int, Event] | None = None) -> None:
        super().__init__(strategy, domain, monitor, environment, valve_count)
        self.planned = dict(planned or {})
        self._situation: Situation | None = None
        self._performed: dict[int, Event] = {}

    def situate(self, situation: Situation) -> None:
        self._situation = situation

    def performed(self, step: int) -> Event | None:
        return self._performed.get(step)

    def read_sensors(self) -> SensorReading:
        situation = self._situation
        if situation is None:  # not driven by a follower's driver: the shadow of the base
            return super().read_sensors()
        self._situation = None
        here = situation.state
        region = self.domain.model.start if here is None else here.region
        event = self.planned.get(situation.step) if here is not None else None
        if event is not None and here is not None:
            after, _ = performed(event, here, [m.state for m in situation.moves], self.domain)
            self._performed[situation.step] = event
            reading = SensorReading(after.health, after.hazard, region)
        else:
            request = self.environment.choose(situation)
            if request is None:
                raise ScenarioFinished("the simulated environment has no more steps",
                                       where(self.name))
            move = next((m for m in situation.moves if m.inputs == request.inputs), None)
            if move is not None:
                sensed = move.state
            else:  # an input the controller refuses (a scenario breaking a rule)
                strategy = self.view.strategy
                values = situation.values
                base = (dict(zip(strategy.variables, values, strict=True)) if values is not None
                        else strategy.valuation(strategy.initial[0]))
                base.update(zip(strategy.inputs, request.inputs, strict=True))
                sensed = self.domain.decode(base)
            reading = SensorReading(sensed.health, sensed.hazard, region)
        self._step += 1
        self.readings.append(reading)
        return reading
