"""The motion_profile, joint_torques and p_control question types through the pipeline."""

import math

import numpy as np
import pytest

from robosolve.load.loader import load_problem_text
from robosolve.run.pipeline import solve_problem
from robosolve.solvers.base import Budgets

ARM = """
robosolve: 1
name: arm
parameters: {L1: 1/2, L2: 2/5, m1: 4, m2: 3, m3: 1, F: %s, g: 9.81}
joints:
  - {name: theta1, type: revolute}
  - {name: theta2, type: revolute}
frames:
  "1": {parent: "0", pose: "Rx(theta1) Ty(L1)"}
  "2": {pose: "Rx(theta2) Ty(L2)"}
bodies:
  - {name: link1, frame: "1", mass: m1, rod: {from: [0, -L1, 0], to: [0, 0, 0]}}
  - {name: link2, frame: "2", mass: m2, rod: {from: [0, -L2, 0], to: [0, 0, 0]}}
  - {name: payload, frame: "2", mass: m3, point: [0, 0, 0]}
forces:
  - {name: F, frame: "2", at: [0, -L2/2, 0], force: [0, 0, -F]}
questions:
%s
"""

PROFILE = """  - {type: motion_profile, id: prof, from: {theta1: 0, theta2: 0}, to: {theta1: pi/2, theta2: -pi/3},
     max_acceleration: {theta1: 2, theta2: 3}}
"""


def run(questions, F="5", budgets=None):
    report = solve_problem(load_problem_text(ARM % (F, PROFILE + questions)), budgets)
    return {a.id: a for a in report.answers}


# A dynamics budget no derivation meets: the solvers take the numeric-only path.
NO_SYMBOLIC_DYNAMICS = Budgets(dynamics_seconds=1e-6)


def test_motion_profile_answers():
    a = run("")["prof"]
    assert a.error is None
    n = a.numeric
    # theta1: sqrt(4 (pi/2) / 2) = sqrt(pi); theta2: sqrt(4 (pi/3) / 3) = 2 sqrt(pi)/3
    assert n["durations"] == pytest.approx({"theta1": math.sqrt(math.pi), "theta2": 2 * math.sqrt(math.pi) / 3})
    assert n["T"] == pytest.approx(math.sqrt(math.pi))
    assert n["accelerations"] == pytest.approx({"theta1": 2, "theta2": 4 / 3})
    assert str(a.symbolic["T"]) == "sqrt(pi)"
    assert set(a.symbolic["profiles"]) == {"theta1", "theta2"}
    assert [f.kind for f in a.figures] == ["motion_profile"]


def test_joint_torques_peaks_by_hand():
    a = run("  - {type: joint_torques}\n")["joint_torques"]
    assert a.error is None, a.error
    # at t = 0+: q = 0, qd = 0, qdd = (2, -4/3).  M11 = L1^2 (m1/3 + m2 + m3) + L2^2 (m2/3 + m3)
    # + 2 L1 L2 (m2/2 + m3) = 2.653333, M12 = L2^2 (m2/3 + m3) + L1 L2 (m2/2 + m3) = 0.82, M22 = 0.32;
    # gravity g1 = g (L1 (m1/2 + m2 + m3) + L2 (m2/2 + m3)) = 4 g, g2 = g L2 (m2/2 + m3) = g;
    # the force F = 5 down at 0.7 m (joint 1) and 0.2 m (joint 2) needs +3.5 and +1.0 more.
    c1 = 2.6533333333333333 * 2 - 0.82 * 4 / 3 + 4 * 9.81 + 3.5
    c2 = 0.82 * 2 - 0.32 * 4 / 3 + 9.81 + 1.0
    act = a.numeric["actuators"]
    assert act["C1"]["peak"] == pytest.approx(c1, rel=1e-12) and act["C1"]["t_peak"] == 0
    assert act["C2"]["peak"] == pytest.approx(c2, rel=1e-12) and act["C2"]["t_peak"] == 0
    # the closed forms hold the arm after T: gravity of the final pose and the force
    import sympy as sp
    pw = a.symbolic["profiles"]["C1"]
    from robosolve.core.symbols import TIME as t
    # final pose: link 1 vertical (no gravity moment), link 2 at pi/6 from horizontal; F stays
    # perpendicular to link 2, so its moment about joint 1 is F (L1 cos(theta2) + L2/2)
    hold = 9.81 * 0.4 * 2.5 * math.cos(math.pi / 6) + 5 * (0.5 * math.cos(-math.pi / 3) + 0.2)
    # the profile keeps the parameters as symbols (symbolic answers keep every parameter)
    assert {"L1", "L2", "m2", "m3", "F", "g"} <= {s.name for s in pw.free_symbols}
    data = {"L1": 0.5, "L2": 0.4, "m1": 4, "m2": 3, "m3": 1, "F": 5, "g": 9.81}
    values = {s: data[s.name] for s in pw.free_symbols if s.name in data}
    assert float(pw.xreplace(values).subs(t, 10)) == pytest.approx(hold, rel=1e-12)


