"""Work-space trajectory (course summary §1.2.2): a line or an arc of the task coordinates, timed
along its length, converted to joint motion by inverse kinematics and the Jacobian.

The math is in robosolve/motion/task_path.py; this module builds the arm's task map from the
model (x(q), J(q), J_dot q_dot, lambdified), picks the IK branch at `from` (the IK engine, as
`select: limits` does, or the given `start`), and writes the answer.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import sympy as sp

from robosolve.core.numpy_code import numpy_modules
from robosolve.core.prose import Num, Text
from robosolve.errors import MissingValues, SolverError
from robosolve.ik.engine import IKJoint, solve_ik
from robosolve.load.expressions import point_symbol
from robosolve.motion import task_path as tp
from robosolve.motion.profiles import NumericPlan
from robosolve.solvers.base import Answer, FigureSpec, SolveContext, Step, missing_note
from robosolve.solvers.common import robot_drawing
from robosolve.core.printing import latex, sstr

SAMPLES = 401
TABLE_ROWS = 11
# The ideal scheme's joint reference joins every 5th sample by quintics (q, q_dot, q_ddot matched):
# the join is off by about 1e-12 rad in q and 1e-7 rad/s^2 in q_ddot on the 2R exam arm (O(h^6)),
# far below the tracking errors, and the simulation restarts 5 times less often.
KNOT_EVERY = 5


class BadInput(Exception):
    """An input mistake found with the robot's model: (option key, message)."""

    def __init__(self, key: str, message: str):
        super().__init__(message)
        self.key, self.message = key, message


class OutOfReach(Exception):
    """`from` is out of the arm's reach (an answer, not a mistake): why, as prose (str or Text)."""

    def __init__(self, reason):
        super().__init__(str(reason))
        self.reason = reason


@dataclass
class TaskTrajectory:
    """A converted trajectory, as the closed-loop control reads it."""

    coords: list                   # the coordinates as written (point placeholders kept)
    labels: list                   # the coordinates as text ("E.y")
    tex: list
    path: tp.Path
    timing: tp.Timing
    arm: tp.Arm
    conv: tp.Conversion
    joints: list                   # joint names
    start_configuration: np.ndarray | None = None     # at `from` (the branch followed), when reached

    def desired(self, t: float, segment: int | None = None):
        """(x_d, x_dot_d, x_ddot_d) at t; after T the end, at rest."""
        if t >= self.timing.T:
            x = self.path.at(self.path.length)[0]
            return x, np.zeros_like(x), np.zeros_like(x)
        return tp.task_state(self.path, self.timing, max(t, 0.0), segment)[1:]

    @property
    def start(self) -> np.ndarray:
        return self.conv.q[:, 0]

    def plan(self, every: int = KNOT_EVERY) -> NumericPlan:
        """The joint reference as piecewise quintics matching q, q_dot, q_ddot at every
        ``every``-th sample of each interval of the timing law (and at its ends)."""
        c = self.conv
        knots = []
        for seg in range(len(self.timing.breaks) - 1):
            idx = np.nonzero(c.segment == seg)[0]
            if idx.size:
                knots += list(idx[::every]) + ([idx[-1]] if (idx.size - 1) % every else [])
        breaks, coeffs = [float(c.t[0])], []
        for a, b in zip(knots[:-1], knots[1:]):
            h = float(c.t[b] - c.t[a])
            if h <= 0:
                continue
            coeffs.append(_hermite(c.q[:, a], c.qd[:, a], c.qdd[:, a], c.q[:, b], c.qd[:, b], c.qdd[:, b], h))
            breaks.append(float(c.t[b]))
        return NumericPlan(breaks, coeffs, c.q[:, 0], c.q[:, -1])


def _hermite(q0, v0, a0, q1, v1, a1, h):
    """(n, 6) quintic coefficients about the interval's start."""
    A = np.array([[h ** 3, h ** 4, h ** 5], [3 * h ** 2, 4 * h ** 3, 5 * h ** 4], [6 * h, 12 * h ** 2, 20 * h ** 3]])
    rhs = np.vstack([q1 - (q0 + v0 * h + a0 * h * h / 2), v1 - (v0 + a0 * h), a1 - a0])
    hi = np.linalg.solve(A, rhs)
    return np.column_stack([q0, v0, a0 / 2, hi.T])


