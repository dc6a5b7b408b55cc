"""Shape functions psi(eta) of the column deflection, eta = xi / H in [0, 1], psi(1) = 1.

The column deflection is u(t) psi(xi/H). Every column integral the energies need reduces to six
moments of the shape over eta in [0, 1] (see ``mechanics.column_integral``) plus the stiffness
integral of psi''. Polynomial shapes are integrated exactly in rational arithmetic, so the cubic
shape of the paper's eq (1) gives exactly 3/8, 33/140 and 11/40; other shapes use Gauss-Legendre
quadrature, exact to rounding for smooth functions.
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction
from typing import Callable

import numpy as np

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
        """psi at eta: exact for a Fraction, floating point for a float or a CasADi expression."""
        if isinstance(eta, Fraction):
            return sum(c * eta**k for k, c in self.coefficients.items())
        return sum(float(c) * eta**k for k, c in self.coefficients.items())

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
    """psi(eta) given as a smooth function with its second derivative: Gauss-Legendre moments."""

    def __init__(self, description: str, psi: Callable, psi_dd: Callable, points: int = 40):
        self.description = description
        self.psi, self.psi_dd, self.points = psi, psi_dd, points
        if abs(psi(1.0) - 1.0) > 1e-14:
            raise ValueError(f"shape {description!r}: psi(1) must be 1 (u is the top displacement)")

    def value(self, eta):
        return self.psi(eta)

    def moments(self) -> Moments:
        x, w = np.polynomial.legendre.leggauss(self.points)
        eta, w = 0.5 * (x + 1.0), 0.5 * w
        psi = np.array([self.psi(e) for e in eta])
        dd = np.array([self.psi_dd(e) for e in eta])
        values = {
            "1": float(w.sum()),
            "eta": float(w @ eta),
            "psi": float(w @ psi),
            "eta2": float(w @ eta**2),
            "eta_psi": float(w @ (eta * psi)),
            "psi2": float(w @ psi**2),
        }
        return Moments(values, float(w @ dd**2))
