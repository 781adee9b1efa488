"""The forward_dynamics question type through the pipeline, `t` in expressions, and forces
that vary with time during forward_dynamics, p_control and joint_torques.

References: the closed forms of the course's pendulum (turning point C θ* = G sin θ*, the
free swing between 0 and −π), and pinocchio (``aba`` / ``rnea`` with external forces)
integrated by scipy's LSODA, independent of robosolve's dynamics and integrator.
"""

import math

import numpy as np
import pytest
from scipy.optimize import brentq

from robosolve.errors import InputError
from robosolve.load.loader import load_problem_text
from robosolve.run.pipeline import solve_problem

ARM = """
robosolve: 1
name: pendulum
parameters: {L: 1, m1: 2, m2: 1, g: 9.81, F: %s}
joints: [{name: theta, type: revolute, actuator: C, limits: [-pi, pi]}]
frames: {"1": {parent: "0", pose: "Rx(theta) Ty(L)"}}
bodies:
  - {name: link, frame: "1", mass: m1, rod: {from: [0, -L, 0], to: [0, 0, 0]}}
  - {name: payload, frame: "1", mass: m2, point: [0, 0, 0]}
forces: [{name: P, frame: "1", at: [0, -L/3, 0], force: [0, 0, %s]}]
questions:
%s
"""
G = (2 / 2 + 1) * 9.81 * 1          # (m1/2 + m2) g L
INERTIA = (2 / 3 + 1) * 1           # (m1/3 + m2) L^2


def answers(questions, F="0", force="-F"):
    report = solve_problem(load_problem_text(ARM % (F, force, questions)))
    return {a.id: a for a in report.answers}


def issues(text):
    with pytest.raises(InputError) as exc:
        load_problem_text(text, "f.yaml")
    return [str(i) for i in exc.value.issues]


def test_free_swing_between_0_and_minus_pi():
    a = answers("  - {id: free, type: forward_dynamics, duration: 3}\n")["free"]
    assert a.error is None, a.error
    n = a.numeric
    assert n["max"]["theta"] == 0.0
    assert n["min"]["theta"] == pytest.approx(-math.pi, abs=1e-8)
    assert n["energy"]["start"] == 0.0 and abs(n["energy"]["end"]) < 1e-7
    assert a.symbolic["equations"][0].endswith("= -2*F*L/3")      # symbolic: F kept (0 here)
    assert [f.kind for f in a.figures] == ["forward_dynamics"]
    assert len(a.figures[0].data["t"]) <= 1001


def test_constant_torque_too_weak_turns_back_at_the_course_closed_form():
    C = 12
    a = answers(f"  - {{id: weak, type: forward_dynamics, actuators: {{C: {C}}}, duration: 3}}\n")["weak"]
    # energy: C θ = G sin θ at the turning point θ* in (−π, 0)
    theta_star = brentq(lambda x: C * x - G * math.sin(x), -math.pi + 1e-9, -1e-3)
    assert a.numeric["min"]["theta"] == pytest.approx(theta_star, rel=1e-8)
    assert a.numeric["max"]["theta"] == 0.0


def test_strong_torque_spins_and_leaves_the_limits():
    a = answers("  - {id: strong, type: forward_dynamics, actuators: {C: 40}, duration: 3}\n")["strong"]
    assert a.numeric["final"]["theta"] > 2 * math.pi
    assert any("leaves its limits" in n for n in a.notes)
    # energy balance: E_end - E_start = C Δθ (the work of a constant torque)
    e = a.numeric["energy"]
    assert e["end"] - e["start"] == pytest.approx(40 * a.numeric["final"]["theta"], rel=1e-8)


def test_start_rates_and_at_overrides_parameters():
    qs = ("  - {id: r, type: forward_dynamics, start: {theta: -pi/2, theta_dot: 1}, duration: 1,"
          " at: {m2: 0}}\n")
    a = answers(qs)["r"]
    # energy at the start with m2 = 0: T = m1 L^2 θ'^2 / 6, U = m1 g L sin θ / 2
    assert a.numeric["energy"]["start"] == pytest.approx(2 / 6 - 9.81, rel=1e-9)


def test_null_parameter_omits_the_numbers_with_a_note():
    a = answers("  - {id: r, type: forward_dynamics, duration: 1}\n", F="~")["r"]
    assert a.numeric == {}
    assert any("F" in n and "null" in n for n in a.notes)
    assert "F" in a.symbolic["equations"][0]


