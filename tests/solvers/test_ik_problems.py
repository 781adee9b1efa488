"""IK on every robot of problems/: closed form and numeric sets agree, answers verified by FK.

For each problem file with a robot of up to three joints: a target is made by
the direct kinematics at a configuration inside the limits (the first joints'
coordinates of E), and solve_ik must return both sets, equal, containing that
configuration. Every inverse_kinematics question of the files is solved through
the pipeline and each reported solution is checked with the model's own FK.
"""

from __future__ import annotations

import dataclasses
import math
import os
from pathlib import Path

import pytest
import sympy as sp

from robosolve.ik.engine import IKJoint, solve_ik
from robosolve.ik.numeric import wrap_angle
from robosolve.load.loader import load_problem
from robosolve.model import RobotModel
from robosolve.run.pipeline import solve_context, solve_problem

PROBLEMS = sorted((Path(__file__).resolve().parents[2] / "problems").glob("*.yaml"))
EXTRA = os.environ.get("ROBOSOLVE_IK_EXTRA_PROBLEMS")    # e.g. other folders, ':'-separated
if EXTRA:
    PROBLEMS += sorted(p for d in EXTRA.split(":") for p in Path(d).glob("*.yaml"))


def _model(path):
    problem = load_problem(path)
    if not problem.has_robot or not problem.joints:
        pytest.skip("no robot")
    return problem, RobotModel(problem), solve_context(problem, RobotModel(problem))


@pytest.mark.parametrize("path", PROBLEMS, ids=[p.stem for p in PROBLEMS])
def test_closed_form_and_numeric_agree_on_every_robot(path):
    problem, model, ctx = _model(path)
    n = len(model.joints)
    if n > 3 or "E" not in model.points:
        pytest.skip("closed-form comparison for robots of up to 3 joints with a point E")
    params = ctx.substitutions({})
    values = {s: float(v) for s, v in params.items() if v is not None and not v.free_symbols}
    joints, q_star = [], {}
    for k, j in enumerate(model.joints):
        lim = None
        if j.limits is not None:
            lim = tuple(float(sp.N(v.xreplace(params))) for v in j.limits)
        joints.append(IKJoint(j.symbol, j.is_revolute, lim))
        if lim is not None:
            lo, hi = lim
            q_star[j.name] = lo + (0.37 + 0.11 * k) * (hi - lo)
        else:
            q_star[j.name] = 0.4 + 0.3 * k
    p = model.point0("E")
    subs = dict(values)
    subs.update({j.symbol: q_star[j.name] for j in model.joints})
    coords = [sp.Symbol(f"E.{a}") for a in "xyz"]
    # choose n coordinates that depend on the joints
    eqs = []
    for c, e in zip(coords, p):
        if len(eqs) < n and e.free_symbols & set(model.q):
            eqs.append((e, c))
            values[c] = float(e.evalf(subs=subs))
    if len(eqs) < n:
        pytest.skip("E has fewer independent coordinates than joints")
    res = solve_ik(eqs, joints, values, target_symbols=set(coords))
    if res.closed_form is None:
        pytest.skip(f"numeric only here ({res.closed_form_note})")
    assert res.agree, (res.closed_form_values, res.all_solutions)
    assert any(all(abs(wrap_angle(s[j.name] - q_star[j.name]) if j.revolute else s[j.name] - q_star[j.name]) < 1e-8
                   for j in joints) for s in res.all_solutions)


@pytest.mark.parametrize("path", PROBLEMS, ids=[p.stem for p in PROBLEMS])
def test_ik_questions_of_problem_files_verified_by_fk(path):
    problem = load_problem(path)
    qs = [q for q in problem.questions if q.type == "inverse_kinematics"]
    if not qs:
        pytest.skip("no inverse_kinematics question")
    problem = dataclasses.replace(problem, questions=qs)    # the IK questions only (fast)
    report = solve_problem(problem)
    model = report.model
    ctx = solve_context(problem, model)
    for q, ans in zip(problem.questions, report.answers):
        if q.type != "inverse_kinematics":
            continue
        assert ans.error is None, ans.error
        params = ctx.substitutions({s: v for s, v in q.at.items() if s in problem.parameters})
        sols = ans.numeric["solutions"]
        if ans.extra.get("unreachable"):
            assert sols == [] and ans.extra["reason"]
            continue
        assert sols and ans.numeric["selected"] in sols
        for sol in sols:
            subs = dict(params)
            subs.update({j.symbol: sol[j.name] for j in model.joints})
            if not isinstance(q.options["target"], list):
                _check_pose(model, q, subs, params)
                continue
            for text, lhs, rhs in q.options["target"]:
                got = float(model.coordinate(lhs).evalf(subs=subs))
                want = float(sp.sympify(rhs).evalf(subs=subs))
                d = got - want
                if "theta" in text and "." not in text:
                    d = wrap_angle(d)
                assert abs(d) < 1e-9, (text, got, want)
            for j in model.joints:
                if j.limits is not None and j.is_revolute:
                    lo, hi = (float(sp.N(v.xreplace(params))) for v in j.limits)
                    v = sol[j.name]
                    assert any(lo - 1e-9 <= v + 2 * math.pi * k <= hi + 1e-9 for k in (-1, 0, 1))


def _check_pose(model, q, subs, params):
    """A pose target: the frame's (or the point's) pose by the model's own FK, entry by entry."""
    tgt = q.options["target"]
    frame = model.point_local(q.point)[0] if q.point_given else q.frame
    M = model.M0(frame).evalf(subs=subs)
    R = tgt.R.evalf(subs=params)
    p = tgt.p.evalf(subs=params)
    if q.point_given:
        p = p - R * model.point_local(q.point)[1].evalf(subs=params)
    for i in range(3):
        assert abs(float(M[i, 3] - p[i])) < 1e-9
        for j in range(3):
            assert abs(float(M[i, j] - R[i, j])) < 1e-9
