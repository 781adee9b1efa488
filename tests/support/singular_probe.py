"""A probe of the `jacobian` question's singular configurations on robots robosolve has not
seen (issue 26): random arms written as problem YAML, solved through the whole pipeline
(results.json), and each answer checked against an independent reference, Robotics Toolbox's
`jacob0` of the same DH table and numpy's SVD.

* soundness: every reported condition (a mapping joint → value or an equation string),
  met at random configurations (a least-squares solve of the condition from random
  starts), makes σ_min/σ_max of the reference Jacobian ~0;
* completeness: rank-deficient configurations found independently (a least-squares solve
  of the reference's maximal minors from random starts, then checked by SVD) each satisfy
  some reported condition;
* layout: the keys and shapes of the answer match the spec (J n×m, det or manipulability,
  singularities a list of mappings or strings), and the numeric J matches the reference.

`random_case(family, rng)` makes one case: a `Case` (the YAML text, the reference Jacobian as a
function of q, the joint kinds). `check_case(case)` solves it and returns the list of problems
found (empty when the answer passes). Families: see `FAMILIES`.
"""

from __future__ import annotations

import itertools
import json
import math
from dataclasses import dataclass, field

import numpy as np
import sympy as sp

PI2 = math.pi / 2

__all__ = ["Case", "FAMILIES", "random_case", "solve_case", "check_answer", "check_case"]


@dataclass
class Row:
    kind: str            # "R" or "P"
    a: float = 0.0
    d: float = 0.0       # constant d (revolute) / offset added to the joint (prismatic: unused)
    alpha: float = 0.0
    theta: float = 0.0   # constant θ offset (revolute: added to q; prismatic: the fixed θ)


@dataclass
class Case:
    name: str
    family: str
    rows: list
    convention: str = "standard"
    tool: float = 0.0                 # a tool frame Tz(tool) after the last row (0: none)
    geometric: bool = True
    rows_out: list | None = None      # the reference's rows kept (None: all 6 / the first 3)
    coordinates: list | None = None   # YAML coordinates (None: the default)
    at: list = field(default_factory=list)
    limits_free: bool = True

    @property
    def n(self):
        return len(self.rows)

    def kinds(self):
        return ["revolute" if r.kind == "R" else "prismatic" for r in self.rows]


# ---------------------------------------------------------------------------
# YAML

def _num(x: float) -> str:
    for k, txt in ((0, "0"), (PI2, "pi/2"), (-PI2, "-pi/2"), (math.pi, "pi")):
        if abs(x - k) < 1e-15:
            return txt
    return repr(round(x, 6))


def yaml_text(case: Case) -> str:
    params, rows = {}, []
    for i, r in enumerate(case.rows, 1):
        q = f"q{i}"
        ent = {}
        for key in ("a", "d"):
            v = getattr(r, key)
            if key == "d" and r.kind == "P":
                ent["d"] = q if abs(v) < 1e-15 else f"{q} + d{i}"
                if abs(v) >= 1e-15:
                    params[f"d{i}"] = v
                continue
            if abs(v) < 1e-15:
                ent[key] = "0"
            else:
                params[f"{key}{i}"] = v
                ent[key] = f"{key}{i}"
        ent["alpha"] = _num(r.alpha)
        if r.kind == "R":
            ent["theta"] = q if abs(r.theta) < 1e-15 else f"{q} + {_num(r.theta)}"
        else:
            ent["theta"] = _num(r.theta)
        rows.append(ent)
    out = [f"robosolve: 1", f"name: {case.name}", "parameters:"]
    out += [f"  {k}: {_num(v)}" for k, v in params.items()]
    if case.tool:
        out.append(f"  dt: {_num(case.tool)}")
    if not params and not case.tool:
        out[-1] = "parameters: {}"
    out.append("joints:")
    for i, r in enumerate(case.rows, 1):
        out.append(f"  - {{name: q{i}, type: {'revolute' if r.kind == 'R' else 'prismatic'}}}")
    out += ["dh:", f"  convention: {case.convention}", "  rows:"]
    order = ("theta", "d", "a", "alpha") if case.convention == "standard" else ("alpha", "a", "theta", "d")
    for ent in rows:
        out.append("    - {" + ", ".join(f"{k}: {ent[k]}" for k in order) + "}")
    if case.tool:
        out += ["frames:", f'  T: {{parent: "{case.n}", pose: "Tz(dt)"}}']
    at = ", ".join(f"q{i}: {_num(v)}" for i, v in enumerate(case.at, 1))
    opts = "geometric: true, " if case.geometric else ""
    if case.coordinates:
        opts += "coordinates: [" + ", ".join(case.coordinates) + "], "
    out += ["questions:", f"  - {{type: jacobian, {opts}at: {{{at}}}}}", ""]
    return "\n".join(out)


