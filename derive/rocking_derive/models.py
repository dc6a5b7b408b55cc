"""Model descriptions and kernel variants: the file a model developer edits.

A *model* is a shape function for the column deflection (or a tuple of them, a Ritz basis: one
deformation coordinate u_i each, the deflection is sum u_i psi_i) plus a set of masses. A *variant* is a
model specialised symbolically: masses removed (their parameter is replaced by the constant 0 before
anything is derived, so their terms never reach the kernels), the column made rigid (u = 0, one
degree of freedom), or the rotation linearised. Every variant exports the same set of functions
(see ``kernels.py``), so the Rust solver runs any of them through one trait.

To change the model, edit or add a ``Model`` below and list its variants in ``VARIANTS``, then run
``cargo xtask regen``: the IR, the Rust kernels and the golden samples are rebuilt, and the physics
tests of the ``rocking-kernels`` crate run on every variant.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from fractions import Fraction

import sympy as sp

import mpmath

from .shape import ETA, Basis, Function, Polynomial


@dataclass(frozen=True)
class Param:
    """A symbolic parameter. ``physical`` names the field of the Rust struct ``Physical`` that
    supplies it; parameters a model adds beyond those have a ``default`` instead."""

    name: str
    doc: str
    physical: str | None = None
    default: float | None = None
    derived: str | None = None  # computed by the solver from the others ("modal_damping")


@dataclass(frozen=True)
class ColumnMass:
    """Mass distributed uniformly along the column (parameter ``mass`` is the total)."""

    mass: str


@dataclass(frozen=True)
class LumpedMass:
    """A point mass on the column axis at height eta * H, moving with the column deflection.
    ``removable``: a scene may switch it off (``[effects] <mass> = false``); the top mass m is the
    unit of mass of the dimensionless form and stays."""

    mass: str
    eta: Fraction | str = Fraction(1)  # a number, or the name of a parameter
    removable: bool = True


@dataclass(frozen=True)
class BaseMass:
    """The thin rigid base plate: mass at the base centre and inertia ``inertia`` about a corner."""

    mass: str
    inertia: str


#: Parameters every model has; their order is the order of the kernels' parameter array.
CORE_PARAMS = (
    Param("h", "column height H", "h"),
    Param("b", "half-width B of the base", "b"),
    Param("ei", "bending stiffness EI of the column", "ei"),
    Param("m", "top mass m", "m"),
    Param("m_c", "total column mass m_c", "m_c"),
    Param("m_b", "base mass m_b", "m_b"),
    Param("i_bc", "base inertia about a corner, I_bc = I_b + m_b B^2", "i_bc"),
    Param("zeta", "fixed-base damping ratio", "zeta"),
    Param("g", "gravitational acceleration", "g"),
)


@dataclass(frozen=True)
class Model:
    """``shape``: one function (the one-coordinate model, psi(1) = 1: u is the top displacement)
    or a tuple of them (one coordinate u_i each). Every function has psi(0) = psi'(0) = 0."""

    name: str
    description: str
    shape: Polynomial | Function | tuple
    masses: tuple
    extra_params: tuple[Param, ...] = ()

    def __post_init__(self):
        basis = self.basis
        basis.check(f"model {self.name!r}")
        # psi(1) exact, or at the working precision for a transcendental function (then 1 in f64).
        if not isinstance(self.shape, tuple) and float(basis.functions[0].at_top()) != 1.0:
            raise ValueError(f"model {self.name!r}: psi(1) must be 1 (u is the top displacement)")

    @property
    def basis(self) -> Basis:
        return Basis(self.shape if isinstance(self.shape, tuple) else (self.shape,))

    @property
    def coordinates(self) -> int:
        """n, the number of deformation coordinates u_1..u_n."""
        return len(self.basis)

    @property
    def params(self) -> tuple[Param, ...]:
        """The parameter vector: the core, the model's own, and with several coordinates the
        upper triangle of the modal damping matrix (row by row), which the solver computes from
        the fixed-base modes and their damping ratios (rocking_kernels::modes)."""
        n = self.coordinates
        damping = tuple(
            Param(f"c_{i + 1}_{j + 1}", f"modal damping matrix C, row {i + 1}, column {j + 1} (from zeta "
                  "and the fixed-base modes)", derived="modal_damping")
            for i in range(n) for j in range(i, n)
        ) if n > 1 else ()
        return CORE_PARAMS + self.extra_params + damping


