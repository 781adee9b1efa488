"""The rank conditions of wide Jacobians by structure (robosolve.kinematics.wide_rank and
singularities), checked against an independent reference: Robotics Toolbox robots built from the
same DH tables (`jacob0`, numpy's SVD). At random configurations ON each reported family J
loses rank (σ_min < 1e-9 σ_max); at random generic configurations it does not. Families given
by equations are met by a least-squares solve of their equations from random starts."""

from pathlib import Path

import numpy as np
import pytest
import sympy as sp
from scipy.optimize import least_squares

from robosolve.kinematics.singularities import SearchBudget, find_singularities
from robosolve.kinematics.wide_rank import OverBudget, wide_minors
from robosolve.load.loader import load_problem
from robosolve.model import RobotModel
from robosolve.solvers.base import Budgets

rtb = pytest.importorskip("roboticstoolbox")
from spatialmath import SE3  # noqa: E402  (with the toolbox)

ROOT = Path(__file__).resolve().parents[2]


def _engine(name, geometric):
    problem = load_problem(ROOT / "problems" / f"{name}.yaml")
    model = RobotModel(problem)
    pframe, plocal = model.point_local("E")
    wide = wide_minors(model, pframe, plocal, problem.last_frame, geometric, 3000)
    params = {s: v for s, v in problem.parameters.items()}
    # the solvers' own counted budget: the bundled arms' searches must finish within it
    res = find_singularities(None, model.q, {q: "revolute" for q in model.q}, params,
                             minors=wide.minors, work=SearchBudget(Budgets().rank_nodes))
    return problem, model, wide, res


def _values(problem):
    return {s.name: float(v) for s, v in problem.parameters.items() if v is not None}


def _ur5_reference(p):
    links = [rtb.RevoluteDH(d=p["d1"], alpha=np.pi / 2), rtb.RevoluteDH(a=p["a2"]), rtb.RevoluteDH(a=p["a3"]),
             rtb.RevoluteDH(d=p["d4"], alpha=np.pi / 2), rtb.RevoluteDH(d=p["d5"], alpha=-np.pi / 2),
             rtb.RevoluteDH(d=p["d6"])]
    robot = rtb.DHRobot(links)
    return lambda q: robot.jacob0(q)[:3, :]          # the flange's position Jacobian


def _panda_reference(p):
    links = [rtb.RevoluteMDH(d=p["d1"]), rtb.RevoluteMDH(alpha=-np.pi / 2),
             rtb.RevoluteMDH(alpha=np.pi / 2, d=p["d3"]), rtb.RevoluteMDH(alpha=np.pi / 2, a=p["a4"]),
             rtb.RevoluteMDH(alpha=-np.pi / 2, a=-p["a4"], d=p["d5"]), rtb.RevoluteMDH(alpha=np.pi / 2),
             rtb.RevoluteMDH(alpha=np.pi / 2, a=p["a6"])]
    robot = rtb.DHRobot(links, tool=SE3(0, 0, p["d7"]))
    return robot.jacob0


def _ratio(jac, q):
    sv = np.linalg.svd(jac(np.asarray(q, dtype=float)), compute_uv=False)
    return sv[-1] / sv[0]


def _points_on(cond, model, params, rng, count=4):
    """Configurations on the family: its values, random others; its equations solved by least squares."""
    q = list(model.q)
    fixed = {s: float(sp.sympify(v).xreplace(params)) for s, v in cond.values}
    eqs = [sp.sympify(e).xreplace(params).xreplace({s: v for s, v in fixed.items()}) for e in cond.equations]
    free = [s for s in q if s not in fixed]
    f = sp.lambdify([free], eqs, "numpy") if eqs else None
    out = []
    for _ in range(50 * count):
        x0 = rng.uniform(-np.pi, np.pi, len(free))
        if f is not None:
            sol = least_squares(lambda x: np.asarray(f(x), dtype=float), x0, xtol=1e-15, ftol=1e-15, gtol=1e-15)
            if np.max(np.abs(f(sol.x))) > 1e-12:
                continue
            x0 = sol.x
        d = dict(zip(free, x0))
        d.update(fixed)
        out.append([d[s] for s in q])
        if len(out) == count:
            break
    return out


