"""Synchronized motion profiles: the seed's §7.4 (corrected), RTB trajectories as references."""

import numpy as np
import pytest
import sympy as sp

from robosolve.core.symbols import TIME
from robosolve.motion.profiles import ProfileError, synchronize

t = TIME    # the profiles' time (a real symbol)


def _eval(expr, times):
    f = sp.lambdify(t, expr, "numpy")
    return np.array([float(f(x)) for x in times])


def test_base_profile_of_the_course():
    # §7.4.1: 0 -> 1 in 1 s, |acc| = 4: 2t^2 | -2t^2 + 4t - 1
    p = synchronize(["q"], [0], [1], [4])
    assert p.T == 1
    j = p.joints[0]
    assert j.acceleration == 4 and j.own_time == 1
    a, b = j.segments
    assert sp.expand(a.position - 2 * t ** 2) == 0
    assert sp.expand(b.position - (-2 * t ** 2 + 4 * t - 1)) == 0
    assert a.t1 == sp.Rational(1, 2)


def test_errata_123_two_to_minus_two_with_acc_2():
    # ERRATA 123: from 2 to -2 with a_max = 2 needs T = 2*sqrt(2), not 2
    p = synchronize(["q"], [2], [-2], [2])
    assert sp.simplify(p.T - 2 * sp.sqrt(2)) == 0
    assert p.joints[0].acceleration == 2
    pos = p.position(0)
    assert pos.subs(t, p.T) == -2
    assert sp.simplify(pos.subs(t, p.T / 2)) == 0
    assert p.joints[0].direction == -1


def test_synchronized_time_is_the_max_not_joint_1():
    # ERRATA 126: the slowest joint is joint 2 here
    p = synchronize(["a", "b", "c"], [0, 0, 0], [1, 4, -1], [4, 1, 1])
    own = [j.own_time for j in p.joints]
    assert own == [1, 4, 2]
    assert p.T == 4 and p.slowest == ("b",)
    # rescaled a_i = 4|D_i|/T^2, magnitudes (ERRATA 125)
    assert [j.acceleration for j in p.joints] == [sp.Rational(1, 4), 1, sp.Rational(1, 4)]
    for i, j in enumerate(p.joints):
        assert p.position(i).subs(t, p.T) == j.end


@pytest.mark.parametrize("shape", ["bang-bang", "trapezoidal", "quintic"])
def test_joint_that_does_not_move(shape):
    p = synchronize(["a", "b"], [0.5, 1], [0.5, 2], [2, 3], shape=shape, max_velocity=[1, 1])
    still = p.joints[0]
    assert still.own_time == 0 and still.acceleration == 0 and not still.moves
    assert p.position(0) == sp.Float(0.5) or p.position(0) == 0.5
    q, qd, qdd = p.numeric_plan().evaluate(np.linspace(-1, float(p.T) + 1, 50))
    assert np.all(q[0] == 0.5) and np.all(qd[0] == 0) and np.all(qdd[0] == 0)


def test_nothing_moves():
    p = synchronize(["a", "b"], [1, 2], [1, 2], [1, 1])
    assert p.T == 0
    q, _, _ = p.numeric_plan().evaluate([0.0, 1.0])
    assert np.allclose(q, [[1, 1], [2, 2]])