def test_joint_torques_with_a_parameter_override_follow_the_profile_it_draws():
    """`at: {m3: 2}` on joint_torques whose profile's limit is m3: the question is the arm with
    m3 = 2 throughout, its profile included (it was the recorded profile of m3 = 1 under the
    dynamics of m3 = 2). By hand, as above, at t = 0+ with m3 = 2: T = sqrt(pi), qdd = (2, -4/3);
    M11 = L1^2 (m1/3 + m2 + m3) + L2^2 (m2/3 + m3) + 2 L1 L2 (m2/2 + m3), M12 = L2^2 (m2/3 + m3)
    + L1 L2 (m2/2 + m3), M22 = L2^2 (m2/3 + m3); g1 = g (L1 (m1/2 + m2 + m3) + L2 (m2/2 + m3)),
    g2 = g L2 (m2/2 + m3); the force adds 3.5 and 1.0."""
    profile = ("  - {type: motion_profile, id: limited, from: {theta1: 0, theta2: 0}, to: {theta1: pi/2, "
               "theta2: -pi/3}, max_acceleration: {theta1: m3, theta2: 3}}\n"
               "  - {type: joint_torques, profile: limited, at: {m3: 2}}\n")
    a = run(profile)["joint_torques"]
    assert a.error is None, a.error
    L1, L2, m1, m2, m3, g = 0.5, 0.4, 4, 3, 2, 9.81
    M11 = L1 ** 2 * (m1 / 3 + m2 + m3) + L2 ** 2 * (m2 / 3 + m3) + 2 * L1 * L2 * (m2 / 2 + m3)
    M12, M22 = L2 ** 2 * (m2 / 3 + m3) + L1 * L2 * (m2 / 2 + m3), L2 ** 2 * (m2 / 3 + m3)
    g1, g2 = g * (L1 * (m1 / 2 + m2 + m3) + L2 * (m2 / 2 + m3)), g * L2 * (m2 / 2 + m3)
    act = a.numeric["actuators"]
    assert act["C1"]["peak"] == pytest.approx(M11 * 2 - M12 * 4 / 3 + g1 + 3.5, rel=1e-12)
    assert act["C2"]["peak"] == pytest.approx(M12 * 2 - M22 * 4 / 3 + g2 + 1.0, rel=1e-12)


@pytest.mark.parametrize("profile_at, follower_at", [("{m3: 2}", None), ("{m3: 5}", "{m3: 2}")])
def test_joint_torques_work_on_the_arm_of_the_profile_they_follow(profile_at, follower_at):
    """The profile question carries `at: {m3: 2}`, joint_torques none: the torques are those of the
    arm with m3 = 2 (the profile's limit and the dynamics alike), not the profile of m3 = 2 under
    the data's m3 = 1; a follower's own `at` goes on top (m3: 5 on the profile, 2 on the follower:
    m3 = 2 throughout). By hand as in the test above (t = 0+, m3 = 2)."""
    questions = ("  - {type: motion_profile, id: limited, from: {theta1: 0, theta2: 0}, to: {theta1: pi/2, "
                 f"theta2: -pi/3}}, max_acceleration: {{theta1: m3, theta2: 3}}, at: {profile_at}}}\n"
                 "  - {type: joint_torques, profile: limited" + (f", at: {follower_at}" if follower_at else "") + "}\n")
    a = run(questions)["joint_torques"]
    assert a.error is None, a.error
    L1, L2, m1, m2, m3, g = 0.5, 0.4, 4, 3, 2, 9.81
    M11 = L1 ** 2 * (m1 / 3 + m2 + m3) + L2 ** 2 * (m2 / 3 + m3) + 2 * L1 * L2 * (m2 / 2 + m3)
    M12, M22 = L2 ** 2 * (m2 / 3 + m3) + L1 * L2 * (m2 / 2 + m3), L2 ** 2 * (m2 / 3 + m3)
    g1, g2 = g * (L1 * (m1 / 2 + m2 + m3) + L2 * (m2 / 2 + m3)), g * L2 * (m2 / 2 + m3)
    act = a.numeric["actuators"]
    assert act["C1"]["peak"] == pytest.approx(M11 * 2 - M12 * 4 / 3 + g1 + 3.5, rel=1e-12)
    assert act["C2"]["peak"] == pytest.approx(M12 * 2 - M22 * 4 / 3 + g2 + 1.0, rel=1e-12)


