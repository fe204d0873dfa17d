"""The requested displacement of a gait cycle: goal (dx, dy, dθ) and its tolerance.

A gait is a cycle from the start pose back to it (thesis 2.3); the chapter 5 searches look
for one whose net chassis displacement, in the frame of the start pose, is the goal.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from gaitc.diagnostics import UsageError


@dataclass(frozen=True)
class Goal:
    """Displacement per cycle (mm, mm, degrees) and how close counts as reached."""

    dx: float
    dy: float
    dtheta: float = 0.0
    tolerance: float = 5.0  # mm, on the (dx, dy) distance
    angle_tolerance: float = 5.0  # degrees

    def error(self, x: float, y: float, heading: float) -> tuple[float, float]:
        """Distance (mm) and absolute angle difference (degrees) of a displacement."""
        return math.hypot(x - self.dx, y - self.dy), abs(angle_difference(heading, self.dtheta))

    def reached(self, x: float, y: float, heading: float) -> bool:
        far, turn = self.error(x, y, heading)
        return far <= self.tolerance + 1e-9 and turn <= self.angle_tolerance + 1e-9

    def __str__(self) -> str:
        return f"({self.dx:g} mm, {self.dy:g} mm, {self.dtheta:g} deg)"


def angle_difference(a: float, b: float) -> float:
    """``a - b`` in degrees, wrapped into [-180, 180)."""
    return (a - b + 180.0) % 360.0 - 180.0


def numbers(text: str, option: str, low: int, high: int) -> list[float]:
    """``low`` to ``high`` comma-separated finite numbers of ``option``, or a UsageError."""
    parts = [p.strip() for p in text.split(",")]
    if not low <= len(parts) <= high:
        want = f"{low}" if low == high else f"{low} to {high}"
        raise UsageError(f"{option}: expected {want} comma-separated numbers, got {text!r}")
    out = []
    for p in parts:
        try:
            value = float(p)
        except ValueError:
            raise UsageError(f"{option}: {p!r} is not a number (in {text!r})") from None
        if not math.isfinite(value):
            raise UsageError(f"{option}: {p!r} is not a finite number")
        out.append(value)
    return out


def parse_goal(text: str, tolerance: str | None = None) -> Goal:
    """``DX,DY[,DTHETA]`` (mm, mm, degrees) and an optional ``MM[,DEG]`` tolerance.

    Raises :class:`~gaitc.diagnostics.UsageError` with the reason when either is malformed.
    """
    values = numbers(text, "--goal", 2, 3)
    dtheta = values[2] if len(values) == 3 else 0.0
    if abs(dtheta) >= 180.0:
        raise UsageError(
            f"--goal: the rotation {dtheta:g} deg must lie strictly between -180 and 180"
        )
    if tolerance is None:
        return Goal(values[0], values[1], dtheta)
    tol = numbers(tolerance, "--tolerance", 1, 2)
    if any(t <= 0 for t in tol):
        raise UsageError(f"--tolerance: must be positive, got {tolerance!r}")
    return Goal(values[0], values[1], dtheta, tol[0], tol[1] if len(tol) == 2 else 5.0)
