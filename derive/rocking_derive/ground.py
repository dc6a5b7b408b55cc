"""The ground under the base: a tensionless Winkler bed and the two-spring foundation (issue 44).

Model-independent: the ground acts on the base plate alone, whose configuration is (theta, v) with
v the settlement of the base centre (positive into the ground) and theta the rotation of the
mechanics (clockwise positive, equations.md section 0). A base point at the body abscissa x
(-B <= x <= B from the base centre) then sits at the depth

    d(x) = v + x sin(theta)          (its penetration into the ground where d > 0)

with exact rotation (clockwise: the right half goes down), and its depth rate is
d'(x) = v' + x cos(theta) theta'. d and d' are linear in x, so every integral over the contact
length is a polynomial in its end points: the kernels are closed form, one expression per contact
state:

* full contact: d > 0 on the whole base, the contact is [-B, B];
* one edge lifted: the lift-off point x0 = -v / sin(theta) lies inside the base and the contact
  is [x0, s B], s = sgn(theta) (the side that goes down: d > 0 there);
* flight: no contact, no force.

Two springs: one spring and dashpot at each corner x = -B, B, acting while that corner presses
(d > 0); the states are the same (both corners, the corner s B, none).

The bed pushes with the pressure p(x) = k d(x) + c d'(x) where d > 0 (k: N/m per m of base width,
c: N s/m per m; the two-spring foundation's k, c are each corner's). Dashpot convention: the
dashpot acts exactly where the spring is compressed, d > 0. The contact length is then a matter of
geometry alone (the events are the edges' depths crossing zero, with no velocity in them), the
dissipation c d'^2 >= 0 is a positive integral in every state, and the resultant force is
continuous in time through every event (the contact length changes continuously, the integrand
stays bounded). The price: near a receding edge the local force k d + c d' can be negative (a
pull of at most c |d'| per unit length, over the strip where k d < -c d', of width c |d'| / k
beside the edge); the clipped alternative max(0, k d + c d') never pulls, but its contact edge
would depend on the velocity and its energy split would not be the spring's V plus c d'^2.

Generalised forces: a point's height is -d(x), so the virtual work of the upward pressure is
-integral of p (dv + x cos(theta) dtheta) dx:

    Q_v = -integral p dx,      Q_theta = -cos(theta) integral p x dx.

The strain energy is V = integral k d^2 / 2 and the dissipated power D = integral c d'^2 (over the
contact). Because d = 0 at a moving contact edge, the spring part of Q is exactly -grad V (the
boundary terms of Leibniz's rule vanish), and the ground's power on the structure is
Q . (v', theta') = -(dV/dt + D): the energy balance closes with V and the integral of D.

The horizontal position of the base is a kinematic constraint of the structure (no sliding): the
corner toward which it leans keeps its place as on the rigid surface (the structure's free-base
equations, not this module).
"""

from __future__ import annotations

import casadi as ca

#: The ground's parameters, in the order of the kernels' parameter array.
PARAMS = (
    ("b", "half-width B of the base"),
    ("k", "stiffness: of the bed per unit base length (winkler, N/m^2), or of each corner's spring "
          "(two-spring, N/m)"),
    ("c", "damping: of the bed per unit base length (winkler, N s/m^2), or of each corner's "
          "dashpot (two-spring, N s/m)"),
)

#: The outputs of every contact-state kernel.
OUTPUTS = (
    ("q_theta", "generalised force of the ground on theta (a moment, in the sense of theta)"),
    ("q_v", "generalised force of the ground on v (= -R_v, R_v the upward resultant)"),
    ("strain", "strain energy V of the springs"),
    ("dissipation", "power D taken by the dashpots (>= 0)"),
    ("contact_fraction", "contact length over 2 B (two-spring: corners pressing over 2)"),
    ("pressure_lo", "pressure k d + c d' at the left end of the contact (two-spring: that corner's "
                    "force); 0 in flight"),
    ("pressure_hi", "pressure at the right end of the contact (two-spring: that corner's force)"),
    ("depth_left", "depth d(-B) of the left corner (> 0: it presses)"),
    ("depth_right", "depth d(B) of the right corner"),
)

KINDS = {
    "winkler": "tensionless Winkler bed: springs and dashpots spread uniformly over [-B, B]",
    "two_spring": "two-spring foundation: a spring and a dashpot at each corner",
}

STATES = {
    "full": "full contact",
    "edge": "one edge lifted (winkler: the lift-off point x0 = -v / sin(theta) inside the base; "
            "two-spring: only the corner s B presses), s = sgn(theta)",
    "flight": "flight: no contact",
}


class GroundSymbols:
    def __init__(self):
        sym = ca.SX.sym
        self.theta, self.v, self.theta_dot, self.v_dot = sym("theta"), sym("v"), sym("theta_dot"), sym("v_dot")
        self.s = sym("s")
        self.params = {name: sym(name) for name, _ in PARAMS}

    @property
    def y(self) -> list:
        return [self.theta, self.v, self.theta_dot, self.v_dot]


