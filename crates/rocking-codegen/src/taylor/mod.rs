//! Taylor-mode kernels: the same instruction tape, evaluated on truncated power series.
//!
//! Each elementary operation of the tape has a recurrence for the Taylor coefficients of its
//! result (automatic differentiation in Taylor mode, Jorba & Zou 2005): sums are coefficient-wise,
//! a product is a Cauchy product, a quotient, a square root and the sine/cosine pair are
//! triangular recurrences in the result's own lower coefficients. Rendering the tape once per
//! coefficient order k gives, for an ODE right-hand side x' = f(x, ug(t)), the coefficients of
//! the solution x(t0 + h) = Σ x_k h^k by x_{k+1} = f_k / (k + 1).
//!
//! The tape is first rewritten by [`crate::simplify`] so that each product of series (the only
//! operations whose cost grows with the order) is computed once. Each right-hand side also gets a
//! `_free` twin without the ground acceleration, for the steps after the excitation, where its
//! products with the (zero) excitation need not be computed; and a quotient's recurrence
//! multiplies by the denominator's reciprocal, computed once per step, so that no division lies
//! on the path from one order to the next.
//!
//! Work variables that depend only on constants, the pivot `s` and the parameters are computed
//! once as scalars before the order loop; only time-dependent ones become series. Of those, only
//! the ones whose lower coefficients a recurrence reads (the arguments of products, quotients,
//! square roots and sines, and the results of the self-referencing ones) keep arrays; the rest
//! are a local of the current order (found by a first rendering pass). An input series and a
//! copy of a series (an assignment, a sine or cosine of the shared recurrence) are no arrays of
//! their own: the recurrences read the input's rows or the copied array in place, which spares
//! each call the zeroing and each order the copying (the kernels' per-step memsets). The recurrences
//! themselves are the hand-written helpers of `rocking_kernels::series`.
//!
//! The sums over lower orders of every product, quotient and sine recurrence of an order read
//! only coefficients computed at earlier orders, so each order starts with all of them at once
//! (`series::dots`, up to [`DOTS_PER_LOOP`] per loop, each summed as alone, so the same bits):
//! one loop instead of one per node, and independent sums the CPU overlaps (the point-mass
//! `_free` kernel at order 16: 464 → 433 ns, `cargo bench -p rocking-kernels --bench kernels --
//! taylor_rocking_rhs_N17/point_mass_free`). Only the terms with a coefficient of the current
//! order wait for the order's earlier nodes.

use serde::Serialize;

use crate::ir::{Function, Input, Instruction, Ir};
use crate::render::render_template;
use crate::render::text::str_lit;
use crate::simplify::simplify;
use crate::Result;

mod tape;

use tape::{render_fn, TaylorFn};

const TAYLOR_TEMPLATE: &str = include_str!("../../templates/taylor.rs.tera");
const TAYLOR_MOD_TEMPLATE: &str = include_str!("../../templates/taylor_mod.rs.tera");

/// Directory of the rendered Taylor modules, relative to the repository root.
pub const TAYLOR_DIR: &str = "generated/src/taylor";

/// The functions rendered in Taylor mode: ODE right-hand sides (their output is the derivative
/// of their state input) and the event and energy functions evaluated along a step.
const ODE_FUNCTIONS: &[&str] = &["rocking_rhs", "contact_rhs"];
const SERIES_FUNCTIONS: &[&str] = &["uplift", "energy", "power", "free_power", "flight"];
/// The functions rendered one order at a time ([`Mode::Orders`]): the two sides of
/// M(q) q'' = F(q, q', t) that the solver solves at run time: for the rocking phase on the rigid
/// surface (where that is cheaper than the symbolic `rocking_rhs`) and for the free base on
/// compliant ground (the structure's mass matrix and forcing, the ground's generalised forces of
/// each contact state).
const ORDER_FUNCTIONS: &[&str] = &[
    "mass_matrix",
    "forcing",
    "free_mass_matrix",
    "free_forcing",
    "winkler_full",
    "winkler_edge",
    "two_spring_full",
    "two_spring_edge",
];

/// How a function is rendered in Taylor mode.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Mode {
    /// An ODE's right-hand side: fills the solution's coefficients in place, order by order.
    Ode,
    /// The first N coefficients of each output along given input series.
    Series,
    /// A closure that returns coefficient k of each output when called with k = 0, 1, 2, ... in
    /// turn, reading the input series' coefficients up to k: for a right-hand side the solver
    /// assembles at run time (`x_{k+1}` from the outputs' k-th coefficients, e.g. by solving
    /// M_0 q''_k = F_k − Σ_{j≥1} M_j q''_{k−j}), whose inputs' next coefficients exist only
    /// after the call.
    Orders,
}

#[derive(Serialize)]
struct TaylorView {
    header: String,
    variant: String,
    params_use: String,
    name_lit: String,
    functions: Vec<TaylorFn>,
}

