//! One function of the tape in Taylor mode: the recurrences of each operation, rendered once per
//! coefficient order (see the parent module).

use std::collections::{BTreeMap, BTreeSet};

use serde::Serialize;

use super::{is_const_input, Mode};
use crate::ir::Function;
use crate::ir::Instruction;
use crate::render::text::float_literal;
use crate::simplify::check_series_op;
use crate::{Error, Result};

#[derive(Serialize)]
pub(super) struct TaylorFn {
    name: String,
    pub(super) doc: Vec<String>,
    args: String,
    ret: String,
    prelude: Vec<String>,
    loop_head: String,
    body: Vec<String>,
    result: String,
}

/// What a work variable holds.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Kind {
    /// A scalar known before the order loop (`wN: f64`).
    Const,
    /// A truncated series (`wN: [f64; N]`).
    Series,
    /// A series of which only the current order's coefficient is ever read (`let wN: f64` in
    /// the order loop).
    Coef,
}

/// Renders one function in Taylor mode, with every time-dependent variable a series when `keep`
/// is `None`, or only those in `keep`. Also returns the variables whose lower coefficients a
/// recurrence reads.
pub(super) fn render_fn(
    origin: &str,
    f: &Function,
    mode: Mode,
    keep: Option<&BTreeSet<String>>,
) -> Result<(TaylorFn, BTreeSet<String>)> {
    let err = |i: usize, msg: String| {
        Error::invalid(
            origin,
            format!("Taylor mode of {:?}, instruction {i}: {msg}", f.name),
        )
    };
    let n_out = f.output.elements.len();
    // The state input of an ODE: the first series input with as many elements as the output.
    let state = if mode == Mode::Ode {
        let k = f
            .inputs
            .iter()
            .position(|i| !is_const_input(i) && !i.scalar && i.elements.len() == n_out)
            .ok_or_else(|| {
                err(
                    0,
                    "no state input with as many elements as the output".into(),
                )
            })?;
        Some(k)
    } else {
        None
    };

    // The tape may re-assign a work variable; every assignment gets its own name here (series
    // need all their lower coefficients until the last order), `w7`, then `w7_1`, `w7_2`, ...
    let mut current: BTreeMap<usize, (String, Kind)> = BTreeMap::new();
    let mut versions: BTreeMap<usize, usize> = BTreeMap::new();
    let mut define = |current: &mut BTreeMap<usize, (String, Kind)>, w: usize, k: Kind| {
        let v = versions.entry(w).and_modify(|v| *v += 1).or_insert(0);
        let name = if *v == 0 {
            format!("w{w}")
        } else {
            format!("w{w}_{v}")
        };
        current.insert(w, (name.clone(), k));
        name
    };
    let mut prelude = Vec::new();
    let mut body = Vec::new();
    let mut history: BTreeSet<String> = BTreeSet::new();
    // A time-dependent variable: an array when its history is read, else the current coefficient.
    let series_kind = |name: &str| match keep {
        Some(keep) if !keep.contains(name) => Kind::Coef,
        _ => Kind::Series,
    };
    // The statement that sets the current coefficient of a new time-dependent variable.
    let assign = |name: &str, kind: Kind, expr: String| match kind {
        Kind::Coef => format!("let {name} = {expr};"),
        _ => format!("{name}[k] = {expr};"),
    };
    // sin/cos of the same series argument share one recurrence: argument -> (sin, cos) arrays.
    let mut trig: BTreeMap<String, (String, String)> = BTreeMap::new();
    // 1 / b[0] of each denominator b, computed at order 0: a multiplication, not a division, on
    // the path from one order to the next.
    let mut reciprocals: BTreeMap<String, String> = BTreeMap::new();
    let mut outputs: Vec<Option<(String, Kind)>> = vec![None; n_out];
    // The pairs whose sums over lower orders `series::dots` takes at the top of each order.
    let mut dot_pairs: Vec<(String, String)> = Vec::new();

    let get = |current: &BTreeMap<usize, (String, Kind)>, i: usize, w: usize| {
        current.get(&w).cloned().ok_or_else(|| {
            err(
                i,
                format!("work variable w{w} is read before it is written"),
            )
        })
    };
    // The k-th coefficient of a work variable, as an expression.
    let coef = |(name, k): &(String, Kind)| match k {
        Kind::Series => format!("{name}[k]"),
        Kind::Coef => name.clone(),
        Kind::Const => format!("at0(k, {name})"),
    };

    for (i, ins) in f.instructions.iter().enumerate() {
        match ins {
            Instruction::Input {
                dest,
                input,
                element,
            } => {
                let inp = f
                    .inputs
                    .get(*input)
                    .ok_or_else(|| err(i, format!("input {input} out of range")))?;
                let expr = if inp.scalar {
                    inp.name.clone()
                } else {
                    format!("{}[{element}]", inp.name)
                };
                if is_const_input(inp) {
                    let name = define(&mut current, *dest, Kind::Const);
                    prelude.push(format!("let {name}: f64 = {expr};"));
                } else if series_kind(&expr) == Kind::Series {
                    // The input's own coefficients, read in place: no array to zero and copy.
                    // An ODE's state row k + 1 is written after every read of order k.
                    current.insert(*dest, (expr, Kind::Series));
                } else {
                    let name = define(&mut current, *dest, Kind::Coef);
                    body.push(assign(&name, Kind::Coef, format!("{expr}[k]")));
                }
            }
            Instruction::Const { dest, value } => {
                let name = define(&mut current, *dest, Kind::Const);
                prelude.push(format!("let {name}: f64 = {};", float_literal(*value)));
            }
            Instruction::Output { element, src } => {
                let v = get(&current, i, *src)?;
                *outputs
                    .get_mut(*element)
                    .ok_or_else(|| err(i, format!("output {element} out of range")))? = Some(v);
            }
            Instruction::Op { op, dest, args } => {
                let vars = args
                    .iter()
                    .map(|&a| get(&current, i, a))
                    .collect::<Result<Vec<_>>>()?;
                let no_rule = || err(i, format!("operation {op:?} has no Taylor-mode rule"));
                if vars.iter().all(|(_, k)| *k == Kind::Const) {
                    // Constant along the step: the ordinary scalar operation, once.
                    let names: Vec<String> = vars.iter().map(|(n, _)| n.clone()).collect();
                    let expr = scalar_expr(op, &names).ok_or_else(no_rule)?;
                    let name = define(&mut current, *dest, Kind::Const);
                    prelude.push(format!("let {name}: f64 = {expr};"));
                    continue;
                }
                let (a, ka) = &vars[0];
                let ca = coef(&vars[0]);
                check_series_op(op, vars.len()).map_err(|msg| err(i, msg))?;
                // A copy of a series whose history is kept anyway (an assignment, or the sine
                // and cosine arrays of their shared recurrence) is that series, by another name.
                if op == "assign" && *ka == Kind::Series {
                    current.insert(*dest, vars[0].clone());
                    continue;
                }
                if op == "sin" || op == "cos" {
                    reads(&mut history, &[a]);
                    let (s, c) = trig.entry(a.clone()).or_insert_with(|| {
                        let id = ident(a);
                        let (s, c) = (format!("sin_{id}"), format!("cos_{id}"));
                        let da = format!("d_{id}");
                        for array in [&da, &s, &c] {
                            prelude.push(format!("let mut {array} = [0.0f64; N];"));
                        }
                        let ds = dot(&mut dot_pairs, &da, &c);
                        let dc = dot(&mut dot_pairs, &da, &s);
                        body.push(format!(
                            "series::sin_cos_d({ds}, {dc}, &{a}, &mut {da}, &mut {s}, &mut {c}, k);"
                        ));
                        (s, c)
                    });
                    let src = if op == "sin" { s.clone() } else { c.clone() };
                    current.insert(*dest, (src, Kind::Series));
                    continue;
                }
                // Named after its arguments are read: the tape may re-assign an argument's slot.
                let d = define(&mut current, *dest, Kind::Series);
                let dk = series_kind(&d);
                current.insert(*dest, (d.clone(), dk));
                let mut reads = |names: &[&String]| reads(&mut history, names);
                let set = |expr: String| assign(&d, dk, expr);
                let line = match op.as_str() {
                    "assign" => set(ca),
                    "neg" => set(format!("-{ca}")),
                    "twice" => set(format!("2.0 * {ca}")),
                    "sq" => {
                        reads(&[a]);
                        set(format!("series::sq(&{a}, k)"))
                    }
                    "sqrt" => {
                        reads(&[a, &d]);
                        format!("series::sqrt(&{a}, &mut {d}, k);")
                    }
                    "add" | "sub" => {
                        let sign = if op == "add" { '+' } else { '-' };
                        set(format!("{ca} {sign} {}", coef(&vars[1])))
                    }
                    "mul" => {
                        let (b, kb) = &vars[1];
                        let cb = coef(&vars[1]);
                        match (ka, kb) {
                            (Kind::Const, _) => set(format!("{a} * {cb}")),
                            (_, Kind::Const) => set(format!("{ca} * {b}")),
                            _ => {
                                reads(&[a, b]);
                                let sum = dot(&mut dot_pairs, a, b);
                                set(format!("series::mul_d({sum}, &{a}, &{b}, k)"))
                            }
                        }
                    }
                    "div" => {
                        let (b, kb) = &vars[1];
                        match kb {
                            Kind::Const => set(format!("{ca} / {b}")),
                            _ => {
                                reads(&[b, &d]);
                                let inv = reciprocals.entry(b.clone()).or_insert_with(|| {
                                    let inv = format!("inv_{}", ident(b));
                                    prelude.push(format!("let mut {inv} = 0.0f64;"));
                                    body.push(format!("if k == 0 {{ {inv} = 1.0 / {b}[0]; }}"));
                                    inv
                                });
                                let sum = dot(&mut dot_pairs, b, &d);
                                set(format!("series::div_d({sum}, {ca}, &{b}, &{d}, {inv}, k)"))
                            }
                        }
                    }
                    _ => return Err(no_rule()),
                };
                if dk == Kind::Series {
                    prelude.push(format!("let mut {d} = [0.0f64; N];"));
                }
                body.push(line);
            }
        }
    }

    body.splice(0..0, dots_statements(&dot_pairs));

    let mut args = Vec::new();
    // Orders: the series inputs are the closure's arguments, read at every call.
    let mut closure_args = Vec::new();
    for (j, inp) in f.inputs.iter().enumerate() {
        let ty = if inp.params {
            "&Params".to_string()
        } else if is_const_input(inp) {
            "f64".to_string()
        } else if Some(j) == state {
            format!("&mut [[f64; N]; {}]", inp.elements.len())
        } else if inp.scalar {
            "&[f64; N]".to_string()
        } else {
            format!("&[[f64; N]; {}]", inp.elements.len())
        };
        if mode == Mode::Orders && !is_const_input(inp) {
            closure_args.push((inp.name.clone(), ty));
        } else {
            args.push(format!("{}: {ty}", inp.name));
        }
    }
    let mut doc = Vec::new();
    let missing = || {
        err(
            f.instructions.len(),
            "an output element is never written".into(),
        )
    };
    let (ret, result, loop_head) = match (mode, state) {
        (Mode::Ode, Some(sj)) => {
            let x = &f.inputs[sj].name;
            // One division per order: x_{k+1} = f_k / (k + 1) for every component.
            body.push("let inv_k1 = 1.0 / (k + 1) as f64;".to_string());
            for (e, out) in outputs.iter().enumerate() {
                let out = out.as_ref().ok_or_else(missing)?;
                body.push(format!("{x}[{e}][k + 1] = {} * inv_k1;", coef(out)));
            }
            doc.push(format!(
                "/// Taylor coefficients of the solution of `{x}' = {}(..)`: on entry `{x}[i][0]` holds",
                f.name
            ));
            doc.push(format!(
                "/// the state at the expansion point; on return `{x}[i][k]` is the k-th coefficient."
            ));
            doc.push("/// Series inputs hold their first N coefficients.".to_string());
            (
                String::new(),
                String::new(),
                "for k in 0..N - 1 {".to_string(),
            )
        }
        (Mode::Orders, _) => {
            let outs = outputs
                .iter()
                .map(|o| o.as_ref().map(coef).ok_or_else(missing))
                .collect::<Result<Vec<_>>>()?;
            body.push(format!("[{}]", outs.join(", ")));
            let types: Vec<&str> = closure_args.iter().map(|(_, t)| t.as_str()).collect();
            let params: Vec<String> = closure_args
                .iter()
                .map(|(n, t)| format!("{n}: {t}"))
                .collect();
            doc.push(format!(
                "/// `{}` one Taylor order at a time: the closure called with k = 0, 1, 2, ... in turn",
                f.name
            ));
            doc.push(
                "/// (and series whose coefficients up to k are set) returns each output's k-th"
                    .to_string(),
            );
            doc.push("/// coefficient.".to_string());
            (
                format!(
                    " -> impl FnMut(usize, {}) -> [f64; {n_out}]",
                    types.join(", ")
                ),
                String::new(),
                format!("move |k: usize, {}| {{", params.join(", ")),
            )
        }
        _ => {
            prelude.push(format!("let mut out = [[0.0f64; N]; {n_out}];"));
            for (e, out) in outputs.iter().enumerate() {
                let out = out.as_ref().ok_or_else(missing)?;
                body.push(format!("out[{e}][k] = {};", coef(out)));
            }
            doc.push(format!(
                "/// The first N Taylor coefficients of each output of `{}` along series inputs.",
                f.name
            ));
            (
                format!(" -> [[f64; N]; {n_out}]"),
                "out".to_string(),
                "for k in 0..N {".to_string(),
            )
        }
    };
    let rendered = TaylorFn {
        name: f.name.clone(),
        doc,
        args: args.join(", "),
        ret,
        prelude,
        loop_head,
        body,
        result,
    };
    Ok((rendered, history))
}

