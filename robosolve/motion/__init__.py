"""Motion: the references a robot follows, and the actuator forces along them.

Pure engines on plain sympy/numpy inputs (no loader, no I/O):

* :mod:`robosolve.motion.profiles`: bang-bang, trapezoidal and quintic profiles,
  each joint's own time, the synchronized time T and the rescaled values;
* :mod:`robosolve.motion.torques`: actuator forces along a profile, closed form
  piecewise in t and signed peaks;
* :mod:`robosolve.motion.task_path`: work-space paths (line, arc), timed along their
  length and converted to joints.

The simulations that integrate the equations of motion along these references are in
:mod:`robosolve.simulation`.
"""
