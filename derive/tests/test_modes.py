"""Checks of the derivation for several deformation coordinates (docs/modes.md).

Run from the repository root, as .ci/run does:
``PYTHONPATH=derive .venv/bin/python -m unittest discover -s derive/tests`` (CasADi, sympy, mpmath
and numpy from the project venv; numpy only here, never in what the derivation emits).
"""

from __future__ import annotations

import random
import unittest
from fractions import Fraction

import casadi as ca
import mpmath
import numpy as np
import sympy as sp

from rocking_derive.ir import casadi_function
from rocking_derive.kernels import kernels
from rocking_derive.mechanics import Mechanics, Symbols
from rocking_derive.models import CUBIC, PAPER, Model, Variant
from rocking_derive.shape import ETA, Function, Polynomial

ETA2 = Polynomial("eta^2", {2: Fraction(1)})
ETA3 = Polynomial("eta^3", {3: Fraction(1)})


def model(name: str, shape) -> Variant:
    return Variant(name, name, "", Model(name, name, shape, PAPER.masses))


def structure(rng: random.Random) -> dict[str, float]:
    """SI parameters of a paper-like structure (H = 20 m, B = 3 m) with random masses."""
    values = {"h": 20.0, "b": 3.0, "ei": 4e10, "m": rng.uniform(1e5, 3e5), "m_c": rng.uniform(1e5, 3e5),
              "m_b": rng.uniform(0.5e5, 1e5), "zeta": 0.03, "g": 9.81}
    values["i_bc"] = values["m_b"] * 9.0 * 4.0 / 3.0
    return values


def params(variant: Variant, values: dict[str, float], damping: np.ndarray) -> list[float]:
    """The parameter vector of ``variant``: ``values`` and the modal damping matrix ``damping``."""
    n = len(damping)
    upper = {f"c_{i + 1}_{j + 1}": damping[i, j] for i in range(n) for j in range(i, n)}
    return [{**values, **upper}[p.name] for p in variant.model.params]


def functions(variant: Variant) -> dict[str, ca.Function]:
    return {k.name: casadi_function(k) for k in kernels(variant)}


def call(f: ca.Function, *args) -> np.ndarray:
    return np.array(ca.DM(f(*args)).full()).reshape(-1)


