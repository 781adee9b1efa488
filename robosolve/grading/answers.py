"""Answers files (grading.md "The answers file"): YAML with line numbers -> `Submission`.

Two stages, so that `grade` can read a file before it knows which problem it names:
`read_answers` checks the file's own layout (YAML, `robosolve-answers: 1`, `problem`,
`student`, `answers` a mapping of mappings); `resolve_answers` checks the question ids
and answer keys against the problem and the question-type registry, flattening nested
mappings of record keys into dotted keys. Both report every issue as
`FILE:LINE: path: message` (the loader's `InputIssue`), with a did-you-mean.
The values themselves are parsed later, key by key (a value that does not parse is
that key's `invalid` verdict, not an error of the file).
"""

from __future__ import annotations

import os
import stat
from dataclasses import dataclass, field
from pathlib import Path

from robosolve.errors import InputError, InputIssue
from robosolve.load.expressions import did_you_mean, meant_value
from robosolve.load.loader import as_meant, foreign_file, path_str, type_name, under
from robosolve.load.yamlsource import Source, YamlProblem, parse_yaml, path_problem, read_text_file
from robosolve.questions.registry import RECORD, question_type
from robosolve.variants.naming import safe_name  # noqa: F401  (the one rule, variants.md)

FORMAT_KEY = "robosolve-answers"
TOP_KEYS = (FORMAT_KEY, "problem", "student", "answers")
#: An answers file may be larger than a problem file (yamlsource.MAX_FILE_BYTES): it may hold the
#: reference's own symbolic answers given back (a 7-joint arm's equations of motion run to
#: 1.3 MB); still bounded, so that reading and grading it stays a matter of seconds.
ANSWERS_MAX_FILE_BYTES = 4_000_000


@dataclass
class Given:
    """One answer key as the file gives it: the raw YAML value and where it is."""

    key: str                       # dotted path, e.g. "force.lengths"
    value: object                  # plain YAML data (numbers, strings, lists, mappings)
    path: tuple                    # YAML path, for FILE:LINE messages
    line: int
    problem: str = ""              # `grade` only: why this key cannot be graded (unknown, twice)


@dataclass
class Submission:
    file: str
    student: str
    problem_file: Path | None      # resolved against the answers file's folder
    raw: dict                      # question id -> raw mapping (before resolve_answers)
    source: Source
    answers: dict = field(default_factory=dict)   # question id -> {dotted key: Given}
    issues: list = field(default_factory=list)    # layout issues found by read_answers (not fatal)
    notes: list = field(default_factory=list)     # `grade` only: unknown question ids, as messages
    blank_student: bool = False    # `student: ""` or `~` (a template's blank): the file's name stands

    def where(self, path) -> tuple[int, str]:
        return self.source.line(path), path_str(path)


class _Issues:
    def __init__(self, source: Source):
        self.src = source
        self.items: list[InputIssue] = []
        self.pending: list = []   # (dotted key, raw value, path) of each issue about a key
        self.renamed: list = []   # misspelt keys read as meant (load.loader.as_meant): not judged

    def error(self, path, message: str, key=None, value=None) -> None:
        if under(path, self.renamed):
            return
        self.items.append(InputIssue(self.src.file, self.src.line(path), path_str(path), message))
        self.pending.append((key, value, path))

    def raise_if_any(self) -> None:
        if self.items:
            raise InputError(self.items)


def read_answers(file) -> Submission:
    """Read an answers file and check its layout.

    Raises InputError when nothing can be checked further (YAML, not a mapping, format key,
    `answers`); smaller issues are kept in `issues` and raised by `resolve_answers` together
    with those of the questions and keys, so one run reports every mistake.
    """
    return read_answers_text(read_text_file(file, line=1, limit=ANSWERS_MAX_FILE_BYTES), str(file))


