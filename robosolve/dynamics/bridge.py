"""The one bridge between a problem's `RobotModel` and the dynamics engine (one derivation
per model, shared by the solvers of every question type with `needs_dynamics`).

    dyn = dynamics_for(model)                 # Dynamics (symbolic), cached per model
    nd, note = numeric_for(model, subs)       # NumericDynamics; numeric-only fallback
    nd, dyn = simulation_dynamics(model, subs)  # NumericDynamics compiled in one function
                                              # (closed-loop ODE), dyn None on the fallback

The model is read duck-typed (frames, joints, bodies, forces, M_local, J_local): this
module imports nothing above the engines.
"""

from __future__ import annotations

import weakref

from robosolve.core.timing import time_limit
from robosolve.dynamics.api import derive_dynamics, numeric_dynamics
from robosolve.dynamics.engine import DynamicsEngine
from robosolve.dynamics.numeric import ChainDynamics, NumericDynamics, lambdify_dynamics
from robosolve.dynamics.types import BodySpec, Dynamics, FrameSpec, JointSpec, LoadSpec
from robosolve.errors import SymbolicTimeout

__all__ = ["engine_inputs", "dynamics_for", "numeric_for", "numeric_energies", "simulation_dynamics",
           "DYNAMICS_SECONDS"]

# Budget of the symbolic derivation before the numeric-only path takes over. The PUMA 560
# (6 joints, 51 symbolic parameters) takes ~5 s on a 2-core machine.
DYNAMICS_SECONDS = 90.0

_CACHE: "weakref.WeakKeyDictionary" = weakref.WeakKeyDictionary()

NUMERIC_ONLY_NOTE = ("the symbolic equations of motion took too long: the numeric values come "
                     "from the numeric-only path (mass matrix and velocity terms assembled "
                     "numerically from the body-frame L matrices)")


def _ordered_frames(model) -> list[str]:
    """Frames with every parent before its children (file order otherwise)."""
    names = list(model.frame_names())
    done, out = {"0"}, []
    while len(out) < len(names):
        progressed = False
        for f in names:
            if f not in done and model.frames[f].parent in done:
                out.append(f)
                done.add(f)
                progressed = True
        if not progressed:
            raise ValueError("frames do not form a tree rooted at frame 0")
    return out


def engine_inputs(model) -> dict:
    """The engine's plain inputs from a RobotModel."""
    frames = [FrameSpec(f, model.frames[f].parent, model.M_local(f))
              for f in _ordered_frames(model)]
    joints = [JointSpec(j.name, j.symbol, j.dot, j.ddot, j.actuator,
                        "revolute" if j.is_revolute else "prismatic")
              for j in model.joints]
    bodies = [BodySpec(b.name, b.frame, model.J_local(b)) for b in model.bodies]
    loads = []
    for f in model.forces:
        loads.append(LoadSpec(
            f.name, f.frame,
            force=list(f.force) if f.force is not None else None,
            point=list(f.at) if f.at is not None else None,
            torque=list(f.torque) if f.torque is not None else None,
            in_frame=f.in_frame))
    return dict(frames=frames, joints=joints, bodies=bodies, gravity=list(model.gravity),
                loads=loads)


def _store(model) -> dict:
    try:
        return _CACHE.setdefault(model, {})
    except TypeError:  # not weak-referenceable: cache on the object itself
        return model.__dict__.setdefault("_dynamics_cache", {})


def dynamics_for(model, seconds: float | None = DYNAMICS_SECONDS) -> Dynamics:
    """Symbolic equations of motion of the model's robot (cached).

    Raises robosolve.errors.SymbolicTimeout past `seconds` (the failure is cached too, so
    the next solver goes straight to the numeric path).
    """
    store = _store(model)
    if "dynamics" in store:
        if isinstance(store["dynamics"], SymbolicTimeout):
            raise store["dynamics"]
        return store["dynamics"]
    token = None
    try:
        with time_limit(seconds or 0) as token:
            dyn = derive_dynamics(**engine_inputs(model))
    except SymbolicTimeout as exc:
        # (token None: the limit expired while it was being set up, so it is ours)
        if token is not None and getattr(exc, "token", token) is not token:
            raise  # an enclosing limit expired: not ours to record
        store["dynamics"] = exc
        raise
    store["dynamics"] = dyn
    return dyn


def _joint_free(model, subs: dict) -> dict:
    joint_syms = set(model.q) | set(model.qd) | set(model.qdd)
    return {k: v for k, v in subs.items() if k not in joint_syms}


def _large(dyn) -> bool:
    return bool(getattr(dyn.engine, "large", False))


def _chain(dyn, subs) -> NumericDynamics:
    """A big robot's NumericDynamics from numeric code (see dynamics.numeric.ChainDynamics)."""
    return ChainDynamics(dyn.engine, subs).numeric()


def _subs_key(kind: str, subs: dict) -> tuple:
    return (kind, tuple(sorted((str(k), str(v)) for k, v in subs.items())))


def numeric_for(model, subs: dict, seconds: float | None = DYNAMICS_SECONDS
                ) -> tuple[NumericDynamics, str | None]:
    """NumericDynamics with the values `subs` (parameters); a note when the symbolic
    derivation was cut short and the numeric-only path answered."""
    subs = _joint_free(model, subs)
    key = _subs_key("numeric", subs)
    store = _store(model)
    if key in store:
        return store[key]
    try:
        dyn = dynamics_for(model, seconds)
        # a big robot's expressions are thousands of terms: numeric code, not lambdify
        out = (_chain(dyn, subs) if _large(dyn) else lambdify_dynamics(dyn, subs), None)
    except SymbolicTimeout:
        out = (numeric_dynamics(**engine_inputs(model), subs=subs), NUMERIC_ONLY_NOTE)
    store[key] = out
    return out


def numeric_energies(model, subs: dict, q, qd) -> dict:
    """{kinetic_energy, potential_energy}: per body and `total`, at (q, q̇), from numeric code
    (ChainDynamics, no symbolic derivation): the energies of the numeric-only path."""
    out = ChainDynamics(DynamicsEngine(**engine_inputs(model)), _joint_free(model, subs)).evaluate(q, qd)
    return {key: {**out[key], "total": float(sum(out[key].values()))}
            for key in ("kinetic_energy", "potential_energy")}


def simulation_dynamics(model, subs: dict, seconds: float | None = DYNAMICS_SECONDS
                        ) -> tuple[NumericDynamics, Dynamics | None]:
    """(NumericDynamics, Dynamics or None) for simulations and torque samples.

    From the symbolic Dynamics (M, c, g, f_ext lambdified in one function, which the
    closed-loop ODE calls thousands of times) when it can be derived in time; otherwise
    the numeric-only path (cached per parameter values), with None for the Dynamics.
    Raises ValueError naming the parameters without a value.
    """
    try:
        dyn = dynamics_for(model, seconds)
    except SymbolicTimeout:
        dyn = None
    if dyn is not None:
        if _large(dyn):
            return _chain(dyn, _joint_free(model, subs)), dyn
        return NumericDynamics.from_dynamics(dyn, subs), dyn
    key = _subs_key("numeric-only", subs)
    store = _store(model)
    if key not in store:
        store[key] = numeric_dynamics(**engine_inputs(model), subs=subs)
    return store[key], None
