"""The problem file's `grading:` section (grading.md): tolerances and partial credit.

```yaml
grading:
  rtol: 0.01                                   # tolerances of the comparison
  atol: 1e-6
  partial: {negated: 0.5, transposed: 0.5}     # diagnosis -> share of the key's marks
  entries: proportional                        # matrices / vectors: share of entries right
```

Shares are kept exact (`fractions.Fraction`); a share outside [0, 1] or an unknown
diagnosis is an input error with its line (and a did-you-mean).
"""

from __future__ import annotations

from fractions import Fraction

import sympy as sp

from robosolve.load.expressions import Namespace, did_you_mean

# every diagnosis of grading.md's table, in its order (robosolve/grading/diagnose.py names them)
DIAGNOSES = ("transposed", "negated", "degrees", "inverse", "parameters_substituted",
             "incomplete_set", "extra_in_set", "wrong_shape", "dh_convention", "rows_swapped",
             "end_effector_frame", "quaternion_order")
GRADING_KEYS = ("rtol", "atol", "partial", "entries")
ENTRIES = ("all", "proportional")


def exact_fraction(e) -> Fraction:
    """An exact sympy number as a Fraction (a float by its shortest decimal: 0.5 -> 1/2)."""
    if isinstance(e, sp.Rational):
        return Fraction(int(e.p), int(e.q))
    return Fraction(repr(float(e)))


def read_grading(chk, value) -> dict:
    """The `grading` mapping -> {rtol, atol: float; partial: {diagnosis: Fraction}; entries: str}."""
    if value is None or not chk.mapping(("grading",), value, GRADING_KEYS):
        return {}
    out = {}
    for key in ("rtol", "atol"):
        if key in value:
            number = _number(chk, ("grading", key), value[key])
            if number is not None:
                out[key] = float(number)
    if "partial" in value:
        out["partial"] = _partial(chk, value["partial"])
    if "entries" in value:
        v = value["entries"]
        if v not in ENTRIES:
            chk.error(("grading", "entries"), f"expected one of: {', '.join(ENTRIES)}, got {v!r}"
                      + (did_you_mean(v, ENTRIES) if isinstance(v, str) else ""))
        else:
            out["entries"] = v
    return out


def _number(chk, path, v, upper=None):
    e = chk.expr(path, v, Namespace({}, what="number"))
    if e is None:
        return None
    ok = e.is_number and e.is_real and e.is_finite and e.is_nonnegative
    if ok and upper is not None:
        ok = bool(e <= upper)
    if not ok:
        bound = "a number >= 0" if upper is None else "a share between 0 and 1"
        chk.error(path, f"expected {bound}, got {v!r}")
        return None
    return e


def _partial(chk, value) -> dict:
    path = ("grading", "partial")
    if not isinstance(value, dict):
        chk.error(path, "expected a mapping diagnosis -> share (e.g. {negated: 0.5})")
        return {}
    out = {}
    for name, share in value.items():
        if name not in DIAGNOSES:
            chk.error(path + (name,), f"unknown diagnosis '{name}'" + did_you_mean(str(name), DIAGNOSES)
                      + f" (expected one of: {', '.join(DIAGNOSES)})")
            continue
        e = _number(chk, path + (name,), share, upper=1)
        if e is not None:
            out[name] = exact_fraction(e)
    return out
