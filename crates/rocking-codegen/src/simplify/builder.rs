//! The builder of the rewritten tape: every value a linear combination of atoms with constant
//! coefficients, and each product of two atoms made once.

use std::collections::{BTreeMap, BTreeSet};

use crate::ir::Instruction;

/// A work variable of the rewritten tape.
pub(super) type Node = usize;

/// A coefficient constant along the step: `±1` or `±` a scalar node.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub(super) struct Coef {
    pub(super) neg: bool,
    pub(super) var: Option<Node>,
}

pub(super) const ONE: Coef = Coef {
    neg: false,
    var: None,
};

/// `Σ coef · atom + offset`, the terms keyed by atom.
#[derive(Clone, Debug, Default, PartialEq, Eq, PartialOrd, Ord)]
pub(super) struct Lin {
    pub(super) terms: BTreeMap<Node, Coef>,
    pub(super) offset: Option<Coef>,
}

impl Lin {
    pub(super) fn atom(a: Node) -> Lin {
        Lin {
            terms: BTreeMap::from([(a, ONE)]),
            offset: None,
        }
    }
}

/// The value of an original work variable: constant along the step, or a combination.
#[derive(Clone, Debug)]
pub(super) enum Val {
    Scalar(Node),
    Series(Lin),
}

/// Whether an operation's arguments commute (their order is normalised for sharing).
pub(super) fn commutes(op: &str) -> bool {
    matches!(op, "add" | "mul")
}

/// Structural names of expressions, shared by the passes of [`simplify`]: two nodes of any pass
/// with the same name compute the same expression, whatever their node numbers.
#[derive(Default)]
pub(super) struct Names {
    pub(super) ids: BTreeMap<(String, Vec<u64>), u64>,
}

impl Names {
    pub(super) fn id(&mut self, key: (String, Vec<u64>)) -> u64 {
        let next = self.ids.len() as u64;
        *self.ids.entry(key).or_insert(next)
    }
}

pub(super) struct Builder {
    pub(super) tape: Vec<Instruction>,
    /// Scalar and nonlinear series nodes by (operation, arguments): each is computed once.
    pub(super) ops: BTreeMap<(String, Vec<Node>), Node>,
    pub(super) consts: BTreeMap<u64, Node>,
    /// Combinations already evaluated into a node.
    pub(super) evaluated: BTreeMap<Lin, Node>,
    /// The structural name of each node.
    pub(super) names: Names,
    pub(super) name_of: BTreeMap<Node, u64>,
    /// Names of the products a previous pass ended up computing: free to expand into.
    pub(super) expected: BTreeSet<u64>,
}

impl Builder {
    pub(super) fn fresh(&self) -> Node {
        self.tape.len()
    }

    pub(super) fn constant(&mut self, value: f64) -> Node {
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
    pub(super) fn name(&mut self, node: Node, op: &str, mut args: Vec<u64>) {
        if commutes(op) {
            args.sort_unstable();
        }
        let id = self.names.id((op.to_string(), args));
        self.name_of.insert(node, id);
    }

    /// The name of a product of `x` and `y`, if any pass has met one.
    pub(super) fn product_name(&self, x: Node, y: Node) -> Option<u64> {
        let mut args = vec![*self.name_of.get(&x)?, *self.name_of.get(&y)?];
        args.sort_unstable();
        self.names.ids.get(&("mul".to_string(), args)).copied()
    }

    /// Whether a node is the constant zero (the excitation of a `_free` twin, and what it
    /// multiplies).
    pub(super) fn is_zero(&self, n: Node) -> bool {
        matches!(self.tape[n], Instruction::Const { value, .. } if value == 0.0)
    }

    /// Whether a coefficient is zero, so that its term vanishes.
    pub(super) fn vanishes(&self, c: Coef) -> bool {
        c.var.is_some_and(|v| self.is_zero(v))
    }

    /// `op(args)` when a zero argument decides it without an operation: `0·x`, `0 + x`, ...
    pub(super) fn fold_zero(&mut self, op: &str, args: &[Node]) -> Option<Node> {
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
    pub(super) fn op(&mut self, op: &str, mut args: Vec<Node>) -> Node {
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

    pub(super) fn exists(&self, op: &str, mut args: Vec<Node>) -> bool {
        if commutes(op) {
            args.sort_unstable();
        }
        self.ops.contains_key(&(op.to_string(), args))
    }

    /// The magnitude of a coefficient as a node (`1` becomes the constant 1).
    pub(super) fn magnitude(&mut self, c: Coef) -> Node {
        match c.var {
            Some(v) => v,
            None => self.constant(1.0),
        }
    }

    pub(super) fn coef_mul(&mut self, a: Coef, b: Coef) -> Coef {
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
    pub(super) fn coef_add(&mut self, a: Coef, b: Coef) -> Option<Coef> {
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

    pub(super) fn coef_inv(&mut self, c: Coef) -> Coef {
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

    pub(super) fn add(&mut self, a: &Lin, b: &Lin) -> Lin {
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

    pub(super) fn scale(&mut self, a: &Lin, c: Coef) -> Lin {
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
    pub(super) fn with_offset(&mut self, a: &Lin, x: Node, neg: bool) -> Lin {
        let b = Lin {
            terms: BTreeMap::new(),
            offset: Some(Coef { neg, var: Some(x) }),
        };
        self.add(a, &b)
    }

    /// A combination as a value: a scalar when no series term is left.
    pub(super) fn value(&mut self, lin: Lin) -> Val {
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
    pub(super) fn eval(&mut self, lin: &Lin) -> Node {
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
    pub(super) fn node(&mut self, v: &Val) -> Node {
        match v {
            Val::Scalar(n) => *n,
            Val::Series(lin) => self.eval(lin),
        }
    }

    /// The number of atoms a product would add: expanded over the terms, or as it stands.
    pub(super) fn new_products(&self, a: &Lin, b: &Lin) -> (usize, usize) {
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

    pub(super) fn mul(&mut self, a: &Lin, b: &Lin) -> Lin {
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
    pub(super) fn div(&mut self, num: &Val, den: &Lin) -> Lin {
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
