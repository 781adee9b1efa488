"""`robosolve grade`: many submissions, each problem solved once, graded in parallel.

The parent reads every answers file, finds each one's problem (`--problem`, `--variants`
or its own `problem:`), solves each distinct problem once, and sends the references to
worker processes (pickled once per worker, through the pool's initializer); the workers
grade the submissions. Outputs are written into a temporary folder that replaces DIR at
the end (`robosolve.run.outputs`, the output-folder rule of problem-format.md §2), so they are
deterministic and never half-written.
"""

from __future__ import annotations

import csv
import io
import os
from dataclasses import dataclass, field
from pathlib import Path

from robosolve.errors import ExitStatus, InputError
from robosolve.grading.answers import missing_problem, read_answers, resolve_answers, safe_name
from robosolve.grading.grader import Grader, invalid_result
from robosolve.grading.matching import TableError, VariantsTable, read_table
from robosolve.grading.record import GRADES_COLUMNS, SUMMARY_COLUMNS, grade_rows, record_json, summary_row
from robosolve.run.interrupts import process_pool


# Earlier outputs removed when DIR is the working directory (written in place): never `*.json`,
# which could be a user's own file there; a student's earlier record is then left behind.
OWN_OUTPUTS = ("grades.csv", "summary.csv", "feedback/*.md", "gradebook/*.csv")


class UsageError(Exception):
    """A usage error or an invalid problem file: exit 2, nothing written."""


@dataclass
class Job:
    index: int                     # position in the sorted submissions
    file: str
    student: str
    problem_key: str | None        # the resolved problem file, or None when unknown
    answers: dict | None           # resolved answers, or None when the file is invalid
    error: str = ""
    notes: tuple = ()              # unknown question ids (the rest is graded)
    duplicate: bool = False        # a second submission with an earlier one's student id
    reason: str = ""               # why it is invalid, as the feedback says it (no file name)
    variant: str = ""              # --variants: the variant it answers
    row: int | None = None         # --variants with a roster: its roster row
    shape_key: str | None = None   # unmatched (--variants): a variant whose questions its rows list
    note: str = ""                 # --variants: it answered another student's variant (named by problem:)


def collect(sources, warnings=None) -> list[Path]:
    """The answers files of `sources` (files, or folders of *.yaml / *.yml); a link in a folder
    that points nowhere is left out with a warning appended to `warnings`."""
    files = []
    for s in sources:
        p = Path(s)
        if p.is_dir():
            found = sorted(f for f in p.iterdir() if f.suffix.lower() in (".yaml", ".yml"))   # ANSWERS.YAML too
            files += [f for f in found if f.is_file()]
            if warnings is not None:
                warnings += [f"{f}: skipped: a symbolic link to {os.readlink(f)}, which does not exist"
                             for f in found if f.is_symlink() and not f.exists()]
        elif p.is_file():
            files.append(p)
        else:
            raise UsageError(f"{s}: no such file or folder")
    return sorted(set(files))


def _nested_hint(sources) -> str:
    """A folder of folders (an LMS's download: one folder per student) is not searched below its
    own files: say where the answers files are and how to give them."""
    nested = sorted({str(d) for s in sources if Path(s).is_dir() for d in Path(s).iterdir()
                     if d.is_dir() and any(f.suffix.lower() in (".yaml", ".yml") for f in d.iterdir())})
    if not nested:
        return ""
    return (f"; the folders given are searched without their subfolders, and {len(nested)} of those hold "
            f"answers files ({nested[0]}{', …' if len(nested) > 1 else ''}): give them, e.g. "
            f"`robosolve grade {Path(next(s for s in sources if Path(s).is_dir())) / '*'} …`")


def _problem_for(sub, problem, table):
    """(problem file, Match or None); ValueError (MatchError) when no problem is found."""
    if problem is not None:
        return Path(problem), None
    if table is not None:
        match = table.match(sub.student, sub.problem_file)
        return match.problem, match
    if sub.problem_file is None:
        raise ValueError("no problem: the answers file has no `problem:` (or give --problem)")
    return sub.problem_file, None


def read_variants(folder) -> "VariantsTable":
    try:
        return read_table(Path(folder))
    except TableError as exc:
        raise UsageError(str(exc)) from None


