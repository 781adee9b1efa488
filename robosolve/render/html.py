"""report.html: the Markdown report as one self-contained page, laid out like a course handout.

* Math: every `$...$` and `$$...$$` of report.md is converted to MathML with latex2mathml
  (the optional `html` extra), rendered natively by current browsers: no script, no network.
  Matrices get brackets drawn by CSS (`mtable.rs-matrix`), so they stretch to the matrix's
  height whatever math fonts the reader's device has.
* Text: report.md is parsed with markdown-it-py (installed with rich), raw HTML off — a
  problem's description cannot inject markup; the only HTML kept is the report's own
  `<a id="note-…"></a>` anchors of the course notes.
* Figures: embedded as `data:` URIs from the output folder.
* Layout: a readable serif at ~17 px, 46 em column, ruled tables, wide formulas and
  tables scroll sideways on a phone, print styles (A4 margins, no page break inside a
  figure, formula or table row).
"""

from __future__ import annotations

import base64
import html
import re
from pathlib import Path

NOTE_ANCHOR = re.compile(r'<a id="(note-[a-z0-9-]+)"></a>')
DISPLAY = re.compile(r"^\$\$\n(.*?)\n\$\$$", re.S | re.M)
# a formula's escaped characters (\$ of a name such as "a$b", \\ of a matrix's rows) are part of it:
# `\$` is a dollar inside the formula, not its end (as GitHub and Jupyter read it)
INLINE = re.compile(r"(?<![\\$])\$(?!\$)((?:\\.|[^$\\\n])+?)\$")
# `$$...$$` within one line (a description may write display math so, as Jupyter reads it)
DISPLAY_IN_LINE = re.compile(r"(?<![\\$])\$\$(?!\$)((?:\\.|[^$\\\n])+?)\$\$(?!\$)")
FENCED_MATRIX = re.compile(
    r'<mo stretchy="true" fence="true" form="prefix">([\[(|])</mo>(<mtable>)(.*?)</mtable>'
    r'<mo stretchy="true" fence="true" form="postfix">([\])|])</mo>', re.S)
BRACKET_CLASS = {"[": "rs-bracket", "(": "rs-paren", "|": "rs-bars"}


class HtmlUnavailable(RuntimeError):
    """The optional `html` extra (latex2mathml) is not installed."""


def _converter():
    try:
        from latex2mathml.converter import convert_to_element
    except ImportError:                     # pragma: no cover - depends on the environment
        raise HtmlUnavailable("report.html needs latex2mathml: pip install 'robosolve[html]' "
                              "(from a clone of robosolve: pip install '.[html]')") from None
    return convert_to_element


# latex2mathml writes its characters as numeric references (&#x0003C;) and unescapes its whole
# serialised tree, so a `<` typed in \text{...} would come out as markup (`<script>`): every
# other `<`, `>`, `"` and `&` of a text or attribute becomes a reference first
RAW_MARKUP = re.compile(r"[<>\"]|&(?!#x[0-9A-Fa-f]+;|#[0-9]+;)")
# attributes a formula can set from its source (\href, \style, \class) that could run or
# restyle anything on the page; latex2mathml writes none of them on its own
UNSAFE_ATTRIBUTE = re.compile(r"href|style|class|id|on.*|.*:.*", re.I)


def _inert(text: str | None) -> str | None:
    return None if text is None else RAW_MARKUP.sub(lambda m: f"&#x{ord(m.group()[0]):05X};", text)


def _mathml(tree) -> str:
    """latex2mathml's own serialisation of its tree, with no markup but its elements."""
    from xml.etree.ElementTree import tostring
    from xml.sax.saxutils import unescape

    for element in tree.iter():
        element.text, element.tail = _inert(element.text), _inert(element.tail)
        element.attrib = {name: _inert(value) for name, value in element.attrib.items()
                          if not UNSAFE_ATTRIBUTE.fullmatch(name)}
    return unescape(tostring(tree, encoding="unicode"))


