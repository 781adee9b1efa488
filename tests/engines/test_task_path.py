"""Work-space trajectories (motion/task_path.py, solvers/task_trajectory.py) against independent
references: closed-form timing, RTB's numeric IK per sample, finite differences, and an
independent integration (scipy, textbook 2R dynamics) of the work-space PD law."""

from __future__ import annotations

import json
import math
import subprocess
import sys

import numpy as np
import pytest

from robosolve.motion import task_path as tp

ARM_2R = """robosolve: 1
name: planar-2r
parameters: {L1: 1/2, L2: 2/5, m1: 2, m2: 1, g: 9.81}
joints:
  - {name: q1, type: revolute}
  - {name: q2, type: revolute}
frames:
  "1": {parent: "0", pose: "Rz(q1) Tx(L1)"}
  "2": {pose: "Rz(q2) Tx(L2)"}
gravity: [0, -g, 0]
bodies:
  - {name: b1, frame: "1", mass: m1, point: [0, 0, 0]}
  - {name: b2, frame: "2", mass: m2, point: [0, 0, 0]}
questions:
"""

LINE = """  - type: task_trajectory
    id: line
    coordinates: [E.x, E.y]
    from: {E.x: 0.7, E.y: 0.1}
    to: {E.x: 0.2, E.y: 0.6}
    max_velocity: 0.6
    max_acceleration: 3
"""


def _solve(write_problem, tmp_path, text):
    f = write_problem(text)
    out = tmp_path / "out"
    r = subprocess.run([sys.executable, "-m", "robosolve", "solve", str(f), "--out", str(out)],
                       capture_output=True, text=True)
    return r, (json.loads((out / "results.json").read_text()) if r.returncode != 2 else None)


def test_trapezoidal_and_bang_bang_timing_match_their_closed_forms():
    t = tp.trapezoidal(2.0, 0.5, 1.0)                # cruise reached: L >= v^2/a
    assert t.kind == "trapezoidal" and t.T == pytest.approx(2.0 / 0.5 + 0.5 / 1.0)
    for tt in np.linspace(0, t.T, 37):
        s, sd, sdd = t.at(tt)
        ta = 0.5
        ref = (0.5 * tt ** 2 if tt <= ta else 2.0 - 0.5 * (t.T - tt) ** 2 if tt >= t.T - ta
               else 0.5 * ta ** 2 + 0.5 * (tt - ta))
        assert s == pytest.approx(ref, abs=1e-12)
    b = tp.trapezoidal(0.1, 0.5, 1.0)                # not reached: bang-bang
    assert b.kind == "bang-bang" and b.T == pytest.approx(2 * math.sqrt(0.1)) and b.at(b.T)[0] == pytest.approx(0.1)
    q = tp.quintic(1.0, 2.0)
    assert q.at(2.0)[0] == pytest.approx(1.0) and q.at(1.0)[1] == pytest.approx(15 / 16)


def test_circle_needs_an_equidistant_centre_and_goes_the_shorter_way():
    with pytest.raises(tp.PathError):
        tp.circle([1, 0], [0, 1], [0.1, 0])
    p = tp.circle([1, 0], [0, 1], [0, 0])
    assert p.length == pytest.approx(math.pi / 2)
    assert np.allclose(p.at(p.length)[0], [0, 1])
    p2 = tp.circle([1, 0], [0, -1], [0, 0])          # the shorter way: clockwise
    assert p2.length == pytest.approx(math.pi / 2) and p2.at(p2.length / 2)[0][1] < 0


def _arm_2r(L1=0.5, L2=0.4):
    x = lambda q: np.array([L1 * math.cos(q[0]) + L2 * math.cos(q[0] + q[1]),
                            L1 * math.sin(q[0]) + L2 * math.sin(q[0] + q[1])])
    def J(q):
        s1, c1, s12, c12 = math.sin(q[0]), math.cos(q[0]), math.sin(q[0] + q[1]), math.cos(q[0] + q[1])
        return np.array([[-L1 * s1 - L2 * s12, -L2 * s12], [L1 * c1 + L2 * c12, L2 * c12]])
    def h(q, qd):
        a, b = qd[0], qd[0] + qd[1]
        return np.array([-L1 * math.cos(q[0]) * a * a - L2 * math.cos(q[0] + q[1]) * b * b,
                         -L1 * math.sin(q[0]) * a * a - L2 * math.sin(q[0] + q[1]) * b * b])
    return tp.Arm(x, J, h, [True, True])


