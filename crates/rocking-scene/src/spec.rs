//! The typed scene: one struct per table of a scene file (serde, unknown keys refused), as
//! [`crate::scene`] reads it and [`crate::setup`] builds it.

use rocking::{DampingConvention, Preset};
use serde::{Deserialize, Serialize};
use toml::Value;

use crate::ground_spec::GroundSpec;

/// A model's own parameters given in a scene, by name.
pub type ModelParams = Vec<(&'static str, f64)>;
/// A model's mass switches given in a scene, by name.
pub type MassSwitches = Vec<(&'static str, bool)>;

/// `[structure]`: physical (SI) or dimensionless. All optional here; the combination is checked
/// when the structure is built.
#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StructureSpec {
    /// The model (`name` of a `Model` in derive/rocking_derive/models.py); default the paper's.
    pub model: Option<String>,
    /// The values of the parameters the model adds (`m_a = 0.5`), taken out of the table before
    /// the rest is deserialized.
    #[serde(skip)]
    pub extra: ModelParams,
    // Dimensionless form (eq 34).
    pub omega_n_over_p: Option<f64>,
    pub alpha: Option<f64>,
    pub gamma_mc: Option<f64>,
    pub gamma_mb: Option<f64>,
    pub gamma_ib: Option<f64>,
    pub damping: Option<DampingConvention>,
    /// Length scale R (m), to report seconds.
    pub r: Option<f64>,
    /// p = sqrt(g/R) (1/s), to report seconds.
    pub p: Option<f64>,
    // Both forms.
    pub zeta: Option<f64>,
    /// `zeta = [ζ_1, ζ_2, ...]`: the fixed-base damping ratio of each mode of a model of several
    /// deformation coordinates, taken out of the table before the rest is deserialized.
    #[serde(skip)]
    pub zeta_per_mode: Option<Vec<f64>>,
    // Physical form (SI).
    pub h: Option<f64>,
    pub b: Option<f64>,
    pub ei: Option<f64>,
    pub m: Option<f64>,
    pub m_c: Option<f64>,
    pub m_b: Option<f64>,
    pub i_bc: Option<f64>,
    pub g: Option<f64>,
}

/// `[excitation]`: a flat table; which keys a `kind` uses is checked when it is built.
#[derive(Clone, Debug, Default, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct ExcitationSpec {
    pub kind: Option<String>,
    pub omega_p_over_p: Option<f64>,
    pub omega_p: Option<f64>,
    pub amplitude: Option<f64>,
    pub amplitude_g: Option<f64>,
    pub a_p: Option<f64>,
    pub shape: Option<String>,
    pub velocity_amplitude: Option<f64>,
    pub v_p: Option<f64>,
    pub gamma: Option<f64>,
    pub nu: Option<f64>,
    pub path: Option<String>,
    pub scale: Option<f64>,
    /// Units of a record whose header states none: "g", "cm/s2" or "m/s2".
    pub units: Option<String>,
    // record-format keys (issue 14)
    /// Layout of the record file: "at2", "text", "esm" or "knet" (default: from its extension).
    pub format: Option<String>,
    /// Time step (s) of a one-column text record.
    pub dt: Option<f64>,
}

/// `[effects]`.
#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EffectsSpec {
    /// The model's removable masses switched on or off by name (`m_a = false`), taken out of the
    /// table before the rest is deserialized.
    #[serde(skip)]
    pub masses: MassSwitches,
    pub flexibility: Option<bool>,
    pub column_mass: Option<bool>,
    pub base_mass: Option<bool>,
    pub damping: Option<bool>,
    pub large_rotations: Option<bool>,
    /// "vvel", "adjex", "housner" or { restitution = r }.
    pub impact: Option<Value>,
    /// Angle in rad, or "pi/2".
    pub overturn: Option<Value>,
    pub energy: Option<bool>,
    /// false: the fixed-base twin (held in full contact, no uplift check).
    pub uplift: Option<bool>,
    /// The ground's coefficient of friction: a warning when the run needs more.
    pub friction: Option<f64>,
    /// Compliant ground: the bearing pressure (SI, Pa) over a footing `footing_length` (m) long
    /// out of the plane, or `bearing_over_mean` against max_ground_pressure_over_mean: a
    /// warning when the pressure under the base exceeds it (`ground::bearing`).
    pub bearing: Option<f64>,
    pub footing_length: Option<f64>,
    pub bearing_over_mean: Option<f64>,
}

