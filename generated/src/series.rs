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

/// `Σ_j x[j] y[n − 1 − j]`, summed in order of j. On slices, not index ranges: the loop then has
/// no bounds checks and inlines (a `RangeInclusive` fold did not, and took a quarter of a
/// Taylor step).
///
/// Why the recurrences below sum the terms of orders `1..k` first: the kernels compute order k of
/// every tape node in turn, so only the terms with a coefficient of order k (`a[k] b[0]`,
/// `a[0] b[k]`) wait for this order's earlier nodes. Summed last, they leave the long sum of older
/// terms off the dependency chain from node to node, and the CPU overlaps the sums of the whole
/// tape (summed first, the tape ran one add latency per term).
#[inline(always)]
fn dot_rev(x: &[f64], y: &[f64]) -> f64 {
    x.iter().zip(y.iter().rev()).map(|(a, b)| a * b).sum()
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

/// Coefficient `k` of `c = a / b`, given `a[k]` and `c[0..k]`: `b c = a`.
#[inline(always)]
#[must_use]
pub fn div<const N: usize>(a_k: f64, b: &[f64; N], c: &[f64; N], k: usize) -> f64 {
    if k == 0 {
        return a_k / b[0];
    }
    let old: f64 = dot_rev(&b[1..k], &c[1..k]);
    (a_k - b[k] * c[0] - old) / b[0]
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
/// `c' = −s a'`.
#[inline(always)]
pub fn sin_cos<const N: usize>(a: &[f64; N], s: &mut [f64; N], c: &mut [f64; N], k: usize) {
    if k == 0 {
        (s[0], c[0]) = a[0].sin_cos();
        return;
    }
    let (mut ds, mut dc) = (0.0, 0.0);
    // j = 1..k with c[k − j] and s[k − j], on slices (see `dot_rev`); j = k last.
    let pairs = c[1..k].iter().rev().zip(s[1..k].iter().rev());
    for (j, (aj, (ckj, skj))) in (1..).zip(a[1..k].iter().zip(pairs)) {
        let ja = f64::from(j) * aj;
        ds += ja * ckj;
        dc += ja * skj;
    }
    let ka = k as f64 * a[k];
    let inv_k = 1.0 / k as f64;
    s[k] = (ds + ka * c[0]) * inv_k;
    c[k] = -(dc + ka * s[0]) * inv_k;
}
