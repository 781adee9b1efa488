"""report.html keeps no TeX when a name holds a line break (an inline formula never spans lines)
or a description writes display math on one line, `$$E = mc^2$$`."""

import re

from robosolve.load.loader import load_problem
from robosolve.render.drawing import InlineFigures
from robosolve.render.html import render_html
from robosolve.run.pipeline import render_files, solve_problem

BROKEN_NAME = """\
robosolve: 1
name: line-break-in-a-name
parameters: {L: 1}
joints:
  - {name: q1, type: revolute}
frames:
  "tool\\nframe": {parent: "0", pose: "Rz(q1) Tx(L)"}
questions:
  - {type: displacement, from: {q1: 0}, to: {q1: 0.5}}
"""


def _outside_math(page: str) -> str:
    page = re.sub(r"<style>.*?</style>", "", page, flags=re.S)
    return re.sub(r"<math\b.*?</math>", "", page, flags=re.S)


def test_a_frame_name_with_a_line_break_stays_inside_its_formula(tmp_path):
    path = tmp_path / "p.yaml"
    path.write_text(BROKEN_NAME, encoding="utf-8")
    files = render_files(solve_problem(load_problem(path)), ("md", "html"), InlineFigures())
    md = files["report.md"].decode("utf-8")
    assert "\\mathrm{tool\\ frame}" in md
    outside = _outside_math(files["report.html"].decode("utf-8"))
    assert "$" not in outside and "\\mathrm" not in outside, re.search(r".{60}(\$|\\mathrm).{60}", outside, re.S)


def test_display_math_written_on_one_line_becomes_mathml():
    page = render_html("# t\n\nEnergy $$E = m c^2$$ and $x$, a price of \\$5.\n\n$$\\frac{1}{2}$$\n", None, "t")
    outside = _outside_math(page)
    assert "\\frac" not in outside and "$$" not in outside and "$5" in outside
    assert page.count('<math display="block">') == 2 and page.count('<math display="inline">') == 1
    assert '<div class="rs-display"><math display="block">' in page     # alone in its paragraph
