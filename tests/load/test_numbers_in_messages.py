"""Messages show numbers as the user wrote them or in a short form, never a 301-digit fraction:
a variants step of 1e-300 printed 1/10**300's digits twice; a long exact number given as a
parameter or an answer was quoted whole; float limits were printed as sympy's 15-digit Floats."""

from __future__ import annotations

import re
from decimal import Decimal
from pathlib import Path

import pytest
from typer.testing import CliRunner

from robosolve.cli import app
from robosolve.errors import InputError
from robosolve.load.loader import load_problem_text

ROOT = Path(__file__).resolve().parents[2]
RODS = (ROOT / "problems" / "planar-2r-rods.yaml").read_text(encoding="utf-8")
runner = CliRunner()


def _issues(text: str) -> list[str]:
    with pytest.raises(InputError) as exc:
        load_problem_text(text, "p.yaml")
    return [str(i) for i in exc.value.issues]


def _longest_digit_run(text: str) -> int:
    return max((len(m) for m in re.findall(r"\d+", text)), default=0)


def test_a_variants_step_of_too_many_digits_is_said_at_its_line_as_written():
    out = _issues(RODS + "variants:\n  parameters:\n    L1: {range: [0, 1], step: 1e-300}\n")
    assert len(out) == 1 and out[0].startswith("p.yaml:58: variants.parameters.L1.step: 1e-300 is an exact "
                                               "number of 301 digits"), out
    assert _longest_digit_run(out[0]) <= 3


def test_a_drawn_value_of_too_many_digits_is_shown_by_its_decimal_value(tmp_path):
    """Every step and bound is short, the values drawn are not: 1 + k·1e-29 up to 100 has 31
    digits. The message names the draw in a short decimal form, and its size."""
    p = tmp_path / "p.yaml"
    p.write_text(RODS + "variants:\n  parameters:\n    L1: {range: [1, 100], step: 1e-29}\n", encoding="utf-8")
    r = runner.invoke(app, ["variants", str(p), "--count", "2", "--out", str(tmp_path / "o"), "--no-solve"])
    assert r.exit_code == 2, r.output
    drawn = re.search(r"draws L1 ≈ ([0-9.]+), which is not a valid problem: parameters\.L1: the value is an exact "
                      r"number of 31 digits", r.output)
    assert drawn and 1 <= float(drawn.group(1)) <= 100, r.output
    assert _longest_digit_run(r.output) <= 12 and not (tmp_path / "o").exists()


def _variants_message(tmp_path, text: str) -> str:
    p = tmp_path / "p.yaml"
    p.write_text(text, encoding="utf-8")
    r = runner.invoke(app, ["variants", str(p), "--count", "2", "--out", str(tmp_path / "o"), "--no-solve"])
    assert r.exit_code == 2 and not (tmp_path / "o").exists(), r.output
    lines = [x for x in r.output.splitlines() if x.strip()]
    assert len(lines) == 1, r.output
    return lines[0].replace(str(p), "p.yaml")


def test_a_drawn_value_of_too_many_digits_gets_advice_about_its_range_not_about_typing_it(tmp_path):
    """A drawn value of 1 + k/10^29 in [10, 100] has a numerator of 31 digits (by hand): nobody
    typed it, so the advice is the loader's for a typed value no more ("write it as a decimal
    number") but about the range and step that drew it, told at that entry's line (58)."""
    line = _variants_message(tmp_path, RODS + "variants:\n  parameters:\n    L1: {range: [1, 100], step: 1e-29}\n")
    assert line.startswith("p.yaml:58: variants.parameters.L1: variant 2 draws L1 ≈ "), line
    assert "parameters.L1: the value is an exact number of 31 digits" in line
    assert "decimal number" not in line and "of its problem.yaml" not in line
    assert line.endswith("the values drawn from range [1, 100], step 1e-29 are that long: use a coarser step "
                         "(fewer digits in the step and the range's ends); nothing was written"), line


def test_a_parameter_computed_from_a_draw_names_the_draw_it_comes_from(tmp_path):
    """L2 = L1/11 with L1 = k/10^29 (30 digits at most): its denominator 11·10^29 has 31 digits
    (by hand), so L2 is refused; the message is told at L1's entry, the draw that made it."""
    text = RODS.replace("L2: 1/2", "L2: L1/11") + "variants:\n  parameters:\n    L1: {range: [0, 1], step: 1e-29}\n"
    assert len(str(11 * 10**29)) == 31
    line = _variants_message(tmp_path, text)
    assert line.startswith("p.yaml:58: variants.parameters.L1: variant "), line
    assert "parameters.L2: L1/11 is an exact number of 31 digits" in line and "decimal number" not in line
    assert "it is computed from L1, whose values drawn from range [0, 1], step 1e-29 have too many digits: " \
           "use a coarser step" in line, line


def test_a_long_exact_parameter_is_said_by_its_size():
    digits = "1" * 45
    out = _issues(RODS.replace("L2: 1/2", f"L2: {digits}"))
    assert out == [f"p.yaml:12: parameters.L2: the value is an exact number of 45 digits (about "
                   f"{float(Decimal(digits)):.3g}): robosolve keeps exact numbers of at most 30 digits, whose "
                   "arithmetic stays fast; write it as a decimal number"]


def test_float_limits_are_quoted_as_written():
    out = _issues(RODS.replace("limits: [-pi, pi]", "limits: [0.1, 0.05]"))
    assert out == ["p.yaml:18: joints[0].limits: lower limit 0.1 is not below upper limit 0.05"]
    out = _issues(RODS.replace("limits: [-pi, pi]", "limits: [-0.5, 0.5]") + "paper: {at: {theta1: 1.5}}\n")
    assert out == ["p.yaml:56: paper.at.theta1: 1.5 is outside the limits of theta1 [-0.5, 0.5]"]


def test_a_huge_given_answer_is_shown_in_four_digits(tmp_path):
    from tests._grading import TWO_R, dedent

    (tmp_path / "two-r.yaml").write_text(dedent(TWO_R), encoding="utf-8")
    given = "7" * 400
    (tmp_path / "a.yaml").write_text(f"robosolve-answers: 1\nproblem: two-r.yaml\nanswers:\n  jacobian:\n"
                                     f"    det: {given}\n", encoding="utf-8")
    r = runner.invoke(app, ["check", str(tmp_path / "a.yaml"), "--json", "-"])
    expected = f"given {Decimal(given):.3e}".replace("E+", "e+")         # 7.778e+399
    assert expected in r.output and _longest_digit_run(r.output) < 20, r.output


def test_a_draw_that_breaks_a_rule_is_placed_at_the_line_of_the_source_it_breaks(tmp_path):
    """A negative mass drawn for m1: the variant's problem.yaml is never written (and is dumped
    from data, its lines are not the source's), so the message cites the source's line of
    bodies[0].mass — found here by reading the file's text."""
    text = RODS + "variants:\n  parameters:\n    m1: {choices: [-2, -1]}\n"
    mass_line = next(i for i, x in enumerate(text.splitlines(), 1) if "mass: m1" in x)
    line = _variants_message(tmp_path, text)
    assert "bodies[0].mass: a mass cannot be negative" in line, line
    assert f"(line {mass_line} of p.yaml)" in line and "its problem.yaml" not in line, line
