"""Answers the way people type them (papers.md "What students may write"): matrices and
vectors as MATLAB or Python strings, `^` for powers; `check --echo`, `check --no-expected`."""

from __future__ import annotations

import json
import re

import pytest
from typer.testing import CliRunner

from robosolve.cli import app
from robosolve.grading.typed import ArrayTextError, parse_array

runner = CliRunner()


@pytest.mark.parametrize("text, expected", [
    ("[1 0; 0 1]", [["1", "0"], ["0", "1"]]),
    ("[1, 0; 0, 1]", [["1", "0"], ["0", "1"]]),
    ("[[1, 0], [0, 1]]", [["1", "0"], ["0", "1"]]),
    ("[0.43, 0.65, 0]", ["0.43", "0.65", "0"]),
    ("[1 -2]", ["1", "-2"]),
    ("[1 - 2]", ["1 - 2"]),
    ("[cos(a + b) -sin(a + b); L1^2 deg(30)]", [["cos(a + b)", "-sin(a + b)"], ["L1^2", "deg(30)"]]),
    ("[a * b, c]", ["a * b", "c"]),
    ("[]", []),
    ("[4.929\t1.171]", ["4.929", "1.171"]),                  # a tab between entries
    ("[1 2\n3 4]", [["1", "2"], ["3", "4"]]),                # MATLAB: an end of line ends a row
    ("[1 2;\n 3 4;\n]", [["1", "2"], ["3", "4"]]),
    ("[1, 2,]", ["1", "2"]),                                  # Python's trailing comma
    ("[[1, 2], [3, 4],]", [["1", "2"], ["3", "4"]]),
    ("[1 2;]", ["1", "2"]),
    ("[1 2 3]'", [["1"], ["2"], ["3"]]),                      # MATLAB's transpose
    ("[1 2; 3 4].'", [["1", "3"], ["2", "4"]]),
])
def test_parse_array(text, expected):
    assert parse_array(text) == expected


@pytest.mark.parametrize("text", ["[1, 2", "[1, , 2]", "[[1, 2], 3]", "1 2", "[(1, 2]", "[;1 2]", "[1 2]''"])
def test_parse_array_refuses(text):
    with pytest.raises(ArrayTextError):
        parse_array(text)


ARM = """\
robosolve: 1
name: arm
parameters: {L1: 1/2, L2: 2/5}
joints:
  - {name: theta1, type: revolute}
  - {name: theta2, type: revolute}
frames:
  "1": {pose: "Rz(theta1) Tx(L1)"}
  "2": {pose: "Rz(theta2) Tx(L2)"}
questions:
  - {type: position, at: {theta1: 0, theta2: pi/2}}
"""


def _answers(tmp_path, m, position):
    (tmp_path / "arm.yaml").write_text(ARM)
    f = tmp_path / "a.yaml"
    f.write_text("robosolve-answers: 1\nproblem: arm.yaml\nstudent: s1\nanswers:\n  position:\n"
                 f"    M: {json.dumps(m)}\n    position: {json.dumps(position)}\n")
    return f


M_MATLAB = ("[cos(theta1 + theta2) -sin(theta1 + theta2) 0 L1*cos(theta1) + L2*cos(theta1 + theta2); "
            "sin(theta1 + theta2) cos(theta1 + theta2) 0 L1*sin(theta1) + L2*sin(theta1 + theta2); "
            "0 0 1 0; 0 0 0 1]")


def test_typed_matrix_and_powers_are_graded(tmp_path):
    f = _answers(tmp_path, M_MATLAB, "[0.5, 0.4, 0]")
    r = runner.invoke(app, ["check", str(f), "--json", "-"])
    assert r.exit_code == 0, r.output
    f = _answers(tmp_path, [[0, -1, 0, "2^(-1)"], [1, 0, 0, "0.4"], [0, 0, 1, 0], [0, 0, 0, 1]], "[0.5; 0.4; 0]")
    r = runner.invoke(app, ["check", str(f), "--json", "-"])
    assert r.exit_code == 0, r.output


