"""Grading a class (grading.md, last section): roster matching, feedback pages, gradebooks.

One fixture runs the teacher's workflow once: an LMS-style roster (headers in the LMS's
case) -> `variants --roster` -> four students, three submissions (one by `problem:`, one by
the roster's ID column, one mistyped id) -> `grade --variants --gradebook`. Each LMS file is
read back by a checker written from that LMS's documented import rules.
"""

from __future__ import annotations

import csv
import io
import math
import re
from fractions import Fraction
from pathlib import Path

import pytest
import yaml
from typer.testing import CliRunner

from robosolve.cli import app

runner = CliRunner()

PROBLEM = """\
robosolve: 1
name: arm
title: Midterm, two-link arm
parameters: {L1: 1/2, L2: 2/5, F: 5}
joints:
  - {name: q1, type: revolute}
  - {name: q2, type: revolute}
frames:
  "1": {parent: "0", pose: "Rz(q1) Tx(L1)"}
  "2": {pose: "Rz(q2) Tx(L2)"}
questions:
  - {type: position, at: {q1: pi/6, q2: pi/3}, grade: [M]}
  - {type: statics, force: [0, -F], coordinates: [E.x, E.y], at: {q1: pi/6, q2: pi/3}, marks: 3}
grading:
  partial: {negated: 1/2}
variants:
  parameters:
    L2: {choices: [3/10, 2/5, 1/2, 3/5]}
"""
# the LMS export: Canvas's five student columns, then Moodle's and Blackboard's ids
ROSTER = """\
Student,ID,SIS User ID,SIS Login ID,Section,Email,IDNumber,Username
Jo Smith,101,S-1,jsmith,A,jo@uni.edu,2025/314,jsmith
Ann Lee,102,S-2,alee,A,ann@uni.edu,2025/100,alee
Bo Chen,103,S-3,bchen,B,bo@uni.edu,2025/207,bchen
Al Ng,104,S-4,ang,B,al@uni.edu,2025/555,ang
"""
M = [["cos(q1 + q2)", "-sin(q1 + q2)", 0, "L1*cos(q1) + L2*cos(q1 + q2)"],
     ["sin(q1 + q2)", "cos(q1 + q2)", 0, "L1*sin(q1) + L2*sin(q1 + q2)"], [0, 0, 1, 0], [0, 0, 0, 1]]
FQ = {"q1": "F*(L1*cos(q1) + L2*cos(q1 + q2))", "q2": "F*L2*cos(q1 + q2)"}      # Fq = −Jᵀ·Fs
FQ_NEG = {"q1": "-F*(L1*cos(q1) + L2*cos(q1 + q2))", "q2": "-F*L2*cos(q1 + q2)"}


def answers(fq, student=None, problem=None) -> str:
    data = {"robosolve-answers": 1}
    if problem:
        data["problem"] = problem
    if student:
        data["student"] = student
    data["answers"] = {"position": {"M": M}, "statics": {"Fq": fq}}
    return yaml.safe_dump(data, sort_keys=False)


@pytest.fixture(scope="module")
def course(tmp_path_factory):
    root = tmp_path_factory.mktemp("course")
    (root / "arm.yaml").write_text(PROBLEM, encoding="utf-8")
    (root / "roster.csv").write_text(ROSTER, encoding="utf-8")
    exams = root / "exams"
    r = runner.invoke(app, ["variants", str(root / "arm.yaml"), "--roster", str(root / "roster.csv"),
                            "--out", str(exams), "--no-solve"])
    assert r.exit_code == 0, r.output
    subs = root / "subs"
    subs.mkdir()
    # Jo: no `student:` line, but `problem:` names Jo's own variant
    (subs / "paper-17.yaml").write_text(answers(FQ, problem="../exams/arm-jo-smith/problem.yaml"))
    # Ann: the roster's IDNumber column, with blanks around it; Fq negated (half credit)
    (subs / "ann.yaml").write_text(answers(FQ_NEG, student=" 2025/100 "))
    # someone mistyped their id
    (subs / "typo.yaml").write_text(answers(FQ, student="2025/10"))
    out = root / "grades"
    r = runner.invoke(app, ["grade", str(subs), "--variants", str(exams), "--out", str(out),
                            "--gradebook", "canvas,moodle,blackboard", "--jobs", "1"])
    assert r.exit_code == 1, r.output          # the mistyped id is invalid
    return root


