"""One mistake, one message: a misspelt key gives its did-you-mean and nothing else — not the
"missing" or "needs" messages of the key it meant, nor errors in the sections and questions that
use it. Found by misspelling every key of the bundled problems (the loader had 48 cascades in
question keys and ~450 across sections); the cases below are one of each kind, then the sweeps of
every key and every word (and, slow, every value broken)."""

from __future__ import annotations

import copy
import re
from pathlib import Path

import pytest
import yaml

from robosolve.errors import InputError
from robosolve.load.loader import load_problem_text

ROOT = Path(__file__).resolve().parents[2]


def _issues(data) -> list[str]:
    with pytest.raises(InputError) as exc:
        load_problem_text(yaml.safe_dump(data, sort_keys=False, allow_unicode=True), "p.yaml")
    return [str(i) for i in exc.value.issues]


def _renamed(node: dict, key, wrong) -> None:
    items = list(node.items())
    node.clear()
    node.update((wrong if k == key else k, v) for k, v in items)


def _at(data, path):
    for p in path:
        data = data[p]
    return data


CASES = [   # (problem, path of the mapping, key, misspelling, what used to follow it)
    ("exam-2r-full", (), "joints", "jints", "unknown name 'theta1' in every frame"),
    ("exam-2r-full", (), "parameters", "prameters", "unknown names L1, m1 everywhere"),
    ("exam-2r-full", (), "frames", "fames", "unknown frames in the bodies"),
    ("exam-2r-full", ("joints", 0), "name", "nme", "theta1 unknown in frames and `at`"),
    ("exam-2r-full", ("joints", 0), "type", "tpe", "theta1 unknown in frames and `at`"),
    ("exam-2r-full", ("bodies", 2), "point", "pint", "exactly one mass distribution"),
    ("exam-2r-full", ("questions", 3), "force", "frce", "expected force, torque or weight"),
    ("exam-2r-full", ("questions", 3), "coordinates", "cordinates", "3 components expected"),
    ("exam-2r-full", ("questions", 7, "max_acceleration"), "theta1", "teta1", "missing joint theta1"),
    ("pendulum-runs", ("joints", 0), "actuator", "atuator", "unknown actuator C in three questions"),
    ("kuka-kr", ("dh",), "rows", "rws", "no rows, unknown frames in the bodies"),
    ("workspace-2r-line", ("questions", 0), "coordinates", "cordinates", "tall J, gains of E.x missing"),
    ("workspace-2r-line", ("questions", 0), "max_velocity", "mx_velocity", "the timing needs max_velocity"),
    ("workspace-2r-line", ("questions", 1), "trajectory", "tajectory", "needs a motion_profile question"),
    ("rigid-displacements", ("questions", 5), "angle", "agle", "missing required key 'angle'"),
    ("rigid-displacements", ("questions", 12), "space", "sapce", "3-DOF joints only with space: spatial"),
]


@pytest.mark.parametrize("name, path, key, wrong, cascade", CASES,
                         ids=[f"{c[0]}:{'.'.join(map(str, c[1] + (c[2],)))}" for c in CASES])
def test_a_misspelt_key_gives_its_did_you_mean_alone(name, path, key, wrong, cascade):
    data = yaml.safe_load((ROOT / "problems" / f"{name}.yaml").read_text())
    _renamed(_at(data, path), key, wrong)
    issues = _issues(data)
    assert len(issues) == 1, (cascade, issues)
    assert f"'{wrong}'" in issues[0] and f"did you mean '{key}'" in issues[0]


VALUE_CASES = [   # (problem, path of the value, misspelling, what used to follow it)
    ("exam-2r-full", ("questions", 2, "type"), "jcobian", "variants: unknown question id 'jacobian'"),
    ("exam-2r-full", ("questions", 7, "type"), "mtion_profile", "no motion_profile question with id 'profile'"),
    ("workspace-2r-line", ("questions", 0, "type"), "tsk_trajectory", "no task_trajectory with id 'line'"),
    ("ik-planar-3r", ("joints", 0, "type"), "rvolute", "unknown name theta1 in frames and targets"),
    ("scara-rrp", ("joints", 2, "type"), "pismatic", "unknown name l in frames and `at`"),
    ("kuka-kr", ("dh", "convention"), "sandard", "no frames: unknown frames in the bodies"),
    ("panda", ("dh", "convention"), "mdified", "unknown parent frame 7"),
    ("workspace-2r-line", ("questions", 1, "law"), "tsk_pd_gravity", "law p takes gains per joint"),
    ("rigid-displacements", ("questions", 12, "space"), "satial", "3-DOF joints only with space: spatial"),
]


