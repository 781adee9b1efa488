"""Output folders belong to robosolve (problem-format.md §2): refusals, the mark, atomic
replacement, the working directory written in place, umask, concurrent runs, interrupts.

The reference is the spec's rule itself, checked on the file system after real runs
(subprocesses where signals, umask or concurrency matter).
"""

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest
from typer.testing import CliRunner

from conftest import MINI, PROBLEMS, ROOT
from robosolve.run import interrupts
from robosolve.cli import app
from robosolve.run.outputs import MARK, OutputFolderError, check_output_folder, write_output_folder

runner = CliRunner()


def snapshot(folder: Path) -> dict:
    """Every entry under `folder` with its bytes (None for folders) and mode."""
    return {p.relative_to(folder).as_posix(): (None if p.is_dir() else p.read_bytes(), p.stat().st_mode)
            for p in sorted(folder.rglob("*"))}


def run_cli(args, cwd, **kw):
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    return subprocess.run([sys.executable, "-m", "robosolve", *args], cwd=cwd, env=env,
                          capture_output=True, text=True, timeout=300, **kw)


def test_out_on_folder_with_foreign_file_exits_2_and_leaves_it_untouched(write_problem, tmp_path):
    src = write_problem(MINI)
    thesis = tmp_path / "mythesis"
    thesis.mkdir()
    (thesis / "chapter1.tex").write_text("\\chapter{One}")
    before = snapshot(thesis)
    result = runner.invoke(app, ["solve", str(src), "--out", str(thesis)])
    assert result.exit_code == 2
    assert "chapter1.tex" in result.output and "touched nothing" in result.output
    assert "Traceback" not in result.output
    assert snapshot(thesis) == before
    assert sorted(p.name for p in tmp_path.iterdir()) == ["mythesis", "p.yaml"]  # no debris


def test_a_folder_named_like_the_mark_marks_nothing(write_problem, tmp_path):
    """The mark is a file (spec §2): a user's folder holding a .robosolve folder beside their data
    is refused and kept, not replaced."""
    src = write_problem(MINI)
    mine = tmp_path / "mine"
    (mine / MARK).mkdir(parents=True)
    (mine / MARK / "settings").write_text("x")
    (mine / "data.txt").write_text("keep me")
    before = snapshot(mine)
    result = runner.invoke(app, ["solve", str(src), "--out", str(mine)])
    assert result.exit_code == 2 and "touched nothing" in result.output
    assert snapshot(mine) == before


def test_new_and_empty_and_marked_folders_are_written_with_the_mark(write_problem, tmp_path):
    src = write_problem(MINI)
    for name in ("new", "empty"):
        if name == "empty":
            (tmp_path / name).mkdir()
        assert runner.invoke(app, ["solve", str(src), "--out", str(tmp_path / name)]).exit_code == 0
        assert (tmp_path / name / MARK).read_bytes() == b""
        assert (tmp_path / name / "report.md").exists()
    # a marked folder is robosolve's: replaced as a whole (stale files go)
    (tmp_path / "new" / "figures" / "stale.png").write_bytes(b"old")
    assert runner.invoke(app, ["solve", str(src), "--out", str(tmp_path / "new")]).exit_code == 0
    assert not (tmp_path / "new" / "figures" / "stale.png").exists()
    assert sorted(p.name for p in tmp_path.iterdir() if p.name.startswith(".")) == []


@pytest.mark.parametrize("out", ["", "..", "FILE", "FILE/sub", "/"])
def test_odd_out_values_are_refused_cleanly(tmp_path, out):
    work = tmp_path / "work"
    work.mkdir()
    (work / "p.yaml").write_text(MINI)
    (work / "FILE").write_text("mine")
    (work / "other").mkdir()  # the current folder is not empty, '..' holds it
    before = snapshot(tmp_path)
    result = run_cli(["solve", "p.yaml", "--out", out], cwd=work)
    assert result.returncode == 2, result.stderr
    assert "Traceback" not in result.stderr and result.stderr.strip()
    assert snapshot(tmp_path) == before