def _check(name, geometric, reference, seed):
    problem, model, wide, res = _engine(name, geometric)
    values = _values(problem)
    params = {s: v for s, v in problem.parameters.items() if v is not None}
    jac = reference(values)
    rng = np.random.default_rng(seed)
    assert res.conditions
    for cond in res.conditions:
        points = _points_on(cond, model, params, rng)
        assert points, cond.mapping()       # every family is met
        for point in points:
            assert _ratio(jac, point) < 1e-9, (cond.mapping(), point)
    for _ in range(20):
        assert _ratio(jac, rng.uniform(-np.pi, np.pi, len(model.q))) > 1e-6
    return wide, res


def test_ur5_flange_position_jacobian_rank_conditions():
    wide, res = _check("ur5", False, _ur5_reference, 5)
    assert wide.zero_columns == [5]        # joint 6 does not move the flange's origin
    assert wide.terms <= 3000
    # the wrist aligned (s5 = 0) with the elbow stretched or folded: a family the search must find
    assert any(str(q) == "q5" and v == 0 for c in res.conditions for q, v in c.values)


def test_panda_geometric_jacobian_rank_conditions():
    _check("panda", True, _panda_reference, 7)


def test_the_minors_equal_the_jacobians_minors():
    """The minors by structure (rotated rows) are J's own maximal minors: numbers against the toolbox."""
    problem = load_problem(ROOT / "problems" / "ur5.yaml")
    model = RobotModel(problem)
    pframe, plocal = model.point_local("E")
    wide = wide_minors(model, pframe, plocal, problem.last_frame, False, 3000)
    values = _values(problem)
    jac = _ur5_reference(values)
    rng = np.random.default_rng(3)
    params = {s: v for s, v in problem.parameters.items() if v is not None}
    for _ in range(3):
        q = rng.uniform(-np.pi, np.pi, 6)
        jn = jac(q)
        subs = dict(params)
        subs.update(dict(zip(model.q, q)))
        for cols, minor in zip(wide.columns, wide.minors):
            want = np.linalg.det(jn[:, cols])
            got = float(sp.sympify(minor).xreplace(subs)) if minor != 0 else 0.0
            assert abs(got - want) < 1e-12


def test_a_tiny_term_budget_stops_the_minors():
    problem = load_problem(ROOT / "problems" / "ur5.yaml")
    model = RobotModel(problem)
    pframe, plocal = model.point_local("E")
    with pytest.raises(OverBudget):
        wide_minors(model, pframe, plocal, problem.last_frame, False, 50)


@pytest.mark.parametrize("name, geometric", [("ur5", False), ("ur5", True), ("panda", True)])
def test_rows_frame_by_frame_are_the_rows_in_each_frame(name, geometric):
    """The Jacobian's rows in every frame of the chain, each from the one before by its local pose
    (wide_rank._rows_in_every_frame), are the same ring elements as ⁰R_kᵀ·rows computed for each
    frame k (_rows_in): the normal form modulo sᵢ² + cᵢ² = 1 is unique (a self-check of two
    routes; the minors themselves are checked against Robotics Toolbox above)."""
    from robosolve.kinematics import wide_rank as W
    from robosolve.kinematics.structured_det import RingChain

    problem = load_problem(ROOT / "problems" / f"{name}.yaml")
    model = RobotModel(problem)
    pframe, plocal = model.point_local("E")
    frame = problem.last_frame
    top = frame if geometric and pframe in model.chain(frame) + ["0"] else pframe
    ring = RingChain(model, top, points=[list(plocal)])
    n, m = len(model.q), 6 if geometric else 3
    w = ring.point0(pframe, ring.points[0])
    l_point = [ring.l0(i, pframe) for i in range(n)]
    l_frame = [ring.l0(i, frame) for i in range(n)] if geometric else l_point
    rows = ring.columns(l_point, l_frame, w)[:m]
    direct = [W._rows_in(ring, rows, k, geometric, w) for k in ["0"] + list(ring.chain)]
    assert W._rows_in_every_frame(ring, rows, geometric, w) == direct
