//! The module of one kernel variant (`generated/src/kernels/<variant>.rs`): its parameters and
//! functions.

use std::collections::BTreeSet;

use serde::Serialize;

use super::indices::{index_consts, IndexConst, InputMod};
use super::tape::{operations_line, render_tape};
use super::text::{
    array_lines, camel_case, code_list, doc_lines, float_literal, is_ident, is_work_var_name,
    one_line, str_lit,
};
use super::{render_template, VARIANT_TEMPLATE};
use crate::ir::{Function, Input, Ir};
use crate::{Error, Result};

/// Names the generator reserves inside a variant module.
const RESERVED_FN_NAMES: &[&str] = &["params", "param", "call", "casadi_sign"];
const RESERVED_INPUT_NAMES: &[&str] = &["casadi_sign", "phys"];

#[derive(Serialize)]
pub(super) struct FnView {
    name: String,
    doc: Vec<String>,
    /// Arguments of the free function (unused ones prefixed with `_`).
    args: String,
    /// Arguments of the trait method (never prefixed).
    trait_args: String,
    /// Argument names, for forwarding.
    call_args: String,
    ret: String,
    body: Vec<String>,
    result: Vec<String>,
    output_doc: String,
    output_consts: Vec<IndexConst>,
    input_mods: Vec<InputMod>,
    /// `[a, b, c]` pattern over the dynamic inputs.
    dyn_pattern: String,
    /// Lines converting the dynamic inputs.
    dyn_convert: Vec<String>,
    dyn_result: String,
}

#[derive(Serialize)]
struct VariantView {
    header: Vec<String>,
    variant: String,
    camel: String,
    name_lit: String,
    model_lit: String,
    title_lit: String,
    title: String,
    np: usize,
    param_names: Vec<String>,
    param_table: Vec<String>,
    phys_arg: String,
    extra_arg: String,
    removed: Vec<String>,
    rigid: bool,
    small_angle: bool,
    param_body: Vec<String>,
    param_consts: Vec<IndexConst>,
    functions: Vec<FnView>,
    needs_sign: bool,
}

/// Every function of `ir`, rendered (names must be unique), and whether any reads the sign.
pub(super) fn render_functions(origin: &str, ir: &Ir) -> Result<(Vec<FnView>, bool)> {
    let mut functions = Vec::new();
    let mut needs_sign = false;
    let mut fn_names = BTreeSet::new();
    for f in &ir.functions {
        if !fn_names.insert(f.name.as_str()) {
            return Err(Error::invalid(
                origin,
                format!("duplicate function name {:?}", f.name),
            ));
        }
        let (view, sign) = render_function(origin, ir, f)?;
        needs_sign |= sign;
        functions.push(view);
    }
    Ok((functions, needs_sign))
}