def prepare(files, problem=None, table=None, rtol=None, atol=None):
    """Read every submission, solve every problem once. Returns (jobs, references)."""
    jobs, problems = read_jobs(files, problem, table)
    return jobs, solve_jobs(jobs, problems, rtol, atol)


def read_jobs(files, problem=None, table=None, warnings=None):
    """Read every submission and find its problem (nothing solved yet): (jobs, problems), where
    `problems` maps each resolved problem file to (its path, the submissions graded against it).
    `table`: the VariantsTable of --variants (matching.py); `warnings` gets a line for each
    blank `student:` (graded under the file's name)."""
    jobs, problems = [], {}
    common = None                 # with --problem, even an unreadable submission has its problem
    if problem is not None:
        if not Path(problem).is_file():
            raise UsageError(f"{problem}: no such problem file")
        common = str(Path(problem).resolve())
        problems[common] = (Path(problem), [])
    for i, f in enumerate(files):
        try:
            sub = read_answers(f)
        except InputError as exc:
            jobs.append(Job(i, str(f), _fallback_student(f), common, None, str(exc)))
            continue
        if sub.blank_student and warnings is not None:
            line, _ = sub.where(("student",))
            warnings.append(f"{f}:{line}: student: empty; graded under the file's name, '{sub.student}' "
                            "(write the student's id there to file it under that id)")
        refused = [str(x) for x in sub.issues if x.path == "problem"]
        if refused and problem is None and table is None:   # a device or folder as `problem:`
            jobs.append(Job(i, str(f), sub.student, None, None, "\n".join(refused)))
            continue
        try:
            path, match = _problem_for(sub, problem, table)
        except ValueError as exc:
            jobs.append(Job(i, str(f), sub.student, None, None, f"{f}: {exc}", reason=str(exc)))
            continue
        student_fields = {}
        if match is not None:
            sub.student = match.student
            student_fields = {"variant": match.variant, "row": match.row, "note": _variant_note(table, match)}
            if student_fields["note"] and warnings is not None:
                row = ", in that student's gradebook row" if table.has_roster else ""
                warnings.append(f"{f}: this submission of '{sub.student}' {student_fields['note']} "
                                f"(filed under '{sub.student}'{row})")
        if not Path(path).is_file():
            missing = missing_problem(sub) if problem is None and match is None else None
            jobs.append(Job(i, str(f), sub.student, None, None, str(missing) if missing is not None
                            else f"{f}: the problem file {path} does not exist"))
            continue
        key = str(Path(path).resolve())
        problems.setdefault(key, (path, []))[1].append((i, sub))
        jobs.append(Job(i, str(f), sub.student, key, None, **student_fields))
    return jobs, problems


def _variant_note(table, match) -> str:
    """Why a submission's variant is not its student's own (`problem:` names another student's):
    said in its record and feedback, '' when it is its own."""
    if not match.own_variant:
        return ""
    row = table.row_of(match.variant)
    whose = table.cell(row, "student") if row is not None else ""
    answered = f"the variant of '{whose}' ({match.variant}, " if whose else f"variant {match.variant} ("
    return (f"answered {answered}named by `problem:`), not its own ({match.own_variant}); "
            f"graded against {match.variant}")


def input_paths(files, problems) -> list[Path]:
    """The files `grade` reads: the answers files and their problems."""
    return [*map(Path, files), *(Path(path) for path, _ in problems.values())]


def solve_jobs(jobs, problems, rtol=None, atol=None) -> dict:
    """Solve each problem once and resolve its submissions' answers: the references."""
    from robosolve.grading.check import solve_reference

    references = {}
    for key, (path, subs) in sorted(problems.items()):
        try:
            references[key] = solve_reference(path, rtol=rtol, atol=atol)
        except InputError as exc:
            raise UsageError(str(exc)) from None
        for i, sub in subs:
            try:
                resolve_answers(sub, references[key].problem, strict=False)
                jobs[i].answers, jobs[i].notes = sub.answers, tuple(sub.notes)
            except InputError as exc:
                jobs[i].error = str(exc)
    _mark_duplicates(jobs)
    if any(j.variant for j in jobs) and references:
        for job in jobs:
            if job.problem_key is None:
                job.shape_key = min(references)
    return references


def _fallback_student(f) -> str:
    return Path(f).stem


