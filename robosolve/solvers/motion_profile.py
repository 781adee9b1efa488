"""Question 7: synchronized joint motion profiles (bang-bang, trapezoidal, quintic).

Each joint alone at its limits needs its own time; the synchronized time T is
the largest of them (docs/course-notes.md#note-motion-sync), and the other joints are slowed down to end
at T: rescaled accelerations for bang-bang (a_i = 4|D_i|/T^2),
lowered cruise velocities for trapezoidal, peak accelerations for quintic.
"""

from __future__ import annotations

import sympy as sp

from robosolve.core.prose import Num, Text
from robosolve.core.symbols import TIME
from robosolve.errors import SolverError
from robosolve.load.problem import Question
from robosolve.motion.profiles import ProfileError, SyncProfile, synchronize
from robosolve.solvers.base import Answer, FigureSpec, SolveContext, Step
from robosolve.core.printing import latex

T_SYMBOL = TIME
SAMPLES = 401


def _unit(kind: str, order: int) -> str:
    base = "rad" if kind == "revolute" else "m"
    return base + ("", "/s", "/s²")[order]


def _num(e, unit: str = "") -> Text:
    """A value for a table: the number (the renderer formats it), or its LaTeX when symbolic."""
    try:
        return Text(Num(float(sp.N(e)), unit))
    except TypeError:
        return Text("$" + latex(e) + "$" + (" " + unit if unit else ""))


def compute(question: Question, ctx: SolveContext) -> SyncProfile:
    """The synchronized profile of the question (recorded in the context for the
    questions that refer to it)."""
    prof = _synchronized(question, ctx)
    ctx.record_profile(question.id, prof)
    return prof


def followed_profile(qid: str, ctx: SolveContext, at: dict | None) -> SyncProfile:
    """The profile `qid` as a question with `at` follows it: the recorded one, or, when `at`
    overrides a parameter, the profile synchronized again with it (`to: {q2: d_max}` followed
    with `at: {d_max: 0.3}` goes to 0.3)."""
    recorded = ctx.profile(qid)
    ref = ctx.reference_under(qid, at)
    return recorded if ref is None else _synchronized(ref, ctx)


def _synchronized(question: Question, ctx: SolveContext) -> SyncProfile:
    model = ctx.model
    opts = question.options
    shape = opts.get("shape", "bang-bang")
    subs = ctx.substitutions(question.at)
    joints = model.joints
    names = [j.name for j in joints]

    def values(key):
        m = opts.get(key) or {}
        return [sp.sympify(m[n]).xreplace(subs) for n in names] if m else None

    start, end, acc, vel = values("from"), values("to"), values("max_acceleration"), values("max_velocity")
    try:
        prof = synchronize(names, start, end, acc, shape=shape, max_velocity=vel, t=T_SYMBOL)
    except ProfileError as exc:
        raise SolverError(str(exc)) from None
    return prof


def solve(question: Question, ctx: SolveContext) -> Answer:
    model = ctx.model
    prof = compute(question, ctx)
    ans = Answer(question.type, question.id)
    shape = question.options.get("shape", "bang-bang")
    subs = ctx.substitutions(question.at)
    joints = model.joints
    syms = {j.name: latex(j.symbol, symbol_names=ctx.symbol_latex) for j in joints}
    ans.steps += steps(prof, shape, joints, syms)
    # -- answers
    ans.symbolic["durations"] = {jm.name: jm.own_time for jm in prof.joints}
    ans.symbolic["T"] = prof.T
    ans.symbolic["accelerations"] = {jm.name: jm.acceleration for jm in prof.joints}
    if shape == "trapezoidal":
        ans.symbolic["velocities"] = {jm.name: jm.velocity for jm in prof.joints}
    ans.symbolic["profiles"] = {jm.name: prof.position(i) for i, jm in enumerate(prof.joints)}

    numeric_keys = ["durations", "T", "accelerations"] + (["velocities"] if shape == "trapezoidal" else [])
    for key in numeric_keys:
        ctx.try_numeric(ans, key, ans.symbolic[key], subs, key)

    _figure(ans, prof, shape, joints, syms)
    return ans