@dataclass(frozen=True)
class Variant:
    name: str  # Rust module name
    title: str
    doc: str
    model: Model
    remove: tuple[str, ...] = ()  # mass parameters fixed to zero (their masses vanish)
    rigid: bool = False  # u = 0: one degree of freedom
    small_angle: bool = False  # sin(theta) -> theta, cos(theta) -> 1 - theta^2/2 in the energies
    impact_doc: str = field(default="")


# --- the paper's model ---------------------------------------------------------------------------

CUBIC = Polynomial("psi = 3/2 eta^2 - 1/2 eta^3 (paper eq 1)", {2: Fraction(3, 2), 3: Fraction(-1, 2)})

PAPER = Model(
    name="cubic",
    description="Elastic cantilever with distributed mass, a top mass and a rigid base (paper Fig. 1)",
    shape=CUBIC,
    masses=(ColumnMass("m_c"), LumpedMass("m", removable=False), BaseMass("m_b", "i_bc")),
)

# --- two examples of the model developer's path (kept, so they stay tested) ----------------------

COSINE = Model(
    name="cosine",
    description="Same masses, shape psi = 1 - cos(pi xi / 2H)",
    shape=Function("psi = 1 - cos(pi eta / 2)", 1 - sp.cos(sp.pi * ETA / 2)),
    masses=PAPER.masses,
)

PLATFORM = Model(
    name="cubic_platform",
    description="The paper's model plus a lumped mass m_a at height eta_a H (e.g. a platform)",
    shape=CUBIC,
    masses=PAPER.masses + (LumpedMass("m_a", "eta_a"),),
    extra_params=(
        Param("m_a", "added lumped mass", default=0.0),
        Param("eta_a", "height of the added mass as a fraction of H", default=0.5),
    ),
)

# --- several deformation coordinates: the paper's masses on a Ritz basis -------------------------

POLYNOMIAL2 = Model(
    name="polynomial2",
    description="The paper's masses, two deformation coordinates: a polynomial basis",
    shape=(Polynomial("eta^2", {2: Fraction(1)}), Polynomial("eta^3", {3: Fraction(1)})),
    masses=PAPER.masses,
)

POLYNOMIAL3 = Model(
    name="polynomial3",
    description="The paper's masses, three deformation coordinates: a polynomial basis",
    shape=POLYNOMIAL2.shape + (Polynomial("eta^4", {4: Fraction(1)}),),
    masses=PAPER.masses,
)

# The span of POLYNOMIAL2 in another basis: the two models must give the same motion (a test of
# the basis invariance of the equations and of the impact maps nearest in the kinetic-energy norm).
CUBIC_QUADRATIC = Model(
    name="cubic_quadratic",
    description="The paper's masses, two deformation coordinates: the paper's cubic and eta^2 (the "
                "span of polynomial2)",
    shape=(CUBIC, Polynomial("eta^2", {2: Fraction(1)})),
    masses=PAPER.masses,
)


def cantilever_mode(k: int) -> Function:
    """The k-th vibration mode of a uniform clamped-free Euler-Bernoulli cantilever, scaled to 1 at
    the top: phi(eta) = cosh(b eta) - cos(b eta) - sigma (sinh(b eta) - sin(b eta)), b = beta_k the
    k-th root of 1 + cos(b) cosh(b) = 0 and sigma = (cosh b + cos b) / (sinh b + sin b), both to 40
    digits (mpmath, deterministic)."""
    digits = Function.DIGITS
    with mpmath.workdps(digits + 10):
        beta = mpmath.findroot(lambda b: 1 + mpmath.cos(b) * mpmath.cosh(b), (2 * k - 1) * mpmath.pi / 2)
        sigma = (mpmath.cosh(beta) + mpmath.cos(beta)) / (mpmath.sinh(beta) + mpmath.sin(beta))
        top = mpmath.cosh(beta) - mpmath.cos(beta) - sigma * (mpmath.sinh(beta) - mpmath.sin(beta))
        b, c, d = (sp.Float(mpmath.nstr(v, digits + 5), digits + 5) for v in (beta, sigma, 1 / top))
    phi = d * (sp.cosh(b * ETA) - sp.cos(b * ETA) - c * (sp.sinh(b * ETA) - sp.sin(b * ETA)))
    return Function(f"cantilever mode {k} (beta = {mpmath.nstr(beta, 12)})", phi)


