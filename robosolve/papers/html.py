"""paper.html and papers.html: the paper as one self-contained printable page (papers.md).

The report's HTML rules (render/html.py: MathML, no script, no network, figures as data:
URIs), print styles for A4 and Letter (`@page` margins), and an empty answer box after each
graded key, shaped like its answer: a grid of r × c cells for a matrix, a row of labelled
cells for a vector or a per-joint mapping, a line for a scalar, a few lines for a set;
no box is split across pages. papers.html holds every variant's paper, one per page.
"""

from __future__ import annotations

import html
import re

from robosolve.papers.keys import decided, graded_keys, placeholder
from robosolve.questions import registry as R

BOX = re.compile(r"RSBOX(\d+)N(\d+)X")

PAPER_CSS = """
.rs-box { margin: .35em 0 .9em; break-inside: avoid; page-break-inside: avoid; }
.rs-grid { border-collapse: collapse; border: none; font-size: .85em; }
.rs-grid td { border: 1px solid #444; width: 4.6em; height: 1.9em; padding: 0; }
.rs-grid th { border: none; font-weight: normal; color: #555; padding: 0 .4em; font-size: .9em;
              text-align: center; }
.rs-line { border-bottom: 1px solid #444; height: 1.9em; max-width: 30em; }
.rs-lines .rs-line { max-width: none; }
.rs-field { margin: .2em 0; }
.rs-field > span { color: #555; font-size: .85em; }
.rs-paper-sep { break-before: page; page-break-before: always; }
figure.rs-drawing { float: right; width: 50%; margin: 0 0 .6em 1.2em; }
.rs-data { clear: both; columns: 2 22em; column-gap: 2.2em; }
.rs-data h3 { margin-top: .2em; }
.rs-data .rs-table, .rs-data p { break-inside: avoid; }
.rs-data > h2:first-child, .rs-data > .rs-wide { column-span: all; }
@media print {
  @page { size: auto; margin: 15mm 14mm 16mm; }   /* A4 or Letter: the printer's paper */
  html { font-size: 9pt; }
  p { margin: .45em 0; }
  .rs-table { margin: .4em 0; }
  h1 { font-size: 1.5em; margin-top: 0; }
  h2 { margin: 1em 0 .4em; }
  h3 { margin: .9em 0 .3em; }
  .rs-table, figure, .rs-box, li { break-inside: avoid; page-break-inside: avoid; }
  h2, h3, .rs-give { break-after: avoid; page-break-after: avoid; }   /* with what follows */
  figure { margin: .4em 0; }
  img { max-height: 66mm; }
}
"""


def _grid(rows: int, cols: int, col_labels=None) -> str:
    head = ""
    if col_labels:
        head = "<tr>" + "".join(f"<th>{html.escape(c)}</th>" for c in col_labels) + "</tr>"
    body = "".join("<tr>" + "<td></td>" * cols + "</tr>" for _ in range(rows))
    return f'<table class="rs-grid">{head}{body}</table>'


def box_html(ak, question, problem) -> str:
    """The empty answer box of one key."""
    shape = placeholder(ak, question, problem)
    kind = ak.kind
    if kind == R.MATRIX and isinstance(shape, list):
        inner = _grid(len(shape), len(shape[0]))
    elif kind == R.VECTOR and isinstance(shape, list):
        inner = _grid(1, len(shape))
    elif kind in (R.JOINT_MAP, R.ACTUATOR_MAP, R.CONTROL_MAP, R.COORDINATE_MAP) and isinstance(shape, dict):
        inner = _grid(1, len(shape), list(shape))
    elif kind == R.ACTUATOR_RECORDS and isinstance(shape, dict):
        fields = [f.name for f in ak.fields]
        rows = "".join(f"<tr><th>{html.escape(a)}</th>" + "<td></td>" * len(fields) + "</tr>" for a in shape)
        inner = ('<table class="rs-grid"><tr><th></th>' + "".join(f"<th>{html.escape(f)}</th>" for f in fields)
                 + f"</tr>{rows}</table>")
    elif kind == R.MATRIX_LIST and isinstance(shape, list) and shape:
        labels = [f"{e}" for e in (decided(ak, question, problem)[0] or range(1, len(shape) + 1))]
        return "".join(f'<div class="rs-field"><span>frame {html.escape(str(e))}</span>'
                       f'<div class="rs-box">{_grid(4, 4)}</div></div>' for e in labels)
    elif kind == R.MATRIX_MAP and isinstance(shape, dict) and shape:
        return "".join(f'<div class="rs-field"><span>{html.escape(b)}</span>'
                       f'<div class="rs-box">{_grid(len(m), len(m[0]))}</div></div>' for b, m in shape.items())
    elif kind == R.BODY_MAP and isinstance(shape, dict):
        inner = _grid(1, len(shape), list(shape))
    elif kind == R.EQUATIONS and isinstance(shape, list):
        inner = '<div class="rs-lines">' + '<div class="rs-line"></div>' * max(len(shape), 1) + "</div>"
    elif kind == R.RECORD:
        inner = "".join(f'<div class="rs-field"><span>{html.escape(f.name)}</span>'
                        f'{box_html(f, question, problem)}</div>' for f in ak.fields)
        return inner
    elif kind in (R.JOINT_MAP_SET, R.VECTOR_SET, R.JOINT_MAP_LIST, R.AXES, R.EQUATIONS, R.MATRIX_LIST):
        inner = '<div class="rs-lines">' + '<div class="rs-line"></div>' * 4 + "</div>"
    else:
        inner = '<div class="rs-line"></div>'
    return f'<div class="rs-box">{inner}</div>'


