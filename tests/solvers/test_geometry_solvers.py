"""displacement / orientation / dof questions through the whole pipeline, checked
against independent references (numpy poses, spatialmath, hand values)."""

import math
from pathlib import Path

import numpy as np
import pytest
import sympy as sp

from robosolve.run.pipeline import solve_file
from robosolve.render.results_json import results_document

PROBLEM = Path(__file__).resolve().parents[2] / "problems" / "rigid-displacements.yaml"


@pytest.fixture(scope="module")
def answers():
    report = solve_file(PROBLEM)
    return {a.id: a for a in report.answers}


def scara_pose(t1, t2, l, L1=0.5, L2=0.4, h=1.0):
    def rz(a):
        m = np.eye(4)
        m[:2, :2] = [[math.cos(a), -math.sin(a)], [math.sin(a), math.cos(a)]]
        return m

    def tr(x, y, z):
        m = np.eye(4)
        m[:3, 3] = [x, y, z]
        return m

    return tr(0, 0, h) @ rz(t1) @ tr(L1, 0, 0) @ rz(t2) @ tr(L2, 0, 0) @ tr(0, 0, -l)


def axis_consistent(n, q):
    q = np.array(q)
    r, dt = q[:3, :3], q[:3, 3]
    u, p = np.array(n["u"]), np.array(n["P"])
    np.testing.assert_allclose((np.eye(3) - r) @ p + n["h"] * u, dt, atol=1e-10)
    assert p @ u == pytest.approx(0, abs=1e-12)
    assert n["pitch"] == pytest.approx(n["h"] / n["alpha"])


def test_displacement_between_configurations(answers):
    a = answers["scara-move"]
    assert a.error is None
    m1, m2 = scara_pose(0, 0, 0), scara_pose(math.pi / 2, math.pi / 6, 0.1)
    q = m2 @ np.linalg.inv(m1)
    np.testing.assert_allclose(a.numeric["Q"], q, atol=1e-12)
    assert a.numeric["alpha"] == pytest.approx(2 * math.pi / 3)
    np.testing.assert_allclose(a.numeric["u"], [0, 0, 1], atol=1e-12)
    assert a.numeric["h"] == pytest.approx(-0.1)
    axis_consistent(a.numeric, q)
    # the symbolic answer keeps L1, L2 and agrees with the numbers
    vals = {sp.Symbol("L1"): sp.Rational(1, 2), sp.Symbol("L2"): sp.Rational(2, 5)}
    assert a.symbolic["alpha"] == 2 * sp.pi / 3
    sym_p = [float(sp.sympify(str(x)).subs({sp.Symbol(k.name): v for k, v in vals.items()}))
             for x in a.symbolic["P"]]
    np.testing.assert_allclose(sym_p, a.numeric["P"], atol=1e-12)
    assert a.figures and a.figures[0].kind == "helical_axis"


def test_displacement_given_matrices(answers):
    a = answers["screw-given"]
    s3 = math.sqrt(3)
    np.testing.assert_allclose(a.numeric["u"], [1 / s3] * 3)
    assert a.numeric["alpha"] == pytest.approx(2 * math.pi / 3)
    assert a.numeric["h"] == pytest.approx(s3 / 6)  # u . (1, -1, 1/2)
    axis_consistent(a.numeric, a.numeric["Q"])
    assert a.symbolic["P"] == [sp.Rational(2, 3), sp.Rational(-1, 2), sp.Rational(-1, 6)]
    h = answers["half-turn"]
    assert h.numeric["alpha"] == pytest.approx(math.pi) and h.numeric["u"] == [0.0, 1.0, 0.0]
    axis_consistent(h.numeric, h.numeric["Q"])
    t = answers["translation"]
    assert t.numeric["alpha"] == 0.0 and t.numeric["P"] is None and t.numeric["pitch"] is None
    assert t.numeric["h"] == pytest.approx(3.0)


