"""Joint-space motion: synchronized profiles, torques along them, closed-loop control.

Pure engines on plain sympy/numpy inputs (no loader, no I/O):

* :mod:`robosolve.motion.profiles`: bang-bang, trapezoidal and quintic profiles,
  each joint's own time, the synchronized time T and the rescaled values;
* :mod:`robosolve.motion.torques`: actuator forces along a profile, closed form
  piecewise in t and signed peaks;
* :mod:`robosolve.motion.control`: closed-loop simulation (p, pd, pd_gravity,
  computed_torque) with max and final errors.

The numeric equations of motion they take are
:class:`robosolve.dynamics.numeric.NumericDynamics` (built by the model bridge,
:mod:`robosolve.dynamics.bridge`).
"""
