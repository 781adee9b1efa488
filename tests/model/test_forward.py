"""The one chain computation (model/description.py, core/chain/forward.py, core/chain/algebras.py)
against independent references: Robotics Toolbox's `fkine` / `jacob0` of a standard-DH arm,
finite differences of the poses along a motion for W = Ṁ M⁻¹ and H = M̈ M⁻¹, and the three
algebras (sympy, trig ring, numpy) against each other."""

import dataclasses

import numpy as np
import pytest
import sympy as sp

from conftest import PROBLEMS
from robosolve.core.transforms import rigid_inverse
from robosolve.load.loader import load_problem, load_problem_text
from robosolve.model import RobotModel
from robosolve.core.chain.algebras import NumpyChainAlgebra, SympyChainAlgebra
from robosolve.model.description import ChainDescription
from robosolve.core.chain.forward import forward

rtb = pytest.importorskip("roboticstoolbox")

# two joints in one frame's pose (a twist that is not constant), a joint with a factor 2,
# a prismatic joint, a point off the last origin
TANGLE = """\
robosolve: 1
name: tangle
parameters: {L1: 0.7, L2: 0.4, h: 0.3}
joints:
  - {name: q1, type: revolute}
  - {name: q2, type: revolute}
  - {name: d3, type: prismatic}
  - {name: q4, type: revolute}
frames:
  "1": {pose: "Tz(h) Rz(q1) Tx(L1) Ry(q2)"}
  "2": {pose: "Rx(2*q4) Tz(d3) Tx(L2)"}
points:
  P: {frame: "2", at: [0.1, -0.2, 0.05]}
questions:
  - {type: position, point: P}
"""


@pytest.fixture(scope="module")
def puma():
    problem = load_problem(PROBLEMS / "puma560-dynamics.yaml")
    p = {s.name: float(v) for s, v in problem.parameters.items()}
    ref = rtb.DHRobot([
        rtb.RevoluteDH(d=p["d1"], alpha=np.pi / 2), rtb.RevoluteDH(a=p["a2"]),
        rtb.RevoluteDH(d=p["d3"], a=p["a3"], alpha=-np.pi / 2),
        rtb.RevoluteDH(d=p["d4"], alpha=np.pi / 2), rtb.RevoluteDH(alpha=-np.pi / 2), rtb.RevoluteDH()])
    return problem, RobotModel(problem), ref


@pytest.fixture(scope="module")
def tangle():
    problem = load_problem_text(TANGLE)
    return problem, RobotModel(problem)


def _subs(problem, q, qd=None, qdd=None):
    subs = {s: v for s, v in problem.parameters.items() if v is not None}
    for j in problem.joints:
        subs[j.symbol] = q[j.index]
        if qd is not None:
            subs[j.dot] = qd[j.index]
        if qdd is not None:
            subs[j.ddot] = qdd[j.index]
    return subs


def test_description_is_the_problems_chain_and_immutable(tangle):
    problem, model = tangle
    d = ChainDescription.from_problem(problem)
    assert d.frames == ("1", "2") and d.parent("2") == "1" and d.parent("0") is None
    assert d.chain("2") == ["1", "2"] and d.moved_by("1") == [0, 1] and d.moved_by("2") == [2, 3]
    assert [d.joint_frame(i) for i in range(4)] == ["1", "1", "2", "2"]
    assert d.constant_twist("1") is None and d.constant_twist("2") is None
    assert d.points["P"].frame == "2"
    with pytest.raises(dataclasses.FrozenInstanceError):
        d.frames = ()
    with pytest.raises(TypeError):
        d.frame["3"] = d.frame["1"]


def test_numpy_chain_is_rtb_fkine_and_jacob0(puma):
    problem, model, ref = puma
    rng = np.random.default_rng(7)
    for _ in range(3):
        q = rng.uniform(-np.pi, np.pi, 6)
        data = forward(model.description, NumpyChainAlgebra(model.description, _subs(problem, q)))
        np.testing.assert_allclose(data.M("6"), ref.fkine(q).A, atol=1e-12)
        # the columns of the geometric Jacobian from the L matrices: (L p, vex L)
        p = np.append(data.M("6")[:3, 3], 1.0)
        cols = [np.concatenate([(data.L(i, "6") @ p)[:3], [data.L(i, "6")[2, 1], data.L(i, "6")[0, 2],
                                                           data.L(i, "6")[1, 0]]]) for i in range(6)]
        np.testing.assert_allclose(np.array(cols).T, ref.jacob0(q), atol=1e-12)


