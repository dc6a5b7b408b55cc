//! `rocking models` and the Python package's `models()`: every generated model, its variants,
//! parameters and effect switches, read from the registry the derivation generates (nothing here
//! names a model).

use rocking::ModelInfo;
use rocking_kernels::{kernels::MODELS, Role, VariantInfo};

/// What a variant removes or fixes, in words.
fn specialisation(v: &VariantInfo) -> String {
    let mut what = Vec::new();
    if !v.removed.is_empty() {
        what.push(format!("{} = 0", v.removed.join(" = ")));
    }
    if v.rigid {
        what.push("rigid column (u = 0)".to_string());
    }
    if v.small_angle {
        what.push("small angles".to_string());
    }
    if what.is_empty() {
        "nothing removed: the model as it is".to_string()
    } else {
        what.join(", ")
    }
}

fn role(r: Role) -> String {
    match r {
        Role::Other => String::new(),
        Role::Mass { kind, removable } => format!(
            " [{} mass{}]",
            format!("{kind:?}").to_lowercase(),
            if removable { ", switch" } else { "" }
        ),
        Role::InertiaOf(m) => format!(" [inertia of {m}]"),
        Role::HeightOf(m) => format!(" [height of {m}, fraction of H]"),
        Role::ModalDamping => " [modal damping, derived from zeta]".to_string(),
    }
}

fn model_text(m: &ModelInfo) -> String {
    let mut out = format!(
        "model \"{}\": {}\n  shape: {}\n",
        m.name, m.description, m.shape
    );
    out.push_str(
        "  variants (the solver picks the most specialised one that runs a scene exactly):\n",
    );
    for v in m.variant_infos() {
        out.push_str(&format!("    {:<16} {}\n", v.name, specialisation(v)));
    }
    out.push_str(
        "  parameters ([structure] keys; the physical form in SI, or in R = g = m = 1 units):\n",
    );
    for p in m.params {
        let default = p
            .default
            .map(|d| format!(" (default {d})"))
            .unwrap_or_default();
        out.push_str(&format!(
            "    {:<6} {}{default}{}\n",
            p.name,
            p.doc,
            role(p.role)
        ));
    }
    let switches: Vec<&str> = m.removable_masses().collect();
    out.push_str(&format!(
        "  effect switches ([effects], default true): flexibility, damping, large_rotations, {}\n",
        switches.join(", ")
    ));
    out
}

/// The listing of every model, then the excitation kinds and impact models a scene may name.
pub fn text() -> String {
    let mut out = MODELS.iter().map(model_text).collect::<Vec<_>>().join("\n");
    out.push_str("\nexcitation kinds ([excitation] kind):\n");
    for k in crate::excitation::KINDS {
        let keys = if k.keys.is_empty() {
            "no other key".to_string()
        } else {
            k.keys.join(", ")
        };
        out.push_str(&format!("  {:<13} {} (keys: {keys})\n", k.name, k.doc));
    }
    out.push_str("\nimpact models ([effects] impact):\n");
    for m in rocking::ImpactModel::NAMED {
        out.push_str(&format!("  {:<13} {}\n", m.name(), m.doc()));
    }
    out.push_str(&format!(
        "  {:<13} {}\n",
        "{ restitution = r }",
        rocking::ImpactModel::Restitution(0.0).doc()
    ));
    out
}

/// The listing as JSON.
pub fn json() -> serde_json::Value {
    let models: Vec<serde_json::Value> = MODELS
        .iter()
        .map(|m| {
            serde_json::json!({
                "name": m.name,
                "description": m.description,
                "shape": m.shape,
                "full_variant": m.full,
                "variants": m.variant_infos().map(|v| serde_json::json!({
                    "name": v.name, "title": v.title, "removed": v.removed,
                    "rigid": v.rigid, "small_angle": v.small_angle,
                })).collect::<Vec<_>>(),
                "params": m.params.iter().map(|p| serde_json::json!({
                    "name": p.name, "doc": p.doc, "default": p.default,
                    "role": role(p.role).trim().trim_matches(['[', ']']).to_string(),
                })).collect::<Vec<_>>(),
                "effect_switches": m.removable_masses().collect::<Vec<_>>(),
            })
        })
        .collect();
    let kinds: Vec<serde_json::Value> = crate::excitation::KINDS
        .iter()
        .map(|k| serde_json::json!({ "name": k.name, "doc": k.doc, "keys": k.keys }))
        .collect();
    let impacts: Vec<serde_json::Value> = rocking::ImpactModel::NAMED
        .iter()
        .chain(&[rocking::ImpactModel::Restitution(0.0)])
        .map(|m| serde_json::json!({ "name": m.name(), "doc": m.doc() }))
        .collect();
    serde_json::json!({ "models": models, "excitation_kinds": kinds, "impact_models": impacts })
}

/// The structure's whole parameter set in model units, by name, in the model's order.
pub fn params_json(s: &rocking::Structure) -> serde_json::Value {
    let mut map = serde_json::Map::new();
    for p in s.model().params {
        map.insert(p.name.to_string(), serde_json::json!(s.param(p.name)));
    }
    serde_json::Value::Object(map)
}

/// The structure's whole parameter set, `name = value`, in the model's order.
pub fn params_line(s: &rocking::Structure) -> String {
    s.model()
        .params
        .iter()
        .map(|p| format!("{} = {:.6}", p.name, s.param(p.name).unwrap_or(f64::NAN)))
        .collect::<Vec<_>>()
        .join(", ")
}
