"""The structure's equations on compliant ground (issue 44): the base is free to sink.

The rigid-rocking kinematics of ``mechanics.py`` about the leaning corner s = sgn(theta) (origin at
that corner, b = s B, body-frame velocities) plus a vertical translation of the whole body by the
depth of that corner,

    w = v + s B sin(theta)          (v: settlement of the base centre, positive into the ground),

which is the depth d(s B) of ground.py. The leaning corner never moves horizontally, so the base
centre is at x_c = s B (1 - cos(theta)) from where it was at rest (issue 44's constraint
x_c = -sgn(theta) B (1 - cos theta) in its own sign of x): the rigid surface is the limit w = 0.
Heights and vertical velocities do not depend on s (a base point at the body abscissa X is at the
depth v + X sin(theta)); the horizontal velocity x_c' = s B sin(theta) theta' vanishes at
theta = 0, so switching s there needs no impact map: position and velocity are continuous.

With the pivot's velocity (0, -w') in the world frame, a point's velocity is that of the rocking
motion plus (0, -w'), so

    T = T_rock + M w'^2 / 2 - w' d/dt(S_y),     V_g = g (S_y - M w),

with S_y = sum m y (world heights above the pivot, ``Mechanics.world_sums``) and M the total mass;
the strain and the ground acceleration's potentials are those of the rocking motion (horizontal
positions do not depend on w). Lagrange's equations over q = [theta, v, u_1..u_n] give
M(q) q'' = F(q, q', ug) + Q_ground, where Q_ground = [Q_theta, Q_v, 0..0] are the ground's
generalised forces of ground.py (added at run time: the ground's kind and contact state are the
solver's). M is solved at run time (a dense LDL^T of size n + 2), not symbolically.

The rigid variant keeps one interface: its u row reads u'' = 0 (M_uu = 1, F_u = 0).
"""

from __future__ import annotations

import casadi as ca

from .mechanics import Mechanics


class FreeBase:
    """M, F, energies and base forces of one variant on compliant ground."""

    def __init__(self, mech: Mechanics):
        self.mech = mech
        self.v, self.v_dot = ca.SX.sym("v"), ca.SX.sym("v_dot")
        m = mech
        self.qr, self.qdr = m.q, m.qd  # the rocking coordinates [theta, u..] (rigid: [theta])
        self.q = ca.vertcat(m.theta, self.v, *([] if m.rigid else m.us))
        self.qd = ca.vertcat(m.theta_dot, self.v_dot, *([] if m.rigid else m.u_dots))
        sin, cos = ca.sin(m.theta), ca.cos(m.theta)
        self.w = self.v + m.b * sin
        self.w_dot = self.v_dot + m.b * cos * m.theta_dot
        self.total_mass = m.over_points(lambda psis, y: ca.SX(1))
        self.sx, self.sy = m.world_sums()
        # The pivot's velocity enters T through the world-vertical velocity of the rocking motion,
        # with the exact rotation: T = sum m |R v_body - (0, w')|^2 / 2 is then a sum of squares
        # (positive definite) in every variant. A small-angle variant's approximate world
        # heights (sin -> theta, cos -> 1 - theta^2/2) are not a rotation of its body-frame
        # velocities and would make M indefinite; its gravity keeps them.
        sy_exact = self.sy
        if m.variant.small_angle:
            b = m.b
            sy_exact = m.over_masses(lambda xc, y, xcd, yd: -(xc - b) * sin + y * cos)
        self.sy_dot = ca.mtimes(ca.jacobian(sy_exact, self.qr), self.qdr)

    def kinetic(self) -> ca.SX:
        return self.mech.kinetic() + self.total_mass * self.w_dot**2 / 2 - self.w_dot * self.sy_dot

    def gravity(self) -> ca.SX:
        return self.mech.g * (self.sy - self.total_mass * self.w)

    def equations(self):
        """(M, F) of M q'' = F + Q_ground over q = [theta, v, u..]."""
        m = self.mech
        t = self.kinetic()
        _, v_s, v_a = m.potentials()
        lag = t - self.gravity() - v_s - v_a
        mass = ca.hessian(t, self.qd)[0]
        force = ca.gradient(lag, self.q) - ca.mtimes(ca.jacobian(ca.gradient(lag, self.qd), self.q), self.qd)
        if not m.rigid:
            for i in range(m.n):
                force[2 + i] -= m.damping_force(i)
        return mass, force

    def momentum_x(self) -> ca.SX:
        """Horizontal momentum: d/dt sum m x (x does not depend on v)."""
        return ca.mtimes(ca.jacobian(self.sx, self.q), self.qd)

    def energy(self) -> list[ca.SX]:
        """[kinetic, gravity, strain, momentum_x]."""
        _, v_s, _ = self.mech.potentials()
        return [self.kinetic(), self.gravity(), v_s, self.momentum_x()]

    def power(self) -> list[ca.SX]:
        """[ground, damping]: dE/dt = ground - damping + the ground's power Q . (theta', v')."""
        m = self.mech
        damping = ca.SX(0) if m.rigid else m.damping_power()
        return [-m.ug * self.momentum_x(), damping]

    def forces(self, theta_ddot, v_ddot, u_ddots) -> dict[str, ca.SX]:
        """``Mechanics.base_forces`` with the pivot's vertical acceleration w''."""
        m = self.mech
        w_ddot = v_ddot + m.b * (ca.cos(m.theta) * theta_ddot - ca.sin(m.theta) * m.theta_dot**2)
        return m.base_forces(theta_ddot, u_ddots, w_ddot=w_ddot)
