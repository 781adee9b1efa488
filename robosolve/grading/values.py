"""Answer values -> one tree layout per answer kind, for the given and the expected alike.

A tree is built of lists, dicts (names in order) and leaves: a sympy expression (or a
float), `None` (null), a bool or a str (BOOL/TEXT kinds), or an `Equation` (the residual
lhs − rhs of an `"lhs = rhs"` string). The kind of each key comes from the registry's
answer schema, never from the question type's name.
"""

from __future__ import annotations

from dataclasses import dataclass

import sympy as sp

from robosolve.load.expressions import ExpressionError, did_you_mean, shown, typed_math
from robosolve.load.loader import type_name
from robosolve.questions import registry as R


class ValueProblem(Exception):
    """A given value that cannot be read (the key's verdict is `invalid`)."""

    def __init__(self, message: str, wrong_shape: bool = False):
        super().__init__(message)
        self.wrong_shape = wrong_shape


@dataclass(frozen=True)
class Equation:
    """An equation `lhs = rhs`, kept as its residual lhs − rhs."""

    residual: object
    text: str = ""


@dataclass(frozen=True)
class Pieces:
    """A piecewise leaf cut on the intervals of [0, T] where it and the leaf it is compared with
    are each one expression (grading/pieces.py): the part on each interval, t rescaled in it."""

    parts: tuple
    intervals: tuple = ()          # (start, end) of each part's interval, s


MAP_KINDS = (R.JOINT_MAP, R.ACTUATOR_MAP, R.BODY_MAP, R.COORDINATE_MAP, R.CONTROL_MAP)
ARRAY_KINDS = (R.VECTOR, R.MATRIX, R.VECTOR_SET, R.AXES)
#: mappings a student may write as a vector, one value per entry in a known order: joints,
#: actuators, and a control question's errors (per joint, or per task coordinate)
ORDERED_MAP_KINDS = (R.JOINT_MAP, R.ACTUATOR_MAP, R.CONTROL_MAP, R.COORDINATE_MAP)
SET_KINDS = (R.JOINT_MAP_SET, R.VECTOR_SET)


#: One expression of an answers file (whose size is bounded by answers.ANSWERS_MAX_FILE_BYTES):
#: the reference's longest expressions (a 7-joint arm's velocity terms, 320,000 characters an
#: entry) can be given back.
ANSWER_MAX_CHARS = 1_000_000
ANSWER_MAX_NODES = 2_000_000


def answers_namespace(problem):
    """The names an answer to `problem` may use: the problem's, and the target entries r11…r33,
    px, py, pz a closed form of the inverse kinematics of a pose is written in (the spec's pose row)."""
    from robosolve.load.expressions import Namespace
    from robosolve.load.pose_target import PoseTarget

    names = dict(problem.names)
    if any(isinstance(q.options.get("target"), PoseTarget) for q in problem.questions):
        entries = [f"r{i}{j}" for i in (1, 2, 3) for j in (1, 2, 3)] + ["px", "py", "pz"]
        names.update({n: sp.Symbol(n) for n in entries if n not in names})
    return Namespace(names, problem.points.keys(), what="name", max_chars=ANSWER_MAX_CHARS,
                     max_nodes=ANSWER_MAX_NODES, piecewise=True)


def entry_names(problem, question_id: str, key: str):
    """The names of the entries of a mapping answer in the order the question's paper lists
    them (its type's `paper_layout`: a control question's errors per joint or per task
    coordinate), or None when the question does not decide them."""
    from robosolve.questions.registry import question_type

    question = next((q for q in problem.questions if q.id == question_id), None)
    layout = question_type(question.type).paper_layout if question is not None else None
    if layout is None:
        return None
    entries = layout(question, problem).get(key, (None, None))[0]
    return None if entries is None else [str(e) for e in entries]


def _label(where: str) -> str:
    return f"{where}: " if where else ""