def test_joint_path_matches_rtb_ikine_per_sample_and_finite_differences():
    import roboticstoolbox as rtb
    from spatialmath import SE3

    arm = _arm_2r()
    path, timing = tp.line([0.7, 0.1], [0.2, 0.6]), tp.trapezoidal(math.hypot(0.5, 0.5), 0.6, 3.0)
    q0 = tp.newton(arm, path.a, [0.0, 1.0])
    conv = tp.follow(arm, path, timing, q0, samples=201)
    assert conv.failure is None
    robot = rtb.DHRobot([rtb.RevoluteDH(a=0.5), rtb.RevoluteDH(a=0.4)])
    for k in range(0, conv.t.size, 20):
        T = SE3(conv.x[0, k], conv.x[1, k], 0)
        sol = robot.ikine_LM(T, q0=conv.q[:, k] + 0.05, mask=[1, 1, 0, 0, 0, 0], tol=1e-12)
        assert sol.success and np.allclose(sol.q, conv.q[:, k], atol=1e-7)
    # q_dot, q_ddot against central differences of the converted path, inside a segment
    t0, h = 0.6, 1e-4
    st = [tp.state_at(arm, path, timing, conv, t, 1) for t in (t0 - h, t0, t0 + h)]
    assert np.allclose((st[2][0] - st[0][0]) / (2 * h), st[1][1], atol=1e-6)
    assert np.allclose((st[2][1] - st[0][1]) / (2 * h), st[1][2], atol=1e-5)


def test_a_line_through_a_singularity_is_an_answer_not_a_crash():
    arm = _arm_2r(0.5, 0.5)                          # equal links: the base is a singular point
    path, timing = tp.line([0.5, 0.0], [-0.5, 0.0]), tp.quintic(1.0, 1.0)
    conv = tp.follow(arm, path, timing, tp.newton(arm, [0.5, 0.0], [-1.0, 2.0]), samples=201)
    assert conv.failure is not None and conv.failure["kind"] in ("singular", "unreachable")


@pytest.mark.parametrize("end", [(0.8, 0.6), (0.6, 0.8), (0.9, math.sqrt(1 - 0.81)), (1.0, 0.0)])
def test_a_line_that_ends_on_the_reach_of_the_stretched_arm_is_singular_at_t_T(end):
    """|to| = L1 + L2: the stretched arm, det J = L1 L2 sin(q2) = 0 (closed form). Newton lands on such
    an end only to ~sqrt(its tolerance) along the singular direction (q2 ~ 3e-6, sigma ~ 7e-7): the
    test against sigma must allow for it (the ends off the x axis were followed to the end with
    q2 < 0, joint accelerations in the hundreds and no `singular`)."""
    arm = _arm_2r(0.5, 0.5)
    path, timing = tp.line([0.5, 0.2], end), tp.quintic(math.dist([0.5, 0.2], end), 1.0)
    conv = tp.follow(arm, path, timing, tp.newton(arm, path.a, [-0.6, 2.0]))
    assert conv.failure is not None and conv.failure["kind"] == "singular" and conv.failure["t"] == 1.0


def test_a_line_that_starts_on_the_reach_of_the_stretched_arm_is_singular_at_t_0():
    """`from` at |x| = L1 + L2 (a singular start): the conversion stops at its first sample, with no
    sample kept (it crashed building its empty arrays)."""
    arm = _arm_2r(0.5, 0.5)
    path, timing = tp.line([1.0, 0.0], [0.5, 0.2]), tp.quintic(math.hypot(0.5, 0.2), 1.0)
    conv = tp.follow(arm, path, timing, np.array([0.0, 0.0]))
    assert conv.failure is not None and conv.failure["kind"] == "singular" and conv.failure["t"] == 0.0
    assert conv.q.shape == (2, 0) and conv.x.shape == (2, 0) and conv.t.size == 0


def test_a_path_from_a_singular_start_is_a_singular_answer_at_t_0():
    """The spec: a `from` at a singular configuration is `singular` at t = 0, with `start` given (it was
    an internal error). Reference: |from| = L1 + L2, the stretched arm q = (atan2(y, x), 0)."""
    from robosolve.load.loader import load_problem_text
    from robosolve.render.results_json import answer_record
    from robosolve.run.pipeline import solve_problem

    text = ARM_2R.replace("L2: 2/5", "L2: 1/2") + LINE.replace("E.x: 0.7, E.y: 0.1", "E.x: 0.8, E.y: 0.6") + (
        "  - {type: p_control, trajectory: line, law: pd_gravity, gains: {q1: 100, q2: 100}, "
        "gains_d: {q1: 10, q2: 10}}\n")
    report = solve_problem(load_problem_text(text))
    got = {a.id: json.loads(json.dumps(answer_record(a, []))) for a in report.answers}
    a = got["line"]
    assert "error" not in a and a["singular"] is True and a["reason"].startswith("at t = 0 s ")
    assert a["numeric"]["start"] == pytest.approx({"q1": math.atan2(0.6, 0.8), "q2": 0.0}, abs=1e-9)
    assert "end" not in a["numeric"] and "max_joint_velocity" not in a["numeric"]
    assert "cannot be followed" in got["p_control"]["error"]


