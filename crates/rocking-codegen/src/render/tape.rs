//! A CasADi instruction tape as Rust statements: one `let` per instruction.

use std::collections::BTreeMap;

use super::text::float_literal;
use crate::ir::{Function, Input, Instruction};
use crate::{Error, Result};

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

/// A function's tape as Rust: its statements and what they touch.
pub(super) struct Tape {
    /// One statement per instruction.
    pub(super) body: Vec<String>,
    /// Which output elements the tape writes.
    pub(super) outputs: Vec<bool>,
    /// Which inputs the tape reads.
    pub(super) inputs_used: Vec<bool>,
    /// Operation counts, for the doc line.
    pub(super) ops: BTreeMap<String, usize>,
    /// Whether it calls `casadi_sign`.
    pub(super) needs_sign: bool,
}

pub(super) fn render_tape(origin: &str, f: &Function) -> Result<Tape> {
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

pub(super) fn operations_line(ops: &BTreeMap<String, usize>) -> String {
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
