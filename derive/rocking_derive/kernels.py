"""The functions every variant exports, with named inputs and outputs.

The interface is the same for every variant (state [theta, u, theta', u'] even for the rigid
column, whose kernels never read u), so the solver can run any variant through one Rust trait.
A model with n deformation coordinates has the same functions with each u entry expanded to
u_1..u_n: x = [theta, u_1..u_n, theta', u_1'..u_n'], q = [theta, u_1..u_n],
xc = [u_1..u_n, u_1'..u_n'], xi = [u_1..u_n, u_1'..u_n', theta'].
"""

from __future__ import annotations

from dataclasses import dataclass

import casadi as ca

from .free_base import FreeBase
from .mechanics import Mechanics, Symbols, at, flexible_twin, solve_spd
from .models import Variant


@dataclass
class Input:
    name: str
    doc: str
    elements: list[str]
    symbols: list[ca.SX]
    scalar: bool = False
    params: bool = False


@dataclass
class Output:
    name: str
    doc: str
    elements: list[str]
    exprs: list
    scalar: bool = False


@dataclass
class Kernel:
    name: str
    doc: str
    inputs: list[Input]
    output: Output


#: Outputs of the section-force kernels.
FORCES = ("moment", "shear", "axial", "moment_elastic", "reaction_h", "reaction_v")
FORCES_DOC = (
    "\n\nThe section is the column's foot, at the base centre on the line of the pivots. The column, "
    "its top mass and every mass on it are in equilibrium under gravity acting on the deflected "
    "masses, their inertia from absolute accelerations (ground motion included) and the plate's "
    "actions. Body components (equations.md section 0): X along the plate, positive towards "
    "positive u; Y up the column axis. `moment` M_b: the moment of the column on the plate, positive "
    "in the sense of theta > 0 (clockwise), which is the sign of the curvature at the base; `shear` "
    "V_b and `axial` N_b: the force of the plate on the column along X and Y (N_b > 0: compression); "
    "`moment_elastic` M_el = EI psi''(0) u / H^2, the moment of the curvature (a rigid column has "
    "none: M_b); `reaction_h`, `reaction_v`: the force of the ground on the whole body (column, "
    "masses, base) at the pivot, in the world frame (x towards +x, y up), impact impulses excluded."
)


def expanded(stem: str, n: int) -> list[str]:
    """The names of a per-coordinate quantity: ``stem`` for one coordinate, ``stem_1`` ..
    ``stem_n`` for several."""
    return [stem] if n == 1 else [f"{stem}_{i + 1}" for i in range(n)]


def triangle(stem: str, n: int) -> list[str]:
    """The names of the upper triangle of a symmetric n x n matrix of the u_i, row by row."""
    return [stem] if n == 1 else [f"{stem}_{i + 1}_{j + 1}" for i in range(n) for j in range(i, n)]


#: What several deformation coordinates change in a kernel's meaning (appended to its doc).
SEVERAL = {
    "mass_matrix": "Several coordinates: the upper triangle row by row over q = [theta, u_1..u_n].",
    "power": "Several coordinates: damping = u'^T C u' with the modal damping matrix C of the parameters.",
    "impact_vvel": "Several coordinates: u' = kappa M^-1 h, h_i = sum m psi_i v_x before the impact, "
                   "kappa so that the kinetic energy is that of the horizontal velocities and the top "
                   "keeps the sign of its velocity (docs/modes.md).",
    "impact_adjex": "Several coordinates: each full-contact candidate is the u' nearest the pre-impact u' "
                    "in the kinetic-energy norm that meets its condition, u' + lambda M^-1 c for (26) and "
                    "u' + lambda M^-1 Gamma for (30) (docs/modes.md).",
    "structure": "Several coordinates: the fixed-base mass and stiffness matrices of the u_i (upper "
                 "triangles, row by row: the frequencies and modes are their eigenproblem, solved by "
                 "rocking_kernels::modes), gamma_tilde = M^-1 Gamma (u'' = -gamma_tilde ug + ... in full "
                 "contact), then the rigid-body quantities as for one coordinate.",
    "shape": "Several coordinates: the functions psi_1..psi_n; the deflection is sum u_i psi_i(eta).",
    "forces_contact": "Several coordinates: M_el = EI sum psi_i''(0) u_i / H^2.",
    "forces_rocking": "Several coordinates: M_el = EI sum psi_i''(0) u_i / H^2.",
    "section_forces": "Several coordinates: M_el = EI sum psi_i''(0) u_i / H^2.",
    "static_uplift": "Several coordinates: u_uplift_i, the static deflection K u = -Gamma ug then.",
}


