"""Question 10: closed-loop simulation of the arm following the motion profile.

Plant M(q) qdd + c(q, qd) + g(q) = tau + f_ext(q) (numeric, lambdified with cse),
controller chosen by `law` (spec, "Control"): p (the course's tau = Kp (q_d - q)),
pd, pd_gravity, computed_torque.  The arm starts at rest at `start` (default the
profile's start).  The ODE is integrated in error coordinates with LSODA (stiff-
capable), restarted at each switching instant; see robosolve/simulation/joint_control.py.
"""

from __future__ import annotations

import numpy as np
import sympy as sp

from robosolve.core.prose import Num, Text
from robosolve.errors import SolverError
from robosolve.load.problem import Question
from robosolve.simulation.joint_control import simulate
from robosolve.solvers.motion_profile import followed_profile
from robosolve.solvers.base import Answer, FigureSpec, SolveContext, Step, missing_note
from robosolve.core.printing import latex

SAMPLES = 2001

LAW_TEX = {
    "p": "\\tau = K_p\\,e",
    "pd": "\\tau = K_p\\,e + K_d\\,\\dot e",
    "pd_gravity": "\\tau = K_p\\,e + K_d\\,\\dot e + g(q)",
    "computed_torque": "\\tau = M(q)\\,(\\ddot q_d + K_d\\,\\dot e + K_p\\,e) + c(q, \\dot q) + g(q)",
}
LAW_TEXT = {
    "p": "proportional control (the course's controller), with no gravity compensation: the "
         "actuators act as springs $K_p e$ pulling each joint towards its desired value, so under "
         "gravity or a load an error remains",
    "pd": "proportional-derivative control: the derivative term damps the oscillations",
    "pd_gravity": "PD control with gravity compensation $g(q)$",
    "computed_torque": "computed-torque control: the model is inverted, so the error obeys "
                       "$\\ddot e + K_d\\,\\dot e + K_p\\,e = 0$ (exactly, with an exact model and no external force)",
}


def _above_noise(x: float, scale: float) -> float:
    """x, or 0 when it is below 1e-9 of ``scale`` (integration noise, not an error)."""
    x = float(x)
    return 0.0 if abs(x) <= 1e-9 * abs(float(scale)) else x


def _unit(kind: str) -> str:
    return "rad" if kind == "revolute" else "m"


def _float(ctx, expr, subs, what):
    try:
        return float(ctx.numeric(sp.sympify(expr), subs))
    except Exception:
        raise SolverError(f"{what} must be a number (got {expr})") from None


def _external_series(res, i, r):
    """Joint i's generalized external force along the run, or None when it is zero throughout."""
    ext = getattr(res, "external", None)
    if ext is None or not np.any(np.abs(ext[i]) > 1e-12):
        return None
    return r(ext[i])


def _law_sentence(law: str, kp: list) -> str:
    if law == "p" and not any(kp):
        return ("proportional control with $K_p = 0$: the actuators exert no torque, so the arm "
                "moves under gravity and the external loads alone")
    return LAW_TEXT[law]