def test_p_control_answers_and_options():
    ans = run("""  - {type: p_control, gains: {theta1: 5000, theta2: 5000}}
  - {type: p_control, id: ct, law: computed_torque, gains: {theta1: 100, theta2: 100},
     gains_d: {theta1: 20, theta2: 20}, start: {theta1: 0.1, theta2: 0}, duration: 1}
""", F="0")
    p = ans["p_control"]
    assert p.error is None, p.error
    assert set(p.numeric) >= {"max_error", "final_error"}
    assert list(p.numeric["max_error"]) == ["theta1", "theta2"]
    assert 0 < p.numeric["max_error"]["theta1"] < 0.05
    assert [f.kind for f in p.figures] == ["control_tracking", "control_effort"]
    ct = ans["ct"]
    # computed torque with no external force: e'' + 20 e' + 100 e = 0 from e(0) = -0.1
    e_end = -0.1 * (1 + 10 * 1) * math.exp(-10)
    assert ct.numeric["max_error"]["theta1"] == pytest.approx(0.1, rel=1e-6)
    assert ct.numeric["final_error"]["theta1"] == pytest.approx(e_end, rel=1e-4, abs=1e-15)
    assert ct.numeric["max_error"]["theta2"] < 1e-9


def test_null_parameter_gives_notes_not_errors():
    ans = run("  - {type: joint_torques}\n  - {type: p_control, gains: {theta1: 50, theta2: 50}}\n", F="~")
    jt, pc = ans["joint_torques"], ans["p_control"]
    assert jt.error is None and "actuators" not in jt.numeric and "profiles" in jt.symbolic
    assert any("F" in n for n in jt.notes)
    assert pc.error is None and not pc.numeric and any("F" in n for n in pc.notes)


def test_profile_that_failed_gives_an_error_answer():
    text = ARM % ("5", """  - {type: motion_profile, id: prof, shape: trapezoidal, from: {theta1: 0, theta2: 0},
     to: {theta1: 1, theta2: 0}, max_acceleration: {theta1: 1, theta2: 1}, max_velocity: {theta1: L1/L1, theta2: 1}}
  - {type: joint_torques}
""")
    ans = {a.id: a for a in solve_problem(load_problem_text(text)).answers}
    assert ans["prof"].error is None
    # a still joint in a trapezoidal profile (Robotics Toolbox crashes on it)
    assert ans["prof"].numeric["durations"]["theta2"] == 0
    assert ans["joint_torques"].error is None


def test_two_routes_numeric_only_path_matches_the_symbolic_one():
    # two routes of one engine (symbolic M, c, g lambdified vs the numeric-only assembly)
    qs = "  - {type: joint_torques}\n  - {type: p_control, gains: {theta1: 500, theta2: 500}}\n"
    sym = run(qs)
    num = run(qs, budgets=NO_SYMBOLIC_DYNAMICS)
    assert "profiles" not in num["joint_torques"].symbolic
    assert any("numerically" in n for n in num["joint_torques"].notes)
    for act in ("C1", "C2"):
        assert num["joint_torques"].numeric["actuators"][act]["peak"] == pytest.approx(
            sym["joint_torques"].numeric["actuators"][act]["peak"], rel=1e-9)
    for key in ("max_error", "final_error"):
        assert num["p_control"].numeric[key] == pytest.approx(sym["p_control"].numeric[key], rel=1e-4, abs=1e-12)


SCARA_QUESTIONS = """
questions:
  - {type: motion_profile, id: prof, shape: trapezoidal, from: {theta1: 0, theta2: 0, l: 0},
     to: {theta1: pi/2, theta2: pi/2, l: 1/5}, max_acceleration: {theta1: 2, theta2: 3, l: 1},
     max_velocity: {theta1: 1, theta2: 1, l: 1/2}}
  - {type: joint_torques}
  - {type: p_control, law: pd, gains: {theta1: 300, theta2: 300, l: 300},
     gains_d: {theta1: 20, theta2: 20, l: 20}}
"""


def test_two_routes_scara_prismatic_three_joints_symbolic_vs_numeric_only():
    # the compiled 3-joint closed loop (M solved by symbolic LU) against the engine's
    # numeric-only M, c, g with numpy solves; and the prismatic joint's holding force
    from pathlib import Path

    base = (Path(__file__).resolve().parents[2] / "problems" / "scara-rrp.yaml").read_text()
    text = base[:base.index("questions:")] + SCARA_QUESTIONS

    def solve_all(budgets=None):
        return {a.id: a for a in solve_problem(load_problem_text(text), budgets).answers}

    sym = solve_all()
    f3 = sym["joint_torques"].numeric["actuators"]["F3"]
    # l is measured downwards (M23 = Tz(-l)): the actuator holds the payload (m3 g = 19.62 N)
    # and brakes its descent at 1 m/s^2 at the end: -m3 (g + a) = -21.62 N
    assert f3["peak"] == pytest.approx(-2 * (9.81 + 1), rel=1e-12)
    num = solve_all(NO_SYMBOLIC_DYNAMICS)
    for act in ("C1", "C2", "F3"):
        assert num["joint_torques"].numeric["actuators"][act]["peak"] == pytest.approx(
            sym["joint_torques"].numeric["actuators"][act]["peak"], rel=1e-9)
    for key in ("max_error", "final_error"):
        assert num["p_control"].numeric[key] == pytest.approx(sym["p_control"].numeric[key], rel=1e-4, abs=1e-12)


