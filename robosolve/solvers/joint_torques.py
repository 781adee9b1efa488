"""Question 9: the actuator forces that make the arm follow the motion profile.

The equations of motion M(q) qdd + c(q, qd) + g(q) = actuators + f_ext are solved
for the actuators, and the profile of the referenced motion profile question is
substituted for q, qd, qdd.  The profile is polynomial between switching instants,
so each actuator is a closed-form expression of t on each interval; it jumps where
an acceleration jumps (0, T/2, T for bang-bang).  Peaks are signed, over [0, T],
one-sided limits at the jumps included.
"""

from __future__ import annotations

import sympy as sp

from robosolve.core.prose import Num, Text
from robosolve.core.symbols import TIME
from robosolve.errors import SolverError, SymbolicTimeout
from robosolve.load.problem import Question
from robosolve.motion.torques import closed_form_pieces, torques_along
from robosolve.solvers.motion_profile import followed_profile
from robosolve.solvers.base import Answer, FigureSpec, SolveContext, Step, missing_note
from robosolve.core.printing import latex



def _bound(x):
    """An interval's end in a formula: exact as it is (sqrt(pi)/2), a decimal as a number the
    renderer writes (1.05409, not 1.05409255338946)."""
    x = sp.sympify(x)
    return Num(float(x)) if x.atoms(sp.Float) else latex(x)


def _unit(kind: str) -> str:
    return "N·m" if kind == "revolute" else "N"


def solve(question: Question, ctx: SolveContext) -> Answer:
    model = ctx.model
    ans = Answer(question.type, question.id)
    at = ctx.working_at(question, ans)
    prof = followed_profile(question.options.get("profile"), ctx, at)
    subs = ctx.substitutions(at)
    joints = model.joints
    act_names = [str(j.actuator) for j in joints]

    dyn = ctx.dynamics()
    lines = [f"{latex(j.actuator)}" for j in joints]
    if dyn is not None:
        tau = dyn.actuator_expressions()
        ans.steps.append(Step(
            "Actuators from the equations of motion",
            "The equations of motion $M(q)\\,\\ddot q + c(q, \\dot q) + g(q) = \\tau + f_{ext}(q)$, solved for the "
            "actuators (inverse dynamics):",
            equations=[(lines[i], tau[i]) for i in range(len(joints))],
        ))
    else:
        tau = None
        ans.note("the symbolic equations of motion took too long: the torques are given numerically only")

    _closed_form(ans, ctx, prof, tau, subs, joints, act_names, lines)

    # -- numeric: samples and signed peaks
    if not prof.T.is_number:
        ans.note(missing_note("torques", sorted(s.name for s in prof.T.free_symbols), ctx.problem))
        return ans
    try:
        fast, _ = ctx.simulation_dynamics(subs)
    except ValueError as exc:
        ans.note(f"numeric torques omitted: {exc}")
        return ans
    res = _torques_along(prof, fast, act_names)
    # an interior peak is found to ~1e-12 in value but only ~1e-8 in time (the maximum is
    # flat): the answer schema keeps 8 digits of t_peak (registry: AnswerKey.digits)
    ans.numeric["actuators"] = {act_names[i]: {"peak": res.peaks[i], "t_peak": res.t_peaks[i]}
                                for i in range(len(joints))}
    ans.steps += peak_steps(res, prof, joints)
    _figure(ans, res, prof, joints, act_names)
    return ans


def _torques_along(prof, fast, act_names):
    """The sampled actuators and their peaks; a force with no value along the profile (the square
    root or logarithm of a negative number: the math module raises, numpy gives nan) is said."""
    import math

    import numpy as np

    why = "a square root or logarithm of a negative number in a force?"
    try:
        with np.errstate(invalid="ignore", over="ignore", divide="ignore"):
            res = torques_along(prof, fast, act_names)
    except (ValueError, OverflowError) as exc:
        if isinstance(exc, np.linalg.LinAlgError):
            raise
        raise SolverError(f"the actuators have no value along the profile ({exc}: {why})") from None
    if not all(math.isfinite(v) for v in list(res.peaks) + list(res.t_peaks)):
        raise SolverError(f"the actuators have no finite value along the profile ({why})")
    return res


