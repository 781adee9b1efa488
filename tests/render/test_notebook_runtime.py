"""The notebook's runtime (robosolve/render/notebook_runtime.py), in-process, against robosolve's
engines: chain products, W and H, Jacobians, the equations of motion, profiles, torques along a
profile, the closed loop and a forward-dynamics run, rotations and screws."""

import ast
import functools
import inspect
import math

import numpy as np
import pytest
import sympy as sp

from robosolve.load.loader import load_problem
from robosolve.model.chain import RobotModel
from robosolve.render import notebook_runtime as rt
from robosolve.core.chain import forward, numpy_algebra
from robosolve.model.numeric import NumericChain
from robosolve.render.notebook import data_cell, runtime_source
from robosolve.questions.notebook_code import literal

from conftest import PROBLEMS

ROBOTS = ["exam-2r-full", "scara-payload-dynamics", "one-link-eom", "polar-rrp"]


def _setup(name):
    """(problem, RobotModel, runtime Robot built by the notebook's own data cell, parameter values)."""
    problem = load_problem(PROBLEMS / f"{name}.yaml")
    namespace = dict(vars(rt))
    exec(data_cell(problem), namespace)             # the notebook's data cell, as the kernel runs it
    values = {}
    for _ in range(len(problem.parameters) + 1):
        values = {s: sp.sympify(v).subs(values) for s, v in problem.parameters.items() if v is not None}
    return problem, RobotModel(problem), namespace["robot"], values


def _state(problem, rng):
    out = {}
    for j in problem.joints:
        out[j.symbol], out[j.dot], out[j.ddot] = (sp.Float(x) for x in rng.uniform(-1.2, 1.2, 3))
    return out


def _robot_subs(robot, state):
    """The same state on the runtime's symbols (matched by name)."""
    return {robot.names[s.name]: v for s, v in state.items()}


def _n(expr, subs):
    return np.array(sp.N(sp.Matrix(expr).subs(subs)).tolist(), dtype=float)


def _imported(source) -> set:
    tree = ast.parse(source)
    modules = {a.name for n in ast.walk(tree) if isinstance(n, ast.Import) for a in n.names}
    return modules | {n.module for n in ast.walk(tree) if isinstance(n, ast.ImportFrom)}


def test_the_runtime_imports_only_sympy_numpy_and_matplotlib():
    """The runtime imports robosolve's numeric chain computation only (forward.py imports
    nothing, numpy_algebra.py numpy), and the notebook's runtime cell, which copies both in
    before it, imports nothing of robosolve."""
    modules = _imported(inspect.getsource(rt))
    assert {m.split(".")[0] for m in modules} <= {"numpy", "sympy", "matplotlib", "IPython", "robosolve"}
    assert {m for m in modules if m.startswith("robosolve")} == {"robosolve.core.chain.forward",
                                                                  "robosolve.core.chain.numpy_algebra"}
    assert _imported(inspect.getsource(forward)) == set()
    assert _imported(inspect.getsource(numpy_algebra)) == {"numpy"}
    cell = runtime_source()
    assert {m.split(".")[0] for m in _imported(cell)} <= {"numpy", "sympy", "matplotlib", "IPython"}
    namespace = {}
    exec(compile(cell, "runtime cell", "exec"), namespace)      # runs without robosolve's modules
    assert namespace["ChainData"].__module__ != "robosolve.core.chain.forward"
    tree = ast.parse(cell)
    calls = {n.func.id for n in ast.walk(tree) if isinstance(n, ast.Call) and isinstance(n.func, ast.Name)}
    assert not calls & {"open", "exec", "eval", "__import__"}


@pytest.mark.parametrize("name", ROBOTS)
def test_chain_products_points_and_velocity_matrices_match_the_model(name):
    problem, model, robot, values = _setup(name)
    rng = np.random.default_rng(3)
    for _ in range(2):
        state = _state(problem, rng)
        mine = {**_robot_subs(robot, values), **_robot_subs(robot, state)}
        theirs = {**values, **state}
        for frame in problem.frames:
            assert _n(robot.pose(frame), mine) == pytest.approx(_n(model.M0(frame), theirs), abs=1e-12)
            W, H = robot.velocity_matrices(frame)
            assert _n(W, mine) == pytest.approx(_n(model.W0(frame), theirs), abs=1e-10)
            assert _n(H, mine) == pytest.approx(_n(model.H0(frame), theirs), abs=1e-10)
        for point in problem.points:
            assert _n(robot.point0(point), mine) == pytest.approx(_n(model.point0(point), theirs), abs=1e-12)
        J = robot.jacobian(["E_x", "E_y", "E_z"])
        assert _n(J, mine) == pytest.approx(_n(model.point0("E").jacobian(model.q), theirs), abs=1e-12)