def test_the_task_figure_gives_an_angle_coordinate_in_rad():
    """Coordinates [E.x, q1 + q2]: the second is the angle of link 2 (a sum of revolute angles, rad);
    the work-space tracking figure labelled every coordinate and its error in m."""
    from robosolve.load.loader import load_problem_text
    from robosolve.run.pipeline import solve_problem

    text = ARM_2R + """  - type: task_trajectory
    id: line
    coordinates: [E.x, q1 + q2]
    from: {E.x: 0.7, q1 + q2: 0.2}
    to: {E.x: 0.5, q1 + q2: 0.6}
    duration: 0.3
  - {type: p_control, trajectory: line, law: task_pd_gravity, gains: {E.x: 400, q1 + q2: 40},
     gains_d: {E.x: 40, q1 + q2: 4}}
"""
    report = solve_problem(load_problem_text(text))
    control = next(a for a in report.answers if a.type == "p_control")
    assert control.error is None, control.error
    (figure,) = [f for f in control.figures if f.name == "task"]
    assert [j["unit"] for j in figure.data["joints"]] == ["m", "rad"]


def test_a_line_passing_near_the_base_says_it_passes_near_a_singularity_not_through_one():
    """L1 = L2: the base is singular. The line y = x + 0.001 misses it by 0.001/sqrt(2) m, where the
    folded arm has sigma_min(J) ~ |E| = 7.1e-4 (J's first column is (-E.y, E.x), nearly normal to the
    second, of length L2 = 1/2; checked below):
    J keeps its rank, but q1 turns by ~pi within a millimetre, faster than the samples follow. The
    reason said "crosses a singular configuration ... J loses rank"."""
    from robosolve.load.loader import load_problem_text
    from robosolve.render.results_json import answer_record
    from robosolve.run.pipeline import solve_problem

    d = 0.001 / math.sqrt(2)
    q2 = 2 * math.acos(d)                            # |E| = 2 L cos(q2 / 2), L = 1/2
    sv = np.linalg.svd(_arm_2r(0.5, 0.5).J([0.3, q2]), compute_uv=False)
    assert sv[-1] == pytest.approx(d, rel=1e-3)      # not singular where it passes nearest
    text = ARM_2R.replace("L2: 2/5", "L2: 1/2") + LINE.replace("E.x: 0.7, E.y: 0.1", "E.x: 0.3, E.y: 0.301").replace(
        "E.x: 0.2, E.y: 0.6", "E.x: -0.3, E.y: -0.299")
    (a,) = solve_problem(load_problem_text(text)).answers
    record = answer_record(a, [])
    reason = record["reason"]
    assert record["singular"] is True and "loses rank" not in reason
    assert "close to a singular configuration" in reason


def test_solver_answers_and_pd_matches_an_independent_integration(write_problem, tmp_path):
    from scipy.integrate import solve_ivp

    # the gains are parameters, as a variant draws them (literal gains: the workspace-2r-line
    # golden); parameters stopped the question with an internal error (a symbol to float)
    law = """  - type: p_control
    trajectory: line
    law: task_pd_gravity
    gains: {E.x: Kp, E.y: Kp}
    gains_d: {E.x: Kd, E.y: Kd}
"""
    arm_2r = ARM_2R.replace("g: 9.81}", "g: 9.81, Kp: 800, Kd: 60}")
    r, res = _solve(write_problem, tmp_path, arm_2r + LINE + law)
    assert r.returncode == 0, r.stderr
    a = res["answers"]["line"]["numeric"]
    assert a["length"] == pytest.approx(math.hypot(0.5, 0.5))
    assert a["T"] == pytest.approx(a["length"] / 0.6 + 0.6 / 3)
    # independent: textbook 2R with point masses at the link ends, the same law, scipy
    arm, L1, L2, m1, m2, g = _arm_2r(), 0.5, 0.4, 2.0, 1.0, 9.81
    path, timing = tp.line([0.7, 0.1], [0.2, 0.6]), tp.trapezoidal(math.hypot(0.5, 0.5), 0.6, 3.0)
    q0 = np.array([a["start"]["q1"], a["start"]["q2"]])

    def rhs(t, y):
        q, qd = y[:2], y[2:]
        c2, s2 = math.cos(q[1]), math.sin(q[1])
        M = np.array([[(m1 + m2) * L1 ** 2 + m2 * L2 ** 2 + 2 * m2 * L1 * L2 * c2, m2 * L2 ** 2 + m2 * L1 * L2 * c2],
                      [m2 * L2 ** 2 + m2 * L1 * L2 * c2, m2 * L2 ** 2]])
        c = np.array([-m2 * L1 * L2 * s2 * (2 * qd[0] * qd[1] + qd[1] ** 2), m2 * L1 * L2 * s2 * qd[0] ** 2])
        G = np.array([(m1 + m2) * g * L1 * math.cos(q[0]) + m2 * g * L2 * math.cos(q[0] + q[1]),
                      m2 * g * L2 * math.cos(q[0] + q[1])])
        _s, xd, vd, _ad = tp.task_state(path, timing, min(t, timing.T))
        e, ed = xd - arm.x(q), vd - arm.J(q) @ qd
        tau = arm.J(q).T @ (800 * e + 60 * ed) + G
        return np.concatenate([qd, np.linalg.solve(M, tau - c - G)])

    ts = np.linspace(0, timing.T, 3001)
    sol = solve_ivp(rhs, (0, timing.T), np.concatenate([q0, [0, 0]]), t_eval=ts, rtol=1e-11, atol=1e-12,
                    method="DOP853", max_step=0.01)
    err = np.array([tp.task_state(path, timing, t)[1] - arm.x(sol.y[:2, k]) for k, t in enumerate(ts)]).T
    got = res["answers"]["p_control"]["numeric"]
    for i, c in enumerate(("E.x", "E.y")):
        assert got["max_error"][c] == pytest.approx(np.max(np.abs(err[i])), rel=2e-3)
        assert got["final_error"][c] == pytest.approx(err[i, -1], rel=1e-3, abs=1e-9)


