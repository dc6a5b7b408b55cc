//! The hybrid driver: full contact, rocking about either corner, impacts, overturning.
//!
//! The driver is generic over the kernel variant `V` (monomorphised: no run-time branch for absent
//! effects) and the ground motion `M`. It owns two fixed-size integrators, one per phase, and
//! moves between them at located events:
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

use nalgebra::SVector;
use rocking_kernels::kernels::index::{
    energy as en, impact_adjex as ax, impact_housner as ho, impact_vvel as vv, power as pwr,
    rocking_rhs as rr,
};
use rocking_motion::GroundMotion;
use rocking_ode::events::{locate, Direction};
use rocking_ode::poly;
use rocking_ode::taylor::{Taylor, TaylorOptions, TaylorSystem};
use rocking_ode::{Integrator, OdeError, Options as OdeOptions, Tolerances};

use crate::dense::{StepView, TaylorStep};
use crate::options::{History, ImpactModel, Method, Options};
use crate::results::{
    EnergyBalance, EventKind, EventRecord, HistoryRow, Phase, Run, SolverStats, Summary, Time,
};
use crate::structure::{Derived, Structure};
use crate::taylor::{ContactSystem, RockingSystem, TaylorVariant};

/// Why a run failed.
#[derive(Debug, Clone, PartialEq)]
pub enum SimError {
    /// The integrator failed (step-size underflow, non-finite state, too many steps).
    Integration(OdeError),
    /// A guard on the number of events or steps fired: the run would not end.
    Guard(String),
    /// Invalid options.
    Options(String),
    /// The model itself became singular (see the message).
    Singular(String),
}

impl std::fmt::Display for SimError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            SimError::Integration(e) => write!(f, "{e}"),
            SimError::Guard(m) | SimError::Options(m) | SimError::Singular(m) => f.write_str(m),
        }
    }
}

impl std::error::Error for SimError {}

impl From<OdeError> for SimError {
    fn from(e: OdeError) -> Self {
        SimError::Integration(e)
    }
}

/// A phase's integrator state: the mechanical state, then W and D when they are carried.
type Y<const N: usize> = SVector<f64, N>;
type G2 = SVector<f64, 2>;

/// Where the hybrid system goes next.
enum Next {
    Contact {
        t: f64,
        u: f64,
        u_dot: f64,
        w: f64,
        d: f64,
        /// Just come to rest: no uplift before one step has been taken (see `contact`).
        settle: bool,
    },
    Rocking {
        t: f64,
        s: f64,
        x: [f64; 4],
        n: i32,
        w: f64,
        d: f64,
    },
    Done {
        t: f64,
        phase: Phase,
        s: f64,
        state: [f64; 4],
        w: f64,
        d: f64,
    },
}

/// Post-impact state chosen by an impact model.
enum After {
    Contact {
        u_dot: f64,
        energy: f64,
    },
    Rocking {
        theta_dot: f64,
        u_dot: f64,
        energy: f64,
    },
}

/// One run: `NR` and `NC` are the sizes of the rocking and contact states (4 and 2, or 6 and 4
/// with the energy integrals).
struct Sim<'a, V: TaylorVariant, M: GroundMotion + ?Sized, const NR: usize, const NC: usize> {
    p: V::Params,
    motion: &'a M,
    opts: &'a Options,
    derived: Derived,
    p_seconds: Option<f64>,
    rest_rate: f64,
    significant_rate: f64,
    v_rest: f64,
    ode_options: OdeOptions,
    contact_tol: Tolerances<NC>,
    rocking_tol: Tolerances<NR>,
    /// Natural scales of the phase states (the Taylor method integrates the state over them).
    contact_scale: [f64; NC],
    rocking_scale: [f64; NR],
    stats: SolverStats,
    max_theta: f64,
    max_u: f64,
    impacts: u64,
    significant: u64,
    energy_capped: u64,
    events: u64,
    first_uplift: Option<f64>,
    first_impact: Option<f64>,
    overturn: Option<f64>,
    losses: f64,
    log: Vec<EventRecord>,
    history: Vec<HistoryRow>,
    next_grid: f64,
}

const RIGHT: f64 = 1.0;
const LEFT: f64 = -1.0;

/// Runs one simulation with kernel variant `V`; `ENERGY` switches the energy bookkeeping on.
pub fn simulate<V: TaylorVariant, M: GroundMotion + ?Sized, const ENERGY: bool>(
    structure: &Structure,
    motion: &M,
    opts: &Options,
) -> Result<Run, SimError> {
    if ENERGY {
        run::<V, M, 6, 4>(structure, motion, opts)
    } else {
        run::<V, M, 4, 2>(structure, motion, opts)
    }
}

