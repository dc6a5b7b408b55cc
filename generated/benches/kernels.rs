//! Kernel microbenchmarks: the cost of one right-hand side per variant.
//!
//! `cargo bench -p rocking-kernels --bench kernels`; numbers are in docs/performance.md.

use std::hint::black_box;

use criterion::{criterion_group, criterion_main, Criterion};
use rocking_kernels::kernels::{
    AddedMass, CosineShape, Full, MasslessBase, MasslessColumn, PointMass, Rigid, SmallAngle,
};
use rocking_kernels::{Physical, Variant};

fn bench_variant<V: Variant>(c: &mut Criterion) {
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
}

criterion_group! {
    name = benches;
    config = Criterion::default().warm_up_time(std::time::Duration::from_millis(300)).measurement_time(std::time::Duration::from_secs(1));
    targets = kernels
}
criterion_main!(benches);