@pytest.mark.parametrize("edit, where", [
    (LINE.replace("    max_velocity: 0.6\n", "    path: {circle: {center: [0.1, 0.1]}}\n    max_velocity: 0.6\n"),
     "path"),
    (LINE + "  - {type: p_control, trajectory: line, law: task_pd_gravity, gains: {E.x: 1, E.z: 1}, "
            "gains_d: {E.x: 1, E.y: 1}}\n", "gains.E.z"),
    (LINE.replace("coordinates: [E.x, E.y]", "coordinates: [E.x]").replace(", E.y: 0.1", "").replace(", E.y: 0.6", "")
     + "  - {type: p_control, trajectory: line, law: task_computed_torque, gains: {E.x: 1}, gains_d: {E.x: 1}}\n",
     "square"),
    (LINE + "  - {type: p_control, trajectory: line, law: task_pd_gravity, gains: {q1: 1, q2: 1}, "
            "gains_d: {q1: 1, q2: 1}}\n", "per coordinate"),
], ids=["centre-not-equidistant", "gain-of-a-missing-coordinate", "computed-torque-wide-J",
        "joint-gains-for-a-task-law"])
def test_bad_inputs_exit_2_with_file_and_line(write_problem, tmp_path, edit, where):
    r, _ = _solve(write_problem, tmp_path, ARM_2R + edit)
    assert r.returncode == 2, r.stderr
    assert ".yaml:" in r.stderr and where in r.stderr and "Traceback" not in r.stderr
    assert not (tmp_path / "out").exists()


def _line_crossing(a, b, radius, timing):
    """The instant a straight line from a to b, timed by `timing`, crosses the circle of `radius`
    about the base (closed form of |a + s u| = radius, then s(t) inverted on a fine grid)."""
    a, b = np.array(a, dtype=float), np.array(b, dtype=float)
    u = (b - a) / np.linalg.norm(b - a)
    half_b = float(a @ u)
    s_cross = -half_b + math.sqrt(half_b ** 2 - (a @ a - radius ** 2))
    ts = np.linspace(0, timing.T, 400001)
    return s_cross, ts[int(np.argmax([timing.at(t)[0] >= s_cross for t in ts]))]


def test_a_line_whose_end_is_out_of_reach_is_an_unreachable_answer(write_problem, tmp_path):
    """The spec: a path that leaves the workspace is an answer (`unreachable`, `reason` with t and the
    point), its end beyond the reach included; a p_control that follows it says it has no reference."""
    text = LINE.replace("E.x: 0.2, E.y: 0.6", "E.x: 1.5, E.y: 0.6") + (
        "  - {type: p_control, trajectory: line, law: pd_gravity, gains: {q1: 100, q2: 100}, "
        "gains_d: {q1: 10, q2: 10}}\n")
    r, res = _solve(write_problem, tmp_path, ARM_2R + text)
    assert r.returncode == 1, r.stderr                   # the p_control has no reference: its error
    a = res["answers"]["line"]
    assert a["unreachable"] is True and "singular" not in a and "out of the arm's reach" in a["reason"]
    length = math.hypot(0.8, 0.5)
    assert a["numeric"]["length"] == pytest.approx(length) and "end" not in a["numeric"]
    _s, t_cross = _line_crossing([0.7, 0.1], [1.5, 0.6], 0.9, tp.trapezoidal(length, 0.6, 3.0))
    words = a["reason"].split()
    assert words[:3] == ["at", "t", "="] and abs(float(words[3]) - t_cross) < 1e-4
    x, y = (float(v) for v in a["reason"].split("(")[1].split(")")[0].replace("E.x = ", "").replace("E.y = ", "").split(","))
    assert math.hypot(x, y) == pytest.approx(0.9, abs=1e-5)    # the point where it leaves: on the reach
    assert "cannot be followed" in res["answers"]["p_control"]["error"]


def test_a_line_that_starts_out_of_reach_is_an_unreachable_answer_at_t_0(write_problem, tmp_path):
    r, res = _solve(write_problem, tmp_path, ARM_2R + LINE.replace("E.x: 0.7, E.y: 0.1", "E.x: 1.7, E.y: 0.1"))
    assert r.returncode == 0, r.stderr
    a = res["answers"]["line"]
    assert a["unreachable"] is True and a["reason"].startswith("at t = 0 s the path starts at (E.x = 1.7, E.y = 0.1)")
    assert a["numeric"]["length"] == pytest.approx(math.hypot(1.5, 0.5)) and "start" not in a["numeric"]
    assert a["figures"] == []


