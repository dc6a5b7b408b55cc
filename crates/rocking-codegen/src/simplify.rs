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

use std::collections::{BTreeMap, BTreeSet};

use crate::ir::{Function, Instruction};
use crate::{Error, Result};

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

/// A work variable of the rewritten tape.
type Node = usize;

/// A coefficient constant along the step: `±1` or `±` a scalar node.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
struct Coef {
    neg: bool,
    var: Option<Node>,
}

const ONE: Coef = Coef {
    neg: false,
    var: None,
};

/// `Σ coef · atom + offset`, the terms keyed by atom.
#[derive(Clone, Debug, Default, PartialEq, Eq, PartialOrd, Ord)]
struct Lin {
    terms: BTreeMap<Node, Coef>,
    offset: Option<Coef>,
}

impl Lin {
    fn atom(a: Node) -> Lin {
        Lin {
            terms: BTreeMap::from([(a, ONE)]),
            offset: None,
        }
    }
}

/// The value of an original work variable: constant along the step, or a combination.
#[derive(Clone, Debug)]
enum Val {
    Scalar(Node),
    Series(Lin),
}

/// Whether an operation's arguments commute (their order is normalised for sharing).
fn commutes(op: &str) -> bool {
    matches!(op, "add" | "mul")
}

/// Structural names of expressions, shared by the passes of [`simplify`]: two nodes of any pass
/// with the same name compute the same expression, whatever their node numbers.
#[derive(Default)]
struct Names {
    ids: BTreeMap<(String, Vec<u64>), u64>,
}

impl Names {
    fn id(&mut self, key: (String, Vec<u64>)) -> u64 {
        let next = self.ids.len() as u64;
        *self.ids.entry(key).or_insert(next)
    }
}

struct Builder {
    tape: Vec<Instruction>,
    /// Scalar and nonlinear series nodes by (operation, arguments): each is computed once.
    ops: BTreeMap<(String, Vec<Node>), Node>,
    consts: BTreeMap<u64, Node>,
    /// Combinations already evaluated into a node.
    evaluated: BTreeMap<Lin, Node>,
    /// The structural name of each node.
    names: Names,
    name_of: BTreeMap<Node, u64>,
    /// Names of the products a previous pass ended up computing: free to expand into.
    expected: BTreeSet<u64>,
}

impl Builder {
    fn fresh(&self) -> Node {
        self.tape.len()
    }

    fn constant(&mut self, value: f64) -> Node {
        if let Some(&n) = self.consts.get(&value.to_bits()) {
            return n;
        }
        let dest = self.fresh();
        self.tape.push(Instruction::Const { dest, value });
        self.consts.insert(value.to_bits(), dest);
        self.name(dest, "const", vec![value.to_bits()]);
        dest
    }

    /// Names `node` as `op(args)` (argument names sorted for a commutative operation).
    fn name(&mut self, node: Node, op: &str, mut args: Vec<u64>) {
        if commutes(op) {
            args.sort_unstable();
        }
        let id = self.names.id((op.to_string(), args));
        self.name_of.insert(node, id);
    }

    /// The name of a product of `x` and `y`, if any pass has met one.
    fn product_name(&self, x: Node, y: Node) -> Option<u64> {
        let mut args = vec![*self.name_of.get(&x)?, *self.name_of.get(&y)?];
        args.sort_unstable();
        self.names.ids.get(&("mul".to_string(), args)).copied()
    }

    /// Whether a node is the constant zero (the excitation of a `_free` twin, and what it
    /// multiplies).
    fn is_zero(&self, n: Node) -> bool {
        matches!(self.tape[n], Instruction::Const { value, .. } if value == 0.0)
    }

    /// Whether a coefficient is zero, so that its term vanishes.
    fn vanishes(&self, c: Coef) -> bool {
        c.var.is_some_and(|v| self.is_zero(v))
    }

    /// `op(args)` when a zero argument decides it without an operation: `0·x`, `0 + x`, ...
    fn fold_zero(&mut self, op: &str, args: &[Node]) -> Option<Node> {
        let zero = |n: Node| self.is_zero(n);
        match (op, args) {
            ("mul", &[a, b]) if zero(a) || zero(b) => Some(if zero(a) { a } else { b }),
            ("add", &[a, b]) if zero(a) => Some(b),
            ("add" | "sub", &[a, b]) if zero(b) => Some(a),
            ("sub", &[a, b]) if zero(a) => Some(self.op("neg", vec![b])),
            ("div", &[a, _]) | ("neg" | "twice" | "sq" | "sqrt" | "sin", &[a]) if zero(a) => {
                Some(a)
            }
            _ => None,
        }
    }

