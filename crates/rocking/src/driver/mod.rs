//! The hybrid driver: full contact, rocking about either corner, impacts, overturning.
//!
//! The driver is generic over the kernel variant `V` (monomorphised: no run-time branch for absent
//! effects) and the ground motion `M`. Each phase runs one integrator from its start to its first
//! event; the loop here moves between phases and picks the integrator of each (Runge–Kutta or
//! Taylor, from the options):
//!
//! * **contact** (state `[u, u', W, D]`, each `u` the n deformation coordinates u_1..u_n): events f_+ and f_- of eq (24) rising through zero
//!   (uplift about that corner). At every start of a contact phase the uplift functions are checked
//!   at once, which is how the rigid limit works (impact, zero-length contact, re-uplift).
//! * **rocking about s** (state `[θ, u, θ', u', W, D]`): the impact event s θ / (t − t0)^n falling
//!   through zero, regularised so it cannot fire at the phase start t0 (n = 2 after an uplift, where
//!   θ' = 0; n = 1 after an immediate-rocking impact), and the overturning event s θ − θ_over.
//!
//! W and D (ground work and damping dissipation) are carried as two more state components only
//! when the energy bookkeeping is asked for (`ENERGY`);
//! they are excluded from the error control so that trajectories do not depend on it.
//!
//! Rooms: `state` (the run's state, carried integrals and guards), `transitions` (uplift, rocking
//! events, impacts), `impact` (the impact policy, a pure function), `rk_phases` and
//! `taylor_phases` (one integrator each, they never call each other), `record` (what a run
//! records, values only), `recorder` (each step's bookkeeping, the event log's entries, the
//! summary). Where each component sits in the states: [`crate::layout`].

mod force_record;
mod forces;
mod ground_phases;
mod impact;
mod record;
mod recorder;
mod rk_phases;
mod state;
mod taylor_phases;
mod transitions;

use rocking_kernels::kernels::index::{energy as en, static_uplift as su};
use rocking_motion::GroundMotion;
use rocking_ode::{Options as OdeOptions, Tolerances};

use crate::error::SimError;
use crate::layout::{Contact, Part, Rocking};
use crate::options::{Method, Options};
use crate::results::{Run, SolverStats};
use crate::structure::{Derived, Structure};
use crate::taylor::TaylorVariant;
use nalgebra::DMatrix;
use record::Record;
use rocking_kernels::modes::Matrices;
use rocking_kernels::{Array, Variant};
use state::{contact_of, Integrals, Metric, Next, Sim, LEFT, RIGHT, Y};
use transitions::ContactStart;

pub use ground_phases::simulate_ground;

/// Runs one simulation with kernel variant `V`, whose rocking and contact states have `NR` and
/// `NC` components: `V::X::LEN` and `V::Xc::LEN`, or two more each to carry the ground work and
/// the damping dissipation (the energy bookkeeping). The dispatch gives them from the variant's
/// layout (`with_variant!(name, V, L => simulate::<V, _, { L::X + 2 }, { L::XC + 2 }>(..))`).
///
/// # Panics
///
/// When `NR` and `NC` are not the variant's lengths, both with or both without the integrals.
pub fn simulate<V: TaylorVariant, M: GroundMotion + ?Sized, const NR: usize, const NC: usize>(
    structure: &Structure,
    motion: &M,
    opts: &Options,
) -> Result<Run, SimError> {
    set_up::<V, M, NR, NC>(structure, motion, opts)?.run()
}

