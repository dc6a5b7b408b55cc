//! The study's cases: the structures, motions and runs each stands for, and their classes.

use std::f64::consts::PI;
use std::path::Path;

use rocking::{
    Accuracy, DampingConvention, Dimensionless, Effects, History, ImpactModel, Initial, Options,
    Structure,
};
use rocking_motion::{Excitation, SinePulse};
use serde::{Deserialize, Serialize};
use serde_json::{json, Value};

use super::params_of;
use crate::Result;

/// The long-record case: a record of the IDA's set (directory relative to scenes/) and its scale,
/// PGA/(g tan α) ≈ 637, where the turbine rocks through ~147 impacts without overturning.
const LONG_RECORD_DIR: &str = "../../shared/data/ground-motions";

const LONG_RECORD: &str = "HAU000.AT2";

const LONG_RECORD_SCALE: f64 = 1130.0;

/// The class of runs a case stands for. The presets are chosen on the [`Class::Standard`] cases
/// and their errors hold there; the others are measured and reported per class (issue 47 item 14:
/// an error amplified by hundreds of impacts is a property of the run, not of a preset).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Class {
    /// Pulses, free rocking and records with up to ~150 impacts: where the presets are chosen.
    Standard,
    /// Long records with hundreds of impacts: each impact carries the error of the one before.
    ManyImpacts,
    /// A chatter to rest (restitution 1, ~450,000 impacts): only the maxima are determined.
    Chatter,
}

impl Class {
    pub const ALL: [Class; 3] = [Class::Standard, Class::ManyImpacts, Class::Chatter];

    /// The name in rust.json and in the report.
    pub fn name(self) -> &'static str {
        match self {
            Class::Standard => "standard",
            Class::ManyImpacts => "many-impacts",
            Class::Chatter => "chatter",
        }
    }

    /// What the class stands for, for the report.
    pub fn description(self) -> &'static str {
        match self {
            Class::Standard => "pulses, free rocking and records with up to ~150 impacts (the presets are chosen here)",
            Class::ManyImpacts => "long records with hundreds of impacts",
            Class::Chatter => "a chatter to rest: restitution 1, ~450,000 impacts",
        }
    }
}

/// One case of the study.
pub struct Case {
    pub name: &'static str,
    pub class: Class,
    pub title: String,
    pub structure: Structure,
    pub effects: Effects,
    pub motion: Excitation,
    pub impact: ImpactModel,
    pub t_end: f64,
    pub initial: Initial,
    /// Spectrum slice: amplitudes a_p/(g tan α) at the fixed ω_p/p = `omega_p`.
    pub slice: Option<(f64, Vec<f64>)>,
    /// Exact Housner impact times (τ) when the case has them.
    pub exact_impacts: Option<Vec<f64>>,
}

pub(super) fn dimless(
    alpha: f64,
    wn: f64,
    gmc: f64,
    gmb: f64,
    zeta: f64,
    conv: DampingConvention,
) -> Structure {
    Structure::from_dimensionless(
        &Dimensionless {
            omega_n_over_p: wn,
            alpha,
            gamma_mc: gmc,
            gamma_mb: gmb,
            gamma_ib: 1.0,
            zeta,
            damping: conv,
        },
        None,
    )
    .expect("valid structure")
}

/// Exact impact times of the rigid point-mass block (α, from rest at θ0, Housner's e = cos 2α).
fn housner_impacts(alpha: f64, theta0: f64, t_end: f64) -> Vec<f64> {
    use rocking_verification::{housner_next_amplitude, housner_quarter_period};
    let e = (2.0 * alpha).cos();
    let mut th = theta0;
    let mut t = housner_quarter_period(alpha, th);
    let mut out = Vec::new();
    while t < t_end && out.len() < 40 {
        out.push(t);
        th = housner_next_amplitude(alpha, e, th);
        t += 2.0 * housner_quarter_period(alpha, th);
    }
    out
}

/// The setup of a scene of `scenes/` with overrides, through `rocking-scene` (the paper's cases
/// are typed once, in their scene files).
fn scene(file: &str, sets: &[String]) -> Result<rocking_scene::setup::Setup> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../scenes")
        .join(file);
    let sc = rocking_scene::scene::load(&path, sets).map_err(|e| e.to_string())?;
    Ok(rocking_scene::setup::build(&sc).map_err(|e| e.to_string())?)
}

