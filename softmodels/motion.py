"""The interface every chapter 4 motion model offers: chassis poses and valve transitions."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Protocol


@dataclass(frozen=True)
class Pose2D:
    """Chassis pose in the world frame, mm and radians."""

    x: float
    y: float
    theta: float

    def compose(self, other: Pose2D) -> Pose2D:
        """Apply ``other``, given in this pose's body frame."""
        c, s = math.cos(self.theta), math.sin(self.theta)
        return Pose2D(
            self.x + c * other.x - s * other.y,
            self.y + s * other.x + c * other.y,
            self.theta + other.theta,
        )


ValveState = tuple[bool, ...]  # one entry per valve/leg in the robot file's leg order


class MotionModel(Protocol):
    """A model predicting the chassis motion of one valve transition."""

    name: str

    def transition(self, start: ValveState, end: ValveState, period_s: float) -> Pose2D:
        """Body-frame displacement of the chassis when the valves switch from ``start`` to
        ``end`` and are held ``period_s`` seconds, starting from ``start``'s steady state."""
        ...
