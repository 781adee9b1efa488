"""Simulations: the equations of motion integrated in time.

Pure engines on numeric equations of motion
(:class:`robosolve.dynamics.numeric.NumericDynamics`, built by :mod:`robosolve.dynamics.bridge`):

* :mod:`robosolve.simulation.forward`: forward dynamics of given actuator forces
  (the forward-dynamics questions): one compiled right-hand side, DOP853 / Radau, extremes,
  work and energy;
* :mod:`robosolve.simulation.joint_control`: joint-space closed loop (p, pd, pd_gravity,
  computed_torque) following a motion profile, with max and final errors;
* :mod:`robosolve.simulation.task_control`: work-space closed loop on the task error
  (task_pd_gravity through Jᵀ, task_computed_torque).

The references they follow (profiles, task paths) are in :mod:`robosolve.motion`.
"""
