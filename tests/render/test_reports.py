"""Report wording and layout (issue 16): course notes, stated configurations, the
position chain, readable line lengths. Checks against the golden reports and small
problems whose numbers are computed here independently (numpy, by hand)."""

import json
import math
import re
from pathlib import Path

import numpy as np
import pytest

from robosolve.core.course_notes import NOTES, notes_page
from robosolve.run.pipeline import solve_file
from robosolve.render.markdown import render_report

ROOT = Path(__file__).resolve().parents[2]
GOLDEN = ROOT / "tests" / "golden"
FORBIDDEN = re.compile(r"errata", re.IGNORECASE)


def test_course_notes_page_is_generated_from_the_notes():
    page = (ROOT / "docs" / "course-notes.md").read_text(encoding="utf-8")
    assert page == notes_page(), "regenerate: python -m robosolve.core.course_notes docs/course-notes.md"


def test_no_report_doc_or_solver_cites_a_document_outside_the_project():
    files = [*GOLDEN.glob("*/report.md"), *(ROOT / "docs").rglob("*.md"), ROOT / "README.md",
             *(ROOT / "problems").glob("*.yaml"), *(ROOT / "robosolve").rglob("*.py")]
    offenders = [str(f.relative_to(ROOT)) for f in files if FORBIDDEN.search(f.read_text(encoding="utf-8"))]
    assert offenders == []


def test_every_note_link_of_a_report_has_its_note_in_the_report():
    for report in GOLDEN.glob("*/report.md"):
        text = report.read_text(encoding="utf-8")
        links = set(re.findall(r"\]\(#note-([a-z0-9-]+)\)", text))
        anchors = set(re.findall(r'<a id="note-([a-z0-9-]+)"></a>', text))
        assert links <= set(NOTES), report
        assert links == anchors, report


def test_no_line_of_a_golden_report_is_unreadably_long():
    for report in GOLDEN.glob("*/report.md"):
        longest = max(len(line) for line in report.read_text(encoding="utf-8").splitlines())
        assert longest <= 2000, (report, longest)


TWO_FRAMES = """
robosolve: 1
name: two-frames
parameters: {L1: 1/2, L2: 1/3}
joints:
  - {name: q1, type: revolute}
  - {name: q2, type: revolute}
frames:
  "1": {parent: "0", pose: "Rz(q1) Tx(L1)"}
  "2": {pose: "Rz(q2) Tx(L2)"}
points:
  P: {frame: "2", at: [0, 0, 0]}
questions:
  - {type: position, frame: "1", point: P, at: {q1: pi/6, q2: pi/4, L1: 1}}
"""


def _rz_tx(q, a):
    c, s = math.cos(q), math.sin(q)
    return np.array([[c, -s, 0, a * c], [s, c, 0, a * s], [0, 0, 1, 0], [0, 0, 0, 1]])


def test_position_chain_reaches_the_point_frame(write_problem):
    report = solve_file(write_problem(TWO_FRAMES))
    ans = report.answers[0]
    m01, m12 = _rz_tx(math.pi / 6, 1.0), _rz_tx(math.pi / 4, 1 / 3)
    chain = ans.numeric["chain"]
    assert len(chain) == 2 and len(ans.symbolic["chain"]) == 2
    np.testing.assert_allclose(chain[0], m01, atol=1e-12)
    np.testing.assert_allclose(chain[1], m12, atol=1e-12)
    np.testing.assert_allclose(ans.numeric["M"], m01, atol=1e-12)            # frame 1 itself
    np.testing.assert_allclose(ans.numeric["position"], (m01 @ m12)[:3, 3], atol=1e-12)


def test_configuration_and_overrides_are_stated(write_problem):
    report = solve_file(write_problem(TWO_FRAMES))
    md = render_report(report, {})
    # the data section shows the override next to the base value
    row = next(line for line in md.splitlines() if line.startswith("| $L_{1}$"))
    assert "\\frac{1}{2}" in row and "$1$ in `position`" in row
    # the answer states joints (exact and decimal) and the override before its numbers
    section = md.split("## 1. ")[1]
    config = section.index("**Configuration of the numbers.**")
    assert config < section.index("#### Numeric values")
    stated = section[config:section.index("#### Numeric values")]
    assert "\\theta" not in stated and "q_{1} = \\frac{\\pi}{6} \\approx 0.523599" in stated
    assert "L_{1} = 1$ (data: $\\frac{1}{2}$)" in stated


