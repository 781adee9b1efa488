"""Variants (spec variants.md): the section's validation, the draws, `require`, the command.

`require` is checked independently: the planar 2R's direct kinematics and Jacobian are
written here with numpy (not robosolve's), and reachability is decided by the closed-form
2R inverse (law of cosines) with the joint limits applied by hand.
"""

from __future__ import annotations

import csv
import io
import itertools
import math
import textwrap
from pathlib import Path

import numpy as np
import pytest
import sympy as sp
from typer.testing import CliRunner

from robosolve.cli import app
from robosolve.errors import InputError
from robosolve.load.loader import load_problem, load_problem_text
from robosolve.variants.naming import count_ids, safe_name
from robosolve.variants.workflow import plan_variants

runner = CliRunner()

BASE = """\
robosolve: 1
name: arm
parameters: {L1: 1/2, L2: 2/5, m1: 4, x: 0.6, y: 0.3, q2a: pi/2}
joints:
  - {name: theta1, type: revolute, limits: [-pi, pi]}
  - {name: theta2, type: revolute, limits: [-deg(150), deg(150)]}
frames:
  "1": {pose: "Rz(theta1) Tx(L1)"}
  "2": {pose: "Rz(theta2) Tx(L2)"}
questions:
  - {type: jacobian, id: jac, at: {theta1: pi/6, theta2: q2a}}
  - {type: inverse_kinematics, id: ik, target: {E.x: x, E.y: y}}
"""

SECTION = """\
variants:
  parameters:
    L1: {range: [0.3, 0.6], step: 0.1}
    L2: {range: [0.2, 0.5], step: 0.1}
    m1: {choices: [2, 3, 4, 5]}
    x: {range: [0.1, 0.9], step: 0.2}
    q2a: {choices: [0, pi/3, pi/2, 2*pi/3]}
  require:
    - "L1 > L2"
    - {reachable: ik}
    - {nonsingular: jac}
"""


def problem_file(tmp_path, section=SECTION, base=BASE, name="arm.yaml") -> Path:
    p = tmp_path / name
    p.write_text(base + textwrap.dedent(section), encoding="utf-8")
    return p


def errors(text: str) -> list[str]:
    with pytest.raises(InputError) as exc:
        load_problem_text(text, "p.yaml")
    return [str(i) for i in exc.value.issues]


# ---------------------------------------------------------------------------
# the section, validated by the loader

def test_solve_ignores_a_valid_section():
    plain = load_problem_text(BASE, "p.yaml")
    with_section = load_problem_text(BASE + SECTION, "p.yaml")
    assert plain.variants is None
    assert [p.name for p in with_section.variants.parameters] == ["L1", "L2", "m1", "x", "q2a"]
    assert with_section.parameters == plain.parameters      # the base values are used
    L1 = with_section.variants.parameter("L1")
    assert [L1.value(i) for i in range(L1.size)] == [sp.Rational(k, 10) for k in range(3, 7)]


