"""`robosolve check`: one answers file against its problem (library side; no printing)."""

from __future__ import annotations

from pathlib import Path

from robosolve.errors import InputError, InputIssue
from robosolve.grading.answers import missing_problem, read_answers, resolve_answers
from robosolve.grading.grader import Grader, SubmissionResult
from robosolve.grading.reference import Reference


def problem_path(sub, override) -> Path:
    if override is not None:
        return Path(override)
    if sub.problem_file is None and any(i.path == "problem" for i in sub.issues):
        raise InputError(sub.issues)      # `problem:` given but refused: said once
    if sub.problem_file is None:
        raise InputError(sub.issues + [InputIssue(sub.file, sub.source.line(()), "",
                                                  "no problem: give `problem: FILE` in the answers file "
                                                  "or --problem")])
    missing = missing_problem(sub)
    if missing is not None:
        raise InputError(sub.issues + [missing])
    return sub.problem_file


def solve_reference(path, rtol=None, atol=None) -> Reference:
    """Load and solve a problem once (InputError when it is not valid input)."""
    from robosolve.load.loader import load_problem
    from robosolve.run.pipeline import solve_problem

    return Reference.from_report(solve_problem(load_problem(path)), rtol=rtol, atol=atol)


def check_file(answers, problem=None, rtol=None, atol=None, before_solving=None, reveal: bool = True,
               on_read=None) -> tuple[SubmissionResult, Reference]:
    """Grade one answers file. Raises InputError (exit 2) for an invalid file or problem.

    `before_solving(inputs)`, when given, is called with the files read (the answers file and
    its problem) before any work: the caller refuses an output that would overwrite one.
    `reveal`: False hides every expected value from the feedback (`--no-expected`);
    `on_read(submission, problem)`: called once the answers are placed (`--echo`)."""
    sub = read_answers(answers)
    from robosolve.load.loader import load_problem
    from robosolve.run.pipeline import solve_problem

    path = problem_path(sub, problem)
    if before_solving is not None:
        before_solving([Path(answers), Path(path)])
    try:
        prob = load_problem(path)
    except InputError as exc:
        raise InputError(list(dict.fromkeys(sub.issues + exc.issues))) from None
    resolve_answers(sub, prob)
    if on_read is not None:
        on_read(sub, prob)
    ref = Reference.from_report(solve_problem(prob), rtol=rtol, atol=atol)
    return Grader(ref, reveal=reveal).grade(sub.student, sub.answers), ref


def read_back(sub, problem) -> list[tuple[str, str, str]]:
    """(question, key, how the value was read) for every key the submission gives (`--echo`):
    the value as robosolve understood it, or why it cannot be read."""
    from robosolve.grading.grader import show
    from robosolve.grading.values import Reader, ValueProblem, answers_namespace, blanks, entry_names
    from robosolve.questions.registry import question_type

    reader = Reader(answers_namespace(problem),
                    joints=[(j.name, j.symbol) for j in problem.joints],
                    actuators=[str(j.actuator) for j in problem.joints])
    types = {q.id: question_type(q.type) for q in problem.questions}
    out = []
    for qid, keys in sub.answers.items():
        for key, given in keys.items():
            ak = types[qid].key(key)
            if given.problem or ak is None:
                out.append((qid, key, given.problem or "unknown key"))
                continue
            if blanks(given.value):
                out.append((qid, key, "not filled in (~)"))
                continue
            try:
                out.append((qid, key, show(reader.read(ak, given.value, entries=entry_names(problem, qid, key)))))
            except ValueProblem as exc:
                out.append((qid, key, f"cannot be read: {exc}"))
    return out