fn render_function(origin: &str, ir: &Ir, f: &Function) -> Result<(FnView, bool)> {
    let err = |msg: String| Error::invalid(origin, format!("function {:?}: {msg}", f.name));
    if !is_ident(&f.name) || RESERVED_FN_NAMES.contains(&f.name.as_str()) {
        return Err(err("invalid or reserved function name".into()));
    }
    let mut seen = BTreeSet::new();
    let mut n_params_inputs = 0;
    for inp in &f.inputs {
        if !is_ident(&inp.name)
            || is_work_var_name(&inp.name)
            || RESERVED_INPUT_NAMES.contains(&inp.name.as_str())
        {
            return Err(err(format!(
                "invalid or reserved input name {:?}",
                inp.name
            )));
        }
        if !seen.insert(inp.name.as_str()) {
            return Err(err(format!("duplicate input name {:?}", inp.name)));
        }
        if inp.scalar && inp.elements.len() != 1 {
            return Err(err(format!(
                "scalar input {:?} must have exactly one element",
                inp.name
            )));
        }
        if inp.params {
            n_params_inputs += 1;
            let names: Vec<&str> = ir.params.iter().map(|p| p.name.as_str()).collect();
            let elems: Vec<&str> = inp.elements.iter().map(String::as_str).collect();
            if inp.scalar || names != elems {
                return Err(err(format!(
                    "params input {:?} must list the variant's parameters {names:?}, found {elems:?}",
                    inp.name
                )));
            }
        }
    }
    if n_params_inputs > 1 {
        return Err(err("more than one params input".into()));
    }
    let n_out = f.output.elements.len();
    if f.output.scalar && n_out != 1 {
        return Err(err("scalar output must have exactly one element".into()));
    }

    let tape = render_tape(origin, f)?;

    let arg_type = |inp: &Input| {
        if inp.params {
            "&Params".to_string()
        } else if inp.scalar {
            "f64".to_string()
        } else {
            format!("&[f64; {}]", inp.elements.len())
        }
    };
    let args = f
        .inputs
        .iter()
        .zip(&tape.inputs_used)
        .map(|(inp, used)| {
            let u = if *used { "" } else { "_" };
            format!("{u}{}: {}", inp.name, arg_type(inp))
        })
        .collect::<Vec<_>>()
        .join(", ");
    let trait_args = f
        .inputs
        .iter()
        .map(|inp| format!("{}: {}", inp.name, arg_type(inp)))
        .collect::<Vec<_>>()
        .join(", ");
    let call_args = f
        .inputs
        .iter()
        .map(|i| i.name.clone())
        .collect::<Vec<_>>()
        .join(", ");
    let ret = if f.output.scalar {
        "f64".to_string()
    } else {
        format!("[f64; {n_out}]")
    };
    let values: Vec<String> = (0..n_out)
        .map(|k| {
            if tape.outputs[k] {
                format!("o{k}")
            } else {
                "0.0".to_string()
            }
        })
        .collect();
    let result = if f.output.scalar {
        vec![values[0].clone()]
    } else {
        array_lines(&values)
    };

    // Doc comment.
    let mut doc = doc_lines("///", &f.doc);
    if !doc.is_empty() {
        doc.push("///".into());
    }
    doc.push("/// # Inputs".into());
    doc.push("///".into());
    if f.inputs.is_empty() {
        doc.push("/// (none)".into());
    }
    for inp in &f.inputs {
        let d = one_line(&inp.doc);
        let sep = if d.is_empty() { "" } else { ": " };
        doc.push(format!(
            "/// - `{}: {}`{sep}{d} — {}",
            inp.name,
            arg_type(inp),
            code_list(&inp.elements)
        ));
    }
    doc.push("///".into());
    doc.push("/// # Output".into());
    doc.push("///".into());
    let d = one_line(&f.output.doc);
    let sep = if d.is_empty() { "" } else { ": " };
    doc.push(format!(
        "/// `{}: {ret}`{sep}{d} — {}",
        f.output.name,
        code_list(&f.output.elements)
    ));
    doc.push("///".into());
    doc.push(format!("/// {}.", operations_line(&tape.ops)));

    let output_consts = index_consts(
        origin,
        &format!("function {:?}, output {:?}", f.name, f.output.name),
        &f.output.elements,
        &[],
    )?;
    let mut input_mods = Vec::new();
    for inp in f.inputs.iter().filter(|i| !i.scalar && !i.params) {
        input_mods.push(InputMod {
            name: inp.name.clone(),
            doc: format!(
                "Indices of the elements of input `{}` of [`{}()`](super::{}()).",
                inp.name, f.name, f.name
            ),
            consts: index_consts(
                origin,
                &format!("function {:?}, input {:?}", f.name, inp.name),
                &inp.elements,
                &[],
            )?,
        });
    }

    // Dynamic dispatch.
    let dyn_pattern = format!(
        "[{}]",
        f.inputs
            .iter()
            .map(|i| i.name.clone())
            .collect::<Vec<_>>()
            .join(", ")
    );
    let dyn_convert = f
        .inputs
        .iter()
        .map(|inp| {
            let n = &inp.name;
            if inp.scalar {
                format!("let {n}: f64 = match {n} {{ [v] => *v, _ => return None }};")
            } else {
                format!("let {n}: {} = (*{n}).try_into().ok()?;", arg_type(inp))
            }
        })
        .collect();
    let dyn_result = if f.output.scalar {
        format!("Some(vec![{}({call_args})])", f.name)
    } else {
        format!("Some({}({call_args}).to_vec())", f.name)
    };

    Ok((
        FnView {
            name: f.name.clone(),
            doc,
            args,
            trait_args,
            call_args,
            ret,
            body: tape.body,
            result,
            output_doc: format!(
                "Indices of the elements of the output `{}` of [`{}()`].",
                f.output.name, f.name
            ),
            output_consts,
            input_mods,
            dyn_pattern,
            dyn_convert,
            dyn_result,
        },
        tape.needs_sign,
    ))
}

pub(super) fn check_variant_name(origin: &str, ir: &Ir) -> Result<()> {
    let ok = is_ident(&ir.variant)
        && ir
            .variant
            .chars()
            .all(|c| c == '_' || c.is_ascii_lowercase() || c.is_ascii_digit())
        && ir.variant.starts_with(|c: char| c.is_ascii_lowercase())
        && ir.variant != "kernels";
    if ok {
        Ok(())
    } else {
        Err(Error::invalid(
            origin,
            format!(
                "variant name {:?} is not a snake_case module name",
                ir.variant
            ),
        ))
    }
}

/// The kind of derived parameter the renderer knows: an entry of the modal damping matrix of a
/// model with several deformation coordinates, filled by `crate::modes::fill_derived`.
pub(super) const DERIVED_DAMPING: &str = "modal_damping";

