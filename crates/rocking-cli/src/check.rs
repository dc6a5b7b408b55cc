//! `rocking check`: what a scene describes, its derived quantities and, on compliant ground,
//! the ground's statics and the small-amplitude frequencies on it (docs/ground.md), without
//! running it.

use std::path::Path;

use rocking::ground_modes::small_vibrations;
use rocking::ground_statics::statics;
use rocking_scene::models;
use rocking_scene::setup::Setup;
use rocking_scene::SceneError;
use rocking_study::report;

use crate::error::CliError;
use crate::load_base;

pub(crate) fn check(scene: &Path, set: &[String], json: bool) -> Result<(), CliError> {
    // What `run`, `spectrum`, `batch` and `ida` refuse in the scene, by their own checks.
    let base = load_base(scene, set)?;
    rocking_study::plan::check_table(&base)?;
    rocking_study::ida::check_table(&base)?;
    let m = base.model(&[])?;
    let mut derived = report::derived_json(&m)?;
    if json {
        // The column's natural frequencies (rad per unit of model time, ascending), here and
        // not in a run's summary (whose bytes the digests pin).
        let f = m.structure.frequencies();
        derived["fixed_base_frequencies"] = serde_json::json!(f.fixed_base);
        derived["uplifted_frequencies"] = serde_json::json!(f.uplifted);
        derived["fixed_base_damping_ratios"] = serde_json::json!(f.fixed_base_damping);
        derived["uplifted_damping_ratios"] = serde_json::json!(f.uplifted_damping);
        if let Some(g) = ground(&m)? {
            derived["ground"] = g;
        }
        let v = serde_json::json!({
            "scene": scene.display().to_string(),
            "model": m.structure.model().name,
            "params": models::params_json(&m.structure),
            "overrides": set,
            "kernel_variant": m.variant.name,
            "variant_reasons": m.reasons,
            "excitation": m.excitation_description,
            "t_end": m.options.t_end * m.units.p_model,
            "excitation_end": m.excitation_end * m.units.p_model,
            "derived": derived,
        });
        out!("{v}");
        return Ok(());
    }
    let d = m.structure.derived();
    let u = &m.units;
    out!("scene: {}", scene.display());
    if let Some(t) = &m.title {
        out!("title: {t}");
    }
    let model = m.structure.model();
    out!("model: {} ({})", model.name, model.description);
    out!(
        "parameters (model units): {}",
        models::params_line(&m.structure)
    );
    out!("kernel variant: {}", m.variant.name);
    for r in &m.reasons {
        out!("  because {r}");
    }
    out!("excitation: {}", m.excitation_description);
    let secs = |tau: f64| match m.structure.p_per_second() {
        Some(p) => format!(" ({:.4} s)", tau / p),
        None => String::new(),
    };
    let ex_end = m.excitation_end * u.p_model;
    out!("excitation ends at τ = {ex_end:.4}{}", secs(ex_end));
    out!(
        "simulated: τ = 0 .. {:.4}{}",
        m.options.t_end * u.p_model,
        secs(m.options.t_end * u.p_model)
    );
    out!(
        "derived quantities ({}):",
        derived["units"].as_str().unwrap_or("")
    );
    if let Some(ps) = m.structure.p_per_second() {
        out!("  p          = {:.6} (= {ps:.6} 1/s)", d.p);
    } else {
        out!("  p          = {:.6}", d.p);
    }
    out!(
        "  ω_n        = {:.6} (ω_n/p = {:.4})",
        d.omega_n,
        d.omega_n / d.p
    );
    out!("  ω_up       = {:.6}", d.omega_up);
    out!("  S          = {:.6}", d.modal_s);
    out!("  α          = {:.6} rad", d.alpha);
    out!("  u_cr       = {:.6e}", d.u_cr);
    out!(
        "  θ_cr       = {:.6} rad (θ_cr/α = {:.4})",
        d.theta_cr,
        d.theta_cr / d.alpha
    );
    out!("  E_ref      = {:.6e}", d.e_ref);
    let number = |key: &str| derived[key].as_f64().unwrap_or(f64::NAN);
    out!(
        "  static uplift threshold = {:.6} g tan α",
        number("static_uplift_over_g_tan_alpha")
    );
    out!(
        "  W          = {:.6e}, W B = {:.6e} (the base moment at uplift)",
        number("weight"),
        number("uplift_moment")
    );
    out!(
        "  M_el       = {:.6} W B at static uplift (the elastic moment; P-Δ and the shape make up the rest)",
        number("elastic_moment_at_uplift_over_wb")
    );
    if let Some(g) = ground(&m)? {
        let n = |key: &str| g[key].as_f64().unwrap_or(f64::NAN);
        out!(
            "compliant ground ({}; docs/ground.md), from its kernels:",
            g["kind"].as_str().unwrap_or("")
        );
        out!(
            "  K_v        = {:.6e} (ω_v/p = {:.4}, the vertical frequency of the whole mass)",
            n("k_v"),
            n("omega_v_over_p")
        );
        out!(
            "  v0         = {:.6e} (static settlement W / K_v; v0/B = {:.4e})",
            n("settlement"),
            n("settlement_over_b")
        );
        out!(
            "  k_θ        = {:.6e} (rotational stiffness before lift-off, dM/dθ at θ = 0; {:.4} W B per rad)",
            n("rotational_stiffness"),
            n("rotational_stiffness_over_wb")
        );
        out!(
            "  lift-off   = {:.4} W B at θ = {:.6e} rad (θ/α = {:.4e}): the first edge's moment",
            n("lift_off_moment_over_wb"),
            n("lift_off_theta"),
            n("lift_off_theta_over_alpha")
        );
        out!(
            "  mean pressure = {:.6e} (W / 2B; two springs: W / 2 per corner)",
            n("mean_pressure")
        );
        let omegas = g["frequencies_over_p"]
            .as_array()
            .cloned()
            .unwrap_or_default();
        let names = g["frequency_modes"].as_array().cloned().unwrap_or_default();
        let list: Vec<String> = omegas
            .iter()
            .zip(&names)
            .map(|(w, m)| {
                format!(
                    "{} {:.6}",
                    m.as_str().unwrap_or(""),
                    w.as_f64().unwrap_or(f64::NAN)
                )
            })
            .collect();
        out!(
            "  small-amplitude frequencies on the ground, ω/p: {}",
            list.join(", ")
        );
        out!(
            "  (linear eigenproblem in (θ, v, u) at rest; K's estimated relative error {:.1e})",
            n("stiffness_error")
        );
        out!(
            "  stiffness ratio ω_max/p = {:.4}: the highest frequency the step must follow",
            n("omega_max_over_p")
        );
    }
    Ok(())
}