def test_a_line_that_ends_stretched_is_a_singular_answer_at_t_T(write_problem, tmp_path):
    r, res = _solve(write_problem, tmp_path, ARM_2R + LINE.replace("E.x: 0.2, E.y: 0.6", "E.x: 0.9, E.y: 0.0"))
    assert r.returncode == 0, r.stderr
    a = res["answers"]["line"]
    T = a["numeric"]["T"]
    assert T == pytest.approx(math.hypot(0.2, 0.1) / 0.6 + 0.6 / 3) or T == pytest.approx(2 * math.sqrt(math.hypot(0.2, 0.1) / 3))
    assert a["singular"] is True and "unreachable" not in a
    assert abs(float(a["reason"].split()[3]) - T) < 1e-6 and "E.x = 0.9" in a["reason"]


def test_an_arc_leaving_the_reach_is_an_unreachable_answer(write_problem, tmp_path):
    arc = (LINE.replace("E.x: 0.7, E.y: 0.1", "E.x: 0.8, E.y: 0.3").replace("E.x: 0.2, E.y: 0.6", "E.x: 0.3, E.y: 0.8")
           .replace("    max_velocity: 0.6\n", "    path: {circle: {center: [0.3, 0.3]}}\n    max_velocity: 0.6\n"))
    r, res = _solve(write_problem, tmp_path, ARM_2R + arc)
    assert r.returncode == 0, r.stderr
    a = res["answers"]["line"]
    assert a["unreachable"] is True and "out of the arm's reach" in a["reason"]
    # the instant where the arc crosses the circle of radius L1 + L2 = 0.9 about the base
    c, rad = np.array([0.3, 0.3]), 0.5
    th = [math.atan2(p[1] - c[1], p[0] - c[0]) for p in ((0.8, 0.3), (0.3, 0.8))]
    ths = np.linspace(th[0], th[1], 200001)
    pts = c[:, None] + rad * np.vstack([np.cos(ths), np.sin(ths)])
    k = int(np.argmax(np.hypot(*pts) > 0.9))
    s_cross = rad * (ths[k] - th[0])
    timing = tp.trapezoidal(rad * math.pi / 2, 0.6, 3.0)
    ts = np.linspace(0, timing.T, 200001)
    t_cross = ts[int(np.argmax([timing.at(t)[0] >= s_cross for t in ts]))]
    assert a["reason"].startswith("at t = ") and abs(float(a["reason"].split()[3]) - t_cross) < 1e-4


def test_a_parameter_without_value_is_an_answer_error_not_an_input_error(write_problem, tmp_path):
    r, res = _solve(write_problem, tmp_path, ARM_2R.replace("L2: 2/5", "L2: ~") + LINE)
    assert r.returncode == 1 and "L2" in res["answers"]["line"]["error"]


def test_the_task_error_of_a_joint_law_peaks_between_samples_and_is_found_there():
    # The ideal scheme with an undamped p law (tau = Kp (q_d - q)): the work-space error
    # oscillates, and its crests fall between the output samples.  Independent reference:
    # textbook 2R point-mass dynamics, the closed-form elbow IK for q_d(t), scipy DOP853, the
    # error's crest refined on the dense output.  (The samples' largest value was 4e-5 low.)
    from scipy.integrate import solve_ivp
    from scipy.optimize import minimize_scalar

    from robosolve.load.loader import load_problem_text
    from robosolve.run.pipeline import solve_problem

    law = "  - {type: p_control, trajectory: line, law: p, gains: {q1: 3000, q2: 3000}}\n"
    answers = {a.id: a for a in solve_problem(load_problem_text(ARM_2R + LINE + law)).answers}
    got = answers["p_control"].numeric["max_task_error"]
    start = answers["line"].numeric["start"]
    L1, L2, m1, m2, g = 0.5, 0.4, 2.0, 1.0, 9.81
    a, b = np.array([0.7, 0.1]), np.array([0.2, 0.6])
    L, v, acc = math.hypot(0.5, 0.5), 0.6, 3.0
    ta, T = v / acc, L / v + v / acc

    def x_d(t):
        s = 0.5 * acc * t * t if t <= ta else (v * (t - ta / 2) if t <= T - ta else L - 0.5 * acc * (T - t) ** 2)
        return a + (b - a) * s / L

    elbow = 1.0 if start["q2"] > 0 else -1.0

    def q_d(t):
        x, y = x_d(t)
        q2 = elbow * math.acos((x * x + y * y - L1 * L1 - L2 * L2) / (2 * L1 * L2))
        return np.array([math.atan2(y, x) - math.atan2(L2 * math.sin(q2), L1 + L2 * math.cos(q2)), q2])

    def fk(q):
        return np.array([L1 * math.cos(q[0]) + L2 * math.cos(q[0] + q[1]), L1 * math.sin(q[0]) + L2 * math.sin(q[0] + q[1])])

    def rhs(t, y):
        q, qd = y[:2], y[2:]
        c2, s2 = math.cos(q[1]), math.sin(q[1])
        M = np.array([[(m1 + m2) * L1 ** 2 + m2 * L2 ** 2 + 2 * m2 * L1 * L2 * c2, m2 * L2 ** 2 + m2 * L1 * L2 * c2],
                      [m2 * L2 ** 2 + m2 * L1 * L2 * c2, m2 * L2 ** 2]])
        c = np.array([-m2 * L1 * L2 * s2 * (2 * qd[0] * qd[1] + qd[1] ** 2), m2 * L1 * L2 * s2 * qd[0] ** 2])
        G = np.array([(m1 + m2) * g * L1 * math.cos(q[0]) + m2 * g * L2 * math.cos(q[0] + q[1]),
                      m2 * g * L2 * math.cos(q[0] + q[1])])
        return np.concatenate([qd, np.linalg.solve(M, 3000 * (q_d(t) - q) - c - G)])

    q0 = np.array([start["q1"], start["q2"]])
    assert fk(q0) == pytest.approx(a, abs=1e-12) and q_d(0.0) == pytest.approx(q0, abs=1e-12)
    pieces, y = [], np.concatenate([q0, [0.0, 0.0]])
    for lo, hi in ((0.0, ta), (ta, T - ta), (T - ta, T)):
        sol = solve_ivp(rhs, (lo, hi), y, method="DOP853", rtol=1e-11, atol=1e-13, dense_output=True)
        pieces.append((lo, hi, sol))
        y = sol.y[:, -1]

    def error(t, i):
        sol = next(s for lo, hi, s in pieces if t <= hi)
        return abs(x_d(t)[i] - fk(sol.sol(t)[:2])[i])

    # every step of the reference solver, and its midpoints: the crests are bracketed
    ts = np.unique(np.concatenate([np.concatenate([s.t, (s.t[1:] + s.t[:-1]) / 2]) for _lo, _hi, s in pieces]))
    for i, c in enumerate(("E.x", "E.y")):
        vals = np.array([error(t, i) for t in ts])
        k = int(np.argmax(vals))
        crest = minimize_scalar(lambda t: -error(t, i), bounds=(ts[max(k - 1, 0)], ts[min(k + 1, ts.size - 1)]),
                                method="bounded", options={"xatol": 1e-12})
        assert got[c] == pytest.approx(max(vals[k], -crest.fun), rel=1e-6)


