"""Forward kinematics, once for every algebra (pinocchio's Data): M, L, W, H of each frame.

`forward(description, algebra)` returns a `ChainData` that computes, on first use and once,

* ⁰M_f = ⁰M_p A_f (the chain product);
* ⁰Lᵢ for the motion of a frame: Σ over the frames g of its chain whose pose contains qᵢ of
  ⁰M_p(g) ᵖLᵢ ⁰M_p(g)⁻¹ (one term for an ordinary serial robot);
* ⁰W_{p,f} = Σᵢ ⁰Lᵢ q̇ᵢ over the joints of A_f, and Rivals: ⁰W_f = ⁰W_p + ⁰W_{p,f};
* ⁰H_{p,f} = ⁰Lᵢ q̈ᵢ + (⁰Lᵢ)² q̇ᵢ² for one joint with a constant twist, else ⁰M_p Ä A⁻¹ ⁰M_p⁻¹;
  Coriolis: ⁰H_f = ⁰H_p + 2 ⁰W_p ⁰W_{p,f} + ⁰H_{p,f};
* points: ⁰M_f [p; 1];
* the body-frame route (the dynamics engine's): ᵃM_f between a frame and an ancestor, and
  ᵇLᵢ = ⁰M_f⁻¹ ∂⁰M_f/∂qᵢ, built from the relative poses (small entries).

The algebra is a small strategy object; the entries are its own (sympy expressions, trig-ring
polynomials, floats):

* inputs from the description: `pose(f)` = A_f, `twist(f, i)` = ∂A_f/∂qᵢ A_f⁻¹ (in the
  parent), `acceleration(f)` = Ä_f A_f⁻¹, `rate(i, order)` = q̇ᵢ / q̈ᵢ (scalars),
  `coordinates(name)` = a point's coordinates in its frame; for the body-frame route,
  `body_twist(f, i)` = A_f⁻¹ ∂A_f/∂qᵢ;
* operations: `identity()`, `zero()`, `compose(a, b)` (pose products), `inverse(m)` (of a
  pose), `act(m, l)` (m l m⁻¹ of a twist: skew rotation block), `conjugate(m, a)` (m a m⁻¹
  of any 4×4), `add`, `scale(a, s)`, `mul(a, b)`, `tidy(a)` (the normal form of a product),
  `expand(a)` (of a sum), `point(m, p)`.

Each quantity asks only for what it needs: an algebra without rates (the ring) serves M, L,
points and the body-frame L.

The description needs `parent`, `chain`, `moved_by`, `joint_frame`, `constant_twist` and
`point_frame` (robosolve.model.description.ChainDescription; the notebook's `Robot` chain); the
body-frame route needs only `parent`, `chain` and `moved_by` (robosolve.dynamics.engine's
DynamicsEngine, its own description). This module imports nothing, so that it can be copied
into a notebook as it is.
"""

BASE = "0"


