"""robosolve.core.minimize against scipy's minimize_scalar(method="bounded"): the same iterates,
so the same x and f(x), bit for bit."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.optimize import minimize_scalar

from robosolve.core.minimize import minimize_bounded

FUNCS = [lambda x: (x - 0.3) ** 2,
         lambda x: -abs(math.sin(7 * x) * math.exp(-x)),
         lambda x: -abs(np.cos(3 * x) + 0.1 * x),
         lambda x: abs(x - 1.0),
         lambda x: 1.0,
         lambda x: x ** 3 - x]


@pytest.mark.parametrize("k", range(len(FUNCS)))
@pytest.mark.parametrize("bounds,xatol", [((0.0, 1.0), 1e-12), ((-2.0, 3.5), 1e-5), ((0.25, 0.2500001), 1e-12),
                                          ((1.0, 1.0), 1e-12), ((-1.0, 2.0), 1e-12 * 2.3)])
def test_identical_to_scipy(k, bounds, xatol):
    ours = minimize_bounded(FUNCS[k], bounds, xatol=xatol)
    ref = minimize_scalar(FUNCS[k], bounds=bounds, method="bounded", options={"xatol": xatol})
    assert (ours.x, ours.fun, ours.nfev, ours.status) == (ref.x, ref.fun, ref.nfev, ref.status)
    assert type(ours.x) is type(ref.x) and type(ours.fun) is type(ref.fun)


def test_bad_bounds():
    with pytest.raises(ValueError):
        minimize_bounded(FUNCS[0], (1.0, 0.0))
    with pytest.raises(ValueError):
        minimize_bounded(FUNCS[0], (0.0, math.inf))