def test_the_report_states_the_start_the_run_really_starts_from():
    # a control along a trajectory from a given `start` said "from the trajectory's start"
    from robosolve.load.loader import load_problem_text
    from robosolve.run.pipeline import solve_problem

    law = ("  - {type: p_control, id: given, trajectory: line, law: pd_gravity, gains: {q1: 100, q2: 100},"
           " gains_d: {q1: 10, q2: 10}, start: {q1: 0.1, q2: 1.3}, duration: 0.2}\n"
           "  - {type: p_control, id: default, trajectory: line, law: pd_gravity, gains: {q1: 100, q2: 100},"
           " gains_d: {q1: 10, q2: 10}, duration: 0.2}\n")
    answers = {a.id: a for a in solve_problem(load_problem_text(ARM_2R + LINE + law)).answers}
    step = lambda qid: next(s for s in answers[qid].steps if s.title.startswith("Closed loop"))  # noqa: E731
    given, default = step("given").text, step("default").text
    assert "integrated from $q_{1} = #$, $q_{2} = #$, at rest" in given and "trajectory's start" not in given
    assert "integrated from the trajectory's start, at rest" in default

    def numbers(text):
        for piece in text:
            if isinstance(piece, tuple):
                yield from numbers(piece)
            elif not isinstance(piece, str):
                yield piece.value

    assert [0.1, 1.3] == [v for v in numbers(given) if v in (0.1, 1.3)]


def test_a_run_ending_a_rounding_after_a_path_sample_leaves_no_empty_interval():
    """duration 0.2 against a path sampled at k·Δt (a break at 0.19999999999999998): the last
    interval was 2.8e-17 s long, LSODA refused it ("illegal input") and the run fell back to
    Radau with a warning on the console. Now no warning, and the run ends at the duration."""
    import warnings

    from robosolve.load.loader import load_problem_text
    from robosolve.run.pipeline import solve_problem

    law = ("  - {type: p_control, id: default, trajectory: line, law: pd_gravity, gains: {q1: 100, q2: 100},"
           " gains_d: {q1: 10, q2: 10}, duration: 0.2}\n")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        answers = {a.id: a for a in solve_problem(load_problem_text(ARM_2R + LINE + law)).answers}
    values = answers["default"].numeric
    assert values["t_max_error"] == {"q1": 0.2, "q2": 0.2}, values