class Reader:
    """Builds trees from YAML data (given) or from an Answer's values (expected)."""

    def __init__(self, namespace, expected: bool = False, joints=(), actuators=()):
        self.ns = namespace
        self.expected = expected
        self.joints = list(joints)          # (name, symbol) in joint order, for given values
        self.actuators = list(actuators)    # their actuators' names, in joint order

    # -- per-joint values written as people write them -----------------------
    def _in_joint_order(self, value, names=None):
        """Joint values written as a vector (`Fq: [8.66, 0]`, an IK solution `[-0.17, 1.47]`):
        the mapping joint -> value they are in joint order, when there is one per joint
        (`names`: the actuators', for actuator values)."""
        names = [name for name, _ in self.joints] if names is None else names
        if (len(names or ()) == 1 and isinstance(value, (int, float, str)) and not isinstance(value, bool)
                and not (isinstance(value, str) and "=" in value)):
            return {names[0]: value}        # one joint (a pendulum): its value written alone
        if (names and isinstance(value, (list, tuple)) and len(value) == len(names)
                and not any(isinstance(v, (list, tuple, dict)) for v in value)):
            return dict(zip(names, value))
        return value

    def _asked_vector_names(self, value, entries):
        """The joints a vector of joint values is in the order of: the question's asked joints when
        they are fewer than the robot's and the vector has one value each (an IK whose target
        theta3 does not move: `[a, b]` is {theta1: a, theta2: b}); else every joint (None)."""
        joints = [name for name, _ in self.joints]
        if (entries and set(entries) < set(joints) and isinstance(value, (list, tuple))
                and len(value) == len(entries)):
            return list(entries)
        return None

    def _as_joint_values(self, element):
        """A condition written as equations that each give one joint a value (`"theta2 = pi"`,
        `"theta3 = 0, theta5 = 0"`) is the mapping joint -> value it states, as the reference
        writes such a condition; any other equation stays one (`"L1*cos(theta2) + L2 = 0"`)."""
        if not (isinstance(element, tuple) and element and all(isinstance(x, Equation) for x in element)):
            return element
        names = dict((sym, name) for name, sym in self.joints)
        values = {}
        for eq in element:
            r = sp.sympify(eq.residual)
            used = [q for q in names if r.has(q)]
            if len(used) != 1:
                return element
            q = used[0]
            slope = sp.diff(r, q)
            if slope not in (1, -1) or names[q] in values:
                return element
            values[names[q]] = sp.expand(q - r / slope)
        return {name: values[name] for name, _ in self.joints if name in values}

    def _joints_only(self, element, where):
        """A set element written as a mapping is keyed by joint names (an IK solution, a
        singular condition): any other name is no value the key can have."""
        names = [name for name, _ in self.joints]
        if not isinstance(element, dict) or not names:
            return
        for k in element:
            if k not in names:
                raise ValueProblem(f"{_label(where)}'{k}' is not a joint (the joints: {', '.join(names)})"
                                   + did_you_mean(k, names))

    def _asked_joints_only(self, mapping, entries):
        """A given mapping of joint values without the joints the question does not ask for:
        `entries` names the joints it does (an inverse kinematics whose target some joint does
        not move: that joint is in no solution, grading.md), and a value given for one of the
        robot's other joints is ignored alike in every key. Any other name stays."""
        if not isinstance(mapping, dict) or not entries:
            return mapping
        left_out = {name for name, _ in self.joints} - set(entries)
        return {k: v for k, v in mapping.items() if k not in left_out}

    # -- leaves -----------------------------------------------------------
    def scalar(self, value, where=""):
        if value is None:
            return None
        if self.expected and isinstance(value, (float, int, sp.Basic)) and not isinstance(value, bool):
            return value
        if isinstance(value, bool) or not isinstance(value, (int, float, str)):
            raise ValueProblem(f"{_label(where)}expected a number or an expression, got {type_name(value)}")
        if isinstance(value, str) and not self.expected:
            value = typed_math(value)
        try:
            return self.ns.parse(value)
        except ExpressionError as exc:
            raise ValueProblem(f"{_label(where)}{exc}") from None

    def equation(self, value, where=""):
        if not isinstance(value, str) or value.count("=") != 1:
            raise ValueProblem(f"{_label(where)}expected an equation \"lhs = rhs\", got "
                               + (repr(shown(value)) if isinstance(value, str) else type_name(value)))
        lhs, rhs = value.split("=")
        return Equation(self.scalar(lhs, where) - self.scalar(rhs, where), value)

    # -- containers -------------------------------------------------------
    def vector(self, value, where=""):
        if isinstance(value, sp.MatrixBase):
            value = list(value)
        if not isinstance(value, (list, tuple)):
            raise ValueProblem(f"{_label(where)}expected a list (a vector), got {type_name(value)}",
                               wrong_shape=True)
        return [self.scalar(v, _join(where, f"entry {i + 1}")) for i, v in enumerate(value)]

    def matrix(self, value, where=""):
        if isinstance(value, sp.MatrixBase):
            value = value.tolist()
        if (not isinstance(value, (list, tuple)) or not value
                or not all(isinstance(r, (list, tuple)) for r in value)
                or any(len(r) != len(value[0]) for r in value)):
            raise ValueProblem(f"{_label(where)}expected a matrix as a list of rows of equal length",
                               wrong_shape=True)
        return [[self.scalar(v, _join(where, f"entry ({i + 1}, {j + 1})")) for j, v in enumerate(r)]
                for i, r in enumerate(value)]

    def mapping(self, value, leaf, where=""):
        if not isinstance(value, dict):
            raise ValueProblem(f"{_label(where)}expected a mapping name -> value, got {type_name(value)}",
                               wrong_shape=True)
        return {str(k): leaf(v, _join(where, str(k))) for k, v in value.items()}

    def joint_map_or_equations(self, value, where="", equations=True):
        """A set element: a mapping joint -> value, or an equation string (singularities);
        `equations`: whether the key's elements may be equations (for what the message asks)."""
        if isinstance(value, str) and (self.expected or "=" in value):
            return tuple(self.equation(part, where) for part in _split_equations(value))
        if not isinstance(value, dict):
            written = repr(shown(value)) if isinstance(value, str) else type_name(value)
            raise ValueProblem(f"{_label(where)}expected a mapping joint -> value ({self._example()})"
                               + (' or an equation "lhs = rhs"' if equations else "") + f", got {written}",
                               wrong_shape=not isinstance(value, str))
        return self.mapping(value, self.scalar, where)

    def _example(self) -> str:
        """A mapping of every joint, as the message of an unreadable set element shows it."""
        return "{" + ", ".join(f"{name}: …" for name, _ in self.joints) + "}"

    def _joint_set(self, ak, value, where):
        """A set of joint values as people write it, as the list of its elements: one mapping
        alone is the set of it; a text saying there is none (`none`, `no solution`, `∅`, `{}`)
        the empty set; a matrix typed as one string a row per element; "theta2 = 0 or theta2 =
        pi" its conditions. Anything else is no set (the message says what one looks like)."""
        if _says_none(value) or value == {} or (isinstance(value, list) and len(value) == 1
                                                and _says_none(value[0])):
            return []
        if isinstance(value, dict):
            return [value]        # one solution (one condition) written alone: the set of it
        if isinstance(value, str) and value.strip().startswith("["):
            return self._typed_rows(value, where)
        if isinstance(value, str) and "=" in value:
            return [value]
        if isinstance(value, (list, tuple)):
            return value
        written = repr(shown(value)) if isinstance(value, str) else type_name(value)
        raise ValueProblem(f"{_label(where)}expected a set of joint values: a list of mappings joint -> value, "
                           f"[{self._example()}, …]"
                           + (', or of equations "lhs = rhs"' if ak.by_value else "")
                           + f", or [] for none; got {written}", wrong_shape=not isinstance(value, str))

    # -- by kind ----------------------------------------------------------
    def read(self, ak, value, where="", entries=None):
        """The tree of `value` for answer key `ak`; `entries`: the names of a mapping's entries
        in the order the question lists them (`entry_names`), for one written as a vector."""
        kind = ak.kind
        if isinstance(value, str) and value.strip().startswith("[") and kind in ARRAY_KINDS:
            value = self.array_text(kind, value, where)
        elif kind in (R.VECTOR, R.MATRIX) and self._typed_unquoted(value):
            value = self.array_text(kind, "[" + ", ".join(str(v) for v in value) + "]", where)
        if kind == R.SCALAR:
            return self.scalar(value, where)
        if kind in (R.VECTOR, R.MATRIX) and all_null(value):
            return None           # null where the reference has null (an axis at an angle of 0)
        if kind == R.VECTOR:
            return self.vector(value, where)
        if kind == R.MATRIX:
            return self.matrix(value, where)
        if kind == R.MATRIX_LIST:
            return [self._typed(R.MATRIX, m, _join(where, f"matrix {i + 1}"))
                    for i, m in enumerate(self._list(value, where))]
        if kind in ORDERED_MAP_KINDS and not self.expected:
            names = {R.JOINT_MAP: None, R.ACTUATOR_MAP: self.actuators}.get(kind, entries)
            if kind == R.JOINT_MAP or names is not None:
                if isinstance(value, str) and value.strip().startswith("["):
                    value = self._typed_vector(value, where)
                if kind == R.JOINT_MAP:
                    names = self._asked_vector_names(value, entries)
                value = self._in_joint_order(value, names)
        if kind == R.JOINT_MAP and not self.expected:
            return self._asked_joints_only(self.mapping(value, self.scalar, where), entries)
        if kind in MAP_KINDS:
            return self.mapping(value, self.scalar, where)
        if kind == R.MATRIX_MAP:
            return self.mapping(value, lambda v, w: self._typed(R.MATRIX, v, w), where)
        if kind == R.JOINT_MAP_SET and not self.expected:
            value = self._joint_set(ak, value, where)
        if kind in (R.JOINT_MAP_SET, R.JOINT_MAP_LIST):
            items = self._list(value, where)
            if not self.expected:
                if kind == R.JOINT_MAP_SET:      # "theta2 = 0 or theta2 = pi": two conditions
                    items = [part for v in items for part in _alternatives(v)]
                items = [self._in_joint_order(v, self._asked_vector_names(v, entries)) for v in items]
            out = [self.joint_map_or_equations(v, _join(where, f"element {i + 1}"), ak.by_value)
                   for i, v in enumerate(items)]
            if self.expected:
                return out
            for i, x in enumerate(out):
                self._joints_only(x, _join(where, f"element {i + 1}"))
            return [self._asked_joints_only(self._as_joint_values(x), entries) for x in out]
        if kind == R.AXES:      # an infinite semi-axis (a force ellipse at a singularity) is null
            return [None if v is None else self._typed(R.VECTOR, v, _join(where, f"element {i + 1}"))
                    for i, v in enumerate(self._list(value, where))]
        if kind == R.VECTOR_SET:
            return [self._typed(R.VECTOR, v, _join(where, f"element {i + 1}"))
                    for i, v in enumerate(self._list(value, where))]
        if kind == R.EQUATIONS:
            return [self.equation(v, _join(where, f"equation {i + 1}")) for i, v in enumerate(self._list(value, where))]
        if kind == R.RECORD:
            if not isinstance(value, dict):
                raise ValueProblem(f"{_label(where)}expected a mapping of "
                                   + ", ".join(f.name for f in ak.fields), wrong_shape=True)
            out = {}
            for k, v in value.items():
                f = ak.field(str(k))
                if f is None:
                    continue          # the answers loader already refused unknown fields
                out[str(k)] = self.read(f, v, _join(where, str(k)))
            return out
        if kind == R.ACTUATOR_RECORDS:
            def record(v, w):
                return self.mapping(v, self.scalar, w)
            return self.mapping(value, record, where)
        if kind == R.BOOL:
            said = as_bool(value)
            if value is not None and said is None:
                raise ValueProblem(f"{_label(where)}expected true or false, got "
                                   + (repr(shown(value)) if isinstance(value, str) else type_name(value)))
            return said
        if kind == R.TEXT:
            return None if value is None else str(value)
        raise ValueProblem(f"answers of kind {kind} cannot be checked")

    def _typed(self, kind, value, where):
        """One matrix (`kind` MATRIX) or vector (VECTOR) of a list or mapping of them (a chain's
        poses, the centre-of-mass Jacobians, semi-axes, Euler triples), which may be typed as
        one string like a key's whole value."""
        if isinstance(value, str) and value.strip().startswith("[") and not self.expected:
            value = self.array_text(kind, value, where)
        return self.matrix(value, where) if kind == R.MATRIX else self.vector(value, where)

    def array_text(self, kind, value, where=""):
        """A matrix or vector (`kind`) typed as one string (MATLAB or Python notation)."""
        from robosolve.grading.typed import ArrayTextError, parse_array

        try:
            out = parse_array(value)
        except ArrayTextError as exc:
            raise ValueProblem(f"{_label(where)}cannot read {shown(value)!r} as a matrix or vector: {exc}") from None
        if kind == R.VECTOR and out and all(isinstance(r, list) and len(r) == 1 for r in out):
            out = [r[0] for r in out]             # a column [a; b; c]
        if kind == R.MATRIX and out and not isinstance(out[0], list):
            out = [out]                           # one row
        return out

    def _typed_unquoted(self, value) -> bool:
        """A MATLAB matrix or vector typed without quotes: YAML reads `[0 0.43 0.65]` as one
        string entry and `[a, b; c, d]` as ['a', 'b; c', 'd']. Taken as typed text when an entry
        holds a `;` or is no expression but several ones separated by spaces; `[a -b]`, which
        reads as a - b, stays one entry."""
        from robosolve.grading.typed import ArrayTextError, row_entries

        if self.expected or not isinstance(value, list) or not value:
            return False
        if not all(isinstance(v, (str, int, float)) and not isinstance(v, bool) for v in value):
            return False
        texts = [v for v in value if isinstance(v, str)]
        if any(";" in v for v in texts):
            return True
        for v in texts:
            try:
                if len(row_entries(v)) < 2:
                    continue
            except ArrayTextError:
                continue
            try:
                self.ns.parse(v)
            except ExpressionError:
                return True
        return False

    def _typed_vector(self, value, where):
        from robosolve.grading.typed import ArrayTextError, parse_array

        try:
            out = parse_array(value)
        except ArrayTextError as exc:
            raise ValueProblem(f"{_label(where)}cannot read {shown(str(value))!r} as a vector: {exc}") from None
        if out and all(isinstance(r, list) and len(r) == 1 for r in out):
            out = [r[0] for r in out]             # a column [a; b]
        return out

    def _typed_rows(self, value, where):
        """A set of joint values typed as a matrix, one row per element in joint order (a
        vector, or a column of one value per joint, is one element)."""
        from robosolve.grading.typed import ArrayTextError, parse_array

        try:
            out = parse_array(value)
        except ArrayTextError as exc:
            raise ValueProblem(f"{_label(where)}cannot read {value!r} as rows of joint values: {exc}") from None
        n = len(self.joints)
        if out and all(isinstance(r, list) for r in out):
            if n > 1 and len(out) == n and all(len(r) == 1 for r in out):
                return [[r[0] for r in out]]
            return out
        return [[x] for x in out] if n == 1 else ([out] if out else [])

    def _list(self, value, where):
        if not isinstance(value, (list, tuple)):
            raise ValueProblem(f"{_label(where)}expected a list, got {type_name(value)}", wrong_shape=True)
        return value


