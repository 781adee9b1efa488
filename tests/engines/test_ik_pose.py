"""IK of a pose (robosolve.ik.pose) against Robotics Toolbox for Python (test-only reference).

- PUMA 560 at random generic poses: the 8 solutions of kinematic decoupling equal RTB's
  `ikine_a` for its 8 configurations, each reaching the target to 1e-9 (RTB's `fkine`).
- UR5: the 8 numeric solutions reach the target to 1e-9 and contain every solution RTB's
  `ikine_LM` finds from many starts.
- An unreachable pose is an answer with a reason.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import sympy as sp

rtb = pytest.importorskip("roboticstoolbox")

from robosolve.core.transforms import dh_standard  # noqa: E402
from robosolve.ik.engine import IKJoint  # noqa: E402
from robosolve.core.angles import wrap_angle  # noqa: E402
from robosolve.ik.pose import solve_pose  # noqa: E402

NAMES = [f"q{i}" for i in range(1, 7)]


def _factors(robot):
    qs = sp.symbols("q1:7")
    return [dh_standard(q + float(L.offset), float(L.d), float(L.a), float(L.alpha))
            for L, q in zip(robot.links, qs)], [IKJoint(q) for q in qs]


def _contains(sols, q, tol):
    return any(all(abs(wrap_angle(s[n] - float(v))) < tol for n, v in zip(NAMES, q)) for s in sols)


def _check_reaches(robot, sols, T):
    for s in sols:
        assert np.max(np.abs(robot.fkine([s[n] for n in NAMES]).A - T)) < 1e-9


@pytest.mark.parametrize("seed", [1, 7])
def test_puma560_decoupling_matches_ikine_a(seed):
    puma = rtb.models.DH.Puma560()
    F, joints = _factors(puma)
    rng = np.random.default_rng(seed)
    q0 = rng.uniform(-2.5, 2.5, 6)
    q0[4] = rng.choice([-1, 1]) * rng.uniform(0.3, 2.5)      # generic: away from the wrist singularity
    q0[2] = rng.uniform(-1.0, 1.0)
    T = puma.fkine(q0).A
    res = solve_pose(F, joints, T[:3, :3], T[:3, 3])
    assert res.status == "ok" and res.method == "decoupling"
    assert len(res.solutions) == 8
    _check_reaches(puma, res.solutions, T)
    ref = [puma.ikine_a(puma.fkine(q0), config=c) for c in ("lun", "luf", "ldn", "ldf", "run", "ruf", "rdn", "rdf")]
    ref = [s.q for s in ref if s.success]
    assert len(ref) == 8
    for q in ref:
        assert _contains(res.solutions, q, 1e-6), q
    assert res.closed_form and {"q1", "q6"} <= set(res.closed_form[0])
    names = {str(s) for s in res.closed_form[0]["q1"].free_symbols}
    assert names <= {"px", "py", "pz", "r11", "r12", "r13", "r21", "r22", "r23", "r31", "r32", "r33"}


@pytest.mark.parametrize("model, method", [("Puma560", "decoupling"), ("UR5", "three parallel axes")])
def test_closed_form_evaluates_to_the_solutions(model, method):
    puma = getattr(rtb.models.DH, model)()
    F, joints = _factors(puma)
    q0 = [0.3, -0.5, 0.4, 0.7, -0.9, 1.2]
    T = puma.fkine(q0).A
    res = solve_pose(F, joints, T[:3, :3], T[:3, 3])
    assert res.method == method and len(res.solutions) == 8
    vals = {sp.Symbol(f"r{i + 1}{j + 1}"): T[i, j] for i in range(3) for j in range(3)}
    vals.update(dict(zip(sp.symbols("px py pz"), T[:3, 3])))
    hits = 0
    for br in res.closed_form:
        q = {}
        try:
            while len(q) < 6:       # each formula may use the joints found before it
                ready = [n for n in NAMES if n not in q
                         and {str(x) for x in br[n].free_symbols} <= {str(k) for k in vals} | set(q)]
                if not ready:
                    raise ValueError
                for n in ready:
                    v = complex(sp.N(br[n].xreplace({**vals, **{sp.Symbol(k): x for k, x in q.items()}})))
                    if abs(v.imag) > 1e-9:
                        raise ValueError
                    q[n] = v.real
        except (ValueError, TypeError, ZeroDivisionError):
            continue
        if np.max(np.abs(puma.fkine([q[n] for n in NAMES]).A - T)) < 1e-8:
            hits += 1
            assert _contains(res.solutions, [q[n] for n in NAMES], 1e-6)
    assert hits >= 8


@pytest.mark.parametrize("seed", [3])
def test_ur5_eight_solutions_against_fkine_and_ikine_lm(seed):
    from spatialmath import SE3

    ur5 = rtb.models.DH.UR5()
    F, joints = _factors(ur5)
    rng = np.random.default_rng(seed)
    q0 = rng.uniform(-2.5, 2.5, 6)
    T = ur5.fkine(q0).A
    res = solve_pose(F, joints, T[:3, :3], T[:3, 3])
    assert res.status == "ok" and len(res.solutions) == 8
    _check_reaches(ur5, res.solutions, T)
    assert _contains(res.solutions, q0, 1e-9)
    found = 0
    for k in range(24):
        s = ur5.ikine_LM(SE3(T), q0=rng.uniform(-np.pi, np.pi, 6), seed=k, tol=1e-12, ilimit=200)
        if s.success:
            found += 1
            assert _contains(res.solutions, s.q, 1e-5), s.q
    assert found > 0


def test_unreachable_pose_is_an_answer():
    puma = rtb.models.DH.Puma560()
    F, joints = _factors(puma)
    res = solve_pose(F, joints, np.eye(3), [3.0, 0.0, 0.5])
    assert res.status == "unreachable" and res.solutions == [] and "reach" in res.reason


def test_limits_reject_and_select():
    puma = rtb.models.DH.Puma560()
    F, joints = _factors(puma)
    joints[0] = IKJoint(joints[0].symbol, True, (0.0, 1.0))
    q0 = [0.3, -0.5, 0.4, 0.7, -0.9, 1.2]
    T = puma.fkine(q0).A
    res = solve_pose(F, joints, T[:3, :3], T[:3, 3], select={n: v for n, v in zip(NAMES, q0)})
    assert 0 < len(res.solutions) < 8 and res.rejected
    assert all(0 <= s["q1"] <= 1 for s in res.solutions)
    assert all(abs(res.selected[n] - v) < 1e-9 for n, v in zip(NAMES, q0))


# -- problem files: the pose target through the loader and the solver -----------------------------

PUMA_YAML = """robosolve: 1
name: puma-pose
parameters: {{d1: 0.67183, a2: 0.4318, d3: 0.15005, a3: 0.0203, d4: 0.4318}}
joints:
{joints}
dh:
  convention: standard
  rows:
    - {{theta: q1, d: d1, a: 0, alpha: pi/2}}
    - {{theta: q2, d: 0, a: a2, alpha: 0}}
    - {{theta: q3, d: d3, a: a3, alpha: -pi/2}}
    - {{theta: q4, d: d4, a: 0, alpha: pi/2}}
    - {{theta: q5, d: 0, a: 0, alpha: -pi/2}}
    - {{theta: q6, d: 0, a: 0, alpha: 0}}
