"""Problem file (YAML, format 1) -> validated `Problem`, or every issue at once.

Each check appends an `InputIssue` (file, line, path, message) and carries on,
so one run reports every problem of the file (spec §4).
"""

from __future__ import annotations

import math
import re

import sympy as sp

from robosolve.core.parameters import resolve_parameters
from robosolve.core.symbols import TIME
from robosolve.errors import InputError, InputIssue, InputWarning
from robosolve.load import questions as qschema
from robosolve.load.expressions import (
    RESERVED, ExpressionError, Namespace, degrees_hint, did_you_mean, digits_issue, meant_value, missing_keys,
    size_issue, value_issue,
)
from robosolve.load.physical import LUMPED_ROTOR, inertia_issue, pseudo_inertia_issue, triangle_issue
from robosolve.load.problem import (
    PRISMATIC, REVOLUTE, Body, Force, Frame, Joint, Point, Problem,
)
from robosolve.load.yamlsource import Source, YamlProblem, parse_yaml, read_text_file
from robosolve.questions.registry import types_where

NAME_RE = re.compile(r"[a-z0-9_-]+")  # used with fullmatch: "$" would accept a final newline
IDENT_RE = re.compile(r"^[A-Za-z][A-Za-z0-9_]*$")
# `E` is a point's name (problem-format.md, Expressions): the end point, by default the origin of
# the last frame, that every question about "the point" uses. A parameter, joint or actuator
# of that name would leave those questions without their point: refused where it is declared.
DEFAULT_POINT = "E"
DEFAULT_POINT_TAKEN = ("'E' is the name of the end point (by default the origin of the last frame, "
                       "used by every question without `point`; E.x is its x): choose another name, "
                       "such as E_1 or Ey")
PYTHON_KEYWORDS = {
    "False", "None", "True", "and", "as", "assert", "async", "await", "break", "class",
    "continue", "def", "del", "elif", "else", "except", "finally", "for", "from", "global",
    "if", "import", "in", "is", "lambda", "nonlocal", "not", "or", "pass", "raise",
    "return", "try", "while", "with", "yield",
}


def _time_refused() -> str:
    """Where time may appear, from the types following forces in time (`QuestionType.time_use`)
    and those with laws in t (`time_laws`)."""
    uses = [phrase for _, phrase in sorted(t.time_use for t in types_where("time_use"))]
    laws = " and ".join(f"in the `{t.time_laws}` laws of a {t.name} question" for t in types_where("time_laws"))
    return ("`t` (time) has no meaning here: time may appear only in `forces` (followed along "
            + ", ".join(uses[:-1]) + " or " + uses[-1] + ") and " + laws)


TIME_REFUSED = _time_refused()
TOP_KEYS = ("robosolve", "name", "title", "description", "parameters", "joints", "frames",
            "dh", "points", "gravity", "bodies", "forces", "questions", "grading", "variants", "paper")
POSE_OPS = ("Tx", "Ty", "Tz", "Rx", "Ry", "Rz")
DH_KEYS = ("theta", "d", "a", "alpha")
MDH_KEYS = ("alpha", "a", "theta", "d")


def path_str(path) -> str:
    out = ""
    for p in path:
        if isinstance(p, int):
            out += f"[{p}]"
        else:
            out += ("." if out else "") + str(p)
    return out


def type_name(value) -> str:
    if value is None:
        return "null"
    if isinstance(value, bool):
        return "a boolean"
    if isinstance(value, (int, float)):
        return "a number"
    if isinstance(value, str):
        return "a string"
    if isinstance(value, list):
        return "a list"
    if isinstance(value, dict):
        return "a mapping"
    return type(value).__name__


def _exact_if_whole(e):
    """A Float with a whole value as the Integer it is (sympy does not take 1.0 for 1)."""
    if isinstance(e, sp.Float) and float(e).is_integer():
        return sp.Integer(int(e))
    return e


def foreign_file(data: dict, own_keys, what: str) -> str | None:
    """Why a mapping with none of a robosolve file's keys is another kind of file — one message
    for the wrong file, not one per key it has and per key it lacks — or None. `what`: the file
    expected, in words."""
    keys = [str(k) for k in data]
    if "format" in keys and ("score" in keys or "max_score" in keys):
        return f"this is a result record (what `robosolve check --json` and `grade` write), not {what}"
    if "format" in keys and set(keys) <= {"format", "problem", "answers"}:
        return f"this is a results.json (the answers `robosolve solve` writes), not {what}"
    if any(k in own_keys for k in data):
        return None
    if not keys:
        return f"the file is an empty mapping: expected {what}"
    if "nbformat" in keys:
        return f"this is a Jupyter notebook, not {what}"
    shown = ", ".join(keys[:5]) + (", …" if len(keys) > 5 else "")
    return f"not {what}: none of its keys ({shown}) is one of them"


def as_meant(path, value: dict, allowed) -> list[tuple]:
    """Each misspelt key of `value` (`cordinates`, `jints`) renamed in place to the key its
    did-you-mean suggests; the paths of the keys renamed. Its message is given already and the
    file is rejected, so the rest is checked as its author meant it: one mistake gives one
    message — not "the timing needs max_velocity" beside it, nor "unknown name theta1" in every
    frame after a misspelt `joints:`. What is wrong inside the renamed key itself is not said
    (the caller drops messages under the paths returned): it is checked once the name is right."""
    meant: dict = {}
    for key in value:
        if key not in allowed:
            close = meant_value(key, allowed)
            if close is not None and close not in value and close not in meant.values():
                meant[key] = close
    if meant:
        items = list(value.items())
        value.clear()
        value.update((meant.get(k, k), v) for k, v in items)
    return [tuple(path) + (key,) for key in meant.values()]


def under(path, prefixes) -> bool:
    """Whether `path` is one of `prefixes` or inside one."""
    path = tuple(path)
    return any(path[:len(p)] == p for p in prefixes)