pub fn cases(quick: bool) -> Result<Vec<Case>> {
    let fb = DampingConvention::FixedBase;
    let mut v = Vec::new();
    let fig3_scene = scene("fig3-vvel.toml", &[])?;
    let (fig3, fig3_pulse) = (fig3_scene.structure, fig3_scene.excitation);
    for (name, impact) in [
        ("fig3-vvel", ImpactModel::Vvel),
        ("fig3-adjex", ImpactModel::Adjex),
    ] {
        if quick && name == "fig3-adjex" {
            continue;
        }
        v.push(Case {
            name,
            class: Class::Standard,
            title: format!(
                "Fig. 3 ({}): point mass, ω_n/p = 11.9, α = 0.2, ζ = 0.005; sine ω_p/p = 5.1, a_p/(g tan α) = 1.30; τ ≤ 8",
                if name.ends_with("vvel") { "VVEL" } else { "ADJex" }
            ),
            structure: fig3,
            effects: Effects::default(),
            motion: fig3_pulse.clone(),
            impact,
            t_end: 8.0,
            initial: Initial::default(),
            slice: None,
            exact_impacts: None,
        });
    }
    let t5 = 2.0 * PI / 4.0 + 20.0;
    for (name, wn) in [
        ("fig5-flexible", 5.0),
        ("fig5-stiff", 20.0),
        ("near-rigid", 200.0),
    ] {
        if quick && name != "fig5-flexible" {
            continue;
        }
        let fig5 = scene(
            "fig5-flexible.toml",
            &[format!("structure.omega_n_over_p={wn:?}")],
        )?;
        v.push(Case {
            name,
            class: Class::Standard,
            title: format!(
                "{}: γ_mc = 1, γ_mb = 2, γ_Ib = 1, α = 0.1, ζ = 0.005 fixed-base, ω_n/p = {wn}; sine ω_p/p = 4, a_p/(g tan α) = 3; VVEL; τ ≤ pulse + 20",
                match name { "fig5-flexible" => "Fig. 5 flexible", "fig5-stiff" => "Fig. 5 stiff", _ => "Near-rigid column" }
            ),
            structure: fig5.structure,
            effects: Effects::default(),
            motion: fig5.excitation,
            impact: ImpactModel::Vvel,
            t_end: t5,
            initial: Initial::default(),
            slice: None,
            exact_impacts: None,
        });
    }
    // Rigid point-mass block in free rocking from θ0 = α/2, Housner's rule: exact impact times.
    let (alpha, t_rigid) = (0.2, 22.0);
    v.push(Case {
        name: "rigid-free",
        class: Class::Standard,
        title: "Rigid block (point mass, α = 0.2) in free rocking from θ0 = α/2, Housner's impact rule; τ ≤ 22".into(),
        structure: dimless(alpha, 11.9, 0.0, 0.0, 0.0, fb),
        effects: Effects { flexibility: false, ..Effects::default() },
        motion: Excitation::None,
        impact: ImpactModel::Housner,
        t_end: t_rigid,
        initial: Initial { theta: 0.5 * alpha, ..Initial::default() },
        slice: None,
        exact_impacts: Some(housner_impacts(alpha, 0.5 * alpha, t_rigid)),
    });
    if !quick {
        // 123 m wind turbine under El Centro 1940 NS × 3: the scene's structure, record and end.
        let turbine = scene("wind-turbine-elcentro.toml", &[])?;
        let (structure, t_end) = (turbine.structure, turbine.options.t_end);
        v.push(Case {
            name: "elcentro-turbine",
            class: Class::Standard,
            title: "123 m wind turbine (H = 120 m, B = 6 m, T_n ≈ 4.5 s, SI units) under El Centro 1940 NS × 3; VVEL; record + 10/p".into(),
            structure,
            effects: Effects::default(),
            motion: turbine.excitation,
            impact: ImpactModel::Vvel,
            t_end,
            initial: Initial::default(),
            slice: None,
            exact_impacts: None,
        });
        // The same turbine under a long record with many impacts: an IDA run of
        // wind-turbine-ida.toml that amplifies errors (bench/NOTES.md). The records live beside the
        // repository (../shared/data); without them the case is left out, and says so.
        let record = format!("{LONG_RECORD_DIR}/{LONG_RECORD}");
        if Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../scenes")
            .join(&record)
            .is_file()
        {
            let sets = [
                format!("excitation.path={record}"),
                format!("excitation.scale={LONG_RECORD_SCALE}"),
            ];
            let ida = scene("wind-turbine-ida.toml", &sets)?;
            v.push(Case {
                name: "long-record",
                class: Class::Standard,
                title: format!("The turbine of `elcentro-turbine` under {LONG_RECORD} × {LONG_RECORD_SCALE} (28 s, ~147 impacts; an IDA run of scenes/wind-turbine-ida.toml); VVEL; record + 10/p"),
                structure: ida.structure,
                effects: Effects::default(),
                motion: ida.excitation,
                impact: ImpactModel::Vvel,
                t_end: ida.options.t_end,
                initial: Initial::default(),
                slice: None,
                exact_impacts: None,
            });
        } else {
            eprintln!("rocking-bench: {record} (relative to scenes/) not found: case long-record left out");
        }
    }
    // The hard classes (measured per class; the presets are not chosen on them). A long record
    // with hundreds of impacts: scenes/many-impacts.toml, its record beside the repository.
    match scene("many-impacts.toml", &[]) {
        Ok(many) => v.push(Case {
            name: "many-impacts",
            class: Class::ManyImpacts,
            title: "ARL360 (Northridge 1994) × 8: cubic column, α = 0.1, ω_n/p = 80, γ_mc = γ_mb = 1, ζ = 0.02, Housner's rule, 836 impacts; record + 10/p (scenes/many-impacts.toml)".into(),
            structure: many.structure,
            effects: many.effects,
            motion: many.excitation,
            impact: many.options.impact,
            t_end: many.options.t_end,
            initial: Initial::default(),
            slice: None,
            exact_impacts: None,
        }),
        Err(e) => eprintln!("rocking-bench: case many-impacts left out: {e}"),
    }
    if !quick {
        // Fig. 5's flexible column with a restitution of 1: it chatters through ~450,000 impacts,
        // most of them tiny, until the rest rule ends it near τ = 110 (bench/NOTES.md).
        let sets = [
            "effects.impact={restitution=1.0}".to_string(),
            "solver.after_excitation=120".to_string(),
        ];
        let chatter = scene("fig5-flexible.toml", &sets)?;
        v.push(Case {
            name: "chatter",
            class: Class::Chatter,
            title: "Fig. 5 flexible (ω_n/p = 5, α = 0.1) with a restitution of 1: sine ω_p/p = 4, a_p/(g tan α) = 3; ~450,000 impacts until the rest rule ends the chatter near τ = 110; τ ≤ pulse + 120".into(),
            structure: chatter.structure,
            effects: chatter.effects,
            motion: chatter.excitation,
            impact: chatter.options.impact,
            t_end: chatter.options.t_end,
            initial: Initial::default(),
            slice: None,
            exact_impacts: None,
        });
    }
    // A column of the Fig-8 spectrum: the overturning boundary at ω_p/p = 4.
    let n = if quick { 12 } else { 40 };
    let amps: Vec<f64> = (0..n)
        .map(|k| 1.0 + 19.0 * k as f64 / (n - 1) as f64)
        .collect();
    v.push(Case {
        name: "spectrum-slice",
        class: Class::Standard,
        title: format!(
            "Fig-8 spectrum column: γ_mb = γ_mc = 2, ω_n/p = 5, α = 0.1, uplifted ζ = 0.01; sine ω_p/p = 4, a_p/(g tan α) = 1..20 ({n} cells); τ ≤ pulse + 20"
        ),
        structure: scene("spectra/fig8.toml", &[])?.structure,
        effects: Effects::default(),
        motion: Excitation::None,
        impact: ImpactModel::Vvel,
        t_end: 2.0 * PI / 4.0 + 20.0,
        initial: Initial::default(),
        slice: Some((4.0, amps)),
        exact_impacts: None,
    });
    Ok(v)
}

