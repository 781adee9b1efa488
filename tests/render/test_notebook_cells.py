"""report.ipynb's recomputing cells run in-process (the runtime's namespace, the notebook's own data
cell) and recompute the right values, checked against closed forms by hand."""

import re

import numpy as np

from robosolve.load.loader import load_problem
from robosolve.render import notebook_runtime as rt
from robosolve.render.notebook import code_cells
from robosolve.run.pipeline import solve_problem

ARM_2R = """\
robosolve: 1
name: point-on-link-one
parameters: {L1: 0.6, L2: 0.4}
joints:
  - {name: q1, type: revolute}
  - {name: q2, type: revolute}
frames:
  "1": {parent: "0", pose: "Rz(q1) Tx(L1)"}
  "2": {pose: "Rz(q2) Tx(L2)"}
points:
  G: {frame: "1", at: [-0.3, 0, 0]}
questions:
  - type: velocity_acceleration
    point: G
    at: {q1: 0.5, q2: -1.1, q1_dot: 1.5, q2_dot: -0.7, q1_ddot: 0.3, q2_ddot: 0.9}
"""


def _run_cells(tmp_path, text, capsys):
    path = tmp_path / "problem.yaml"
    path.write_text(text, encoding="utf-8")
    problem = load_problem(path)
    report = solve_problem(problem)
    namespace = dict(vars(rt))
    for source in code_cells(problem, report.answers)[1:]:      # the data cell, then the answers'
        exec(source, namespace)
    return capsys.readouterr().out


def _recomputed(printed, key):
    m = re.search(rf"recomputed {key} = (\[.*?\])\n", printed)
    return np.array(eval(m.group(1)))                           # a printed list of floats


def test_the_velocity_of_a_point_fixed_in_another_frame_than_the_question_s(tmp_path, capsys):
    """G is fixed in frame 1, the question's frame is 2: G moves with frame 1 (by hand, G at
    r = 0.3 m from the base on link 1: v = r q1'(-s1, c1), a = r q1''(-s1, c1) - r q1'^2 (c1, s1))."""
    printed = _run_cells(tmp_path, ARM_2R, capsys)
    r, q1, w, wd = 0.3, 0.5, 1.5, 0.3
    c, s = np.cos(q1), np.sin(q1)
    assert np.allclose(_recomputed(printed, "velocity"), [-r * w * s, r * w * c, 0], atol=1e-9)
    assert np.allclose(_recomputed(printed, "acceleration"),
                       [-r * wd * s - r * w * w * c, r * wd * c - r * w * w * s, 0], atol=1e-9)
    assert "DIFFERS" not in printed and printed.count("agrees with robosolve") == 8


def test_the_angular_velocity_and_the_auxiliary_frame_are_recomputed(tmp_path, capsys):
    """Every number of the answer is recomputed (angular_velocity, a principal key, and W_aux, H_aux
    were only printed). By hand on the 2R, frame 2: omega = (0, 0, q1' + q2'), omega' = (0, 0, q1'' +
    q2''); W_aux and H_aux are frame 2's W and H with the origin moved to G (fixed in frame 1): their
    last columns are the velocity and acceleration of frame 2's point at G."""
    printed = _run_cells(tmp_path, ARM_2R, capsys)
    (l1, l2), (q1, q2), (d1, d2), (a1, a2) = (0.6, 0.4), (0.5, -1.1), (1.5, -0.7), (0.3, 0.9)
    w, wd = d1 + d2, a1 + a2
    u = lambda a: np.array([np.cos(a), np.sin(a), 0.0])
    n = lambda a: np.array([-np.sin(a), np.cos(a), 0.0])
    g, p2 = 0.3 * u(q1), l1 * u(q1) + l2 * u(q1 + q2)
    v2 = l1 * d1 * n(q1) + l2 * w * n(q1 + q2)
    a2v = l1 * (a1 * n(q1) - d1 ** 2 * u(q1)) + l2 * (wd * n(q1 + q2) - w ** 2 * u(q1 + q2))
    r = g - p2
    omega = np.array([[0, -w, 0], [w, 0, 0], [0, 0, 0]])
    w_aux, h_aux = np.zeros((4, 4)), np.zeros((4, 4))
    w_aux[:3, :3], w_aux[:3, 3] = omega, v2 + np.cross([0, 0, w], r)
    h_aux[:3, :3] = np.array([[0, -wd, 0], [wd, 0, 0], [0, 0, 0]]) + omega @ omega
    h_aux[:3, 3] = a2v + np.cross([0, 0, wd], r) - w ** 2 * r
    assert np.allclose(_recomputed(printed, "angular_velocity"), [0, 0, w], atol=1e-9)
    assert np.allclose(_recomputed(printed, "angular_acceleration"), [0, 0, wd], atol=1e-9)
    assert np.allclose(_recomputed(printed, "W_aux"), w_aux, atol=1e-9)
    assert np.allclose(_recomputed(printed, "H_aux"), h_aux, atol=1e-9)
    assert "DIFFERS" not in printed