class Checker:
    """Collects issues against a parsed source; helpers return None on failure."""

    def __init__(self, source: Source):
        self.src = source
        self.issues: list[InputIssue] = []
        self.warnings: list[InputWarning] = []
        # numeric values of the parameters (set once they are read) and of the current
        # question's `at`: every expression read afterwards is checked with them
        self.values: dict | None = None
        self.overrides: dict = {}
        self.renamed: list[tuple] = []     # misspelt keys read as meant (`as_meant`): not judged

    def error(self, path, message: str):
        if self.renamed and under(path, self.renamed):
            return
        self.issues.append(InputIssue(self.src.file, self.src.line(path), path_str(path), message))

    def warn(self, path, message: str, subject: tuple = ()):
        """Accepted, but maybe a mistake: said by the report and the CLI (Problem.warnings)."""
        self.warnings.append(InputWarning(self.src.file, self.src.line(path), path_str(path), message, subject))

    # -- shapes ---------------------------------------------------------
    def mapping(self, path, value, allowed, required=(), what="keys") -> bool:
        if not isinstance(value, dict):
            self.error(path, f"expected a mapping, got {type_name(value)}")
            return False
        for key in value:
            if key not in allowed:
                self.error(path + (key,), f"unknown key '{key}'"
                           + did_you_mean(key, allowed)
                           + f" (expected one of: {', '.join(allowed)})")
        missing = [key for key in required if key not in value and not self.misspelt(value, key, allowed)]
        if missing:     # (a question written bare lacks them all: one message)
            self.error(path, missing_keys(missing))
        self.renamed += as_meant(path, value, allowed)
        return True

    def entries(self, section: str, value, what: str, allowed, required=()):
        """(i, path, item) for each entry of the list `section` that is a mapping of allowed
        keys: none for a missing section, one error for a section that is not a list."""
        if value is None:
            return
        if not isinstance(value, list):
            self.error((section,), f"expected a list of {what}, got {type_name(value)}")
            return
        for i, item in enumerate(value):
            path = (section, i)
            if self.mapping(path, item, allowed, required=required):
                yield i, path, item

    @staticmethod
    def misspelt(value: dict, key: str, allowed) -> bool:
        """True when an unknown key of `value` is a misspelling of `key`: its did-you-mean
        already says what is wrong, so a 'missing key' would be a second message for one mistake."""
        return any(k not in allowed and meant_value(k, allowed) == key for k in value)

    def string(self, path, value, pattern=None, hint="") -> str | None:
        if not isinstance(value, str):
            self.error(path, f"expected a string, got {type_name(value)}")
            return None
        if pattern is not None and not pattern.fullmatch(value):
            self.error(path, f"invalid value {value!r}{hint}")
            return None
        return value

    def boolean(self, path, value) -> bool | None:
        if not isinstance(value, bool):
            self.error(path, f"expected true or false, got {type_name(value)}")
            return None
        return value

    def expr(self, path, value, ns: Namespace):
        if value is None or isinstance(value, (list, dict)):
            self.error(path, f"expected a number or an expression, got {type_name(value)}")
            return None
        try:
            e = ns.parse(value)
        except ExpressionError as exc:
            self.error(path, str(exc))
            return None
        issue = self.value_issue(e, value if isinstance(value, str) else None)
        if issue is not None:
            self.error(path, issue)
            return None
        return e

    def value_issue(self, e, shown: str | None = None) -> str | None:
        """Why `e`, with the parameters' values (and the question's `at`), is not a finite real
        number; None when it is one or still depends on joints, time or null parameters."""
        if self.values is None:
            return None
        return value_issue(e, {**self.values, **self.overrides}, shown)

    def number_value(self, e) -> float | None:
        """The real value of `e` with the known values, or None when it has none (yet)."""
        if self.values is None:
            return None
        v = sp.sympify(e.xreplace({**self.values, **self.overrides}))
        if v.free_symbols:
            return None
        try:
            c = complex(sp.N(v, 15))
        except (TypeError, ValueError):
            return None
        return c.real if abs(c.imag) <= 1e-12 * max(1.0, abs(c.real)) else None

    def vector(self, path, value, ns: Namespace, length=3):
        if not isinstance(value, list) or (length is not None and len(value) != length):
            n = f"{length} " if length else ""
            self.error(path, f"expected a list of {n}numbers or expressions, got "
                       + (f"{len(value)} items" if isinstance(value, list) else type_name(value)))
            return None
        items = [self.expr(path + (i,), v, ns) for i, v in enumerate(value)]
        if any(i is None for i in items):
            return None
        return sp.Matrix(items)

    def matrix(self, path, value, ns: Namespace, shapes=((4, 4),)):
        ok_shape = (isinstance(value, list) and value and all(isinstance(r, list) for r in value)
                    and (len(value), len(value[0])) in shapes
                    and all(len(r) == len(value[0]) for r in value))
        if not ok_shape:
            want = " or ".join(f"{r}x{c}" for r, c in shapes)
            self.error(path, f"expected a {want} matrix (a list of rows)")
            return None
        rows = [[self.expr(path + (i, j), v, ns) for j, v in enumerate(r)] for i, r in enumerate(value)]
        if any(v is None for r in rows for v in r):
            return None
        # 1.0 and 0.0 in a matrix mean 1 and 0: exact, so that the products stay exact
        return sp.Matrix([[_exact_if_whole(v) for v in r] for r in rows])


# ----------------------------------------------------------------------
def _degrees_hint(raw) -> str:
    """A revolute joint's limits beyond one turn: degrees written where radians are read."""
    shown = ", ".join(f"deg({v})" for v in raw)
    return (f"limits {_flow(raw)} of a revolute joint are beyond one turn (±2π ≈ ±6.283 rad): angles "
            f"are radians; if they are degrees, write [{shown}]")


