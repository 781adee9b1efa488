"""The same robots built with ``sympy.physics.mechanics`` (Kane and Lagrange).

Independent reference for the tests and the benchmark only (no robosolve code path uses
it): frames from elementary rotations (`orient_axis`) and translations (`locatenew`),
bodies from mass, centre of mass and classical inertia, gravity, actuators (torque couple
on the joint's frame and its reaction on the previous one; force pair for a prismatic
joint) and the external loads.
"""

from __future__ import annotations

from dataclasses import dataclass

import sympy as sp


@dataclass
class MechanicsModel:
    N: object
    q: list          # dynamicsymbols
    u: list          # generalized speeds (= q')
    qmap: dict       # robosolve joint symbol -> dynamicsymbol
    bodies: list
    loads: list      # gravity + actuators + external loads
    gravity_loads: list
    actuator_loads: list
    external_loads: list
    heights: dict    # body name -> potential energy expression


def build(robot, actuators: bool = True) -> MechanicsModel:
    import sympy.physics.mechanics as me

    names = [j.name for j in robot.joints]
    q = [me.dynamicsymbols(n) for n in names]
    u = [me.dynamicsymbols(n + "_u") for n in names]
    qmap = {j.q: qi for j, qi in zip(robot.joints, q)}
    N = me.ReferenceFrame("N")
    O = me.Point("O")
    O.set_vel(N, 0)
    frames = {"0": (N, O)}
    axes = {"x": 0, "y": 1, "z": 2}
    act_loads = []
    counter = [0]

    def fresh(prefix):
        counter[0] += 1
        return f"{prefix}{counter[0]}"

    def unit(frame, k):
        return [frame.x, frame.y, frame.z][k]

    for name, parent, motions in robot.frames:
        F, P = frames[parent]
        parent_frame = F
        for kind, e in motions:
            e = sp.sympify(e).xreplace(qmap)
            k = axes[kind[1]]
            joint = next((i for i, qi in enumerate(q) if e.has(qi)), None)
            if kind[0] == "R":
                F2 = me.ReferenceFrame(fresh("F"))
                F2.orient_axis(F, unit(F, k), e)
                if joint is not None and actuators:
                    tau = robot.joints[joint].actuator * sp.diff(e, q[joint]) * unit(F, k)
                    act_loads += [(F2, tau), (parent_frame, -tau)]
                F = F2
            else:
                P2 = P.locatenew(fresh("P"), e * unit(F, k))
                P2.set_vel(N, P2.pos_from(O).dt(N))
                if joint is not None and actuators:
                    force = robot.joints[joint].actuator * sp.diff(e, q[joint]) * unit(F, k)
                    Pp = P.locatenew(fresh("Pp"), e * unit(F, k))
                    P.set_vel(N, P.pos_from(O).dt(N))
                    Pp.v2pt_theory(P, N, F)
                    act_loads += [(P2, force), (Pp, -force)]
                P = P2
        frames[name] = (F, P)

    def vec(frame, comps):
        return sum((sp.sympify(c).xreplace(qmap) * unit(frame, k)
                    for k, c in enumerate(comps)), sp.S.Zero * frame.x)

    bodies, grav_loads, heights = [], [], {}
    gvec = vec(N, robot.gravity)
    for b in robot.bodies:
        F, P = frames[b.frame]
        mc = P.locatenew(b.name + "_G", vec(F, b.com))
        mc.set_vel(N, mc.pos_from(O).dt(N))
        ig = sp.Matrix(b.inertia)
        inertia = me.inertia(F, ig[0, 0], ig[1, 1], ig[2, 2], ig[0, 1], ig[1, 2], ig[0, 2])
        body = me.RigidBody(b.name, mc, F, b.mass, (inertia, mc))
        bodies.append(body)
        grav_loads.append((mc, b.mass * gvec))
        heights[b.name] = -b.mass * gvec.dot(mc.pos_from(O))
        body.potential_energy = heights[b.name]
    ext = []
    for ld in robot.loads:
        F, P = frames[ld.frame]
        Fin = frames[ld.in_frame or ld.frame][0]
        if ld.force is not None:
            pt = P.locatenew(fresh("L"), vec(F, ld.point or [0, 0, 0]))
            pt.set_vel(N, pt.pos_from(O).dt(N))
            ext.append((pt, vec(Fin, ld.force)))
        if ld.torque is not None:
            ext.append((F, vec(Fin, ld.torque)))
    return MechanicsModel(N, q, u, qmap, bodies, grav_loads + act_loads + ext, grav_loads,
                          act_loads, ext, heights)


def kane(model: MechanicsModel):
    """(mass matrix, forcing) with q' = u: M(q) u' = forcing(q, u)."""
    import sympy.physics.mechanics as me

    t = me.dynamicsymbols._t
    km = me.KanesMethod(model.N, q_ind=model.q, u_ind=model.u,
                        kd_eqs=[qi.diff(t) - ui for qi, ui in zip(model.q, model.u)])
    km.kanes_equations(model.bodies, model.loads)
    return km.mass_matrix, km.forcing


def lagrange(model: MechanicsModel):
    """(mass matrix, forcing) of LagrangesMethod (non-conservative loads as forcelist)."""
    import sympy.physics.mechanics as me

    lag = me.Lagrangian(model.N, *model.bodies)
    lm = me.LagrangesMethod(lag, model.q, forcelist=model.actuator_loads +
                            model.external_loads or None, frame=model.N)
    lm.form_lagranges_equations()
    return lm.mass_matrix, lm.forcing


def to_plain(expr, model: MechanicsModel, robot):
    """Replace dynamicsymbols (q, q', u, q'') by the robosolve joint symbols."""
    import sympy.physics.mechanics as me

    t = me.dynamicsymbols._t
    rep = {}
    for j, qi, ui in zip(robot.joints, model.q, model.u):
        rep[qi.diff(t, 2)] = j.qdd
        rep[qi.diff(t)] = j.qd
        rep[ui.diff(t)] = j.qdd
        rep[ui] = j.qd
        rep[qi] = j.q
    return expr.subs(rep)