/// At most this many sums in one `series::dots` loop: one SSE2 accumulator each, with room left
/// among the 16 registers for the loads (more would spill to the stack).
const DOTS_PER_LOOP: usize = 10;

/// Registers the pair `(a, b)` for the fused sums of an order and names its sum (`dot3`).
fn dot(pairs: &mut Vec<(String, String)>, a: &str, b: &str) -> String {
    pairs.push((a.to_string(), b.to_string()));
    format!("dot{}", pairs.len() - 1)
}

/// The statements at the top of an order that take every registered pair's sum over lower
/// orders, [`DOTS_PER_LOOP`] pairs per loop (the groups as even as that allows).
fn dots_statements(pairs: &[(String, String)]) -> Vec<String> {
    if pairs.is_empty() {
        return Vec::new();
    }
    let groups = pairs.len().div_ceil(DOTS_PER_LOOP);
    let size = pairs.len().div_ceil(groups);
    let mut lines = Vec::new();
    for (g, chunk) in pairs.chunks(size).enumerate() {
        let names: Vec<String> = (0..chunk.len())
            .map(|j| format!("dot{}", g * size + j))
            .collect();
        lines.push(format!("let [{}] = series::dots(", names.join(", ")));
        lines.push("    [".to_string());
        for (a, b) in chunk {
            lines.push(format!("        (&{a}, &{b}),"));
        }
        lines.push("    ],".to_string());
        lines.push("    k,".to_string());
        lines.push(");".to_string());
    }
    lines
}

