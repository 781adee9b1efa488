"""The draw of variant k: a function of (seed, k) only, distinct from variants 1..k-1.

Attempt a of variant k picks, for each varied parameter, the value of index
``H(seed, k, a, name) mod size`` where H is SHA-256 read as an integer: stable on every
machine, Python and numpy version (never Python's `hash()`, whose strings are salted per
process, nor a numpy stream, which numpy does not promise to keep across versions). The
first attempt that meets `require` and differs from every earlier variant is variant k, so
variant k never depends on how many variants are asked for.

When the grid has at most COUNT_LIMIT combinations, the valid ones are counted first (too
few: an error with the count) and, should 1000 attempts in a row all be rejected (the grid
nearly used up), variant k is picked among the remaining valid combinations with
``H(seed, k, "remaining")``, so it is found whenever it exists.
"""

from __future__ import annotations

import hashlib

import numpy as np

from robosolve.errors import InputError, InputIssue

COUNT_LIMIT = 100_000
MAX_REJECTIONS = 1000


def stable_int(*parts) -> int:
    text = "\x1f".join(str(p) for p in ("robosolve-variants-1",) + parts)
    return int.from_bytes(hashlib.sha256(text.encode("utf-8")).digest(), "big")


def attempt_indices(spec, seed: int, k: int, attempt: int) -> tuple:
    return tuple(stable_int(seed, k, attempt, p.name) % p.size for p in spec.parameters)


class Drawer:
    def __init__(self, spec, checker, seed: int, file: str):
        self.spec = spec
        self.checker = checker
        self.seed = seed
        self.file = file
        self.valid = None          # boolean grid (small grids), after count()
        self.used: set = set()
        self.drawn: list = []

    def count(self, progress=None) -> int | None:
        """Distinct combinations meeting `require`, or None when the grid is too large to count."""
        if self.spec.grid_size > COUNT_LIMIT:
            return None
        self.valid = self.checker.valid_grid(progress)
        return int(self.valid.sum())

    def _ok(self, idx):
        if self.valid is not None:
            return None if self.valid[idx] else self.checker.first_failure(idx)
        return self.checker.first_failure(idx)

    def next(self) -> tuple:
        """Variant k = len(drawn) + 1: its index tuple (raises InputError when none is found)."""
        k = len(self.drawn) + 1
        failures: dict = {}
        duplicates = 0
        for attempt in range(MAX_REJECTIONS):
            idx = attempt_indices(self.spec, self.seed, k, attempt)
            bad = self._ok(idx)
            if bad is None and idx not in self.used:
                return self._accept(idx)
            if bad is None:
                duplicates += 1
            else:
                failures[id(bad)] = (failures.get(id(bad), (0, bad))[0] + 1, bad)
        if self.valid is not None:
            remaining = np.flatnonzero(self.valid)
            left = [tuple(int(i) for i in np.unravel_index(f, self.valid.shape)) for f in remaining]
            left = [t for t in left if t not in self.used]
            if left:
                return self._accept(left[stable_int(self.seed, k, "remaining") % len(left)])
        where = f"variant {k}"
        if failures:
            n, worst = max(failures.values(), key=lambda t: t[0])
            raise InputError([InputIssue(
                self.file, worst.line, worst.path,
                f"{where}: {MAX_REJECTIONS} draws in a row are rejected ({n} of them by this condition, "
                f"{worst.text!r}{f'; {duplicates} repeat an earlier variant' if duplicates else ''}): "
                "widen the ranges or relax the condition")])
        raise InputError([InputIssue(
            self.file, self.spec.line, "variants",
            f"{where}: {MAX_REJECTIONS} draws in a row repeat earlier variants: the section allows too "
            "few distinct variants")])

    def _accept(self, idx):
        self.used.add(idx)
        self.drawn.append(idx)
        return idx

    def values(self, idx) -> dict:
        """name -> exact value of a drawn index tuple."""
        return {p.name: p.value(i) for p, i in zip(self.spec.parameters, idx)}
