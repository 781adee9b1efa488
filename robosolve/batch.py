"""`robosolve batch`: many problems in parallel processes, and the golden check.

Golden folders hold `<problem name>/report.md` and `results.json` (figures are
not compared: PNG bytes depend on the matplotlib build).
"""

from __future__ import annotations

import difflib
import glob
import json
import shutil
import tempfile
from pathlib import Path

from robosolve.errors import EXIT_ANSWER_ERROR, EXIT_INPUT, EXIT_OK, InputError

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


def solve_one(path: str, out_dir: str) -> dict:
    """Load, solve and write one problem in this process (a summary row; never raises on bad input)."""
    results = list(_solve_all([Path(path)], Path(out_dir), 1, None, lambda: None))
    return results[0]


def _tasks(files):
    """One task per file (its YAML text); unreadable files become rows at once."""
    from robosolve.execution import make_task

    tasks, rows = [], {}
    for i, f in enumerate(files):
        try:
            text = Path(f).read_bytes().decode("utf-8")
        except (OSError, UnicodeDecodeError) as exc:
            why = "the file is not UTF-8 text" if isinstance(exc, UnicodeDecodeError) else \
                f"cannot read the file: {exc.strerror or exc}"
            rows[i] = {"file": str(f), "name": None, "status": EXIT_INPUT, "answered": 0, "total": 0,
                       "messages": [f"{f}:1: {why}"]}
            text = None
        tasks.append(None if text is None else make_task(text, str(f)))
    return tasks, rows


def _solve_all(files, out_dir: Path, jobs, scheduler, advance):
    """Solve every file on the chosen back-end; write each result's files as it arrives.
    Returns the summary rows in file order."""
    from robosolve.execution import owned, replace_folder, run_tasks

    tasks, rows = _tasks(files)
    todo = [i for i, t in enumerate(tasks) if t is not None]
    for _ in rows:
        advance()
    for j, res in run_tasks([tasks[i] for i in todo], jobs, scheduler):
        i = todo[j]
        files_out = res.pop("files") or {}
        res.pop("version", None)
        if res["name"] and res["status"] != EXIT_INPUT:
            target = out_dir / res["name"]
            if owned(target):
                replace_folder(files_out, target)
            else:
                res["status"] = EXIT_INPUT
                res["messages"] = [f"{target}: exists and is not a robosolve output folder "
                                   "(no .robosolve mark, not empty): not touched"]
        rows[i] = res
        advance()
    return [rows[i] for i in range(len(files))]


def run(files, out=None, jobs=0, golden=None, update=False, scheduler=None) -> int:
    from rich.console import Console
    from rich.progress import Progress
    from rich.table import Table

    console = Console(stderr=True)
    tmp = None
    if golden is not None:
        tmp = Path(tempfile.mkdtemp(prefix="robosolve-check-"))
        out_dir = tmp
    else:
        out_dir = Path(out)
        out_dir.mkdir(parents=True, exist_ok=True)
    try:
        from robosolve.execution import SchedulerError

        try:
            with Progress(console=console, transient=True) as progress:
                task = progress.add_task("solving", total=len(files))
                results = _solve_all(files, out_dir, jobs, scheduler, lambda: progress.advance(task))
        except SchedulerError as exc:
            console.print(str(exc), markup=False, highlight=False)
            return EXIT_INPUT
        results.sort(key=lambda r: r["file"])
        names = [r["name"] for r in results if r["name"]]
        dup = sorted({n for n in names if names.count(n) > 1})
        status = max([r["status"] for r in results] + [EXIT_OK])
        table = Table(title="robosolve batch")
        for col in ("file", "problem", "answered", "status"):
            table.add_column(col)
        for r in results:
            label = {EXIT_OK: "ok", EXIT_ANSWER_ERROR: "errors", EXIT_INPUT: "invalid"}[r["status"]]
            table.add_row(r["file"], r["name"] or "—", f"{r['answered']}/{r['total']}", label)
        console.print(table)
        for r in results:
            for m in r["messages"]:
                console.print(f"{r['file']}: {m}", markup=False, highlight=False)
        if dup:
            console.print(f"several files share the problem name(s) {', '.join(dup)}: outputs overwrote "
                          "each other", markup=False)
            status = max(status, EXIT_INPUT)
        if golden is not None:
            golden = Path(golden)
            if update:
                for n in names:
                    dest = golden / n
                    dest.mkdir(parents=True, exist_ok=True)
                    for g in GOLDEN_FILES:
                        shutil.copyfile(out_dir / n / g, dest / g)
                console.print(f"golden folder {golden} updated ({len(names)} problems)", markup=False)
            else:
                diffs = compare_tree(out_dir, golden, names)
                for line in diffs:
                    print(line)
                if diffs:
                    status = max(status, EXIT_ANSWER_ERROR)
                    console.print("golden check: differences found (rerun with --update to accept them)",
                                  markup=False)
                else:
                    console.print(f"golden check: {len(names)} problems identical", markup=False)
        return status
    finally:
        if tmp is not None:
            shutil.rmtree(tmp, ignore_errors=True)


def compare_tree(new_root: Path, golden_root: Path, names) -> list[str]:
    out = []
    for n in names:
        for g in GOLDEN_FILES:
            new, old = new_root / n / g, golden_root / n / g
            if not old.exists():
                out.append(f"--- {old}: missing in the golden folder")
                continue
            a, b = old.read_text(encoding="utf-8"), new.read_text(encoding="utf-8")
            if g.endswith(".json"):
                out += [f"{old}: {d}" for d in compare_json(json.loads(a), json.loads(b))]
            elif a != b:
                out += list(difflib.unified_diff(a.splitlines(), b.splitlines(), str(old), f"{n}/{g} (new)",
                                                 lineterm=""))
    return out


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
    return [] if old == new else [f"{path}: {old!r} -> {new!r}"]