def test_orientation_against_spatialmath(answers):
    smb = pytest.importorskip("spatialmath.base")
    sm = pytest.importorskip("spatialmath")
    r = np.array([[0, -0.5, math.sqrt(3) / 2], [0, math.sqrt(3) / 2, 0.5], [-1, 0, 0]])
    a = answers["given-rotation"]
    # pitch = +pi/2: RPY singular, ZYZ regular
    assert a.numeric["rpy"]["singular"] is True and len(a.numeric["rpy"]["solutions"]) == 1
    roll, pitch, yaw = a.numeric["rpy"]["solutions"][0]
    np.testing.assert_allclose(smb.rpy2r(roll, pitch, yaw, order="zyx"), r, atol=1e-12)
    np.testing.assert_allclose(a.numeric["zyz"]["solutions"][0], smb.tr2eul(r), atol=1e-12)
    theta, v = smb.tr2angvec(r)
    assert a.numeric["axis_angle"]["angle"] == pytest.approx(theta)
    np.testing.assert_allclose(a.numeric["axis_angle"]["axis"], v, atol=1e-9)
    np.testing.assert_allclose(a.numeric["quaternion"], sm.UnitQuaternion(r).vec, atol=1e-12)
    # the tool of the SCARA at (pi/3, pi/6, 1/10) is Rz(pi/2): ZYZ singular, phi + psi = pi/2
    t = answers["tool-orientation"]
    assert t.numeric["zyz"]["singular"] is True
    assert t.symbolic["zyz"]["solutions"] == [[sp.pi / 2, 0, 0]]
    assert t.symbolic["quaternion"] == [sp.sqrt(2) / 2, 0, 0, sp.sqrt(2) / 2]
    c = answers["cyclic-rotation"]
    assert c.symbolic["quaternion"] == [sp.Rational(1, 2)] * 4
    assert c.symbolic["axis_angle"]["angle"] == 2 * sp.pi / 3


def test_dof_answers(answers):
    assert answers["serial-4r"].numeric["dof"] == 4
    assert answers["five-bar"].numeric["dof"] == 2      # ERRATA item 5
    assert answers["spatial-four-bar"].numeric["dof"] == -2
    assert any("over-constrained" in n for n in answers["spatial-four-bar"].notes)
    assert answers["stewart"].numeric["dof"] == 6


def test_problem_without_robot(write_problem):
    path = write_problem("""
        robosolve: 1
        name: no-robot
        parameters:
          a: ~
        questions:
          - type: displacement
            from: [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]
            to: [[1, 0, 0, a], [0, 0, -1, 0], [0, 1, 0, 0], [0, 0, 0, 1]]
          - type: orientation
            matrix: [[1, 0, 0], [0, 1, 0], [0, 0, 1]]
          - {type: dof, bodies: 4, joints_1dof: 4}
          - {type: dof, bodies: 3, joints_1dof: 3, space: planar}
    """)
    report = solve_file(path)
    doc = results_document(report, {})["answers"]
    d = doc["displacement"]
    assert d["symbolic"]["u"] == ["1", "0", "0"] and d["symbolic"]["h"] == "a"
    assert d["symbolic"]["alpha"] == "pi/2"
    assert d["numeric"] == {} and any("a" in n for n in d["notes"])  # null parameter
    o = doc["orientation"]
    assert o["numeric"]["axis_angle"] == {"axis": None, "angle": 0.0}
    assert o["numeric"]["quaternion"] == [1.0, 0.0, 0.0, 0.0]
    assert o["numeric"]["zyz"]["singular"] is True and o["numeric"]["rpy"]["singular"] is False
    assert doc["dof"]["numeric"]["dof"] == 1
    assert doc["dof-2"]["numeric"]["dof"] == 0 and doc["dof-2"]["notes"]