impl Case {
    /// The motions of the case (one, or one per cell of a slice).
    pub(super) fn motions(&self) -> Vec<Excitation> {
        match &self.slice {
            None => vec![self.motion.clone()],
            Some((wp, amps)) => {
                let ta = self.structure.derived().alpha.tan();
                amps.iter()
                    .map(|a| SinePulse::new(a * ta, *wp).into())
                    .collect()
            }
        }
    }

    pub(super) fn options(&self, acc: Accuracy, diagnostic: bool) -> Options {
        Options {
            accuracy: acc,
            impact: self.impact,
            t_end: self.t_end,
            energy: diagnostic,
            event_log: diagnostic,
            history: if diagnostic {
                History::Steps
            } else {
                History::None
            },
            // Timings are for the whole simulated duration, like the peers (no early stop).
            stop_when_known: false,
            // The peers compute no section forces; a spectrum's cells skip them too.
            forces: false,
            // Nor the largest top deflection: the answers compared hold max θ/α, not max |u|.
            max_deflection: false,
            initial: self.initial,
            ..Options::default()
        }
    }
}

/// The case as the SciPy peer needs it.
pub(super) fn case_json(case: &Case, variant: &str, reduced: &Structure) -> Value {
    let d = reduced.derived();
    let rigid = !case.effects.flexibility;
    let motion = |m: &Excitation| -> Value {
        match m {
            Excitation::None => json!({"kind": "none"}),
            Excitation::Sine(s) => {
                json!({"kind": "sine", "amplitude": s.amplitude, "omega": s.omega, "start": s.start})
            }
            Excitation::Record(r) => json!({"kind": "record", "dt": r.dt(),
                "samples": r.samples().iter().map(|x| x * r.scale()).collect::<Vec<f64>>()}),
            _ => json!({"kind": "unsupported"}),
        }
    };
    json!({
        "name": case.name,
        "variant": variant,
        "params": params_of(variant, reduced),
        "alpha": d.alpha, "p": d.p, "omega_n": d.omega_n, "e_ref": d.e_ref,
        "u_scale": if rigid { 1.0 } else { d.u_cr },
        "ud_scale": if rigid { 1.0 } else { d.u_cr * d.omega_n },
        "impact": ImpactModel::name(case.impact),
        "t_end": case.t_end,
        "initial": [case.initial.theta, case.initial.u, case.initial.theta_dot, case.initial.u_dot],
        "rest_rate": Options::default().rest_rate,
        "overturn_angle": Options::default().overturn_angle,
        "motions": case.motions().iter().map(motion).collect::<Vec<_>>(),
        "amplitudes": case.slice.as_ref().map(|(_, a)| a.clone()),
    })
}
