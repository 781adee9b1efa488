"""The Franka Panda (problems/panda.yaml: modified DH, 7 joints, 7 point masses): its equations
of motion against Robotics Toolbox (`inertia`, `coriolis`, `gravload`, `rne`) built from the
same modified DH table and point masses (r = centre of mass, I = 0), at random states.

Three routes are checked: the numeric code (`ChainDynamics`, what the solver's numbers come
from), the engine's polynomials in cos/sin (what results.json prints, evaluated here), and the
whole solve of the problem (results.json's numbers and symbolic strings)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import sympy as sp

rtb = pytest.importorskip("roboticstoolbox")

from robosolve.dynamics.bridge import engine_inputs  # noqa: E402
from robosolve.dynamics.engine import DynamicsEngine  # noqa: E402
from robosolve.dynamics.numeric import ChainDynamics  # noqa: E402
from robosolve.load.loader import load_problem, load_problem_text  # noqa: E402
from robosolve.model import RobotModel  # noqa: E402

PROBLEMS = Path(__file__).resolve().parents[2] / "problems"


def _values(problem) -> dict:
    return {s: v for s, v in problem.parameters.items()}


def _rtb_twin(problem):
    """The problem's modified DH chain (frames with a body) and point masses as an RTB DHRobot."""
    values = _values(problem)

    def num(e):
        return float(sp.N(sp.sympify(e).xreplace(values)))

    links = []
    for name, frame in problem.frames.items():
        body = next((b for b in problem.bodies if b.frame == name), None)
        if body is None:
            continue            # the flange: no mass, after the last joint
        al, a, _, d = frame.factors
        links.append(rtb.RevoluteMDH(d=num(d), a=num(a), alpha=num(al), m=float(body.mass),
                                     r=[num(v) for v in body.data["at"]], I=np.zeros(3), Jm=0.0, G=1.0))
    g = next(v for s, v in values.items() if s.name == "g")
    return rtb.DHRobot(links, gravity=[0, 0, -float(g)])


def _close(x, ref):
    ref = np.asarray(ref, dtype=float)
    return np.allclose(x, ref, rtol=1e-8, atol=1e-8 * max(1.0, np.abs(ref).max()))


def _cut(joints: int) -> str:
    """problems/panda.yaml with its first `joints` joints, rows and bodies (no questions)."""
    text = (PROBLEMS / "panda.yaml").read_text()
    head, rest = text.split("joints:\n", 1)
    lines = rest.split("questions:")[0].splitlines()
    keep = []
    for line in lines:
        for k in range(joints + 1, 8):
            if f"q{k}" in line or f'frame: "{k}"' in line or line.startswith("frames:") or "F:" in line:
                break
        else:
            keep.append(line)
    return head + "joints:\n" + "\n".join(keep) + "\nquestions:\n  - {type: equations_of_motion}\n"


@pytest.fixture(scope="module")
def panda():
    problem = load_problem(PROBLEMS / "panda.yaml")
    return problem, RobotModel(problem), _rtb_twin(problem)


def test_rtb_twin_matches_the_published_panda(panda):
    """Our table and masses are the ones of RTB's own models.DH.Panda, whose frame 7 is our
    flange F (d7 folded into its last row) and whose tool is a further Tz(0.103) Rz(−π/4)."""
    problem, model, robot = panda
    ref = rtb.models.DH.Panda()
    q = np.random.default_rng(1).uniform(-2, 2, 7)
    flange = np.array(model.M0("F").xreplace({**_values(problem), **dict(zip(model.q, q))}).evalf(),
                      dtype=float)
    ref_flange = ref.fkine(q).A @ np.linalg.inv(ref.tool.A)
    assert np.allclose(flange, ref_flange, atol=1e-12)
    assert np.allclose(robot.fkine(q).A @ _tz(0.107), ref_flange, atol=1e-12)
    for k, (ours, theirs) in enumerate(zip(robot.links, ref.links)):
        assert ours.m == pytest.approx(theirs.m, abs=1e-12)
        shift = np.array([0, 0, 0.107 if k == 6 else 0.0])
        # link 1's centre of mass height lies on joint 1's axis: RTB's 0 there changes nothing
        mask = np.array([1, 1, 0 if k == 0 else 1])
        assert np.allclose(mask * (ours.r - shift), mask * theirs.r, atol=1e-12)