def test_the_three_algebras_agree(puma):
    problem, model, _ = puma
    q = np.array([0.3, -1.1, 0.7, 0.2, 1.3, -0.4])
    num = forward(model.description, NumpyChainAlgebra(model.description, _subs(problem, q)))
    subs = _subs(problem, q)
    ring = model.ring_chain(model.chain("6"))
    for f in ("3", "6"):
        np.testing.assert_allclose(np.array(model.M0(f).xreplace(subs).evalf(), dtype=float), num.M(f), atol=1e-12)
        np.testing.assert_allclose(np.array(ring.algebra.ring.to_matrix(ring.M(f)).xreplace(subs).evalf(),
                                            dtype=float), num.M(f), atol=1e-12)
    for i in range(6):
        np.testing.assert_allclose(np.array(ring.algebra.ring.to_matrix(ring.L(i, "6")).xreplace(subs).evalf(),
                                            dtype=float), num.L(i, "6"), atol=1e-12)


def _pose_along(problem, model, q0, qd, qdd, t, frame):
    """⁰M of `frame` at q(t) = q0 + qd t + qdd t²/2 (the reference of the derivatives)."""
    q = q0 + qd * t + qdd * t * t / 2
    return forward(model.description, NumpyChainAlgebra(model.description, _subs(problem, q))).M(frame)


@pytest.fixture(scope="module")
def scara():
    problem = load_problem(PROBLEMS / "scara-rrp.yaml")
    return problem, RobotModel(problem)


@pytest.mark.parametrize("robot, frame, point", [("tangle", "1", "P"), ("tangle", "2", "P"),
                                                 ("scara", "3", "E")])
def test_w_and_h_are_finite_differences_of_m(request, robot, frame, point):
    """W = Ṁ M⁻¹ and H = M̈ M⁻¹ by central differences, for the numpy and the sympy route
    (Rivals and Coriolis; the non-constant twist of a frame moved by two joints, and the
    constant twists of the SCARA's frames, H = L q̈ + L² q̇²)."""
    problem, model = request.getfixturevalue(robot)
    rng = np.random.default_rng(3)
    q0, qd, qdd = (rng.uniform(-1, 1, len(problem.joints)) for _ in range(3))
    h = 1e-4
    m = [_pose_along(problem, model, q0, qd, qdd, t, frame) for t in (-h, 0.0, h)]
    inv = np.linalg.inv(m[1])
    w_ref = (m[2] - m[0]) / (2 * h) @ inv
    h_ref = (m[2] - 2 * m[1] + m[0]) / h ** 2 @ inv
    subs = _subs(problem, q0, qd, qdd)
    num = forward(model.description, NumpyChainAlgebra(model.description, subs))
    np.testing.assert_allclose(num.W(frame), w_ref, atol=1e-6)
    np.testing.assert_allclose(num.H(frame), h_ref, atol=1e-5)
    sym = forward(model.description, SympyChainAlgebra(model.description))
    for value, ref, tol in ((sym.W(frame), w_ref, 1e-6), (sym.H(frame), h_ref, 1e-5)):
        np.testing.assert_allclose(np.array(value.xreplace(subs).evalf(), dtype=float), ref, atol=tol)
    # a point: ⁰p̈ = last column of H at the point's auxiliary frame, against differences
    p = [np.append(_point_along(problem, model, q0, qd, qdd, t, point), 1.0) for t in (-h, 0.0, h)]
    pframe = model.description.points[point].frame
    np.testing.assert_allclose((num.W(pframe) @ p[1])[:3], (p[2] - p[0])[:3] / (2 * h), atol=1e-6)
    np.testing.assert_allclose((num.H(pframe) @ p[1])[:3], (p[2] - 2 * p[1] + p[0])[:3] / h ** 2, atol=1e-5)


def _point_along(problem, model, q0, qd, qdd, t, name):
    q = q0 + qd * t + qdd * t * t / 2
    return forward(model.description, NumpyChainAlgebra(model.description, _subs(problem, q))).point(name)


def test_each_quantity_is_computed_once(tangle):
    problem, model = tangle
    calls = []

    class Counting(SympyChainAlgebra):
        def compose(self, a, b):
            calls.append("compose")
            return super().compose(a, b)

        def act(self, m, a):
            calls.append("act")
            return super().act(m, a)

    data = forward(model.description, Counting(model.description))
    first = data.H("2")
    assert data.H("2") is first and data.W("2") is data.W("2")
    data.L(0, "2"), data.L(3, "2"), data.point("P")
    assert calls.count("compose") == 2          # ⁰M₁, ⁰M₂
    assert calls.count("act") == 4              # one moved twist per (frame, joint)
    assert sp.simplify(data.M("2") - model.M0("2")) == sp.zeros(4, 4)