def _join(where: str, more: str) -> str:
    return f"{where}, {more}" if where else more


def _alternatives(value) -> list:
    """The elements of a set written as one string joined by `or` ("theta2 = 0 or theta2 = pi");
    any other value is one element. (`or` is no name: it cannot be part of an expression.)"""
    import re

    if not isinstance(value, str) or not re.search(r"\bor\b", value):
        return [value]
    return [part.strip() for part in re.split(r"\bor\b", value)]


#: YAML's spellings of true and false, which a student may quote (`unreachable: 'yes'`)
TRUE_WORDS = frozenset({"true", "yes", "y", "on"})
FALSE_WORDS = frozenset({"false", "no", "n", "off"})


def as_bool(value):
    """A true/false answer as written: a YAML boolean, or one of YAML's spellings of one typed
    as text (`'true'`, `'Yes'`, `'off'`, in any case); None for anything else."""
    if isinstance(value, bool):
        return value
    if isinstance(value, str):
        word = value.strip().lower()
        return True if word in TRUE_WORDS else False if word in FALSE_WORDS else None
    return None


#: words that say a set has no element (compared in lower case, spaces and a final stop dropped)
NO_ELEMENT = frozenset({"none", "nothing", "empty", "emptyset", "∅", "{}", "[]", "nosolution", "nosolutions",
                        "norealsolution", "norealsolutions", "nosingularity", "nosingularities", "unreachable"})


