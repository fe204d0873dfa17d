"""The active/passive model of thesis section 4.1.2: limbs of active (pressurised) and
passive segments, as Frenet-frame curves (:mod:`.frenet`), their kinematics and mass
properties (:mod:`.kinematics`), the robot's components and their matrices
(:mod:`.robot`), the quasi-static rest pose of minimum energy (:mod:`.statics`), and the
motion model the gait searches use (:mod:`.model`); :mod:`.description` (with the YAML
node reader of :mod:`.reader`) reads the robot file's ``model: active_passive:`` section.
"""
