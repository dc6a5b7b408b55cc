//! The summary object of a run (`--json`, summary.json, Python's `summary`): its quantities as
//! they serialize, the force maxima in SI, the ratios to the fixed-base twin, the derived
//! quantities of the structure, and the warnings of the assumptions a run breaks.

use std::path::Path;

use rocking::{ForceSummary, Summary, Time};
use serde_json::{json, Value};

use rocking_scene::setup::Setup;
use rocking_scene::SceneError;

use crate::StudyError;

use super::Report;

/// Derived quantities of the structure, for `check` and the summary. A non-finite value would be
/// written as `null`: it is an error instead (the model checks them when it is built).
pub fn derived_json(model: &Setup) -> Result<Value, SceneError> {
    let d = model.structure.derived();
    let u = &model.units;
    let lift = model.structure.static_uplift();
    let mut v = json!({
        "p": d.p,
        "p_per_second": model.structure.p_per_second(),
        "omega_n": d.omega_n,
        "omega_n_over_p": d.omega_n / d.p,
        "omega_up": d.omega_up,
        "modal_s": d.modal_s,
        "alpha": d.alpha,
        "r": d.r,
        "zeta_fixed_base": d.zeta_fixed_base,
        "zeta_uplifted": d.zeta_uplifted,
        "u_cr": d.u_cr,
        "theta_cr": d.theta_cr,
        "e_ref": d.e_ref,
        "static_uplift_over_g_tan_alpha":
            model.structure.static_uplift_acceleration() / u.accel_g_tan_alpha(),
        "weight": lift.weight,
        "uplift_moment": lift.moment,
        "elastic_moment_at_uplift_over_wb": lift.elastic_moment / lift.moment,
        "units": if u.physical { "SI (s, m, kg)" } else { "model (R = g = m = 1, time τ)" },
    });
    // A scene that gives each mode its own ratio: all of them (`zeta_fixed_base` is the first's).
    let per_mode = model.structure.modal_damping_ratios();
    if per_mode.len() > 1 {
        v["zeta_fixed_base_per_mode"] = json!(per_mode);
    }
    if let Some((k, _)) = v
        .as_object()
        .into_iter()
        .flatten()
        .find(|(k, x)| x.is_null() && k.as_str() != "p_per_second")
    {
        return Err(SceneError::input(format!(
            "the derived quantity {k} is not finite: the structure's values are out of range"
        )));
    }
    Ok(v)
}

/// The summary object printed by `--json` and written to summary.json: the run's
/// [`quantities`] (with the force maxima in SI when the scene has units), with what produced it
/// (scene, model and its parameters, the `--set` overrides, title, variant and why, excitation),
/// the derived quantities and the warnings.
pub fn summary_json(
    model: &Setup,
    scene: &Path,
    overrides: &[String],
    report: &Report,
) -> Result<Value, StudyError> {
    let run = &report.run;
    let mut out = quantities(&run.summary, report.fixed_base.as_ref(), si_scale(model))?;
    out.insert("scene".into(), json!(scene.display().to_string()));
    // What produced the result: the model, its whole parameter set, and the overrides.
    out.insert("model".into(), json!(model.structure.model().name));
    out.insert(
        "params".into(),
        rocking_scene::models::params_json(&model.structure),
    );
    out.insert("overrides".into(), json!(overrides));
    out.insert("title".into(), json!(model.title));
    out.insert("variant_reasons".into(), json!(model.reasons));
    out.insert("excitation".into(), json!(model.excitation_description));
    out.insert("derived".into(), derived_json(model)?);
    let w = warnings(model, &run.summary);
    if run.summary.forces.is_some() || !w.is_empty() {
        out.insert("warnings".into(), json!(w));
    }
    Ok(Value::Object(out))
}

/// The ratios of a run's force maxima to its fixed-base twin's (rocking over fixed base).
pub const RATIOS: [&str; 2] = ["base_moment_ratio", "base_shear_ratio"];

/// The SI scale of a physical scene's forces: the uplift moment W B (N m) and the weight W (N);
/// `None` for a dimensionless scene.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SiScale {
    /// W B, N m.
    pub moment: f64,
    /// W, N.
    pub weight: f64,
}

/// The SI scale of the scene's forces, when it has physical units.
pub fn si_scale(model: &Setup) -> Option<SiScale> {
    model.units.physical.then(|| {
        let lift = model.structure.static_uplift();
        SiScale {
            moment: lift.moment,
            weight: lift.weight,
        }
    })
}

/// The keys of the force maxima in SI, which only a physical scene reports.
pub const SI_MAXIMA: [&str; 2] = ["max_base_moment_nm", "max_base_shear_n"];

/// The force maxima in SI ([`SI_MAXIMA`]) added to `out`.
fn insert_si(out: &mut serde_json::Map<String, Value>, f: &ForceSummary, si: SiScale) {
    let values = [
        f.max_base_moment_over_wb * si.moment,
        f.max_base_shear_over_w * si.weight,
    ];
    for (key, v) in SI_MAXIMA.into_iter().zip(values) {
        out.insert(key.into(), json!(v));
    }
}

