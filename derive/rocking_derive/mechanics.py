"""Kinematics, energies and Lagrange's equations of a rocking model, in CasADi SX.

Conventions (equations.md section 0): the origin is at the active pivot corner; theta > 0 is a
clockwise rotation about the right corner (s = +1), theta < 0 about the left corner (s = -1). The
pivot sits at the body coordinate X = s B from the base centre, so the sign s enters only through
b = s B. u is the column-top displacement relative to the base, perpendicular to the column axis.

Velocities are taken in the body frame, where a point at body coordinates (X, Y) relative to the
pivot has |v|^2 = (X' + theta' Y)^2 + (Y' - theta' X)^2: the kinetic energy then contains no
trigonometric function at all, as (A3)-(A4) do, and nothing has to be simplified.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from fractions import Fraction

import casadi as ca

from .models import BaseMass, ColumnMass, LumpedMass, Variant


@dataclass
class Symbols:
    """The symbolic inputs shared by every function of one variant."""

    theta: ca.SX
    u: ca.SX
    theta_dot: ca.SX
    u_dot: ca.SX
    ug: ca.SX  # ground acceleration
    s: ca.SX  # active pivot, +1 right corner, -1 left corner
    u_ddot: ca.SX  # a free symbol for the column acceleration (errata comparisons only)
    params: dict[str, ca.SX]

    @staticmethod
    def create(variant: Variant) -> "Symbols":
        sym = ca.SX.sym
        return Symbols(
            sym("theta"), sym("u"), sym("theta_dot"), sym("u_dot"), sym("ug"), sym("s"), sym("u_ddot"),
            {p.name: sym(p.name) for p in variant.model.params},
        )


def solve_linear(residual: ca.SX, x: ca.SX) -> ca.SX:
    """The root of residual(x) = a x + c, which must be affine in x."""
    a = ca.jacobian(residual, x)
    if ca.depends_on(a, x):
        raise ValueError("solve_linear: the residual is not affine in the unknown")
    return -ca.substitute(residual, x, ca.SX(0)) / a


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
        self.moments = model.shape.moments()
        # Parameters, with removed masses replaced by the constant 0 before any derivation.
        self.P = dict(symbols.params)
        for name in variant.remove:
            self.P[name] = ca.SX(0)
        P = self.P
        self.H, self.B, self.g = P["h"], P["b"], P["g"]
        self.rigid = variant.rigid
        self.theta, self.theta_dot = symbols.theta, symbols.theta_dot
        self.u = ca.SX(0) if self.rigid else symbols.u
        self.u_dot = ca.SX(0) if self.rigid else symbols.u_dot
        self.s = symbols.s
        self.b = self.s * self.B  # pivot offset from the base centre
        self.ug = symbols.ug
        if variant.small_angle:
            self.sin, self.cos = self.theta, 1 - self.theta**2 / 2
        else:
            self.sin, self.cos = ca.sin(self.theta), ca.cos(self.theta)
        self.q = ca.vertcat(self.theta) if self.rigid else ca.vertcat(self.theta, self.u)
        self.qd = ca.vertcat(self.theta_dot) if self.rigid else ca.vertcat(self.theta_dot, self.u_dot)

    # --- summing over the masses --------------------------------------------------------------

    def _column_integral(self, f) -> ca.SX:
        """Integral over eta in [0, 1] of f(psi(eta), eta H), exact for f quadratic in (eta, psi)."""
        eta, psi = ca.SX.sym("eta"), ca.SX.sym("psi")
        q = f(psi, eta * self.H)
        z = ca.vertcat(eta, psi)
        hess, grad = ca.hessian(q, z)
        if ca.depends_on(hess, z):
            raise ValueError("column integrand is not quadratic in (eta, psi)")
        zero = [(eta, 0), (psi, 0)]
        mom = self.moments.values
        exact = self.moments.exact
        half = {k: (float(exact[k] / 2) if exact else mom[k] / 2) for k in ("eta2", "psi2")}
        total = (
            at(q, zero) * mom["1"]
            + at(grad[0], zero) * mom["eta"]
            + at(grad[1], zero) * mom["psi"]
            + hess[0, 0] * half["eta2"]
            + hess[0, 1] * mom["eta_psi"]
            + hess[1, 1] * half["psi2"]
        )
        return total

    def over_points(self, f, base=True) -> ca.SX:
        """Sum over all masses of mass * f(psi, y), with psi the shape function at the mass point
        (its body abscissa from the base centre is u psi) and y its height above the base."""
        total = ca.SX(0)
        shape = self.variant.model.shape
        for mass in self.variant.model.masses:
            m = self.P[mass.mass]
            if isinstance(mass, ColumnMass):
                total += m * self._column_integral(f)
            elif isinstance(mass, LumpedMass):
                eta = self.P[mass.eta] if isinstance(mass.eta, str) else mass.eta
                psi = shape.value(eta)
                psi = float(psi) if isinstance(psi, Fraction) else psi
                eta_f = float(eta) if isinstance(eta, Fraction) else eta
                total += m * f(psi, eta_f * self.H)
            elif isinstance(mass, BaseMass):
                if base:
                    total += m * f(ca.SX(0), ca.SX(0))
            else:
                raise TypeError(f"unknown mass kind {mass!r}")
        return total

    def over_masses(self, f, u=None, u_dot=None, base=True) -> ca.SX:
        """Sum over all masses of mass * f(X_c, Y, X_c', Y'), body coordinates from the base centre."""
        u = self.u if u is None else u
        u_dot = self.u_dot if u_dot is None else u_dot
        return self.over_points(lambda psi, y: f(u * psi, y, u_dot * psi, ca.SX(0)), base)

    def base_inertia_about_pivot(self) -> ca.SX:
        return sum((self.P[m.inertia] for m in self.variant.model.masses if isinstance(m, BaseMass)), ca.SX(0))

    def plate_inertia(self) -> ca.SX:
        """I_bc of thin rectangular base plates, m_b (B^2/3 + B^2) = 4/3 m_b B^2 (the unit of gamma_ib)."""
        return sum((4 * self.P[m.mass] * self.B**2 / 3 for m in self.variant.model.masses
                    if isinstance(m, BaseMass)), ca.SX(0))

    def base_spin_inertia(self) -> ca.SX:
        """I_b about the base centre: I_bc - m_b B^2 (written with b^2 = B^2)."""
        total = ca.SX(0)
        for m in self.variant.model.masses:
            if isinstance(m, BaseMass):
                total += self.P[m.inertia] - self.P[m.mass] * self.B**2
        return total

    # --- energies ------------------------------------------------------------------------------

    def kinetic(self, theta_dot=None, u=None, u_dot=None, b=None) -> ca.SX:
        """T, eq (A4): rotation about the pivot plus the deflection rate."""
        th = self.theta_dot if theta_dot is None else theta_dot
        b = self.b if b is None else b

        def v2(xc, y, xcd, yd):
            xp = xc - b
            return (xcd + th * y) ** 2 + (yd - th * xp) ** 2

        return self.over_masses(v2, u, u_dot, base=False) / 2 + self.base_inertia_about_pivot() * th**2 / 2

    def world_sums(self):
        """(sum m x, sum m y) in the world frame with the origin at the pivot, eq (A1)."""
        b, c, s = self.b, self.cos, self.sin
        sx = self.over_masses(lambda xc, y, xcd, yd: (xc - b) * c + y * s)
        sy = self.over_masses(lambda xc, y, xcd, yd: -(xc - b) * s + y * c)
        return sx, sy

    def potentials(self):
        """(V_g gravity, V_s strain, V_a d'Alembert of the ground acceleration), eq (A6) corrected."""
        sx, sy = self.world_sums()
        v_s = self.k_tilde() * self.u**2 / 2
        return self.g * sy, v_s, self.ug * sx

    def k_tilde(self) -> ca.SX:
        """Generalised stiffness, eq (5): EI / H^3 times the integral of psi''(eta)^2."""
        return self.P["ei"] / self.H**3 * self.moments.stiffness

    def momentum_x(self) -> ca.SX:
        """Horizontal momentum P_x = d/dt sum m x, consistent with V_a (so dE/dt = -ug P_x - c u'^2)."""
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

    def omega_n(self) -> ca.SX:
        return ca.sqrt(self.k_tilde() / self.m_tilde())

    def damping_c(self) -> ca.SX:
        """c = 2 zeta omega_n m~: zeta is the fixed-base damping ratio of the column."""
        return 2 * self.P["zeta"] * self.omega_n() * self.m_tilde()

    def contact_accel(self) -> ca.SX:
        """u'' in full contact, eq (3); the pivot sign drops out (checked by the caller)."""
        if self.rigid:
            return ca.SX(0)
        t, v = self.contact_lagrangian()
        lag = t - v
        m = ca.hessian(t, self.u_dot)[0]
        rhs = (
            ca.gradient(lag, self.u)
            - ca.jacobian(ca.gradient(lag, self.u_dot), self.u) * self.u_dot
            - self.damping_c() * self.u_dot
        )
        return at(rhs / m, [(self.s, 1)])

    # --- rocking about corner s --------------------------------------------------------------

    def equations(self):
        """(M, F) of M q'' = F while rocking, from Lagrange's equations (A7)-(A8)."""
        t = self.kinetic()
        v_g, v_s, v_a = self.potentials()
        lag = t - v_g - v_s - v_a
        mass = ca.hessian(t, self.qd)[0]
        force = ca.gradient(lag, self.q) - ca.mtimes(ca.jacobian(ca.gradient(lag, self.qd), self.q), self.qd)
        if not self.rigid:
            force[1] -= self.damping_c() * self.u_dot
        return mass, force

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
        return self.s * (f_theta - at(mass[0, 1], rest) * self.contact_accel())

    # --- section forces at the column base and the ground reaction -----------------------------

    def base_forces(self, theta_ddot, u_ddot) -> dict[str, ca.SX]:
        """The section forces at the column base and the ground reaction, by Newton's law for every
        mass, for a motion with the accelerations theta'' and u''.

        The section is the column's foot at the base centre O (the thin plate's centre, on the line
        of the pivots). Body components: X along the plate (towards positive u), Y up the column
        axis. A mass point at (X, Y) = (u psi, eta H) from O is at r = Rot(theta) (X - b, Y) from
        the pivot, with Rot' = Rot J (J (X, Y) = (Y, -X), theta clockwise), so its absolute
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
        """
        sin, cos = ca.sin(self.theta), ca.cos(self.theta)
        b, g, ug, thd = self.b, self.g, self.ug, self.theta_dot

        def supplied(psi, y):
            """(f_X, f_Y) at the point (u psi, y)."""
            x = self.u * psi
            f_x = theta_ddot * y - thd**2 * (x - b) + u_ddot * psi + ug * cos - g * sin
            f_y = -theta_ddot * (x - b) - thd**2 * y - 2 * thd * self.u_dot * psi + ug * sin + g * cos
            return f_x, f_y

        def column(f):
            return self.over_points(f, base=False)

        moment = column(lambda psi, y: self.u * psi * supplied(psi, y)[1] - y * supplied(psi, y)[0])
        total_x = self.over_points(lambda psi, y: supplied(psi, y)[0])
        total_y = self.over_points(lambda psi, y: supplied(psi, y)[1])
        return {
            "moment": moment,
            "shear": column(lambda psi, y: supplied(psi, y)[0]),
            "axial": column(lambda psi, y: supplied(psi, y)[1]),
            # A rigid column has no curvature: its section moment is the equilibrium one.
            "moment_elastic": moment if self.rigid else self.elastic_moment(self.u),
            "reaction_h": cos * total_x + sin * total_y,
            "reaction_v": -sin * total_x + cos * total_y,
        }

    def contact_forces(self, u_ddot=None) -> dict[str, ca.SX]:
        """``base_forces`` in full contact (theta = theta' = theta'' = 0), with u'' of eq (3) unless
        given. Nothing depends on the pivot then (checked)."""
        u_ddot = self.contact_accel() if u_ddot is None else u_ddot
        rest = [(self.theta, 0), (self.theta_dot, 0)]
        forces = {k: at(v, rest) for k, v in self.base_forces(ca.SX(0), u_ddot).items()}
        if any(ca.depends_on(v, self.s) for v in forces.values()):
            raise ValueError("the section forces in full contact depend on the pivot")
        return forces

    def static_uplift(self) -> dict[str, ca.SX]:
        """The quasi-static uplift about the right corner: the ground acceleration ug that, applied
        so slowly that u' = u'' = 0, makes f_+ = 0, the column's deflection u then and its elastic
        base moment. The equilibrium moment then is W B (f_s = s M_b - W B)."""
        rest = [(self.u_dot, 0), (self.s, 1)]
        u_static = solve_linear(at(self.contact_accel(), rest), self.u)  # u'' = 0: u(ug)
        f_plus = at(self.uplift(), rest + [(self.u, u_static)])
        ug = solve_linear(f_plus, self.ug)
        u = at(u_static, [(self.ug, ug)])
        weight = self.g * self.over_points(lambda psi, y: ca.SX(1))
        return {
            "weight": weight, "moment_uplift": weight * self.B, "ug_uplift": ug, "u_uplift": u,
            "moment_elastic_uplift": self.elastic_moment(u),
        }

    def elastic_moment(self, u) -> ca.SX:
        """The bending moment EI psi''(0) u / H^2 of the deflection u psi at the column base."""
        return self.P["ei"] / self.H**2 * self.variant.model.shape.curvature_at_base() * u

    # --- impacts (theta returns to 0 while rocking about s1 = s; the corner -s hits) ----------

    def angular_momentum(self, pivot_b, about_b, u, u_dot, theta_dot) -> ca.SX:
        """Clockwise angular momentum about the base point X = about_b, at theta = 0, for a motion
        that rotates about the pivot X = pivot_b (body frame = world frame at theta = 0)."""

        def moment(xc, y, xcd, yd):
            vx = xcd + theta_dot * y
            vy = yd - theta_dot * (xc - pivot_b)
            return y * vx - (xc - about_b) * vy

        return self.over_masses(moment, u, u_dot) + self.base_spin_inertia() * theta_dot

    def momentum_x_at_rest_angle(self, u_dot, theta_dot, u) -> ca.SX:
        return self.over_masses(lambda xc, y, xcd, yd: xcd + theta_dot * y, u, u_dot)

    def impact_maps(self, u1, u1d, th1d):
        """The candidate post-impact states of ADJex (26)-(30), Housner and VVEL (31)-(32)."""
        b1 = self.s * self.B
        b2 = -b1
        x = ca.SX.sym("x_unknown")
        e_before = self.kinetic(th1d, u1, u1d, b1)
        l_pre = self.angular_momentum(b1, b2, u1, u1d, th1d)
        maps = {"e_before": e_before}
        # Immediate rocking about the impacting corner, u' kept (ADJex (28)-(29), Housner).
        th2 = solve_linear(self.angular_momentum(b2, b2, u1, u1d, x) - l_pre, x)
        maps["theta_dot_rocking"] = th2
        maps["u_dot_rocking"] = u1d
        maps["e_rocking"] = self.kinetic(th2, u1, u1d, b2)
        if self.rigid:
            return maps
        # Full contact from angular momentum (26)-(27).
        u2 = solve_linear(self.angular_momentum(b2, b2, u1, x, ca.SX(0)) - l_pre, x)
        maps["u_dot_contact"] = u2
        maps["e_contact"] = self.kinetic(ca.SX(0), u1, u2, b2)
        # Full contact from horizontal momentum (30).
        p_pre = self.momentum_x_at_rest_angle(u1d, th1d, u1)
        u_hm = solve_linear(self.momentum_x_at_rest_angle(x, ca.SX(0), u1) - p_pre, x)
        maps["u_dot_momentum"] = u_hm
        maps["e_momentum"] = self.kinetic(ca.SX(0), u1, u_hm, b2)
        # VVEL (31)-(32): the kinetic energy of the horizontal velocities survives, in full contact.
        e_vh = self.over_masses(lambda xc, y, xcd, yd: (xcd + th1d * y) ** 2, u1, u1d) / 2
        m_c = at(self.m_tilde(), [(self.u, u1)])
        top_vx = u1d * self.variant.model.shape.value(1.0) + th1d * self.H
        maps["u_dot_vvel"] = ca.sign(top_vx) * ca.sqrt(2 * e_vh / m_c)
        maps["e_vvel"] = e_vh
        return maps

    # --- reference quantities ------------------------------------------------------------------

    def rigid_gravity_profile(self):
        """V_g(theta) at u = 0, s = +1, which is A sin(theta) + C cos(theta) for a rigid body."""
        v_g, _, _ = self.potentials()
        v = at(v_g, [(self.u, 0), (self.s, 1)])
        a = at(ca.jacobian(v, self.theta), [(self.theta, 0)])
        c = at(v, [(self.theta, 0)])
        return a, c


def flexible_twin(variant: Variant) -> Variant:
    """The same masses with a deformable column and exact rotations (for reference quantities)."""
    return replace(variant, rigid=False, small_angle=False)
