"""Question 6: inverse kinematics — every solution, closed form where it exists.

The target is a set of equations `coordinate = value`. The derivation is the
exam's (elimination, cos θ = K, atan2), done by `robosolve.ik.closed_form`;
the numeric set comes from a deterministic multi-start search
(`robosolve.ik.numeric`) and the two must agree. Joint limits reject solutions
(listed with the limit they break), `select` picks one, `velocity` gives q̇
there. An unreachable target is an answer: `solutions: []`, `unreachable`,
`reason`.
"""

from __future__ import annotations

import math

import sympy as sp

from robosolve.core.prose import Num, Text
from robosolve.errors import SolverError, SymbolicTimeout
from robosolve.ik import closed_form as cfm
from robosolve.ik.engine import IKJoint, chop_noise, solve_ik, velocity_ik
from robosolve.ik.numeric import wrap_angle
from robosolve.load.pose_target import PoseTarget
from robosolve.load.problem import Question
from robosolve.questions.inverse_kinematics import solved_joints
from robosolve.solvers.ik_pose import solve_pose_question
from robosolve.solvers.base import Answer, FigureSpec, MissingValues, SolveContext, Step, missing_note
from robosolve.solvers.common import robot_drawing
from robosolve.core.printing import latex



def _is_point_coordinate(e) -> bool:
    return isinstance(e, sp.Symbol) and "." in e.name


def _angle_text(v: float, revolute: bool) -> Text:
    if not revolute:
        return Text(Num(v))
    return Text(Num(v), " (", Num(math.degrees(v)), "°)")


def solve(question: Question, ctx: SolveContext) -> Answer:
    model = ctx.model
    if model is None or not model.joints:
        raise SolverError("inverse kinematics needs a robot (joints and frames)")
    ans = Answer(question.type, question.id)
    opts = question.options
    joints = model.joints
    names = {j.symbol: latex(j.symbol) for j in joints}
    symnames = dict(ctx.symbol_latex)

    def tex(e):
        return latex(e, symbol_names=symnames)

    subs = ctx.substitutions({s: v for s, v in question.at.items() if s in ctx.problem.parameters})
    params = {s: v for s, v in subs.items()}
    if isinstance(opts["target"], PoseTarget):
        ik_joints, limit_notes = _ik_joints(joints, ctx, params)
        for n_ in limit_notes:
            ans.note(n_)
        res = solve_pose_question(question, ctx, ans, ik_joints, params, tex)
        if res is not None:                   # None: a null parameter, said in a note
            figure(ans, ctx, params, res, ik_joints, question)
        return ans
    equations, target_syms, shown, values, missing = _target_equations(opts["target"], model, ctx, params)
    # the unknowns are the joints that move the target (the paper asks for those: questions/)
    joints = solved_joints(question, ctx.problem)
    left_out = [j.name for j in model.joints if j not in joints]
    if left_out:
        ans.note(", ".join(left_out) + (" does" if len(left_out) == 1 else " do") + " not move the target: "
                 "any value reaches it, and the solutions give the other joints")
    ik_joints, limit_notes = _ik_joints(joints, ctx, params)
    for n_ in limit_notes:
        ans.note(n_)
    ans.steps.append(_equations_step(equations, target_syms, shown, values, joints, ik_joints, tex))

    if missing:
        _symbolic_only(ans, ctx, equations, ik_joints, names, tex, sorted(missing))
        return ans

    select = opts.get("select", "limits")
    select_num = None
    if isinstance(select, dict):
        select_num = {k: ctx.numeric(v, params) for k, v in select.items()}

    res = solve_ik(equations, ik_joints, values, select=select_num or "limits",
                   time_limit_s=ctx.budgets.closed_form_seconds, target_symbols=target_syms,
                   latex_names=names, tex=tex, labels=[t for t, _, _, _ in shown])

    if res.status == "redundant":
        return _redundant_answer(ans, res, ik_joints, tex)
    if res.status == "overdetermined":
        raise SolverError(_overdetermined_reason(res, shown) + (
            f" ({', '.join(left_out)} {'does' if len(left_out) == 1 else 'do'} not move the target.)"
            if left_out else ""))

    _closed_form_steps(ans, res, shown, len(equations), len(joints), names, values, tex, ik_joints)
    ans.steps.append(_solutions_step(res, names, ik_joints))
    for note in res.notes:
        ans.note(note)

    ans.numeric["solutions"] = [dict(d) for d in res.solutions]
    if res.status == "unreachable":
        ans.extra["unreachable"] = True
        ans.extra["reason"] = res.reason
        ans.numeric["solutions"] = []
        ans.steps.append(Step("Unreachable target", "No solution: " + (res.reason_tex or "") + "."))
        figure(ans, ctx, params, res, ik_joints, question)
        return ans

    how = ("the first of the sorted solutions inside the joint limits" if select_num is None else
           "the solution nearest the configuration " + Text.join(", ", [
               Text(f"${names[j.symbol]}$ = ", Num(select_num.get(j.name, 0.0))) for j in ik_joints]))
    ans.numeric["selected"] = dict(res.selected)
    ans.steps.append(Step("Selected solution", Text("Selected: ", how, "."),
                          equations=[(names[j.symbol], res.selected[j.name]) for j in ik_joints]))
    if opts.get("velocity"):
        _velocity(ans, ctx, model, opts["velocity"], params, ik_joints, res, values, tex)
    figure(ans, ctx, params, res, ik_joints, question)
    return ans