/// What a run reports about itself: its [`Summary`] as it serializes (a time `*_time` as τ, with
/// `*_time_s` in seconds; an unbounded `max_required_friction` as the string `"inf"`), with
/// `si` (a physical scene) the force maxima in SI `max_base_moment_nm` and `max_base_shear_n`,
/// and with its fixed-base twin's summary the twin's force maxima (`fixed_base`, in SI too with
/// `si`) and the ratios `base_moment_ratio`, `base_shear_ratio` (rocking over fixed base; absent
/// where the twin carries no force). A sweep's cells report any numeric entry (and `"inf"`, as
/// +∞: [`number`]).
pub fn quantities(
    run: &Summary,
    twin: Option<&Summary>,
    si: Option<SiScale>,
) -> Result<serde_json::Map<String, Value>, StudyError> {
    let mut out = serde_json::Map::new();
    for (key, value) in serialized(run)? {
        if key.ends_with("_time") {
            let (tau, seconds) = match value {
                Value::Object(t) => (t["tau"].clone(), t["seconds"].clone()),
                _ => (Value::Null, Value::Null),
            };
            out.insert(format!("{key}_s"), seconds);
            out.insert(key, tau);
        } else {
            out.insert(key, value);
        }
    }
    if let (Some(f), Some(si)) = (&run.forces, si) {
        insert_si(&mut out, f, si);
    }
    if let (Some(f), Some(t)) = (&run.forces, twin) {
        if let Some(tf) = &t.forces {
            let mut fixed = serialized(tf)?;
            fixed.retain(|k, _| !k.ends_with("_time"));
            // Left out where the twin did not track it (NaN: `Options::max_deflection` off).
            if !t.max_u_over_ucr.is_nan() {
                fixed.insert("max_u_over_ucr".into(), json!(t.max_u_over_ucr));
            }
            // On compliant ground the twin is the linear foundation: its ground keys too.
            if let Some(g) = &t.ground {
                let ground = serialized(g)?.into_iter();
                fixed.extend(ground.filter(|(k, _)| !k.ends_with("_time")));
            }
            if let Some(si) = si {
                insert_si(&mut fixed, tf, si);
            }
            out.insert("fixed_base".into(), Value::Object(fixed));
            let ratios = [
                (
                    RATIOS[0],
                    f.max_base_moment_over_wb,
                    tf.max_base_moment_over_wb,
                ),
                (RATIOS[1], f.max_base_shear_over_w, tf.max_base_shear_over_w),
            ];
            for (key, rocking, fixed) in ratios {
                // A twin that carries no force (no excitation) has no ratio.
                if fixed > 0.0 {
                    out.insert(key.into(), json!(rocking / fixed));
                }
            }
        }
    }
    Ok(out)
}

/// The number of a reported quantity's JSON value: a number, or +∞ for the string `"inf"` (an
/// unbounded `max_required_friction`); `None` for anything else.
pub fn number(v: &Value) -> Option<f64> {
    match v {
        Value::String(s) if s == rocking::UNBOUNDED => Some(f64::INFINITY),
        v => v.as_f64().filter(|x| x.is_finite()),
    }
}

/// A serializable value as a JSON object; a non-finite number is an error naming its field.
fn serialized(v: &impl serde::Serialize) -> Result<serde_json::Map<String, Value>, StudyError> {
    let value = serde_path_to_error::serialize(v, serde_json::value::Serializer).map_err(|e| {
        StudyError::NonFinite {
            quantity: e.path().to_string(),
            detail: e.inner().to_string(),
        }
    })?;
    match value {
        Value::Object(map) => Ok(map),
        _ => unreachable!("a struct serializes to an object"),
    }
}

/// The model's assumptions that a run breaks, with the first time it does: friction and the
/// ground's pull (with the forces tracked), the bearing pressure (compliant ground).
pub fn warnings(model: &Setup, summary: &Summary) -> Vec<String> {
    let when = |t: Time| match t.seconds {
        Some(s) => format!("τ = {:.6} (t = {s:.6} s)", t.tau),
        None => format!("τ = {:.6}", t.tau),
    };
    let mut out = Vec::new();
    let bearing = summary.ground.as_ref().and_then(|g| {
        let q = model.options.bearing_over_mean?;
        Some((
            g.first_bearing_exceeded_time??,
            q,
            g.max_ground_pressure_over_mean,
        ))
    });
    if let Some((t, q, max)) = bearing {
        out.push(format!(
            "the pressure under the base exceeds the bearing pressure ({q:.4} times the mean) \
             first at {}: the ground would yield there, which the model does not include (max \
             pressure {max:.4} times the mean)",
            when(t),
        ));
    }
    let Some(f) = &summary.forces else {
        return out;
    };
    if let (Some(t), Some(mu)) = (f.first_slip_time, model.options.friction) {
        // Unbounded once R_v < 0 (the lift-off warning below says when).
        let max = if f.max_required_friction.is_finite() {
            format!("{:.4}", f.max_required_friction)
        } else {
            "unbounded, as R_v falls below zero".to_string()
        };
        out.push(format!(
            "the required friction |R_h|/R_v exceeds the ground's friction {mu} first at {}: \
             the structure would slide there, which the model does not include (max required \
             friction {max})",
            when(t),
        ));
    }
    if let Some(t) = f.first_lift_off_time {
        out.push(format!(
            "the vertical reaction R_v falls below zero first at {} (min R_v/W = {:.4}): the \
             ground would have to pull, the structure would jump there, which the model does not \
             include; no friction holds it there (max required friction unbounded)",
            when(t),
            f.min_vertical_reaction_over_w
        ));
    }
    out
}
