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
from robosolve.grading.answers import read_answers, resolve_answers, safe_name
from robosolve.grading.grader import Grader, invalid_result
from robosolve.grading.record import (
    GRADES_COLUMNS, SUMMARY_COLUMNS, feedback_markdown, grade_rows, record_json, summary_row,
)
from robosolve.run.interrupts import process_pool


# Earlier outputs removed when DIR is the working directory (written in place): never `*.json`,
# which could be a user's own file there; a student's earlier record is then left behind.
OWN_OUTPUTS = ("grades.csv", "summary.csv", "feedback/*.md")


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


def collect(sources, warnings=None) -> list[Path]:
    """The answers files of `sources` (files, or folders of *.yaml / *.yml); a link in a folder
    that points nowhere is left out with a warning appended to `warnings`."""
    files = []
    for s in sources:
        p = Path(s)
        if p.is_dir():
            found = sorted(f for f in p.iterdir() if f.suffix in (".yaml", ".yml"))
            files += [f for f in found if f.is_file()]
            if warnings is not None:
                warnings += [f"{f}: skipped: a symbolic link to {os.readlink(f)}, which does not exist"
                             for f in found if f.is_symlink() and not f.exists()]
        elif p.is_file():
            files.append(p)
        else:
            raise UsageError(f"{s}: no such file or folder")
    return sorted(set(files))


def read_variants(folder: Path) -> dict:
    """student id (as written, and made safe) and variant id -> that variant's problem.yaml."""
    table = folder / "variants.csv"
    try:
        text = table.read_text(encoding="utf-8")
    except OSError as exc:
        raise UsageError(f"{table}: cannot read the variants table ({exc.strerror or exc})")
    rows = list(csv.DictReader(io.StringIO(text)))
    if rows and not {"variant", "student"} <= set(rows[0]):
        raise UsageError(f"{table}: expected the columns variant,student,seed,…")
    name = _base_name(folder, [row["variant"] for row in rows], table)
    out = {}
    for row in rows:
        variant = row["variant"]
        problem = folder / f"{name}-{variant}" / "problem.yaml"
        student = row.get("student") or ""
        for key in dict.fromkeys((student, safe_name(student), variant)):   # ordered, no duplicates
            if key:
                out.setdefault(key, problem)
    return out


def _base_name(folder: Path, variants: list, table: Path) -> str:
    """The problem name <name> such that every variant has DIR/<name>-<variant>/problem.yaml.

    (A folder name alone is ambiguous: `exam-jo-smith` ends with `-smith` too.)
    """
    if not variants:
        return ""
    first = variants[0]
    candidates = sorted(p.parent.name[: -len(first) - 1] for p in folder.glob(f"*-{first}/problem.yaml"))
    for name in candidates:
        if all((folder / f"{name}-{v}" / "problem.yaml").is_file() for v in variants):
            return name
    raise UsageError(f"{table}: no folder <name>-<variant>/problem.yaml for every variant in {folder}")


def _problem_for(sub, problem, variants):
    if problem is not None:
        return Path(problem)
    if variants is not None:
        hit = variants.get(sub.student) or variants.get(safe_name(sub.student))
        if hit is None:
            raise ValueError(f"student '{sub.student}' is not in the variants table")
        return hit
    if sub.problem_file is None:
        raise ValueError("no problem: the answers file has no `problem:` (or give --problem)")
    return sub.problem_file


def prepare(files, problem=None, variants_dir=None, rtol=None, atol=None):
    """Read every submission, solve every problem once. Returns (jobs, references)."""
    jobs, problems = read_jobs(files, problem, variants_dir)
    return jobs, solve_jobs(jobs, problems, rtol, atol)


