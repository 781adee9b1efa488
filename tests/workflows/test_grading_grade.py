"""`robosolve grade`: a folder mixing good, bad and broken submissions; the CSVs computed by
hand from grading.md; duplicate ids; the output-folder rule; --variants; determinism."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest
from typer.testing import CliRunner

from robosolve.cli import app
from tests._grading import dedent

ROOT = Path(__file__).resolve().parents[2]
runner = CliRunner()

PROBLEM = """
robosolve: 1
name: two-r-grade
parameters: {L1: 1/2, L2: 2/5, F: 5}
joints:
  - {name: q1, type: revolute}
  - {name: q2, type: revolute}
frames:
  "1": {parent: "0", pose: "Rz(q1) Tx(L1)"}
  "2": {pose: "Rz(q2) Tx(L2)"}
questions:
  - {type: position, at: {q1: pi/6, q2: pi/3}, grade: [M, position, chain]}
  - {type: jacobian, coordinates: [E.x, E.y], at: {q1: pi/6, q2: pi/3}, grade: [det, singularities], marks: 2}
  - {type: statics, force: [0, -F], coordinates: [E.x, E.y], at: {q1: pi/6, q2: pi/3}, marks: 3}
"""

M = ('[["cos(q1 + q2)", "-sin(q1 + q2)", 0, "L1*cos(q1) + L2*cos(q1 + q2)"], '
     '["sin(q1 + q2)", "cos(q1 + q2)", 0, "L1*sin(q1) + L2*sin(q1 + q2)"], [0, 0, 1, 0], [0, 0, 0, 1]]')
M_T = ('[["cos(q1 + q2)", "sin(q1 + q2)", 0, 0], ["-sin(q1 + q2)", "cos(q1 + q2)", 0, 0], [0, 0, 1, 0], '
       '["L1*cos(q1) + L2*cos(q1 + q2)", "L1*sin(q1) + L2*sin(q1 + q2)", 0, 1]]')
CHAIN = ('[[["cos(q1)", "-sin(q1)", 0, "L1*cos(q1)"], ["sin(q1)", "cos(q1)", 0, "L1*sin(q1)"], [0, 0, 1, 0], '
         '[0, 0, 0, 1]], [["cos(q2)", "-sin(q2)", 0, "L2*cos(q2)"], ["sin(q2)", "cos(q2)", 0, "L2*sin(q2)"], '
         '[0, 0, 1, 0], [0, 0, 0, 1]]]')
# E at q1 = 30°, q2 = 60°: x = L1·cos 30° = 0.4330, y = L1·sin 30° + L2 = 0.65
POSITION = "[0.4330, 0.65, 0]"
FQ = '{q1: "F*(L1*cos(q1) + L2*cos(q1 + q2))", q2: "F*L2*cos(q1 + q2)"}'
FQ_NEG = '{q1: "-F*(L1*cos(q1) + L2*cos(q1 + q2))", q2: "-F*L2*cos(q1 + q2)"}'

ALICE = f"""
robosolve-answers: 1
problem: ../p.yaml
answers:
  position: {{M: {M}, position: {POSITION}, chain: {CHAIN}}}
  jacobian: {{det: "L1*L2*sin(q2)", singularities: [{{q2: pi}}, {{q2: 0}}]}}
  statics: {{Fq: {FQ}}}
"""
BOB = f"""
robosolve-answers: 1
problem: ../p.yaml
student: bob
answers:
  position: {{M: {M_T}, position: {POSITION}, chain: {CHAIN}}}
  jacobian: {{det: "0.2*sin(q2)"}}
  statics: {{Fq: {FQ_NEG}}}