def latex_to_mathml(tex: str, display: bool) -> str:
    """MathML of a formula; one latex2mathml cannot read (a teacher's description with a broken
    formula) is shown as its source, escaped, instead of stopping the page."""
    convert_to_element = _converter()
    try:
        out = _mathml(convert_to_element(tex.strip(), display="block" if display else "inline"))
    except Exception:                       # latex2mathml raises its own errors and others
        return f'<code class="rs-tex">{html.escape(tex.strip())}</code>'

    out = out.replace(' xmlns="http://www.w3.org/1998/Math/MathML"', "", 1)   # implied in HTML5
    # stretchy fences around a matrix become CSS-drawn brackets on the table itself
    out = FENCED_MATRIX.sub(
        lambda m: f'<mtable class="rs-matrix {BRACKET_CLASS[m.group(1)]}">{m.group(3)}</mtable>', out)
    return out


def unused_mark(md: str) -> str:
    """Letters that occur nowhere in `md`: the stand-ins for its formulas and anchors, which
    markdown cannot touch, begin with them, so no text of the report (a description that writes
    such a stand-in) is taken for one."""
    mark = "RS"
    while mark in md:
        mark += "Q"
    return mark


def _protect_math(md: str, mark: str) -> tuple[str, list[tuple[str, bool]]]:
    """Replace math by tokens `<mark>MATH<n>X` markdown cannot touch; returns (text, [(tex, display)])."""
    found: list[tuple[str, bool]] = []

    def keep(tex: str, display: bool) -> str:
        found.append((tex, display))
        return f"{mark}MATH{len(found) - 1}X"

    md = DISPLAY.sub(lambda m: keep(m.group(1), True), md)
    lines = []
    for line in md.split("\n"):
        in_table = line.startswith("|")
        line = DISPLAY_IN_LINE.sub(lambda m: keep(m.group(1), True), line)
        lines.append(INLINE.sub(
            lambda m: keep(m.group(1).replace("\\|", "|") if in_table else m.group(1), False), line))
    return "\n".join(lines), found


def _embed_images(body: str, figures) -> str:
    """Image sources -> data: URIs. `figures`: relative path -> PNG bytes, or a folder."""
    def data_uri(m):
        src = html.unescape(m.group(1))
        if isinstance(figures, dict):
            data = figures.get(src)
        elif figures is not None and (Path(figures) / src).is_file():
            data = (Path(figures) / src).read_bytes()
        else:
            data = None
        if data is None:
            return 'src=""'
        return f'src="data:image/png;base64,{base64.b64encode(data).decode("ascii")}"'

    return re.sub(r'src="([^"]*)"', data_uri, body)


def markdown_to_html_body(md: str, folder=None) -> str:
    from markdown_it import MarkdownIt

    mark = unused_mark(md)
    md = NOTE_ANCHOR.sub(lambda m: f"{mark}ANCHOR{m.group(1)}X", md)
    text, math = _protect_math(md, mark)
    body = MarkdownIt("commonmark", {"html": False, "typographer": False}).enable("table").render(text)
    body = re.sub(mark + r"ANCHOR(note-[a-z0-9-]+)X", r'<a id="\1"></a>', body)
    # a display formula alone in its paragraph becomes a block of its own
    body = re.sub(f"<p>{mark}MATH" + r"(\d+)X</p>",
                  lambda m: f'<div class="rs-display">{mark}MATH{m.group(1)}X</div>', body)
    body = re.sub(mark + r"MATH(\d+)X", lambda m: latex_to_mathml(*math[int(m.group(1))]), body)
    body = body.replace("<table>", '<div class="rs-table"><table>').replace("</table>", "</table></div>")
    body = re.sub(r'<p>(<img [^>]*>)</p>', r'<figure>\1</figure>', body)
    return _embed_images(body, folder)


