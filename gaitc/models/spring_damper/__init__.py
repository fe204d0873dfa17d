"""The generalized spring-damper model of thesis section 4.1.1: the robot file's
``model: spring_damper:`` section (:mod:`.description`), the limb maps for all limbs at once
(:mod:`.limbs`), Coulomb friction with stiction (:mod:`.friction`, section 4.1.3), and the
model itself, eq. 4.1 with centroidal chassis dynamics and its integrator (:mod:`.model`).
"""