def _boxes(body: str, problem, model) -> str:
    by_index = {q.index: q for q in problem.questions}

    def sub(m):
        q = by_index[int(m.group(1))]
        gk = graded_keys(q, problem)[int(m.group(2))]
        return box_html(gk.answer_key, q, problem)

    return BOX.sub(sub, body)


WIDE_COLUMNS = 6      # a table of this many columns or more (the forces': name, frame, point, force,
                      # torque, components) is wider than half an A4 page: it spans both columns


def _wide(data: str) -> str:
    """The data section with each wide table and its heading spanning both columns: in one
    column such a table ran past the page's margin, and the printer cut it."""
    def sub(m):
        head = re.search(r"<thead>\s*<tr>(.*?)</tr>", m.group(2), re.S)
        if head is None or head.group(1).count("<th") < WIDE_COLUMNS:
            return m.group(0)
        return f'<div class="rs-wide">{m.group(1)}{m.group(2)}</div>'

    return re.sub(r'(<h3>[^<]*</h3>\n)?(<div class="rs-table"><table>.*?</table></div>)', sub, data, flags=re.S)


def paper_body(markdown: str, problem, model, files) -> str:
    from robosolve.render.html import markdown_to_html_body

    body = markdown_to_html_body(markdown, files)
    # the data tables side by side (two columns when the page is wide enough)
    body = re.sub(r"(<h2>Data</h2>.*?)(?=<h2>Questions</h2>)", lambda m: f'<div class="rs-data">{_wide(m.group(1))}</div>\n',
                  body, count=1, flags=re.S)
    # the drawing beside the header and the conventions
    fig = re.search(r"<figure>.*?</figure>\n?", body, re.S)
    if fig:
        body = body.replace(fig.group(0), "", 1)
        drawing = fig.group(0).replace("<figure>", '<figure class="rs-drawing">', 1)
        body = re.sub(r"(</h1>\n)", lambda m: m.group(1) + drawing, body, count=1)
    body = body.replace("<p><strong>What to give</strong>", '<p class="rs-give"><strong>What to give</strong>')
    return _boxes(body, problem, model)


def page(body: str, title: str) -> str:
    from robosolve.render.html import CSS

    return ("<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
            "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
            "<meta name=\"generator\" content=\"robosolve\">\n"
            f"<title>{html.escape(title)}</title>\n<style>{CSS}{PAPER_CSS}</style>\n</head>\n<body>\n"
            f"{body}</body>\n</html>\n")


def render_paper_html(markdown: str, problem, model, files) -> str:
    return page(paper_body(markdown, problem, model, files), problem.title or problem.name)


BODY = re.compile(r"<body>\n(.*)</body>", re.S)


def join_papers(pages: list[tuple[str, str]], title: str) -> str:
    """Every paper's body, in order, each from a new printed page."""
    parts = []
    for k, (name, text) in enumerate(pages):
        m = BODY.search(text)
        inner = m.group(1) if m else text
        cls = "rs-paper rs-paper-sep" if k else "rs-paper"
        parts.append(f'<section class="{cls}" id="{html.escape(name)}">\n{inner}</section>\n')
    return page("".join(parts), title)
