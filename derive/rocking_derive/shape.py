"""Shape functions psi(eta) of the column deflection, eta = xi / H in [0, 1], psi(1) = 1.

The column deflection is u(t) psi(xi/H). Every column integral the energies need reduces to six
moments of the shape over eta in [0, 1] (see ``mechanics.column_integral``) plus the stiffness
integral of psi''. Polynomial shapes are integrated exactly in rational arithmetic, so the cubic
shape of the paper's eq (1) gives exactly 3/8, 33/140 and 11/40; other shapes (a sympy expression)
use Gauss-Legendre quadrature in mpmath at 40 digits. Every value is rounded once to f64: nothing
here depends on the CPU, a BLAS kernel, the thread count or the hash seed.
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
        if sum(self.coefficients.values()) != 1:
            raise ValueError(f"shape {description!r}: psi(1) must be 1 (u is the top displacement)")

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
        d2 = {k - 2: c * k * (k - 1) for k, c in psi.items() if k >= 2}
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
        if sp.simplify(self.expr.subs(ETA, 1) - 1) != 0:
            raise ValueError(f"shape {description!r}: psi(1) must be 1 (u is the top displacement)")
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
