"""core/angles.wrap_angle: the spec's (−π, π] on floats and exact sympy angles, edges first."""

import math
import random

import pytest
import sympy as sp

from robosolve.core.angles import SNAP, wrap_angle


@pytest.mark.parametrize("a, expected", [
    (math.pi, math.pi), (-math.pi, math.pi), (3 * math.pi, math.pi), (-3 * math.pi, math.pi),
    (2 * math.pi, 0.0), (-2 * math.pi, 0.0), (0.0, 0.0), (-0.0, 0.0), (-1e-20, 0.0),
    (1.0, 1.0), (-1.0, -1.0), (3 * math.pi / 2, -math.pi / 2), (-math.pi + SNAP / 2, math.pi),
])
def test_float_edges(a, expected):
    w = wrap_angle(a)
    assert isinstance(w, float)
    assert w == pytest.approx(expected, abs=1e-15)
    assert math.copysign(1.0, w) == math.copysign(1.0, expected)   # never -0.0


def test_float_is_exact_in_range_and_a_rotation_outside():
    rng = random.Random(7)
    for _ in range(2000):
        a = rng.uniform(-3.1, 3.1)
        assert wrap_angle(a) == a                    # no round-off for angles in range
        k = rng.randint(-5, 5)
        w = wrap_angle(a + 2 * math.pi * k)
        assert -math.pi < w <= math.pi
        assert math.cos(w) == pytest.approx(math.cos(a), abs=1e-12)
        assert math.sin(w) == pytest.approx(math.sin(a), abs=1e-12)
    assert -math.pi < wrap_angle(-math.pi + 2 * SNAP) < -math.pi + 3 * SNAP   # not snapped


def test_numpy_floats():
    np = pytest.importorskip("numpy")
    assert wrap_angle(np.float64(-np.pi)) == math.pi


@pytest.mark.parametrize("a, expected", [
    (sp.pi, sp.pi), (-sp.pi, sp.pi), (3 * sp.pi, sp.pi), (-3 * sp.pi, sp.pi), (2 * sp.pi, 0),
    (3 * sp.pi / 2, -sp.pi / 2), (5 * sp.pi / 3, -sp.pi / 3), (-sp.pi / 7, -sp.pi / 7),
    (sp.pi + sp.atan(2), sp.atan(2) - sp.pi), (sp.Integer(7), 7 - 2 * sp.pi),
    (-sp.Rational(1, 10) ** 30, -sp.Rational(1, 10) ** 30),
])
def test_exact_edges(a, expected):
    w = wrap_angle(a)
    assert isinstance(w, sp.Basic)
    assert sp.simplify(w - expected) == 0
    assert -math.pi < float(w) <= math.pi


def test_symbols_and_floats_inside_exact_angles():
    x = sp.Symbol("x")
    assert wrap_angle(x + 7) == x + 7                               # a symbolic angle: as it is
    w = wrap_angle(sp.Float(4.71238898038469) + 0 * sp.pi)
    assert isinstance(w, sp.Float) and float(w) == pytest.approx(-math.pi / 2, abs=1e-14)
    assert wrap_angle(sp.I) == sp.I                                  # not a real number
