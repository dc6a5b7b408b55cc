//! Turns IR into the view models fed to the Tera templates.
//!
//! All text that depends on the IR (expressions, signatures, doc lines) is built here,
//! so the templates only do layout.

use std::collections::{BTreeMap, BTreeSet};

use serde::Serialize;

use crate::ir::{Function, Input, Instruction, Ir};
use crate::layout::{self, SizedType};
use crate::{Error, Result};

const VARIANT_TEMPLATE: &str = include_str!("../templates/variant.rs.tera");
const MOD_TEMPLATE: &str = include_str!("../templates/mod.rs.tera");
const GROUND_TEMPLATE: &str = include_str!("../templates/ground.rs.tera");

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

/// Names the generator reserves inside a variant module.
const RESERVED_FN_NAMES: &[&str] = &["params", "param", "call", "casadi_sign"];
const RESERVED_INPUT_NAMES: &[&str] = &["casadi_sign", "phys"];

const RUST_KEYWORDS: &[&str] = &[
    "as", "async", "await", "break", "const", "continue", "crate", "dyn", "else", "enum", "extern",
    "false", "fn", "for", "gen", "if", "impl", "in", "let", "loop", "match", "mod", "move", "mut",
    "pub", "ref", "return", "self", "Self", "static", "struct", "super", "trait", "true", "type",
    "unsafe", "use", "where", "while", "abstract", "become", "box", "do", "final", "macro",
    "override", "priv", "try", "typeof", "unsized", "virtual", "yield",
];

fn tera_for(name: &str, source: &str, origin: &str) -> Result<tera::Tera> {
    let mut tera = tera::Tera::default();
    tera.autoescape_on(Vec::new());
    tera.add_raw_template(name, source)
        .map_err(|e| Error::template(origin, &e))?;
    Ok(tera)
}

pub(crate) fn render_template<T: Serialize>(
    name: &str,
    source: &str,
    view: &T,
    origin: &str,
) -> Result<String> {
    let tera = tera_for(name, source, origin)?;
    let ctx = tera::Context::from_serialize(view).map_err(|e| Error::template(origin, &e))?;
    let text = tera
        .render(name, &ctx)
        .map_err(|e| Error::template(origin, &e))?;
    Ok(tidy(&text))
}

/// Strips trailing whitespace, collapses runs of blank lines and ends with one newline.
fn tidy(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut blank = 0;
    for line in text.lines() {
        let line = line.trim_end();
        if line.is_empty() {
            blank += 1;
            if blank > 1 {
                continue;
            }
        } else {
            blank = 0;
        }
        out.push_str(line);
        out.push('\n');
    }
    while out.ends_with("\n\n") {
        out.pop();
    }
    out
}

/// Formats an `f64` as a Rust expression that evaluates to exactly that value:
/// the shortest round-trip representation, always with a `.` or an exponent
/// (`3.0`, `0.375`, `1e-20`, `-0.0`), or `f64::INFINITY`, `f64::NEG_INFINITY`, `f64::NAN`.
pub fn float_literal(v: f64) -> String {
    if v.is_nan() {
        return "f64::NAN".to_string();
    }
    if v.is_infinite() {
        return if v > 0.0 {
            "f64::INFINITY".to_string()
        } else {
            "f64::NEG_INFINITY".to_string()
        };
    }
    let s = format!("{v:?}");
    if s.contains(['.', 'e', 'E']) {
        s
    } else {
        format!("{s}.0")
    }
}

/// `snake_case` → `CamelCase` (`full` → `Full`, `rigid_base` → `RigidBase`).
pub fn camel_case(name: &str) -> String {
    let mut out = String::new();
    for part in name.split('_').filter(|p| !p.is_empty()) {
        let mut chars = part.chars();
        if let Some(c) = chars.next() {
            out.extend(c.to_uppercase());
            out.push_str(chars.as_str());
        }
    }
    out
}

fn is_ident(s: &str) -> bool {
    let mut chars = s.chars();
    matches!(chars.next(), Some(c) if c == '_' || c.is_ascii_alphabetic())
        && chars.all(|c| c == '_' || c.is_ascii_alphanumeric())
        && s != "_"
        && !RUST_KEYWORDS.contains(&s)
}

fn is_work_var_name(s: &str) -> bool {
    let mut chars = s.chars();
    matches!(chars.next(), Some('w' | 'o')) && s.len() > 1 && chars.all(|c| c.is_ascii_digit())
}

pub(crate) fn str_lit(s: &str) -> String {
    format!("{s:?}")
}