    /// The node of `op(args)`, shared with an earlier identical one.
    fn op(&mut self, op: &str, mut args: Vec<Node>) -> Node {
        if let Some(n) = self.fold_zero(op, &args) {
            return n;
        }
        if commutes(op) {
            args.sort_unstable();
        }
        let key = (op.to_string(), args);
        if let Some(&n) = self.ops.get(&key) {
            return n;
        }
        let dest = self.fresh();
        // A product of a node with itself is its square (half the recurrence's work).
        let (op, args) = match key.1.as_slice() {
            &[a, b] if key.0 == "mul" && a == b => ("sq".to_string(), vec![a]),
            _ => key.clone(),
        };
        self.tape.push(Instruction::Op { op, dest, args });
        let arg_names = key.1.iter().map(|a| self.name_of[a]).collect();
        self.name(dest, &key.0, arg_names);
        self.ops.insert(key, dest);
        dest
    }

    fn exists(&self, op: &str, mut args: Vec<Node>) -> bool {
        if commutes(op) {
            args.sort_unstable();
        }
        self.ops.contains_key(&(op.to_string(), args))
    }

    /// The magnitude of a coefficient as a node (`1` becomes the constant 1).
    fn magnitude(&mut self, c: Coef) -> Node {
        match c.var {
            Some(v) => v,
            None => self.constant(1.0),
        }
    }

    fn coef_mul(&mut self, a: Coef, b: Coef) -> Coef {
        let var = match (a.var, b.var) {
            (None, v) | (v, None) => v,
            (Some(x), Some(y)) => Some(self.op("mul", vec![x, y])),
        };
        Coef {
            neg: a.neg != b.neg,
            var,
        }
    }

    /// `a + b`, or `None` when they cancel.
    fn coef_add(&mut self, a: Coef, b: Coef) -> Option<Coef> {
        if a.var == b.var {
            if a.neg != b.neg {
                return None;
            }
            let two = self.constant(2.0);
            let var = match a.var {
                Some(v) => self.op("mul", vec![two, v]),
                None => two,
            };
            return Some(Coef {
                neg: a.neg,
                var: Some(var),
            });
        }
        let (x, y) = (self.magnitude(a), self.magnitude(b));
        Some(match (a.neg, b.neg) {
            (na, nb) if na == nb => Coef {
                neg: na,
                var: Some(self.op("add", vec![x, y])),
            },
            (false, _) => Coef {
                neg: false,
                var: Some(self.op("sub", vec![x, y])),
            },
            (true, _) => Coef {
                neg: false,
                var: Some(self.op("sub", vec![y, x])),
            },
        })
    }

    fn coef_inv(&mut self, c: Coef) -> Coef {
        match c.var {
            None => c,
            Some(v) => {
                let one = self.constant(1.0);
                Coef {
                    neg: c.neg,
                    var: Some(self.op("div", vec![one, v])),
                }
            }
        }
    }

    fn add(&mut self, a: &Lin, b: &Lin) -> Lin {
        let mut sum = a.clone();
        for (&atom, &c) in &b.terms {
            if self.vanishes(c) {
                continue;
            }
            match sum.terms.get(&atom).copied() {
                None => {
                    sum.terms.insert(atom, c);
                }
                Some(old) => match self.coef_add(old, c) {
                    Some(new) if !self.vanishes(new) => {
                        sum.terms.insert(atom, new);
                    }
                    _ => {
                        sum.terms.remove(&atom);
                    }
                },
            }
        }
        sum.offset = match (a.offset, b.offset) {
            (x, None) | (None, x) => x,
            (Some(x), Some(y)) => self.coef_add(x, y),
        };
        sum.offset = sum.offset.filter(|&o| !self.vanishes(o));
        sum
    }

    fn scale(&mut self, a: &Lin, c: Coef) -> Lin {
        let mut out = Lin::default();
        for (&atom, &t) in &a.terms {
            let t = self.coef_mul(t, c);
            if !self.vanishes(t) {
                out.terms.insert(atom, t);
            }
        }
        out.offset = a
            .offset
            .map(|o| self.coef_mul(o, c))
            .filter(|&o| !self.vanishes(o));
        out
    }

    /// A combination with the scalar `x` added.
    fn with_offset(&mut self, a: &Lin, x: Node, neg: bool) -> Lin {
        let b = Lin {
            terms: BTreeMap::new(),
            offset: Some(Coef { neg, var: Some(x) }),
        };
        self.add(a, &b)
    }

