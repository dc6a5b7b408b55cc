//! The structure on compliant ground (issue 44, docs/ground.md): one Runge–Kutta phase per
//! contact state, to its first event.
//!
//! State `y = [θ, v, u_1..u_n, θ', v', u_1'..u_n']` (v the settlement of the base centre,
//! positive into the ground) and three carried integrals outside the error control: the ground
//! acceleration's work, the column's damping and the ground's dissipation. The structure's
//! M(q) and F (the variant's `free_*` kernels, `derive/rocking_derive/free_base.py`) about the
//! leaning corner s = sgn θ, plus the ground's Q_θ, Q_v of the contact state (the ground's
//! kernels), solved at run time by L D Lᵀ ([`crate::spd`]).
//!
//! The contact state is which corners press (their depths d(∓B) > 0, kernel outputs): both
//! (full contact), one (one edge lifted) or none (flight). Events, located on the dense output
//! and refined as on the rigid surface: a corner's depth crossing zero either way (a lift-off or
//! a landing), θ crossing zero (s switches; position and velocity are continuous, no impact map),
//! and overturning at s θ = θ_over. No impact maps: the contact is resolved in time.

use rocking_kernels::ground as gk;
use rocking_kernels::modes::Matrices;
use rocking_kernels::{Array, Variant};
use rocking_motion::GroundMotion;
use rocking_ode::events::{locate, refine, Direction};
use rocking_ode::{Integrator, Options as OdeOptions, Tolerances};

use nalgebra::SVector;

use crate::error::SimError;
use crate::ground::Ground;
use crate::layout::{Free, FreePart};
use crate::options::{History, Options};
use crate::results::{
    EnergyBalance, EventKind, EventRecord, ForceSummary, GroundRow, GroundSummary, HistoryRow,
    Phase, Run, SolverStats, Summary, Time,
};
use crate::spd::solve_upper;
use crate::structure::{Derived, Structure};
use crate::taylor::TaylorVariant;

/// Indices of the ground kernels' output (the same in every kind and state).
use gk::winkler_full as go;

mod contact;
mod past;
mod peaks;
mod record;
mod series;

use contact::{contact_fraction, Contact, Kin};
use past::{past, past_on_polynomial};

/// The structure's energies, power terms and forces: the `free_*` kernels' outputs, in order.
const KINETIC: usize = 0;
const GRAVITY: usize = 1;
const STRAIN: usize = 2;
const POWER_GROUND: usize = 0;
const POWER_DAMPING: usize = 1;

/// What the run keeps track of.
#[derive(Default)]
struct Track {
    max_theta: f64,
    max_u: f64,
    max_settlement: f64,
    max_pressure: f64,
    min_pressure: f64,
    min_contact: f64,
    lift_offs: u64,
    landings: u64,
    significant_landings: u64,
    first_lift_off: Option<f64>,
    first_landing: Option<f64>,
    overturn: Option<f64>,
    events: u64,
    max_moment: f64,
    max_shear: f64,
    max_elastic: f64,
    max_friction: f64,
    min_rv: f64,
    first_slip: Option<f64>,
    first_pull: Option<f64>,
    first_bearing: Option<f64>,
    next_grid: f64,
    /// The measures searched for peaks at the last step's end, its time and contact state.
    last_peaked: Option<(f64, Contact, peaks::Peaked)>,
    history: Vec<HistoryRow>,
    coordinates: Vec<f64>,
    log: Vec<EventRecord>,
    stats: SolverStats,
}

/// A run on compliant ground with variant `V`; `N` = `V::Y::LEN + 3`.
struct GroundSim<'a, V: Variant, M: GroundMotion + ?Sized, const N: usize> {
    k: Kin<V>,
    p: V::Params,
    motion: &'a M,
    opts: &'a Options,
    derived: Derived,
    p_seconds: Option<f64>,
    weight: f64,
    wb: f64,
    /// The static settlement v0 = W / K_v.
    v0: f64,
    /// The mean pressure W / (2B) (two springs: the corner force W / 2).
    mean_pressure: f64,
    /// T + V_g + V_s + V_ground at rest at θ = 0, v = v0 (the energies' zero).
    e_rest: f64,
    /// The fastest rate of the run: ω_v, the column's highest frequency, p, the excitation's
    /// (the margin of the search for peaks inside a step).
    fastest_rate: f64,
    top: V::Shape,
    tol: Tolerances<N>,
    ode_options: OdeOptions,
    /// Whether the phases run the Taylor method ([`GroundSim::phase_taylor`]).
    taylor: bool,
    rec: Track,
}