@pytest.mark.parametrize("section, expected", [
    ("variants:\n  parameters:\n    L3: {choices: [1, 2]}\n",
     "p.yaml:15: variants.parameters.L3: undeclared parameter 'L3' (did you mean 'L2'?) (a varied parameter "
     "must be declared in `parameters`, with its base value)"),
    ("variants:\n  parameters:\n    L1: {range: [0.6, 0.3], step: 0.05}\n",
     "p.yaml:15: variants.parameters.L1.range: empty range [0.6, 0.3]: the low end is above the high end"),
    ("variants:\n  parameters:\n    L1: {range: [0.3, 0.6], step: 0}\n",
     "p.yaml:15: variants.parameters.L1.step: the step must be positive, got 0"),
    ("variants:\n  parameters:\n    L1: {range: [0.3, 0.6], step: -0.1}\n",
     "p.yaml:15: variants.parameters.L1.step: the step must be positive, got -0.1"),
    ("variants:\n  parameters:\n    L1: {range: [0.3, 0.6]}\n",
     "p.yaml:15: variants.parameters.L1: a range needs a step (values range[0] + k*step within the range)"),
    ("variants:\n  parameters:\n    q2a: {choices: [pi/6, deg(30)]}\n",
     "p.yaml:15: variants.parameters.q2a.choices[1]: choices must be distinct: 'deg(30)' equals 'pi/6'"),
    ("variants:\n  parameters:\n    m1: {choices: []}\n",
     "p.yaml:15: variants.parameters.m1.choices: expected a non-empty list of values"),
    ("variants:\n  parameters:\n    m1: {choises: [1, 2]}\n",
     "p.yaml:15: variants.parameters.m1.choises: unknown key 'choises' (did you mean 'choices'?) "
     "(expected one of: range, step, choices)"),
    ("variants:\n  parameters:\n    m1: {choices: [1, 2]}\n  require:\n    - {reachable: ikk}\n",
     "p.yaml:17: variants.require[0].reachable: unknown question id 'ikk' (did you mean 'ik'?) (known: jac, ik)"),
    ("variants:\n  parameters:\n    m1: {choices: [1, 2]}\n  require:\n    - {reachable: jac}\n",
     "p.yaml:17: variants.require[0].reachable: question 'jac' is a jacobian question: reachable needs an "
     "inverse_kinematics question"),
    ("variants:\n  parameters:\n    m1: {choices: [1, 2]}\n  require:\n    - {nonsingular: ik}\n",
     "p.yaml:17: variants.require[0].nonsingular: question 'ik' is a inverse_kinematics question: nonsingular "
     "needs a question with a Jacobian (jacobian, statics, ellipsoids)"),
    ("variants:\n  parameters:\n    m1: {choices: [1, 2]}\n  require:\n    - \"m1 = 2\"\n",
     "p.yaml:17: variants.require[0]: expected one inequality such as \"L1 > L2\" (operators < <= > >=), "
     "got 'm1 = 2'"),
    ("variants:\n  parameters:\n    m1: {choices: [1, 2]}\n  require:\n    - \"m1 > L\"\n",
     "p.yaml:17: variants.require[0]: unknown parameter 'L' in 'L' (did you mean 'L2'?)"),
    ("variants:\n  parameters:\n    m1: {choices: [1, 2]}\n  require:\n    - \"L1 > L2\"\n",
     "p.yaml:17: variants.require[0]: 'L1 > L2' involves no varied parameter: it would hold for every variant "
     "or for none"),
    ("variants:\n  parameters:\n    theta1: {choices: [1, 2]}\n",
     "p.yaml:15: variants.parameters.theta1: 'theta1' is a joint, not a parameter: vary a joint value through "
     "a parameter used in `at`, a target or a profile"),
    # one mistake, one message: a condition on a parameter whose entry is wrong says nothing more
    ("variants:\n  parameterss:\n    L1: {choices: [1, 2]}\n  require:\n    - \"L1 > L2\"\n",
     "p.yaml:14: variants.parameterss: unknown key 'parameterss' (did you mean 'parameters'?) "
     "(expected one of: parameters, require)"),
    ("variants:\n  parameters:\n    L1: {range: [0.3, 0.6]}\n  require:\n    - \"L1 > L2\"\n",
     "p.yaml:15: variants.parameters.L1: a range needs a step (values range[0] + k*step within the range)"),
    ("variants:\n  parameters: {m1: {choices: [1, 2]}}\n  requires: []\n",
     "p.yaml:15: variants.requires: unknown key 'requires' (did you mean 'require'?) "
     "(expected one of: parameters, require)"),
])
def test_invalid_sections_give_file_line_messages(section, expected):
    assert errors(BASE + section) == [expected]


def test_a_condition_on_a_parameter_defined_from_a_varied_one_follows_the_draw(tmp_path):
    """`Lc: L1/2` follows a drawn L1 (docs/variants.md), so "Lc > 0.2" is a condition on L1 —
    it was refused as one that 'involves no varied parameter'. By hand: L1/2 > 0.2 keeps 0.5
    and 0.6 of the three choices."""
    base = BASE.replace("parameters: {L1: 1/2,", "parameters: {Lc: L1/2, L1: 1/2,")
    section = "variants:\n  parameters:\n    L1: {choices: [0.3, 0.5, 0.6]}\n  require:\n    - \"Lc > 0.2\"\n"
    plan = plan_variants(problem_file(tmp_path, section, base=base), [("1", ""), ("2", "")], seed=0)
    assert sorted(v.values["L1"] for v in plan.variants) == [sp.Rational(1, 2), sp.Rational(3, 5)]


def test_cli_solve_and_validate_reject_a_bad_section(tmp_path):
    p = problem_file(tmp_path, "variants:\n  parameters:\n    L1: {range: [0.3, 0.6], step: 0}\n")
    result = runner.invoke(app, ["validate", str(p)])
    assert result.exit_code == 2
    result = runner.invoke(app, ["solve", str(p), "--out", str(tmp_path / "o")])
    assert result.exit_code == 2 and not (tmp_path / "o").exists()


