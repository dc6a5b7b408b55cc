//! The rocking phase's M(q) q'' = F solved symbolically (the generated `rocking_rhs`) against
//! at run time (`rocking::rhs`), per call, for the cantilever bases of n = 1 … 8 modes: the
//! state rate a Runge–Kutta stage takes, and a Taylor step's series of 16 coefficients.
//! `cargo bench -p rocking --bench solve`; the crossover it finds is `rocking::rhs`'s and is
//! written in docs/performance.md.

use std::hint::black_box;

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use rocking::rhs::{rocking_rate, rocking_series, Solve};
use rocking::{DampingConvention, Dimensionless, Structure, TaylorVariant};
use rocking_kernels::{with_variant, Array, ModelInfo};

/// Coefficients of the Taylor series (a step at the `default` preset runs 12–16).
const N: usize = 16;

/// A rocking state of a few tenths of the slenderness and small deformations.
fn state<V: TaylorVariant>() -> V::X {
    let nq = V::Q::LEN;
    V::X::from_fn(|i| {
        let j = i % nq;
        let sign = if i % 3 == 0 { -1.0 } else { 1.0 };
        sign * if j == 0 { 0.05 } else { 1e-3 / (j * j) as f64 }
    })
}

fn per_model<V: TaylorVariant>(c: &mut Criterion, n: usize, s: &Structure) {
    let p = s.params::<V>();
    let x = state::<V>();
    let mut g = c.benchmark_group("rate");
    for how in [Solve::Symbolic, Solve::RunTime] {
        g.bench_with_input(BenchmarkId::new(format!("{how:?}"), n), &x, |b, x| {
            b.iter(|| rocking_rate::<V>(black_box(x), 0.3, 1.0, &p, how))
        });
    }
    g.finish();
    let mut g = c.benchmark_group("taylor16");
    let mut ug = [0.0; N];
    ug[..3].copy_from_slice(&[0.3, 0.1, -0.02]);
    for how in [Solve::Symbolic, Solve::RunTime] {
        g.bench_with_input(BenchmarkId::new(format!("{how:?}"), n), &x, |b, x| {
            b.iter(|| {
                // On the stack, as a step's state (18 rows: eight modes).
                let mut rows = [[0.0; N]; 18];
                let y = &mut rows[..x.values().len()];
                for (yi, xi) in y.iter_mut().zip(black_box(x).values()) {
                    yi[0] = *xi;
                }
                rocking_series::<V, N>(y, &ug, 1.0, &p, how);
                y[0][N - 1]
            })
        });
    }
    g.finish();
}

fn solve(c: &mut Criterion) {
    let d = Dimensionless {
        omega_n_over_p: 8.0,
        alpha: 0.2,
        gamma_mc: 0.5,
        gamma_mb: 0.5,
        gamma_ib: 1.0,
        zeta: 0.05,
        damping: DampingConvention::FixedBase,
    };
    for n in 1..=8 {
        let name = format!("cantilever_modes{n}");
        let model = ModelInfo::find(&name).expect("the cantilever bases are generated");
        let s = Structure::dimensionless_of_model(model, &d, &[], None).unwrap();
        with_variant!(model.full, V, L => per_model::<V>(c, n, &s)).unwrap();
    }
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(20).warm_up_time(std::time::Duration::from_millis(300)).measurement_time(std::time::Duration::from_secs(1));
    targets = solve
}
criterion_main!(benches);