/// The ground's statics and the small-amplitude frequencies on it, as JSON (`None`: the rigid
/// surface). Frequencies in the structure's time unit and over p.
fn ground(m: &Setup) -> Result<Option<serde_json::Value>, CliError> {
    let Some(g) = m.ground.as_ref() else {
        return Ok(None);
    };
    let lift = m.structure.static_uplift();
    let (w, wb) = (lift.weight, lift.moment);
    let d = m.structure.derived();
    let st = statics(g, w);
    let modes = small_vibrations(&m.structure, &m.effects, g)
        .map_err(|e| SceneError::input(format!("the small vibrations on the ground: {e}")))?;
    let mass = w / m.structure.param("g").unwrap_or(1.0);
    let omega_v = (st.k_v / mass).sqrt();
    let over_p: Vec<f64> = modes.omega.iter().map(|w| w / d.p).collect();
    let omega_max = over_p.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    Ok(Some(serde_json::json!({
        "kind": g.kind.name(),
        "k_v": st.k_v,
        "omega_v_over_p": omega_v / d.p,
        "settlement": st.settlement,
        "settlement_over_b": st.settlement / g.b,
        "rotational_stiffness": st.k_rot,
        "rotational_stiffness_over_wb": st.k_rot / wb,
        "lift_off_theta": st.lift_off.theta,
        "lift_off_theta_over_alpha": st.lift_off.theta / d.alpha,
        "lift_off_moment": st.lift_off.moment,
        "lift_off_moment_over_wb": st.lift_off.moment / wb,
        "mean_pressure": st.mean_pressure,
        "frequencies": modes.omega,
        "frequencies_over_p": over_p,
        "frequency_modes": modes.dominant.iter().map(|c| c.name()).collect::<Vec<_>>(),
        "omega_max_over_p": omega_max,
        "stiffness_error": modes.stiffness_error,
    })))
}