ARM_LOADS = """\
robosolve: 1
name: loads-on-a-2r
parameters: {L1: 0.6, L2: 0.4, m: 2, g: 9.81, P: ~}
joints:
  - {name: q1, type: revolute}
  - {name: q2, type: revolute}
frames:
  "1": {parent: "0", pose: "Rz(q1) Tx(L1)"}
  "2": {pose: "Rz(q2) Tx(L2)"}
gravity: [0, -g, 0]
bodies:
  - {name: tip, frame: "2", mass: m, point: [0, 0, 0]}
questions:
  - {type: statics, force: [3, -4, 0], torque: [0, 0, 1.5], weight: true, at: {q1: 0.5, q2: -1.1}}
  - {type: statics, force: [P, 0, 0], at: {q1: 0.5, q2: -1.1}}
  - type: displacement
    frame: "1"
    at: {q1: 0.5, q2: 0}
    from: [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]
    to: [[cos(0.3), -sin(0.3), 0, 0.1], [sin(0.3), cos(0.3), 0, 0.2], [0, 0, 1, 0.3], [0, 0, 0, 1]]
"""


def test_every_load_of_a_statics_question_and_a_displacement_in_a_frame(tmp_path, capsys):
    """Force, torque and weight together (by hand on the 2R: Fq = -J_P^T (F + m g) - J_w^T tau,
    J_w = [1, 1]); a null parameter: the cell shows the formula and evaluates nothing; a displacement
    given in frame 0 and written in frame 1: Q_1 = 0M_1^-1 Q 0M_1 (by hand: rotation Rz(0.3), the
    translation Rz(-q1)((Rz(0.3) - I) p1 + t), p1 the origin of frame 1)."""
    printed = _run_cells(tmp_path, ARM_LOADS, capsys)
    q1, q2, L1, L2 = 0.5, -1.1, 0.6, 0.4
    s1, c1, s12, c12 = np.sin(q1), np.cos(q1), np.sin(q1 + q2), np.cos(q1 + q2)
    jp = np.array([[-L1 * s1 - L2 * s12, -L2 * s12], [L1 * c1 + L2 * c12, L2 * c12]])
    load = np.array([3.0, -4.0 - 2 * 9.81])
    assert np.allclose(_recomputed(printed, "Fq"), -jp.T @ load - 1.5, atol=1e-9)
    rz = lambda a: np.array([[np.cos(a), -np.sin(a), 0], [np.sin(a), np.cos(a), 0], [0, 0, 1]])
    p1 = np.array([L1 * c1, L1 * s1, 0])
    q_k = np.eye(4)
    q_k[:3, :3] = rz(0.3)
    q_k[:3, 3] = rz(-q1) @ ((rz(0.3) - np.eye(3)) @ p1 + [0.1, 0.2, 0.3])
    assert np.allclose(_recomputed(printed, "Q"), q_k, atol=1e-9)
    assert "DIFFERS" not in printed and printed.count("agrees with robosolve") == 7


