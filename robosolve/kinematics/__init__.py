"""Kinematics engines: Jacobians, singular configurations, statics, ellipsoids.

Pure functions on plain sympy / numpy inputs (no dependency on the loader); the
question solvers in ``robosolve.solvers`` wire them to the robot model.
"""