def test_golden_results_keep_a_chain_per_frame_used():
    # self-check of the golden files against the loader's frames (robosolve against itself)
    data = json.loads((GOLDEN / "scara-rrp" / "results.json").read_text())
    assert len(data["answers"]["position"]["numeric"]["chain"]) == 3


ONE_LINK_KP0 = """
robosolve: 1
name: kp-zero
parameters: {L: 1, m1: 2, g: 9.81, F: 3}
joints:
  - {name: theta, type: revolute, actuator: C}
frames:
  "1": {parent: "0", pose: "Rx(theta) Ty(L)"}
bodies:
  - {name: link, frame: "1", mass: m1, rod: {from: [0, -L, 0], to: [0, 0, 0]}}
forces:
  - {name: F, frame: "1", at: [0, -L/3, 0], force: [0, 0, -F], in: "1"}
questions:
  - {type: motion_profile, id: move, from: {theta: 0}, to: {theta: 1/2}, max_acceleration: {theta: 2}}
  - {type: p_control, profile: move, gains: {theta: 0}}
"""


def test_p_control_with_zero_gain_and_the_external_force_in_the_effort_plot(write_problem):
    report = solve_file(write_problem(ONE_LINK_KP0))
    control = report.answers[1]
    text = " ".join(s.text.words() if hasattr(s.text, "words") else s.text for s in control.steps)
    assert "springs" not in text and "K_p = 0" in text
    effort = next(f for f in control.figures if f.name == "effort")
    ext = effort.data["actuators"][0]["external"]
    # follower force F = 3 N at 2L/3 perpendicular to the link: f_theta = -2/3 F L = -2 (by hand)
    assert ext is not None and np.allclose(ext, -2.0, atol=1e-9)
    assert np.allclose(effort.data["actuators"][0]["values"], 0.0)


def test_every_question_type_has_its_page_and_its_row_in_problem_format():
    from robosolve.questions.registry import QUESTION_TYPES

    table = (ROOT / "docs" / "problem-format.md").read_text(encoding="utf-8")
    assert "specification" not in table
    for name, qt in QUESTION_TYPES.items():
        assert (ROOT / qt.doc_page).is_file(), qt.doc_page
        assert re.search(rf"^\| `{name}` \|", table, flags=re.M), name


def test_compact_notation_is_defined_once_and_means_what_it_says():
    import sympy as sp

    from robosolve.load.loader import load_problem
    from robosolve.render.compact import CompactTrig

    problem = load_problem(ROOT / "problems" / "scara-rrp.yaml")
    t1, t2, l = problem.joint_symbols
    compact = CompactTrig(problem)
    expr = 2 * sp.cos(t1) + sp.sin(t1 + t2) * l + sp.cos(2 * t1) + sp.sin(l)
    short = compact(expr)
    # back-substituting the meaning of each compact symbol gives the expression again
    back = short.xreplace({s: f(a) for s, (f, a) in compact.meaning.items()})
    assert sp.simplify(back - expr) == 0
    names = {compact.names[s] for s in short.free_symbols if s in compact.names}
    assert names == {"c_{1}", "s_{12}"}            # cos(2θ1) and sin(l) keep their own form
    for report in GOLDEN.glob("*/report.md"):
        text = report.read_text(encoding="utf-8")
        notation = [line for line in text.splitlines() if line.startswith("Notation (the course's)")]
        assert len(notation) <= 1, report
        used = set(re.findall(r"(?<![A-Za-z\\])([cs]_\{\d+\})", text))
        defined = set(re.findall(r"\$([cs]_\{\d+\}) = ", notation[0])) if notation else set()
        assert used == defined, (report, used ^ defined)


def test_a_big_matrix_is_shown_entry_by_entry_with_every_entry():
    import sympy as sp

    from robosolve.render.compact import display_lines
    from robosolve.render.markdown import Tex

    q = sp.symbols("q1:7")
    big = sp.Matrix(4, 4, lambda i, j: 0 if i == 3 else sum(sp.cos(x) * sp.sin(y) for x in q for y in q[: i + j + 1]))
    intro, lines = display_lines("{}^{0}M_{6}", big, Tex({}))
    assert intro is not None and "[4,1], [4,2], [4,3], [4,4] are 0" in intro
    assert len(lines) == 12
    assert all(line.removeprefix("\\begin{array}{rl}\n").startswith(f"{{}}^{{0}}M_{{6}}[{i},{j}]")
               for line, (i, j) in
               zip(lines, [(i, j) for i in range(1, 4) for j in range(1, 5)]))
    assert max(len(x) for line in lines for x in line.split("\n")) <= 400
