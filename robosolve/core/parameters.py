"""The one resolution of a problem's parameters: each value that is an expression of other
parameters (``m2: 2*m1``) gets their values, in passes until nothing changes."""

from __future__ import annotations

__all__ = ["resolve_parameters"]


def resolve_parameters(parameters: dict, overrides: dict | None = None, varied=()) -> dict:
    """Parameter symbol -> its value with every other parameter resolved.

    `parameters` maps each symbol to an expression of the parameters, or None (no value:
    the parameter stays a symbol). `overrides` (a question's `at`) replace the values of the
    parameters they name (other keys are ignored). The `varied` symbols count as known (they
    map to themselves, unless overridden): the values are then expressions of them (a variant
    template). A parameter left symbolic (None, or depending on one) is not in the result.
    The result is ordered as the values were resolved: varied first, then pass by pass in the
    file's order."""
    raw = dict(parameters)
    for s, v in (overrides or {}).items():
        if s in raw:
            raw[s] = v
    known = {s: s for s in varied if s not in (overrides or {})}
    pending = {s: e for s, e in raw.items() if s not in known and e is not None}
    progressed = True
    while pending and progressed:
        progressed = False
        for s, e in list(pending.items()):
            if (e.free_symbols & raw.keys()) <= known.keys():
                known[s] = e.xreplace(known)
                pending.pop(s)
                progressed = True
    return known
