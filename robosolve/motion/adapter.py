"""Thin adapter from the solver context to the dynamics engine and the motion engines.

The dynamics engine (``robosolve.dynamics``, another helper's module) takes plain
sympy specs; this module builds them from ``ctx.model`` and caches the result in
``ctx.shared`` so that equations_of_motion, joint_torques and p_control derive the
equations of motion once per problem.  It also keeps the synchronized profiles of
the motion_profile answers for the questions that refer to them.
"""

from __future__ import annotations

import sympy as sp

from robosolve.errors import SymbolicTimeout
from robosolve.solvers.base import SolveContext

PROFILES_KEY = "motion.profiles"          # ctx.shared[...] : question id -> SyncProfile
SYMBOLIC_KEY = "dynamics"                 # shared with equations_of_motion when it stores a Dynamics
NUMERIC_KEY = "motion.dynamics.numeric"   # parameter-substituted Dynamics (fast derivation)


def store_profile(ctx: SolveContext, qid: str, profile) -> None:
    ctx.shared.setdefault(PROFILES_KEY, {})[qid] = profile


def profile_for(ctx: SolveContext, qid: str):
    """The SyncProfile of motion_profile question ``qid`` (None if it was not answered)."""
    return ctx.shared.get(PROFILES_KEY, {}).get(qid)


def _specs(model):
    from robosolve.dynamics.api import BodySpec, FrameSpec, JointSpec, LoadSpec

    frames = [FrameSpec(f, model.frames[f].parent, model.M_local(f)) for f in model.frame_names()]
    joints = [JointSpec(j.name, j.symbol, j.dot, j.ddot, j.actuator, j.kind) for j in model.joints]
    bodies = [BodySpec(b.name, b.frame, model.J_local(b)) for b in model.bodies]
    loads = [LoadSpec(f.name, f.frame, force=None if f.force is None else list(f.force), point=list(f.at),
                      torque=None if f.torque is None else list(f.torque), in_frame=f.in_frame)
             for f in model.forces]
    return frames, joints, bodies, list(model.gravity), loads


def symbolic_dynamics(ctx: SolveContext, seconds: float | None = None):
    """The symbolic Dynamics (parameters kept), or None when it takes too long.

    Uses the dynamics helper's ``dynamics_for(model)`` (cached per model, shared with
    equations_of_motion) when it exists; otherwise derives it here.
    """
    try:
        from robosolve.dynamics.model import dynamics_for
    except ImportError:                      # older engine without the model bridge
        dynamics_for = None
    if dynamics_for is not None:
        try:
            return dynamics_for(ctx.model) if seconds is None else dynamics_for(ctx.model, seconds)
        except SymbolicTimeout:
            return None
    from robosolve.dynamics.api import Dynamics, derive_dynamics

    dyn = ctx.shared.get(SYMBOLIC_KEY)
    if isinstance(dyn, Dynamics):
        return dyn
    if ctx.shared.get(SYMBOLIC_KEY + ".failed"):
        return None
    try:
        with (ctx.time_limit(seconds) if seconds else ctx.time_limit()):
            dyn = derive_dynamics(*_specs(ctx.model))
    except SymbolicTimeout:
        ctx.shared[SYMBOLIC_KEY + ".failed"] = True
        return None
    ctx.shared[SYMBOLIC_KEY] = dyn
    return dyn


def numeric_engine(ctx: SolveContext, subs: dict):
    """(FastDynamics, Dynamics or None) for the simulation and the torque samples.

    From the symbolic Dynamics (cached, shared with equations_of_motion) when it can be
    derived in time; otherwise from the engine's numeric-only path (callables).
    Raises ValueError naming the parameters without a value.
    """
    from robosolve.motion.numeric import FastDynamics

    dyn = symbolic_dynamics(ctx)
    if dyn is not None:
        return fast_dynamics(dyn, subs), dyn
    key = (NUMERIC_KEY, tuple(sorted((str(k), str(v)) for k, v in subs.items())))
    if key not in ctx.shared:
        from robosolve.dynamics.api import numeric_dynamics

        params = {k: v for k, v in subs.items() if k in ctx.problem.parameters}
        missing = sorted(s.name for s, v in ctx.problem.parameters.items() if v is None and s not in params)
        if missing:
            raise ValueError("no value for " + ", ".join(missing))
        nd = numeric_dynamics(*_specs(ctx.model), subs=params)
        ctx.shared[key] = FastDynamics.from_callables(nd.n, nd.mass, nd.velocity_terms, nd.gravity, nd.external)
    return ctx.shared[key], None


def fast_dynamics(dyn, subs: dict):
    """FastDynamics (one lambdified function for M, c, g, f_ext) with ``subs`` substituted."""
    from robosolve.motion.numeric import FastDynamics

    params = {sp.sympify(k): sp.sympify(v) for k, v in subs.items()}
    # forces given as functions of time use the loader's t (a real symbol)
    return FastDynamics.from_symbolic(dyn.mass_matrix, dyn.velocity_terms, dyn.gravity_terms,
                                      dyn.q, dyn.qd, external=dyn.external_forces, subs=params,
                                      time=sp.Symbol("t", real=True))