def _integral(coefficients: list, lo, hi):
    """Integral over [lo, hi] of sum_i coefficients[i] x^i."""
    terms = [c * (hi ** (i + 1) - lo ** (i + 1)) / (i + 1) for i, c in enumerate(coefficients)]
    out = terms[0]
    for t in terms[1:]:
        out = out + t
    return out


def _times(a: list, b: list) -> list:
    """Product of two polynomials in x (coefficient lists)."""
    out = [ca.SX(0)] * (len(a) + len(b) - 1)
    for i, x in enumerate(a):
        for j, y in enumerate(b):
            out[i + j] = out[i + j] + x * y
    return out


def ground_state(kind: str, state: str, g: GroundSymbols) -> dict[str, ca.SX]:
    """The outputs of OUTPUTS for one kind and contact state."""
    if kind not in KINDS or state not in STATES:
        raise ValueError(f"unknown ground {kind!r} / state {state!r}")
    B, k, c = g.params["b"], g.params["k"], g.params["c"]
    sin, cos = ca.sin(g.theta), ca.cos(g.theta)
    depth = [g.v, sin]  # d(x) = v + x sin(theta)
    rate = [g.v_dot, cos * g.theta_dot]  # d'(x)
    pressure = [k * depth[0] + c * rate[0], k * depth[1] + c * rate[1]]

    def at(poly, x):
        return poly[0] + poly[1] * x

    out = {"depth_left": at(depth, -B), "depth_right": at(depth, B)}
    zero = ca.SX(0)
    if state == "flight":
        out.update(q_theta=zero, q_v=zero, strain=zero, dissipation=zero, contact_fraction=zero,
                   pressure_lo=zero, pressure_hi=zero)
    elif kind == "winkler":
        if state == "full":
            lo, hi = -B, B

            def over(poly):
                return _integral(poly, lo, hi)

            out["contact_fraction"] = ca.SX(1)
        else:
            x0 = -g.v / sin
            # The contact runs from x0 to s B: the integral over it is s times that from x0 to s B.
            lo, hi = x0, g.s * B

            def over(poly):
                return g.s * _integral(poly, lo, hi)

            out["contact_fraction"] = g.s * (hi - lo) / (2 * B)
        out["q_v"] = -over(pressure)
        out["q_theta"] = -cos * over(_times(pressure, [zero, ca.SX(1)]))
        out["strain"] = k * over(_times(depth, depth)) / 2
        out["dissipation"] = c * over(_times(rate, rate))
        ends = (at(pressure, lo), at(pressure, hi))
        # Left and right ends of the contact in the base frame.
        if state == "full":
            out["pressure_lo"], out["pressure_hi"] = ends
        else:
            # s = +1: [x0, B]; s = -1: [-B, x0] (lo = x0 is then the right end).
            out["pressure_lo"] = (1 + g.s) / 2 * ends[0] + (1 - g.s) / 2 * ends[1]
            out["pressure_hi"] = (1 + g.s) / 2 * ends[1] + (1 - g.s) / 2 * ends[0]
    else:
        corners = [-B, B] if state == "full" else [g.s * B]
        q_v, q_theta, strain, dissipation = [], [], [], []
        for x in corners:
            f = at(pressure, x)
            q_v.append(-f)
            q_theta.append(-cos * f * x)
            strain.append(k * at(depth, x) ** 2 / 2)
            dissipation.append(c * at(rate, x) ** 2)

        def add(terms):
            out_ = terms[0]
            for t in terms[1:]:
                out_ = out_ + t
            return out_

        out.update(q_v=add(q_v), q_theta=add(q_theta), strain=add(strain), dissipation=add(dissipation))
        if state == "full":
            out["contact_fraction"] = ca.SX(1)
            out["pressure_lo"], out["pressure_hi"] = at(pressure, -B), at(pressure, B)
        else:
            out["contact_fraction"] = ca.SX(0.5)
            f = at(pressure, g.s * B)
            out["pressure_lo"] = (1 - g.s) / 2 * f
            out["pressure_hi"] = (1 + g.s) / 2 * f
    return {name: out[name] for name, _ in OUTPUTS}


