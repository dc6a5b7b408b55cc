//! A small dense symmetric positive definite solve at run time: A x = b by A = L D Lᵀ, from the
//! upper triangle of A stored row by row (the generated mass matrices' layout), on the stack.
//!
//! The kernels emit M(q) and F; solving here instead of symbolically keeps the generated code's
//! size linear in the number of outputs for the free-base equations (n + 2 unknowns, up to 10 for
//! eight modes). No pivoting: a mass matrix needs none. Reusable by any M q'' = F of the kernels.

/// The largest system [`solve_upper`] takes.
pub(crate) const MAX: usize = 16;

/// Solves A x = b in place (`b` becomes x) for the n × n symmetric positive definite A whose
/// upper triangle is `upper`, row by row (n = `b.len()`, `upper.len()` = n (n + 1) / 2).
///
/// Returns the smallest pivot of D over the largest diagonal entry of A (≤ 0 or NaN: A is not
/// positive definite there, and x is not meaningful).
pub(crate) fn solve_upper(upper: &[f64], b: &mut [f64]) -> f64 {
    let n = b.len();
    assert!(
        n <= MAX && upper.len() == n * (n + 1) / 2,
        "solve_upper: {n} unknowns"
    );
    // Row i of the upper triangle starts at i n − i (i − 1) / 2.
    let at = |i: usize, j: usize| {
        let (i, j) = if i <= j { (i, j) } else { (j, i) };
        upper[i * n - i * i.saturating_sub(1) / 2 + (j - i)]
    };
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
    d[..n].iter().copied().fold(f64::INFINITY, f64::min) / largest
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
