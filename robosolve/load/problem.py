"""The validated problem: plain dataclasses holding sympy expressions.

Everything here is produced by `robosolve.load.loader.load_problem` and is
already checked: names resolve, references exist, shapes are right.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import sympy as sp

REVOLUTE = "revolute"
PRISMATIC = "prismatic"


@dataclass
class Joint:
    """A generalized coordinate q_i with its velocity, acceleration and actuator."""

    index: int                      # 0-based position in joint order
    name: str
    kind: str                       # REVOLUTE or PRISMATIC
    symbol: sp.Symbol
    dot: sp.Symbol
    ddot: sp.Symbol
    actuator: sp.Symbol
    limits: tuple | None            # (lo, hi) sympy expressions, or None
    line: int = 0

    @property
    def is_revolute(self) -> bool:
        return self.kind == REVOLUTE


@dataclass
class Frame:
    """A frame's pose relative to its parent, as the user gave it."""

    name: str
    parent: str
    kind: str                       # "pose", "matrix", "dh", "mdh"
    factors: list = field(default_factory=list)   # pose: [(op, expr)], dh/mdh: the 4 params
    matrix: sp.Matrix | None = None               # kind == "matrix"
    line: int = 0


@dataclass
class Point:
    name: str
    frame: str
    at: sp.Matrix                   # 3x1, coordinates in `frame`
    line: int = 0
    implicit: bool = False          # the default E (origin of the last frame)


@dataclass
class Body:
    name: str
    frame: str
    mass: sp.Expr | None
    kind: str                       # "point", "rod", "com", "pseudo_inertia"
    data: dict                      # point: {at}, rod: {from, to}, com: {com, inertia}, pseudo: {J}
    line: int = 0


@dataclass
class Force:
    name: str
    frame: str                      # body (frame) it acts on
    at: sp.Matrix                   # 3x1 in `frame`
    force: sp.Matrix | None         # 3x1 components in `in_frame`
    torque: sp.Matrix | None        # 3x1 components in `in_frame`
    in_frame: str
    line: int = 0


@dataclass
class Question:
    type: str
    id: str
    index: int
    at: dict = field(default_factory=dict)        # Symbol -> sympy value
    point: str = "E"
    frame: str = ""
    options: dict = field(default_factory=dict)   # other keys, parsed
    line: int = 0
    point_given: bool = False
    frame_given: bool = False
    marks: object = 1                               # weight when graded (sympy Rational or Float)
    grade: tuple = ()                               # graded answer keys (dotted); () = principal
    text: str | None = None                         # the teacher's wording on the paper (papers.md)
    lines: dict = field(default_factory=dict)       # option key -> its line in the file
    # keys given but refused (their messages given): what depends on them says nothing more
    rejected: frozenset = frozenset()


@dataclass
class Problem:
    file: str
    name: str
    title: str | None
    description: str | None
    parameters: dict                 # Symbol -> sympy expression (of parameters) or None
    joints: list
    frames: dict                     # name -> Frame, in file order (frame "0" not listed)
    points: dict                     # name -> Point
    gravity: sp.Matrix
    gravity_given: bool
    bodies: list
    forces: list
    questions: list
    names: dict                      # every name usable in expressions -> sympy object
    has_robot: bool = True
    grading: dict = field(default_factory=dict)   # {"rtol": float, "atol": float} when given
    variants: object = None          # robosolve.load.variants.VariantSpec, or None
    paper_at: dict = field(default_factory=dict)  # `paper: {at}`: the drawing's joint values (papers.md)
    warnings: list = field(default_factory=list)  # errors.InputWarning: accepted data that may be a mistake

    @property
    def last_frame(self) -> str:
        return list(self.frames)[-1] if self.frames else "0"

    def joint(self, name: str) -> Joint | None:
        for j in self.joints:
            if j.name == name:
                return j
        return None

    @property
    def joint_symbols(self) -> list:
        return [j.symbol for j in self.joints]

    def followed(self, question: Question) -> Question | None:
        """The question `question` follows: the work-space trajectory it names (`trajectory`), else
        the motion profile (`profile`); None for a question that follows none."""
        o = question.options
        qid = o.get("trajectory") if o.get("trajectory") is not None else o.get("profile")
        return next((x for x in self.questions if x.id == qid), None) if isinstance(qid, str) else None

    def working_at(self, question: Question) -> dict:
        """The `at` the question computes everything with (dynamics, kinematics, start, the
        reference it follows): its own, beneath it the parameter overrides of the question it
        follows. A follower works on the arm of its reference: a controller following a
        trajectory of `at: {L2: 0.45}` simulates the arm with L2 = 0.45, its own `at` on top (its own win)."""
        ref = self.followed(question)
        inherited = {s: v for s, v in (ref.at if ref is not None else {}).items() if s in self.parameters}
        return {**inherited, **question.at} if inherited else question.at