def test_a_parameter_override_in_at_moves_the_reference_the_start_and_the_task_map(write_problem, tmp_path):
    """`at: {L2: 0.45}` on the p_control: the whole question is the arm with L2 = 0.45 (its start
    by IK, its task map x(q), its dynamics), not the trajectory's L2 = 0.4 mixed with dynamics of
    0.45. Reference: closed-form 2R kinematics, IK and dynamics with L2 = 0.45, scipy's DOP853."""
    from scipy.integrate import solve_ivp

    law = """  - type: p_control
    trajectory: line
    law: task_pd_gravity
    gains: {E.x: 800, E.y: 800}
    gains_d: {E.x: 60, E.y: 60}
    at: {L2: 0.45}
"""
    r, res = _solve(write_problem, tmp_path, ARM_2R + LINE + law)
    assert r.returncode == 0, r.stderr
    L1, L2, m1, m2, g = 0.5, 0.45, 2.0, 1.0, 9.81

    def x(q):
        return np.array([L1 * math.cos(q[0]) + L2 * math.cos(q[0] + q[1]),
                         L1 * math.sin(q[0]) + L2 * math.sin(q[0] + q[1])])

    def jac(q):
        s1, c1, s12, c12 = math.sin(q[0]), math.cos(q[0]), math.sin(q[0] + q[1]), math.cos(q[0] + q[1])
        return np.array([[-L1 * s1 - L2 * s12, -L2 * s12], [L1 * c1 + L2 * c12, L2 * c12]])

    # the start: the closed-form IK of `from` on the branch the trajectory follows (sign of q2)
    elbow = math.copysign(1.0, res["answers"]["line"]["numeric"]["start"]["q2"])
    a = np.array([0.7, 0.1])
    q2 = elbow * math.acos((a @ a - L1 ** 2 - L2 ** 2) / (2 * L1 * L2))
    q0 = np.array([math.atan2(a[1], a[0]) - math.atan2(L2 * math.sin(q2), L1 + L2 * math.cos(q2)), q2])
    path, timing = tp.line([0.7, 0.1], [0.2, 0.6]), tp.trapezoidal(math.hypot(0.5, 0.5), 0.6, 3.0)

    def rhs(t, y):
        q, qd = y[:2], y[2:]
        c2, s2 = math.cos(q[1]), math.sin(q[1])
        M = np.array([[(m1 + m2) * L1 ** 2 + m2 * L2 ** 2 + 2 * m2 * L1 * L2 * c2, m2 * L2 ** 2 + m2 * L1 * L2 * c2],
                      [m2 * L2 ** 2 + m2 * L1 * L2 * c2, m2 * L2 ** 2]])
        c = np.array([-m2 * L1 * L2 * s2 * (2 * qd[0] * qd[1] + qd[1] ** 2), m2 * L1 * L2 * s2 * qd[0] ** 2])
        G = np.array([(m1 + m2) * g * L1 * math.cos(q[0]) + m2 * g * L2 * math.cos(q[0] + q[1]),
                      m2 * g * L2 * math.cos(q[0] + q[1])])
        _s, xd, vd, _ad = tp.task_state(path, timing, min(t, timing.T))
        e, ed = xd - x(q), vd - jac(q) @ qd
        return np.concatenate([qd, np.linalg.solve(M, jac(q).T @ (800 * e + 60 * ed) + G - c - G)])

    ts = np.linspace(0, timing.T, 3001)
    sol = solve_ivp(rhs, (0, timing.T), np.concatenate([q0, [0, 0]]), t_eval=ts, rtol=1e-11, atol=1e-12,
                    method="DOP853", max_step=0.01)
    err = np.array([tp.task_state(path, timing, t)[1] - x(sol.y[:2, k]) for k, t in enumerate(ts)]).T
    got = res["answers"]["p_control"]["numeric"]
    for i, c in enumerate(("E.x", "E.y")):
        assert got["max_error"][c] == pytest.approx(np.max(np.abs(err[i])), rel=2e-3)
        assert got["final_error"][c] == pytest.approx(err[i, -1], rel=1e-3, abs=1e-9)


def test_computed_torque_from_off_the_path_peaks_at_t_0_exactly(write_problem, tmp_path):
    """Task computed torque with an exact model: e'' + Kd e' + Kp e = 0, e(0) = x_d(0) - x(start),
    e'(0) = 0 (the timing starts at rest). Kp = 100, Kd = 20 is critically damped:
    e = e0 (1 + 10 t) exp(-10 t), whose magnitude only falls, so the largest error is the start's,
    at t = 0 (core/extremes.py: the start ties with the polish a hair inside, not 2e-9 s)."""
    law = """  - type: p_control
    trajectory: line
    law: task_computed_torque
    gains: {E.x: 100, E.y: 100}
    gains_d: {E.x: 20, E.y: 20}
    start: {q1: -0.6, q2: 1.9}
    duration: 1
"""
    r, res = _solve(write_problem, tmp_path, ARM_2R + LINE + law)
    assert r.returncode == 0, r.stderr
    q = (-0.6, 1.9)
    x0 = (0.5 * math.cos(q[0]) + 0.4 * math.cos(q[0] + q[1]), 0.5 * math.sin(q[0]) + 0.4 * math.sin(q[0] + q[1]))
    e0 = (0.7 - x0[0], 0.1 - x0[1])
    got = res["answers"]["p_control"]["numeric"]
    for i, c in enumerate(("E.x", "E.y")):
        assert got["max_error"][c] == pytest.approx(abs(e0[i]), rel=1e-5)   # 6 digits kept
        assert got["t_max_error"][c] == 0
        assert got["final_error"][c] == pytest.approx(e0[i] * 11 * math.exp(-10), rel=1e-4, abs=1e-9)