def file_name(student: str) -> str:
    """The name of a submission's files (<name>.json, feedback/<name>.md): the student id made
    safe (variants.md); an id with no letter or digit of [a-z0-9] (王小明, Иван, ???) would give
    an empty name, so it is named by 8 hexadecimal digits of its SHA-256 — two such students
    are two files, not one student graded twice (a duplicate)."""
    import hashlib

    return safe_name(student) or "student-" + hashlib.sha256(student.encode("utf-8")).hexdigest()[:8]


def _mark_duplicates(jobs) -> None:
    """A submission whose student was already seen, in job order (the files sorted by path), is
    graded invalid: the same id (compared as file names), or, with --variants and a roster, the
    same roster row (`problem:` of Ann's variant and `student: Ann Lee` are one student)."""
    by_name, by_row = {}, {}
    for job in jobs:
        name = file_name(job.student)
        first = by_name.get(name) or (by_row.get(job.row) if job.row is not None else None)
        if first is not None:
            same = "" if file_name(first.student) == name else f" (the same roster student as '{first.student}')"
            job.reason = f"duplicate student id '{job.student}'{same}: {first.file} came first"
            job.answers = None
            job.error = job.error or f"{job.file}: {job.reason}"
            job.duplicate = True
        by_name.setdefault(name, job)
        if job.row is not None:
            by_row.setdefault(job.row, job)


# -- workers --------------------------------------------------------------------
_REFERENCES: dict = {}
_GRADERS: dict = {}


def _init_worker(references, worker: bool = False) -> None:
    if worker:
        from robosolve.core.processes import worker_init

        worker_init()
    _REFERENCES.clear()
    _REFERENCES.update(references)
    _GRADERS.clear()


def grade_job(job: Job):
    index, result = _graded(job)
    result.note = job.note
    return index, result


def _graded(job: Job):
    ref = _REFERENCES.get(job.problem_key or job.shape_key)
    if job.answers is None:
        return job.index, invalid_result(ref, job.student, job.error, job.reason, bool(job.problem_key))
    grader = _GRADERS.get(job.problem_key)
    if grader is None:
        grader = _GRADERS[job.problem_key] = Grader(ref)
    try:
        return job.index, grader.grade(job.student, job.answers, job.notes)
    except Exception as exc:  # noqa: BLE001 - a grading bug must not lose the other submissions
        return job.index, invalid_result(ref, job.student, f"{job.file}: internal error while grading "
                                                           f"({type(exc).__name__}: {exc})")