/// Runs `structure` on `ground` under `motion` with variant `V` by the options' method (see
/// [`crate::simulate_on_ground`]).
///
/// # Panics
///
/// When `N` is not `V::Y::LEN + 3`.
pub fn simulate_ground<V: TaylorVariant, M: GroundMotion + ?Sized, const N: usize>(
    structure: &Structure,
    ground: &Ground,
    motion: &M,
    opts: &Options,
) -> Result<Run, SimError> {
    assert_eq!(N, V::Y::LEN + 3, "state size for variant {}", V::NAME);
    opts.validate()?;
    if opts.accuracy.method == crate::Method::Taylor && !motion.accel_series(0.0, &mut [0.0; 2]) {
        return Err(SimError::NoTaylorSeries);
    }
    let p = structure.params::<V>();
    let derived = structure.derived_by::<V>();
    let uplift = V::static_uplift(&p);
    let weight = uplift.values()[rocking_kernels::kernels::index::static_uplift::WEIGHT];
    let wb = uplift.values()[rocking_kernels::kernels::index::static_uplift::MOMENT_UPLIFT];
    let statics = ground.statics(weight);
    let v0 = statics.settlement;
    let g = structure.param("g").unwrap_or(1.0);
    let omega_v = (statics.k_v * g / weight).sqrt();
    let mean_pressure = ground.mean_pressure(weight);
    let method = opts
        .accuracy
        .method
        .runge_kutta()
        .unwrap_or(rocking_ode::Method::Dop853);
    let ode_options = OdeOptions {
        max_steps: opts.max_steps,
        ..OdeOptions::new(method)
    };
    let tol_value = opts.accuracy.tol;
    let (a, pf) = (derived.alpha, derived.p);
    let u_scale = if V::RIGID { 1.0 } else { derived.u_cr };
    let tol = Tolerances {
        rtol: tol_value,
        atol: SVector::<f64, N>::from_fn(|i, _| match Free::<V>::part(i) {
            FreePart::Theta => a * tol_value,
            FreePart::V => v0 * tol_value,
            FreePart::U(_) => u_scale * tol_value,
            FreePart::ThetaDot => a * pf * tol_value,
            FreePart::VDot => v0 * omega_v * tol_value,
            FreePart::UDot(_) => u_scale * derived.omega_n.max(pf) * tol_value,
            FreePart::Integral(_) => f64::INFINITY,
        }),
    };
    let mut sim = GroundSim::<V, M, N> {
        k: Kin {
            p,
            ground: *ground,
            bilateral: !opts.uplift,
        },
        p,
        motion,
        opts,
        derived,
        p_seconds: structure.p_per_second(),
        weight,
        wb,
        v0,
        mean_pressure,
        e_rest: 0.0,
        fastest_rate: peaks::fastest_rate::<V, M>(&p, &derived, omega_v, motion),
        top: V::shape(1.0),
        tol,
        ode_options,
        taylor: opts.accuracy.method.runge_kutta().is_none(),
        rec: Track {
            min_contact: f64::INFINITY,
            min_pressure: f64::INFINITY,
            min_rv: f64::INFINITY,
            ..Track::default()
        },
    };
    // Point masses on the column axis alone (no column or base mass) have no rotational
    // inertia once the base may sink: M is singular (docs/ground.md).
    let q0 = V::Qf::from_fn(|i| if i == Free::<V>::V { v0 } else { 0.0 });
    let mut probe = [1.0; crate::spd::MAX];
    let pivot = solve_upper(
        V::free_mass_matrix(&q0, 1.0, &p).values(),
        &mut probe[..Free::<V>::NQ],
    );
    if pivot.is_nan() || pivot <= 1e-12 {
        return Err(SimError::SingularOnGround {
            variant: V::NAME,
            pivot: Some(pivot),
        });
    }
    let rest = sim.y_of(0.0, v0, &[0.0; 0]);
    sim.e_rest = sim.total_energy(&rest, 1.0, sim.k.contact_of(&rest));
    sim.run()
}

