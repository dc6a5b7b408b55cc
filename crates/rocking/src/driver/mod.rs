//! The hybrid driver: full contact, rocking about either corner, impacts, overturning.
//!
//! The driver is generic over the kernel variant `V` (monomorphised: no run-time branch for absent
//! effects) and the ground motion `M`. Each phase runs one integrator from its start to its first
//! event; the loop here moves between phases and picks the integrator of each (Runge–Kutta or
//! Taylor, from the options):
//!
//! * **contact** (state `[u, u', W, D]`): events f_+ and f_- of eq (24) rising through zero
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
//! Rooms: `state` (the run's state and guards, the lowest file), `transitions` (uplift, rocking
//! events, impacts), `impact` (the impact policy, a pure function), `rk_phases` and
//! `taylor_phases` (one integrator each, they never call each other), `recorder` (maxima,
//! history, events, summary).

mod impact;
mod recorder;
mod rk_phases;
mod state;
mod taylor_phases;
mod transitions;

use rocking_kernels::kernels::index::energy as en;
use rocking_motion::GroundMotion;
use rocking_ode::{Options as OdeOptions, Tolerances};

use crate::error::SimError;
use crate::options::{Method, Options};
use crate::results::{Run, SolverStats};
use crate::structure::Structure;
use crate::taylor::TaylorVariant;
use state::{Next, Record, Sim, LEFT, RIGHT, Y};
use transitions::ContactStart;

/// Runs one simulation with kernel variant `V`; `ENERGY` switches the energy bookkeeping on.
pub fn simulate<V: TaylorVariant, M: GroundMotion + ?Sized, const ENERGY: bool>(
    structure: &Structure,
    motion: &M,
    opts: &Options,
) -> Result<Run, SimError> {
    if ENERGY {
        set_up::<V, M, 6, 4>(structure, motion, opts)?.run()
    } else {
        set_up::<V, M, 4, 2>(structure, motion, opts)?.run()
    }
}

/// The run's fixed quantities: the variant's own reference quantities and scales, tolerances.
fn set_up<'a, V: TaylorVariant, M: GroundMotion + ?Sized, const NR: usize, const NC: usize>(
    structure: &Structure,
    motion: &'a M,
    opts: &'a Options,
) -> Result<Sim<'a, V, M, NR, NC>, SimError> {
    opts.validate()?;
    if opts.accuracy.method == Method::Taylor && !motion.accel_series(0.0, &mut [0.0; 2]) {
        return Err(SimError::NoTaylorSeries);
    }
    let tol = opts.accuracy.tol;
    let derived = structure.derived_by::<V>();
    let p = structure.params::<V>();
    let (a, pf) = (derived.alpha, derived.p);
    let (u_scale, ud_scale) = if V::RIGID {
        (1.0, 1.0)
    } else {
        (derived.u_cr, derived.u_cr * derived.omega_n)
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
    let contact_scale: [f64; NC] = std::array::from_fn(|i| [u_scale, ud_scale, 1.0, 1.0][i]);
    let rocking_scale: [f64; NR] =
        std::array::from_fn(|i| [a, u_scale, a * pf, ud_scale, 1.0, 1.0][i]);
    let contact_tol = Tolerances {
        rtol: tol,
        atol: Y::<NC>::from_fn(|i, _| if i < 2 { contact_scale[i] * tol } else { off }),
    };
    let rocking_tol = Tolerances {
        rtol: tol,
        atol: Y::<NR>::from_fn(|i, _| if i < 4 { rocking_scale[i] * tol } else { off }),
    };
    let e0 = V::energy(&[0.0; 4], RIGHT, &p);
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
        rec: Record::default(),
    })
}

impl<V: TaylorVariant, M: GroundMotion + ?Sized, const NR: usize, const NC: usize>
    Sim<'_, V, M, NR, NC>
{
    /// From the initial state to the end of the run, one phase at a time.
    fn run(mut self) -> Result<Run, SimError> {
        let i = self.opts.initial;
        let x0 = [i.theta, i.u, i.theta_dot, i.u_dot];
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
                w: 0.0,
                d: 0.0,
            }
        } else {
            Next::Contact {
                t: 0.0,
                u: i.u,
                u_dot: i.u_dot,
                w: 0.0,
                d: 0.0,
                settle: false,
            }
        };
        let taylor = self.opts.accuracy.method == Method::Taylor;
        loop {
            next = match next {
                Next::Contact {
                    t,
                    u,
                    u_dot,
                    w,
                    d,
                    settle,
                } => {
                    let start = [u, u_dot, w, d];
                    match self.contact_start(t, start, settle)? {
                        ContactStart::Lifted(next) => next,
                        ContactStart::Contact { settling, .. } if taylor => {
                            self.contact_taylor(t, start, settling)?
                        }
                        ContactStart::Contact { settling, f0 } => {
                            self.contact_rk(t, start, settling, f0)?
                        }
                    }
                }
                Next::Rocking { t, s, x, n, w, d } if taylor => {
                    self.rocking_taylor(t, s, x, n, w, d)?
                }
                Next::Rocking { t, s, x, n, w, d } => self.rocking_rk(t, s, x, n, w, d)?,
                Next::Done {
                    t,
                    phase,
                    s,
                    state,
                    w,
                    d,
                } => {
                    let summary = self.summary(t, phase, s, &state, (w, d), e_initial);
                    return Ok(Run {
                        summary,
                        events: self.rec.log,
                        history: self.rec.history,
                    });
                }
            };
        }
    }
}
