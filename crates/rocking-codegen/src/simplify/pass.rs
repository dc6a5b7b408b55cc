//! One pass over the tape: each instruction into the builder's combinations, the outputs and the
//! nodes the nonlinear ones need evaluated, dead nodes dropped.

use std::collections::{BTreeMap, BTreeSet};

use super::builder::*;
use super::{check_series_op, live, series_products, Pass};
use crate::ir::{Function, Instruction};
use crate::{Error, Result};

pub(super) fn pass(
    origin: &str,
    f: &Function,
    is_const_input: &impl Fn(usize) -> bool,
    names: Names,
    expected: BTreeSet<u64>,
) -> Result<Pass> {
    let err = |i: usize, msg: String| {
        Error::invalid(
            origin,
            format!("Taylor mode of {:?}, instruction {i}: {msg}", f.name),
        )
    };
    let mut b = Builder {
        tape: Vec::new(),
        ops: BTreeMap::new(),
        consts: BTreeMap::new(),
        evaluated: BTreeMap::new(),
        names,
        name_of: BTreeMap::new(),
        expected,
    };
    let mut vals: BTreeMap<usize, Val> = BTreeMap::new();
    for (i, ins) in f.instructions.iter().enumerate() {
        match ins {
            Instruction::Input {
                dest,
                input,
                element,
            } => {
                let node = b.fresh();
                b.tape.push(Instruction::Input {
                    dest: node,
                    input: *input,
                    element: *element,
                });
                b.name(node, "input", vec![*input as u64, *element as u64]);
                let v = if is_const_input(*input) {
                    Val::Scalar(node)
                } else {
                    Val::Series(Lin::atom(node))
                };
                vals.insert(*dest, v);
            }
            Instruction::Const { dest, value } => {
                let n = b.constant(*value);
                vals.insert(*dest, Val::Scalar(n));
            }
            Instruction::Output { element, src } => {
                let v = vals.get(src).cloned().ok_or_else(|| {
                    err(
                        i,
                        format!("work variable w{src} is read before it is written"),
                    )
                })?;
                let n = b.node(&v);
                b.tape.push(Instruction::Output {
                    element: *element,
                    src: n,
                });
            }
            Instruction::Op { op, dest, args } => {
                let vs = args
                    .iter()
                    .map(|a| {
                        vals.get(a).cloned().ok_or_else(|| {
                            err(
                                i,
                                format!("work variable w{a} is read before it is written"),
                            )
                        })
                    })
                    .collect::<Result<Vec<_>>>()?;
                let arg = |j: usize| {
                    vs.get(j)
                        .cloned()
                        .ok_or_else(|| err(i, format!("{op:?} lacks argument {j}")))
                };
                if vs.iter().all(|v| matches!(v, Val::Scalar(_))) {
                    let nodes = vs.iter().map(|v| b.node(v)).collect();
                    vals.insert(*dest, Val::Scalar(b.op(op, nodes)));
                    continue;
                }
                check_series_op(op, vs.len()).map_err(|msg| err(i, msg))?;
                let v = match op.as_str() {
                    "assign" => arg(0)?,
                    "neg" | "twice" => {
                        let Val::Series(a) = arg(0)? else {
                            unreachable!("a series argument")
                        };
                        let c = if op == "neg" {
                            Coef {
                                neg: true,
                                var: None,
                            }
                        } else {
                            Coef {
                                neg: false,
                                var: Some(b.constant(2.0)),
                            }
                        };
                        Val::Series(b.scale(&a, c))
                    }
                    "add" | "sub" => {
                        let neg = op == "sub";
                        let lin = match (arg(0)?, arg(1)?) {
                            (Val::Series(x), Val::Series(y)) => {
                                let y = if neg {
                                    b.scale(
                                        &y,
                                        Coef {
                                            neg: true,
                                            var: None,
                                        },
                                    )
                                } else {
                                    y
                                };
                                b.add(&x, &y)
                            }
                            (Val::Series(x), Val::Scalar(s)) => b.with_offset(&x, s, neg),
                            (Val::Scalar(s), Val::Series(y)) => {
                                let y = if neg {
                                    b.scale(
                                        &y,
                                        Coef {
                                            neg: true,
                                            var: None,
                                        },
                                    )
                                } else {
                                    y
                                };
                                b.with_offset(&y, s, false)
                            }
                            (Val::Scalar(_), Val::Scalar(_)) => unreachable!("handled above"),
                        };
                        b.value(lin)
                    }
                    "mul" | "sq" => {
                        let (x, y) = if op == "sq" {
                            (arg(0)?, arg(0)?)
                        } else {
                            (arg(0)?, arg(1)?)
                        };
                        let lin = match (x, y) {
                            (Val::Series(x), Val::Series(y)) => b.mul(&x, &y),
                            (Val::Series(l), Val::Scalar(s)) | (Val::Scalar(s), Val::Series(l)) => {
                                b.scale(
                                    &l,
                                    Coef {
                                        neg: false,
                                        var: Some(s),
                                    },
                                )
                            }
                            (Val::Scalar(_), Val::Scalar(_)) => unreachable!("handled above"),
                        };
                        b.value(lin)
                    }
                    "div" => match arg(1)? {
                        Val::Scalar(s) => {
                            let Val::Series(x) = arg(0)? else {
                                unreachable!("a series numerator")
                            };
                            let inv = b.coef_inv(Coef {
                                neg: false,
                                var: Some(s),
                            });
                            Val::Series(b.scale(&x, inv))
                        }
                        Val::Series(den) => {
                            let q = b.div(&arg(0)?, &den);
                            Val::Series(q)
                        }
                    },
                    "sqrt" | "sin" | "cos" => {
                        let n = b.node(&arg(0)?);
                        Val::Series(Lin::atom(b.op(op, vec![n])))
                    }
                    _ => return Err(err(i, format!("operation {op:?} has no Taylor-mode rule"))),
                };
                vals.insert(*dest, v);
            }
        }
    }
    let function = Function {
        instructions: live(b.tape),
        ..f.clone()
    };
    let products = series_products(&function, is_const_input)
        .into_iter()
        .map(|n| b.name_of[&n])
        .collect();
    Ok(Pass {
        function,
        names: b.names,
        products,
    })
}