def rows(path: Path) -> list:
    return list(csv.reader(io.StringIO(path.read_text(encoding="utf-8"))))


def test_roster_csv_is_the_roster_with_variant_first(course):
    got = rows(course / "exams" / "roster.csv")
    given = rows(course / "roster.csv")
    assert got[0] == ["variant"] + given[0]
    assert [r[1:] for r in got[1:]] == given[1:]
    assert [r[0] for r in got[1:]] == ["jo-smith", "ann-lee", "bo-chen", "al-ng"]


def test_matching_and_filing(course):
    summary = {r[0]: r[1:] for r in rows(course / "grades" / "summary.csv")[1:]}
    # matched by problem: filed under its own id (the file name); through the roster: the roster's student
    assert summary == {"2025/10": ["0", "4", "0.0"], "Ann Lee": ["2.5", "4", "62.5"],
                       "paper-17": ["4", "4", "100.0"]}
    grades = rows(course / "grades" / "grades.csv")
    assert ["Ann Lee", "statics", "Fq", "incorrect", "negated", "1.5", "3"] in grades


def test_unmatched_student_says_why_with_did_you_mean(course):
    exams = course / "exams"
    reason = f"student '2025/10' is not in the roster of {exams}; did you mean '2025/100'?"
    page = (course / "grades" / "feedback" / "2025-10.md").read_text()
    assert f"No answer was graded: {reason}\n" in page and "could not be read" not in page
    record = yaml.safe_load((course / "grades" / "2025-10.json").read_text())
    keys = record["questions"]["statics"]["keys"]
    assert keys["Fq"]["verdict"] == "invalid" and keys["Fq"]["feedback"] == reason


def test_feedback_page(course):
    page = (course / "grades" / "feedback" / "ann-lee.md").read_text()
    import re
    statement = re.search(r"## 2. statics\n\n(.*)\n", page).group(1)
    assert "balance" in statement.lower() or "force" in statement.lower(), statement
    assert "E" in statement and "q_{1}" in statement, statement
    assert "### `Fq`: incorrect (negated)" in page
    assert "- You gave: `{q1: -F*(L1*cos(q1) + L2*cos(q1 + q2)), q2: -F*L2*cos(q1 + q2)}`" in page
    assert "- What is wrong: this is −Fq" in page
    assert "- Expected: `Fq = " in page
    assert "- Marks: 1.5 of 3 (partial credit)" in page
    assert "Your worked solution: [report.md](../../exams/arm-ann-lee/report.md)" in page
    jo = (course / "grades" / "feedback" / "paper-17.md").read_text()
    assert "(../../exams/arm-jo-smith/report.md)" in jo


def test_no_expected_feedback(course, tmp_path):
    out = tmp_path / "g"
    r = runner.invoke(app, ["grade", str(course / "subs" / "ann.yaml"), "--variants", str(course / "exams"),
                            "--out", str(out), "--no-expected", "--jobs", "1"])
    assert r.exit_code == 0, r.output
    page = (out / "feedback" / "ann-lee.md").read_text()
    assert "this is −Fq" in page and "- You gave:" in page
    assert "xpected" not in page
    assert "xpected" not in (out / "ann-lee.json").read_text()


# -- the importers' rules ---------------------------------------------------------
def canvas_import(text: str) -> dict:
    """lib/gradebook_importer.rb: a header row with `Student` then `ID` (more than 3 columns);
    `SIS User ID` and `SIS Login ID` together after ID; `Section` the last student column;
    an optional `Points Possible` row; a student found by ID, SIS ids or name; a blank or
    `-` score is no score; the other columns are assignments (by title)."""
    table = list(csv.reader(io.StringIO(text)))
    header = table[0]
    assert len(header) > 3 and "Student" in header[0] and "ID" in header[1]
    columns = 3
    if re.search(r"SIS\s+User\s+ID", header[2]) and re.search(r"SIS\s+Login\s+ID", header[3]):
        columns += 2
    assert "Section" in header[columns - 1]
    assignments = header[columns:]
    assert assignments and all(a not in ("Student", "ID", "SIS User ID", "SIS Login ID", "Section")
                               and not re.search("Current Score|Final Score|Current Grade|Final Grade", a)
                               for a in assignments)
    body = [r for r in table[1:] if not r[0].startswith("Points Possible")]
    scores = {}
    for r in body:
        assert len(r) == len(header)
        who = r[1] or r[2] or r[3] or r[0]
        assert who, "a student row needs an ID, SIS id or name"
        for a, v in zip(assignments, r[columns:]):
            assert v in ("", "-") or re.fullmatch(r"-?\d+(\.\d{1,4})?", v), v
            scores[(who, a)] = v
    return scores


