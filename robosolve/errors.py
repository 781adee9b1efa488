"""Every exception robosolve raises on purpose, and the exit statuses (`ExitStatus`).

Only the CLI turns these into messages and exit codes.
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import IntEnum


class ExitStatus(IntEnum):
    """The exit statuses of every command (spec §4), in one place."""

    OK = 0              # every question answered (an unreachable IK target is an answer)
    ANSWER_ERROR = 1    # some question answered with `error` (or a golden mismatch, a wrong answer)
    INPUT = 2           # invalid input or usage: nothing written
    SIGINT = 130        # interrupted (Ctrl-C)
    SIGTERM = 143       # terminated


class RobosolveError(Exception):
    """Base class of robosolve's own errors."""


@dataclass(frozen=True)
class InputIssue:
    """One problem of a problem file: where it is and what is wrong."""

    file: str
    line: int
    path: str
    message: str

    def __str__(self) -> str:
        where = f"{self.path}: " if self.path else ""
        line = f":{self.line}" if self.line > 0 else ""  # 0: about the whole file (cannot read it)
        return f"{self.file}{line}: {where}{self.message}"


@dataclass(frozen=True)
class InputWarning(InputIssue):
    """Given data that is accepted but may be a mistake, about `subject` (("body", "link1")):
    `FILE:LINE: where: warning: body 'link1': what` (the report says it too)."""

    subject: tuple = ()

    def __str__(self) -> str:
        where = f"{self.path}: " if self.path else ""
        line = f":{self.line}" if self.line > 0 else ""
        about = f"{self.subject[0]} '{self.subject[1]}': " if self.subject else ""
        return f"{self.file}{line}: {where}warning: {about}{self.message}"


class InputError(RobosolveError):
    """A problem file is invalid; carries every issue found, in file order."""

    def __init__(self, issues: list[InputIssue]):
        self.issues = sorted(issues, key=lambda i: (i.file, i.line, i.path, i.message))
        super().__init__("\n".join(str(i) for i in self.issues))


class SymbolicTimeout(BaseException):
    """A symbolic step exceeded its time limit (the solver then answers numerically).

    A BaseException, so that sympy's internal `except Exception` blocks cannot
    swallow it; `token` identifies the `time_limit` block that expired, so an inner
    block never mistakes an outer block's expiry for its own.
    """

    def __init__(self, message: str = "", token: object = None):
        super().__init__(message)
        self.token = token


class SolverError(RobosolveError):
    """A question cannot be answered; the message becomes the answer's `error`."""


class MissingValues(Exception):
    """Numeric evaluation needs values that are not given (null parameters, joints)."""

    def __init__(self, names):
        self.names = sorted(set(names))
        super().__init__(", ".join(self.names))