MISSING_VALUES = """\
robosolve: 1
name: values-not-given
parameters: {L1: ~, L2: 0.4, k: ~}
joints:
  - {name: q1, type: revolute}
  - {name: q2, type: revolute}
frames:
  "1": {parent: "0", pose: "Rz(q1) Tx(L1)"}
  "2": {pose: "Rz(q2) Tx(L2)"}
questions:
  - {type: position, at: {q1: 0.5, q2: -1.1}}
  - {type: jacobian, coordinates: [E.x, E.y], at: {q1: 0.5, q2: -1.1}}
  - {type: jacobian, id: geometric, geometric: true, at: {q1: 0.5, q2: -1.1}}
  - {type: ellipsoids, coordinates: [E.x, E.y], joint_compliance: [k, k], at: {q1: 0.5, q2: -1.1, L1: 0.6}}
  - {type: orientation, at: {q2: 0.3}}
  - {type: velocity_acceleration, at: {q1: 0.5, q2: -1.1, L1: 0.6}}
  - {type: displacement, from: {q1: 0, q2: 0}, to: {q1: 0.5, q2: 0.1}}
"""


def test_cells_of_answers_without_numbers_show_the_formulas_and_evaluate_nothing(tmp_path, capsys):
    """A null parameter (L1, k), a joint missing from `at` (orientation), rates missing (W, H):
    robosolve gives no numbers, so the cells show the formulas; the notebook runs on (each cell used
    to stop it with TypeError: Cannot convert expression to float)."""
    path = tmp_path / "problem.yaml"
    path.write_text(MISSING_VALUES, encoding="utf-8")
    problem = load_problem(path)
    report = solve_problem(problem)
    main = {"position": "M", "jacobian": "J", "geometric": "J", "ellipsoids": "compliance", "orientation": "zyz",
            "velocity_acceleration": "W", "displacement": "Q"}
    assert all(main[a.id] not in a.numeric for a in report.answers), [(a.id, list(a.numeric)) for a in report.answers]
    namespace = dict(vars(rt))
    for source in code_cells(problem, report.answers)[1:]:
        exec(source, namespace)
    assert "DIFFERS" not in capsys.readouterr().out


ELLIPSES_3R = """\
robosolve: 1
name: ellipses-of-a-planar-3r
parameters: {L1: 0.5, L2: 0.4, L3: 0.3}
joints:
  - {name: q1, type: revolute}
  - {name: q2, type: revolute}
  - {name: q3, type: revolute}
frames:
  "1": {parent: "0", pose: "Rz(q1) Tx(L1)"}
  "2": {pose: "Rz(q2) Tx(L2)"}
  "3": {pose: "Rz(q3) Tx(L3)"}
questions:
  - {type: ellipsoids, coordinates: [E.x, E.y], at: {q1: 0.3, q2: 0.8, q3: -0.5},
     velocity: {E.y: -0.2, E.x: 0.1}, budgets: {compliance: 2}}
"""


def test_the_ellipses_cell_recomputes_a_the_joint_rates_and_the_default_compliance(tmp_path, capsys):
    """A = J J^T, the joint rates for the desired velocity (a wide J: the minimum-norm
    J^T (J J^T)^-1 v) and the compliance ellipse with the default Kq = I (Ka times the eigenvalues
    of J J^T) are recomputed, not only printed; J of the planar 3R by hand."""
    printed = _run_cells(tmp_path, ELLIPSES_3R, capsys)
    lengths, angles = np.array([0.5, 0.4, 0.3]), np.cumsum([0.3, 0.8, -0.5])
    jac = np.array([[-(lengths[k:] * np.sin(angles[k:])).sum() for k in range(3)],
                    [(lengths[k:] * np.cos(angles[k:])).sum() for k in range(3)]])
    a = jac @ jac.T
    assert np.allclose(_recomputed(printed, "A"), a, atol=1e-9)
    rates = eval(re.search(r"recomputed q_dot = (\{.*?\})\n", printed).group(1))
    assert np.allclose(list(rates.values()), jac.T @ np.linalg.solve(a, [0.1, -0.2]), atol=1e-9)
    assert np.allclose(_recomputed(printed, "compliance"), 2 * np.sort(np.linalg.eigvalsh(a))[::-1], atol=1e-9)
    assert "DIFFERS" not in printed



