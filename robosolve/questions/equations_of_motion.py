"""The `equations_of_motion` question type (Equations of motion): options, checks, answer schema."""

from __future__ import annotations

import sympy as sp

from robosolve.questions.schema import ACTUATOR_MAP, BODY_MAP, EQUATIONS, JOINT_MAP, MATRIX, N, VECTOR, QuestionType, _k
from robosolve.questions.wording import asked, listing
from robosolve.questions.notebook_code import at_literal, compare_line, guarded, lines, robosolve_numbers


def _has_time(force) -> bool:
    parts = list(force.force or []) + list(force.torque or [])
    return any("t" in {s.name for s in getattr(e, "free_symbols", ())} for e in parts)


def _check(ql, path, item, q):
    if "at" not in item:
        return
    timed = [f.name for f in ql.b.problem.forces if _has_time(f)]
    if timed:
        follow = ql.type_name("time_laws")
        forces = f"forces {', '.join(timed)} vary" if len(timed) > 1 else f"force {timed[0]} varies"
        ql.chk.error(path + ("at",), f"the {forces} with time t, so the numbers at a configuration would need "
                     f"a time: drop `at` (the symbolic equations keep t), or follow the motion with a {follow} "
                     "question")

def _needs_configuration(q, joints) -> str:
    """The actuators' values are computed at a configuration: every joint's value in `at`
    (rates and accelerations not given are 0)."""
    given = {getattr(s, "name", str(s)) for s in (q.at or {})}
    missing = [j.name for j in joints if j.name not in given]
    return "" if not missing else ("the actuators are computed only at a configuration: give "
                                   + ", ".join(missing) + " in at")


def _words(q, say) -> dict:
    actuators = ", ".join(f"${say.tex(j.actuator)}$" for j in say.problem.joints)
    return {
        "mass_matrix": "the mass matrix $M(q)$",
        "velocity_terms": "the velocity terms $c(q, \\dot q)$",
        "gravity_terms": "the gravity terms $g(q)$",
        "generalized_forces": "the generalized forces $Q$ (actuators plus external forces)",
        "equations": "the equation of each joint (written \"left side = right side\")",
        "kinetic_energy": "the kinetic energy $T$ of each body and their total",
        "potential_energy": "the potential energy $U$ of each body and their total",
        "actuators": f"the actuator actions ({actuators}) needed at the given configuration, rates and accelerations",
    }


def _statement(q, say) -> str:
    """The paper's statement (papers.md), from the bodies, forces and `at` of the data, then what
    the question grades (M, c, g, Q, the equations, the energies, the actuators needed)."""
    at = say.at(q)
    return ("With the bodies, forces and gravity of the data, derive the equations of motion "
            "$M(q)\\,\\ddot q + c(q, \\dot q) + g(q) = Q$; give " + listing(asked(q, say, _words(q, say)))
            + (f"; give the numbers {at}" if at else "") + ".")


def notebook_cell(q, answer, problem):
    """The notebook's cell that recomputes the answer (questions/notebook_code.py). Without a
    whole configuration in `at` (every joint, rate and acceleration) there are no numbers to
    recompute: the cell shows the equations by Lagrange (a small arm) only."""
    actuators = [str(j.actuator) for j in problem.joints]
    if not all(s in q.at for j in problem.joints for s in (j.symbol, j.dot, j.ddot)):
        return lines(
            f"at = {at_literal(q)}",
            "# no whole configuration in `at`: the answers are symbolic (above)",
            "if len(robot.joints) <= 2:                # the formulas of a small arm, by Lagrange",
            "    show(*robot.lagrange(at)[:3])",
        )
    return lines(
        f"at = {at_literal(q)}",
        "# M, c, g and the external forces' Q at the configuration (numbers along the chain)",
        "mass, c, grav, Q = robot.dynamics_at(at)",
        "accelerations = robot.number(sp.Matrix(robot.accelerations), at).ravel()",
        "if len(robot.joints) <= 2:                # the formulas of a small arm, by Lagrange",
        "    show(*robot.lagrange(at)[:3])",
        "# T = 1/2 tr(M' J M'^T) and U = -g.(M J e4) of each body, and their totals",
        "kinetic, potential = robot.energies_at(at)",
        robosolve_numbers(answer, ["mass_matrix", "velocity_terms", "gravity_terms", "actuators",
                                   "kinetic_energy", "potential_energy"]),
        *guarded(answer, ("kinetic_energy", compare_line("kinetic_energy", "kinetic")),
                 ("potential_energy", compare_line("potential_energy", "potential")),
                 ("mass_matrix", compare_line("mass_matrix", "mass")),
                  ("velocity_terms", compare_line("velocity_terms", "c")),
                  ("gravity_terms", compare_line("gravity_terms", "grav")),
                  ("actuators", "# the joint actions tau = M q'' + c + g - Q\n"
                   + compare_line("actuators", f"dict(zip({actuators!r}, mass @ accelerations + c + grav - Q))"))),
    )


TYPE = QuestionType(
    "equations_of_motion", "Equations of motion", "§8 question 8",
    statement=_statement,
    options={},
    needs_dynamics=True,
    answers=(
        _k("mass_matrix", MATRIX, "M(q)", principal=True, shape=(N, N), notation="M(q)"),
        _k("velocity_terms", VECTOR, "c(q, q̇)", principal=True, unit="effort", shape=(N,)),
        _k("gravity_terms", VECTOR, "g(q)", principal=True, unit="effort", shape=(N,)),
        _k("generalized_forces", JOINT_MAP, "actuator plus external forces, per joint",
           principal=True, unit="effort"),
        _k("equations", EQUATIONS, "one equation per joint", numeric=False),
        _k("kinetic_energy", BODY_MAP, "T per body and total", unit="J"),
        _k("potential_energy", BODY_MAP, "U per body and total", unit="J"),
        _k("actuators", ACTUATOR_MAP, "actuator values needed at the question's configuration, rates "
           "and accelerations", unit="effort", symbolic=False, needs=_needs_configuration),
    ),
    cost=0.7, cost_growth=2.5, unit="dynamics",
    check=_check,
    notebook_cells=notebook_cell,
)