CSS = """
:root { --ink: #1b1b1b; --rule: #555; --soft: #e6e3dc; --accent: #7a2e12; }
html { font-size: 17px; }
body { margin: 0 auto; max-width: 46em; padding: 1.2em 1.1em 3em; color: var(--ink);
       background: #fff; font-family: "Charter", "Bitstream Charter", "Source Serif Pro",
       "Georgia", "DejaVu Serif", serif; line-height: 1.5; font-variant-numeric: lining-nums; }
h1 { font-size: 1.75em; line-height: 1.2; margin: .4em 0 .6em; padding-bottom: .3em;
     border-bottom: 2px solid var(--ink); }
h2 { font-size: 1.35em; margin: 2em 0 .5em; padding-bottom: .15em; border-bottom: 1px solid var(--rule);
     color: var(--accent); }
h3 { font-size: 1.12em; margin: 1.4em 0 .4em; }
h4 { font-size: 1em; margin: 1.3em 0 .3em; font-style: italic; font-weight: 600; }
h1, h2, h3, h4 { font-family: "Fira Sans", "Source Sans Pro", "Helvetica Neue", "DejaVu Sans",
                 sans-serif; break-after: avoid; }
p, li { hyphens: auto; }
code { font-family: "Fira Mono", "DejaVu Sans Mono", monospace; font-size: .86em;
       background: #f3f1ec; padding: .05em .25em; border-radius: 3px; }
a { color: var(--accent); }
math { font-family: "STIX Two Math", "Latin Modern Math", "Cambria Math", "Noto Sans Math", math; }
math[display="block"] { font-size: 1.05em; }
.rs-display { overflow-x: auto; overflow-y: hidden; margin: .7em 0; padding: .15em 0; }
.rs-display math { margin: 0 auto; }
/* Matrix brackets drawn on the table: they always span its full height. */
mtable.rs-matrix { padding: .12em .42em; margin: 0 .18em; }
mtable.rs-bracket { border-left: 1.3px solid currentColor; border-right: 1.3px solid currentColor;
  background-image: linear-gradient(currentColor, currentColor), linear-gradient(currentColor, currentColor),
                    linear-gradient(currentColor, currentColor), linear-gradient(currentColor, currentColor);
  background-size: .3em 1.3px; background-repeat: no-repeat;
  background-position: left top, left bottom, right top, right bottom; }
mtable.rs-paren { border-left: 1.3px solid currentColor; border-right: 1.3px solid currentColor;
  border-radius: .7em / 50%; }
mtable.rs-bars { border-left: 1.3px solid currentColor; border-right: 1.3px solid currentColor; }
mtable.rs-matrix mtd { padding: .2em .55em; }
mtd[columnalign="left"] { text-align: left; }
mtd[columnalign="right"] { text-align: right; }
.rs-table { overflow-x: auto; margin: .8em 0; }
table { border-collapse: collapse; font-size: .93em; border-top: 2px solid var(--ink);
        border-bottom: 2px solid var(--ink); }
th { text-align: left; border-bottom: 1px solid var(--ink); font-weight: 600; }
th, td { padding: .3em .75em; vertical-align: middle; }
tbody tr + tr td { border-top: 1px solid var(--soft); }
figure { margin: 1em 0; text-align: center; }
img { max-width: 100%; height: auto; }
ul { padding-left: 1.3em; }
header.rs-meta { font-size: .8em; color: #666; margin-bottom: .4em; }
@media (max-width: 600px) {
  html { font-size: 16px; }
  h1 { font-size: 1.45em; }
  body { padding: .8em .7em 2em; }
}
@media print {
  @page { size: A4; margin: 16mm 15mm 18mm; }
  html { font-size: 10.5pt; }
  body { max-width: none; padding: 0; }
  a { color: inherit; text-decoration: none; }
  h2 { break-before: auto; }
  figure, .rs-display, tr, img { break-inside: avoid; }
  .rs-display, .rs-table { overflow: visible; }
  img { max-height: 120mm; }
}
"""


def render_html(markdown: str, folder=None, title: str = "robosolve report") -> str:
    """The whole page. `folder`: the figures (relative path -> PNG bytes, or the output folder
    holding figures/), embedded; None leaves image sources empty."""
    body = markdown_to_html_body(markdown, folder)
    return ("<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
            "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
            "<meta name=\"generator\" content=\"robosolve\">\n"
            f"<title>{html.escape(title)}</title>\n<style>{CSS}</style>\n</head>\n<body>\n"
            f"{body}</body>\n</html>\n")


def render_html_file(report, markdown: str, figure_paths, files) -> str:
    """The `html` format (robosolve.render.formats); `files`: the figures rendered so far."""
    problem = report.problem
    return render_html(markdown, files, problem.title or problem.name)
