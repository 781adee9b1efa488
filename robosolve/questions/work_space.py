"""What the work-space question types share (course summary §1.2.2): the coordinates of a
trajectory question, their units, the gains' units, and the words of a timed path in a paper.

Not a question type (the registry lists its type modules by name, and this is not one of them).
"""

from __future__ import annotations

import sympy as sp

from robosolve.load.expressions import point_symbol

__all__ = ["coordinate_list", "coordinate_unit", "common_unit", "joint_unit", "gain_unit", "path_phrase",
           "coordinate_names"]


def coordinate_list(q) -> list:
    """The coordinates of a trajectory question as written (default the point's x, y, z in frame 0)."""
    raw = q.options.get("coordinates")
    return list(raw) if raw else [point_symbol(q.point, a) for a in "xyz"]


def coordinate_unit(c, problem) -> str | None:
    """m for a point's coordinate or an expression of prismatic joints, rad for an expression of
    revolute joints alone (an orientation angle such as θ₁ + θ₂ + θ₃), None otherwise."""
    c = sp.sympify(c)
    if isinstance(c, sp.Symbol) and "." in c.name:
        return "m"
    kinds = {j.kind for j in problem.joints if j.symbol in c.free_symbols}
    others = c.free_symbols - {j.symbol for j in problem.joints}
    if others or len(kinds) != 1:
        return None
    return "rad" if kinds == {"revolute"} else "m"


def common_unit(units) -> str | None:
    """The unit shared by every coordinate, else None."""
    units = set(units)
    return units.pop() if len(units) == 1 else None


def joint_unit(problem, suffix: str = "") -> str:
    """rad (or m) + suffix for the problem's joints: 'rad/s', or 'rad/s (revolute) or m/s (prismatic)'."""
    kinds = {j.kind for j in problem.joints}
    if kinds == {"revolute"}:
        return "rad" + suffix
    if kinds == {"prismatic"}:
        return "m" + suffix
    return f"rad{suffix} (revolute joints) or m{suffix} (prismatic)"


def gain_unit(unit: str | None, derivative: bool, computed_torque: bool) -> str:
    """The unit of a gain on an error in `unit` (m or rad): a spring or a damper, N/m, N·s/m,
    N·m/rad, N·m·s/rad; for a computed-torque law the error's own dynamics, s⁻², s⁻¹."""
    if computed_torque:
        return "s⁻¹" if derivative else "s⁻²"
    if unit is None:
        return ""
    return {("m", False): "N/m", ("m", True): "N·s/m", ("rad", False): "N·m/rad",
            ("rad", True): "N·m·s/rad"}[(unit, derivative)]


def coordinate_names(q) -> list[str]:
    """The coordinates as the answers key them ("E.y")."""
    return [str(c) for c in coordinate_list(q)]


def path_phrase(q, say) -> str:
    """'moves along a straight line from $E_y = 0.7$, … to …, with a trapezoidal timing law along
    the path: maximum speed … m/s and maximum acceleration … m/s²' (a trajectory question)."""
    o = q.options

    def place(eqs):
        return ", ".join(say.equals(lhs, rhs) for _, lhs, rhs in eqs)

    path = o.get("path")
    if isinstance(path, dict) and path.get("kind") == "circle":
        shape = f"along the arc of the circle of centre {say.math(list(path['center']))}"
        if path.get("normal") is not None:
            shape += f" and normal {say.math(list(path['normal']))}"
        shape += " (the shorter way)"
    else:
        shape = "along a straight line"
    text = f"moves {shape} from {place(o['from'])} to {place(o['to'])}"
    if "duration" in o:
        return text + (f", with a quintic timing law along the path (rest to rest, zero acceleration at "
                       f"both ends) over {say.value(o['duration'])} s")
    unit = common_unit(coordinate_unit(c, say.problem) for c in coordinate_list(q))
    speed, acc = (f" {unit}/s", f" {unit}/s²") if unit else ("", "")
    return text + (f", with a trapezoidal timing law along the path: maximum speed "
                   f"{say.value(o['max_velocity'])}{speed} and maximum acceleration "
                   f"{say.value(o['max_acceleration'])}{acc}"
                   + ("" if unit else " (the path's length measured in the coordinates' own units)"))
