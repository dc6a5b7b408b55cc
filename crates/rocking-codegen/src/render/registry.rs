//! The registry of every variant (`generated/src/kernels/mod.rs`): the variant list, the models
//! with their parameters and roles, the shared indices and the layouts.

use std::collections::{BTreeMap, BTreeSet};

use serde::Serialize;

use super::indices::{index_entries, IndexFn};
use super::text::{camel_case, float_literal, one_line, str_lit};
use super::variant::{check_variant_name, DERIVED_DAMPING};
use super::{render_template, MOD_TEMPLATE};
use crate::ir::Ir;
use crate::layout::{self, SizedType};
use crate::{Error, Result};

/// Lints silenced on every generated variant module (declared in `mod.rs`).
const ALLOWED_LINTS: &[&str] = &[
    "clippy::all",
    "clippy::pedantic",
    "clippy::nursery",
    "unused_parens",
    "unused_variables",
    "non_snake_case",
    "missing_docs",
];

#[derive(Serialize)]
struct ModEntry {
    module: String,
    camel: String,
    name_lit: String,
    title: String,
    title_lit: String,
    model_lit: String,
    removed: Vec<String>,
    rigid: bool,
    small_angle: bool,
    /// Number of deformation coordinates.
    nq: usize,
    /// Its `layout::nq<n>` module.
    group: String,
    /// The associated types of its `crate::Layout`.
    types: Vec<SizedType>,
    /// The names of its `structure` outputs, as literals.
    structure_names: Vec<String>,
}

#[derive(Serialize)]
struct ParamEntry {
    name_lit: String,
    doc_lit: String,
    default: String,
    role: String,
}

#[derive(Serialize)]
struct ModelEntry {
    name_lit: String,
    description_lit: String,
    shape_lit: String,
    coordinates: usize,
    full_lit: String,
    variants: Vec<String>,
    params: Vec<ParamEntry>,
}

#[derive(Serialize)]
struct ModView {
    header: String,
    allow: Vec<String>,
    variants: Vec<ModEntry>,
    /// The `VARIANTS` array on one line, when rustfmt would keep it there.
    variants_inline: String,
    models: Vec<ModelEntry>,
    max_params: usize,
    index: Vec<IndexFn>,
    layouts: Vec<layout::Group>,
}

/// The Rust expression of a parameter's role (`crate::Role`).
fn role_expr(origin: &str, p: &crate::ir::Param) -> Result<String> {
    let kind = |k: &str| match k {
        "column" => Ok("Column"),
        "lumped" => Ok("Lumped"),
        "base" => Ok("Base"),
        other => Err(Error::invalid(
            origin,
            format!("param {:?}: unknown mass kind {other:?}", p.name),
        )),
    };
    if let Some(kind) = &p.derived {
        if kind != DERIVED_DAMPING || p.mass.is_some() || p.inertia_of.is_some() {
            return Err(Error::invalid(
                origin,
                format!(
                    "param {:?}: a derived parameter of kind {kind:?} has no role",
                    p.name
                ),
            ));
        }
        return Ok("crate::Role::ModalDamping".to_string());
    }
    Ok(match (&p.mass, &p.inertia_of, &p.height_of) {
        (Some(k), None, None) => format!(
            "crate::Role::Mass {{ kind: crate::MassKind::{}, removable: {} }}",
            kind(k)?,
            p.removable
        ),
        (None, Some(of), None) => format!("crate::Role::InertiaOf({})", str_lit(of)),
        (None, None, Some(of)) => format!("crate::Role::HeightOf({})", str_lit(of)),
        (None, None, None) => "crate::Role::Other".to_string(),
        _ => {
            return Err(Error::invalid(
                origin,
                format!("param {:?}: more than one role", p.name),
            ))
        }
    })
}

