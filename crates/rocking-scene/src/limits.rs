//! Bounds on scene values beyond their physical ranges: magnitudes whose products would
//! overflow, and derived quantities that must be finite. Kept apart from model.rs so that the
//! checks are listed in one place; each error names the key the user wrote and its range.

use rocking::{Derived, Structure};

use crate::scene::{Source, StructureSpec};
use crate::SceneError;

/// A number for a message: as written for ordinary magnitudes, in short exponent form (`1e308`,
/// not 309 digits) for very large or very small ones.
pub use rocking_motion::short_number as short;

/// Largest |value| of a dimensional structure key (SI): far beyond any structure, far below
/// the f64 overflow of the products formed from them (EI/H³, m g R, ...).
pub const MAX_MAGNITUDE: f64 = 1e20;

/// Largest ω_n/p: a column this stiff is rigid for every purpose (the rigid variant uses 1000).
pub const MAX_OMEGA_N_OVER_P: f64 = 1e6;

/// Largest mass ratio γ.
pub const MAX_GAMMA: f64 = 1e6;

/// Largest slenderness: B/H ≤ 1000, as the structure requires (α < atan(1000) ≈ 1.5698 rad).
pub fn max_alpha() -> f64 {
    1000f64.atan()
}

/// Largest ground acceleration amplitude, in g: no excitation comes near it.
pub const MAX_ACCEL_G: f64 = 1e4;

/// Largest excitation frequency ω_p/p: its period is then 6e-6 of the structure's time scale.
pub const MAX_OMEGA_P_OVER_P: f64 = 1e6;

/// Magnitudes of the `[structure]` keys the user wrote, checked before anything is formed from
/// them (so that `h = 1e308` is reported as `h`, not as an overflowed product).
pub fn structure_magnitudes(src: &Source, s: &StructureSpec) -> Result<(), SceneError> {
    let dimensional = [
        ("h", s.h),
        ("b", s.b),
        ("ei", s.ei),
        ("m", s.m),
        ("m_c", s.m_c),
        ("m_b", s.m_b),
        ("i_bc", s.i_bc),
        ("g", s.g),
        ("r", s.r),
        ("p", s.p),
    ];
    for (k, v) in dimensional {
        if let Some(v) = v.filter(|v| v.is_finite() && *v != 0.0) {
            if !(v.abs() <= MAX_MAGNITUDE && v.abs() >= 1.0 / MAX_MAGNITUDE) {
                return Err(src.not_allowed(
                    &format!("structure.{k}"),
                    v,
                    &format!(
                        "|{k}| between {} and {} (or 0 where allowed)",
                        short(1.0 / MAX_MAGNITUDE),
                        short(MAX_MAGNITUDE)
                    ),
                ));
            }
        }
    }
    if let Some(w) = s
        .omega_n_over_p
        .filter(|w| w.is_finite() && *w > MAX_OMEGA_N_OVER_P)
    {
        return Err(src.not_allowed(
            "structure.omega_n_over_p",
            w,
            &format!(
                "0 < omega_n/p <= {} (stiffer is rigid: [effects] flexibility = false)",
                short(MAX_OMEGA_N_OVER_P)
            ),
        ));
    }
    for (k, v) in [
        ("gamma_mc", s.gamma_mc),
        ("gamma_mb", s.gamma_mb),
        ("gamma_ib", s.gamma_ib),
    ] {
        if let Some(v) = v.filter(|v| v.is_finite() && *v > MAX_GAMMA) {
            return Err(src.not_allowed(
                &format!("structure.{k}"),
                v,
                &format!("{k} <= {}", short(MAX_GAMMA)),
            ));
        }
    }
    if let Some(a) = s
        .alpha
        .filter(|a| a.is_finite() && *a >= max_alpha() && *a < std::f64::consts::FRAC_PI_2)
    {
        return Err(src.not_allowed(
            "structure.alpha",
            a,
            &format!(
                "a slenderness 0 < alpha < {:.4} rad (B/H < 1000)",
                max_alpha()
            ),
        ));
    }
    Ok(())
}

