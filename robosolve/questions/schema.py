"""The shared vocabulary of the question types: answer key kinds, `AnswerKey`, `QuestionType`.

Each question type builds one `QuestionType` in its own module `robosolve/questions/<type>.py`;
`robosolve/questions/registry.py` collects them.
"""

from __future__ import annotations

import importlib
from dataclasses import dataclass, field
from typing import Callable

# -- answer key kinds -----------------------------------------------------------
# The vocabulary of answer layouts (problem-format.md "Definitions and layouts").
SCALAR = "scalar"                 # one number or expression
VECTOR = "vector"                 # list of scalars; `shape` = (length,)
MATRIX = "matrix"                 # list of rows; `shape` = (rows, cols)
MATRIX_LIST = "matrix_list"       # list of matrices (e.g. the chain ⁰M₁, ¹M₂, …)
JOINT_MAP = "joint_map"           # joint name -> scalar, in joint order
ACTUATOR_MAP = "actuator_map"     # actuator name -> scalar, in joint order
COORDINATE_MAP = "coordinate_map"  # task coordinate (as written, "E.y") -> scalar, in the question's order
CONTROL_MAP = "control_map"       # a JOINT_MAP, or a COORDINATE_MAP for a work-space control law
BODY_MAP = "body_map"             # body name -> scalar, plus `total`
MATRIX_MAP = "matrix_map"         # name -> matrix (e.g. body -> 3xn Jacobian)
JOINT_MAP_SET = "joint_map_set"   # set of joint mappings (IK solutions, singularities)
JOINT_MAP_LIST = "joint_map_list"  # ordered list of joint mappings (closed forms)
VECTOR_SET = "vector_set"         # set of vectors (Euler-angle solution sets)
AXES = "axes"                     # list of vectors, sorted by length, each up to its sign
EQUATIONS = "equations"           # list of "lhs = rhs" strings, one per joint
RECORD = "record"                 # nested mapping with its own `fields`
ACTUATOR_RECORDS = "actuator_records"  # actuator name -> record (`fields`)
BOOL = "bool"
TEXT = "text"

KINDS = (SCALAR, VECTOR, MATRIX, MATRIX_LIST, JOINT_MAP, ACTUATOR_MAP, COORDINATE_MAP, CONTROL_MAP, BODY_MAP, MATRIX_MAP,
         JOINT_MAP_SET, JOINT_MAP_LIST, VECTOR_SET, AXES, EQUATIONS, RECORD, ACTUATOR_RECORDS,
         BOOL, TEXT)

# Shape tokens: an int, or a letter bound per question:
#   "n" the number of joints, "m" the number of coordinates of the question,
#   "r" the rows of J (m, or 6 for a geometric Jacobian).
N, M, R = "n", "m", "r"


@dataclass(frozen=True)
class AnswerKey:
    """One key of an answer, as results.json lays it out.

    `principal`: graded by default (grading.md) whenever the reference answer has it.
    `angle`: values are angles, compared modulo 2π (in a joint mapping or set of joint
    mappings: the revolute joints' values only). `unordered`: a set, order ignored.
    `sign_free`: each vector up to its sign. `symbolic`/`numeric`: where it may appear;
    `top`: beside `type` in the answer (not inside symbolic/numeric). `digits`: the
    significant digits results.json keeps of its numbers when the computation is worth
    fewer than the default 12 (a simulation's errors); render/numbers.py applies it.
    """

    name: str
    kind: str
    doc: str = ""
    principal: bool = False
    shape: tuple = ()
    angle: bool = False
    unordered: bool = False
    sign_free: bool = False
    symbolic: bool = True
    numeric: bool = True
    top: bool = False
    fields: tuple = ()            # for RECORD / ACTUATOR_RECORDS: AnswerKeys of the fields
    digits: int | None = None     # significant digits in results.json (None: the default)
    # -- for the grader (grading.md) --
    by_value: bool = False        # values compared as numbers even when written as expressions
    pose: bool = False            # a 4x4 homogeneous pose: the `inverse` diagnosis applies
    quaternion: bool = False      # [η, εx, εy, εz]: the `quaternion_order` diagnosis applies
    dh_built: str = ""            # "pose" / "point": built from the pose of the question's frame
                                  #   (the `dh_convention` diagnosis applies)
    in_frame0: bool = False       # a vector or Jacobian in frame 0 (`end_effector_frame` applies)
    reaches: bool = False         # IK solutions: judged by the pose they reach
    notation: str = ""            # the course's symbol in feedback ("{sub}": the question's frame
                                  #   as a subscript); hints may use {frame} and {symbol}
    hints: tuple = ()             # (diagnosis, sentence in the course's words) pairs
    # -- for papers and answers templates (papers.md) --
    unit: str = ""                # SI unit of the values; "joint" (rad or m by the joint's kind),
                                  #   "joint/s", "joint/s²", "effort" (N·m or N), "" none
    # -- for the loader: a key only some questions of the type compute (q_dot needs a velocity) --
    needs: Callable | None = None  # (question, its joints) -> why this question does not compute the
                                   #   key ("" when it does): a grade list naming it is refused

    @property
    def symbol(self) -> str:
        return self.notation or self.name

    def hint(self, diagnosis: str) -> str:
        return dict(self.hints).get(diagnosis, "")

    def field(self, name: str) -> "AnswerKey | None":
        return next((f for f in self.fields if f.name == name), None)


