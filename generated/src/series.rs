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
    if k == 0 {
        return a[0] * b[0];
    }
    dot_rev(&a[1..k], &b[1..k]) + (a[0] * b[k] + a[k] * b[0])
}

/// `Σ_j x[j] y[n − 1 − j]` (slices of one length), in two lanes: the terms of even j and of
/// odd j summed apart, then added, then the last term of an odd length. On x86_64 the lanes are
/// one SSE2 register (two terms per load, multiply and add: 9 % off a full-mass Taylor step at
/// order 16, `cargo bench -p rocking-kernels --bench kernels -- taylor`); elsewhere the same
/// operations in the same order on scalars, so the result is the same bit for bit.
///
/// Why the recurrences below sum the terms of orders `1..k` first: the kernels compute order k of
/// every tape node in turn, so only the terms with a coefficient of order k (`a[k] b[0]`,
/// `a[0] b[k]`) wait for this order's earlier nodes. Summed last, they leave the long sum of older
/// terms off the dependency chain from node to node, and the CPU overlaps the sums of the whole
/// tape (summed first, the tape ran one add latency per term).
#[inline(always)]
fn dot_rev(x: &[f64], y: &[f64]) -> f64 {
    #[cfg(target_arch = "x86_64")]
    {
        dot_rev_sse2(x, y)
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        dot_rev_scalar(x, y)
    }
}

/// [`dot_rev`] on scalars.
#[cfg(any(test, not(target_arch = "x86_64")))]
#[inline(always)]
fn dot_rev_scalar(x: &[f64], y: &[f64]) -> f64 {
    let n = x.len();
    assert_eq!(n, y.len(), "dot_rev of slices of different lengths");
    let (mut even, mut odd) = (0.0, 0.0);
    let mut i = 0;
    while i + 2 <= n {
        even += x[i] * y[n - 1 - i];
        odd += x[i + 1] * y[n - 2 - i];
        i += 2;
    }
    let mut r = even + odd;
    if i < n {
        r += x[i] * y[0];
    }
    r
}

/// [`dot_rev`] in an SSE2 register (part of every x86_64 CPU).
#[cfg(target_arch = "x86_64")]
#[inline(always)]
fn dot_rev_sse2(x: &[f64], y: &[f64]) -> f64 {
    use core::arch::x86_64::{
        _mm_add_pd, _mm_add_sd, _mm_cvtsd_f64, _mm_loadu_pd, _mm_mul_pd, _mm_setzero_pd,
        _mm_shuffle_pd, _mm_unpackhi_pd,
    };
    let n = x.len();
    assert_eq!(n, y.len(), "dot_rev of slices of different lengths");
    let mut i = 0;
    // SAFETY: SSE2 is in the x86_64 baseline; each load reads two f64 at x[i..i + 2] or
    // y[n − 2 − i..n − i], inside the slices because i + 2 <= n.
    let lanes = unsafe {
        let mut acc = _mm_setzero_pd();
        while i + 2 <= n {
            let a = _mm_loadu_pd(x.as_ptr().add(i));
            let b = _mm_loadu_pd(y.as_ptr().add(n - 2 - i));
            // [y[n − 2 − i], y[n − 1 − i]] swapped to pair with [x[i], x[i + 1]].
            acc = _mm_add_pd(acc, _mm_mul_pd(a, _mm_shuffle_pd::<1>(b, b)));
            i += 2;
        }
        _mm_cvtsd_f64(_mm_add_sd(acc, _mm_unpackhi_pd(acc, acc)))
    };
    if i < n {
        lanes + x[i] * y[0]
    } else {
        lanes
    }
}