/// The body of `params_with`: the parameter array, and where some are derived from the others,
/// the hand-written function that fills them in.
fn param_body(values: &[String], derived: bool, camel: &str) -> Vec<String> {
    let mut lines = array_lines(values);
    if derived {
        lines[0] = format!("let p = {}", lines[0]);
        let last = lines.len() - 1;
        lines[last].push(';');
        lines.push(format!("crate::modes::fill_derived::<{camel}>(p, phys)"));
    }
    lines
}

/// The `//!` lines that open a generated module: what generated it from what (`what`: the
/// variant or kernel set), the IR's title and doc, and its source.
pub(super) fn module_header(ir: &Ir, what: &str) -> Vec<String> {
    let mut header = vec![format!(
        "//! @generated by `cargo xtask regen` from derive/rocking_derive (CasADi {}): {what}. Do not edit.",
        ir.casadi
    )];
    header.push("//!".into());
    header.push(format!("//! # {}", one_line(&ir.title)));
    let doc = doc_lines("//!", &ir.doc);
    if !doc.is_empty() {
        header.push("//!".into());
        header.extend(doc);
    }
    header.push("//!".into());
    header.push(format!(
        "//! Source: `{}`, generator: {}.",
        ir.source, ir.generator
    ));
    header
}

/// Renders the module `generated/src/kernels/<variant>.rs` for one IR document.
pub fn render_variant(ir: &Ir) -> Result<String> {
    let origin = ir.origin();
    check_variant_name(&origin, ir)?;

    let header = module_header(ir, &format!("model {}, variant {}", ir.model, ir.variant));

    // Parameters.
    let mut param_table = vec![
        "/// | # | name | value | meaning |".to_string(),
        "/// |---|------|-------|---------|".to_string(),
    ];
    let mut param_values = Vec::new();
    let mut uses_phys = false;
    let mut n_extra = 0;
    let mut derived = false;
    for (k, p) in ir.params.iter().enumerate() {
        let (value, source) = match (&p.physical, &p.default, &p.derived) {
            (None, None, Some(kind)) if kind == DERIVED_DAMPING => {
                derived = true;
                uses_phys = true;
                (
                    "0.0".to_string(),
                    "derived (`crate::modes::fill_derived`)".to_string(),
                )
            }
            (None, None, Some(kind)) => {
                return Err(Error::invalid(
                    &origin,
                    format!(
                        "param {:?}: unknown derived kind {kind:?} (known: {DERIVED_DAMPING:?})",
                        p.name
                    ),
                ))
            }
            (Some(field), None, None) => {
                if !is_ident(field) {
                    return Err(Error::invalid(
                        &origin,
                        format!(
                            "param {:?}: physical field {field:?} is not an identifier",
                            p.name
                        ),
                    ));
                }
                uses_phys = true;
                (format!("phys.{field}"), format!("`Physical::{field}`"))
            }
            (None, Some(v), None) => {
                let lit = float_literal(v.0);
                let value = format!("extra.get({n_extra}).copied().unwrap_or({lit})");
                n_extra += 1;
                (value, format!("`{lit}` (default)"))
            }
            _ => {
                return Err(Error::invalid(
                    &origin,
                    format!(
                    "param {:?} must have exactly one of \"physical\", \"default\" and \"derived\"",
                    p.name
                ),
                ))
            }
        };
        param_table.push(format!(
            "/// | {k} | `{}` | {source} | {} |",
            p.name,
            one_line(&p.doc).replace('|', "\\|")
        ));
        param_values.push(value);
    }
    let names: Vec<String> = ir.params.iter().map(|p| p.name.clone()).collect();
    let param_docs: Vec<String> = ir
        .params
        .iter()
        .map(|p| {
            let d = one_line(&p.doc);
            if d.is_empty() {
                format!("Index of `{}`.", p.name)
            } else {
                format!("Index of `{}`: {d}", p.name)
            }
        })
        .collect();
    let param_consts = index_consts(&origin, "params", &names, &param_docs)?;

    let (functions, needs_sign) = render_functions(&origin, ir)?;

    let view = VariantView {
        header,
        variant: ir.variant.clone(),
        camel: camel_case(&ir.variant),
        name_lit: str_lit(&ir.variant),
        model_lit: str_lit(&ir.model),
        title_lit: str_lit(&one_line(&ir.title)),
        title: one_line(&ir.title),
        np: ir.params.len(),
        param_names: names.iter().map(|n| str_lit(n)).collect(),
        param_table,
        phys_arg: if uses_phys { "phys" } else { "_phys" }.to_string(),
        extra_arg: if n_extra > 0 { "extra" } else { "_extra" }.to_string(),
        removed: ir.removed.iter().map(|n| str_lit(n)).collect(),
        rigid: ir.rigid,
        small_angle: ir.small_angle,
        param_body: param_body(&param_values, derived, &camel_case(&ir.variant)),
        param_consts,
        functions,
        needs_sign,
    };
    render_template("variant.rs", VARIANT_TEMPLATE, &view, &origin)
}