def solve(question: Question, ctx: SolveContext) -> Answer:
    model = ctx.model
    opts = question.options
    ref = opts.get("profile")
    ans = Answer(question.type, question.id)
    at = ctx.working_at(question, ans)
    prof = followed_profile(ref, ctx, at) if "trajectory" not in opts else None
    subs = ctx.substitutions(at)
    joints = model.joints
    names = [j.name for j in joints]
    law = opts.get("law", "p")
    if prof is None:
        return _solve_trajectory(question, ctx, ans, subs, law, at)
    if not prof.T.is_number:
        ans.note(missing_note("simulation", sorted(s.name for s in prof.T.free_symbols), ctx.problem))
        return ans

    kp = [_float(ctx, opts["gains"][n], subs, f"gains.{n}") for n in names]
    kd = [_float(ctx, opts["gains_d"][n], subs, f"gains_d.{n}") for n in names] if "gains_d" in opts else None
    start = [_float(ctx, opts["start"][n], subs, f"start.{n}") for n in names] if "start" in opts else None
    duration = _float(ctx, opts["duration"], subs, "duration") if "duration" in opts else float(prof.T)
    if not duration > 0:
        raise SolverError("the simulation needs a positive duration (does the profile move at all?)")

    negative = [n for n, k in zip(names, kp + (kd or [])) if k < 0]
    if negative and law != "computed_torque":
        ans.note("a negative gain (" + ", ".join(sorted(set(negative))) + ") makes the loop unstable: "
                 "the error grows exponentially instead of being corrected")
    syms = [latex(j.symbol, symbol_names=ctx.symbol_latex) for j in joints]
    gains_tex = Text.join(",\\quad ", [Text(f"K_{{p,{syms[i]}}} = ", Num(kp[i])) for i in range(len(joints))])
    if kd is not None:
        gains_tex += Text(",\\quad ", Text.join(",\\quad ", [Text(f"K_{{d,{syms[i]}}} = ", Num(kd[i]))
                                                             for i in range(len(joints))]))
    start_txt = ("the profile's start" if start is None else
                 Text.join(", ", [Text(f"${syms[i]} = ", Num(start[i]), "$") for i in range(len(joints))]))
    ans.steps.append(Step(
        "Closed loop",
        Text(f"Error $e = q_d - q$ (desired profile `{ref}` minus actual). Law: {_law_sentence(law, kp)}. "
             "The actuators replace $\\tau$ in the equations of motion, which become a system of ODEs in $q$; "
             "it is integrated from ", start_txt, ", at rest, over $[0, ", Num(duration), "]$ s."),
        equations=[("", LAW_TEX[law]),
                   ("", "M(q)\\,\\ddot q + c(q, \\dot q) + g(q) = \\tau + f_{ext}(q)"),
                   ("", gains_tex)],
    ))
    try:
        fast, _ = ctx.simulation_dynamics(subs)
    except ValueError as exc:
        ans.note(f"numeric simulation omitted: {exc}")
        return ans
    plan = prof.numeric_plan()
    try:
        res = simulate(fast, plan, law, kp, kd, start=start, duration=duration, samples=SAMPLES)
    except RuntimeError as exc:          # SimulationTooLong or an integration failure
        raise SolverError(str(exc)) from None
    except (ValueError, ZeroDivisionError, np.linalg.LinAlgError) as exc:
        if "invertible" in str(exc) or "singular" in str(exc).lower() or isinstance(exc, ZeroDivisionError):
            raise SolverError("the mass matrix M(q) is singular (a joint moves no mass: a point mass on its axis, a body of mass 0?), "
                              "so the motion under control is not defined") from None
        raise

    # The simulation is accurate to ~1e-6 relative (tests: 1e-4 required); more digits would be
    # noise that differs between machines: the answer schema keeps 6 (registry AnswerKey.digits).
    ans.numeric["max_error"] = {n: float(res.max_error[i]) for i, n in enumerate(names)}
    ans.numeric["final_error"] = {n: _above_noise(res.final_error[i], res.max_error[i])
                                  for i, n in enumerate(names)}
    ans.numeric["t_max_error"] = {n: float(res.t_max_error[i]) for i, n in enumerate(names)}
    rows = [[f"${syms[i]}$", Num(res.max_error[i], _unit(j.kind)),
             Num(res.t_max_error[i]), Num(res.final_error[i], _unit(j.kind))]
            for i, j in enumerate(joints)]
    ans.steps.append(Step(
        "Tracking errors",
        "Integrated with LSODA (it switches to a stiff method when the gains make the loop stiff), relative "
        "tolerance $10^{-8}$ on the error itself, restarting at each switching instant of the profile; the "
        "maximum is refined on the solver's dense output.",
        table=(["joint", "max |e|", "at t (s)", Text("e at t = ", Num(duration), " s")], rows),
    ))

    _figures(ans, res, prof, plan, duration, law, joints, syms)
    return ans


def _figures(ans, res, prof, plan, duration, law, joints, syms) -> None:
    """Tracking (actual vs desired, error) and effort figures of the simulation."""
    names = [j.name for j in joints]

    def r(a):
        return [float(x) for x in a]

    common = {"t": r(res.t), "T": float(prof.T), "duration": duration,
              "switches": [float(x) for x in plan.breaks[1:-1] if x < duration]}
    ans.figures.append(FigureSpec(
        "tracking", "control_tracking", f"{law} control: actual vs desired, and the error",
        dict(common, joints=[{"name": n, "label": syms[i], "unit": _unit(joints[i].kind),
                              "q": r(res.q[i]), "q_desired": r(res.q_desired[i]), "error": r(res.error[i])}
                             for i, n in enumerate(names)]),
    ))
    ans.figures.append(FigureSpec(
        "effort", "control_effort", f"{law} control: actuator effort",
        dict(common, actuators=[{"name": str(j.actuator), "label": latex(j.actuator),
                                 "unit": "N·m" if j.kind == "revolute" else "N", "values": r(res.effort[i]),
                                 "external": _external_series(res, i, r)}
                                for i, j in enumerate(joints)]),
    ))