# ---------------------------------------------------------------------------
# independent checks of the 2R arm (numpy, not robosolve)

def fk(L1, L2, t1, t2):
    return np.array([L1 * math.cos(t1) + L2 * math.cos(t1 + t2), L1 * math.sin(t1) + L2 * math.sin(t1 + t2)])


def jacobian(L1, L2, t1, t2):
    s1, c1, s12, c12 = math.sin(t1), math.cos(t1), math.sin(t1 + t2), math.cos(t1 + t2)
    return np.array([[-L1 * s1 - L2 * s12, -L2 * s12], [L1 * c1 + L2 * c12, L2 * c12]])


def reachable(L1, L2, x, y, t2_max=math.radians(150)):
    """Law of cosines: cos t2 = (d² − L1² − L2²)/(2 L1 L2); a solution inside |t2| <= t2_max."""
    c = (x * x + y * y - L1 * L1 - L2 * L2) / (2 * L1 * L2)
    if c > 1 + 1e-12 or c < -1 - 1e-12:
        return False
    t2 = math.acos(max(-1.0, min(1.0, c)))
    for s in (t2, -t2):
        t1 = math.atan2(y, x) - math.atan2(L2 * math.sin(s), L1 + L2 * math.cos(s))
        assert np.allclose(fk(L1, L2, t1, s), [x, y], atol=1e-9)
        if abs(s) <= t2_max + 1e-9:
            return True
    return False


def test_draws_stay_in_their_sets_and_meet_require(tmp_path):
    p = problem_file(tmp_path)
    plan = plan_variants(p, [(i, "") for i in count_ids(40)], seed=7)
    sets = {"L1": {sp.Rational(k, 10) for k in range(3, 7)}, "L2": {sp.Rational(k, 10) for k in range(2, 6)},
            "m1": {2, 3, 4, 5}, "x": {sp.Rational(k, 10) for k in range(1, 10, 2)},
            "q2a": {0, sp.pi / 3, sp.pi / 2, 2 * sp.pi / 3}}
    seen = set()
    for v in plan.variants:
        vals = v.values
        for name, allowed in sets.items():
            assert vals[name] in allowed, (v.id, name, vals[name])
        L1, L2, x, q2 = (float(vals[n]) for n in ("L1", "L2", "x", "q2a"))
        assert L1 > L2
        assert reachable(L1, L2, x, 0.3), v.id
        sv = np.linalg.svd(jacobian(L1, L2, math.pi / 6, q2), compute_uv=False)
        assert sv[-1] > 1e-6 * sv[0], v.id
        key = tuple(vals[n] for n in sets)
        assert key not in seen
        seen.add(key)
    # the conditions bite: q2a = 0 (singular) and short arms (unreachable) exist in the grid
    assert any(not reachable(a / 10, b / 10, c / 10, 0.3)
               for a, b, c in itertools.product(range(3, 7), range(2, 6), range(1, 10, 2)) if a > b)


def test_the_count_agrees_with_an_independent_enumeration(tmp_path):
    from robosolve.variants.draw import Drawer
    from robosolve.variants.require import RequirementChecker
    from robosolve.variants.workflow import load_source, template_problem

    p = problem_file(tmp_path)
    problem, data = load_source(p)
    drawer = Drawer(problem.variants, RequirementChecker(template_problem(data, problem), problem.variants,
                                                         str(p)), 0, str(p))
    expected = 0
    for a, b, m, c, q in itertools.product(range(3, 7), range(2, 6), range(4), range(1, 10, 2), range(4)):
        q2 = (0, math.pi / 3, math.pi / 2, 2 * math.pi / 3)[q]
        sv = np.linalg.svd(jacobian(a / 10, b / 10, math.pi / 6, q2), compute_uv=False)
        expected += a > b and reachable(a / 10, b / 10, c / 10, 0.3) and sv[-1] > 1e-6 * sv[0]
    assert drawer.count() == expected


