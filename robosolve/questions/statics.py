"""The `statics` question type (Statics): options, checks, answer schema."""

from __future__ import annotations

from robosolve.load import validators as V
from robosolve.questions.schema import JOINT_MAP, QuestionType, _k
from robosolve.questions.notebook_code import at_literal, compare_line, coordinates, lines, literal, robosolve_numbers, text


def _check(ql, path, item, q):
    chk, opts = ql.chk, q.options
    ncoord = len(opts["coordinates"]) if "coordinates" in opts else 3
    if not any(k in item for k in ("force", "torque")) and not opts.get("weight") and "weight" not in q.rejected:
        chk.error(path, "expected force, torque or weight: true")
    if "force" in opts and len(opts["force"]) != ncoord:
        chk.error(path + ("force",), f"expected {ncoord} components (one per coordinate), "
                  f"got {len(opts['force'])}")
    if "torque" in opts and "coordinates" in item:
        if "coordinates" in opts and _default_coordinates(opts["coordinates"], q.point):
            del opts["coordinates"]     # written out, they are the default: the load stays a wrench
        else:
            chk.error(path + ("torque",), "a torque needs the default coordinates (the point's x, y, z)")
    if opts.get("weight"):
        ql.require_gravity(path)
        if not ql.b.problem.bodies and not ql.b.bodies_given:
            chk.error(path + ("weight",), "weight: true needs bodies (masses)")

def _default_coordinates(coordinates, point) -> bool:
    """Whether `coordinates` are the point's x, y, z in that order (the default, written out)."""
    from robosolve.load.expressions import point_symbol

    return list(coordinates) == [point_symbol(point, axis) for axis in "xyz"]


def _statement(q, say) -> str:
    """The paper's statement (papers.md), from the load, its coordinates and `at`."""
    o, at = q.options, say.at(q)
    along = (f"one component per coordinate {say.coordinates(o['coordinates'])}" if o.get("coordinates")
             else "its components in frame 0")
    loads = []
    if "force" in o:
        loads.append(f"the force $F_s = $ {say.math(list(o['force']))} applied at {say.point(q)} ({along})")
    if "torque" in o:
        loads.append(f"the torque {say.math(list(o['torque']))} on {say.frame(q)}")
    if o.get("weight"):
        loads.append("the weight of the bodies (gravity of the data)")
    return ("Compute the joint forces $F_q$ (one per joint) that balance " + " and ".join(loads)
            + (f", {at}" if at else "") + ".")


def notebook_cell(q, answer, problem):
    """The notebook's cell that recomputes the answer (questions/notebook_code.py): each load's
    share, Fq = -J^T F - J_w^T tau - sum J_G^T m g; symbolic only when robosolve has no numbers
    (a null parameter), so the cell never evaluates what is not given."""
    o = q.options
    force, torque = o.get("force"), o.get("torque")
    numeric = "Fq" in answer.numeric
    return lines(
        f"at = {at_literal(q)}",
        f"Fq = sp.zeros({len(problem.joints)}, 1)",
        *([f"J = robot.jacobian({coordinates(q)})",
           f"F = robot.vector({literal([text(x) for x in force])})",
           "Fq -= J.T * F          # what the joints exert to balance F"] if force is not None else []),
        *([f"tau = robot.vector({literal([text(x) for x in torque])})",
           f"Fq -= robot.angular_jacobian({q.frame!r}).T * tau    # a pure torque on the frame: -J_w^T tau"]
          if torque is not None else []),
        "Fq += robot.weight_forces(at)    # the bodies' own weight: -sum J_G^T m g" if o.get("weight") else None,
        robosolve_numbers(answer, ["Fq"]),
        compare_line("Fq", "robot.number(Fq, at).ravel()") if numeric else "show(Fq)",
    )


TYPE = QuestionType(
    "statics", "Statics", "§8 question 4",
    statement=_statement,
    options={"force": V.v_exprs, "torque": V.v_vector3, "weight": V.v_bool, "coordinates": V.v_coordinates},
    defaults={"weight": False},
    answers=(
        _k("Fq", JOINT_MAP, "joint forces balancing the load, Fq = −Jᵀ·Fs", principal=True, unit="effort",
           hints=(("negated", "Fq = −Jᵀ·Fs is what the joints exert to balance the load; "
                              "+Jᵀ·Fs is the load's own action on the joints"),)),
    ),
    cost=0.2,
    check=_check, has_jacobian=True,
    notebook_cells=notebook_cell,
)
