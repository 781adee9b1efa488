"""Gradescope (grading.md, last section): `check --json-format gradescope` and the
autograder of docs/grading.md, run against a fake /autograder tree."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest
import yaml
from typer.testing import CliRunner

from robosolve.cli import app
from tests.workflows.test_grading_class import FQ, FQ_NEG, PROBLEM, ROSTER, answers

ROOT = Path(__file__).resolve().parents[2]
runner = CliRunner()


@pytest.fixture(scope="module")
def exam(tmp_path_factory):
    root = tmp_path_factory.mktemp("gs")
    (root / "arm.yaml").write_text(PROBLEM.replace("variants:", "unused:").split("unused:")[0])
    (root / "bad.yaml").write_text(answers(FQ_NEG, student="s1", problem="arm.yaml"))
    return root


def check(args):
    return runner.invoke(app, ["check", *map(str, args)])


def test_gradescope_layout(exam):
    out = exam / "results.json"
    r = check([exam / "bad.yaml", "--json", out, "--json-format", "gradescope"])
    assert r.exit_code == 1, r.output
    data = json.loads(out.read_text())
    assert list(data) == ["score", "max_score", "tests", "output"]
    assert (data["score"], data["max_score"]) == (2.5, 4)
    assert [t["name"] for t in data["tests"]] == ["position.M", "statics.Fq"]
    assert data["tests"][0] == {"name": "position.M", "score": 1, "max_score": 1, "output": "correct: "}
    fq = data["tests"][1]
    assert (fq["score"], fq["max_score"]) == (1.5, 3)
    assert fq["output"].startswith("incorrect: this is −Fq") and "expected Fq = " in fq["output"]
    assert sum(t["score"] for t in data["tests"]) == data["score"]
    assert data["output"] == "2.5/4: statics.Fq negated"


def test_gradescope_no_expected(exam):
    out = exam / "hidden.json"
    r = check([exam / "bad.yaml", "--json", out, "--json-format", "gradescope", "--no-expected"])
    assert r.exit_code == 1
    text = out.read_text()
    assert "this is −Fq" in text and "xpected" not in text
    assert "xpected" not in r.output


def test_json_format_usage_errors(exam):
    r = check([exam / "bad.yaml", "--json", exam / "x.json", "--json-format", "gradscope"])
    assert r.exit_code == 2 and "unknown format 'gradscope' (did you mean 'gradescope'?)" in r.output
    r = check([exam / "bad.yaml", "--json-format", "gradescope"])
    assert r.exit_code == 2 and "--json-format goes with --json FILE" in r.output
    assert not (exam / "x.json").exists()


# -- the autograder of docs/grading.md ----------------------------------------------
SCRIPTS = ROOT / "docs" / "gradescope"


def test_docs_show_the_autograder_as_it_is():
    doc = (ROOT / "docs" / "grading.md").read_text(encoding="utf-8")
    for name in ("setup.sh", "run_autograder"):
        assert f"```bash\n{(SCRIPTS / name).read_text()}```" in doc, name
        subprocess.run(["bash", "-n", str(SCRIPTS / name)], check=True)


def autograde(tree: Path, users: list) -> dict:
    (tree / "submission_metadata.json").write_text(json.dumps({"id": 1, "users": users}))
    env = {**os.environ, "AUTOGRADER_ROOT": str(tree), "ROBOSOLVE": f"{sys.executable} -m robosolve",
           "PYTHONPATH": str(ROOT)}
    results = tree / "results" / "results.json"
    results.unlink(missing_ok=True)
    subprocess.run(["bash", str(SCRIPTS / "run_autograder")], env=env, check=True, timeout=600,
                   capture_output=True)
    return json.loads(results.read_text())


def test_autograder_round_trip(tmp_path):
    (tmp_path / "arm.yaml").write_text(PROBLEM)
    (tmp_path / "class.csv").write_text(ROSTER)
    tree = tmp_path / "autograder"
    exams = tree / "source" / "exams"
    r = runner.invoke(app, ["variants", str(tmp_path / "arm.yaml"), "--roster", str(tmp_path / "class.csv"),
                            "--out", str(exams), "--no-solve"])
    assert r.exit_code == 0, r.output
    (tree / "submission").mkdir()
    (tree / "submission" / "answers.yaml").write_text(answers(FQ_NEG))
    # Ann, by her e-mail in Gradescope's metadata (case differs)
    data = autograde(tree, [{"email": "Ann@uni.edu", "name": "Ann", "sid": ""}])
    assert (data["score"], data["max_score"]) == (2.5, 4)
    assert data["tests"][1]["output"].startswith("incorrect: this is −Fq")
    assert "xpected" not in json.dumps(data, ensure_ascii=False)
    # Bo, by his student id, with every answer right (symbolic: right in every variant)
    (tree / "submission" / "answers.yaml").write_text(answers(FQ))
    assert autograde(tree, [{"email": "", "name": "", "sid": "2025/207"}])["score"] == 4
    # a user the roster does not know: score 0 and why
    data = autograde(tree, [{"email": "who@else.edu", "name": "Who", "sid": ""}])
    assert data["score"] == 0 and "0 roster rows match" in data["output"]
    # an answers file that is not valid input
    (tree / "submission" / "answers.yaml").write_text(yaml.safe_dump({"robosolve-answers": 1, "answrs": {}}))
    data = autograde(tree, [{"email": "ann@uni.edu"}])
    assert data["score"] == 0 and "could not be checked" in data["output"] and "answrs" in data["output"]