/// Doc-comment lines (`prefix` + text) for a markdown block; blank lines kept.
fn doc_lines(prefix: &str, text: &str) -> Vec<String> {
    let text = text.trim();
    if text.is_empty() {
        return Vec::new();
    }
    text.lines()
        .map(|l| {
            let l = l.trim_end();
            if l.is_empty() {
                prefix.to_string()
            } else {
                format!("{prefix} {l}")
            }
        })
        .collect()
}

/// Single-line text (no newlines), for list items and table cells.
fn one_line(text: &str) -> String {
    text.split_whitespace().collect::<Vec<_>>().join(" ")
}

fn code_list(items: &[String]) -> String {
    if items.is_empty() {
        "(none)".to_string()
    } else {
        items
            .iter()
            .map(|e| format!("`{e}`"))
            .collect::<Vec<_>>()
            .join(", ")
    }
}

/// An array expression: on one line when short, else one element per line.
fn array_lines(values: &[String]) -> Vec<String> {
    let one = format!("[{}]", values.join(", "));
    if one.len() <= 60 {
        vec![one]
    } else {
        let mut lines = vec!["[".to_string()];
        lines.extend(values.iter().map(|v| format!("    {v},")));
        lines.push("]".to_string());
        lines
    }
}

#[derive(Serialize)]
pub(crate) struct IndexConst {
    name: String,
    index: usize,
    doc: String,
}

fn index_consts(
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
    name: String,
    doc: String,
    consts: Vec<IndexConst>,
}