@pytest.mark.parametrize("name", ROBOTS)
def test_the_chain_at_numbers_matches_the_model_and_the_numeric_chain(name):
    """robot.chain_at (the notebook's data through robosolve's numeric chain computation) against
    the symbolic RobotModel evaluated and robosolve's NumericChain, at random states."""
    problem, model, robot, values = _setup(name)
    rng = np.random.default_rng(5)
    state = _state(problem, rng)
    mine = {s.name: str(v) for s, v in state.items()}
    theirs = {**values, **state}
    chain, numeric = robot.chain_at(mine), NumericChain(model, theirs)
    for frame in problem.frames:
        for got, want in ((chain.M(frame), model.M0(frame)), (chain.W(frame), model.W0(frame)),
                          (chain.H(frame), model.H0(frame))):
            assert got == pytest.approx(_n(want, theirs), abs=1e-10)
        assert chain.H(frame) == pytest.approx(numeric.H0(frame), abs=1e-10)
        for i in range(len(problem.joints)):
            assert chain.L(i, frame) == pytest.approx(_n(model.L0(i, frame), theirs), abs=1e-12)
    for point in problem.points:
        assert chain.point(point) == pytest.approx(_n(model.point0(point), theirs).ravel(), abs=1e-12)


@pytest.mark.parametrize("name", ["exam-2r-full", "scara-payload-dynamics", "one-link-eom"])
def test_lagrange_matches_the_dynamics_engine(name):
    from robosolve.dynamics.bridge import dynamics_for

    problem, model, robot, values = _setup(name)
    dyn = dynamics_for(model)
    mass, c, grav, Q = robot.lagrange()
    rng = np.random.default_rng(5)
    for _ in range(2):
        state = _state(problem, rng)
        mine = {**_robot_subs(robot, values), **_robot_subs(robot, state)}
        theirs = {**values, **state}
        for a, b in ((mass, dyn.mass_matrix), (c, dyn.velocity_terms), (grav, dyn.gravity_terms),
                     (Q, dyn.external_forces)):
            assert _n(a, mine) == pytest.approx(_n(b, theirs), abs=1e-9)
        # the weight's generalized forces are the gravity terms g(q)
        assert _n(robot.weight_forces(), mine) == pytest.approx(_n(dyn.gravity_terms, theirs), abs=1e-9)


@pytest.mark.parametrize("shape", ["bang-bang", "trapezoidal", "quintic"])
def test_profiles_match_the_motion_engine(shape):
    from robosolve.motion.profiles import synchronize

    start, end, acc, vel = [0.0, 1.0, -0.5], [1.5, 0.2, -0.5], [2.0, 1.0, 3.0], [1.0, 0.5, 1.0]
    ref = synchronize(["a", "b", "c"], [sp.Float(x) for x in start], [sp.Float(x) for x in end],
                      [sp.Float(x) for x in acc], shape=shape,
                      max_velocity=[sp.Float(x) for x in vel] if shape == "trapezoidal" else None,
                      t=sp.Symbol("t"))
    mine = rt.Profile(start, end, acc, shape=shape, max_velocity=vel)
    assert mine.T == pytest.approx(float(ref.T), rel=1e-12)
    assert mine.durations == pytest.approx([float(j.own_time) for j in ref.joints], rel=1e-12)
    assert mine.accelerations == pytest.approx([float(j.acceleration) for j in ref.joints], rel=1e-12)
    plan = ref.numeric_plan()
    times = np.linspace(0, mine.T, 37)
    q, qd, qdd = plan.evaluate(times)
    for k, time in enumerate(times[1:-1], 1):
        got = mine.evaluate(time)
        assert got[0] == pytest.approx(q[:, k], abs=1e-12)
        assert got[1] == pytest.approx(qd[:, k], abs=1e-12)
        assert got[2] == pytest.approx(qdd[:, k], abs=1e-12)


def _exam_profile_and_dynamics():
    from robosolve.dynamics.bridge import simulation_dynamics
    from robosolve.motion.profiles import synchronize

    problem, model, robot, values = _setup("exam-2r-full")
    pq = next(q for q in problem.questions if q.type == "motion_profile")
    names = [j.name for j in problem.joints]
    start = [sp.sympify(pq.options["from"][n]).subs(values) for n in names]
    end = [sp.sympify(pq.options["to"][n]).subs(values) for n in names]
    acc = [sp.sympify(pq.options["max_acceleration"][n]).subs(values) for n in names]
    ref = synchronize(names, start, end, acc, t=sp.Symbol("t"))
    mine = rt.Profile([float(x) for x in start], [float(x) for x in end], [float(x) for x in acc])
    fast, _ = simulation_dynamics(model, values)
    return problem, robot, ref, mine, fast


def test_torque_peaks_match_the_torque_engine():
    from robosolve.motion.torques import torques_along

    problem, robot, ref, mine, fast = _exam_profile_and_dynamics()
    want = torques_along(ref, fast, [str(j.actuator) for j in problem.joints])
    peaks, when = rt.torque_peaks(robot, mine)
    assert peaks == pytest.approx(want.peaks, rel=1e-8)
    assert when == pytest.approx(want.t_peaks, abs=1e-6)


