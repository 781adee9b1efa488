"""`robosolve batch`: many problems in parallel processes, and the golden check.

Golden folders hold `<problem name>/report.md` and `results.json` (figures are
not compared: PNG bytes depend on the matplotlib build).
"""

from __future__ import annotations

import contextlib
import difflib
import glob
import json
import os
from dataclasses import dataclass, field
from pathlib import Path

from robosolve.errors import ExitStatus, InputError

GOLDEN_FILES = ("report.md", "results.json")
FLOAT_RTOL = 1e-9
FLOAT_ATOL = 1e-12


def collect(source: str) -> list[Path]:
    p = Path(source)
    if p.is_dir():
        files = [f for f in p.iterdir() if f.suffix in (".yaml", ".yml") and f.is_file()]
    else:
        files = [Path(f) for f in glob.glob(source) if Path(f).is_file()]
    return sorted(files)


def why_no_files(source: str) -> str:
    """Why `collect(source)` found nothing, in the user's words: a device, pipe or socket is
    not a problem file (`batch /dev/zero`); otherwise no *.yaml / *.yml matched."""
    import stat

    try:
        mode = Path(source).stat().st_mode
    except OSError:
        mode = None
    if mode is not None and not (stat.S_ISREG(mode) or stat.S_ISDIR(mode)):
        return ("a device, pipe or socket, not a regular file: give a problem file, a folder "
                "of them or a glob pattern")
    return "no problem files found"


def solve_one(path: str, formats=("md",)) -> dict:
    """Load, solve, render one problem file in this process: a summary and the files
    (relative path -> bytes); never raises on bad input. Writes nothing."""
    from robosolve.load.yamlsource import read_text_file
    from robosolve.run.execution import make_task, read_error, solve_task

    try:
        text = read_text_file(path)
    except InputError as exc:
        return read_error(path, exc)
    return solve_task(make_task(text, str(path), formats))


def declared_names(files) -> dict[str, str | None]:
    """file -> the problem name it declares (None when unreadable or not a valid name).

    A quick YAML read, so that duplicate names and refused output folders stop the batch
    before any work; the full validation happens in the workers.
    """
    import yaml

    from robosolve.load.loader import NAME_RE
    from robosolve.load.yamlsource import read_text_file

    names = {}
    for f in files:
        try:
            data = yaml.safe_load(read_text_file(f))
            name = data.get("name") if isinstance(data, dict) else None
        except Exception:  # reported properly by the loader later
            name = None
        names[str(f)] = name if isinstance(name, str) and NAME_RE.fullmatch(name) else None
    return names


def refusals(names: dict, out, golden, update) -> list[str]:
    """Why the batch must not start (duplicate names, output folders robosolve does not own)."""
    from robosolve.run.outputs import OutputFolderError, check_collection, check_output_folder

    by_name: dict[str, list[str]] = {}
    for f, n in names.items():
        if n is not None:
            by_name.setdefault(n, []).append(f)
    msgs = [f"several problem files have the name '{n}' ({', '.join(fs)}): their outputs would "
            "overwrite each other; give each a different `name`" for n, fs in sorted(by_name.items())
            if len(fs) > 1]
    root = Path(out) if golden is None else (Path(golden) if update else None)
    if root is None or msgs:
        return msgs
    try:
        check_collection(root)
        for n in sorted(by_name):
            check_output_folder(root / n, inputs=list(names), legacy=GOLDEN_FILES if golden else ())
    except OutputFolderError as exc:
        msgs.append(str(exc))
    return msgs


def _results(files, jobs, formats=("md",), scheduler=None):
    """Yield each file's summary as it is solved, on the chosen back-end (robosolve.run.execution:
    this process, the warm process pool, or Dask); an interrupt stops the workers at once."""
    from robosolve.load.yamlsource import read_text_file
    from robosolve.run.execution import make_task, read_error, run_tasks

    tasks = []
    for f in files:
        try:
            tasks.append(make_task(read_text_file(f), str(f), formats))
        except InputError as exc:
            yield read_error(str(f), exc)
    for _, r in run_tasks(tasks, jobs, scheduler):
        yield r


@dataclass
class BatchOutcome:
    """What `batch` did, for the CLI to print: refusals (nothing done), one summary per file,
    write errors, and the golden check's differences (lines, in file order)."""

    status: int
    refused: list = field(default_factory=list)
    results: list = field(default_factory=list)
    write_errors: list = field(default_factory=list)
    diff_lines: list = field(default_factory=list)
    solved: int = 0
    orphans: list = field(default_factory=list)    # golden folders no file checked makes
    unnamed: list = field(default_factory=list)    # files whose name could not be read (YAML error)


def run(files, out=None, jobs=0, golden=None, update=False, formats=("md",), scheduler=None,
        progress=None) -> BatchOutcome:
    """Solve every file on the chosen back-end and write (or compare) each result.
    `progress(total)` is a context manager yielding `advance()` (the CLI's bar), or None."""
    from robosolve.run.execution import SchedulerError

    if golden is not None and "md" not in formats:     # golden folders hold report.md
        formats = ("md", *formats)
    jobs = jobs or os.cpu_count() or 1
    names = declared_names(files)
    refused = refusals(names, out, golden, update)
    if refused:
        return BatchOutcome(ExitStatus.INPUT, refused=refused)
    try:
        results, diffs, write_errors = _solve_and_write(files, names, out, jobs, golden, update, formats,
                                                        scheduler, progress)
    except SchedulerError as exc:
        return BatchOutcome(ExitStatus.INPUT, refused=[str(exc)])
    results.sort(key=lambda r: r.file)
    solved = len([r for r in results if r.name])
    status = max([r.status for r in results] + [ExitStatus.OK])
    if write_errors:
        status = max(status, ExitStatus.INPUT)
    lines = [line for f in sorted(diffs) for line in diffs[f]]
    if lines:
        status = max(status, ExitStatus.ANSWER_ERROR)
    known = {r.name for r in results if r.name} | {n for n in names.values() if n}
    named = {r.file for r in results if r.name}
    return BatchOutcome(status, results=results, write_errors=write_errors, diff_lines=lines, solved=solved,
                        orphans=orphan_goldens(golden, known) if golden is not None else [],
                        unnamed=sorted(f for f, n in names.items() if n is None and f not in named))


