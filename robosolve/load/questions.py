"""Validation of the `questions:` list: keys of every type, parsed options, ids.

Questions are validated for every type of the spec, whether or not its solver
exists yet; the solver then finds `question.options` already parsed (sympy
expressions, joint mappings keyed by joint name in joint order).
"""

from __future__ import annotations

import re

from robosolve.load.expressions import Namespace, degrees_hint, did_you_mean, meant_value, value_issue
from robosolve.load.problem import Question
from robosolve.questions.registry import COMMON_KEYS, QUESTION_TYPES, RECORD, types_where

ID_RE = re.compile(r"^[A-Za-z0-9_-]+$")
# Options the others are judged against (the coordinates, the law, the space, what is followed):
# when one is refused, its question's type checks do not run on a default in its place.
CONTEXT_KEYS = frozenset({"coordinates", "law", "space", "trajectory", "profile", "point", "frame", "at"})


def may_be_refused(refused_ids: set, ref) -> bool:
    """Whether `ref` may be the id of a question refused whole, said already (`refused_ids`: their
    ids, None for one that had no readable id)."""
    return ref in refused_ids or None in refused_ids


def load_questions(builder, value) -> list:
    chk = builder.chk
    if value is None:
        if isinstance(builder.data, dict) and "questions" in builder.data:
            chk.error(("questions",), "expected a non-empty list of questions")
        return []
    if not isinstance(value, list) or not value:
        chk.error(("questions",), "expected a non-empty list of questions")
        return []
    ql = _QuestionLoader(builder)
    questions = []
    for i, item in enumerate(value):
        q = ql.load(i, item)
        if q is not None:
            questions.append(q)
        else:       # refused whole (its message given): references to it say nothing more
            ql.refused_ids.add(item.get("id") if isinstance(item, dict) and isinstance(item.get("id"), str)
                               else None)
    ql.assign_ids(questions, value)
    ql.check_references(questions)
    builder.refused_question_ids = ql.refused_ids      # (the variants section's references)
    return questions