class ChainData:
    """The chain data of one description over one algebra (every quantity memoised)."""

    def __init__(self, description, algebra):
        self.description = description
        self.algebra = algebra
        self._memo = {("M", BASE): algebra.identity(), ("W", BASE): algebra.zero(),
                      ("H", BASE): algebra.zero()}

    def _get(self, key, build):
        memo = self._memo
        if key not in memo:
            memo[key] = build()
        return memo[key]

    # -- poses ------------------------------------------------------------
    def M(self, frame):
        """⁰M_f: the pose of `frame` in frame 0."""
        key = ("M", frame)
        if key in self._memo:
            return self._memo[key]
        parent = self.description.parent(frame)
        return self._get(key, lambda: self.algebra.compose(self.M(parent), self.algebra.pose(frame)))

    def point(self, name):
        """A point's coordinates in frame 0 (3 entries)."""
        frame = self.description.point_frame(name)
        return self._get(("point", name), lambda: self.algebra.point(
            self.M(frame), self.algebra.coordinates(name)))

    # -- L matrices ---------------------------------------------------------
    def twist(self, frame, index):
        """ᵖLᵢ: joint `index`'s twist in the parent of `frame` (the algebra's input)."""
        return self._get(("twist", frame, index), lambda: self.algebra.twist(frame, index))

    def moved_twist(self, frame, index):
        """⁰M_p ᵖLᵢ ⁰M_p⁻¹: the contribution of `frame`'s pose to ⁰Lᵢ."""
        parent = self.description.parent(frame)
        return self._get(("moved", frame, index), lambda: self.algebra.act(
            self.M(parent), self.twist(frame, index)))

    def L(self, index, frame=None):
        """⁰Lᵢ for the motion of `frame` (default: the frame joint `index` moves); zero when
        the joint does not move it."""
        desc = self.description
        frame = frame or desc.joint_frame(index)

        def build():
            total = self.algebra.zero()
            for f in desc.chain(frame):
                if index in desc.moved_by(f):
                    total = self.algebra.add(total, self.moved_twist(f, index))
            return total
        return self._get(("L", index, frame), build)

    # -- in the body frame (the dynamics engine's route: small entries) ------------------
    def relative(self, ancestor, frame):
        """ᵃM_f: the pose of `frame` in its ancestor `ancestor` (the identity when equal)."""
        if ancestor == frame:
            return self.algebra.identity()
        if ancestor == BASE:
            return self.M(frame)
        parent = self.description.parent(frame)
        return self._get(("rel", ancestor, frame), lambda: self.algebra.compose(
            self.relative(ancestor, parent), self.algebra.pose(frame)))

    def body_twist(self, frame, index):
        """A_f⁻¹ ∂A_f/∂qᵢ: joint `index`'s twist in `frame` itself (the algebra's input)."""
        return self._get(("body_twist", frame, index), lambda: self.algebra.body_twist(frame, index))

    def body_L(self, index, frame):
        """ᵇLᵢ = ⁰M_f⁻¹ ∂⁰M_f/∂qᵢ = Σ_g ᵍM_f⁻¹ (A_g⁻¹ ∂A_g/∂qᵢ) ᵍM_f over the frames g of the
        chain whose pose contains qᵢ: ⁰Lᵢ seen in `frame` (it depends only on the joints
        between joint i and `frame`)."""
        desc, alg = self.description, self.algebra

        def build():
            total = alg.zero()
            for g in desc.chain(frame):
                if index in desc.moved_by(g):
                    r = self.relative(g, frame)
                    total = alg.add(total, alg.mul(alg.mul(alg.inverse(r), self.body_twist(g, index)), r))
            return alg.tidy(total)
        return self._get(("body_L", index, frame), build)

    # -- velocities and accelerations ---------------------------------------
    def W_relative(self, frame):
        """⁰W_{p,f} = Σ ⁰Lᵢ q̇ᵢ over the joints of the frame's local pose."""
        alg = self.algebra

        def build():
            w = alg.zero()
            for i in self.description.moved_by(frame):
                w = alg.add(w, alg.scale(self.moved_twist(frame, i), alg.rate(i, 1)))
            return w
        return self._get(("W_rel", frame), build)

    def H_relative(self, frame):
        """⁰H_{p,f}: the relative acceleration matrix of `frame` in frame 0."""
        alg, desc = self.algebra, self.description

        def build():
            i = desc.constant_twist(frame)
            if i is not None:
                l0 = self.moved_twist(frame, i)
                return alg.add(alg.scale(l0, alg.rate(i, 2)),
                               alg.scale(alg.tidy(alg.mul(l0, l0)), alg.rate(i, 1) ** 2))
            return alg.tidy(alg.conjugate(self.M(desc.parent(frame)), alg.acceleration(frame)))
        return self._get(("H_rel", frame), build)

    def W(self, frame):
        """Rivals: ⁰W_f = ⁰W_p + ⁰W_{p,f}."""
        key = ("W", frame)
        if key in self._memo:
            return self._memo[key]
        parent = self.description.parent(frame)
        return self._get(key, lambda: self.algebra.expand(
            self.algebra.add(self.W(parent), self.W_relative(frame))))

    def H(self, frame):
        """Coriolis: ⁰H_f = ⁰H_p + 2 ⁰W_p ⁰W_{p,f} + ⁰H_{p,f}."""
        key = ("H", frame)
        if key in self._memo:
            return self._memo[key]
        alg = self.algebra
        parent = self.description.parent(frame)

        def build():
            coriolis = alg.scale(alg.mul(self.W(parent), self.W_relative(frame)), 2)
            return alg.expand(alg.add(alg.add(self.H(parent), coriolis), self.H_relative(frame)))
        return self._get(key, build)


def forward(description, algebra) -> ChainData:
    """The chain data of `description` over `algebra` (computed lazily, each entry once)."""
    return ChainData(description, algebra)
