"""Where the course summary is wrong or ambiguous, and what robosolve does instead.

The notes themselves are data, in `course_notes.yaml` beside this module: by topic, one
entry per note with a short anchor, a title and a Markdown body (inline LaTeX in `$...$`).
That file is the single source of the notes:

* solvers cite a note with `note_link(anchor)`, a Markdown link to `#note-<anchor>`;
* the report renderer copies every note a report cites into the report itself
  (section "Notes on the course summary"), so the link works wherever the report
  is read — on GitHub, in report.html, offline — without depending on where the
  output folder lies relative to the project's docs;
* `docs/course-notes.md` is generated from it (`python -m robosolve.core.course_notes docs/course-notes.md`)
  and a test keeps the page in sync.

String helpers over that data: no sympy, cheap to import (one small YAML read).
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import Path


@dataclass(frozen=True)
class CourseNote:
    anchor: str
    title: str
    topic: str
    body: str


def _read_notes() -> tuple[CourseNote, ...]:
    """The notes of course_notes.yaml (beside this module), in page order."""
    import yaml

    text = (Path(__file__).with_name("course_notes.yaml")).read_text(encoding="utf-8")
    topics = yaml.load(text, Loader=getattr(yaml, "CSafeLoader", yaml.SafeLoader))
    return tuple(CourseNote(n["anchor"], n["title"], topic, n["body"])
                 for topic, notes in topics.items() for n in notes)


_NOTES = _read_notes()

NOTES: dict[str, CourseNote] = {n.anchor: n for n in _NOTES}

LINK_RE = re.compile(r"\(#note-([a-z0-9-]+)\)")


def note_link(anchor: str, label: str | None = None) -> str:
    """A Markdown link to the note, e.g. `[course note: H is Ẇ + W², …](#note-h-matrix)`."""
    note = NOTES[anchor]           # KeyError: a citation of a note that does not exist
    return f"[{label or 'course note: ' + note.title}](#note-{anchor})"


def cited(texts) -> list[str]:
    """Anchors cited in `texts`, in the order of the notes page."""
    found = set()
    for t in texts:
        found.update(LINK_RE.findall(t or ""))
    return [a for a in NOTES if a in found]


def note_block(note: CourseNote, heading: str = "###") -> str:
    """One note as Markdown with an explicit anchor (GitHub keeps `id` as `user-content-…`
    and still follows `#note-…` links to it; the HTML renderer keeps it as is)."""
    return f'{heading} <a id="note-{note.anchor}"></a>{note.title}\n\n{note.body}'


def notes_page() -> str:
    """docs/course-notes.md."""
    out = ["# Notes on the course summary",
           "Where the course summary is wrong or ambiguous, and what robosolve does instead. "
           "Every correction was re-derived with sympy and checked numerically against "
           "independent references (Robotics Toolbox, spatialmath, sympy.physics.mechanics); "
           "the tests cite them. Reports copy the notes they rely on into their own last "
           "section, so a report can be read alone; this page collects them all.",
           "Notation: ${}^{i}M_{j}$ is the pose of frame $j$ in frame $i$; $c_1 = \\cos\\theta_1$, "
           "$s_{12} = \\sin(\\theta_1 + \\theta_2)$; matrix entries are 1-based [row, column].",
           "## Contents"]
    topics: dict[str, list[CourseNote]] = {}
    for n in _NOTES:
        topics.setdefault(n.topic, []).append(n)
    out.append("\n".join(f"- {topic}: " + ", ".join(f"[{n.title}](#note-{n.anchor})" for n in notes)
                         for topic, notes in topics.items()))
    for topic, notes in topics.items():
        out.append(f"## {topic}")
        out += [note_block(n) for n in notes]
    return "\n\n".join(out) + "\n"


if __name__ == "__main__":      # python -m robosolve.core.course_notes docs/course-notes.md
    import sys
    from pathlib import Path

    Path(sys.argv[1]).write_text(notes_page(), encoding="utf-8")
