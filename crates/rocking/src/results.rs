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

/// A quantity the run did not track (NaN), left out of the summary.
fn untracked(x: &f64) -> bool {
    x.is_nan()
}

/// How an unbounded value (+∞) is written where a format has no infinity: the summary's JSON
/// (`max_required_friction` once R_v < 0) and history.csv.
pub const UNBOUNDED: &str = "inf";

/// A float that is finite or +∞: +∞ is written as the string [`UNBOUNDED`] (JSON has no infinity; the
/// history writes `inf` alike); a NaN or −∞ is an error naming the field, as in [`finite`].
fn finite_or_inf<S: Serializer>(x: &f64, s: S) -> Result<S::Ok, S::Error> {
    if *x == f64::INFINITY {
        s.serialize_str(UNBOUNDED)
    } else {
        finite(x, s)
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
    /// On compliant ground: no point of the base presses (flight).
    Flight,
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
    /// max |u| / u_cr (0 for a rigid column; NaN, left out of the summary, when
    /// [`Options::max_deflection`](crate::Options::max_deflection) is off).
    #[serde(serialize_with = "finite", skip_serializing_if = "untracked")]
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
    /// Section forces at the column base and ground reactions, when tracked (`Options::forces`).
    #[serde(flatten, skip_serializing_if = "Option::is_none")]
    pub forces: Option<ForceSummary>,
    /// On compliant ground (issue 44, docs/ground.md): pressure, contact, lift-offs, settlement
    /// and the ground's dissipation; absent on the rigid surface.
    #[serde(flatten, skip_serializing_if = "Option::is_none")]
    pub ground: Option<GroundSummary>,
}

/// What a run on compliant ground reports of the ground (W the total weight, B the half-width,
/// v0 = W / K_v the static settlement), from every accepted step's end and every event.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct GroundSummary {
    /// The largest pressure under the base over the mean W / (2B) (two springs: the larger
    /// corner force over W / 2).
    #[serde(serialize_with = "finite")]
    pub max_ground_pressure_over_mean: f64,
    /// The least pressure at an end of the contact over the mean (two springs: the smaller
    /// corner force over W / 2; 0 where a corner is lifted): below zero the ground pulls, which
    /// only the linear-foundation twin's bilateral springs can (how far, is what it tells), or a
    /// dashpot at the end of a contact that is unloading.
    #[serde(serialize_with = "finite")]
    pub min_ground_pressure_over_mean: f64,
    /// The smallest contact length over 2B (two springs: corners pressing over 2; 0 in flight).
    #[serde(serialize_with = "finite")]
    pub min_contact_fraction: f64,
    /// Edge (corner) lift-off events.
    pub lift_offs: u64,
    /// max v / v0, v the settlement of the base centre.
    #[serde(serialize_with = "finite")]
    pub max_settlement_over_static: f64,
    /// The energy the ground's dashpots took, ∫ D dt, over E_ref.
    #[serde(serialize_with = "finite")]
    pub ground_energy_dissipated: f64,
    /// The first time the largest pressure under the base exceeded the bearing pressure
    /// (`Options::bearing_over_mean`; checked at every accepted step's end and event, as the
    /// maxima are). Absent from the summary unless a bearing pressure is given.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub first_bearing_exceeded_time: Option<Option<Time>>,
}

