//! Hybrid simulation of a deformable cantilever rocking on a rigid surface.
//!
//! The model is the one of Vassiliou, Mackie & Stojadinović (2015): an elastic cantilever with
//! distributed mass and a cubic shape function, a top mass, a rigid base with mass and inertia,
//! rocking on a rigid surface under a horizontal ground acceleration. The physics comes from the
//! generated kernels of [`rocking_kernels`]; this crate integrates it through its phases (full
//! contact, rocking about either corner, impacts, overturning) with the event-locating
//! Runge–Kutta integrators of [`rocking_ode`] and the Taylor method generated from the
//! derivation.
//!
//! It owns the hybrid logic (phases, events, the impact policy) and the run's summary; it must
//! not know the physics beyond the generated kernels' interface (no equation is typed here),
//! nor scene files, units of a record, or how results are written.
//!
//! # A run
//!
//! 1. Describe the structure, physically ([`Structure::from_physical`]) or by the dimensionless
//!    groups of the paper's eq (34) ([`Structure::from_dimensionless`], time in τ = p t).
//! 2. Choose a ground motion from [`rocking_motion`] (pulses, PEER records), in the same units.
//! 3. Choose [`Options`]: accuracy preset, impact model, end time, what to record.
//! 4. [`simulate`] picks the most specialised kernel variant for the structure and the [`Effects`]
//!    asked for, runs it monomorphised, and returns a [`Run`]: the [`Summary`], and the event log
//!    and time history when asked for.
//!
//! ```
//! use rocking::{simulate, DampingConvention, Dimensionless, Effects, Options, Structure};
//! use rocking_motion::SinePulse;
//!
//! // The paper's Fig. 3 case: a_p/(g tan α) = 1.30, ω_n/p = 11.9, ω_p/p = 5.1, α = 0.2, ζ = 0.005.
//! let d = Dimensionless {
//!     omega_n_over_p: 11.9, alpha: 0.2, gamma_mc: 0.0, gamma_mb: 0.0, gamma_ib: 1.0,
//!     zeta: 0.005, damping: DampingConvention::FixedBase,
//! };
//! let structure = Structure::from_dimensionless(&d, None).unwrap();
//! let pulse = SinePulse::new(1.30 * 0.2f64.tan(), 5.1); // R = g = 1: accelerations in g
//! let options = Options { t_end: 4.0, ..Options::default() };
//! let run = simulate(&structure, &pulse, &Effects::default(), &options).unwrap();
//! assert_eq!(run.summary.kernel_variant, "point_mass");
//! assert!(run.summary.impacts >= 2 && !run.summary.overturned);
//! ```

#![warn(missing_docs)]

mod dense;
mod driver;
mod error;
mod extremes;
mod ground;
pub mod ground_modes;
pub mod ground_statics;
mod layout;
mod options;
mod results;
pub mod rhs;
mod spd;
mod structure;
mod taylor;

pub use driver::simulate as simulate_variant;
pub use error::{OptionError, SimError};
pub use extremes::{Extreme, Extremes, ForceExtreme, ForceExtremes, GroundExtreme, GroundExtremes};
pub use ground::{Ground, GroundKind, GroundStatics};
pub use options::{
    Accuracy, History, ImpactModel, Initial, Measured, Method, Options, Preset, MAX_HISTORY_ROWS,
};
pub use results::{
    required_friction, EnergyBalance, EventKind, EventRecord, ForceSummary, GroundRow,
    GroundSummary, HistoryRow, Phase, Run, SolverStats, Summary, Time, UNBOUNDED,
};
pub use rocking_kernels::{ModelInfo, VariantInfo};
pub use structure::{
    find_model, model_names, plate_inertia, DampingConvention, Derived, Dimensionless, Frequencies,
    ParamError, StaticUplift, Structure, PAPER_MODEL,
};
pub use taylor::TaylorVariant;

use rocking_kernels::{kernels::MAX_PARAMS, with_variant, Role};
use rocking_motion::GroundMotion;

