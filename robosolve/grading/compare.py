"""Compare an evaluated given tree with an evaluated expected tree, by answer kind.

Both trees hold numpy arrays (one value per sample point) where the answer has numbers.
`compare(ak, given, expected, rules)` returns an `Outcome`: right or not, the labels of
the wrong entries, a shape mismatch, or the matching counts of a set. The rules of
grading.md: |given − expected| ≤ atol + rtol·|expected| at every point; angles modulo 2π;
equations up to one non-zero constant factor; sets without order (a maximum matching);
ellipsoid axes up to the sign of each vector.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from robosolve.grading.values import MAP_KINDS, Equation, Pieces
from robosolve.load.expressions import did_you_mean
from robosolve.questions import registry as R

TWO_PI = 2 * math.pi


@dataclass(frozen=True)
class Tolerance:
    rtol: float = 0.005
    atol: float = 1e-6


@dataclass
class Rules:
    """How leaves are compared: tolerance, the points used, which names are angles."""

    tol: Tolerance
    mask: np.ndarray                     # the sample points taken into account
    revolute: frozenset = frozenset()    # joint names whose values are angles
    fixed: object = None                 # mask of the points that keep the parameters at their values


@dataclass
class Outcome:
    ok: bool
    wrong: list = field(default_factory=list)   # labels of wrong entries, in order
    shape: str = ""                  # a layout that differs from the expected one
    unknown: str = ""                # a name the answer cannot have (e.g. a joint that does not exist)
    where: list = field(default_factory=list)   # index paths of the first wrong entries (vectors, matrices, maps)
    matched: int = 0                 # sets: expected elements matched by a given one
    n_given: int = 0
    n_expected: int = 0

    @staticmethod
    def of(wrong: list) -> "Outcome":
        return Outcome(not wrong, wrong)


def is_number(x) -> bool:
    return isinstance(x, np.ndarray)


def negate(tree):
    """−tree for every number of an evaluated tree (equations, null, bools unchanged)."""
    if isinstance(tree, dict):
        return {k: negate(v) for k, v in tree.items()}
    if isinstance(tree, list):
        return [negate(v) for v in tree]
    if isinstance(tree, tuple):
        return tuple(negate(v) for v in tree)
    if isinstance(tree, Pieces):
        return Pieces(tuple(negate(v) for v in tree.parts), tree.intervals)
    return -tree if is_number(tree) else tree


def leaf_ok(g, e, angle: bool, rules: Rules) -> bool:
    if isinstance(e, Pieces) or isinstance(g, Pieces):       # a profile: right on every interval
        return (isinstance(e, Pieces) and isinstance(g, Pieces) and len(g.parts) == len(e.parts)
                and all(leaf_ok(a, b, angle, rules) for a, b in zip(g.parts, e.parts)))
    if isinstance(e, Equation) or isinstance(g, Equation):
        if not (isinstance(e, Equation) and isinstance(g, Equation)):
            return False
        return equation_ok(g.residual, e.residual, rules)
    if not (is_number(g) and is_number(e)):
        return g == e if not (is_number(g) or is_number(e)) else False
    m = rules.mask
    gv, ev = g[m], e[m]
    if not np.all(np.isfinite(gv)):
        return False
    d = gv - ev
    if angle:
        d = np.mod(d + math.pi, TWO_PI) - math.pi
    return bool(np.all(np.abs(d) <= rules.tol.atol + rules.tol.rtol * np.abs(ev)))


def equation_ok(g, e, rules: Rules) -> bool:
    """g = c·e at every point, for one constant c ≠ 0 (both residuals zero is right too)."""
    m = rules.mask
    gv, ev = g[m], e[m]
    if not np.all(np.isfinite(gv)):
        return False
    scale = max(float(np.max(np.abs(ev))), float(np.max(np.abs(gv))), 1e-300)
    if float(np.max(np.abs(ev))) <= rules.tol.atol:
        return float(np.max(np.abs(gv))) <= rules.tol.atol
    c = float(np.dot(gv, ev) / np.dot(ev, ev))
    if abs(c) * float(np.max(np.abs(ev))) <= 1e-9 * scale:
        return False
    return bool(np.all(np.abs(gv - c * ev) <= rules.tol.atol + rules.tol.rtol * np.abs(c * ev)))


# -- containers ---------------------------------------------------------------
def _vector(g, e, angle, rules, what="entry") -> Outcome:
    if not isinstance(g, list) or len(g) != len(e):
        n = len(g) if isinstance(g, list) else 1
        return Outcome(False, shape=f"{n} entries where {len(e)} are expected")
    bad = [i for i, (a, b) in enumerate(zip(g, e)) if not leaf_ok(a, b, angle, rules)]
    return Outcome(not bad, [f"{what} {i + 1}" for i in bad], where=[(i,) for i in bad])


def shape_of(m) -> tuple:
    return (len(m), len(m[0]) if m else 0)


def _matrix(g, e, rules, prefix="") -> Outcome:
    if shape_of(g) != shape_of(e):
        return Outcome(False, shape="{}x{} where {}x{} is expected".format(*shape_of(g), *shape_of(e)))
    bad = [(i, j) for i, (rg, re_) in enumerate(zip(g, e))
           for j, (a, b) in enumerate(zip(rg, re_)) if not leaf_ok(a, b, False, rules)]
    return Outcome(not bad, [f"{prefix}entry ({i + 1}, {j + 1})" for i, j in bad], where=bad)


def _names(g: dict, e: dict) -> tuple[str, list]:
    """(unknown-name message, expected names missing from g)."""
    for k in g:
        if k not in e:
            return (f"'{k}' is not one of the expected names ({', '.join(e)})" + did_you_mean(k, e)), []
    return "", [k for k in e if k not in g]


def _map(g, e, angle_of, rules, leaf=None) -> Outcome:
    if not isinstance(g, dict):
        return Outcome(False, shape="a mapping name -> value is expected")
    unknown, missing = _names(g, e)
    if unknown:
        return Outcome(False, unknown=unknown)
    wrong, where = [], []          # the entries of `where` label the first ones of `wrong`
    for k in e:
        if k in g:
            if leaf is not None:
                sub = leaf(g[k], e[k])
                if not sub.ok:
                    if sub.shape or sub.unknown:
                        return Outcome(False, shape=f"{k}: {sub.shape}" if sub.shape else "",
                                       unknown=sub.unknown)
                    wrong.append(k if not sub.wrong else f"{k} ({', '.join(sub.wrong)})")
            elif not leaf_ok(g[k], e[k], angle_of(k), rules):
                wrong.append(k)
                where.append((k,))
    wrong += [f"no value for {k}" for k in missing]
    return Outcome(not wrong, wrong, where=where)


def _element_ok(g, e, angle_of, rules) -> bool:
    if isinstance(e, dict):
        return isinstance(g, dict) and set(g) == set(e) and all(
            leaf_ok(g[k], e[k], angle_of(k), rules) for k in e)
    if isinstance(e, tuple):      # equations of a singular condition
        return isinstance(g, tuple) and len(g) == len(e) and all(
            leaf_ok(a, b, False, rules) for a, b in zip(g, e))
    return isinstance(g, list) and len(g) == len(e) and all(
        leaf_ok(a, b, angle_of(None), rules) for a, b in zip(g, e))


def value_rules(rules: Rules) -> Rules:
    """The rules of values compared as numbers (singular conditions, grading.md): at the points
    that keep the parameters at their values, when the points move them too."""
    if rules.fixed is None or not (rules.mask & rules.fixed).any():
        return rules
    return Rules(rules.tol, rules.mask & rules.fixed, rules.revolute)


def max_matching(adj: list[list[bool]]) -> int:
    """Size of a maximum matching given[i] -> expected[j] (augmenting paths; sets are small)."""
    n_exp = len(adj[0]) if adj else 0
    owner = [-1] * n_exp

    def augment(i, seen):
        for j in range(n_exp):
            if adj[i][j] and not seen[j]:
                seen[j] = True
                if owner[j] < 0 or augment(owner[j], seen):
                    owner[j] = i
                    return True
        return False

    return sum(1 for i in range(len(adj)) if augment(i, [False] * n_exp))


def _set(g, e, angle_of, rules, by_value: bool = False) -> Outcome:
    if not isinstance(g, list):
        return Outcome(False, shape="a list is expected")
    values = value_rules(rules) if by_value else rules
    adj = [[_element_ok(a, b, angle_of, values if isinstance(b, dict) else rules) for b in e] for a in g]
    matched = max_matching(adj) if g and e else 0
    ok = matched == len(e) == len(g)
    wrong = [] if ok else [f"{matched} of the {len(e)} expected elements matched, {len(g)} given"]
    if not ok:
        wrong += _elements_short(g, e)
    return Outcome(ok, wrong, matched=matched, n_given=len(g), n_expected=len(e))


def _elements_short(g: list, e: list) -> list[str]:
    """"element 2: no value for q2" for each given mapping that leaves out a joint every
    expected element has (an IK solution; singular conditions name different joints)."""
    keys = {tuple(sorted(b)) for b in e if isinstance(b, dict)}
    if len(keys) != 1 or len(e) != sum(isinstance(b, dict) for b in e):
        return []
    names = [k for k in e[0]]
    return [f"element {i + 1}: no value for " + ", ".join(k for k in names if k not in a)
            for i, a in enumerate(g) if isinstance(a, dict) and any(k not in a for k in names)]


def _axes(g, e, rules, sign_free: bool) -> Outcome:
    if not isinstance(g, list) or len(g) != len(e):
        return Outcome(False, shape=f"{len(g) if isinstance(g, list) else 1} axes where {len(e)} are expected")
    wrong = []
    for i, (a, b) in enumerate(zip(g, e)):
        if a is None or b is None:      # an infinite semi-axis: null, and only null, is right
            if a is not b:
                wrong.append(f"axis {i + 1}")
            continue
        if not isinstance(a, list) or len(a) != len(b):
            return Outcome(False, shape=f"axis {i + 1} has {len(a) if isinstance(a, list) else 1} "
                                        f"components where {len(b)} are expected")
        plus = all(leaf_ok(x, y, False, rules) for x, y in zip(a, b))
        minus = sign_free and all(leaf_ok(x, negate(y), False, rules) for x, y in zip(a, b))
        if not (plus or minus):
            wrong.append(f"axis {i + 1}")
    return Outcome.of(wrong)


def _record(ak, g, e, rules) -> Outcome:
    if not isinstance(g, dict):
        return Outcome(False, shape="a mapping of " + ", ".join(e) + " is expected")
    wrong, sets = [], []
    for name, ev in e.items():
        f = ak.field(name)
        if name not in g:
            if ev is not None:            # (a field the reference leaves null may be left out)
                wrong.append(f"no value for {name}")
            continue
        sub = compare(f, g[name], ev, rules)
        if sub.unknown or sub.shape:
            return Outcome(False, shape=f"{name}: {sub.shape}", unknown=sub.unknown)
        if not sub.ok:
            wrong.append(name if not sub.wrong else f"{name} ({', '.join(sub.wrong)})")
            sets += [sub] if sub.n_expected or sub.n_given else []
    out = Outcome.of(wrong)
    if len(wrong) == 1 and len(sets) == 1:     # only a set field wrong: its counts (incomplete_set …)
        out.matched, out.n_given, out.n_expected = sets[0].matched, sets[0].n_given, sets[0].n_expected
    return out


def compare(ak, g, e, rules: Rules) -> Outcome:
    """Compare the evaluated given tree `g` with the evaluated expected tree `e` of key `ak`."""
    kind = ak.kind

    def angle_of(name):
        if not ak.angle:
            return False
        if kind in (R.JOINT_MAP, R.JOINT_MAP_SET, R.JOINT_MAP_LIST):
            return name in rules.revolute
        return True

    if kind in (R.SCALAR, R.BOOL, R.TEXT) or e is None or g is None:     # (null: only null is right)
        return Outcome.of([] if leaf_ok(g, e, angle_of(None), rules) else ["the value"])
    if kind == R.VECTOR:
        return _vector(g, e, angle_of(None), rules)
    if kind == R.MATRIX:
        if not isinstance(g, list) or not g or not isinstance(g[0], list):
            return Outcome(False, shape="a matrix (list of rows) is expected")
        return _matrix(g, e, rules)
    if kind == R.MATRIX_LIST:
        if not isinstance(g, list) or len(g) != len(e):
            return Outcome(False, shape=f"{len(g) if isinstance(g, list) else 1} matrices where "
                                        f"{len(e)} are expected")
        wrong = []
        for i, (a, b) in enumerate(zip(g, e)):
            sub = _matrix(a, b, rules, prefix=f"matrix {i + 1} ")
            if sub.shape:
                return Outcome(False, shape=f"matrix {i + 1}: {sub.shape}")
            wrong += sub.wrong
        return Outcome.of(wrong)
    if kind in MAP_KINDS:
        return _map(g, e, angle_of, rules)
    if kind == R.MATRIX_MAP:
        return _map(g, e, angle_of, rules, leaf=lambda a, b: _matrix(a, b, rules))
    if kind == R.ACTUATOR_RECORDS:
        return _map(g, e, angle_of, rules,
                    leaf=lambda a, b: _map(a, b, lambda n: False, rules))
    if ak.unordered:
        return _set(g, e, angle_of, rules, ak.by_value)
    if kind == R.JOINT_MAP_LIST:
        if not isinstance(g, list) or len(g) != len(e):
            return Outcome(False, shape=f"{len(g) if isinstance(g, list) else 1} elements where "
                                        f"{len(e)} are expected")
        return Outcome.of([f"element {i + 1}" for i, (a, b) in enumerate(zip(g, e))
                           if not _element_ok(a, b, angle_of, rules)])
    if kind == R.AXES:
        return _axes(g, e, rules, ak.sign_free)
    if kind == R.EQUATIONS:
        return _vector(g, e, False, rules, what="equation")
    if kind == R.RECORD:
        return _record(ak, g, e, rules)
    return Outcome(False, ["this kind of answer cannot be compared"])


def equivalents(ak, g, e, rules: Rules) -> list:
    """The other ways of writing the expected rotation that its convention leaves open
    (problem-format.md: an angle in [0, π], η ≥ 0): at an angle of π, the axis −u as well as u;
    at 0, any unit axis (or null, as the reference writes it); a quaternion whose η is 0, −q
    as well as q. Each an evaluated expected tree, for the given `g`."""
    if ak.quaternion and isinstance(e, list) and e and _all_near(e[0], 0.0, rules):
        return [negate(e)]
    if ak.kind == R.RECORD and {f.name for f in ak.fields} == {"solutions", "singular"} and isinstance(e, dict):
        return _singular_euler_representatives(ak.name, g, e, rules)
    if ak.kind != R.RECORD or {f.name for f in ak.fields} != {"axis", "angle"} or not isinstance(e, dict):
        return []
    angle, axis = e.get("angle"), e.get("axis")
    if is_number(angle) and _all_near(np.abs(np.mod(angle + math.pi, TWO_PI) - math.pi), math.pi, rules):
        return [{**e, "axis": negate(axis)}] if axis is not None else []
    given = g.get("axis") if isinstance(g, dict) else None
    if is_number(angle) and _all_near(angle, 0.0, rules) and isinstance(given, list) and len(given) == 3 \
            and all(is_number(x) for x in given):
        norm = np.sqrt(sum(x * x for x in given))
        if _all_near(norm, 1.0, rules):
            return [{**e, "axis": given}]
    return []


def _singular_euler_representatives(convention: str, g, e, rules: Rules) -> list:
    """At a singularity of ZYZ (θ = 0 or π) or roll-pitch-yaw (pitch = ±π/2) the angles are a
    family: the reference writes one representative (the last angle 0), and any member of the
    family written with `singular: true` is the same rotation and right. Each given triple is
    judged by the rotation it makes."""
    if e.get("singular") is not True or not isinstance(g, dict) or g.get("singular") is not True:
        return []
    given, expected = g.get("solutions"), e.get("solutions")
    if not (isinstance(given, list) and isinstance(expected, list) and expected and len(given) == len(expected)):
        return []
    if not all(isinstance(t, list) and len(t) == 3 and all(is_number(a) for a in t) for t in given + expected):
        return []
    target = _euler_rotation(convention, expected[0])
    for triple in given:
        gap = np.abs(_euler_rotation(convention, triple) - target).max(axis=-1)   # per sample point
        if not _all_near(gap, 0.0, rules):
            return []
    return [{**e, "solutions": given}]


def _euler_rotation(convention: str, angles) -> np.ndarray:
    """R of three angles (each a number or an array over the sample points), entries last:
    zyz = Rz(φ)·Ry(θ)·Rz(ψ); rpy [roll, pitch, yaw] = Rz(yaw)·Ry(pitch)·Rx(roll)."""
    a, b, c = (np.asarray(x, dtype=float) for x in angles)

    def rz(t):
        z, o = np.zeros_like(t), np.ones_like(t)
        return np.stack([np.cos(t), -np.sin(t), z, np.sin(t), np.cos(t), z, z, z, o], -1).reshape(t.shape + (3, 3))

    def ry(t):
        z, o = np.zeros_like(t), np.ones_like(t)
        return np.stack([np.cos(t), z, np.sin(t), z, o, z, -np.sin(t), z, np.cos(t)], -1).reshape(t.shape + (3, 3))

    def rx(t):
        z, o = np.zeros_like(t), np.ones_like(t)
        return np.stack([o, z, z, z, np.cos(t), -np.sin(t), z, np.sin(t), np.cos(t)], -1).reshape(t.shape + (3, 3))

    rot = rz(a) @ ry(b) @ rz(c) if convention == "zyz" else rz(c) @ ry(b) @ rx(a)
    return rot.reshape(rot.shape[:-2] + (9,))


def _all_near(values, target: float, rules: Rules) -> bool:
    v = np.asarray(values)[rules.mask]
    return bool(v.size) and bool(np.all(np.abs(v - target) <= rules.tol.atol + rules.tol.rtol * abs(target)))