@pytest.mark.parametrize("law, kp, kd", [("p", [400.0, 300.0], None), ("pd_gravity", [200.0, 100.0], [20.0, 10.0]),
                                          ("computed_torque", [100.0, 100.0], [20.0, 20.0])])
def test_closed_loop_matches_the_control_engine(law, kp, kd):
    from robosolve.simulation.joint_control import simulate

    problem, robot, ref, mine, fast = _exam_profile_and_dynamics()
    want = simulate(fast, ref.numeric_plan(), law, kp, kd, start=[0.05, -0.02])
    max_error, t_max, final, _, _ = rt.simulate_control(robot, mine, law, kp, kd, start=[0.05, -0.02])
    assert max_error == pytest.approx(want.max_error, rel=1e-5, abs=1e-9)
    assert final == pytest.approx(want.final_error, rel=1e-4, abs=1e-8)


def test_a_forward_run_matches_the_solver():
    from robosolve.run.pipeline import solve_problem

    problem, model, robot, values = _setup("pendulum-runs")
    report = solve_problem(problem)
    names = [j.name for j in problem.joints]
    for q, answer in zip(problem.questions, report.answers):
        if q.type != "forward_dynamics":
            continue
        laws = {str(k): str(v) for k, v in (q.options.get("actuators") or {}).items()}
        at = {s.name: str(v) for s, v in q.at.items()}
        here = {s: sp.sympify(v).subs(values) for s, v in {**values, **q.at}.items()}
        start = q.options.get("start") or {}
        q0 = [float(sp.sympify(start.get(n, 0)).subs(here)) for n in names]
        v0 = [float(sp.sympify(start.get(f"{n}_dot", 0)).subs(here)) for n in names]
        duration = float(sp.sympify(q.options["duration"]).subs(here))
        times, qs, rates = rt.forward_run(robot, laws, q0, v0, duration, at)
        low, high = rt.extremes(times, qs, rates)
        want = answer.numeric
        assert qs[-1] == pytest.approx(list(want["final"].values()), rel=1e-6, abs=1e-8)
        assert rates[-1] == pytest.approx(list(want["final_velocity"].values()), rel=1e-6, abs=1e-8)
        assert low == pytest.approx(list(want["min"].values()), rel=1e-7, abs=1e-8)
        assert high == pytest.approx(list(want["max"].values()), rel=1e-7, abs=1e-8)


def test_rotations_and_screws_match_the_geometry_engines():
    from robosolve.geometry.helical import normalise_screw  # noqa: F401  (the engine exists)
    from robosolve.geometry.rotations import axis_angle_numeric, quaternion_numeric

    rng = np.random.default_rng(11)
    for _ in range(20):
        a, b, c = rng.uniform(-3, 3, 3)
        R = np.array(sp.N(rt.Rz(a) * rt.Ry(b) * rt.Rx(c)).tolist(), dtype=float)[:3, :3]
        want = axis_angle_numeric(R)
        alpha, u = rt.axis_angle(R)
        assert alpha == pytest.approx(float(want.angle), abs=1e-12)
        assert u == pytest.approx([float(x) for x in want.axis], abs=1e-9)
        assert rt.quaternion(R) == pytest.approx(quaternion_numeric(R), abs=1e-12)
        for roll, pitch, yaw in rt.euler_rpy(R):
            back = np.array(sp.N(rt.Rz(yaw) * rt.Ry(pitch) * rt.Rx(roll)).tolist(), dtype=float)[:3, :3]
            assert back == pytest.approx(R, abs=1e-12)
        for phi, theta, psi in rt.euler_zyz(R):
            back = np.array(sp.N(rt.Rz(phi) * rt.Ry(theta) * rt.Rz(psi)).tolist(), dtype=float)[:3, :3]
            assert back == pytest.approx(R, abs=1e-12)
        axis, angle, through, h = rng.normal(size=3), rng.uniform(0.1, 3), rng.normal(size=3), rng.normal()
        Q = rt.screw_displacement(axis, angle, through, h)
        u, alpha, h2, P, pitch = rt.helical_axis(Q)
        L = rt.screw_matrix(u, P, pitch)
        import scipy.linalg

        assert scipy.linalg.expm(alpha * L) == pytest.approx(Q, abs=1e-10)


def test_compare_says_whether_the_numbers_agree(capsys):
    rt.compare("x", {"a": 1.0, "b": [2.0, 3.0]}, {"a": 1.0 + 1e-9, "b": [2.0, 3.0]})
    rt.compare("y", [1.0, 2.0], [1.0, 2.1])
    rt.compare("z", [1.0, 2.0], [1.0])
    out = capsys.readouterr().out
    assert out.count("agrees with robosolve") == 1 and out.count("DIFFERS") == 2


@pytest.mark.parametrize("value", ['b": open("X","w").write("x"), "c', "arm \"A\"", "$\\{_<script>x",
                                   math.inf, -math.inf, 1e-300, [1, {"k": None}], True, "a\nb", "\u00e9\u2019"])
