"""Gait primitives from the gait graph of thesis chapter 2 (Algorithm 1, sections 2.2-2.5).

Pipeline: :mod:`robot` (YAML description) → :mod:`kinematics` (constant curvature) →
:mod:`poses` (stable poses) → :mod:`motion` (transitions) → :mod:`graph` → :mod:`search`.
"""

from __future__ import annotations

from gaitgraph.robot import RobotFileError, load_robot

__all__ = ["RobotFileError", "load_robot"]
