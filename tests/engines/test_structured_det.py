"""det J by structure (robosolve.kinematics.structured_det) and the PUMA 560's singular
configurations, checked against an independent reference: Robotics Toolbox's Puma560
(`jacob0`, standard DH, Corke's numbers) — det values at random configurations, rank loss
at every reported condition, and completeness against a scan for det sign changes."""

from pathlib import Path

import numpy as np
import pytest
import sympy as sp
from scipy.optimize import brentq

from robosolve.kinematics.structured_det import structured_det
from robosolve.load.loader import load_problem
from robosolve.run.pipeline import solve_problem

rtb = pytest.importorskip("roboticstoolbox")

ROOT = Path(__file__).resolve().parents[2]
RNG = np.random.default_rng(560)
PARAMS = {"d1": 0.6718, "a2": 0.4318, "d3": 0.15005, "a3": 0.0203, "d4": 0.4318}


@pytest.fixture(scope="module")
def puma_answer(tmp_path_factory):
    src = (ROOT / "problems" / "puma560-dynamics.yaml").read_text(encoding="utf-8")
    head = src.split("\nquestions:")[0]
    for k, v in PARAMS.items():       # the toolbox's rounding of d1
        head = head.replace(f"  {k}: ", f"  {k}: {v} #", 1)
    path = tmp_path_factory.mktemp("puma") / "puma-jacobian.yaml"
    path.write_text(head + "\nquestions:\n  - {type: jacobian, geometric: true, at: "
                    "{q1: 0.1, q2: 0.7, q3: -0.4, q4: 0.3, q5: 0.9, q6: -0.2}}\n", encoding="utf-8")
    report = solve_problem(load_problem(path))
    (answer,) = report.answers
    assert answer.error is None
    return answer


@pytest.fixture(scope="module")
def puma():
    return rtb.models.DH.Puma560()


def _numbers(expr):
    """The parameters replaced by the toolbox's values (matched by name: the problem's
    symbols carry assumptions)."""
    expr = sp.sympify(expr)
    return expr.xreplace({s: PARAMS[s.name] for s in expr.free_symbols if s.name in PARAMS})


def _joints(expr):
    by_name = {s.name: s for s in sp.sympify(expr).free_symbols}
    return [by_name.get(f"q{i}", sp.Symbol(f"q{i}")) for i in range(1, 7)]


def _det_function(det):
    return sp.lambdify([_joints(det)], _numbers(det), "numpy")


def test_symbolic_det_matches_the_toolbox(puma_answer, puma):
    det = _det_function(puma_answer.symbolic["det"])
    for _ in range(20):
        q = RNG.uniform(-np.pi, np.pi, 6)
        ref = np.linalg.det(puma.jacob0(q))
        assert det(q) == pytest.approx(ref, rel=1e-9, abs=1e-12)


def test_det_is_the_arm_factor_times_the_wrist_factor(puma_answer):
    det = sp.sympify(puma_answer.symbolic["det"])
    q = _joints(det)
    factors = [f for f in sp.Mul.make_args(det) if f.free_symbols & set(q)]
    joints = [sorted(str(s) for s in f.free_symbols & set(q)) for f in factors]
    assert sorted(joints) == [["q2", "q3"], ["q3"], ["q5"]]
    assert any(step.title == "Decoupling at the wrist" for step in puma_answer.steps)


def _conditions(answer):
    values, equations = [], []
    for c in answer.symbolic["singularities"]:
        if isinstance(c, str):
            equations.append(c)
        else:
            values.append(c)
    return values, equations


def _value(text):
    return float(sp.sympify(text).xreplace({sp.Symbol(k): v for k, v in PARAMS.items()}))  # strings: plain symbols