"""
CAROL = "robosolve-answers: 1\nanswers:\n  position: {M: [1\n"          # broken YAML
ALICE_AGAIN = ALICE.replace("answers:\n", "student: Alice\nanswers:\n", 1)

GRADES = """\
student,question,key,verdict,diagnosis,score,out_of
Alice,position,M,invalid,,0,0.3333
Alice,position,position,invalid,,0,0.3333
Alice,position,chain,invalid,,0,0.3333
Alice,jacobian,det,invalid,,0,1
Alice,jacobian,singularities,invalid,,0,1
Alice,statics,Fq,invalid,,0,3
alice,position,M,correct,,0.3333,0.3333
alice,position,position,correct,,0.3333,0.3333
alice,position,chain,correct,,0.3333,0.3333
alice,jacobian,det,correct,,1,1
alice,jacobian,singularities,correct,,1,1
alice,statics,Fq,correct,,3,3
bob,position,M,incorrect,transposed,0,0.3333
bob,position,position,correct,,0.3333,0.3333
bob,position,chain,correct,,0.3333,0.3333
bob,jacobian,det,incorrect,parameters_substituted,0,1
bob,jacobian,singularities,missing,,0,1
bob,statics,Fq,incorrect,negated,0,3
carol,position,M,invalid,,0,0.3333
carol,position,position,invalid,,0,0.3333
carol,position,chain,invalid,,0,0.3333
carol,jacobian,det,invalid,,0,1
carol,jacobian,singularities,invalid,,0,1
carol,statics,Fq,invalid,,0,3
"""
# alice: 1 + 2 + 3 = 6 of 6; bob: 2/3 of 6 = 11.1 %
SUMMARY = """\
student,score,max_score,percent
Alice,0,6,0.0
alice,6,6,100.0
bob,0.6667,6,11.1
carol,0,6,0.0
"""


@pytest.fixture
def classroom(tmp_path):
    (tmp_path / "p.yaml").write_text(dedent(PROBLEM), encoding="utf-8")
    subs = tmp_path / "subs"
    subs.mkdir()
    for name, text in (("alice", ALICE), ("bob-file", BOB), ("carol", CAROL), ("alice2", ALICE_AGAIN)):
        (subs / f"{name}.yaml").write_text(dedent(text), encoding="utf-8")
    (subs / "notes.txt").write_text("not an answers file", encoding="utf-8")
    return tmp_path


def grade(args, cwd=None, env=None):
    cmd = [sys.executable, "-m", "robosolve", "grade", *map(str, args)]
    full_env = {**os.environ, "PYTHONPATH": str(ROOT), **(env or {})}
    return subprocess.run(cmd, capture_output=True, text=True, cwd=cwd or ROOT, env=full_env, timeout=600)


def test_grade_mixed_folder(classroom):
    out = classroom / "out"
    r = grade([classroom / "subs", "--out", out, "--problem", classroom / "p.yaml", "--jobs", "2"])
    assert r.returncode == 1, r.stderr
    assert (out / "grades.csv").read_text() == GRADES
    assert (out / "summary.csv").read_text() == SUMMARY
    assert (out / ".robosolve").exists()
    assert sorted(p.name for p in out.iterdir()) == [".robosolve", "alice.json", "bob.json", "carol.json",
                                                     "feedback", "grades.csv", "summary.csv"]
    bob = json.loads((out / "bob.json").read_text())
    assert bob["score"] == 0.6667 and bob["max_score"] == 6
    assert bob["questions"]["statics"]["keys"]["Fq"]["diagnosis"] == "negated"
    carol = json.loads((out / "carol.json").read_text())
    assert "YAML syntax error" in carol["error"]
    feedback = (out / "feedback" / "bob.md").read_text()
    assert "this is ⁰M₂ transposed: the columns of R are the axes of frame 2 in frame 0" in feedback
    assert "duplicate student id 'Alice'" in r.stderr


def test_grade_solves_each_problem_once_and_uses_problem_key(classroom):
    # without --problem each submission names ../p.yaml; carol names none and stays invalid
    out = classroom / "out2"
    r = grade([classroom / "subs" / "alice.yaml", classroom / "subs" / "bob-file.yaml", "--out", out])
    assert r.returncode == 0, r.stderr
    assert (out / "summary.csv").read_text() == "student,score,max_score,percent\nalice,6,6,100.0\nbob,0.6667,6,11.1\n"


def test_foreign_output_folder_refused(classroom):
    out = classroom / "mine"
    out.mkdir()
    (out / "thesis.tex").write_text("precious", encoding="utf-8")
    r = grade([classroom / "subs" / "alice.yaml", "--out", out, "--problem", classroom / "p.yaml"])
    assert r.returncode == 2
    assert "robosolve did not write" in r.stderr
    assert sorted(p.name for p in out.iterdir()) == ["thesis.tex"]


def test_invalid_problem_is_exit_2(classroom):
    (classroom / "bad.yaml").write_text("robosolve: 1\nname: x\nquestions: [{type: positon}]\n", encoding="utf-8")
    r = grade([classroom / "subs" / "alice.yaml", "--out", classroom / "o", "--problem", classroom / "bad.yaml"])
    assert r.returncode == 2
    assert "bad.yaml:3" in r.stderr and not (classroom / "o").exists()


def test_variants_folder(classroom):
    variants = classroom / "variants"
    (variants / "two-r-grade-1").mkdir(parents=True)
    (variants / "two-r-grade-2").mkdir(parents=True)
    base = dedent(PROBLEM)
    (variants / "two-r-grade-1" / "problem.yaml").write_text(base.replace("two-r-grade", "two-r-grade-1"))
    (variants / "two-r-grade-2" / "problem.yaml").write_text(
        base.replace("two-r-grade", "two-r-grade-2").replace("L2: 2/5", "L2: 3/5"))
    (variants / "variants.csv").write_text("variant,student,seed,L2\n1,alice,0,2/5\n2,bob,0,3/5\n")
    out = classroom / "vout"
    r = grade([classroom / "subs" / "alice.yaml", classroom / "subs" / "bob-file.yaml", "--out", out,
               "--variants", variants])
    assert r.returncode == 0, r.stderr
    alice = json.loads((out / "alice.json").read_text())
    bob = json.loads((out / "bob.json").read_text())
    assert alice["problem"] == "two-r-grade-1" and alice["score"] == 6
    assert bob["problem"] == "two-r-grade-2"
    # bob's numeric position is now wrong (L2 = 3/5 moves E); his symbolic chain is still right
    keys = bob["questions"]["position"]["keys"]
    assert keys["position"]["verdict"] == "incorrect" and keys["chain"]["verdict"] == "correct"


def test_outputs_identical_whatever_hash_seed_and_jobs(classroom):
    outs = []
    for seed, jobs in (("0", "1"), ("4242", "2")):
        out = classroom / f"det-{seed}"
        r = grade([classroom / "subs", "--out", out, "--problem", classroom / "p.yaml", "--jobs", jobs],
                  env={"PYTHONHASHSEED": seed})
        assert r.returncode == 1, r.stderr
        outs.append({str(p.relative_to(out)): p.read_bytes() for p in sorted(out.rglob("*")) if p.is_file()})
    assert outs[0] == outs[1]
    assert len(outs[0]) == 9


def test_grade_usage_errors(classroom):
    r = runner.invoke(app, ["grade", str(classroom / "nothing-here"), "--out", str(classroom / "o")])
    assert r.exit_code == 2
    r = runner.invoke(app, ["grade", str(classroom / "subs"), "--out", str(classroom / "o"),
                            "--problem", str(classroom / "p.yaml"), "--variants", str(classroom)])
    assert r.exit_code == 2


def test_each_problem_is_solved_once(classroom, monkeypatch):
    import robosolve.grading.check as check_mod
    from robosolve.grading.grade import prepare

    calls = []
    real = check_mod.solve_reference

    def counting(path, **kw):
        calls.append(str(path))
        return real(path, **kw)

    monkeypatch.setattr(check_mod, "solve_reference", counting)
    subs = classroom / "subs"
    jobs, refs = prepare([subs / "alice.yaml", subs / "bob-file.yaml", subs / "alice2.yaml"])
    assert len(calls) == 1 and len(refs) == 1
    assert [j.duplicate for j in jobs] == [False, False, True]


def test_unknown_keys_are_invalid_for_that_key_only_in_grade(classroom):
    from robosolve.grading.grade import grade_all, prepare
    from robosolve.grading.record import record

    dan = classroom / "dan.yaml"
    dan.write_text(dedent("""
        robosolve-answers: 1
        problem: p.yaml
        answers:
          positon: {M: 1}
          jacobian: {dett: 1, det: "L1*L2*sin(q2)"}
        """), encoding="utf-8")
    jobs, refs = prepare([dan])
    (result,) = grade_all(jobs, refs, 1)
    rec = record(result)
    assert rec["notes"] == [f"{dan}:4: answers.positon: unknown question id 'positon' (did you mean "
                            "'position'?) (the problem's questions: position, jacobian, statics)"]
    keys = rec["questions"]["jacobian"]["keys"]
    assert list(keys) == ["det", "singularities", "dett"]
    assert keys["det"]["verdict"] == "correct"
    assert keys["dett"]["verdict"] == "invalid" and "did you mean 'det'?" in keys["dett"]["feedback"]
    assert rec["score"] == 1           # det: half of jacobian's 2 marks


def test_variants_table_with_roster_names(tmp_path):
    from robosolve.grading.grade import read_variants

    for v in ("smith", "jo-smith"):
        (tmp_path / f"exam-{v}").mkdir()
        (tmp_path / f"exam-{v}" / "problem.yaml").write_text("robosolve: 1\n")
    (tmp_path / "variants.csv").write_text("variant,student,seed,L1\nsmith,Smith,0,1/2\njo-smith,Jo Smith,0,3/5\n")
    table = read_variants(tmp_path)
    assert table.match("Jo Smith", None).problem == table.match("jo-smith", None).problem \
        == tmp_path / "exam-jo-smith" / "problem.yaml"
    assert table.match("Smith", None).problem == tmp_path / "exam-smith" / "problem.yaml"


def test_ids_without_a_latin_letter_are_different_students(tmp_path):
    """王小明, 李雷 and Иван have no character of [a-z0-9]: their safe names are empty. They were
    all filed as 'student', so every one after the first was graded `invalid` as a "duplicate
    student id" of an id nobody else had; each is now named by 8 hex digits of its id's
    SHA-256, and the same id twice is still a duplicate."""
    import csv
    import hashlib

    (tmp_path / "p.yaml").write_text(dedent(PROBLEM), encoding="utf-8")
    subs = tmp_path / "subs"
    subs.mkdir()
    ids = {"a": "王小明", "b": "李雷", "c": "Иван Петров", "d": "李雷"}
    for stem, student in ids.items():
        (subs / f"{stem}.yaml").write_text(f"robosolve-answers: 1\nproblem: ../p.yaml\nstudent: {student}\n"
                                           "answers:\n  statics: {Fq: " + FQ + "}\n", encoding="utf-8")
    out = tmp_path / "g"
    r = runner.invoke(app, ["grade", str(subs), "--out", str(out), "--jobs", "1"])
    assert r.exit_code == 1, r.output                      # d.yaml repeats b.yaml's id
    summary = list(csv.reader((out / "summary.csv").open(encoding="utf-8")))[1:]
    assert sorted((row[0], row[1]) for row in summary) == sorted(
        [("王小明", "3"), ("李雷", "3"), ("Иван Петров", "3"), ("李雷", "0")])
    names = {f"student-{hashlib.sha256(s.encode('utf-8')).hexdigest()[:8]}" for s in set(ids.values())}
    assert {p.stem for p in out.glob("*.json")} == names
    assert {p.stem for p in (out / "feedback").glob("*.md")} == names