class BasisInvariance(unittest.TestCase):
    """{eta^2, eta^3} and {psi_cubic, eta^2} span the same functions: u_a = T v with
    psi_cubic = 3/2 eta^2 - 1/2 eta^3, so every kernel of one is the other's through T."""

    T = np.array([[1.5, 1.0], [-0.5, 0.0]])

    def test_every_kernel_agrees_through_the_change_of_basis(self):
        a, b = model("basis_a", (ETA2, ETA3)), model("basis_b", (CUBIC, ETA2))
        fa, fb = functions(a), functions(b)
        rng = random.Random(28)
        worst = 0.0
        for _ in range(20):
            # A damping matrix in basis a, and the same damping in basis b: T^T C T.
            c_a = np.array([[rng.uniform(1e5, 2e5), 0.0], [0.0, rng.uniform(1e5, 2e5)]])
            c_a[0, 1] = c_a[1, 0] = rng.uniform(-5e4, 5e4)
            values = structure(rng)
            pa, pb = params(a, values, c_a), params(b, values, self.T.T @ c_a @ self.T)
            theta, thd, ug, s = rng.uniform(-0.2, 0.2), rng.uniform(-0.5, 0.5), rng.uniform(-5, 5), rng.choice([1, -1])
            v = np.array([rng.uniform(-0.1, 0.1), rng.uniform(-0.1, 0.1)])
            vd = np.array([rng.uniform(-0.5, 0.5), rng.uniform(-0.5, 0.5)])
            u, ud = self.T @ v, self.T @ vd
            xa, xb = [theta, *u, thd, *ud], [theta, *v, thd, *vd]

            def agree(got_a, got_b, what):
                nonlocal worst
                scale = max(1.0, np.abs(got_a).max())
                err = np.abs(got_a - got_b).max() / scale
                worst = max(worst, err)
                self.assertLess(err, 1e-12, f"{what}: {got_a} vs {got_b}")

            def velocities(out_b, k):  # the u entries of b's output at k, k+1 mapped to basis a
                out = out_b.copy()
                out[k:k + 2] = self.T @ out_b[k:k + 2]
                return out

            # Scalars and physical quantities: equal.
            for name, args in (("energy", ((xa, xb), s)), ("power", ((xa, xb), ug, s)),
                               ("forces_rocking", ((xa, xb), ug, s))):
                (x_a, x_b), *rest = args
                agree(call(fa[name], x_a, *rest, pa), call(fb[name], x_b, *rest, pb), name)
            xca, xcb = [*u, *ud], [*v, *vd]
            for name in ("uplift", "forces_contact"):
                extra = (ug, s) if name == "uplift" else (ug,)
                agree(call(fa[name], xca, *extra, pa), call(fb[name], xcb, *extra, pb), name)
            # Derivatives: the u entries through T.
            agree(call(fa["rocking_rhs"], xa, ug, s, pa),
                  velocities(velocities(call(fb["rocking_rhs"], xb, ug, s, pb), 1), 4), "rocking_rhs")
            agree(call(fa["contact_rhs"], xca, ug, pa),
                  velocities(velocities(call(fb["contact_rhs"], xcb, ug, pb), 0), 2), "contact_rhs")
            # Impact maps, every candidate: u' entries through T, theta' and energies equal.
            xia, xib = [*u, *ud, thd], [*v, *vd, thd]
            agree(call(fa["impact_vvel"], xia, s, pa), velocities(call(fb["impact_vvel"], xib, s, pb), 2),
                  "impact_vvel")
            agree(call(fa["impact_housner"], xia, s, pa),
                  velocities(call(fb["impact_housner"], xib, s, pb), 1), "impact_housner")
            adj_b = call(fb["impact_adjex"], xib, s, pb)
            for k in (0, 4, 8):  # u'_contact, u'_rocking, u'_momentum
                adj_b = velocities(adj_b, k)
            agree(call(fa["impact_adjex"], xia, s, pa), adj_b, "impact_adjex")
        print(f"basis invariance: worst relative difference {worst:.1e}")


def tip_mass_beta(r: float, k: int) -> mpmath.mpf:
    """The k-th root of 1 + cos b cosh b + r b (cos b sinh b - sin b cosh b) = 0."""
    f = lambda b: 1 / mpmath.cosh(b) + mpmath.cos(b) + r * b * (mpmath.cos(b) * mpmath.tanh(b) - mpmath.sin(b))  # noqa: E731
    grid = [mpmath.mpf(i) / 100 for i in range(1, 2000)]
    roots = [mpmath.findroot(f, (x0, x1), solver="anderson") for x0, x1 in zip(grid, grid[1:]) if f(x0) * f(x1) < 0]
    return roots[k - 1]


def tip_mass_mode(r: float, k: int) -> tuple[Function, mpmath.mpf]:
    """The k-th mode of the cantilever with a tip mass r m_c: the shape of the bare cantilever's
    modes (psi''(1) = 0 fixes sigma), its beta from the tip-mass frequency equation."""
    with mpmath.workdps(Function.DIGITS + 10):
        beta = tip_mass_beta(r, k)
        sigma = (mpmath.cosh(beta) + mpmath.cos(beta)) / (mpmath.sinh(beta) + mpmath.sin(beta))
        b, c = (sp.Float(mpmath.nstr(v, Function.DIGITS + 5), Function.DIGITS + 5) for v in (beta, sigma))
    phi = sp.cosh(b * ETA) - sp.cos(b * ETA) - c * (sp.sinh(b * ETA) - sp.sin(b * ETA))
    return Function(f"tip-mass mode {k}", phi), beta


