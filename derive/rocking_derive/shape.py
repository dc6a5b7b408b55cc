"""Shape functions psi(eta) of the column deflection, eta = xi / H in [0, 1].

The column deflection is u(t) psi(xi/H) for one function (psi(1) = 1: u is the top displacement),
or sum u_i(t) psi_i(xi/H) for a basis of several (``Basis``). Every column integral the energies
need reduces to moments of the shapes over eta in [0, 1] (see ``mechanics.column_integral``):
of 1, eta, eta^2, psi_i, eta psi_i and psi_i psi_j, plus the stiffness integrals of psi_i'' psi_j''.
Polynomial shapes are integrated exactly in rational arithmetic, so the cubic shape of the paper's
eq (1) gives exactly 3/8, 33/140 and 11/40; other shapes (a sympy expression) use Gauss-Legendre
quadrature in mpmath at 40 digits. Every value is rounded once to f64: nothing here depends on
the CPU, a BLAS kernel, the thread count or the hash seed.
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction

import casadi as ca
import mpmath
import sympy as sp

#: The symbol of the height coordinate eta = xi / H in a shape expression.
ETA = sp.Symbol("eta")

#: Names of the mass moments, each the integral over eta in [0, 1] of the named product.
MOMENTS = ("1", "eta", "psi", "eta2", "eta_psi", "psi2")


@dataclass(frozen=True)
class Moments:
    """Integrals over eta in [0, 1]: of 1, eta, psi, eta^2, eta*psi, psi^2, and (psi'')^2."""

    values: dict[str, float]
    stiffness: float  # integral of (d^2 psi / d eta^2)^2; k~ = EI / H^3 * stiffness
    exact: dict[str, Fraction] | None = None  # rational values for polynomial shapes


class Polynomial:
    """psi(eta) = sum_k c_k eta^k with rational coefficients: moments are exact fractions."""

    def __init__(self, description: str, coefficients: dict[int, Fraction]):
        self.description = description
        self.coefficients = {k: Fraction(v) for k, v in coefficients.items() if v != 0}
        if any(k < 0 for k in self.coefficients):
            raise ValueError(f"shape {description!r}: a polynomial has no negative powers of eta")

    def value(self, eta):
        """psi at eta: exact for a Fraction, correctly rounded for a float (computed exactly,
        rounded once), a CasADi expression for a CasADi symbol."""
        if isinstance(eta, Fraction):
            return sum(c * eta**k for k, c in self.coefficients.items())
        if isinstance(eta, (int, float)):
            return float(self.value(Fraction(eta)))
        return sum(float(c) * eta**k for k, c in self.coefficients.items())

    def curvature_at_base(self) -> float:
        """psi''(0), the second derivative in eta at the base (exact, rounded once)."""
        return float(2 * self.coefficients.get(2, Fraction(0)))

    def at_base(self) -> tuple[float, float]:
        """(psi(0), psi'(0)), exact."""
        return self.coefficients.get(0, Fraction(0)), self.coefficients.get(1, Fraction(0))

    def at_top(self):
        """psi(1), exact."""
        return sum(self.coefficients.values(), Fraction(0))

    def sympy(self) -> sp.Expr:
        """psi as an exact sympy polynomial in ``ETA``."""
        return sum((sp.Rational(c.numerator, c.denominator) * ETA**k
                    for k, c in sorted(self.coefficients.items())), sp.Integer(0))

    def _second(self) -> dict[int, Fraction]:
        return {k - 2: c * k * (k - 1) for k, c in self.coefficients.items() if k >= 2}

    def _mul(self, a: dict[int, Fraction], b: dict[int, Fraction]) -> dict[int, Fraction]:
        out: dict[int, Fraction] = {}
        for i, x in a.items():
            for j, y in b.items():
                out[i + j] = out.get(i + j, Fraction(0)) + x * y
        return out

    @staticmethod
    def _integral(p: dict[int, Fraction]) -> Fraction:
        return sum((c / (k + 1) for k, c in p.items()), Fraction(0))

    def moments(self) -> Moments:
        psi = self.coefficients
        eta = {1: Fraction(1)}
        one = {0: Fraction(1)}
        d2 = self._second()
        exact = {
            "1": self._integral(one),
            "eta": self._integral(eta),
            "psi": self._integral(psi),
            "eta2": self._integral(self._mul(eta, eta)),
            "eta_psi": self._integral(self._mul(eta, psi)),
            "psi2": self._integral(self._mul(psi, psi)),
        }
        stiffness = self._integral(self._mul(d2, d2))
        return Moments({k: float(v) for k, v in exact.items()}, float(stiffness), exact)


class Function:
    """psi(eta) given as a sympy expression in ``ETA``: moments by Gauss-Legendre in mpmath.

    psi'' is derived by sympy. Every moment is computed at ``DIGITS`` significant digits in
    mpmath (pure Python: no BLAS or LAPACK, so no dependence on the CPU or its math kernels) and
    rounded once to f64, so the derivation writes the same bytes on every machine.
    """

    #: Working precision of the quadrature, in decimal digits.
    DIGITS = 40

    def __init__(self, description: str, psi: sp.Expr):
        self.description = description
        self.expr = sp.sympify(psi)
        free = self.expr.free_symbols - {ETA}
        if free:
            raise ValueError(f"shape {description!r}: psi may depend on eta only, not on {free}")
        self.expr_dd = sp.diff(self.expr, ETA, 2)
        self._casadi = sp.lambdify(ETA, self.expr, modules=[_CASADI_FUNCTIONS, "math"])

    def value(self, eta):
        """psi at eta: correctly rounded for a number, a CasADi expression for a CasADi symbol."""
        if isinstance(eta, (Fraction, int, float)):
            exact = self.expr.subs(ETA, sp.Rational(eta.numerator, eta.denominator)
                                   if isinstance(eta, Fraction) else sp.Rational(eta))
            return float(sp.N(exact, self.DIGITS))
        return self._casadi(eta)

    def curvature_at_base(self) -> float:
        """psi''(0), the second derivative in eta at the base (correctly rounded)."""
        return float(sp.N(self.expr_dd.subs(ETA, 0), self.DIGITS))

    def at_base(self) -> tuple[sp.Expr, sp.Expr]:
        """(psi(0), psi'(0)): exact where sympy simplifies them, else at the working precision."""
        return tuple(_exact_or_numeric(e.subs(ETA, 0), self.DIGITS)
                     for e in (self.expr, sp.diff(self.expr, ETA)))

    def at_top(self) -> sp.Expr:
        """psi(1): exact where sympy simplifies it, else at the working precision."""
        return _exact_or_numeric(self.expr.subs(ETA, 1), self.DIGITS)

    def sympy(self) -> sp.Expr:
        return self.expr

    def moments(self) -> Moments:
        with mpmath.workdps(self.DIGITS):
            psi = sp.lambdify(ETA, self.expr, modules="mpmath")
            dd = sp.lambdify(ETA, self.expr_dd, modules="mpmath")
            integrands = {
                "1": lambda e: mpmath.mpf(1),
                "eta": lambda e: e,
                "psi": psi,
                "eta2": lambda e: e**2,
                "eta_psi": lambda e: e * psi(e),
                "psi2": lambda e: psi(e) ** 2,
            }
            values = {k: _integral(f, self.description, k) for k, f in integrands.items()}
            stiffness = _integral(lambda e: dd(e) ** 2, self.description, "(psi'')^2")
        return Moments(values, stiffness)


def _exact_or_numeric(value: sp.Expr, digits: int):
    """A constant expression simplified exactly, or, when sympy cannot, evaluated at ``digits``
    digits with what is below 10^-(digits - 10) of its terms read as zero."""
    exact = sp.simplify(value)
    if exact.is_number and exact.is_rational:
        return exact
    number = sp.N(value, digits)
    return sp.Integer(0) if abs(number) < sp.Float(10) ** (10 - digits) else number


Shape = Polynomial | Function


@dataclass(frozen=True)
class BasisMoments:
    """The moments of a basis psi_1..psi_n over eta in [0, 1], each rounded once to f64.

    ``eta`` holds the integrals of 1, eta and eta^2 (keys "1", "eta", "eta2"); the tuples are
    indexed by function: ``psi[i]`` of psi_i, ``eta_psi[i]`` of eta psi_i, ``psi_psi[i][j]`` of
    psi_i psi_j and ``stiffness[i][j]`` of psi_i'' psi_j''. ``half_eta2`` and ``half_psi2[i]``
    are half of the squares' integrals, from the exact value where there is one (a polynomial)."""

    eta: dict[str, float]
    half_eta2: float
    psi: tuple[float, ...]
    eta_psi: tuple[float, ...]
    psi_psi: tuple[tuple[float, ...], ...]
    half_psi2: tuple[float, ...]
    stiffness: tuple[tuple[float, ...], ...]


class Basis:
    """The shape functions of a column with n deformation coordinates: its deflection is
    sum u_i psi_i(eta). One function is the one-coordinate model, with exactly the moments
    the function gives alone."""

    def __init__(self, functions: tuple[Shape, ...]):
        if not functions:
            raise ValueError("a shape basis needs at least one function")
        for f in functions:
            if not isinstance(f, (Polynomial, Function)):
                raise TypeError(f"a shape must be a Polynomial or a Function, not {f!r}")
        self.functions = tuple(functions)

    def __len__(self) -> int:
        return len(self.functions)

    @property
    def description(self) -> str:
        if len(self.functions) == 1:
            return self.functions[0].description
        return "; ".join(f"psi_{i + 1}: {f.description}" for i, f in enumerate(self.functions))

    def values(self, eta) -> tuple:
        """(psi_1(eta), ..., psi_n(eta)), each as ``value`` gives it."""
        return tuple(f.value(eta) for f in self.functions)

    def moments(self) -> BasisMoments:
        own = [f.moments() for f in self.functions]
        first = own[0]
        half = lambda m, k: float(m.exact[k] / 2) if m.exact else m.values[k] / 2  # noqa: E731
        n = len(own)
        psi_psi = [[own[i].values["psi2"] if i == j else 0.0 for j in range(n)] for i in range(n)]
        stiffness = [[own[i].stiffness if i == j else 0.0 for j in range(n)] for i in range(n)]
        for table, derivative in ((psi_psi, 0), (stiffness, 2)):
            for i in range(n):
                for j in range(i + 1, n):
                    v = _cross(self.functions[i], self.functions[j], derivative)
                    # Functions orthogonal in this product integrate to zero to the quadrature's
                    # resolution: zero, so that no term of rounding noise reaches the kernels.
                    if abs(v) <= _RESOLUTION * abs(table[i][i] * table[j][j]) ** 0.5:
                        v = 0.0
                    table[i][j] = table[j][i] = v
        return BasisMoments(
            eta={k: first.values[k] for k in ("1", "eta", "eta2")},
            half_eta2=half(first, "eta2"),
            psi=tuple(m.values["psi"] for m in own),
            eta_psi=tuple(m.values["eta_psi"] for m in own),
            psi_psi=tuple(map(tuple, psi_psi)),
            half_psi2=tuple(half(m, "psi2") for m in own),
            stiffness=tuple(map(tuple, stiffness)),
        )

    def check(self, where: str) -> None:
        """Refuses a basis that does not describe a cantilever clamped in its base, or whose
        functions are not independent: psi_i(0) = 0 (the column's foot stays at the base
        centre), psi_i'(0) = 0 (it leaves the base perpendicularly: the section forces take the
        elastic moment from the curvature EI psi''(0) u / H^2 of a clamped column), and a
        positive definite Gram matrix of psi_i (else the mass matrix is singular)."""
        for i, f in enumerate(self.functions):
            name = f"psi_{i + 1} ({f.description!r})" if len(self.functions) > 1 else f"psi ({f.description!r})"
            value, slope = f.at_base()
            if value != 0:
                raise ValueError(f"{where}: {name} has psi(0) = {value}; the column's foot must stay at "
                                 "the base centre: psi(0) = 0")
            if slope != 0:
                raise ValueError(f"{where}: {name} has psi'(0) = {slope}; the column is clamped in its "
                                 "base (its section forces need it): psi'(0) = 0")
        if len(self.functions) > 1:
            gram = sp.Matrix(self.moments().psi_psi)
            minors = [gram[:k, :k].det() for k in range(1, len(self.functions) + 1)]
            if not all(m > 1e-12 * gram[0, 0] ** (k + 1) for k, m in enumerate(minors)):
                raise ValueError(f"{where}: the shape functions are not linearly independent "
                                 "(their Gram matrix is singular): drop one")


#: The relative resolution of the quadrature (``_integral`` demands an error estimate below it).
_RESOLUTION = 10.0 ** (-(Function.DIGITS - 10))


def _cross(a: Shape, b: Shape, derivative: int) -> float:
    """The integral over [0, 1] of the ``derivative``-th derivatives of a and b, multiplied:
    exact for two polynomials, else Gauss-Legendre at ``Function.DIGITS`` digits."""
    if isinstance(a, Polynomial) and isinstance(b, Polynomial):
        pa = a.coefficients if derivative == 0 else a._second()
        pb = b.coefficients if derivative == 0 else b._second()
        return float(Polynomial._integral(a._mul(pa, pb)))
    with mpmath.workdps(Function.DIGITS):
        fa, fb = (sp.lambdify(ETA, sp.diff(f.sympy(), ETA, derivative), modules="mpmath") for f in (a, b))
        what = "psi_i psi_j" if derivative == 0 else "psi_i'' psi_j''"
        return _integral(lambda e: fa(e) * fb(e), f"{a.description} x {b.description}", what)


#: CasADi counterparts of the sympy functions a shape may use (for psi at a symbolic height).
_CASADI_FUNCTIONS = {
    "sin": ca.sin, "cos": ca.cos, "tan": ca.tan, "exp": ca.exp, "log": ca.log, "sqrt": ca.sqrt,
    "sinh": ca.sinh, "cosh": ca.cosh, "tanh": ca.tanh, "atan": ca.atan,
}


def _integral(f, description: str, what: str) -> float:
    """Integral of f over [0, 1] by Gauss-Legendre at the working precision, rounded once to f64.

    mpmath refines the degree until two estimates agree; the error estimate must be far below
    the f64 resolution, so that rounding the result is the only error left."""
    value, error = mpmath.quad(f, [0, 1], method="gauss-legendre", error=True)
    if not error < mpmath.mpf(10) ** (-(Function.DIGITS - 10)) * max(1, abs(value)):
        raise ValueError(f"shape {description!r}: the quadrature of {what} did not converge "
                         f"(error estimate {mpmath.nstr(error, 3)}); is psi smooth on [0, 1]?")
    return float(value)