def test_literals_are_python_literals_of_the_same_value(value):
    source = literal(value)
    if isinstance(value, float) and not math.isfinite(value):
        assert eval(source, {"__builtins__": {"float": float}}) == value   # float('inf'), nothing else
    else:
        assert ast.literal_eval(source) == value
    assert literal(float("nan")) == "float('nan')"


@pytest.mark.parametrize("name", ["exam-2r-full", "scara-payload-dynamics", "one-link-eom"])
def test_numeric_equations_of_motion_match_the_symbolic_ones(name):
    problem, model, robot, values = _setup(name)
    mass, c, grav, Q = robot.lagrange()
    rng = np.random.default_rng(7)
    state = _state(problem, rng)
    at = {s.name: str(v) for s, v in state.items()}
    got = robot.dynamics_at(at)
    mine = {**_robot_subs(robot, values), **_robot_subs(robot, state)}
    for a, b in zip(got, (mass, c, grav, Q)):
        assert a == pytest.approx(_n(b, mine).reshape(a.shape), abs=1e-9)


def test_numeric_equations_of_motion_of_the_puma_match_the_golden_report():
    """Six joints: the numeric chain answers in seconds where a symbolic Lagrange would take minutes."""
    import json

    from conftest import ROOT

    problem, _, robot, _ = _setup("puma560-dynamics")
    q = problem.questions[0]
    mass, c, grav, _ = robot.dynamics_at({s.name: str(v) for s, v in q.at.items()})
    want = json.loads((ROOT / "tests" / "golden" / "puma560-dynamics" / "results.json").read_text())
    want = want["answers"][q.id]["numeric"]
    assert mass == pytest.approx(np.array(want["mass_matrix"]), abs=1e-9)
    assert c == pytest.approx(want["velocity_terms"], abs=1e-9)
    assert grav == pytest.approx(want["gravity_terms"], abs=1e-9)


# -- work-space trajectories and the closed loops along them ------------------------------------

ARM_3R = """robosolve: 1
name: r
parameters: {}
joints: [{name: q1, type: revolute}, {name: q2, type: revolute}, {name: q3, type: revolute}]
frames:
  "1": {parent: "0", pose: "Rz(q1) Tx(0.5)"}
  "2": {pose: "Rz(q2) Tx(0.4)"}
  "3": {pose: "Rz(q3) Tx(0.3)"}
questions:
"""
SCARA = """robosolve: 1
name: r
parameters: {}
joints: [{name: q1, type: revolute}, {name: q2, type: revolute}, {name: d3, type: prismatic}]
frames:
  "1": {parent: "0", pose: "Tz(1) Rz(q1) Tx(0.5)"}
  "2": {pose: "Rz(q2) Tx(0.4)"}
  "3": {pose: "Tz(d3)"}
questions:
"""
TRAJECTORIES = {
    # the bundled problem's line: trapezoidal, the first sorted IK solution at `from`
    "2r-line": None,
    "3r-quintic-with-orientation": ARM_3R + """  - {type: task_trajectory, coordinates: [E.x, E.y, "q1 + q2 + q3"],
     from: {E.x: 0.8, E.y: 0.2, "q1 + q2 + q3": 0.3}, to: {E.x: 0.4, E.y: 0.6, "q1 + q2 + q3": 1.2},
     duration: 2, shape: quintic}
""",
    "3r-wide-bang-bang-from-start": ARM_3R + """  - {type: task_trajectory, coordinates: [E.x, E.y], from: {E.x: 0.8, E.y: 0.2},
     to: {E.x: 0.7, E.y: 0.3}, max_velocity: 0.5, max_acceleration: 2, start: {q1: 0.2, q2: -0.3, q3: 0.4}}
""",
    "scara-half-circle": SCARA + """  - type: task_trajectory
    from: {E.x: 0.6, E.y: 0.3, E.z: 0.8}
    to: {E.x: 0.2, E.y: 0.6, E.z: 0.9}
    path: {circle: {center: [0.4, 0.45, 0.85], normal: [0.3, 0.4, 0]}}
    max_velocity: 0.4
    max_acceleration: 1.5
""",
    "2r-planar-arc": """robosolve: 1
name: r
parameters: {}
joints: [{name: q1, type: revolute}, {name: q2, type: revolute}]
frames:
  "1": {parent: "0", pose: "Rz(q1) Tx(0.5)"}
  "2": {pose: "Rz(q2) Tx(0.4)"}
questions:
  - {type: task_trajectory, coordinates: [E.x, E.y], from: {E.x: 0.7, E.y: 0.1}, to: {E.x: 0.1, E.y: 0.7},
     path: {circle: {center: [0.1, 0.1]}}, duration: 1.5, shape: quintic}
""",
}


