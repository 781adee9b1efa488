"""The `inverse_kinematics` question type (Inverse kinematics): options, checks, answer schema."""

from __future__ import annotations

import sympy as sp

from robosolve.core.prose import name_md
from robosolve.core.transforms import ELEMENTARY, dh_modified, dh_standard
from robosolve.load import validators as V
from robosolve.load.pose_target import is_pose_target
from robosolve.questions.schema import BOOL, JOINT_MAP, JOINT_MAP_LIST, JOINT_MAP_SET, TEXT, QuestionType, _k
from robosolve.questions.wording import asked, listing
from robosolve.questions.notebook_code import at_literal, compare_line, lines, literal, text


def notebook_cell(q, answer, problem):
    """The notebook's cell that recomputes the answer (questions/notebook_code.py)."""
    target = q.options.get("target") or []
    if not isinstance(target, list):
        return _pose_cell(q, answer, problem, target)
    if not target:
        return None
    solved = solved_joints(q, problem)      # a joint that moves nothing in the target is no unknown
    limits = []
    for j in solved:
        lo, hi = j.limits if j.limits else ((-sp.pi, sp.pi) if j.kind == "revolute" else (-10, 10))
        limits.append([text(lo), text(hi)])
    residual = [f"({text(lhs)}) - ({text(rhs)})" for _, lhs, rhs in target]
    names = [j.name for j in solved]
    unknowns = ("robot.joints" if len(solved) == len(problem.joints) else
                "[robot.joints[i] for i in " + repr([j.index for j in solved]) + "]")
    want = {"solutions": sorted(answer.numeric.get("solutions") or [], key=lambda s: tuple(s.values()))}
    code = [
        f"at = {at_literal(q)}",
        "# Newton iterations (least-squares steps) from a grid of starts, kept within the joint limits",
        f"task = robot.vector({literal([text(lhs) for _, lhs, _ in target])})",
        f"residual = (task - robot.vector({literal([text(rhs) for _, _, rhs in target])})).subs(robot.fixed(at))",
        f"limits = [[robot.number(robot.parse(x), at) for x in pair] for pair in {literal(limits)}]",
        f"solutions = newton_solutions(residual, {unknowns}, limits, {literal([j.kind == 'revolute' for j in solved])})",
        "# (at a workspace boundary a solution is a double root: Newton then finds it to ~1e-7 only)",
        f"compare('solutions', [dict(zip({names!r}, s)) for s in solutions], robosolve['solutions'], atol=1e-6)",
    ]
    if answer.numeric.get("selected"):
        want["selected"] = answer.numeric["selected"]
        code += _selection_lines(q, problem)
    velocity = q.options.get("velocity")
    if velocity and "q_dot" in answer.numeric and answer.numeric.get("selected"):
        want["q_dot"] = answer.numeric["q_dot"]
        code += [
            "# velocity IK at the solution selected: J(q) q' = v",
            "selected = robosolve['selected'] if not solutions else dict(zip(" + repr(names) + ", mine))",
            f"v = robot.number(robot.vector({literal([text(v) for _, _, v in velocity])}), at).ravel()",
            f"rates_of = robot.vector({literal([text(lhs) for _, lhs, _ in velocity])})",
            f"Jq = robot.number(rates_of.jacobian({unknowns}), "
            "{**at, **{k: repr(float(x)) for k, x in selected.items()}})",
            "q_dot = np.linalg.lstsq(Jq, v, rcond=None)[0]",
            compare_line("q_dot", f"dict(zip({names!r}, q_dot))"),
        ]
    return lines(*code[:6], "robosolve = " + literal(want), *code[6:])


