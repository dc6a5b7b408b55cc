//! The rocking phase's M(q) q'' = F solved at run time (the generated M and F, an L D Lᵀ
//! factorisation here; `rocking::rhs`) against the generated symbolic solve (`rocking_rhs`),
//! on every variant of every model at random states about both corners: the state rates, and
//! the Taylor series of a step (one factorisation of M₀ and the recursion
//! M₀ q''ₖ = Fₖ − Σⱼ Mⱼ q''ₖ₋ⱼ against the series of the symbolic solve). The two are the same
//! equations solved in another order, so they agree to rounding amplified by M's condition
//! number κ: the bound is 1e-15 κ of each block's size (κ at least 100; κ ≤ 290 for the
//! cantilever bases up to eight modes, so at most 3e-13 there, 1.5e5 for the ill-conditioned
//! monomials of `polynomial3`), while a missing product or a wrong order changes the rates by
//! their own size.

use rocking::rhs::{rocking_rate, rocking_series, Solve};
use rocking::{DampingConvention, Dimensionless, Structure, TaylorVariant};
use rocking_kernels::{with_variant, Array};

/// Coefficients of the compared series (a Taylor step at the `default` preset runs 12–16).
const N: usize = 16;

/// A small deterministic generator of numbers in [−1, 1).
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((self.0 >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
    }
}

/// The largest difference of `a` and `b` over rows `rows`, relative to the largest |a| there.
fn block_error(a: &[f64], b: &[f64], rows: std::ops::Range<usize>) -> f64 {
    let size = rows.clone().map(|i| a[i].abs()).fold(0.0, f64::max);
    let diff = rows.map(|i| (a[i] - b[i]).abs()).fold(0.0, f64::max);
    if size == 0.0 {
        diff
    } else {
        diff / size
    }
}

/// The difference of two series of a step's state, as the step would see it: Σₖ |aₖ − bₖ| hᵏ
/// of each row over the largest Σₖ |aₖ| hᵏ of its block (q or q'), at the step h on which the
/// last coefficient of `a` adds 1e-16 of the state's size (the Taylor integrator's step at a
/// tolerance of 1e-16). A single coefficient's difference is not the measure: where a
/// coefficient cancels to nearly nothing, its rounding is large against itself and does not
/// matter to the step.
fn series_error<const N: usize>(a: &[[f64; N]], b: &[[f64; N]]) -> f64 {
    let nq = a.len() / 2;
    let size = a.iter().map(|r| r[0].abs()).fold(0.0, f64::max);
    let last = a.iter().map(|r| r[N - 1].abs()).fold(0.0, f64::max);
    let h = (1e-16 * size / last).powf(1.0 / (N - 1) as f64);
    let poly =
        |c: &dyn Fn(usize) -> f64| (0..N).map(|k| c(k).abs() * h.powi(k as i32)).sum::<f64>();
    [0..nq, nq..2 * nq]
        .into_iter()
        .map(|rows| {
            let block = rows.clone().map(|i| poly(&|k| a[i][k])).fold(0.0, f64::max);
            let diff = rows
                .map(|i| poly(&|k| a[i][k] - b[i][k]))
                .fold(0.0, f64::max);
            diff / block
        })
        .fold(0.0, f64::max)
}

/// The worst errors of the rates ([`block_error`] of the accelerations) and of the series
/// ([`series_error`]) of variant `V` with parameters `p`, at 100 random states about each
/// corner (u ≡ u' ≡ 0 for a rigid variant, whose kernels never read u).
fn compare<V: TaylorVariant>(
    p: &V::Params,
    alpha: f64,
    rigid: bool,
    rng: &mut Rng,
) -> (f64, f64, f64) {
    let nq = V::Q::LEN;
    let (mut rate, mut series, mut kappa) = (0.0f64, 0.0f64, 0.0f64);
    for _ in 0..100 {
        // θ within the overturning range, u_i of a thousandth of the height falling with the
        // mode number, velocities of the same sizes per unit time.
        let x = V::X::from_fn(|i| {
            let j = i % nq;
            let size = match j {
                0 => alpha,
                _ if rigid => 0.0,
                _ => 1e-3 / (j * j) as f64,
            };
            size * rng.next()
        });
        let ug = rng.next();
        for s in [1.0, -1.0] {
            kappa = kappa.max(conditioning::<V>(&x, s, p));
            let a = rocking_rate::<V>(&x, ug, s, p, Solve::Symbolic);
            let b = rocking_rate::<V>(&x, ug, s, p, Solve::RunTime);
            rate = rate.max(block_error(a.values(), b.values(), nq..2 * nq));
            assert_eq!(
                &a.values()[..nq],
                &b.values()[..nq],
                "{}: q' is x's",
                V::NAME
            );

            let mut ug_series = [0.0; N];
            ug_series[0] = ug;
            ug_series[1] = 0.5 * rng.next();
            ug_series[2] = 0.1 * rng.next();
            let mut ya = vec![[0.0; N]; 2 * nq];
            for (yi, xi) in ya.iter_mut().zip(x.values()) {
                yi[0] = *xi;
            }
            let mut yb = ya.clone();
            rocking_series::<V, N>(&mut ya, &ug_series, s, p, Solve::Symbolic);
            rocking_series::<V, N>(&mut yb, &ug_series, s, p, Solve::RunTime);
            series = series.max(series_error(&ya, &yb));
        }
    }
    (rate, series, kappa)
}

/// The condition number of M(q) at the state `x` about `s` (its eigenvalues' ratio).
fn conditioning<V: TaylorVariant>(x: &V::X, s: f64, p: &V::Params) -> f64 {
    let n = V::Q::LEN;
    let q = V::Q::from_fn(|i| x.values()[i]);
    let upper = V::mass_matrix(&q, s, p);
    let mut m = nalgebra::DMatrix::zeros(n, n);
    let mut e = 0;
    for i in 0..n {
        for j in i..n {
            m[(i, j)] = upper.values()[e];
            m[(j, i)] = upper.values()[e];
            e += 1;
        }
    }
    let eig = m.symmetric_eigenvalues();
    eig.max() / eig.min()
}

#[test]
fn the_run_time_solve_is_the_symbolic_one_on_every_variant() {
    let mut rng = Rng(0x5eed_0045);
    for model in rocking_kernels::kernels::MODELS {
        let d = Dimensionless {
            omega_n_over_p: 8.0,
            alpha: 0.2,
            gamma_mc: 0.5,
            gamma_mb: 0.5,
            gamma_ib: 1.0,
            zeta: 0.05,
            damping: DampingConvention::FixedBase,
        };
        let s = Structure::dimensionless_of_model(model, &d, &[], None).unwrap();
        for name in model.variants {
            let (rate, series, kappa) = with_variant!(*name, V, L => {
                let rigid = rocking_kernels::VariantInfo::find(name).unwrap().rigid;
                compare::<V>(&s.params::<V>(), 0.2, rigid, &mut rng)
            })
            .unwrap();
            eprintln!(
                "{:<20} {name:<22} κ(M) ≤ {kappa:.1e}: rates {rate:.1e} apart, series {series:.1e}",
                model.name
            );
            let bound = 1e-15 * kappa.max(100.0);
            assert!(rate <= bound, "{name}: rates {rate:e} apart (κ {kappa:e})");
            assert!(
                series <= bound,
                "{name}: series {series:e} apart (κ {kappa:e})"
            );
        }
    }
}
