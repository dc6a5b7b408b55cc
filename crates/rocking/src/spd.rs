//! A small dense symmetric positive definite solve at run time: A x = b by A = L D Lᵀ, from the
//! upper triangle of A stored row by row (the generated mass matrices' layout), on the stack.
//!
//! The kernels emit M(q) and F; solving here instead of symbolically keeps the generated code's
//! size linear in the number of outputs for the free-base equations (n + 2 unknowns, up to 10 for
//! eight modes). No pivoting: a mass matrix needs none. Reusable by any M q'' = F of the kernels,
//! and along Taylor series ([`second_order_series`]: one factorisation per series).

/// The largest system [`solve_upper`] takes.
pub(crate) const MAX: usize = 16;

/// Solves A x = b in place (`b` becomes x) for the n × n symmetric positive definite A whose
/// upper triangle is `upper`, row by row (n = `b.len()`, `upper.len()` = n (n + 1) / 2).
///
/// Returns the smallest pivot of D over the largest diagonal entry of A (≤ 0 or NaN: A is not
/// positive definite there, and x is not meaningful).
pub(crate) fn solve_upper(upper: &[f64], b: &mut [f64]) -> f64 {
    let ldl = Ldl::factor(upper, b.len());
    ldl.solve(b);
    ldl.pivot()
}

/// Row-major index of entry (i, j) of the upper triangle of an n × n symmetric matrix.
fn upper_index(n: usize, i: usize, j: usize) -> usize {
    let (i, j) = if i <= j { (i, j) } else { (j, i) };
    // Row i of the upper triangle starts at i n − i (i − 1) / 2.
    i * n - i * i.saturating_sub(1) / 2 + (j - i)
}

/// A = L D Lᵀ of a symmetric positive definite A (unit lower L), for several right-hand sides.
pub(crate) struct Ldl {
    n: usize,
    low: [[f64; MAX]; MAX],
    d: [f64; MAX],
    /// The smallest pivot of D over the largest diagonal entry of A.
    pivot: f64,
}

impl Ldl {
    /// Factors the n × n A of upper triangle `upper` (row by row).
    pub(crate) fn factor(upper: &[f64], n: usize) -> Self {
        assert!(
            n <= MAX && upper.len() == n * (n + 1) / 2,
            "Ldl::factor: {n} unknowns"
        );
        let at = |i: usize, j: usize| upper[upper_index(n, i, j)];
        let mut low = [[0.0f64; MAX]; MAX];
        let mut d = [0.0f64; MAX];
        let mut largest = 0.0f64;
        for j in 0..n {
            largest = largest.max(at(j, j).abs());
            let mut dj = at(j, j);
            for k in 0..j {
                dj -= low[j][k] * low[j][k] * d[k];
            }
            d[j] = dj;
            for i in j + 1..n {
                let mut v = at(i, j);
                for k in 0..j {
                    v -= low[i][k] * low[j][k] * d[k];
                }
                low[i][j] = v / dj;
            }
        }
        let pivot = d[..n].iter().copied().fold(f64::INFINITY, f64::min) / largest;
        Self { n, low, d, pivot }
    }

    /// Solves A x = b in place (`b` of length n becomes x).
    pub(crate) fn solve(&self, b: &mut [f64]) {
        let (n, low, d) = (self.n, &self.low, &self.d);
        for i in 0..n {
            for k in 0..i {
                b[i] -= low[i][k] * b[k];
            }
        }
        for i in (0..n).rev() {
            b[i] /= d[i];
            for k in i + 1..n {
                b[i] -= low[k][i] * b[k];
            }
        }
    }

    /// The smallest pivot of D over the largest diagonal entry of A (≤ 0 or NaN: A is not
    /// positive definite).
    pub(crate) fn pivot(&self) -> f64 {
        self.pivot
    }
}

/// Taylor coefficients of the solution of M(q) q'' = F(q, q', t), state `y = [q, q']` (2n rows,
/// n = `acc.len()`), from `y[i][0]`: `order(k, y, m_k, f_k)` writes the k-th coefficients of
/// M's upper triangle (row by row) and of F from y's coefficients up to k (the generated
/// kernels of `Mode::Orders`, one call per order in turn). Then
/// M_0 q''_k = F_k − Σ_{j=1..k} M_j q''_{k−j} (the Cauchy product of M q'' = F), with one
/// factorisation of M_0 per series, and `y_{k+1} = [q'_k, q''_k] / (k + 1)`. `m`
/// (n (n + 1) / 2 rows) and `acc` (n rows, q''s coefficients) are work arrays.
pub(crate) fn second_order_series<const N: usize>(
    y: &mut [[f64; N]],
    m: &mut [[f64; N]],
    acc: &mut [[f64; N]],
    mut order: impl FnMut(usize, &[[f64; N]], &mut [f64], &mut [f64]),
) {
    let (n, nm) = (acc.len(), m.len());
    assert!(
        n <= MAX && nm == n * (n + 1) / 2 && y.len() == 2 * n,
        "second_order_series: {n} unknowns"
    );
    let mut mk = [0.0; MAX * (MAX + 1) / 2];
    let mut fk = [0.0; MAX];
    let mut ldl: Option<Ldl> = None;
    for k in 0..N - 1 {
        order(k, y, &mut mk[..nm], &mut fk[..n]);
        for (e, row) in m.iter_mut().enumerate() {
            row[k] = mk[e];
        }
        let f = &mut fk[..n];
        for j in 1..=k {
            for (i, fi) in f.iter_mut().enumerate() {
                for (l, al) in acc.iter().enumerate() {
                    *fi -= m[upper_index(n, i, l)][j] * al[k - j];
                }
            }
        }
        let ldl = ldl.get_or_insert_with(|| Ldl::factor(&mk[..nm], n));
        ldl.solve(f);
        let inv = 1.0 / (k + 1) as f64;
        for i in 0..n {
            acc[i][k] = f[i];
            y[i][k + 1] = y[n + i][k] * inv;
            y[n + i][k + 1] = f[i] * inv;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 4 × 4 SPD system with a known solution: the residual of A x = b is at rounding level.
    #[test]
    fn solves_a_symmetric_positive_definite_system() {
        let a = [
            [4.0, 1.0, 0.5, 0.2],
            [1.0, 3.0, 0.3, 0.1],
            [0.5, 0.3, 2.0, 0.4],
            [0.2, 0.1, 0.4, 1.5],
        ];
        let x = [1.0, -2.0, 0.5, 3.0];
        let mut b: Vec<f64> = (0..4)
            .map(|i| (0..4).map(|j| a[i][j] * x[j]).sum())
            .collect();
        let upper: Vec<f64> = (0..4).flat_map(|i| (i..4).map(move |j| a[i][j])).collect();
        let pivot = solve_upper(&upper, &mut b);
        assert!(pivot > 0.1, "{pivot}");
        for i in 0..4 {
            assert!((b[i] - x[i]).abs() < 1e-14, "{b:?}");
        }
        // Not positive definite: the pivot says so.
        let mut c = [1.0, 1.0];
        assert!(solve_upper(&[1.0, 2.0, 1.0], &mut c) <= 0.0);
    }
}