points:
  T: {{frame: "6", at: [0, 0, 0.1]}}
questions:
  - {question}
"""


def _yaml(question):
    joints = "\n".join(f"  - {{name: q{i}, type: revolute}}" for i in range(1, 7))
    return PUMA_YAML.format(joints=joints, question=question)


def _matrix(T):
    return "[" + ", ".join("[" + ", ".join(repr(float(v)) for v in r) + "]" for r in T) + "]"


def _puma_T(q0):
    return rtb.models.DH.Puma560().fkine(q0).A


@pytest.mark.parametrize("target, message", [
    ("{pose: [[1, 0, 0, 0.5], [0, 1, 0, 0], [0, 0, 1, 0.5], [0, 0, 1, 1]]}", "last row"),
    ("{pose: [[1, 0.1, 0, 0.5], [0, 1, 0, 0], [0, 0, 1, 0.5], [0, 0, 0, 1]]}", "not a rotation"),
    ("{pose: [[-1, 0, 0, 0.5], [0, 1, 0, 0], [0, 0, 1, 0.5], [0, 0, 0, 1]]}", "not a rotation"),
    ("{position: [0.5, 0, 0.5], R: [[1, 0, 0], [0, 1, 0], [0, 0, 1]], rpy: [0, 0, 0]}", "given twice"),
    ("{position: [0.5, 0, 0.5]}", "missing"),
    ("{pose: [[1, 0, 0, 0.5], [0, 1, 0, 0], [0, 0, 1, 0.5], [0, 0, 0, 1]], zyz: [0, 0, 0]}", "given twice"),
])
def test_bad_pose_targets_are_input_errors(target, message):
    from robosolve.errors import InputError
    from robosolve.load.loader import load_problem_text

    with pytest.raises(InputError) as exc:
        load_problem_text(_yaml(f"{{type: inverse_kinematics, target: {target}}}"), "p.yaml")
    text = str(exc.value)
    assert message in text and "p.yaml:" in text


@pytest.mark.parametrize("target, key, suggestion", [
    ("{postion: [0.5, 0, 0.5], rpy: [0, 0, 0]}", "postion", "position"),      # with an orientation
    ("{postion: [0.5, 0, 0.5]}", "postion", "position"),                      # read as equations
    ("{position: [0.5, 0, 0.5], rp: [0, 0, 0]}", "rp", "rpy"),
])
def test_a_misspelt_pose_key_gives_one_message_with_its_did_you_mean(target, key, suggestion):
    from robosolve.errors import InputError
    from robosolve.load.loader import load_problem_text

    with pytest.raises(InputError) as exc:
        load_problem_text(_yaml(f"{{type: inverse_kinematics, target: {target}}}"), "p.yaml")
    issues = exc.value.issues
    assert len(issues) == 1, [str(i) for i in issues]       # no "missing" for the misspelt key
    assert f"target.{key}:" in str(issues[0]) and f"did you mean '{suggestion}'" in str(issues[0])


def test_pose_with_point_is_an_input_error_exit_2(tmp_path):
    import subprocess
    import sys

    f = tmp_path / "p.yaml"
    f.write_text(_yaml("{type: inverse_kinematics, point: T, target: {pose: "
                       "[[1, 0, 0, 0.5], [0, 1, 0, 0], [0, 0, 1, 0.5], [0, 0, 0, 1]]}}"))
    out = tmp_path / "out"
    r = subprocess.run([sys.executable, "-m", "robosolve", "solve", str(f), "-o", str(out)],
                       capture_output=True, text=True, cwd=str(Path(__file__).resolve().parents[2]))
    assert r.returncode == 2, r.stderr
    assert "p.yaml:" in r.stderr + r.stdout and "point" in r.stderr + r.stdout
    assert not out.exists()


def test_rounded_rotation_is_projected_with_a_note():
    from robosolve.load.loader import load_problem_text

    T = np.round(_puma_T([0.3, -0.5, 0.4, 0.7, -0.9, 1.2]), 4)
    p = load_problem_text(_yaml(f"{{type: inverse_kinematics, target: {{pose: {_matrix(T)}}}}}"), "p.yaml")
    tgt = p.questions[0].options["target"]
    assert tgt.note and "nearest rotation" in tgt.note
    R = np.array(tgt.R, dtype=float)
    assert np.max(np.abs(R.T @ R - np.eye(3))) < 1e-12 and np.max(np.abs(R - T[:3, :3])) < 1e-3
    exact = load_problem_text(_yaml("{type: inverse_kinematics, target: {position: [0.5, 0.1, 0.4], "
                                    "R: [[sqrt(2)/2, -sqrt(2)/2, 0], [sqrt(2)/2, sqrt(2)/2, 0], [0, 0, 1]]}}"),
                              "p.yaml").questions[0].options["target"]
    assert exact.note is None and exact.R[0, 0] == sp.sqrt(2) / 2


def test_point_target_with_rpy_through_the_solver():
    """The point T = (0, 0, 0.1) in frame 6, orientation by roll-pitch-yaw: 8 solutions, each putting T
    and frame 6's axes where asked (RTB's fkine with the tool offset)."""
    from spatialmath import SE3
    from spatialmath.base import tr2rpy

    from robosolve.load.loader import load_problem_text
    from robosolve.run.pipeline import solve_problem

    q0 = [0.3, -0.5, 0.4, 0.7, -0.9, 1.2]
    puma = rtb.models.DH.Puma560()
    T = (puma.fkine(q0) * SE3(0, 0, 0.1)).A
    rpy = tr2rpy(T[:3, :3], order="zyx")
    q = (f"{{type: inverse_kinematics, point: T, target: {{position: {list(map(float, T[:3, 3]))}, "
         f"rpy: {list(map(float, rpy))}}}}}")
    report = solve_problem(load_problem_text(_yaml(q), "p.yaml"))
    ans = report.answers[0]
    assert ans.error is None, ans.error
    sols = ans.numeric["solutions"]
    assert len(sols) == 8
    for s in sols:
        Ts = (puma.fkine([s[n] for n in NAMES]) * SE3(0, 0, 0.1)).A
        assert np.max(np.abs(Ts - T)) < 1e-9
    assert _contains(sols, q0, 1e-9)
    assert ans.numeric["selected"] == sols[0]


def test_puma560_wrist_singularity_gives_a_representative_with_a_note():
    puma = rtb.models.DH.Puma560()
    F, joints = _factors(puma)
    q0 = [0.3, -0.5, 0.4, 0.7, 0.0, 1.2]            # q5 = 0: axes 4 and 6 aligned
    T = puma.fkine(q0).A
    res = solve_pose(F, joints, T[:3, :3], T[:3, 3])
    assert res.status == "ok" and res.method == "decoupling"
    _check_reaches(puma, res.solutions, T)
    singular = [s for s, f in zip(res.all_solutions, res.wrist_singular) if f]
    assert len(singular) == 1 and singular[0]["q6"] == 0.0
    assert abs(wrap_angle(singular[0]["q4"] - (q0[3] + q0[5]))) < 1e-9     # only the sum is fixed
    assert len(res.solutions) == 7 and any("wrist singularity" in str(n) for n in res.notes)


def test_ur5_unreachable_pose_is_an_answer():
    ur5 = rtb.models.DH.UR5()
    F, joints = _factors(ur5)
    res = solve_pose(F, joints, np.eye(3), [2.5, 0.0, 0.3])
    assert res.status == "unreachable" and res.solutions == [] and "reach" in res.reason
