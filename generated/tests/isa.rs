//! The Taylor kernels the solver runs through `best_isa!` (the rocking right-hand sides, with and
//! without ground motion) give the same bits in the x86_64 baseline and in the instruction set it
//! picks (AVX2 where the CPU has it), for every variant: the solver's results do not depend on the
//! CPU it runs on.

use rocking_kernels::{best_isa, isa, kernels, taylor, Array, Physical};

mod common;
use common::Rng;

/// Compares `a` and `b` row by row, coefficient by coefficient, bit for bit.
fn assert_same<const N: usize>(what: &str, a: &[[f64; N]], b: &[[f64; N]]) -> usize {
    assert_eq!(a.len(), b.len(), "{what}");
    for (i, (ra, rb)) in a.iter().zip(b).enumerate() {
        for (k, (va, vb)) in ra.iter().zip(rb).enumerate() {
            assert!(
                va.to_bits() == vb.to_bits(),
                "{what}, N = {N}: row {i}, coefficient {k}: baseline {va:e}, {} {vb:e}",
                isa::best()
            );
        }
    }
    a.len() * N
}

/// Defines `compare_at::<N>()`: both rocking right-hand sides of every variant on random inputs,
/// both ways; returns the number of coefficients compared. Each variant's comparison is a
/// function of its own (module `$m`), kept out of line: one function holding every variant's
/// kernels inlined twice at N = 17 made rustc overflow its stack once the eight-mode bases came.
macro_rules! define_compare_at {
    ($($ty:ident => $m:ident : $nq:ident),* $(,)?) => {
    $(
    #[allow(non_snake_case)]
    mod $m {
        use super::*;

        #[inline(never)]
        pub fn compare<const N: usize>() -> usize {
            let mut compared = 0;
            use kernels::layout::$nq as l;
            type V = kernels::$ty;
            let mut rng = Rng(0x15a0_0001 ^ stringify!($m).len() as u64);
            for trial in 0..8 {
                let phys: Physical = common::structure(&mut rng);
                let p = common::params::<V>(&mut rng, &phys);
                let x0 = common::state::<V>(&mut rng, &phys);
                let s = if trial % 2 == 0 { 1.0 } else { -1.0 };
                let mut ug = [0.0; N];
                for c in ug.iter_mut().take(N.min(6)) {
                    *c = rng.range(-3.0, 3.0);
                }
                let mut x = [[0.0; N]; l::X];
                for (row, v) in x.iter_mut().zip(x0.values()) {
                    row[0] = *v;
                }
                let what = |k: &str| format!("{}::{k}", stringify!($m));

                let (mut a, mut b) = (x, x);
                taylor::$m::rocking_rhs::<N>(&mut a, &ug, s, &p);
                best_isa!(taylor::$m::rocking_rhs::<N>(&mut b, &ug, s, &p));
                compared += assert_same(&what("rocking_rhs"), &a, &b);
                let full = a;

                let (mut a, mut b) = (x, x);
                taylor::$m::rocking_rhs_free::<N>(&mut a, s, &p);
                best_isa!(taylor::$m::rocking_rhs_free::<N>(&mut b, s, &p));
                compared += assert_same(&what("rocking_rhs_free"), &a, &b);

                assert!(
                    full.iter().flatten().all(|v| v.is_finite()),
                    "{}: a non-finite coefficient (the inputs must be sound for the comparison \
                     to mean something)",
                    stringify!($m)
                );
            }
            compared
        }
    }
    )*

    fn compare_at<const N: usize>() -> usize {
        0 $(+ $m::compare::<N>())*
    }
    };
}

rocking_kernels::for_each_variant!(define_compare_at, layout);

#[test]
fn the_rocking_kernels_give_the_same_bits_in_every_instruction_set() {
    // Order 16 (N = order + 1), the order of the `accurate` preset: each N is compiled anew (a
    // minute of CI's build per N); the digests of the example outputs (.ci/digests.sh) cover the
    // other orders end to end.
    let compared = compare_at::<17>();
    eprintln!(
        "{compared} Taylor coefficients: baseline and {} agree bit for bit",
        isa::best()
    );
    if isa::best() == "baseline" {
        eprintln!("this CPU has no AVX2: both sides ran the baseline code");
    }
    assert!(compared > 2_000, "only {compared} coefficients compared");
}