ENERGIES_2R = """\
robosolve: 1
name: energies-of-a-2r
parameters: {L1: 0.6, L2: 0.4, m1: 2, m2: 1.5, g: 9.81}
joints:
  - {name: q1, type: revolute}
  - {name: q2, type: revolute}
frames:
  "1": {parent: "0", pose: "Rz(q1) Tx(L1)"}
  "2": {pose: "Rz(q2) Tx(L2)"}
gravity: [0, -g, 0]
bodies:
  - {name: rod, frame: "1", mass: m1, rod: {from: [-L1, 0, 0], to: [0, 0, 0]}}
  - {name: tip, frame: "2", mass: m2, point: [0, 0, 0]}
questions:
  - {type: jacobian, coordinates: [E.x, E.y], bodies: true, at: {q1: 0.5, q2: -1.1}}
  - type: equations_of_motion
    at: {q1: 0.5, q2: -1.1, q1_dot: 1.5, q2_dot: -0.7, q1_ddot: 0, q2_ddot: 0}
"""


def _found(printed, *keys):
    return {k: eval(re.search(rf"recomputed {k} = (\{{.*?\}})\n", printed).group(1)) for k in keys}


def test_the_energies_and_the_centre_of_mass_jacobians_are_recomputed(tmp_path, capsys):
    """kinetic_energy, potential_energy (equations_of_motion) and com_jacobians (jacobian,
    bodies: true) were only printed; by hand on the 2R: the rod's T = m1 L1^2 q1'^2 / 6,
    U = m1 g L1 s1 / 2, J_G = d(L1/2 (c1, s1))/dq; the tip's T = m2 |v|^2 / 2, U = m2 g y."""
    printed = _run_cells(tmp_path, ENERGIES_2R, capsys)
    (l1, l2), (m1, m2), g = (0.6, 0.4), (2, 1.5), 9.81
    (q1, q2), (d1, d2) = (0.5, -1.1), (1.5, -0.7)
    s1, c1, s12, c12 = np.sin(q1), np.cos(q1), np.sin(q1 + q2), np.cos(q1 + q2)
    v_tip = np.array([-l1 * s1 * d1 - l2 * s12 * (d1 + d2), l1 * c1 * d1 + l2 * c12 * (d1 + d2)])
    kinetic = [m1 * l1 ** 2 * d1 ** 2 / 6, m2 * v_tip @ v_tip / 2]
    potential = [m1 * g * l1 * s1 / 2, m2 * g * (l1 * s1 + l2 * s12)]
    found = _found(printed, "kinetic_energy", "potential_energy", "com_jacobians")
    assert np.allclose(list(found["kinetic_energy"].values()), kinetic + [sum(kinetic)], atol=1e-9)
    assert np.allclose(list(found["potential_energy"].values()), potential + [sum(potential)], atol=1e-9)
    j_tip = np.array([[-l1 * s1 - l2 * s12, -l2 * s12], [l1 * c1 + l2 * c12, l2 * c12], [0, 0]])
    j_rod = np.array([[-l1 * s1 / 2, 0], [l1 * c1 / 2, 0], [0, 0]])
    assert np.allclose(found["com_jacobians"]["rod"], j_rod, atol=1e-9)
    assert np.allclose(found["com_jacobians"]["tip"], j_tip, atol=1e-9)
    assert "DIFFERS" not in printed


