"""The report formats of `--format`, registered in one place.

Each format names its file and a renderer `render(report, markdown, figure_paths, files) -> str`
(imported on first use); `markdown` is report.md's text, which the other formats build on, and
`files` the outputs rendered so far (relative path -> bytes: the figures to embed).
results.json and figures/ are not formats: they are always written.
"""

from __future__ import annotations

import importlib
import importlib.util
from dataclasses import dataclass


@dataclass(frozen=True)
class ReportFormat:
    name: str
    filename: str
    renderer: str            # "module:function"
    needs: tuple = ()        # importable modules of its optional extra
    extra: str = ""          # pip extra that provides them

    def render(self, report, markdown: str, figure_paths: dict, files: dict) -> str:
        module, func = self.renderer.split(":")
        return getattr(importlib.import_module(module), func)(report, markdown, figure_paths, files)


FORMATS = {
    "md": ReportFormat("md", "report.md", "robosolve.render.markdown:render_markdown_file"),
    "html": ReportFormat("html", "report.html", "robosolve.render.html:render_html_file",
                         needs=("latex2mathml",), extra="html"),
    "ipynb": ReportFormat("ipynb", "report.ipynb", "robosolve.render.notebook:render_notebook_file",
                          needs=("nbformat",), extra="notebook"),
}
DEFAULT_FORMATS = ("md",)


def parse_formats(text: str | None) -> tuple[str, ...]:
    """'md,html' -> ('md', 'html'); raises ValueError with a message for the user."""
    if text is None:
        return DEFAULT_FORMATS
    names = [t.strip().lower() for t in text.split(",") if t.strip()]
    if not names:
        raise ValueError("--format needs at least one of " + ", ".join(FORMATS))
    for n in names:
        if n not in FORMATS:
            from robosolve.load.expressions import did_you_mean

            hint = did_you_mean(n, FORMATS)
            raise ValueError(f"--format: unknown format '{n}'{hint}; choose from {', '.join(FORMATS)}")
    names = tuple(dict.fromkeys(names))
    missing = {n: [m for m in FORMATS[n].needs if importlib.util.find_spec(m) is None] for n in names}
    missing = {n: ms for n, ms in missing.items() if ms}
    if missing:
        raise ValueError(missing_extras_message(missing))
    return names


def missing_extras_message(missing: dict) -> str:
    """Everything the asked formats lack, in one message, with both ways to install it."""
    needs = " and ".join(f"--format {n} needs {' and '.join(ms)}" for n, ms in missing.items())
    extras = ",".join(FORMATS[n].extra for n in missing)
    return (f"{needs} (optional packages): pip install 'robosolve[{extras}]' "
            f"(from a clone of robosolve: pip install '.[{extras}]')")