def moodle_import(text: str, map_by: str) -> dict:
    """grade/import/csv: a header row of unique names; the teacher maps one column to a user
    field (email, idnumber) and the others to grade items or their feedback; a grade is a
    number, an empty cell is left alone."""
    table = list(csv.reader(io.StringIO(text)))
    header = table[0]
    assert len(set(header)) == len(header) and all(header)
    ident = header.index(map_by)
    out = {}
    for r in table[1:]:
        assert len(r) == len(header) and r[ident]
        assert r[2] == "" or re.fullmatch(r"\d+(\.\d{1,4})?", r[2])
        out[r[ident]] = (r[2], r[3])
    return out


def blackboard_upload(text: str) -> dict:
    """Grade Center upload: a `Username` column identifies the user (required, unique);
    each other column is a Grade Center column by name; a number or empty."""
    table = list(csv.reader(io.StringIO(text)))
    header = table[0]
    assert header[0] == "Username" and len(header) == 2
    users = [r[0] for r in table[1:]]
    assert all(users) and len(set(users)) == len(users)
    return {r[0]: r[1] for r in table[1:]}


def test_canvas_gradebook(course):
    text = (course / "grades" / "gradebook" / "canvas.csv").read_text()
    assert text.splitlines()[0] == "Student,ID,SIS User ID,SIS Login ID,Section,"  '"Midterm, two-link arm"'
    scores = canvas_import(text)
    assert scores == {("101", "Midterm, two-link arm"): "4", ("102", "Midterm, two-link arm"): "2.5",
                      ("103", "Midterm, two-link arm"): "", ("104", "Midterm, two-link arm"): ""}
    assert rows(course / "grades" / "gradebook" / "canvas.csv")[1] == \
        ["Jo Smith", "101", "S-1", "jsmith", "A", "4"]


def test_moodle_gradebook(course):
    text = (course / "grades" / "gradebook" / "moodle.csv").read_text()
    assert rows(course / "grades" / "gradebook" / "moodle.csv")[0] == \
        ["email", "idnumber", "Midterm, two-link arm", "Midterm, two-link arm feedback"]
    by_email = moodle_import(text, "email")
    assert by_email == {"jo@uni.edu": ("4", "4/4"), "ann@uni.edu": ("2.5", "2.5/4: statics.Fq negated"),
                        "bo@uni.edu": ("", ""), "al@uni.edu": ("", "")}
    assert moodle_import(text, "idnumber")["2025/100"][0] == "2.5"


def test_blackboard_gradebook(course):
    got = blackboard_upload((course / "grades" / "gradebook" / "blackboard.csv").read_text())
    assert list(got.items()) == [("jsmith", "4"), ("alee", "2.5"), ("bchen", ""), ("ang", "")]


def test_gradebook_usage_errors(course, tmp_path):
    subs = str(course / "subs" / "ann.yaml")
    r = runner.invoke(app, ["grade", subs, "--variants", str(course / "exams"), "--out", str(tmp_path / "a"),
                            "--gradebook", "canvas,moodel"])
    assert r.exit_code == 2 and "unknown LMS 'moodel' (did you mean 'moodle'?)" in r.output
    assert not (tmp_path / "a").exists()
    r = runner.invoke(app, ["grade", subs, "--problem", str(course / "arm.yaml"), "--out", str(tmp_path / "b"),
                            "--gradebook", "canvas"])
    assert r.exit_code == 2 and "--gradebook needs a roster" in r.output
    assert not (tmp_path / "b").exists()


def test_an_empty_gradebook_option_is_a_usage_error():
    """`--gradebook ""` names no LMS: refused like `--gradebook ,` (it was taken as not given)."""
    from robosolve.grading.gradebook import GradebookError, parse_lms

    assert parse_lms(None) == ()
    for text in ("", ",", " , "):
        with pytest.raises(GradebookError, match="give some of canvas, moodle, blackboard"):
            parse_lms(text)