fn run<V: TaylorVariant, M: GroundMotion + ?Sized, const NR: usize, const NC: usize>(
    structure: &Structure,
    motion: &M,
    opts: &Options,
) -> Result<Run, SimError> {
    opts.validate().map_err(SimError::Options)?;
    if opts.accuracy.method == Method::Taylor && !motion.accel_series(0.0, &mut [0.0; 2]) {
        return Err(SimError::Options(
            "method = taylor needs the excitation's Taylor series, which this motion does not \
             give (the Ricker and Mavroeidis-Papageorgiou pulses): use dop853, or \
             Preset::accuracy_for, which does for this motion"
                .into(),
        ));
    }
    let tol = opts.accuracy.tol;
    // The running variant's own reference quantities and scales.
    let derived = structure.derived_by::<V>();
    let p = structure.params::<V>();
    let rigid = V::RIGID;
    let (a, pf) = (derived.alpha, derived.p);
    let u_scale = if rigid { 1.0 } else { derived.u_cr };
    let ud_scale = if rigid {
        1.0
    } else {
        derived.u_cr * derived.omega_n
    };
    let off = f64::INFINITY; // W and D take no part in the error control
    let ode = OdeOptions {
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
    let sim = Sim::<V, M, NR, NC> {
        p,
        motion,
        opts,
        derived,
        p_seconds: structure.p_per_second(),
        rest_rate: opts.rest_rate * a * pf,
        significant_rate: 0.01 * a * pf,
        v_rest: e0[en::GRAVITY] + e0[en::STRAIN],
        ode_options: ode,
        contact_tol,
        rocking_tol,
        contact_scale,
        rocking_scale,
        stats: SolverStats::default(),
        max_theta: 0.0,
        max_u: 0.0,
        impacts: 0,
        energy_capped: 0,
        significant: 0,
        events: 0,
        first_uplift: None,
        first_impact: None,
        overturn: None,
        losses: 0.0,
        log: Vec::new(),
        history: Vec::new(),
        next_grid: 0.0,
    };
    sim.run()
}

impl<'a, V: TaylorVariant, M: GroundMotion + ?Sized, const NR: usize, const NC: usize>
    Sim<'a, V, M, NR, NC>
{
    /// Whether W and D are carried (the energy bookkeeping was asked for).
    const ENERGY: bool = NR > 4;

    fn time(&self, t: f64) -> Time {
        let tau = t * self.derived.p;
        Time {
            tau,
            seconds: self.p_seconds.map(|ps| tau / ps),
        }
    }

    fn total_energy(&self, x: &[f64; 4], s: f64) -> f64 {
        let e = V::energy(x, s, &self.p);
        e[en::KINETIC] + e[en::GRAVITY] + e[en::STRAIN] - self.v_rest
    }

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
        let (t_end, phase, s_end, state, w, d) = loop {
            next = match next {
                Next::Contact {
                    t,
                    u,
                    u_dot,
                    w,
                    d,
                    settle,
                } => self.contact(t, u, u_dot, w, d, settle)?,
                Next::Rocking { t, s, x, n, w, d } => self.rocking(t, s, x, n, w, d)?,
                Next::Done {
                    t,
                    phase,
                    s,
                    state,
                    w,
                    d,
                } => break (t, phase, s, state, w, d),
            };
        };
        let e_ref = self.derived.e_ref;
        let (energy, residual) = if Self::ENERGY {
            let last = self.total_energy(&state, s_end);
            let residual = (last - e_initial - w + d + self.losses) / e_ref;
            let balance = EnergyBalance {
                initial: e_initial / e_ref,
                last: last / e_ref,
                ground_work: w / e_ref,
                damping: d / e_ref,
                impact_losses: self.losses / e_ref,
            };
            (Some(balance), Some(residual))
        } else {
            (None, None)
        };
        let rigid = V::RIGID;
        let summary = Summary {
            kernel_variant: V::NAME,
            max_theta_over_alpha: self.max_theta / self.derived.alpha,
            max_theta_over_theta_cr: self.max_theta / self.derived.theta_cr,
            max_u_over_ucr: if rigid {
                0.0
            } else {
                self.max_u / self.derived.u_cr
            },
            overturned: self.overturn.is_some(),
            overturn_time: self.overturn.map(|t| self.time(t)),
            impacts: self.impacts,
            significant_impacts: self.significant,
            energy_capped_impacts: self.energy_capped,
            first_uplift_time: self.first_uplift.map(|t| self.time(t)),
            first_impact_time: self.first_impact.map(|t| self.time(t)),
            final_phase: phase,
            end_time: self.time(t_end),
            energy_balance_residual: residual,
            energy,
            solver_stats: self.stats,
        };
        Ok(Run {
            summary,
            events: self.log,
            history: self.history,
        })
    }

    fn track(&mut self, x: &[f64; 4]) {
        self.max_theta = self.max_theta.max(x[0].abs());
        self.max_u = self.max_u.max(x[1].abs());
    }

    fn count_event(&mut self, t: f64) -> Result<(), SimError> {
        self.events += 1;
        if self.events > self.opts.max_events {
            return Err(SimError::Guard(format!(
                "more than {} events by τ = {:.6}: the run does not settle (raise max_events, or the rest rate)",
                self.opts.max_events,
                self.time(t).tau
            )));
        }
        Ok(())
    }

    fn t_stop(&self, t: f64) -> f64 {
        self.motion
            .next_kink(t)
            .map_or(self.opts.t_end, |k| k.min(self.opts.t_end))
    }

    fn record_history(&mut self, t: f64, x: &[f64; 4], phase: Phase, s: f64) {
        let e = V::energy(x, s, &self.p);
        let row = HistoryRow {
            tau: t * self.derived.p,
            theta: x[0],
            u: x[1],
            theta_dot: x[2],
            u_dot: x[3],
            phase,
            e_kin: e[en::KINETIC] / self.derived.e_ref,
            e_total: (e[en::KINETIC] + e[en::GRAVITY] + e[en::STRAIN] - self.v_rest)
                / self.derived.e_ref,
            ug: self.motion.accel(t),
        };
        self.history.push(row);
    }

    /// History rows for the step (t_old, t_new] of a phase, from the dense output.
    fn step_history(
        &mut self,
        t_old: f64,
        t_new: f64,
        at: impl Fn(f64) -> [f64; 4],
        phase: Phase,
        s: f64,
    ) {
        match self.opts.history {
            History::None => {}
            History::Steps => self.record_history(t_new, &at(t_new), phase, s),
            History::Grid(dt) => {
                while self.next_grid <= t_new {
                    if self.next_grid >= t_old {
                        let tg = self.next_grid;
                        self.record_history(tg, &at(tg), phase, s);
                    }
                    self.next_grid += dt;
                }
            }
        }
    }

    fn log_event(
        &mut self,
        t: f64,
        kind: EventKind,
        branch: &'static str,
        phase_after: Phase,
        pre: [f64; 3],
        energies: (f64, f64),
    ) {
        if self.opts.event_log {
            let e_ref = self.derived.e_ref;
            self.log.push(EventRecord {
                time: self.time(t),
                kind,
                branch,
                phase_after,
                theta_dot: pre[0],
                u: pre[1],
                u_dot: pre[2],
                energy_before: energies.0 / e_ref,
                energy_after: energies.1 / e_ref,
            });
        }
    }

    /// The uplift test at the start of a contact phase and at every step.
    fn uplift_functions(&self, u: f64, u_dot: f64, ug: f64) -> G2 {
        let xc = [u, u_dot];
        G2::new(
            V::uplift(&xc, ug, RIGHT, &self.p),
            V::uplift(&xc, ug, LEFT, &self.p),
        )
    }

    /// In contact after the excitation: can the column's vibration energy ever uplift the base?
    /// f_s is affine in (u, u') and the free vibration stays inside the energy ellipse, so the
    /// largest reachable f_s is f_s(0) + sqrt(2 E (a²/k̃ + b²/m̃)).
    fn can_never_uplift(&self, u: f64, u_dot: f64) -> bool {
        let f = |a: f64, b: f64| V::uplift(&[a, b], 0.0, RIGHT, &self.p);
        let (c, a, b) = (
            f(0.0, 0.0),
            f(1.0, 0.0) - f(0.0, 0.0),
            f(0.0, 1.0) - f(0.0, 0.0),
        );
        let e = V::energy(&[0.0, u, 0.0, u_dot], RIGHT, &self.p);
        let vib = e[en::KINETIC] + e[en::STRAIN];
        let reach =
            (2.0 * vib * (a * a / self.derived.k_tilde + b * b / self.derived.m_tilde)).sqrt();
        c + reach < 0.0
    }

    /// Whether the base really lifts about `s` at `t` from full contact: the rocking equations
    /// give s θ'' > 0. It is equivalent to f_s > 0 (equations.md 1.2) except within rounding of
    /// f_s = 0, where it decides consistently with the integrator that will follow: with the
    /// Taylor method, θ'' is that integrator's first coefficient, computed as its first step
    /// will (the Taylor-mode kernel regroups the tape, so the pointwise θ'' may differ from it
    /// in the last bits and a lift decided on it could turn back at once); `ug` is ü_g(t) for
    /// the Runge–Kutta methods.
    fn lifts(&self, s: f64, t: f64, u: f64, u_dot: f64, ug: f64) -> bool {
        if self.opts.accuracy.method == Method::Taylor {
            let y0 = self.rocking_start([0.0, u, 0.0, u_dot], 0.0, 0.0);
            let mut x: [[f64; 2]; NR] = std::array::from_fn(|i| [y0[i], 0.0]);
            self.rocking_system(s).coefficients::<2>(t, &mut x);
            return s * x[2][1] > 0.0;
        }
        s * V::rocking_rhs(&[0.0, u, 0.0, u_dot], ug, s, &self.p)[rr::THETA_DDOT] > 0.0
    }

    /// The first time in [t_a, t_b] at which the base lifts about `s`, given that f_s rises
    /// through zero at t_a; `None` when it lifts nowhere in (t_a, t_b] (a rounding-level
    /// excursion of f_s).
    fn first_lift(
        &self,
        dense: impl Fn(f64) -> [f64; 4],
        s: f64,
        t_a: f64,
        t_b: f64,
    ) -> Option<f64> {
        let lifts_at = |t: f64| {
            let y = dense(t);
            self.lifts(s, t, y[1], y[3], self.motion.accel(t))
        };
        if lifts_at(t_a) {
            return Some(t_a);
        }
        // f_s may fall below zero again before t_b (an excursion shorter than a long Taylor
        // step): bring t_b halfway back to t_a until the base lifts there, or until the gap is
        // a rounding-level one.
        let mut t_b = t_b;
        while !lifts_at(t_b) {
            let mid = 0.5 * (t_a + t_b);
            if mid <= t_a || mid >= t_b {
                return None;
            }
            t_b = mid;
        }
        let (mut lo, mut hi) = (t_a, t_b);
        while hi - lo > 4.0 * f64::EPSILON * hi.abs().max(1.0) {
            let mid = 0.5 * (lo + hi);
            if lifts_at(mid) {
                hi = mid;
            } else {
                lo = mid;
            }
        }
        Some(hi)
    }

    /// The longest contact step from `t0`: the excitation's resolution while it lasts.
    fn contact_h_max(&self, t0: f64) -> f64 {
        if t0 < self.motion.end() {
            self.motion.resolution()
        } else {
            f64::INFINITY
        }
    }

    /// Integrator options for a contact phase starting at `t0`.
    fn phase_options(&self, t0: f64) -> OdeOptions {
        OdeOptions {
            h_max: self.contact_h_max(t0),
            ..self.ode_options
        }
    }

    /// The guard on the total number of step attempts of a run.
    fn guard_steps<const N: usize>(&self, ode: &Integrator<N>) -> Result<(), SimError> {
        self.guard_step_count(ode.stats(), ode.t())
    }

    fn guard_step_count(&self, st: rocking_ode::Stats, t: f64) -> Result<(), SimError> {
        let steps = self.stats.steps + self.stats.rejected_steps + st.steps + st.rejected;
        if steps > self.opts.max_steps {
            return Err(SimError::Guard(format!(
                "more than {} integrator steps by τ = {:.6}: the run does not end (raise max_steps)",
                self.opts.max_steps,
                self.time(t).tau
            )));
        }
        Ok(())
    }

    /// An integration failure while rocking, explained when the mass matrix became singular.
    fn explain_failure(&self, e: OdeError, y: &[f64], s: f64) -> SimError {
        let [mtt, mtu, muu] = V::mass_matrix(&[y[0], y[1]], s, &self.p);
        let conditioning = (mtt * muu - mtu * mtu) / (mtt * muu);
        if conditioning.is_finite() && conditioning > 1e-8 {
            return SimError::Integration(e);
        }
        SimError::Singular(format!(
            "the mass matrix became singular at τ = {:.6} (det M / (M_θθ M_uu) = {conditioning:.1e}, \
             u/u_cr = {:.1}): with a massless column the top mass is then above the pivot and θ and u \
             cannot be told apart; such deflections are far outside the model's validity ({e})",
            self.time(e.t).tau,
            y[1] / self.derived.u_cr,
        ))
    }

    /// Full contact from `t0`. The uplift functions are checked at once (after an impact this is
    /// how the rigid limit works), except when the structure has just come to rest (`settle`):
    /// then a first step is taken before an uplift is possible, so that a grazing excursion of
    /// f_s cannot make the run chatter at one instant.
    #[allow(clippy::too_many_arguments)]
    fn contact(
        &mut self,
        t0: f64,
        u: f64,
        u_dot: f64,
        w: f64,
        d: f64,
        settle: bool,
    ) -> Result<Next, SimError> {
        let ug0 = self.motion.accel_right(t0);
        let f = self.uplift_functions(u, u_dot, ug0);
        for (k, s) in [(0, RIGHT), (1, LEFT)] {
            if !settle && f[k] > 0.0 && self.lifts(s, t0, u, u_dot, ug0) {
                return self.uplift(t0, s, u, u_dot, w, d);
            }
        }
        if self.opts.accuracy.method == Method::Taylor {
            return self.contact_taylor(t0, [u, u_dot, w, d], settle);
        }
        // The settling step exists for an f_s already above zero at the rest (a grazing
        // excursion that would make the run chatter at one instant); with every f_s below zero
        // the first step looks for crossings inside it as every step does (placing a crossing of
        // the first step at its end delayed a near-rigid column's uplift by a tenth of its
        // period: 1e-4 τ at DOP853 1e-10, `an_uplift_after_a_rest_is_located_inside_the_first_step`).
        let mut settling = settle && f.iter().any(|g| *g > 0.0);
        let full_history = !matches!(self.opts.history, History::None);
        let may_stop = self.opts.stop_when_known && !full_history;
        let (p, motion) = (self.p, self.motion);
        let mut rhs = |t: f64, y: &Y<NC>| -> Y<NC> {
            let ug = motion.accel(t);
            let dx = V::contact_rhs(&[y[0], y[1]], ug, &p);
            let mut out = Y::<NC>::zeros();
            out[0] = dx[0];
            out[1] = dx[1];
            if Self::ENERGY {
                let pw = V::power(&[0.0, y[0], 0.0, y[1]], ug, RIGHT, &p);
                out[2] = pw[pwr::GROUND];
                out[3] = pw[pwr::DAMPING];
            }
            out
        };
        let mut g = |t: f64, y: &Y<NC>| -> G2 {
            let ug = motion.accel(t);
            G2::new(
                V::uplift(&[y[0], y[1]], ug, RIGHT, &p),
                V::uplift(&[y[0], y[1]], ug, LEFT, &p),
            )
        };
        // A rigid column in contact gives the error control nothing to follow: the steps are
        // bounded by the excitation's resolution, so that no excursion of f_s falls between them.
        let mut ode = Integrator::new(self.phase_options(t0), self.contact_tol)?;
        ode.reset(t0, Y::<NC>::from_fn(|i, _| [u, u_dot, w, d][i]), &mut rhs)?;
        let mut g_old = f;
        let dirs = [Direction::Rising, Direction::Rising];
        let excitation_end = motion.end();
        loop {
            let t_stop = self.t_stop(ode.t());
            let info = ode.step(&mut rhs, t_stop)?;
            self.guard_steps(&ode)?;
            let (t_old, t_new) = (info.t_old, info.t_new);
            let g_new = g(t_new, ode.y());
            let located =
                locate(&mut ode, &mut g, &dirs, &g_old, &g_new).map(|ev| (ev.t, ev.index, t_new));
            // In the settling step, an f_s that started above zero and is still there at its end
            // lifts at the end; a rising crossing of one that started below zero is an uplift.
            let crossing = if std::mem::take(&mut settling) {
                located.or_else(|| (0..2).find(|&k| g_new[k] > 0.0).map(|k| (t_new, k, t_new)))
            } else {
                located.or_else(|| grazing(&mut g, &|t| ode.dense(t), t_old, t_new, &g_old, &g_new))
            };
            let lift = crossing.and_then(|(t_up, index, t_far)| {
                let s = if index == 0 { RIGHT } else { LEFT };
                self.first_lift(|t| contact_state(&ode.dense(t)), s, t_up, t_far)
                    .map(|t| (t, index))
            });
            if let Some((t_up, index)) = lift {
                let dense = |t| contact_state(&ode.dense(t));
                self.extremes_contact(&dense, t_old, t_up);
                let y = ode.dense(t_up);
                self.step_history(
                    t_old,
                    t_up,
                    |t| contact_state(&ode.dense(t)),
                    Phase::Contact,
                    RIGHT,
                );
                self.stats.add(ode.take_stats());
                let s = if index == 0 { RIGHT } else { LEFT };
                let (w, d) = carried(&y, 2);
                return self.uplift(t_up, s, y[0], y[1], w, d);
            }
            let dense = |t| contact_state(&ode.dense(t));
            self.extremes_contact(&dense, t_old, t_new);
            self.step_history(
                t_old,
                t_new,
                |t| contact_state(&ode.dense(t)),
                Phase::Contact,
                RIGHT,
            );
            g_old = g_new;
            let y = *ode.y();
            let done = t_new >= self.opts.t_end
                || (may_stop && t_new >= excitation_end && self.can_never_uplift(y[0], y[1]));
            if done {
                self.stats.add(ode.take_stats());
                let (w, d) = carried(&y, 2);
                return Ok(Next::Done {
                    t: t_new,
                    phase: Phase::Contact,
                    s: RIGHT,
                    state: [0.0, y[0], 0.0, y[1]],
                    w,
                    d,
                });
            }
        }
    }

    fn uplift(
        &mut self,
        t: f64,
        s: f64,
        u: f64,
        u_dot: f64,
        w: f64,
        d: f64,
    ) -> Result<Next, SimError> {
        self.count_event(t)?;
        self.first_uplift.get_or_insert(t);
        let e = V::energy(&[0.0, u, 0.0, u_dot], s, &self.p)[en::KINETIC];
        self.log_event(
            t,
            EventKind::Uplift,
            "",
            Phase::rocking(s),
            [0.0, u, u_dot],
            (e, e),
        );
        Ok(Next::Rocking {
            t,
            s,
            x: [0.0, u, 0.0, u_dot],
            n: 2,
            w,
            d,
        })
    }

    /// max |u| within a contact step, including a turning point inside it.
    fn extremes_contact(&mut self, step: &impl StepView, t_old: f64, t_new: f64) {
        let (a, b) = (step.state(t_old), step.state(t_new));
        self.max_u = self.max_u.max(b[1].abs());
        if a[3] * b[3] < 0.0 && step.bound(1) > self.max_u {
            let tm = turning_point(|t| step.component(3, t), t_old, t_new, a[3]);
            self.max_u = self.max_u.max(step.component(1, tm).abs());
        }
    }

    /// max |θ| and |u| within a rocking step, including turning points inside it.
    fn extremes_rocking(&mut self, step: &impl StepView, t_old: f64, t_new: f64) {
        const SAMPLES: u32 = 32;
        let (a, b) = (step.state(t_old), step.state(t_new));
        self.track(&[b[0], b[1], 0.0, 0.0]);
        for (pos, rate) in [(0usize, 2usize), (1, 3)] {
            let max = if pos == 0 { self.max_theta } else { self.max_u };
            if step.bound(pos) <= max {
                continue;
            }
            // A step from rest (θ' = 0 at an uplift) has no sign change at its ends: its first
            // turning point lies after a point of the other sign than the end's, which one of
            // a few samples finds unless the excursion is far shorter than the step.
            let start = if a[rate] == 0.0 && b[rate] != 0.0 {
                (1..SAMPLES)
                    .map(|j| t_old + (t_new - t_old) * f64::from(j) / f64::from(SAMPLES))
                    .map(|t| (t, step.component(rate, t)))
                    .find(|&(_, r)| r * b[rate] < 0.0)
            } else {
                Some((t_old, a[rate]))
            };
            if let Some((ta, ra)) = start.filter(|&(_, r)| r * b[rate] < 0.0) {
                let tm = turning_point(|t| step.component(rate, t), ta, t_new, ra);
                let y = step.component(pos, tm).abs();
                if pos == 0 {
                    self.max_theta = self.max_theta.max(y);
                } else {
                    self.max_u = self.max_u.max(y);
                }
            }
        }
    }

    #[allow(clippy::too_many_arguments)]
    fn rocking(
        &mut self,
        t0: f64,
        s: f64,
        x0: [f64; 4],
        n: i32,
        w: f64,
        d: f64,
    ) -> Result<Next, SimError> {
        if self.opts.accuracy.method == Method::Taylor {
            return self.rocking_taylor(t0, s, x0, n, w, d);
        }
        let (p, motion) = (self.p, self.motion);
        let over = self.opts.overturn_angle;
        let mut rhs = |t: f64, y: &Y<NR>| -> Y<NR> {
            let ug = motion.accel(t);
            let x = [y[0], y[1], y[2], y[3]];
            let dx = V::rocking_rhs(&x, ug, s, &p);
            let mut out = Y::<NR>::zeros();
            out.fixed_rows_mut::<4>(0).copy_from_slice(&dx);
            if Self::ENERGY {
                let pw = V::power(&x, ug, s, &p);
                out[4] = pw[pwr::GROUND];
                out[5] = pw[pwr::DAMPING];
            }
            out
        };
        // The impact event s θ / (t − t0)^n, with its limit at t0 (equations.md §5, note 4).
        let start_limit = if n == 0 {
            s * x0[0]
        } else if n == 1 {
            s * x0[2]
        } else {
            s * V::rocking_rhs(&x0, motion.accel_right(t0), s, &p)[rr::THETA_DDOT] / 2.0
        };
        // An uplift exactly at f_s = 0 has θ'' = 0: keep the event armed (it fires at once if θ
        // turns back, which ends the zero-length rocking phase with an impact).
        let start_limit = start_limit.max(f64::MIN_POSITIVE);
        let mut g = |t: f64, y: &Y<NR>| -> G2 {
            let dt = t - t0;
            let impact = if dt > 0.0 {
                s * y[0] / dt.powi(n)
            } else {
                start_limit
            };
            G2::new(impact, s * y[0] - over)
        };
        let y0 = Y::<NR>::from_fn(|i, _| [x0[0], x0[1], x0[2], x0[3], w, d][i]);
        let mut ode = Integrator::new(self.ode_options, self.rocking_tol)?;
        ode.reset(t0, y0, &mut rhs)?;
        let mut g_old = g(t0, &y0);
        let dirs = [Direction::Falling, Direction::Rising];
        let phase = Phase::rocking(s);
        loop {
            let t_stop = self.t_stop(ode.t());
            let info = ode
                .step(&mut rhs, t_stop)
                .map_err(|e| self.explain_failure(e, ode.y().as_slice(), s))?;
            self.guard_steps(&ode)?;
            let (t_old, t_new) = (info.t_old, info.t_new);
            let g_new = g(t_new, ode.y());
            if let Some(ev) = locate(&mut ode, &mut g, &dirs, &g_old, &g_new) {
                let dense = |t| rocking_state(&ode.dense(t));
                self.extremes_rocking(&dense, t_old, ev.t);
                self.step_history(t_old, ev.t, |t| rocking_state(&ode.dense(t)), phase, s);
                self.stats.add(ode.take_stats());
                let y = ev.y;
                let (w, d) = carried(&y, 4);
                return self.rocking_event(ev.index, ev.t, s, rocking_state(&y), w, d);
            }
            let dense = |t| rocking_state(&ode.dense(t));
            self.extremes_rocking(&dense, t_old, t_new);
            self.step_history(t_old, t_new, |t| rocking_state(&ode.dense(t)), phase, s);
            g_old = g_new;
            if t_new >= self.opts.t_end {
                let y = *ode.y();
                self.stats.add(ode.take_stats());
                let (w, d) = carried(&y, 4);
                return Ok(Next::Done {
                    t: t_new,
                    phase,
                    s,
                    state: [y[0], y[1], y[2], y[3]],
                    w,
                    d,
                });
            }
        }
    }

    /// The event `index` (0 impact, 1 overturning) of a rocking phase about `s` at `t`, state `x`.
    fn rocking_event(
        &mut self,
        index: usize,
        t: f64,
        s: f64,
        x: [f64; 4],
        w: f64,
        d: f64,
    ) -> Result<Next, SimError> {
        if index == 0 {
            return self.impact(t, s, [x[1], x[3], x[2]], w, d);
        }
        self.count_event(t)?;
        self.overturn = Some(t);
        self.track(&x);
        let e = V::energy(&x, s, &self.p)[en::KINETIC];
        self.log_event(
            t,
            EventKind::Overturn,
            "",
            Phase::Overturned,
            [x[2], x[1], x[3]],
            (e, e),
        );
        Ok(Next::Done {
            t,
            phase: Phase::Overturned,
            s,
            state: x,
            w,
            d,
        })
    }

    /// A Taylor integrator for a phase: order from the tolerance, the mechanical components
    /// controlled (W and D carried).
    fn taylor<const N: usize>(
        &self,
        h_max: f64,
        t0: f64,
        y0: [f64; N],
        mechanical: usize,
    ) -> Result<Taylor<N>, SimError> {
        let opts = TaylorOptions {
            h_max,
            max_steps: self.opts.max_steps,
            controlled: std::array::from_fn(|i| i < mechanical),
            ..TaylorOptions::new(self.opts.accuracy.tol)
        };
        let mut ode = Taylor::new(opts)?;
        ode.reset(t0, y0)?;
        Ok(ode)
    }

    /// Full contact from `t0` with the Taylor method (see [`Self::contact`]; the uplift
    /// functions' series along each step are the event polynomials).
    fn contact_taylor(
        &mut self,
        t0: f64,
        start: [f64; 4],
        mut settling: bool,
    ) -> Result<Next, SimError> {
        let scale = self.contact_scale;
        let y0: [f64; NC] = std::array::from_fn(|i| start[i] / scale[i]);
        let mut ode = self.taylor(self.contact_h_max(t0), t0, y0, 2)?;
        let mut sys = ContactSystem::<V, M, NC> {
            p: self.p,
            motion: self.motion,
            scale,
        };
        let unscale = |y: [f64; NC]| -> [f64; NC] { std::array::from_fn(|i| y[i] * scale[i]) };
        let may_stop = self.opts.stop_when_known && matches!(self.opts.history, History::None);
        let excitation_end = self.motion.end();
        // The settling step exists for an f_s already above zero at the rest (a grazing
        // excursion that would make the run chatter at one instant); otherwise the first step
        // looks for crossings inside it as usual (as in the Runge–Kutta path).
        if settling {
            let g0 = self.uplift_functions(start[0], start[1], self.motion.accel_right(t0));
            settling = g0.iter().any(|g| *g > 0.0);
        }
        loop {
            let t_stop = self.t_stop(ode.t());
            ode.step(&mut sys, t_stop)?;
            self.guard_step_count(ode.stats(), ode.t())?;
            let (t_old, t_new) = (ode.t_old(), ode.t());
            let dirs = [Direction::Rising, Direction::Rising];
            let rising = ode.locate(&mut sys, &dirs).map(|ev| (ev.t, ev.index));
            // A rising root inside the settling step comes after f_s fell below zero: a real
            // uplift, as on any step (missed when only the end was looked at, once steps grew to
            // a fraction of the period).
            let crossing = if std::mem::take(&mut settling) && rising.is_none() {
                let y = unscale(*ode.y());
                let g_new = self.uplift_functions(y[0], y[1], self.motion.accel(t_new));
                (0..2).find(|&k| g_new[k] > 0.0).map(|k| (t_new, k))
            } else {
                rising
            };
            let step = TaylorStep {
                ode: &ode,
                scale,
                rows: [None, Some(0), None, Some(1)],
            };
            let dense = |t: f64| step.state(t);
            let lift = crossing.and_then(|(t_up, index)| {
                let s = if index == 0 { RIGHT } else { LEFT };
                self.first_lift(dense, s, t_up, t_new).map(|t| (t, s))
            });
            if let Some((t_up, s)) = lift {
                self.extremes_contact(&step, t_old, t_up);
                self.step_history(t_old, t_up, dense, Phase::Contact, RIGHT);
                self.stats.add(ode.take_stats());
                let y = unscale(ode.dense(t_up));
                let (w, d) = carried_array(&y, 2);
                return self.uplift(t_up, s, y[0], y[1], w, d);
            }
            self.extremes_contact(&step, t_old, t_new);
            self.step_history(t_old, t_new, dense, Phase::Contact, RIGHT);
            let y = unscale(*ode.y());
            let done = t_new >= self.opts.t_end
                || (may_stop && t_new >= excitation_end && self.can_never_uplift(y[0], y[1]));
            if done {
                self.stats.add(ode.take_stats());
                let (w, d) = carried_array(&y, 2);
                return Ok(Next::Done {
                    t: t_new,
                    phase: Phase::Contact,
                    s: RIGHT,
                    state: [0.0, y[0], 0.0, y[1]],
                    w,
                    d,
                });
            }
        }
    }

    /// The rocking phase about `s` as the Taylor integrator sees it.
    fn rocking_system(&self, s: f64) -> RockingSystem<'a, V, M, NR> {
        RockingSystem {
            p: self.p,
            motion: self.motion,
            s,
            scale: self.rocking_scale,
        }
    }

    /// The scaled Taylor state of `[θ, u, θ', u']` and the carried integrals `W`, `D`.
    fn rocking_start(&self, x: [f64; 4], w: f64, d: f64) -> [f64; NR] {
        let start = [x[0], x[1], x[2], x[3], w, d];
        std::array::from_fn(|i| start[i] / self.rocking_scale[i])
    }

    /// Rocking about `s` from `t0` with the Taylor method (see [`Self::rocking`]). The impact is
    /// the first falling root of s θ's polynomial on a step, the overturning the first rising root
    /// of s θ − θ_over's. The start guard of the RK path is exact here: at the phase start θ and,
    /// after an uplift, θ' are exactly 0, so the polynomial's factor τ^n is exact and
    /// [`poly::first_root`] divides it out before it looks for a root.
    #[allow(clippy::too_many_arguments)]
    fn rocking_taylor(
        &mut self,
        t0: f64,
        s: f64,
        x0: [f64; 4],
        n: i32,
        w: f64,
        d: f64,
    ) -> Result<Next, SimError> {
        let scale = self.rocking_scale;
        let y0 = self.rocking_start(x0, w, d);
        let mut ode = self.taylor(f64::INFINITY, t0, y0, 4)?;
        let mut sys = self.rocking_system(s);
        let unscale = |y: [f64; NR]| -> [f64; NR] { std::array::from_fn(|i| y[i] * scale[i]) };
        let over = self.opts.overturn_angle / scale[0];
        let phase = Phase::rocking(s);
        loop {
            let t_stop = self.t_stop(ode.t());
            ode.step(&mut sys, t_stop)
                .map_err(|e| self.explain_failure(e, &unscale(*ode.y()), s))?;
            self.guard_step_count(ode.stats(), ode.t())?;
            let (t_old, t_new) = (ode.t_old(), ode.t());
            let h = t_new - t_old;
            let order = ode.order();
            let theta = &ode.coefficients()[0][..=order];
            let mut g = [[0.0; 21]; 2];
            for (k, &c) in theta.iter().enumerate() {
                g[0][k] = s * c;
                g[1][k] = s * c;
            }
            g[1][0] -= over;
            // An uplift exactly at f_s = 0 (θ'' = 0) that turns back at once: an impact at t0,
            // as the RK path's armed event fires at its first step.
            let first = t_old == t0 && n > 0;
            let turns_back = first && g[0].iter().find(|c| **c != 0.0).is_some_and(|c| *c < 0.0);
            // One bound of θ's change over the step rules out both events on most steps.
            let tail = theta[1..]
                .iter()
                .rev()
                .fold(0.0, |acc, c| (acc + c.abs()) * h);
            let root = |g: &[f64], dir| {
                let far = poly::far_from_zero(g[0], tail, order);
                (!far).then(|| poly::first_root(g, h, dir).map(|r| r.tau))?
            };
            let roots: [Option<f64>; 2] = if turns_back {
                [Some(0.0), None]
            } else {
                [
                    root(&g[0][..=order], Direction::Falling),
                    root(&g[1][..=order], Direction::Rising),
                ]
            };
            // The earliest; the impact on ties.
            let event = roots
                .iter()
                .enumerate()
                .filter_map(|(i, r)| r.map(|tau| (i, tau)))
                .min_by(|a, b| a.1.total_cmp(&b.1));
            let step = TaylorStep {
                ode: &ode,
                scale,
                rows: [Some(0), Some(1), Some(2), Some(3)],
            };
            let dense = |t: f64| step.state(t);
            if let Some((index, tau)) = event {
                // Strictly after t_old for a root inside the step, even below t_old's ulp.
                let t = if tau >= h {
                    t_new
                } else if tau == 0.0 {
                    t_old
                } else {
                    (t_old + tau).max(after(t_old)).min(t_new)
                };
                self.extremes_rocking(&step, t_old, t);
                self.step_history(t_old, t, dense, phase, s);
                self.stats.add(ode.take_stats());
                self.stats.events += 1;
                let y = unscale(ode.dense(t));
                let (w, d) = carried_array(&y, 4);
                return self.rocking_event(index, t, s, rocking_state_array(&y), w, d);
            }
            self.extremes_rocking(&step, t_old, t_new);
            self.step_history(t_old, t_new, dense, phase, s);
            if t_new >= self.opts.t_end {
                let y = unscale(*ode.y());
                self.stats.add(ode.take_stats());
                let (w, d) = carried_array(&y, 4);
                return Ok(Next::Done {
                    t: t_new,
                    phase,
                    s,
                    state: rocking_state_array(&y),
                    w,
                    d,
                });
            }
        }
    }

    /// No impact may create kinetic energy. Housner's rule and a fixed restitution conserve
    /// angular momentum or scale θ' alone, which on a deformable column can raise the kinetic
    /// energy (the paper says so for ADJex). Where a map's post-impact state has more kinetic
    /// energy than before the impact (beyond rounding, 1e-9 relative), its velocities are
    /// scaled down by one common factor to keep exactly the pre-impact kinetic energy: the
    /// direction of motion the map chose is kept, and no energy is created. Returns the state
    /// and whether it was capped (counted in the summary, named `*-energy-capped` in the log).
    fn without_energy_gain(
        &mut self,
        after: After,
        e_before: f64,
        u: f64,
        s: f64,
    ) -> (After, bool) {
        let p = &self.p;
        // Kinetic energy is a quadratic form in the velocities, so it scales with k².
        let (e_after, rest) = match after {
            After::Contact { energy, .. } | After::Rocking { energy, .. } => {
                (energy, V::energy(&[0.0, u, 0.0, 0.0], s, p)[en::KINETIC])
            }
        };
        let (t_before, t_after) = (e_before - rest, e_after - rest);
        let gains = t_after > t_before * (1.0 + 1e-9) && t_after > 0.0;
        if !gains {
            return (after, false);
        }
        self.energy_capped += 1;
        let k = (t_before.max(0.0) / t_after).sqrt();
        let capped = match after {
            After::Contact { u_dot, .. } => {
                let ud = k * u_dot;
                After::Contact {
                    u_dot: ud,
                    energy: V::energy(&[0.0, u, 0.0, ud], s, p)[en::KINETIC],
                }
            }
            After::Rocking {
                theta_dot, u_dot, ..
            } => {
                let (td, ud) = (k * theta_dot, k * u_dot);
                After::Rocking {
                    theta_dot: td,
                    u_dot: ud,
                    energy: V::energy(&[0.0, u, td, ud], s, p)[en::KINETIC],
                }
            }
        };
        (capped, true)
    }

    /// The impact at θ = 0 while rocking about `s`: the corner −s hits the ground.
    fn impact(&mut self, t: f64, s: f64, xi: [f64; 3], w: f64, d: f64) -> Result<Next, SimError> {
        self.count_event(t)?;
        let [u, u_dot, theta_dot] = xi;
        if theta_dot.abs() >= self.significant_rate {
            self.significant += 1;
        }
        let p = &self.p;
        let s2 = -s;
        let contact_energy = |ud: f64| V::energy(&[0.0, u, 0.0, ud], s2, p)[en::KINETIC];
        if theta_dot.abs() < self.rest_rate {
            // A negligible rocking excursion (grazing, or the end of a Zeno sequence): the base
            // settles in full contact with the column's motion unchanged.
            let e_before = V::energy(&[0.0, u, theta_dot, u_dot], s, p)[en::KINETIC];
            let after = After::Contact {
                u_dot,
                energy: contact_energy(u_dot),
            };
            let (after, capped) = self.without_energy_gain(after, e_before, u, s);
            let pre = [theta_dot, u, u_dot];
            let (After::Contact { u_dot, energy } | After::Rocking { u_dot, energy, .. }) = after;
            let e_after = energy;
            self.losses += e_before - e_after;
            self.log_event(
                t,
                EventKind::Rest,
                if capped { "rest-energy-capped" } else { "rest" },
                Phase::Contact,
                pre,
                (e_before, e_after),
            );
            return Ok(Next::Contact {
                t,
                u,
                u_dot,
                w,
                d,
                settle: true,
            });
        }
        self.impacts += 1;
        self.first_impact.get_or_insert(t);
        let rocking_energy = |td: f64, ud: f64| V::energy(&[0.0, u, td, ud], s2, p)[en::KINETIC];
        let (after, branch, e_before) = match self.opts.impact {
            ImpactModel::Vvel => {
                let v = V::impact_vvel(&xi, s, p);
                if v[vv::ROCK] != 0.0 {
                    (
                        After::Rocking {
                            theta_dot: v[vv::THETA_DOT],
                            u_dot: v[vv::U_DOT],
                            energy: v[vv::ENERGY_AFTER],
                        },
                        "vvel-rigid-limit",
                        v[vv::ENERGY_BEFORE],
                    )
                } else {
                    (
                        After::Contact {
                            u_dot: v[vv::U_DOT],
                            energy: v[vv::ENERGY_AFTER],
                        },
                        "vvel-contact",
                        v[vv::ENERGY_BEFORE],
                    )
                }
            }
            ImpactModel::Adjex => {
                let a = V::impact_adjex(&xi, s, p);
                let e_i = a[ax::ENERGY_BEFORE];
                let rocking_ok = s2 * a[ax::THETA_DOT_ROCKING] > 0.0;
                let contact = (
                    a[ax::ENERGY_CONTACT],
                    "adjex-contact",
                    After::Contact {
                        u_dot: a[ax::U_DOT_CONTACT],
                        energy: a[ax::ENERGY_CONTACT],
                    },
                );
                let rocking = (
                    a[ax::ENERGY_ROCKING],
                    "adjex-rocking",
                    After::Rocking {
                        theta_dot: a[ax::THETA_DOT_ROCKING],
                        u_dot: a[ax::U_DOT_ROCKING],
                        energy: a[ax::ENERGY_ROCKING],
                    },
                );
                let momentum = (
                    a[ax::ENERGY_MOMENTUM],
                    "adjex-momentum",
                    After::Contact {
                        u_dot: a[ax::U_DOT_MOMENTUM],
                        energy: a[ax::ENERGY_MOMENTUM],
                    },
                );
                let best = if rocking_ok && rocking.0 < contact.0 {
                    rocking
                } else {
                    contact
                };
                let chosen = if best.0 <= e_i {
                    best
                } else if momentum.0 <= e_i {
                    momentum
                } else {
                    // Every candidate gains energy (unspecified by the paper): take the least.
                    let least = if momentum.0 < best.0 { momentum } else { best };
                    (least.0, "adjex-least-energy-gain", least.2)
                };
                (chosen.2, chosen.1, e_i)
            }
            ImpactModel::Housner => {
                let h = V::impact_housner(&xi, s, p);
                if s2 * h[ho::THETA_DOT] > 0.0 {
                    (
                        After::Rocking {
                            theta_dot: h[ho::THETA_DOT],
                            u_dot: h[ho::U_DOT],
                            energy: h[ho::ENERGY_AFTER],
                        },
                        "housner",
                        h[ho::ENERGY_BEFORE],
                    )
                } else {
                    // A squat body whose angular momentum reverses cannot rock on: it stops.
                    (
                        After::Contact {
                            u_dot,
                            energy: contact_energy(u_dot),
                        },
                        "housner-stop",
                        h[ho::ENERGY_BEFORE],
                    )
                }
            }
            ImpactModel::Restitution(r) => {
                let td = r * theta_dot;
                let e_b = V::energy(&[0.0, u, theta_dot, u_dot], s, p)[en::KINETIC];
                (
                    After::Rocking {
                        theta_dot: td,
                        u_dot,
                        energy: rocking_energy(td, u_dot),
                    },
                    "restitution",
                    e_b,
                )
            }
        };
        let (after, kind, branch) = match after {
            After::Rocking {
                theta_dot: td,
                u_dot: ud,
                ..
            } if td.abs() < self.rest_rate => (
                After::Contact {
                    u_dot: ud,
                    energy: contact_energy(ud),
                },
                EventKind::Rest,
                branch,
            ),
            other => (other, EventKind::Impact, branch),
        };
        let (after, capped) = self.without_energy_gain(after, e_before, u, s2);
        let branch = if capped {
            capped_branch(branch)
        } else {
            branch
        };
        let e_after = match after {
            After::Contact { energy, .. } | After::Rocking { energy, .. } => energy,
        };
        self.losses += e_before - e_after;
        let pre = [theta_dot, u, u_dot];
        match after {
            After::Contact { u_dot: ud, .. } => {
                self.log_event(t, kind, branch, Phase::Contact, pre, (e_before, e_after));
                Ok(Next::Contact {
                    t,
                    u,
                    u_dot: ud,
                    w,
                    d,
                    settle: kind == EventKind::Rest,
                })
            }
            After::Rocking {
                theta_dot: td,
                u_dot: ud,
                ..
            } => {
                self.log_event(
                    t,
                    kind,
                    branch,
                    Phase::rocking(s2),
                    pre,
                    (e_before, e_after),
                );
                Ok(Next::Rocking {
                    t,
                    s: s2,
                    x: [0.0, u, td, ud],
                    n: 1,
                    w,
                    d,
                })
            }
        }
    }
}