# -- setup ------------------------------------------------------------------------------
def coordinates(question, model) -> list:
    """The question's coordinates as written (point placeholders kept)."""
    raw = question.options.get("coordinates")
    return list(raw) if raw else [point_symbol(question.point, a) for a in "xyz"]


def _arm(model, coords, subs) -> tuple[tp.Arm, sp.Matrix]:
    q = list(model.q)
    qd = [sp.Symbol(f"_qd{i}") for i in range(len(q))]
    x = sp.Matrix([model.coordinate(c) for c in coords]).xreplace(subs)
    x = x.xreplace(subs)
    J = x.jacobian(q)
    # J_dot = d(J q_dot)/dq (J = dx/dq: its derivatives are symmetric in the two joints)
    jdot = (J * sp.Matrix(qd)).jacobian(q)
    jdq = jdot * sp.Matrix(qd)
    mods = numpy_modules()
    fx = sp.lambdify([q], list(x), modules=mods)
    fJ = sp.lambdify([q], J.tolist(), modules=mods)
    fh = sp.lambdify([q, qd], list(jdq), modules=mods)
    fjd = sp.lambdify([q, qd], jdot.tolist(), modules=mods)
    n, m = len(q), len(coords)
    arm = tp.Arm(lambda v: np.asarray(fx(list(v)), dtype=float).reshape(m),
                 lambda v: np.asarray(fJ(list(v)), dtype=float).reshape(m, n),
                 lambda v, w: np.asarray(fh(list(v), list(w)), dtype=float).reshape(m),
                 [j.is_revolute for j in model.joints],
                 lambda v, w: np.asarray(fjd(list(v), list(w)), dtype=float).reshape(m, n))
    return arm, x


def _values(ctx, mapping, coords, key, subs) -> np.ndarray:
    out = []
    for c in coords:
        v = next((rhs for _t, lhs, rhs in mapping if sp.expand(lhs - c) == 0), None)
        if v is None:
            raise BadInput(key, f"no value for the coordinate {c}")
        out.append(float(ctx.numeric(v, subs)))
    return np.array(out)


def _ik_joints(model, ctx, subs):
    out = []
    for j in model.joints:
        lim = None
        if j.limits is not None:
            try:
                lim = tuple(float(v) for v in ctx.numeric(list(j.limits), subs))
            except Exception:
                lim = None
        out.append(IKJoint(j.symbol, j.is_revolute, lim))
    return out


def _ik(ctx, model, x_expr, target, subs):
    """(configuration, IKResult or None) reaching ``target``: the IK engine's selected
    solution; for fewer coordinates than joints, none here (the solution nearest q = 0)."""
    n, m = len(model.q), len(target)
    values = {s: float(v) for s, v in subs.items() if getattr(v, "is_number", False)}
    if m < n:
        return None, None
    try:
        res = solve_ik([(x_expr[i], float(target[i])) for i in range(m)], _ik_joints(model, ctx, subs), values,
                       time_limit_s=ctx.budgets.closed_form_seconds)
    except (TypeError, ValueError):      # a closed form evaluated off its domain (complex values)
        raise OutOfReach("no configuration of the arm puts the point there") from None
    if res.status == "unreachable" or res.selected is None:
        raise OutOfReach(res.reason or "no configuration reaches it")
    return np.array([res.selected[j.name] for j in model.joints], dtype=float), res


# check_input's setup of a question, reused by solve (the IK and the lambdified arm are half of
# a small problem's work): id(question) -> (question, budgets, setup); a few, the latest
_SETUPS: dict = {}
_KEPT_SETUPS = 8