PENDULUM = """\
robosolve: 1
name: a-free-pendulum
parameters: {L: 2, m: 50, g: 9.81}
joints:
  - {name: th, type: revolute}
frames:
  "1": {parent: "0", pose: "Rz(th) Tx(L)"}
gravity: [0, -g, 0]
bodies:
  - {name: rod, frame: "1", mass: m, rod: {from: [-L, 0, 0], to: [0, 0, 0]}}
questions:
  - {type: forward_dynamics, start: {th: 0.5, th_dot: 1.5}, duration: 0.5}
  - {type: forward_dynamics, id: from-rest, duration: 5}
"""


def test_the_energy_of_a_run_is_recomputed(tmp_path, capsys):
    """forward_dynamics' energy was only printed; by hand: T + U = m L^2 th'^2 / 6 + m g L sin(th) / 2,
    kept by a free run. From rest at th = 0 (T + U = 0) the end's energy is round-off, which
    robosolve writes 0: it agrees within the run's energy scale."""
    printed = _run_cells(tmp_path, PENDULUM, capsys)
    start = 50 * 2 ** 2 * 1.5 ** 2 / 6 + 50 * 9.81 * 2 * np.sin(0.5) / 2
    energy = eval(re.search(r"recomputed energy = (\{.*?\})\n", printed).group(1))
    assert np.allclose([energy["start"], energy["end"]], [start, start], rtol=1e-8)
    assert "DIFFERS" not in printed and printed.count("(agrees with robosolve)") == 10


SINGULAR_2R = """\
robosolve: 1
name: singular-2r
parameters: {L1: 0.6, L2: 0.4}
joints:
  - {name: q1, type: revolute}
  - {name: q2, type: revolute}
frames:
  "1": {parent: "0", pose: "Rz(q1) Tx(L1)"}
  "2": {pose: "Rz(q2) Tx(L2)"}
questions:
  - {type: jacobian, coordinates: [E.x, E.y], at: {q1: 0.5, q2: -1.1}}
  - {type: jacobian, id: no-at, coordinates: [E.y, E.x]}
  - {type: jacobian, id: never, coordinates: [E.x, E.y, "q1 + q2"]}
"""


def test_the_singular_conditions_are_checked(tmp_path, capsys):
    """The singularities (a principal key) were only printed: the cell now evaluates J at each
    condition and finds it singular, with or without numbers in `at`. By hand: det J = L1 L2 sin(q2),
    so J loses rank exactly at q2 = 0 and q2 = pi, whatever q1; with q1 + q2 as a third row the
    minors L1 L2 s2, -L1 s1, L1 c1 never vanish together: no condition, nothing to check."""
    printed = _run_cells(tmp_path, SINGULAR_2R, capsys)
    ratios = re.findall(r"recomputed singularities = (\[.*?\])\n", printed)
    assert len(ratios) == 2 and all(len(eval(r)) == 2 and np.allclose(eval(r), 0, atol=1e-12) for r in ratios)
    assert "conditions = [{'q2': '0'}, {'q2': 'pi'}]" in "".join(
        code_cells(load_problem(tmp_path / "problem.yaml"), solve_problem(load_problem(tmp_path / "problem.yaml")).answers))
    assert "DIFFERS" not in printed


IK_2R = """\
robosolve: 1
name: selection-of-a-2r
parameters: {L1: 0.5, L2: 0.5}
joints:
  - {name: q1, type: revolute}
  - {name: q2, type: revolute}
frames:
  "1": {parent: "0", pose: "Rz(q1) Tx(L1)"}
  "2": {pose: "Rz(q2) Tx(L2)"}
questions:
  - {type: inverse_kinematics, target: {E.x: 0.6, E.y: 0.3}}
  - {type: inverse_kinematics, id: near, target: {E.x: 0.6, E.y: 0.3}, select: {q1: 1, q2: 5},
     velocity: {E.x: 0.1, E.y: -0.1}}
"""