# -- along a work-space trajectory (course summary §1.2.2) ---------------------------------
def _task_gains(ctx, opts, key, traj, subs):
    """The gains per coordinate of the trajectory, in its order (numbers or parameters: a
    variant draws `gains: {E.y: Kp}`)."""
    given = opts[key]["coordinates"]
    return [_float(ctx, next(v for _t, lhs, v in given if sp.expand(lhs - c) == 0), subs, f"{key}.{c}")
            for c in traj.coords]


def _solve_trajectory(question, ctx, ans, subs, law, at):
    from robosolve.simulation.task_control import TASK_LAWS, simulate_task
    from robosolve.solvers.task_trajectory import followed_trajectory

    opts, model = question.options, ctx.model
    traj = followed_trajectory(opts["trajectory"], ctx, at)
    names = [j.name for j in model.joints]
    duration = _float(ctx, opts["duration"], subs, "duration") if "duration" in opts else traj.timing.T
    start = ([_float(ctx, opts["start"][n], subs, f"start.{n}") for n in names] if "start" in opts
             else traj.start)
    try:
        dyn, _ = ctx.simulation_dynamics(subs)
    except ValueError as exc:
        ans.note(f"numeric simulation omitted: {exc}")
        return ans
    task = law in TASK_LAWS
    if task:
        kp, kd = _task_gains(ctx, opts, "gains", traj, subs), _task_gains(ctx, opts, "gains_d", traj, subs)
    else:
        kp = [_float(ctx, opts["gains"][n], subs, f"gains.{n}") for n in names]
        kd = [_float(ctx, opts["gains_d"][n], subs, f"gains_d.{n}") for n in names] if "gains_d" in opts else None
    given = None
    if "start" in opts:      # the configuration the run starts from, as the report states it
        syms = [latex(j.symbol, symbol_names=ctx.symbol_latex) for j in model.joints]
        given = Text.join(", ", [Text(f"${syms[i]} = ", Num(start[i]), "$") for i in range(len(names))])
    _trajectory_law_step(ans, opts["trajectory"], law, task, traj, kp, kd, duration, given)
    try:
        if task:
            res = simulate_task(dyn, traj.arm, traj.desired, traj.timing.breaks, law, kp, kd, start, duration,
                                samples=SAMPLES)
            e_task, t_grid = res.error, res.t
        else:
            res = simulate(dyn, traj.plan(), law, kp, kd, start=start, duration=duration, samples=SAMPLES)
            t_grid = res.t
            xd = np.array([traj.desired(t)[0] for t in t_grid]).T
            e_task = xd - np.array([traj.arm.x(res.q[:, k]) for k in range(t_grid.size)]).T
    except RuntimeError as exc:
        raise SolverError(str(exc)) from None
    except (np.linalg.LinAlgError, ZeroDivisionError):
        raise SolverError("a singular matrix along the run (M(q), or J for task_computed_torque: the arm "
                          "reached a singular configuration)") from None
    keys = traj.labels if task else names
    ans.numeric["max_error"] = {k: float(res.max_error[i]) for i, k in enumerate(keys)}
    ans.numeric["final_error"] = {k: _above_noise(res.final_error[i], res.max_error[i]) for i, k in enumerate(keys)}
    ans.numeric["t_max_error"] = {k: float(res.t_max_error[i]) for i, k in enumerate(keys)}
    max_task = res.max_error if task else _max_task_error(traj, res, t_grid, e_task, duration)
    ans.numeric["max_task_error"] = {k: float(max_task[i]) for i, k in enumerate(traj.labels)}
    rows = [[f"${traj.tex[i]}$", Num(max_task[i]), Num(e_task[i, -1])] for i in range(len(traj.labels))]
    ans.steps.append(Step("Work-space errors", Text(
        "The error $x_d - x(q)$ of each task coordinate along the run (largest over the ", Num(t_grid.size),
        " output samples, refined on the solver's dense output)."),
        table=(["coordinate", "max |x_d - x|", Text("at t = ", Num(duration), " s")], rows)))
    if not task:
        ans.steps.append(Step("Joint errors", "", table=(["joint", "max |e|", "at t (s)", "final e"], [
            [n, Num(res.max_error[i]), Num(res.t_max_error[i]), Num(res.final_error[i])] for i, n in enumerate(names)])))
    _task_figure(ans, traj, t_grid, e_task, law, duration, ctx.problem)
    if not task:
        syms = [latex(j.symbol, symbol_names=ctx.symbol_latex) for j in model.joints]
        plan = traj.plan()
        plan.breaks = np.asarray(traj.timing.breaks)     # the switching instants marked in the figure
        _figures(ans, res, _Horizon(traj.timing.T), plan, duration, law, model.joints, syms)
    return ans