def test_loader_errors():
    text = ARM % ("0", "-F", "  - {type: forward_dynamics, actuators: {Cx: 1}, duration: 0, at: {theta: 1},"
                  " start: {theta_ddot: 1}}\n  - {type: forward_dynamics}\n")
    msgs = issues(text)
    assert any("actuators.Cx: unknown actuator 'Cx' (did you mean 'C'?)" in m for m in msgs)
    assert any("duration: expected a positive duration" in m for m in msgs)
    assert any("at.theta" in m and "parameters only" in m and "start" in m for m in msgs)
    assert any("start.theta_ddot" in m for m in msgs)
    assert any("missing required key 'duration'" in m for m in msgs)
    assert all(m.startswith("f.yaml:") for m in msgs)


@pytest.mark.parametrize("where,snippet", [
    ("frame", 'frames: {"1": {parent: "0", pose: "Rx(theta) Ty(L*t)"}}'),
    ("body", 'bodies: [{name: link, frame: "1", mass: m1*t, point: [0, 0, 0]}]'),
])
def test_t_refused_where_it_means_nothing(where, snippet):
    text = ARM % ("0", "-F", "  - {type: equations_of_motion}\n")
    key = "frames:" if where == "frame" else "bodies:"
    lines = text.splitlines()
    start = next(i for i, l in enumerate(lines) if l.startswith(key))
    end = start + 1
    while end < len(lines) and lines[end].startswith("  "):
        end += 1
    text = "\n".join(lines[:start] + [snippet] + lines[end:])
    msgs = issues(text)
    # (a frame that fails to load also leaves its bodies and points without a frame: the
    # loader's cascade, not this check's)
    assert "`t` (time) has no meaning here" in msgs[0], msgs
    assert msgs[0].startswith("f.yaml:6:" if where == "frame" else "f.yaml:7:")


def test_t_in_a_statics_force_is_refused():
    msgs = issues(ARM % ("0", "-F", "  - {type: statics, force: [0, 0, t]}\n"))
    assert len(msgs) == 1 and "has no meaning here" in msgs[0]


def test_timed_force_with_a_configuration_is_refused():
    msgs = issues(ARM % ("0", "-F*sin(t)", "  - {type: equations_of_motion, at: {theta: 0}}\n"))
    assert len(msgs) == 1 and "varies with time" in msgs[0] and "at" in msgs[0]
    # without `at` the symbolic equations keep t
    a = answers("  - {type: equations_of_motion}\n", F="3", force="-F*sin(t)")["equations_of_motion"]
    assert "sin(t)" in a.symbolic["equations"][0]


# ------------------------------------------------------------ forces varying with time
def pin_arm(force_of_t):
    pin = pytest.importorskip("pinocchio")
    model = pin.Model()
    j = model.addJoint(0, pin.JointModelRX(), pin.SE3.Identity(), "theta")
    model.appendBodyToJoint(j, pin.Inertia(2.0, np.array([0, 0.5, 0]), np.diag([2 / 12, 0, 2 / 12])),
                            pin.SE3.Identity())
    model.appendBodyToJoint(j, pin.Inertia(1.0, np.array([0, 1.0, 0]), np.zeros((3, 3))), pin.SE3.Identity())
    model.gravity.linear = np.array([0, 0, -9.81])
    data = model.createData()
    p = np.array([0, 2 / 3, 0])

    def fext(t):
        f = np.array([0, 0, force_of_t(t)])
        return [pin.Force.Zero(), pin.Force(f, np.cross(p, f))]

    return pin, model, data, fext


def test_forward_dynamics_with_a_force_varying_in_time_against_pinocchio():
    from scipy.integrate import solve_ivp

    a = answers("  - {id: r, type: forward_dynamics, actuators: {C: 20 + 5*theta_dot}, duration: 2.5}\n",
                F="3", force="-F*sin(2*t)")["r"]
    assert a.error is None, a.error
    pin, model, data, fext = pin_arm(lambda t: -3 * math.sin(2 * t))

    def f(t, y):
        q, v = y[:1], y[1:]
        return np.concatenate([v, pin.aba(model, data, q, v, np.array([20 + 5 * v[0]]), fext(t))])

    sol = solve_ivp(f, (0, 2.5), [0.0, 0.0], method="LSODA", rtol=1e-12, atol=1e-13)
    scale = max(1.0, abs(sol.y[0, -1]))
    assert a.numeric["final"]["theta"] == pytest.approx(sol.y[0, -1], abs=1e-8 * scale)
    assert a.numeric["final_velocity"]["theta"] == pytest.approx(sol.y[1, -1], rel=1e-8)


PROFILE = ("  - {type: motion_profile, id: prof, from: {theta: 0}, to: {theta: pi/2},"
           " max_acceleration: {theta: 4}}\n")


