//! CPU time: of a simulation (the median of repeated runs) and of one kernel call.

use std::hint::black_box;

use rocking::Structure;
use rocking_kernels::{with_variant, OneCoordinate};

/// Process CPU time in seconds.
pub fn cpu_time() -> f64 {
    let mut ts = libc::timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    // SAFETY: clock_gettime writes into the timespec we own.
    unsafe { libc::clock_gettime(libc::CLOCK_PROCESS_CPUTIME_ID, &mut ts) };
    ts.tv_sec as f64 + 1e-9 * ts.tv_nsec as f64
}

/// Median CPU seconds of `f` (repeated until `min_total` seconds, at least 3 times, except that
/// one run of more than `5 min_total` is timed once: the chatter case's 1.7 s runs, whose
/// timing noise is small against their length), and the number of repeats.
pub(super) fn time_median(mut f: impl FnMut(), min_total: f64) -> (f64, usize) {
    let mut samples: Vec<f64> = Vec::new();
    let start = cpu_time();
    let long = |s: &[f64]| s.len() == 1 && s[0] > 5.0 * min_total;
    while (samples.len() < 3 && !long(&samples))
        || (cpu_time() - start < min_total && samples.len() < 100_000)
    {
        let t0 = cpu_time();
        f();
        samples.push(cpu_time() - t0);
    }
    samples.sort_by(|a, b| a.partial_cmp(b).unwrap());
    (samples[samples.len() / 2], samples.len())
}

/// ns per call of the rocking and contact right-hand sides of a variant (direct microtiming).
fn kernel_ns<V: OneCoordinate>(s: &Structure) -> (f64, f64) {
    let p = s.params::<V>();
    let n = 2_000_000;
    let mut x = [0.05, 1e-3, -0.02, 3e-3];
    let best = |f: &mut dyn FnMut()| {
        (0..5)
            .map(|_| {
                let t0 = cpu_time();
                f();
                (cpu_time() - t0) * 1e9 / n as f64
            })
            .fold(f64::INFINITY, f64::min)
    };
    let rock = best(&mut || {
        for k in 0..n {
            let d = V::rocking_rhs(
                black_box(&x),
                black_box(0.3 + 1e-9 * k as f64),
                black_box(1.0),
                black_box(&p),
            );
            x[0] = black_box(x[0]) + 0.0 * d[2];
        }
    });
    let cont = best(&mut || {
        for k in 0..n {
            let xc = black_box([x[1], x[3]]);
            let d = V::contact_rhs(&xc, black_box(0.3 + 1e-9 * k as f64), black_box(&p));
            x[1] = black_box(x[1]) + 0.0 * d[1];
        }
    });
    (rock, cont)
}

/// ns per call of the kernels of the variant called `name` (through the generated dispatch).
pub(super) fn variant_ns(name: &str, s: &Structure) -> (f64, f64) {
    with_variant!(name, V => kernel_ns::<V>(s)).expect("a generated variant")
}

/// The parameter vector of the variant called `name` for the structure `s`.
pub(super) fn params_of(name: &str, s: &Structure) -> Vec<f64> {
    with_variant!(name, V => s.params::<V>().as_ref().to_vec()).expect("a generated variant")
}