def test_the_selected_solution_is_recomputed(tmp_path, capsys):
    """`selected` was robosolve's alone (and the joint rates were taken at it): the cell now
    selects by the spec's rule. By hand: q2 = ±acos((x² + y² − L1² − L2²) / (2 L1 L2)),
    q1 = atan2(y, x) − atan2(L2 s2, L1 + L2 c2); select: limits takes the first in joint order
    (the negative q1), and (1, 5) is nearest the elbow-down one, 5 − 2π being close to −1.67."""
    printed = _run_cells(tmp_path, IK_2R, capsys)
    c2 = (0.6 ** 2 + 0.3 ** 2 - 0.5) / 0.5
    sols = sorted((np.arctan2(0.3, 0.6) - np.arctan2(0.5 * np.sin(q2), 0.5 + 0.5 * c2 * 1), q2)
                  for q2 in (np.arccos(c2), -np.arccos(c2)))
    selected = [eval(m) for m in re.findall(r"recomputed selected = (\{.*?\})\n", printed)]
    assert np.allclose([list(s.values()) for s in selected], [sols[0], sols[1]], atol=1e-9)
    jac = np.array([[-0.5 * np.sin(sols[1][0]) - 0.5 * np.sin(sum(sols[1])), -0.5 * np.sin(sum(sols[1]))],
                    [0.5 * np.cos(sols[1][0]) + 0.5 * np.cos(sum(sols[1])), 0.5 * np.cos(sum(sols[1]))]])
    rates = eval(re.search(r"recomputed q_dot = (\{.*?\})\n", printed).group(1))
    assert np.allclose(list(rates.values()), np.linalg.solve(jac, [0.1, -0.1]), atol=1e-9)
    assert "DIFFERS" not in printed


def test_the_cell_of_an_unanswered_question_says_why(tmp_path, capsys):
    """A question robosolve answers with an error (a gain that is a null parameter) used to get a
    cell printing `{}`; it now prints robosolve's reason, from a literal (a quote in it is text)."""
    text = ARM_LOADS.replace("questions:", "questions:\n  - {type: motion_profile, id: pr, from: {q1: 0, q2: 0}, "
                             "to: {q1: 1, q2: 1}, max_acceleration: {q1: 1, q2: 1}}\n"
                             "  - {type: p_control, profile: pr, law: pd, gains: {q1: 10, q2: 10}, "
                             "gains_d: {q1: P, q2: 1}}", 1)
    printed = _run_cells(tmp_path, text, capsys)
    assert "robosolve: gains_d.q1 must be a number (got P)" in printed
    assert "\n{}\n" not in printed


ROUNDED_DISPLACEMENT = """\
robosolve: 1
name: rounded-by-hand
questions:
  - type: displacement
    from: [[1, 0, 0, 1], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]
    to: [[0.707, -0.707, 0, 0.3], [0.707, 0.707, 0, 0.2], [0, 0, 1, 0.5], [0, 0, 0, 1]]
"""


def test_a_displacement_between_matrices_rounded_by_hand_is_recomputed_as_robosolve_reads_it(tmp_path, capsys):
    """robosolve reads 0.707 as the nearest rotation, Rz(π/4): so does the cell (it said Q
    DIFFERS). By hand: Q = M_to·M_from⁻¹ with M_to's rotation Rz(π/4)."""
    printed = _run_cells(tmp_path, ROUNDED_DISPLACEMENT, capsys)
    c = np.cos(np.pi / 4)
    m_to = np.array([[c, -c, 0, 0.3], [c, c, 0, 0.2], [0, 0, 1, 0.5], [0, 0, 0, 1]])
    m_from = np.eye(4)
    m_from[0, 3] = 1
    assert np.allclose(_recomputed(printed, "Q"), m_to @ np.linalg.inv(m_from), atol=1e-12)
    assert "DIFFERS" not in printed, printed
