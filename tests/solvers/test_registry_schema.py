"""Every answer of every bundled problem conforms to the registry's answer schema.

The registry (robosolve.questions.registry) is the one description of each question
type; this test reads the golden results.json files (written by the solvers) and checks
each key against the schema, independently of the code that wrote them.
"""

import json
from pathlib import Path

import pytest

from robosolve.load.loader import load_problem
from robosolve.questions import registry as reg

ROOT = Path(__file__).resolve().parents[2]
GOLDEN = sorted((ROOT / "tests" / "golden").glob("*/results.json"))


def _is_scalar(v, part):
    if v is None:          # null: a degenerate value (an infinite semi-axis, no axis point)
        return True
    return isinstance(v, str) if part == "symbolic" else isinstance(v, (int, float)) and not isinstance(v, bool)


def _check_vector(v, part, length=None):
    assert isinstance(v, list), v
    if isinstance(length, int):
        assert len(v) == length
    assert all(_is_scalar(x, part) for x in v), v


def _check_matrix(v, part, rows=None, cols=None):
    assert isinstance(v, list) and v and all(isinstance(r, list) for r in v), v
    if isinstance(rows, int):
        assert len(v) == rows
    widths = {len(r) for r in v}
    assert len(widths) == 1
    if isinstance(cols, int):
        assert widths == {cols}
    for r in v:
        assert all(_is_scalar(x, part) for x in r)


def conform(key: reg.AnswerKey, v, part, ctx):
    k = key.kind
    if v is None:          # the spec's null values (P of a pure translation, pitch)
        return
    n = len(ctx["joints"])
    shape = tuple(n if s == reg.N else s for s in key.shape)
    if k == reg.SCALAR:
        assert _is_scalar(v, part), (key.name, v)
    elif k == reg.VECTOR:
        _check_vector(v, part, shape[0] if shape else None)
    elif k == reg.MATRIX:
        _check_matrix(v, part, *(shape + (None, None))[:2])
    elif k == reg.MATRIX_LIST:
        assert isinstance(v, list)
        for m in v:
            _check_matrix(m, part)
    elif k == reg.JOINT_MAP:
        assert isinstance(v, dict) and list(v) == [j for j in ctx["joints"] if j in v], (key.name, v)
        assert all(_is_scalar(x, part) for x in v.values())
    elif k == reg.COORDINATE_MAP or (k == reg.CONTROL_MAP and not set(v) & set(ctx["joints"])):
        assert isinstance(v, dict) and v and all(isinstance(c, str) for c in v), (key.name, v)
        assert all(_is_scalar(x, part) for x in v.values())
    elif k == reg.CONTROL_MAP:
        assert isinstance(v, dict) and list(v) == [j for j in ctx["joints"] if j in v], (key.name, v)
        assert all(_is_scalar(x, part) for x in v.values())
    elif k == reg.ACTUATOR_MAP:
        assert isinstance(v, dict) and list(v) == [a for a in ctx["actuators"] if a in v], (key.name, v)
        assert all(_is_scalar(x, part) for x in v.values())
    elif k == reg.BODY_MAP:
        assert isinstance(v, dict) and list(v)[-1] == "total"
        assert set(v) - {"total"} <= set(ctx["bodies"])
        assert all(_is_scalar(x, part) for x in v.values())
    elif k == reg.MATRIX_MAP:
        assert isinstance(v, dict) and set(v) <= set(ctx["bodies"])
        for m in v.values():
            _check_matrix(m, part, 3, n)
    elif k in (reg.JOINT_MAP_SET, reg.JOINT_MAP_LIST):
        assert isinstance(v, list)
        for item in v:
            if isinstance(item, str) and key.name == "singularities":
                assert "=" in item      # spec: an equation string where no joint can be isolated
                continue
            assert isinstance(item, dict) and set(item) <= set(ctx["joints"])
            assert list(item) == [j for j in ctx["joints"] if j in item]
            assert all(_is_scalar(x, part) for x in item.values())
    elif k in (reg.VECTOR_SET, reg.AXES):
        assert isinstance(v, list)
        for item in v:
            if item is not None:
                _check_vector(item, part, shape[-1] if shape and isinstance(shape[-1], int) else None)
    elif k == reg.EQUATIONS:
        assert isinstance(v, list) and all(isinstance(e, str) and " = " in e for e in v)
    elif k == reg.RECORD:
        assert isinstance(v, dict)
        for name, x in v.items():
            f = key.field(name)
            assert f is not None, f"{key.name}.{name} is not in the schema"
            conform(f, x, part, ctx)
    elif k == reg.ACTUATOR_RECORDS:
        assert isinstance(v, dict) and list(v) == [a for a in ctx["actuators"] if a in v]
        for rec in v.values():
            for name, x in rec.items():
                f = key.field(name)
                assert f is not None, f"{key.name}.*.{name} is not in the schema"
                conform(f, x, part, ctx)
    elif k == reg.BOOL:
        assert isinstance(v, bool)
    elif k == reg.TEXT:
        assert isinstance(v, str)
    else:
        raise AssertionError(f"unknown kind {k}")