def test_a_few_variants_do_not_count_the_whole_grid_first(tmp_path, monkeypatch):
    """Two variants of a 21 × 21 × 41 grid of lengths and targets: robosolve ran the IK search of
    every combination (18,081 of them, minutes) before drawing the first; the draws check a few.
    Each drawn target is reachable by the closed-form 2R inverse written here."""
    import robosolve.ik.numeric as numeric

    searches = []
    real = numeric.solve_all
    monkeypatch.setattr(numeric, "solve_all", lambda *a, **k: searches.append(1) or real(*a, **k))
    section = ("variants:\n  parameters:\n    L1: {range: [0.4, 0.6], step: 0.01}\n"
               "    L2: {range: [0.2, 0.4], step: 0.01}\n    x: {range: [0.3, 0.7], step: 0.01}\n"
               "  require:\n    - {reachable: ik}\n")
    plan = plan_variants(problem_file(tmp_path, section), [(i, "") for i in count_ids(2)], seed=0)
    assert len(plan.variants) == 2 and len(searches) < 50
    for v in plan.variants:
        assert reachable(*(float(v.values[n]) for n in ("L1", "L2", "x")), 0.3)


def test_variant_k_does_not_change_when_the_count_grows(tmp_path):
    p = problem_file(tmp_path)
    small = plan_variants(p, [(i, "") for i in count_ids(5)], seed=3)
    large = plan_variants(p, [(i, "") for i in count_ids(8)], seed=3)
    assert [v.values for v in small.variants] == [v.values for v in large.variants[:5]]
    other = plan_variants(p, [(i, "") for i in count_ids(5)], seed=4)
    assert [v.values for v in other.variants] != [v.values for v in small.variants]


def test_too_few_distinct_variants_is_an_error_with_the_count(tmp_path):
    section = ("variants:\n  parameters:\n    L1: {choices: [0.3, 0.4, 0.5]}\n    L2: {choices: [0.3, 0.4]}\n"
               "  require:\n    - \"L1 > L2\"\n")
    p = problem_file(tmp_path, section)
    out = tmp_path / "out"
    result = runner.invoke(app, ["variants", str(p), "--count", "4", "--out", str(out), "--no-solve"])
    assert result.exit_code == 2
    assert f"{p}:13: variants: only 3 distinct variants meet `require` (4 asked)" in result.output
    assert not out.exists()
    # exactly as many as exist: all of them, each once
    result = runner.invoke(app, ["variants", str(p), "--count", "3", "--out", str(out), "--no-solve"])
    assert result.exit_code == 0, result.output
    rows = list(csv.DictReader(io.StringIO((out / "variants.csv").read_text())))
    assert sorted((r["L1"], r["L2"]) for r in rows) == [("1/2", "2/5"), ("1/2", "3/10"), ("2/5", "3/10")]


def test_a_condition_no_drawn_value_meets_is_named_at_its_line(tmp_path):
    """L1 is drawn from 0.3 … 0.6 and `require` asks L1 > 1: the message said only that 0 variants
    meet `require`, at the section's line, leaving the teacher to find which condition; conditions
    each met by some values but never together keep that message."""
    section = ("variants:\n  parameters:\n    L1: {range: [0.3, 0.6], step: 0.1}\n"
               "    L2: {range: [0.2, 0.5], step: 0.1}\n  require:\n    - \"L1 > L2\"\n    - \"L1 > 1\"\n")
    p = problem_file(tmp_path, section)
    result = runner.invoke(app, ["variants", str(p), "--count", "2", "--out", str(tmp_path / "o"), "--no-solve"])
    assert result.exit_code == 2 and not (tmp_path / "o").exists()
    assert (f"{p}:19: variants.require[1]: only 0 distinct variants meet `require` (2 asked): 'L1 > 1' holds "
            "for none of the values the section draws; widen the ranges or relax the condition") in result.output
    p = problem_file(tmp_path, section.replace('"L1 > 1"', '"L2 > L1"'))
    result = runner.invoke(app, ["variants", str(p), "--count", "2", "--out", str(tmp_path / "o"), "--no-solve"])
    assert result.exit_code == 2
    assert f"{p}:13: variants: only 0 distinct variants meet `require` (2 asked)" in result.output


def test_a_condition_that_never_holds_stops_after_1000_draws(tmp_path):
    section = ("variants:\n  parameters:\n    L1: {range: [0, 1], step: 0.000001}\n"
               "  require:\n    - \"L1 > 2\"\n")
    p = problem_file(tmp_path, section)
    result = runner.invoke(app, ["variants", str(p), "--count", "2", "--out", str(tmp_path / "o"), "--no-solve"])
    assert result.exit_code == 2
    assert (f"{p}:17: variants.require[0]: variant 1: 1000 draws in a row are rejected (1000 of them by this "
            "condition, 'L1 > 2'): widen the ranges or relax the condition") in result.output
    assert not (tmp_path / "o").exists()