class _QuestionLoader:
    def __init__(self, b):
        self.b = b
        self.chk = b.chk
        # a joint where only parameters may stand (a target's value, a gain) is a mistake of its
        # own: say so, not "unknown parameter 'q1'"
        joint_refused = {j.name: f"'{j.name}' is a joint: this value is a number or an expression "
                                 "of the parameters" for j in b.joints if isinstance(j.name, str)}
        self.params_ns = Namespace({s.name: s for s in b.parameters}, what="parameter",
                                   refused=joint_refused,
                                   unknown_ok=b.parameters_refused)   # (refused whole: said already)
        self.joint_names = [j.name for j in b.joints]
        self.profile_type = self.type_name("makes_profile")
        self.refused_ids: set = set()      # ids of questions refused whole (None: one had no id)

    def refused(self, ref) -> bool:
        """Whether `ref` may be the id of a question refused whole (said already)."""
        return may_be_refused(self.refused_ids, ref)

    @staticmethod
    def type_name(flag: str) -> str:
        """The name of the (first) question type with `flag` set (questions/schema.py)."""
        return types_where(flag)[0].name

    # ------------------------------------------------------------------
    def load(self, i, item):
        chk, b = self.chk, self.b
        path = ("questions", i)
        if not isinstance(item, dict):
            chk.error(path, f"expected a mapping with a `type`, got {type(item).__name__}")
            return None
        item = self.typed(path, item)
        if item is None:
            return None
        qtype = item["type"]
        qt = QUESTION_TYPES[qtype]
        schema = qt.options
        n_before = len(chk.issues)
        chk.mapping(path, item, COMMON_KEYS + tuple(schema), required=qt.required)
        q = Question(type=qtype, id="", index=i, line=chk.src.line(path))
        rejected = set()
        if "id" in item:
            ident = item["id"]
            if not isinstance(ident, str) or not ID_RE.fullmatch(ident):
                chk.error(path + ("id",), "expected an id of letters, digits, '_' or '-'")
                rejected.add("id")
                self.refused_ids.add(None)      # references to it may use another spelling
                # the id as written stands for the question (references to it say nothing more)
                q.id = ident if isinstance(ident, str) and ident.strip() else f"<questions[{i}]>"
            else:
                q.id = ident
        q.frame = b.last_frame()
        if "frame" in item:
            f = b._frame_ref(path + ("frame",), item["frame"])
            if f is not None:
                q.frame, q.frame_given = f, True
        if "point" in item:
            p = item["point"]
            if isinstance(p, str) and p in b.rejected_points:
                pass  # the point's own error is reported: one mistake, one message
            elif not isinstance(p, str) or p not in b.points:
                chk.error(path + ("point",), f"unknown point {p!r}"
                          + (did_you_mean(p, b.points) if isinstance(p, str) else "")
                          + (f" (known: {', '.join(b.points)})" if b.points else ""))
            else:
                q.point, q.point_given = p, True
        if "at" in item:
            before = len(chk.issues)
            q.at = self.at(path + ("at",), item["at"])
            if len(chk.issues) > before:
                rejected.add("at")
        chk.overrides = self.at_values(q.at)  # the question's options are checked with its `at`
        if "marks" in item:
            q.marks = self.marks(path + ("marks",), item["marks"])
        if "grade" in item:
            q.grade = self.grade_keys(path + ("grade",), item["grade"], qt)
        if "text" in item:
            from robosolve.load.paper import question_text
            q.text = question_text(self.chk, path + ("text",), item["text"], self.b.parameters)
        q.lines = {str(k): chk.src.line(path + (k,)) for k in item}
        for key, validator in schema.items():
            if key in item:
                before = len(chk.issues)
                v = validator(self, path + (key,), item[key], q)
                if v is not None:
                    q.options[key] = v
                if v is None or len(chk.issues) > before:
                    rejected.add(key)
        q.rejected = frozenset(rejected)
        self.type_rules(path, item, q)
        chk.overrides = {}
        return q

    def typed(self, path, item: dict) -> dict | None:
        """The question with a known `type`, or None after saying what is wrong with it. A
        misspelt type (`jcobian`) is said once, then read as the type it suggests with its own
        checks silent, so the questions and sections that use it (its id, its profile) say
        nothing more."""
        chk = self.chk
        qtype = item.get("type")
        if isinstance(qtype, str) and qtype in QUESTION_TYPES:
            return item
        meant = meant_value(qtype, QUESTION_TYPES)
        if meant is not None:
            chk.error(path + ("type",), f"unknown question type {qtype!r}" + did_you_mean(qtype, QUESTION_TYPES)
                      + f" (expected one of: {', '.join(QUESTION_TYPES)})")
            chk.renamed.append(path)
            return dict(item, type=meant)
        if "type" not in item:
            known = set(COMMON_KEYS).union(*(t.options for t in QUESTION_TYPES.values()))
            typo = next((k for k in item if isinstance(k, str) and k not in known
                         and did_you_mean(k, ["type"])), None)
            if typo is not None:        # `tpye: position`: the key, not a missing type
                chk.error(path + (typo,), f"unknown key '{typo}' (did you mean 'type'?)")
            else:
                chk.error(path, "missing required key 'type'")
        else:
            chk.error(path + ("type",), f"unknown question type {qtype!r}"
                      + (did_you_mean(qtype, QUESTION_TYPES) if isinstance(qtype, str) else "")
                      + f" (expected one of: {', '.join(QUESTION_TYPES)})")
        return None

    def type_rules(self, path, item, q):
        """The checks every type shares (robot, joints, duration, dynamics), then the type's own
        (`QuestionType.check`, in robosolve/questions/<type>.py)."""
        chk, b = self.chk, self.b
        t, opts = q.type, q.options
        qt = QUESTION_TYPES[t]
        needs_robot = qt.needs_robot(item)
        if needs_robot and not b.problem.has_robot:
            chk.error(path + ("type",), f"a {t} question needs a robot: define joints and frames")
        if needs_robot and qt.needs_joints and not b.joints:
            if b.problem.has_robot and not b.joint_name_refused:
                chk.error(path + ("type",), f"a {t} question needs joints")
        if "duration" in opts:
            value = chk.number_value(opts["duration"])
            if value is not None and not value > 0:
                chk.error(path + ("duration",), f"must be positive (seconds), got {item['duration']!r}")
        if qt.check is not None and not (q.rejected & CONTEXT_KEYS) and not b.joint_name_refused:
            # the type's checks judge its options against these (a force per coordinate, gains per
            # the law's kind): with one refused (and said), they would judge a default in its place
            qt.check(self, path, item, q)
            self.graded_keys_computed(path, q, qt)
        if qt.needs_dynamics:
            self.require_gravity(path)
            if not b.problem.bodies and not b.bodies_given:
                chk.error(path + ("type",), "this question needs bodies (masses)")
            masses = [chk.number_value(body.mass) for body in b.problem.bodies if body.mass is not None]
            if qt.integrates and masses and all(m == 0 for m in masses):
                chk.error(path + ("type",), "every body has mass 0, so the mass matrix M(q) is singular "
                          "and the motion cannot be integrated: give the bodies their masses")

    def graded_keys_computed(self, path, q, qt):
        """A graded key the question does not compute would be `no_reference` for every student
        while the paper asks for it (q_dot without a velocity, the centre-of-mass Jacobians
        without bodies: true): said with the key's line."""
        keys = {a.name: a for a in qt.answers}
        for i, name in enumerate(q.grade or ()):
            key = keys.get(name.split(".")[0])
            why = key.needs(q, self.b.joints) if key is not None and key.needs else ""
            if why:
                self.chk.error(path + ("grade", i), f"'{name}' is not an answer of this question: {why}")

    def require_gravity(self, path):
        """A question using gravity needs it declared."""
        if self.b.problem.gravity is None and not self.b.gravity_refused:
            # a parameter declared under a name close to g is most likely it, misspelt
            self.chk.error(path + ("type",), "this question uses gravity: declare g in parameters"
                           + did_you_mean("g", [s.name for s in self.b.parameters])
                           + " (the default gravity is [0, 0, -g]) or give gravity")

    # -- ids and references --------------------------------------------
    def assign_ids(self, questions, raw):
        chk = self.chk
        counts: dict[str, int] = {}
        for q in questions:
            if not q.id:
                counts[q.type] = counts.get(q.type, 0) + 1
                q.id = q.type if counts[q.type] == 1 else f"{q.type}-{counts[q.type]}"
        seen = {}
        for q in questions:
            if q.id in seen:
                chk.error(("questions", q.index, "id"), f"duplicate question id '{q.id}' "
                          f"(also questions[{seen[q.id]}])")
            else:
                seen[q.id] = q.index

    def check_references(self, questions):
        chk = self.chk
        source = self.profile_type
        profiles = [q for q in questions if QUESTION_TYPES[q.type].makes_profile]
        for q in questions:
            if QUESTION_TYPES[q.type].resolve is not None:
                QUESTION_TYPES[q.type].resolve(self, q, questions)
            if not QUESTION_TYPES[q.type].uses_profile or "trajectory" in q.options or "trajectory" in q.rejected:
                continue
            if "profile" in q.rejected or str(q.options.get("law", "")).startswith("task_"):
                continue        # (a task law follows a `trajectory`: its own check asks for one)
            ref = q.options.get("profile")
            if ref is None:
                if not profiles and not self.refused_ids:
                    chk.error(("questions", q.index), f"needs a {source} question (none in the file)")
                elif profiles and profiles[0].index > q.index:
                    chk.error(("questions", q.index), f"needs a {source} question before it (the first one, "
                              f"'{profiles[0].id}', is questions[{profiles[0].index}]: put it before; "
                              "questions are answered in file order)")
                elif profiles:
                    q.options["profile"] = profiles[0].id
            elif ref not in [p.id for p in profiles] and not self.refused(ref):
                chk.error(("questions", q.index, "profile"), f"no {source} question with id '{ref}'"
                          + did_you_mean(ref, [p.id for p in profiles]))
            elif (later := next((p for p in profiles if p.id == ref and p.index > q.index), None)):
                # solved in file order: the follower would find no answer yet
                chk.error(("questions", q.index, "profile"), f"the {source} question '{ref}' is "
                          f"questions[{later.index}], after this one: put it before (questions are "
                          "answered in file order)")

    # -- validators ---------------------------------------------------
    def marks(self, path, value):
        e = self.chk.expr(path, value, Namespace({}, what="number"))
        if e is None:
            return 1
        if not (e.is_number and e.is_real and e.is_nonnegative):
            self.chk.error(path, f"expected a number >= 0, got {value!r}")
            return 1
        return e

    def grade_keys(self, path, value, qt):
        chk = self.chk
        if not isinstance(value, list) or not value or not all(isinstance(v, str) for v in value):
            chk.error(path, "expected a non-empty list of answer keys (e.g. [M, position])")
            return ()
        known = [a.name for a in qt.answers if not a.top]
        # a record's field may be graded alone (force.lengths); not a field of the records of a
        # mapping (actuators.peak: each actuator has one), which no answers file can hold
        known += [f"{a.name}.{f.name}" for a in qt.answers if a.kind == RECORD for f in a.fields]
        out = []
        for i, key in enumerate(value):
            if key not in known:
                chk.error(path + (i,), f"unknown answer key '{key}' for a {qt.name} question"
                          + did_you_mean(key, known) + f" (keys: {', '.join(known)})")
            elif key in out:
                chk.error(path + (i,), f"answer key '{key}' listed twice")
            else:
                out.append(key)
        return tuple(out)

    def at(self, path, value):
        chk, b = self.chk, self.b
        if not isinstance(value, dict):
            chk.error(path, f"expected a mapping of joint or parameter values, got {type(value).__name__}")
            return {}
        allowed = {}
        for j in b.joints:
            allowed[j.name], allowed[j.dot.name], allowed[j.ddot.name] = j.symbol, j.dot, j.ddot
        for s in b.parameters:
            allowed[s.name] = s
        out, paths = {}, {}
        values, chk.values = chk.values, None  # checked below, joints with the overridden parameters
        try:
            for key, v in value.items():
                if key not in allowed:
                    if not (self.b.joint_name_refused or self.b.parameters_refused):   # (said already)
                        chk.error(path + (key,), f"unknown joint or parameter '{key}'" + did_you_mean(key, allowed))
                    continue
                e = chk.expr(path + (key,), v, self.params_ns)
                if e is not None:
                    out[allowed[key]], paths[allowed[key]] = e, path + (key,)
        finally:
            chk.values = values
        for j in b.joints:            # a revolute joint's value that reads like degrees (30, 90)
            hint = degrees_hint(out.get(j.symbol)) if j.kind == "revolute" else None
            if hint is not None:
                chk.warn(paths[j.symbol], hint)
        params = {s: e for s, e in out.items() if s in b.parameters}
        for s, e in list(out.items()):
            shown = value[s.name] if isinstance(value.get(s.name), str) else None
            issue = chk.value_issue(e, shown) if s in params else (
                None if chk.values is None else value_issue(e, {**b._values(params), **params}, shown))
            if issue is not None:
                chk.error(paths[s], issue)
                out.pop(s)
        return out

    def at_values(self, at: dict) -> dict:
        """Values of every symbol a question's options may use: parameters (with the `at`
        overrides) and the `at` joint values."""
        if not at or self.chk.values is None:
            return {}
        params = {s: e for s, e in at.items() if s in self.b.parameters}
        values = self.b._values(params)
        return {**values, **{s: e.xreplace(values) for s, e in at.items() if s not in params}}