def setup(question, ctx: SolveContext):
    """Everything before the conversion; raises BadInput for a mistake in the file. The same
    question with the same budgets gives the same setup, computed once."""
    hit = _SETUPS.get(id(question))
    if hit is not None and hit[0] is question and hit[1] == ctx.budgets:
        return hit[2]
    out = _setup(question, ctx)
    while len(_SETUPS) >= _KEPT_SETUPS:
        _SETUPS.pop(next(iter(_SETUPS)))
    _SETUPS[id(question)] = (question, ctx.budgets, out)
    return out


def _setup(question, ctx: SolveContext):
    model, opts = ctx.model, question.options
    subs = ctx.substitutions(question.at)
    coords = coordinates(question, model)
    arm, x_expr = _arm(model, coords, subs)
    unknown = sorted(str(v) for v in x_expr.free_symbols - set(model.q))
    if unknown:
        raise MissingValues(unknown)
    for c, x in zip(coords, x_expr):
        if not x.free_symbols & set(model.q):
            raise BadInput("coordinates" if "coordinates" in opts else "type",
                           f"{c} does not move with the joints (it is {sstr(x)} in every configuration): "
                           "each task coordinate must change as the arm moves"
                           + ("" if "coordinates" in opts else "; give `coordinates` (e.g. [E.x, E.y])"))
    a = _values(ctx, opts["from"], coords, "from", subs)
    b = _values(ctx, opts["to"], coords, "to", subs)
    path = _path(ctx, opts.get("path", {"kind": "line"}), a, b, subs)
    timing = _timing(ctx, opts, path.length, subs)
    # A path that leaves the workspace or meets a singular configuration is an answer (`unreachable`
    # or `singular`, with t and the point), its ends included: `follow` finds a singular end, or
    # the instant the path leaves the reach; a `from` out of reach is the path leaving it at t = 0.
    outside = None
    try:
        q_from, res = _ik(ctx, model, x_expr, a, subs)
    except OutOfReach as exc:            # the reason may be prose with numbers (Text)
        q_from, res, outside = None, None, exc.reason
    # J wide (fewer coordinates than joints): `from` has a family of solutions, and the start is
    # the one nearest the given `start` (or q = 0), not wherever Newton's steps happen to stop
    onto_from = tp.nearest_solution if a.size < len(model.q) else tp.newton
    if "start" in opts and outside is None:
        q0 = np.array([float(ctx.numeric(opts["start"][j.name], subs)) for j in model.joints])
        q_from = onto_from(arm, a, q0)
        if q_from is None:
            if tp.newton(arm, a, np.zeros(len(model.q))) is None and res is None:
                outside = "Newton's method reaches it neither from `start` nor from q = 0"
            else:
                raise BadInput("start", "Newton's method from this configuration does not reach `from`")
    elif q_from is None and outside is None:
        q_from = onto_from(arm, a, np.zeros(len(model.q)))
        if q_from is None:
            outside = "Newton's method from q = 0 does not reach it"
    return coords, arm, path, timing, q_from, res, subs, outside


def _path(ctx, spec, a, b, subs) -> tp.Path:
    try:
        if spec["kind"] == "line":
            return tp.line(a, b)
        center = [float(ctx.numeric(v, subs)) for v in spec["center"]]
        if len(center) != a.size:
            raise BadInput("path", f"the centre has {len(center)} coordinates, the path {a.size}")
        normal = ([float(ctx.numeric(v, subs)) for v in spec["normal"]] if spec.get("normal") else None)
        return tp.circle(a, b, center, normal)
    except tp.PathError as exc:
        raise BadInput(exc.key, str(exc)) from None


def _timing(ctx, opts, length, subs) -> tp.Timing:
    if "duration" in opts:
        return tp.quintic(length, float(ctx.numeric(opts["duration"], subs)))
    v = float(ctx.numeric(opts["max_velocity"], subs))
    acc = float(ctx.numeric(opts["max_acceleration"], subs))
    for key, val in (("max_velocity", v), ("max_acceleration", acc)):
        if not val > 0:
            raise BadInput(key, f"must be positive, got {val:g}")
    return tp.trapezoidal(length, v, acc)