def test_echo_and_no_expected(tmp_path):
    f = _answers(tmp_path, "[1 0; 0 1]", "[0.5, 0.41, 0]")
    r = runner.invoke(app, ["check", str(f), "--echo", "--no-expected"])
    assert r.exit_code == 1
    out = r.output
    assert "read them" in out and out.index("read them") < out.index("verdict")
    assert "[[1, 0], [0, 1]]" in out and "[0.5, 0.41, 0]" in out
    assert "wrong_shape" in out
    verdicts = out.split("verdict", 1)[1]
    assert not re.search(r"expected \S+ =|; expected", verdicts)
    assert not re.search(r"\b0\.4\b", verdicts)
    r = runner.invoke(app, ["check", str(f), "--no-expected", "--json", str(tmp_path / "r.json")])
    record = (tmp_path / "r.json").read_text()
    assert "entry 2 is 0.41" in record and not re.search(r"expected \S+ =|; expected", record)
    r = runner.invoke(app, ["check", str(f), "--json", str(tmp_path / "r2.json")])
    assert "expected position = [0.5, 0.4, 0]" in (tmp_path / "r2.json").read_text()


def test_matlab_typed_without_quotes_is_read_as_typed(tmp_path):
    """YAML reads an unquoted `[0.5 0.4 0]` as one string entry and `[a, b; c, d]` as
    ['a', 'b; c', 'd']: both are read as the MATLAB text they were (they were `invalid`:
    "cannot parse expression '0.5 0.4 0'", "a list of rows of equal length")."""
    (tmp_path / "arm.yaml").write_text(ARM)
    f = tmp_path / "a.yaml"
    f.write_text("robosolve-answers: 1\nproblem: arm.yaml\nstudent: s1\nanswers:\n  position:\n"
                 "    M: [0, -1, 0, 1/2; 1, 0, 0, 2/5; 0 0 1 0; 0 0 0 1]\n"
                 "    position: [0.5 0.4 0]\n")
    r = runner.invoke(app, ["check", str(f), "--json", "-"])
    assert r.exit_code == 0, r.output
    # a YAML list whose entries are expressions stays so: `1 -1/2` is 1 - 1/2 there, not two entries
    f.write_text("robosolve-answers: 1\nproblem: arm.yaml\nstudent: s1\nanswers:\n  position:\n"
                 "    M: [[0, -1, 0, 1/2], [1, 0, 0, 2/5], [0, 0, 1, 0], [0, 0, 0, 1]]\n"
                 "    position: [1 -1/2, 0.4, 0]\n")
    r = runner.invoke(app, ["check", str(f), "--json", "-"])
    assert r.exit_code == 0, r.output


@pytest.mark.parametrize("typed, read", [
    ("−0.45", "-0.45"),            # a Unicode minus, as pasted from a printed paper or a PDF
    ("2·L1 × 3", "2*L1*3"),
    ("π/2", "pi/2"),
    ("L1² + L2³", "L1**2 + L2**3"),
    ("√3/4", "sqrt(3)/4"),
    ("√(L1 + L2)", "sqrt(L1 + L2)"),
    ("√L1", "sqrt(L1)"),
    ("30°", "pi/6"),               # degrees: was invalid ("write deg(30)")
    ("-22.5° + L1", "-pi/8 + L1"),
    # a product printed by juxtaposition (was invalid: '2pi', '2sqrt(2)')
    ("2π", "2*pi"),
    ("3π/4", "3*pi/4"),
    ("2√2", "2*sqrt(2)"),
    ("√2π", "sqrt(2)*pi"),
    ("π√2", "pi*sqrt(2)"),
    ("0.5√(L1 + L2)", "sqrt(L1 + L2)/2"),
    ("(L1 + L2)π", "(L1 + L2)*pi"),
    ("2π²", "2*pi**2"),
])
def test_typography_of_pasted_answers(typed, read):
    import sympy as sp

    from robosolve.load.expressions import Namespace, typed_math

    L1, L2 = sp.symbols("L1 L2")
    ns = Namespace({"L1": L1, "L2": L2})
    assert sp.simplify(ns.parse(typed_math(typed)) - ns.parse(read)) == 0


def test_a_pasted_minus_and_a_decimal_comma_in_check(tmp_path):
    f = _answers(tmp_path, [[0, -1, 0, "1/2"], [1, 0, 0, "2/5"], [0, 0, 1, 0], [0, 0, 0, 1]], ["0.5", "0.4", "−0"])
    r = runner.invoke(app, ["check", str(f)])
    assert r.exit_code == 0, r.output
    f = _answers(tmp_path, [[0, -1, 0, "1/2"], [1, 0, 0, "2/5"], [0, 0, 1, 0], [0, 0, 0, 1]], ["0,5", "0.4", "0"])
    r = runner.invoke(app, ["check", str(f), "--json", str(tmp_path / "r.json")])
    assert r.exit_code == 1
    assert "decimals are written with a point: 0.5" in (tmp_path / "r.json").read_text()