def test_the_body_frame_route_is_the_l_matrix_seen_in_the_body(puma, tangle):
    """ᵇLᵢ = ⁰M⁻¹ ⁰Lᵢ ⁰M (numpy, and exactly in the trig ring), ᵃM_f ⁰M_a = ⁰M_f."""
    problem, model, _ = puma
    q = np.array([0.3, -1.1, 0.7, 0.2, 1.3, -0.4])
    num = forward(model.description, NumpyChainAlgebra(model.description, _subs(problem, q)))
    for i in range(6):
        m = num.M("6")
        np.testing.assert_allclose(num.body_L(i, "6"), np.linalg.inv(m) @ num.L(i, "6") @ m, atol=1e-12)
    np.testing.assert_allclose(num.M("2") @ num.relative("2", "5"), num.M("5"), atol=1e-12)
    ring = model.ring_chain(model.chain("4"))
    alg = ring.algebra
    for i in range(4):
        m = ring.M("4")
        assert ring.body_L(i, "4") == alg.mul(alg.mul(alg.inverse(m), ring.L(i, "4")), m)
    tproblem, tmodel = tangle
    sym = forward(tmodel.description, SympyChainAlgebra(tmodel.description))
    m, subs = sym.M("2"), _subs(tproblem, [0.4, -0.8, 0.15, 0.6])
    for i in range(4):
        diff = (sym.body_L(i, "2") - rigid_inverse(m) * sym.L(i, "2") * m).xreplace(subs).evalf()
        assert np.abs(np.array(diff, dtype=float)).max() < 1e-12


@pytest.mark.parametrize("algebra", ["trig", pytest.param("sympy", marks=pytest.mark.slow)])
def test_the_chain_data_over_the_dynamics_engines_own_algebra(algebra):
    """The route the dynamics engine takes (ListChainAlgebra over its own ring, or its
    SympyAlgebra fallback, and its poses): ⁰M, ⁰L and the body-frame ᵇL of ChainData equal the
    engine's public M0, L0 and Lb at random numbers."""
    from support.robots import anthropomorphic_3r
    from robosolve.dynamics.engine import DynamicsEngine
    from robosolve.core.chain.algebras import ListChainAlgebra

    r = anthropomorphic_3r()
    eng = DynamicsEngine(**r.engine_inputs(), algebra=algebra)
    alg = eng.alg
    local = {f: [[alg.from_expr(x) for x in row] for row in eng.local(f).tolist()] for f in eng.order}

    class Structure:                       # what forward.py asks of a description
        parent = staticmethod(lambda f: None if f == "0" else eng.frames[f].parent)
        chain = staticmethod(eng.path)
        moved_by = staticmethod(lambda f: [i for i in range(eng.n) if eng.local(f).has(eng.q[i])])
        joint_frame = staticmethod(eng.joint_frame)

    data = forward(Structure, ListChainAlgebra(alg, local))
    rng = np.random.default_rng(11)
    subs = {**{k: float(v) for k, v in r.values.items()}, **dict(zip(eng.q, rng.uniform(-1, 1, eng.n)))}

    def num(m):
        return np.array(sp.Matrix(m).xreplace(subs).evalf(), dtype=float)

    last = eng.order[-1]
    np.testing.assert_allclose(num(alg.to_matrix(data.M(last))), num(eng.M0(last)), atol=1e-12)
    for i in range(eng.n):
        np.testing.assert_allclose(num(alg.to_matrix(data.L(i, last))), num(eng.L0(i, last)), atol=1e-12)
        np.testing.assert_allclose(num(alg.to_matrix(data.body_L(i, last))), num(eng.Lb(i, last)), atol=1e-12)


def test_a_context_without_names_still_solves(tangle):
    """A SolveContext built by hand (no LaTeX names handed in) answers with sympy's own LaTeX;
    the pipeline's context names the poses' factors."""
    from robosolve.run.pipeline import solve_context
    from robosolve.solvers import position
    from robosolve.solvers.base import SolveContext

    problem, model = tangle
    plain = position.solve(problem.questions[0], SolveContext(problem, model))
    named = position.solve(problem.questions[0], solve_context(problem, model))
    assert plain.numeric == named.numeric
    lhs = [lhs for step in named.steps for lhs, _ in step.equations]
    assert any("R_{z}" in x for x in lhs) and not any("R_{z}" in x for step in plain.steps
                                                     for x, _ in step.equations)
