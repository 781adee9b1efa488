"""Question 10: closed-loop simulation of the arm following the motion profile.

Plant M(q) qdd + c(q, qd) + g(q) = tau + f_ext(q) (numeric, lambdified with cse),
controller chosen by `law` (spec, "Control"): p (the course's tau = Kp (q_d - q)),
pd, pd_gravity, computed_torque.  The arm starts at rest at `start` (default the
profile's start).  The ODE is integrated in error coordinates with LSODA (stiff-
capable), restarted at each switching instant; see robosolve/motion/control.py.
"""

from __future__ import annotations

import sympy as sp

from robosolve.errors import SolverError
from robosolve.load.problem import Question
from robosolve.motion.control import simulate
from robosolve.render.numbers import report_number
from robosolve.solvers.base import Answer, FigureSpec, SolveContext, Step, missing_note

SAMPLES = 2001

LAW_TEX = {
    "p": "\\tau = K_p\\,e",
    "pd": "\\tau = K_p\\,e + K_d\\,\\dot e",
    "pd_gravity": "\\tau = K_p\\,e + K_d\\,\\dot e + g(q)",
    "computed_torque": "\\tau = M(q)\\,(\\ddot q_d + K_d\\,\\dot e + K_p\\,e) + c(q, \\dot q) + g(q)",
}
LAW_TEXT = {
    "p": "proportional control (the course's controller), with no gravity compensation: the arm settles "
         "where the springs $K_p e$ balance gravity, so an error remains",
    "pd": "proportional-derivative control: the derivative term damps the oscillations",
    "pd_gravity": "PD control with gravity compensation $g(q)$",
    "computed_torque": "computed-torque control: the model is inverted, so the error obeys "
                       "$\\ddot e + K_d\\,\\dot e + K_p\\,e = 0$ (exactly, with an exact model and no external force)",
}


ANSWER_DIGITS = 6


def _sig(x: float, scale: float | None = None) -> float:
    """x with ANSWER_DIGITS significant digits; below 1e-9 of ``scale`` it is 0 (noise)."""
    x = float(x)
    if scale is not None and abs(x) <= 1e-9 * abs(float(scale)):
        return 0.0
    return float(f"{x:.{ANSWER_DIGITS}g}") + 0.0


def _unit(kind: str) -> str:
    return "rad" if kind == "revolute" else "m"


def _float(ctx, expr, subs, what):
    try:
        return float(ctx.numeric(sp.sympify(expr), subs))
    except Exception:
        raise SolverError(f"{what} must be a number (got {expr})") from None


def solve(question: Question, ctx: SolveContext) -> Answer:
    model = ctx.model
    opts = question.options
    ref = opts.get("profile")
    prof = ctx.profile(ref)
    if prof is None:
        raise SolverError(f"the motion profile '{ref}' has no answer")
    ans = Answer(question.type, question.id)
    subs = ctx.substitutions(question.at)
    joints = model.joints
    names = [j.name for j in joints]
    law = opts.get("law", "p")
    if not prof.T.is_number:
        ans.note(missing_note("simulation", sorted(s.name for s in prof.T.free_symbols), ctx.problem))
        return ans

    kp = [_float(ctx, opts["gains"][n], subs, f"gains.{n}") for n in names]
    kd = [_float(ctx, opts["gains_d"][n], subs, f"gains_d.{n}") for n in names] if "gains_d" in opts else None
    start = [_float(ctx, opts["start"][n], subs, f"start.{n}") for n in names] if "start" in opts else None
    duration = _float(ctx, opts["duration"], subs, "duration") if "duration" in opts else float(prof.T)
    if not duration > 0:
        raise SolverError("the simulation needs a positive duration (does the profile move at all?)")

    syms = [sp.latex(j.symbol, symbol_names=model.symbol_latex) for j in joints]
    gains_tex = ",\\quad ".join(f"K_{{p,{syms[i]}}} = {report_number(kp[i])}" for i in range(len(joints)))
    if kd is not None:
        gains_tex += ",\\quad " + ",\\quad ".join(f"K_{{d,{syms[i]}}} = {report_number(kd[i])}"
                                                  for i in range(len(joints)))
    start_txt = ("the profile's start" if start is None else
                 ", ".join(f"${syms[i]} = {report_number(start[i])}$" for i in range(len(joints))))
    ans.steps.append(Step(
        "Closed loop",
        f"Error $e = q_d - q$ (desired profile `{ref}` minus actual). Law: {LAW_TEXT[law]}. "
        "The actuators replace $\\tau$ in the equations of motion, which become a system of ODEs in $q$; "
        f"it is integrated from {start_txt}, at rest, over $[0, {report_number(duration)}]$ s.",
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

    # The simulation is accurate to ~1e-6 relative (tests: 1e-4 required); more digits would be
    # noise that differs between machines, so the answers keep ANSWER_DIGITS significant digits.
    ans.numeric["max_error"] = {n: _sig(res.max_error[i]) for i, n in enumerate(names)}
    ans.numeric["final_error"] = {n: _sig(res.final_error[i], scale=res.max_error[i]) for i, n in enumerate(names)}
    ans.numeric["t_max_error"] = {n: _sig(res.t_max_error[i]) for i, n in enumerate(names)}
    rows = [[f"${syms[i]}$", f"{report_number(res.max_error[i])} {_unit(j.kind)}",
             report_number(res.t_max_error[i]), f"{report_number(res.final_error[i])} {_unit(j.kind)}"]
            for i, j in enumerate(joints)]
    ans.steps.append(Step(
        "Tracking errors",
        "Integrated with LSODA (it switches to a stiff method when the gains make the loop stiff), relative "
        "tolerance $10^{-8}$ on the error itself, restarting at each switching instant of the profile; the "
        "maximum is refined on the solver's dense output.",
        table=(["joint", "max |e|", "at t (s)", f"e at t = {report_number(duration)} s"], rows),
    ))

    def r(a):
        return [float(f"{float(x):.10g}") + 0.0 for x in a]

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
        dict(common, actuators=[{"name": str(j.actuator), "label": sp.latex(j.actuator),
                                 "unit": "N·m" if j.kind == "revolute" else "N", "values": r(res.effort[i])}
                                for i, j in enumerate(joints)]),
    ))
    return ans
