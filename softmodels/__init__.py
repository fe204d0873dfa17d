"""Dynamic soft-robot models of thesis chapter 4 (sections 4.1 and 4.2).

:mod:`motion` holds the types every model shares (chassis pose, valve state, the
``MotionModel`` protocol); :mod:`description` reads the ``model:`` fields of a robot file;
:mod:`spring_damper` is the generalized spring-damper model of section 4.1.1 with the
friction of :mod:`friction`; :mod:`characterization` fits its parameters to recorded data
(section 4.2.1); :mod:`gait_graph` builds the gait graph from simulated transitions and
searches it for forward gaits (section 4.2.2).
"""

from __future__ import annotations

from softmodels.motion import MotionModel, Pose2D, ValveState

__all__ = ["MotionModel", "Pose2D", "ValveState"]