CANTILEVER_MODES2 = Model(
    name="cantilever_modes2",
    description="The paper's masses, two deformation coordinates: the first two cantilever modes",
    shape=(cantilever_mode(1), cantilever_mode(2)),
    masses=PAPER.masses,
)

CANTILEVER_MODES3 = Model(
    name="cantilever_modes3",
    description="The paper's masses, three deformation coordinates: the first three cantilever modes",
    shape=CANTILEVER_MODES2.shape + (cantilever_mode(3),),
    masses=PAPER.masses,
)

#: Larger cantilever-mode bases, n = 4 .. 8 (issue 45): how many modes the base forces need.
CARDINALS = {4: "four", 5: "five", 6: "six", 7: "seven", 8: "eight"}
CANTILEVER_MODES1 = Model(
    name="cantilever_modes1",
    description="The paper's masses, one deformation coordinate: the first cantilever mode",
    shape=cantilever_mode(1),
    masses=PAPER.masses,
)
CANTILEVER_MODES = {1: CANTILEVER_MODES1, 2: CANTILEVER_MODES2, 3: CANTILEVER_MODES3}
for _n in range(4, 9):
    CANTILEVER_MODES[_n] = Model(
        name=f"cantilever_modes{_n}",
        description=f"The paper's masses, {CARDINALS[_n]} deformation coordinates: the first {CARDINALS[_n]} "
                    "cantilever modes",
        shape=CANTILEVER_MODES[_n - 1].shape + (cantilever_mode(_n),),
        masses=PAPER.masses,
    )

VARIANTS = (
    Variant("full", "Full model: distributed column mass, top mass, base mass and inertia", "", PAPER),
    Variant(
        "massless_column",
        "Massless column (m_c = 0): top mass, base mass and inertia",
        "",
        PAPER,
        remove=("m_c",),
    ),
    Variant(
        "massless_base",
        "Massless base (m_b = I_bc = 0): distributed column mass and top mass",
        "",
        PAPER,
        remove=("m_b", "i_bc"),
    ),
    Variant(
        "point_mass",
        "Top mass only (m_c = m_b = I_bc = 0): the model of Acikgoz & DeJong",
        "",
        PAPER,
        remove=("m_c", "m_b", "i_bc"),
    ),
    Variant(
        "rigid",
        "Rigid column (u = 0): one degree of freedom, Housner's rocking block with these masses",
        "The column deflection is frozen: `u` and `u_dot` are inputs for a uniform interface but are "
        "never read, and `u_ddot` is 0. The VVEL map is its rigid limit: the horizontal kinetic "
        "energy is kept and projected on the rocking mode about the impacting corner "
        "(equations.md 4.2). ADJex has no full-contact branch without a deformation degree of "
        "freedom: its contact energies are +inf, so it reduces to Housner's rule.",
        PAPER,
        rigid=True,
    ),
    Variant(
        "small_angle",
        "Full model linearised in theta (sin -> theta, cos -> 1 - theta^2/2 in the energies)",
        "Consistent to second order in the energies, so that the energy balance of a run still closes.",
        PAPER,
        small_angle=True,
    ),
    Variant("cosine_shape", "Example: the full model with the shape psi = 1 - cos(pi xi / 2H)", "", COSINE),
    Variant("added_mass", "Example: the full model plus a lumped mass m_a at height eta_a H", "", PLATFORM),
    Variant("polynomial2", "The full model on the basis eta^2, eta^3: two deformation coordinates", "",
            POLYNOMIAL2),
    Variant("polynomial3", "The full model on the basis eta^2, eta^3, eta^4: three deformation coordinates",
            "", POLYNOMIAL3),
    Variant("cubic_quadratic", "The full model on the basis psi_cubic, eta^2: two deformation "
            "coordinates (the span of polynomial2)", "", CUBIC_QUADRATIC),
    Variant("cantilever_modes2", "The full model on the first two cantilever modes: two deformation "
            "coordinates", "", CANTILEVER_MODES2),
    Variant("cantilever_modes3", "The full model on the first three cantilever modes: three deformation "
            "coordinates", "", CANTILEVER_MODES3),
    Variant("cantilever_modes1", "The full model on the first cantilever mode: one deformation coordinate",
            "", CANTILEVER_MODES1),
    *(Variant(f"cantilever_modes{n}", f"The full model on the first {CARDINALS[n]} cantilever modes: "
              f"{CARDINALS[n]} deformation coordinates", "", CANTILEVER_MODES[n]) for n in range(4, 9)),
)