    /// A combination as a value: a scalar when no series term is left.
    fn value(&mut self, lin: Lin) -> Val {
        if !lin.terms.is_empty() {
            return Val::Series(lin);
        }
        Val::Scalar(match lin.offset {
            None => self.constant(0.0),
            Some(Coef { neg: false, var }) => match var {
                Some(v) => v,
                None => self.constant(1.0),
            },
            Some(Coef { neg: true, var }) => match var {
                Some(v) => self.op("neg", vec![v]),
                None => self.constant(-1.0),
            },
        })
    }

    /// The node holding a combination, evaluated once: a single atom is itself.
    fn eval(&mut self, lin: &Lin) -> Node {
        if lin.offset.is_none() && lin.terms.len() == 1 {
            if let Some((&atom, &ONE)) = lin.terms.iter().next() {
                return atom;
            }
        }
        if let Some(&n) = self.evaluated.get(lin) {
            return n;
        }
        // Positive terms first, so a negative one is a subtraction.
        let mut parts: Vec<(bool, Node)> = Vec::new();
        for (&atom, &c) in &lin.terms {
            let node = match c.var {
                None => atom,
                Some(v) => self.op("mul", vec![v, atom]),
            };
            parts.push((c.neg, node));
        }
        if let Some(o) = lin.offset {
            let m = self.magnitude(o);
            parts.push((o.neg, m));
        }
        parts.sort_by_key(|&(neg, _)| neg);
        let (neg0, first) = parts[0];
        let mut acc = if neg0 {
            self.op("neg", vec![first])
        } else {
            first
        };
        for &(neg, node) in &parts[1..] {
            acc = self.op(if neg { "sub" } else { "add" }, vec![acc, node]);
        }
        self.evaluated.insert(lin.clone(), acc);
        acc
    }

    /// A node for an argument of a nonlinear operation.
    fn node(&mut self, v: &Val) -> Node {
        match v {
            Val::Scalar(n) => *n,
            Val::Series(lin) => self.eval(lin),
        }
    }

    /// The number of atoms a product would add: expanded over the terms, or as it stands.
    fn new_products(&self, a: &Lin, b: &Lin) -> (usize, usize) {
        let mut pairs = BTreeSet::new();
        for &x in a.terms.keys() {
            for &y in b.terms.keys() {
                pairs.insert((x.min(y), x.max(y)));
            }
        }
        let free = |x: Node, y: Node| {
            self.exists("mul", vec![x, y])
                || self
                    .product_name(x, y)
                    .is_some_and(|n| self.expected.contains(&n))
        };
        let expanded = pairs.iter().filter(|&&(x, y)| !free(x, y)).count();
        let node = |l: &Lin| -> Option<Node> {
            match l.terms.iter().next() {
                Some((&atom, &ONE)) if l.terms.len() == 1 && l.offset.is_none() => Some(atom),
                _ => self.evaluated.get(l).copied(),
            }
        };
        let whole = match (node(a), node(b)) {
            (Some(x), Some(y)) if self.exists("mul", vec![x, y]) => 0,
            _ => 1,
        };
        (expanded, whole)
    }

    fn mul(&mut self, a: &Lin, b: &Lin) -> Lin {
        let (expanded, whole) = self.new_products(a, b);
        if expanded > whole {
            let (x, y) = (self.eval(a), self.eval(b));
            return Lin::atom(self.op("mul", vec![x, y]));
        }
        let mut out = Lin::default();
        for (&x, &cx) in &a.terms {
            for (&y, &cy) in &b.terms {
                let c = self.coef_mul(cx, cy);
                let p = Lin::atom(self.op("mul", vec![x, y]));
                let term = self.scale(&p, c);
                out = self.add(&out, &term);
            }
        }
        let cross = [(a.offset, b), (b.offset, a)];
        for (o, other) in cross {
            if let Some(o) = o {
                let terms = Lin {
                    terms: other.terms.clone(),
                    offset: None,
                };
                let t = self.scale(&terms, o);
                out = self.add(&out, &t);
            }
        }
        if let (Some(x), Some(y)) = (a.offset, b.offset) {
            let c = self.coef_mul(x, y);
            let t = Lin {
                terms: BTreeMap::new(),
                offset: Some(c),
            };
            out = self.add(&out, &t);
        }
        out
    }

    /// `num / den` with a series denominator: a constant factor of the denominator hoisted.
    fn div(&mut self, num: &Val, den: &Lin) -> Lin {
        let n = self.node(num);
        if den.offset.is_none() && den.terms.len() == 1 {
            let (&atom, &c) = den.terms.iter().next().expect("one term");
            let q = Lin::atom(self.op("div", vec![n, atom]));
            let inv = self.coef_inv(c);
            return self.scale(&q, inv);
        }
        let d = self.eval(den);
        Lin::atom(self.op("div", vec![n, d]))
    }
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

fn pass(
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
