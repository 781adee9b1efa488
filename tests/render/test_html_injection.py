"""report.html and paper.html show a teacher's text as written: a formula of a description
(`$\\text{<script>...}$`, `\\href`, `\\style`) adds no markup to the page, and a text that writes
one of the page's own stand-ins for formulas and anchors (RSMATH0X) is text, not a formula.
The page is read back with the standard library's HTML parser (an independent reader)."""

from html.parser import HTMLParser

from robosolve.render.html import markdown_to_html_body, render_html

MATHML = {"math", "mrow", "mi", "mn", "mo", "mtext", "mstyle", "mspace", "mfrac", "msup", "msub",
          "msubsup", "mtable", "mtr", "mtd", "mover", "munder", "munderover", "msqrt", "mroot",
          "menclose", "mpadded", "mphantom"}
PAGE = {"html", "head", "meta", "title", "style", "body", "p", "div", "code", "h1", "h2", "a"}


class Reader(HTMLParser):
    def __init__(self):
        super().__init__(convert_charrefs=True)
        self.tags, self.attributes, self.mtext = [], [], []
        self._open = []

    def handle_starttag(self, tag, attrs):
        self.tags.append(tag)
        self.attributes += [(tag, name, value) for name, value in attrs]
        self._open.append(tag)

    def handle_endtag(self, tag):
        if self._open and self._open[-1] == tag:
            self._open.pop()

    def handle_data(self, data):
        if self._open and self._open[-1] == "mtext":
            self.mtext.append(data.replace("\xa0", " "))


def _read(page: str) -> Reader:
    reader = Reader()
    reader.feed(page)
    reader.close()
    return reader


def test_a_formula_of_the_text_adds_no_markup_and_shows_its_text_as_written():
    md = ("# T\n\nSee $\\text{<script>alert(1)</script>}$, $\\href{javascript:alert(1)}{x}$, "
          "$\\style{color:red}{y}$, $\\class{evil}{z}$ and $\\text{a & \"b\"}$\n\n"
          "$$\n\\mbox{<img src=x onerror=alert(3)>}\n$$\n")
    reader = _read(render_html(md, {}, "T"))
    assert set(reader.tags) <= MATHML | PAGE, set(reader.tags) - MATHML - PAGE
    assert not [(tag, name, value) for tag, name, value in reader.attributes
                if name in ("href", "style", "class", "src", "onerror") and not value.startswith("rs-")]
    assert reader.mtext == ["<script>alert(1)</script>", 'a & "b"', "<img src=x onerror=alert(3)>"]


def test_a_text_that_writes_a_stand_in_is_shown_as_written():
    md = ("# T\n\nRSMATH99X and RSMATH0X, RSQMATH0X, RSANCHORnote-fooX and $x$\n\n"
          "| a | b |\n| --- | --- |\n| RSMATH1X | $y$ |\n")
    body = markdown_to_html_body(md, {})
    assert "RSMATH99X and RSMATH0X, RSQMATH0X, RSANCHORnote-fooX and <math" in body
    assert "<td>RSMATH1X</td>" in body
    assert body.count("<math") == 2 and '<a id="note-foo">' not in body


def test_a_name_with_a_dollar_stays_inside_its_formula():
    """A frame named "a$b `x` }{" is written \\$ inside its formula (name_tex, as GitHub and
    Jupyter read it): the page converts the whole formula, leaving no TeX, in prose and in a table."""
    from robosolve.core.prose import name_md, name_tex

    name = "a$b `x` $$y$$ }{\\"
    tex = f"{{}}^{{0}}M_{{{name_tex(name)}}}"
    md = (f"# T\n\nThe block of ${tex}$ and $x^2$ of {name_md(name)}.\n\n"
          f"| frame | pose |\n| --- | --- |\n| {name_md(name)} | ${tex} \\\\ 1$ |\n")
    body = markdown_to_html_body(md, {})
    reader = _read(body)
    assert body.count("<math") == 3 and "mathrm" not in body and "<code>" not in body, body
    assert [t for t in reader.tags if t in ("p", "td")] == ["p", "td", "td"]     # one row, two cells
