"""Output folders belong to robosolve (problem-format.md §2): claim, write, replace.

The whole API, for every command that writes a folder (solve, batch, grade, variants):

- `check_output_folder(path, inputs=())` raises `OutputFolderError` (exit 2) when robosolve
  may not write `path`; it touches nothing, so commands call it for every target before
  doing any work.
- `check_collection(path)` likewise for a folder that holds output folders (`--out DIR` with
  several problems, a golden folder): it may hold anything, but must be a folder (or absent).
- `write_output_folder(path, files)` writes a mapping relative path -> bytes as the folder
  `path`, marked with `.robosolve`: the folder is built beside the target and swapped in, so
  a reader sees the old or the new outputs, never a mixture. The current working directory
  is written in place instead (each file atomically), removing only robosolve's own earlier
  outputs. It re-checks ownership under a lock, so two runs into one folder both end cleanly
  and leave one complete output.

A folder may be replaced when it is missing, empty, or holds the mark `.robosolve` (an
empty file; its existence is what counts). `legacy=` names files that let an unmarked folder
count as robosolve's (golden folders made before the mark existed). New folders and files
follow the umask. SIGINT/SIGTERM are held back while the swap and the clean-up run, so an
interrupt never leaves a temporary folder or the previous outputs under a hidden name.
"""

from __future__ import annotations

import contextlib
import ctypes
import errno
import fnmatch
import os
import secrets
import shutil
import signal
import threading
from collections.abc import Iterable, Mapping
from pathlib import Path

from robosolve.errors import RobosolveError
from robosolve.run.interrupts import raise_if_interrupted

MARK = ".robosolve"
# Files robosolve itself writes into an output folder: in the working directory (written in
# place) only these are removed when a new run no longer produces them.
OWN_OUTPUT_PATTERNS = ("report.md", "report.html", "report.ipynb", "results.json", "figures/*.png",
                       "grades.json", "grades.md", "grades.csv", "variants.json")
_TMP_TAG = "robosolve-tmp"


class OutputFolderError(RobosolveError):
    """robosolve may not write this folder (exit 2): the message says why and what to do."""


# ---------------------------------------------------------------- checks (touch nothing)

def _describe(entries: list[str]) -> str:
    shown = ", ".join(sorted(entries)[:3])
    return shown + (f" and {len(entries) - 3} more" if len(entries) > 3 else "")


def _is_cwd(path: Path) -> bool:
    try:
        return path.resolve() == Path.cwd().resolve()
    except OSError:
        return False


def _inside(child: Path, parent: Path) -> bool:
    try:
        child.resolve().relative_to(parent.resolve())
        return True
    except (ValueError, OSError):
        return False


def _same(a: Path, b: Path) -> bool:
    try:
        return a.resolve() == b.resolve()
    except OSError:
        return False


def check_output_file(path, inputs: Iterable = ()) -> None:
    """Raise OutputFolderError unless robosolve may (re)write the single file `path`
    (`check --json FILE`): not a folder, not inside a file, not one of the `inputs` it reads."""
    if str(path) == "":
        raise OutputFolderError("the output file name is empty")
    path = Path(path)
    if path.is_dir():
        raise OutputFolderError(f"{path}: is a folder; give a file name (robosolve writes one JSON file)")
    if path.exists() and not path.is_file():   # the write would replace the device or pipe itself
        raise OutputFolderError(f"{path}: is a device, pipe or socket; robosolve writes a regular file "
                                "(it replaces the file as a whole) and has touched nothing. Give a file "
                                "name, or '-' for standard output")
    blocker = _first_non_folder(path.parent)
    if blocker is not None:
        raise OutputFolderError(f"{path}: {blocker} is a file, not a folder; give another file name")
    for f in inputs:
        if _same(path, Path(f)) or (path.exists() and Path(f).exists() and os.path.samefile(path, f)):
            raise OutputFolderError(f"{path}: is {f}, a file robosolve reads; writing there would "
                                    "overwrite it, and robosolve has touched nothing. Give another file name")