def test_batch_out_file_refused(tmp_path):
    (tmp_path / "p.yaml").write_text(MINI)
    (tmp_path / "FILE").write_text("mine")
    result = runner.invoke(app, ["batch", str(tmp_path), "--out", str(tmp_path / "FILE"), "--jobs", "1"])
    assert result.exit_code == 2
    assert "is a file" in result.output
    assert (tmp_path / "FILE").read_text() == "mine"


def test_batch_refuses_foreign_output_folder_before_working(tmp_path):
    (tmp_path / "p.yaml").write_text(MINI)
    (tmp_path / "out" / "mini").mkdir(parents=True)
    (tmp_path / "out" / "mini" / "mine.txt").write_text("keep")
    result = runner.invoke(app, ["batch", str(tmp_path / "p.yaml"), "--out", str(tmp_path / "out")])
    assert result.exit_code == 2
    assert "mine.txt" in result.output
    assert sorted(os.listdir(tmp_path / "out" / "mini")) == ["mine.txt"]


def test_current_folder_written_in_place(tmp_path):
    (tmp_path / "p.yaml").write_text(MINI)
    work = tmp_path / "w"
    work.mkdir()
    assert run_cli(["solve", "../p.yaml", "--out", "."], cwd=work).returncode == 0
    assert (work / MARK).exists() and (work / "results.json").exists()
    # later: the user adds a file, an earlier figure is no longer produced
    (work / "notes.md").write_text("mine")
    (work / "figures" / "old-robot.png").write_bytes(b"png")
    inode = work.stat().st_ino
    result = run_cli(["solve", "../p.yaml", "--out", str(work)], cwd=work)
    assert result.returncode == 0, result.stderr
    assert (work / "notes.md").read_text() == "mine"
    assert not (work / "figures" / "old-robot.png").exists()
    assert work.stat().st_ino == inode  # written in place, not swapped
    assert sorted(p.name for p in work.iterdir() if p.name.startswith(".")) == [MARK]


def test_unmarked_current_folder_refused(tmp_path):
    (tmp_path / "p.yaml").write_text(MINI)
    before = snapshot(tmp_path)
    result = run_cli(["solve", "p.yaml", "--out", "."], cwd=tmp_path)
    assert result.returncode == 2
    assert "current folder" in result.stderr
    assert snapshot(tmp_path) == before


def test_outputs_follow_the_umask(tmp_path):
    (tmp_path / "p.yaml").write_text(MINI)
    result = run_cli(["solve", "p.yaml", "--out", "o"], cwd=tmp_path, preexec_fn=lambda: os.umask(0o027))
    assert result.returncode == 0, result.stderr
    for p in [tmp_path / "o", *(tmp_path / "o").rglob("*")]:
        want = 0o750 if p.is_dir() else 0o640
        assert p.stat().st_mode & 0o777 == want, p
    result = run_cli(["solve", "p.yaml", "--out", "o2"], cwd=tmp_path, preexec_fn=lambda: os.umask(0o002))
    assert (tmp_path / "o2").stat().st_mode & 0o777 == 0o775  # not drwx------


def test_solve_default_out_and_duplicate_names_refused_before_work(write_problem, tmp_path):
    a = write_problem(MINI, "a.yaml")
    b = write_problem(MINI, "b.yaml")
    result = run_cli(["solve", str(a), str(b)], cwd=tmp_path)
    assert result.returncode == 2
    assert "name 'mini'" in result.stderr
    assert not (tmp_path / "out").exists()


def test_batch_duplicate_names_refused_before_work(tmp_path):
    (tmp_path / "a.yaml").write_text(MINI)
    (tmp_path / "b.yaml").write_text(MINI)
    result = runner.invoke(app, ["batch", str(tmp_path), "--out", str(tmp_path / "o"), "--jobs", "2"])
    assert result.exit_code == 2
    assert "name 'mini'" in result.output
    assert not (tmp_path / "o").exists()