def test_each_matrix_or_vector_of_a_list_may_be_typed(tmp_path):
    """A list (or mapping) of matrices or vectors — a chain's poses, the centre-of-mass
    Jacobians, ellipse semi-axes, Euler triples — may have each element typed as one MATLAB
    string, like a key's whole value (was `invalid`: "expected a matrix as a list of rows")."""
    import numpy as np

    problem = ARM.replace("questions:\n  - {type: position, at: {theta1: 0, theta2: pi/2}}\n", """\
bodies:
  - {name: tip, frame: "2", mass: 1, point: [0, 0, 0]}
questions:
  - {type: position, at: {theta1: 0, theta2: pi/2}, grade: [chain]}
  - {type: jacobian, coordinates: [E.x, E.y], bodies: true, at: {theta1: 0, theta2: pi/2}, grade: [com_jacobians]}
  - {type: ellipsoids, coordinates: [E.x, E.y], at: {theta1: 0, theta2: pi/2}, grade: [force.semi_axes]}
  - {type: orientation, matrix: [[1, 0, 0], [0, 0, -1], [0, 1, 0]], grade: [zyz]}
""")
    (tmp_path / "arm.yaml").write_text(problem, encoding="utf-8")
    # the force ellipse at theta = (0, pi/2): J = [[-L2, -L2], [L1, 0]], semi-axes (1/sqrt(nu))·v
    J = np.array([[-0.4, -0.4], [0.5, 0.0]])
    nu, V = np.linalg.eigh(J @ J.T)                  # ascending nu: decreasing force lengths
    axes = [-(V[:, i] / np.sqrt(nu[i])) for i in range(2)]     # each axis's sign is free
    typed_axes = [f"[{a[0]:.5f} {a[1]:.5f}]" for a in axes]
    # Rx(pi/2) = Rz(-pi/2)·Ry(pi/2)·Rz(pi/2), and the other triple (phi + pi, -theta, psi + pi)
    rz = lambda a: np.array([[np.cos(a), -np.sin(a), 0], [np.sin(a), np.cos(a), 0], [0, 0, 1]])  # noqa: E731
    ry = lambda a: np.array([[np.cos(a), 0, np.sin(a)], [0, 1, 0], [-np.sin(a), 0, np.cos(a)]])  # noqa: E731
    for phi, theta, psi in [(-np.pi / 2, np.pi / 2, np.pi / 2), (np.pi / 2, -np.pi / 2, -np.pi / 2)]:
        assert np.allclose(rz(phi) @ ry(theta) @ rz(psi), [[1, 0, 0], [0, 0, -1], [0, 1, 0]])
    answers = {
        "robosolve-answers": 1, "problem": "arm.yaml",
        "answers": {
            "position": {"chain": [
                "[cos(theta1) -sin(theta1) 0 L1*cos(theta1); sin(theta1) cos(theta1) 0 L1*sin(theta1); 0 0 1 0; 0 0 0 1]",
                "[cos(theta2), -sin(theta2), 0, L2*cos(theta2); sin(theta2), cos(theta2), 0, L2*sin(theta2);"
                " 0, 0, 1, 0; 0, 0, 0, 1]"]},
            "jacobian": {"com_jacobians": {"tip": (
                "[-L1*sin(theta1) - L2*sin(theta1 + theta2) -L2*sin(theta1 + theta2);"
                " L1*cos(theta1) + L2*cos(theta1 + theta2) L2*cos(theta1 + theta2); 0 0]")}},
            "ellipsoids": {"force.semi_axes": typed_axes},
            "orientation": {"zyz": {"solutions": ["[-pi/2 pi/2 pi/2]", "[pi/2; -pi/2; -pi/2]"], "singular": False}},
        }}
    (tmp_path / "a.yaml").write_text(json.dumps(answers), encoding="utf-8")
    r = runner.invoke(app, ["check", str(tmp_path / "a.yaml"), "--json", str(tmp_path / "r.json")])
    record = json.loads((tmp_path / "r.json").read_text())
    verdicts = {(q, k): v["verdict"] for q, rec in record["questions"].items() for k, v in rec["keys"].items()}
    assert verdicts == {("position", "chain"): "correct", ("jacobian", "com_jacobians"): "correct",
                        ("ellipsoids", "force.semi_axes"): "correct", ("orientation", "zyz"): "correct"}, verdicts
    assert r.exit_code == 0, r.output
