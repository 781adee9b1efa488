"""The draw of variant k: a function of (seed, k) only, distinct from variants 1..k-1.

Attempt a of variant k picks, for each varied parameter, the value of index
``H(seed, k, a, name) mod size`` where H is SHA-256 read as an integer: stable on every
machine, Python and numpy version (never Python's `hash()`, whose strings are salted per
process, nor a numpy stream, which numpy does not promise to keep across versions). The
first attempt that meets `require` and differs from every earlier variant is variant k, so
variant k never depends on how many variants are asked for.

When the grid has at most COUNT_LIMIT combinations and 1000 attempts in a row are all rejected
(the grid nearly used up, or a condition that rarely holds), the valid combinations are counted
and variant k is picked among the remaining ones with ``H(seed, k, "remaining")``, so it is found
whenever it exists; when none remains, the count is the error's (fewer distinct variants than
asked). The grid is counted only then: counting checks every combination (an IK search each, a
second apiece for a 6-joint pose), while the draws of a class usually check a few per variant —
and the first attempt that meets `require` is variant k either way, so the draws are the same.
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


class TooFew(Exception):
    """Fewer distinct combinations meet `require` than are asked: `count` of them; `never`: the
    conditions that hold for no combination at all (when none meets `require`)."""

    def __init__(self, count: int, never=()):
        self.count = count
        self.never = list(never)
        super().__init__(count)


class Drawer:
    def __init__(self, spec, checker, seed: int, file: str, count_progress=None):
        self.spec = spec
        self.checker = checker
        self.seed = seed
        self.file = file
        self.count_progress = count_progress   # () -> a progress step, for counting the grid
        self.valid = None          # boolean grid (small grids), once counted
        self.used: set = set()
        self.drawn: list = []

    def count(self, progress=None) -> int | None:
        """Distinct combinations meeting `require`, or None when the grid is too large to count."""
        if self.spec.grid_size > COUNT_LIMIT:
            return None
        if self.valid is None:
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
        if self.spec.grid_size <= COUNT_LIMIT:
            self.count(self.count_progress() if self.count_progress else None)
            remaining = np.flatnonzero(self.valid)
            left = [tuple(int(i) for i in np.unravel_index(f, self.valid.shape)) for f in remaining]
            left = [t for t in left if t not in self.used]
            if left:
                return self._accept(left[stable_int(self.seed, k, "remaining") % len(left)])
            raise TooFew(len(self.used), self.checker.never_met() if not self.used else ())
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