/// Which physical effects a run includes. An effect that is off, or implied absent by a zero
/// parameter, selects a more specialised kernel variant of the structure's model.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Effects {
    /// Column flexibility (false: rigid column, one degree of freedom).
    pub flexibility: bool,
    /// Viscous damping in the column.
    pub damping: bool,
    /// Exact rotations (false: the small-angle model).
    pub large_rotations: bool,
    /// Masses switched off, by parameter name (`m_c`, `m_b`, a model's own such as `m_a`): each
    /// is set to zero, a base mass with its inertia. They must be removable masses of the model.
    pub masses_off: MassesOff,
}

/// A set of mass parameters switched off (at most one per parameter of a model; `Copy`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct MassesOff {
    names: [&'static str; MAX_PARAMS],
    n: usize,
}

impl Default for MassesOff {
    fn default() -> Self {
        MassesOff {
            names: [""; MAX_PARAMS],
            n: 0,
        }
    }
}

impl MassesOff {
    /// The names, in the order they were switched off.
    pub fn iter(&self) -> impl Iterator<Item = &'static str> + '_ {
        self.names[..self.n].iter().copied()
    }

    /// Whether the mass `name` is switched off.
    pub fn contains(&self, name: &str) -> bool {
        self.iter().any(|m| m == name)
    }
}

impl Default for Effects {
    fn default() -> Self {
        Effects {
            flexibility: true,
            damping: true,
            large_rotations: true,
            masses_off: MassesOff::default(),
        }
    }
}

impl Effects {
    /// These effects with the mass `name` switched off.
    ///
    /// # Panics
    /// When more masses are switched off than a model has parameters.
    pub fn without_mass(mut self, name: &'static str) -> Effects {
        let m = &mut self.masses_off;
        if !m.contains(name) {
            m.names[m.n] = name;
            m.n += 1;
        }
        self
    }
}

/// The variant a run gets: the structure with the switched-off effects removed, the most
/// specialised generated variant of its model that runs it exactly, and the reasons.
#[derive(Clone, Debug, PartialEq)]
pub struct Selection {
    /// The structure that is simulated (switched-off masses and damping set to zero).
    pub structure: Structure,
    /// The kernel variant.
    pub variant: &'static VariantInfo,
    /// Why, in words.
    pub reasons: Vec<String>,
}

/// Selects the variant for `structure` and `effects` from the generated registry: among the
/// variants of the structure's model that match the flexibility and rotation effects and whose
/// removed masses are all zero, the one that removes the most.
pub fn select_variant(structure: &Structure, effects: &Effects) -> Result<Selection, ParamError> {
    let model = structure.model();
    let mut s = *structure;
    let mut reasons = Vec::new();
    for name in effects.masses_off.iter() {
        if !model.removable_masses().any(|m| m == name) {
            return Err(ParamError {
                parameter: name,
                value: 0.0,
                allowed: format!(
                    "`{name}` is not a mass model `{}` can switch off (its masses: {})",
                    model.name,
                    model.removable_masses().collect::<Vec<_>>().join(", ")
                ),
            });
        }
        let mut zeroed = vec![name];
        zeroed.extend(
            model
                .params
                .iter()
                .filter(|p| p.role == Role::InertiaOf(name))
                .map(|p| p.name),
        );
        if zeroed.iter().any(|z| s.param(z) != Some(0.0)) {
            for z in &zeroed {
                s = s.with_param(z, 0.0)?;
            }
            reasons.push(format!("{name} = false: {} set to 0", zeroed.join(" and ")));
        }
    }
    if !effects.damping && s.modal_damping_ratios().iter().any(|&z| z != 0.0) {
        s = s.with_param("zeta", 0.0)?;
        reasons.push("damping = false: zeta set to 0".to_string());
    }
    let candidates = model.variant_infos().filter(|v| {
        v.rigid != effects.flexibility
            && v.small_angle != effects.large_rotations
            && v.removed.iter().all(|r| s.param(r) == Some(0.0))
    });
    let mut best: Option<&'static VariantInfo> = None;
    for v in candidates {
        if best.is_none_or(|b| v.removed.len() > b.removed.len()) {
            best = Some(v);
        }
    }
    let Some(variant) = best else {
        let (parameter, what) = if !effects.flexibility {
            ("flexibility", "rigid")
        } else {
            ("large_rotations", "small-angle")
        };
        return Err(ParamError {
            parameter,
            value: 0.0,
            allowed: format!(
                "model `{}` has no {what} variant (its variants: {}); add one in \
                 derive/rocking_derive/models.py",
                model.name,
                model.variants.join(", ")
            ),
        });
    };
    if variant.rigid {
        reasons.push("flexibility = false: rigid column, one degree of freedom".to_string());
    }
    if variant.small_angle {
        reasons.push(
            "large_rotations = false: small-angle model (sin θ → θ, cos θ → 1 − θ²/2)".to_string(),
        );
    }
    if !variant.removed.is_empty() {
        reasons.push(format!(
            "{} = 0: {}",
            variant.removed.join(" = "),
            variant.title
        ));
    } else if !variant.rigid && !variant.small_angle {
        let zero: Vec<&str> = model
            .removable_masses()
            .filter(|m| s.param(m) == Some(0.0))
            .collect();
        reasons.push(if zero.is_empty() {
            format!("all masses present: {}", variant.title)
        } else {
            format!(
                "no variant of model `{}` removes {} = 0: {}",
                model.name,
                zero.join(", "),
                variant.title
            )
        });
    }
    Ok(Selection {
        structure: s,
        variant,
        reasons,
    })
}