# ---------------------------------------------------------------------------
# names and the roster

@pytest.mark.parametrize("student, name", [
    ("Jo Smith", "jo-smith"), ("2024/017", "2024-017"), ("  Ann--Lee!! ", "ann--lee"), ("s_12", "s_12"),
    ("Émile Zola", "mile-zola"), ("--x--", "x")])
def test_safe_names(student, name):
    assert safe_name(student) == name


def test_count_ids_are_zero_padded():
    assert count_ids(9)[-1] == "9" and count_ids(12)[:2] == ["01", "02"] and count_ids(200)[0] == "001"
    assert count_ids(200)[-1] == "200"


def test_roster_collisions_are_input_errors(tmp_path):
    p = problem_file(tmp_path)
    roster = tmp_path / "class.csv"
    roster.write_text("student,email\nJo Smith,a@b\nAnn,c@d\njo  smith,e@f\n", encoding="utf-8")
    result = runner.invoke(app, ["variants", str(p), "--roster", str(roster), "--out", str(tmp_path / "o")])
    assert result.exit_code == 2
    assert (f"{roster}:4: student: 'jo  smith' and 'Jo Smith' (line 2) give the same folder name 'jo-smith'"
            in result.output)
    roster.write_text("name\nJo\n", encoding="utf-8")
    result = runner.invoke(app, ["variants", str(p), "--roster", str(roster), "--out", str(tmp_path / "o")])
    assert result.exit_code == 2 and "no `student` column (columns: name)" in result.output


def test_roster_messages_give_the_line_a_row_starts_on_and_quote_long_ids_short(tmp_path):
    """A quoted cell over two lines (a spreadsheet's note) shifted every later line number by one;
    a 5,000-character id was quoted whole."""
    from robosolve.errors import InputError
    from robosolve.variants.naming import read_roster

    roster = tmp_path / "class.csv"
    roster.write_text('student,notes\nJo,"two\nlines"\nAnn,x\nann,y\n', encoding="utf-8")
    with pytest.raises(InputError) as err:
        read_roster(roster)
    assert [str(i) for i in err.value.issues] == [
        f"{roster}:5: student: 'ann' and 'Ann' (line 4) give the same folder name 'ann'"]
    roster.write_text("student\n" + "é" * 5000 + "\n", encoding="utf-8")
    with pytest.raises(InputError) as err:
        read_roster(roster)
    assert len(str(err.value.issues[0])) < 400 and "gives an empty folder name" in str(err.value.issues[0])


@pytest.mark.parametrize("condition", ["1/(m1 - 4) > 0", "sqrt(m1 - 4) > 0", "log(m1 - 4) > -10"])
def test_a_condition_without_value_for_a_draw_is_not_met(tmp_path, condition):
    """m1 = 4 makes the condition 1/0, sqrt(0)... : a draw where it has no real value (or is 0
    against > 0) is drawn again; it ended `variants` with a Python traceback (a complex number)."""
    section = f"variants:\n  parameters:\n    m1: {{choices: [4, 5, 6]}}\n  require:\n    - \"{condition}\"\n"
    p = problem_file(tmp_path, section)
    r = runner.invoke(app, ["variants", str(p), "--count", "2", "--no-solve", "--out", str(tmp_path / "o")])
    assert r.exit_code == 0, r.output
    rows = list(csv.DictReader(io.StringIO((tmp_path / "o" / "variants.csv").read_text())))
    assert sorted(row["m1"] for row in rows) == ["5", "6"]
    from robosolve.variants.require import _exact_sign
    assert _exact_sign(sp.sqrt(-1) - 0) is None and _exact_sign(sp.Integer(1) / 0) is None
    assert _exact_sign(sp.sqrt(2) - sp.Rational(141421356237, 10**11)) == 1


PLANAR_3R_POSE = """\
robosolve: 1
name: p3
parameters: {L1: 1/2, L2: 2/5, L3: 1/10, x: 0.6, y: 0.2, phi: 0}
joints:
  - {name: q1, type: revolute, limits: [-pi, pi]}
  - {name: q2, type: revolute, limits: [0, deg(150)]}
  - {name: q3, type: revolute, limits: [-pi, pi]}
frames:
  "1": {pose: "Rz(q1) Tx(L1)"}
  "2": {pose: "Rz(q2) Tx(L2)"}
  "3": {pose: "Rz(q3) Tx(L3)"}
questions:
  - {type: inverse_kinematics, id: ik, target: {position: [x, y, 0], rpy: [0, 0, phi]}}
variants:
  parameters:
    x: {choices: [0.2, 0.6]}
    phi: {choices: [0, pi]}
  require:
    - {reachable: ik}
"""