# -- compute ------------------------------------------------------------------------
def _target_equations(target, model, ctx, params):
    """The equations of the target, the point-coordinate symbols kept in them, what the
    report shows, the numeric values of the symbols, and the names whose values are missing."""
    equations, target_syms, shown = [], set(), []
    values: dict = {}
    missing: set = set()
    for text, lhs, rhs in target:
        lhs_q = model.coordinate(lhs)
        if _is_point_coordinate(lhs):
            # keep the target coordinate as a symbol (E.x) in the closed form
            rhs_sym = lhs
            target_syms.add(lhs)
            try:
                values[lhs] = ctx.numeric(rhs, params)
            except MissingValues as exc:
                missing |= set(exc.names)
        else:
            rhs_sym = rhs
        equations.append((lhs_q, rhs_sym))
        shown.append((text, lhs_q, rhs_sym, rhs))
    q_syms = {j.symbol for j in model.joints}
    for lhs_q, rhs_sym in equations:
        for s in (sp.sympify(lhs_q).free_symbols | sp.sympify(rhs_sym).free_symbols):
            if s in q_syms or s in target_syms:
                continue
            if s in params:
                try:
                    values[s] = ctx.numeric(s, params)
                except MissingValues as exc:
                    missing |= set(exc.names)
            else:
                missing.add(s.name)
    return equations, target_syms, shown, values, missing


def _ik_joints(joints, ctx, params):
    """The IK engine's joints, with their limits where these have values."""
    ik_joints, limit_notes = [], []
    for j in joints:
        lim = None
        if j.limits is not None:
            try:
                lo, hi = ctx.numeric(list(j.limits), params)
                lim = (float(lo), float(hi))
            except MissingValues as exc:
                limit_notes.append(f"the limits of {j.name} need {', '.join(exc.names)}: not applied")
        ik_joints.append(IKJoint(j.symbol, j.is_revolute, lim))
    return ik_joints, limit_notes


def _overdetermined_reason(res, shown) -> str:
    """Why no configuration satisfies every equation, with the solution count of each choice."""
    parts = []
    for sub in res.subsets:
        keys = ", ".join(shown[k][0] for k in sub["equations"])
        cnt = "infinitely many" if sub["family"] else str(len(sub["solutions"]))
        parts.append(f"{{{keys}}}: {cnt} solution{'s' if cnt != '1' else ''}")
    return res.reason + " " + "; ".join(parts) + "."