def check_input(question, ctx: SolveContext) -> list[tuple[str, str]]:
    """The mistakes only the model shows (the circle, a `start` off `from`): (key, message)."""
    try:
        setup(question, ctx)
    except BadInput as exc:
        return [(exc.key, exc.message)]
    except Exception:                  # anything else is the solver's to report
        return []
    return []


# -- solve ---------------------------------------------------------------------------------
def solve(question, ctx: SolveContext) -> Answer:
    model = ctx.model
    ans = Answer(question.type, question.id)
    try:
        coords, arm, path, timing, q_from, res, subs, outside = setup(question, ctx)
    except BadInput as exc:
        raise SolverError(f"{exc.key}: {exc.message}") from None
    except MissingValues as exc:
        raise SolverError(missing_note("trajectory", exc.names, ctx.problem)) from None
    except (TypeError, ValueError) as exc:
        raise SolverError(f"the trajectory needs numeric data ({exc})") from None
    names = [j.name for j in model.joints]
    labels = [str(c) for c in coords]
    tex = [latex(c, symbol_names=ctx.symbol_latex) for c in coords]
    ans.numeric["T"] = timing.T
    ans.numeric["length"] = path.length
    if outside is not None:
        ctx.record_trajectory(question.id, None)
        return _outside_at_start(ans, coords, labels, tex, path, timing, outside)
    conv = tp.follow(arm, path, timing, q_from, samples=SAMPLES)
    traj = TaskTrajectory(coords, labels, tex, path, timing, arm, conv, names, np.asarray(q_from, dtype=float))
    ans.numeric["start"] = {n: float(q_from[i]) for i, n in enumerate(names)}
    _path_steps(ans, traj, res, question, model, ctx.symbol_latex)
    if conv.failure is not None:
        ctx.record_trajectory(question.id, None)
        _failure(ans, traj, model)
        if conv.t.size == 0:             # singular at `from` itself: no motion to draw
            return ans
    else:
        ctx.record_trajectory(question.id, traj)
        vel, acc, (smin, tmin) = tp.extremes(arm, path, timing, conv)
        ans.numeric["end"] = {n: float(conv.q[i, -1]) for i, n in enumerate(names)}
        ans.numeric["max_joint_velocity"] = {n: float(vel[i]) for i, n in enumerate(names)}
        ans.numeric["max_joint_acceleration"] = {n: float(acc[i]) for i, n in enumerate(names)}
        ans.numeric["min_singular_value"] = smin
        _joint_steps(ans, traj, model, ctx.symbol_latex, vel, acc, smin, tmin)
    _figures(ans, ctx, traj, subs, question)
    return ans


def followed_trajectory(qid: str, ctx: SolveContext, at: dict | None) -> TaskTrajectory:
    """The trajectory `qid` as a question with `at` follows it: the recorded one, or, when `at`
    overrides a parameter (a length, a limit), the trajectory converted again with it, so the
    reference, its start and the task map are those of the arm the question simulates."""
    recorded = ctx.trajectory(qid)
    ref = ctx.reference_under(qid, at)
    if ref is None:
        return recorded
    own = next(q for q in ctx.problem.questions if q.id == qid).at     # the trajectory's own overrides
    changed = ", ".join(sorted(s.name for s, v in at.items()
                               if s in ctx.problem.parameters and (s not in own or own[s] != v)))
    try:
        coords, arm, path, timing, q_from, _res, _subs, outside = setup(ref, ctx)
    except BadInput as exc:
        raise SolverError(f"with this question's {changed}, the trajectory '{qid}': {exc.key}: {exc.message}") from None
    except MissingValues as exc:
        raise SolverError(missing_note("trajectory", exc.names, ctx.problem)) from None
    if outside is not None:
        raise SolverError(f"with this question's {changed}, the trajectory '{qid}' starts out of reach "
                          "(its `from`): there is no reference to track")
    conv = tp.follow(arm, path, timing, q_from, samples=SAMPLES)
    if conv.failure is not None:
        raise SolverError(f"with this question's {changed}, the trajectory '{qid}' cannot be followed "
                          "(it leaves the workspace or meets a singular configuration): there is no reference to track")
    return TaskTrajectory(coords, recorded.labels, recorded.tex, path, timing, arm, conv, recorded.joints,
                          np.asarray(q_from, dtype=float))