def test_moodle_needs_email_or_idnumber(tmp_path):
    (tmp_path / "arm.yaml").write_text(PROBLEM)
    (tmp_path / "class.csv").write_text("Student,Username\nJo Smith,jsmith\n")
    exams = tmp_path / "exams"
    assert runner.invoke(app, ["variants", str(tmp_path / "arm.yaml"), "--roster", str(tmp_path / "class.csv"),
                               "--out", str(exams), "--no-solve"]).exit_code == 0
    (tmp_path / "jo.yaml").write_text(answers(FQ, student="jsmith"))
    r = runner.invoke(app, ["grade", str(tmp_path / "jo.yaml"), "--variants", str(exams), "--out",
                            str(tmp_path / "g"), "--gradebook", "moodle"])
    assert r.exit_code == 2 and "has no `email` or `idnumber` column" in r.output
    assert not (tmp_path / "g").exists()


def _grade_again(course, tmp_path, submissions: dict):
    """`grade --variants` of the course's exams on these submissions (file name -> text)."""
    subs = tmp_path / "subs"
    subs.mkdir()
    for name, text in submissions.items():
        (subs / name).write_text(text)
    out = tmp_path / "g"
    r = runner.invoke(app, ["grade", str(subs), "--variants", str(course / "exams"), "--out", str(out),
                            "--gradebook", "canvas", "--jobs", "1"])
    return r, out


@pytest.mark.parametrize("by_problem_first", [True, False])
@pytest.mark.parametrize("own_id", ["102", "s-999"])
def test_two_submissions_of_one_roster_student_are_a_duplicate(course, tmp_path, by_problem_first, own_id):
    """Ann Lee twice: once by `problem:` (her variant), as her roster ID `102` (so filed under
    her roster name) or as an id the roster does not hold (filed under it, her variant's row
    standing for it), once by her roster name. The file sorted later is the duplicate (graded
    invalid, naming the first), and `grade` exits 1 — both were graded and the gradebook
    silently kept one score."""
    by_problem = answers(FQ, student=own_id, problem=str(course / "exams" / "arm-ann-lee" / "problem.yaml"))
    by_name = answers(FQ_NEG, student="Ann Lee")         # Fq negated: half of its 3 marks, 2.5 / 4
    first, second = ("a.yaml", "b.yaml") if by_problem_first else ("b.yaml", "a.yaml")
    r, out = _grade_again(course, tmp_path, {first: by_problem, second: by_name})
    assert r.exit_code == 1, r.output
    filed = "Ann Lee" if own_id == "102" else own_id
    kept, dup = (filed, "Ann Lee") if by_problem_first else ("Ann Lee", filed)
    score = "4" if by_problem_first else "2.5"
    assert sorted(row[:2] for row in rows(out / "summary.csv")[1:]) == sorted([[kept, score], [dup, "0"]])
    same = "" if kept == dup else f" (the same roster student as '{kept}')"
    assert f"duplicate student id '{dup}'{same}: " in " ".join(r.output.split())
    if kept != dup:                # the duplicate has its own record
        record = yaml.safe_load((out / f"{re.sub('[^a-z0-9_-]+', '-', dup.lower())}.json").read_text())
        reason = record["questions"]["statics"]["keys"]["Fq"]["feedback"]
        assert reason.startswith(f"duplicate student id '{dup}'") and str(tmp_path / "subs" / "a.yaml") in reason
    canvas = {row[1]: row[-1] for row in rows(out / "gradebook" / "canvas.csv")[1:]}
    assert canvas == {"101": "", "102": score, "103": "", "104": ""}


def _pose_numbers(L1, L2, q1=math.pi / 6, q2=math.pi / 3) -> list:
    """The two-link arm's 0M2 at (q1, q2), closed form, 6 decimals (as a student writes it)."""
    c, s = math.cos(q1 + q2), math.sin(q1 + q2)
    return [[round(c, 6), round(-s, 6), 0, round(L1 * math.cos(q1) + L2 * c, 6)],
            [round(s, 6), round(c, 6), 0, round(L1 * math.sin(q1) + L2 * s, 6)], [0, 0, 1, 0], [0, 0, 0, 1]]