/// The recurrences that read lower coefficients (of arguments, or of the result) keep them.
fn reads(history: &mut BTreeSet<String>, names: &[&String]) {
    history.extend(names.iter().map(|n| (*n).clone()));
}

/// A series' name as part of an identifier: an input read in place is `x[2]`, which gives `x2`.
fn ident(series: &str) -> String {
    series.replace(['[', ']'], "")
}

/// The scalar form of an operation on constants (the same forms as the ordinary kernels).
fn scalar_expr(op: &str, a: &[String]) -> Option<String> {
    let x = a.first()?;
    Some(match (op, a.len()) {
        ("assign", 1) => x.clone(),
        ("neg", 1) => format!("-{x}"),
        ("sq", 1) => format!("{x} * {x}"),
        ("twice", 1) => format!("2.0 * {x}"),
        ("sqrt", 1) => format!("{x}.sqrt()"),
        ("sin", 1) => format!("{x}.sin()"),
        ("cos", 1) => format!("{x}.cos()"),
        ("fabs", 1) => format!("{x}.abs()"),
        ("atan2", 2) => format!("{x}.atan2({})", a[1]),
        ("add", 2) => format!("{x} + {}", a[1]),
        ("sub", 2) => format!("{x} - {}", a[1]),
        ("mul", 2) => format!("{x} * {}", a[1]),
        ("div", 2) => format!("{x} / {}", a[1]),
        _ => return None,
    })
}