def test_p_control_with_a_force_varying_in_time_against_pinocchio():
    from scipy.integrate import solve_ivp

    from robosolve.motion.profiles import synchronize
    import sympy as sp

    a = answers(PROFILE + "  - {type: p_control, gains: {theta: 400}, duration: 2}\n", F="3",
                force="-F*cos(3*t)")["p_control"]
    assert a.error is None and not a.notes, (a.error, a.notes)
    pin, model, data, fext = pin_arm(lambda t: -3 * math.cos(3 * t))
    plan = synchronize(["theta"], [0], [sp.pi / 2], [4]).numeric_plan()
    errs = []
    y = np.zeros(2)
    br = [b for b in plan.breaks if b < 2] + [2.0]
    for lo, hi in zip(br[:-1], br[1:]):
        k = plan.interval(lo) if lo < plan.T else None

        def f(t, yy, k=k):
            qdes = plan.evaluate([t], k=k)[0][:, 0]
            tau = 400 * (qdes - yy[:1])
            return np.concatenate([yy[1:], pin.aba(model, data, yy[:1], yy[1:], tau, fext(t))])

        sol = solve_ivp(f, (lo, hi), y, method="LSODA", rtol=1e-11, atol=1e-13, dense_output=True)
        y = sol.y[:, -1]
        ts = np.linspace(lo, hi, 20001)
        errs.append(plan.evaluate(ts, k=k)[0][0] - sol.sol(ts)[0])
    e = np.concatenate(errs)
    assert a.numeric["max_error"]["theta"] == pytest.approx(np.abs(e).max(), rel=1e-4)
    assert a.numeric["final_error"]["theta"] == pytest.approx(e[-1], abs=1e-4 * np.abs(e).max())


def test_joint_torques_with_a_force_varying_in_time_against_pinocchio_rnea():
    from robosolve.motion.profiles import synchronize
    import sympy as sp

    a = answers(PROFILE + "  - {type: joint_torques}\n", F="3", force="-F*cos(3*t)")["joint_torques"]
    assert a.error is None and not a.notes, (a.error, a.notes)
    pin, model, data, fext = pin_arm(lambda t: -3 * math.cos(3 * t))
    plan = synchronize(["theta"], [0], [sp.pi / 2], [4]).numeric_plan()
    best = 0.0
    for k in range(len(plan.coeffs)):
        lo, hi = plan.breaks[k], plan.breaks[k + 1]
        for t in np.linspace(lo, hi, 4001):
            q, qd, qdd = (x[:, 0] for x in plan.evaluate([t], k=k))
            tau = pin.rnea(model, data, q, qd, qdd, fext(t))[0]
            if abs(tau) > abs(best):
                best = tau
    assert a.numeric["actuators"]["C"]["peak"] == pytest.approx(best, rel=1e-6)
    assert "cos(3*t)" in str(a.symbolic["profiles"]["C"])


def test_joint_torques_symbolic_profile_keeps_the_parameters_and_matches_pinocchio():
    import sympy as sp
    from robosolve.motion.profiles import synchronize

    a = answers(PROFILE + "  - {type: joint_torques}\n", F="3", force="-F*cos(3*t)")["joint_torques"]
    prof = a.symbolic["profiles"]["C"]
    names = {s.name for s in prof.free_symbols}
    assert {"L", "m1", "m2", "g", "F", "t"} <= names          # the dynamics stay symbolic
    values = {sp.Symbol(n, real=True): v for n, v in dict(L=1, m1=2, m2=1, g=9.81, F=3).items()}
    values.update({s: values[sp.Symbol(s.name, real=True)] for s in prof.free_symbols if s.name != "t"})
    tsym = next(s for s in prof.free_symbols if s.name == "t")
    pin, model, data, fext = pin_arm(lambda t: -3 * math.cos(3 * t))
    plan = synchronize(["theta"], [0], [sp.pi / 2], [4]).numeric_plan()
    for t in (0.1, 0.4, 0.7, 1.1, 1.5):
        q, qd, qdd = (x[:, 0] for x in plan.evaluate([t]))
        ref = pin.rnea(model, data, q, qd, qdd, fext(t))[0]
        assert float(prof.xreplace(values).subs(tsym, t)) == pytest.approx(ref, rel=1e-9)


