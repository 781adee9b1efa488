"""The output-folder rule (problem-format.md §2) for `grade`, until the shared API lands.

Same names and signatures as the shared `robosolve.outputs` being written (issue 11), so the
switch is an import: `check_output_folder(path, inputs)` refuses a folder robosolve does not
own (exists, not empty, no `.robosolve` mark); `write_output_folder(path, files)` builds the
folder beside the target, marks it and swaps it in, so a reader sees old or new, never a mix.
"""

from __future__ import annotations

import os
import shutil
import tempfile
from pathlib import Path

from robosolve.errors import RobosolveError

MARK = ".robosolve"


class OutputFolderError(RobosolveError):
    """robosolve may not write this folder (exit 2)."""


def check_output_folder(path, inputs=()) -> None:
    path = Path(path)
    if path.exists() and not path.is_dir():
        raise OutputFolderError(f"{path}: this is a file; robosolve writes a folder there. "
                                "Give --out a new folder name")
    if not path.exists():
        return
    for f in inputs:
        try:
            Path(f).resolve().relative_to(path.resolve())
        except ValueError:
            continue
        raise OutputFolderError(f"{path}: holds the input {f}, which replacing the folder would delete. "
                                "Give --out a new folder name")
    entries = os.listdir(path)
    if entries and MARK not in entries:
        shown = ", ".join(sorted(entries)[:3]) + (f" and {len(entries) - 3} more" if len(entries) > 3 else "")
        raise OutputFolderError(
            f"{path}: this folder holds files robosolve did not write ({shown}); robosolve only replaces "
            f"folders that are new, empty, or marked with a {MARK} file by an earlier run, and it has "
            "touched nothing. Give --out a new folder name, or empty the folder")


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


def write_output_folder(path, files, inputs=()) -> Path:
    """Make `path` an output folder holding exactly `files` (relative path -> bytes) and the mark."""
    path = Path(path)
    check_output_folder(path, inputs)
    parent = path.absolute().parent
    parent.mkdir(parents=True, exist_ok=True)
    mask = _umask()
    tmp = Path(tempfile.mkdtemp(prefix=f".{path.name}.", dir=parent))
    old = None
    try:
        os.chmod(tmp, 0o777 & ~mask)
        for rel, data in {MARK: b"", **files}.items():
            target = tmp / rel
            target.parent.mkdir(parents=True, exist_ok=True)
            target.write_bytes(data)
            os.chmod(target, 0o666 & ~mask)
        for d in tmp.rglob("*"):
            if d.is_dir():
                os.chmod(d, 0o777 & ~mask)
        if path.exists():
            old = parent / f".{path.name}.old-{os.getpid()}"
            path.rename(old)
        tmp.rename(path)
    except BaseException:
        if old is not None and not path.exists():
            old.rename(path)
        shutil.rmtree(tmp, ignore_errors=True)
        raise
    finally:
        if old is not None and old.exists() and path.exists():
            shutil.rmtree(old, ignore_errors=True)
    return path