def _says_none(value) -> bool:
    """`value` is text saying there is no element: `none`, `None`, `no solution`, `∅`, `"{}"`."""
    return isinstance(value, str) and "".join(value.lower().split()).rstrip(".!") in NO_ELEMENT


def _split_equations(text: str) -> list[str]:
    """'a = 0, theta2 = pi' -> ['a = 0', 'theta2 = pi'] (commas inside brackets kept)."""
    from robosolve.grading.typed import split_top_level

    return [p.strip() for p in split_top_level(text, ",", strict=False) if p.strip()]


def map_leaves(tree, fn, is_leaf=lambda x: isinstance(x, sp.Basic)):
    """The tree (dicts, lists, tuples, equations) with every leaf `x` for which `is_leaf(x)`
    holds replaced by `fn(x)`, depth first in order (an equation's leaf is its residual);
    other leaves are kept as they are."""
    if isinstance(tree, dict):
        return {k: map_leaves(v, fn, is_leaf) for k, v in tree.items()}
    if isinstance(tree, list):
        return [map_leaves(v, fn, is_leaf) for v in tree]
    if isinstance(tree, tuple):
        return tuple(map_leaves(v, fn, is_leaf) for v in tree)
    if isinstance(tree, Equation):
        return Equation(map_leaves(tree.residual, fn, is_leaf), tree.text)
    if isinstance(tree, Pieces):
        return Pieces(tuple(map_leaves(v, fn, is_leaf) for v in tree.parts), tree.intervals)
    return fn(tree) if is_leaf(tree) else tree