def test_reachable_of_a_pose_target_agrees_with_the_planar_3r_closed_form(tmp_path):
    """`reachable` on an IK question with a pose target (it stopped `variants` with 'cannot be
    checked'): the reference is the planar 3R by hand — the wrist point p − L3·(cos φ, sin φ),
    then the law of cosines with q2 in its limits [0, 150°]."""
    from robosolve.variants.require import RequirementChecker
    from robosolve.variants.workflow import load_source, template_problem

    p = problem_file(tmp_path, "", base=PLANAR_3R_POSE)
    problem, data = load_source(p)
    spec = problem.variants
    checker = RequirementChecker(template_problem(data, problem), spec, str(p))

    def by_hand(x, phi, y=0.2, L1=0.5, L2=0.4, L3=0.1):
        wx, wy = x - L3 * math.cos(phi), y - L3 * math.sin(phi)
        c = (wx * wx + wy * wy - L1 * L1 - L2 * L2) / (2 * L1 * L2)
        return abs(c) <= 1 and 0 <= math.acos(c) <= math.radians(150)

    # (0.2, 0): the elbow would need 154°, beyond its limit; (0.6, 0): reachable
    for idx in ((0, 0), (1, 0)):
        x, phi = (float(par.value(i)) for par, i in zip(spec.parameters, idx))
        assert (checker.first_failure(idx) is None) == by_hand(x, phi), (x, phi)
    assert not by_hand(0.2, 0) and by_hand(0.6, 0)


def test_roster_student_k_gets_variant_k(tmp_path):
    p = problem_file(tmp_path)
    roster = tmp_path / "class.csv"
    roster.write_text("student\nJo Smith\n2024/017\nAnn\n", encoding="utf-8")
    by_roster = tmp_path / "r"
    by_count = tmp_path / "c"
    assert runner.invoke(app, ["variants", str(p), "--roster", str(roster), "--out", str(by_roster),
                               "--no-solve", "--seed", "5"]).exit_code == 0
    assert runner.invoke(app, ["variants", str(p), "--count", "3", "--out", str(by_count), "--no-solve",
                               "--seed", "5"]).exit_code == 0
    r = list(csv.reader(io.StringIO((by_roster / "variants.csv").read_text())))
    c = list(csv.reader(io.StringIO((by_count / "variants.csv").read_text())))
    assert r[0] == c[0] == ["variant", "student", "seed", "L1", "L2", "m1", "x", "q2a"]
    assert [row[:3] for row in r[1:]] == [["jo-smith", "Jo Smith", "5"], ["2024-017", "2024/017", "5"],
                                          ["ann", "Ann", "5"]]
    assert [row[3:] for row in r[1:]] == [row[3:] for row in c[1:]]
    assert [row[:3] for row in c[1:]] == [["1", "", "5"], ["2", "", "5"], ["3", "", "5"]]
    assert sorted(x.name for x in by_roster.iterdir()) == [".robosolve", "arm-2024-017", "arm-ann",
                                                           "arm-jo-smith", "roster.csv", "variants.csv"]
    assert (by_roster / "roster.csv").read_text() == "variant,student\njo-smith,Jo Smith\n2024-017,2024/017\nann,Ann\n"


@pytest.mark.parametrize("sep", [";", "\t"], ids=["semicolons", "tabs"])
def test_a_roster_saved_with_semicolons_or_tabs_is_read_as_with_commas(tmp_path, sep):
    """Spreadsheets in many locales save CSV with `;` (`,` is their decimal mark), some LMS exports
    with tabs: the same students, the same variants, and DIR/roster.csv written with commas."""
    p = problem_file(tmp_path)
    rows = [["Student", "Email", "Note"], ["Jo Smith", "jo@x.org", "1,5"], ["2024/017", "b@x.org", ""]]
    commas, other = tmp_path / "commas.csv", tmp_path / "other.csv"
    with open(commas, "w", newline="", encoding="utf-8") as fh:
        csv.writer(fh, lineterminator="\n").writerows(rows)
    with open(other, "w", newline="", encoding="utf-8") as fh:
        csv.writer(fh, delimiter=sep, lineterminator="\n").writerows(rows)
    outs = []
    for roster in (commas, other):
        out = tmp_path / roster.stem
        result = runner.invoke(app, ["variants", str(p), "--roster", str(roster), "--out", str(out), "--no-solve"])
        assert result.exit_code == 0, result.output
        outs.append(out)
    for name in ("variants.csv", "roster.csv"):
        assert (outs[0] / name).read_bytes() == (outs[1] / name).read_bytes()
    assert list(csv.reader(io.StringIO((outs[1] / "roster.csv").read_text()))) == [
        ["variant", "Student", "Email", "Note"], ["jo-smith", "Jo Smith", "jo@x.org", "1,5"],
        ["2024-017", "2024/017", "b@x.org", ""]]