# ---------------------------------------------------------------------------
# the reference

def reference(case: Case):
    """q -> the reference Jacobian (numpy), Robotics Toolbox's jacob0 of the same table."""
    import roboticstoolbox as rtb
    from spatialmath import SE3

    links = []
    for r in case.rows:
        if case.convention == "standard":
            links.append(rtb.RevoluteDH(d=r.d, a=r.a, alpha=r.alpha, offset=r.theta) if r.kind == "R"
                         else rtb.PrismaticDH(theta=r.theta, a=r.a, alpha=r.alpha, offset=r.d))
        else:
            links.append(rtb.RevoluteMDH(d=r.d, a=r.a, alpha=r.alpha, offset=r.theta) if r.kind == "R"
                         else rtb.PrismaticMDH(theta=r.theta, a=r.a, alpha=r.alpha, offset=r.d))
    robot = rtb.DHRobot(links, tool=SE3.Tz(case.tool) if case.tool else None)
    keep = case.rows_out if case.rows_out is not None else (list(range(6)) if case.geometric else [0, 1, 2])
    return lambda q: robot.jacob0(np.asarray(q, dtype=float))[keep, :]


def ratio(J) -> float:
    sv = np.linalg.svd(J, compute_uv=False)
    return float(sv[-1] / sv[0]) if sv[0] > 0 else 0.0


def minors(J) -> np.ndarray:
    m, n = J.shape
    k = min(m, n)
    if m == n:
        return np.array([np.linalg.det(J)])
    if m < n:
        return np.array([np.linalg.det(J[:, list(c)]) for c in itertools.combinations(range(n), k)])
    return np.array([np.linalg.det(J[list(c), :]) for c in itertools.combinations(range(m), k)])


# ---------------------------------------------------------------------------
# random robots

def _len(rng, lo=0.1, hi=0.8):
    return round(float(rng.uniform(lo, hi) * rng.choice([-1, 1])), 4)


def _maybe(rng, p, lo=0.05, hi=0.6):
    return _len(rng, lo, hi) if rng.random() < p else 0.0


def _offset(rng, p=0.3):
    return float(rng.choice([PI2, -PI2, math.pi])) if rng.random() < p else 0.0


def _sign(rng):
    return float(rng.choice([PI2, -PI2]))


def fam_spherical(rng):
    """6R, standard DH, PUMA / KUKA / ABB style arm (offsets random) with a spherical wrist."""
    rows = [Row("R", a=_maybe(rng, 0.5), d=_maybe(rng, 0.6), alpha=_sign(rng), theta=_offset(rng)),
            Row("R", a=_len(rng), d=_maybe(rng, 0.4), alpha=0.0, theta=_offset(rng)),
            Row("R", a=_maybe(rng, 0.5), d=_maybe(rng, 0.3), alpha=_sign(rng), theta=_offset(rng)),
            Row("R", d=_len(rng), alpha=_sign(rng), theta=_offset(rng, 0.15)),
            Row("R", alpha=_sign(rng), theta=_offset(rng, 0.15)),
            Row("R", d=_maybe(rng, 0.7), theta=_offset(rng, 0.15))]
    return rows, "standard", 0.0


def fam_spherical_mdh(rng):
    """6R, modified DH, spherical wrist, a tool frame."""
    rows = [Row("R", d=_maybe(rng, 0.5), theta=_offset(rng)),
            Row("R", a=_maybe(rng, 0.5), d=_maybe(rng, 0.4), alpha=_sign(rng), theta=_offset(rng)),
            Row("R", a=_len(rng), d=_maybe(rng, 0.3), theta=_offset(rng)),
            Row("R", a=_maybe(rng, 0.5), d=_len(rng), alpha=_sign(rng), theta=_offset(rng, 0.15)),
            Row("R", alpha=_sign(rng), theta=_offset(rng, 0.15)),
            Row("R", alpha=_sign(rng), theta=_offset(rng, 0.15))]
    return rows, "modified", _maybe(rng, 0.7)