@functools.lru_cache(maxsize=None)
def _trajectory_setup(key):
    """(problem, engine pieces (coords, arm, path, timing, q_from), the notebook's namespace after
    the data cell and the cell's trajectory lines); built once per key (the tests only read them)."""
    from robosolve.load.loader import load_problem_text
    from robosolve.questions.notebook_code import trajectory_lines
    from robosolve.solvers import task_trajectory as tt
    from robosolve.solvers.base import SolveContext

    text = TRAJECTORIES[key]
    problem = load_problem(PROBLEMS / "workspace-2r-line.yaml") if text is None else load_problem_text(text, "r.yaml")
    q = next(x for x in problem.questions if x.type == "task_trajectory")
    ctx = SolveContext(problem, RobotModel(problem))
    engine = tt.setup(q, ctx)
    namespace = dict(vars(rt))
    exec(data_cell(problem) + "\n" + "\n".join(trajectory_lines(q, problem)), namespace)
    return problem, ctx, engine, namespace


@pytest.mark.parametrize("kind", ["line", "arc-2d", "half-circle-3d"])
@pytest.mark.parametrize("timing", [(None, 0.5, 2.0), (None, 2.0, 1.0), (1.7, None, None)],
                         ids=["trapezoidal", "bang-bang", "quintic"])
def test_paths_and_timing_laws_match_the_task_path_engine(kind, timing):
    from robosolve.motion import task_path as tp

    if kind == "line":
        args = ([0.7, 0.2], [0.3, 0.5])
        ref = tp.line(*args)
        mine = rt.TaskPath(*args)
    elif kind == "arc-2d":
        ref = tp.circle([0.7, 0.1], [0.1, 0.7], [0.1, 0.1])
        mine = rt.TaskPath([0.7, 0.1], [0.1, 0.7], center=[0.1, 0.1])
    else:
        ref = tp.circle([0.6, 0.3, 0.8], [0.2, 0.6, 0.9], [0.4, 0.45, 0.85], [0.3, 0.4, 0])
        mine = rt.TaskPath([0.6, 0.3, 0.8], [0.2, 0.6, 0.9], center=[0.4, 0.45, 0.85], normal=[0.3, 0.4, 0])
    assert mine.length == pytest.approx(ref.length, rel=1e-14)
    duration, v, a = timing
    want = tp.quintic(ref.length, duration) if duration else tp.trapezoidal(ref.length, v, a)
    got = rt.Timing(mine.length, max_velocity=v, max_acceleration=a, duration=duration)
    assert (got.kind, got.T) == (want.kind, pytest.approx(want.T, rel=1e-14))
    assert got.breaks == pytest.approx(want.breaks, rel=1e-14)
    if got.kind == "trapezoidal":                   # the closed form, independently
        assert got.T == pytest.approx(mine.length / v + v / a, rel=1e-14)
    elif got.kind == "bang-bang":
        assert got.T == pytest.approx(2 * math.sqrt(mine.length / a), rel=1e-14)
    for seg, (lo, hi) in enumerate(zip(got.breaks[:-1], got.breaks[1:])):
        for t in np.linspace(lo, hi, 7):
            assert got.at(t, seg) == pytest.approx(want.at(t, seg), rel=1e-13, abs=1e-15)
            s = want.at(t, seg)[0]
            for x, y in zip(mine.at(s), ref.at(s)):
                assert x == pytest.approx(y, rel=1e-13, abs=1e-15)


@pytest.mark.parametrize("key", list(TRAJECTORIES))
def test_the_joint_path_and_its_extremes_match_the_engine(key):
    from robosolve.motion import task_path as tp

    problem, _, (coords, arm, path, timing, q_from, _res, _subs, _outside), ns = _trajectory_setup(key)
    mine_arm, mine = ns["arm"], ns["trajectory"]
    rng = np.random.default_rng(11)
    for _ in range(3):                              # the task map, at random states
        q, qd = rng.uniform(-1, 1, len(problem.joints)), rng.uniform(-1, 1, len(problem.joints))
        assert mine_arm.x(q) == pytest.approx(arm.x(q), abs=1e-13)
        assert mine_arm.J(q) == pytest.approx(arm.J(q), abs=1e-13)
        assert mine_arm.jdot_qdot(q, qd) == pytest.approx(arm.jdot_qdot(q, qd), abs=1e-12)
        h = 1e-6                                    # and J' q' by a central difference of J q'
        fd = (mine_arm.J(q + h * qd) - mine_arm.J(q - h * qd)) @ qd / (2 * h)
        assert mine_arm.jdot_qdot(q, qd) == pytest.approx(fd, abs=1e-7)
    assert ns["start"] == pytest.approx(q_from, abs=1e-9)
    conv = tp.follow(arm, path, timing, q_from, samples=401)
    assert mine.failure is None and conv.failure is None
    assert mine.t == pytest.approx(conv.t, abs=1e-15)
    for a, b in ((mine.q, conv.q), (mine.qd, conv.qd), (mine.qdd, conv.qdd), (mine.x, conv.x)):
        assert a == pytest.approx(b, abs=1e-9)
    assert mine.sigma == pytest.approx(conv.sigma, abs=1e-9)
    vel, acc, (smin, tmin) = mine.extremes()
    want_vel, want_acc, (want_smin, want_tmin) = tp.extremes(arm, path, timing, conv)
    assert vel == pytest.approx(want_vel, rel=1e-8)
    assert acc == pytest.approx(want_acc, rel=1e-8)
    assert smin == pytest.approx(want_smin, rel=1e-8)


