"""What the type modules' notebook cells share (`QuestionType.notebook_cells`, report.ipynb).

A type's cell builder `(question, answer, problem) -> str | None` returns the Python source of
the cell that recomputes the answer with the notebook's runtime (robosolve/render/notebook_runtime.py,
whose names the cell uses: `robot`, `compare`, `Profile`, ...), or None for an option layout it
does not rebuild (the notebook then shows robosolve's numbers and says so). Every value from
the problem reaches the source through `literal` (Python literals: repr), never as code.
"""

from __future__ import annotations

import dataclasses
import math

import sympy as sp

from robosolve.core.printing import sstr

__all__ = ["text", "literal", "at_literal", "robosolve_numbers", "lines", "compare_line", "guarded",
           "coordinates", "jacobian_lines", "profile_lines", "trajectory_lines", "coordinate_values",
           "question_by_id", "followed_question"]

def text(expr) -> str:
    """A sympy value as the text the runtime parses (`Robot.parse`): str() (core/printing's, the
    same in every process), the point coordinates P.x written P_x."""
    expr = sp.sympify(expr)
    rep = {s: sp.Symbol(s.name.replace(".", "_")) for s in expr.free_symbols if "." in s.name}
    return sstr(expr.xreplace(rep)) if rep else sstr(expr)


def literal(value) -> str:
    """Python source of plain data: numbers, strings, None, booleans, lists, mappings; a sympy
    value becomes its text (a string), a float that is not finite float('inf') / float('nan')."""
    if isinstance(value, dict):
        return "{" + ", ".join(f"{literal(k)}: {literal(v)}" for k, v in value.items()) + "}"
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(literal(v) for v in value) + "]"
    if value is None or isinstance(value, (bool, str, int)):
        return repr(value)
    if isinstance(value, float) or hasattr(value, "dtype"):
        value = float(value)
        return repr(value) if math.isfinite(value) else f"float({repr(value)!r})"
    if isinstance(value, sp.MatrixBase):
        return literal([[text(x) for x in value.row(i)] for i in range(value.rows)])
    return repr(text(value))


def at_literal(question, problem=None) -> str:
    """The question's configuration `at` as {name: text}; with `problem`, the `at` it computes with
    (`Problem.working_at`: a follower's own on its reference's parameter overrides)."""
    at = question.at if problem is None else problem.working_at(question)
    return literal({s.name: text(v) for s, v in at.items()})


def robosolve_numbers(answer, keys) -> str:
    """robosolve's numbers of the answer (the keys it has), as one literal assignment."""
    return "robosolve = " + literal({k: answer.numeric[k] for k in keys if k in answer.numeric})


def lines(*parts) -> str:
    return "\n".join(p for p in parts if p is not None)


def compare_line(key, expr, *, want=None, rtol=None, atol=None) -> str:
    tol = ("" if rtol is None else f", rtol={rtol!r}") + ("" if atol is None else f", atol={atol}")
    return f"compare({key!r}, {expr}, robosolve[{key!r}]{want or ''}{tol})"


def guarded(answer, *calls) -> list[str]:
    """compare(...) lines, each only when robosolve answered that key."""
    return [c for key, c in calls if key in answer.numeric]


def coordinates(q) -> str:
    coords = q.options.get("coordinates")
    if coords:
        return literal([text(c) for c in coords])
    return literal([f"{q.point}_{axis}" for axis in "xyz"])


def jacobian_lines(q) -> list[str]:
    return [f"at = {at_literal(q)}",
            f"J = robot.jacobian({coordinates(q)})",
            "Jn = robot.number(J, at)"]


def profile_lines(pq, problem) -> list[str] | None:
    """`profile = Profile(...)`: the profile question `pq`'s motion, numerically."""
    o = pq.options
    shape = o.get("shape", "bang-bang")
    names = [j.name for j in problem.joints]

    def values(key):
        m = o.get(key) or {}
        return [text(m.get(n, 0)) for n in names]

    vel = f", max_velocity=numbers({literal(values('max_velocity'))})" if shape == "trapezoidal" else ""
    return [f"at = {at_literal(pq)}",
            "numbers = lambda texts: [robot.number(robot.parse(x), at) for x in texts]",
            f"profile = Profile(numbers({literal(values('from'))}), numbers({literal(values('to'))}), "
            f"numbers({literal(values('max_acceleration'))}), shape={shape!r}{vel})"]


def question_by_id(problem, qid):
    """The question of the problem with the id `qid` (a profile a question refers to)."""
    return next(x for x in problem.questions if x.id == qid)


def followed_question(problem, qid, follower):
    """The reference `qid` (a profile, a trajectory) as `follower` follows it: with the parameter
    overrides the follower computes with (`Problem.working_at`: the reference's own, the
    follower's on top) (the solvers' `reference_under`)."""
    ref = question_by_id(problem, qid)
    params = {s: v for s, v in problem.working_at(follower).items() if s in problem.parameters}
    return dataclasses.replace(ref, at={**ref.at, **params}) if params else ref



def coordinate_values(mapping, coords) -> list[str]:
    """The texts of a mapping coordinate -> value ([(text, lhs, value)]) in the order of `coords`."""
    return [text(next(v for _t, lhs, v in mapping if sp.expand(lhs - c) == 0)) for c in coords]


def trajectory_lines(tq, problem) -> list[str]:
    """`trajectory = TaskTrajectory(...)`: the work-space trajectory question `tq`'s path, timed and
    converted to joint motion from its start's branch, numerically."""
    from robosolve.load.expressions import point_symbol

    o = tq.options
    coords = list(o.get("coordinates") or [point_symbol(tq.point, a) for a in "xyz"])
    path = o.get("path") if isinstance(o.get("path"), dict) else {"kind": "line"}
    circle = "" if path.get("kind") != "circle" else f", center=numbers({literal([text(v) for v in path['center']])})" \
        + (f", normal=numbers({literal([text(v) for v in path['normal']])})" if path.get("normal") else "")
    timing = (f"duration=robot.number(robot.parse({text(o['duration'])!r}), at)" if "duration" in o else
              f"max_velocity=robot.number(robot.parse({text(o['max_velocity'])!r}), at), "
              f"max_acceleration=robot.number(robot.parse({text(o['max_acceleration'])!r}), at)")
    limits = [[text(lo), text(hi)] for lo, hi in
              (j.limits if j.limits else ((-sp.pi, sp.pi) if j.kind == "revolute" else (-10, 10)) for j in problem.joints)]
    given = (f"numbers({literal([text(o['start'][j.name]) for j in problem.joints])})"
             if isinstance(o.get("start"), dict) else "None")
    return [f"at = {at_literal(tq)}",
            "numbers = lambda texts: np.array([robot.number(robot.parse(x), at) for x in texts])",
            f"arm = TaskArm(robot, {coordinates(tq)}, at)",
            f"path = TaskPath(numbers({literal(coordinate_values(o['from'], coords))}), "
            f"numbers({literal(coordinate_values(o['to'], coords))}){circle})",
            f"timing = Timing(path.length, {timing})",
            f"limits = [[robot.number(robot.parse(x), at) for x in pair] for pair in {literal(limits)}]",
            "# the configuration at `from` whose inverse-kinematics branch is followed",
            f"start = arm.start(path.a, limits, {given})",
            "trajectory = TaskTrajectory(arm, path, timing, start)"]