def grade_all(jobs, references, n_jobs: int, progress=None) -> list:
    """Results in job order; `progress(n)` is called as submissions finish."""
    results = [None] * len(jobs)
    n_jobs = max(1, min(n_jobs or os.cpu_count() or 1, len(jobs)))
    if n_jobs == 1:
        _init_worker(references)
        for job in jobs:
            i, r = grade_job(job)
            results[i] = r
            if progress:
                progress(1)
        return results
    with process_pool(max_workers=n_jobs, initializer=_init_worker, initargs=(references, True)) as pool:
        for i, r in pool.map(grade_job, jobs, chunksize=max(1, len(jobs) // (4 * n_jobs))):
            results[i] = r
            if progress:
                progress(1)
    return results


# -- outputs --------------------------------------------------------------------
def _csv(rows, header) -> str:
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(header)
    w.writerows(rows)
    return buf.getvalue()


@dataclass
class Outputs:
    """What `grade` writes beyond grades.csv, summary.csv and the records."""

    out: Path | None = None            # DIR (for the relative links of the feedback pages)
    table: VariantsTable | None = None  # --variants
    gradebooks: tuple = ()             # LMS names (--gradebook)
    no_expected: bool = False          # feedback never shows an expected value


def render(jobs, results, references, options: Outputs | None = None) -> dict:
    """relative path -> text of every output file."""
    options = options or Outputs()
    if options.no_expected:
        results = [r.without_expected() for r in results]
    order = sorted(range(len(jobs)), key=lambda i: (results[i].student, i))
    files: dict[str, str] = {}
    grades, summary, by_row = [], [], {}
    owned = {file_name(results[i].student) for i in order if not jobs[i].duplicate}
    for i in order:
        r = results[i]
        grades += grade_rows(r)
        summary.append(summary_row(r))
        name = file_name(r.student)
        if jobs[i].duplicate and (name in owned or f"{name}.json" in files):
            continue              # the first submission with this id owns its files
        if jobs[i].row is not None and not jobs[i].duplicate:
            by_row[jobs[i].row] = r
        files[f"{name}.json"] = record_json(r)
        files[f"feedback/{name}.md"] = _feedback(jobs[i], r, references, options)
    files["grades.csv"] = _csv(grades, GRADES_COLUMNS)
    files["summary.csv"] = _csv(summary, SUMMARY_COLUMNS)
    if options.gradebooks:
        from robosolve.grading.gradebook import gradebooks

        files.update(gradebooks(options.gradebooks, options.table, _title(options.table, references), by_row))
    return files


def _feedback(job, result, references, options) -> str:
    from robosolve.grading.feedback import page

    ref = references.get(job.problem_key) if job.problem_key else None
    questions = {q.id: q for q in ref.problem.questions} if ref is not None else {}
    link = ""
    if job.variant and options.table is not None and options.out is not None:
        report = options.table.problems[job.variant].parent / "report.md"
        link = os.path.relpath(report.resolve(), (Path(options.out) / "feedback").resolve()).replace(os.sep, "/")
    return page(result, questions, ref.problem if ref is not None else None, link=link,
                reason=job.reason, show_expected=not options.no_expected)


def _title(table, references) -> str:
    for key in sorted(references):
        title = references[key].problem.title
        if title:
            return title.strip()
    return table.name if table is not None and table.name else \
        (references[min(references)].name if references else "robosolve")


@dataclass
class GradeOutcome:
    """What `grade` did, for the CLI to print: the jobs (one per submission, in file order),
    their results, the exit status."""

    status: int
    jobs: list
    results: list
    warnings: list = field(default_factory=list)


def run_grade(sources, out, problem=None, variants_dir=None, n_jobs=0, rtol=None, atol=None,
              progress_factory=None, gradebook=None, no_expected=False) -> GradeOutcome:
    """Grade every submission and write DIR. Raises UsageError / OutputFolderError (exit 2,
    nothing written); `progress_factory(total)` is a context manager yielding `advance(n)`;
    `gradebook`: the --gradebook text ('canvas,moodle'); `no_expected`: --no-expected."""
    from robosolve.grading.gradebook import GradebookError, missing_columns, parse_lms
    from robosolve.run.outputs import check_output_folder, write_output_folder

    try:
        lms = parse_lms(gradebook)
    except GradebookError as exc:
        raise UsageError(str(exc)) from None
    warnings: list = []
    files = collect(sources, warnings)
    inputs = [*files, *([Path(problem)] if problem is not None else []),
              *([Path(variants_dir)] if variants_dir is not None else []),
              *(Path(s) for s in sources if Path(s).is_dir())]
    check_output_folder(Path(out), inputs)
    table = read_variants(variants_dir) if variants_dir is not None else None
    if lms and (table is None or not table.has_roster):
        raise UsageError("--gradebook needs a roster: give --variants DIR of `robosolve variants --roster` "
                         "(DIR/roster.csv)" + ("" if table is None else f"; {table.folder} has no roster.csv"))
    if lms and missing_columns(lms, table):
        raise UsageError(missing_columns(lms, table))
    if not files:
        raise UsageError("\n".join([*warnings, "no answers files found (*.yaml, *.yml)" + _nested_hint(sources)]))
    jobs, problems = read_jobs(files, problem, table, warnings)
    inputs += input_paths(files, problems)
    check_output_folder(Path(out), inputs)
    references = solve_jobs(jobs, problems, rtol, atol)
    if progress_factory is not None:
        with progress_factory(len(jobs)) as advance:
            results = grade_all(jobs, references, n_jobs, advance)
    else:
        results = grade_all(jobs, references, n_jobs)
    options = Outputs(Path(out), table, lms, no_expected)
    outputs = {rel: text.encode("utf-8") for rel, text in render(jobs, results, references, options).items()}
    write_output_folder(Path(out), outputs, inputs, own=OWN_OUTPUTS)
    status = ExitStatus.ANSWER_ERROR if any(j.answers is None for j in jobs) else ExitStatus.OK
    return GradeOutcome(status, jobs, results, warnings)


__all__ = ["run_grade", "UsageError", "GradeOutcome"]
