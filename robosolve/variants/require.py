"""Cheap numeric checks of a variants section's `require` conditions.

Each condition is reduced once, symbolically, to a function of the varied parameters
only (every other parameter resolved to its value, the question's `at` substituted),
lambdified, then evaluated with numbers for each draw; results are memoised on the
values of the parameters the condition actually depends on, so counting a grid costs one
evaluation per distinct sub-combination, not one per combination.

- inequality: evaluated in floating point; within 1e-9 of equality, decided exactly;
- `nonsingular`: the smallest singular value of J at the question's `at` is above 1e-6
  times the largest (J from robosolve.kinematics' analytic / geometric Jacobian);
- `reachable`: the IK engine's numeric search (robosolve.ik.numeric.solve_all, the same
  multi-start search and the same joint-limit rule as the inverse kinematics solver)
  finds at least one solution inside the limits; for a pose target, the solver's own pose
  IK (robosolve.ik.pose.solve_pose) without its closed form.

The checks run on a *template* problem in which the varied parameters are null (plain
real symbols): the base problem's symbols may carry `positive=True`, which would be wrong
for draws of other signs.
"""

from __future__ import annotations

import itertools
import math

import numpy as np
import sympy as sp

from robosolve.core.parameters import resolve_parameters
from robosolve.core.simplify import full
from robosolve.errors import InputError, InputIssue

SINGULAR_RATIO = 1e-6
TIE = 1e-9
QUICK_STARTS = 6          # per joint, for the first reachability search


class Condition:
    """One requirement as a function of some varied parameters (by index)."""

    def __init__(self, requirement, relevant: tuple, evaluate):
        self.requirement = requirement
        self.relevant = relevant                 # indices into spec.parameters
        self._evaluate = evaluate                # (exact values, float values) -> bool
        self._memo: dict = {}

    def holds(self, spec, idx: tuple) -> bool:
        key = tuple(idx[i] for i in self.relevant)
        hit = self._memo.get(key)
        if hit is None:
            exact = [spec.parameters[i].value(k) for i, k in zip(self.relevant, key)]
            hit = bool(self._evaluate(exact, [float(sp.N(e, 17)) for e in exact]))
            self._memo[key] = hit
        return hit

    def ever_holds(self) -> bool:
        """Whether any combination evaluated so far meets the condition."""
        return any(self._memo.values())

    def table(self, spec, progress=None) -> np.ndarray:
        """Truth over the product of the relevant parameters' value sets."""
        sizes = [spec.parameters[i].size for i in self.relevant]
        out = np.zeros(sizes, dtype=bool)
        full = [0] * len(spec.parameters)
        for key in itertools.product(*[range(s) for s in sizes]):
            for i, k in zip(self.relevant, key):
                full[i] = k
            out[key] = self.holds(spec, tuple(full))
            if progress is not None:
                progress()
        return out


def _exact_sign(e) -> int | None:
    """The sign of the number `e` (exact, then to 50 digits), or None when it has no real value:
    a division by zero, the square root or logarithm of a negative number."""
    v = full(e)
    if v == 0:
        return 0
    if v.is_extended_real and v.is_finite:
        if v.is_positive:
            return 1
        if v.is_negative:
            return -1
    try:
        c = complex(sp.N(v, 50))
    except (TypeError, ValueError):
        return None
    if not (math.isfinite(c.real) and math.isfinite(c.imag)) or abs(c.imag) > 1e-30 * max(1.0, abs(c.real)):
        return None
    return int(np.sign(c.real))