@pytest.mark.parametrize("hers_first", [True, False])
def test_answering_another_students_variant_keeps_the_students_row(course, tmp_path, hers_first):
    """Ann Lee's file names Jo Smith's variant by `problem:` and answers it right (M in numbers,
    closed form with Jo's L2); Jo hands in his own with M of Ann's L2 (wrong for his variant).
    Ann is graded against Jo's variant but stays Ann: her gradebook row, her files, a note
    naming Jo's variant; Jo is not her duplicate (he was: his submission invalid, his row Ann's
    score, hers empty)."""
    exams = course / "exams"
    params = {v: yaml.safe_load((exams / f"arm-{v}" / "problem.yaml").read_text())["parameters"]
              for v in ("jo-smith", "ann-lee")}
    length = {v: [float(Fraction(str(p[k]))) for k in ("L1", "L2")] for v, p in params.items()}
    assert length["jo-smith"][1] != length["ann-lee"][1]      # the two variants differ in M
    hers = yaml.safe_dump({"robosolve-answers": 1, "problem": str(exams / "arm-jo-smith" / "problem.yaml"),
                           "student": "Ann Lee", "answers": {"position": {"M": _pose_numbers(*length["jo-smith"])},
                                                             "statics": {"Fq": FQ}}}, sort_keys=False)
    his = yaml.safe_dump({"robosolve-answers": 1, "student": "Jo Smith",
                          "answers": {"position": {"M": _pose_numbers(*length["ann-lee"])},
                                      "statics": {"Fq": FQ}}}, sort_keys=False)
    names = ("a.yaml", "b.yaml") if hers_first else ("b.yaml", "a.yaml")
    r, out = _grade_again(course, tmp_path, {names[0]: hers, names[1]: his})
    assert r.exit_code == 0, r.output          # every submission read, no duplicate
    assert rows(out / "summary.csv")[1:] == [["Ann Lee", "4", "4", "100.0"], ["Jo Smith", "3", "4", "75.0"]]
    assert ["Jo Smith", "position", "M", "incorrect", "", "0", "1"] in rows(out / "grades.csv")
    canvas = {row[1]: row[-1] for row in rows(out / "gradebook" / "canvas.csv")[1:]}
    assert canvas == {"101": "3", "102": "4", "103": "", "104": ""}
    ann = yaml.safe_load((out / "ann-lee.json").read_text())
    note = "answered the variant of 'Jo Smith' (jo-smith, named by `problem:`), not its own (ann-lee)"
    assert ann["problem"] == "arm-jo-smith" and note in ann["note"]
    assert "note" not in yaml.safe_load((out / "jo-smith.json").read_text())
    page = (out / "feedback" / "ann-lee.md").read_text()
    assert f"Note: this submission {note}; graded against jo-smith.\n" in page
    assert "/exams/arm-jo-smith/report.md)" in page          # her worked solution: the variant she answered
    said = " ".join(r.output.split())
    assert f"this submission of 'Ann Lee' {note}; graded against jo-smith (filed under 'Ann Lee', in that student's gradebook row)" in said
    assert "jo-smith" not in (out / "feedback" / "jo-smith.md").read_text().replace("arm-jo-smith", "")


def test_a_variant_id_is_filed_under_the_roster_student(course, tmp_path):
    """`student: ann-lee` (the variant's id, a column of roster.csv) is matched through the
    roster, so filed under the roster's student, `Ann Lee`, like any other roster value."""
    r, out = _grade_again(course, tmp_path, {"x.yaml": answers(FQ_NEG, student="ANN-LEE"),
                                             "y.yaml": answers(FQ, student="ann lee")})
    assert r.exit_code == 1, r.output            # the same student twice
    assert rows(out / "summary.csv")[1:] == [["Ann Lee", "2.5", "4", "62.5"], ["Ann Lee", "0", "4", "0.0"]]
    canvas = {row[1]: row[-1] for row in rows(out / "gradebook" / "canvas.csv")[1:]}
    assert canvas == {"101": "", "102": "2.5", "103": "", "104": ""}