def test_not_a_rotation_is_an_error_not_a_traceback(write_problem):
    path = write_problem("""
        robosolve: 1
        name: bad-matrix
        questions:
          - type: orientation
            matrix: [[1, 0, 0], [0, 2, 0], [0, 0, 1]]
          - type: displacement
            from: [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]
            to: [[1, 1, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]
    """)
    # not valid input: refused where it is read (exit 2), with the line of each matrix
    from robosolve.errors import InputError

    with pytest.raises(InputError) as info:
        solve_file(path)
    text = str(info.value)
    assert ":5: questions[0].matrix: not a rotation" in text
    assert ":8: questions[1].to: not a rototranslation" in text


def test_displacement_expressed_in_another_frame(write_problem):
    path = write_problem("""
        robosolve: 1
        name: in-frame
        parameters: {L1: 1}
        joints:
          - {name: theta1, type: revolute}
        frames:
          "1": {parent: "0", pose: "Rz(theta1) Tx(L1)"}
        questions:
          - type: displacement
            from: [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]
            to: [[0, -1, 0, 1], [1, 0, 0, 0], [0, 0, 1, 2], [0, 0, 0, 1]]
            frame: "1"
            at: {theta1: pi/2}
    """)
    a = solve_file(path).answers[0]
    m0k = np.array([[0, -1, 0, 0], [1, 0, 0, 1], [0, 0, 1, 0], [0, 0, 0, 1]], dtype=float)
    q0 = np.array([[0, -1, 0, 1], [1, 0, 0, 0], [0, 0, 1, 2], [0, 0, 0, 1]], dtype=float)
    qk = np.linalg.inv(m0k) @ q0 @ m0k
    np.testing.assert_allclose(a.numeric["Q"], qk, atol=1e-12)
    axis_consistent(a.numeric, qk)
    assert a.numeric["h"] == pytest.approx(2.0) and a.numeric["alpha"] == pytest.approx(math.pi / 2)


def test_helical_axis_figures_draw(answers, tmp_path):
    pytest.importorskip("matplotlib")
    from robosolve.render.plots import draw

    for name in ("scara-move", "half-turn", "translation"):
        spec = answers[name].figures[0]
        out = tmp_path / f"{name}.png"
        draw(spec, out)
        assert out.stat().st_size > 10_000


@pytest.mark.parametrize("angle", [1e-7, 3e-6, math.pi - 1e-7])
def test_orientation_of_float_matrices_near_the_special_cases(write_problem, angle):
    """A float matrix a hair away from the identity or a half turn is a rotation with its own
    angles (it was refused: 1 - cos^2 of a float at 1e-14 was dropped as round-off, then
    trace(R) = 3 - 1e-14 was "neither 3 nor -1"); symbolic and numeric agree. Reference: scipy."""
    from scipy.spatial.transform import Rotation

    r = Rotation.from_rotvec(angle * np.array([0.0, -0.6, 0.8])).as_matrix()
    path = write_problem(f"""
        robosolve: 1
        name: tiny-rotation
        questions:
          - type: orientation
            matrix: {[[float(x) for x in row] for row in r]}
    """)
    o = results_document(solve_file(path), {})["answers"]["orientation"]
    n = o["numeric"]
    assert n["axis_angle"]["angle"] == pytest.approx(angle, rel=1e-6)
    assert np.allclose(n["axis_angle"]["axis"], [0.0, -0.6, 0.8], atol=1e-6)
    q = n["quaternion"]
    assert np.allclose(Rotation.from_quat([q[1], q[2], q[3], q[0]]).as_matrix(), r, atol=1e-12)
    for phi, theta, psi in n["zyz"]["solutions"]:
        ref = Rotation.from_euler("ZYZ", [phi, theta, psi]).as_matrix()
        assert np.abs(ref - r).max() < 1e-9   # near the lock the angles are ill-conditioned
    for roll, pitch, yaw in n["rpy"]["solutions"]:
        ref = Rotation.from_euler("ZYX", [yaw, pitch, roll]).as_matrix()
        assert np.abs(ref - r).max() < 1e-9   # near the lock the angles are ill-conditioned
    s = o["symbolic"]
    assert float(s["axis_angle"]["angle"]) == pytest.approx(n["axis_angle"]["angle"], rel=1e-9)
    assert s["zyz"]["singular"] == n["zyz"]["singular"]
    assert len(s["rpy"]["solutions"]) == len(n["rpy"]["solutions"])