/// The run's fixed quantities: the variant's own reference quantities and scales, tolerances.
fn set_up<'a, V: TaylorVariant, M: GroundMotion + ?Sized, const NR: usize, const NC: usize>(
    structure: &Structure,
    motion: &'a M,
    opts: &'a Options,
) -> Result<Sim<'a, V, M, NR, NC>, SimError> {
    let (nx, nc) = (V::X::LEN, V::Xc::LEN);
    assert!(
        (NR, NC) == (nx, nc) || (NR, NC) == (nx + 2, nc + 2),
        "state sizes {NR}, {NC} for variant {} ({nx}, {nc} without the energy integrals)",
        V::NAME
    );
    opts.validate()?;
    if opts.accuracy.method == Method::Taylor && !motion.accel_series(0.0, &mut [0.0; 2]) {
        return Err(SimError::NoTaylorSeries);
    }
    let tol = opts.accuracy.tol;
    let derived = structure.derived_by::<V>();
    let p = structure.params::<V>();
    let (a, pf) = (derived.alpha, derived.p);
    let n = V::NQ;
    let top = V::shape(1.0);
    // Each u_i so that u_i ψ_i(1) is of order u_cr, each u_i' the same times ω_n.
    let u_scale = |i: usize| {
        if V::RIGID {
            1.0
        } else if n == 1 {
            derived.u_cr
        } else {
            let psi = top.values()[i].abs();
            if psi > 0.0 {
                derived.u_cr / psi
            } else {
                derived.u_cr
            }
        }
    };
    let ud_scale = |i: usize| {
        if V::RIGID {
            1.0
        } else {
            u_scale(i) * derived.omega_n
        }
    };
    let off = f64::INFINITY; // W and D take no part in the error control
    let ode_options = OdeOptions {
        max_steps: opts.max_steps,
        // The Taylor method keeps these for nothing but the RK options' shape.
        ..OdeOptions::new(
            opts.accuracy
                .method
                .runge_kutta()
                .unwrap_or(rocking_ode::Method::Dop853),
        )
    };
    let contact_scale: [f64; NC] = std::array::from_fn(|i| match Contact::<V>::part(i) {
        Part::U(k) => u_scale(k),
        Part::UDot(k) => ud_scale(k),
        _ => 1.0,
    });
    let rocking_scale: [f64; NR] = std::array::from_fn(|i| match Rocking::<V>::part(i) {
        Part::Theta => a,
        Part::U(k) => u_scale(k),
        Part::ThetaDot => a * pf,
        Part::UDot(k) => ud_scale(k),
        Part::Integral(_) => 1.0,
    });
    let contact_tol = Tolerances {
        rtol: tol,
        atol: Y::<NC>::from_fn(|i, _| match Contact::<V>::part(i) {
            Part::Integral(_) => off,
            _ => contact_scale[i] * tol,
        }),
    };
    let rocking_tol = Tolerances {
        rtol: tol,
        atol: Y::<NR>::from_fn(|i, _| match Rocking::<V>::part(i) {
            Part::Integral(_) => off,
            _ => rocking_scale[i] * tol,
        }),
    };
    let e0 = V::energy(&V::X::from_fn(|_| 0.0), RIGHT, &p);
    let uplift = V::static_uplift(&p);
    // The excitation's resolution is a sixteenth of its shortest period.
    let excitation_rate = 2.0 * std::f64::consts::PI / (16.0 * motion.resolution());
    let (metric, first_mode, highest) = column_metric::<V>(&p, &derived);
    let fastest_rate = [
        derived.omega_n,
        derived.omega_up,
        highest,
        pf,
        excitation_rate,
    ]
    .into_iter()
    .filter(|w| w.is_finite())
    .fold(0.0, f64::max);
    Ok(Sim {
        p,
        motion,
        opts,
        derived,
        p_seconds: structure.p_per_second(),
        rest_rate: opts.rest_rate * a * pf,
        significant_rate: 0.01 * a * pf,
        v_rest: e0[en::GRAVITY] + e0[en::STRAIN],
        ode_options,
        contact_tol,
        rocking_tol,
        contact_scale,
        rocking_scale,
        stats: SolverStats::default(),
        events: 0,
        weight: uplift.values()[su::WEIGHT],
        wb: uplift.values()[su::MOMENT_UPLIFT],
        fastest_rate,
        top,
        first_mode,
        metric,
        rec: Record::default(),
    })
}