def test_batch_negative_jobs_is_a_usage_error(tmp_path):
    (tmp_path / "a.yaml").write_text(MINI)
    result = runner.invoke(app, ["batch", str(tmp_path), "--out", str(tmp_path / "o"), "--jobs", "-1"])
    assert result.exit_code == 2
    assert result.exception is None or isinstance(result.exception, SystemExit)


def test_concurrent_runs_into_one_folder_end_cleanly(tmp_path):
    (tmp_path / "p.yaml").write_text(MINI)
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    procs = [subprocess.Popen([sys.executable, "-m", "robosolve", "solve", "p.yaml", "--out", "o"], cwd=tmp_path,
                              env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE) for _ in range(4)]
    for p in procs:
        _, err = p.communicate(timeout=300)
        assert p.returncode == 0, err
    assert sorted(os.listdir(tmp_path / "o")) == [MARK, "figures", "report.md", "results.json"]
    assert sorted(os.listdir(tmp_path)) == ["o", "p.yaml"]


def test_golden_folders_without_the_mark_get_it_with_one_update(tmp_path):
    (tmp_path / "p.yaml").write_text(MINI)
    golden = tmp_path / "golden"
    assert runner.invoke(app, ["batch", str(tmp_path / "p.yaml"), "--check", str(golden), "--update"]).exit_code == 0
    (golden / "mini" / MARK).unlink()  # as made before the mark existed
    assert runner.invoke(app, ["batch", str(tmp_path / "p.yaml"), "--check", str(golden)]).exit_code == 0
    assert runner.invoke(app, ["batch", str(tmp_path / "p.yaml"), "--check", str(golden), "--update"]).exit_code == 0
    assert sorted(os.listdir(golden / "mini")) == [MARK, "report.md", "results.json"]
    (golden / "mini" / MARK).unlink()
    (golden / "mini" / "mine.txt").write_text("keep")  # not a golden folder any more
    result = runner.invoke(app, ["batch", str(tmp_path / "p.yaml"), "--check", str(golden), "--update"])
    assert result.exit_code == 2 and (golden / "mini" / "mine.txt").exists()


def test_write_output_folder_api(tmp_path, monkeypatch):
    """The API other commands reuse: a mapping relative path -> bytes becomes a marked folder."""
    target = tmp_path / "g" / "out"
    write_output_folder(target, {"a.txt": b"1", "sub/b.bin": b"\x00"})
    assert (target / "a.txt").read_bytes() == b"1" and (target / "sub" / "b.bin").read_bytes() == b"\x00"
    write_output_folder(target, {"c.txt": b"2"})
    assert sorted(os.listdir(target)) == [MARK, "c.txt"]
    with pytest.raises(ValueError):
        write_output_folder(target, {"../escape": b""})
    assert not (tmp_path / "g" / "escape").exists()
    (tmp_path / "g" / "foreign").mkdir()
    (tmp_path / "g" / "foreign" / "x").write_text("x")
    with pytest.raises(OutputFolderError):
        check_output_folder(tmp_path / "g" / "foreign")
    # a replaced folder may not hold the problem file being read
    with pytest.raises(OutputFolderError, match="robosolve reads"):
        check_output_folder(target, inputs=[target / "c.txt"])
    # an interrupt that library code swallowed: nothing is written after it
    monkeypatch.setattr(interrupts, "_received", [signal.SIGINT])
    with pytest.raises(KeyboardInterrupt):
        write_output_folder(tmp_path / "late", {"a": b""})
    assert not (tmp_path / "late").exists()
    assert sorted(p.name for p in (tmp_path / "g").iterdir()) == ["foreign", "out"]