def _tz(d):
    out = np.eye(4)
    out[2, 3] = d
    return out


def test_numeric_code_against_rtb(panda):
    problem, model, robot = panda
    nd = ChainDynamics(DynamicsEngine(**engine_inputs(model)), _values(problem))
    rng = np.random.default_rng(26)
    for _ in range(5):
        q, qd, qdd = rng.uniform(-np.pi, np.pi, (3, 7))
        out = nd.evaluate(q, qd)
        assert _close(out["mass_matrix"], robot.inertia(q))
        assert _close(out["velocity_terms"], robot.coriolis(q, qd) @ qd)
        assert _close(out["gravity_terms"], robot.gravload(q))
        tau = out["mass_matrix"] @ qdd + out["velocity_terms"] + out["gravity_terms"]
        assert _close(tau, robot.rne(q, qd, qdd))


def test_four_joint_cut_polynomials_against_rtb():
    """The engine's polynomials (the symbolic answers) of the first four links, evaluated."""
    problem = load_problem_text(_cut(4), "panda-4.yaml")
    model = RobotModel(problem)
    robot = _rtb_twin(problem)
    eng = DynamicsEngine(**engine_inputs(model))
    alg, values = eng.alg, _values(problem)
    exprs = [alg.to_expr(x) for row in eng._rM() for x in row] + [alg.to_expr(x) for x in eng._rg()]
    f = sp.lambdify([model.q], [e.xreplace(values) for e in exprs])
    rng = np.random.default_rng(4)
    for _ in range(5):
        q = rng.uniform(-np.pi, np.pi, 4)
        out = np.array(f(q), dtype=float)
        assert _close(out[:16].reshape(4, 4), robot.inertia(q))
        assert _close(out[16:], robot.gravload(q))


AT = {"q1": 0.1, "q2": -0.4, "q3": 0.2, "q4": -1.9, "q5": 0.3, "q6": 1.5, "q7": 0.6,
      "q1_dot": 0.5, "q2_dot": -0.3, "q3_dot": 0.8, "q4_dot": 0.1, "q5_dot": -0.6, "q6_dot": 0.4,
      "q7_dot": 0.2, "q1_ddot": 1, "q2_ddot": -0.5, "q3_ddot": 0.2, "q4_ddot": 0.7, "q5_ddot": -1,
      "q6_ddot": 0.3, "q7_ddot": -0.8}


@pytest.fixture(scope="module")
def solved():
    """The Panda with one equations-of-motion question, solved in this process (~5 s)."""
    import json

    from robosolve.run.pipeline import solve_loaded

    text = (PROBLEMS / "panda.yaml").read_text().split("questions:")[0]
    text += "questions:\n  - type: equations_of_motion\n    at: {" + ", ".join(
        f"{k}: {v}" for k, v in AT.items()) + "}\n"
    problem = load_problem_text(text, "panda-eom.yaml")
    result = solve_loaded(problem)
    assert result.status == 0, result.messages
    doc = json.loads(result.files["results.json"])
    return problem, doc["answers"]["equations_of_motion"], result.files["report.md"].decode()


def test_solved_numbers_against_rtb(solved, panda):
    problem, answer, _ = solved
    robot = panda[2]
    q, qd, qdd = (np.array([AT[f"q{i}{s}"] for i in range(1, 8)], dtype=float)
                  for s in ("", "_dot", "_ddot"))
    num = answer["numeric"]
    assert _close(num["mass_matrix"], robot.inertia(q))
    assert _close(num["velocity_terms"], robot.coriolis(q, qd) @ qd)
    assert _close(num["gravity_terms"], robot.gravload(q))
    assert _close([num["actuators"][f"C{i}"] for i in range(1, 8)], robot.rne(q, qd, qdd))
    kinetic = 0.5 * qd @ robot.inertia(q) @ qd
    assert num["kinetic_energy"]["total"] == pytest.approx(kinetic, rel=1e-9)