def steps(prof: SyncProfile, shape: str, joints, syms: dict) -> list[Step]:
    """The worked solution: own times, synchronized time, rescaled values, profiles."""
    steps: list[Step] = []
    steps += _own_times(prof, shape, joints, syms)

    # -- step 2: synchronized time
    slow = ", ".join(f"${syms[n]}$" for n in prof.slowest) or "—"
    steps.append(Step(
        "Synchronized time",
        "All joints must start and stop together, so the motion lasts as long as the slowest joint "
        f"(here {slow}), which keeps its limits; the others are slowed down to end at the same instant. "
        "(The course's worked example takes joint 1's time: that holds only when joint 1 is the slowest.)",
        # the decimal value too when T is exact and not an integer (a decimal T is shown once)
        equations=[("T = \\max_i T_i", prof.T)] + ([("T", float(sp.N(prof.T)))] if prof.T.is_number
                                                     and not prof.T.is_Integer and not prof.T.has(sp.Float)
                                                     else []),
    ))

    # -- step 3: rescaled values
    if shape == "bang-bang":
        rule, what = "a_i = \\dfrac{4\\,\\lvert\\Delta_i\\rvert}{T^2}", "accelerations"
    elif shape == "quintic":
        rule, what = "a_i = \\dfrac{10\\,\\lvert\\Delta_i\\rvert}{\\sqrt{3}\\,T^2}", "peak accelerations"
    else:
        rule = ("v_i = \\dfrac{a_i T - \\sqrt{a_i^2 T^2 - 4 a_i \\lvert\\Delta_i\\rvert}}{2},"
                "\\qquad t_{a,i} = v_i / a_i")
        what = "cruise velocities (accelerations kept)"
    eqs = [("", rule)]
    rows = []
    for jm, j in zip(prof.joints, joints):
        if shape == "trapezoidal":
            eqs.append((f"v_{{{syms[j.name]}}}", jm.velocity))
            switches = Text.join(", ", [_num(s) for s in jm.switch_times]) if jm.switch_times else "—"
            rows.append([f"${syms[j.name]}$", _num(jm.acceleration, _unit(j.kind, 2)),
                         _num(jm.velocity, _unit(j.kind, 1)), switches])
        else:
            eqs.append((f"a_{{{syms[j.name]}}}", jm.acceleration))
            rows.append([f"${syms[j.name]}$", _num(jm.acceleration, _unit(j.kind, 2)),
                         _num(jm.velocity, _unit(j.kind, 1))])
    header = ["joint", "acceleration", "cruise velocity", "switching instants (s)"] if shape == "trapezoidal" \
        else ["joint", "acceleration" if shape == "bang-bang" else "peak acceleration", "peak velocity"]
    steps.append(Step(f"Rescaled {what}", "At the synchronized time T:", equations=eqs,
                          table=(header, rows)))

    # -- step 4: profiles
    forms = {
        "bang-bang": ("With $s_i = \\operatorname{sign}(\\Delta_i)$: $q_i(t) = q_{i,0} + s_i\\,a_i t^2/2$ for "
                      "$0 \\le t \\le T/2$ and $q_{i,0} + s_i\\,(a_i T^2/4 - a_i (T - t)^2/2)$ for "
                      "$T/2 < t \\le T$; the joint is at rest before 0 and after T."),
        "trapezoidal": ("With $s_i = \\operatorname{sign}(\\Delta_i)$: $q_{i,0} + s_i a_i t^2/2$ while accelerating, "
                        "$q_{i,0} + s_i (v_i t - v_i^2/(2a_i))$ while cruising, $q_{i,f} - s_i a_i (T - t)^2/2$ "
                        "while decelerating; at rest before 0 and after T."),
        "quintic": "$q_i(t) = q_{i,0} + \\Delta_i\\,(10s^3 - 15s^4 + 6s^5)$, $s = t/T$; at rest before 0 and after T.",
    }[shape]
    steps.append(Step("Profiles", forms, equations=[
        (f"{syms[j.name]}(t)", prof.position(i)) for i, j in enumerate(joints)]))
    return steps