def _dangling_link(path: Path) -> OutputFolderError | None:
    """The refusal of a path through a symbolic link whose target does not exist (the folder
    cannot be swapped in over the link, nor made inside it), or None."""
    for p in [*reversed(path.parents), path]:
        if p.is_symlink() and not p.exists():
            return OutputFolderError(f"{path}: {p} is a symbolic link to {os.readlink(p)}, which does not "
                                     "exist; robosolve has touched nothing. Create that folder, or give "
                                     "another name")
    return None


def _first_non_folder(path: Path) -> Path | None:
    """The first existing ancestor-or-self of `path` that is not a folder, if any."""
    for p in [*reversed(path.parents), path]:
        if p.exists() and not p.is_dir():
            return p
    return None


def check_collection(path) -> None:
    """A folder of output folders: it may hold anything, but must be (or become) a folder."""
    if str(path) == "":
        raise OutputFolderError("--out is empty: give a folder name (use '.' for the current folder)")
    path = Path(path)
    if (dangling := _dangling_link(path)) is not None:
        raise dangling
    blocker = _first_non_folder(path)
    if blocker is not None:
        raise OutputFolderError(f"{path}: {blocker} is a file, not a folder; "
                                "give --out a folder (a new one is created)")


def check_output_folder(path, inputs: Iterable = (), legacy: Iterable[str] = ()) -> None:
    """Raise OutputFolderError unless robosolve may (re)write the folder `path`.

    `inputs` are the files being read (a replaced folder must not hold one of them).
    """
    if str(path) == "":
        raise OutputFolderError("--out is empty: give a folder name (use '.' for the current folder)")
    path = Path(path)
    if (dangling := _dangling_link(path)) is not None:
        raise dangling
    blocker = _first_non_folder(path)
    if blocker is not None:
        what = "this is a file" if blocker == path else f"is inside {blocker}, which is a file"
        raise OutputFolderError(f"{path}: {what}; robosolve writes a folder there. "
                                "Give --out a new folder name")
    inputs = [Path(f) for f in inputs]
    for f in inputs:
        if f.is_dir() and _inside(path, f):
            what = "is the folder" if _same(path, f) else "is inside the folder"
            raise OutputFolderError(f"{path}: {what} {f}, which robosolve reads; it has touched nothing. "
                                    "Give --out a folder outside it")
    if not path.exists():
        return
    cwd = _is_cwd(path)
    if not cwd and _inside(Path.cwd(), path):
        raise OutputFolderError(f"{path}: holds the current folder; robosolve would replace it. "
                                "Give --out a new folder name")
    if not cwd:
        for f in inputs:
            if _inside(f, path):
                raise OutputFolderError(f"{path}: holds {f}, which robosolve reads and replacing the folder "
                                        "would delete; robosolve has touched nothing. Give --out a new folder name")
    try:
        entries = os.listdir(path)
    except OSError as exc:
        raise OutputFolderError(f"{path}: cannot read the folder ({exc.strerror or exc})") from None
    # the mark is a file: a folder named .robosolve (a user's, or a made-up one) marks nothing
    if not entries or (MARK in entries and os.path.isfile(os.path.join(path, MARK))):
        return
    legacy = set(legacy)
    if legacy and set(entries) <= legacy:
        return
    where = "the current folder" if cwd else "this folder"
    raise OutputFolderError(
        f"{path}: {where} holds files robosolve did not write ({_describe(entries)}); robosolve only "
        f"replaces folders that are new, empty, or marked with a {MARK} file by an earlier run, "
        "and it has touched nothing. Give --out a new folder name, or empty the folder")


# ---------------------------------------------------------------- signals, umask, lock

@contextlib.contextmanager
def signals_deferred():
    """Hold back SIGINT and SIGTERM for the block (delivered at its end)."""
    if not hasattr(signal, "pthread_sigmask"):
        yield
        return
    sigs = {signal.SIGINT, signal.SIGTERM}
    old = signal.pthread_sigmask(signal.SIG_BLOCK, sigs)
    try:
        yield
    finally:
        signal.pthread_sigmask(signal.SIG_SETMASK, old)


_umask_lock = threading.Lock()


def _umask() -> int:
    with _umask_lock:  # os.umask can only be read by setting it
        mask = os.umask(0o022)
        os.umask(mask)
    return mask


