//! The standard normal distribution, accurate in the tails (libm's erfc),
//! because likelihoods of stripes far from the median live there.

use std::f64::consts::{FRAC_1_SQRT_2, PI};

/// Below this, Φ(x) underflows in erfc and the asymptotic forms are used.
const TAIL: f64 = -37.0;

/// Φ(x), the standard normal CDF.
pub fn cdf(x: f64) -> f64 {
    0.5 * libm::erfc(-x * FRAC_1_SQRT_2)
}

/// ln Φ(x), finite far into the lower tail.
pub fn ln_cdf(x: f64) -> f64 {
    if x < TAIL {
        // Mills ratio: Φ(x) ≈ φ(x)/|x| · (1 − 1/x²)
        -0.5 * x * x - (-x).ln() - 0.5 * (2.0 * PI).ln() + (1.0 - 1.0 / (x * x)).ln()
    } else {
        cdf(x).ln()
    }
}

/// φ(x)/Φ(x) (the inverse Mills ratio), finite far into the lower tail.
pub fn hazard(x: f64) -> f64 {
    if x < TAIL {
        // asymptotic expansion: −x / (1 − 1/x² + 3/x⁴)
        let r = 1.0 / (x * x);
        -x / (1.0 - r + 3.0 * r * r)
    } else {
        (-0.5 * x * x).exp() / (2.0 * PI).sqrt() / cdf(x)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn values_and_tails() {
        assert!((cdf(0.0) - 0.5).abs() < 1e-16);
        assert!((cdf(1.959963984540054) - 0.975).abs() < 1e-15);
        // continuity of the tail forms at the switch
        let (a, b) = (ln_cdf(TAIL - 1e-9), ln_cdf(TAIL + 1e-9));
        assert!(((a - b) / b).abs() < 1e-6, "{a} {b}");
        let (a, b) = (hazard(TAIL - 1e-9), hazard(TAIL + 1e-9));
        assert!(((a - b) / b).abs() < 1e-6, "{a} {b}");
        assert!(ln_cdf(-200.0).is_finite() && hazard(-200.0).is_finite());
    }
}
