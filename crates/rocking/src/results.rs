//! What a run reports: the summary, the event log and the time history.

use serde::{Serialize, Serializer};

/// Serializes a float that must be finite: a NaN or an infinity is an error naming the field
/// (through `serde_path_to_error`), never a `null` in a result.
fn finite<S: Serializer>(x: &f64, s: S) -> Result<S::Ok, S::Error> {
    if x.is_finite() {
        s.serialize_f64(*x)
    } else {
        Err(serde::ser::Error::custom(format!("not finite ({x})")))
    }
}

/// [`finite`] for an optional float (`None` is `null`).
fn finite_opt<S: Serializer>(x: &Option<f64>, s: S) -> Result<S::Ok, S::Error> {
    match x {
        Some(x) => finite(x, s),
        None => s.serialize_none(),
    }
}

/// A time, as τ = p t and, when the structure has a time scale, in seconds.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Time {
    /// Dimensionless time τ = p t.
    #[serde(serialize_with = "finite")]
    pub tau: f64,
    /// Seconds, when known.
    #[serde(serialize_with = "finite_opt")]
    pub seconds: Option<f64>,
}

/// The phase of the hybrid system.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Phase {
    /// Full contact: θ = θ' = 0, the column vibrates as a fixed-base cantilever.
    Contact,
    /// Rocking about the right corner (θ > 0).
    RockingRight,
    /// Rocking about the left corner (θ < 0).
    RockingLeft,
    /// Overturned (terminal).
    Overturned,
}

impl Phase {
    /// The rocking phase about pivot `s`.
    pub fn rocking(s: f64) -> Phase {
        if s > 0.0 {
            Phase::RockingRight
        } else {
            Phase::RockingLeft
        }
    }
}

/// Work counters of the integrator, summed over all phases.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
pub struct SolverStats {
    /// Accepted steps.
    pub steps: u64,
    /// Rejected steps.
    pub rejected_steps: u64,
    /// Right-hand-side (kernel) evaluations.
    pub rhs_evaluations: u64,
    /// Located events (uplift, impact, overturning).
    pub events: u64,
}

impl SolverStats {
    pub(crate) fn add(&mut self, s: rocking_ode::Stats) {
        self.steps += s.steps;
        self.rejected_steps += s.rejected;
        self.rhs_evaluations += s.rhs_evals;
        self.events += s.events;
    }
}

/// The answer of a run. Serialized, it is the summary a run reports (`rocking run --json`,
/// summary.json, Python's `Result.summary`): every field is reported as it is named here (a
/// time `*_time` as τ, with `*_time_s` in seconds), so a field added here is reported with no
/// other edit.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Summary {
    /// The generated kernel variant that ran.
    pub kernel_variant: &'static str,
    /// max |θ| / α.
    #[serde(serialize_with = "finite")]
    pub max_theta_over_alpha: f64,
    /// max |θ| / θ_cr.
    #[serde(serialize_with = "finite")]
    pub max_theta_over_theta_cr: f64,
    /// max |u| / u_cr (0 for a rigid column).
    #[serde(serialize_with = "finite")]
    pub max_u_over_ucr: f64,
    /// Whether the structure overturned.
    pub overturned: bool,
    /// When it overturned.
    pub overturn_time: Option<Time>,
    /// Number of impacts.
    pub impacts: u64,
    /// Impacts with |θ'| >= 0.01 α p.
    pub significant_impacts: u64,
    /// Impacts whose model's map would have created kinetic energy and that kept the pre-impact
    /// kinetic energy instead (branch `*-energy-capped` in the event log; ARCHITECTURE.md).
    pub energy_capped_impacts: u64,
    /// First uplift.
    pub first_uplift_time: Option<Time>,
    /// First impact.
    pub first_impact_time: Option<Time>,
    /// Phase at the end of the run.
    pub final_phase: Phase,
    /// Time at which the run ended (early when the answer was known).
    pub end_time: Time,
    /// (E_final + ground work out + damping + impact losses − E_initial) / E_ref, when the energy
    /// bookkeeping was asked for.
    #[serde(serialize_with = "finite_opt")]
    pub energy_balance_residual: Option<f64>,
    /// Energy bookkeeping in units of E_ref, when asked for.
    pub energy: Option<EnergyBalance>,
    /// Integrator work.
    pub solver_stats: SolverStats,
}

/// The terms of E_final = E_initial + W_ground − D − Σ losses, in units of E_ref.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct EnergyBalance {
    /// Total energy T + V_g + V_s at the start, relative to the structure at rest.
    #[serde(serialize_with = "finite")]
    pub initial: f64,
    /// Total energy at the end.
    #[serde(serialize_with = "finite")]
    pub last: f64,
    /// Work done by the ground acceleration, ∫ −ü_g P_x dt.
    #[serde(serialize_with = "finite")]
    pub ground_work: f64,
    /// Viscous dissipation in the column, ∫ c u'² dt.
    #[serde(serialize_with = "finite")]
    pub damping: f64,
    /// Kinetic energy lost in impacts.
    #[serde(serialize_with = "finite")]
    pub impact_losses: f64,
}

/// What happened at an event.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum EventKind {
    /// The base uplifted about a corner.
    Uplift,
    /// The base hit the ground.
    Impact,
    /// |θ| reached the overturning angle.
    Overturn,
    /// The rest rule ended a vanishing rocking motion.
    Rest,
}

/// One entry of the event log.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct EventRecord {
    /// When.
    pub time: Time,
    /// What.
    pub kind: EventKind,
    /// Impacts: which branch of the impact model was taken.
    pub branch: &'static str,
    /// Phase after the event.
    pub phase_after: Phase,
    /// θ' just before the event.
    pub theta_dot: f64,
    /// u at the event.
    pub u: f64,
    /// u' just before the event.
    pub u_dot: f64,
    /// Kinetic energy before, / E_ref.
    pub energy_before: f64,
    /// Kinetic energy after, / E_ref.
    pub energy_after: f64,
}

/// One row of the time history.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct HistoryRow {
    /// τ = p t.
    pub tau: f64,
    /// θ (rad).
    pub theta: f64,
    /// u.
    pub u: f64,
    /// θ'.
    pub theta_dot: f64,
    /// u'.
    pub u_dot: f64,
    /// Phase.
    pub phase: Phase,
    /// Kinetic energy / E_ref.
    pub e_kin: f64,
    /// Total energy (relative to rest) / E_ref.
    pub e_total: f64,
    /// Ground acceleration.
    pub ug: f64,
}

/// Everything a run produced.
#[derive(Clone, Debug, PartialEq)]
pub struct Run {
    /// The summary.
    pub summary: Summary,
    /// Events, when asked for.
    pub events: Vec<EventRecord>,
    /// Time history, when asked for.
    pub history: Vec<HistoryRow>,
}