def solved_joints(q, problem) -> list:
    """The joints a solution gives: those that move the target (a joint that moves nothing in it,
    the seventh of an arm asked the pose of frame 6 or the wrist joints of an arm asked its wrist
    centre, is in no solution: solvers/ik_pose.py, solvers/inverse_kinematics.py)."""
    target = q.options.get("target")
    if isinstance(target, list):
        moving = set()
        for _, lhs, _ in target:
            moving |= _target_symbols(sp.sympify(lhs), problem)
        solved = [j for j in problem.joints if j.symbol in moving]
        return solved or list(problem.joints)      # no joint at all: every configuration (ik/engine.py)
    frame = problem.points[q.point].frame if q.point_given else q.frame
    moving: set = set()
    while frame in problem.frames:
        for m in _factor_matrices(problem.frames[frame]):
            moving |= m.free_symbols
        frame = problem.frames[frame].parent
    return [j for j in problem.joints if j.symbol in moving]


def _target_symbols(lhs, problem) -> set:
    """The symbols a target coordinate depends on: its own, and for a point's coordinate (W.x)
    those of that coordinate in frame 0. The point is carried through the frames' factors from
    its own frame down to frame 0 (a vector, never a product of poses), so a joint that does not
    move it drops out as written: Rz(theta6) of [0, 0, 0] is [0, 0, 0], no simplification needed."""
    out = set()
    for s in lhs.free_symbols:
        name, _, axis = s.name.partition(".")
        if not axis or name not in problem.points:
            out.add(s)
            continue
        point = problem.points[name]
        v, frame = sp.Matrix(list(point.at) + [1]), point.frame
        while frame in problem.frames:
            for m in reversed(_factor_matrices(problem.frames[frame])):
                v = m * v
            frame = problem.frames[frame].parent
        out |= sp.sympify(v["xyz".index(axis)]).free_symbols
    return out


def _factor_matrices(f) -> list:
    """The 4×4 matrices whose product is the frame's pose, as written."""
    if f.kind == "matrix":
        return [sp.Matrix(f.matrix)]
    if f.kind == "dh":
        return [dh_standard(*f.factors)]
    if f.kind == "mdh":
        return [dh_modified(*f.factors)]
    return [ELEMENTARY[op](arg) for op, arg in f.factors]


def paper_layout(q, problem) -> dict:
    """A pose target's solutions give only the joints that move its frame (papers: the template)."""
    names = [j.name for j in solved_joints(q, problem)]
    if len(names) == len(problem.joints):
        return {}
    return {"solutions": (names, None), "selected": (names, None), "q_dot": (names, None)}


def _fixed_joints(q, say) -> str:
    """' $q_7$ does not move frame 6: it is in no solution.' ('' when every joint moves the target)."""
    solved = solved_joints(q, say.problem)
    free = [j for j in say.problem.joints if j not in solved]
    if not free:
        return ""
    where = ("the target" if isinstance(q.options.get("target"), list) else
             f"point {q.point}" if q.point_given else f"frame {name_md(q.frame)}")
    return (f" {say.joints(free)} {'does' if len(free) == 1 else 'do'} not move {where}: "
            f"{'it is' if len(free) == 1 else 'they are'} in no solution.")


def _selection_lines(q, problem) -> list[str]:
    """The solution selected: the first (select: limits), or the nearest to the given configuration
    (Euclidean, revolute differences wrapped; a joint not given counts as 0)."""
    select = q.options.get("select")
    names = [j.name for j in problem.joints]
    if not isinstance(select, dict):
        return ["# the solution selected: the first (select: limits)",
                "mine = solutions[0] if solutions else None",
                f"compare('selected', dict(zip({names!r}, mine)) if solutions else {{}}, robosolve['selected'], atol=1e-6)"]
    near = [text(select.get(n, 0)) for n in names]
    revolute = [j.kind == "revolute" for j in problem.joints]
    return ["# the solution selected: the nearest to the given configuration (angles wrapped)",
            f"near = robot.number(robot.vector({literal(near)}), at).ravel()",
            f"gap = lambda s: np.linalg.norm([wrap(a - b) if r else a - b for a, b, r in zip(s, near, {literal(revolute)})])",
            "mine = min(solutions, key=gap) if solutions else None",
            f"compare('selected', dict(zip({names!r}, mine)) if solutions else {{}}, robosolve['selected'], atol=1e-6)"]