def test_matching_rules_in_order(tmp_path):
    from robosolve.grading.matching import MatchError, read_table

    for v in ("jo", "ann", "3"):
        (tmp_path / f"exam-{v}").mkdir()
        (tmp_path / f"exam-{v}" / "problem.yaml").write_text("robosolve: 1\n")
    (tmp_path / "variants.csv").write_text("variant,student,seed\njo,Jo,0\nann,Ann,0\n3,,0\n")
    (tmp_path / "roster.csv").write_text("variant,STUDENT,E-Mail,Group\njo,Jo,jo@x.org,G1\nann,Ann,ann@x.org,G1\n")
    table = read_table(tmp_path)
    # 1. problem: inside DIR wins over the student id
    m = table.match("Ann", tmp_path / "exam-jo" / "problem.yaml")
    assert (m.variant, m.student) == ("jo", "Ann")
    #    ... but the student is who the id says: Ann's row, her own variant noted
    assert (m.row, m.own_variant) == (1, "ann")
    m = table.match("ann@x.org", tmp_path / "exam-jo" / "problem.yaml")
    assert (m.variant, m.student, m.row, m.own_variant) == ("jo", "Ann", 1, "ann")
    #    an id the roster does not hold: the variant's row stands for it, filed under the id
    m = table.match("nobody", tmp_path / "exam-jo" / "problem.yaml")
    assert (m.variant, m.student, m.row, m.own_variant) == ("jo", "nobody", 0, "")
    #    a value two rows share, one of them the variant's: that row
    m = table.match("G1", tmp_path / "exam-jo" / "problem.yaml")
    assert (m.variant, m.student, m.row, m.own_variant) == ("jo", "Jo", 0, "")
    # 2. any roster column, trimmed, case ignored; filed under the roster's student
    m = table.match("  JO@X.ORG ", tmp_path / "elsewhere.yaml")
    assert (m.variant, m.student, m.row) == ("jo", "Jo", 0)
    # a value two variants share
    with pytest.raises(MatchError, match=r"student 'G1' matches 2 variants in the roster of .*\(jo, ann\)"):
        table.match("G1", None)
    # 3. the variant ids
    assert table.match("3", None).variant == "3"
    # nothing: a did-you-mean among the roster's values
    with pytest.raises(MatchError) as exc:
        table.match("ann@x.orgg", None)
    assert str(exc.value) == f"student 'ann@x.orgg' is not in the roster of {tmp_path}; did you mean 'ann@x.org'?"


def test_feedback_statement_is_the_papers_with_rates_named(tmp_path):
    """The feedback page states a question as the paper does: the rates `q1_dot`, `q1_ddot` in
    the problem's notation (q̇₁, q̈₁), not sympy's default print of the names (q_{1 dot})."""
    (tmp_path / "p.yaml").write_text(PROBLEM.split("questions:")[0] + """questions:
  - {type: velocity_acceleration, at: {q1: pi/6, q2: pi/3, q1_dot: 1, q2_dot: 2, q1_ddot: 0, q2_ddot: 1}}
""", encoding="utf-8")
    (tmp_path / "s.yaml").write_text("robosolve-answers: 1\nproblem: p.yaml\nanswers: {}\n")
    r = runner.invoke(app, ["paper", str(tmp_path / "p.yaml"), "--out", str(tmp_path / "paper")])
    assert r.exit_code == 0, r.output
    r = runner.invoke(app, ["grade", str(tmp_path / "s.yaml"), "--out", str(tmp_path / "g"), "--jobs", "1"])
    assert r.exit_code == 0, r.output
    paper = (tmp_path / "paper" / "paper.md").read_text(encoding="utf-8")
    page = (tmp_path / "g" / "feedback" / "s.md").read_text(encoding="utf-8")
    statement = re.search(r"## 1\. velocity_acceleration\n\n(.*)\n", page).group(1)
    assert "\\dot{q}_{1} = 1" in statement and "\\ddot{q}_{2} = 1" in statement, statement
    assert "dot}" not in statement.replace("\\dot{q}", "").replace("\\ddot{q}", ""), statement
    assert statement in paper


def test_another_variant_without_a_roster_is_noted_by_its_ids(course, tmp_path):
    """A `variants --count` folder names no student: a file of variant 1 (by its id) that names
    variant 2's problem.yaml is graded against 2, filed under '1', and its note names both ids."""
    exams = tmp_path / "exams"                  # what `variants --count 2` writes (two of the course's variants)
    for v, given in (("1", "ann-lee"), ("2", "jo-smith")):
        (exams / f"arm-{v}").mkdir(parents=True)
        (exams / f"arm-{v}" / "problem.yaml").write_text((course / "exams" / f"arm-{given}" / "problem.yaml").read_text())
    (exams / "variants.csv").write_text("variant,student,seed\n1,,0\n2,,0\n")
    subs = tmp_path / "subs"
    subs.mkdir()
    (subs / "a.yaml").write_text(answers(FQ, student="1", problem=str(exams / "arm-2" / "problem.yaml")))
    r = runner.invoke(app, ["grade", str(subs), "--variants", str(exams), "--out", str(tmp_path / "g"), "--jobs", "1"])
    assert r.exit_code == 0, r.output
    record = yaml.safe_load((tmp_path / "g" / "1.json").read_text())
    assert record["student"] == "1"
    assert record["note"] == "answered variant 2 (named by `problem:`), not its own (1); graded against 2"