def test_every_condition_makes_the_toolbox_jacobian_singular(puma_answer, puma):
    values, equations = _conditions(puma_answer)
    assert {tuple(c) for c in values} == {("q3",), ("q5",)}
    assert len(values) == 4 and len(equations) == 1
    for cond in values:
        for _ in range(3):
            q = RNG.uniform(-np.pi, np.pi, 6)
            for name, text in cond.items():
                q[int(name[1]) - 1] = _value(text)
            assert np.linalg.svd(puma.jacob0(q), compute_uv=False)[-1] < 1e-9, cond
    # the shoulder: a root of the equation in q2 (q3 and the others random)
    lhs = sp.sympify(equations[0].split("=")[0]).xreplace({sp.Symbol(k): v for k, v in PARAMS.items()})
    f = sp.lambdify(sp.symbols("q2 q3"), lhs)
    q = RNG.uniform(-np.pi, np.pi, 6)
    grid = np.linspace(-np.pi, np.pi, 721)
    vals = [f(t, q[2]) for t in grid]
    k = next(i for i in range(len(grid) - 1) if vals[i] * vals[i + 1] < 0)
    q[1] = brentq(lambda t: f(t, q[2]), grid[k], grid[k + 1], xtol=1e-14)
    assert np.linalg.svd(puma.jacob0(q), compute_uv=False)[-1] < 1e-9


def _roots(f, grid):
    vals = np.array([f(t) for t in grid])
    ks = np.nonzero(np.sign(vals[:-1]) != np.sign(vals[1:]))[0]
    return [brentq(f, grid[k], grid[k + 1], xtol=1e-12) for k in ks]


@pytest.mark.parametrize("joint", [1, 2, 4])
def test_no_singularity_missed_along_a_joint(puma_answer, puma, joint):
    """Scan q2, q3 or q5 over (−π, π] with the toolbox: the sign changes of det J are
    exactly the reported values of that joint and the roots of the reported equation."""
    values, equations = _conditions(puma_answer)
    name = f"q{joint + 1}"
    grid = np.linspace(-np.pi, np.pi, 3601) + 1.3e-3       # π inside the scanned range
    lhs = _numbers(equations[0].split("=")[0])
    by_name = {s.name: s for s in lhs.free_symbols}
    while True:            # other joints random, with the reported roots apart on the grid
        q = RNG.uniform(-np.pi, np.pi, 6)
        reported = [_value(c[name]) for c in values if name in c]
        if name in by_name:
            f = sp.lambdify([by_name[name]], lhs.xreplace(
                {s: q[int(n[1]) - 1] for n, s in by_name.items() if n != name}))
            reported += _roots(f, grid)
        gaps = np.diff(sorted(reported))
        if not len(gaps) or gaps.min() > 0.01:
            break

    def det(t):
        qq = q.copy()
        qq[joint] = t
        return np.linalg.det(puma.jacob0(qq))

    def wrap(xs):
        return sorted({round(float(np.angle(np.exp(1j * x))), 9) for x in xs})

    found, reported = wrap(_roots(det, grid)), wrap(reported)
    assert len(found) == len(reported) > 0
    for a, b in zip(found, reported):
        assert abs(a - b) < 1e-6


def test_structured_det_of_a_block_triangular_matrix():
    """A 4×4 with a zero block, rows and columns shuffled: the product of the blocks'
    determinants equals sympy's det (independent), with sin² + cos² = 1 used."""
    x, y, z, a = sp.symbols("x y z a")
    q = [x, y, z]
    blocks = sp.Matrix([
        [sp.cos(x), -sp.sin(x), 0, 0],
        [sp.sin(x), sp.cos(x), 0, 0],
        [a * sp.sin(y), sp.cos(z), a * sp.cos(y) * sp.sin(z), 1],
        [sp.cos(y + z), 3, sp.sin(z), sp.cos(y)],
    ])
    m = blocks.extract([2, 0, 3, 1], [1, 3, 0, 2])
    out = structured_det(m, q)
    assert len(out.blocks) == 2
    ref = m.det(method="berkowitz")
    for _ in range(5):
        sub = {s: RNG.uniform(-2, 2) for s in (x, y, z, a)}
        assert float(out.det.xreplace(sub)) == pytest.approx(float(ref.xreplace(sub)), rel=1e-12)
    assert not out.det.has(sp.Pow) or all(not p.base.has(x) for p in out.det.atoms(sp.Pow))
