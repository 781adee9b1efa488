"""Inverse kinematics engine: every solution, closed form where it exists.

Pure math on plain sympy inputs (no robot model, no I/O):

- `numeric.solve_all` finds every isolated solution of a square or
  over-determined system ``f(q) = 0`` by a deterministic multi-start
  Levenberg-Marquardt, refined to machine precision, deduplicated with the
  angles wrapped into (-pi, pi].
- `closed_form.derive` eliminates unknowns the way an exam solution does
  (linear isolation, a cos q + b sin q = c, cos^2 + sin^2 = 1 elimination,
  atan2 recovery) and returns the derivation as data.
- `engine.solve_ik` puts both together: counts the equations, checks that the
  two sets agree, applies joint limits and the selection rule, explains
  unreachable targets and computes velocity IK.
"""


