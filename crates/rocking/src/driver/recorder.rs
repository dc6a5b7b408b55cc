//! What a run records as it goes: each step's bookkeeping (the guard on steps, the maxima of θ
//! and u with turning points inside steps, the forces' extremes, the history rows: one function
//! for every phase and integrator, [`Sim::record_step`]), the event log, and at the end the
//! summary.

use rocking_kernels::kernels::index::energy as en;
use rocking_kernels::Array;
use rocking_motion::GroundMotion;
use rocking_ode::roots::turning_point;

use super::forces::ForcesAt;
use super::state::{Integrals, Sim};
use crate::dense::StepView;
use crate::error::SimError;
use crate::layout::Rocking;
use crate::options::History;
use crate::results::{EnergyBalance, EventKind, EventRecord, HistoryRow, Phase, Summary};
use crate::taylor::TaylorVariant;

/// What a phase's bookkeeping carries from step to step: the phase (full contact, or rocking
/// about `s`) and the forces at the end of its last step (with their rates, where it took them).
pub(super) struct PhaseRecord {
    contact: bool,
    s: f64,
    phase: Phase,
    forces: ForcesAt,
}

/// A step a phase's integrator took, from `t_old` to `t_new`, the phase's step attempts
/// (accepted and rejected) so far counted.
#[derive(Clone, Copy)]
pub(super) struct Step {
    pub(super) t_old: f64,
    pub(super) t_new: f64,
    pub(super) attempts: u64,
}