def _independent_task_pd_2r(L2, m2, kp, kd, elbow, L1=0.5, m1=2.0, g=9.81):
    """max |x_d - x| and the final error of each coordinate of task_pd_gravity along LINE, for the
    2R of ARM_2R with the given L2 and m2: closed-form kinematics, IK, dynamics and trapezoidal
    timing written here from the textbook, integrated by scipy's DOP853."""
    from scipy.integrate import solve_ivp

    a, b = np.array([0.7, 0.1]), np.array([0.2, 0.6])
    length, vmax, amax = float(np.linalg.norm(b - a)), 0.6, 3.0
    ta, T = vmax / amax, length / vmax + vmax / amax       # the cruise is reached: length > vmax^2 / amax
    u = (b - a) / length

    def desired(t):
        t = min(t, T)
        if t <= ta:
            s, sd = 0.5 * amax * t ** 2, amax * t
        elif t >= T - ta:
            s, sd = length - 0.5 * amax * (T - t) ** 2, amax * (T - t)
        else:
            s, sd = 0.5 * amax * ta ** 2 + vmax * (t - ta), vmax
        return a + s * u, sd * u

    def x(q):
        return np.array([L1 * math.cos(q[0]) + L2 * math.cos(q[0] + q[1]),
                         L1 * math.sin(q[0]) + L2 * math.sin(q[0] + q[1])])

    def jac(q):
        s1, c1, s12, c12 = math.sin(q[0]), math.cos(q[0]), math.sin(q[0] + q[1]), math.cos(q[0] + q[1])
        return np.array([[-L1 * s1 - L2 * s12, -L2 * s12], [L1 * c1 + L2 * c12, L2 * c12]])

    q2 = elbow * math.acos((a @ a - L1 ** 2 - L2 ** 2) / (2 * L1 * L2))
    q0 = np.array([math.atan2(a[1], a[0]) - math.atan2(L2 * math.sin(q2), L1 + L2 * math.cos(q2)), q2])

    def rhs(t, y):
        q, qd = y[:2], y[2:]
        c2, s2 = math.cos(q[1]), math.sin(q[1])
        M = np.array([[(m1 + m2) * L1 ** 2 + m2 * L2 ** 2 + 2 * m2 * L1 * L2 * c2, m2 * L2 ** 2 + m2 * L1 * L2 * c2],
                      [m2 * L2 ** 2 + m2 * L1 * L2 * c2, m2 * L2 ** 2]])
        c = np.array([-m2 * L1 * L2 * s2 * (2 * qd[0] * qd[1] + qd[1] ** 2), m2 * L1 * L2 * s2 * qd[0] ** 2])
        xd, vd = desired(t)
        e, ed = xd - x(q), vd - jac(q) @ qd
        return np.concatenate([qd, np.linalg.solve(M, jac(q).T @ (kp * e + kd * ed) - c)])   # g(q) cancels

    ts = np.linspace(0, T, 3001)
    sol = solve_ivp(rhs, (0, T), np.concatenate([q0, [0, 0]]), t_eval=ts, rtol=1e-11, atol=1e-12,
                    method="DOP853", max_step=0.01)
    err = np.array([desired(t)[0] - x(sol.y[:2, k]) for k, t in enumerate(ts)]).T
    return np.max(np.abs(err), axis=1), err[:, -1]


@pytest.mark.parametrize("line_at, follower_at, L2, m2", [
    ("{L2: 0.45}", None, 0.45, 1.0),                      # the trajectory's override holds for its follower
    ("{L2: 0.45, m2: 3}", "{m2: 1.5}", 0.45, 1.5),        # the follower's own override wins
])
def test_a_follower_works_on_the_arm_of_the_trajectory_it_follows(line_at, follower_at, L2, m2):
    """A trajectory with `at: {L2: 0.45}` followed by a p_control without one: the run is the arm
    with L2 = 0.45 throughout (the reference, its start, the task map and the dynamics), not the
    reference of 0.45 under kinematics and dynamics of the data's 0.4; the follower's own `at`
    goes on top. Reference: `_independent_task_pd_2r` (closed-form 2R, scipy DOP853)."""
    from robosolve.load.loader import load_problem_text
    from robosolve.run.pipeline import solve_problem

    law = ("  - {type: p_control, trajectory: line, law: task_pd_gravity, gains: {E.x: 800, E.y: 800}, "
           "gains_d: {E.x: 60, E.y: 60}" + (f", at: {follower_at}" if follower_at else "") + "}\n")
    text = ARM_2R + LINE + f"    at: {line_at}\n" + law
    answers = {a.id: a for a in solve_problem(load_problem_text(text, "f.yaml")).answers}
    got = answers["p_control"]
    assert got.error is None, got.error
    elbow = math.copysign(1.0, answers["line"].numeric["start"]["q2"])
    max_err, final = _independent_task_pd_2r(L2, m2, 800, 60, elbow)
    for i, c in enumerate(("E.x", "E.y")):
        assert got.numeric["max_error"][c] == pytest.approx(max_err[i], rel=2e-3)
        assert got.numeric["final_error"][c] == pytest.approx(final[i], rel=1e-3, abs=1e-9)