/// The derived quantities a run reports must be finite (and E_ref, p, u_cr positive): values
/// that pass every key's range can still combine badly; refused rather than written as null.
pub fn derived_quantities(
    src: &Source,
    structure: &Structure,
    d: &Derived,
    physical: bool,
) -> Result<(), SceneError> {
    let threshold = structure.static_uplift_acceleration();
    let quantities = [
        ("p", d.p, true),
        ("omega_n", d.omega_n, true),
        ("omega_up", d.omega_up, true),
        ("S", d.modal_s, true),
        ("u_cr", d.u_cr, true),
        ("theta_cr", d.theta_cr, true),
        ("E_ref", d.e_ref, true),
        ("static uplift threshold", threshold, false),
    ];
    for (name, v, positive) in quantities {
        if !(v.is_finite() && (!positive || v > 0.0)) {
            let keys = if physical {
                "h, b, ei, m, m_c, m_b, i_bc, g"
            } else {
                "omega_n_over_p, alpha, gamma_mc, gamma_mb, gamma_ib, zeta"
            };
            return Err(src.err(
                "structure",
                format_args!(
                    "[structure] gives the derived quantity {name} = {}, which must be finite{}: \
                     the values of {keys} are out of range together",
                    short(v),
                    if positive { " and > 0" } else { "" }
                ),
            ));
        }
    }
    Ok(())
}

/// A ground acceleration (peak, in g) formed from the key `path` (given as `v`).
pub fn acceleration(src: &Source, path: &str, v: f64, in_g: f64) -> Result<(), SceneError> {
    if in_g.abs() <= MAX_ACCEL_G {
        Ok(())
    } else {
        Err(src.not_allowed(
            path,
            v,
            &format!(
                "it gives a peak ground acceleration of {} g; at most {} g",
                short(in_g.abs()),
                short(MAX_ACCEL_G)
            ),
        ))
    }
}

/// An excitation frequency ω_p/p formed from the key `path` (given as `v`).
pub fn frequency(src: &Source, path: &str, v: f64, over_p: f64) -> Result<(), SceneError> {
    if over_p <= MAX_OMEGA_P_OVER_P {
        Ok(())
    } else {
        Err(src.not_allowed(
            path,
            v,
            &format!(
                "it gives omega_p/p = {}; at most {}",
                short(over_p),
                short(MAX_OMEGA_P_OVER_P)
            ),
        ))
    }
}

/// Longest record, in τ = p t: a run's clock is an f64, which at 1e9 τ resolves 2e-7 τ, still
/// finer than any event the structure's time scale makes; a record longer than that (years for
/// any structure) is a wrong time step, and its run would end in "step size underflow".
pub const MAX_RECORD_TAU: f64 = 1e9;

/// A record the run cannot get through: longer than [`MAX_RECORD_TAU`], or needing more than
/// `max_steps` steps — every sample is a kink (a step ends there), and while the record lasts a
/// flexible column (fixed-base ω_n, model units) vibrates, which no integrator here follows in
/// fewer than one step per period. `record` is in model time, `p` in 1/model time;
/// `sec_per_unit` gives seconds for the message, `name` names the file.
pub fn record_length(
    src: &Source,
    name: &str,
    record: &rocking_motion::Record,
    p: f64,
    omega_n: Option<f64>,
    sec_per_unit: f64,
    max_steps: u64,
) -> Result<(), SceneError> {
    use rocking_motion::GroundMotion;
    use std::f64::consts::TAU;
    let lasts = format!(
        "the record {name} lasts {} s ({} samples of dt = {} s)",
        short(record.end() * sec_per_unit),
        record.len(),
        short(record.dt() * sec_per_unit)
    );
    let fix = "check the record's time step (DT, in s)";
    let tau = record.end() * p;
    if tau > MAX_RECORD_TAU {
        return Err(src.err(
            "excitation.path",
            format_args!(
                "{lasts}, {:.1e} τ: at most {} τ (τ = p t), beyond which a run's clock cannot \
                 resolve its events; {fix}",
                tau,
                short(MAX_RECORD_TAU)
            ),
        ));
    }
    let periods = omega_n.map_or(0.0, |w| record.end() * w / TAU);
    let steps = record.len() as f64 - 1.0 + periods;
    if steps <= max_steps as f64 {
        return Ok(());
    }
    let why = if periods > 0.0 {
        "one per sample, one per period of the column's vibration"
    } else {
        "one per sample"
    };
    Err(src.err(
        "excitation.path",
        format_args!(
            "{lasts}: at least {steps:.1e} integrator steps ({why}), more than `max_steps` = {} \
             in [solver]; {fix} or raise max_steps",
            short(max_steps as f64)
        ),
    ))
}