/// The column's K and M in full contact, inverted (k̃ and m̃ for one coordinate), its first
/// fixed-base mode with a unit top deflection (1 for one coordinate; NaN where the mass matrix
/// is singular), and its highest fixed-base or uplifted frequency (NaN for one coordinate, whose
/// ω_n and ω_up are the derived ones).
fn column_metric<V: Variant>(p: &V::Params, derived: &Derived) -> (Metric, V::Shape, f64) {
    let (k, m) = (derived.k_tilde, derived.m_tilde);
    if V::NQ == 1 {
        let one = DMatrix::from_element(1, 1, 1.0);
        let metric = Metric {
            k,
            m,
            k_inv: one.clone(),
            m_inv: one,
        };
        return (metric, V::Shape::from_fn(|_| 1.0), f64::NAN);
    }
    let mats = Matrices::of::<V>(p);
    let nan = || DMatrix::from_element(V::NQ, V::NQ, f64::NAN);
    let metric = Metric {
        k,
        m,
        k_inv: mats.stiffness.clone().try_inverse().unwrap_or_else(nan),
        m_inv: mats.mass.clone().try_inverse().unwrap_or_else(nan),
    };
    let fixed = mats.fixed_base();
    let phi = fixed.as_ref().map(|modes| modes.shapes[0].clone());
    let first_mode = V::Shape::from_fn(|i| phi.as_ref().map_or(f64::NAN, |phi| phi[i]));
    let last = |m: Option<&rocking_kernels::modes::Modes>| {
        m.and_then(|m| m.omega.last().copied()).unwrap_or(f64::NAN)
    };
    let highest = last(fixed.as_ref()).max(last(mats.uplifted().as_ref()));
    (metric, first_mode, highest)
}

impl<V: TaylorVariant, M: GroundMotion + ?Sized, const NR: usize, const NC: usize>
    Sim<'_, V, M, NR, NC>
{
    /// The initial rocking state: for several coordinates the initial `u` and `u'` are top
    /// deflections along the first fixed-base mode φ_1.
    fn initial_state(&self) -> V::X {
        let i = self.opts.initial;
        let n = V::NQ;
        let phi = self.first_mode.values();
        // One coordinate: its u is the top deflection (φ_1 = 1 is not multiplied in).
        let along = |v: f64, k: usize| if n == 1 { v } else { v * phi[k] };
        V::X::from_fn(|k| match Rocking::<V>::part(k) {
            Part::Theta => i.theta,
            Part::U(k) => along(i.u, k),
            Part::ThetaDot => i.theta_dot,
            Part::UDot(k) => along(i.u_dot, k),
            Part::Integral(_) => 0.0,
        })
    }

    /// From the initial state to the end of the run, one phase at a time.
    fn run(mut self) -> Result<Run, SimError> {
        let i = self.opts.initial;
        let x0 = self.initial_state();
        let s0 = if i.theta > 0.0 || (i.theta == 0.0 && i.theta_dot > 0.0) {
            RIGHT
        } else {
            LEFT
        };
        let e_initial = self.total_energy(&x0, s0);
        self.track(&x0);
        let mut next = if i.theta != 0.0 || i.theta_dot != 0.0 {
            // Free rocking from θ0 != 0 needs no regularisation (n = 0); from θ = 0 with θ' != 0, n = 1.
            Next::Rocking {
                t: 0.0,
                s: s0,
                x: x0,
                n: if i.theta != 0.0 { 0 } else { 1 },
                carried: Integrals::default(),
            }
        } else {
            Next::Contact {
                t: 0.0,
                xc: contact_of::<V>(&x0),
                carried: Integrals::default(),
                settle: false,
            }
        };
        let taylor = self.opts.accuracy.method == Method::Taylor;
        loop {
            next = match next {
                Next::Contact {
                    t,
                    xc,
                    carried,
                    settle,
                } => match self.contact_start(t, xc, carried, settle)? {
                    ContactStart::Lifted(next) => next,
                    ContactStart::Contact { settling, .. } if taylor => {
                        self.contact_taylor(t, xc, carried, settling)?
                    }
                    ContactStart::Contact { settling, f0 } => {
                        self.contact_rk(t, xc, carried, settling, f0)?
                    }
                },
                Next::Rocking {
                    t,
                    s,
                    x,
                    n,
                    carried,
                } if taylor => self.rocking_taylor(t, s, x, n, carried)?,
                Next::Rocking {
                    t,
                    s,
                    x,
                    n,
                    carried,
                } => self.rocking_rk(t, s, x, n, carried)?,
                Next::Done {
                    t,
                    phase,
                    s,
                    state,
                    carried,
                } => {
                    let summary = self.summary(t, phase, s, &state, carried, e_initial);
                    return Ok(Run {
                        summary,
                        events: self.rec.log,
                        history: self.rec.history,
                        coordinates: self.rec.coordinates,
                    });
                }
            };
        }
    }
}