@dataclass(frozen=True)
class QuestionType:
    """One question type: its options, its rules and its answer schema."""

    name: str
    title: str
    seed: str                      # where the course summary treats it
    options: dict                  # option key -> validator function (robosolve/load/validators.py)
    answers: tuple                 # AnswerKeys, in the order of grading.md's table
    required: tuple = ()
    defaults: dict = field(default_factory=dict)
    needs_robot: Callable[[dict], bool] = lambda item: True
    needs_dynamics: bool = False   # gravity, bodies and the equations of motion
    figures: tuple = ()            # (figure name, plot kind) pairs it may draw
    doc: str = ""                  # docs/questions/<name>.md unless given
    # principal keys that depend on the question's form: options -> key paths (grading.md's
    # table for a type with two forms, e.g. displacement from/to or from a screw); None: the
    # AnswerKeys' `principal` flags (which then describe the default form)
    principal_for: Callable[[dict], tuple] | None = None
    # What splitting a problem's questions between two processes needs (split_solve.py):
    # `cost`, a rough CPU time of one question on a 3-joint robot (relative: only the balance
    # counts), times (joints / 3) ** `cost_growth`, times `cost_factor(question, joints)` where
    # the question's options change it (a wide Jacobian's rank search); `unit`, a name shared by
    # the types whose questions must be solved in one process (they share a derivation or
    # results: the dynamics, a motion profile and the torques along it).
    cost: float = 0.2
    cost_growth: float = 1.0
    cost_factor: Callable | None = None
    unit: str | None = None
    # The type's own cross-field checks, called by the question loader after the options are
    # parsed: check(ql, path, item, question) reports with ql.chk.error (load/questions.py).
    check: Callable | None = None
    # Its checks across questions, after every question is loaded: resolve(ql, question, questions)
    # (references to other questions by id, beyond the `profile` of `uses_profile`).
    resolve: Callable | None = None
    needs_joints: bool = True      # with a robot, it needs joints (False: frames alone will do)
    integrates: bool = False       # integrates the motion: the mass matrix must be invertible
    makes_trajectory: bool = False  # its answer is a work-space trajectory (a control question follows it)
    makes_profile: bool = False    # its answer is a motion profile other questions refer to
    uses_profile: bool = False     # refers to a profile question by id (`profile` option)
    has_jacobian: bool = False     # its answer has a Jacobian J at the question's `at`
    reaches: bool = False          # it searches configurations reaching a target (`reachable`)
    model_checked: bool = False    # its solver's `check_input(question, ctx)` finds input mistakes
                                   #   only the robot's model shows (run/pipeline.py check_inputs)
    # (rank, phrase): where time-varying forces are followed, in the loader's message that
    # refuses `t` elsewhere ("a simulation run"); time_laws: its option whose values
    # may use t
    time_use: tuple = ()
    time_laws: str = ""
    # The paper statement of a question (issue 23: None until the type provides it), and the
    # builder of its notebook cell, notebook_cell(question, answer, problem) -> Python source
    # or None (questions/notebook_code.py; render/notebook.py calls it).
    statement: Callable | None = None
    notebook_cells: Callable | None = None
    # The principal keys a question's answer will have, known before solving (papers.md, the
    # answers template): paper_keys(options, joints) with the parsed options and the number of
    # joints; None: ``principal_keys_for(options)``
    paper_keys: Callable | None = None
    # What the question decides about the layout of some of its keys, known before solving:
    # paper_layout(question, problem) -> {key: (entries, unit)}, entries the names of a mapping's
    # entries (a control law's errors per joint or per coordinate) or None, unit its unit or None
    # (papers.md: the template's placeholders, the paper's "what to give")
    paper_layout: Callable | None = None

    def split_cost(self, joints: int, question=None) -> float:
        """The `cost` of one question of this type on a robot with `joints` joints (of this
        question, when given and the type has a `cost_factor`)."""
        base = self.cost * (max(joints, 1) / 3) ** self.cost_growth
        if self.cost_factor is not None and question is not None:
            base *= self.cost_factor(question, joints)
        return base

    @property
    def doc_page(self) -> str:
        return self.doc or f"docs/questions/{self.name}.md"

    @property
    def solver_module(self) -> str:
        return f"robosolve.solvers.{self.name}"

    def solver(self):
        """The solver's `solve(question, ctx) -> Answer` (imports it on first use)."""
        return importlib.import_module(self.solver_module).solve

    def key(self, path: str) -> AnswerKey | None:
        """The AnswerKey of a (dotted) path, e.g. 'force.semi_axes'."""
        head, _, rest = path.partition(".")
        k = next((a for a in self.answers if a.name == head), None)
        while k is not None and rest:
            head, _, rest = rest.partition(".")
            k = k.field(head)
        return k

    def principal_keys_for(self, options: dict | None = None) -> tuple:
        """The principal keys of one question (its parsed or raw options): those of its form
        when the type has several (``principal_for``), else ``principal_keys``."""
        if self.principal_for is not None and options is not None:
            return tuple(self.principal_for(options))
        return self.principal_keys

    def template_keys(self, options: dict, joints: int) -> tuple:
        """The principal keys of a question known before solving (papers.md)."""
        if self.paper_keys is not None:
            return tuple(self.paper_keys(options, joints))
        return self.principal_keys_for(options)

    @property
    def principal_keys(self) -> tuple:
        """Dotted paths of the principal keys, in the order of grading.md (default form)."""
        out = []
        for a in self.answers:
            if a.principal:
                out.append(a.name)
            for f in a.fields:
                if f.principal:
                    out.append(f"{a.name}.{f.name}")
        return tuple(out)


def _k(name, kind, doc="", **kw) -> AnswerKey:
    return AnswerKey(name, kind, doc, **kw)