/// Coefficient `k` of `a²` (the Cauchy product with its symmetric half folded).
#[inline(always)]
#[must_use]
pub fn sq<const N: usize>(a: &[f64; N], k: usize) -> f64 {
    if k == 0 {
        return a[0] * a[0];
    }
    // Σ_{j=1}^{k−1} a[j] a[k−j]: pairs j < k − j twice, and the middle term for even k.
    let m = k.div_ceil(2);
    let half: f64 = dot_rev(&a[1..m], &a[k + 1 - m..k]);
    let mid = if k % 2 == 0 { a[k / 2] * a[k / 2] } else { 0.0 };
    (2.0 * half + mid) + 2.0 * (a[0] * a[k])
}

/// Coefficient `k` of `c = a / b`, given `a[k]`, `c[0..k]` and `inv_b0 = 1 / b[0]`: `b c = a`.
/// The reciprocal is computed once per step by the caller, so an order waits for a
/// multiplication here, not a division (8 % off a point-mass Taylor step at order 16).
#[inline(always)]
#[must_use]
pub fn div<const N: usize>(a_k: f64, b: &[f64; N], c: &[f64; N], inv_b0: f64, k: usize) -> f64 {
    if k == 0 {
        return a_k * inv_b0;
    }
    let old: f64 = dot_rev(&b[1..k], &c[1..k]);
    (a_k - b[k] * c[0] - old) * inv_b0
}

/// Writes coefficient `k` of `c = √a` into `c[k]`, from `c[0..k]`: `c² = a`.
#[inline(always)]
pub fn sqrt<const N: usize>(a: &[f64; N], c: &mut [f64; N], k: usize) {
    if k == 0 {
        c[0] = a[0].sqrt();
        return;
    }
    let inner: f64 = dot_rev(&c[1..k], &c[1..k]);
    c[k] = (a[k] - inner) / (2.0 * c[0]);
}

/// Writes coefficient `k` of `sin a` and `cos a` into `s[k]` and `c[k]`: `s' = c a'`,
/// `c' = −s a'`. `da` keeps `j a[j]` (the coefficients of `a'`, shifted by one), written here
/// at each order, so that both sums are [`dot_rev`]s (8 % off a point-mass Taylor step at order 16).
#[inline(always)]
pub fn sin_cos<const N: usize>(
    a: &[f64; N],
    da: &mut [f64; N],
    s: &mut [f64; N],
    c: &mut [f64; N],
    k: usize,
) {
    if k == 0 {
        (s[0], c[0]) = a[0].sin_cos();
        return;
    }
    da[k] = k as f64 * a[k];
    // Σ_{j=1}^{k−1} j a[j] c[k − j] (and s), then j = k last (see `dot_rev`).
    let ds = dot_rev(&da[1..k], &c[1..k]);
    let dc = dot_rev(&da[1..k], &s[1..k]);
    let inv_k = 1.0 / k as f64;
    s[k] = (ds + da[k] * c[0]) * inv_k;
    c[k] = -(dc + da[k] * s[0]) * inv_k;
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The vector lanes and the scalar fallback agree bit for bit, at every length a kernel uses.
    #[test]
    fn dot_rev_is_the_same_on_every_target() {
        let x: Vec<f64> = (0..40)
            .map(|i| (f64::from(i) * 0.7).sin() * 1e3_f64.powi(i % 5))
            .collect();
        let y: Vec<f64> = (0..40)
            .map(|i| (f64::from(i) * 1.3).cos() / (1.0 + f64::from(i)))
            .collect();
        for n in 0..40 {
            let (a, b) = (dot_rev(&x[..n], &y[..n]), dot_rev_scalar(&x[..n], &y[..n]));
            assert_eq!(a.to_bits(), b.to_bits(), "length {n}: {a:e} vs {b:e}");
            let plain: f64 = x[..n]
                .iter()
                .zip(y[..n].iter().rev())
                .map(|(p, q)| p * q)
                .sum();
            assert!(
                (a - plain).abs()
                    <= 1e-13
                        * x[..n]
                            .iter()
                            .zip(y[..n].iter().rev())
                            .map(|(p, q)| (p * q).abs())
                            .sum::<f64>()
            );
        }
    }
}