def _velocity(ans, ctx, model, velocity, params, ik_joints, res, values, tex) -> None:
    """q_dot at the selected solution for the target rates, with its step."""
    joints = [j for j in model.joints if any(j.symbol == k.symbol for k in ik_joints)]
    # float noise (cos(1.5707963267949) ≈ 1e-16 beside a wrist joint) is no dependence
    coords = [chop_noise(model.coordinate(l)) for _, l, _ in velocity]
    rates = [r for _, _, r in velocity]
    undetermined = [j.name for j in model.joints if j not in joints
                    and any(j.symbol in sp.sympify(c).free_symbols for c in coords)]
    if undetermined:       # the target leaves them free: no selected value to take J at
        ans.note(f"the velocity's coordinates depend on {', '.join(undetermined)}, which the target does "
                 "not determine: no q_dot (give the velocity of coordinates of the target)")
        return
    try:
        rate_vals = [ctx.numeric(r, params) for r in rates]
        vik = velocity_ik(coords, rate_vals, ik_joints, res.selected, values)
    except MissingValues as exc:
        ans.note(missing_note("q_dot", exc.names, ctx.problem))
    else:
        ans.numeric["q_dot"] = dict(vik.q_dot)
        Jsym = sp.Matrix(coords).jacobian([j.symbol for j in ik_joints])
        qd_names = [j.dot for j in joints]
        method = {"inverse": "$\\dot q = J^{-1}\\,\\dot s$",
                  "least_squares": "least squares, $\\dot q = J^{+}\\,\\dot s$",
                  "min_norm": "minimum norm, $\\dot q = J^{+}\\,\\dot s$"}[vik.method]
        ans.steps.append(Step(
            "Velocity inverse kinematics",
            "Differentiating the coordinates gives $\\dot s = J(q)\\,\\dot q$ with "
            f"$J = \\partial s / \\partial q$; at the selected solution, {method}.",
            equations=[("J", Jsym), ("J", vik.J.tolist()),
                       ("\\dot s", [float(v) for v in rate_vals]),
                       (tex(sp.Matrix(qd_names)), [[vik.q_dot[j.name]] for j in ik_joints])],
        ))
        if vik.note:
            ans.note(vik.note)


# -- steps --------------------------------------------------------------------------
def _equations_step(equations, target_syms, shown, values, joints, ik_joints, tex) -> Step:
    n, m = len(joints), len(equations)
    eq_step = Step(
        "Equations of the target",
        "Each coordinate of the target, written with the direct kinematics, gives one equation "
        f"in the joint variables: {m} equation{'s' if m != 1 else ''} for {n} unknown joint"
        f"{'s' if n != 1 else ''}."
        + (" Point coordinates such as $E_{x}$ on the right stand for the target values, given below."
           if target_syms else ""),
        equations=[(tex(l), r) for _, l, r, _ in shown],
    )
    from robosolve.ik.engine import is_angular
    ang = [is_angular(sp.sympify(l) - sp.sympify(r), ik_joints) for l, r in equations]
    if any(ang):
        eq_step.text += (" An equation that is a sum of angles (an orientation) is satisfied modulo "
                         "$2\\pi$.")
    if target_syms:
        eq_step.table = (("target", "value"), [(f"${tex(s)}$", Num(values[s]))
                                                for s in sorted(target_syms, key=sp.default_sort_key)
                                                if s in values])
    return eq_step