def kernels(variant: Variant) -> list[Kernel]:
    sym = Symbols.create(variant)
    mech = Mechanics(variant, sym)
    twin = Mechanics(flexible_twin(variant), sym)  # reference quantities: flexible, exact angles
    n = mech.n
    names = [p.name for p in variant.model.params]
    u_, ud_ = expanded("u", n), expanded("u_dot", n)

    x = Input("x", "state while rocking", ["theta", *u_, "theta_dot", *ud_],
              [sym.theta, *sym.us, sym.theta_dot, *sym.u_dots])
    q = Input("q", "configuration", ["theta", *u_], [sym.theta, *sym.us])
    xc = Input("xc", "state in full contact (theta = theta' = 0)", [*u_, *ud_], [*sym.us, *sym.u_dots])
    xi = Input("xi", "state just before the impact (theta = 0)", [*u_, *ud_, "theta_dot"],
               [*sym.us, *sym.u_dots, sym.theta_dot])
    ug = Input("ug", "horizontal ground acceleration (positive towards +x)", ["ug"], [sym.ug], scalar=True)
    s = Input("s", "active pivot: +1 right corner (theta > 0), -1 left corner", ["s"], [sym.s], scalar=True)
    s1 = Input("s", "pivot before the impact; the corner -s hits the ground", ["s"], [sym.s], scalar=True)
    p = Input("p", "parameters", names, [sym.params[n] for n in names], params=True)
    eta_sym = ca.SX.sym("eta")
    eta = Input("eta", "height along the column over H (0 at the base, 1 at the top)", ["eta"], [eta_sym],
                scalar=True)

    mass, force = mech.equations()
    if mech.rigid:
        # u is frozen: its row reads u'' = 0, which keeps one interface for every variant.
        m_out = [mass[0, 0], ca.SX(0), ca.SX(1)]
        f_out = [force[0], ca.SX(0)]
        acc = [force[0] / mass[0, 0], ca.SX(0)]
    else:
        m_out = [mass[i, j] for i in range(n + 1) for j in range(i, n + 1)]
        f_out = [force[i] for i in range(n + 1)]
        acc = mech.accelerations()
    m_names = ["m_tt", *expanded("m_tu", n), *triangle("m_uu", n)]

    v_g, v_s, _ = mech.potentials()
    p_x = mech.momentum_x()
    damping = ca.SX(0) if mech.rigid else mech.damping_power()
    contact = mech.contact_accels()

    impact = mech.impact_maps(sym.us, sym.u_dots, sym.theta_dot)
    inf = ca.SX(float("inf"))
    if mech.rigid:
        # Rigid limit of VVEL (equations.md 4.2): full contact keeps the horizontal kinetic energy,
        # then the base re-uplifts at once and only the rocking-mode projection of the velocity remains.
        flex = twin.impact_maps([ca.SX(0)], [ca.SX(0)], sym.theta_dot)
        mt, _ = twin.equations()
        after = [(sym.theta, 0), (sym.u, 0), (sym.s, -sym.s)]
        th2 = at(mt[0, 1], after) / at(mt[0, 0], after) * flex["u_dot_vvel"][0]
        vvel = [ca.SX(1), th2, ca.SX(0), mech.kinetic(th2, [ca.SX(0)], [ca.SX(0)], -mech.b), impact["e_before"]]
        adjex = [ca.SX(0), inf, impact["theta_dot_rocking"], ca.SX(0), impact["e_rocking"],
                 impact["e_before"], ca.SX(0), inf]
    else:
        vvel = [ca.SX(0), ca.SX(0), *impact["u_dot_vvel"], impact["e_vvel"], impact["e_before"]]
        adjex = [*impact["u_dot_contact"], impact["e_contact"], impact["theta_dot_rocking"],
                 *impact["u_dot_rocking"], impact["e_rocking"], impact["e_before"],
                 *impact["u_dot_momentum"], impact["e_momentum"]]
    housner = [impact["theta_dot_rocking"], *(impact["u_dot_rocking"] if not mech.rigid else [ca.SX(0)]),
               impact["e_rocking"], impact["e_before"]]

    # Reference quantities, from the flexible exact-angle twin with this variant's masses.
    a_g, c_g = twin.rigid_gravity_profile()
    h, b, g = sym.params["h"], sym.params["b"], sym.params["g"]
    r = ca.sqrt(h**2 + b**2)
    rigid_body = {
        "theta_cr": ca.atan2(a_g, c_g), "e_ref": ca.sqrt(a_g**2 + c_g**2) - c_g, "r": r,
        "alpha": ca.atan2(b, h), "p_freq": ca.sqrt(g / r), "i_bc_plate": twin.plate_inertia(),
    }
    _, tv = twin.contact_lagrangian()
    if n == 1:
        m_t, k_t = twin.m_tilde(), twin.k_tilde()
        gamma = ca.jacobian(ca.gradient(tv, sym.u), sym.ug) / m_t  # u'' = -gamma ug + ...
        w_n = twin.omega_n()
        mt, _ = twin.equations()
        rest = [(sym.theta, 0), (sym.u, 0), (sym.s, 1)]
        j0, m_tu, m_uu = at(mt[0, 0], rest), at(mt[0, 1], rest), at(mt[1, 1], rest)
        modal_s = ca.sqrt(j0 / (j0 - m_tu**2 / m_uu))
        f_plus = at(twin.uplift(), [(sym.u_dot, 0), (sym.ug, 0), (sym.s, 1)])
        u_cr = -at(f_plus, [(sym.u, 0)]) / ca.jacobian(f_plus, sym.u)
        structure = {
            "m_tilde": m_t, "k_tilde": k_t, "gamma_tilde": gamma, "omega_n": w_n,
            "damping_c": twin.damping_c(), "modal_s": modal_s, "omega_up": w_n * modal_s,
            "zeta_up": sym.params["zeta"] * modal_s, "theta_cr": rigid_body["theta_cr"], "u_cr": u_cr,
            **{k: rigid_body[k] for k in ("e_ref", "r", "alpha", "p_freq", "i_bc_plate")},
        }
    else:
        m_block, k_block = twin.mass_block(), twin.stiffness()
        load = ca.jacobian(ca.gradient(tv, ca.vertcat(*sym.us)), sym.ug)  # Gamma: u'' = -M^-1 Gamma ug + ...
        upper = [(i, j) for i in range(n) for j in range(i, n)]
        structure = {
            **dict(zip(triangle("m_tilde", n), [m_block[i, j] for i, j in upper])),
            **dict(zip(triangle("k_tilde", n), [k_block[i][j] for i, j in upper])),
            **dict(zip(expanded("gamma_tilde", n), solve_spd(m_block, [load[i] for i in range(n)]))),
            **rigid_body,
        }

    # Section forces and ground reactions, with the accelerations of the phase's own equations.
    forces = list(FORCES)
    rocking = mech.base_forces(acc[0], acc[1:])
    qdd_syms = [ca.SX.sym(e) for e in ["theta_ddot", *expanded("u_ddot", n)]]
    qdd = Input("qdd", "accelerations [theta'', u''] (the rigid column's u'' is 0)",
                ["theta_ddot", *expanded("u_ddot", n)], qdd_syms)
    given = mech.base_forces(qdd_syms[0], [ca.SX(0)] if mech.rigid else qdd_syms[1:])
    in_contact = mech.contact_forces()
    uplift_static = twin.static_uplift()
    shapes = list(mech.basis.values(eta_sym))

    def doc(name, text):
        return text + " " + SEVERAL[name] if n > 1 and name in SEVERAL else text

    K = Kernel
    found = [
        K("mass_matrix", doc("mass_matrix", "Mass matrix M(q) of the rocking phase about corner s (symmetric)."),
          [q, s, p], Output("m", "upper triangle of M", m_names, m_out)),
        K("forcing", "Right-hand side F of M q'' = F while rocking about corner s: gravity, ground "
          "acceleration, stiffness, damping and velocity terms (corrected eqs (8)-(9)).", [x, ug, s, p],
          Output("f", "generalised forces", ["f_theta", *expanded("f_u", n)], f_out)),
        K("rocking_rhs", "State derivative while rocking about corner s (M q'' = F solved by LDL^T, theta last).",
          [x, ug, s, p], Output("dx", "state derivative", ["theta_dot", *ud_, "theta_ddot", *expanded("u_ddot", n)],
                                [mech.theta_dot, *mech.u_dots, *acc])),
        K("contact_rhs", "State derivative in full contact, eq (3): the fixed-base cantilever.", [xc, ug, p],
          Output("dxc", "state derivative", [*ud_, *expanded("u_ddot", n)], [*mech.u_dots, *contact])),
        K("uplift", "Uplift function f_s of eq (24): in full contact the base starts to rock about corner s "
          "as soon as f_s > 0 (f_+ + f_- < 0, so at most one corner at a time).", [xc, ug, s, p],
          Output("f_s", "uplift function", ["f_s"], [mech.uplift()], scalar=True)),
        K("energy", "Kinetic energy, gravity and strain potentials and horizontal momentum while rocking "
          "about corner s (theta = theta' = 0 gives full contact).", [x, s, p],
          Output("e", "energies and momentum", ["kinetic", "gravity", "strain", "momentum_x"],
                 [mech.kinetic(), v_g, v_s, p_x])),
        K("power", doc("power", "Power balance terms: dE/dt = ground - damping, with ground = -ug P_x and "
          "damping = c u'^2."), [x, ug, s, p],
          Output("w", "power terms", ["ground", "damping"], [-sym.ug * p_x, damping])),
        K("impact_vvel", doc("impact_vvel", "VVEL impact map, eqs (31)-(32): the kinetic energy of the "
          "vertical velocities is lost and the structure continues in full contact (`rock` = 0, `u_dot`), "
          "or for the rigid column in its rigid limit, rocking about the impacting corner (`rock` = 1, "
          "`theta_dot`)."),
          [xi, s1, p], Output("vvel", "post-impact state", ["rock", "theta_dot", *ud_, "energy_after",
                                                             "energy_before"], vvel)),
        K("impact_adjex", doc("impact_adjex", "ADJex impact candidates, eqs (26)-(30): full contact from "
          "angular momentum, immediate rocking about the impacting corner (admissible when -s "
          "theta_dot_rocking > 0), and the horizontal-momentum fallback, each with its kinetic energy. "
          "The choice is the solver's."),
          [xi, s1, p], Output("adjex", "candidate post-impact states",
                              [*expanded("u_dot_contact", n), "energy_contact", "theta_dot_rocking",
                               *expanded("u_dot_rocking", n), "energy_rocking", "energy_before",
                               *expanded("u_dot_momentum", n), "energy_momentum"],
                              adjex)),
        K("impact_housner", "Housner's rule: angular momentum about the impacting corner is conserved and "
          "the structure rocks on about that corner with u' unchanged.", [xi, s1, p],
          Output("housner", "post-impact state", ["theta_dot", *ud_, "energy_after", "energy_before"],
                 housner)),
        K("structure", doc("structure", "Fixed-base and reference quantities: eqs (5)-(7), (18)-(19), "
          "(39)-(40), E_ref (the rigid column's potential-energy barrier with all masses), R, alpha, "
          "p = sqrt(g/R) and the thin-plate base inertia 4/3 m_b B^2 (the unit of gamma_ib)."),
          [p], Output("st", "structure quantities", list(structure), list(structure.values()))),
        K("shape", doc("shape", "Shape function psi(eta) of the column: its deflection at height eta H is "
          "psi(eta) u (psi(0) = 0, psi(1) = 1), for drawing the deformed column."), [eta],
          Output("psi", "shape function", expanded("psi", n), shapes, scalar=n == 1)),
        K("forces_contact", doc("forces_contact", "Section forces at the column base and ground reaction in full contact "
          "(theta = theta' = 0), with u'' from eq (3). |moment| <= W B in full contact: f_s = s moment "
          "- W B (eq 24), W the total weight." + FORCES_DOC),
          [xc, ug, p], Output("fc", "section forces and ground reaction", forces,
                              [in_contact[k] for k in forces])),
        K("forces_rocking", doc("forces_rocking", "Section forces at the column base and ground reaction while rocking about "
          "corner s, with theta'' and u'' from the rocking equations (corrected (8)-(9)). The base "
          "plate's moment balance about its centre: moment = s B (reaction_v cos theta + reaction_h sin "
          "theta) + I_b theta'', I_b = I_bc - m_b B^2. The rotation is exact in every variant: a "
          "small-angle variant's forces are those of the motion its equations predict." + FORCES_DOC),
          [x, ug, s, p], Output("fr", "section forces and ground reaction", forces,
                                [rocking[k] for k in forces])),
        K("section_forces", doc("section_forces", "The outputs of forces_rocking for the accelerations "
          "qdd = [theta'', u''] the integrator already has (the state derivative it evaluated at x), "
          "without solving M q'' = F again; in full contact x has theta = theta' = 0 and qdd theta'' = 0 "
          "(any s), and the outputs are those of forces_contact." + FORCES_DOC),
          [x, qdd, ug, s, p], Output("fs", "section forces and ground reaction", forces,
                                     [given[k] for k in forces])),
        K("static_uplift", doc("static_uplift", "Quasi-static uplift about the right corner (s = +1; the left corner is its "
          "mirror), from the flexible exact-angle twin: the total weight W, the base moment W B at "
          "which the base uplifts (f_s = s M_b - W B), the ground acceleration ug (< 0) that lifts "
          "the base when applied so slowly that u' = u'' = 0, the deflection u then, and the elastic "
          "moment EI psi''(0) u / H^2 at the column base then, which differs from W B by the P-Delta "
          "moment and the shape function's error (docs/design-forces.md)."),
          [p], Output("up", "static uplift", list(uplift_static), list(uplift_static.values()))),
    ]
    return found + free_base_kernels(mech, sym, p, ug, s)


