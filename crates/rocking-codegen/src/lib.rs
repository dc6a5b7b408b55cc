//! Renders the intermediate form produced by the symbolic derivation
//! (`derive/rocking_derive`, one JSON file per kernel variant in `generated/ir/`)
//! into the Rust modules of the `rocking-kernels` crate (`generated/src/kernels/`).
//!
//! The output is deterministic (no maps with unspecified order, no timestamps) and is
//! laid out by the templates themselves: the generated variant modules are not run
//! through rustfmt.
//!
//! Entry points: [`render_variant`], [`render_mod`] and [`render_all`].
//!
//! It owns how the IR becomes Rust (templates, the Taylor-mode tape); it must not know any
//! equation, model or variant by name: everything it renders comes from the IR.

mod error;
pub mod ir;
mod layout;
mod render;
mod simplify;
mod taylor;

use std::collections::BTreeMap;
use std::path::Path;

pub use error::{Error, Result};
pub use ir::{load_dir, Float, Function, Golden, Input, Instruction, Ir, Output, Param};
pub use render::{camel_case, float_literal, render_ground, render_mod, render_variant};
pub use taylor::{render_taylor, render_taylor_ground, render_taylor_mod, TAYLOR_DIR};

/// Directory of the IR files, relative to the repository root.
pub const IR_DIR: &str = "generated/ir";
/// Directory of the rendered kernel modules, relative to the repository root.
pub const KERNELS_DIR: &str = "generated/src/kernels";
/// The ground's IR (model-independent kernels, issue 44), relative to the repository root.
pub const GROUND_IR: &str = "generated/ir/ground/ground.json";
/// The ground's rendered module, relative to the repository root.
pub const GROUND_RS: &str = "generated/src/ground.rs";

/// Renders every `*.json` IR file of `ir_dir`.
///
/// Returns the contents of every rendered file keyed by its path relative to the
/// repository root, with `/` separators (`generated/src/kernels/<variant>.rs`,
/// `generated/src/kernels/mod.rs` and their Taylor-mode twins in `generated/src/taylor/`, and
/// `generated/src/ground.rs` from `ground/ground.json` when there is one).
pub fn render_all(ir_dir: &Path) -> Result<BTreeMap<String, String>> {
    let irs = load_dir(ir_dir)?;
    let mut out = BTreeMap::new();
    for ir in &irs {
        let origin = ir.origin();
        let stem = Path::new(&origin)
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_default();
        if stem != ir.variant {
            return Err(Error::invalid(
                &origin,
                format!(
                    "variant {:?} must be stored in a file named {:?}",
                    ir.variant,
                    format!("{}.json", ir.variant)
                ),
            ));
        }
        let path = format!("{KERNELS_DIR}/{}.rs", ir.variant);
        out.insert(path, render_variant(ir)?);
    }
    out.insert(format!("{KERNELS_DIR}/mod.rs"), render_mod(&irs)?);
    for ir in &irs {
        out.insert(
            format!("{TAYLOR_DIR}/{}.rs", ir.variant),
            render_taylor(ir)?,
        );
    }
    // The ground's kernels, when the IR directory has them (`ground/ground.json`).
    let path = ir_dir.join("ground").join("ground.json");
    let ground = if path.is_file() {
        Some(Ir::load(&path)?)
    } else {
        None
    };
    if let Some(ground) = &ground {
        out.insert(GROUND_RS.to_string(), render_ground(ground)?);
        out.insert(
            format!("{TAYLOR_DIR}/{}.rs", ground.variant),
            render_taylor_ground(ground)?,
        );
    }
    let taylor: Vec<&Ir> = irs.iter().chain(&ground).collect();
    out.insert(format!("{TAYLOR_DIR}/mod.rs"), render_taylor_mod(&taylor)?);
    Ok(out)
}
