"""IK solutions judged by the pose they reach (grading.md "Diagnosis"; issue 24).

A solution that reaches the target within the joint limits is right even when its numbers
are not robosolve's (an angle off by 2π, a different but valid branch); a set still needs
every branch: as many distinct solutions as the reference has, each reaching the target.
`reach_data` keeps, beside the reference, the residuals lhs − rhs of the target's equations
in the joint symbols (the parameters substituted) and the joint limits.
"""

from __future__ import annotations

import math

import numpy as np
import sympy as sp

TWO_PI = 2 * math.pi


def reach_data(model, problem, question, subs) -> tuple:
    """((joint name, symbol) pairs, residual expressions, scales, {name: (lo, hi)}), or ()."""
    target = question.options.get("target") if isinstance(question.options, dict) else None
    if model is None or not target:
        return ()
    joints = tuple((j.name, j.symbol) for j in problem.joints)
    q_syms = {s for _, s in joints}
    params = {s: v for s, v in subs.items() if s not in q_syms}
    residuals, scales = [], []
    try:
        for _, lhs, rhs in target:
            r = (sp.sympify(model.coordinate(lhs)) - sp.sympify(rhs)).xreplace(params)
            if not r.free_symbols <= q_syms:
                return ()
            residuals.append(r)
            scales.append(max(1.0, abs(float(sp.N(sp.sympify(rhs).xreplace(params))))))
    except (TypeError, ValueError):
        return ()
    limits = {}
    for j in problem.joints:
        if j.limits is not None:
            try:
                limits[j.name] = tuple(float(sp.N(x.xreplace(params))) for x in j.limits)
            except (TypeError, ValueError):
                pass
    return joints, tuple(residuals), tuple(scales), limits


def _within(name, value, revolute, limits) -> float | None:
    """The value moved by whole turns into the joint's limits (revolute), or None."""
    lo, hi = limits.get(name, (-math.inf, math.inf))
    if name in revolute:
        if math.isinf(lo):
            return value
        k = math.ceil((lo - value) / TWO_PI - 1e-9)
        value = value + k * TWO_PI
    return value if lo - 1e-6 <= value <= hi + 1e-6 else None


def reaches(data, element: dict, revolute, tol) -> bool:
    """Does this solution (joint name -> number) reach the target within the limits?"""
    joints, residuals, scales, limits = data
    values = {}
    for name, sym in joints:
        if name not in element:
            return False
        v = _within(name, float(element[name]), revolute, limits)
        if v is None:
            return False
        values[sym] = v
    for r, scale in zip(residuals, scales):
        x = float(sp.N(r.xreplace(values)))
        if not math.isfinite(x) or abs(x) > tol.atol + tol.rtol * scale:
            return False
    return True


def _same(a: dict, b: dict, revolute, tol) -> bool:
    for k in a:
        d = a[k] - b[k]
        if k in revolute:
            d = (d + math.pi) % TWO_PI - math.pi
        if abs(d) > tol.atol + tol.rtol * max(1.0, abs(b[k])):
            return False
    return True


def set_reaches(data, given, n_expected: int, revolute, tol) -> bool:
    """Every branch: `n_expected` distinct given solutions, each reaching the target."""
    if not data or not isinstance(given, list) or len(given) != n_expected or not n_expected:
        return False
    elements = []
    for g in given:
        if not isinstance(g, dict):
            return False
        try:
            element = {k: float(np.asarray(v).ravel()[0]) for k, v in g.items()}
        except (TypeError, ValueError, IndexError):
            return False
        if not reaches(data, element, revolute, tol):
            return False
        if any(_same(element, other, revolute, tol) for other in elements):
            return False
        elements.append(element)
    return True