@pytest.mark.parametrize("name, path, wrong, cascade", VALUE_CASES,
                         ids=[f"{c[0]}:{'.'.join(map(str, c[1]))}" for c in VALUE_CASES])
def test_a_misspelt_word_gives_its_did_you_mean_alone(name, path, wrong, cascade):
    data = yaml.safe_load((ROOT / "problems" / f"{name}.yaml").read_text())
    right = _at(data, path[:-1])[path[-1]]
    _at(data, path[:-1])[path[-1]] = wrong
    issues = _issues(data)
    assert len(issues) == 1, (cascade, issues)
    assert f"'{wrong}'" in issues[0] and f"did you mean '{right}'" in issues[0]


def test_the_meant_key_is_not_judged_but_other_mistakes_still_are():
    """What is inside the misspelt key is checked once its name is right (a second message about a
    key the file does not have would confuse); a mistake elsewhere is still its own message."""
    data = yaml.safe_load((ROOT / "problems" / "workspace-2r-line.yaml").read_text())
    q = data["questions"][0]
    q["max_velocity"] = -1
    _renamed(q, "coordinates", "cordinates")
    issues = _issues(data)
    assert len(issues) == 2, issues
    assert any("cordinates" in i for i in issues) and any("max_velocity" in i and "positive" in i for i in issues)


def test_a_misspelt_question_type_key_says_so():
    data = yaml.safe_load((ROOT / "problems" / "scara-rrp.yaml").read_text())
    _renamed(data["questions"][0], "type", "tpye")
    assert [i.split(": ", 1)[1] for i in _issues(data)] == ["questions[0].tpye: unknown key 'tpye' (did you mean 'type'?)"]


def test_an_answers_file_given_as_a_problem_is_one_message():
    text = (ROOT / "problems" / "answers" / "exam-2r-full-student.yaml").read_text()
    with pytest.raises(InputError) as exc:
        load_problem_text(text, "a.yaml")
    assert len(exc.value.issues) == 1 and "answers file" in str(exc.value.issues[0])


def test_a_misspelt_top_key_of_an_answers_file_is_one_message():
    from robosolve.grading.answers import read_answers_text

    text = (ROOT / "problems" / "answers" / "exam-2r-full-student.yaml").read_text()
    submission = read_answers_text(text.replace("robosolve-answers: 1", "robosolve-anwers: 1"), "a.yaml")
    issues = [str(i) for i in submission.issues]       # (not "missing robosolve-answers" besides)
    assert len(issues) == 1 and "did you mean 'robosolve-answers'" in issues[0], issues


def _keys(node, path=()):
    """(path of a mapping, key) for the keys the loader reads by name (not the names of data:
    parameters, frames, `at`, targets, gains, …)."""
    data_keys = {"parameters", "at", "gains", "gains_d", "target", "from", "to", "start", "select",
                 "velocity", "force", "limits", "values", "variants", "grading", "paper"}
    if isinstance(node, dict):
        for k, v in node.items():
            if not isinstance(k, str) or k in data_keys:
                continue
            if not (path == ("frames",) or (len(path) == 2 and path[0] == "questions" and k in ("type", "id"))):
                yield path, k
            yield from _keys(v, path + (k,))
    elif isinstance(node, list):
        for i, v in enumerate(node):
            yield from _keys(v, path + (i,))


def _not_one_message(mutants, suggestion: bool) -> list:
    """(what, messages) of each mutated problem (what, data) that does not give exactly one
    message (with a did-you-mean, when `suggestion`), or is accepted."""
    flagged = []
    for what, bad in mutants:
        try:
            load_problem_text(yaml.safe_dump(bad, sort_keys=False, allow_unicode=True), "p.yaml")
        except InputError as exc:
            issues = [str(i) for i in exc.issues]
            if len(issues) != 1 or (suggestion and "did you mean" not in issues[0]):
                flagged.append((what, issues[:3]))
        else:
            flagged.append((what, "accepted"))
    return flagged