def _target(q, say) -> tuple[str, str]:
    """(what the configurations put where, what there is none of)."""
    o = q.options
    if not isinstance(o["target"], list):       # a pose target (load/pose_target.py)
        t = o["target"]
        where = f"the point {q.point}" if q.point_given else f"frame {name_md(q.frame)}"
        orientation = f"$R = {say.tex(t.R)}$"
        if t.given in ("zyz", "rpy") and t.angles is not None:     # the angles as given, and their R
            names, product = (("\\varphi, \\theta, \\psi", "R_z(\\varphi)\\,R_y(\\theta)\\,R_z(\\psi)")
                              if t.given == "zyz" else
                              ("\\mathrm{roll}, \\mathrm{pitch}, \\mathrm{yaw}",
                               "R_z(\\mathrm{yaw})\\,R_y(\\mathrm{pitch})\\,R_x(\\mathrm{roll})"))
            words = "ZYZ Euler angles" if t.given == "zyz" else "roll-pitch-yaw angles"
            angles = ", ".join(say.value(a) for a in t.angles)
            orientation = f"of {words} $({names})$ = ({angles}), $R = {product} = {say.tex(t.R)}$"
        return f"{where} at the position ${say.tex(t.p)}$ with the orientation {orientation}", "pose"
    return ", ".join(say.equals(lhs, rhs) for _, lhs, rhs in o["target"]), "target"


def _selection(q, say) -> str:
    """The solution `selected` (and the joint rates) refers to, in words."""
    select = q.options.get("select")
    if isinstance(select, dict):
        return (f"the solution nearest to {say.joint_values(select)} (Euclidean distance of the joint "
                "values, angles wrapped into $(-\\pi, \\pi]$)")
    return ("the first solution, in the order of the joints' values ("
            + say.joints(solved_joints(q, say.problem)) + "; smallest first)")


def _words(q, say) -> dict:
    out = {"selected": f"the selected solution: {_selection(q, say)}",
           "closed_form": ("the closed-form solution: each branch as one expression per joint, in the "
                           + ("entries of the target pose ($r_{11}$ … $r_{33}$, $p_x$, $p_y$, $p_z$)"
                              if not isinstance(q.options["target"], list) else "target's coordinates"))}
    if "velocity" in q.options:
        wanted = ", ".join(say.equals(lhs, rhs, rate=True) for _, lhs, rhs in q.options["velocity"])
        out["q_dot"] = f"the joint rates giving {wanted} at {_selection(q, say)}"
    return out


def _statement(q, say) -> str:
    """The paper's statement (papers.md), from the target, then what the question grades: every
    solution, the selected one (by its rule), the joint rates of a velocity, the closed form."""
    target, kind = _target(q, say)
    rest = listing(asked(q, say, _words(q, say)))
    joints, fixed = say.joints(solved_joints(q, say.problem)), _fixed_joints(q, say)
    if "solutions" in say.asked(q):
        return (f"Find every configuration ({joints}) within the joint limits that puts {target} "
                f"(none, if the {kind} cannot be reached)" + (f"; give also {rest}" if rest else "") + "." + fixed)
    return (f"Of the configurations ({joints}) within the joint limits that put {target}, "
            f"give {rest}." + fixed)


