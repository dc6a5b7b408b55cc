//! What a run records as it goes: the maxima of θ and u (turning points inside steps included),
//! the time history, the event log, and at the end the summary.

use rocking_kernels::kernels::index::energy as en;
use rocking_motion::GroundMotion;
use rocking_ode::roots::turning_point;

use super::state::Sim;
use crate::dense::StepView;
use crate::options::History;
use crate::results::{EnergyBalance, EventKind, EventRecord, HistoryRow, Phase, Summary};
use crate::taylor::TaylorVariant;

impl<V: TaylorVariant, M: GroundMotion + ?Sized, const NR: usize, const NC: usize>
    Sim<'_, V, M, NR, NC>
{
    pub(super) fn track(&mut self, x: &[f64; 4]) {
        self.rec.max_theta = self.rec.max_theta.max(x[0].abs());
        self.rec.max_u = self.rec.max_u.max(x[1].abs());
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
        self.rec.history.push(row);
    }

    /// History rows for the step (t_old, t_new] of a phase, from the dense output.
    pub(super) fn step_history(
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

    /// An event of the log (when asked for): `pre` is [θ', u, u'] before it, `energies` the
    /// kinetic energy before and after.
    pub(super) fn log_event(
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
            let record = EventRecord {
                time: self.time(t),
                kind,
                branch,
                phase_after,
                theta_dot: pre[0],
                u: pre[1],
                u_dot: pre[2],
                energy_before: energies.0 / e_ref,
                energy_after: energies.1 / e_ref,
            };
            self.rec.log.push(record);
        }
    }

    /// max |u| within a contact step, including a turning point inside it.
    pub(super) fn extremes_contact(&mut self, step: &impl StepView, t_old: f64, t_new: f64) {
        let (a, b) = (step.state(t_old), step.state(t_new));
        self.rec.max_u = self.rec.max_u.max(b[1].abs());
        if a[3] * b[3] < 0.0 && step.bound(1) > self.rec.max_u {
            let tm = turning_point(|t| step.component(3, t), t_old, t_new, a[3]);
            self.rec.max_u = self.rec.max_u.max(step.component(1, tm).abs());
        }
    }

    /// max |θ| and |u| within a rocking step, including turning points inside it.
    pub(super) fn extremes_rocking(&mut self, step: &impl StepView, t_old: f64, t_new: f64) {
        const SAMPLES: u32 = 32;
        let (a, b) = (step.state(t_old), step.state(t_new));
        self.track(&[b[0], b[1], 0.0, 0.0]);
        for (pos, rate) in [(0usize, 2usize), (1, 3)] {
            let max = if pos == 0 {
                self.rec.max_theta
            } else {
                self.rec.max_u
            };
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
                    self.rec.max_theta = self.rec.max_theta.max(y);
                } else {
                    self.rec.max_u = self.rec.max_u.max(y);
                }
            }
        }
    }

    /// The summary of a run that ended at `t_end` in `phase` about `s` with `state` and the
    /// energy integrals (w, d), having started with the energy `e_initial`.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn summary(
        &self,
        t_end: f64,
        phase: Phase,
        s: f64,
        state: &[f64; 4],
        (w, d): (f64, f64),
        e_initial: f64,
    ) -> Summary {
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
        }
    }
}
