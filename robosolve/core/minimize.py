"""Bounded scalar minimisation, step for step scipy's
``minimize_scalar(fun, bounds=(a, b), method="bounded", options={"xatol": ...})`` (Brent's
method: golden sections and parabolic steps; scipy 1.17's ``_minimize_scalar_bounded``,
BSD-3-Clause, Copyright (c) 2001-2002 Enthought, Inc. 2003, SciPy Developers).

Why a copy: ``import scipy.optimize`` costs about half a second of CPU, more than the
refinements of extremes it is used for (a task path's joint rates, a closed loop's errors).
The same operations on the same types (numpy's abs, sign and maximum), so the same iterates and
the same answer as scipy (`tests/engines/test_minimize.py` compares them).
"""

from __future__ import annotations

from math import sqrt

import numpy as np

__all__ = ["minimize_bounded", "Minimum"]


class Minimum:
    """What the callers read of scipy's OptimizeResult."""

    def __init__(self, x, fun, nfev, status):
        self.fun = np.asarray(fun)[()]
        self.x = np.reshape(x, self.fun.shape)[()]
        self.nfev = self.nit = nfev
        self.status, self.success = status, status == 0


def minimize_bounded(func, bounds, xatol: float = 1e-5, maxiter: int = 500) -> Minimum:
    """The minimum of func on [a, b] to xatol (scipy's bounded method)."""
    x1, x2 = bounds
    if not (np.size(x1) == 1 and np.isfinite(x1) and np.size(x2) == 1 and np.isfinite(x2)):
        raise ValueError("Optimization bounds must be finite scalars.")
    if x1 > x2:
        raise ValueError("The lower bound exceeds the upper bound.")
    flag = 0
    sqrt_eps = sqrt(2.2e-16)
    golden_mean = 0.5 * (3.0 - sqrt(5.0))
    a, b = x1, x2
    fulc = a + golden_mean * (b - a)
    nfc, xf = fulc, fulc
    rat = e = 0.0
    x = xf
    fx = func(x)
    num = 1
    fu = np.inf
    ffulc = fnfc = fx
    xm = 0.5 * (a + b)
    tol1 = sqrt_eps * np.abs(xf) + xatol / 3.0
    tol2 = 2.0 * tol1
    while np.abs(xf - xm) > (tol2 - 0.5 * (b - a)):
        golden = 1
        if np.abs(e) > tol1:                        # a parabolic fit?
            golden = 0
            r = (xf - nfc) * (fx - ffulc)
            q = (xf - fulc) * (fx - fnfc)
            p = (xf - fulc) * q - (xf - nfc) * r
            q = 2.0 * (q - r)
            if q > 0.0:
                p = -p
            q = np.abs(q)
            r = e
            e = rat
            if (np.abs(p) < np.abs(0.5 * q * r)) and (p > q * (a - xf)) and (p < q * (b - xf)):
                rat = (p + 0.0) / q
                x = xf + rat
                if ((x - a) < tol2) or ((b - x) < tol2):
                    si = np.sign(xm - xf) + ((xm - xf) == 0)
                    rat = tol1 * si
            else:
                golden = 1
        if golden:                                  # a golden-section step
            e = a - xf if xf >= xm else b - xf
            rat = golden_mean * e
        si = np.sign(rat) + (rat == 0)
        x = xf + si * np.maximum(np.abs(rat), tol1)
        fu = func(x)
        num += 1
        if fu <= fx:
            if x >= xf:
                a = xf
            else:
                b = xf
            fulc, ffulc = nfc, fnfc
            nfc, fnfc = xf, fx
            xf, fx = x, fu
        else:
            if x < xf:
                a = x
            else:
                b = x
            if (fu <= fnfc) or (nfc == xf):
                fulc, ffulc = nfc, fnfc
                nfc, fnfc = x, fu
            elif (fu <= ffulc) or (fulc == xf) or (fulc == nfc):
                fulc, ffulc = x, fu
        xm = 0.5 * (a + b)
        tol1 = sqrt_eps * np.abs(xf) + xatol / 3.0
        tol2 = 2.0 * tol1
        if num >= maxiter:
            flag = 1
            break
    if np.isnan(xf) or np.isnan(fx) or np.isnan(fu):
        flag = 2
    return Minimum(xf, fx, num, flag)