def fam_ur(rng):
    """6R, UR family: joints 2, 3, 4 parallel, offset wrist, random lengths and signs."""
    rows = [Row("R", d=_len(rng), alpha=_sign(rng)),
            Row("R", a=_len(rng), d=_maybe(rng, 0.3)),
            Row("R", a=_len(rng), d=_maybe(rng, 0.3)),
            Row("R", d=_len(rng), alpha=_sign(rng)),
            Row("R", d=_len(rng), alpha=_sign(rng)),
            Row("R", d=_maybe(rng, 0.8))]
    return rows, "standard", 0.0


def fam_stanford(rng):
    """Stanford arm: R R P with a spherical wrist."""
    rows = [Row("R", d=_maybe(rng, 0.5), alpha=-PI2),
            Row("R", d=_maybe(rng, 0.8), alpha=PI2),
            Row("P", theta=float(rng.choice([0.0, -PI2])), d=_maybe(rng, 0.3)),
            Row("R", alpha=-PI2),
            Row("R", alpha=PI2),
            Row("R", d=_maybe(rng, 0.7))]
    return rows, "standard", 0.0


def fam_general6(rng):
    """6R with random right-angle / parallel twists and random offsets (no special wrist)."""
    rows = [Row("R", a=_maybe(rng, 0.5), d=_maybe(rng, 0.5),
                alpha=float(rng.choice([0.0, PI2, -PI2])), theta=_offset(rng, 0.2)) for _ in range(6)]
    return rows, str(rng.choice(["standard", "modified"])), 0.0


def fam_arm(n):
    def make(rng):
        """nR spatial arm (position Jacobian of the flange, 3×n)."""
        rows = [Row("R", d=_maybe(rng, 0.5), a=_maybe(rng, 0.7), alpha=float(rng.choice([0.0, PI2, -PI2])),
                    theta=_offset(rng, 0.2)) for _ in range(n)]
        if all(r.a == 0 for r in rows):
            rows[-1].a = _len(rng)
        return rows, str(rng.choice(["standard", "modified"])), _maybe(rng, 0.3)
    return make


def fam_planar(n):
    def make(rng):
        """nR planar arm (x, y of the flange: 2×n)."""
        rows = [Row("R", a=_len(rng), theta=_offset(rng, 0.2)) for _ in range(n)]
        return rows, "standard", 0.0
    return make


def fam_scara(rng):
    """SCARA: R R P R (position 3×4), random lengths."""
    rows = [Row("R", a=_len(rng), d=_maybe(rng, 0.5)),
            Row("R", a=_len(rng), alpha=float(rng.choice([0.0, math.pi]))),
            Row("P"),
            Row("R", d=_maybe(rng, 0.3))]
    return rows, "standard", 0.0


FAMILIES = {
    "spherical": (fam_spherical, True, None),
    "spherical_mdh": (fam_spherical_mdh, True, None),
    "ur": (fam_ur, True, None),
    "stanford": (fam_stanford, True, None),
    "general6": (fam_general6, True, None),
    "flange6": (fam_spherical, False, None),        # 3×6 position Jacobian of a 6R flange
    "ur_flange": (fam_ur, False, None),
    "arm3": (fam_arm(3), False, None),
    "arm4": (fam_arm(4), False, None),
    "arm5": (fam_arm(5), False, None),
    "planar2": (fam_planar(2), False, [0, 1]),
    "planar3": (fam_planar(3), False, [0, 1]),
    "planar3_pose": (fam_planar(3), False, [0, 1, 5]),
    "scara": (fam_scara, False, None),
    "seven": (None, True, None),                     # 6×7: a spherical arm plus a joint
}


def random_case(family: str, rng, index: int = 0) -> Case:
    make, geometric, rows_out = FAMILIES[family]
    if family == "seven":
        rows, conv, tool = fam_spherical(rng)
        rows.insert(int(rng.integers(1, 4)), Row("R", a=_maybe(rng, 0.5), d=_len(rng), alpha=_sign(rng)))
    else:
        rows, conv, tool = make(rng)
    case = Case(f"probe-{family.replace('_', '-')}-{index}", family, rows, conv, tool, geometric, rows_out)
    if rows_out == [0, 1]:
        case.coordinates = ["E.x", "E.y"]
    elif rows_out == [0, 1, 5]:
        case.coordinates = ["E.x", "E.y", "q1 + q2 + q3"]
    case.at = [round(float(x), 3) for x in rng.uniform(-2.5, 2.5, case.n)]
    return case


# ---------------------------------------------------------------------------
# solving and reading the answer