@contextlib.contextmanager
def _locked(folder: Path):
    """An exclusive lock on the parent folder (flock on its descriptor: no lock file left behind)."""
    try:
        import fcntl
    except ImportError:  # pragma: no cover - not POSIX
        yield
        return
    fd = os.open(folder, os.O_RDONLY)
    try:
        fcntl.flock(fd, fcntl.LOCK_EX)
        yield
    finally:
        os.close(fd)


def _exchange(a: Path, b: Path) -> bool:
    """Swap two paths atomically (Linux renameat2 RENAME_EXCHANGE); False when unavailable."""
    try:
        libc = ctypes.CDLL(None, use_errno=True)
        renameat2 = libc.renameat2
    except (OSError, AttributeError):
        return False
    at_fdcwd, rename_exchange = -100, 2
    rc = renameat2(at_fdcwd, os.fsencode(a), at_fdcwd, os.fsencode(b), rename_exchange)
    if rc == 0:
        return True
    err = ctypes.get_errno()
    if err in (errno.ENOSYS, errno.EINVAL, errno.ENOTSUP, errno.EPERM):
        return False
    raise OSError(err, os.strerror(err), str(b))


# ---------------------------------------------------------------- writing

def _safe_rel(rel: str) -> Path:
    p = Path(rel)
    if p.is_absolute() or ".." in p.parts or not p.parts or rel in (".", MARK):
        raise ValueError(f"not a relative output path: {rel!r}")
    return p


def _fill(folder: Path, files: Mapping[str, bytes], mode_dir: int, mode_file: int) -> None:
    for rel, data in files.items():
        target = folder / _safe_rel(rel)
        target.parent.mkdir(parents=True, exist_ok=True, mode=mode_dir)
        target.write_bytes(data)
        os.chmod(target, mode_file)
    for d in [folder, *(p for p in folder.rglob("*") if p.is_dir())]:
        os.chmod(d, mode_dir)
    mark = folder / MARK
    mark.write_bytes(b"")
    os.chmod(mark, mode_file)


def _remove(path: Path) -> None:
    if path.is_dir() and not path.is_symlink():
        shutil.rmtree(path, ignore_errors=True)
    elif path.exists() or path.is_symlink():
        with contextlib.suppress(OSError):
            path.unlink()


def write_output_folder(path, files: Mapping[str, bytes], inputs: Iterable = (),
                        legacy: Iterable[str] = (), own: Iterable[str] = OWN_OUTPUT_PATTERNS) -> Path:
    """Make `path` a robosolve output folder holding exactly `files` (plus the mark).

    Raises OutputFolderError (nothing touched) when the folder is not robosolve's.
    `own` (globs of relative paths) names the earlier outputs removed from the working
    directory, which is written in place.
    """
    path = Path(path)
    inputs, legacy = list(inputs), list(legacy)
    check_output_folder(path, inputs, legacy)
    try:
        with _new_parents_removed_on_error(path):
            return _write_folder(path, files, inputs, legacy, tuple(own))
    except OSError as exc:   # a full disk, a read-only place: nothing was replaced
        raise OutputFolderError(write_error_text(path, exc)) from None


def write_error_text(path, exc: OSError) -> str:
    """The one message of a failed write (a full disk, no permission): the path and the reason."""
    return f"{path}: cannot write the outputs ({exc.strerror or exc})"


@contextlib.contextmanager
def _new_parents_removed_on_error(path: Path):
    """Folders created on the way to `path` are removed again (when empty) if the write fails."""
    missing = [p for p in [*reversed(path.absolute().parents), path.absolute()][:-1] if not p.exists()]
    try:
        yield
    except BaseException:
        for p in reversed(missing):
            with contextlib.suppress(OSError):
                p.rmdir()
        raise


def write_file(path, data: bytes, inputs: Iterable = ()) -> None:
    """Write one file atomically (a temporary file beside it, renamed over it), after
    `check_output_file`; a failed write raises OutputFolderError and leaves nothing behind."""
    path = Path(path)
    check_output_file(path, inputs)
    try:
        with _new_parents_removed_on_error(path):
            path.parent.mkdir(parents=True, exist_ok=True)
            tmp = path.with_name(f".{path.name}.{_TMP_TAG}-{os.getpid()}-{secrets.token_hex(4)}")
            with signals_deferred():
                try:
                    raise_if_interrupted()
                    tmp.write_bytes(data)
                    os.chmod(tmp, 0o666 & ~_umask())
                    os.replace(tmp, path)
                finally:
                    _remove(tmp)
    except OSError as exc:
        raise OutputFolderError(f"{path}: cannot write the file ({exc.strerror or exc})") from None