impl<V: TaylorVariant, M: GroundMotion + ?Sized, const N: usize> GroundSim<'_, V, M, N> {
    /// The state at rest with rotation `theta`, settlement `v` and deformation `us` (missing
    /// entries 0).
    fn y_of(&self, theta: f64, v: f64, us: &[f64]) -> V::Y {
        V::Y::from_fn(|i| match Free::<V>::part(i) {
            FreePart::Theta => theta,
            FreePart::V => v,
            FreePart::U(k) => us.get(k).copied().unwrap_or(0.0),
            _ => 0.0,
        })
    }

    /// T + V_g + V_s + V_ground (from zero at rest on the ground).
    fn total_energy(&self, y: &V::Y, s: f64, c: Contact) -> f64 {
        let e = V::free_energy(y, s, &self.p);
        e[KINETIC] + e[GRAVITY] + e[STRAIN] + self.k.ground(y, c)[go::STRAIN] - self.e_rest
    }

    fn time(&self, t: f64) -> Time {
        let tau = t * self.derived.p;
        Time {
            tau,
            seconds: self.p_seconds.map(|ps| tau / ps),
        }
    }

    /// The top deflection Σ u_i ψ_i(1) (`rate`: its rate).
    fn top(&self, y: &V::Y, rate: bool) -> f64 {
        if V::RIGID {
            return 0.0;
        }
        let psi = self.top.values();
        let us = &y.values()[Free::<V>::us(rate)];
        psi.iter().zip(us).map(|(p, u)| p * u).sum()
    }

    fn initial_state(&self) -> V::Y {
        let i = self.opts.initial;
        let n = Free::<V>::NQ;
        let v = i.v.unwrap_or_else(|| {
            crate::ground_statics::equilibrium_settlement(&self.k.ground, self.weight, i.theta)
        });
        // Several coordinates: the initial u and u' are top deflections along the first mode.
        let phi: Vec<f64> = if V::RIGID {
            vec![0.0]
        } else if n == 3 {
            vec![1.0]
        } else {
            Matrices::of::<V>(&self.p)
                .fixed_base()
                .map_or(vec![f64::NAN; n - 2], |m| {
                    m.shapes[0].iter().copied().collect()
                })
        };
        V::Y::from_fn(|k| match Free::<V>::part(k) {
            FreePart::Theta => i.theta,
            FreePart::V => v,
            FreePart::U(k) => i.u * phi[k],
            FreePart::ThetaDot => i.theta_dot,
            FreePart::UDot(k) => i.u_dot * phi[k],
            FreePart::VDot | FreePart::Integral(_) => 0.0,
        })
    }

    fn run(mut self) -> Result<Run, SimError> {
        let y0 = self.initial_state();
        let i = self.opts.initial;
        let mut s = if i.theta > 0.0 || (i.theta == 0.0 && i.theta_dot >= 0.0) {
            1.0
        } else {
            -1.0
        };
        let mut c = self.k.contact_of(&y0);
        let e_initial = self.total_energy(&y0, s, c);
        let mut t = 0.0;
        let mut y = y0;
        let mut carried = [0.0; 3];
        let mut fired: Option<usize> = None;
        self.observe(t, &y, s, c);
        if !matches!(self.opts.history, History::None) {
            self.record(t, &y, s, c);
            if let History::Grid(dt) = self.opts.history {
                self.rec.next_grid = dt;
            }
        }
        let end = loop {
            let end = if self.taylor {
                self.phase_taylor(t, y, s, c, carried, fired)?
            } else {
                self.phase(t, y, s, c, carried, fired)?
            };
            t = end.t;
            y = end.y;
            carried = end.carried;
            match end.event {
                None => {
                    let phase = c.phase(false);
                    break End { phase, t, y, s, c };
                }
                Some(0) => {
                    // θ through zero: the leaning corner changes.
                    s = -s;
                    let after = c.phase(false);
                    self.log(t, EventKind::PivotSwitch, corner(s < 0.0), after, &y);
                    fired = Some(0);
                }
                Some(3) => {
                    self.rec.overturn = Some(t);
                    self.log(t, EventKind::Overturn, "overturn", Phase::Overturned, &y);
                    let phase = Phase::Overturned;
                    break End { phase, t, y, s, c };
                }
                Some(k) => {
                    let left = k == 1;
                    let pressing = if left { &mut c.left } else { &mut c.right };
                    let was = *pressing;
                    *pressing = !was;
                    let after = c.phase(false);
                    if was {
                        self.rec.lift_offs += 1;
                        self.rec.first_lift_off.get_or_insert(t);
                        self.log(t, EventKind::LiftOff, corner(left), after, &y);
                    } else {
                        self.rec.landings += 1;
                        self.rec.first_landing.get_or_insert(t);
                        let theta_dot = y.values()[Free::<V>::THETA_DOT];
                        if theta_dot.abs() >= 0.01 * self.derived.alpha * self.derived.p {
                            self.rec.significant_landings += 1;
                        }
                        self.log(t, EventKind::Landing, corner(left), after, &y);
                    }
                    fired = Some(k);
                }
            }
            self.rec.events += 1;
            if self.rec.events > self.opts.max_events {
                return Err(SimError::TooManyEvents {
                    max_events: self.opts.max_events,
                    tau: t * self.derived.p,
                });
            }
        };
        let summary = self.finish(&end, carried, e_initial);
        Ok(self.into_run(summary))
    }

    /// One phase from `t0`: to its first event (`Some(index)`: 0 θ through zero, 1 or 2 the
    /// left or right corner's depth through zero, 3 overturning) or the end of the run.
    fn phase(
        &mut self,
        t0: f64,
        y0: V::Y,
        s: f64,
        c: Contact,
        carried: [f64; 3],
        fired: Option<usize>,
    ) -> Result<PhaseEnd<V>, SimError> {
        let (nqf, integrals) = (Free::<V>::NQ, Free::<V>::INTEGRALS);
        let theta = Free::<V>::THETA;
        let motion = self.motion;
        let over = self.opts.overturn_angle;
        let k = self.k;
        let mut rhs = |t: f64, z: &SVector<f64, N>| -> SVector<f64, N> {
            let ug = motion.accel(t);
            let y = V::Y::from_fn(|i| z[i]);
            let (acc, g) = k.accelerations(&y, ug, s, c);
            let pw = V::free_power(&y, ug, s, &k.p);
            let mut out = SVector::<f64, N>::zeros();
            for i in 0..nqf {
                out[i] = z[Free::<V>::rate(i)];
                out[Free::<V>::rate(i)] = acc.values()[i];
            }
            let rates = [pw[POWER_GROUND], pw[POWER_DAMPING], g[go::DISSIPATION]];
            for (k, rate) in rates.into_iter().enumerate() {
                out[integrals + k] = rate;
            }
            out
        };
        let mut g = |_t: f64, z: &SVector<f64, N>| -> SVector<f64, 4> {
            let y = V::Y::from_fn(|i| z[i]);
            let [l, r] = k.depths(&y);
            SVector::<f64, 4>::new(s * z[theta], l, r, s * z[theta] - over)
        };
        let dirs = self.directions(c);
        let z0 = SVector::<f64, N>::from_fn(|i, _| match Free::<V>::part(i) {
            FreePart::Integral(k) => carried[k],
            _ => y0.values()[i],
        });
        let mut ode = Integrator::new(self.ode_options, self.tol)?;
        ode.reset(t0, z0, &mut rhs)?;
        // The event that started this phase is strictly past its surface ([`past`]): its
        // component starts on this phase's side, so a return across the surface in the first
        // step (a grazing touch) is a crossing, and the root search cannot find one at t0.
        // Where `past` could not get there (the component within rounding of 0 for longer than
        // it may move), the component starts at the least margin on this phase's side: it does
        // not fire again at once, and a return is still a crossing. (Started at 0, a return was
        // never one, since a crossing needs a strict sign at the step start: a corner that turned
        // back into the bed stayed pressing under a state that said lifted, and the run ended in
        // a step-size underflow; docs/ground.md.)
        let mut g_old = g(t0, &z0);
        if let Some(i) = fired {
            if let Some(margin) = start_margin(dirs[i], g_old[i]) {
                g_old[i] = margin;
            }
        }
        let mut first_on_zero = fired != Some(0) && y0.values()[theta] == 0.0;
        let (t_old, t, z, event) = loop {
            let t_stop = motion
                .next_kink(ode.t())
                .map_or(self.opts.t_end, |k| k.min(self.opts.t_end));
            let info = ode.step(&mut rhs, t_stop)?;
            let st = ode.stats();
            self.guard_steps(st.steps + st.rejected, ode.t())?;
            let g_new = g(info.t_new, ode.y());
            if first_on_zero && s * ode.y()[theta] < 0.0 {
                self.rec.stats.add(ode.take_stats());
                return Ok(PhaseEnd::other_corner_leads(t0, y0, carried));
            }
            first_on_zero = false;
            if let Some(ev) = locate(&mut ode, &mut g, &dirs, &g_old, &g_new) {
                let ev = refine(&mut ode, &mut rhs, &mut g, ev);
                let noise = self.event_noise(ev.y[Free::<V>::V], ev.index);
                let ev = past(&mut ode, &mut rhs, &mut g, dirs[ev.index], noise, ev);
                break (info.t_old, ev.t, ev.y, Some(ev.index));
            }
            if info.t_new >= self.opts.t_end {
                break (info.t_old, info.t_new, *ode.y(), None);
            }
            let y = V::Y::from_fn(|i| ode.y()[i]);
            self.record_step(|t| ode.dense(t), info.t_old, info.t_new, &y, s, c);
            g_old = g_new;
        };
        let y = V::Y::from_fn(|i| z[i]);
        self.record_step(|t| ode.dense(t), t_old, t, &y, s, c);
        self.rec.stats.add(ode.take_stats());
        Ok(PhaseEnd {
            t,
            y,
            carried: std::array::from_fn(|k| z[integrals + k]),
            event,
        })
    }

    /// The rounding of event function `index` at settlement `v`: 64 ulps of its scale (α for θ;
    /// a depth v + x sin θ rounds at the size of its terms, B + |v|).
    fn event_noise(&self, v: f64, index: usize) -> f64 {
        let (a, depth) = (self.derived.alpha, self.k.ground.b + v.abs());
        64.0 * f64::EPSILON * [a, depth, depth, a][index]
    }

    /// The guard on a phase's step count (`steps` so far, `t` the last step's end).
    fn guard_steps(&self, steps: u64, t: f64) -> Result<(), SimError> {
        if steps > self.opts.max_steps {
            return Err(SimError::TooManySteps {
                max_steps: self.opts.max_steps,
                tau: t * self.derived.p,
            });
        }
        Ok(())
    }

    /// The directions of the events `[s θ, d(−B), d(B), s θ − θ_over]` in contact state `c`: θ
    /// through zero falling, a pressing corner's depth falling (a lift-off), a lifted one's
    /// rising (a landing), the overturning angle rising.
    fn directions(&self, c: Contact) -> [Direction; 4] {
        let falls = |pressing: bool| {
            if pressing {
                Direction::Falling
            } else {
                Direction::Rising
            }
        };
        [
            Direction::Falling,
            falls(c.left),
            falls(c.right),
            Direction::Rising,
        ]
    }

    /// The bookkeeping of every step of every phase: the history rows of (t_old, t_end]
    /// (`dense` its dense output; t_end the step's end or its event), then the maxima at its end
    /// state `y`.
    fn record_step(
        &mut self,
        dense: impl Fn(f64) -> SVector<f64, N>,
        t_old: f64,
        t_end: f64,
        y: &V::Y,
        s: f64,
        c: Contact,
    ) {
        // The structure's state at any t of the step (the integrals dropped).
        let at = |t: f64| {
            let z = dense(t);
            V::Y::from_fn(|i| z[i])
        };
        self.step_rows(&at, t_old, t_end, s, c);
        self.peaks_inside(&at, t_old, t_end, s, c);
        self.observe(t_end, y, s, c);
    }

    /// History rows of the step (t_old, t_new], `at` its state at a time.
    fn step_rows(&mut self, at: &impl Fn(f64) -> V::Y, t_old: f64, t_new: f64, s: f64, c: Contact) {
        match self.opts.history {
            History::None => {}
            History::Steps => self.record(t_new, &at(t_new), s, c),
            History::Grid(dt) => {
                while self.rec.next_grid <= t_new {
                    if self.rec.next_grid >= t_old {
                        let tg = self.rec.next_grid;
                        self.record(tg, &at(tg), s, c);
                    }
                    self.rec.next_grid += dt;
                }
            }
        }
    }
}