/// The models of the variants (sorted by name), each with its parameters, which must be the
/// same in every variant of the model.
fn model_entries(sorted: &[&Ir]) -> Result<Vec<ModelEntry>> {
    let mut by_model: BTreeMap<&str, Vec<&Ir>> = BTreeMap::new();
    for ir in sorted {
        by_model.entry(ir.model.as_str()).or_default().push(ir);
    }
    let mut out = Vec::new();
    for (name, irs) in by_model {
        let first = irs[0];
        for ir in &irs[1..] {
            if ir.coordinates != first.coordinates {
                return Err(Error::invalid(
                    &ir.origin(),
                    format!(
                        "variant {:?} of model {name:?} has {} deformation coordinates, {:?} {}",
                        ir.variant, ir.coordinates, first.variant, first.coordinates
                    ),
                ));
            }
            if ir.params != first.params {
                return Err(Error::invalid(
                    &ir.origin(),
                    format!(
                        "variant {:?} of model {name:?} has other parameters than {:?}",
                        ir.variant, first.variant
                    ),
                ));
            }
        }
        // The variant that runs the model as it is: nothing removed, flexible, exact angles.
        let full = irs
            .iter()
            .find(|ir| ir.removed.is_empty() && !ir.rigid && !ir.small_angle)
            .unwrap_or(&first);
        let params = first
            .params
            .iter()
            .map(|p| {
                Ok(ParamEntry {
                    name_lit: str_lit(&p.name),
                    doc_lit: str_lit(&one_line(&p.doc)),
                    default: match p.default {
                        Some(v) => format!("Some({})", float_literal(v.0)),
                        None => "None".to_string(),
                    },
                    role: role_expr(&first.origin(), p)?,
                })
            })
            .collect::<Result<Vec<_>>>()?;
        out.push(ModelEntry {
            name_lit: str_lit(name),
            description_lit: str_lit(&one_line(&first.model_description)),
            shape_lit: str_lit(&one_line(&first.shape)),
            coordinates: first.coordinates,
            full_lit: str_lit(&full.variant),
            variants: irs.iter().map(|ir| str_lit(&ir.variant)).collect(),
            params,
        });
    }
    Ok(out)
}

/// Renders `generated/src/kernels/mod.rs` declaring every variant (sorted by name).
pub fn render_mod(irs: &[Ir]) -> Result<String> {
    let mut sorted: Vec<&Ir> = irs.iter().collect();
    sorted.sort_by(|a, b| a.variant.cmp(&b.variant));
    let mut seen = BTreeSet::new();
    let mut seen_camel = BTreeSet::new();
    for ir in &sorted {
        check_variant_name(&ir.origin(), ir)?;
        if !seen.insert(ir.variant.as_str()) || !seen_camel.insert(camel_case(&ir.variant)) {
            return Err(Error::invalid(
                &ir.origin(),
                format!("variant name {:?} is used twice", ir.variant),
            ));
        }
    }
    let versions: BTreeSet<&str> = sorted.iter().map(|ir| ir.casadi.as_str()).collect();
    let versions = versions.into_iter().collect::<Vec<_>>().join(", ");
    let header = if versions.is_empty() {
        "//! @generated by `cargo xtask regen` from derive/rocking_derive. Do not edit.".to_string()
    } else {
        format!(
            "//! @generated by `cargo xtask regen` from derive/rocking_derive (CasADi {versions}). Do not edit."
        )
    };
    let inline = sorted
        .iter()
        .map(|ir| format!("({0}::NAME, {0}::TITLE)", ir.variant))
        .collect::<Vec<_>>()
        .join(", ");
    // Mirror rustfmt's layout (array_width = 60, max_width = 100) so `cargo fmt`
    // leaves this file alone.
    let single = format!("pub const VARIANTS: &[(&str, &str)] = &[{inline}];");
    let variants_inline = if sorted.is_empty() {
        " ".to_string()
    } else if inline.len() + 2 <= 60 && single.len() <= 100 {
        inline
    } else {
        String::new()
    };
    let view = ModView {
        header,
        allow: ALLOWED_LINTS.iter().map(ToString::to_string).collect(),
        variants_inline,
        models: model_entries(&sorted)?,
        max_params: sorted.iter().map(|ir| ir.params.len()).max().unwrap_or(0),
        // Today's indices: common to the variants of one coordinate (the layouts of several
        // coordinates are in `layout::nq<n>::index`).
        index: index_entries(
            &sorted
                .iter()
                .copied()
                .filter(|ir| ir.coordinates == 1)
                .collect::<Vec<_>>(),
        )?,
        layouts: layout::groups(&sorted)?,
        variants: sorted
            .iter()
            .map(|ir| -> Result<ModEntry> {
                Ok(ModEntry {
                    module: ir.variant.clone(),
                    camel: camel_case(&ir.variant),
                    name_lit: str_lit(&ir.variant),
                    title: one_line(&ir.title),
                    title_lit: str_lit(&one_line(&ir.title)),
                    model_lit: str_lit(&ir.model),
                    removed: ir.removed.iter().map(|n| str_lit(n)).collect(),
                    rigid: ir.rigid,
                    small_angle: ir.small_angle,
                    nq: ir.coordinates,
                    group: layout::group_name(ir.coordinates),
                    types: layout::types(ir)?,
                    structure_names: layout::structure_names(ir),
                })
            })
            .collect::<Result<_>>()?,
    };
    render_template(
        "mod.rs",
        MOD_TEMPLATE,
        &view,
        "generated/src/kernels/mod.rs",
    )
}