impl<V: TaylorVariant, M: GroundMotion + ?Sized, const NR: usize, const NC: usize>
    Sim<'_, V, M, NR, NC>
{
    /// The bookkeeping of a phase (full contact about [`RIGHT`](super::state::RIGHT), or
    /// rocking about `s`) that starts at `t0` with the rocking state `x0`: the forces at its
    /// start, recorded.
    pub(super) fn start_phase(&mut self, phase: Phase, s: f64, t0: f64, x0: &V::X) -> PhaseRecord {
        let contact = phase == Phase::Contact;
        let forces = ForcesAt {
            forces: self.forces_start(contact, s, t0, x0),
            rates: None,
        };
        PhaseRecord {
            contact,
            s,
            phase,
            forces,
        }
    }

    /// The bookkeeping of every step of every phase, whichever integrator took it: the guard
    /// on the run's steps, then over (t_old, t_end] of `step` (t_end its end, or its event;
    /// `view` its dense output) the maxima of θ (rocking) and u, the forces' extremes, and the
    /// history rows. Returns where the next step must end.
    pub(super) fn record_step(
        &mut self,
        rec: &mut PhaseRecord,
        view: &impl StepView<V::X>,
        step: Step,
        t_end: f64,
    ) -> Result<f64, SimError> {
        let t_stop = self.record_step_but_forces(rec, view, step, t_end)?;
        self.record_step_forces(rec, view, step.t_old, t_end);
        Ok(t_stop)
    }

    /// [`record_step`](Self::record_step) without the forces, which the caller records later
    /// ([`record_step_forces`](Self::record_step_forces), before the next step's): a Taylor
    /// step's end has its exact rates only from the step after it.
    pub(super) fn record_step_but_forces(
        &mut self,
        rec: &mut PhaseRecord,
        view: &impl StepView<V::X>,
        step: Step,
        t_end: f64,
    ) -> Result<f64, SimError> {
        self.guard_steps(step.attempts, step.t_new)?;
        let t_old = step.t_old;
        if rec.contact {
            self.extremes_contact(view, t_old, t_end);
        } else {
            self.extremes_rocking(view, t_old, t_end);
        }
        self.step_history(t_old, t_end, |t| view.state(t), rec.phase, rec.s);
        Ok(self.t_stop(step.t_new))
    }

    /// The forces' part of [`record_step`](Self::record_step) over (t_old, t_end].
    pub(super) fn record_step_forces(
        &mut self,
        rec: &mut PhaseRecord,
        view: &impl StepView<V::X>,
        t_old: f64,
        t_end: f64,
    ) {
        rec.forces = self.extremes_forces(view, rec.contact, rec.s, t_old, rec.forces, t_end);
    }

    /// Tracks |θ| and the top deflection |u| of the rocking state `x`.
    pub(super) fn track(&mut self, x: &V::X) {
        self.rec
            .track(x.values()[Rocking::<V>::THETA], self.top(x, false));
    }

    fn record_history(&mut self, t: f64, x: &V::X, phase: Phase, s: f64) {
        let e = V::energy(x, s, &self.p);
        let ug = self.motion.accel(t);
        let f = self.model_forces(phase == Phase::Contact, s, ug, x);
        let row = HistoryRow {
            t,
            theta: x.values()[Rocking::<V>::THETA],
            u: self.top(x, false),
            theta_dot: x.values()[Rocking::<V>::THETA_DOT],
            u_dot: self.top(x, true),
            phase,
            e_kin: e[en::KINETIC],
            e_total: e[en::KINETIC] + e[en::GRAVITY] + e[en::STRAIN] - self.v_rest,
            ug,
            base_moment: f.moment,
            base_shear: f.shear,
            elastic_base_moment: f.elastic,
            horizontal_reaction: f.horizontal,
            vertical_reaction: f.vertical,
            ground: None,
        };
        self.rec.history.push(row);
        if V::NQ > 1 {
            let x = x.values();
            self.rec
                .coordinates
                .extend_from_slice(&x[Rocking::<V>::us(false)]);
            self.rec
                .coordinates
                .extend_from_slice(&x[Rocking::<V>::us(true)]);
        }
    }

    /// History rows for the step (t_old, t_new] of a phase, from the dense output.
    fn step_history(
        &mut self,
        t_old: f64,
        t_new: f64,
        at: impl Fn(f64) -> V::X,
        phase: Phase,
        s: f64,
    ) {
        match self.opts.history {
            History::None => {}
            History::Steps => self.record_history(t_new, &at(t_new), phase, s),
            History::Grid(dt) => {
                while self.rec.next_grid <= t_new {
                    if self.rec.next_grid >= t_old {
                        let tg = self.rec.next_grid;
                        self.record_history(tg, &at(tg), phase, s);
                    }
                    self.rec.next_grid += dt;
                }
            }
        }
    }

    /// An event of the log (when asked for): `pre` the rocking state before it (θ', the top
    /// deflection u and its rate are logged), `energies` the kinetic energy before and after.
    pub(super) fn log_event(
        &mut self,
        t: f64,
        kind: EventKind,
        branch: &'static str,
        phase_after: Phase,
        pre: &V::X,
        energies: (f64, f64),
    ) {
        if self.opts.event_log {
            let (theta_dot, u, u_dot) = (
                pre.values()[Rocking::<V>::THETA_DOT],
                self.top(pre, false),
                self.top(pre, true),
            );
            let e_ref = self.derived.e_ref;
            let record = EventRecord {
                time: self.time(t),
                kind,
                branch,
                phase_after,
                theta_dot,
                u,
                u_dot,
                energy_before: energies.0 / e_ref,
                energy_after: energies.1 / e_ref,
            };
            self.rec.log.push(record);
        }
    }

    /// The top deflection (`rate`: its rate) at `t` in a step, from the step's components.
    fn top_at(&self, step: &impl StepView<V::X>, rate: bool, t: f64) -> f64 {
        self.top_by(|i| step.component(i, t), Rocking::<V>::us(rate).start)
    }

    /// A bound of the top deflection's size over a step.
    fn top_bound(&self, step: &impl StepView<V::X>) -> f64 {
        if V::NQ == 1 {
            return step.bound(Rocking::<V>::u(0));
        }
        let psi = self.top.values();
        (0..V::NQ)
            .map(|i| psi[i].abs() * step.bound(Rocking::<V>::u(i)))
            .sum()
    }

    /// max |u| within a contact step, including a turning point inside it.
    fn extremes_contact(&mut self, step: &impl StepView<V::X>, t_old: f64, t_new: f64) {
        if !self.opts.max_deflection {
            return;
        }
        let (a, b) = (step.state(t_old), step.state(t_new));
        let (a_rate, b_top) = (self.top(&a, true), self.top(&b, false));
        self.rec.max_u = self.rec.max_u.max(b_top.abs());
        if a_rate * self.top(&b, true) < 0.0 && self.top_bound(step) > self.rec.max_u {
            let tm = turning_point(|t| self.top_at(step, true, t), t_old, t_new, a_rate);
            self.rec.max_u = self.rec.max_u.max(self.top_at(step, false, tm).abs());
        }
    }

    /// max |θ| and (where tracked) |u| within a rocking step, including turning points inside it.
    fn extremes_rocking(&mut self, step: &impl StepView<V::X>, t_old: f64, t_new: f64) {
        let (a, b) = (step.state(t_old), step.state(t_new));
        self.rec
            .track(b.values()[Rocking::<V>::THETA], self.top(&b, false));
        // θ from its rate θ', then the top deflection from its rate (if tracked).
        self.turning_point_extreme::<false>(step, (&a, &b), t_old, t_new);
        if self.opts.max_deflection {
            self.turning_point_extreme::<true>(step, (&a, &b), t_old, t_new);
        }
    }

    /// max |θ| (`TOP` false) or max |u| of the top (`TOP` true) at a turning point inside the
    /// rocking step (t_old, t_new) whose end states are `a` and `b`.
    fn turning_point_extreme<const TOP: bool>(
        &mut self,
        step: &impl StepView<V::X>,
        (a, b): (&V::X, &V::X),
        t_old: f64,
        t_new: f64,
    ) {
        const SAMPLES: u32 = 32;
        let (theta, theta_dot) = (Rocking::<V>::THETA, Rocking::<V>::THETA_DOT);
        let value = |t: f64| {
            if TOP {
                self.top_at(step, false, t)
            } else {
                step.component(theta, t)
            }
        };
        let rate_at = |t: f64| {
            if TOP {
                self.top_at(step, true, t)
            } else {
                step.component(theta_dot, t)
            }
        };
        let (ra, rb) = if TOP {
            (self.top(a, true), self.top(b, true))
        } else {
            (a.values()[theta_dot], b.values()[theta_dot])
        };
        // Without a sign change of the rate at the ends, or a start from rest, the search
        // below finds nothing: skip the bound too (most steps).
        let from_rest = ra == 0.0 && rb != 0.0;
        if !(ra * rb < 0.0 || from_rest) {
            return;
        }
        let (max, bound) = if TOP {
            (self.rec.max_u, self.top_bound(step))
        } else {
            (self.rec.max_theta, step.bound(theta))
        };
        if bound <= max {
            return;
        }
        // A step from rest (θ' = 0 at an uplift) has no sign change at its ends: its first
        // turning point lies after a point of the other sign than the end's, which one of
        // a few samples finds unless the excursion is far shorter than the step.
        let start = if from_rest {
            (1..SAMPLES)
                .map(|j| t_old + (t_new - t_old) * f64::from(j) / f64::from(SAMPLES))
                .map(|t| (t, rate_at(t)))
                .find(|&(_, r)| r * rb < 0.0)
        } else {
            Some((t_old, ra))
        };
        if let Some((ta, r0)) = start.filter(|&(_, r)| r * rb < 0.0) {
            let tm = turning_point(rate_at, ta, t_new, r0);
            let y = value(tm).abs();
            if TOP {
                self.rec.max_u = self.rec.max_u.max(y);
            } else {
                self.rec.max_theta = self.rec.max_theta.max(y);
            }
        }
    }

    /// The summary of a run that ended at `t_end` in `phase` about `s` with `state` and the
    /// energy integrals `carried`, having started with the energy `e_initial`.
    pub(super) fn summary(
        &self,
        t_end: f64,
        phase: Phase,
        s: f64,
        state: &V::X,
        carried: Integrals,
        e_initial: f64,
    ) -> Summary {
        let Integrals { w, d } = carried;
        let e_ref = self.derived.e_ref;
        let losses = self.rec.losses;
        let (energy, residual) = if Self::ENERGY {
            let last = self.total_energy(state, s);
            let residual = (last - e_initial - w + d + losses) / e_ref;
            let balance = EnergyBalance {
                initial: e_initial / e_ref,
                last: last / e_ref,
                ground_work: w / e_ref,
                damping: d / e_ref,
                impact_losses: losses / e_ref,
                ground_dissipation: None,
            };
            (Some(balance), Some(residual))
        } else {
            (None, None)
        };
        let rec = &self.rec;
        Summary {
            kernel_variant: V::NAME,
            max_theta_over_alpha: rec.max_theta / self.derived.alpha,
            max_theta_over_theta_cr: rec.max_theta / self.derived.theta_cr,
            max_u_over_ucr: if V::RIGID {
                0.0
            } else if !self.opts.max_deflection {
                f64::NAN
            } else {
                rec.max_u / self.derived.u_cr
            },
            overturned: rec.overturn.is_some(),
            overturn_time: rec.overturn.map(|t| self.time(t)),
            impacts: rec.impacts,
            significant_impacts: rec.significant,
            energy_capped_impacts: rec.energy_capped,
            first_uplift_time: rec.first_uplift.map(|t| self.time(t)),
            first_impact_time: rec.first_impact.map(|t| self.time(t)),
            final_phase: phase,
            end_time: self.time(t_end),
            energy_balance_residual: residual,
            energy,
            solver_stats: self.stats,
            forces: self.force_summary(),
            ground: None,
        }
    }
}