def read_jobs(files, problem=None, variants_dir=None):
    """Read every submission and find its problem (nothing solved yet): (jobs, problems), where
    `problems` maps each resolved problem file to (its path, the submissions graded against it)."""
    variants = read_variants(Path(variants_dir)) if variants_dir is not None else None
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
        try:
            path = _problem_for(sub, problem, variants)
        except ValueError as exc:
            jobs.append(Job(i, str(f), sub.student, None, None, f"{f}: {exc}"))
            continue
        if not Path(path).is_file():
            jobs.append(Job(i, str(f), sub.student, None, None, f"{f}: the problem file {path} does not exist"))
            continue
        key = str(Path(path).resolve())
        problems.setdefault(key, (path, []))[1].append((i, sub))
        jobs.append(Job(i, str(f), sub.student, key, None))
    return jobs, problems


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
    return references


def _fallback_student(f) -> str:
    return Path(f).stem


def _mark_duplicates(jobs) -> None:
    seen = set()
    for job in jobs:
        name = safe_name(job.student) or "student"
        if name in seen:
            job.answers = None
            job.error = job.error or f"{job.file}: duplicate student id '{job.student}' (another submission has it)"
            job.duplicate = True
        seen.add(name)


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
    ref = _REFERENCES.get(job.problem_key) if job.problem_key else None
    if job.answers is None:
        return job.index, invalid_result(ref, job.student, job.error)
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


def render(jobs, results, references) -> dict:
    """relative path -> text of every output file."""
    order = sorted(range(len(jobs)), key=lambda i: (results[i].student, i))
    files: dict[str, str] = {}
    grades, summary = [], []
    for i in order:
        r = results[i]
        grades += grade_rows(r)
        summary.append(summary_row(r))
        if jobs[i].duplicate:
            continue              # the first submission with this id owns its files
        name = safe_name(r.student) or "student"
        files[f"{name}.json"] = record_json(r)
        ref = references.get(jobs[i].problem_key) if jobs[i].problem_key else None
        titles = _titles(ref)
        files[f"feedback/{name}.md"] = feedback_markdown(r, titles)
    files["grades.csv"] = _csv(grades, GRADES_COLUMNS)
    files["summary.csv"] = _csv(summary, SUMMARY_COLUMNS)
    return files


def _titles(ref) -> dict:
    if ref is None:
        return {}
    from robosolve.questions.registry import title

    return {q.id: title(q.type) for q in ref.questions}


@dataclass
class GradeOutcome:
    """What `grade` did, for the CLI to print: the jobs (one per submission, in file order),
    their results, the exit status."""

    status: int
    jobs: list
    results: list
    warnings: list = field(default_factory=list)


def run_grade(sources, out, problem=None, variants_dir=None, n_jobs=0, rtol=None, atol=None,
              progress_factory=None) -> GradeOutcome:
    """Grade every submission and write DIR. Raises UsageError / OutputFolderError (exit 2,
    nothing written); `progress_factory(total)` is a context manager yielding `advance(n)`."""
    from robosolve.run.outputs import check_output_folder, write_output_folder

    warnings: list = []
    files = collect(sources, warnings)
    inputs = [*files, *([Path(problem)] if problem is not None else []),
              *([Path(variants_dir)] if variants_dir is not None else []),
              *(Path(s) for s in sources if Path(s).is_dir())]
    check_output_folder(Path(out), inputs)
    if not files:
        raise UsageError("\n".join([*warnings, "no answers files found (*.yaml, *.yml)"]))
    jobs, problems = read_jobs(files, problem, variants_dir)
    inputs += input_paths(files, problems)
    check_output_folder(Path(out), inputs)
    references = solve_jobs(jobs, problems, rtol, atol)
    if progress_factory is not None:
        with progress_factory(len(jobs)) as advance:
            results = grade_all(jobs, references, n_jobs, advance)
    else:
        results = grade_all(jobs, references, n_jobs)
    outputs = {rel: text.encode("utf-8") for rel, text in render(jobs, results, references).items()}
    write_output_folder(Path(out), outputs, inputs, own=OWN_OUTPUTS)
    status = ExitStatus.ANSWER_ERROR if any(j.answers is None for j in jobs) else ExitStatus.OK
    return GradeOutcome(status, jobs, results, warnings)


__all__ = ["run_grade", "UsageError", "GradeOutcome"]
