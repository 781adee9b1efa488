"""Angles wrapped into (−π, π], the spec's one rule (problem-format.md: IK order and
singular values; Euler angles, grading.md's comparison of joint values).

`wrap_angle` takes a float or a sympy number and returns the same kind:

* a float: the exact remainder modulo 2π (`math.remainder`, no round-off for angles already
  in range), then the edges: a value within `SNAP` (1e-12) above −π is −π up to round-off
  and becomes π; |value| < 1e-15 becomes 0.0 (never −0.0);
* an exact sympy angle: shifted by the multiple 2πk with k = ⌈(a − π) / 2π⌉ (exact for
  multiples of π, else decided by sympy's evaluation), so −π ↦ π, 3π ↦ π, 3π/2 ↦ −π/2; an angle with free symbols is returned as it is; an inexact one
  (a Float inside) becomes a Float of the float rule.
"""

from __future__ import annotations

import math

import sympy as sp

__all__ = ["SNAP", "wrap_angle"]

TWO_PI = 2.0 * math.pi
SNAP = 1e-12        # a float this close above -pi is -pi up to round-off: it becomes pi
TINY = 1e-15        # a float this close to 0 is 0


def wrap_angle(value):
    """`value` in (−π, π]: a float for a float, a sympy expression for a sympy one."""
    if isinstance(value, sp.Basic):
        return _wrap_exact(value)
    return _wrap_float(float(value))


def _wrap_float(a: float) -> float:
    w = math.remainder(a, TWO_PI)           # exact, in [-pi, pi]
    if w <= -math.pi + SNAP:
        return math.pi
    if abs(w) < TINY:
        return 0.0
    return w + 0.0


def _wrap_exact(a):
    if a.free_symbols:
        return a
    if a.atoms(sp.Float):                   # inexact input: a float, not "float + pi"
        return sp.Float(_wrap_float(float(sp.N(a, 30))), 15)
    k = sp.ceiling((a - sp.pi) / (2 * sp.pi))   # exact for multiples of pi (3pi -> 1)
    if not k.is_Integer:                    # not a real number
        return a
    return a - 2 * sp.pi * k if k else a