def free_symbols(tree) -> set:
    found: set = set()
    map_leaves(tree, lambda e: found.update(e.free_symbols))
    return found


def substitute(tree, subs: dict):
    """The tree with `subs` put in (exact), e.g. the parameters' values."""
    return map_leaves(tree, lambda e: e.xreplace(subs))


def all_null(value) -> bool:
    """null, or a list (of lists) of nothing but nulls: a template's [~, ~, ~] left as it is."""
    if isinstance(value, list):
        return bool(value) and all(all_null(v) for v in value)
    return value is None


def blanks(value, expected=(), where: str = "") -> list[str]:
    """The entries of a given value still holding `~` (null), named as the grader names them:
    a key with one left is `missing` (papers.md), never `invalid`. An entry whose `expected`
    value (the same layout; `()` when unknown) is itself null (an infinite length) is no blank."""
    if value is None or (expected is None and all_null(value)):   # a template's [~, ~, ~] for null
        return [] if expected is None else [where or "the value"]
    out: list[str] = []

    def sub(k):
        try:
            return expected[k]
        except (KeyError, IndexError, TypeError):
            return ()

    if isinstance(value, dict):
        for k, v in value.items():
            out += blanks(v, sub(k), f"{where}.{k}" if where else str(k))
    elif isinstance(value, list):
        matrix = value and all(isinstance(r, list) for r in value) and all(
            not isinstance(x, (list, dict)) for r in value for x in r)
        lead = where + " " if where else ""
        for i, v in enumerate(value):
            if matrix:
                row = sub(i)
                out += [f"{lead}entry ({i + 1}, {j + 1})" for j, x in enumerate(v)
                        if x is None and _entry(row, j) is not None]
            else:
                out += blanks(v, sub(i), f"{lead}entry {i + 1}")
    return out


def _entry(row, j):
    try:
        return row[j]
    except (KeyError, IndexError, TypeError):
        return ()