def _evaluate(problem, texts):
    """Each symbolic string read back by sympy and evaluated at AT with the parameters."""
    values = {**{s: v for s, v in problem.parameters.items()}}
    names = {s.name: s for s in values}
    for k, v in AT.items():
        names.setdefault(k, sp.Symbol(k))
    values.update({names[k]: v for k, v in AT.items()})
    return [float(sp.sympify(t, locals=names).xreplace(values)) for t in texts]


def test_solved_symbolic_mass_matrix_and_gravity_read_back(solved):
    """results.json's symbolic M(q) and g(q), read back by sympy, give the numbers."""
    problem, answer, report = solved
    sym, num = answer["symbolic"], answer["numeric"]
    m = _evaluate(problem, [x for row in sym["mass_matrix"] for x in row])
    assert _close(np.array(m).reshape(7, 7), num["mass_matrix"])
    assert _close(_evaluate(problem, sym["gravity_terms"]), num["gravity_terms"])
    assert "M(q)[1,1] = \\text{(long:" in report and "M(q)[7,7] = " in report
    for key in ("kinetic_energy", "potential_energy"):
        names = ["total", "link2", "link7"]
        assert _close(_evaluate(problem, [sym[key][k] for k in names]), [num[key][k] for k in names])


@pytest.mark.slow
def test_solved_symbolic_velocity_terms_and_equations_read_back(solved):
    problem, answer, _ = solved
    sym, num = answer["symbolic"], answer["numeric"]
    assert _close(_evaluate(problem, sym["velocity_terms"]), num["velocity_terms"])
    lhs = _evaluate(problem, [e.split(" = ")[0] for e in sym["equations"]])
    assert _close(lhs, [num["actuators"][f"C{i}"] for i in range(1, 8)])


def test_term_by_term_reduction_is_the_division():
    """TrigAlgebra.reduce's term-by-term elimination of sin² gives the normal form of the
    division by {sᵢ² + cᵢ² − 1}: equal with exact coefficients, within rounding with decimals."""
    from robosolve.core.trigring import TrigAlgebra

    q = sp.symbols("q1:4", real=True)
    a, b = sp.symbols("a b")
    rng = np.random.default_rng(9)
    for decimal in (False, True):
        exprs = []
        for _ in range(6):
            terms = []
            for _ in range(8):
                c = (sp.Float(rng.normal()) if decimal
                     else sp.Rational(int(rng.integers(-9, 9)), int(rng.integers(1, 5))))
                e = [int(x) for x in rng.integers(0, 4, 6)]
                trig = sp.Mul(*[sp.sin(qi) ** e[k] * sp.cos(qi) ** e[3 + k] for k, qi in enumerate(q)])
                terms.append(c * (a if e[0] % 2 else b) * trig)
            exprs.append(sp.Add(*terms))
        alg = TrigAlgebra.from_inputs(list(q), exprs)
        alg.term_by_term = True
        for p in alg.elements:
            for r in (p, p * p):
                fast, division = alg.reduce(r), r.rem(alg._basis)
                if decimal:
                    assert all(abs(float(c2)) < 1e-9 for c2 in _coefficients(fast - division))
                    assert all(m[k] < 2 for m in fast for k, _ in alg._slots)
                else:
                    assert fast == division


def _coefficients(p):
    out = []
    for c in p.values():
        out += list(c.values()) if hasattr(c, "values") else [c]
    return out


def test_bridge_numeric_and_lazy_expressions_of_the_big_robot(panda):
    """Through the model bridge (what joint torques and simulations use): numeric code for a
    big robot, and its sympy expressions built on first use (here g(q), against RTB)."""
    from robosolve.dynamics.bridge import dynamics_for, numeric_for
    from robosolve.solvers.base import SolveContext

    problem, model, robot = panda
    values = SolveContext(problem, model).substitutions({})
    nd, note = numeric_for(model, values)
    assert note is None
    dyn = dynamics_for(model)
    assert dyn.engine.large and "gravity_terms" not in vars(dyn)
    g = sp.lambdify([model.q], list(dyn.gravity_terms.xreplace(_values(problem))))
    rng = np.random.default_rng(8)
    for _ in range(3):
        q, qd, qdd = rng.uniform(-np.pi, np.pi, (3, 7))
        assert _close(nd.actuators(q, qd, qdd), robot.rne(q, qd, qdd))
        assert _close(g(q), robot.gravload(q))