@pytest.mark.parametrize("path", GOLDEN, ids=lambda p: p.parent.name)
def test_every_golden_answer_conforms_to_the_registry(path):
    data = json.loads(path.read_text())
    problem = load_problem(ROOT / "problems" / f"{data['problem']}.yaml")
    ctx = {"joints": [j.name for j in problem.joints],
           "actuators": [str(j.actuator) for j in problem.joints],
           "bodies": [b.name for b in problem.bodies]}
    for qid, answer in data["answers"].items():
        qt = reg.QUESTION_TYPES[answer["type"]]
        for part in ("symbolic", "numeric"):
            for name, v in answer.get(part, {}).items():
                key = qt.key(name)
                assert key is not None, f"{qid}: {part}.{name} is not in the {qt.name} schema"
                assert getattr(key, part), f"{qid}: {name} is not expected in {part}"
                conform(key, v, part, ctx)
        for name in set(answer) - {"type", "symbolic", "numeric", "figures", "notes", "error"}:
            key = qt.key(name)
            assert key is not None and key.top, f"{qid}: top-level {name} is not in the schema"
            conform(key, answer[name], "numeric", ctx)


def test_every_type_has_a_solver_module_and_a_doc_page():
    import importlib.util
    for qt in reg.QUESTION_TYPES.values():
        assert importlib.util.find_spec(qt.solver_module) is not None, qt.name
        assert all(k.kind in reg.KINDS for k in qt.answers)
        assert qt.principal_keys, qt.name


def test_principal_keys_follow_grading_md():
    # the table of grading.md, written out independently of the registry
    expected = {
        "position": ("M", "position"),
        "velocity_acceleration": ("velocity", "acceleration", "angular_velocity"),
        "jacobian": ("J", "det", "manipulability", "singularities"),
        "statics": ("Fq",),
        "ellipsoids": ("force.lengths", "velocity.lengths", "condition_number"),
        "inverse_kinematics": ("solutions", "q_dot"),
        "motion_profile": ("durations", "T", "accelerations"),
        "equations_of_motion": ("mass_matrix", "velocity_terms", "gravity_terms", "generalized_forces"),
        "joint_torques": ("actuators",),
        "p_control": ("max_error", "final_error"),
        "forward_dynamics": ("final", "max", "min"),
        "displacement": ("u", "alpha", "h", "P"),          # given from/to (the default form)
        "orientation": ("zyz", "rpy", "axis_angle", "quaternion"),
        "dof": ("dof",),
    }
    for name, keys in expected.items():
        assert reg.QUESTION_TYPES[name].principal_keys == keys, name
    # principal keys that depend on the question's form (grading.md: Q, L given a screw)
    disp = reg.QUESTION_TYPES["displacement"]
    assert disp.principal_keys_for({"axis": [0, 0, 1], "angle": 1}) == ("Q", "L")
    assert disp.principal_keys_for({"from": [], "to": []}) == ("u", "alpha", "h", "P")
    assert reg.QUESTION_TYPES["dof"].principal_keys_for({"bodies": 3}) == ("dof",)