def _angle_units_written(raw) -> bool:
    """Limits written with deg() or pi say their unit: beyond one turn they are meant (an ABB
    IRB 140's axis 6 turns ±400°), not degrees read as radians."""
    return any(isinstance(v, str) and ("deg(" in v or "pi" in v) for v in raw)


def _flow(raw) -> str:
    return "[" + ", ".join(str(v) for v in raw) + "]"


def _not_real(written, fv: complex) -> str:
    """Why a parameter's value is refused, in the words the user wrote."""
    what = f"{written!r}" if isinstance(written, str) else str(written)
    if fv.real != fv.real or abs(fv.real) == float("inf") or fv.imag != fv.imag or abs(fv.imag) == float("inf"):
        return f"{what} is undefined or infinite"
    return (f"{what} is not a real number (it is complex, {fv.real:.6g}{fv.imag:+.6g}i: a square root or "
            "logarithm of a negative number, or acos/asin beyond [-1, 1]?)")


def load_problem(file) -> Problem:
    """Read and validate a problem file. Raises InputError with every issue."""
    return load_problem_text(read_text_file(file), str(file))


def load_problem_text(text: str, file: str = "<input>") -> Problem:
    try:
        source, duplicates = parse_yaml(text, file)
    except YamlProblem as exc:
        raise InputError([InputIssue(file, exc.line, path_str(exc.path), exc.message)])
    chk = Checker(source)
    for line, path, key in duplicates:
        chk.issues.append(InputIssue(file, line, path_str(path), f"duplicate key '{key}'"))
    try:
        problem = _ProblemBuilder(chk).build()
    except (RecursionError, MemoryError):
        chk.issues.append(InputIssue(file, 1, "", "the file is too large or too deeply nested to check"))
    except Exception as exc:  # a validation bug must still end as a clear message, not a traceback
        if not chk.issues:
            chk.issues.append(InputIssue(file, 1, "", f"cannot validate this file ({type(exc).__name__}: {exc})"))
    if chk.issues:
        raise InputError(grouped(chk.issues))
    return problem


_UNKNOWN_NAME = re.compile(r"^(?:unknown (?:name|parameter)\b[^']*'(?P<name>[^']+)' in "
                           r"|unknown (?:joint or parameter|joint or joint rate|joint|actuator) '(?P<key>[^']+)'"
                           r"|undeclared parameter '(?P<varied>[^']+)'"
                           r"|unknown frame '(?P<frame>[^']+)')")


def grouped(issues: list) -> list:
    """One message per unknown name, however many expressions use it (a parameter left out of
    `parameters:` is one mistake): the first use, with the lines of the others; and one message for
    the same words said of several places (three questions that "use gravity: declare g"), with
    the lines of the others. The issues stay in their order."""
    def name(issue):
        """The name a message says is unknown, wherever it is used (an expression, a key of `at`,
        a varied parameter; a joint's rates with the joint): a definition misspelt, or left out, is
        one mistake however many sections use it. Frames are names of their own."""
        m = _UNKNOWN_NAME.match(issue.message)
        if m is None:
            return None
        if m.group("frame") is not None:
            return ("frame", m.group("frame"))
        return ("symbol", re.sub(r"_d?dot$", "", m.group("name") or m.group("key") or m.group("varied")))

    def more_uses(first, others):
        lines = sorted({o.line for o in others})
        return (f" (and {len(others)} more use{'s' if len(others) > 1 else ''}: "
                f"line{'s' if len(lines) > 1 else ''} {', '.join(map(str, lines))})")

    def same_for(first, others):
        lines = sorted({o.line for o in others} - {first.line})
        where = ", ".join(o.path or "the file" for o in others)
        return (f" (the same for {where}"
                + (f": line{'s' if len(lines) > 1 else ''} {', '.join(map(str, lines))})" if lines else ")"))

    return _merged(_merged(issues, name, more_uses), lambda issue: issue.message, same_for)


def _merged(issues: list, key, note) -> list:
    """The issues with one `key` merged into the first of them, `note(first, others)` added to its
    message; those whose key is None kept as they are."""
    groups: dict = {}
    for k, issue in enumerate(issues):
        if key(issue) is not None:
            groups.setdefault(key(issue), []).append(k)
    out = []
    for k, issue in enumerate(issues):
        ks = groups.get(key(issue), [k])
        if k != ks[0]:
            continue
        if len(ks) > 1:
            issue = InputIssue(issue.file, issue.line, issue.path,
                               issue.message + note(issue, [issues[j] for j in ks[1:]]))
        out.append(issue)
    return out


