//! Labels in the paper's notation for the quantities figures share (the reported quantities and
//! the history columns have theirs in `rocking_study::report`'s lists), and for each scene key a
//! sweep may vary (one place: a new knob or model parameter gets its label here, or from the
//! registry's parameter doc).

use rocking_kernels::kernels::MODELS;

/// Dimensionless time.
pub const TAU: &str = "τ = p t";
/// Rocking angle over the slenderness.
pub const THETA_OVER_ALPHA: &str = "θ/α";
/// The largest |θ|/α of a run.
pub const MAX_THETA_OVER_ALPHA: &str = "max |θ|/α";
/// Column-top deflection over the deflection at uplift.
pub const U_OVER_UCR: &str = "u/u_cr";
/// Energy over the reference energy.
pub const E_OVER_EREF: &str = "E/E_ref";
/// Ground acceleration over the uplift acceleration of the rigid block.
pub const UG_OVER_G_TAN_ALPHA: &str = "ü_g/(g tan α)";
/// The fraction of the runs that overturned (a batch, a one-axis sweep).
pub const FRACTION_OVERTURNED: &str = "fraction overturned";
/// A record's scale factor.
pub use crate::knob::SCALE_FACTOR;

/// The label of a scene key a sweep varies: the paper's notation for the keys of the format; for
/// a parameter a model adds (`structure.m_a`), its name and the registry's doc; else the key.
pub fn axis_label(key: &str) -> String {
    if let Some(label) = crate::knob::label(key) {
        return label.to_string();
    }
    key.strip_prefix("structure.")
        .and_then(|name| {
            MODELS
                .iter()
                .flat_map(|m| m.extra_params())
                .find(|p| p.name == name)
        })
        .map(|p| format!("{} ({})", p.name, p.doc))
        .unwrap_or_else(|| key.to_string())
}

/// `label = value` for a title or a legend, with the value in short form.
pub fn axis_value(key: &str, value: f64) -> String {
    format!("{} = {}", axis_label(key), short(value))
}

/// A number in at most 4 significant digits, without trailing zeros.
fn short(v: f64) -> String {
    if v == 0.0 {
        return "0".into();
    }
    if v.abs() >= 1e5 || v.abs() < 1e-3 {
        return format!("{v:.3e}");
    }
    let s = format!("{v:.4}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    s.to_string()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_knob_key_has_a_label_in_the_papers_notation() {
        for key in crate::knob::number_keys().chain(crate::knob::text_keys()) {
            assert_ne!(axis_label(key), key, "{key} has no label");
        }
        assert_eq!(axis_label("excitation.omega_p_over_p"), "ω_p/p");
        assert_eq!(axis_label("excitation.amplitude"), "a_p/(g tan α)");
        assert_eq!(axis_value("structure.omega_n_over_p", 2.5), "ω_n/p = 2.5");
    }

    #[test]
    fn a_model_parameter_is_labelled_from_the_registry() {
        let (model, p) = MODELS
            .iter()
            .find_map(|m| m.extra_params().next().map(|p| (m, p)))
            .expect("a model that adds a parameter");
        let label = axis_label(&format!("structure.{}", p.name));
        assert!(
            label.contains(p.doc),
            "{} of {}: {label}",
            p.name,
            model.name
        );
    }
}