def test_figures_are_drawn(tmp_path):
    from robosolve.run.pipeline import write_outputs

    report = solve_problem(load_problem_text(ARM % ("5", PROFILE + """  - {type: joint_torques}
  - {type: p_control, law: pd, gains: {theta1: 300, theta2: 300}, gains_d: {theta1: 20, theta2: 20}}
""")))
    out = write_outputs(report, tmp_path / "out")
    names = sorted(p.name for p in (out / "figures").iterdir())
    assert names == ["joint_torques-torques.png", "p_control-effort.png", "p_control-tracking.png",
                     "prof-profile.png"]
    assert all(a.notes == [] for a in report.answers)          # no "could not be drawn" note


def test_null_acceleration_limit_keeps_the_profile_symbolic():
    text = (ARM % ("5", """  - {type: motion_profile, id: prof, from: {theta1: 0, theta2: 0}, to: {theta1: pi/2, theta2: -pi/3},
     max_acceleration: {theta1: a1, theta2: 3}}
  - {type: joint_torques}
  - {type: p_control, gains: {theta1: 50, theta2: 50}}
""")).replace("F: 5,", "F: 5, a1: ~,")
    ans = {a.id: a for a in solve_problem(load_problem_text(text)).answers}
    assert all(a.error is None for a in ans.values())
    assert "Max" in str(ans["prof"].symbolic["T"]) and "T" not in ans["prof"].numeric
    assert ans["joint_torques"].notes == ["numeric torques omitted: it needs the null parameter a1"]
    assert ans["p_control"].notes == ["numeric simulation omitted: it needs the null parameter a1"]


def test_trapezoidal_cruise_velocities_are_an_answer_key():
    """A trapezoidal profile's lowered cruise velocities (results.json `velocities`) are a key of
    the type's schema, so a teacher may grade them: against the closed form v (T − v/a) = Δ of the
    slower joint (Δ = 0.5, a = 2, T = 2.5 from the first joint: v = (5 − √21)/2)."""
    from robosolve.questions.registry import QUESTION_TYPES

    problem = load_problem_text("""robosolve: 1
name: trap
parameters: {L: 1}
joints: [{name: q1, type: revolute}, {name: q2, type: revolute}]
frames: {"1": {parent: "0", pose: "Rz(q1) Tx(L)"}, "2": {pose: "Rz(q2) Tx(L)"}}
questions:
  - {type: motion_profile, shape: trapezoidal, from: {q1: 0, q2: 0}, to: {q1: 2, q2: 0.5},
     max_acceleration: {q1: 2, q2: 2}, max_velocity: {q1: 1, q2: 1}, grade: [T, velocities]}
""", "trap.yaml")
    answer = solve_problem(problem).answers[0]
    assert answer.numeric["T"] == pytest.approx(2.5)
    assert answer.numeric["velocities"]["q1"] == pytest.approx(1.0)
    assert answer.numeric["velocities"]["q2"] == pytest.approx((5 - math.sqrt(21)) / 2, rel=1e-12)
    assert "velocities" in [k.name for k in QUESTION_TYPES["motion_profile"].answers]


def test_synchronized_time_shown_once_when_it_is_a_decimal_and_twice_when_exact():
    # exact data: T = sqrt(pi) and its decimal 1.77245; decimal data: T = 1.77245 once
    exact = run("")["prof"]
    decimal = solve_problem(load_problem_text(ARM % ("5", """  - {type: motion_profile, id: prof, from: {theta1: 0.0, theta2: 0.0},
     to: {theta1: 1.5, theta2: -1.0}, max_acceleration: {theta1: 2.0, theta2: 3.0}}
""")), None).answers[0]
    step = lambda a: next(s for s in a.steps if s.title == "Synchronized time")  # noqa: E731
    assert [lhs for lhs, _ in step(exact).equations] == ["T = \\max_i T_i", "T"]
    assert [lhs for lhs, _ in step(decimal).equations] == ["T = \\max_i T_i"]
    assert float(step(decimal).equations[0][1]) == pytest.approx(math.sqrt(4 * 1.5 / 2.0), rel=1e-14)
