"""The mistakes people make (grading.md "Diagnosis"), as transformations of a value.

Each diagnosis turns the expected value (or reads the given one) the way the mistake
does; the first one after which the given value is right names the mistake. The
order is grading.md's: transposed, negated, degrees, inverse, parameters_substituted,
incomplete_set / extra_in_set (wrong_shape is a layout, found by the comparison).
The feedback sentence is in the course's words; a key's registry `hints` add the
course's explanation for that key.
"""

from __future__ import annotations

import math

import numpy as np

from robosolve.grading.compare import Outcome, Rules, compare, is_number, negate
from robosolve.questions import registry as R

ORDER = ("transposed", "negated", "degrees", "inverse", "parameters_substituted",
         "incomplete_set", "extra_in_set", "wrong_shape", "dh_convention", "rows_swapped",
         "end_effector_frame", "quaternion_order")


def transpose(tree):
    return [list(col) for col in zip(*tree)]


def _is_matrix(tree) -> bool:
    return (isinstance(tree, list) and bool(tree) and all(isinstance(r, list) for r in tree)
            and all(is_number(x) for r in tree for x in r))


def invert_pose(tree):
    """The inverse of a 4x4 matrix at every sample point (None when singular)."""
    if not _is_matrix(tree) or len(tree) != 4 or any(len(r) != 4 for r in tree):
        return None
    stack = np.stack([np.stack(r, axis=-1) for r in tree], axis=-2)   # (points, 4, 4)
    try:
        with np.errstate(all="ignore"):
            inv = np.linalg.inv(stack)
    except np.linalg.LinAlgError:
        return None
    return [[inv[:, i, j] for j in range(4)] for i in range(4)]


def map_angles(ak, tree, revolute, fn):
    """Apply `fn` to the angle values of a tree, by the key's schema."""
    if ak.kind == R.RECORD:
        return {k: (map_angles(ak.field(k), v, revolute, fn) if ak.field(k) else v)
                for k, v in tree.items()} if isinstance(tree, dict) else tree
    if not ak.angle:
        return tree
    by_name = ak.kind in (R.JOINT_MAP, R.JOINT_MAP_SET, R.JOINT_MAP_LIST)

    def walk(t, angle):
        if isinstance(t, dict):
            return {k: walk(v, (k in revolute) if by_name else angle) for k, v in t.items()}
        if isinstance(t, list):
            return [walk(v, angle) for v in t]
        if isinstance(t, tuple):
            return tuple(walk(v, angle) for v in t)
        return fn(t) if angle and is_number(t) else t

    return walk(tree, not by_name)


def has_angles(ak) -> bool:
    return ak.angle or any(f.angle for f in ak.fields)


def rows_swapped(tree):
    """[ω; v] for [v; ω]: the lower three rows of a 6-row matrix above the upper three."""
    if _is_matrix(tree) and len(tree) == 6:
        return tree[3:] + tree[:3]
    return None


def quaternion_xyzw(tree):
    """(x, y, z, w) for (w, x, y, z)."""
    if isinstance(tree, list) and len(tree) == 4 and all(is_number(x) for x in tree):
        return tree[1:] + tree[:1]
    return None


def diagnose(ak, g, e, rules: Rules, outcome: Outcome, symbolic: bool, alts: dict | None = None) -> str:
    """The first mistake of ORDER that explains the given value `g`, or ''.

    `alts`: diagnosis -> the evaluated value that mistake gives, for the mistakes that need
    the robot (grading/alternatives.py: dh_convention, end_effector_frame)."""
    def right(gv, ev, r=rules) -> bool:
        o = compare(ak, gv, ev, r)
        return o.ok

    if ak.kind == R.MATRIX and _is_matrix(e) and isinstance(g, list):
        if right(g, transpose(e)):
            return "transposed"
    if outcome.shape:
        return "wrong_shape"
    if outcome.unknown:
        return ""
    if right(g, negate(e)):
        return "negated"
    if has_angles(ak) and right(map_angles(ak, g, rules.revolute, lambda x: x * (math.pi / 180)), e):
        return "degrees"
    if ak.pose:
        inv = invert_pose(e)
        if inv is not None and right(g, inv):
            return "inverse"
    if symbolic and rules.fixed is not None:
        fixed = Rules(rules.tol, rules.mask & rules.fixed, rules.revolute)
        if fixed.mask.any() and right(g, e, fixed):
            return "parameters_substituted"
    if outcome.n_expected or outcome.n_given:
        if outcome.n_given < outcome.n_expected and outcome.matched == outcome.n_given:
            return "incomplete_set"
        if outcome.n_given > outcome.n_expected and outcome.matched == outcome.n_expected:
            return "extra_in_set"
    return _structural(ak, g, e, right, alts or {})


def _structural(ak, g, e, right, alts: dict) -> str:
    """The mistakes of the robot's conventions, in ORDER."""
    for name in ("dh_convention", "rows_swapped", "end_effector_frame", "quaternion_order"):
        if name == "rows_swapped":
            value = rows_swapped(e) if ak.kind == R.MATRIX else None
        elif name == "quaternion_order":
            value = quaternion_xyzw(e) if ak.quaternion else None
        else:
            value = alts.get(name)
        if value is not None and right(g, value):
            return name
    return ""


SENTENCES = {
    "transposed": "this is {symbol} transposed",
    "negated": "this is −{symbol}",
    "degrees": "these angles are in degrees: answers are in radians (write pi/6 or deg(30), not 30)",
    "inverse": "this is the inverse of {symbol}",
    "parameters_substituted": "this is right only at the problem's values of {params}: a symbolic "
                              "answer keeps the parameters as symbols",
    "incomplete_set": "the set is incomplete: {missing} of the {n_expected} expected elements "
                      "{missing_verb} missing",
    "extra_in_set": "the set has {extra} element{extra_s} too many (every expected one is there)",
    "wrong_shape": "{shape}",
    "dh_convention": "this is {symbol} computed with the other DH convention (standard rows "
                     "Rz(θ)·Tz(d)·Tx(a)·Rx(α), modified rows Rx(α)·Tx(a)·Rz(θ)·Tz(d)): the problem's "
                     "rows are read in the convention they are given in",
    "rows_swapped": "the angular rows are above the linear ones: the geometric Jacobian is "
                    "[v; ω] (linear velocity rows first, then ω)",
    "end_effector_frame": "this is {symbol} expressed in frame {frame}: the answer is expressed "
                          "in frame 0 (multiply by ⁰R{frame_sub})",
    "quaternion_order": "the quaternion is written (x, y, z, w): the course writes it "
                        "(η, εx, εy, εz), the scalar part first",
}


def sentence(diagnosis: str, ak, *, symbol: str, frame: str, outcome: Outcome, params: str) -> str:
    missing = outcome.n_expected - outcome.n_given
    extra = outcome.n_given - outcome.n_expected
    text = SENTENCES[diagnosis].format(
        symbol=symbol, frame=frame, params=params or "the parameters", n_expected=outcome.n_expected,
        missing=missing, missing_verb="is" if missing == 1 else "are",
        extra=extra, extra_s="" if extra == 1 else "s", shape=outcome.shape,
        frame_sub=frame.translate(str.maketrans("0123456789", "₀₁₂₃₄₅₆₇₈₉")) if frame.isdigit() else f"[{frame}]")
    hint = ak.hint(diagnosis)
    if hint:
        text += ": " + hint.format(frame=frame, symbol=symbol)
    elif diagnosis == "negated":
        text += " (every sign is the opposite of the expected one)"
    return text