def solve_case(case: Case) -> dict:
    """results.json's answer of the jacobian question (through the whole pipeline)."""
    from robosolve.run.execution import make_task, solve_task

    res = solve_task(make_task(yaml_text(case), f"{case.name}.yaml"))
    files = getattr(res, "files", {}) or {}
    raw = files.get("results.json")
    if raw is None:
        return {"error": f"no results.json: {getattr(res, 'messages', None)}"}
    data = json.loads(raw)
    (ans,) = data["answers"].values()
    return ans


def _split(text: str) -> list[str]:
    out, depth, cur = [], 0, ""
    for ch in text:
        if ch in "([{":
            depth += 1
        elif ch in ")]}":
            depth -= 1
        if ch == "," and depth == 0:
            out.append(cur.strip())
            cur = ""
        else:
            cur += ch
    if cur.strip():
        out.append(cur.strip())
    return out


def parse_condition(cond, case: Case):
    """[(kind, expr)]: kind 'angle' (q − v, wrapped), 'length' (q − v) or 'eq' (expr = 0),
    every expression in the joint symbols q1..qn with the parameters' values."""
    q = sp.symbols(f"q1:{case.n + 1}")
    names = {s.name: s for s in q}
    params = _param_values(case)
    loc = dict(names)
    loc.update({k: sp.Symbol(k) for k in params})
    sub = {sp.Symbol(k): v for k, v in params.items()}
    parts = []
    items = cond.items() if isinstance(cond, dict) else [p.split("=", 1) for p in _split(cond)]
    for lhs, rhs in items:
        lhs = lhs.strip()
        if lhs in names:
            v = sp.sympify(rhs, locals=loc).xreplace(sub)
            kind = "angle" if case.rows[int(lhs[1:]) - 1].kind == "R" else "length"
            parts.append((kind, names[lhs] - v))
        else:
            e = sp.sympify(lhs, locals=loc) - sp.sympify(rhs, locals=loc)
            parts.append(("eq", e.xreplace(sub)))
    return q, parts


def _param_values(case: Case) -> dict:
    out = {}
    for i, r in enumerate(case.rows, 1):
        for key in ("a", "d"):
            v = getattr(r, key)
            if abs(v) >= 1e-15:
                out[f"{key}{i}"] = v
    if case.tool:
        out["dt"] = case.tool
    return out


def residual_function(cond, case: Case):
    q, parts = parse_condition(cond, case)
    exprs = []
    for kind, e in parts:
        exprs.append(2 * sp.sin(e / 2) if kind == "angle" else e)
    f = sp.lambdify([q], exprs, "numpy")

    def res(x):
        v = np.asarray(f(np.asarray(x, dtype=float)), dtype=complex).reshape(-1)
        return v
    return res


def points_on(cond, case: Case, rng, count=4, tries=60):
    from scipy.optimize import least_squares

    res = residual_function(cond, case)
    out = []
    for _ in range(tries):
        x0 = rng.uniform(-math.pi, math.pi, case.n)
        try:
            r0 = res(x0)
        except (ValueError, ZeroDivisionError, TypeError):
            continue
        if np.any(np.abs(r0.imag) > 1e-12):
            # a value that is not real here (acos of more than 1): try another start
            continue
        try:
            sol = least_squares(lambda x: res(x).real, x0, xtol=1e-15, ftol=1e-15, gtol=1e-15)
        except ValueError:
            continue
        r = res(sol.x)
        if np.max(np.abs(r)) < 1e-11:
            out.append(sol.x)
            if len(out) == count:
                break
    return out


def singular_points(case: Case, rng, starts=40):
    """Rank-deficient configurations of the reference, found by a least-squares solve of its
    maximal minors (normalised) from random starts, kept when σ_min/σ_max < 1e-9."""
    from scipy.optimize import least_squares

    jac = reference(case)
    out = []
    for _ in range(starts):
        x0 = rng.uniform(-math.pi, math.pi, case.n)
        scale = max(1e-300, np.max(np.abs(minors(jac(x0)))))
        sol = least_squares(lambda x: minors(jac(x)) / scale, x0, xtol=1e-15, ftol=1e-15, gtol=1e-15,
                            max_nfev=400 * case.n)
        if ratio(jac(sol.x)) < 1e-9:
            x = np.array(sol.x)
            for i, r in enumerate(case.rows):
                if r.kind == "R":
                    x[i] = math.remainder(x[i], 2 * math.pi)
            out.append(x)
    return out


