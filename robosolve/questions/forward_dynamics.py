"""The `forward_dynamics` question type:
Forward dynamics (the motion under given actuators); its options, checks and answer schema.
"""

from __future__ import annotations

from robosolve.load import validators as V
from robosolve.questions.schema import EQUATIONS, JOINT_MAP, RECORD, SCALAR, QuestionType, _k
from robosolve.questions.wording import asked, listing
from robosolve.questions.notebook_code import at_literal, compare_line, guarded, lines, literal, robosolve_numbers, text


def _check(ql, path, item, q):
    """`at` overrides parameters only: the motion starts from `start`; each actuator law has a
    value at the start of the run (t = 0, the `start` state)."""
    for key, _ in V.joint_motion_in_at(ql, item):
        ql.chk.error(path + ("at", key), f"a forward_dynamics question's `at` may override "
                     f"parameters only: give the starting value of '{key}' in `start` "
                     "(joint values and <joint>_dot rates)")
    if "start" in q.rejected or "at" in q.rejected:
        return                      # the start state is not known: said already
    start = q.options.get("start") or {}
    initial = {ql.b.names["t"]: 0}
    for j in ql.b.joints:
        initial[j.symbol] = start.get(j.name, 0)
        initial[j.dot] = start.get(j.dot.name, 0)
    written = item.get("actuators") if isinstance(item.get("actuators"), dict) else {}
    for name, law in (q.options.get("actuators") or {}).items():
        shown = written.get(name)
        issue = ql.chk.value_issue(law.xreplace(initial), shown if isinstance(shown, str) else None)
        if issue is not None:
            ql.chk.error(path + ("actuators", name), "the law has no value at the start of the run (t = 0, "
                         f"the `start` state): {issue}")

WORDS = {
    "final": "each joint's value at the end (unwrapped: an arm that turns twice ends near $4\\pi$)",
    "max": "each joint's largest value over the run",
    "min": "each joint's smallest value over the run",
    "final_velocity": "each joint's rate at the end",
    "energy": "the total energy $T + U$ at the start and at the end of the run",
    "energy.start": "the total energy $T + U$ at $t = 0$",
    "energy.end": "the total energy $T + U$ at the end of the run",
    "equations": ("the equations of motion with the actuator laws substituted (one per joint, "
                  "each written \"left side = right side\")"),
}


def _start(q, say) -> str:
    """The whole state at t = 0: every joint's value and rate (those not given are 0)."""
    start = q.options.get("start") or {}
    joints = say.problem.joints
    values = {j.name: start.get(j.name, 0) for j in joints}
    rates = {j.dot.name: start.get(j.dot.name, 0) for j in joints}
    if all(v == 0 for v in rates.values()):
        return f"at rest from {say.joint_values(values)}"
    return f"from {say.joint_values(values)}, with the rates {say.joint_values(rates)}"


def _statement(q, say) -> str:
    """The paper's statement (papers.md), from the start state (every joint and rate), the
    actuator laws (every actuator) and the duration, then what the question grades."""
    o = q.options
    laws = o.get("actuators") or {}
    actuators = {str(j.actuator): laws.get(str(j.actuator), 0) for j in say.problem.joints}
    acting = (f", with the actuators {say.joint_values(actuators)}" if any(v != 0 for v in actuators.values())
              else ", with no actuator action")
    return (f"Starting {_start(q, say)}{acting}, the robot moves for {say.value(o['duration'])} s under the "
            f"bodies, forces and gravity of the data. Give {listing(asked(q, say, WORDS))}.")