#[derive(Serialize)]
struct FnView {
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

/// How an operation is written in Rust.
enum OpForm {
    /// Unary, `{0}` is the argument.
    Unary(&'static str),
    /// Binary, `{0}` and `{1}` are the arguments.
    Binary(&'static str),
}

fn op_form(op: &str) -> Option<OpForm> {
    use OpForm::{Binary, Unary};
    Some(match op {
        "assign" => Unary("{0}"),
        "neg" => Unary("-{0}"),
        "sq" => Unary("{0} * {0}"),
        "twice" => Unary("2.0 * {0}"),
        "inv" => Unary("1.0 / {0}"),
        "sqrt" => Unary("{0}.sqrt()"),
        "sin" => Unary("{0}.sin()"),
        "cos" => Unary("{0}.cos()"),
        "tan" => Unary("{0}.tan()"),
        "asin" => Unary("{0}.asin()"),
        "acos" => Unary("{0}.acos()"),
        "atan" => Unary("{0}.atan()"),
        "sinh" => Unary("{0}.sinh()"),
        "cosh" => Unary("{0}.cosh()"),
        "tanh" => Unary("{0}.tanh()"),
        "asinh" => Unary("{0}.asinh()"),
        "acosh" => Unary("{0}.acosh()"),
        "atanh" => Unary("{0}.atanh()"),
        "exp" => Unary("{0}.exp()"),
        "expm1" => Unary("{0}.exp_m1()"),
        "log" => Unary("{0}.ln()"),
        "log1p" => Unary("{0}.ln_1p()"),
        "fabs" => Unary("{0}.abs()"),
        "floor" => Unary("{0}.floor()"),
        "ceil" => Unary("{0}.ceil()"),
        "sign" => Unary("casadi_sign({0})"),
        "not" => Unary("if {0} == 0.0 { 1.0 } else { 0.0 }"),
        "add" => Binary("{0} + {1}"),
        "sub" => Binary("{0} - {1}"),
        "mul" => Binary("{0} * {1}"),
        "div" => Binary("{0} / {1}"),
        "fmod" => Binary("{0} % {1}"),
        "pow" => Binary("{0}.powf({1})"),
        // `constpow` is special-cased (powi) when the exponent is an integral constant.
        "constpow" => Binary("{0}.powf({1})"),
        "atan2" => Binary("{0}.atan2({1})"),
        "hypot" => Binary("{0}.hypot({1})"),
        "copysign" => Binary("{0}.copysign({1})"),
        "fmin" => Binary("{0}.min({1})"),
        "fmax" => Binary("{0}.max({1})"),
        "lt" => Binary("if {0} < {1} { 1.0 } else { 0.0 }"),
        "le" => Binary("if {0} <= {1} { 1.0 } else { 0.0 }"),
        "eq" => Binary("if {0} == {1} { 1.0 } else { 0.0 }"),
        "ne" => Binary("if {0} != {1} { 1.0 } else { 0.0 }"),
        "and" => Binary("if {0} != 0.0 && {1} != 0.0 { 1.0 } else { 0.0 }"),
        "or" => Binary("if {0} != 0.0 || {1} != 0.0 { 1.0 } else { 0.0 }"),
        "if_else_zero" => Binary("if {0} != 0.0 { {1} } else { 0.0 }"),
        _ => return None,
    })
}

fn fill(form: &str, args: &[String]) -> String {
    let mut s = form.replace("{0}", &args[0]);
    if let Some(b) = args.get(1) {
        s = s.replace("{1}", b);
    }
    s
}

struct Tape {
    body: Vec<String>,
    outputs: Vec<bool>,
    inputs_used: Vec<bool>,
    ops: BTreeMap<String, usize>,
    needs_sign: bool,
}

fn render_tape(origin: &str, f: &Function) -> Result<Tape> {
    let ctx = |i: usize, msg: String| {
        Error::invalid(
            origin,
            format!("function {:?}, instruction {i}: {msg}", f.name),
        )
    };
    let n_out = f.output.elements.len();
    let mut tape = Tape {
        body: Vec::with_capacity(f.instructions.len()),
        outputs: vec![false; n_out],
        inputs_used: vec![false; f.inputs.len()],
        ops: BTreeMap::new(),
        needs_sign: false,
    };
    // Which work variables hold a value, and which hold a known constant.
    let mut defined: Vec<bool> = Vec::new();
    let mut consts: Vec<Option<f64>> = Vec::new();
    fn set(defined: &mut Vec<bool>, consts: &mut Vec<Option<f64>>, w: usize, c: Option<f64>) {
        if defined.len() <= w {
            defined.resize(w + 1, false);
            consts.resize(w + 1, None);
        }
        defined[w] = true;
        consts[w] = c;
    }
    let read = |defined: &Vec<bool>, i: usize, w: usize| -> Result<String> {
        if defined.get(w).copied().unwrap_or(false) {
            Ok(format!("w{w}"))
        } else {
            Err(ctx(
                i,
                format!("work variable w{w} is read before it is written"),
            ))
        }
    };
    for (i, ins) in f.instructions.iter().enumerate() {
        match ins {
            Instruction::Input {
                dest,
                input,
                element,
            } => {
                let inp: &Input = f.inputs.get(*input).ok_or_else(|| {
                    ctx(
                        i,
                        format!("input {input} out of range ({} inputs)", f.inputs.len()),
                    )
                })?;
                let name = inp.elements.get(*element).ok_or_else(|| {
                    ctx(
                        i,
                        format!(
                            "element {element} of input {:?} out of range ({} elements)",
                            inp.name,
                            inp.elements.len()
                        ),
                    )
                })?;
                tape.inputs_used[*input] = true;
                let expr = if inp.scalar {
                    inp.name.clone()
                } else {
                    format!("{}[{element}]", inp.name)
                };
                tape.body.push(format!("let w{dest} = {expr}; // {name}"));
                set(&mut defined, &mut consts, *dest, None);
            }
            Instruction::Const { dest, value } => {
                tape.body
                    .push(format!("let w{dest}: f64 = {};", float_literal(*value)));
                set(&mut defined, &mut consts, *dest, Some(*value));
            }
            Instruction::Output { element, src } => {
                if *element >= n_out {
                    return Err(ctx(
                        i,
                        format!("output element {element} out of range ({n_out} elements)"),
                    ));
                }
                let v = read(&defined, i, *src)?;
                tape.outputs[*element] = true;
                tape.body.push(format!(
                    "let o{element} = {v}; // {}",
                    f.output.elements[*element]
                ));
            }
            Instruction::Op { op, dest, args } => {
                let form = op_form(op).ok_or_else(|| ctx(i, format!("unknown op {op:?}")))?;
                let (arity, pattern) = match form {
                    OpForm::Unary(p) => (1, p),
                    OpForm::Binary(p) => (2, p),
                };
                if args.len() != arity {
                    return Err(ctx(
                        i,
                        format!("op {op:?} takes {arity} argument(s), found {}", args.len()),
                    ));
                }
                let names = args
                    .iter()
                    .map(|&a| read(&defined, i, a))
                    .collect::<Result<Vec<_>>>()?;
                let expr = match op.as_str() {
                    "constpow" => match consts.get(args[1]).copied().flatten() {
                        Some(e) if e.fract() == 0.0 && e.abs() <= f64::from(i32::MAX - 1) => {
                            // Integral exponent: exact conversion guarded above.
                            #[allow(clippy::cast_possible_truncation)]
                            let n = e as i32;
                            format!("{}.powi({n})", names[0])
                        }
                        _ => fill(pattern, &names),
                    },
                    _ => fill(pattern, &names),
                };
                if op == "sign" {
                    tape.needs_sign = true;
                }
                let c = if op == "assign" {
                    consts.get(args[0]).copied().flatten()
                } else {
                    None
                };
                *tape.ops.entry(op.clone()).or_insert(0) += 1;
                tape.body.push(format!("let w{dest} = {expr};"));
                set(&mut defined, &mut consts, *dest, c);
            }
        }
    }
    Ok(tape)
}

fn operations_line(ops: &BTreeMap<String, usize>) -> String {
    let counted: Vec<(&String, &usize)> = ops.iter().filter(|(k, _)| *k != "assign").collect();
    let total: usize = counted.iter().map(|(_, n)| **n).sum();
    let mut sorted = counted;
    sorted.sort_by(|a, b| b.1.cmp(a.1).then_with(|| a.0.cmp(b.0)));
    let detail = sorted
        .iter()
        .map(|(k, n)| format!("{n} {k}"))
        .collect::<Vec<_>>()
        .join(", ");
    if detail.is_empty() {
        format!("Operations: {total}")
    } else {
        format!("Operations: {total} ({detail})")
    }
}

/// Every function of `ir`, rendered (names must be unique), and whether any reads the sign.
fn render_functions(origin: &str, ir: &Ir) -> Result<(Vec<FnView>, bool)> {
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

fn check_variant_name(origin: &str, ir: &Ir) -> Result<()> {
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
const DERIVED_DAMPING: &str = "modal_damping";

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

/// Renders the module `generated/src/kernels/<variant>.rs` for one IR document.
pub fn render_variant(ir: &Ir) -> Result<String> {
    let origin = ir.origin();
    check_variant_name(&origin, ir)?;

    let mut header = vec![format!(
        "//! @generated by `cargo xtask regen` from derive/rocking_derive (CasADi {}): model {}, variant {}. Do not edit.",
        ir.casadi, ir.model, ir.variant
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
    let mut header = vec![format!(
        "//! @generated by `cargo xtask regen` from derive/rocking_derive (CasADi {}): {}. Do not edit.",
        ir.casadi, ir.variant
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
pub(crate) struct IndexFn {
    name: String,
    doc: String,
    consts: Vec<IndexConst>,
    input_mods: Vec<InputMod>,
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn literals() {
        assert_eq!(float_literal(0.375), "0.375");
        assert_eq!(float_literal(1e-20), "1e-20");
        assert_eq!(float_literal(1e300), "1e300");
        assert_eq!(float_literal(-0.0), "-0.0");
        assert_eq!(float_literal(3.0), "3.0");
        assert_eq!(float_literal(-2.5), "-2.5");
        assert_eq!(float_literal(0.1), "0.1");
        assert_eq!(float_literal(1e16), "1e16");
        assert_eq!(float_literal(f64::INFINITY), "f64::INFINITY");
        assert_eq!(float_literal(f64::NEG_INFINITY), "f64::NEG_INFINITY");
        assert_eq!(float_literal(f64::NAN), "f64::NAN");
        // Round trip through Rust's own parser.
        for v in [
            0.1,
            1.0 / 3.0,
            6.02214076e23,
            5e-324,
            f64::MAX,
            -1.7976931348623157e308,
        ] {
            let lit = float_literal(v);
            assert!(lit.contains(['.', 'e']), "{lit}");
            assert_eq!(lit.parse::<f64>().unwrap().to_bits(), v.to_bits(), "{lit}");
        }
    }

    #[test]
    fn camel() {
        assert_eq!(camel_case("full"), "Full");
        assert_eq!(camel_case("rigid_base"), "RigidBase");
        assert_eq!(camel_case("p2_linear"), "P2Linear");
    }

    #[test]
    fn tidy_collapses_blank_lines() {
        assert_eq!(tidy("a  \n\n\n\nb\n\n"), "a\n\nb\n");
    }

    #[test]
    fn identifiers() {
        assert!(is_ident("theta_dot"));
        assert!(!is_ident("fn"));
        assert!(!is_ident("2x"));
        assert!(!is_ident("a-b"));
        assert!(is_work_var_name("w12"));
        assert!(is_work_var_name("o0"));
        assert!(!is_work_var_name("w"));
        assert!(!is_work_var_name("wx"));
    }
}