def free_base_kernels(mech: Mechanics, sym: Symbols, p: Input, ug: Input, s: Input) -> list[Kernel]:
    """The structure on compliant ground (free_base.py): q = [theta, v, u_1..u_n]. The ground's own
    generalised forces [Q_theta, Q_v] (ground.py) are added to F at run time."""
    free = FreeBase(mech)
    n = mech.n
    u_, ud_, udd_ = expanded("u", n), expanded("u_dot", n), expanded("u_ddot", n)
    qf = Input("qf", "configuration on compliant ground: rotation, settlement of the base centre "
               "(positive into the ground), deformation", ["theta", "v", *u_], [sym.theta, free.v, *sym.us])
    y = Input("y", "state on compliant ground", ["theta", "v", *u_, "theta_dot", "v_dot", *ud_],
              [sym.theta, free.v, *sym.us, sym.theta_dot, free.v_dot, *sym.u_dots])
    acc_syms = [ca.SX.sym(e) for e in ["theta_ddot", "v_ddot", *udd_]]
    qdd = Input("qdd", "accelerations [theta'', v'', u''] (from M q'' = F + Q_ground)",
                ["theta_ddot", "v_ddot", *udd_], acc_syms)
    mass, force = free.equations()
    dim = 3 if mech.rigid else n + 2
    if mech.rigid:
        # u is frozen: its row reads u'' = 0 (one interface for every variant).
        full_m = [[mass[0, 0], mass[0, 1], ca.SX(0)], [None, mass[1, 1], ca.SX(0)], [None, None, ca.SX(1)]]
        f_out = [force[0], force[1], ca.SX(0)]
    else:
        full_m = [[mass[i, j] if j >= i else None for j in range(dim)] for i in range(dim)]
        f_out = [force[i] for i in range(dim)]
    labels = ["t", "v", *(["u"] if n == 1 else [f"u{i + 1}" for i in range(n)])]
    m_names = [f"m_{labels[i]}_{labels[j]}" for i in range(dim) for j in range(i, dim)]
    m_out = [full_m[i][j] for i in range(dim) for j in range(i, dim)]
    forces = list(FORCES)
    f_values = free.forces(acc_syms[0], acc_syms[1], [ca.SX(0)] if mech.rigid else acc_syms[2:])
    ground_note = (" On compliant ground (derive/rocking_derive/free_base.py): the rigid-rocking kinematics "
                   "about the leaning corner s = sgn(theta) plus a vertical translation by that corner's "
                   "depth w = v + s B sin(theta).")
    K = Kernel
    return [
        K("free_mass_matrix", "Mass matrix M(q) over q = [theta, v, u_1..u_n], upper triangle row by row "
          "(symmetric positive definite; a rigid column's u row is the identity)." + ground_note,
          [qf, s, p], Output("m", "upper triangle of M", m_names, m_out)),
        K("free_forcing", "Right-hand side F of M q'' = F + Q_ground without the ground: gravity, ground "
          "acceleration, stiffness, damping and velocity terms; Q_ground = [Q_theta, Q_v, 0..] from the "
          "ground's kernels." + ground_note, [y, ug, s, p],
          Output("f", "generalised forces", ["f_theta", "f_v", *expanded("f_u", n)], f_out)),
        K("free_energy", "Kinetic energy, gravity (heights over the rest position of the leaning corner, "
          "the ground's surface) and strain potentials and horizontal momentum." + ground_note, [y, s, p],
          Output("e", "energies and momentum", ["kinetic", "gravity", "strain", "momentum_x"], free.energy())),
        K("free_power", "Power terms: dE/dt = ground - damping + Q_theta theta' + Q_v v', with ground = "
          "-ug P_x and damping u'^T C u'." + ground_note, [y, ug, s, p],
          Output("w", "power terms", ["ground", "damping"], free.power())),
        K("free_forces", "Section forces at the column base and the ground's force on the body (the bed's "
          "resultant and the horizontal force that keeps the leaning corner in place), for the "
          "accelerations qdd." + ground_note + FORCES_DOC, [y, qdd, ug, s, p],
          Output("ff", "section forces and ground reaction", forces, [f_values[k] for k in forces])),
    ]
