"""Where the course summary is wrong or ambiguous, and what robosolve does instead.

One entry per note: a short anchor, a title and a Markdown body (inline LaTeX in
`$...$`). This module is the single source of the notes:

* solvers cite a note with `note_link(anchor)`, a Markdown link to `#note-<anchor>`;
* the report renderer copies every note a report cites into the report itself
  (section "Notes on the course summary"), so the link works wherever the report
  is read — on GitHub, in report.html, offline — without depending on where the
  output folder lies relative to the project's docs;
* `docs/course-notes.md` is generated from it (`python -m robosolve.core.course_notes`)
  and a test keeps the page in sync.

Pure data and string helpers: no sympy, cheap to import.
"""

from __future__ import annotations

import re
from dataclasses import dataclass


@dataclass(frozen=True)
class CourseNote:
    anchor: str
    title: str
    topic: str
    body: str


_NOTES = (
    # -- frames and matrices ----------------------------------------------------
    CourseNote("frame-notation", "Which way a pose matrix maps", "Frames and matrices",
               "${}^{i}M_{j}$ is the pose of frame $j$ in frame $i$: it maps coordinates in $j$ to "
               "coordinates in $i$, ${}^{i}P = {}^{i}M_{j}\\,{}^{j}P$, and poses chain as "
               "${}^{0}M_{3} = {}^{0}M_{1}\\,{}^{1}M_{2}\\,{}^{2}M_{3}$. The summary sometimes writes "
               "the indices the other way round (${}^{i}_{i-1}M$ for the pose of $i$ in $i-1$) and "
               "uses the letter Q both for the joint vector and for the displacement matrix; "
               "robosolve keeps $q$ for joints and $Q$ for displacements."),
    CourseNote("inverse-pose", "The inverse of a pose matrix", "Frames and matrices",
               "${}^{0}M_{1}^{-1} = \\left[\\begin{matrix} R^T & -R^T t \\\\ 0 & 1 \\end{matrix}\\right]$. "
               "The summary gives the last column as the translation without the rotation and the "
               "minus sign, and the last row as zeros; the last column is the position of "
               "$O_0$ seen from frame 1, $-R^T t$, and the last row is $[0\\ 0\\ 0\\ 1]$."),
    CourseNote("dh-order", "Denavit–Hartenberg: order of the factors and the matrix",
               "Frames and matrices",
               "Standard DH is ${}^{i-1}M_{i} = R_z(\\theta_i)\\,T_z(d_i)\\,T_x(a_i)\\,R_x(\\alpha_i)$, "
               "each factor applied in the current (moving) frame, so the matrices multiply left "
               "to right; the summary's twist $\\varphi$ is $\\alpha$ here. Its order \"translate "
               "along z, rotate about z, rotate about x, translate along x\" gives the same matrix "
               "(a rotation and a translation along the same axis commute). The general matrix "
               "printed in the summary has $+\\sin\\theta\\cos\\alpha$ in entry [1,2]: the entry is "
               "$-\\sin\\theta\\cos\\alpha$ (the printed block is not a rotation). Modified DH "
               "(`mdh`) is $R_x(\\alpha)\\,T_x(a)\\,R_z(\\theta)\\,T_z(d)$."),
    CourseNote("scara-frames", "The SCARA's frames", "Frames and matrices",
               "In the summary's SCARA, $O_1$ and $O_2$ are both at height $h$, so "
               "${}^{1}M_{2} = R_z(\\theta_2)\\,T_x(L_2)$ has no vertical offset (with one, "
               "$z_E = 2h - l$), and ${}^{2}M_{3} = T_z(-l)$ is a rototranslation with an "
               "identity rotation block (the summary prints it with a zero block). With $l$ "
               "measured downwards, its L matrix has $-1$ in entry [3,4], not $+1$; and the "
               "end-effector velocity is $v_y = L_1 c_1\\dot\\theta_1 + L_2 c_{12}(\\dot\\theta_1 + "
               "\\dot\\theta_2)$ (a plus sign), $v_z = -\\dot l$ (a rate, not $-l$)."),
    # -- velocities and accelerations ------------------------------------------
    CourseNote("w-matrix", "W: which frame, which point", "Velocity and acceleration",
               "$W = \\dot M M^{-1}$ is expressed in frame 0. Its last column is the velocity of "
               "the point of the moving body that is passing through $O_0$ at that instant, not "
               "of the frame's origin; a point's velocity is $\\dot P = W P$, or the last column "
               "of $W$ in the auxiliary frame (origin at the point, axes of frame 0). Rivals' "
               "theorem ${}^{0}W_{0,2} = {}^{0}W_{0,1} + {}^{0}W_{1,2}$ holds only with every term "
               "in frame 0: ${}^{0}W_{1,2} = {}^{0}M_{1}\\,{}^{1}W_{1,2}\\,{}^{0}M_{1}^{-1}$. Adding "
               "${}^{1}W_{1,2}$ as it stands is wrong."),
    CourseNote("h-matrix", "H is Ẇ + W², not Ẇ·W²", "Velocity and acceleration",
               "The acceleration matrix is $H = \\ddot M M^{-1} = \\dot W + W^2$ (a sum), because "
               "$\\tfrac{d}{dt}M^{-1} = -M^{-1}\\dot M M^{-1}$; the summary writes a product. In "
               "Coriolis' theorem ${}^{0}H_{0,2} = {}^{0}H_{0,1} + 2\\,{}^{0}W_{0,1}\\,{}^{0}W_{1,2} "
               "+ {}^{0}H_{1,2}$ every term is in frame 0 and the order of the product is "
               "$W_{0,1} W_{1,2}$; the relative term is ${}^{1}H_{1,2}$ moved to frame 0, not "
               "$\\tfrac{d}{dt}({}^{0}W_{1,2}) + ({}^{0}W_{1,2})^2$."),
    CourseNote("l-matrix", "L matrices and the sign of a prismatic joint", "Velocity and acceleration",
               "robosolve generates each L matrix from the pose, $L = \\partial M/\\partial q\\; M^{-1}$, "
               "instead of writing it by hand: its translation column is the direction in which "
               "the frame moves when $q$ grows (for $T_z(-l)$ that is $-z$). Moved to frame 0: "
               "${}^{0}L_i = {}^{0}M_{i-1}\\,{}^{i-1}L_i\\,{}^{0}M_{i-1}^{-1}$. For one joint, "
               "$W = L\\dot q$ and $H = L\\ddot q + L^2 \\dot q^2$. The infinitesimal screw is "
               "$Q(d\\alpha) = I + d\\alpha\\,L$ with $L = [[u], t; 0, 0]$ and "
               "$t = -[u]P^* + p\\,u$ — without the extra $d\\alpha$ the summary puts in $t$."),
    # -- statics and ellipsoids --------------------------------------------------
    CourseNote("jacobian-shape", "The Jacobian's rows and columns", "Statics and ellipsoids",
               "$J = \\partial S/\\partial Q$ has one row per task coordinate and one column per "
               "joint, in joint order; the summary gives $Q$ and $S$ the same length, which only "
               "holds for a square Jacobian."),
    CourseNote("statics-sign", "The sign of Fq", "Statics and ellipsoids",
               "From virtual work, $F_q = -J^T F_s$ is what the joints must exert to balance an "
               "external load $F_s$ applied at the end effector. In the equations of motion the "
               "generalized forces $f$ are the forces applied to the robot (actuators plus "
               "external loads), so in a static pose without gravity $f = F_q + J^T F_s = 0$. "
               "The summary's closing list writes $-J_s \\cdot T \\cdot F_s$ for $-J_s^T F_s$."),
    CourseNote("ellipsoid-axes", "Semi-axes of the ellipsoids", "Statics and ellipsoids",
               "With $A = J J^T$, eigenvalues $\\nu_i$ (roots of $\\det(A - \\nu I) = 0$) and unit "
               "eigenvectors $\\hat\\vartheta_i$ (non-zero solutions of $(A - \\nu_i I)\\vartheta = 0$, "
               "normalised): the force ellipsoid $F^T A F = K_f^2$ has semi-axes "
               "$\\frac{K_f}{\\sqrt{\\nu_i}}\\hat\\vartheta_i$ and the velocity ellipsoid "
               "$V^T A^{-1} V = K_v^2$ has $K_v\\sqrt{\\nu_i}\\,\\hat\\vartheta_i$. The summary "
               "multiplies the eigenvectors by the eigenvalues, uses the velocity budget in the "
               "force ellipse, writes $\\det(A - I)$ and $(A - \\nu_i I)F$ for the eigen-problem, "
               "and $A^{-1} = J^{-1} J^T$ for $(J J^T)^{-1} = J^{-T} J^{-1}$. robosolve names the "
               "three budgets $K_f$, $K_v$, $K_a$ (the summary reuses $K_q$). For a redundant arm "
               "(J wider than tall) the velocity ellipsoid is the same with the minimum-norm joint "
               "rates $\\dot Q = J^{+} V$. At a singular pose an eigenvalue is zero: the force "
               "semi-axis is infinite and is reported as such, never divided by zero."),
    CourseNote("compliance-ellipsoid", "The compliance ellipsoid", "Statics and ellipsoids",
               "$K_q$ holds the joint compliances ($\\delta q = K_q \\tau$, rad/(N·m) or m/N). With "
               "$K_s = J K_q J^T$ the ellipsoid is $\\delta S^T K_s^{-T} K_s^{-1} \\delta S = K_a^2$ "
               "(an inner product — the summary writes outer products and sets it to 0), and its "
               "semi-axes are $K_a \\kappa_i$ along the unit eigenvectors of $K_s$, $\\kappa_i$ its "
               "eigenvalues."),
    CourseNote("condition-number", "Condition number", "Statics and ellipsoids",
               "robosolve reports the condition number of $A = J J^T$, $\\max\\nu/\\min\\nu$, as the "
               "summary defines it. It is $\\mathrm{cond}(J)^2$; the ratio of the ellipse's longest "
               "to shortest semi-axis is its square root. The summary's numeric example "
               "($L_1 = L_2 = 0.5$, $q_1 = q_2 = 0$) is a singular pose, where the force ellipse "
               "degenerates into two lines; take e.g. $q_2 = \\pi/2$."),
    # -- displacements and orientation -----------------------------------------
    CourseNote("displacement-matrix", "Direction of the displacement matrix", "Displacements and orientation",
               "A body point moves as ${}^{0}P_2 = Q_0\\,{}^{0}P_1$ (the summary has the two "
               "positions swapped once), with $Q_0 = {}^{0}M_2\\,{}^{0}M_1^{-1}$. Its translation "
               "$\\Delta T$ is where the body point that started at $O_0$ ends, in frame 0 "
               "coordinates."),
    CourseNote("q3-inverse", "The displacement seen from another frame", "Displacements and orientation",
               "Expressed in frame $k$ the displacement matrix is "
               "$Q_k = ({}^{0}M_k)^{-1}\\,Q_0\\,{}^{0}M_k$; the summary's "
               "$Q_3 = {}^{0}M_3\\,Q_0\\,{}^{3}M_0$ has the two outer factors inverted."),
    CourseNote("helical-axis", "The helical axis from Q", "Displacements and orientation",
               "From the rotation block $R$: $\\cos\\alpha = (\\operatorname{tr}R - 1)/2$ and "
               "$\\sin\\alpha = \\tfrac12|\\operatorname{vex}(R - R^T)|$ (the summary omits the "
               "$\\tfrac12$). For $0 < \\alpha < \\pi$, $u = \\operatorname{vex}(R - R^T)/(2\\sin\\alpha)$. "
               "From the diagonal, $u_x = \\pm\\sqrt{(r_{11} - \\cos\\alpha)/(1 - \\cos\\alpha)}$ "
               "(not $r_{11} - 1$, which gives a negative radicand), and the products "
               "$u_x u_z = (r_{13} + r_{31})/(2(1 - \\cos\\alpha))$ have no square root; at "
               "$\\alpha = \\pi$, $u_i^2 = (r_{ii} + 1)/2$ and $u_i u_j = (r_{ij} + r_{ji})/4$. "
               "robosolve takes $\\alpha \\in [0, \\pi]$ with $\\sin\\alpha \\ge 0$, which fixes the "
               "sign of $u$. Then $h = u \\cdot \\Delta T$, the axis point nearest the origin is "
               "$P^* = (I - R^T)\\Delta T / (2(1 - \\cos\\alpha))$ and the pitch is $h/\\alpha$. "
               "The formula for $P^*$ does not hold \"in all cases\": a pure translation "
               "($\\alpha = 0$) has $u = \\Delta T/|\\Delta T|$, no axis point and no finite pitch."),
    CourseNote("orientation", "RPY, ZYZ, axis–angle, quaternion", "Displacements and orientation",
               "Roll–pitch–yaw is $R = R_z(\\text{yaw})\\,R_y(\\text{pitch})\\,R_x(\\text{roll})$: "
               "about the fixed x, then fixed y, then fixed z axes (the composition the summary "
               "describes is $R_x R_y R_z$); it is singular at pitch $= \\pm\\pi/2$, not at "
               "$\\pm\\pi$. ZYZ is $R_z(\\varphi)\\,R_y(\\theta)\\,R_z(\\psi)$, singular at "
               "$\\theta = 0$ and $\\pi$. Both have two solution sets away from the singularity. "
               "The axis–angle has $\\alpha \\in [0, \\pi]$; the unit quaternion "
               "$[\\eta, \\varepsilon] = [\\cos\\frac{\\alpha}{2}, \\sin\\frac{\\alpha}{2} u]$ is "
               "given with $\\eta \\ge 0$ ($q$ and $-q$ are the same rotation)."),
    # -- dynamics ----------------------------------------------------------------
    CourseNote("pseudo-inertia", "Entries of the pseudo-inertia matrix", "Dynamics",
               "$J = \\int p\\,p^T dm$ with homogeneous $p = [x, y, z, 1]^T$: the upper-left block "
               "holds $\\int x^2 dm$, $\\int xy\\,dm$, …, the last column $m x_G, m y_G, m z_G, m$. "
               "Its off-diagonal entries are $+\\int xy\\,dm$, the opposite of the classical "
               "tensor's products of inertia: \"$I_{ab} = -J_{ab}$\" holds only when $J_{ab}$ "
               "means the entry of the classical tensor. From the classical tensor $I_G$ about the "
               "centre of mass $c$ (the problem file's `inertia`): "
               "$J_{3\\times3} = \\tfrac12\\operatorname{tr}(I_G)\\,\\mathbb{1} - I_G + m\\,c\\,c^T$. "
               "A point mass is not zero \"except $I_{xx}$\": its last row and column hold "
               "$m x_G$ and $m$ too."),
    CourseNote("pseudo-scalar-product", "The pseudo scalar product", "Dynamics",
               "$A \\otimes B = A_{32}B_{32} + A_{13}B_{13} + A_{21}B_{21} + A_{14}B_{14} + "
               "A_{24}B_{24} + A_{34}B_{34}$: the first term uses entry [3,2], not [3,1] as "
               "in the summary's text (its own program is right). $\\Phi \\otimes W = C\\cdot\\omega "
               "+ F\\cdot v$ is the power when both are in the same frame and $W$ is the absolute "
               "velocity matrix; the generalized force of joint $i$ is "
               "$f_i = (\\sum_{j \\ge i} {}^{0}\\Phi_j) \\otimes {}^{0}L_i$."),
    CourseNote("matrix-of-actions", "The matrix of actions", "Dynamics",
               "$\\Phi = \\sum (F P^T - P F^T) + [C]$, where the moment is about the origin of the "
               "frame $\\Phi$ is written in, and a change of frame is $M\\,\\Phi\\,M^T$ (the same "
               "$M$ on both sides: the summary's program multiplies by ${}^{0}M_2^T$ on the "
               "right). Each link's $\\Phi$ collects $+$ its own actuator, $-$ the next joint's "
               "reaction and the external loads on it; force components given in another frame "
               "are rotated first. In the summary's example the torques $C_1$ and $C_2$ are "
               "swapped in $C_{tot}$, and in the one-link arm the third row of ${}^{1}\\Phi_1$ is "
               "$[0, C + FL/3, 0, -F]$ (the diagonal of $\\Phi$ is always zero)."),
    CourseNote("gravity", "Gravity and potential energy", "Dynamics",
               "$z$ is vertical (perpendicular to the floor, not parallel to it) with gravity "
               "$(0, 0, -g)$ by default. $H_g$ holds the gravity vector in its last column and "
               "$U = -\\operatorname{tr}(H_g\\,{}^{0}J)$, which is $m g z_G$; "
               "$T = \\tfrac12\\operatorname{tr}(W J W^T)$. The summary's $T_2 = \\tfrac12 m_2 L^2 "
               "\\theta^2$ is $\\tfrac12 m_2 L^2 \\dot\\theta^2$."),
    CourseNote("one-link-arm", "The one-link arm: the force and the motions", "Dynamics",
               "The summary's force $F$ acts at $\\tfrac23 L$ from the joint with components "
               "$(0, 0, -F)$ in frame 1: it turns with the link, and $f_\\theta = C - \\tfrac23 F L$. "
               "Read with components in frame 0 it would give $C - \\tfrac23 F L\\cos\\theta$, so "
               "a problem file says which frame the components are in (`in`). The equation of "
               "motion is $(\\tfrac{m_1}{3} + m_2)L^2\\ddot\\theta + (\\tfrac{m_1}{2} + m_2)gL\\cos"
               "\\theta = C - \\tfrac23 F L$. With a constant torque too weak to lift the arm, the "
               "lower turning point solves $C\\theta^* = G\\sin\\theta^*$, $G = (\\tfrac{m_1}{2} + "
               "m_2)gL$ — it is $-\\pi/2$ only for one value of $C$; with a stronger torque the "
               "acceleration $(C - G\\cos\\theta)/I$ is not constant, and without friction the arm "
               "spins ever faster."),
    CourseNote("lagrange", "Lagrange's equations and the generalized forces", "Dynamics",
               "$\\frac{d}{dt}\\frac{\\partial\\mathcal L}{\\partial\\dot q_i} - \\frac{\\partial"
               "\\mathcal L}{\\partial q_i} = f_i$ with $\\mathcal L = T - U$ and $f_i$ the "
               "generalized forces applied (actuator plus external loads). robosolve writes them "
               "as $M(q)\\ddot q + c(q, \\dot q) + g(q) = f$."),
    # -- motion -------------------------------------------------------------------
    CourseNote("motion-sync", "Synchronizing the joints' motions", "Motion",
               "Each joint alone needs $T_i = \\sqrt{4|\\Delta_i|/a_i}$ (bang-bang); the common "
               "time is the largest, $T = \\max T_i$ — the summary's program takes joint 1's time, "
               "right only when joint 1 is the slowest. The other joints are slowed to "
               "$a_i = 4|\\Delta_i|/T^2$; magnitudes are used ($\\sqrt{}$ of a negative "
               "displacement is imaginary) and the sign goes into the profile. The summary's "
               "example \"from 2 to −2 in 2 s with a maximum acceleration of 2\" actually uses an "
               "acceleration of 4; with 2 the move needs $T = 2\\sqrt2$ s."),
    CourseNote("torque-jumps", "Torques of a bang-bang motion", "Motion",
               "A bang-bang profile has steps in its acceleration, so the actuator torques "
               "$M(q)\\ddot q + \\dots$ jump at $0$, $T/2$ and $T$; at a jump both one-sided values "
               "are real and the peak is the larger in magnitude."),
    # -- mechanisms ---------------------------------------------------------------
    CourseNote("mobility", "Degrees of freedom of a mechanism", "Mechanisms",
               "Grübler's $n = 3(m - 1) - 2c_1 - c_2$ is the planar count; in space "
               "(Kutzbach) $n = 6(m - 1) - 5c_1 - 4c_2 - 3c_3$, with $m$ counting the base and "
               "$c_k$ the joints that leave $k$ degrees of freedom. The summary's five-bar "
               "parallel robot has $3\\cdot4 - 2\\cdot5 = 2$ DOF, not 3. A spherical joint "
               "leaves 3 rotations; the two-rotation joint is the universal (Cardan) joint."),
)

