//! Hybrid simulation of a deformable cantilever rocking on a rigid surface.
//!
//! The model is the one of Vassiliou, Mackie & Stojadinović (2015): an elastic cantilever with
//! distributed mass and a cubic shape function, a top mass, a rigid base with mass and inertia,
//! rocking on a rigid surface under a horizontal ground acceleration. The physics comes from the
//! generated kernels of [`rocking_kernels`]; this crate integrates it through its phases (full
//! contact, rocking about either corner, impacts, overturning) with the event-locating
//! Runge–Kutta integrators of [`rocking_ode`].
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

mod driver;
mod options;
mod results;
mod structure;

pub use driver::{simulate as simulate_variant, SimError};
pub use options::{Accuracy, History, ImpactModel, Initial, Options, Preset};
pub use results::{
    EnergyBalance, EventKind, EventRecord, HistoryRow, Phase, Run, SolverStats, Summary, Time,
};
pub use rocking_ode::Method;
pub use structure::{DampingConvention, Derived, Dimensionless, ParamError, Structure};

use rocking_kernels::kernels::{Full, MasslessBase, MasslessColumn, PointMass, Rigid, SmallAngle};
use rocking_motion::GroundMotion;

/// Which physical effects a run includes. An effect that is off, or implied absent by a zero
/// parameter, selects a more specialised kernel variant.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Effects {
    /// Column flexibility (false: rigid column, one degree of freedom).
    pub flexibility: bool,
    /// Distributed column mass.
    pub column_mass: bool,
    /// Base mass and inertia.
    pub base_mass: bool,
    /// Viscous damping in the column.
    pub damping: bool,
    /// Exact rotations (false: the small-angle model).
    pub large_rotations: bool,
}

impl Default for Effects {
    fn default() -> Self {
        Effects {
            flexibility: true,
            column_mass: true,
            base_mass: true,
            damping: true,
            large_rotations: true,
        }
    }
}

/// The generated kernel variants the solver can run.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum KernelVariant {
    /// All masses, flexible column.
    Full,
    /// m_c = 0.
    MasslessColumn,
    /// m_b = I_bc = 0.
    MasslessBase,
    /// m_c = m_b = I_bc = 0.
    PointMass,
    /// u ≡ 0.
    Rigid,
    /// Linearised in θ.
    SmallAngle,
}

impl KernelVariant {
    /// The generated module name.
    pub fn name(self) -> &'static str {
        use rocking_kernels::Variant;
        match self {
            KernelVariant::Full => Full::NAME,
            KernelVariant::MasslessColumn => MasslessColumn::NAME,
            KernelVariant::MasslessBase => MasslessBase::NAME,
            KernelVariant::PointMass => PointMass::NAME,
            KernelVariant::Rigid => Rigid::NAME,
            KernelVariant::SmallAngle => SmallAngle::NAME,
        }
    }
}

/// The structure with the switched-off effects removed, the most specialised variant that runs
/// it exactly, and the reasons for the choice.
pub fn select_variant(
    structure: &Structure,
    effects: &Effects,
) -> Result<(Structure, KernelVariant, Vec<String>), ParamError> {
    let mut ph = *structure.physical();
    let mut why = Vec::new();
    if !effects.column_mass && ph.m_c != 0.0 {
        ph.m_c = 0.0;
        why.push("column_mass = false: m_c set to 0".to_string());
    }
    if !effects.base_mass && (ph.m_b != 0.0 || ph.i_bc != 0.0) {
        ph.m_b = 0.0;
        ph.i_bc = 0.0;
        why.push("base_mass = false: m_b and I_bc set to 0".to_string());
    }
    if !effects.damping && ph.zeta != 0.0 {
        ph.zeta = 0.0;
        why.push("damping = false: zeta set to 0".to_string());
    }
    let reduced = structure.with_physical(ph)?;
    let no_column = ph.m_c == 0.0;
    let no_base = ph.m_b == 0.0 && ph.i_bc == 0.0;
    let variant = if !effects.flexibility {
        why.push("flexibility = false: rigid column, one degree of freedom".to_string());
        KernelVariant::Rigid
    } else if !effects.large_rotations {
        why.push(
            "large_rotations = false: small-angle model (sin θ → θ, cos θ → 1 − θ²/2)".to_string(),
        );
        KernelVariant::SmallAngle
    } else if no_column && no_base {
        why.push("m_c = 0 and m_b = I_bc = 0: top mass only".to_string());
        KernelVariant::PointMass
    } else if no_column {
        why.push("m_c = 0: massless column".to_string());
        KernelVariant::MasslessColumn
    } else if no_base {
        why.push("m_b = I_bc = 0: massless base".to_string());
        KernelVariant::MasslessBase
    } else {
        why.push("all masses present: full model".to_string());
        KernelVariant::Full
    };
    Ok((reduced, variant, why))
}

/// Runs a simulation with the most specialised kernel variant for `structure` and `effects`.
pub fn simulate<M: GroundMotion>(
    structure: &Structure,
    motion: &M,
    effects: &Effects,
    options: &Options,
) -> Result<Run, SimError> {
    let (structure, variant, _) =
        select_variant(structure, effects).map_err(|e| SimError::Options(e.to_string()))?;
    macro_rules! run {
        ($v:ty) => {
            if options.energy {
                driver::simulate::<$v, M, true>(&structure, motion, options)
            } else {
                driver::simulate::<$v, M, false>(&structure, motion, options)
            }
        };
    }
    match variant {
        KernelVariant::Full => run!(Full),
        KernelVariant::MasslessColumn => run!(MasslessColumn),
        KernelVariant::MasslessBase => run!(MasslessBase),
        KernelVariant::PointMass => run!(PointMass),
        KernelVariant::Rigid => run!(Rigid),
        KernelVariant::SmallAngle => run!(SmallAngle),
    }
}
