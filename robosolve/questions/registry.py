"""The question-type registry: every question type described once.

For each type: its option keys (with the loader's validator for each), required
keys and defaults, whether it needs a robot or the dynamics, its title, its solver
module, its figures, its doc page, and its **answer schema** — every key of
results.json with its kind, so that the loader, the renderers, the schema tests
and the grader read one table instead of knowing question types by name.

Adding a question type = a solver module `robosolve/solvers/<type>.py`, an entry
in `QUESTION_TYPES` below, and a page `docs/questions/<type>.md`.

This module is pure data (no sympy, no numpy): it is imported by the loader,
the renderers and the CLI alike, and must stay cheap.
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

KINDS = (SCALAR, VECTOR, MATRIX, MATRIX_LIST, JOINT_MAP, ACTUATOR_MAP, BODY_MAP, MATRIX_MAP,
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
    notation: str = ""            # the course's symbol in feedback ("{sub}": the question's frame
                                  #   as a subscript); hints may use {frame} and {symbol}
    hints: tuple = ()             # (diagnosis, sentence in the course's words) pairs

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
    options: dict                  # option key -> loader validator name (v_<name>)
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
    # counts), times (joints / 3) ** `cost_growth`; `unit`, a name shared by the types whose
    # questions must be solved in one process (they share a derivation or results: the
    # dynamics, a motion profile and the torques along it).
    cost: float = 0.2
    cost_growth: float = 1.0
    unit: str | None = None

    def split_cost(self, joints: int) -> float:
        """The `cost` of one question of this type on a robot with `joints` joints."""
        return self.cost * (max(joints, 1) / 3) ** self.cost_growth

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


def _ellipse(name: str, what: str, principal: bool) -> AnswerKey:
    return _k(name, RECORD, f"the {what} ellipsoid", fields=(
        _k("semi_axes", AXES, "semi-axes scaled to their lengths, by decreasing length",
           shape=(M, M), sign_free=True, symbolic=False),
        _k("lengths", VECTOR, "semi-axis lengths, decreasing", principal=principal, shape=(M,)),
        _k("directions", AXES, "unit directions of the semi-axes", shape=(M, M), sign_free=True,
           symbolic=False),
    ))


def _displacement_needs_robot(item: dict) -> bool:
    return any(isinstance(item.get(k), dict) for k in ("from", "to"))


def _displacement_principal(options: dict) -> tuple:
    """grading.md: u, alpha, h, P given from/to; Q, L given a screw."""
    return ("Q", "L") if "axis" in options else ("u", "alpha", "h", "P")


def _orientation_needs_robot(item: dict) -> bool:
    return "matrix" not in item


_TYPES = [
    QuestionType(
        "position", "Position (direct kinematics)", "§8 question 1",
        options={},
        answers=(
            _k("M", MATRIX, "pose ⁰Mₖ of the frame in frame 0", principal=True, shape=(4, 4),
               pose=True, notation="⁰M{sub}", hints=(
                   ("transposed", "the columns of R are the axes of frame {frame} in frame 0, and the "
                                  "last column is the origin of frame {frame} in frame 0"),
                   ("inverse", "that is the pose of frame 0 in frame {frame}; {symbol} gives frame "
                               "{frame} in frame 0 ({symbol} = ⁰M₁·¹M₂·…)"))),
            _k("position", VECTOR, "the point in frame 0", principal=True, shape=(3,)),
            _k("chain", MATRIX_LIST, "ⁱ⁻¹Mᵢ of each frame in its parent, from frame 1 on"),
        ),
        figures=(("robot", "robot"),),
        cost=0.1,
    ),
    QuestionType(
        "velocity_acceleration", "Velocity and acceleration", "§8 question 2",
        options={},
        answers=(
            _k("velocity", VECTOR, "velocity of the point in frame 0", principal=True, shape=(3,)),
            _k("acceleration", VECTOR, "acceleration of the point in frame 0", principal=True, shape=(3,)),
            _k("angular_velocity", VECTOR, "ω of the frame in frame 0", principal=True, shape=(3,)),
            _k("angular_acceleration", VECTOR, "ω̇ of the frame in frame 0", shape=(3,)),
            _k("W", MATRIX, "W₀ₖ = Ṁ M⁻¹, expressed in frame 0", shape=(4, 4)),
            _k("H", MATRIX, "H₀ₖ = M̈ M⁻¹ = Ẇ + W², expressed in frame 0", shape=(4, 4)),
            _k("W_aux", MATRIX, "W in the auxiliary frame (origin at the point)", shape=(4, 4)),
            _k("H_aux", MATRIX, "H in the auxiliary frame", shape=(4, 4)),
        ),
        cost=0.8, cost_growth=2,
    ),
    QuestionType(
        "jacobian", "Jacobian and singular configurations", "§8 question 3",
        options={"coordinates": "coordinates", "geometric": "bool", "bodies": "bool"},
        defaults={"geometric": False, "bodies": False},
        answers=(
            _k("J", MATRIX, "the Jacobian of the coordinates", principal=True, shape=(R, N),
               hints=(("transposed", "J has one row per coordinate and one column per joint: "
                                     "column i is ∂(coordinates)/∂qᵢ"),)),
            _k("det", SCALAR, "det J (square J)", principal=True),
            _k("manipulability", SCALAR, "product of the singular values (J not square)", principal=True),
            _k("singularities", JOINT_MAP_SET, "conditions joint -> value making J lose rank",
               principal=True, angle=True, unordered=True, by_value=True),
            _k("com_jacobians", MATRIX_MAP, "body -> 3xn Jacobian of its centre of mass", shape=(3, N)),
        ),
        cost=0.5, cost_growth=2,
    ),
    QuestionType(
        "statics", "Statics", "§8 question 4",
        options={"force": "exprs", "torque": "vector3", "weight": "bool", "coordinates": "coordinates"},
        defaults={"weight": False},
        answers=(
            _k("Fq", JOINT_MAP, "joint forces balancing the load, Fq = −Jᵀ·Fs", principal=True,
               hints=(("negated", "Fq = −Jᵀ·Fs is what the joints exert to balance the load; "
                                  "+Jᵀ·Fs is the load's own action on the joints"),)),
        ),
        cost=0.2,
    ),
    QuestionType(
        "ellipsoids", "Force, velocity and compliance ellipsoids", "§8 question 5",
        options={"coordinates": "coordinates", "budgets": "budgets",
                 "joint_compliance": "exprs", "velocity": "exprs"},
        required=("at",),
        defaults={"budgets": {"force": 1, "velocity": 1, "compliance": 1}},
        answers=(
            _ellipse("force", "force", True),
            _ellipse("velocity", "velocity", True),
            _k("condition_number", SCALAR, "max/min eigenvalue of A", principal=True),
            _ellipse("compliance", "compliance", False),
            _k("A", MATRIX, "A = J Jᵀ", shape=(M, M)),
            _k("eigenvalues", VECTOR, "eigenvalues of A, decreasing", shape=(M,)),
            _k("q_dot", JOINT_MAP, "joint rates giving the desired velocity", symbolic=False),
        ),
        figures=(("ellipsoids", "ellipsoids"),),
        cost=0.3,
    ),
    QuestionType(
        "inverse_kinematics", "Inverse kinematics", "§8 question 6",
        options={"target": "equations", "velocity": "equations", "select": "select"},
        required=("target",),
        defaults={"select": "limits"},
        answers=(
            _k("solutions", JOINT_MAP_SET, "every solution within the limits, sorted",
               principal=True, angle=True, unordered=True, symbolic=False),
            _k("q_dot", JOINT_MAP, "joint rates at the selected solution", principal=True,
               symbolic=False),
            _k("selected", JOINT_MAP, "the selected solution", angle=True, symbolic=False),
            _k("closed_form", JOINT_MAP_LIST, "closed-form solution branches", numeric=False),
            _k("unreachable", BOOL, "true when there is no solution", top=True),
            _k("reason", TEXT, "why there is no solution", top=True),
        ),
        figures=(("solutions", "ik_solutions"),),
        cost=0.8,
    ),
    QuestionType(
        "motion_profile", "Motion profile", "§8 question 7",
        options={"from": "joint_values", "to": "joint_values", "max_acceleration": "joint_values",
                 "shape": "shape", "max_velocity": "joint_values"},
        required=("from", "to", "max_acceleration"),
        defaults={"shape": "bang-bang"},
        answers=(
            _k("durations", JOINT_MAP, "each joint alone at its maximum acceleration", principal=True),
            _k("T", SCALAR, "the synchronized duration", principal=True),
            _k("accelerations", JOINT_MAP, "rescaled accelerations", principal=True),
            _k("profiles", JOINT_MAP, "joint -> piecewise expression in t", numeric=False),
        ),
        figures=(("profile", "motion_profile"),),
        cost=0.1, unit="dynamics",
    ),
    QuestionType(
        "equations_of_motion", "Equations of motion", "§8 question 8",
        options={},
        needs_dynamics=True,
        answers=(
            _k("mass_matrix", MATRIX, "M(q)", principal=True, shape=(N, N), notation="M(q)"),
            _k("velocity_terms", VECTOR, "c(q, q̇)", principal=True, shape=(N,)),
            _k("gravity_terms", VECTOR, "g(q)", principal=True, shape=(N,)),
            _k("generalized_forces", JOINT_MAP, "actuator plus external forces, per joint",
               principal=True),
            _k("equations", EQUATIONS, "one equation per joint", numeric=False),
            _k("kinetic_energy", BODY_MAP, "T per body and total"),
            _k("potential_energy", BODY_MAP, "U per body and total"),
            _k("actuators", ACTUATOR_MAP, "actuator values needed at `at`", symbolic=False),
        ),
        cost=0.7, cost_growth=2.5, unit="dynamics",
    ),
    QuestionType(
        "joint_torques", "Actuator torques along the profile", "§8 question 9",
        options={"profile": "profile_ref"},
        needs_dynamics=True,
        answers=(
            _k("actuators", ACTUATOR_RECORDS, "actuator -> signed peak and its time", principal=True,
               symbolic=False, fields=(_k("peak", SCALAR, "signed value of largest magnitude"),
                                       # an interior peak is flat: its time is known to ~1e-8
                                       _k("t_peak", SCALAR, "time of the peak", digits=8))),
            _k("profiles", ACTUATOR_MAP, "actuator -> piecewise expression in t", numeric=False),
        ),
        figures=(("torques", "joint_torques"),),
        cost=0.4, cost_growth=2.5, unit="dynamics",
    ),
    QuestionType(
        "p_control", "Closed-loop control", "§8 question 10",
        options={"profile": "profile_ref", "gains": "joint_values", "law": "law",
                 "gains_d": "joint_values", "start": "joint_values", "duration": "expr"},
        required=("gains",),
        defaults={"law": "p"},
        needs_dynamics=True,
        answers=(
            # the simulation is accurate to ~1e-6 relative: 6 digits, the same on every machine
            _k("max_error", JOINT_MAP, "max |e| over the run", principal=True, symbolic=False,
               digits=6),
            _k("final_error", JOINT_MAP, "signed e at the end", principal=True, symbolic=False,
               digits=6),
            _k("t_max_error", JOINT_MAP, "time of the largest |e|", symbolic=False, digits=6),
        ),
        figures=(("tracking", "control_tracking"), ("effort", "control_effort")),
        cost=1.3, unit="dynamics",
    ),
    QuestionType(
        "forward_dynamics", "Forward dynamics (the motion under given actuators)", "§6.5",
        options={"start": "start_state", "actuators": "actuator_laws", "duration": "duration"},
        required=("duration",),
        needs_dynamics=True,
        answers=(
            # the run is accurate to ~1e-9 of its scale (tests: 1e-8 against pinocchio): 10 digits
            _k("final", JOINT_MAP, "joint values at the end (unwrapped)", principal=True, symbolic=False,
               digits=10),
            _k("max", JOINT_MAP, "largest value of each joint over the run", principal=True,
               symbolic=False, digits=10),
            _k("min", JOINT_MAP, "smallest value of each joint over the run", principal=True,
               symbolic=False, digits=10),
            _k("final_velocity", JOINT_MAP, "joint rates at the end", symbolic=False, digits=10),
            _k("energy", RECORD, "total energy T + U", symbolic=False, fields=(
                _k("start", SCALAR, "at t = 0", digits=10),
                _k("end", SCALAR, "at the end of the run", digits=10))),
            _k("equations", EQUATIONS, "the equations of motion with the actuator laws substituted",
               numeric=False),
        ),
        figures=(("joint_<name>", "forward_dynamics"),),
        cost=0.2, cost_growth=2.5, unit="dynamics",
    ),
    QuestionType(
        "displacement", "Rigid displacement (helical axis)", "§3.1",
        # two forms: from/to (two poses or configurations) or a screw (axis, angle, through,
        # translation); "from/to or axis" is checked by the loader's type rules
        options={"from": "pose_or_config", "to": "pose_or_config", "axis": "vector3_params",
                 "angle": "expr", "through": "vector3_params", "translation": "expr"},
        needs_robot=_displacement_needs_robot,
        answers=(
            _k("u", VECTOR, "unit vector of the helical axis", principal=True, shape=(3,)),
            _k("alpha", SCALAR, "rotation angle in [0, π]", principal=True, angle=True),
            _k("h", SCALAR, "translation along the axis", principal=True),
            _k("P", VECTOR, "the axis point nearest the origin", principal=True, shape=(3,)),
            _k("Q", MATRIX, "the displacement matrix", shape=(4, 4), pose=True,
               hints=(("inverse", "this is the displacement back, from `to` to `from`"),)),
            _k("pitch", SCALAR, "h / α"),
            _k("L", MATRIX, "[[u], P×u + pitch·u; 0, 0] (given a screw)", shape=(4, 4)),
        ),
        principal_for=_displacement_principal,
        figures=(("helical_axis", "helical_axis"),),
        cost=0.05,
    ),
    QuestionType(
        "orientation", "Orientation representations", "§5.6",
        options={"matrix": "rotation_matrix"},
        needs_robot=_orientation_needs_robot,
        answers=(
            _k("zyz", RECORD, "R = Rz(φ)·Ry(θ)·Rz(ψ)", principal=True, fields=(
                _k("solutions", VECTOR_SET, "[φ, θ, ψ] solution sets", shape=(3,), angle=True,
                   unordered=True),
                _k("singular", BOOL, "at a singularity"))),
            _k("rpy", RECORD, "R = Rz(yaw)·Ry(pitch)·Rx(roll)", principal=True, fields=(
                _k("solutions", VECTOR_SET, "[roll, pitch, yaw] solution sets", shape=(3,), angle=True,
                   unordered=True),
                _k("singular", BOOL, "at a singularity"))),
            _k("axis_angle", RECORD, "axis and angle in [0, π]", principal=True, fields=(
                _k("axis", VECTOR, "unit axis", shape=(3,)),
                _k("angle", SCALAR, "angle in [0, π]", angle=True))),
            _k("quaternion", VECTOR, "[η, εx, εy, εz], η ≥ 0", principal=True, shape=(4,)),
        ),
        cost=0.1,
    ),
    QuestionType(
        "dof", "Degrees of freedom", "§1.1",
        options={"bodies": "count", "joints_1dof": "count", "joints_2dof": "count",
                 "joints_3dof": "count", "space": "space"},
        required=("bodies",),
        defaults={"space": "planar"},
        needs_robot=lambda item: False,
        answers=(
            _k("dof", SCALAR, "Grübler (planar) / Kutzbach (spatial)", principal=True),
        ),
        cost=0.01,
    ),
]

QUESTION_TYPES: dict[str, QuestionType] = {t.name: t for t in _TYPES}

# Keys every question may have, whatever its type (problem-format.md "Questions").
COMMON_KEYS = ("type", "id", "at", "point", "frame", "marks", "grade")


def question_type(name: str) -> QuestionType:
    return QUESTION_TYPES[name]


def title(name: str) -> str:
    t = QUESTION_TYPES.get(name)
    return t.title if t is not None else name