/// Renders the Taylor module of one variant.
pub fn render_taylor(ir: &Ir) -> Result<String> {
    let path = format!("{}.json", ir.variant);
    let params = format!("crate::kernels::{}::Params", ir.variant);
    render_module(
        ir,
        &path,
        &params,
        &format!("crate::kernels::{}", ir.variant),
    )
}

/// Renders the Taylor module of the ground's kernels (`generated/ir/ground/ground.json`):
/// `generated/src/taylor/ground.rs`.
pub fn render_taylor_ground(ir: &Ir) -> Result<String> {
    render_module(
        ir,
        "ground/ground.json",
        "crate::ground::Params",
        "crate::ground",
    )
}

fn render_module(ir: &Ir, json: &str, params: &str, kernels: &str) -> Result<String> {
    let origin = ir.origin();
    let mut functions = Vec::new();
    for f in &ir.functions {
        let name = f.name.as_str();
        let mode = if ODE_FUNCTIONS.contains(&name) {
            Mode::Ode
        } else if SERIES_FUNCTIONS.contains(&name) {
            Mode::Series
        } else if ORDER_FUNCTIONS.contains(&name) {
            Mode::Orders
        } else {
            continue;
        };
        let twin = if mode == Mode::Ode {
            free_twin(f)
        } else {
            None
        };
        for (g, note) in std::iter::once((f.clone(), None)).chain(twin) {
            let g = simplify(&origin, &g, |j| g.inputs.get(j).is_some_and(is_const_input))?;
            let (_, history) = render_fn(&origin, &g, mode, None)?;
            let mut rendered = render_fn(&origin, &g, mode, Some(&history))?.0;
            rendered.doc.extend(note);
            functions.push(rendered);
        }
    }
    let view = TaylorView {
        header: format!(
            "//! @generated by `cargo xtask regen` from generated/ir/{json}. Do not edit."
        ),
        variant: kernels.to_string(),
        params_use: params.to_string(),
        name_lit: str_lit(&ir.variant),
        functions,
    };
    render_template(
        "taylor.rs",
        TAYLOR_TEMPLATE,
        &view,
        &format!("{TAYLOR_DIR}/{}.rs", ir.variant),
    )
}

#[derive(Serialize)]
struct TaylorModView {
    variants: Vec<String>,
}

/// Renders `generated/src/taylor/mod.rs` declaring the Taylor module of every IR of `irs` (the
/// variants, and the ground's when there is one).
pub fn render_taylor_mod(irs: &[&Ir]) -> Result<String> {
    let mut variants: Vec<String> = irs.iter().map(|ir| ir.variant.clone()).collect();
    variants.sort();
    render_template(
        "taylor_mod.rs",
        TAYLOR_MOD_TEMPLATE,
        &TaylorModView { variants },
        &format!("{TAYLOR_DIR}/mod.rs"),
    )
}

/// The twin of an ODE right-hand side for a step on which its excitation is identically zero
/// (free vibration after a pulse or a record): `{name}_free`, without the scalar series inputs
/// (the ground acceleration), which read as the constant 0. [`simplify`] folds that zero through
/// the constant factors, so every product that carried the excitation vanishes and the twin
/// computes fewer series products (the full-mass rocking right-hand side: 7 instead of 10, the
/// point-mass one 6 instead of 9). `None` when there is no such input.
/// Also returns the doc line that says so.
fn free_twin(f: &Function) -> Option<(Function, Option<String>)> {
    let zero: Vec<usize> = (0..f.inputs.len())
        .filter(|&j| f.inputs[j].scalar && !is_const_input(&f.inputs[j]))
        .collect();
    if zero.is_empty() {
        return None;
    }
    let names: Vec<String> = zero
        .iter()
        .map(|&j| format!("`{}`", f.inputs[j].name))
        .collect();
    let instructions = f
        .instructions
        .iter()
        .map(|ins| match *ins {
            Instruction::Input { dest, input, .. } if zero.contains(&input) => {
                Instruction::Const { dest, value: 0.0 }
            }
            Instruction::Input {
                dest,
                input,
                element,
            } => Instruction::Input {
                dest,
                input: input - zero.iter().filter(|&&j| j < input).count(),
                element,
            },
            ref other => other.clone(),
        })
        .collect();
    let twin = Function {
        name: format!("{}_free", f.name),
        doc: f.doc.clone(),
        inputs: (0..f.inputs.len())
            .filter(|j| !zero.contains(j))
            .map(|j| f.inputs[j].clone())
            .collect(),
        output: f.output.clone(),
        instructions,
        golden: Vec::new(),
        taylor_order: None,
        taylor_golden: Vec::new(),
    };
    let note = format!(
        "/// The twin of `{}` with {} identically zero: for the steps after the excitation.",
        f.name,
        names.join(", ")
    );
    Some((twin, Some(note)))
}

/// Whether an input is constant along a step (the pivot and the parameters).
fn is_const_input(inp: &Input) -> bool {
    inp.params || inp.name == "s"
}
