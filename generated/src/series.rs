//! Recurrences of truncated power series, for the Taylor-mode kernels of [`crate::taylor`].
//!
//! A series is `[f64; N]`, `a(t0 + h) = Σ a[k] h^k`. Each function computes coefficient `k` of
//! a result from coefficients `0..=k` of its arguments and `0..k` of itself (Jorba & Zou 2005,
//! Section 3), so the generated kernels can run the whole tape once per order. Hand-written: the
//! generator only emits calls to these.

/// Coefficient `k` of a constant `c`.
#[inline(always)]
#[must_use]
pub fn at0(k: usize, c: f64) -> f64 {
    if k == 0 {
        c
    } else {
        0.0
    }
}

/// Coefficient `k` of the product `a b` (Cauchy product).
#[inline(always)]
#[must_use]
pub fn mul<const N: usize>(a: &[f64; N], b: &[f64; N], k: usize) -> f64 {
    (0..=k).map(|j| a[j] * b[k - j]).sum()
}

/// Coefficient `k` of `a²` (the Cauchy product with its symmetric half folded).
#[inline(always)]
#[must_use]
pub fn sq<const N: usize>(a: &[f64; N], k: usize) -> f64 {
    let half: f64 = (0..k.div_ceil(2)).map(|j| a[j] * a[k - j]).sum();
    let mid = if k % 2 == 0 { a[k / 2] * a[k / 2] } else { 0.0 };
    2.0 * half + mid
}

/// Coefficient `k` of `c = a / b`, given `a[k]` and `c[0..k]`: `b c = a`.
#[inline(always)]
#[must_use]
pub fn div<const N: usize>(a_k: f64, b: &[f64; N], c: &[f64; N], k: usize) -> f64 {
    let tail: f64 = (1..=k).map(|j| b[j] * c[k - j]).sum();
    (a_k - tail) / b[0]
}

/// Writes coefficient `k` of `c = √a` into `c[k]`, from `c[0..k]`: `c² = a`.
#[inline(always)]
pub fn sqrt<const N: usize>(a: &[f64; N], c: &mut [f64; N], k: usize) {
    if k == 0 {
        c[0] = a[0].sqrt();
        return;
    }
    let inner: f64 = (1..k).map(|j| c[j] * c[k - j]).sum();
    c[k] = (a[k] - inner) / (2.0 * c[0]);
}

/// Writes coefficient `k` of `sin a` and `cos a` into `s[k]` and `c[k]`: `s' = c a'`,
/// `c' = −s a'`.
#[inline(always)]
pub fn sin_cos<const N: usize>(a: &[f64; N], s: &mut [f64; N], c: &mut [f64; N], k: usize) {
    if k == 0 {
        (s[0], c[0]) = a[0].sin_cos();
        return;
    }
    let (mut ds, mut dc) = (0.0, 0.0);
    for j in 1..=k {
        let ja = j as f64 * a[j];
        ds += ja * c[k - j];
        dc += ja * s[k - j];
    }
    let kf = k as f64;
    s[k] = ds / kf;
    c[k] = -dc / kf;
}

#[cfg(test)]
mod tests {
    use super::*;

    /// exp-free checks on series with known coefficients.
    #[test]
    fn recurrences_match_known_series() {
        // a = 1 + t, b = 2 - t + t^2
        let a = [1.0, 1.0, 0.0, 0.0, 0.0, 0.0];
        let b = [2.0, -1.0, 1.0, 0.0, 0.0, 0.0];
        let prod: Vec<f64> = (0..6).map(|k| mul(&a, &b, k)).collect();
        assert_eq!(prod, [2.0, 1.0, 0.0, 1.0, 0.0, 0.0]);
        let squares: Vec<f64> = (0..6).map(|k| sq(&b, k)).collect();
        let cauchy: Vec<f64> = (0..6).map(|k| mul(&b, &b, k)).collect();
        assert_eq!(squares, cauchy);
        // 1 / (1 - t) = Σ t^k
        let one = [1.0, 0.0, 0.0, 0.0, 0.0, 0.0];
        let d = [1.0, -1.0, 0.0, 0.0, 0.0, 0.0];
        let mut q = [0.0; 6];
        for k in 0..6 {
            q[k] = div(one[k], &d, &q, k);
        }
        assert_eq!(q, [1.0; 6]);
        // √(1 + 2t + t²) = 1 + t
        let mut r = [0.0; 6];
        for k in 0..6 {
            sqrt(&[1.0, 2.0, 1.0, 0.0, 0.0, 0.0], &mut r, k);
        }
        assert_eq!(r, a);
        // sin(t), cos(t): 1/k! with alternating signs
        let t = [0.0, 1.0, 0.0, 0.0, 0.0, 0.0];
        let (mut s, mut c) = ([0.0; 6], [0.0; 6]);
        for k in 0..6 {
            sin_cos(&t, &mut s, &mut c, k);
        }
        let want_s = [0.0, 1.0, 0.0, -1.0 / 6.0, 0.0, 1.0 / 120.0];
        let want_c = [1.0, 0.0, -0.5, 0.0, 1.0 / 24.0, 0.0];
        for k in 0..6 {
            assert!((s[k] - want_s[k]).abs() < 1e-16, "sin[{k}] = {}", s[k]);
            assert!((c[k] - want_c[k]).abs() < 1e-16, "cos[{k}] = {}", c[k]);
        }
    }
}