def _key_misspelt(data, path, key):
    bad = copy.deepcopy(data)
    _renamed(_at(bad, path), key, key[0] + key[2:])          # a letter dropped
    return bad


def _value_set(data, path, value):
    bad = copy.deepcopy(data)
    _at(bad, path[:-1])[path[-1]] = value
    return bad


@pytest.mark.parametrize("name", sorted(p.stem for p in (ROOT / "problems").glob("*.yaml")))
def test_every_key_of_a_bundled_problem_misspelt_gives_one_message(name):
    data = yaml.safe_load((ROOT / "problems" / f"{name}.yaml").read_text())
    mutants = (((path, key), _key_misspelt(data, path, key)) for path, key in _keys(data)
               if len(key) >= 4 and not (path and path[0] == "description"))
    assert _not_one_message(mutants, suggestion=True) == []


def _words(node, path=()):
    """(path, value) of the string values that are words the loader reads as a choice or a
    reference (joint types, laws, conventions, question types, shapes)."""
    import re

    if isinstance(node, dict):
        items = [(k, v) for k, v in node.items() if k not in ("description", "title", "name", "text", "id")]
    elif isinstance(node, list):
        items = list(enumerate(node))
    else:
        return
    for k, v in items:
        if isinstance(v, str) and re.fullmatch(r"[a-z_]{4,}", v):
            yield path + (k,), v
        yield from _words(v, path + (k,))


@pytest.mark.parametrize("name", sorted(p.stem for p in (ROOT / "problems").glob("*.yaml")))
def test_every_word_of_a_bundled_problem_misspelt_gives_one_message(name):
    data = yaml.safe_load((ROOT / "problems" / f"{name}.yaml").read_text())
    mutants = ((path, _value_set(data, path, word[0] + word[2:])) for path, word in _words(data))
    assert _not_one_message(mutants, suggestion=True) == []


def _values(node, path=()):
    """(path, value) of every number or string of the file but its prose."""
    if isinstance(node, dict):
        items = [(k, v) for k, v in node.items() if k not in ("description", "title", "text", "robosolve")]
    elif isinstance(node, list):
        items = list(enumerate(node))
    else:
        return
    for k, v in items:
        if isinstance(v, (str, int, float)) and not isinstance(v, bool):
            yield path + (k,), v
        yield from _values(v, path + (k,))


@pytest.mark.slow
@pytest.mark.parametrize("name", sorted(p.stem for p in (ROOT / "problems").glob("*.yaml")))
def test_every_value_of_a_bundled_problem_broken_gives_one_message(name):
    """A broken expression or a list in place of any one value: one message. (Before: a joint
    whose name or type was refused made its name unknown in every frame; a refused coordinate
    made the force, the velocity and the gains of the questions that follow it wrong in length;
    a refused law judged the gains as law p's; a refused `at` made the variants section say the
    question has no value for that joint; a refused id left its references dangling.)"""
    data = yaml.safe_load((ROOT / "problems" / f"{name}.yaml").read_text())
    broken = ("2*", [1, 2, 3, 4, 5, 6, 7])            # each value one way (time)
    mutants = (((path, broken[k % 2]), _value_set(data, path, broken[k % 2]))
               for k, (path, _v) in enumerate(_values(data)))
    flagged = [f for f in _not_one_message(mutants, suggestion=False) if f[1] != "accepted"]
    assert flagged == []