def _write_folder(path: Path, files, inputs, legacy, own) -> Path:
    mask = _umask()
    mode_dir, mode_file = 0o777 & ~mask, 0o666 & ~mask
    if path.exists() and _is_cwd(path):
        _write_in_place(path.resolve(), files, mode_file, mode_dir, own, inputs)
        return path
    parent = path.resolve().parent if path.exists() else path.absolute().parent
    parent.mkdir(parents=True, exist_ok=True)
    name = path.resolve().name if path.exists() else path.name
    real = parent / name
    tmp = parent / f".{name}.{_TMP_TAG}-{os.getpid()}-{secrets.token_hex(4)}"
    # The files are already bytes, so the whole write is quick: interrupts wait for its end,
    # and no temporary folder can be left behind by one.
    with signals_deferred():
        try:
            raise_if_interrupted()
            tmp.mkdir(mode=0o700)
            _fill(tmp, files, mode_dir, mode_file)
            with _locked(parent):
                check_output_folder(real, inputs, legacy)  # again: another run may have been quicker
                _swap_in(tmp, real)
        finally:
            _remove(tmp)
    return path


def _swap_in(tmp: Path, real: Path) -> None:
    """Put the filled folder `tmp` at `real`; afterwards `tmp` holds what is to be deleted."""
    if not real.exists():
        os.rename(tmp, real)
        return
    if _exchange(tmp, real):
        return
    old = real.with_name(f".{real.name}.{_TMP_TAG}-old-{os.getpid()}-{secrets.token_hex(4)}")
    os.rename(real, old)
    try:
        os.rename(tmp, real)
    except BaseException:
        os.rename(old, real)
        raise
    os.rename(old, tmp)


def _write_in_place(folder: Path, files: Mapping[str, bytes], mode_file: int, mode_dir: int,
                    own: tuple[str, ...], inputs=()) -> None:
    """The working directory cannot be swapped: write each file atomically, then prune."""
    rels = {_safe_rel(r).as_posix(): data for r, data in files.items()}
    with signals_deferred(), _locked(folder):
        raise_if_interrupted()
        check_output_folder(folder)
        earlier = [p.relative_to(folder).as_posix() for p in folder.rglob("*") if p.is_file()]
        pruned = [r for r in earlier if r not in rels and any(fnmatch.fnmatchcase(r, g) for g in own)]
        for rel in [*rels, *pruned]:
            for f in inputs:
                if _same(folder / rel, Path(f)):
                    raise OutputFolderError(f"{folder / rel}: is {f}, a file robosolve reads; writing "
                                            "there would overwrite it, and robosolve has touched nothing. "
                                            "Give --out a new folder name")
        for rel, data in {**rels, MARK: b""}.items():
            target = folder / rel
            target.parent.mkdir(parents=True, exist_ok=True, mode=mode_dir)
            tmp = target.with_name(f".{target.name}.{_TMP_TAG}-{os.getpid()}")
            try:
                tmp.write_bytes(data)
                os.chmod(tmp, mode_file)
                os.replace(tmp, target)
            finally:
                _remove(tmp)
        for rel in earlier:
            if rel not in rels and rel != MARK and any(fnmatch.fnmatchcase(rel, g) for g in own):
                (folder / rel).unlink(missing_ok=True)
        for sub in sorted({(folder / r).parent for r in earlier}, key=lambda p: -len(p.parts)):
            if sub != folder and sub.is_dir() and not any(sub.iterdir()):
                sub.rmdir()


def read_folder(path) -> dict[str, bytes]:
    """The files of a folder as a mapping relative path -> bytes (the mark left out)."""
    path = Path(path)
    return {p.relative_to(path).as_posix(): p.read_bytes()
            for p in sorted(path.rglob("*")) if p.is_file() and p.name != MARK}
