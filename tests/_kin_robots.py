"""Small robots for the kinematics engine tests, built from elementary transforms."""

from __future__ import annotations

import sympy as sp

from robosolve.core.matrices import l_matrix
from robosolve.core.transforms import dh_standard, rot_y, rot_z, trans_x, trans_z

t1, t2, t3, d, l = sp.symbols("theta1 theta2 theta3 d l")
L1, L2, L3, h, a2, a3 = sp.symbols("L1 L2 L3 h a2 a3")
R, P = "revolute", "prismatic"


def prod(ms):
    out = sp.eye(4)
    for m in ms:
        out = out * m
    return out


class Robot:
    """frames: one list of elementary matrices per frame (frame i holds joint i)."""

    def __init__(self, q, kinds, frames, params):
        self.q = list(q)
        self.kinds = dict(zip(self.q, kinds))
        self.params = params
        self.local = [prod(f) for f in frames]
        self.M0 = []
        m = sp.eye(4)
        for loc in self.local:
            m = m * loc
            self.M0.append(m)
        self._l0 = None

    @property
    def L0(self):
        if self._l0 is None:
            self._l0 = [l_matrix(self.M0[i], qi) for i, qi in enumerate(self.q)]
        return self._l0

    @property
    def E(self):
        return self.M0[-1][:3, 3]


def scara():
    return Robot([t1, t2, l], [R, R, P],
                 [[trans_z(h), rot_z(t1), trans_x(L1)], [rot_z(t2), trans_x(L2)], [trans_z(-l)]],
                 {L1: sp.Rational(1, 2), L2: sp.Rational(2, 5), h: 1})


def planar2r():
    return Robot([t1, t2], [R, R], [[rot_z(t1), trans_x(L1)], [rot_z(t2), trans_x(L2)]],
                 {L1: sp.Rational(1, 2), L2: sp.Rational(1, 2)})


def planar3r():
    return Robot([t1, t2, t3], [R, R, R],
                 [[rot_z(t1), trans_x(L1)], [rot_z(t2), trans_x(L2)], [rot_z(t3), trans_x(L3)]],
                 {L1: sp.Rational(1, 2), L2: sp.Rational(2, 5), L3: sp.Rational(3, 10)})


def polar():
    """Polar RRP: azimuth θ1 about z, elevation θ2 (positive up), radial extension d."""
    return Robot([t1, t2, d], [R, R, P], [[rot_z(t1)], [rot_y(-t2)], [trans_x(d)]], {})


def anthropomorphic():
    return Robot([t1, t2, t3], [R, R, R],
                 [[dh_standard(t1, h, 0, sp.pi / 2)], [dh_standard(t2, 0, a2, 0)],
                  [dh_standard(t3, 0, a3, 0)]],
                 {h: sp.Rational(1, 2), a2: sp.Rational(2, 5), a3: sp.Rational(3, 10)})