@pytest.mark.parametrize("shape", ["bang-bang", "trapezoidal", "quintic"])
def test_profiles_are_smooth_rest_to_rest_and_respect_limits(shape):
    start, end, amax, vmax = [0, sp.pi / 2, 1], [1, -sp.pi / 4, sp.Rational(3, 2)], [4, 2, 3], [1, 3, sp.Rational(1, 2)]
    p = synchronize(["a", "b", "c"], start, end, amax, shape=shape, max_velocity=vmax)
    T = float(p.T)
    for i, j in enumerate(p.joints):
        pos, vel, acc = p.position(i), p.velocity(i), p.acceleration(i)
        assert sp.simplify(pos.subs(t, 0) - j.start) == 0
        assert sp.simplify(pos.subs(t, p.T) - j.end) == 0
        assert vel.subs(t, 0) == 0 and sp.simplify(vel.subs(t, p.T)) == 0
        # continuity of q and qd at every switching instant
        for s in j.segments[1:]:
            prev = next(x for x in j.segments if x.t1 == s.t0)
            for order in (0, 1):
                left = sp.diff(prev.position, t, order).subs(t, s.t0)
                right = sp.diff(s.position, t, order).subs(t, s.t0)
                assert abs(float(left - right)) < 1e-12
        ts = np.linspace(0, T, 2001)
        a = np.abs(_eval(acc, ts))
        assert a.max() <= float(j.max_acceleration) * (1 + 1e-9)
        assert a.max() == pytest.approx(float(j.acceleration), rel=1e-5)
        if shape == "trapezoidal":
            v = np.abs(_eval(vel, ts))
            assert v.max() <= float(j.max_velocity) * (1 + 1e-9)
            assert v.max() == pytest.approx(float(j.velocity), rel=1e-9)
        # the numeric plan agrees with the exact Piecewise
        q, qd, qdd = p.numeric_plan().evaluate(ts)
        assert np.allclose(q[i], _eval(pos, ts), atol=1e-12)
        assert np.allclose(qd[i], _eval(vel, ts), atol=1e-12)
    assert float(p.T) == pytest.approx(max(float(j.own_time) for j in p.joints))


def test_trapezoidal_times():
    # |D| = 1 >= v^2/a = 1/4: T = |D|/v + v/a = 5/4; |D| = 1 < 9/2: bang-bang time sqrt(2)
    p = synchronize(["a", "b"], [0, 0], [1, 1], [4, 2], shape="trapezoidal", max_velocity=[1, 3])
    assert [j.own_time for j in p.joints] == [sp.Rational(5, 4), sp.sqrt(2)]
    assert p.T == sp.sqrt(2)
    # the other joint keeps a = 4 and lowers its cruise velocity to end at T
    j = p.joints[0]
    assert j.acceleration == 4
    vc = float(j.velocity)
    assert vc * (float(p.T) - vc / 4) == pytest.approx(1, rel=1e-12)


def test_against_robotics_toolbox_trajectories():
    rtb = pytest.importorskip("roboticstoolbox")
    start, end = [0, 2, -1], [1, -2, -1.5]
    for shape in ("bang-bang", "trapezoidal", "quintic"):
        p = synchronize(["a", "b", "c"], start, end, [4, 2, 1], shape=shape, max_velocity=[0.8, 3, 0.3])
        T = float(p.T)
        ts = np.linspace(0, T, 101)
        q, qd, qdd = p.numeric_plan().evaluate(ts)
        for i, j in enumerate(p.joints):
            if shape == "quintic":
                ref = rtb.quintic(start[i], end[i], ts)
            elif shape == "bang-bang":
                ref = rtb.trapezoidal(start[i], end[i], ts, V=2 * (end[i] - start[i]) / T * (1 - 1e-13))
            else:
                ref = rtb.trapezoidal(start[i], end[i], ts, V=float(j.direction * j.velocity) * (1 - 1e-13))
            assert np.allclose(q[i], ref.q, atol=1e-9), (shape, i)
            assert np.allclose(qd[i], ref.qd, atol=1e-9), (shape, i)


def test_quintic_peak_acceleration():
    p = synchronize(["a"], [0], [2], [3], shape="quintic")
    T = p.T
    # T_i = sqrt(10|D|/(sqrt(3) a))
    assert abs(float(T) - np.sqrt(10 * 2 / (np.sqrt(3) * 3))) < 1e-12
    s = (3 - sp.sqrt(3)) / 6
    assert abs(float(p.acceleration(0).subs(t, s * T)) - 3) < 1e-12


def test_bad_input():
    with pytest.raises(ProfileError, match="positive"):
        synchronize(["a"], [0], [1], [0])
    with pytest.raises(ProfileError, match="max_velocity"):
        synchronize(["a"], [0], [1], [1], shape="trapezoidal")
    with pytest.raises(ProfileError, match="unknown shape"):
        synchronize(["a"], [0], [1], [1], shape="cubic")


def test_symbolic_limits_stay_symbolic():
    a1, a2 = sp.symbols("a1 a2", positive=True)
    p = synchronize(["a", "b"], [0, 0], [1, 2], [a1, a2])
    assert p.T == sp.Max(2 / sp.sqrt(a1), 2 * sp.sqrt(2) / sp.sqrt(a2))