/// `[solver]`.
#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SolverSpec {
    pub accuracy: Option<Preset>,
    pub method: Option<String>,
    pub tol: Option<f64>,
    pub after_excitation: Option<f64>,
    /// Guards that end a run that would not end: integrator steps and events.
    pub max_steps: Option<f64>,
    pub max_events: Option<f64>,
}

/// `[initial]`.
#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct InitialSpec {
    pub theta_over_alpha: Option<f64>,
    pub u_over_ucr: Option<f64>,
    pub theta_dot_over_alpha_p: Option<f64>,
    pub u_dot_over_ucr_omega_n: Option<f64>,
    /// The base's settlement over the static settlement v₀ (compliant ground only; default: at
    /// rest in vertical equilibrium at the initial θ).
    pub v_over_static: Option<f64>,
}

/// `[output]`.
#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OutputSpec {
    /// "none" or "steps".
    pub history: Option<String>,
    /// Grid spacing in τ.
    pub history_dt: Option<f64>,
    pub events: Option<bool>,
    pub plots: Option<bool>,
    /// An animated GIF of the structure (`rocking run --animate`), with its frame count and size
    /// in pixels (bounds in `model::Animation`).
    pub animation: Option<bool>,
    pub animation_frames: Option<i64>,
    pub animation_width: Option<i64>,
    pub animation_height: Option<i64>,
    /// Track the section forces and reactions (default true; a sweep may skip them).
    pub forces: Option<bool>,
    /// Run the fixed-base twin too and report the ratios of the forces.
    pub fixed_base_reference: Option<bool>,
}

/// A whole scene file.
#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SceneSpec {
    pub title: Option<String>,
    pub structure: Option<StructureSpec>,
    pub excitation: Option<ExcitationSpec>,
    pub effects: Option<EffectsSpec>,
    /// `[ground]`: the rigid surface when absent.
    pub ground: Option<GroundSpec>,
    pub solver: Option<SolverSpec>,
    pub initial: Option<InitialSpec>,
    pub output: Option<OutputSpec>,
    pub sweep: Option<SweepSpec>,
    /// `[ida]`: the settings of `rocking ida` (issue 14).
    pub ida: Option<IdaSpec>,
}

/// `[ida]`: incremental dynamic analysis and the fragility fit of `rocking ida`. Checked by the
/// command (every key has a default there).
#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct IdaSpec {
    /// Records (paths relative to the scene, files or folders); default: `[sweep] records`.
    pub records: Option<Vec<String>>,
    /// Intensity measure the records are scaled to: "sa" (PSA(T, ζ)) or "pga".
    pub im: Option<String>,
    /// Period T of "sa" (s).
    pub period: Option<f64>,
    /// Damping ratio ζ of "sa".
    pub damping: Option<f64>,
    /// Hunt-and-fill: first level, first step and step increment (m/s²).
    pub first: Option<f64>,
    pub step: Option<f64>,
    pub step_increment: Option<f64>,
    /// Relative tolerance of each capacity.
    pub tolerance: Option<f64>,
    /// Fill until no gap below the capacity is wider than this fraction of it.
    pub max_gap: Option<f64>,
    /// Most analyses per record.
    pub max_runs: Option<usize>,
    /// Multiple-stripe analysis instead of IDA: every record scaled to each of these IM levels
    /// (m/s²), the fit from the fraction that collapsed at each.
    pub stripes: Option<Vec<f64>>,
    /// Collapse: overturning, or max θ/α reaching this limit (when given).
    pub theta_over_alpha_limit: Option<f64>,
    /// Bootstrap resamples and seed of the confidence band.
    pub bootstrap: Option<usize>,
    pub seed: Option<u64>,
}

/// `[sweep]`: the axes of `rocking spectrum` (same syntax as `--axis`) and the reference structure
/// drawn on its figure, and for `rocking batch` a list of records (paths relative to the scene)
/// and scale factors.
#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SweepSpec {
    pub axes: Option<Vec<String>>,
    /// Quantities every cell reports besides its class, max θ/α and impacts: any numeric key of
    /// the run's summary, `fixed_base.KEY` and the ratios to the fixed-base twin.
    pub report: Option<Vec<String>>,
    pub reference: Option<String>,
    pub records: Option<Vec<String>>,
    pub scales: Option<Vec<f64>>,
}
