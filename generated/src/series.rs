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
    let [d] = dots([(a, b)], k);
    mul_d(d, a, b, k)
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
        dot_rev_sse2([(x, y)])[0]
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

/// [`dot_rev`] of M pairs of slices, all of one length, in SSE2 registers (part of every x86_64
/// CPU): one register per pair, its two lanes the terms of even and of odd j. [`dot_rev`] is one
/// pair; [`dots`] all the pairs of an order in one loop.
#[cfg(target_arch = "x86_64")]
#[inline(always)]
fn dot_rev_sse2<const M: usize>(pairs: [(&[f64], &[f64]); M]) -> [f64; M] {
    use core::arch::x86_64::{
        __m128d, _mm_add_pd, _mm_add_sd, _mm_cvtsd_f64, _mm_loadu_pd, _mm_mul_pd, _mm_setzero_pd,
        _mm_shuffle_pd, _mm_unpackhi_pd,
    };
    let n = pairs.first().map_or(0, |(x, _)| x.len());
    for (x, y) in &pairs {
        assert!(
            x.len() == n && y.len() == n,
            "dot_rev of slices of different lengths"
        );
    }
    let mut i = 0;
    // SAFETY: SSE2 is in the x86_64 baseline; each load reads two f64 at x[i..i + 2] or
    // y[n − 2 − i..n − i], inside the slices because i + 2 <= n.
    let mut out = unsafe {
        let mut acc: [__m128d; M] = [_mm_setzero_pd(); M];
        while i + 2 <= n {
            for (acc, (x, y)) in acc.iter_mut().zip(&pairs) {
                let a = _mm_loadu_pd(x.as_ptr().add(i));
                let b = _mm_loadu_pd(y.as_ptr().add(n - 2 - i));
                // [y[n − 2 − i], y[n − 1 − i]] swapped to pair with [x[i], x[i + 1]].
                *acc = _mm_add_pd(*acc, _mm_mul_pd(a, _mm_shuffle_pd::<1>(b, b)));
            }
            i += 2;
        }
        acc.map(|v| _mm_cvtsd_f64(_mm_add_sd(v, _mm_unpackhi_pd(v, v))))
    };
    if i < n {
        for (o, (x, y)) in out.iter_mut().zip(pairs) {
            *o += x[i] * y[0];
        }
    }
    out
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
    let [d] = dots([(b, c)], k);
    div_d(d, a_k, b, c, inv_b0, k)
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
    // Σ_{j=1}^{k−1} j a[j] c[k − j] (and s), then j = k last (see `dot_rev`).
    let [ds, dc] = dots([(&*da, &*c), (&*da, &*s)], k);
    sin_cos_d(ds, dc, a, da, s, c, k);
}

/// The sums `Σ_{j=1}^{k−1} a[j] b[k−j]` of M pairs at once: the part of each product,
/// quotient and sine recurrence of order k that reads only lower orders, so a kernel can sum all
/// of them before it computes any node of the order. One loop for all pairs (each with its own
/// lanes, summed exactly as [`dot_rev`] sums it, so the same bits) instead of one loop per pair.
#[inline(always)]
#[must_use]
pub fn dots<const N: usize, const M: usize>(
    pairs: [(&[f64; N], &[f64; N]); M],
    k: usize,
) -> [f64; M] {
    if k < 2 {
        return [0.0; M];
    }
    #[cfg(target_arch = "x86_64")]
    {
        dot_rev_sse2(pairs.map(|(a, b)| (&a[1..k], &b[1..k])))
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        pairs.map(|(a, b)| dot_rev_scalar(&a[1..k], &b[1..k]))
    }
}

/// [`mul`] with its sum over lower orders `d` already taken by [`dots`].
#[inline(always)]
#[must_use]
pub fn mul_d<const N: usize>(d: f64, a: &[f64; N], b: &[f64; N], k: usize) -> f64 {
    if k == 0 {
        return a[0] * b[0];
    }
    d + (a[0] * b[k] + a[k] * b[0])
}

/// [`div`] with its sum over lower orders `d` already taken by [`dots`] (pair `(b, c)`).
#[inline(always)]
#[must_use]
pub fn div_d<const N: usize>(
    d: f64,
    a_k: f64,
    b: &[f64; N],
    c: &[f64; N],
    inv_b0: f64,
    k: usize,
) -> f64 {
    if k == 0 {
        return a_k * inv_b0;
    }
    (a_k - b[k] * c[0] - d) * inv_b0
}

/// [`sin_cos`] with its two sums over lower orders, `ds` of `(da, c)` and `dc` of `(da, s)`,
/// already taken by [`dots`].
#[inline(always)]
pub fn sin_cos_d<const N: usize>(
    ds: f64,
    dc: f64,
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
    let inv_k = 1.0 / k as f64;
    s[k] = (ds + da[k] * c[0]) * inv_k;
    c[k] = -(dc + da[k] * s[0]) * inv_k;
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The fused sums of [`dots`] are each pair's [`dot_rev`] on scalars, bit for bit, at every
    /// order.
    #[test]
    fn dots_are_each_pairs_dot_rev() {
        const N: usize = 21;
        let series = |f: f64| -> [f64; N] {
            std::array::from_fn(|i| (f * (i as f64 + 0.5)).sin() * 10f64.powi(i as i32 % 7 - 3))
        };
        let (a, b, c) = (series(0.7), series(1.3), series(-2.1));
        for k in 0..N {
            let got = dots([(&a, &b), (&b, &c), (&c, &a), (&a, &a)], k);
            let want = [(&a, &b), (&b, &c), (&c, &a), (&a, &a)].map(|(x, y)| {
                if k == 0 {
                    0.0
                } else {
                    dot_rev_scalar(&x[1..k], &y[1..k])
                }
            });
            for (g, w) in got.iter().zip(want) {
                assert_eq!(g.to_bits(), w.to_bits(), "order {k}: {g:e} vs {w:e}");
            }
            if k >= 3 {
                let direct: f64 = (1..k).map(|j| a[j] * b[k - j]).sum();
                let scale: f64 = (1..k).map(|j| (a[j] * b[k - j]).abs()).sum();
                assert!((got[0] - direct).abs() <= 1e-15 * scale, "order {k}");
            }
        }
    }

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