def _figures(ans, ctx, traj, subs, question) -> None:
    model, conv = ctx.model, traj.conv
    p0 = model.point0(question.point).xreplace(subs)
    fp = sp.lambdify([list(model.q)], list(p0), modules=numpy_modules())
    trace = [[float(v) for v in fp(list(conv.q[:, k]))] for k in range(conv.t.size)]
    poses = []
    last = "end" if conv.failure is None else "last reached"     # a path cut short is not at its end
    if conv.t.size:
        for label, k in (("start", 0), ("middle", conv.t.size // 2), (last, conv.t.size - 1)):
            s2 = dict(subs)
            s2.update({j.symbol: sp.Float(conv.q[i, k]) for i, j in enumerate(model.joints)})
            drw = robot_drawing(ctx, s2)
            if drw is not None:
                poses.append({"label": Text(label, " (t = ", Num(conv.t[k], "s"), ")"), "drawing": drw})
    title = ("Path of the end effector, the arm at start, middle and end" if conv.failure is None else
             "Path of the end effector, cut where it " + ("leaves the reach" if conv.failure["kind"] == "unreachable"
                                                           else "turns singular"))
    ans.figures.append(FigureSpec("path", "task_path", title,
                                  {"trace": trace, "poses": poses, "point": question.point}))
    syms = [latex(j.symbol, symbol_names=ctx.symbol_latex) for j in model.joints]
    ans.figures.append(FigureSpec("joints", "joint_motion", "Joint positions, rates and accelerations",
                                  {"t": [float(v) for v in conv.t], "T": traj.timing.T,
                                   "switches": [float(v) for v in traj.timing.breaks[1:-1]],
                                   "joints": [{"label": syms[i], "unit": "rad" if j.is_revolute else "m",
                                               "q": conv.q[i].tolist(), "qd": conv.qd[i].tolist(),
                                               "qdd": conv.qdd[i].tolist()}
                                              for i, j in enumerate(model.joints)]}))


# -- report --------------------------------------------------------------------------------
def _vec(tex_list, values):
    return Text("$", Text.join(",\\; ", [Text(f"{t} = ", Num(v)) for t, v in zip(tex_list, values)]), "$")


def _path_steps(ans, traj, res, question, model, symbols: dict) -> None:
    path, timing = traj.path, traj.timing
    xs = "\\begin{bmatrix}" + " \\\\ ".join(traj.tex) + "\\end{bmatrix}"
    if path.kind == "line":
        u = (path.b - path.a) / path.length
        text = Text("A straight line from ", _vec(traj.tex, path.a), " to ", _vec(traj.tex, path.b),
                    ", of length $L = ", Num(path.length), "$; with s the length travelled, "
                    "$x(s) = a + s\\,u$, $u = (b - a)/L = [", Text.join(", ", [Num(v) for v in u]), "]$.")
        s_ = sp.Symbol("s")
        eq = [(f"{xs}(s)", "a + s\\,\\frac{b - a}{L}"),
              (f"{xs}(s)", sp.Matrix([sp.Float(path.a[i], 12) + sp.Float(u[i], 12) * s_ for i in range(u.size)]))]
    else:
        text = Text("An arc of the circle of centre c = [", Text.join(", ", [Num(v) for v in path.center]),
                    "] and radius $r = ", Num(path.radius), "$, from ", _vec(traj.tex, path.a), " to ",
                    _vec(traj.tex, path.b), " the shorter way: angle $\\varphi = ", Num(path.angle),
                    "$ rad, length $L = r\\varphi = ", Num(path.length), "$; $e_1 = (a - c)/r = [",
                    Text.join(", ", [Num(v) for v in path.e1]), "]$, $e_2 = [",
                    Text.join(", ", [Num(v) for v in path.e2]), "]$ (in the plane of the arc, towards b).")
        eq = [(f"{xs}(s)", "c + r\\left(\\cos\\frac{s}{r}\\,e_1 + \\sin\\frac{s}{r}\\,e_2\\right)")]
    ans.steps.append(Step("Path", text, equations=eq))
    ans.steps.append(_timing_step(timing))
    if traj.conv is None:           # the path starts out of reach: no branch to follow
        return
    names = [latex(j.symbol, symbol_names=symbols) for j in model.joints]
    q0 = traj.start_configuration
    wide = path.a.size < len(model.q)
    how = ("the configuration of `from` nearest the one given as `start` (fewer coordinates than joints: "
           "a family of solutions; the least |q − start|)" if wide and "start" in question.options else
           "the configuration given as `start`, brought onto `from` by Newton's method"
           if "start" in question.options else
           "the inverse-kinematics solution of `from` that `select: limits` picks (the first of the "
           "sorted solutions inside the joint limits)" if res is not None else
           "the configuration of `from` nearest q = 0 (fewer coordinates than joints: a family of "
           "solutions; the least |q|)")
    cf = ("" if res is None or res.closed_form is None else
          Text(" The IK engine has a closed form here, with ", Num(len(res.closed_form_values)),
               " solution(s) at `from`; the branch followed is the one of this solution."))
    along = (" Along the path, $x(q) = x_d(t)$ leaves a family of configurations: the joints follow the "
             "minimum-norm rates $\\dot q = J^+\\dot x_d$, integrated from sample to sample (classical "
             "Runge-Kutta) and polished by Newton's method onto the path."
             if len(traj.labels) < len(names) else
             " Along the path, each sample is solved by Newton's method from the previous one (predicted "
             "with its rates), which stays on that branch.")
    ans.steps.append(Step("Inverse-kinematics branch", Text("Start: ", how, ".", cf, along),
                          equations=[(names[i], float(q0[i])) for i in range(len(names))]))


def _timing_step(timing) -> Step:
    if timing.kind == "quintic":
        return Step("Timing law", Text("Quintic in $\\tau = t/T$ over $T = ", Num(timing.T), "$ s",
                                       " (rest to rest, zero acceleration at both ends): peak speed $15L/(8T) = ",
                                       Num(timing.v_peak), "$, peak acceleration $10L/(\\sqrt3\\,T^2) = ",
                                       Num(timing.a_max), "$."),
                    equations=[("s(t)", "L\\,(10\\tau^3 - 15\\tau^4 + 6\\tau^5)")])
    if timing.kind == "trapezoidal":
        text = Text("Trapezoidal speed: $L \\ge v^2/a$, so the cruise speed is reached. Acceleration time "
                    "$t_a = v/a = ", Num(timing.t_acc), "$ s, $T = L/v + t_a = ", Num(timing.T), "$ s.")
        eq = [("s(t)", "\\begin{cases} \\tfrac12 a t^2 & 0 \\le t \\le t_a \\\\ "
                       "v\\,(t - t_a/2) & t_a \\le t \\le T - t_a \\\\ "
                       "L - \\tfrac12 a (T - t)^2 & T - t_a \\le t \\le T \\end{cases}")]
    else:
        text = Text("Bang-bang: $L < v^2/a$, the cruise speed is not reached. $t_a = \\sqrt{L/a} = ",
                    Num(timing.t_acc), "$ s, $T = 2t_a = ", Num(timing.T), "$ s, peak speed $a\\,t_a = ",
                    Num(timing.v_peak), "$.")
        eq = [("s(t)", "\\begin{cases} \\tfrac12 a t^2 & 0 \\le t \\le t_a \\\\ "
                       "L - \\tfrac12 a (T - t)^2 & t_a \\le t \\le T \\end{cases}")]
    return Step("Timing law", text, equations=eq)


def _outside_at_start(ans, coords, labels, tex, path, timing, why: str) -> Answer:
    """The answer for a path whose start `from` is out of reach: it leaves the workspace at
    t = 0, so there is no configuration to start from and nothing to convert."""
    traj = TaskTrajectory(coords, labels, tex, path, timing, None, None, [])
    _path_steps(ans, traj, None, None, None, None)
    where = Text.join(", ", [Text(f"{lab} = ", Num(v)) for lab, v in zip(labels, path.a)])
    reason = Text("at t = ", Num(0.0, "s"), " the path starts at (", where, "), out of the arm's reach (",
                  why or "no configuration reaches it", ")")
    ans.extra["unreachable"] = True
    ans.extra["reason"] = reason
    ans.steps.append(Step("The path cannot be followed", Text("No configuration to start from: ", reason, ".")))
    return ans


def _failure(ans, traj, model) -> None:
    f = traj.conv.failure
    where = Text.join(", ", [Text(f"{lab} = ", Num(v)) for lab, v in zip(traj.labels, f["x"])])
    if f["kind"] == "unreachable":
        ans.extra["unreachable"] = True
        reason = Text("at t = ", Num(f["t"], "s"), " the path reaches (", where, "), out of the arm's reach")
    elif "jump" in f:        # J keeps its rank, but the branch is lost between two samples
        ans.extra["singular"] = True
        reason = Text("at t = ", Num(f["t"], "s"), " the path passes close to a singular configuration, near (",
                      where, "): the smallest singular value of J falls to ", Num(f["sigma"]),
                      " and the joints would turn by ", Num(f["jump"], "rad"), " more than their rates predict "
                      "between two samples, too fast to follow")
    else:
        ans.extra["singular"] = True
        reason = Text("at t = ", Num(f["t"], "s"), " the path crosses a singular configuration, at (", where,
                      "): J loses rank and the joint rates are unbounded")
    ans.extra["reason"] = reason
    ans.steps.append(Step("The path cannot be followed", Text("The conversion stops: ", reason, ".")))


def _joint_steps(ans, traj, model, symbols: dict, vel, acc, smin, tmin) -> None:
    conv = traj.conv
    names = [latex(j.symbol, symbol_names=symbols) for j in model.joints]
    wide = len(traj.labels) < len(names)
    ans.steps.append(Step(
        "Joint rates and accelerations",
        "At each sample: $\\dot x_d = x'(s)\\,\\dot s$, $\\ddot x_d = x''(s)\\,\\dot s^2 + x'(s)\\,\\ddot s$; "
        + ("J is wide (fewer coordinates than joints): $J^+ = J^T (J J^T)^{-1}$, the minimum-norm rates, "
           "whose time derivative has a part in the null space of J besides $J^+(\\ddot x_d - \\dot J\\,\\dot q)$. "
           if wide else "$J\\,\\dot q$ is the time derivative of x, hence:"),
        equations=[("\\dot q", "J^{+}\\,\\dot x_d" if wide else "J^{-1}\\,\\dot x_d"),
                   ("\\ddot q", "J^{+}\\,(\\ddot x_d - \\dot J\\,\\dot q) + (I - J^{+}J)\\,\\dot J^T (J J^T)^{-1}\\,\\dot x_d"
                    if wide else "J^{-1}\\,(\\ddot x_d - \\dot J\\,\\dot q)")]))
    idx = np.unique(np.round(np.linspace(0, conv.t.size - 1, TABLE_ROWS)).astype(int))
    head = ["t (s)", "s"] + [f"${t}$" for t in traj.tex] + [f"${n}$" for n in names] + \
        [f"$\\dot {n}$" for n in names]
    rows = [[Num(conv.t[k]), Num(conv.s[k])] + [Num(v) for v in conv.x[:, k]] + [Num(v) for v in conv.q[:, k]]
            + [Num(v) for v in conv.qd[:, k]] for k in idx]
    ans.steps.append(Step("Samples", Text(Num(conv.t.size), " samples (the switching instants of the "
                                          "timing law twice, one per side), ", Num(len(idx)), " of them shown:"), table=(head, rows)))
    rows = [[f"${names[i]}$", Num(vel[i]), Num(acc[i])] for i in range(len(names))]
    ans.steps.append(Step("Extremes over [0, T]", Text(
        "The largest magnitudes, refined between samples on each interval of the timing law; the smallest "
        "singular value of J along the path is ", Num(smin), " (at t = ", Num(tmin, "s"), ")."),
        table=(["joint", "max |q̇|", "max |q̈|"], rows)))