def _closed_form(ans, ctx, prof, tau, subs, joints, act_names, lines) -> None:
    """Each actuator as a closed form in t on each interval of the profile (when the
    symbolic equations are known and the profile's time is a number)."""
    qs, qds, qdds = ctx.model.q, ctx.model.qd, ctx.model.qdd
    bps = prof.breakpoints() if all(b.is_number for b in [prof.T]) else []
    pw = None
    if tau is not None and prof.T.is_number and prof.T != 0:
        try:
            with ctx.time_limit(ctx.budgets.closed_form_seconds):
                # a force varying with time uses the loader's t (core.symbols.TIME), which is the
                # profile's time unless the profile was built with its own
                timed = [sp.sympify(e).xreplace({TIME: prof.t}) for e in tau]
                # the dynamics stay symbolic (spec: symbolic answers keep every parameter); the
                # profile's timing is numeric when its data are; the numbers go in `numeric`
                pieces, pw = closed_form_pieces(prof, timed, qs, qds, qdds)
        except SymbolicTimeout:
            ans.note("the closed-form torque profiles took too long: given numerically only")
            pw = None
        if pw is not None:
            eqs = []
            for k, (a, b) in enumerate(zip(bps[:-1], bps[1:])):
                for i in range(len(joints)):
                    eqs.append((Text(f"{lines[i]}(t)\\big|_{{", _bound(a), " < t < ", _bound(b), "}"), pieces[i][k]))
            ans.steps.append(Step(
                "Closed form along the profile",
                "On each interval between switching instants the profile is a polynomial in $t$; substituting "
                "$q(t)$, $\\dot q(t)$, $\\ddot q(t)$ gives each actuator as a function of time, the parameters "
                "kept as symbols (the numbers are in the peaks below). "
                "Before 0 and after T the actuators hold the arm at rest (against gravity and the external forces).",
                equations=eqs,
            ))
            ans.symbolic["profiles"] = {act_names[i]: pw[i] for i in range(len(joints))}


def peak_steps(res, prof, joints) -> list[Step]:
    """The signed peaks and the jumps at the switching instants, as steps."""
    steps: list[Step] = []
    rows = []
    jumps = sorted({0.0, float(prof.T), *res.breaks})
    for i, j in enumerate(joints):
        at_jump = any(abs(res.t_peaks[i] - s) <= 1e-9 * max(1.0, float(prof.T)) for s in jumps)
        rows.append([f"${latex(j.actuator)}$", Num(res.peaks[i], _unit(j.kind)),
                     Text(Num(res.t_peaks[i])) + (" (a switching instant: one-sided value)" if at_jump else "")])
    steps.append(Step(
        "Peaks",
        "The peak is the signed value of largest magnitude over $[0, T]$; at a switching instant the "
        "actuator jumps, and the larger of the two one-sided values counts.",
        table=(["actuator", "peak", "at t (s)"], rows),
    ))
    if res.jumps:
        header = ["t (s)"] + [f"${latex(j.actuator)}$ before → after" for j in joints]
        jrows = [[Num(t)] + [Text(Num(b[i]), " → ", Num(a[i])) for i in range(len(joints))]
                 for t, b, a in res.jumps]
        steps.append(Step(
            "Jumps at the switching instants",
            "Where a joint acceleration jumps, so does $M(q)\\,\\ddot q$ and the actuators with it (velocities "
            "and positions are continuous). Before 0 and after T the values are the holding forces at rest.",
            table=(header, jrows),
        ))
    return steps


def _figure(ans, res, prof, joints, act_names) -> None:
    ans.figures.append(FigureSpec(
        "torques", "joint_torques", Text("Actuators along the profile (T = ", Num(float(prof.T)), " s)"),
        {"t": [float(x) for x in res.t],
         "T": float(prof.T), "switches": res.breaks,
         "actuators": [{"name": act_names[i], "label": latex(j.actuator), "unit": _unit(j.kind),
                        "values": [float(v) for v in res.values[i]],
                        "peak": res.peaks[i], "t_peak": res.t_peaks[i]} for i, j in enumerate(joints)]},
    ))
