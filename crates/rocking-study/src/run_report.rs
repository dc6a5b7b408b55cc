//! What a run reports, as the `rocking` command writes it and the Python package returns it:
//! the summary object (`--json`, summary.json), the derived quantities, history.csv and
//! events.csv. One implementation, so that both print the same numbers.

use std::fmt::Write as _;
use std::path::Path;

use rocking::Run;
use serde_json::{json, Value};

use rocking_scene::setup::Setup;
use rocking_scene::SceneError;

/// Runs a built scene with the command's error messages: bad options are input errors, a
/// guard that stops a run names the scene settings that bound it.
pub fn simulate(m: &Setup, scene: &Path) -> Result<Run, SceneError> {
    rocking::simulate(&m.structure, &m.excitation, &m.effects, &m.options).map_err(|e| {
        if e.is_invalid_input() {
            SceneError::input(format!("{}: {e}", scene.display()))
        } else if e.is_guard() {
            SceneError::failure(format!(
                "{}: simulation stopped: {e}; both limits are scene settings: `max_steps` and \
                 `max_events` in [solver] (defaults {} and {})",
                scene.display(),
                rocking_scene::limits::short(rocking::Options::default().max_steps as f64),
                rocking_scene::limits::short(rocking::Options::default().max_events as f64)
            ))
        } else {
            SceneError::failure(format!("{}: simulation failed: {e}", scene.display()))
        }
    })
}

fn finite(name: &str, x: f64) -> Result<f64, SceneError> {
    if x.is_finite() {
        Ok(x)
    } else {
        Err(SceneError::failure(format!(
            "the run produced a non-finite {name} ({x}); no results written"
        )))
    }
}

/// Derived quantities of the structure, for `check` and the summary. A non-finite value would be
/// written as `null`: it is an error instead (the model checks them when it is built).
pub fn derived_json(model: &Setup) -> Result<Value, SceneError> {
    let d = model.structure.derived();
    let u = &model.units;
    let v = json!({
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
        "units": if u.physical { "SI (s, m, kg)" } else { "model (R = g = m = 1, time τ)" },
    });
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
/// [`Summary`](rocking::Summary) as it serializes (a time `*_time` as τ and `*_time_s` in seconds),
/// with what produced it (scene, title, variant and why, excitation) and the derived quantities.
pub fn summary_json(model: &Setup, scene: &Path, run: &Run) -> Result<Value, SceneError> {
    let fields = serde_path_to_error::serialize(&run.summary, serde_json::value::Serializer)
        .map_err(|e| {
            SceneError::failure(format!(
                "the run produced a non-finite {}: {}; no results written",
                e.path(),
                e.inner()
            ))
        })?;
    let Value::Object(fields) = fields else {
        unreachable!("a struct serializes to an object")
    };
    let mut out = serde_json::Map::new();
    for (key, value) in fields {
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
    out.insert("scene".into(), json!(scene.display().to_string()));
    out.insert("title".into(), json!(model.title));
    out.insert("variant_reasons".into(), json!(model.reasons));
    out.insert("excitation".into(), json!(model.excitation_description));
    out.insert("derived".into(), derived_json(model)?);
    Ok(Value::Object(out))
}

fn num(out: &mut String, x: f64) -> Result<(), SceneError> {
    let x = finite("history value", x)?;
    let _ = write!(out, ",{x}");
    Ok(())
}

/// history.csv: τ, seconds (when known), normalised state, phase, energies, ground acceleration.
pub fn history_csv(model: &Setup, run: &Run) -> Result<String, SceneError> {
    let d = model.structure.derived();
    let u = &model.units;
    let ps = model.structure.p_per_second();
    let mut out = String::from(
        "tau,t_s,theta_over_alpha,u_over_ucr,theta_dot_over_alpha_p,u_dot_over_ucr_omega_n,\
         phase,e_kin_over_eref,e_total_over_eref,ug_over_g_tan_alpha\n",
    );
    for r in &run.history {
        let _ = write!(out, "{}", finite("τ", r.tau)?);
        match ps {
            Some(p) => num(&mut out, r.tau / p)?,
            None => out.push(','),
        }
        num(&mut out, r.theta / u.alpha)?;
        num(&mut out, r.u / d.u_cr)?;
        num(&mut out, r.theta_dot / (u.alpha * d.p))?;
        num(&mut out, r.u_dot / (d.u_cr * d.omega_n))?;
        let phase = serde_json::to_value(r.phase).unwrap_or(Value::Null);
        let _ = write!(out, ",{}", phase.as_str().unwrap_or("?"));
        num(&mut out, r.e_kin)?;
        num(&mut out, r.e_total)?;
        num(&mut out, r.ug / u.accel_g_tan_alpha())?;
        out.push('\n');
    }
    Ok(out)
}

/// events.csv: one row per uplift, impact, rest or overturning.
pub fn events_csv(model: &Setup, run: &Run) -> Result<String, SceneError> {
    let d = model.structure.derived();
    let u = &model.units;
    let mut out = String::from(
        "tau,t_s,kind,branch,phase_after,theta_dot_over_alpha_p,u_over_ucr,\
         u_dot_over_ucr_omega_n,e_kin_before_over_eref,e_kin_after_over_eref\n",
    );
    for e in &run.events {
        let _ = write!(out, "{}", finite("τ", e.time.tau)?);
        match e.time.seconds {
            Some(s) => num(&mut out, s)?,
            None => out.push(','),
        }
        let kind = serde_json::to_value(e.kind).unwrap_or(Value::Null);
        let phase = serde_json::to_value(e.phase_after).unwrap_or(Value::Null);
        let _ = write!(
            out,
            ",{},{},{}",
            kind.as_str().unwrap_or("?"),
            e.branch,
            phase.as_str().unwrap_or("?")
        );
        num(&mut out, e.theta_dot / (u.alpha * d.p))?;
        num(&mut out, e.u / d.u_cr)?;
        num(&mut out, e.u_dot / (d.u_cr * d.omega_n))?;
        num(&mut out, e.energy_before)?;
        num(&mut out, e.energy_after)?;
        out.push('\n');
    }
    Ok(out)
}
