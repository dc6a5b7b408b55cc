//! The tape rewritten for Taylor mode: every product of two series paid for once.
//!
//! In Taylor mode a product (or quotient, square root, sine) of series costs O(k) operations
//! at order k; a sum or a constant factor costs one. A kernel's cost is therefore its number of
//! such *nonlinear* nodes, and CasADi's tape repeats them under constant factors and offsets:
//! the Fig. 3 right-hand side multiplies θ' by u as `(2θ')·(c u)`, `θ'·(c u)`, `(c θ')·u`, ...
//! This pass keeps every time-dependent value as a linear combination `Σ c_i a_i + c_0` of
//! *atoms* (series inputs and nonlinear results) with coefficients constant along the step, so:
//!
//! - constant factors and offsets are hoisted out of products, and a product of two atoms is
//!   one shared atom whatever the factors (commutative: `a b` and `b a` are one);
//! - a product of two combinations is expanded over their terms when that costs no more new
//!   atoms than multiplying the two combinations as they stand, so later products can share;
//! - a combination is evaluated (once) only where a nonlinear node or an output needs it.
//! - a zero constant (the excitation of a `_free` twin) is folded through the factors and sums
//!   it meets, so a term it multiplies vanishes, and so does a product only that term needed.
//!
//! The coefficients are scalar nodes (products and sums of parameters), computed once before
//! the order loop by the renderer, like every other constant of the tape. The result is an
//! ordinary tape of the same function, in single assignment, without dead nodes.

use std::collections::BTreeSet;

use crate::ir::{Function, Instruction};
use crate::Result;

mod builder;
mod pass;

use builder::{Names, Node};
use pass::pass;

/// Whether `op` has a Taylor-mode recurrence and takes `n` arguments (else the message).
pub(crate) fn check_series_op(op: &str, n: usize) -> std::result::Result<(), String> {
    let arity = match op {
        "add" | "sub" | "mul" | "div" => 2,
        "assign" | "neg" | "twice" | "sq" | "sqrt" | "sin" | "cos" => 1,
        _ => return Err(format!("operation {op:?} has no Taylor-mode rule")),
    };
    if n != arity {
        return Err(format!("{op:?} takes {arity} argument(s)"));
    }
    Ok(())
}

/// The tape of `f` rewritten so that every nonlinear operation on series is computed once
/// (see the module docs). `is_const_input` tells the inputs constant along a step.
///
/// Two passes: whether expanding a product pays depends on products met later in the tape (the
/// full-mass rocking right-hand side computes θ'·(a θ'u − b θ') before θ'·(θ'u) and θ'²), so the
/// second pass counts the products the first one ended up computing as free, and the pass with
/// fewer series products is kept.
pub(crate) fn simplify(
    origin: &str,
    f: &Function,
    is_const_input: impl Fn(usize) -> bool,
) -> Result<Function> {
    let first = pass(
        origin,
        f,
        &is_const_input,
        Names::default(),
        BTreeSet::new(),
    )?;
    let second = pass(origin, f, &is_const_input, first.names, first.products)?;
    let cost = |g: &Function| series_costs(g, &is_const_input).len();
    Ok(if cost(&second.function) < cost(&first.function) {
        second.function
    } else {
        first.function
    })
}

/// The outcome of one pass of [`simplify`].
struct Pass {
    function: Function,
    names: Names,
    /// Names of the series products of the rewritten tape.
    products: BTreeSet<u64>,
}

/// The nonlinear operations on series of a tape (products, squares, quotients, roots, sines),
/// one entry per instruction: those whose Taylor recurrence costs O(k) at order k.
fn series_costs(f: &Function, is_const_input: impl Fn(usize) -> bool) -> Vec<&Instruction> {
    let mut scalar: BTreeSet<Node> = BTreeSet::new();
    let mut costly = Vec::new();
    for ins in &f.instructions {
        match ins {
            Instruction::Const { dest, .. } => {
                scalar.insert(*dest);
            }
            Instruction::Input { dest, input, .. } if is_const_input(*input) => {
                scalar.insert(*dest);
            }
            Instruction::Op { op, dest, args } => {
                let series: Vec<bool> = args.iter().map(|a| !scalar.contains(a)).collect();
                if !series.contains(&true) {
                    scalar.insert(*dest);
                } else if match op.as_str() {
                    "mul" => series.iter().all(|&s| s),
                    "div" => series[1],
                    "sq" | "sqrt" | "sin" | "cos" => true,
                    _ => false,
                } {
                    costly.push(ins);
                }
            }
            _ => {}
        }
    }
    costly
}