def test_a_path_leaving_the_reach_fails_where_the_engine_says():
    from robosolve.motion import task_path as tp

    _, _, (coords, arm, _p, _t, _q, _r, _s, _o), ns = _trajectory_setup("2r-line")
    for a, b in (([0.45, 0.05], [-0.45, 0.05]), ([0.45, 0.3], [0.85, 0.3])):    # the inner hole, the outer rim
        q0 = ns["arm"].start(a, [[-math.pi, math.pi]] * 2)
        path, timing = tp.line(a, b), tp.trapezoidal(float(np.hypot(*np.subtract(b, a))), 0.5, 2.0)
        want = tp.follow(arm, path, timing, q0).failure
        got = rt.TaskTrajectory(ns["arm"], rt.TaskPath(a, b), rt.Timing(path.length, 0.5, 2.0), q0).failure
        assert want is not None and got["kind"] == want["kind"], (got, want)
        # (at the edge of the reach Newton converges slowly: the bisections agree to ~1e-9 s)
        assert got["t"] == pytest.approx(want["t"], abs=1e-7)
        assert got["x"] == pytest.approx(want["x"], abs=1e-7)


def test_a_path_ending_or_starting_on_the_rim_is_singular_there_as_the_engine_says():
    """|x| = L1 + L2 = 0.9 (the stretched arm, off the x axis): Newton solves such an end only to
    sigma ~ 1e-6, which the 1e-6 |J| test let through (both followed the path to its end)."""
    from robosolve.motion import task_path as tp

    _, _, (coords, arm, _p, _t, _q, _r, _s, _o), ns = _trajectory_setup("2r-line")
    rim = [0.54, 0.72]
    for a, b, t_singular in (([0.45, 0.3], rim, None), (rim, [0.45, 0.3], 0.0)):
        q0 = ns["arm"].start(a, [[-math.pi, math.pi]] * 2)
        path, timing = tp.line(a, b), tp.trapezoidal(float(np.hypot(*np.subtract(b, a))), 0.5, 2.0)
        want = tp.follow(arm, path, timing, q0).failure
        got = rt.TaskTrajectory(ns["arm"], rt.TaskPath(a, b), rt.Timing(path.length, 0.5, 2.0), q0).failure
        at = timing.T if t_singular is None else t_singular
        assert want["kind"] == got["kind"] == "singular" and want["t"] == got["t"] == at, (got, want)


@pytest.mark.parametrize("law, kp, kd", [("task_pd_gravity", [2000.0, 1500.0], [100.0, 80.0]),
                                          ("task_computed_torque", [400.0, 400.0], [30.0, 30.0]),
                                          ("pd_gravity", [2000.0, 2000.0], [100.0, 100.0])])
def test_work_space_closed_loops_match_the_control_engines(law, kp, kd):
    """The bundled 2R arm along its line (0.4 s of its 1.25 s, from a displaced start for the task
    laws): the task laws against simulation/task_control.py, the ideal scheme (a joint law on the
    converted trajectory) against simulation/joint_control.py on the solver's own joint plan."""
    from robosolve.motion import task_path as tp
    from robosolve.simulation.joint_control import simulate
    from robosolve.simulation.task_control import simulate_task
    from robosolve.solvers import task_trajectory as tt

    problem, ctx, (coords, arm, path, timing, q_from, _res, subs, _o), ns = _trajectory_setup("2r-line")
    conv = tp.follow(arm, path, timing, q_from, samples=tt.SAMPLES)
    traj = tt.TaskTrajectory(coords, [str(c) for c in coords], [], path, timing, arm, conv,
                             [j.name for j in problem.joints])
    dyn, _ = ctx.simulation_dynamics(subs)
    task = law.startswith("task_")
    start = q_from + np.array([0.01, -0.02]) if task else None
    got = rt.simulate_task_control(ns["robot"], ns["trajectory"], law, kp, kd, start=start, duration=0.4, samples=800)
    if task:
        want = simulate_task(dyn, arm, traj.desired, timing.breaks, law, kp, kd, start, 0.4, samples=2001)
    else:
        want = simulate(dyn, traj.plan(), law, kp, kd, start=traj.start, duration=0.4, samples=2001)
    assert got[0] == pytest.approx(want.max_error, rel=1e-4)
    assert got[2] == pytest.approx(want.final_error, rel=1e-5, abs=1e-9)
    if not task:                                    # the work-space error of the ideal scheme
        x_err = np.array([traj.desired(t)[0] - arm.x(want.q[:, k]) for k, t in enumerate(want.t)])
        assert np.abs(got[5]).max(axis=0) == pytest.approx(np.abs(x_err).max(axis=0), rel=1e-4)


