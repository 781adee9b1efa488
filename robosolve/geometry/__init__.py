"""Rigid-body geometry engines: helical (screw) displacements, rotation
representations and mobility counts.

Pure functions on plain sympy / numpy inputs (no robot model, no I/O):

* `robosolve.geometry.rotations` - ZYZ Euler angles, roll-pitch-yaw,
  axis-angle and unit quaternion of a rotation matrix, both ways;
* `robosolve.geometry.helical` - the displacement matrix Q between two poses
  and its helical axis (u, alpha, h, P*, pitch), both ways;
* `robosolve.geometry.mobility` - Gruebler (planar) and Kutzbach (spatial)
  degrees of freedom.
"""