/// The products and squares among [`series_costs`]: what expanding a product trades in.
fn series_products(f: &Function, is_const_input: impl Fn(usize) -> bool) -> Vec<Node> {
    series_costs(f, is_const_input)
        .into_iter()
        .filter_map(|ins| match ins {
            Instruction::Op { op, dest, .. } if op == "mul" || op == "sq" => Some(*dest),
            _ => None,
        })
        .collect()
}

/// The instructions an output depends on, in order (the rewrite leaves unused coefficients).
fn live(tape: Vec<Instruction>) -> Vec<Instruction> {
    let mut needed: BTreeSet<Node> = BTreeSet::new();
    let mut keep = vec![false; tape.len()];
    for (i, ins) in tape.iter().enumerate().rev() {
        match ins {
            Instruction::Output { src, .. } => {
                keep[i] = true;
                needed.insert(*src);
            }
            Instruction::Input { dest, .. } | Instruction::Const { dest, .. } => {
                keep[i] = needed.contains(dest);
            }
            Instruction::Op { dest, args, .. } => {
                if needed.contains(dest) {
                    keep[i] = true;
                    needed.extend(args.iter().copied());
                }
            }
        }
    }
    tape.into_iter()
        .zip(keep)
        .filter_map(|(ins, k)| k.then_some(ins))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ir::{Input, Output};
    use std::collections::BTreeMap;

    /// `[x0, x1]` a series input, `p` a constant one, one output.
    fn function(instructions: Vec<Instruction>) -> Function {
        let input = |name: &str, params: bool| Input {
            name: name.into(),
            doc: String::new(),
            elements: vec!["a".into(), "b".into()],
            scalar: false,
            params,
        };
        Function {
            name: "f".into(),
            doc: String::new(),
            inputs: vec![input("x", false), input("p", true)],
            output: Output {
                name: "y".into(),
                doc: String::new(),
                elements: vec!["y".into()],
                scalar: true,
            },
            instructions,
            golden: Vec::new(),
            taylor_order: None,
            taylor_golden: Vec::new(),
        }
    }

    fn op(op: &str, dest: usize, args: &[usize]) -> Instruction {
        Instruction::Op {
            op: op.into(),
            dest,
            args: args.to_vec(),
        }
    }

    /// The tape evaluated on numbers (`x`, `p` the two inputs' values).
    fn eval(f: &Function, x: [f64; 2], p: [f64; 2]) -> f64 {
        let mut w: BTreeMap<usize, f64> = BTreeMap::new();
        let mut out = f64::NAN;
        for ins in &f.instructions {
            match ins {
                Instruction::Input {
                    dest,
                    input,
                    element,
                } => {
                    w.insert(
                        *dest,
                        if *input == 0 {
                            x[*element]
                        } else {
                            p[*element]
                        },
                    );
                }
                Instruction::Const { dest, value } => {
                    w.insert(*dest, *value);
                }
                Instruction::Output { src, .. } => out = w[src],
                Instruction::Op { op, dest, args } => {
                    let a = |j: usize| w[&args[j]];
                    let v = match op.as_str() {
                        "add" => a(0) + a(1),
                        "sub" => a(0) - a(1),
                        "mul" => a(0) * a(1),
                        "div" => a(0) / a(1),
                        "neg" => -a(0),
                        "twice" => 2.0 * a(0),
                        "sq" => a(0) * a(0),
                        "sin" => a(0).sin(),
                        _ => panic!("no rule for {op}"),
                    };
                    w.insert(*dest, v);
                }
            }
        }
        out
    }

    fn simplified(f: &Function) -> Function {
        simplify("test.json", f, |j| j == 1).unwrap()
    }

    /// x0·x1 under constant factors and in either order is one product; the value is the
    /// original tape's.
    #[test]
    fn a_product_under_constant_factors_is_computed_once() {
        let f = function(vec![
            Instruction::Input {
                dest: 0,
                input: 0,
                element: 0,
            },
            Instruction::Input {
                dest: 1,
                input: 0,
                element: 1,
            },
            Instruction::Input {
                dest: 2,
                input: 1,
                element: 0,
            },
            op("twice", 3, &[0]),
            op("mul", 4, &[2, 1]),
            op("mul", 5, &[3, 4]),
            op("mul", 6, &[0, 4]),
            op("mul", 7, &[4, 0]),
            op("add", 8, &[5, 6]),
            op("sub", 8, &[8, 7]),
            Instruction::Output { element: 0, src: 8 },
        ]);
        let g = simplified(&f);
        assert_eq!(series_products(&f, |j| j == 1).len(), 3);
        assert_eq!(series_products(&g, |j| j == 1).len(), 1);
        for (x, p) in [([0.3, -1.7], [2.5, 0.0]), ([-4.0, 0.01], [-0.3, 0.0])] {
            let (a, b) = (eval(&f, x, p), eval(&g, x, p));
            assert!((a - b).abs() <= 1e-15 * a.abs(), "{a} vs {b}");
        }
    }

    /// (x0 − p)·x1 + x0·x1 + (p x1)·sin(x0 + p)·sin(x0 + p): the offset is hoisted so the second
    /// product is the first's, the square of a sum is one `sq`, and its factor `x1` one more
    /// product; the value is the original tape's.
    #[test]
    fn offsets_are_hoisted_and_combinations_evaluated_once() {
        let f = function(vec![
            Instruction::Input {
                dest: 0,
                input: 0,
                element: 0,
            },
            Instruction::Input {
                dest: 1,
                input: 0,
                element: 1,
            },
            Instruction::Input {
                dest: 2,
                input: 1,
                element: 0,
            },
            op("sub", 3, &[0, 2]),
            op("mul", 4, &[3, 1]),
            op("mul", 5, &[0, 1]),
            op("add", 6, &[0, 2]),
            op("sin", 7, &[6]),
            op("add", 8, &[0, 2]),
            op("sin", 9, &[8]),
            op("mul", 10, &[7, 9]),
            op("mul", 11, &[2, 1]),
            op("mul", 12, &[11, 10]),
            op("add", 13, &[4, 5]),
            op("add", 13, &[13, 12]),
            Instruction::Output {
                element: 0,
                src: 13,
            },
        ]);
        let g = simplified(&f);
        assert_eq!(series_products(&f, |j| j == 1).len(), 4);
        assert_eq!(series_products(&g, |j| j == 1).len(), 3);
        let sines = g
            .instructions
            .iter()
            .filter(|i| matches!(i, Instruction::Op { op, .. } if op == "sin"))
            .count();
        assert_eq!(sines, 1, "sin(x0 + p) twice is one sine");
        for (x, p) in [([0.3, -1.7], [2.5, 0.0]), ([-4.0, 0.01], [-0.3, 0.0])] {
            let (a, b) = (eval(&f, x, p), eval(&g, x, p));
            assert!((a - b).abs() <= 1e-14 * a.abs().max(1.0), "{a} vs {b}");
        }
    }

    /// θ'·(a θ'u − θ') before θ'·(θ'u) and a θ'²: the first pass multiplies the combination as
    /// it stands (expanding would add two products then), the second knows both products come
    /// anyway and expands it: 3 series products, not 4, and the same value.
    #[test]
    fn a_product_is_expanded_into_products_met_later() {
        let f = function(vec![
            Instruction::Input {
                dest: 0,
                input: 0,
                element: 0,
            },
            Instruction::Input {
                dest: 1,
                input: 0,
                element: 1,
            },
            Instruction::Input {
                dest: 2,
                input: 1,
                element: 0,
            },
            op("mul", 3, &[0, 1]),
            op("mul", 4, &[2, 3]),
            op("sub", 5, &[4, 0]),
            op("mul", 6, &[0, 5]),
            op("mul", 7, &[0, 3]),
            op("mul", 8, &[0, 0]),
            op("mul", 8, &[2, 8]),
            op("add", 9, &[6, 7]),
            op("add", 9, &[9, 8]),
            Instruction::Output { element: 0, src: 9 },
        ]);
        let g = simplified(&f);
        assert_eq!(series_products(&f, |j| j == 1).len(), 4);
        assert_eq!(series_products(&g, |j| j == 1).len(), 3);
        for (x, p) in [([0.3, -1.7], [2.5, 0.0]), ([-4.0, 0.01], [-0.3, 0.0])] {
            let (a, b) = (eval(&f, x, p), eval(&g, x, p));
            assert!((a - b).abs() <= 1e-14 * a.abs().max(1.0), "{a} vs {b}");
        }
    }

    /// What a `_free` twin makes of the excitation: with the series input `g` replaced by the
    /// constant 0, `(g x1)·sin x0 + (g x1 − p)·(g x0) + x0·x1` keeps only `x0 x1`. The zero is
    /// folded through the constant factors, so every product that carried `g` vanishes, and the
    /// sine with them: 1 series product where the forced tape has 5, and where keeping the zero
    /// as a coefficient left `x1 sin x0` to compute. The value is the original tape's at g = 0,
    /// to the bit (only exact zeros are dropped).
    #[test]
    fn products_with_a_zero_excitation_vanish() {
        let input = |dest: usize, input: usize, element: usize| Instruction::Input {
            dest,
            input,
            element,
        };
        let tape = |g: Instruction| {
            vec![
                input(0, 0, 0),
                input(1, 0, 1),
                input(2, 1, 0),
                g,
                op("mul", 4, &[3, 1]),
                op("sin", 5, &[0]),
                op("mul", 6, &[4, 5]),
                op("sub", 7, &[4, 2]),
                op("mul", 8, &[3, 0]),
                op("mul", 9, &[7, 8]),
                op("add", 10, &[6, 9]),
                op("mul", 11, &[0, 1]),
                op("add", 12, &[10, 11]),
                Instruction::Output {
                    element: 0,
                    src: 12,
                },
            ]
        };
        // The forced tape reads g from a third input, a series (the excitation).
        let mut forced = function(tape(input(3, 2, 0)));
        let mut excitation = forced.inputs[0].clone();
        excitation.name = "g".into();
        excitation.scalar = true;
        forced.inputs.push(excitation);
        let forced = simplified(&forced);
        let free = function(tape(Instruction::Const {
            dest: 3,
            value: 0.0,
        }));
        let g = simplified(&free);
        assert_eq!(series_products(&forced, |j| j == 1).len(), 5);
        assert_eq!(series_products(&g, |j| j == 1).len(), 1);
        assert_eq!(series_costs(&g, |j| j == 1).len(), 1);
        for (x, p) in [([0.3, -1.7], [2.5, 0.0]), ([-4.0, 0.01], [-0.3, 0.0])] {
            let (a, b) = (eval(&free, x, p), eval(&g, x, p));
            assert_eq!(a.to_bits(), b.to_bits(), "{a} vs {b}");
        }
    }

    /// A malformed tape is refused with the instruction named, never a panic.
    #[test]
    fn a_wrong_argument_count_is_an_error() {
        let f = function(vec![
            Instruction::Input {
                dest: 0,
                input: 0,
                element: 0,
            },
            Instruction::Input {
                dest: 1,
                input: 1,
                element: 0,
            },
            op("neg", 2, &[1, 0]),
            Instruction::Output { element: 0, src: 2 },
        ]);
        let msg = simplify("test.json", &f, |j| j == 1)
            .unwrap_err()
            .to_string();
        assert!(
            msg.contains("instruction 2: \"neg\" takes 1 argument(s)"),
            "{msg}"
        );
    }
}
