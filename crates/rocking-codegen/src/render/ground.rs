//! The ground's module (`generated/src/ground.rs`): model-independent kernels of one parameter
//! vector.

use serde::Serialize;

use super::indices::{index_consts, IndexConst};
use super::text::{one_line, str_lit};
use super::variant::{module_header, render_functions, FnView};
use super::{render_template, GROUND_TEMPLATE};
use crate::ir::Ir;
use crate::Result;

#[derive(Serialize)]
struct GroundView {
    header: Vec<String>,
    np: usize,
    param_names: Vec<String>,
    param_table: Vec<String>,
    param_consts: Vec<IndexConst>,
    functions: Vec<FnView>,
    needs_sign: bool,
}

/// Renders `generated/src/ground.rs`: the ground's model-independent kernels (issue 44), free
/// functions of one parameter vector, without a `Variant` (their IR is
/// `generated/ir/ground/ground.json`).
pub fn render_ground(ir: &Ir) -> Result<String> {
    let origin = ir.origin();
    let header = module_header(ir, &ir.variant);
    let mut param_table = vec![
        "/// | # | name | meaning |".to_string(),
        "/// |---|------|---------|".to_string(),
    ];
    for (k, p) in ir.params.iter().enumerate() {
        param_table.push(format!(
            "/// | {k} | `{}` | {} |",
            p.name,
            one_line(&p.doc).replace('|', "\\|")
        ));
    }
    let names: Vec<String> = ir.params.iter().map(|p| p.name.clone()).collect();
    let param_docs: Vec<String> = ir
        .params
        .iter()
        .map(|p| format!("Index of `{}`: {}", p.name, one_line(&p.doc)))
        .collect();
    let param_consts = index_consts(&origin, "params", &names, &param_docs)?;
    let (functions, needs_sign) = render_functions(&origin, ir)?;
    let view = GroundView {
        header,
        np: ir.params.len(),
        param_names: names.iter().map(|n| str_lit(n)).collect(),
        param_table,
        param_consts,
        functions,
        needs_sign,
    };
    render_template("ground.rs", GROUND_TEMPLATE, &view, &origin)
}