def test_a_parameter_left_out_is_one_message_with_the_lines_of_its_other_uses():
    data = yaml.safe_load((ROOT / "problems" / "scara-rrp.yaml").read_text())
    frames = yaml.safe_dump(data["frames"])
    name = next(n for n in data["parameters"] if re.search(rf"\b{n}\b", frames))     # one the frames use
    del data["parameters"][name]
    text = yaml.safe_dump(data, sort_keys=False, allow_unicode=True)
    uses = [i + 1 for i, line in enumerate(text.splitlines())
            if re.search(rf"(?<![A-Za-z0-9_]){name}(?![A-Za-z0-9_])", line) and not line.lstrip().startswith(("#", "description"))]
    with pytest.raises(InputError) as exc:
        load_problem_text(text, "p.yaml")
    issues = [str(i) for i in exc.value.issues]
    assert len(issues) == 1 and f"unknown name '{name}'" in issues[0], issues
    if len(uses) > 1:
        assert "more use" in issues[0] and all(str(n) in issues[0] for n in uses[1:]), (uses, issues)


def test_a_joint_without_a_name_is_one_message():
    data = yaml.safe_load((ROOT / "problems" / "exam-2r-full.yaml").read_text())
    del data["joints"][0]["name"]
    issues = _issues(data)
    assert len(issues) == 1 and "joints[0]: missing required key 'name'" in issues[0], issues


def test_the_same_words_for_several_questions_are_one_message_with_their_places():
    data = yaml.safe_load((ROOT / "problems" / "exam-2r-full.yaml").read_text())
    del data["parameters"]["g"]          # four questions use gravity
    issues = _issues(data)
    assert len(issues) == 1 and "declare g" in issues[0], issues
    others = issues[0].split("(the same for ")[1]
    assert others.count("questions[") >= 2 and "lines " in others      # where else, and their lines


def test_task_gains_without_a_law_say_the_law_is_missing():
    data = yaml.safe_load((ROOT / "problems" / "workspace-2r-line.yaml").read_text())
    del data["questions"][1]["law"]       # gains per coordinate: a task law was meant
    issues = _issues(data)
    assert len(issues) == 1 and "need a task law" in issues[0] and "task_pd_gravity" in issues[0], issues


@pytest.mark.parametrize("name", ["kuka-kr", "panda"])
def test_a_dh_table_without_rows_is_one_message(name):
    data = yaml.safe_load((ROOT / "problems" / f"{name}.yaml").read_text())
    del data["dh"]["rows"]           # (before: 'expected rows' twice, every body's frame unknown)
    issues = _issues(data)
    assert len(issues) == 1 and "missing required key 'rows'" in issues[0], issues


@pytest.mark.parametrize("name, path, value, said", [
    # a joint refused whole: its name was unknown in every frame, `at` and target that use it
    ("exam-2r-full", ("joints", 0), "theta1", "joints[0]: expected a mapping, got a string"),
    ("exam-2r-full", ("joints", 1), ["theta2", "revolute"], "joints[1]: expected a mapping, got a list"),
    # a joint name taken already (time, a parameter): the same
    ("kuka-kr", ("joints", 4, "name"), "t", "joints[4].name: name 't' is already used"),
    ("exam-2r-full", ("joints", 1, "name"), "L1", "joints[1].name: name 'L1' is already used"),
    # a refused `weight` of statics: not "expected force, torque or weight: true" besides
    ("exam-2r-full", ("questions", 4, "weight"), "yes", "questions[4].weight: expected true or false"),
    ("planar-2r-rods", ("questions", 2, "weight"), 1, "questions[2].weight: expected true or false"),
])
def test_a_value_of_the_wrong_kind_gives_one_message(name, path, value, said):
    data = yaml.safe_load((ROOT / "problems" / f"{name}.yaml").read_text())
    issues = _issues(_value_set(data, path, value))
    assert len(issues) == 1 and said in issues[0], issues


def _renamed_definition(name, path, key, wrong):
    data = yaml.safe_load((ROOT / "problems" / f"{name}.yaml").read_text())
    node = _at(data, path)
    if isinstance(node, dict) and key in node and path[-1:] != ("name",):
        _renamed(node, key, wrong)            # a key that defines a name (a parameter, a frame)
    else:
        _at(data, path[:-1])[path[-1]] = wrong  # a joint's name
    text = yaml.safe_dump(data, sort_keys=False, allow_unicode=True)
    with pytest.raises(InputError) as exc:
        load_problem_text(text, "p.yaml")
    return text, [str(i) for i in exc.value.issues]