def test_displacement_between_decimal_configurations_of_a_tilted_arm(write_problem):
    """Decimal joint values beside symbolic lengths and a fixed Rx(1/3): the blanket simplify of
    the helical axis ran into its 10 s time limit (a note, and an outcome that hung on the
    machine); now the bounded geometric simplification, symbolic equal to numeric. Reference:
    numpy forward kinematics and scipy's rotation vector."""
    from scipy.spatial.transform import Rotation

    path = write_problem("""
        robosolve: 1
        name: tilted
        parameters: {L1: 0.527, L2: 0.559, L3: 3/7, L4: 1/3}
        joints: [{name: q1, type: revolute}, {name: q2, type: revolute},
                 {name: q3, type: revolute}, {name: q4, type: revolute}]
        frames:
          "1": {parent: "0", pose: "Rx(pi/2) Ry(q1) Tx(L1)"}
          "2": {pose: "Tz(L2/2) Ry(q2) Ty(L2)"}
          "3": {pose: "Rx(1/3) Rz(q3) Tx(L3) Rz(pi/2)"}
          "4": {pose: "Rx(pi/2) Ry(q4) Tx(L4) Rz(pi/2)"}
        questions:
          - type: displacement
            from: {q1: -0.331, q2: 0.821, q3: -0.367, q4: -0.729}
            to: {q1: -0.129, q2: 0.91, q3: 0.066, q4: 0.536}
    """)
    d = results_document(solve_file(path), {})["answers"]["displacement"]
    assert not [n for n in d["notes"] if "time limit" in n]

    def rot(axis, t):
        m = np.eye(4)
        m[:3, :3] = Rotation.from_euler(axis, t).as_matrix()
        return m

    def tr(axis, x):
        m = np.eye(4)
        m["xyz".index(axis), 3] = x
        return m

    def pose(q1, q2, q3, q4):
        L1, L2, L3, L4 = 0.527, 0.559, 3 / 7, 1 / 3
        return (rot("x", math.pi / 2) @ rot("y", q1) @ tr("x", L1) @ tr("z", L2 / 2) @ rot("y", q2)
                @ tr("y", L2) @ rot("x", 1 / 3) @ rot("z", q3) @ tr("x", L3) @ rot("z", math.pi / 2)
                @ rot("x", math.pi / 2) @ rot("y", q4) @ tr("x", L4) @ rot("z", math.pi / 2))

    q = pose(-0.129, 0.91, 0.066, 0.536) @ np.linalg.inv(pose(-0.331, 0.821, -0.367, -0.729))
    rv = Rotation.from_matrix(q[:3, :3]).as_rotvec()
    n = d["numeric"]
    assert np.allclose(n["Q"], q, atol=1e-9)
    assert n["alpha"] == pytest.approx(np.linalg.norm(rv), rel=1e-9)
    assert np.allclose(n["u"], rv / np.linalg.norm(rv), atol=1e-9)
    assert n["h"] == pytest.approx(float(np.dot(n["u"], q[:3, 3])), abs=1e-9)
    s = d["symbolic"]
    assert float(s["alpha"]) == pytest.approx(n["alpha"], rel=1e-9)
    values = {"L1": 0.527, "L2": 0.559, "L3": sp.Rational(3, 7), "L4": sp.Rational(1, 3)}
    assert float(sp.sympify(s["h"]).subs(values)) == pytest.approx(n["h"], abs=1e-9)