def notebook_cell(q, answer, problem):
    """The notebook's cell that recomputes the answer (questions/notebook_code.py)."""
    laws = {str(k): text(v) for k, v in (q.options.get("actuators") or {}).items()}
    actuators = {str(j.actuator) for j in problem.joints}
    if any(a not in actuators for a in laws):
        return None
    start = q.options.get("start") or {}
    names = [j.name for j in problem.joints]
    q0 = [text(start.get(n, 0)) for n in names]
    v0 = [text(start.get(f"{n}_dot", 0)) for n in names]
    keys = ["final", "final_velocity", "max", "min", "energy"]
    return lines(
        f"at = {at_literal(q)}",
        "# M(q) q'' + c + g = tau + Q with the actuator laws, integrated by Dormand-Prince 5(4)",
        f"laws = {literal(laws)}",
        "numbers = lambda texts: [robot.number(robot.parse(x), at) for x in texts]",
        f"duration = robot.number(robot.parse({text(q.options['duration'])!r}), at)",
        f"times, qs, rates = forward_run(robot, laws, numbers({literal(q0)}), numbers({literal(v0)}), duration, at)",
        robosolve_numbers(answer, keys),
        "low, high = extremes(times, qs, rates)",
        *guarded(answer, ("final", compare_line("final", f"dict(zip({names!r}, qs[-1]))", rtol=1e-6)),
                  ("final_velocity", compare_line("final_velocity", f"dict(zip({names!r}, rates[-1]))", rtol=1e-6)),
                  ("max", compare_line("max", f"dict(zip({names!r}, high))", rtol=1e-6)),
                  ("min", compare_line("min", f"dict(zip({names!r}, low))", rtol=1e-6))),
        *([] if "energy" not in answer.numeric else [
            "# T + U at the start and at the end: T = 1/2 tr(M' J M'^T), U = -g.(M J e4) per body",
            "state = lambda k: {**at, **{n: repr(float(x)) for n, x in zip(" + literal(names) + ", qs[k])},",
            "                   **{n + '_dot': repr(float(x)) for n, x in zip(" + literal(names) + ", rates[k])}}",
            "totals = [[e['total'] for e in robot.energies_at(state(k))]       # [T, U] at 5 instants",
            "          for k in np.linspace(0, len(times) - 1, 5).astype(int)]",
            "energy = {'start': sum(totals[0]), 'end': sum(totals[-1])}",
            "# round-off beside the run's energy scale (T + |U| along it) is 0",
            "scale = max(T + abs(U) for T, U in totals)",
            "compare('energy', energy, robosolve['energy'], rtol=1e-6, atol=1e-8 * scale)"]),
        "plot_joints(times, qs, " + literal(names) + ")",
    )


TYPE = QuestionType(
    "forward_dynamics", "Forward dynamics (the motion under given actuators)", "§6.5",
    statement=_statement,
    options={"start": V.v_start_state, "actuators": V.v_actuator_laws, "duration": V.v_duration},
    required=("duration",),
    needs_dynamics=True,
    answers=(
        # the run is accurate to ~1e-9 of its scale (tests: 1e-8 against pinocchio): 10 digits
        _k("final", JOINT_MAP, "joint values at the end (unwrapped)", principal=True, unit="joint", symbolic=False,
           digits=10),
        _k("max", JOINT_MAP, "largest value of each joint over the run", principal=True, unit="joint",
           symbolic=False, digits=10),
        _k("min", JOINT_MAP, "smallest value of each joint over the run", principal=True, unit="joint",
           symbolic=False, digits=10),
        _k("final_velocity", JOINT_MAP, "joint rates at the end", unit="joint/s", symbolic=False, digits=10),
        _k("energy", RECORD, "total energy T + U", unit="J", symbolic=False, fields=(
            _k("start", SCALAR, "at t = 0", digits=10),
            _k("end", SCALAR, "at the end of the run", digits=10))),
        _k("equations", EQUATIONS, "the equations of motion with the actuator laws substituted",
           numeric=False),
    ),
    figures=(("joint_<name>", "forward_dynamics"),),
    cost=0.2, cost_growth=2.5, unit="dynamics",
    check=_check, integrates=True, time_use=(1, "a forward_dynamics run"), time_laws="actuators",
    notebook_cells=notebook_cell,
)