/// The event-log name of an impact branch whose map would have created kinetic energy and was
/// capped (see `Sim::without_energy_gain`).
fn capped_branch(branch: &'static str) -> &'static str {
    match branch {
        "vvel-rigid-limit" | "vvel-contact" => "vvel-energy-capped",
        "adjex-contact" | "adjex-rocking" | "adjex-momentum" | "adjex-least-energy-gain" => {
            "adjex-energy-capped"
        }
        "housner" | "housner-stop" => "housner-energy-capped",
        "restitution" => "restitution-energy-capped",
        _ => "energy-capped",
    }
}

/// The energy integrals (W, D) carried from component `first` on, or zeros when not carried.
fn carried<const N: usize>(y: &Y<N>, first: usize) -> (f64, f64) {
    if N >= first + 2 {
        (y[first], y[first + 1])
    } else {
        (0.0, 0.0)
    }
}

/// The next f64 after a time `t >= 0`.
fn after(t: f64) -> f64 {
    f64::from_bits(t.to_bits() + 1)
}

/// The energy integrals of a Taylor phase's (unscaled) state, as [`carried`].
fn carried_array<const N: usize>(y: &[f64; N], first: usize) -> (f64, f64) {
    if N >= first + 2 {
        (y[first], y[first + 1])
    } else {
        (0.0, 0.0)
    }
}

fn rocking_state_array<const N: usize>(y: &[f64; N]) -> [f64; 4] {
    [y[0], y[1], y[2], y[3]]
}

fn contact_state<const N: usize>(y: &Y<N>) -> [f64; 4] {
    [0.0, y[0], 0.0, y[1]]
}

fn rocking_state<const N: usize>(y: &Y<N>) -> [f64; 4] {
    [y[0], y[1], y[2], y[3]]
}

/// The zero of a rate inside (a, b) where it changes sign (Illinois on the dense output).
fn turning_point(rate: impl Fn(f64) -> f64, a: f64, b: f64, ra: f64) -> f64 {
    let (mut a, mut b, mut fa, mut fb) = (a, b, ra, rate(b));
    let mut side = 0;
    for _ in 0..60 {
        let m = (a * fb - b * fa) / (fb - fa);
        let m = if m > a && m < b { m } else { 0.5 * (a + b) };
        let fm = rate(m);
        if fm == 0.0 || (b - a) <= 1e-14 * b.abs().max(1.0) {
            return m;
        }
        if (fm < 0.0) == (fa < 0.0) {
            a = m;
            fa = fm;
            if side == -1 {
                fb *= 0.5;
            }
            side = -1;
        } else {
            b = m;
            fb = fm;
            if side == 1 {
                fa *= 0.5;
            }
            side = 1;
        }
    }
    0.5 * (a + b)
}

/// An uplift function negative at both ends of a step can still touch zero inside it (grazing).
/// Where it rises at the start of the step and falls at its end, its maximum is found on the
/// dense output (golden section); if that is positive, the uplift is the first positive point
/// after the zero before it.
fn grazing<G, D, const N: usize>(
    g: &mut G,
    dense: &D,
    t_old: f64,
    t_new: f64,
    g_old: &G2,
    g_new: &G2,
) -> Option<(f64, usize, f64)>
where
    G: FnMut(f64, &Y<N>) -> G2,
    D: Fn(f64) -> Y<N>,
{
    let delta = (t_new - t_old) * 1e-4;
    let mut at = |t: f64, k: usize| g(t, &dense(t))[k];
    let mut best: Option<(f64, usize, f64)> = None;
    for k in 0..2 {
        if g_old[k] >= 0.0 || g_new[k] >= 0.0 {
            continue;
        }
        if !(at(t_old + delta, k) > g_old[k] && at(t_new - delta, k) > g_new[k]) {
            continue;
        }
        let r = 0.5 * (5f64.sqrt() - 1.0);
        let (mut a, mut b) = (t_old, t_new);
        let (mut c, mut d) = (b - r * (b - a), a + r * (b - a));
        let (mut fc, mut fd) = (at(c, k), at(d, k));
        while b - a > 4.0 * f64::EPSILON * b.abs().max(1.0) && fc.max(fd) <= 0.0 {
            if fc > fd {
                (b, d, fd) = (d, c, fc);
                c = b - r * (b - a);
                fc = at(c, k);
            } else {
                (a, c, fc) = (c, d, fd);
                d = a + r * (b - a);
                fd = at(d, k);
            }
        }
        let (t_max, f_max) = if fc > fd { (c, fc) } else { (d, fd) };
        if f_max <= 0.0 {
            continue;
        }
        let (mut lo, mut hi) = (t_old, t_max);
        while hi - lo > 4.0 * f64::EPSILON * hi.abs().max(1.0) {
            let mid = 0.5 * (lo + hi);
            if at(mid, k) > 0.0 {
                hi = mid;
            } else {
                lo = mid;
            }
        }
        if best.is_none_or(|(t, _, _)| hi < t) {
            best = Some((hi, k, t_max));
        }
    }
    best
}