def _wait_for_handlers(proc, limit=120.0):
    """Wait until robosolve has installed its signal handlers (SIGTERM caught, which Python
    itself never does): a signal during the interpreter's own start-up, before any robosolve
    code runs, is Python's to handle. Polls /proc, so the delays below count from that point
    whatever the machine's load."""
    status = Path(f"/proc/{proc.pid}/status")
    end = time.monotonic() + limit
    while time.monotonic() < end and proc.poll() is None and status.exists():
        try:
            caught = next(int(ln.split()[1], 16) for ln in status.read_text().splitlines()
                          if ln.startswith("SigCgt:"))
        except (OSError, StopIteration, ValueError):
            return
        if caught & (1 << (signal.SIGTERM - 1)):
            return
        time.sleep(0.01)


def _interrupt(args, cwd, delay, sig=signal.SIGINT, limit=120):
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    proc = subprocess.Popen([sys.executable, "-m", "robosolve", *args], cwd=cwd, env=env,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, start_new_session=True)
    _wait_for_handlers(proc)
    time.sleep(delay)
    os.killpg(proc.pid, sig)  # the whole group, as a terminal's Ctrl-C does
    try:
        _, err = proc.communicate(timeout=limit)
    except subprocess.TimeoutExpired:
        os.killpg(proc.pid, signal.SIGKILL)
        proc.communicate()
        pytest.fail(f"{args} hung after the signal")
    return proc.returncode, err.decode()


def _debris(folder: Path) -> list[str]:
    return sorted(p.relative_to(folder).as_posix() for p in folder.rglob(".*")
                  if p.name != MARK and "robosolve-tmp" in p.name or ".old-" in p.name)


# Delays counted from the moment robosolve's handlers are in place (_wait_for_handlers): a
# signal while the interpreter itself is still starting is Python's to handle, not robosolve's.
@pytest.mark.parametrize("delay", [0.0, 0.3, 1.0, 2.0, 3.5])
def test_sigint_to_solve_exits_130_without_debris(tmp_path, delay):
    src = PROBLEMS / "scara-rrp.yaml"
    code, err = _interrupt(["solve", str(src), "--out", "o"], tmp_path, delay)
    if code == 0:  # finished before the signal: the output is complete
        assert (tmp_path / "o" / "results.json").exists()
    else:
        assert code == 130, err
        assert "Traceback" not in err
    assert _debris(tmp_path) == []


@pytest.mark.parametrize("sig,status", [(signal.SIGINT, 130), (signal.SIGTERM, 143)])
def test_signal_to_batch_with_workers_ends_and_leaves_no_debris(tmp_path, sig, status):
    code, err = _interrupt(["batch", str(PROBLEMS), "--out", "o", "--jobs", "2"], tmp_path, 2.5, sig)
    assert code == status, err
    assert "Traceback" not in err
    assert _debris(tmp_path) == []
    for folder in (tmp_path / "o").glob("*") if (tmp_path / "o").exists() else []:
        assert (folder / MARK).exists() and (folder / "results.json").exists()  # complete or absent


@pytest.mark.parametrize("command", ["solve", "batch"])
@pytest.mark.parametrize("out", ["link", "link/sub"])
def test_a_symbolic_link_to_nowhere_is_refused_before_working(tmp_path, command, out):
    """--out through a symbolic link whose target does not exist: the folder cannot be swapped in
    there (a rename over the link: 'Not a directory', a folder made on its way: 'File exists'),
    and this was found only after solving, in the system's words. Now refused first, in words,
    the link and its target left as they were."""
    (tmp_path / "p.yaml").write_text(MINI)
    (tmp_path / "link").symlink_to(tmp_path / "gone")
    result = run_cli([command, "p.yaml", "--out", out], cwd=tmp_path)
    assert result.returncode == 2, result.stderr
    assert "symbolic link" in result.stderr and "gone" in result.stderr, result.stderr
    assert len(result.stderr.strip().splitlines()) == 1 and "answered" not in result.stdout
    assert sorted(os.listdir(tmp_path)) == ["link", "p.yaml"] and not (tmp_path / "gone").exists()
    assert os.readlink(tmp_path / "link") == str(tmp_path / "gone")