def orphan_goldens(golden, names) -> list[Path]:
    """Golden folders (holding report.md or results.json) that none of `names` makes: their
    problem was removed or renamed, or is not among the files checked."""
    root = Path(golden)
    if not root.is_dir():
        return []
    return [d for d in sorted(root.iterdir()) if d.is_dir() and d.name not in names
            and any((d / g).is_file() for g in GOLDEN_FILES)]


def _solve_and_write(files, names, out, jobs, golden, update, formats, scheduler, progress):
    """Solve every file and write (or compare) each result as it arrives."""
    from robosolve.run.outputs import OutputFolderError, write_output_folder

    results, diffs, write_errors = [], {}, []
    with contextlib.ExitStack() as stack:
        advance = stack.enter_context(progress(len(files))) if progress else (lambda: None)
        for r in stack.enter_context(contextlib.closing(_results(files, jobs, formats, scheduler))):
            out_files, r.files = r.files, {}
            if r.name and golden is None:
                try:
                    write_output_folder(Path(out) / r.name, out_files, inputs=list(names))
                except OutputFolderError as exc:
                    write_errors.append(str(exc))
            elif r.name and update:
                try:
                    write_output_folder(Path(golden) / r.name, {g: out_files[g] for g in GOLDEN_FILES},
                                        inputs=list(names), legacy=GOLDEN_FILES)
                except OutputFolderError as exc:
                    write_errors.append(str(exc))
            elif r.name:
                diffs[r.file] = compare_files(out_files, Path(golden), r.name)
            results.append(r)
            advance()
    return results, diffs, write_errors


def compare_files(new_files: dict, golden_root: Path, name: str) -> list[str]:
    """Differences between one problem's new files (relative path -> bytes) and its golden folder."""
    return _compare_problem(golden_root, name, lambda g: new_files[g].decode("utf-8"))


def compare_tree(new_root: Path, golden_root: Path, names) -> list[str]:
    out = []
    for n in names:
        out += _compare_problem(golden_root, n, lambda g, n=n: (new_root / n / g).read_text(encoding="utf-8"))
    return out


def _compare_problem(golden_root: Path, name: str, new_text) -> list[str]:
    """Differences between the golden files of problem `name` and `new_text(file name)`."""
    out = []
    for g in GOLDEN_FILES:
        old = golden_root / name / g
        if not old.exists():
            out.append(f"--- {old}: missing in the golden folder")
            continue
        a, why = _read_golden(old)
        if why:
            out.append(f"{old}: unreadable golden file ({why}); rerun with --update to rewrite it")
            continue
        b = new_text(g)
        if g.endswith(".json"):
            out += [f"{old}: {d}" for d in compare_json(a, json.loads(b))]
        elif a != b:
            out += list(difflib.unified_diff(a.splitlines(), b.splitlines(), str(old), f"{name}/{g} (new)",
                                             lineterm=""))
    return out


def _read_golden(path: Path):
    """(content, None), or (None, why) for a golden file a bad merge or a hand edit broke: its JSON
    parsed, report.md as text."""
    try:
        text = path.read_text(encoding="utf-8")
    except UnicodeDecodeError as exc:
        return None, f"not UTF-8 text: {exc.reason} at byte {exc.start}"
    except OSError as exc:
        return None, exc.strerror or type(exc).__name__
    if path.suffix != ".json":
        return text, None
    try:
        return json.loads(text), None
    except ValueError as exc:
        return None, f"not JSON: {exc}"


def compare_json(old, new, path="$") -> list[str]:
    """Key-by-key differences, floats compared with a tolerance."""
    if isinstance(old, dict) and isinstance(new, dict):
        out = []
        for k in old:
            if k not in new:
                out.append(f"{path}.{k}: removed")
            else:
                out += compare_json(old[k], new[k], f"{path}.{k}")
        out += [f"{path}.{k}: added" for k in new if k not in old]
        if not out and list(old) != list(new):
            out.append(f"{path}: key order changed")
        return out
    if isinstance(old, list) and isinstance(new, list):
        if len(old) != len(new):
            return [f"{path}: length {len(old)} -> {len(new)}"]
        out = []
        for i, (a, b) in enumerate(zip(old, new)):
            out += compare_json(a, b, f"{path}[{i}]")
        return out
    if isinstance(old, (int, float)) and isinstance(new, (int, float)) and not isinstance(old, bool) \
            and not isinstance(new, bool):
        if abs(old - new) <= FLOAT_ATOL + FLOAT_RTOL * max(abs(old), abs(new)):
            return []
        return [f"{path}: {old!r} -> {new!r}"]
    same = old == new and isinstance(old, bool) == isinstance(new, bool)   # True == 1 in Python, not in JSON
    return [] if same else [f"{path}: {old!r} -> {new!r}"]