@pytest.mark.parametrize("name, path, key, wrong", [
    # a joint's name misspelt where it is defined: its uses in the DH table, in `at` (the joint,
    # its rates) were one message each
    ("panda", ("joints", 1, "name"), "q2", "qq2"),
    ("exam-2r-full", ("joints", 0, "name"), "theta1", "theta_1"),
    # a parameter misspelt where it is declared: the frames, the bodies and the variants section
    ("exam-2r-full", ("parameters",), "L1", "L1x"),
    ("exam-2r-full", ("parameters",), "F", "FF"),
    # a frame's name: the bodies and the forces on it
    ("exam-2r-full", ("frames",), "2", "2x"),
])
def test_a_name_misspelt_where_it_is_defined_is_one_message_with_its_uses(name, path, key, wrong):
    text, issues = _renamed_definition(name, path, key, wrong)
    assert len(issues) == 1, issues
    assert f"'{key}'" in issues[0] and f"did you mean '{wrong}'?" in issues[0], issues
    assert "more use" in issues[0], issues       # each of these names has several uses


@pytest.mark.parametrize("name, index, renamed", [
    ("ik-anthropomorphic-3r", 1, "elbow"),      # its `select` mapping gave "missing joint(s) elbow" too
    ("rigid-displacements", 0, "base"),         # its displacement's `from` and `to`, the same
])
def test_a_joint_renamed_where_it_is_defined_is_one_message(name, index, renamed):
    data = yaml.safe_load((ROOT / "problems" / f"{name}.yaml").read_text())
    old = data["joints"][index]["name"]
    data["joints"][index]["name"] = renamed
    issues = _issues(data)
    assert len(issues) == 1 and f"'{old}'" in issues[0] and "more use" in issues[0], issues


def test_g_misspelt_where_it_is_declared_is_named_by_the_gravity_message():
    """A question that uses gravity said 'declare g in parameters' of a file that declares 'gg':
    the one message now names the parameter it most likely is."""
    data = yaml.safe_load((ROOT / "problems" / "exam-2r-full.yaml").read_text())
    _renamed(data["parameters"], "g", "gg")
    issues = _issues(data)
    assert len(issues) == 1 and "declare g in parameters (did you mean 'gg'?)" in issues[0], issues


@pytest.mark.parametrize("question, said", [
    ("{type: motion_profile}", "questions[0]: missing required keys 'from', 'to' and 'max_acceleration'"),
    ("{type: displacement}", "questions[0]: missing required keys 'from' and 'to' (or give a screw: axis and angle)"),
    ("{type: motion_profile, from: {theta1: 0, theta2: 0}}", "questions[0]: missing required keys 'to' and "
                                                             "'max_acceleration'"),
])
def test_a_question_written_bare_is_one_message_naming_every_key_it_lacks(question, said):
    """One message per key missing made a bare question (the options forgotten: one mistake) three."""
    data = yaml.safe_load((ROOT / "problems" / "exam-2r-full.yaml").read_text())
    data["questions"] = [yaml.safe_load(question)]
    del data["variants"]
    issues = _issues(data)
    assert len(issues) == 1 and said in issues[0], issues


@pytest.mark.parametrize("name, path, value, said", [
    # a section refused whole: every name or frame it defines was unknown wherever used
    ("exam-2r-full", ("parameters",), "L1 = 1/2", "parameters: expected a mapping name: value, got a string"),
    ("exam-2r-full", ("parameters",), [1, 2], "parameters: expected a mapping name: value, got a list"),
    ("planar-2r-rods", ("parameters",), [1, 2], "parameters: expected a mapping name: value, got a list"),
    ("scara-rrp", ("frames",), "Tz(h) Rz(theta1)", "frames: expected a mapping frame name: definition"),
    ("kuka-kr", ("dh",), ["standard"], "dh: expected a mapping, got a list"),
    ("kuka-kr", ("dh", "rows", 2), "q3 0 a3 0", "dh.rows[2]: expected a mapping, got a string"),
])
def test_a_section_refused_whole_is_one_message(name, path, value, said):
    data = yaml.safe_load((ROOT / "problems" / f"{name}.yaml").read_text())
    issues = _issues(_value_set(data, path, value))
    assert len(issues) == 1 and said in issues[0], issues