class RequirementChecker:
    """All conditions of a spec, on the template problem (varied parameters null)."""

    def __init__(self, template, spec, file: str):
        self.problem = template
        self.spec = spec
        self.file = file
        self.symbols = [template.names[p.name] for p in spec.parameters]
        self.varied = set(self.symbols)
        self._model = None
        issues = []
        self.conditions = []
        for r in spec.require:
            try:
                self.conditions.append(self._build(r))
            except _Unusable as exc:
                issues.append(InputIssue(file, r.line, r.path, str(exc)))
        if issues:
            raise InputError(issues)
        # cheap conditions first: a failing inequality spares an IK search
        cost = {"inequality": 0, "nonsingular": 1, "reachable": 2}
        self.conditions.sort(key=lambda c: cost[c.requirement.kind])

    @property
    def model(self):
        if self._model is None:
            from robosolve.model import RobotModel

            self._model = RobotModel(self.problem)
        return self._model

    def first_failure(self, idx: tuple):
        """The first condition (cheapest first) that the draw `idx` breaks, or None."""
        for c in self.conditions:
            if not c.holds(self.spec, idx):
                return c.requirement
        return None

    def valid_grid(self, progress=None) -> np.ndarray:
        """Boolean array over the whole grid (shape: the parameters' sizes)."""
        shape = [p.size for p in self.spec.parameters]
        valid = np.ones(shape, dtype=bool)
        for c in self.conditions:
            t = c.table(self.spec, progress)
            # broadcast the condition's table over the axes it does not depend on
            order = np.argsort(c.relevant)
            t = np.transpose(t, order) if t.ndim > 1 else t
            bshape = [1] * len(shape)
            for i in sorted(c.relevant):
                bshape[i] = shape[i]
            valid &= t.reshape(bshape)
        return valid

    def never_met(self) -> list:
        """The requirements that hold for no combination of their parameters (after valid_grid,
        which evaluates every one): what makes the section impossible."""
        return [c.requirement for c in self.conditions if not c.ever_holds()]

    def table_work(self) -> int:
        return sum(math.prod(self.spec.parameters[i].size for i in c.relevant) for c in self.conditions)

    # ------------------------------------------------------------------
    def _relevant(self, exprs) -> tuple:
        free = set()
        for e in exprs:
            free |= sp.sympify(e).free_symbols
        return tuple(i for i, s in enumerate(self.symbols) if s in free)

    def _only_varied(self, exprs, allowed=()):
        free = set()
        for e in exprs:
            free |= sp.sympify(e).free_symbols
        extra = sorted(s.name for s in free - self.varied - set(allowed))
        if extra:
            raise _Unusable(f"cannot be checked: {', '.join(extra)} ha{'s' if len(extra) == 1 else 've'} no value")

    def _build(self, r) -> Condition:
        if r.kind == "inequality":
            return self._inequality(r)
        if r.kind == "nonsingular":
            return self._nonsingular(r)
        return self._reachable(r)

    def _question(self, qid):
        for q in self.problem.questions:
            if q.id == qid:
                return q
        raise _Unusable(f"unknown question {qid!r}")  # pragma: no cover - validated by the loader

    def _inequality(self, r) -> Condition:
        names = self.problem.names
        swap = {s: names[s.name] for s in (r.lhs - r.rhs).free_symbols if s.name in names}
        d = (r.lhs - r.rhs).xreplace(swap)
        d = d.xreplace(resolve_parameters(self.problem.parameters, varied=self.varied))
        self._only_varied([d])
        rel = self._relevant([d])
        syms = [self.symbols[i] for i in rel]
        fn = sp.lambdify(syms, d, modules="math")
        op = r.op

        def evaluate(exact, floats):
            try:
                x = float(fn(*floats))
            except (ValueError, ZeroDivisionError, OverflowError, TypeError):
                x = float("nan")
            if not math.isfinite(x) or abs(x) <= TIE * max(1.0, *[abs(f) for f in floats]):
                sign = _exact_sign(d.xreplace(dict(zip(syms, exact))))
                if sign is None:         # no real value for this draw (1/0, sqrt(-1)): not met
                    return False
            else:
                sign = 1 if x > 0 else (-1 if x < 0 else 0)
            return {"<": sign < 0, "<=": sign <= 0, ">": sign > 0, ">=": sign >= 0}[op]

        return Condition(r, rel, evaluate)

    def _at_values(self, q) -> tuple[dict, dict]:
        """(parameters resolved with the question's overrides, joint values of its `at`)."""
        overrides = {s: v for s, v in q.at.items() if s in self.problem.parameters}
        params = resolve_parameters(self.problem.parameters, overrides, self.varied)
        joints = {s: v.xreplace(params) for s, v in q.at.items() if s not in self.problem.parameters}
        return params, joints

    def _nonsingular(self, r) -> Condition:
        from robosolve.kinematics.jacobian_math import analytic_jacobian, geometric_jacobian
        from robosolve.solvers.task_space import joint_l0

        q = self._question(r.question)
        model = self.model
        if q.options.get("geometric"):
            pframe, _ = model.point_local(q.point)
            frame = q.frame or self.problem.last_frame
            p0 = model.point0(q.point)
            jp = geometric_jacobian([joint_l0(model, i, pframe) for i in range(len(model.q))], p0)[:3, :]
            jw = geometric_jacobian([joint_l0(model, i, frame) for i in range(len(model.q))], p0)[3:, :]
            J = sp.Matrix.vstack(jp, jw)
        else:
            raw = q.options.get("coordinates")
            coords = list(model.point0(q.point)) if raw is None else [model.coordinate(c) for c in raw]
            J = analytic_jacobian(coords, model.q)
        params, joints = self._at_values(q)
        Jn = J.xreplace(params).xreplace(joints).xreplace(params)
        self._only_varied(list(Jn))
        rel = self._relevant(list(Jn))
        syms = [self.symbols[i] for i in rel]
        fn = sp.lambdify(syms, Jn, modules="numpy", cse=True)

        def evaluate(exact, floats):
            m = np.array(fn(*floats), dtype=float)
            if not np.all(np.isfinite(m)):
                return False
            s = np.linalg.svd(m, compute_uv=False)
            return bool(s.size and s[0] > 0 and s[-1] > SINGULAR_RATIO * s[0])

        return Condition(r, rel, evaluate)

    def _reachable(self, r) -> Condition:
        from robosolve.ik.engine import IKJoint, _boxes, in_limits, is_angular
        from robosolve.ik.numeric import NumericSystem, solve_all

        q = self._question(r.question)
        if not isinstance(q.options["target"], list):
            return self._reachable_pose(r, q)
        model = self.model
        params, _ = self._at_values(q)
        qs = list(model.q)
        exprs, targets, used = [], [], set()
        for _text, lhs, rhs in q.options["target"]:
            original = model.coordinate(lhs) - sp.sympify(rhs)
            used |= original.free_symbols & set(self.problem.parameters)
            exprs.append(original.xreplace(params))
            targets.append(sp.sympify(rhs).xreplace(params))
        limits = [tuple(sp.sympify(v).xreplace(params) for v in j.limits) if j.limits is not None else None
                  for j in model.joints]
        self._only_varied(exprs, allowed=qs)
        self._only_varied([v for lim in limits if lim for v in lim] + targets)
        base = [IKJoint(j.symbol, j.is_revolute, None) for j in model.joints]
        angular = [is_angular(e, base) for e in exprs]
        # the IK engine's scale: the parameters of the equations and the target values
        scale_exprs = [params[s] for s in sorted(used, key=lambda s: s.name) if s in params] + targets
        rel = self._relevant(exprs + [v for lim in limits if lim for v in lim] + scale_exprs)
        syms = [self.symbols[i] for i in rel]
        m, n = len(exprs), len(qs)
        jac = sp.Matrix(exprs).jacobian(qs)
        f_raw = sp.lambdify(qs + syms, exprs, modules="numpy", cse=True)
        j_raw = sp.lambdify(qs + syms, list(jac), modules="numpy", cse=True)
        lim_fn = sp.lambdify(syms, [list(lim) if lim else [0, 0] for lim in limits], modules="math")
        scale_fn = sp.lambdify(syms, scale_exprs, modules="math")

        def stack(cols, N):
            return np.stack([np.broadcast_to(np.asarray(c, dtype=float), (N,)) for c in cols], axis=1)

        def evaluate(exact, floats):
            def f(Q):
                Q = np.atleast_2d(np.asarray(Q, dtype=float))
                return stack(f_raw(*Q.T, *floats), Q.shape[0])

            def jf(Q):
                Q = np.atleast_2d(np.asarray(Q, dtype=float))
                return stack(j_raw(*Q.T, *floats), Q.shape[0]).reshape(Q.shape[0], m, n)

            lims = lim_fn(*floats)
            joints = [IKJoint(j.symbol, j.is_revolute, (float(lo), float(hi)) if limits[i] else None)
                      for i, (j, (lo, hi)) in enumerate(zip(model.joints, lims))]
            scale = max([1.0] + [abs(float(v)) for v in scale_fn(*floats)])
            system = NumericSystem(f, jf, [j.revolute for j in joints], angular, scale)
            boxes = _boxes(joints, scale)
            # a few starts first: a verified solution inside the limits settles it; only a draw
            # that looks unreachable pays for the solver's full search (the same verdict as its)
            for budget in (QUICK_STARTS ** len(joints), None):
                res = solve_all(system, boxes, budget=budget, deflation=budget is None)
                if any(not in_limits({j.name: v for j, v in zip(joints, s.q)}, joints) for s in res.solutions):
                    return True
            return False

        return Condition(r, rel, evaluate)


    def _reachable_pose(self, r, q) -> Condition:
        """A pose target: the solver's own pose IK (robosolve.ik.pose.solve_pose: decoupling at a
        spherical wrist, the UR way, else the numeric search) with the draw's values, without
        deriving the closed form; reachable when a solution lies inside the limits."""
        from robosolve.ik.engine import IKJoint
        from robosolve.ik.pose import solve_pose
        from robosolve.solvers.ik_pose import is_rotation, with_values

        model, target = self.model, q.options["target"]
        params, _ = self._at_values(q)
        frame, c = q.frame, None
        if q.point_given:
            frame, c = model.point_local(q.point)
            c = sp.Matrix(c).xreplace(params)
        factors = [with_values(model.M_local(f), params, model) for f in model.chain(frame)]
        R, p = target.R.xreplace(params), target.p.xreplace(params)
        limits = [tuple(sp.sympify(v).xreplace(params) for v in j.limits) if j.limits is not None else None
                  for j in model.joints]
        qs = set(model.q)
        used = [j for j in model.joints if any(j.symbol in f.free_symbols for f in factors)]
        if not used or len(used) > 6:
            raise _Unusable(f"cannot be checked: the pose of frame {frame} moves with {len(used)} joints "
                            "(a pose target is solved for 1 to 6)")
        given = list(R) + list(p) + (list(c) if c is not None else []) + [v for lim in limits if lim for v in lim]
        self._only_varied(factors, allowed=qs)
        self._only_varied(given)
        rel = self._relevant(factors + given)
        syms = [self.symbols[i] for i in rel]

        def evaluate(exact, floats):
            draw = dict(zip(syms, exact))
            Rn = np.array(sp.N(R.xreplace(draw)), dtype=float).reshape(3, 3)
            pn = np.array(sp.N(p.xreplace(draw)), dtype=float).reshape(3)
            if not (np.all(np.isfinite(Rn)) and np.all(np.isfinite(pn)) and is_rotation(Rn)):
                return False                # the solver refuses such a target: no solution
            if c is not None:
                pn = pn - Rn @ np.array(sp.N(c.xreplace(draw)), dtype=float).reshape(3)
            lims = {j.symbol: lim for j, lim in zip(model.joints, limits)}
            joints = [IKJoint(j.symbol, j.is_revolute, None if lims[j.symbol] is None else
                              tuple(float(sp.N(v.xreplace(draw))) for v in lims[j.symbol])) for j in used]
            chain = [with_values(f, draw, model) for f in factors]
            return bool(solve_pose(chain, joints, Rn, pn, derive=False).solutions)

        return Condition(r, rel, evaluate)


class _Unusable(Exception):
    """A condition that cannot be evaluated with numbers (a value is missing)."""
