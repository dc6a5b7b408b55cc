//! The rocking phase's equations of motion M(q) q'' = F(q, q', ü_g), solved two ways: by the
//! generated `rocking_rhs` (an L D Lᵀ written out symbolically and simplified with M's and F's
//! own terms) or at run time (the generated M and F, factored here). Both give the same state
//! rate to rounding (tests/tests/runtime_solve.rs). Which is cheaper was measured by
//! `cargo bench -p rocking --bench solve` (docs/performance.md, "The symbolic solve against the
//! run-time one"): the symbolic one, for every basis generated (n ≤ 8), by 1.5–2.3× per rate
//! and 1.8–2.0× per Taylor series, so the driver runs `rocking_rhs`. A model of more
//! coordinates can run this module's instead once the bench says it is the cheaper.

use rocking_kernels::{Array, Variant};

use crate::layout::Rocking;
use crate::spd;
use crate::taylor::TaylorVariant;

/// How the rocking phase's M(q) q'' = F is solved.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Solve {
    /// The generated `rocking_rhs` (and its Taylor twin).
    Symbolic,
    /// The generated M(q) and F, and an L D Lᵀ factorisation at run time (along a Taylor step,
    /// one factorisation of M's leading coefficient per step).
    RunTime,
}

/// The rate `[θ', u', θ'', u'']` of the rocking state `x` about corner `s` under the ground
/// acceleration `ug`, solved as `how` says.
#[must_use]
pub fn rocking_rate<V: Variant>(x: &V::X, ug: f64, s: f64, p: &V::Params, how: Solve) -> V::X {
    match how {
        Solve::Symbolic => V::rocking_rhs(x, ug, s, p),
        Solve::RunTime => {
            let xv = x.values();
            let q = V::Q::from_fn(|i| xv[i]);
            let m = V::mass_matrix(&q, s, p);
            let mut qdd = V::forcing(x, ug, s, p);
            spd::solve_upper(m.values(), qdd.values_mut());
            let first = Rocking::<V>::THETA_DOT;
            V::X::from_fn(|i| {
                if i < first {
                    xv[first + i]
                } else {
                    qdd.values()[i - first]
                }
            })
        }
    }
}

/// The Taylor coefficients of the rocking state from `x[i][0]`, solved as `how` says (see
/// [`TaylorVariant::rocking_series`]).
pub fn rocking_series<V: TaylorVariant, const N: usize>(
    x: &mut [[f64; N]],
    ug: &[f64; N],
    s: f64,
    p: &V::Params,
    how: Solve,
) {
    match how {
        Solve::Symbolic => V::rocking_series(x, ug, s, p),
        Solve::RunTime => V::rocking_series_solved(x, ug, s, p),
    }
}