/// The least value on this phase's side of its surface at which an event function that is not
/// strictly on that side at the phase's start (`g0`) starts instead, or `None` when it is.
fn start_margin(dir: Direction, g0: f64) -> Option<f64> {
    match dir {
        Direction::Rising if g0 >= 0.0 => Some(-f64::MIN_POSITIVE),
        Direction::Falling if g0 <= 0.0 => Some(f64::MIN_POSITIVE),
        _ => None,
    }
}

fn corner(left: bool) -> &'static str {
    if left {
        "left-corner"
    } else {
        "right-corner"
    }
}

/// The end of a run: its last phase, time, state, leaning corner and contact state.
struct End<V: Variant> {
    phase: Phase,
    t: f64,
    y: V::Y,
    s: f64,
    c: Contact,
}

/// The end of one phase.
struct PhaseEnd<V: Variant> {
    t: f64,
    y: V::Y,
    carried: [f64; 3],
    event: Option<usize>,
}

impl<V: Variant> PhaseEnd<V> {
    /// A phase started at θ = 0 (not from a switch) whose first step leans the other way: the
    /// other corner leads from the start.
    fn other_corner_leads(t0: f64, y0: V::Y, carried: [f64; 3]) -> Self {
        Self {
            t: t0,
            y: y0,
            carried,
            event: Some(0),
        }
    }
}