def _own_times(prof: SyncProfile, shape: str, joints, syms: dict) -> list[Step]:
    """Step 1: each joint's displacement and its own time at its limits."""
    steps: list[Step] = []
    # -- step 1: displacements and own times
    own_rule = {
        "bang-bang": "T_i = \\sqrt{\\dfrac{4\\,\\lvert\\Delta_i\\rvert}{a_i}}",
        "quintic": "T_i = \\sqrt{\\dfrac{10\\,\\lvert\\Delta_i\\rvert}{\\sqrt{3}\\,a_i}}",
        "trapezoidal": ("T_i = \\dfrac{\\lvert\\Delta_i\\rvert}{v_i} + \\dfrac{v_i}{a_i}"
                        "\\ \\text{if}\\ \\lvert\\Delta_i\\rvert \\ge \\dfrac{v_i^2}{a_i},"
                        "\\quad\\text{else}\\ T_i = \\sqrt{\\dfrac{4\\,\\lvert\\Delta_i\\rvert}{a_i}}"),
    }[shape]
    text = {
        "bang-bang": ("Bang-bang profile (the course's constant-acceleration profile): each joint accelerates "
                      "at $+a_i$ for half of its time and decelerates at $-a_i$ for the other half, so "
                      "$\\lvert\\Delta_i\\rvert = a_i T_i^2/4$. Each joint alone, at its maximum acceleration:"),
        "trapezoidal": ("Trapezoidal profile: acceleration $a_i$ up to the cruise velocity $v_i$, cruise, then "
                        "deceleration. A joint too short to reach $v_i$ moves bang-bang. Each joint alone, at its "
                        "limits:"),
        "quintic": ("Quintic (rest-to-rest) profile $q = q_0 + \\Delta\\,(10s^3 - 15s^4 + 6s^5)$, $s = t/T$, whose "
                    "peak acceleration is $10\\lvert\\Delta\\rvert/(\\sqrt{3}\\,T^2)$. Each joint alone, at its "
                    "maximum acceleration:"),
    }[shape]
    header = ["joint", "from", "to", "Δ", "max acceleration"] + (["max velocity"] if shape == "trapezoidal" else []) \
        + ["own time T_i (s)"]
    rows = []
    for jm, j in zip(prof.joints, joints):
        row = [f"${syms[j.name]}$", _num(jm.start), _num(jm.end), _num(jm.delta),
               _num(jm.max_acceleration, _unit(j.kind, 2))]
        if shape == "trapezoidal":
            row.append(_num(jm.max_velocity, _unit(j.kind, 1)))
        row.append(_num(jm.own_time) + ("" if jm.moves else " (does not move)"))
        rows.append(row)
    steps.append(Step("Displacements and each joint's own time", text,
                          equations=[("", own_rule)] + [(f"T_{{{syms[jm.name]}}}", jm.own_time)
                                                         for jm in prof.joints if jm.moves],
                          table=(header, rows)))
    return steps


def _figure(ans: Answer, prof: SyncProfile, shape: str, joints, syms: dict) -> None:
    """The profiles sampled on [0, T], both sides of each switching instant."""
    # -- figure
    if "T" in ans.numeric and ans.numeric["T"] > 0:
        import numpy as np

        plan = prof.numeric_plan()
        T = plan.T
        breaks = [float(b) for b in plan.breaks]
        ts = np.union1d(np.linspace(0.0, T, SAMPLES), breaks)
        # both sides of each switching instant, so acceleration steps are drawn vertical
        t_all, q_all, qd_all, qdd_all = [], [], [], []
        for k in range(len(plan.coeffs)):
            a, b = breaks[k], breaks[k + 1]
            sel = ts[(ts >= a) & (ts <= b)]
            qq, vv, aa = plan.evaluate(sel, k=k)
            t_all.append(sel), q_all.append(qq), qd_all.append(vv), qdd_all.append(aa)
        t_cat = np.concatenate(t_all)
        Q, QD, QDD = np.hstack(q_all), np.hstack(qd_all), np.hstack(qdd_all)
        ans.figures.append(FigureSpec(
            "profile", "motion_profile",
            Text(f"Synchronized {shape} profile (T = ", Num(T), " s)"),
            {"t": [float(x) for x in t_cat], "T": T,
             "switches": [b for b in breaks[1:-1]],
             "joints": [{"name": j.name, "label": syms[j.name], "kind": j.kind,
                         "q": Q[i].tolist(), "qd": QD[i].tolist(), "qdd": QDD[i].tolist()}
                        for i, j in enumerate(joints)]},
        ))