class _ProblemBuilder:
    def __init__(self, chk: Checker):
        self.chk = chk
        self.data = chk.src.data
        self.file = chk.src.file
        self.rejected_frames: set[str] = set()   # defined but invalid: references stay silent
        self.rejected_points: set[str] = set()
        self.joint_name_refused = False          # a joint's name refused: its uses are not judged
        self.parameters_refused = False          # the parameters section refused whole: the same
        self.actuator_refused = False            # an actuator's name refused: the same
        self.frames_refused = False              # a DH table without rows: its frames' uses, the same
        self.refused_question_ids: set = set()
        self.bodies_given = False
        self.gravity_refused = False

    def build(self) -> Problem | None:
        chk, data = self.chk, self.data
        if not isinstance(data, dict):
            chk.error((), f"the top level must be a mapping (with `robosolve: 1`), got {type_name(data)}")
            return None
        if "robosolve-answers" in data and "robosolve" not in data:
            chk.error((), "this is an answers file (`robosolve-answers: 1`), not a problem: check it with "
                      "`robosolve check FILE`, or give the problem file it answers")
            return None
        foreign = foreign_file(data, TOP_KEYS, "a problem file (a mapping with `robosolve: 1`, `name` and "
                               "`questions`)")
        if foreign is not None:
            chk.error((), foreign)
            return None
        chk.mapping((), data, TOP_KEYS, required=("robosolve", "name", "questions"))
        if "robosolve" in data and (data["robosolve"] != 1 or isinstance(data["robosolve"], bool)):
            chk.error(("robosolve",), f"unsupported format version {data['robosolve']!r} (expected 1)")
        name = None
        if "name" in data:
            name = chk.string(("name",), data["name"], NAME_RE, " (expected lowercase letters, digits, '_' or '-')")
        title = chk.string(("title",), data["title"]) if data.get("title") is not None else None
        description = (chk.string(("description",), data["description"])
                       if data.get("description") is not None else None)

        self.parameters = self._parameters(data.get("parameters"))
        chk.values = self._values()
        self.joints = self._joints(data.get("joints"))
        self.names = self._names()
        # time: meaningful only in forces (along a run, a simulation or a profile) and in
        # the laws of a type with `time_laws`; anywhere else a `t` is refused with what to do instead
        static = {k: v for k, v in self.names.items() if k != "t"}
        lenient = self.joint_name_refused or self.parameters_refused
        self.ns = Namespace(static, what="name", refused={"t": TIME_REFUSED}, unknown_ok=lenient)
        self.ns_time = Namespace(self.names, what="name", unknown_ok=lenient)
        self.frames = self._frames(data.get("frames"), data.get("dh"))
        self.points = self._points(data.get("points"))
        # rejected points parse (their error is already reported), so P.x is not "unknown" too
        self.ns_points = Namespace(static, list(self.points) + sorted(self.rejected_points), what="name",
                                   refused={"t": TIME_REFUSED}, unknown_ok=lenient)
        gravity, gravity_given = self._gravity(data.get("gravity"))
        # given but refused (its own message says why): no "declare g" for each question too
        params = data.get("parameters")
        self.gravity_refused = gravity is None and (data.get("gravity") is not None or self.parameters_refused or (
            isinstance(params, dict) and "g" in params))
        bodies = self._bodies(data.get("bodies"))
        forces = self._forces(data.get("forces"))
        has_robot = bool(self.joints) or bool(self.frames)
        self.problem = Problem(
            file=self.file, name=name or "problem", title=title, description=description,
            parameters=self.parameters, joints=self.joints, frames=self.frames,
            points=self.points, gravity=gravity, gravity_given=gravity_given,
            bodies=bodies, forces=forces, questions=[], names=self.names, has_robot=has_robot,
            warnings=chk.warnings,
        )
        self.problem.questions = qschema.load_questions(self, data.get("questions"))
        self.problem.grading = self._grading(data.get("grading"))
        # validated like every key, then ignored by `solve` (load/variants.py, variants.md)
        from robosolve.load.variants import load_variants
        self.problem.variants = load_variants(self, data.get("variants"))
        from robosolve.load.paper import load_paper
        self.problem.paper_at = load_paper(self, data.get("paper"))
        return self.problem

    def _grading(self, value) -> dict:
        """`grading:` (grading.md): tolerances and partial credit (load/grading_options.py)."""
        from robosolve.load.grading_options import read_grading

        return read_grading(self.chk, value)

    # -- parameters -----------------------------------------------------
    def _parameters(self, value) -> dict:
        chk = self.chk
        if value is None:
            return {}
        if not isinstance(value, dict):
            chk.error(("parameters",), f"expected a mapping name: value, got {type_name(value)}")
            self.parameters_refused = True     # the names it declares: their uses say nothing more
            return {}
        names = []
        for key in value:
            if not IDENT_RE.fullmatch(key) or key in PYTHON_KEYWORDS:
                chk.error(("parameters", key), f"invalid parameter name '{key}' (expected a name like L1 or m_2)")
            elif key in RESERVED:
                chk.error(("parameters", key), f"'{key}' is reserved (a function, a constant or time)")
            elif key == DEFAULT_POINT:     # kept as a name, so that its uses say nothing more
                chk.error(("parameters", key), DEFAULT_POINT_TAKEN)
                names.append(key)
            else:
                names.append(key)
        # First pass with plain real symbols, to resolve values and detect cycles.
        plain = {n: sp.Symbol(n, real=True) for n in names}
        ns = Namespace(plain, what="parameter")
        raw = {}
        for n in names:
            v = value[n]
            if v is None:
                raw[n] = None
                continue
            e = chk.expr(("parameters", n), v, ns)
            if e is not None:
                raw[n] = e
        order = self._parameter_order(raw, plain)
        numeric = {}
        for n in order:
            e = raw.get(n)
            if e is None:
                continue
            known = {plain[k]: numeric[k] for k in numeric if k in plain}
            issue = size_issue(e, known)
            if issue is not None:
                chk.error(("parameters", n), issue)
                raw[n] = None     # refused: its uses say nothing more (one mistake, one message)
                continue
            v = e.xreplace(known)
            if v.free_symbols:
                continue          # depends on a null parameter: stays symbolic
            try:
                fv = complex(sp.N(v))
            except (TypeError, ValueError):
                chk.error(("parameters", n), "value is not a finite number")
                raw[n] = None
                continue
            if abs(fv.imag) > 1e-12 or fv.real != fv.real or abs(fv.real) == float("inf"):
                chk.error(("parameters", n), _not_real(value[n], fv))
                raw[n] = None
                continue
            issue = digits_issue(str(value[n]), v, fv.real)
            if issue is not None:
                chk.error(("parameters", n), issue)
                raw[n] = None
                continue
            numeric[n] = v
        # Final symbols: positive when the value is a positive number (helps sqrt/atan2).
        final = {}
        for n in names:
            nv = numeric.get(n)
            positive = nv is not None and float(sp.N(nv)) > 0
            final[n] = sp.Symbol(n, positive=True) if positive else sp.Symbol(n, real=True)
        swap = {plain[n]: final[n] for n in names}
        return {final[n]: (raw[n].xreplace(swap) if raw.get(n) is not None else None) for n in names}

    def _parameter_order(self, raw, plain):
        order, state = [], {}

        def visit(n, stack):
            if state.get(n) == "done":
                return
            if state.get(n) == "active":
                cycle = " -> ".join(stack[stack.index(n):] + [n])
                self.chk.error(("parameters", n), f"parameters depend on each other in a cycle: {cycle}")
                raw[n] = None
                return
            state[n] = "active"
            e = raw.get(n)
            if e is not None:
                for s in sorted(e.free_symbols, key=lambda s: s.name):
                    if s.name in raw:
                        visit(s.name, stack + [n])
            state[n] = "done"
            order.append(n)

        for n in raw:
            visit(n, [])
        return order

    # -- joints ---------------------------------------------------------
    def _joints(self, value) -> list:
        chk = self.chk
        taken = {s.name for s in self.parameters} | RESERVED
        joints, seen = [], set()
        for i, path, item in chk.entries("joints", value, "joints", ("name", "type", "limits", "actuator"),
                                         required=("name", "type")):
            name = chk.string(path + ("name",), item.get("name"), IDENT_RE, " (expected a name like theta1)") \
                if "name" in item else None
            kind = item.get("type")
            if "type" in item and kind not in (REVOLUTE, PRISMATIC):
                chk.error(path + ("type",), f"unknown joint type {kind!r}"
                          + (did_you_mean(kind, (REVOLUTE, PRISMATIC)) if isinstance(kind, str) else "")
                          + " (expected revolute or prismatic)")
                # read as the type it suggests, or as revolute: the file is rejected already, and the
                # joint's uses (frames, `at`, targets) must not all become "unknown name" too
                kind = meant_value(kind, (REVOLUTE, PRISMATIC)) or REVOLUTE
            if name is None:          # refused or missing (said): its uses are not judged
                self.joint_name_refused = True
                continue
            kind = kind or REVOLUTE   # missing (said): revolute in its place, for its uses
            if name == DEFAULT_POINT:     # still a joint below, so that its uses say nothing more
                chk.error(path + ("name",), DEFAULT_POINT_TAKEN)
            elif name in taken or name in seen or name in PYTHON_KEYWORDS:
                chk.error(path + ("name",), f"name '{name}' is already used")
                self.joint_name_refused = True    # the name its uses give is not judged either
                continue
            seen.add(name)
            n = len(joints) + 1
            default_act = f"C{n}" if kind == REVOLUTE else f"F{n}"
            act = item.get("actuator", default_act)
            if "actuator" in item:
                act = chk.string(path + ("actuator",), act, IDENT_RE, " (expected a name like C1)")
            if act is None:      # reported: the joint stays, with its default actuator (no cascade)
                act, self.actuator_refused = default_act, True
            joints.append(Joint(
                index=len(joints), name=name, kind=kind,
                symbol=sp.Symbol(name, real=True), dot=sp.Symbol(f"{name}_dot", real=True),
                ddot=sp.Symbol(f"{name}_ddot", real=True), actuator=sp.Symbol(act, real=True),
                limits=None, line=chk.src.line(path),
            ))
            joints[-1]._raw_limits = item.get("limits")
        if isinstance(value, list) and not all(isinstance(item, dict) for item in value):
            self.joint_name_refused = True    # a joint refused whole (said): its name's uses are not judged
        # derived names must not collide with anything
        all_names = {s.name for s in self.parameters} | RESERVED | {DEFAULT_POINT}
        for j in joints:
            for derived, where in ((f"{j.name}_dot", "name"), (f"{j.name}_ddot", "name"),
                                   (j.actuator.name, "actuator")):
                if derived == DEFAULT_POINT:
                    chk.error(("joints", j.index, where), DEFAULT_POINT_TAKEN)
                elif derived in all_names:
                    chk.error(("joints", j.index, where),
                              f"'{derived}' (of joint {j.name}) is already used")
                all_names.add(derived)
        pns = Namespace({s.name: s for s in self.parameters}, what="parameter", unknown_ok=self.parameters_refused)
        for j in joints:
            raw = j._raw_limits
            if raw is None:
                continue
            path = ("joints", j.index, "limits")
            if not isinstance(raw, list) or len(raw) != 2:
                chk.error(path, "expected [lower, upper]")
                continue
            lo, hi = chk.expr(path + (0,), raw[0], pns), chk.expr(path + (1,), raw[1], pns)
            if lo is None or hi is None:
                continue
            try:
                vals = self._values()
                flo, fhi = float(sp.N(lo.xreplace(vals))), float(sp.N(hi.xreplace(vals)))
                if not flo < fhi:
                    chk.error(path, f"lower limit {raw[0]} is not below upper limit {raw[1]}")    # as written
                    continue
                if (j.kind == REVOLUTE and max(abs(flo), abs(fhi)) > 2 * math.pi + 0.01  # rounded ±6.2832 is a turn
                        and not _angle_units_written(raw)):
                    chk.error(path, _degrees_hint(raw))
                    continue
            except (TypeError, ValueError):
                pass
            j.limits = (lo, hi)
        return joints

    def _values(self, overrides: dict | None = None) -> dict:
        """Numeric values of the parameters that have one (for sanity checks), with `overrides`
        (a question's `at` values of parameters) replacing theirs."""
        return resolve_parameters(self.parameters, overrides)

    def _names(self) -> dict:
        names = {s.name: s for s in self.parameters}
        for j in self.joints:
            names[j.name] = j.symbol
            names[j.dot.name] = j.dot
            names[j.ddot.name] = j.ddot
            names[j.actuator.name] = j.actuator
        names["t"] = TIME
        return names

    # -- frames ---------------------------------------------------------
    def _frames(self, frames_value, dh_value) -> dict:
        chk = self.chk
        frames: dict[str, Frame] = {}
        n_issues = len(chk.issues)
        if dh_value is not None:
            self._dh_table(dh_value, frames)
        if frames_value is not None:
            if not isinstance(frames_value, dict):
                chk.error(("frames",), f"expected a mapping frame name: definition, got {type_name(frames_value)}")
                self.frames_refused = True    # the frames it defines: their uses say nothing more
            else:
                for key, item in frames_value.items():
                    self._frame(str(key), item, frames, from_dh=dh_value is not None)
                    if str(key) not in frames:
                        self.rejected_frames.add(str(key))
        if frames and len(chk.issues) == n_issues:   # (no cascade after a bad frame)
            used = set()
            for f in frames.values():
                exprs = [e for _, e in f.factors] if f.kind == "pose" else (
                    list(f.matrix) if f.kind == "matrix" else list(f.factors))
                for e in exprs:
                    used |= e.free_symbols
            for j in self.joints:
                if j.symbol not in used:
                    chk.error(("joints", j.index, "name"), f"joint '{j.name}' does not appear in any frame")
        return frames

    def _dh_table(self, value, frames):
        chk = self.chk
        if not chk.mapping(("dh",), value, ("convention", "rows"), required=("rows",)):
            self.frames_refused = True    # the frames the table defines: their uses say nothing more
            return
        conv = value.get("convention", "standard")
        if conv not in ("standard", "modified"):
            chk.error(("dh", "convention"), f"unknown convention {conv!r}"
                      + (did_you_mean(conv, ("standard", "modified")) if isinstance(conv, str) else "")
                      + " (expected standard or modified)")
            # read as the word it suggests, or as standard: the frames stay defined for the
            # bodies, forces and questions that use them (one mistake, one message)
            conv = meant_value(conv, ("standard", "modified")) or "standard"
        rows = value.get("rows")
        if not isinstance(rows, list) or not rows:
            if "rows" in value:          # (missing: the mapping's own message says so)
                chk.error(("dh", "rows"), "expected a non-empty list of rows")
            self.frames_refused = True   # the frames the table would define: their uses say nothing more
            return
        keys = DH_KEYS if conv == "standard" else MDH_KEYS
        for i, row in enumerate(rows):
            path = ("dh", "rows", i)
            if not chk.mapping(path, row, keys, required=keys):
                self.rejected_frames.add(str(i + 1))
                continue
            vals = [chk.expr(path + (k,), row[k], self.ns) for k in keys if k in row]
            if len(vals) != 4 or any(v is None for v in vals):
                self.rejected_frames.add(str(i + 1))
                continue
            name = str(i + 1)
            self._degrees_in_dh(path, dict(zip(keys, vals)))
            frames[name] = Frame(name, str(i), "dh" if conv == "standard" else "mdh",
                                 factors=vals, line=chk.src.line(path))

    def _degrees_in_dh(self, path, row: dict) -> None:
        """A warning for a DH angle (the twist α, a constant θ) that reads like degrees."""
        for key in ("alpha", "theta"):
            hint = degrees_hint(row[key])
            if hint is not None:
                self.chk.warn(path + (key,), hint)

    def _frame(self, name, item, frames, from_dh):
        chk = self.chk
        path = ("frames", name)
        if name == "0":
            chk.error(path, "frame '0' is the fixed base frame and is never listed")
            return
        if name in frames:
            chk.error(path, f"frame '{name}' is already defined" + (" by the dh table" if from_dh else ""))
            return
        if not chk.mapping(path, item, ("parent", "pose", "matrix", "dh", "mdh")):
            return
        given = [k for k in ("pose", "matrix", "dh", "mdh") if k in item]
        if len(given) != 1:
            chk.error(path, "expected exactly one of pose, matrix, dh, mdh"
                      + (f" (got {', '.join(given)})" if given else ""))
            return
        default_parent = list(frames)[-1] if frames else "0"
        parent = str(item.get("parent", default_parent))
        if parent != "0" and parent not in frames and (parent in self.rejected_frames or self.frames_refused):
            return  # its parent was rejected (and reported): one mistake, one message
        if parent != "0" and parent not in frames:
            chk.error(path + ("parent",), f"unknown parent frame '{parent}'"
                      + did_you_mean(parent, list(frames) + ["0"])
                      + " (a parent must be '0' or a frame defined before)")
            return
        kind = given[0]
        line = chk.src.line(path)
        if kind == "pose":
            factors = self._pose(path + ("pose",), item["pose"])
            if factors is not None:
                frames[name] = Frame(name, parent, "pose", factors=factors, line=line)
        elif kind == "matrix":
            m = chk.matrix(path + ("matrix",), item["matrix"], self.ns)
            if m is not None:
                if list(m[3, :]) != [0, 0, 0, 1]:
                    chk.error(path + ("matrix",), "the last row of a pose matrix must be [0, 0, 0, 1]")
                    return
                if not self._is_rigid(m):
                    chk.error(path + ("matrix",), "not a rototranslation: the 3x3 rotation block must be "
                              "orthonormal with determinant 1 (checked at sample joint values)")
                    return
                frames[name] = Frame(name, parent, "matrix", matrix=m, line=line)
        else:
            keys = DH_KEYS if kind == "dh" else MDH_KEYS
            if not chk.mapping(path + (kind,), item[kind], keys, required=keys):
                return
            vals = [chk.expr(path + (kind, k), item[kind][k], self.ns) for k in keys if k in item[kind]]
            if len(vals) == 4 and all(v is not None for v in vals):
                self._degrees_in_dh(path + (kind,), dict(zip(keys, vals)))
                frames[name] = Frame(name, parent, kind, factors=vals, line=line)

    def _is_rigid(self, m) -> bool:
        """Numeric check of a pose matrix at a few deterministic joint values."""
        import numpy as np

        from robosolve.core.transforms import is_rototranslation

        values = self._values()
        free = sorted((m.free_symbols - set(values)), key=lambda s: s.name)
        for k in range(3):
            sample = {s: sp.Float(0.3 + 0.7 * k + 0.11 * i) for i, s in enumerate(free)}
            try:
                a = np.array(m.xreplace(values).xreplace(sample).evalf().tolist(), dtype=float)
            except (TypeError, ValueError):
                return True     # cannot be evaluated (e.g. complex): leave it to the solvers
            if not is_rototranslation(a, tol=1e-9):
                return False
        return True

    def _pose(self, path, text):
        chk = self.chk
        if not isinstance(text, str):
            chk.error(path, f"expected a string of elementary motions like 'Rz(theta1) Tx(L1)', got {type_name(text)}")
            return None
        factors, i, n = [], 0, len(text)
        while i < n:
            c = text[i]
            if c.isspace() or c == "*":
                i += 1
                continue
            op = text[i:i + 2]
            if op not in POSE_OPS:
                word = re.match(r"[A-Za-z_0-9]*", text[i:]).group(0) or text[i]
                chk.error(path, f"unknown elementary motion '{word}'" + did_you_mean(word, POSE_OPS)
                          + " (expected Tx Ty Tz Rx Ry Rz, e.g. 'Tz(h) Rz(theta1)')")
                return None
            j = i + 2
            while j < n and text[j].isspace():
                j += 1
            if j >= n or text[j] != "(":
                chk.error(path, f"expected '(' after {op}")
                return None
            depth, k = 0, j
            while k < n:
                if text[k] == "(":
                    depth += 1
                elif text[k] == ")":
                    depth -= 1
                    if depth == 0:
                        break
                k += 1
            if depth != 0:
                chk.error(path, f"unbalanced parentheses in {text!r}")
                return None
            inner = text[j + 1:k]
            try:
                e = self.ns.parse_text(inner)
            except ExpressionError as exc:
                chk.error(path, str(exc))
                return None
            issue = chk.value_issue(e, inner.strip())
            if issue is not None:
                chk.error(path, f"{op}({inner.strip()}): {issue}")
                return None
            if op[0] == "R" and (hint := degrees_hint(e)) is not None:
                chk.warn(path, f"{op}({inner.strip()}): {hint}")
            factors.append((op, e))
            i = k + 1
        if not factors:
            chk.error(path, "empty pose (write e.g. 'Tx(0)' for a frame that coincides with its parent)")
            return None
        return factors

    # -- points, gravity, bodies, forces ---------------------------------
    def _frame_ref(self, path, value, allow_base=True) -> str | None:
        if value is None or isinstance(value, (list, dict, bool)):
            self.chk.error(path, f"expected a frame name, got {type_name(value)}")
            return None
        name = str(value)
        if name == "0" and allow_base:
            return name
        if name not in self.frames and (name in self.rejected_frames or self.frames_refused):
            return None  # the frame itself was rejected (and reported): no second message
        if name not in self.frames:
            known = list(self.frames) + (["0"] if allow_base else [])
            self.chk.error(path, f"unknown frame '{name}'" + did_you_mean(name, known)
                           + (f" (known: {', '.join(known)})" if known else " (no frames are defined)"))
            return None
        return name

    def _points(self, value) -> dict:
        chk = self.chk
        points: dict[str, Point] = {}
        taken = set(self.names) | RESERVED
        if value is not None:
            if not isinstance(value, dict):
                chk.error(("points",), f"expected a mapping point name: {{frame, at}}, got {type_name(value)}")
            else:
                for name, item in value.items():
                    path = ("points", name)
                    if not IDENT_RE.fullmatch(name) or name in PYTHON_KEYWORDS:
                        chk.error(path, f"invalid point name '{name}'")
                        continue
                    if name in taken:
                        chk.error(path, f"point name '{name}' is already used by a parameter or joint")
                        continue
                    if not chk.mapping(path, item, ("frame", "at"), required=("frame",)):
                        continue
                    frame = self._frame_ref(path + ("frame",), item.get("frame")) if "frame" in item else None
                    at = self.chk.vector(path + ("at",), item.get("at", [0, 0, 0]), self.ns)
                    if frame is not None and at is not None:
                        points[name] = Point(name, frame, at, line=chk.src.line(path))
                    else:
                        self.rejected_points.add(name)
        if "E" not in points and "E" not in taken:
            points["E"] = Point("E", self.last_frame(), sp.zeros(3, 1), line=1, implicit=True)
        return points

    def last_frame(self) -> str:
        return list(self.frames)[-1] if self.frames else "0"

    def _gravity(self, value):
        if value is None:
            g = self.names.get("g")
            if g is not None and g in self.parameters:
                return sp.Matrix([0, 0, -g]), False
            return None, False
        vec = self.chk.vector(("gravity",), value, Namespace({s.name: s for s in self.parameters},
                                                             what="parameter", unknown_ok=self.parameters_refused))
        return vec, True

    def _bodies(self, value) -> list:
        chk = self.chk
        self.bodies_given = bool(value)   # a body refused has its message: no "needs bodies" too
        out, seen = [], set()
        kinds = ("point", "rod", "com", "pseudo_inertia")
        for i, path, item in chk.entries("bodies", value, "bodies", ("name", "frame", "mass") + kinds + ("inertia",),
                                         required=("name", "frame")):
            name = chk.string(path + ("name",), item.get("name")) if "name" in item else None
            if name is not None and name in seen:
                chk.error(path + ("name",), f"body name '{name}' is already used")
                name = None
            seen.add(name)
            frame = self._frame_ref(path + ("frame",), item.get("frame")) if "frame" in item else None
            given = [k for k in kinds if k in item]
            if len(given) != 1:
                chk.error(path, "expected exactly one mass distribution: point, rod, com or pseudo_inertia"
                          + (f" (got {', '.join(given)})" if given else ""))
                continue
            kind = given[0]
            if "inertia" in item and kind != "com":
                chk.error(path + ("inertia",), "inertia goes with com (the inertia tensor about the centre of mass)")
                continue
            mass = None
            if kind != "pseudo_inertia":
                if "mass" not in item:
                    if not chk.misspelt(item, "mass", ("name", "frame", "mass") + kinds + ("inertia",)):
                        chk.error(path, "missing required key 'mass'")
                    continue
                mass = chk.expr(path + ("mass",), item["mass"], self.ns)
                if mass is None:
                    continue
                value = chk.number_value(mass)
                if value is not None and value < 0:
                    chk.error(path + ("mass",), f"a mass cannot be negative, got {item['mass']!r}"
                              + (f" (= {value:g})" if not mass.is_number else ""))
                    continue
            elif "mass" in item:
                chk.error(path + ("mass",), "the mass is the [4,4] entry of pseudo_inertia: do not give both")
                continue
            data = {}
            if kind == "point":
                data["at"] = chk.vector(path + ("point",), item["point"], self.ns)
            elif kind == "rod":
                rod = item["rod"]
                if chk.mapping(path + ("rod",), rod, ("from", "to"), required=("from", "to")) \
                        and "from" in rod and "to" in rod:
                    data["from"] = chk.vector(path + ("rod", "from"), rod["from"], self.ns)
                    data["to"] = chk.vector(path + ("rod", "to"), rod["to"], self.ns)
                else:
                    data["from"] = None
            elif kind == "com":
                data["com"] = chk.vector(path + ("com",), item["com"], self.ns)
                data["inertia"] = (chk.matrix(path + ("inertia",), item["inertia"], self.ns, shapes=((3, 3),))
                                   if "inertia" in item else sp.zeros(3, 3))
                if data["inertia"] is not None and data["inertia"] != data["inertia"].T:
                    chk.error(path + ("inertia",), "the inertia tensor must be symmetric")
                    data["inertia"] = None
                elif not self._physical(path + ("inertia",), data["inertia"],
                                        lambda v: inertia_issue(v, triangle=False)):
                    data["inertia"] = None
                elif name is not None and (values := self._numbers(data["inertia"])) is not None \
                        and (why := triangle_issue(values)):
                    chk.warn(path + ("inertia",), f"{why}; {LUMPED_ROTOR}", ("body", name))
            else:
                data["J"] = chk.matrix(path + ("pseudo_inertia",), item["pseudo_inertia"], self.ns)
                if data["J"] is not None and data["J"] != data["J"].T:
                    chk.error(path + ("pseudo_inertia",), "the pseudo-inertia matrix must be symmetric")
                    data["J"] = None
                elif data["J"] is not None and not self._physical(path + ("pseudo_inertia",), data["J"],
                                                                  pseudo_inertia_issue):
                    data["J"] = None
                if data["J"] is not None:
                    mass = data["J"][3, 3]
            if name is None or frame is None or any(v is None for v in data.values()):
                continue
            out.append(Body(name, frame, mass, kind, data, line=chk.src.line(path)))
        return out

    def _numbers(self, matrix) -> list | None:
        """The rows of `matrix` as floats with the parameters' values, or None (a value unknown)."""
        if matrix is None:
            return None
        values = [self.chk.number_value(sp.sympify(e)) for e in matrix]
        if any(v is None for v in values):
            return None
        return [values[r * matrix.cols:(r + 1) * matrix.cols] for r in range(matrix.rows)]

    def _physical(self, path, matrix, issue) -> bool:
        """False (with the error at `path`) when the numeric values of `matrix` say no body has it
        (robosolve.load.physical); True when it can exist or a value is still unknown."""
        values = self._numbers(matrix)
        if values is None:
            return True
        why = issue(values)
        if why:
            self.chk.error(path, why)
        return why is None

    def _forces(self, value) -> list:
        chk = self.chk
        out, seen = [], set()
        for i, path, item in chk.entries("forces", value, "forces", ("name", "frame", "at", "force", "torque", "in"),
                                         required=("frame",)):
            name = item.get("name", f"force{i + 1}")
            name = chk.string(path + ("name",), name) if "name" in item else name
            if name is not None and name in seen:
                chk.error(path + ("name",), f"force name '{name}' is already used")
                continue
            seen.add(name)
            frame = self._frame_ref(path + ("frame",), item.get("frame"), allow_base=False) \
                if "frame" in item else None
            in_frame = self._frame_ref(path + ("in",), item["in"]) if "in" in item else frame
            at = chk.vector(path + ("at",), item.get("at", [0, 0, 0]), self.ns)
            if "force" not in item and "torque" not in item:
                chk.error(path, "expected a force, a torque, or both")
                continue
            # a force may vary with time t (followed by the types with a `time_use`)
            force = chk.vector(path + ("force",), item["force"], self.ns_time) if "force" in item else None
            torque = chk.vector(path + ("torque",), item["torque"], self.ns_time) if "torque" in item else None
            if ("force" in item and force is None) or ("torque" in item and torque is None):
                continue
            if not all(self._defined_at_start(path + (key,), v, item[key])
                       for key, v in (("force", force), ("torque", torque)) if v is not None):
                continue
            if name is None or frame is None or in_frame is None or at is None:
                continue
            out.append(Force(name, frame, at, force, torque, in_frame, line=chk.src.line(path)))
        return out

    def _defined_at_start(self, path, vector, written) -> bool:
        """A component that varies with time has a value at t = 0 (every run starts there); one
        that also depends on the joints is judged along the run."""
        t = self.names["t"]
        for k, e in enumerate(vector):
            if t in e.free_symbols:
                shown = written[k] if isinstance(written[k], str) else None
                issue = self.chk.value_issue(e.xreplace({t: 0}), shown)
                if issue is not None:
                    self.chk.error(path + (k,), f"no value at t = 0, where every run starts: {issue}")
                    return False
        return True