def _closed_form_steps(ans, res, shown, m, n, names, values, tex, ik_joints) -> None:
    if res.closed_form is not None:
        cf = res.closed_form
        if res.closed_form_subset is not None:
            used = ", ".join(f"`{shown[k][0]}`" for k in res.closed_form_subset)
            how = (": the closed form below uses them all (a joint whose sine and cosine two of them fix is one "
                   "atan2, one branch)" if len(res.closed_form_subset) == m else
                   f", so {n} of them are enough: the closed form below uses {used}")
            ans.steps.append(Step(
                "More equations than joints",
                f"The {m} equations are consistent (a configuration satisfies them all){how}; every branch "
                f"is then checked on all {m}."))
        for st in cf.steps:
            ans.steps.append(Step(st.title, st.text, equations=list(st.equations)))
        nb = len(res.closed_form_branches)
        order = ", ".join(f"${names[q]}$" for q in cf.order())
        ans.steps.append(Step(
            "Closed form",
            f"The choices above give {nb} branch{'es' if nb != 1 else ''} (order of solution: {order}; "
            "each formula may use the joints found before it). With the data, branch by branch "
            "(angles not yet wrapped):",
            table=_branch_table(cf, values, tex, res.all_solutions, ik_joints),
        ))
        ans.symbolic["closed_form"] = [{j.name: b[j.symbol] for j in ik_joints} for b in res.closed_form_branches]
    else:
        ans.steps.append(Step("Closed form", (res.closed_form_note or "no closed form")
                              + ": the solutions below are numeric only."))
        if res.closed_form_note and "within" in res.closed_form_note:
            ans.note(res.closed_form_note + "; solutions found numerically")


def _solutions_step(res, names, ik_joints) -> Step:
    box = Text.join(", ", [
        f"${names[j.symbol]}$ in " + (Text("(−π, π]") if j.revolute else
                                       (Text("[", Num(j.limits[0]), ", ", Num(j.limits[1]), "] and beyond")
                                        if j.limits else Text("a wide interval")))
        for j in ik_joints])
    header = ["#"] + [f"${names[j.symbol]}$" for j in ik_joints] + ["joint limits"]
    rows = []
    rejected = {id(d): b for d, b in res.rejected}
    for k, d in enumerate(res.all_solutions, 1):
        status = "inside" if id(d) not in rejected else "rejected: " + Text.join("; ", rejected[id(d)])
        rows.append([str(k)] + [_angle_text(d[j.name], j.revolute) for j in ik_joints] + [status])
    n = len(res.all_solutions)
    text = ("Numerically, a multi-start Newton search (" + box + ") refined to machine precision finds "
            + (f"{n} distinct solution{'s' if n != 1 else ''}, each checked with the direct kinematics "
               "(residual below $10^{-9}$); angles wrapped into (−π, π]." if n else "no solution."))
    if res.family is not None and len(res.family["free"]) == len(ik_joints) and not res.family["fixed"]:
        text = ("No joint appears in the equations: every configuration is a solution (a continuum); "
                "the table lists one example.")
    if res.closed_form is not None and res.agree is not None:
        text += (" The closed form gives the same set." if res.agree else
                 " The closed form and the numeric search do not give the same set: see the notes.")
    return Step("Every solution", text, table=(header, rows) if rows else None)


def _symbolic_only(ans, ctx, equations, ik_joints, names, tex, missing):
    exprs = [sp.sympify(l) - sp.sympify(r) for l, r in equations]
    if len(exprs) != len(ik_joints):
        raise SolverError(f"{len(exprs)} equations for {len(ik_joints)} joints, and numeric values "
                          f"are missing ({', '.join(missing)})")
    try:
        with ctx.time_limit(ctx.budgets.closed_form_seconds):
            cf = cfm.derive(exprs, [j.symbol for j in ik_joints], [j.revolute for j in ik_joints], names,
                            tex=tex)
            branches = cf.branches()
    except (cfm.NoClosedForm, SymbolicTimeout) as exc:
        raise SolverError(f"no closed form ({exc}) and no numeric solution: it needs values for "
                          + ", ".join(missing)) from None
    for st in cf.steps:
        ans.steps.append(Step(st.title, st.text, equations=list(st.equations)))
    ans.symbolic["closed_form"] = [{j.name: b[j.symbol] for j in ik_joints} for b in branches]
    ans.note(missing_note("solutions", missing, ctx.problem))


