//! Labels in the paper's notation for every quantity a figure shows: the output quantities of a
//! run or a sweep, and each scene key a sweep may vary (one place: a new knob or model parameter
//! gets its label here, or from the registry's parameter doc).

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

/// What a run reports about its forces and its fixed-base twin, in the paper's notation (M_b,
/// V_b the moment and shear at the column base, M_el the elastic moment, R_h and R_v the ground
/// reactions, W the total weight, B the half-width; on compliant ground p the pressure under the
/// base, v its settlement and v₀ the static one); the other quantities by their key.
const QUANTITIES: [(&str, &str); 14] = [
    ("max_theta_over_alpha", MAX_THETA_OVER_ALPHA),
    ("max_u_over_ucr", "max |u|/u_cr"),
    ("max_base_moment_over_wb", "max |M_b|/(W B)"),
    ("max_base_shear_over_w", "max |V_b|/W"),
    ("max_elastic_base_moment_over_wb", "max |M_el|/(W B)"),
    ("max_required_friction", "max |R_h|/R_v"),
    ("min_vertical_reaction_over_w", "min R_v/W"),
    ("base_moment_ratio", "max |M_b|, rocking / fixed base"),
    ("base_shear_ratio", "max |V_b|, rocking / fixed base"),
    ("max_ground_pressure_over_mean", "max p/(W/2B)"),
    ("min_contact_fraction", "min contact length/2B"),
    ("lift_offs", "edge lift-offs"),
    ("max_settlement_over_static", "max v/v₀"),
    ("ground_energy_dissipated", "ground dissipation/E_ref"),
];

/// The label of a quantity a run reports (a key of its summary, as a sweep's `report` names
/// it).
pub fn quantity_label(key: &str) -> &str {
    QUANTITIES
        .iter()
        .find(|(k, _)| *k == key)
        .map_or(key, |(_, label)| label)
}

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
    fn reported_quantities_are_labelled_in_the_papers_notation() {
        assert_eq!(quantity_label("max_base_moment_over_wb"), "max |M_b|/(W B)");
        assert_eq!(quantity_label("impacts"), "impacts");
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
