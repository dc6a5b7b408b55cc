//! Helpers shared by the test files of the generated kernels: a deterministic generator, random
//! structures and states, and a loop over every registered variant.

#![allow(dead_code, unused_macros)] // each test file uses its own subset

use rocking_kernels::{Array, ModelInfo, Physical, Role, Variant};

/// A small deterministic generator (xorshift64*), so the tests need no extra dependency.
pub struct Rng(pub u64);
impl Rng {
    pub fn next(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 11) as f64 / (1u64 << 53) as f64
    }
    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.next()
    }
}

/// A random structure over the whole range the project supports, in physical units.
pub fn structure(rng: &mut Rng) -> Physical {
    let alpha = rng.range(0.01, 0.5);
    let r = rng.range(1.0, 150.0);
    let mut phys = Physical::dimensionless(
        alpha,
        rng.range(1.0, 1000.0),
        rng.range(0.0, 3.0),
        rng.range(0.0, 3.0),
        rng.range(0.9, 1.2),
        rng.range(0.0, 0.2),
    );
    // Scale to R metres, m = 2e5 kg, g = 9.81: exercises units other than R = g = m = 1.
    let (mass, g) = (2.0e5, 9.81);
    phys.h *= r;
    phys.b *= r;
    phys.m *= mass;
    phys.m_c *= mass;
    phys.m_b *= mass;
    phys.i_bc *= mass * r * r;
    phys.ei *= mass * g * r * r; // k = EI/H^3 scales with m g / R
    phys.g = g;
    phys
}

/// A random state `[θ, u_1..u_n, θ', u_1'..u_n']`: θ up to ±1.5 rad, θ' up to ±3 sqrt(g/R), each
/// u_i up to ±0.3 H / n and u_i' up to ±3 sqrt(g/R) H / n (so that the column's top stays within
/// ±0.3 H for a basis with ψ_i(1) = 1).
pub fn state<V: Variant>(rng: &mut Rng, phys: &Physical) -> V::X {
    let n = V::NQ;
    let p = (phys.g / phys.h.hypot(phys.b)).sqrt();
    let share = phys.h / n as f64;
    // The draws, and for one coordinate their values, are those of the one-coordinate tests.
    let mut draw = |bound: f64, rate: f64| -> Vec<f64> {
        (0..n)
            .map(|_| {
                if V::RIGID {
                    0.0
                } else {
                    rng.range(-bound, bound) * rate * share
                }
            })
            .collect()
    };
    let (u, ud) = (draw(0.3, 1.0), draw(3.0, p));
    let (theta, theta_dot) = (rng.range(-1.5, 1.5), rng.range(-3.0, 3.0) * p);
    V::X::from_fn(|i| match i {
        0 => theta,
        i if i <= n => u[i - 1],
        i if i == n + 1 => theta_dot,
        i => ud[i - n - 2],
    })
}

/// The parameter vector of `V` for `phys`, with random values of the parameters its model adds
/// (a lumped mass 0.2 to 2 times the top mass, its height 0.05 to 1 H; others 0.5 to 1.5 times
/// their default) and the masses `V` removes set to zero, as its kernels take them.
pub fn params<V: Variant>(rng: &mut Rng, phys: &Physical) -> V::Params {
    let model = ModelInfo::find(V::MODEL).expect("the variant's model is registered");
    let extra: Vec<f64> = model
        .extra_params()
        .map(|q| match q.role {
            Role::Mass { .. } => phys.m * rng.range(0.2, 2.0),
            Role::HeightOf(_) => rng.range(0.05, 1.0),
            _ => q.default.unwrap_or(1.0) * rng.range(0.5, 1.5),
        })
        .collect();
    let mut p = V::params_with(phys, &extra);
    for name in V::REMOVED {
        let k = V::PARAM_NAMES.iter().position(|n| n == name).unwrap();
        p.as_mut()[k] = 0.0;
    }
    p
}

pub fn close(a: f64, b: f64, rel: f64, scale: f64) -> bool {
    (a - b).abs() <= rel * a.abs().max(b.abs()).max(scale)
}

/// Runs a check on every generated variant (the registry, so a new model is checked too):
/// `for_each_variant!(check)` on those of one deformation coordinate (`check::<V:
/// OneCoordinate>`, with fixed arrays), `for_each_variant!(check, any_coordinates)` on every
/// variant of every model (`check::<V: Variant>`, with the arrays of `V`'s layout).
macro_rules! for_each_variant {
    ($check:ident) => {
        for v in rocking_kernels::kernels::VARIANT_INFO {
            let model = rocking_kernels::ModelInfo::find(v.model).expect("registered model");
            if model.coordinates == 1 {
                rocking_kernels::with_variant!(v.name, V => $check::<V>())
                    .expect("every variant of one coordinate dispatches");
            }
        }
    };
    ($check:ident, any_coordinates) => {
        for v in rocking_kernels::kernels::VARIANT_INFO {
            rocking_kernels::with_variant!(v.name, V, _L => $check::<V>())
                .expect("every variant dispatches");
        }
    };
}
