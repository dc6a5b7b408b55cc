//! What one run carries between its phases: the simulation [`Sim`], where the hybrid system goes
//! [`Next`], and the guards that turn a run that would not end into an error.
//!
//! The lowest room of the driver: every other file imports from here, this one from none of them.

use nalgebra::SVector;
use rocking_kernels::kernels::index::energy as en;
use rocking_motion::GroundMotion;
use rocking_ode::{Options as OdeOptions, Stats, Tolerances};

use super::forces::ForceRecord;
use crate::error::SimError;
use crate::options::Options;
use crate::results::{EventRecord, HistoryRow, Phase, SolverStats, Time};
use crate::structure::Derived;
use crate::taylor::TaylorVariant;

/// A phase's integrator state: the mechanical state, then W and D when they are carried.
pub(super) type Y<const N: usize> = SVector<f64, N>;
/// The two event functions of a phase (f_+ and f_- in contact; impact and overturning while
/// rocking).
pub(super) type G2 = SVector<f64, 2>;

/// The right corner as pivot (θ > 0).
pub(super) const RIGHT: f64 = 1.0;
/// The left corner as pivot (θ < 0).
pub(super) const LEFT: f64 = -1.0;

/// Where the hybrid system goes next.
pub(super) enum Next {
    Contact {
        t: f64,
        u: f64,
        u_dot: f64,
        w: f64,
        d: f64,
        /// Just come to rest: no uplift before one step has been taken (see
        /// [`Sim::contact_start`](super::Sim::contact_start)).
        settle: bool,
    },
    Rocking {
        t: f64,
        s: f64,
        x: [f64; 4],
        /// The impact event is s θ / (t − t0)^n (see the rocking phases).
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

/// One run: `NR` and `NC` are the sizes of the rocking and contact states (4 and 2, or 6 and 4
/// with the energy integrals).
pub(super) struct Sim<
    'a,
    V: TaylorVariant,
    M: GroundMotion + ?Sized,
    const NR: usize,
    const NC: usize,
> {
    pub(super) p: V::Params,
    pub(super) motion: &'a M,
    pub(super) opts: &'a Options,
    pub(super) derived: Derived,
    pub(super) p_seconds: Option<f64>,
    /// |θ'| below which an impact or a rocking start ends in full contact.
    pub(super) rest_rate: f64,
    /// |θ'| from which an impact counts as significant.
    pub(super) significant_rate: f64,
    /// The potential energy at rest (the zero of the reported total energy).
    pub(super) v_rest: f64,
    pub(super) ode_options: OdeOptions,
    pub(super) contact_tol: Tolerances<NC>,
    pub(super) rocking_tol: Tolerances<NR>,
    /// Natural scales of the phase states (the Taylor method integrates the state over them).
    pub(super) contact_scale: [f64; NC],
    pub(super) rocking_scale: [f64; NR],
    pub(super) stats: SolverStats,
    /// Events so far (the guard `max_events`).
    pub(super) events: u64,
    /// The total weight W and the uplift moment W B (the forces' units).
    pub(super) weight: f64,
    pub(super) wb: f64,
    /// The fastest rate of the dynamics (the larger of the column's fixed-base and uplifted
    /// frequencies, the rocking time scale p and the excitation's): how much a quantity can
    /// change inside a step.
    pub(super) fastest_rate: f64,
    pub(super) rec: Record,
}

/// What the run has recorded so far (written by the recorder, read into the summary).
#[derive(Default)]
pub(super) struct Record {
    pub(super) max_theta: f64,
    pub(super) max_u: f64,
    pub(super) impacts: u64,
    pub(super) significant: u64,
    pub(super) energy_capped: u64,
    pub(super) first_uplift: Option<f64>,
    pub(super) first_impact: Option<f64>,
    pub(super) overturn: Option<f64>,
    /// Kinetic energy lost at impacts (the energy balance's third term).
    pub(super) losses: f64,
    pub(super) log: Vec<EventRecord>,
    pub(super) history: Vec<HistoryRow>,
    /// The next time of the history grid.
    pub(super) next_grid: f64,
    /// The extremes of the section forces and reactions.
    pub(super) forces: ForceRecord,
}

impl<V: TaylorVariant, M: GroundMotion + ?Sized, const NR: usize, const NC: usize>
    Sim<'_, V, M, NR, NC>
{
    /// Whether W and D are carried (the energy bookkeeping was asked for).
    pub(super) const ENERGY: bool = NR > 4;

    pub(super) fn time(&self, t: f64) -> Time {
        let tau = t * self.derived.p;
        Time {
            tau,
            seconds: self.p_seconds.map(|ps| tau / ps),
        }
    }

    /// Kinetic plus potential energy, from zero at rest.
    pub(super) fn total_energy(&self, x: &[f64; 4], s: f64) -> f64 {
        let e = V::energy(x, s, &self.p);
        e[en::KINETIC] + e[en::GRAVITY] + e[en::STRAIN] - self.v_rest
    }

    /// Counts an event at `t`; the guard `max_events`.
    pub(super) fn count_event(&mut self, t: f64) -> Result<(), SimError> {
        self.events += 1;
        if self.events > self.opts.max_events {
            return Err(SimError::TooManyEvents {
                max_events: self.opts.max_events,
                tau: self.time(t).tau,
            });
        }
        Ok(())
    }

    /// The guard on the total number of step attempts of a run, given the running phase's
    /// integrator counters at `t`.
    pub(super) fn guard_steps(&self, st: Stats, t: f64) -> Result<(), SimError> {
        let steps = self.stats.steps + self.stats.rejected_steps + st.steps + st.rejected;
        if steps > self.opts.max_steps {
            return Err(SimError::TooManySteps {
                max_steps: self.opts.max_steps,
                tau: self.time(t).tau,
            });
        }
        Ok(())
    }

    /// Where the next step must end: the next kink of the excitation, or the run's end.
    pub(super) fn t_stop(&self, t: f64) -> f64 {
        self.motion
            .next_kink(t)
            .map_or(self.opts.t_end, |k| k.min(self.opts.t_end))
    }

    /// The longest contact step from `t0`: the excitation's resolution while it lasts. A rigid
    /// column in contact gives the error control nothing to follow, so no excursion of f_s may
    /// fall between steps.
    pub(super) fn contact_h_max(&self, t0: f64) -> f64 {
        if t0 < self.motion.end() {
            self.motion.resolution()
        } else {
            f64::INFINITY
        }
    }

    /// An integration failure while rocking, explained when the mass matrix became singular.
    pub(super) fn explain_failure(&self, e: rocking_ode::OdeError, y: &[f64], s: f64) -> SimError {
        let [mtt, mtu, muu] = V::mass_matrix(&[y[0], y[1]], s, &self.p);
        let conditioning = (mtt * muu - mtu * mtu) / (mtt * muu);
        if conditioning.is_finite() && conditioning > 1e-8 {
            return SimError::Integration(e);
        }
        SimError::SingularMassMatrix {
            tau: self.time(e.t).tau,
            conditioning,
            u_over_ucr: y[1] / self.derived.u_cr,
            cause: e,
        }
    }
}

/// The energy integrals (W, D) of a phase's state from component `first` on, or zeros when they
/// are not carried.
pub(super) fn carried(y: &[f64], first: usize) -> (f64, f64) {
    if y.len() >= first + 2 {
        (y[first], y[first + 1])
    } else {
        (0.0, 0.0)
    }
}

/// [θ, u, θ', u'] of a rocking phase's state.
pub(super) fn rocking_state(y: &[f64]) -> [f64; 4] {
    [y[0], y[1], y[2], y[3]]
}

/// The free vibration of the column in full contact with no ground motion: it stays inside the
/// ellipse of its energy `vib` (kinetic + strain) in (u, u'), generalised stiffness `k` and mass
/// `m` (the derived k̃, m̃).
pub(super) struct Ellipse {
    pub(super) vib: f64,
    pub(super) k: f64,
    pub(super) m: f64,
}

impl Ellipse {
    /// For g(u, u') = c + a u + b u' (affine): (c, the largest |a u + b u'| on the ellipse).
    pub(super) fn reach(&self, g: impl Fn(f64, f64) -> f64) -> (f64, f64) {
        let c = g(0.0, 0.0);
        let (a, b) = (g(1.0, 0.0) - c, g(0.0, 1.0) - c);
        (
            c,
            (2.0 * self.vib * (a * a / self.k + b * b / self.m)).sqrt(),
        )
    }
}