@pytest.mark.parametrize("edit, printed", [
    (("E.x: 0.7, E.y: 0.1", "E.x: 1.7, E.y: 0.1"), "no configuration of the arm reaches its start"),
    (("E.x: 0.1, E.y: 0.7", "E.x: 1.5, E.y: 0.7"), "the path cannot be followed: {'kind': 'unreachable'"),
], ids=["from-out-of-reach", "to-out-of-reach"])
def test_the_cell_of_a_path_that_cannot_be_followed_runs_and_says_so(edit, printed, capsys):
    """A path whose start (or end) is out of reach is an answer, and its notebook cell runs: T and
    the length recomputed and compared, then what cannot be followed (no TaskTrajectory without a
    start)."""
    from robosolve.load.loader import load_problem_text
    from robosolve.questions.task_trajectory import notebook_cell
    from robosolve.solvers import task_trajectory as tt
    from robosolve.solvers.base import SolveContext

    text = TRAJECTORIES["2r-planar-arc"].replace("path: {circle: {center: [0.1, 0.1]}}, ", "").replace(*edit)
    problem = load_problem_text(text, "r.yaml")
    q = problem.questions[0]
    answer = tt.solve(q, SolveContext(problem, RobotModel(problem)))
    assert answer.extra.get("unreachable") is True
    namespace = dict(vars(rt))
    exec(data_cell(problem) + "\n" + notebook_cell(q, answer, problem), namespace)
    out = capsys.readouterr().out
    assert printed in out and "DIFFERS" not in out and out.count("agrees with robosolve") >= 2


def test_a_wide_j_starts_where_the_engine_starts_from_a_given_start_and_from_zero():
    """The nearest solution of `from` (J wide) in the notebook is the engine's; a start where
    Newton's steps (capped at 0.5 rad) stop 1e-2 rad off it (robosolve against its own copy)."""
    from robosolve.motion import task_path as tp

    _, _, (coords, arm, _p, _t, _q, _r, _s, _o), ns = _trajectory_setup("3r-wide-bang-bang-from-start")
    for target, given in (([0.8, 0.3], [0.1, 0.6, 0.5]), ([0.8, 0.2], None), ([0.5, 0.5], [-1.0, 2.0, -0.5])):
        want = tp.nearest_solution(arm, target, np.zeros(3) if given is None else given)
        got = ns["arm"].start(target, [[-math.pi, math.pi]] * 3, given)
        assert got == pytest.approx(want, abs=1e-12)


@pytest.mark.parametrize("start_at, exact", [
    ("E.x: 0.8, E.y: 0.6", (math.atan2(0.6, 0.8), 0.0)),
    ("E.x: 1, E.y: 0", (0.0, 0.0)),
], ids=["stretched-0.8-0.6", "stretched-1-0"])
def test_a_start_on_the_rim_agrees_within_the_square_root_of_the_round_off(start_at, exact, capsys):
    """`from` where the arm is stretched (L1 = L2 = 0.5, |from| = 1): a double root of x(q) = from,
    which the notebook's Newton approaches linearly and leaves some 1e-8 rad off (its residual is
    round-off there, the distance its square root); the exact start is (atan2(y, x), 0). The cell's
    comparison allows √(residual) there, and only there: 1e-5 rad off still differs."""
    from robosolve.load.loader import load_problem_text
    from robosolve.questions.task_trajectory import notebook_cell
    from robosolve.solvers import task_trajectory as tt
    from robosolve.solvers.base import SolveContext

    text = TRAJECTORIES["2r-planar-arc"].replace("Tx(0.4)", "Tx(0.5)").replace(
        "path: {circle: {center: [0.1, 0.1]}}, ", "").replace("E.x: 0.7, E.y: 0.1", start_at)
    problem = load_problem_text(text, "r.yaml")
    q = problem.questions[0]
    answer = tt.solve(q, SolveContext(problem, RobotModel(problem)))
    assert list(answer.numeric["start"].values()) == pytest.approx(exact, abs=1e-9)
    namespace = dict(vars(rt))
    exec(data_cell(problem) + "\n" + notebook_cell(q, answer, problem), namespace)
    out = capsys.readouterr().out
    assert "recomputed start" in out and "DIFFERS" not in out, out
    ns_start, tol = namespace["start"], namespace["arm"].root_tolerance(namespace["start"], namespace["path"].a)
    assert np.abs(np.asarray(ns_start) - exact).max() <= tol <= 1e-6
    off = {k: v + 1e-5 for k, v in answer.numeric["start"].items()}
    rt.compare("start", dict(zip(["q1", "q2"], ns_start)), off, atol=tol)
    assert "DIFFERS" in capsys.readouterr().out