def satisfies(cond, case: Case, x, tol=1e-3) -> bool:
    """x lies on the condition: a least-squares solve of its equations from x ends within `tol`
    of x (x itself is only accurate to about σ_min, so a residual test alone is too strict
    where a factor is squared)."""
    from scipy.optimize import least_squares

    try:
        res = residual_function(cond, case)
        r0 = res(x)
    except (ValueError, ZeroDivisionError, TypeError):
        return False
    if not np.all(np.isfinite(r0)) or np.any(np.abs(r0.imag) > 1e-9):
        return False
    if np.max(np.abs(r0)) < 1e-9:
        return True
    try:
        sol = least_squares(lambda y: res(y).real, x, xtol=1e-15, ftol=1e-15, gtol=1e-15)
    except ValueError:
        return False
    return bool(np.max(np.abs(res(sol.x))) < 1e-10 and np.max(np.abs(sol.x - x)) < tol)


def _every_configuration(case: Case, rng) -> float:
    jac = reference(case)
    return max(ratio(jac(rng.uniform(-math.pi, math.pi, case.n))) for _ in range(8))


def check_answer(case: Case, ans: dict, rng, starts=40) -> list[str]:
    """The problems of one answer (empty: it passes)."""
    issues = []
    jac = reference(case)
    m = len(case.rows_out) if case.rows_out is not None else (6 if case.geometric else 3)
    n = case.n
    if "error" in ans:
        return [f"error: {ans['error']}"]
    num, sym = ans.get("numeric", {}), ans.get("symbolic", {})
    J = np.array(num.get("J"), dtype=float)
    if J.shape != (m, n):
        issues.append(f"numeric J has shape {J.shape}, expected {(m, n)}")
    else:
        ref = jac(case.at)
        err = np.max(np.abs(J - ref))
        if err > 1e-9 * max(1.0, np.max(np.abs(ref))):
            issues.append(f"numeric J differs from jacob0 by {err:.3g}")
    if m == n:
        if "det" not in num:
            issues.append("no numeric det for a square J")
        elif abs(num["det"] - np.linalg.det(jac(case.at))) > 1e-8:
            issues.append(f"numeric det {num['det']} vs {np.linalg.det(jac(case.at))}")
    else:
        if "manipulability" not in num:
            issues.append("no numeric manipulability for a wide J")
        else:
            sv = np.linalg.svd(jac(case.at), compute_uv=False)
            if abs(num["manipulability"] - float(np.prod(sv))) > 1e-8:
                issues.append(f"numeric manipulability {num['manipulability']} vs {np.prod(sv)}")
    conds = sym.get("singularities")
    notes = " ".join(ans.get("notes", []))
    if conds is None:
        if "smallest singular value" not in notes:
            issues.append("no singularities and no σ_min note")
        return issues
    if not isinstance(conds, list) or not all(isinstance(c, (dict, str)) for c in conds):
        issues.append(f"singularities layout: {conds!r}")
        return issues
    # soundness
    for c in conds:
        if isinstance(c, dict) and not c:
            worst = _every_configuration(case, rng)
            if worst > 1e-8:
                issues.append(f"UNSOUND 'every configuration': σ_min/σ_max = {worst:.3g} at random q")
            continue
        try:
            pts = points_on(c, case, rng)
        except (sp.SympifyError, SyntaxError, TypeError) as exc:
            issues.append(f"unparseable condition {c!r}: {exc}")
            continue
        if not pts:
            issues.append(f"no real configuration found on {c!r}")
            continue
        # the median: a point found near where two components of an equation family meet is
        # only as accurate as the square root of the residual
        worst = float(np.median([ratio(jac(x)) for x in pts]))
        if worst > 1e-8:
            issues.append(f"UNSOUND {c!r}: σ_min/σ_max = {worst:.3g} on it")
    # completeness
    if any(isinstance(c, dict) and not c for c in conds):
        return issues
    missed = []
    for x in singular_points(case, rng, starts):
        if not any(satisfies(c, case, x) for c in conds):
            missed.append(x)
    if missed:
        issues.append(f"MISSED {len(missed)} singular configurations, e.g. q = {np.round(missed[0], 6).tolist()}")
    return issues


def check_case(case: Case, rng=None, starts=40) -> tuple[dict, list[str]]:
    rng = rng if rng is not None else np.random.default_rng(0)
    ans = solve_case(case)
    return ans, check_answer(case, ans, rng, starts)
