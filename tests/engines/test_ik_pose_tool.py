"""IK of a pose with a tool frame after a spherical wrist (an ABB IRB 120 from its datasheet).

A tool turned with respect to the flange (Tz(d)·Ry(π/6), as a frame of its own or written in the
last joint's pose) leaves the wrist spherical: ³R₆ = (⁰R₃)ᵀ·R·R_tᵀ is the wrist's own product of
rotations, so the decoupling's closed form holds. It was derived on ³R_tool instead (nine
equations the elimination could not solve): no closed form, and minutes of search per arm branch.
The reference is Robotics Toolbox (`DHRobot` with a `tool`, `ikine_LM` from random seeds).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import sympy as sp

from robosolve.core.transforms import dh_standard, rot_x, rot_y, rot_z, trans_z
from robosolve.ik.engine import IKJoint
from robosolve.ik.pose import _after_last_axis, _Chain, _wrist, _wrist_and_tool, solve_pose

rtb = pytest.importorskip("roboticstoolbox")
SE3 = pytest.importorskip("spatialmath").SE3

PI = math.pi
IRB120 = [(0.29, 0.0, -PI / 2, 0.0), (0.0, 0.27, 0.0, -PI / 2), (0.0, 0.07, -PI / 2, 0.0),
          (0.302, 0.0, PI / 2, 0.0), (0.0, 0.0, -PI / 2, 0.0), (0.072, 0.0, 0.0, 0.0)]   # d, a, alpha, offset


def _wrapped_close(a, b, tol=1e-6):
    return all(abs(math.remainder(x - y, 2 * PI)) < tol for x, y in zip(a, b))


def _rtb_solutions(robot, T, seeds=60):
    rng = np.random.default_rng(0)
    sols = []
    for s in rng.uniform(-PI, PI, (seeds, 6)):
        r = robot.ikine_LM(T, q0=s, ilimit=100, slimit=1, tol=1e-12, joint_limits=False)
        # ikine_LM stops within about 1e-6 of a solution: distinct ones are far further apart
        if r.success and not any(_wrapped_close(r.q, o, 1e-4) for o in sols):
            sols.append(np.array(r.q))
    return sols


_COMPILED = {}


def _value(e, known):
    args = sorted(e.free_symbols, key=str)
    if e not in _COMPILED:
        _COMPILED[e] = sp.lambdify(args, e, "numpy")
    with np.errstate(invalid="ignore"):
        return float(_COMPILED[e](*[known[a] for a in args]))


def _branch_values(branch, R, p, names):
    """A closed-form branch evaluated at the target (joints in the order they can be), or None
    where it is not real (acos beyond 1: numpy's nan)."""
    known = {sp.Symbol(f"r{i + 1}{j + 1}"): R[i, j] for i in range(3) for j in range(3)}
    known.update(dict(zip(sp.symbols("px py pz"), p)))
    todo, q = {k: sp.sympify(e) for k, e in branch.items()}, {}
    while todo:
        ready = [k for k, e in todo.items() if not (e.free_symbols - set(known))]
        if not ready:
            return None
        for k in ready:
            e = todo.pop(k)
            v = _value(e, known)
            if not math.isfinite(v):
                return None
            q[k] = known[sp.Symbol(k)] = v
    return [q[n] for n in names]


TOOL = SE3.Tz(0.1) * SE3.Rx(PI / 6) * SE3.Tz(0.15) * SE3.Rz(PI / 4) * SE3.Ry(-PI / 5)


def _factors():
    q = sp.symbols("q1:7")
    factors = [dh_standard(qi + off, d, a, al) for qi, (d, a, al, off) in zip(q, IRB120)]
    # the tool's rotation written in the last joint's pose, and a further tool frame of its own
    factors[5] = factors[5] * trans_z(sp.Rational(1, 10)) * rot_x(sp.pi / 6)
    factors.append(trans_z(sp.Rational(3, 20)) * rot_z(sp.pi / 4) * rot_y(-sp.pi / 5))
    return factors, q


def test_wrist_of_a_turned_tool_is_solved_in_closed_form():
    """³R_tool = ³R₆·R_t: the wrist's closed form is derived on ³R₆ (nine equations of three
    rotations), and its two branches give the target's ³R_tool (Robotics Toolbox's wrist + tool)."""
    factors, q = _factors()
    chain = _Chain([sp.Matrix(f) for f in factors], [IKJoint(s, True, None) for s in q], list(q))
    tail, Rt = _wrist_and_tool(chain, 3)
    wrist = rtb.DHRobot([rtb.RevoluteDH(d=d, a=a, alpha=al, offset=off) for d, a, al, off in IRB120[3:]], tool=TOOL)
    target = wrist.fkine([1.1, -0.7, 0.4]).A[:3, :3]          # ³R_tool
    A = sp.Matrix(3, 3, lambda i, j: sp.Symbol(f"a{i + 1}{j + 1}"))
    found, cf, singular = _wrist(tail, A, target @ np.array(Rt, dtype=float).T,
                                 [IKJoint(s, True, None) for s in q[3:]], {s: str(s) for s in q}, None, 20.0)
    assert cf is not None and not singular and len(found) == 2
    assert any(_wrapped_close(w, [1.1, -0.7, 0.4], 1e-9) for w in found)
    for w in found:
        assert np.max(np.abs(wrist.fkine(w).A[:3, :3] - target)) < 1e-12


@pytest.mark.slow
def test_tool_frame_turned_after_a_spherical_wrist_keeps_the_closed_form():
    factors, q = _factors()
    robot = rtb.DHRobot([rtb.RevoluteDH(d=d, a=a, alpha=al, offset=off) for d, a, al, off in IRB120], tool=TOOL)
    q0 = [0.3, -0.5, 0.8, 1.1, -0.7, 0.4]
    T = robot.fkine(q0).A
    res = solve_pose(factors, [IKJoint(s, True, None) for s in q], T[:3, :3], T[:3, 3])
    names = [str(s) for s in q]
    got = [[s[n] for n in names] for s in res.solutions]
    assert res.method == "decoupling" and res.closed_form, res.notes
    ref = _rtb_solutions(robot, T)
    assert len(got) == len(ref) == 8
    assert all(any(_wrapped_close(g, r, 1e-4) for g in got) for r in ref)
    for g in got:
        assert np.max(np.abs(robot.fkine(g).A - T)) < 1e-9
    # the closed form's branches that reach the target are the solutions
    reached = []
    for b in res.closed_form:
        v = _branch_values(b, T[:3, :3], T[:3, 3], names)
        if v is not None and np.max(np.abs(robot.fkine(v).A - T)) < 1e-9:
            reached.append(v)
    assert all(any(_wrapped_close(g, r, 1e-8) for r in reached) for g in got)
    assert any("R_{t}" in str(eq[0]) for s in res.steps for eq in s.equations)


@pytest.mark.parametrize("rotation", [rot_x(sp.pi / 6), rot_y(-2 * sp.pi / 3), rot_x(sp.pi / 7) * rot_y(sp.pi / 5)])
def test_rotation_after_the_last_joint_is_read_from_its_axis(rotation):
    """F = Rz(q)·Tz(d)·Q: the Q found turns z onto the joint's axis in F's end frame, and F·Qᵀ is
    a rotation about z followed by constants (no q6 left after it)."""
    q = sp.Symbol("q6")
    F = rot_z(q) * trans_z(sp.Rational(1, 10)) * rotation
    Q = _after_last_axis(F[:3, :3], q)
    Qn = np.array(Q, dtype=float)
    axis_in_end = np.array(rotation[:3, :3].T, dtype=float) @ [0, 0, 1.0]   # Qᵀ·z = u
    assert np.allclose(Qn.T @ [0, 0, 1.0], axis_in_end, atol=1e-12)
    FQt = sp.lambdify(q, F[:3, :3] * Q.T)
    Rz = sp.lambdify(q, rot_z(q)[:3, :3])
    # F·Qᵀ = P·Rz(q): the joint's rotation comes last
    P = [np.array(FQt(v), dtype=float) @ np.array(Rz(v), dtype=float).T for v in (0.0, 0.7, -2.1)]
    assert np.allclose(P[0], P[1], atol=1e-12) and np.allclose(P[0], P[2], atol=1e-12)
    assert _after_last_axis(rot_z(q)[:3, :3], q) is None


# -- the UR family with a tool: the row along the parallel axes is the one of ¹M₆ = (⁰M₁)⁻¹·M·T_t⁻¹ --

UR5E = [(0.1625, 0.0, PI / 2), (0.0, -0.425, 0.0), (0.0, -0.3922, 0.0), (0.1333, 0.0, PI / 2),
        (0.0997, 0.0, -PI / 2), (0.0996, 0.0, 0.0)]       # d, a, alpha
UR_TOOL = SE3.Tz(0.05) * SE3.Rx(PI / 7) * SE3.Tz(0.07) * SE3.Rz(0.3) * SE3.Ry(0.2)


def _ur_factors():
    q = sp.symbols("q1:7")
    factors = [dh_standard(qi, d, a, al) for qi, (d, a, al) in zip(q, UR5E)]
    factors[5] = factors[5] * trans_z(sp.Rational(1, 20)) * rot_x(sp.pi / 7)
    factors.append(trans_z(sp.Rational(7, 100)) * rot_z(sp.Rational(3, 10)) * rot_y(sp.Rational(1, 5)))
    return factors, q


def test_ur_family_with_a_tool_keeps_the_closed_form():
    """It fell back to no closed form (the z row of ¹M_tool depends on q2, q3, q4) and took 20 s."""
    factors, q = _ur_factors()
    robot = rtb.DHRobot([rtb.RevoluteDH(d=d, a=a, alpha=al) for d, a, al in UR5E], tool=UR_TOOL)
    q0 = [0.3, -1.1, 1.2, -0.4, 0.9, 0.5]
    T = robot.fkine(q0).A
    res = solve_pose(factors, [IKJoint(s, True, None) for s in q], T[:3, :3], T[:3, 3])
    assert res.method == "three parallel axes" and res.closed_form, res.notes
    names = [str(s) for s in q]
    got = [[s[n] for n in names] for s in res.solutions]
    assert len(got) == 8 and any(_wrapped_close(g, q0, 1e-9) for g in got)
    for g in got:
        assert np.max(np.abs(robot.fkine(g).A - T)) < 1e-9
    assert any(eq[0] == "T_{t}" for s in res.steps for eq in s.equations)


@pytest.mark.slow
def test_ur_family_with_a_tool_every_solution_and_branch():
    factors, q = _ur_factors()
    robot = rtb.DHRobot([rtb.RevoluteDH(d=d, a=a, alpha=al) for d, a, al in UR5E], tool=UR_TOOL)
    T = robot.fkine([2.1, -0.6, -1.9, 0.8, -2.4, 1.3]).A
    res = solve_pose(factors, [IKJoint(s, True, None) for s in q], T[:3, :3], T[:3, 3])
    names = [str(s) for s in q]
    got = [[s[n] for n in names] for s in res.solutions]
    ref = _rtb_solutions(robot, T, seeds=120)
    assert len(got) == len(ref)
    assert all(any(_wrapped_close(g, r, 1e-4) for g in got) for r in ref)
    reached = [v for b in res.closed_form if (v := _branch_values(b, T[:3, :3], T[:3, 3], names)) is not None
               and np.max(np.abs(robot.fkine(v).A - T)) < 1e-9]
    assert all(any(_wrapped_close(g, r, 1e-8) for r in reached) for g in got)