def test_the_cell_of_a_follower_with_a_parameter_override_rebuilds_its_reference_with_it(capsys):
    """joint_torques with `at: {qf: 2}` on a profile to q1 = qf: the cell's profile goes to 2 as
    robosolve's does (it kept the profile question's qf = 1). By hand at t = 0+, point masses at
    the link ends, q = 0: T = 2, qdd = (2, 1/2); M11 = (m1 + m2) L1² + m2 L2² + 2 m2 L1 L2 = 1.31,
    M12 = m2 L2² + m2 L1 L2 = 0.36, M22 = 0.16; g1 = g ((m1 + m2) L1 + m2 L2), g2 = g m2 L2."""
    from robosolve.load.loader import load_problem_text
    from robosolve.questions.joint_torques import notebook_cell
    from robosolve.run.pipeline import solve_problem

    problem = load_problem_text("""robosolve: 1
name: prof
parameters: {L1: 0.5, L2: 0.4, m1: 2, m2: 1, g: 9.81, qf: 1}
joints: [{name: q1, type: revolute}, {name: q2, type: revolute}]
frames:
  "1": {parent: "0", pose: "Rz(q1) Tx(L1)"}
  "2": {pose: "Rz(q2) Tx(L2)"}
gravity: [0, -g, 0]
bodies:
  - {name: b1, frame: "1", mass: m1, point: [0, 0, 0]}
  - {name: b2, frame: "2", mass: m2, point: [0, 0, 0]}
questions:
  - {type: motion_profile, id: mp, from: {q1: 0, q2: 0}, to: {q1: qf, q2: 0.5}, max_acceleration: {q1: 2, q2: 2}}
  - {type: joint_torques, profile: mp, at: {qf: 2}}
""", "r.yaml")
    answer = next(a for a in solve_problem(problem).answers if a.id == "joint_torques")
    want = [1.31 * 2 + 0.36 * 0.5 + 9.81 * (3 * 0.5 + 0.4), 0.36 * 2 + 0.16 * 0.5 + 9.81 * 0.4]
    assert [v["peak"] for v in answer.numeric["actuators"].values()] == pytest.approx(want, rel=1e-9)
    namespace = dict(vars(rt))
    exec(data_cell(problem) + "\n" + notebook_cell(problem.questions[1], answer, problem), namespace)
    out = capsys.readouterr().out
    assert "DIFFERS" not in out and out.count("agrees with robosolve") == 2, out
    assert list(namespace["peaks"]) == pytest.approx(want, rel=1e-9)


def test_the_cell_of_a_follower_works_on_the_arm_of_the_profile_it_follows(capsys):
    """The profile question carries `at: {qf: 2, m2: 2}`, joint_torques none: robosolve and the
    cell both compute the torques of the arm with m2 = 2 (the cell kept the data's m2 = 1 for the
    dynamics). By hand at t = 0+ as in the test above, with m2 = 2: M11 = (m1 + m2) L1² + m2 L2²
    + 2 m2 L1 L2 = 2.12, M12 = m2 L2² + m2 L1 L2 = 0.72, M22 = 0.32, g1 = g ((m1 + m2) L1 + m2 L2),
    g2 = g m2 L2."""
    from robosolve.load.loader import load_problem_text
    from robosolve.questions.joint_torques import notebook_cell
    from robosolve.run.pipeline import solve_problem

    problem = load_problem_text("""robosolve: 1
name: prof
parameters: {L1: 0.5, L2: 0.4, m1: 2, m2: 1, g: 9.81, qf: 1}
joints: [{name: q1, type: revolute}, {name: q2, type: revolute}]
frames:
  "1": {parent: "0", pose: "Rz(q1) Tx(L1)"}
  "2": {pose: "Rz(q2) Tx(L2)"}
gravity: [0, -g, 0]
bodies:
  - {name: b1, frame: "1", mass: m1, point: [0, 0, 0]}
  - {name: b2, frame: "2", mass: m2, point: [0, 0, 0]}
questions:
  - {type: motion_profile, id: mp, from: {q1: 0, q2: 0}, to: {q1: qf, q2: 0.5}, max_acceleration: {q1: 2, q2: 2},
     at: {qf: 2, m2: 2}}
  - {type: joint_torques, profile: mp}
""", "r.yaml")
    answer = next(a for a in solve_problem(problem).answers if a.id == "joint_torques")
    want = [2.12 * 2 + 0.72 * 0.5 + 9.81 * (4 * 0.5 + 2 * 0.4), 0.72 * 2 + 0.32 * 0.5 + 9.81 * 0.8]
    assert [v["peak"] for v in answer.numeric["actuators"].values()] == pytest.approx(want, rel=1e-9)
    namespace = dict(vars(rt))
    exec(data_cell(problem) + "\n" + notebook_cell(problem.questions[1], answer, problem), namespace)
    out = capsys.readouterr().out
    assert "DIFFERS" not in out and out.count("agrees with robosolve") == 2, out
    assert list(namespace["peaks"]) == pytest.approx(want, rel=1e-9)
