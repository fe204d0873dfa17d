"""Gait primitives from the gait graph of thesis chapter 2 (Algorithm 1, sections 2.2-2.5).

Pipeline: :mod:`robot` (YAML) → :mod:`kinematics` → :mod:`poses` → :mod:`motion` →
:mod:`graph` → :mod:`search` / :mod:`resets`; :mod:`pairing` ties gaits of a spec to them.
"""

from __future__ import annotations

from gaitc.gaitgraph.robot import RobotFileError, load_robot

__all__ = ["RobotFileError", "load_robot"]