def test_orientation_of_a_matrix_rounded_by_hand_is_projected_as_an_ik_target_is(write_problem):
    # 0.707 for cos 45°: RᵀR differs from I by 3e-4, within the 1e-3 that a pose target of
    # inverse_kinematics accepts. Its polar decomposition is exactly Rz(π/4) (the matrix is a
    # multiple of it), so the representations are those of Rz(π/4); 0.7 (2e-2 off) stays an error.
    path = write_problem("""
        robosolve: 1
        name: rounded
        questions:
          - type: orientation
            matrix: [[0.707, -0.707, 0], [0.707, 0.707, 0], [0, 0, 1]]
    """)
    doc = results_document(solve_file(path), {})["answers"]["orientation"]
    n = doc["numeric"]
    assert "error" not in doc
    assert n["axis_angle"]["angle"] == pytest.approx(math.pi / 4, abs=1e-12)
    assert n["quaternion"] == pytest.approx([math.cos(math.pi / 8), 0, 0, math.sin(math.pi / 8)], abs=1e-12)
    assert n["rpy"]["solutions"][0] == pytest.approx([0, 0, math.pi / 4], abs=1e-12)
    assert any("nearest rotation" in note for note in doc["notes"])
    far = write_problem("""
        robosolve: 1
        name: far
        questions:
          - type: orientation
            matrix: [[0.7, -0.7, 0], [0.7, 0.7, 0], [0, 0, 1]]
    """)
    from robosolve.errors import InputError

    with pytest.raises(InputError, match="not a rotation"):
        solve_file(far)


def test_displacement_between_matrices_rounded_by_hand_is_projected_as_an_ik_target_is(write_problem):
    # `to` has 0.707 for cos 45° (RᵀR off I by 3e-4, within an IK pose target's 1e-3): its rotation
    # block is a multiple of Rz(π/4), whose polar decomposition is Rz(π/4) exactly. The answers are
    # those of the exact Q = M_to·M_from⁻¹ in closed form (scipy Rotation); `from` is exact and
    # gets no note. 0.7 (2e-2 off) stays the input error at its line.
    from scipy.spatial.transform import Rotation

    path = write_problem("""
        robosolve: 1
        name: rounded
        questions:
          - type: displacement
            from: [[1, 0, 0, 1], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]
            to: [[0.707, -0.707, 0, 0.3], [0.707, 0.707, 0, 0.2], [0, 0, 1, 0.5], [0, 0, 0, 1]]
    """)
    doc = results_document(solve_file(path), {})["answers"]["displacement"]
    n = doc["numeric"]
    assert "error" not in doc
    m_from, m_to = np.eye(4), np.eye(4)
    m_from[:3, 3] = [1, 0, 0]
    m_to[:3, :3] = Rotation.from_rotvec([0, 0, math.pi / 4]).as_matrix()
    m_to[:3, 3] = [0.3, 0.2, 0.5]
    q = m_to @ np.linalg.inv(m_from)
    rotvec = Rotation.from_matrix(q[:3, :3]).as_rotvec()
    alpha = float(np.linalg.norm(rotvec))
    u = rotvec / alpha
    h = float(u @ q[:3, 3])
    # P: the axis point nearest the origin, (I − R)·P = ΔT − h·u with u·P = 0
    a = np.vstack([np.eye(3) - q[:3, :3], u])
    point = np.linalg.lstsq(a, np.append(q[:3, 3] - h * u, 0), rcond=None)[0]
    assert np.array(n["Q"], dtype=float) == pytest.approx(q, abs=1e-12)
    assert n["alpha"] == pytest.approx(alpha, abs=1e-12)
    assert n["u"] == pytest.approx(list(u), abs=1e-12)
    assert n["h"] == pytest.approx(h, abs=1e-12)
    assert n["pitch"] == pytest.approx(h / alpha, abs=1e-12)
    assert n["P"] == pytest.approx(list(point), abs=1e-12)
    assert sum("nearest rotation" in note for note in doc["notes"]) == 1
    far = write_problem("""
        robosolve: 1
        name: far
        questions:
          - type: displacement
            from: [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]
            to: [[0.7, -0.7, 0, 0], [0.7, 0.7, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]
    """)
    from robosolve.errors import InputError

    with pytest.raises(InputError, match=r":6: .*not a rototranslation"):
        solve_file(far)
