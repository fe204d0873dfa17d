"""Types shared by the chapter 4 models: chassis pose, valve state, the motion-model protocol.

A model predicts how the chassis moves when the valves switch from one state to another
and are held for one control period (thesis 4.2.2, "Generating the gait graph"): the
answer is a planar rigid motion in the body frame of the chassis at the start.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Protocol

ValveState = tuple[bool, ...]
"""One entry per valve/leg, in the robot file's leg order; True means pressurised."""


@dataclass(frozen=True)
class Pose2D:
    """Chassis pose in the world frame: position in mm, heading in radians."""

    x: float
    y: float
    theta: float

    def compose(self, other: Pose2D) -> Pose2D:
        """This pose followed by ``other``, which is given in this pose's body frame."""
        c, s = math.cos(self.theta), math.sin(self.theta)
        return Pose2D(
            self.x + c * other.x - s * other.y,
            self.y + s * other.x + c * other.y,
            self.theta + other.theta,
        )

    def inverse(self) -> Pose2D:
        """The motion that undoes this one: ``p.compose(p.inverse())`` is the identity."""
        c, s = math.cos(self.theta), math.sin(self.theta)
        return Pose2D(-(c * self.x + s * self.y), s * self.x - c * self.y, -self.theta)


IDENTITY = Pose2D(0.0, 0.0, 0.0)


class MotionModel(Protocol):
    """A model that predicts the chassis motion of one valve transition."""

    name: str

    def transition(self, start: ValveState, end: ValveState, period_s: float) -> Pose2D:
        """Body-frame chassis displacement when the valves switch from ``start`` to ``end``.

        The robot starts at rest in ``start``'s steady state; ``end`` is held ``period_s``
        seconds.
        """
        ...


@dataclass(frozen=True)
class LoadedModel:
    """A model of one robot file, with what the searches need to know of the robot."""

    model: MotionModel
    robot: str
    valve_legs: tuple[str, ...]  # the leg owning each valve
    period: float  # s, the control period from the robot file
    body_length: float  # mm, for ranking rotation against translation