def _max_task_error(traj, res, t_grid, e_task, duration) -> np.ndarray:
    """max |x_d - x(q)| of each coordinate under a joint law: the samples' largest crests polished
    on the solver's dense output (an undamped loop's oscillation peaks between samples)."""
    from robosolve.simulation.joint_control import max_abs_refined

    def error(t):
        q_des, e = res.dense(t)
        return traj.desired(t)[0] - traj.arm.x(q_des - e)

    xatol = 1e-12 * max(1.0, duration)
    return np.array([max_abs_refined(lambda t, i=i: error(t)[i], t_grid, e_task[i], xatol)[0]
                     for i in range(e_task.shape[0])])


class _Horizon:
    """The reference's duration, as `_figures` reads it from a profile."""

    def __init__(self, T):
        self.T = T


TASK_LAW_TEX = {
    "task_pd_gravity": "\\tau = J^T(q)\\,(K_p\\,e + K_d\\,\\dot e) + g(q)",
    "task_computed_torque": "\\tau = M(q)\\,J^{-1}(q)\\,(\\ddot x_d + K_d\\,\\dot e + K_p\\,e - \\dot J\\,\\dot q) "
                            "+ c(q, \\dot q) + g(q)",
}


def _trajectory_law_step(ans, ref, law, task, traj, kp, kd, duration, start=None):
    if task:
        text = Text(f"Actual work-space scheme: the error is measured in the task coordinates, $e = x_d - x(q)$, "
                    f"$\\dot e = \\dot x_d - J\\,\\dot q$, along the trajectory `{ref}`; gains per coordinate: ",
                    Text.join(", ", [Text(f"$K_{{p,{t}}} = ", Num(kp[i]), f"$, $K_{{d,{t}}} = ", Num(kd[i]), "$")
                                     for i, t in enumerate(traj.tex)]), ".")
        eq = [("", TASK_LAW_TEX[law])]
    else:
        text = Text(f"Ideal work-space scheme: the trajectory `{ref}` is converted to joint references by "
                    "inverse kinematics (its samples' $q$, $\\dot q$, $\\ddot q$, joined by quintics), and the "
                    f"joint law follows them: {_law_sentence(law, kp)}.")
        eq = [("", LAW_TEX[law])]
    ans.steps.append(Step("Closed loop along the work-space trajectory", Text(
        text, " The plant $M(q)\\,\\ddot q + c + g = \\tau + f_{ext}$ is integrated from ",
        "the trajectory's start" if start is None else start, ", at rest, over $[0, ", Num(duration), "]$ s."),
        equations=eq + [("", "M(q)\\,\\ddot q + c(q, \\dot q) + g(q) = \\tau + f_{ext}(q)")]))


def _task_figure(ans, traj, t, e_task, law, duration, problem):
    from robosolve.questions.work_space import coordinate_unit

    xd = np.array([traj.desired(float(s))[0] for s in t]).T
    # m for a point's coordinate, rad for an angle (θ1 + θ2), none for a mixed one
    units = [coordinate_unit(c, problem) or "" for c in traj.coords]
    ans.figures.append(FigureSpec(
        "task", "control_tracking", f"{law} control: each task coordinate against its reference, and the error",
        {"t": [float(v) for v in t], "T": traj.timing.T, "duration": float(duration),
         "switches": [float(v) for v in traj.timing.breaks[1:-1] if v < duration],
         "error_title": "error $e = x_d - x$",
         "joints": [{"name": lab, "label": traj.tex[i], "unit": units[i], "q": (xd[i] - e_task[i]).tolist(),
                     "q_desired": xd[i].tolist(), "error": e_task[i].tolist()}
                    for i, lab in enumerate(traj.labels)]}))
