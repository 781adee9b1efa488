"""The command line: exit codes, nothing written on bad input, batch and the golden check."""

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest
from typer.testing import CliRunner

from conftest import MINI, PROBLEMS, ROOT
from robosolve.cli import app

runner = CliRunner()


def test_help_is_quick_and_lists_commands():
    result = runner.invoke(app, ["--help"])
    assert result.exit_code == 0
    for cmd in ("solve", "validate", "batch"):
        assert cmd in result.output
    # no heavy module imported just for --help
    code = "import sys, robosolve.cli; print(sorted(m for m in ('sympy','numpy','matplotlib') if m in sys.modules))"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=ROOT).stdout
    assert out.strip() == "[]"


def test_solve_writes_outputs(write_problem, tmp_path):
    src = write_problem(MINI)
    out = tmp_path / "o"
    result = runner.invoke(app, ["solve", str(src), "--out", str(out)])
    assert result.exit_code == 0, result.output
    data = json.loads((out / "results.json").read_text())
    assert data["format"] == 1 and data["problem"] == "mini"
    assert data["answers"]["position"]["numeric"]["position"] == [1.0, 0.0, 0.0]
    assert (out / "report.md").read_text().startswith("# mini")
    assert (out / "figures" / "position-robot.png").exists()


def test_invalid_input_exit_2_and_nothing_written(write_problem, tmp_path):
    src = write_problem(MINI.replace("Tx(L)", "Tx(LL)"))
    out = tmp_path / "o"
    result = runner.invoke(app, ["solve", str(src), "--out", str(out)])
    assert result.exit_code == 2
    assert f"{src}:6: frames.1.pose: unknown name 'LL'" in result.output
    assert "Traceback" not in result.output
    assert not out.exists()


def test_unsupported_or_failed_question_exit_1(write_problem, tmp_path, monkeypatch):
    # a question whose solver reports an error still gets its entry, the others are answered; exit 1
    import robosolve.solvers.position as position
    from robosolve.errors import SolverError

    real = position.solve

    def failing_second(question, ctx):
        if question.id == "second":
            raise SolverError("cannot answer this one")
        return real(question, ctx)

    monkeypatch.setattr(position, "solve", failing_second)
    src = write_problem(MINI + "  - {type: position, at: {q: 0}, id: second}\n")
    out = tmp_path / "o"
    result = runner.invoke(app, ["solve", str(src), "--out", str(out)])
    assert result.exit_code == 1, result.output
    answers = json.loads((out / "results.json").read_text())["answers"]
    assert answers["second"]["error"] == "cannot answer this one"
    assert "error" not in answers["position"]
    assert "second: cannot answer this one" in result.output


def test_validate(write_problem):
    good = write_problem(MINI, "good.yaml")
    bad = write_problem(MINI.replace("revolute", "revolut"), "bad.yaml")
    assert runner.invoke(app, ["validate", str(good)]).exit_code == 0
    result = runner.invoke(app, ["validate", str(good), str(bad)])
    assert result.exit_code == 2
    assert "did you mean 'revolute'" in result.output


def test_batch_continues_past_bad_file_and_exit_is_worst(write_problem, tmp_path):
    write_problem(MINI, "a.yaml")
    write_problem(MINI.replace("name: mini", "name: mini2").replace("Tx(L)", "Tx(LL)"), "b.yaml")
    out = tmp_path / "out"
    result = runner.invoke(app, ["batch", str(tmp_path), "--out", str(out), "--jobs", "1"])
    assert result.exit_code == 2
    assert (out / "mini" / "report.md").exists()


def test_golden_check_detects_a_difference(write_problem, tmp_path):
    write_problem(MINI, "a.yaml")
    golden = tmp_path / "golden"
    src = str(tmp_path / "a.yaml")
    assert runner.invoke(app, ["batch", src, "--check", str(golden), "--update", "--jobs", "1"]).exit_code == 0
    assert runner.invoke(app, ["batch", src, "--check", str(golden), "--jobs", "1"]).exit_code == 0
    res = golden / "mini" / "results.json"
    res.write_text(res.read_text().replace("1.0, 0.0, 0.0", "1.5, 0.0, 0.0"))
    result = runner.invoke(app, ["batch", src, "--check", str(golden), "--jobs", "1"])
    assert result.exit_code == 1
    assert "$.answers.position.numeric.position[0]: 1.5 -> 1.0" in result.output


@pytest.mark.parametrize("seed", ["1", "2"])
def test_byte_identical_across_hash_seeds(tmp_path, seed):
    """Same input, same bytes whatever PYTHONHASHSEED (compared with seed 0)."""
    outs = []
    for s in ("0", seed):
        out = tmp_path / f"o{s}"
        env = dict(os.environ, PYTHONHASHSEED=s)
        subprocess.run([sys.executable, "-m", "robosolve", "solve", str(PROBLEMS / "scara-rrp.yaml"),
                        "--out", str(out)], check=True, env=env, cwd=ROOT, capture_output=True)
        outs.append(out)
    for name in ("report.md", "results.json"):
        assert (outs[0] / name).read_bytes() == (outs[1] / name).read_bytes()


def test_golden_outputs_of_bundled_problems():
    """Regenerate every bundled problem and compare with tests/golden (robosolve batch --check)."""
    result = subprocess.run([sys.executable, "-m", "robosolve", "batch", str(PROBLEMS),
                             "--check", str(ROOT / "tests" / "golden")],
                            capture_output=True, text=True, cwd=ROOT)
    assert result.returncode == 0, result.stdout[-5000:] + result.stderr[-3000:]