@pytest.mark.parametrize("pose", ["Rx(theta) Tx(L)", "Rz(pi/2) Rx(pi/2) Rx(theta) Tx(L)"])
def test_a_joint_that_moves_no_mass_is_an_answer_error(pose):
    """A point mass on the joint's axis: M(q) = 0, so q̈ is not defined. The run says so (it
    stopped with 'internal error (NonInvertibleMatrixError …)' or a LinAlgError)."""
    text = f"""
robosolve: 1
name: on-axis
parameters: {{L: 1, m: 2, g: 9.81}}
joints: [{{name: theta, type: revolute}}]
frames: {{"1": {{parent: "0", pose: "{pose}"}}}}
bodies: [{{name: bob, frame: "1", mass: m, point: [0, 0, 0]}}]
questions:
  - {{type: forward_dynamics, start: {{theta: 0.3}}, duration: 1}}
"""
    (a,) = solve_problem(load_problem_text(text)).answers
    assert a.error and "mass matrix M(q) is singular" in a.error and "internal" not in a.error


HANGING_2R = """
robosolve: 1
name: hanging
parameters: {L: 0.1, m: 0.01, g: 9.81}
joints: [{name: q1, type: revolute}, {name: q2, type: revolute}]
frames: {"1": {parent: "0", pose: "Rz(q1) Tx(L)"}, "2": {parent: "1", pose: "Rz(q2) Tx(L)"}}
gravity: [0, -g, 0]
bodies:
  - {name: b1, frame: "1", mass: m, rod: {from: [-L, 0, 0], to: [0, 0, 0]}}
  - {name: b2, frame: "2", mass: m, point: [0, 0, 0]}
questions: [{type: forward_dynamics, id: fd, start: {q1: %s, q2: 0}, duration: 0.5}]
"""
FD_KEYS = {"final", "max", "min", "final_velocity", "energy"}     # the spec's keys, nothing more


def run_step(answer):
    return next(s for s in answer.steps if s.title == "The run")


def test_an_arm_started_at_an_equilibrium_is_said_not_to_move():
    # by hand: the gravity torques of the 2R, g1 = L g m (3/2 cos q1 + cos(q1 + q2)),
    # g2 = L g m cos(q1 + q2), vanish hanging down (q1 = -pi/2, q2 = 0): it stays there
    q1, q2 = -math.pi / 2, 0.0
    assert abs(1.5 * math.cos(q1) + math.cos(q1 + q2)) < 1e-15 and abs(math.cos(q1 + q2)) < 1e-15
    a = answers_of(HANGING_2R % "-pi/2")["fd"]
    assert set(a.numeric) == FD_KEYS
    for key in ("final", "max", "min"):
        assert a.numeric[key] == {"q1": pytest.approx(q1, abs=1e-12), "q2": pytest.approx(q2, abs=1e-12)}
    text = run_step(a).text
    assert "$q_{1}$ stays at its start, $- \\frac{\\pi}{2}$, and $q_{2}$ at $0$" in text
    assert "the start is an equilibrium" in text


def test_an_arm_that_swings_gets_no_sentence_of_rest():
    # a small swing about the hanging equilibrium: both joints move (q1 starts 0.1 rad off)
    a = answers_of(HANGING_2R % "-pi/2 + 0.1")["fd"]
    assert a.numeric["min"]["q1"] < -math.pi / 2 + 0.1 - 1e-3
    text = run_step(a).text
    assert "equilibrium" not in text and "not move" not in text and "stays at" not in text
    free = answers("  - {id: free, type: forward_dynamics, duration: 3}\n")["free"]
    assert "not move" not in run_step(free).text


def test_a_joint_that_does_not_move_is_named():
    # a Cartesian PP arm, gravity along -y: d1 (along x) feels no force and stays at its start,
    # d2 (along y) falls freely, d2(t) = d2(0) - g t^2 / 2 (closed form)
    text = """
robosolve: 1
name: pp
parameters: {m: 2, g: 9.81}
joints: [{name: d1, type: prismatic}, {name: d2, type: prismatic}]
frames: {"1": {parent: "0", pose: "Tx(d1)"}, "2": {parent: "1", pose: "Ty(d2)"}}
gravity: [0, -g, 0]
bodies: [{name: b, frame: "2", mass: m, point: [0, 0, 0]}]
questions: [{type: forward_dynamics, id: fd, start: {d1: 0.3, d2: 1}, duration: 0.4}]
"""
    a = answers_of(text)["fd"]
    assert set(a.numeric) == FD_KEYS
    assert a.numeric["final"]["d1"] == pytest.approx(0.3, abs=1e-12)
    assert a.numeric["final"]["d2"] == pytest.approx(1 - 9.81 * 0.4**2 / 2, rel=1e-9)
    step = run_step(a).text
    assert "$d_{1}$ does not move: it stays at its start, $0.3$" in step
    assert "d_{2}$ does not move" not in step and "equilibrium" not in step


def answers_of(text):
    return {a.id: a for a in solve_problem(load_problem_text(text)).answers}