/// The largest section forces at the column base and the extremes of the ground reactions over
/// a run, from the generated force kernels at every step and inside steps where a new extreme
/// may lie (docs/design-forces.md). M_b is the equilibrium moment (P-Δ and damping included), W
/// the total weight, B the half-width: |M_b| = W B is the moment at which the base uplifts.
/// Reactions exclude impact impulses.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct ForceSummary {
    /// max |M_b| / (W B).
    #[serde(serialize_with = "finite")]
    pub max_base_moment_over_wb: f64,
    /// max |V_b| / W (the shear normal to the column axis).
    #[serde(serialize_with = "finite")]
    pub max_base_shear_over_w: f64,
    /// max |M_el| / (W B), M_el = EI Σ u_i ψ_i''(0) / H² (the moment from the curvature).
    #[serde(serialize_with = "finite")]
    pub max_elastic_base_moment_over_wb: f64,
    /// max |R_h| / R_v: the friction coefficient the no-sliding assumption needs. Unbounded
    /// (`f64::INFINITY`, written `"inf"` in the summary's JSON as `inf` in history.csv) once R_v
    /// falls below zero: no friction holds a base the ground would have to pull. That happens
    /// first at [`first_lift_off_time`](Self::first_lift_off_time), which is the time of the
    /// unbounded demand (no key of its own). Otherwise the largest value over the run, all of
    /// whose instants have R_v > 0, resolved inside steps like the other maxima.
    ///
    /// An instant with R_v = 0 exactly is not a lift-off: with R_h = 0 too it needs no friction
    /// (0/0; at rest on a level ground nothing pushes sideways), and an R_v that only touches
    /// zero without going below is a set of measure zero that a run does not resolve.
    ///
    /// There is no finite "largest over the instants where R_v > 0" beside it: where R_v falls
    /// through zero continuously (the usual lift-off), |R_h| / R_v grows without bound as R_v
    /// goes to 0⁺, so the largest value a run samples before the crossing is set by how close
    /// its steps come to it (23.5, 37.3 and 1020 at the `default`, `accurate` and `reference`
    /// presets for one Fig-8 cell, issue 47 item 5), not by the structure. It is finite and
    /// step-independent only where R_v jumps below zero at an impact, which a summary cannot
    /// tell apart from a continuous crossing.
    #[serde(serialize_with = "finite_or_inf")]
    pub max_required_friction: f64,
    /// min R_v / W (below 0: the ground would have to pull, the no-jumping assumption fails).
    #[serde(serialize_with = "finite")]
    pub min_vertical_reaction_over_w: f64,
    /// The first time |R_h| / R_v exceeded the ground's friction coefficient (`Options::friction`,
    /// when given; R_v > 0): the structure would slide.
    pub first_slip_time: Option<Time>,
    /// The first time R_v fell below zero: the structure would jump, and from there the
    /// required friction is unbounded ([`max_required_friction`](Self::max_required_friction)
    /// is +∞ exactly when this is set).
    pub first_lift_off_time: Option<Time>,
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
    /// On compliant ground: the energy its dashpots took (`last` includes the springs' strain
    /// energy); absent on the rigid surface.
    #[serde(serialize_with = "finite_opt", skip_serializing_if = "Option::is_none")]
    pub ground_dissipation: Option<f64>,
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
    /// On compliant ground: a corner stopped pressing (its depth fell through zero).
    LiftOff,
    /// On compliant ground: a corner pressed again (its depth rose through zero).
    Landing,
    /// On compliant ground: θ passed through zero and the leaning corner changed (no impact).
    PivotSwitch,
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

/// One row of the time history, in the model's units: the report's column list
/// (`rocking_study::report::tables`) normalises it for the tables, figures and Python.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct HistoryRow {
    /// t, model time (τ = p t).
    pub t: f64,
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
    /// Kinetic energy.
    pub e_kin: f64,
    /// Total energy, relative to rest.
    pub e_total: f64,
    /// Ground acceleration.
    pub ug: f64,
    /// M_b: the equilibrium moment at the column base.
    pub base_moment: f64,
    /// V_b.
    pub base_shear: f64,
    /// M_el: the moment from the curvature.
    pub elastic_base_moment: f64,
    /// R_h.
    pub horizontal_reaction: f64,
    /// R_v.
    pub vertical_reaction: f64,
    /// On compliant ground: settlement, contact and pressure (absent on the rigid surface).
    #[serde(flatten, skip_serializing_if = "Option::is_none")]
    pub ground: Option<GroundRow>,
}

/// A history row's ground columns (compliant ground), in the model's units.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct GroundRow {
    /// v, the settlement of the base centre.
    pub settlement: f64,
    /// Contact length over 2B (two springs: corners pressing over 2).
    pub contact_fraction: f64,
    /// The largest pressure under the base (two springs: the larger corner force).
    pub ground_pressure: f64,
    /// The least pressure at an end of the contact (two springs: the smaller corner force; 0 in
    /// flight): below zero where a dashpot pulls at an unloading edge, or the bilateral springs
    /// of the linear-foundation twin pull.
    pub least_pressure: f64,
}

/// |R_h| / R_v, the friction coefficient an instant needs; infinite where R_v <= 0 (no friction
/// holds a structure the ground would have to pull).
pub fn required_friction(horizontal: f64, vertical: f64) -> f64 {
    if vertical > 0.0 {
        horizontal.abs() / vertical
    } else {
        f64::INFINITY
    }
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
    /// With n > 1 deformation coordinates, each history row's u_1..u_n and u_1'..u_n' (2n
    /// numbers per row, in the order of `history`); empty for one coordinate (whose u is the
    /// row's own).
    pub coordinates: Vec<f64>,
}

impl Run {
    /// The number n of deformation coordinates in [`Run::coordinates`] (0 when not recorded).
    pub fn coordinate_count(&self) -> usize {
        self.coordinates.len() / (2 * self.history.len().max(1))
    }

    /// u_1..u_n, u_1'..u_n' of history row `i` (empty for one coordinate).
    pub fn coordinates_of(&self, i: usize) -> &[f64] {
        let w = 2 * self.coordinate_count();
        self.coordinates.get(i * w..(i + 1) * w).unwrap_or(&[])
    }
}