def check_conservative(kind: str, state: str) -> None:
    """The spring part of the generalised forces is -grad V (raises otherwise): a check of the
    closed forms, at a few points, by CasADi's own derivative of V."""
    g = GroundSymbols()
    out = ground_state(kind, state, g)
    q = ca.vertcat(g.theta, g.v)
    grad = ca.gradient(out["strain"], q)
    springs = [ca.substitute(out[name], g.params["c"], ca.SX(0)) for name in ("q_theta", "q_v")]
    f = ca.Function("check", [ca.vertcat(*g.y), g.s, ca.vertcat(*g.params.values())],
                    [ca.vertcat(*springs) + grad])
    # A state with the lift-off point inside the base (theta = 0.1, v = 0.05, B = 1: x0 = -0.5).
    for s, theta in ((1.0, 0.1), (-1.0, -0.1)):
        r = f([theta, 0.05, 0.3, -0.2], s, [1.0, 100.0, 3.0]).full().reshape(-1)
        if max(abs(x) for x in r) > 1e-9:
            raise ValueError(f"ground {kind}/{state}: Q_spring + grad V = {list(r)} is not 0")


def statics(kind: str, g: GroundSymbols, weight: ca.SX) -> dict[str, ca.SX]:
    """The ground's statics under a vertical load W at the base centre and a moment: from the
    full-contact kernel's own derivatives (nothing retyped). Full contact gives Q_v = -K_v v at
    any theta, so the settlement v0 = W / K_v holds until the first edge lifts, at
    sin(theta) = v0 / B; the moment then is -Q_theta."""
    full = ground_state(kind, "full", g)
    rest = [g.theta, g.v, g.theta_dot, g.v_dot]
    k_v = -ca.jacobian(full["q_v"], g.v)
    if ca.depends_on(k_v, ca.vertcat(*rest)):
        raise ValueError(f"ground {kind}: the vertical stiffness in full contact is not constant")
    v0 = weight / k_v
    at_rest = ca.vertcat(g.theta, g.v, g.theta_dot, g.v_dot)
    k_rot = ca.substitute(-ca.jacobian(full["q_theta"], g.theta), at_rest, ca.vertcat(0, v0, 0, 0))
    B = g.params["b"]
    theta_lift = ca.atan2(v0, ca.sqrt(B**2 - v0**2))
    moment_lift = ca.substitute(-full["q_theta"], at_rest, ca.vertcat(theta_lift, v0, 0, 0))
    return {"k_v": k_v, "settlement": v0, "k_rot": k_rot, "theta_lift_off": theta_lift,
            "moment_lift_off": moment_lift}


STATICS_OUTPUTS = {
    "k_v": "vertical stiffness K_v (winkler: 2 k B; two-spring: 2 k)",
    "settlement": "static settlement v0 = W / K_v",
    "k_rot": "rotational stiffness dM/dtheta at theta = 0 in full contact",
    "theta_lift_off": "rotation at which the first edge lifts under W (sin theta = v0 / B)",
    "moment_lift_off": "moment at that rotation (-Q_theta)",
}


def kernels():
    """The ground's kernels, in the form of ``kernels.Kernel`` (imported late: kernels imports
    mechanics)."""
    from .kernels import Input, Kernel, Output

    g = GroundSymbols()
    names = [name for name, _ in PARAMS]
    y = Input("y", "the base's configuration and rates: rotation, settlement of the base centre "
              "(positive into the ground) and their rates", ["theta", "v", "theta_dot", "v_dot"], g.y)
    s = Input("s", "sgn(theta): the side that presses when one edge is lifted", ["s"], [g.s], scalar=True)
    p = Input("p", "ground parameters", names, [g.params[n] for n in names], params=True)
    w_sym = ca.SX.sym("w")
    w = Input("w", "vertical load W on the base centre (the structure's weight)", ["w"], [w_sym], scalar=True)
    out_names = [name for name, _ in OUTPUTS]
    out_doc = "; ".join(f"`{name}`: {doc}" for name, doc in OUTPUTS)
    found = []
    for kind, kind_doc in KINDS.items():
        for state in ("full", "edge"):
            values = ground_state(kind, state, g)
            found.append(Kernel(
                f"{kind}_{state}",
                f"Ground forces, energy, power and contact of the {kind_doc}, {STATES[state]}. "
                "Pressure k d + c d' where d = v + x sin(theta) > 0 (the dashpot acts where the "
                "spring is compressed).",
                [y, s, p], Output("g", out_doc, out_names, [values[n] for n in out_names])))
        st = statics(kind, g, w_sym)
        found.append(Kernel(
            f"{kind}_statics", f"Statics of the {kind_doc} under the vertical load W: "
            + "; ".join(f"`{k}`: {d}" for k, d in STATICS_OUTPUTS.items()) + ".",
            [w, p], Output("st", "statics", list(STATICS_OUTPUTS), [st[k] for k in STATICS_OUTPUTS])))
    values = ground_state("winkler", "flight", g)
    found.append(Kernel("flight", f"Flight ({STATES['flight']}) on either ground: no force; the "
                        "corners' depths (< 0) are the events of landing.", [y, p],
                        Output("g", out_doc, out_names, [values[n] for n in out_names])))
    for kind in KINDS:
        for state in STATES:
            check_conservative(kind, state)
    return found
