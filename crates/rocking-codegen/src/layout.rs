//! The sizes of a variant's kernel arrays, which follow from its number of deformation
//! coordinates n (`"coordinates"` in the IR): each variant's implementation of the hand-written
//! trait `crate::Layout` (its associated array types), and the modules `layout::nq<n>` of
//! `generated/src/kernels/mod.rs` (the sizes as constants, for const-generic code, with the named
//! indices common to the variants with n coordinates).

use std::collections::BTreeMap;

use serde::Serialize;

use crate::ir::Ir;
use crate::render::indices::{index_entries, IndexFn};
use crate::render::text::str_lit;
use crate::{Error, Result};

/// Where an associated type of `Layout` takes its size.
enum Part {
    /// An input, by its name (the same size in every function that takes it).
    Input(&'static str),
    /// The output of a function, by the function's name.
    Output(&'static str),
}

/// The associated types of `crate::Layout` (generated/src/lib.rs declares the same ones), each
/// with the name of its size constant in `layout::nq<n>`.
const TYPES: &[(&str, &str, Part)] = &[
    ("Q", "Q", Part::Input("q")),
    ("X", "X", Part::Input("x")),
    ("Xc", "XC", Part::Input("xc")),
    ("Xi", "XI", Part::Input("xi")),
    ("MassMatrix", "MASS_MATRIX", Part::Output("mass_matrix")),
    ("Forcing", "FORCING", Part::Output("forcing")),
    ("ImpactVvel", "IMPACT_VVEL", Part::Output("impact_vvel")),
    ("ImpactAdjex", "IMPACT_ADJEX", Part::Output("impact_adjex")),
    (
        "ImpactHousner",
        "IMPACT_HOUSNER",
        Part::Output("impact_housner"),
    ),
    ("Structure", "STRUCTURE", Part::Output("structure")),
    ("Shape", "SHAPE", Part::Output("shape")),
    (
        "StaticUplift",
        "STATIC_UPLIFT",
        Part::Output("static_uplift"),
    ),
    ("Qf", "QF", Part::Input("qf")),
    ("Y", "Y", Part::Input("y")),
    (
        "FreeMassMatrix",
        "FREE_MASS_MATRIX",
        Part::Output("free_mass_matrix"),
    ),
];

/// The function whose output names `Layout::STRUCTURE` lists (for code generic over the number
/// of coordinates, which finds the reference quantities by name).
const NAMED_OUTPUT: &str = "structure";

/// One associated type of a variant's `Layout`.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub(crate) struct SizedType {
    /// The associated type's name.
    pub name: String,
    /// The name of its size constant.
    pub konst: String,
    /// Its number of `f64`.
    pub len: usize,
    /// The Rust type: `[f64; len]`, or `f64` for a scalar output.
    pub ty: String,
}

/// The associated types of `ir`'s `Layout`: those whose input or function the variant has.
pub(crate) fn types(ir: &Ir) -> Result<Vec<SizedType>> {
    let origin = ir.origin();
    let mut out = Vec::new();
    for (name, konst, part) in TYPES {
        let (len, scalar) = match part {
            Part::Input(input) => {
                let mut lens = ir
                    .functions
                    .iter()
                    .flat_map(|f| f.inputs.iter())
                    .filter(|i| i.name == *input)
                    .map(|i| (i.elements.len(), i.scalar));
                let Some(first) = lens.next() else { continue };
                if first.1 || lens.any(|l| l != first) {
                    return Err(Error::invalid(
                        &origin,
                        format!("input {input:?} must be an array of one size in every function"),
                    ));
                }
                first
            }
            Part::Output(function) => {
                let Some(f) = ir.functions.iter().find(|f| f.name == *function) else {
                    continue;
                };
                (f.output.elements.len(), f.output.scalar)
            }
        };
        out.push(SizedType {
            name: (*name).to_string(),
            konst: (*konst).to_string(),
            len,
            ty: if scalar {
                "f64".to_string()
            } else {
                format!("[f64; {len}]")
            },
        });
    }
    Ok(out)
}

/// The names of the outputs of `ir`'s `structure` function, as string literals (none without it).
pub(crate) fn structure_names(ir: &Ir) -> Vec<String> {
    ir.functions
        .iter()
        .find(|f| f.name == NAMED_OUTPUT)
        .map(|f| f.output.elements.iter().map(|e| str_lit(e)).collect())
        .unwrap_or_default()
}

/// The module name of the variants with `n` coordinates.
pub(crate) fn group_name(n: usize) -> String {
    format!("nq{n}")
}

/// The module `layout::nq<n>`: the sizes and the named indices of the variants with `n`
/// coordinates.
#[derive(Serialize)]
pub(crate) struct Group {
    name: String,
    nq: usize,
    sizes: Vec<SizedType>,
    /// One coordinate: the indices are `kernels::index` (re-exported, not rendered again).
    reexport: bool,
    index: Vec<IndexFn>,
}

/// The groups of `sorted` by number of coordinates, ascending. Every variant of a group must
/// have the same sizes.
pub(crate) fn groups(sorted: &[&Ir]) -> Result<Vec<Group>> {
    let mut by_n: BTreeMap<usize, Vec<&Ir>> = BTreeMap::new();
    for ir in sorted {
        by_n.entry(ir.coordinates).or_default().push(ir);
    }
    let mut out = Vec::new();
    for (n, irs) in by_n {
        let sizes = types(irs[0])?;
        for ir in &irs[1..] {
            if types(ir)? != sizes {
                return Err(Error::invalid(
                    &ir.origin(),
                    format!(
                        "variant {:?} has other array sizes than {:?}, which has as many \
                         coordinates ({n})",
                        ir.variant, irs[0].variant
                    ),
                ));
            }
        }
        out.push(Group {
            name: group_name(n),
            nq: n,
            sizes,
            reexport: n == 1,
            index: if n == 1 {
                Vec::new()
            } else {
                index_entries(&irs)?
            },
        });
    }
    Ok(out)
}