class TipMassModes(unittest.TestCase):
    """With the tip-mass modes themselves as the basis, the fixed-base frequencies of the
    derivation's M and K are the exact ones, beta_k^2 sqrt(EI / (m_c H^3))."""

    def test_the_tip_mass_modes_give_the_exact_frequencies(self):
        r = 0.5
        with mpmath.workdps(40):
            shapes = [tip_mass_mode(r, k) for k in (1, 2, 3)]
        variant = model("tip_modes", tuple(f for f, _ in shapes))
        mech = Mechanics(variant, Symbols.create(variant))
        h, ei, m_c = 20.0, 4e10, 2e5
        values = {"h": h, "ei": ei, "m_c": m_c, "m": r * m_c}
        subs = [(mech.P[k], v) for k, v in values.items()]
        mass = np.array(ca.DM(ca.substitute(mech.mass_block(), ca.vertcat(*[a for a, _ in subs]),
                                            ca.vertcat(*[v for _, v in subs]))).full())
        stiff = np.array([[float(ca.DM(ca.substitute(e, ca.vertcat(*[a for a, _ in subs]),
                                                     ca.vertcat(*[v for _, v in subs])))) for e in row]
                          for row in mech.stiffness()])
        omega = np.sqrt(np.sort(np.linalg.eigvals(np.linalg.solve(mass, stiff)).real))
        worst = 0.0
        for (_, beta), w in zip(shapes, omega):
            exact = float(beta) ** 2 * (ei / (m_c * h**3)) ** 0.5
            worst = max(worst, abs(w / exact - 1))
            self.assertLess(abs(w / exact - 1), 1e-10, f"{w} vs {exact}")
        print(f"tip-mass modes (m/m_c = {r}): worst relative frequency error {worst:.1e}")


class OneCoordinateReduction(unittest.TestCase):
    """The generalised full-contact maps (nearest velocities in the kinetic-energy norm) give the
    paper's maps (26), (30), (32) for one coordinate."""

    def test_general_maps_reduce_to_the_papers(self):
        variant = Variant("full", "", "", PAPER)
        sym = Symbols.create(variant)
        mech = Mechanics(variant, sym)
        paper = mech.impact_maps(sym.us, sym.u_dots, sym.theta_dot)
        general = mech.impact_maps(sym.us, sym.u_dots, sym.theta_dot, general=True)
        names = ("u_dot_contact", "u_dot_momentum", "u_dot_vvel")
        inputs = [*sym.us, *sym.u_dots, sym.theta_dot, sym.s, *sym.params.values()]
        f = ca.Function("maps", inputs, [ca.vertcat(*[paper[n][0] - general[n][0] for n in names]),
                                         ca.vertcat(*[paper[n][0] for n in names])])
        rng = random.Random(1)
        for _ in range(50):
            p = {"h": rng.uniform(5, 30), "b": rng.uniform(0.5, 4), "ei": 1e9, "m": rng.uniform(0, 2),
                 "m_c": rng.uniform(0, 2), "m_b": rng.uniform(0, 2), "i_bc": rng.uniform(0, 5),
                 "zeta": 0.05, "g": 9.81}
            args = [rng.uniform(-0.1, 0.1), rng.uniform(-1, 1), rng.uniform(-1, 1), rng.choice([1.0, -1.0]),
                    *[p[n] for n in sym.params]]
            diff, value = (np.array(ca.DM(v).full()).reshape(-1) for v in f(*args))
            self.assertLess(np.abs(diff).max(), 1e-12 * max(1.0, np.abs(value).max()), f"{names}: {diff}")


class OneFunctionTuple(unittest.TestCase):
    """A one-function tuple is the one-coordinate model: the paper's model written with
    ``shape=(CUBIC,)`` emits the same bytes of IR (tapes, golden samples, parameters) as
    ``shape=CUBIC``, for the full variant and a specialised one."""

    def test_a_one_function_tuple_emits_the_same_bytes(self):
        from rocking_derive.ir import dumps, variant_ir

        tuple_model = Model(PAPER.name, PAPER.description, (CUBIC,), PAPER.masses)
        for name, remove in (("full", ()), ("point_mass", ("m_c", "m_b", "i_bc"))):
            one = Variant(name, "", "", PAPER, remove=remove)
            tup = Variant(name, "", "", tuple_model, remove=remove)
            self.assertEqual(tup.model.coordinates, 1)
            self.assertEqual(dumps(variant_ir(one)), dumps(variant_ir(tup)), name)


if __name__ == "__main__":
    unittest.main()
