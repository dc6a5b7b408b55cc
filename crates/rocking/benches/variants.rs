//! The speed of each kernel variant against the full model on the same scene: what simulating
//! only the effects a scene calls for saves. `cargo bench -p rocking --bench variants`;
//! numbers in docs/performance.md.

use std::hint::black_box;

use criterion::{criterion_group, criterion_main, Criterion};
use rocking::{simulate_variant, DampingConvention, Dimensionless, Options, Structure};
use rocking_kernels::kernels::{Full, MasslessBase, MasslessColumn, PointMass, Rigid, SmallAngle};
use rocking_motion::SinePulse;

fn structure(gamma_mc: f64, gamma_mb: f64, omega_n: f64) -> Structure {
    let d = Dimensionless {
        omega_n_over_p: omega_n,
        alpha: 0.2,
        gamma_mc,
        gamma_mb,
        gamma_ib: 1.0,
        zeta: 0.005,
        damping: DampingConvention::FixedBase,
    };
    Structure::from_dimensionless(&d, None).unwrap()
}

fn run<V: rocking::TaylorVariant>(s: &Structure, pulse: &SinePulse, o: &Options) -> f64 {
    simulate_variant::<V, _, 4, 2>(s, pulse, o)
        .unwrap()
        .summary
        .max_theta_over_alpha
}

fn variants(c: &mut Criterion) {
    // The paper's Fig. 3 pulse, 8 τ, default preset.
    let pulse = SinePulse::new(1.3 * 0.2f64.tan(), 5.1);
    let o = Options {
        t_end: 8.0,
        ..Options::default()
    };
    let mut g = c.benchmark_group("fig3 scene (m_c = m_b = 0)");
    let s = structure(0.0, 0.0, 11.9);
    g.bench_function("full", |b| {
        b.iter(|| run::<Full>(black_box(&s), &pulse, &o))
    });
    g.bench_function("massless_column", |b| {
        b.iter(|| run::<MasslessColumn>(black_box(&s), &pulse, &o))
    });
    g.bench_function("massless_base", |b| {
        b.iter(|| run::<MasslessBase>(black_box(&s), &pulse, &o))
    });
    g.bench_function("point_mass", |b| {
        b.iter(|| run::<PointMass>(black_box(&s), &pulse, &o))
    });
    g.finish();

    // With column and base mass the uplift threshold is about 2 g tan α: a stronger pulse.
    let pulse = SinePulse::new(3.0 * 0.2f64.tan(), 5.1);
    let mut g = c.benchmark_group("massive scene (γ_mc = γ_mb = 1)");
    let s = structure(1.0, 1.0, 11.9);
    g.bench_function("full", |b| {
        b.iter(|| run::<Full>(black_box(&s), &pulse, &o))
    });
    g.bench_function("small_angle", |b| {
        b.iter(|| run::<SmallAngle>(black_box(&s), &pulse, &o))
    });
    g.finish();

    // A rigid block: the one-degree-of-freedom kernel against the full model made nearly rigid.
    let mut g = c.benchmark_group("rigid scene (γ_mc = γ_mb = 1)");
    let rigid = structure(1.0, 1.0, 11.9);
    let stiff = structure(1.0, 1.0, 1000.0);
    g.bench_function("rigid", |b| {
        b.iter(|| run::<Rigid>(black_box(&rigid), &pulse, &o))
    });
    g.bench_function("full at omega_n/p = 1000", |b| {
        b.iter(|| run::<Full>(black_box(&stiff), &pulse, &o))
    });
    g.finish();
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(20).warm_up_time(std::time::Duration::from_millis(500)).measurement_time(std::time::Duration::from_secs(2));
    targets = variants
}
criterion_main!(benches);
