"""The robot of the chapter 4 physics backend as the online loop's walker.

Each valve state the loop applies is held for one control period in the spring-damper model
(thesis 4.1.1, :mod:`gaitc.models`), continuing from wherever the last one left the robot; the
measured motion of a transition is the model's chassis motion in the body frame of the pose
before it, plus Gaussian noise standing for the pose estimate (the EKF of chapter 4).  The
predictions of the model gait graph start every transition from a steady state (4.2.2), so
what the walker measures differs from them as a real gait's transitions would.  With a model
mismatch the walker executes a robot whose stiffness and friction differ from the file's
(:func:`~gaitc.search.perturbation.perturbed`), so that the loop has something to learn.
"""

from __future__ import annotations

import math

import numpy as np

from gaitc.hw.backend import Backend, HardwareError, SensorReading, where
from gaitc.models.motion import LoadedModel
from gaitc.models.spring_damper.model import SpringDamperModel, State
from gaitc.search.perturbation import perturbed
from gaitc.search.transitions import Step, TransitionModel
from gaitc.search.walker import Outcome


class PhysicsWalker(Backend):
    """Valve states through the spring-damper model; poses are the model graph's states."""

    def __init__(
        self,
        model: TransitionModel,
        start: int,
        loaded: LoadedModel,
        noise: float = 0.0,
        seed: int = 0,
        mismatch: float = 0.0,
    ) -> None:
        super().__init__(len(loaded.valve_legs))
        if not isinstance(loaded.model, SpringDamperModel):
            raise HardwareError(
                f"the physics walker needs the spring-damper model, not {loaded.model.name}",
                where("physics walker"),
            )
        self.physics: SpringDamperModel = loaded.model
        if mismatch:
            robot = perturbed(loaded.model.robot, mismatch, seed)
            self.physics = SpringDamperModel(robot, loaded.model.dt)
        self.model, self.start, self.period = model, start, loaded.period
        self.name = f"physics model ({self.physics.name}) of {loaded.robot}"
        self.legs = tuple(dict.fromkeys(loaded.valve_legs))
        self.sigma = noise
        self.noise = np.random.default_rng(seed + 1)
        self.index = {label: i for i, label in enumerate(model.labels)}
        self.state: State | None = None
        self.pose = start
        self.last: Outcome | None = None
        self.applied: list[str] = []
        self.transitions = 0  # valve states run through the model

    def open(self) -> None:
        """The robot set down at rest with every valve vented."""
        self.state = self.physics.steady_state((False,) * self.valve_count)
        self.pose = self.start

    def close(self) -> None:
        self.state = None

    def wait(self, seconds: float) -> None:
        del seconds  # simulated time: each valve state is held for one control period

    def reset(self) -> None:
        """Back to the rest valve state; the robot stays where it is (it keeps walking)."""
        if self.pose != self.start:
            self._hold(self.model.labels[self.start])
            self.pose = self.start
        self.last = None

    def _hold(self, valves: str) -> tuple[float, float, float]:
        if self.state is None:
            raise HardwareError("the physics walker is not open", where(self.name))
        before = self.state.pose()
        self.state = self.physics.run(self.state, [tuple(c == "1" for c in valves)], self.period)
        self.transitions += 1
        moved = before.inverse().compose(self.state.pose())
        return moved.x, moved.y, math.degrees(moved.theta)

    def apply(self, valves: str) -> None:
        self.check_valves(valves)
        self.applied.append(valves)
        target = self.index.get(valves)
        edge = None if target is None else self.model.find(self.pose, target)
        dx, dy, rot = self._hold(valves)
        if edge is None or target is None:  # a valve state outside the searched graph
            self.last = Outcome(None, self.pose, None)
            return
        if self.sigma > 0:
            jitter = self.noise.normal(0.0, self.sigma, size=3)
            dx, dy, rot = dx + float(jitter[0]), dy + float(jitter[1]), rot + float(jitter[2])
        self.pose = target
        self.last = Outcome(edge, target, Step(dx, dy, rot))

    def read_sensors(self) -> SensorReading:
        """The model has no health sensing: every leg reads healthy (level 2)."""
        return SensorReading(tuple((leg, 2) for leg in self.legs), None, None)
