"""Dynamic soft-robot models of thesis chapter 4 (sections 4.1 and 4.2).

:mod:`.motion` holds the types every model shares (chassis pose, valve state, the
``MotionModel`` protocol, a loaded model); each model family is a package: the generalized
spring-damper model of section 4.1.1 (:mod:`.spring_damper`) and the active/passive model of
section 4.1.2 (:mod:`.active_passive`), each reading its section of the robot file with the
positioned errors of :mod:`.fields`. :mod:`.characterization` fits the spring-damper
parameters to recorded data (section 4.2.1) and :mod:`.robot_edit` writes them back;
:mod:`.gait_graph` builds the gait graph from simulated transitions and searches it
(section 4.2.2); :mod:`.catalogue` names the models for the command line.
"""

from __future__ import annotations

from gaitc.models.motion import MotionModel, Pose2D, ValveState

__all__ = ["MotionModel", "Pose2D", "ValveState"]