# ---------------------------------------------------------------------------
# the command's outputs

def tree(folder: Path) -> dict:
    return {p.relative_to(folder).as_posix(): p.read_bytes() for p in sorted(folder.rglob("*")) if p.is_file()}


@pytest.fixture(scope="module")
def solved(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("variants")
    p = problem_file(tmp)
    out = tmp / "out"
    result = runner.invoke(app, ["variants", str(p), "--count", "3", "--out", str(out), "--jobs", "2"])
    assert result.exit_code == 0, result.output
    return tmp, p, out


def test_outputs_layout_and_csv(solved):
    tmp, p, out = solved
    names = sorted(x.name for x in out.iterdir())
    assert names == [".robosolve", "arm-1", "arm-2", "arm-3", "variants.csv"]
    for v in ("arm-1", "arm-2", "arm-3"):
        assert {"problem.yaml", "report.md", "results.json"} <= {x.name for x in (out / v).iterdir()}
    rows = list(csv.reader(io.StringIO((out / "variants.csv").read_text())))
    assert rows[0] == ["variant", "student", "seed", "L1", "L2", "m1", "x", "q2a"]
    for row in rows[1:]:
        problem = load_problem(out / f"arm-{row[0]}" / "problem.yaml")
        assert problem.name == f"arm-{row[0]}" and problem.variants is None
        values = {s.name: v for s, v in problem.parameters.items()}
        for name, text in zip(rows[0][3:], row[3:]):
            assert values[name] == sp.sympify(text)      # exact values, written as expressions


def test_rerun_is_byte_identical_and_each_variant_resolves_identically(solved, tmp_path):
    tmp, p, out = solved
    again = tmp_path / "again"
    result = runner.invoke(app, ["variants", str(p), "--count", "3", "--out", str(again), "--jobs", "1"])
    assert result.exit_code == 0, result.output
    assert tree(again) == tree(out)
    # robosolve solve on a variant's problem.yaml gives its report and results
    target = tmp_path / "solo"
    assert runner.invoke(app, ["solve", str(out / "arm-2" / "problem.yaml"), "--out", str(target)]).exit_code == 0
    for f in ("report.md", "results.json"):
        assert (target / f).read_bytes() == (out / "arm-2" / f).read_bytes()


def test_an_unmarked_folder_is_refused_and_left_alone(tmp_path):
    p = problem_file(tmp_path)
    out = tmp_path / "mine"
    out.mkdir()
    (out / "notes.txt").write_text("keep me")
    result = runner.invoke(app, ["variants", str(p), "--count", "2", "--out", str(out), "--no-solve"])
    assert result.exit_code == 2 and "holds files robosolve did not write (notes.txt)" in result.output
    assert [x.name for x in out.iterdir()] == ["notes.txt"]


def test_a_rerun_replaces_its_own_folder(tmp_path):
    p = problem_file(tmp_path)
    out = tmp_path / "o"
    assert runner.invoke(app, ["variants", str(p), "--count", "3", "--out", str(out), "--no-solve"]).exit_code == 0
    assert runner.invoke(app, ["variants", str(p), "--count", "2", "--out", str(out), "--no-solve"]).exit_code == 0
    assert sorted(x.name for x in out.iterdir()) == [".robosolve", "arm-1", "arm-2", "variants.csv"]
    assert not [x for x in tmp_path.iterdir() if x.name.startswith(".")]     # no staging debris


def test_usage_errors(tmp_path):
    p = problem_file(tmp_path)
    out = str(tmp_path / "o")
    assert runner.invoke(app, ["variants", str(p), "--out", out]).exit_code == 2
    r = runner.invoke(app, ["variants", str(p), "--count", "2", "--out", out, "--format", "md,pdf"])
    assert r.exit_code == 2 and "unknown format 'pdf'" in r.output
    r = runner.invoke(app, ["variants", str(p), "--count", "2", "--out", out, "--scheduler", "nowhere"])
    assert r.exit_code == 2 and "expected 'local' or an address" in r.output
    plain = tmp_path / "plain.yaml"
    plain.write_text(BASE)
    r = runner.invoke(app, ["variants", str(plain), "--count", "2", "--out", out])
    assert r.exit_code == 2 and "no `variants` section" in r.output
    assert not Path(out).exists()


def test_without_dask_scheduler_says_how_to_install(tmp_path, monkeypatch):
    import importlib.util

    real = importlib.util.find_spec
    monkeypatch.setattr(importlib.util, "find_spec",
                        lambda name, *a: None if name == "distributed" else real(name, *a))
    p = problem_file(tmp_path)
    for args in (["variants", str(p), "--count", "2", "--out", str(tmp_path / "o")],
                 ["batch", str(tmp_path), "--out", str(tmp_path / "b")]):
        r = runner.invoke(app, args + ["--scheduler", "local"])
        assert r.exit_code == 2 and 'pip install "robosolve[dask]"' in r.output
    assert not (tmp_path / "o").exists() and not (tmp_path / "b").exists()


# ---------------------------------------------------------------------------
# the classroom workflow, end to end: roster -> variants -> answers -> grade --variants

def test_roster_to_grades_each_student_against_their_own_variant(tmp_path):
    """The manipulability of the planar 2R (J is 3x2, its z row zero) is |det| = L1*L2*|sin(theta2)|
    (closed form, computed here from variants.csv): Jo answers with Jo's values, Ann copies Jo."""
    import yaml

    p = problem_file(tmp_path)
    roster = tmp_path / "class.csv"
    roster.write_text("student\nJo Smith\nAnn\n", encoding="utf-8")
    exams = tmp_path / "exams"
    r = runner.invoke(app, ["variants", str(p), "--roster", str(roster), "--out", str(exams), "--no-solve"])
    assert r.exit_code == 0, r.output
    rows = {row["student"]: row for row in csv.DictReader(io.StringIO((exams / "variants.csv").read_text()))}

    def det(row):
        return abs(float(sp.sympify(row["L1"]) * sp.sympify(row["L2"]) * sp.sin(sp.sympify(row["q2a"]))))

    assert abs(det(rows["Jo Smith"]) - det(rows["Ann"])) > 0.01 * abs(det(rows["Ann"]))
    subs = tmp_path / "subs"
    subs.mkdir()
    for student, fname in (("Jo Smith", "jo.yaml"), ("Ann", "ann.yaml")):
        (subs / fname).write_text(yaml.safe_dump({
            "robosolve-answers": 1, "student": student,
            "answers": {"jac": {"manipulability": round(det(rows["Jo Smith"]), 5)}}}), encoding="utf-8")
    grades = tmp_path / "grades"
    r = runner.invoke(app, ["grade", str(subs), "--variants", str(exams), "--out", str(grades)])
    assert r.exit_code in (0, 1), r.output
    lines = list(csv.DictReader(io.StringIO((grades / "grades.csv").read_text())))
    det_rows = {row["student"]: row["verdict"] for row in lines if row["question"] == "jac" and row["key"] == "manipulability"}
    assert det_rows == {"Jo Smith": "correct", "Ann": "incorrect"}


def test_a_draw_that_breaks_the_problem_is_one_message_about_the_source(tmp_path):
    """m1 drawn negative makes the body's mass invalid: the message names the source file's
    `variants` line and the drawn values (the variant's own problem.yaml is never written)."""
    base = BASE.replace("questions:", 'bodies:\n  - {name: tip, frame: "2", mass: m1, point: [0, 0, 0]}\nquestions:')
    section = """\
    variants:
      parameters:
        m1: {range: [-2, -1], step: 1}
    """
    p = problem_file(tmp_path, section=section, base=base)
    out = tmp_path / "o"
    r = runner.invoke(app, ["variants", str(p), "--count", "2", "--out", str(out), "--no-solve"])
    assert r.exit_code == 2
    lines = [x for x in r.output.splitlines() if x.strip()]
    variants_line = base.count("\n") + 1
    assert len(lines) == 1, r.output
    assert lines[0].startswith(f"{p}:{variants_line}: variants: variant "), lines[0]
    assert "m1 = -" in lines[0] and "mass" in lines[0] and "1 more variant" in lines[0]
    assert not out.exists()
