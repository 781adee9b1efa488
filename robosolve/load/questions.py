"""Validation of the `questions:` list: keys of every type, parsed options, ids.

Questions are validated for every type of the spec, whether or not its solver
exists yet; the solver then finds `question.options` already parsed (sympy
expressions, joint mappings keyed by joint name in joint order).
"""

from __future__ import annotations

import re

import sympy as sp

from robosolve.load.expressions import ExpressionError, Namespace, did_you_mean, value_issue
from robosolve.load.problem import Question
from robosolve.questions.registry import COMMON_KEYS, QUESTION_TYPES

ID_RE = re.compile(r"^[A-Za-z0-9_-]+$")
SHAPES = ("bang-bang", "trapezoidal", "quintic")
LAWS = ("p", "pd", "pd_gravity", "computed_torque")


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
    ql.assign_ids(questions, value)
    ql.check_references(questions)
    return questions


def _has_time(force) -> bool:
    parts = list(force.force or []) + list(force.torque or [])
    return any("t" in {s.name for s in getattr(e, "free_symbols", ())} for e in parts)


class _QuestionLoader:
    def __init__(self, b):
        self.b = b
        self.chk = b.chk
        self.params_ns = Namespace({s.name: s for s in b.parameters}, what="parameter")
        self.joint_names = [j.name for j in b.joints]

    # ------------------------------------------------------------------
    def load(self, i, item):
        chk, b = self.chk, self.b
        path = ("questions", i)
        if not isinstance(item, dict):
            chk.error(path, f"expected a mapping with a `type`, got {type(item).__name__}")
            return None
        qtype = item.get("type")
        if not isinstance(qtype, str) or qtype not in QUESTION_TYPES:
            if "type" not in item:
                chk.error(path, "missing required key 'type'")
            else:
                chk.error(path + ("type",), f"unknown question type {qtype!r}"
                          + (did_you_mean(qtype, QUESTION_TYPES) if isinstance(qtype, str) else "")
                          + f" (expected one of: {', '.join(QUESTION_TYPES)})")
            return None
        qt = QUESTION_TYPES[qtype]
        schema = qt.options
        n_before = len(chk.issues)
        chk.mapping(path, item, COMMON_KEYS + tuple(schema), required=qt.required)
        q = Question(type=qtype, id="", index=i, line=chk.src.line(path))
        if "id" in item:
            ident = item["id"]
            if not isinstance(ident, str) or not ID_RE.fullmatch(ident):
                chk.error(path + ("id",), "expected an id of letters, digits, '_' or '-'")
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
            q.at = self.at(path + ("at",), item["at"])
        chk.overrides = self.at_values(q.at)  # the question's options are checked with its `at`
        if "marks" in item:
            q.marks = self.marks(path + ("marks",), item["marks"])
        if "grade" in item:
            q.grade = self.grade_keys(path + ("grade",), item["grade"], qt)
        for key, kind in schema.items():
            if key in item:
                v = getattr(self, "v_" + kind)(path + (key,), item[key], q)
                if v is not None:
                    q.options[key] = v
        self.type_rules(path, item, q)
        chk.overrides = {}
        return q

    def type_rules(self, path, item, q):
        chk, b = self.chk, self.b
        t, opts = q.type, q.options
        qt = QUESTION_TYPES[t]
        needs_robot = qt.needs_robot(item)
        if needs_robot and not b.problem.has_robot:
            chk.error(path + ("type",), f"a {t} question needs a robot: define joints and frames")
        if needs_robot and t != "orientation" and t != "displacement" and not b.joints:
            if b.problem.has_robot:
                chk.error(path + ("type",), f"a {t} question needs joints")
        if t == "orientation" and "matrix" in item and "frame" in item:
            chk.error(path, "give either matrix or frame (with at), not both")
        if t == "jacobian" and opts.get("geometric") and "coordinates" in item:
            chk.error(path + ("geometric",), "geometric: true cannot be combined with coordinates")
        ncoord = len(opts["coordinates"]) if "coordinates" in opts else 3
        if t == "statics":
            if not any(k in item for k in ("force", "torque")) and not opts.get("weight"):
                chk.error(path, "expected force, torque or weight: true")
            if "force" in opts and len(opts["force"]) != ncoord:
                chk.error(path + ("force",), f"expected {ncoord} components (one per coordinate), "
                          f"got {len(opts['force'])}")
            if "torque" in opts and "coordinates" in item:
                chk.error(path + ("torque",), "a torque needs the default coordinates (the point's x, y, z)")
        if t == "ellipsoids":
            if "velocity" in opts and len(opts["velocity"]) != ncoord:
                chk.error(path + ("velocity",), f"expected {ncoord} components (one per coordinate), "
                          f"got {len(opts['velocity'])}")
            if "joint_compliance" in opts and len(opts["joint_compliance"]) != len(b.joints):
                chk.error(path + ("joint_compliance",),
                          f"expected {len(b.joints)} values (one per joint), got {len(opts['joint_compliance'])}")
        if t == "motion_profile":
            shape = opts.get("shape", "bang-bang")
            if shape == "trapezoidal" and "max_velocity" not in item:
                chk.error(path, "a trapezoidal profile needs max_velocity")
            if shape != "trapezoidal" and "max_velocity" in item:
                chk.error(path + ("max_velocity",), "max_velocity goes with shape: trapezoidal")
            for key in ("max_acceleration", "max_velocity"):
                for name, v in opts.get(key, {}).items():
                    value = chk.number_value(v)
                    if value is not None and not value > 0:
                        chk.error(path + (key, name), f"must be positive, got {item[key][name]!r}"
                                  + (f" (= {value:g})" if not v.is_number else ""))
        if "duration" in opts:
            value = chk.number_value(opts["duration"])
            if value is not None and not value > 0:
                chk.error(path + ("duration",), f"must be positive (seconds), got {item['duration']!r}")
        if t == "p_control":
            law = opts.get("law", "p")
            if law != "p" and "gains_d" not in item:
                chk.error(path, f"law {law} needs gains_d")
            if law == "p" and "gains_d" in item:
                chk.error(path + ("gains_d",), "gains_d goes with law pd, pd_gravity or computed_torque")
        if t == "forward_dynamics":
            self._forward_dynamics_rules(path, item)
        if t == "displacement":
            self._displacement_rules(path, item, q)
        if t == "equations_of_motion" and "at" in item:
            timed = [f.name for f in b.problem.forces if _has_time(f)]
            if timed:
                chk.error(path + ("at",), f"the force{'s' if len(timed) > 1 else ''} {', '.join(timed)} "
                          "vary with time t, so the numbers at a configuration would need a time: drop `at` "
                          "(the symbolic equations keep t), or follow the motion with a forward_dynamics "
                          "question")
        if t == "dof":
            if opts.get("space", "planar") == "planar" and "joints_3dof" in item:
                chk.error(path + ("joints_3dof",), "3-DOF joints exist only with space: spatial")
        if qt.needs_dynamics or (t == "statics" and opts.get("weight")):
            if b.problem.gravity is None:
                chk.error(path + ("type",), "this question uses gravity: declare g in parameters "
                          "(the default gravity is [0, 0, -g]) or give gravity")
            if not b.problem.bodies and t != "statics":
                chk.error(path + ("type",), "this question needs bodies (masses)")
            masses = [chk.number_value(body.mass) for body in b.problem.bodies if body.mass is not None]
            if t in ("p_control", "forward_dynamics") and masses and all(m == 0 for m in masses):
                chk.error(path + ("type",), "every body has mass 0, so the mass matrix M(q) is singular "
                          "and the motion cannot be integrated: give the bodies their masses")
            if t == "statics" and not b.problem.bodies:
                chk.error(path + ("weight",), "weight: true needs bodies (masses)")

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
        profiles = [q for q in questions if q.type == "motion_profile"]
        for q in questions:
            if q.type not in ("joint_torques", "p_control"):
                continue
            ref = q.options.get("profile")
            if ref is None:
                if not profiles:
                    chk.error(("questions", q.index), "needs a motion_profile question (none in the file)")
                else:
                    q.options["profile"] = profiles[0].id
            elif ref not in [p.id for p in profiles]:
                chk.error(("questions", q.index, "profile"), f"no motion_profile question with id '{ref}'"
                          + did_you_mean(ref, [p.id for p in profiles]))

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
        known += [f"{a.name}.{f.name}" for a in qt.answers for f in a.fields]
        out = []
        for i, key in enumerate(value):
            if qt.key(key) is None or qt.key(key).top:
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
                    chk.error(path + (key,), f"unknown joint or parameter '{key}'" + did_you_mean(key, allowed))
                    continue
                e = chk.expr(path + (key,), v, self.params_ns)
                if e is not None:
                    out[allowed[key]], paths[allowed[key]] = e, path + (key,)
        finally:
            chk.values = values
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

    def v_bool(self, path, value, q):
        return self.chk.boolean(path, value)

    def v_expr(self, path, value, q):
        return self.chk.expr(path, value, self.params_ns)

    def v_exprs(self, path, value, q):
        v = self.chk.vector(path, value, self.b.ns, length=None)
        return list(v) if v is not None else None

    def v_vector3_params(self, path, value, q):
        v = self.chk.vector(path, value, self.params_ns, length=3)
        return list(v) if v is not None else None

    def v_vector3(self, path, value, q):
        v = self.chk.vector(path, value, self.b.ns, length=3)
        return list(v) if v is not None else None

    def v_coordinates(self, path, value, q):
        if not isinstance(value, list) or not value:
            self.chk.error(path, "expected a non-empty list of coordinate expressions (e.g. [E.x, E.y])")
            return None
        out = [self.chk.expr(path + (i,), v, self.b.ns_points) for i, v in enumerate(value)]
        return None if any(e is None for e in out) else out

    def v_budgets(self, path, value, q):
        if not self.chk.mapping(path, value, ("force", "velocity", "compliance")):
            return None
        out = {}
        for k, v in value.items():
            if k in ("force", "velocity", "compliance"):
                e = self.chk.expr(path + (k,), v, self.params_ns)
                if e is not None:
                    out[k] = e
        return out

    def v_equations(self, path, value, q):
        chk = self.chk
        if not isinstance(value, dict) or not value:
            chk.error(path, "expected a mapping coordinate expression: value (e.g. {E.x: 1.2, E.y: 0.3})")
            return None
        out = []
        for key, v in value.items():
            try:
                lhs = self.b.ns_points.parse_text(str(key))
            except ExpressionError as exc:
                chk.error(path + (key,), str(exc))
                continue
            rhs = chk.expr(path + (key,), v, self.params_ns)
            if rhs is not None:
                out.append((str(key), lhs, rhs))
        return out if len(out) == len(value) else None

    def v_joint_values(self, path, value, q, require_all=True):
        chk = self.chk
        if not isinstance(value, dict):
            chk.error(path, "expected a mapping joint: value")
            return None
        for key in value:
            if key not in self.joint_names:
                chk.error(path + (key,), f"unknown joint '{key}'" + did_you_mean(key, self.joint_names)
                          + f" (joints: {', '.join(self.joint_names)})")
        missing = [n for n in self.joint_names if n not in value]
        if require_all and missing:
            chk.error(path, f"missing joint(s) {', '.join(missing)} (give a value for every joint)")
        out = {}
        for n in self.joint_names:
            if n in value:
                e = chk.expr(path + (n,), value[n], self.params_ns)
                if e is not None:
                    out[n] = e
        return out

    def v_select(self, path, value, q):
        if value == "limits":
            return "limits"
        if isinstance(value, dict):
            return self.v_joint_values(path, value, q)
        self.chk.error(path, "expected 'limits' or a configuration (mapping joint: value)")
        return None

    def v_shape(self, path, value, q):
        return self._choice(path, value, SHAPES)

    def v_law(self, path, value, q):
        return self._choice(path, value, LAWS)

    def v_space(self, path, value, q):
        return self._choice(path, value, ("planar", "spatial"))

    def _choice(self, path, value, choices):
        if value not in choices:
            self.chk.error(path, f"unknown value {value!r}"
                           + (did_you_mean(value, choices) if isinstance(value, str) else "")
                           + f" (expected one of: {', '.join(choices)})")
            return None
        return value

    def v_profile_ref(self, path, value, q):
        if not isinstance(value, str):
            self.chk.error(path, "expected the id of a motion_profile question")
            return None
        return value

    def v_count(self, path, value, q):
        if isinstance(value, bool) or not isinstance(value, int) or value < 0:
            self.chk.error(path, "expected a whole number >= 0")
            return None
        if value > 10_000:
            self.chk.error(path, "unreasonably large count (at most 10000)")
            return None
        return value

    def v_pose_or_config(self, path, value, q):
        if isinstance(value, dict):
            return {"config": self.v_joint_values(path, value, q)}
        m = self.chk.matrix(path, value, self.params_ns, shapes=((4, 4),))
        if m is not None and (list(m[3, :]) != [0, 0, 0, 1] or not self.b._is_rigid(m)):
            self.chk.error(path, "not a rototranslation: the last row must be [0, 0, 0, 1] and the 3x3 "
                           "rotation block orthonormal with determinant 1")
            return None
        return {"matrix": m} if m is not None else None

    # -- forward_dynamics ---------------------------------------------
    def v_start_state(self, path, value, q):
        """`start`: joint values and `<joint>_dot` rates at t = 0 (missing ones: 0)."""
        chk, joints = self.chk, self.b.joints
        if not isinstance(value, dict):
            chk.error(path, "expected a mapping joint: value and <joint>_dot: rate (e.g. {theta: 0, theta_dot: 1})")
            return None
        allowed = [j.name for j in joints] + [j.dot.name for j in joints]
        ddots = {j.ddot.name for j in joints}
        out = {}
        for key, v in value.items():
            if key in ddots:
                chk.error(path + (key,), f"'{key}' cannot be given: the accelerations follow from the "
                          "equations of motion (give joint values and <joint>_dot rates)")
                continue
            if key not in allowed:
                chk.error(path + (key,), f"unknown joint or joint rate '{key}'" + did_you_mean(key, allowed)
                          + f" (expected: {', '.join(allowed)})")
                continue
            e = chk.expr(path + (key,), v, self.params_ns)
            if e is not None:
                out[key] = e
        return {k: out[k] for k in allowed if k in out}

    def v_actuator_laws(self, path, value, q):
        """`actuators`: actuator -> expression in t, the joints, their rates and the parameters."""
        chk, b = self.chk, self.b
        if not isinstance(value, dict):
            chk.error(path, "expected a mapping actuator: law (e.g. {C: 70*sin(t)})")
            return None
        acts = [str(j.actuator) for j in b.joints]
        names = {s.name: s for s in b.parameters}
        for j in b.joints:
            names[j.name], names[j.dot.name] = j.symbol, j.dot
        names["t"] = b.names["t"]
        ns = Namespace(names, what="name in the law (it may use t, the joints, their _dot rates, the parameters)")
        out = {}
        for key, v in value.items():
            if key not in acts:
                chk.error(path + (str(key),), f"unknown actuator '{key}'" + did_you_mean(str(key), acts)
                          + f" (actuators: {', '.join(acts)})")
                continue
            e = chk.expr(path + (key,), v, ns)
            if e is not None:
                out[key] = e
        return {a: out[a] for a in acts if a in out}

    def v_duration(self, path, value, q):
        e = self.chk.expr(path, value, self.params_ns)
        if e is not None and e.is_number and not (e.is_real and e.is_positive and e.is_finite):
            self.chk.error(path, f"expected a positive duration in seconds, got {value!r}")
            return None
        return e

    def _displacement_rules(self, path, item, q):
        """Two forms: `from` and `to`, or a screw (`axis`, `angle`, `through`, `translation`)."""
        chk = self.chk
        screw_keys = [k for k in ("axis", "angle", "through", "translation") if k in item]
        pose_keys = [k for k in ("from", "to") if k in item]
        if screw_keys and pose_keys:
            chk.error(path, f"give either from/to or a screw (axis, angle, through, translation), not both "
                      f"(found {', '.join(pose_keys + screw_keys)})")
            return
        if not screw_keys:
            for k in ("from", "to"):
                if k not in item:
                    chk.error(path, f"missing required key '{k}' (or give a screw: axis and angle)")
            return
        if "axis" not in item:
            chk.error(path, f"{', '.join(screw_keys)} describe a screw: give its axis too")
            return
        if "angle" not in item:
            chk.error(path, "missing required key 'angle' (the rotation about the axis, any real value)")
        if "frame" in item:
            chk.error(path + ("frame",), "a screw is given in frame 0: `frame` goes with from/to")
        axis = q.options.get("axis")
        if axis is not None:
            values = self.b._values()
            vals = [sp.sympify(e).xreplace(values) for e in axis]
            if all(v.is_number for v in vals) and all(abs(complex(v)) <= 1e-12 for v in vals):
                chk.error(path + ("axis",), "the zero vector has no direction (give the axis direction, "
                          "any non-zero length)")

    def _forward_dynamics_rules(self, path, item):
        at = item.get("at")
        if not isinstance(at, dict):
            return
        motion = {}
        for j in self.b.joints:
            motion[j.name] = motion[j.dot.name] = motion[j.ddot.name] = j.name
        for key in at:
            if key in motion:
                self.chk.error(path + ("at", key), f"a forward_dynamics question's `at` may override "
                               f"parameters only: give the starting value of '{key}' in `start` "
                               "(joint values and <joint>_dot rates)")

    def v_rotation_matrix(self, path, value, q):
        import sympy as sp

        m = self.chk.matrix(path, value, self.params_ns, shapes=((3, 3), (4, 4)))
        if m is None:
            return None
        full = m if m.shape == (4, 4) else sp.diag(m, 1)
        if m.shape == (4, 4) and list(m[3, :]) != [0, 0, 0, 1]:
            self.chk.error(path, "the last row of a pose matrix must be [0, 0, 0, 1]")
            return None
        if not self.b._is_rigid(full):
            self.chk.error(path, "not a rotation: the 3x3 block must be orthonormal with determinant 1"
                           + (" (checked at sample values of " + ", ".join(sorted(s.name for s in m.free_symbols))
                              + ")" if m.free_symbols else ""))
            return None
        return m

