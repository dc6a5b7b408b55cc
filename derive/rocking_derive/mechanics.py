"""Kinematics, energies and Lagrange's equations of a rocking model, in CasADi SX.

Conventions (equations.md section 0): the origin is at the active pivot corner; theta > 0 is a
clockwise rotation about the right corner (s = +1), theta < 0 about the left corner (s = -1). The
pivot sits at the body coordinate X = s B from the base centre, so the sign s enters only through
b = s B. u is the column-top displacement relative to the base, perpendicular to the column axis;
with a basis of n shape functions the deflection is sum u_i psi_i and q = [theta, u_1..u_n].

Velocities are taken in the body frame, where a point at body coordinates (X, Y) relative to the
pivot has |v|^2 = (X' + theta' Y)^2 + (Y' - theta' X)^2: the kinetic energy then contains no
trigonometric function at all, as (A3)-(A4) do, and nothing has to be simplified.

One coordinate keeps the one-coordinate derivation literally (the same CasADi expressions, so the
same bytes of generated code): sums over the basis start from their first term, and the contact
and impact systems are solved in closed form there. The symmetric positive definite systems (mass
matrices, stiffness; the rocking phase's for any number of coordinates) are solved by an LDL^T
factorisation written out symbolically (``solve_spd``): straight-line, exact in rational
operations, no square root, no pivoting.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from fractions import Fraction

import casadi as ca

from .models import BaseMass, ColumnMass, LumpedMass, Variant


def _only(values: list, what: str):
    if len(values) != 1:
        raise ValueError(f"a model with {len(values)} deformation coordinates has no single {what}")
    return values[0]


@dataclass
class Symbols:
    """The symbolic inputs shared by every function of one variant: one ``us``, ``u_dots`` and
    ``u_ddots`` per deformation coordinate (``u``, ``u_dot``, ``u_ddot`` for a one-coordinate
    model)."""

    theta: ca.SX
    us: list[ca.SX]
    theta_dot: ca.SX
    u_dots: list[ca.SX]
    ug: ca.SX  # ground acceleration
    s: ca.SX  # active pivot, +1 right corner, -1 left corner
    u_ddots: list[ca.SX]  # free symbols for the column accelerations (errata comparisons only)
    params: dict[str, ca.SX]

    @staticmethod
    def create(variant: Variant) -> "Symbols":
        sym = ca.SX.sym
        n = variant.model.coordinates

        def names(stem):
            return [stem] if n == 1 else [f"{stem}_{i + 1}" for i in range(n)]

        theta, us = sym("theta"), [sym(v) for v in names("u")]
        theta_dot, u_dots = sym("theta_dot"), [sym(v) for v in names("u_dot")]
        ug, s, u_ddots = sym("ug"), sym("s"), [sym(v) for v in names("u_ddot")]
        return Symbols(theta, us, theta_dot, u_dots, ug, s, u_ddots,
                       {p.name: sym(p.name) for p in variant.model.params})

    @property
    def u(self) -> ca.SX:
        return _only(self.us, "u")

    @property
    def u_dot(self) -> ca.SX:
        return _only(self.u_dots, "u'")

    @property
    def u_ddot(self) -> ca.SX:
        return _only(self.u_ddots, "u''")


def total(terms) -> ca.SX:
    """t_0 + t_1 + ..., from the first term: one term is itself (no addition of a zero)."""
    terms = list(terms)
    out = terms[0]
    for t in terms[1:]:
        out = out + t
    return out


def dot(a, b) -> ca.SX:
    """a_0 b_0 + a_1 b_1 + ...; for one coordinate the product a_0 b_0 itself."""
    return total(x * y for x, y in zip(a, b, strict=True))


def solve_linear(residual: ca.SX, x: ca.SX) -> ca.SX:
    """The root of residual(x) = a x + c, which must be affine in x."""
    a = ca.jacobian(residual, x)
    if ca.depends_on(a, x):
        raise ValueError("solve_linear: the residual is not affine in the unknown")
    return -ca.substitute(residual, x, ca.SX(0)) / a


def solve_spd(a, b: list, order: list[int] | None = None) -> list:
    """x with A x = b for a symmetric positive definite A (an SX matrix or nested lists, of which
    only the upper triangle is read), by A = L D L^T written out: straight-line, rational, no
    pivoting for stability (a mass or stiffness matrix needs none). ``order`` is the order in which
    the unknowns are eliminated (default: as given); it changes the expressions, not the solution."""
    n = len(b)
    idx = list(range(n)) if order is None else list(order)
    if sorted(idx) != list(range(n)):
        raise ValueError(f"solve_spd: {order} is not an order of {n} unknowns")

    def entry(i, j):
        return a_entry(a, idx[i], idx[j])

    def minus(value, terms):
        return value - total(terms) if terms else value

    low = [[None] * n for _ in range(n)]
    d = [None] * n
    for j in range(n):
        d[j] = minus(entry(j, j), [low[j][k] ** 2 * d[k] for k in range(j)])
        for i in range(j + 1, n):
            low[i][j] = minus(entry(i, j), [low[i][k] * low[j][k] * d[k] for k in range(j)]) / d[j]
    y = []
    for i in range(n):
        y.append(minus(b[idx[i]], [low[i][k] * y[k] for k in range(i)]))
    x = [None] * n
    for i in reversed(range(n)):
        x[idx[i]] = minus(y[i] / d[i], [low[k][i] * x[idx[k]] for k in range(i + 1, n)])
    return x


def a_entry(a, i: int, j: int):
    """Entry (i, j) of a symmetric matrix of which only the upper triangle is read."""
    i, j = min(i, j), max(i, j)
    return a[i, j] if isinstance(a, ca.SX) else a[i][j]


def at(expr: ca.SX, pairs: list[tuple[ca.SX, object]]) -> ca.SX:
    """Substitute several symbols at once."""
    if not pairs:
        return expr
    syms = ca.vertcat(*[p[0] for p in pairs])
    vals = ca.vertcat(*[ca.SX(p[1]) if not isinstance(p[1], ca.SX) else p[1] for p in pairs])
    return ca.substitute(expr, syms, vals)


class Mechanics:
    """Everything derived for one variant. ``rigid`` freezes u; ``small_angle`` linearises theta."""

    def __init__(self, variant: Variant, symbols: Symbols):
        self.variant = variant
        self.sym = symbols
        model = variant.model
        self.basis = model.basis
        self.n = len(self.basis)
        if variant.rigid and self.n > 1:
            raise ValueError(f"variant {variant.name!r}: a rigid column has no deformation coordinates: "
                             "make it a rigid variant of a one-function model with the same masses")
        self.moments = self.basis.moments()
        # Parameters, with removed masses replaced by the constant 0 before any derivation.
        self.P = dict(symbols.params)
        for name in variant.remove:
            self.P[name] = ca.SX(0)
        P = self.P
        self.H, self.B, self.g = P["h"], P["b"], P["g"]
        self.rigid = variant.rigid
        self.theta, self.theta_dot = symbols.theta, symbols.theta_dot
        self.us = [ca.SX(0)] if self.rigid else list(symbols.us)
        self.u_dots = [ca.SX(0)] if self.rigid else list(symbols.u_dots)
        self.s = symbols.s
        self.b = self.s * self.B  # pivot offset from the base centre
        self.ug = symbols.ug
        if variant.small_angle:
            self.sin, self.cos = self.theta, 1 - self.theta**2 / 2
        else:
            self.sin, self.cos = ca.sin(self.theta), ca.cos(self.theta)
        self.q = ca.vertcat(self.theta) if self.rigid else ca.vertcat(self.theta, *self.us)
        self.qd = ca.vertcat(self.theta_dot) if self.rigid else ca.vertcat(self.theta_dot, *self.u_dots)

    @property
    def u(self) -> ca.SX:
        """The deformation coordinate of a one-coordinate model."""
        return _only(self.us, "u")

    @property
    def u_dot(self) -> ca.SX:
        return _only(self.u_dots, "u'")

    def u_at(self, values=None) -> list[tuple[ca.SX, object]]:
        """Substitution pairs u_i -> values_i (0 when not given)."""
        values = [0] * self.n if values is None else values
        return list(zip(self.us, values, strict=True))

    # --- summing over the masses --------------------------------------------------------------

    def _column_integral(self, f) -> ca.SX:
        """Integral over eta in [0, 1] of f(psi_1..psi_n (eta), eta H), exact for f quadratic in
        (eta, psi_1..psi_n): the basis's moments weighted by f's Taylor coefficients."""
        eta = ca.SX.sym("eta")
        psis = [ca.SX.sym("psi")] if self.n == 1 else [ca.SX.sym(f"psi_{i + 1}") for i in range(self.n)]
        q = f(tuple(psis), eta * self.H)
        z = ca.vertcat(eta, *psis)
        hess, grad = ca.hessian(q, z)
        if ca.depends_on(hess, z):
            raise ValueError("column integrand is not quadratic in (eta, psi)")
        zero = [(eta, 0)] + [(p, 0) for p in psis]
        mom, n = self.moments, range(self.n)
        terms = [at(q, zero) * mom.eta["1"], at(grad[0], zero) * mom.eta["eta"]]
        terms += [at(grad[1 + i], zero) * mom.psi[i] for i in n]
        terms += [hess[0, 0] * mom.half_eta2]
        terms += [hess[0, 1 + i] * mom.eta_psi[i] for i in n]
        terms += [hess[1 + i, 1 + j] * (mom.half_psi2[i] if i == j else mom.psi_psi[i][j])
                  for i in n for j in n if j >= i]
        return total(terms)

    def over_points(self, f, base=True) -> ca.SX:
        """Sum over all masses of mass * f(psis, y), with psis the shape functions at the mass point
        (its body abscissa from the base centre is sum u_i psi_i) and y its height above the base."""
        total_ = ca.SX(0)
        for mass in self.variant.model.masses:
            m = self.P[mass.mass]
            if isinstance(mass, ColumnMass):
                total_ += m * self._column_integral(f)
            elif isinstance(mass, LumpedMass):
                eta = self.P[mass.eta] if isinstance(mass.eta, str) else mass.eta
                psis = tuple(float(v) if isinstance(v, Fraction) else v for v in self.basis.values(eta))
                eta_f = float(eta) if isinstance(eta, Fraction) else eta
                total_ += m * f(psis, eta_f * self.H)
            elif isinstance(mass, BaseMass):
                if base:
                    total_ += m * f((ca.SX(0),) * self.n, ca.SX(0))
            else:
                raise TypeError(f"unknown mass kind {mass!r}")
        return total_

    def over_masses(self, f, us=None, u_dots=None, base=True) -> ca.SX:
        """Sum over all masses of mass * f(X_c, Y, X_c', Y'), body coordinates from the base centre."""
        us = self.us if us is None else us
        u_dots = self.u_dots if u_dots is None else u_dots
        return self.over_points(lambda psis, y: f(dot(us, psis), y, dot(u_dots, psis), ca.SX(0)), base)

    def base_inertia_about_pivot(self) -> ca.SX:
        return sum((self.P[m.inertia] for m in self.variant.model.masses if isinstance(m, BaseMass)), ca.SX(0))

    def plate_inertia(self) -> ca.SX:
        """I_bc of thin rectangular base plates, m_b (B^2/3 + B^2) = 4/3 m_b B^2 (the unit of gamma_ib)."""
        return sum((4 * self.P[m.mass] * self.B**2 / 3 for m in self.variant.model.masses
                    if isinstance(m, BaseMass)), ca.SX(0))

    def base_spin_inertia(self) -> ca.SX:
        """I_b about the base centre: I_bc - m_b B^2 (written with b^2 = B^2)."""
        total_ = ca.SX(0)
        for m in self.variant.model.masses:
            if isinstance(m, BaseMass):
                total_ += self.P[m.inertia] - self.P[m.mass] * self.B**2
        return total_

    # --- energies ------------------------------------------------------------------------------

    def kinetic(self, theta_dot=None, us=None, u_dots=None, b=None) -> ca.SX:
        """T, eq (A4): rotation about the pivot plus the deflection rate."""
        th = self.theta_dot if theta_dot is None else theta_dot
        b = self.b if b is None else b

        def v2(xc, y, xcd, yd):
            xp = xc - b
            return (xcd + th * y) ** 2 + (yd - th * xp) ** 2

        return self.over_masses(v2, us, u_dots, base=False) / 2 + self.base_inertia_about_pivot() * th**2 / 2

    def world_sums(self):
        """(sum m x, sum m y) in the world frame with the origin at the pivot, eq (A1)."""
        b, c, s = self.b, self.cos, self.sin
        sx = self.over_masses(lambda xc, y, xcd, yd: (xc - b) * c + y * s)
        sy = self.over_masses(lambda xc, y, xcd, yd: -(xc - b) * s + y * c)
        return sx, sy

    def potentials(self):
        """(V_g gravity, V_s strain, V_a d'Alembert of the ground acceleration), eq (A6) corrected."""
        sx, sy = self.world_sums()
        return self.g * sy, self.strain(self.us), self.ug * sx

    def strain(self, us) -> ca.SX:
        """V_s = 1/2 u^T K u (one coordinate: k~ u^2 / 2)."""
        k, n = self.stiffness(), range(self.n)
        quadratic = total([k[i][i] * us[i] ** 2 for i in n]
                          + [2 * k[i][j] * us[i] * us[j] for i in n for j in n if j > i])
        return quadratic / 2

    def stiffness(self) -> list[list[ca.SX]]:
        """K of the u_i, eq (5) generalised: EI / H^3 times the integrals of psi_i'' psi_j''."""
        return [[self.P["ei"] / self.H**3 * v for v in row] for row in self.moments.stiffness]

    def k_tilde(self) -> ca.SX:
        """Generalised stiffness of one coordinate, eq (5): EI / H^3 times the integral of psi''^2."""
        return _only(self.stiffness(), "k~")[0]

    def momentum_x(self) -> ca.SX:
        """Horizontal momentum P_x = d/dt sum m x, consistent with V_a (so dE/dt = -ug P_x - u'^T C u')."""
        sx, _ = self.world_sums()
        return ca.mtimes(ca.jacobian(sx, self.q), self.qd)

    # --- the fixed-base (full-contact) quantities ------------------------------------------------

    def contact_lagrangian(self):
        """T and V in full contact (theta = theta' = 0), for the flexible column."""
        t = at(self.kinetic(), [(self.theta_dot, 0)])
        v_g, v_s, v_a = self.potentials()
        v = at(v_g + v_s + v_a, [(self.theta, 0)])
        return t, v

    def m_tilde(self) -> ca.SX:
        t, _ = self.contact_lagrangian()
        return at(ca.hessian(t, self.u_dot)[0], [(self.u, 0)])

    def mass_block(self) -> ca.SX:
        """M of the u_i: the Hessian of T in the u_i' (the column's mass distribution: constant)."""
        t, _ = self.contact_lagrangian()
        return at(ca.hessian(t, ca.vertcat(*self.u_dots))[0], self.u_at())

    def omega_n(self) -> ca.SX:
        return ca.sqrt(self.k_tilde() / self.m_tilde())

    def damping_c(self) -> ca.SX:
        """c = 2 zeta omega_n m~: zeta is the fixed-base damping ratio of the column."""
        return 2 * self.P["zeta"] * self.omega_n() * self.m_tilde()

    def damping_force(self, i: int) -> ca.SX:
        """(C u')_i: one coordinate, c u' with c of eq (19); several, the modal damping matrix C of
        the parameters (rocking_kernels::modes computes it from the fixed-base modes)."""
        if self.n == 1:
            return self.damping_c() * self.u_dot
        return total(self.P[f"c_{min(i, j) + 1}_{max(i, j) + 1}"] * self.u_dots[j] for j in range(self.n))

    def damping_power(self) -> ca.SX:
        """u'^T C u', the power the damping takes."""
        return total(self.damping_force(i) * self.u_dots[i] for i in range(self.n)) if self.n > 1 else \
            self.damping_c() * self.u_dot**2

    def contact_accel(self) -> ca.SX:
        """u'' in full contact of a one-coordinate model, eq (3)."""
        return _only(self.contact_accels(), "u''")

    def contact_accels(self) -> list[ca.SX]:
        """The u_i'' in full contact, eq (3) generalised; the pivot sign drops out (checked by the
        caller)."""
        if self.rigid:
            return [ca.SX(0)]
        t, v = self.contact_lagrangian()
        lag = t - v
        if self.n == 1:
            m = ca.hessian(t, self.u_dot)[0]
            rhs = (
                ca.gradient(lag, self.u)
                - ca.jacobian(ca.gradient(lag, self.u_dot), self.u) * self.u_dot
                - self.damping_c() * self.u_dot
            )
            return [at(rhs / m, [(self.s, 1)])]
        m = ca.hessian(t, ca.vertcat(*self.u_dots))[0]
        return [at(a, [(self.s, 1)]) for a in solve_spd(m, self.contact_residual(lag))]

    def contact_residual(self, lag=None) -> list[ca.SX]:
        """The generalised forces on the u_i in full contact, which M u'' equals (several
        coordinates)."""
        if lag is None:
            t, v = self.contact_lagrangian()
            lag = t - v
        u, ud = ca.vertcat(*self.us), ca.vertcat(*self.u_dots)
        rhs = ca.gradient(lag, u) - ca.mtimes(ca.jacobian(ca.gradient(lag, ud), u), ud)
        return [rhs[i] - self.damping_force(i) for i in range(self.n)]

    # --- rocking about corner s --------------------------------------------------------------

    def equations(self):
        """(M, F) of M q'' = F while rocking, from Lagrange's equations (A7)-(A8)."""
        t = self.kinetic()
        v_g, v_s, v_a = self.potentials()
        lag = t - v_g - v_s - v_a
        mass = ca.hessian(t, self.qd)[0]
        force = ca.gradient(lag, self.q) - ca.mtimes(ca.jacobian(ca.gradient(lag, self.qd), self.q), self.qd)
        if not self.rigid:
            for i in range(self.n):
                force[1 + i] -= self.damping_force(i)
        return mass, force

    def accelerations(self) -> list[ca.SX]:
        """[theta'', u_1''..u_n''] while rocking: M q'' = F by LDL^T.

        The coordinates whose block of M is constant (the u_i: the column's mass distribution) are
        eliminated first and theta last. Then their pivots and multipliers divide by constants,
        and the only division by a function of the state is by theta's pivot, the Schur
        complement m_tt - m_tu^T M_uu^-1 m_tu: in the Taylor kernels one series division per
        order, instead of one per coordinate and the products that undo them."""
        mass, force = self.equations()
        dim = 1 + self.n

        def constant(i, j):
            return not ca.depends_on(a_entry(mass, i, j), self.q)

        block = [i for i in range(dim) if constant(i, i)]
        block = [i for i in block if all(constant(i, j) for j in block)]
        order = block + [i for i in range(dim) if i not in block]
        return solve_spd(mass, [force[i] for i in range(dim)], order)

    def uplift(self) -> ca.SX:
        """f_s of eq (24): the base starts to rock about corner s when f_s > 0.

        In full contact theta'' = 0 requires the ground to supply the moment M_tu u''_fc - F_theta;
        f_s = s (F_theta - M_tu u''_fc) is the moment that would turn the body about corner s.
        """
        mass, force = self.equations()
        rest = [(self.theta, 0), (self.theta_dot, 0)]
        f_theta = at(force[0], rest)
        if self.rigid:
            return self.s * f_theta
        if self.n == 1:
            return self.s * (f_theta - at(mass[0, 1], rest) * self.contact_accel())
        coupling = [at(mass[0, 1 + i], rest) for i in range(self.n)]
        return self.s * (f_theta - dot(coupling, self.contact_accels()))

    # --- section forces at the column base and the ground reaction -----------------------------

    def base_forces(self, theta_ddot, u_ddots, w_ddot=None) -> dict[str, ca.SX]:
        """The section forces at the column base and the ground reaction, by Newton's law for every
        mass, for a motion with the accelerations theta'' and u_i''.

        The section is the column's foot at the base centre O (the thin plate's centre, on the line
        of the pivots). Body components: X along the plate (towards positive u), Y up the column
        axis. A mass point at (X, Y) = (sum u_i psi_i, eta H) from O is at r = Rot(theta) (X - b, Y)
        from the pivot, with Rot' = Rot J (J (X, Y) = (Y, -X), theta clockwise), so its absolute
        acceleration in body components is
            a = theta'' J (X - b, Y) - theta'^2 (X - b, Y) + 2 theta' J (X', 0) + (X'', 0) + ug (cos, sin)
        and gravity is g (sin, -cos). f = a - gravity is the force per unit mass its supports must
        supply. Over the column and the masses on it, the sum of f is the force of the base plate
        on the column (X: shear, Y: axial force, compression positive), and the sum of X f_Y - Y f_X
        is the plate's moment on the column about O, counter-clockwise: the column's moment on the
        plate in the sense of theta (clockwise), of the sign of the curvature EI psi''(0) u / H^2.
        Over every mass, the base's included, the sum of f is the ground's force on the body at the
        pivot, turned into the world frame (x, y up).

        The rotation is exact even in a small-angle variant: its forces are those of the motion
        its equations predict (the linearisation enters only through theta'' and u'').

        ``w_ddot``: on compliant ground (free_base.py) the pivot sinks with the acceleration w''
        (world frame (0, -w'')), which adds (w'' sin, -w'' cos) to every point's acceleration in
        body components (None: the rigid surface, the expressions as they were).
        """
        sin, cos = ca.sin(self.theta), ca.cos(self.theta)
        b, g, ug, thd = self.b, self.g, self.ug, self.theta_dot

        def supplied(psis, y):
            """(f_X, f_Y) at the point (sum u_i psi_i, y)."""
            x = dot(self.us, psis)
            coriolis = total(2 * thd * ud * p for ud, p in zip(self.u_dots, psis, strict=True))
            f_x = theta_ddot * y - thd**2 * (x - b) + dot(u_ddots, psis) + ug * cos - g * sin
            f_y = -theta_ddot * (x - b) - thd**2 * y - coriolis + ug * sin + g * cos
            if w_ddot is not None:
                f_x, f_y = f_x + w_ddot * sin, f_y - w_ddot * cos
            return f_x, f_y

        def column(f):
            return self.over_points(f, base=False)

        moment = column(lambda psis, y: dot(self.us, psis) * supplied(psis, y)[1] - y * supplied(psis, y)[0])
        total_x = self.over_points(lambda psis, y: supplied(psis, y)[0])
        total_y = self.over_points(lambda psis, y: supplied(psis, y)[1])
        return {
            "moment": moment,
            "shear": column(lambda psis, y: supplied(psis, y)[0]),
            "axial": column(lambda psis, y: supplied(psis, y)[1]),
            # A rigid column has no curvature: its section moment is the equilibrium one.
            "moment_elastic": moment if self.rigid else self.elastic_moment(self.us),
            "reaction_h": cos * total_x + sin * total_y,
            "reaction_v": -sin * total_x + cos * total_y,
        }

    def contact_forces(self, u_ddots=None) -> dict[str, ca.SX]:
        """``base_forces`` in full contact (theta = theta' = theta'' = 0), with the u_i'' of eq (3)
        unless given. Nothing depends on the pivot then (checked)."""
        u_ddots = self.contact_accels() if u_ddots is None else u_ddots
        rest = [(self.theta, 0), (self.theta_dot, 0)]
        forces = {k: at(v, rest) for k, v in self.base_forces(ca.SX(0), u_ddots).items()}
        if any(ca.depends_on(v, self.s) for v in forces.values()):
            raise ValueError("the section forces in full contact depend on the pivot")
        return forces

    def static_uplift(self) -> dict[str, ca.SX]:
        """The quasi-static uplift about the right corner: the ground acceleration ug that, applied
        so slowly that u' = u'' = 0, makes f_+ = 0, the column's deflection u then and its elastic
        base moment. The equilibrium moment then is W B (f_s = s M_b - W B). Several coordinates:
        the static deflection of K u = -Gamma ug, ``u_uplift_i``."""
        rest = [(u_dot, 0) for u_dot in self.u_dots] + [(self.s, 1)]
        if self.n == 1:
            u_static = [solve_linear(at(self.contact_accel(), rest), self.u)]  # u'' = 0: u(ug)
        else:
            residual = ca.vertcat(*[at(r, rest) for r in self.contact_residual()])  # affine in u
            stiffness = -ca.jacobian(residual, ca.vertcat(*self.us))
            load = at(residual, self.u_at())
            u_static = solve_spd(stiffness, [load[i] for i in range(self.n)])
        f_plus = at(self.uplift(), rest + self.u_at(u_static))
        ug = solve_linear(f_plus, self.ug)
        us = [at(u, [(self.ug, ug)]) for u in u_static]
        weight = self.g * self.over_points(lambda psis, y: ca.SX(1))
        names = ["u_uplift"] if self.n == 1 else [f"u_uplift_{i + 1}" for i in range(self.n)]
        return {
            "weight": weight, "moment_uplift": weight * self.B, "ug_uplift": ug, **dict(zip(names, us)),
            "moment_elastic_uplift": self.elastic_moment(us),
        }

    def elastic_moment(self, us) -> ca.SX:
        """The bending moment EI sum psi_i''(0) u_i / H^2 of the deflection at the column base."""
        return total(self.P["ei"] / self.H**2 * f.curvature_at_base() * u
                     for f, u in zip(self.basis.functions, us, strict=True))

    # --- impacts (theta returns to 0 while rocking about s1 = s; the corner -s hits) ----------

    def angular_momentum(self, pivot_b, about_b, us, u_dots, theta_dot) -> ca.SX:
        """Clockwise angular momentum about the base point X = about_b, at theta = 0, for a motion
        that rotates about the pivot X = pivot_b (body frame = world frame at theta = 0)."""

        def moment(xc, y, xcd, yd):
            vx = xcd + theta_dot * y
            vy = yd - theta_dot * (xc - pivot_b)
            return y * vx - (xc - about_b) * vy

        return self.over_masses(moment, us, u_dots) + self.base_spin_inertia() * theta_dot

    def momentum_x_at_rest_angle(self, u_dots, theta_dot, us) -> ca.SX:
        return self.over_masses(lambda xc, y, xcd, yd: xcd + theta_dot * y, us, u_dots)

    def closest(self, u1d: list, constraint, target) -> list:
        """The velocities u' nearest u1d in the kinetic-energy norm of the column (its mass block
        M) with constraint(u') = target, for a constraint linear in u' with gradient c:
        u' = u1d + lambda M^-1 c, lambda = (target - constraint(u1d)) / (c^T M^-1 c)."""
        x = [ca.SX.sym(f"x_{i}") for i in range(self.n)]
        grad = ca.gradient(constraint(x), ca.vertcat(*x))
        if ca.depends_on(grad, ca.vertcat(*x)):
            raise ValueError("closest: the constraint is not linear in the velocities")
        c = [grad[i] for i in range(self.n)]
        w = solve_spd(self.mass_block(), c)
        lam = (target - constraint(u1d)) / dot(c, w)
        return [v + lam * wi for v, wi in zip(u1d, w)]

    def impact_maps(self, u1, u1d, th1d, general=None):
        """The candidate post-impact states of ADJex (26)-(30), Housner and VVEL (31)-(32), for the
        pre-impact u_i (list ``u1``), u_i' (``u1d``) and theta' (``th1d``). Several coordinates: each
        full-contact map's one scalar condition taken with the velocities nearest the pre-impact
        ones in the kinetic-energy norm (docs/modes.md); one coordinate: the paper's maps, which
        the general ones reduce to (``general=True`` forces them, for that check)."""
        general = self.n > 1 if general is None else general
        b1 = self.s * self.B
        b2 = -b1
        x = ca.SX.sym("x_unknown")
        e_before = self.kinetic(th1d, u1, u1d, b1)
        l_pre = self.angular_momentum(b1, b2, u1, u1d, th1d)
        maps = {"e_before": e_before}
        # Immediate rocking about the impacting corner, u' kept (ADJex (28)-(29), Housner).
        th2 = solve_linear(self.angular_momentum(b2, b2, u1, u1d, x) - l_pre, x)
        maps["theta_dot_rocking"] = th2
        maps["u_dot_rocking"] = list(u1d)
        maps["e_rocking"] = self.kinetic(th2, u1, u1d, b2)
        if self.rigid:
            return maps
        if not general:
            # Full contact from angular momentum (26)-(27).
            u2 = [solve_linear(self.angular_momentum(b2, b2, u1, [x], ca.SX(0)) - l_pre, x)]
            # Full contact from horizontal momentum (30).
            p_pre = self.momentum_x_at_rest_angle(u1d, th1d, u1)
            u_hm = [solve_linear(self.momentum_x_at_rest_angle([x], ca.SX(0), u1) - p_pre, x)]
        else:
            u2 = self.closest(u1d, lambda v: self.angular_momentum(b2, b2, u1, v, ca.SX(0)), l_pre)
            p_pre = self.momentum_x_at_rest_angle(u1d, th1d, u1)
            u_hm = self.closest(u1d, lambda v: self.momentum_x_at_rest_angle(v, ca.SX(0), u1), p_pre)
        maps["u_dot_contact"] = u2
        maps["e_contact"] = self.kinetic(ca.SX(0), u1, u2, b2)
        maps["u_dot_momentum"] = u_hm
        maps["e_momentum"] = self.kinetic(ca.SX(0), u1, u_hm, b2)
        # VVEL (31)-(32): the kinetic energy of the horizontal velocities survives, in full contact.
        e_vh = self.over_masses(lambda xc, y, xcd, yd: (xcd + th1d * y) ** 2, u1, u1d) / 2
        top = self.basis.values(Fraction(1))
        top = [float(v) for v in top]
        if not general:
            m_c = at(self.m_tilde(), [(self.u, _only(u1, "u"))])
            top_vx = _only(u1d, "u'") * top[0] + th1d * self.H
            maps["u_dot_vvel"] = [ca.sign(top_vx) * ca.sqrt(2 * e_vh / m_c)]
        else:
            # h_i = sum m psi_i v_x: the pre-impact horizontal velocity field projected on the basis
            # in the mass norm is M^-1 h; scaled to the energy e_vh, the top's velocity keeping its sign.
            h = [self.over_points(lambda psis, y, i=i: psis[i] * (dot(u1d, psis) + th1d * y))
                 for i in range(self.n)]
            w = solve_spd(self.mass_block(), h)
            top_vx = dot(u1d, top) + th1d * self.H
            kappa = ca.sign(top_vx) * ca.sign(dot(w, top)) * ca.sqrt(2 * e_vh / dot(h, w))
            maps["u_dot_vvel"] = [kappa * wi for wi in w]
        maps["e_vvel"] = e_vh
        return maps

    # --- reference quantities ------------------------------------------------------------------

    def rigid_gravity_profile(self):
        """V_g(theta) at u = 0, s = +1, which is A sin(theta) + C cos(theta) for a rigid body."""
        v_g, _, _ = self.potentials()
        v = at(v_g, self.u_at() + [(self.s, 1)])
        a = at(ca.jacobian(v, self.theta), [(self.theta, 0)])
        c = at(v, [(self.theta, 0)])
        return a, c


def flexible_twin(variant: Variant) -> Variant:
    """The same masses with a deformable column and exact rotations (for reference quantities)."""
    return replace(variant, rigid=False, small_angle=False)