def read_answers_text(text: str, file: str = "<answers>") -> Submission:
    try:
        source, duplicates = parse_yaml(text, file, limit=ANSWERS_MAX_FILE_BYTES)
    except YamlProblem as exc:
        message = exc.message.replace("expected a mapping with `robosolve: 1`",
                                      f"expected a mapping with `{FORMAT_KEY}: 1`")
        raise InputError([InputIssue(file, exc.line, path_str(exc.path), message)])
    issues = _Issues(source)
    for line, path, key in duplicates:
        issues.items.append(InputIssue(file, line, path_str(path), f"duplicate key '{key}'"))
    data = source.data
    if not isinstance(data, dict):
        issues.error((), f"an answers file is a mapping with `{FORMAT_KEY}: 1`, got {type_name(data)}")
        issues.raise_if_any()
    foreign = None if FORMAT_KEY in data or "robosolve" in data else foreign_file(
        data, TOP_KEYS, f"an answers file (a mapping with `{FORMAT_KEY}: 1`, `problem` and `answers`)")
    if foreign is not None:
        issues.error((), foreign)
        issues.raise_if_any()
    if "robosolve" in data and FORMAT_KEY not in data:
        # a problem file given as answers: one message, not one more for each of its keys
        issues.error((), f"missing required key '{FORMAT_KEY}' (the answers format, 1) (this looks like "
                     "a problem file)")
        issues.raise_if_any()
    for key in data:
        if key not in TOP_KEYS:
            issues.error((key,), f"unknown key '{key}'" + did_you_mean(key, TOP_KEYS)
                         + f" (expected one of: {', '.join(TOP_KEYS)})")
    issues.renamed = as_meant((), data, TOP_KEYS)       # a misspelt key: its did-you-mean alone
    if FORMAT_KEY not in data:
        issues.error((), f"missing required key '{FORMAT_KEY}' (the answers format, 1)")
    elif data[FORMAT_KEY] != 1 or isinstance(data[FORMAT_KEY], bool):
        issues.error((FORMAT_KEY,), f"unsupported answers format {data[FORMAT_KEY]!r} (expected 1)")
    problem_file = _problem_file(issues, data, file)
    student = _student(issues, data, file)
    raw = {}
    if "answers" not in data:
        issues.error((), "missing required key 'answers' (question id -> answer key -> value)")
    elif not isinstance(data["answers"], dict):
        issues.error(("answers",), f"expected a mapping question id -> answers, got {type_name(data['answers'])}")
    else:
        for qid, value in data["answers"].items():
            if not isinstance(value, dict):
                issues.error(("answers", qid), f"expected a mapping answer key -> value, got {type_name(value)}")
            else:
                raw[qid] = value
    if any(i.path in ("", FORMAT_KEY, "answers") for i in issues.items):
        issues.raise_if_any()     # no answers to check against a problem: stop here
    blank = "student" in data and (data["student"] is None or (isinstance(data["student"], str)
                                                               and not data["student"].strip()))
    return Submission(file, student, problem_file, raw, source, issues=list(issues.items), blank_student=blank)


def _problem_file(issues: _Issues, data: dict, file: str) -> Path | None:
    """The `problem:` path, resolved against the answers file's folder; a device, a pipe or a
    folder is refused here (it would be read without end or block)."""
    value = data.get("problem")
    if value is None:
        return None
    if not (isinstance(value, str) and value.strip()):
        got = "an empty string" if isinstance(value, str) else type_name(value)
        issues.error(("problem",), f"expected the path of the problem file, got {got}")
        return None
    path = Path(file).parent / value
    unusable = path_problem(str(path), value)
    if unusable:
        issues.error(("problem",), unusable)
        return None
    try:
        mode = os.stat(path).st_mode
    except (OSError, ValueError):
        return path               # missing or unreadable: the loader says so, with the path
    if not stat.S_ISREG(mode):
        kind = "a folder" if stat.S_ISDIR(mode) else "a device, pipe or socket"
        issues.error(("problem",), f"{value!r} is {kind}, not a problem file")
        return None
    return path