NOTES: dict[str, CourseNote] = {n.anchor: n for n in _NOTES}

LINK_RE = re.compile(r"\(#note-([a-z0-9-]+)\)")


def note_link(anchor: str, label: str | None = None) -> str:
    """A Markdown link to the note, e.g. `[course note: H is Ẇ + W², …](#note-h-matrix)`."""
    note = NOTES[anchor]           # KeyError: a citation of a note that does not exist
    return f"[{label or 'course note: ' + note.title}](#note-{anchor})"


def cited(texts) -> list[str]:
    """Anchors cited in `texts`, in the order of the notes page."""
    found = set()
    for t in texts:
        found.update(LINK_RE.findall(t or ""))
    return [a for a in NOTES if a in found]


def note_block(note: CourseNote, heading: str = "###") -> str:
    """One note as Markdown with an explicit anchor (GitHub keeps `id` as `user-content-…`
    and still follows `#note-…` links to it; the HTML renderer keeps it as is)."""
    return f'{heading} <a id="note-{note.anchor}"></a>{note.title}\n\n{note.body}'


def notes_page() -> str:
    """docs/course-notes.md."""
    out = ["# Notes on the course summary",
           "Where the course summary is wrong or ambiguous, and what robosolve does instead. "
           "Every correction was re-derived with sympy and checked numerically against "
           "independent references (Robotics Toolbox, spatialmath, sympy.physics.mechanics); "
           "the tests cite them. Reports copy the notes they rely on into their own last "
           "section, so a report can be read alone; this page collects them all.",
           "Notation: ${}^{i}M_{j}$ is the pose of frame $j$ in frame $i$; $c_1 = \\cos\\theta_1$, "
           "$s_{12} = \\sin(\\theta_1 + \\theta_2)$; matrix entries are 1-based [row, column].",
           "## Contents"]
    topics: dict[str, list[CourseNote]] = {}
    for n in _NOTES:
        topics.setdefault(n.topic, []).append(n)
    out.append("\n".join(f"- {topic}: " + ", ".join(f"[{n.title}](#note-{n.anchor})" for n in notes)
                         for topic, notes in topics.items()))
    for topic, notes in topics.items():
        out.append(f"## {topic}")
        out += [note_block(n) for n in notes]
    return "\n\n".join(out) + "\n"


if __name__ == "__main__":      # python -m robosolve.core.course_notes > docs/course-notes.md
    import sys

    sys.stdout.write(notes_page())