def _redundant_answer(ans, res, ik_joints, tex):
    fam = res.family
    if fam is None:
        raise SolverError(res.reason)
    free = fam["free"]
    cf = fam["closed_form"]
    ans.steps.append(Step(
        "Redundant: infinitely many solutions",
        res.reason + f" The family, with {', '.join('$' + tex(sp.Symbol(f)) + '$' for f in free)} "
        "as parameter:"))
    for st in cf.steps:
        ans.steps.append(Step(st.title, st.text, equations=list(st.equations)))
    ans.symbolic["closed_form"] = [{j.name: b.get(j.symbol, j.symbol) for j in ik_joints}
                                   for b in fam["branches"]]
    ans.numeric["solutions"] = []
    ans.note(res.reason)
    return ans


def figure(ans, ctx, params, res, ik_joints, question):
    sols = res.all_solutions[:12]
    if not sols and res.nearest is None:
        return
    drawings, labels, rejected = [], [], []
    rej = {id(d) for d, _ in res.rejected}
    configs = sols if sols else [res.nearest]
    for k, d in enumerate(configs, 1):
        s2 = dict(params)
        # a joint after the target frame is in no solution: drawn at 0
        s2.update({j.symbol: sp.Float(d.get(j.name, 0)) for j in ik_joints})
        drw = robot_drawing(ctx, s2)
        if drw is None:
            return
        drawings.append(drw)
        lab = Text.join(", ", [Text(f"{j.name}=", Num(d[j.name], digits=3)) for j in ik_joints if j.name in d])
        if sols:
            labels.append(f"#{k}: " + lab + (" (rejected)" if id(d) in rej else ""))
            rejected.append(id(d) in rej)
        else:
            labels.append("nearest: " + lab)
            rejected.append(True)
    point = question.point
    target = None
    coords = {}
    for text, lhs, rhs in (question.options["target"] if isinstance(question.options["target"], list) else ()):
        if _is_point_coordinate(lhs):
            pname, axis = lhs.name.split(".")
            try:
                coords[(pname, axis)] = float(ctx.numeric(rhs, params))
            except MissingValues:
                pass
    if coords:
        pname = sorted({p for p, _ in coords})[0]
        # the unconstrained coordinates from the first drawing (every solution shares the target)
        base = next((p["at"] for p in drawings[0]["points"] if p["name"] == pname), [0.0, 0.0, 0.0])
        target = {"name": pname, "at": [coords.get((pname, a), base[i]) for i, a in enumerate("xyz")],
                  "given": [a for a in "xyz" if (pname, a) in coords]}
    ans.figures.append(FigureSpec(
        "solutions", "ik_solutions",
        "Inverse kinematics: every solution" if sols else "Unreachable target: the nearest configuration",
        {"drawings": drawings, "labels": labels, "rejected": rejected, "target": target,
         "selected": res.selected_index if res.selected is not None else None, "point": point}))


def _branch_table(cf, values, tex, solutions, ik_joints):
    """Each branch of the closed form evaluated with the data (or where it fails)."""
    stages = cf.stages
    header = ["branch"] + [f"${tex(st.joint)}$" for st in stages] + ["result"]
    rows = []
    for k, bv in enumerate(cfm.evaluate(cf, values), 1):
        got = bv.q if bv.q is not None else (bv.partial or {})
        cells = [Num(got[st.joint]) if st.joint in got else "—" for st in stages]
        if bv.failure is None:
            match = [k2 for k2, d in enumerate(solutions, 1)
                     if all(abs(wrap_angle(d[j.name] - bv.q[j.symbol]) if j.revolute else d[j.name] - bv.q[j.symbol])
                            < 1e-6 * max(1.0, abs(d[j.name])) for j in ik_joints)]
            result = f"solution #{match[0]}" if match else "does not satisfy every equation"
        else:
            idx, joint, ex = bv.failure
            what = {"acos": "arccos of", "asin": "arcsin of", "sqrt": "square root of",
                    "atan2": "atan2(0, 0)", "zero": "division by zero", "nan": "undefined"}.get(ex.what, ex.what)
            val = ex.value if isinstance(ex.value, float) else None
            result = Text(f"no ${tex(joint)}$: {what}") + (Text(" ", Num(val)) if val is not None else "")
        rows.append([str(k)] + cells + [result])
    return header, rows
