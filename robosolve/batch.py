"""`robosolve batch`: many problems in parallel processes, and the golden check.

Golden folders hold `<problem name>/report.md` and `results.json` (figures are
not compared: PNG bytes depend on the matplotlib build).
"""

from __future__ import annotations

import difflib
import glob
import json
import os
import shutil
import tempfile
from concurrent.futures import ProcessPoolExecutor, as_completed
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


def solve_one(path: str, out_dir: str, formats=("md",)) -> dict:
    """Worker: load, solve, write. Returns a summary (never raises on bad input)."""
    from robosolve.load.loader import load_problem
    from robosolve.pipeline import solve_problem, write_outputs

    try:
        problem = load_problem(path)
    except InputError as exc:
        return {"file": path, "name": None, "status": EXIT_INPUT, "answered": 0, "total": 0,
                "messages": [str(i) for i in exc.issues]}
    report = solve_problem(problem)
    target = Path(out_dir) / problem.name
    write_outputs(report, target, formats)
    failed = [f"{a.id}: {a.error}" for a in report.answers if a.error is not None]
    return {"file": path, "name": problem.name, "status": report.exit_status,
            "answered": len(report.answers) - len(failed), "total": len(report.answers),
            "messages": failed}


def run(files, out=None, jobs=0, golden=None, update=False, formats=("md",)) -> int:
    from rich.console import Console
    from rich.progress import Progress
    from rich.table import Table

    console = Console(stderr=True)
    jobs = jobs or os.cpu_count() or 1
    tmp = None
    if golden is not None:
        tmp = Path(tempfile.mkdtemp(prefix="robosolve-check-"))
        out_dir = tmp
    else:
        out_dir = Path(out)
        out_dir.mkdir(parents=True, exist_ok=True)
    results = []
    try:
        with Progress(console=console, transient=True) as progress:
            task = progress.add_task("solving", total=len(files))
            if jobs == 1 or len(files) == 1:
                for f in files:
                    results.append(solve_one(str(f), str(out_dir), formats))
                    progress.advance(task)
            else:
                with ProcessPoolExecutor(max_workers=min(jobs, len(files))) as pool:
                    futures = [pool.submit(solve_one, str(f), str(out_dir), formats) for f in files]
                    for fut in as_completed(futures):
                        try:
                            results.append(fut.result())
                        except Exception as exc:  # a crashed worker is reported, not fatal
                            results.append({"file": "?", "name": None, "status": EXIT_ANSWER_ERROR,
                                            "answered": 0, "total": 0, "messages": [repr(exc)]})
                        progress.advance(task)
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
