"""Dynamic soft-robot models of thesis chapter 4 (sections 4.1 and 4.2).

:mod:`motion` holds the types every model shares (chassis pose, valve state, the
``MotionModel`` protocol); :mod:`description` (with :mod:`fields`) reads the ``model:``
section of a robot file; :mod:`limbs` and :mod:`spring_damper` are the generalized
spring-damper model of section 4.1.1, with the friction of :mod:`friction`;
:mod:`characterization` fits its parameters to recorded data (section 4.2.1) and
:mod:`robot_edit` writes them back; :mod:`gait_graph` builds the gait graph from simulated
transitions and searches it (section 4.2.2); :mod:`catalogue` names the models for the
command line.
"""

from __future__ import annotations

from gaitc.models.motion import MotionModel, Pose2D, ValveState

__all__ = ["MotionModel", "Pose2D", "ValveState"]