def missing_problem(sub: Submission) -> InputIssue | None:
    """The answers file's `problem:` names no file: said at its line, with the problem files
    beside it that the name may mean (checked when the problem is needed, not on reading: with
    --problem or a variants folder the name is not used)."""
    path = sub.problem_file
    if path is None or path.exists() or path.is_symlink():
        return None
    written = sub.source.data.get("problem", str(path))
    try:
        near = sorted(p.name for p in path.parent.iterdir() if p.suffix in (".yaml", ".yml")
                      and p.resolve() != Path(sub.file).resolve()) if path.parent.is_dir() else []
    except OSError:
        near = []
    meant = meant_value(path.name, near)
    hint = f" (did you mean '{Path(str(written)).with_name(meant).as_posix()}'?)" if meant else ""
    line, where = sub.where(("problem",))
    return InputIssue(sub.file, line, where, f"'{written}' does not exist ({path}){hint}")


def _student(issues: _Issues, data: dict, file: str) -> str:
    """The `student:` id (default: the answers file's name)."""
    if "student" not in data:
        return Path(file).stem
    s = data["student"]
    if isinstance(s, (str, int)) and not isinstance(s, bool) and str(s).strip():
        return str(s).strip()
    if not (isinstance(s, str) or s is None):
        issues.error(("student",), f"expected the student's id (a name or a number, such as s123456 "
                     f"or \"Jo Smith\"), got {type_name(s)}")
    return Path(file).stem    # "" or ~: a template's blank (papers.md), the file's name stands


def resolve_answers(sub: Submission, problem, strict: bool = True) -> Submission:
    """Check question ids and keys against `problem`; fill `sub.answers`.

    `strict` (check): every issue raises InputError, all at once. Not strict (grade, where
    grading.md makes an unknown key `invalid` for that key only): the file's own layout
    issues still raise, an unknown or repeated key becomes a Given carrying its message,
    and an unknown question id a note of the submission.
    """
    issues = _Issues(sub.source)
    issues.items = list(sub.issues)
    if not strict:
        issues.raise_if_any()
    key_issues = _Issues(sub.source)
    questions = {q.id: q for q in problem.questions}
    sub.answers, notes = {}, []
    for qid, mapping in sub.raw.items():
        path = ("answers", qid)
        q = questions.get(qid)
        if q is None:
            key_issues.error(path, f"unknown question id '{qid}'" + did_you_mean(qid, questions)
                             + f" (the problem's questions: {', '.join(questions)})")
            notes.append(str(key_issues.items[-1]))
            continue
        qt = question_type(q.type)
        out: dict[str, Given] = {}
        before = len(key_issues.items)
        _flatten(key_issues, sub.source, qt, mapping, path, "", out)
        if not strict:
            for issue, (key, value, kpath) in zip(key_issues.items[before:], key_issues.pending[before:]):
                out.setdefault(key, Given(key, value, kpath, issue.line, problem=str(issue)))
        sub.answers[qid] = out
    if strict:
        issues.items += key_issues.items
        issues.raise_if_any()
    else:
        sub.notes = notes
    return sub


def known_keys(qt) -> list[str]:
    """Every key (dotted for record fields) an answers file may give for this type."""
    out = []
    for a in qt.answers:
        out.append(a.name)
        if a.kind == RECORD:
            out += [f"{a.name}.{f.name}" for f in a.fields]
    return out


def _flatten(issues, source, qt, mapping, path, prefix, out) -> None:
    for key, value in mapping.items():
        dotted = f"{prefix}{key}"
        kpath = path + (key,)
        ak = qt.key(dotted)
        parent = qt.key(dotted.rpartition(".")[0]) if "." in dotted else None
        if ak is None or (parent is not None and parent.kind != RECORD):
            known = known_keys(qt)
            issues.error(kpath, f"unknown answer key '{dotted}'"
                         + did_you_mean(dotted, known) + f" (keys of {qt.name} questions: {', '.join(known)})",
                         key=dotted, value=value)
            continue
        if ak.kind == RECORD and isinstance(value, dict):
            _flatten(issues, source, qt, value, kpath, dotted + ".", out)
            continue
        if dotted in out or any(k.startswith(dotted + ".") or dotted.startswith(k + ".") for k in out):
            issues.error(kpath, f"answer key '{dotted}' given twice", key=dotted + " (again)", value=value)
            continue
        out[dotted] = Given(dotted, value, kpath, source.line(kpath))
