//! Kernel microbenchmarks: the cost of one right-hand side (and of the section forces) per variant.
//!
//! `cargo bench -p rocking-kernels --bench kernels`; numbers are in docs/performance.md.

use std::hint::black_box;

use criterion::{criterion_group, criterion_main, Criterion};
use rocking_kernels::kernels::{
    AddedMass, CosineShape, Full, MasslessBase, MasslessColumn, PointMass, Rigid, SmallAngle,
};
use rocking_kernels::{best_isa, isa, OneCoordinate, Physical, Variant};

fn bench_variant<V: OneCoordinate>(c: &mut Criterion) {
    let p = V::params(&Physical::dimensionless(0.1, 5.0, 2.0, 2.0, 1.0, 0.01));
    let x = [0.05, 1e-3, -0.02, 3e-3];
    let mut group = c.benchmark_group(V::NAME);
    group.bench_function("mass_matrix+forcing", |b| {
        b.iter(|| {
            let m = V::mass_matrix(black_box(&[x[0], x[1]]), black_box(1.0), black_box(&p));
            let f = V::forcing(black_box(&x), black_box(0.3), black_box(1.0), black_box(&p));
            (m, f)
        })
    });
    group.bench_function("rocking_rhs", |b| {
        b.iter(|| V::rocking_rhs(black_box(&x), black_box(0.3), black_box(1.0), black_box(&p)))
    });
    group.bench_function("contact_rhs+uplift", |b| {
        b.iter(|| {
            let xc = black_box([x[1], x[3]]);
            let d = V::contact_rhs(&xc, black_box(0.3), black_box(&p));
            let f = V::uplift(&xc, black_box(0.3), black_box(1.0), black_box(&p));
            (d, f)
        })
    });
    // Section forces and ground reaction: each computes its phase's accelerations again.
    group.bench_function("forces_rocking", |b| {
        b.iter(|| V::forces_rocking(black_box(&x), black_box(0.3), black_box(1.0), black_box(&p)))
    });
    group.bench_function("forces_contact", |b| {
        b.iter(|| V::forces_contact(black_box(&[x[1], x[3]]), black_box(0.3), black_box(&p)))
    });
    group.finish();
}

/// One Taylor step's coefficients (the rocking state to order N − 1): what a Taylor step costs,
/// with a ground motion and after it (the `_free` twins).
fn bench_taylor<const N: usize>(c: &mut Criterion) {
    use rocking_kernels::taylor::{full, point_mass};
    let phys = Physical::dimensionless(0.1, 5.0, 2.0, 2.0, 1.0, 0.01);
    let x0 = [0.05, 1e-3, -0.02, 3e-3];
    let mut ug = [0.0; N];
    ug[0] = 0.3;
    ug[1] = -0.1;
    let start = || -> [[f64; N]; 4] {
        let mut x = [[0.0; N]; 4];
        for (xi, v) in x.iter_mut().zip(x0) {
            xi[0] = v;
        }
        x
    };
    let mut group = c.benchmark_group(format!("taylor_rocking_rhs_N{N}"));
    let p = Full::params(&phys);
    group.bench_function(Full::NAME, |b| {
        b.iter(|| {
            let mut x = black_box(start());
            full::rocking_rhs(&mut x, black_box(&ug), black_box(1.0), black_box(&p));
            x
        })
    });
    group.bench_function(format!("{}_free", Full::NAME), |b| {
        b.iter(|| {
            let mut x = black_box(start());
            full::rocking_rhs_free(&mut x, black_box(1.0), black_box(&p));
            x
        })
    });
    let p = PointMass::params(&phys);
    group.bench_function(PointMass::NAME, |b| {
        b.iter(|| {
            let mut x = black_box(start());
            point_mass::rocking_rhs(&mut x, black_box(&ug), black_box(1.0), black_box(&p));
            x
        })
    });
    group.bench_function(format!("{}_free", PointMass::NAME), |b| {
        b.iter(|| {
            let mut x = black_box(start());
            point_mass::rocking_rhs_free(&mut x, black_box(1.0), black_box(&p));
            x
        })
    });
    // The solver runs the kernels through `best_isa!` (AVX2 where the CPU has it, same bits).
    group.bench_function(format!("{}_free/{}", PointMass::NAME, isa::best()), |b| {
        b.iter(|| {
            let mut x = black_box(start());
            best_isa!(point_mass::rocking_rhs_free(
                &mut x,
                black_box(1.0),
                black_box(&p)
            ));
            x
        })
    });
    group.finish();
}

fn kernels(c: &mut Criterion) {
    bench_variant::<Full>(c);
    bench_variant::<MasslessColumn>(c);
    bench_variant::<MasslessBase>(c);
    bench_variant::<PointMass>(c);
    bench_variant::<Rigid>(c);
    bench_variant::<SmallAngle>(c);
    bench_variant::<CosineShape>(c);
    bench_variant::<AddedMass>(c);
    bench_taylor::<13>(c);
    bench_taylor::<17>(c);
    bench_taylor::<21>(c);
}

criterion_group! {
    name = benches;
    config = Criterion::default().warm_up_time(std::time::Duration::from_millis(300)).measurement_time(std::time::Duration::from_secs(1));
    targets = kernels
}
criterion_main!(benches);
