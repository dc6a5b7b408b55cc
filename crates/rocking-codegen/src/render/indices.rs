//! Named indices: the constants that name the elements of a kernel's inputs and outputs, per
//! variant and, where every variant of a group agrees, shared (`kernels::index`, `layout::nq<n>`).

use std::collections::BTreeSet;

use serde::Serialize;

use super::text::is_ident;
use crate::ir::{Function, Ir};
use crate::{Error, Result};

#[derive(Serialize)]
pub(crate) struct IndexConst {
    name: String,
    index: usize,
    doc: String,
}

pub(super) fn index_consts(
    origin: &str,
    what: &str,
    names: &[String],
    docs: &[String],
) -> Result<Vec<IndexConst>> {
    let mut seen = BTreeSet::new();
    names
        .iter()
        .enumerate()
        .map(|(index, name)| {
            if !is_ident(name) {
                return Err(Error::invalid(
                    origin,
                    format!("{what}: element name {name:?} is not a valid identifier"),
                ));
            }
            let upper = name.to_uppercase();
            if !seen.insert(upper.clone()) {
                return Err(Error::invalid(
                    origin,
                    format!("{what}: duplicate element name {name:?}"),
                ));
            }
            Ok(IndexConst {
                name: upper,
                index,
                doc: docs
                    .get(index)
                    .cloned()
                    .unwrap_or_else(|| format!("Index of `{name}`.")),
            })
        })
        .collect()
}

#[derive(Serialize)]
pub(crate) struct InputMod {
    pub(super) name: String,
    pub(super) doc: String,
    pub(super) consts: Vec<IndexConst>,
}

#[derive(Serialize)]
pub(crate) struct IndexFn {
    name: String,
    doc: String,
    consts: Vec<IndexConst>,
    input_mods: Vec<InputMod>,
}

/// Named indices of the functions every variant of `sorted` exports with the same inputs and
/// outputs.
pub(crate) fn index_entries(sorted: &[&Ir]) -> Result<Vec<IndexFn>> {
    let Some(first) = sorted.first() else {
        return Ok(Vec::new());
    };
    let layout = |f: &Function| {
        (
            // The parameter vector differs between models; its indices are per variant.
            f.inputs
                .iter()
                .map(|i| {
                    (
                        i.name.clone(),
                        if i.params {
                            Vec::new()
                        } else {
                            i.elements.clone()
                        },
                    )
                })
                .collect::<Vec<_>>(),
            f.output.elements.clone(),
        )
    };
    let mut out = Vec::new();
    for f in &first.functions {
        let same = sorted.iter().all(|ir| {
            ir.functions
                .iter()
                .any(|g| g.name == f.name && layout(g) == layout(f))
        });
        if !same {
            continue;
        }
        let origin = first.origin();
        let mut input_mods = Vec::new();
        for inp in f.inputs.iter().filter(|i| !i.scalar && !i.params) {
            input_mods.push(InputMod {
                name: inp.name.clone(),
                doc: format!("Indices of the elements of input `{}`.", inp.name),
                consts: index_consts(&origin, &f.name, &inp.elements, &[])?,
            });
        }
        out.push(IndexFn {
            name: f.name.clone(),
            doc: format!(
                "Indices of the output `{}` of `{}` (and of its inputs).",
                f.output.name, f.name
            ),
            consts: index_consts(&origin, &f.name, &f.output.elements, &[])?,
            input_mods,
        });
    }
    Ok(out)
}