def _check(ql, path, item, q):
    """`at` overrides parameters only: the joints are the unknowns (they were ignored silently);
    a pose target is the pose of a frame the joints move, never of the fixed frame 0."""
    for key, joint in V.joint_motion_in_at(ql, item):
        hint = (" (to choose the solution nearest a configuration, give it in `select`)"
                if key == joint else " (joint rates come from `velocity`)")
        ql.chk.error(path + ("at", key), "an inverse_kinematics question solves for the joints: "
                     f"its `at` may override parameters only, not '{key}'{hint}")
    if is_pose_target(item.get("target")):
        if q.point_given and ql.b.points[q.point].frame == "0":
            ql.chk.error(path + ("point",), f"point {q.point} is fixed in frame 0, which no joint moves: a "
                         "pose target's point is fixed in a moving frame (its orientation is that frame's)")
        elif q.point_given and q.frame_given and ql.b.points[q.point].frame != q.frame:
            # the spec's point is fixed in `frame`: another frame's orientation was silently dropped
            pf = ql.b.points[q.point].frame
            ql.chk.error(path + ("frame",), f"point {q.point} is fixed in frame {pf}, not in frame {q.frame}: "
                         f"a pose target's point is fixed in the question's frame, whose orientation the target "
                         f"gives (remove `frame`, or give a point fixed in frame {q.frame})")
        elif q.frame_given and not q.point_given and q.frame == "0":
            ql.chk.error(path + ("frame",), "frame 0 is the fixed base, which no joint moves: a pose target "
                         f"is the pose of a moving frame (e.g. frame: '{ql.b.last_frame()}', the default)")


def _pose_cell(q, answer, problem, target):
    """A pose target: each of robosolve's solutions checked by the direct kinematics (a search
    over six joints is too long for a notebook cell)."""
    frame = problem.points[q.point].frame if q.point_given else q.frame
    want = {"solutions": answer.numeric.get("solutions") or []}
    # the joints the solutions give (a joint that does not move the target frame is in none)
    names = [j.name for j in problem.joints if any(j.name in s for s in want["solutions"])]
    R = [[text(target.R[i, k]) for k in range(3)] for i in range(3)]
    p = [text(v) for v in target.p]
    where = (f"(robot.pose({frame!r})[:3, :3].row_join(robot.point0({q.point!r})))" if q.point_given
             else f"robot.pose({frame!r})[:3, :]")
    return lines(
        f"at = {at_literal(q)}",
        f"target = robot.number(robot.matrix({literal(R)}).row_join(robot.vector({literal(p)})), at)",
        "robosolve = " + literal(want),
        "# every solution robosolve lists, put through the direct kinematics: it must reach the pose",
        f"fk = {where}",
        "reached = [s for s in robosolve['solutions']",
        f"           if np.max(np.abs(robot.number(fk, {{**at, **{{k: repr(float(v)) for k, v in s.items()}}}}) - target)) < 1e-9]",
        f"compare('solutions', [{{k: s[k] for k in {names!r}}} for s in reached], robosolve['solutions'])",
    )


TYPE = QuestionType(
    "inverse_kinematics", "Inverse kinematics", "§8 question 6",
    statement=_statement,
    options={"target": V.v_ik_target, "velocity": V.v_equations, "select": V.v_select},
    required=("target",),
    defaults={"select": "limits"},
    answers=(
        _k("solutions", JOINT_MAP_SET, "every solution within the limits, sorted",
           principal=True, unit="joint", angle=True, unordered=True, symbolic=False, reaches=True),
        _k("q_dot", JOINT_MAP, "joint rates at the selected solution", principal=True, unit="joint/s",
           symbolic=False,
           needs=lambda q, joints: "" if "velocity" in q.options else "q_dot is computed only for a given velocity"),
        _k("selected", JOINT_MAP, "the selected solution", angle=True, unit="joint", symbolic=False),
        _k("closed_form", JOINT_MAP_LIST, "closed-form solution branches", numeric=False),
        _k("unreachable", BOOL, "true when there is no solution", top=True),
        _k("reason", TEXT, "why there is no solution", top=True),
    ),
    figures=(("solutions", "ik_solutions"),),
    paper_keys=lambda options, joints: ("solutions",) + (("q_dot",) if "velocity" in options else ()),
    # grows like the equations of motion (measured: 0.3 s CPU for a 3R arm, 2.5-2.9 s for the
    # pose of a UR5 or a KUKA arm)
    cost=0.8, cost_growth=2.5,
    reaches=True,
    notebook_cells=notebook_cell, paper_layout=paper_layout,
    check=_check,
)
