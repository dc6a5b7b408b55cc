//! The statics of a structure on compliant ground (issue 44, docs/ground.md), from the ground's
//! generated kernels alone ([`rocking_kernels::ground`]; nothing of the ground's physics is
//! written here): the settlement under the weight, the rotational stiffness before lift-off, the
//! first edge's lift-off, and the moment–rotation curve after it, by root searches on the
//! kernels' vertical resultant and corner depths.
//!
//! Sign conventions are the mechanics': θ > 0 turns the base clockwise, the right corner goes
//! down and the left one lifts first; the moment M = −Q_θ is the moment the ground resists with
//! (positive for θ > 0), v the settlement of the base centre (positive into the ground).

use rocking_kernels::ground::winkler_full as go;

use crate::ground::Ground;

/// One point of the ground's moment–rotation curve under a vertical load W at rest.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MomentPoint {
    /// The rotation θ.
    pub theta: f64,
    /// The settlement v of the base centre in vertical equilibrium (−Q_v = W) at θ.
    pub settlement: f64,
    /// The moment the ground resists with, −Q_θ.
    pub moment: f64,
    /// The contact length over 2B (two springs: the pressing corners over 2).
    pub contact_fraction: f64,
}

/// The statics of a compliant ground under a vertical load W: the typed result of [`statics`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Statics {
    /// The vertical load W on the base centre.
    pub weight: f64,
    /// The whole ground's vertical stiffness K_v (the statics kernel's ∂(−Q_v)/∂v).
    pub k_v: f64,
    /// The static settlement v0 = W / K_v.
    pub settlement: f64,
    /// The rotational stiffness dM/dθ at θ = 0 in full contact (the statics kernel: CasADi's
    /// derivative of the full-contact Q_θ, exact up to rounding).
    pub k_rot: f64,
    /// The first edge's lift-off: where the rising corner's depth at vertical equilibrium
    /// reaches 0 (a root search on the kernels).
    pub lift_off: MomentPoint,
    /// The mean pressure under W ([`Ground::mean_pressure`]).
    pub mean_pressure: f64,
}

/// The settlement v at which the base at rest with rotation `theta` is in vertical equilibrium
/// under `weight`, −Q_v(θ, v) = W, in the contact state the corners' depths give: bisection to
/// adjacent floats (−Q_v grows with v in every state). At θ = 0 it is the statics kernel's
/// v0 = W / K_v.
#[must_use]
pub fn equilibrium_settlement(ground: &Ground, weight: f64, theta: f64) -> f64 {
    let v0 = ground.statics(weight).settlement;
    if theta == 0.0 {
        return v0;
    }
    let rv = |v: f64| -ground.at(&[theta, v, 0.0, 0.0])[go::Q_V] - weight;
    let reach = ground.b * theta.sin().abs();
    let (mut lo, mut hi) = (-reach, v0 + reach);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if rv(mid) < 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    hi
}

/// The ground's moment at rest at rotation `theta` under `weight`, in vertical equilibrium.
#[must_use]
pub fn moment_at(ground: &Ground, weight: f64, theta: f64) -> MomentPoint {
    let v = equilibrium_settlement(ground, weight, theta);
    let g = ground.at(&[theta, v, 0.0, 0.0]);
    MomentPoint {
        theta,
        settlement: v,
        moment: -g[go::Q_THETA],
        contact_fraction: g[go::CONTACT_FRACTION],
    }
}

/// The first edge lift-off under `weight` for θ > 0: the rotation where the left corner's depth
/// at vertical equilibrium falls to 0, by bisection on θ in (0, π/2) to adjacent floats, and the
/// moment there.
#[must_use]
pub fn first_lift_off(ground: &Ground, weight: f64) -> MomentPoint {
    let left_depth = |theta: f64| {
        let v = equilibrium_settlement(ground, weight, theta);
        ground.depths(&[theta, v, 0.0, 0.0])[0]
    };
    let (mut lo, mut hi) = (0.0f64, std::f64::consts::FRAC_PI_2);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if left_depth(mid) > 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    // The last rotation in full contact: the moment of the full-contact state at lift-off.
    moment_at(ground, weight, lo)
}

/// The statics of `ground` under the vertical load `weight`.
#[must_use]
pub fn statics(ground: &Ground, weight: f64) -> Statics {
    let st = ground.statics(weight);
    Statics {
        weight,
        k_v: st.k_v,
        settlement: st.settlement,
        k_rot: st.k_rot,
        lift_off: first_lift_off(ground, weight),
        mean_pressure: ground.mean_pressure(weight),
    }
}

/// The moment–rotation curve under `weight` at the rotations `thetas` (before and after
/// lift-off alike).
#[must_use]
pub fn moment_rotation(ground: &Ground, weight: f64, thetas: &[f64]) -> Vec<MomentPoint> {
    thetas
        .iter()
        .map(|&t| moment_at(ground, weight, t))
        .collect()
}