/// Runs a simulation with the most specialised kernel variant for `structure` and `effects`.
///
/// The driver sees the ground motion as `&dyn GroundMotion`: it is compiled once per variant,
/// here, whatever motion types the callers have (monomorphised per motion type, every test
/// binary and tool instantiated the whole driver again; the virtual call per evaluation of ü_g
/// costs nothing measurable beside a kernel call, see docs/performance.md).
pub fn simulate(
    structure: &Structure,
    motion: &dyn GroundMotion,
    effects: &Effects,
    options: &Options,
) -> Result<Run, SimError> {
    let sel = select_variant(structure, effects).map_err(SimError::NoVariant)?;
    run_selected(sel.variant, &sel.structure, None, motion, options)
}

/// Runs a simulation on compliant ground (issue 44, docs/ground.md) with the most specialised
/// kernel variant for `structure` and `effects`: the free-base equations of the variant and the
/// ground's kernels, integrated by the options' method (the Taylor method's series solved order
/// by order at run time, docs/ground.md). The energy integrals are always carried; the
/// summary's energy balance is reported when `options.energy` is set.
pub fn simulate_on_ground(
    structure: &Structure,
    ground: &Ground,
    motion: &dyn GroundMotion,
    effects: &Effects,
    options: &Options,
) -> Result<Run, SimError> {
    let sel = select_variant(structure, effects).map_err(SimError::NoVariant)?;
    run_selected(sel.variant, &sel.structure, Some(ground), motion, options)
}

/// Runs the generated variant called `name` (monomorphised through the generated dispatch) on a
/// structure of its model.
pub fn run_variant(
    name: &str,
    structure: &Structure,
    motion: &dyn GroundMotion,
    options: &Options,
) -> Result<Run, SimError> {
    match VariantInfo::find(name) {
        Some(v) => run_selected(v, structure, None, motion, options),
        None => Err(SimError::UnknownVariant {
            name: name.to_string(),
            model: Some(structure.model().name),
        }),
    }
}

/// Runs `variant` on `structure` (a [`Selection`]'s pair, chosen once when a scene is built):
/// on `ground` when given one, else on the rigid surface.
pub fn run_selected(
    variant: &'static VariantInfo,
    structure: &Structure,
    ground: Option<&Ground>,
    motion: &dyn GroundMotion,
    options: &Options,
) -> Result<Run, SimError> {
    let name = variant.name;
    if variant.model != structure.model().name {
        return Err(SimError::UnknownVariant {
            name: name.to_string(),
            model: Some(structure.model().name),
        });
    }
    with_variant!(name, V, L => match ground {
        Some(g) => driver::simulate_ground::<V, dyn GroundMotion, { L::Y + 3 }>(
            structure, g, motion, options,
        ),
        None if options.energy => {
            driver::simulate::<V, dyn GroundMotion, { L::X + 2 }, { L::XC + 2 }>(
                structure, motion, options,
            )
        }
        None => driver::simulate::<V, dyn GroundMotion, { L::X }, { L::XC }>(structure, motion, options),
    })
    .unwrap_or_else(|| {
        Err(SimError::UnknownVariant {
            name: name.to_string(),
            model: None,
        })
    })
}
