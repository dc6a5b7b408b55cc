//! The section forces at the column base and the ground reactions along a run: evaluated by the
//! generated force kernels at every step's end and, where a new extreme may lie inside a step, at
//! that extreme (golden-section search on the step's dense output), and the first instants at
//! which the model's no-sliding and no-jumping assumptions fail; recorded in a
//! [`ForceRecord`](super::force_record::ForceRecord).

use rocking_kernels::kernels::index::forces_rocking as fk;
use rocking_motion::GroundMotion;
use rocking_ode::roots::{first_true, golden_max};

use super::force_record::{Forces, MEASURES};
use super::state::{contact_of, contact_x, Ellipse, Sim};
use crate::dense::StepView;
use crate::results::ForceSummary;
use crate::taylor::TaylorVariant;

impl<V: TaylorVariant, M: GroundMotion + ?Sized, const NR: usize, const NC: usize>
    Sim<'_, V, M, NR, NC>
{
    /// The forces at `t` of the state `x` = [θ, u, θ', u'], in full contact (`contact`) or
    /// rocking about `s` (each phase's accelerations: a row at an event is on its own side).
    pub(super) fn forces_at(&self, contact: bool, s: f64, t: f64, x: &V::X) -> Forces {
        self.forces_of(contact, s, self.motion.accel(t), x)
    }

    /// The forces of the state `x` under the ground acceleration `ug`, normalised by W and W B.
    fn forces_of(&self, contact: bool, s: f64, ug: f64, x: &V::X) -> Forces {
        self.model_forces(contact, s, ug, x)
            .per_weight(self.weight, self.wb)
    }

    /// The forces of the state `x` under the ground acceleration `ug`, in the model's units.
    pub(super) fn model_forces(&self, contact: bool, s: f64, ug: f64, x: &V::X) -> Forces {
        // Both kernels name their outputs alike (index::forces_contact has the same order).
        let f = if contact {
            V::forces_contact(&contact_of::<V>(x), ug, &self.p)
        } else {
            V::forces_rocking(x, ug, s, &self.p)
        };
        Forces {
            moment: f[fk::MOMENT],
            shear: f[fk::SHEAR],
            elastic: f[fk::MOMENT_ELASTIC],
            horizontal: f[fk::REACTION_H],
            vertical: f[fk::REACTION_V],
        }
    }

    /// The forces of the state at the start of a phase (after its event), recorded.
    pub(super) fn forces_start(&mut self, contact: bool, s: f64, t: f64, x: &V::X) -> Forces {
        let f = self.forces_at(contact, s, t, x);
        if self.opts.forces {
            self.rec
                .forces
                .record(&f.measures(), [t; MEASURES], self.opts.friction);
        }
        f
    }

    /// The forces over the step (t_old, t_new] of a phase, `f_old` those at t_old: the end's,
    /// and, for each reported quantity whose ends come within the step's possible overshoot of
    /// its largest so far, the extreme inside the step. Returns the forces at t_new.
    pub(super) fn extremes_forces(
        &mut self,
        step: &impl StepView<V::X>,
        contact: bool,
        s: f64,
        t_old: f64,
        f_old: Forces,
        t_new: f64,
    ) -> Forces {
        if !self.opts.forces {
            return f_old;
        }
        let at = |t: f64| self.forces_at(contact, s, t, &step.state(t));
        let f_new = at(t_new);
        let h = t_new - t_old;
        // A quantity oscillating at ω rises above its values at both ends of a step of length h
        // by at most (ω h)²/8 of its amplitude: only a step whose ends come within twice that of
        // the largest so far can hold a new largest value.
        let omega_h = self.fastest_rate * h;
        let margin = (0.25 * omega_h * omega_h).min(1.0);
        let (m_old, m_new) = (f_old.measures(), f_new.measures());
        let (mut peak, mut when) = (m_new, [t_new; MEASURES]);
        let max = self.rec.forces.max;
        let scale = |k: usize| m_old[k].abs().max(m_new[k].abs()).max(max[k].abs());
        let near: Vec<usize> = (0..MEASURES)
            .filter(|&k| {
                let ends = m_old[k].max(m_new[k]);
                ends.is_finite() && ends >= max[k] - margin * scale(k)
            })
            .collect();
        if !near.is_empty() && h > 0.0 {
            // Slopes at both ends (one-sided differences on the step's dense output): a maximum
            // inside the step rises from its start and falls to its end; the cubic through the
            // ends' values and slopes tells, to O((ω h)⁴), whether it can beat the record.
            let delta = 1e-6 * h;
            let (m_a, m_b) = (at(t_old + delta).measures(), at(t_new - delta).measures());
            let tolerance = (omega_h * omega_h).powi(2) / 192.0;
            for k in near {
                let d0 = (m_a[k] - m_old[k]) / delta * h;
                let d1 = (m_new[k] - m_b[k]) / delta * h;
                if !(d0 > 0.0 && d1 < 0.0) {
                    continue;
                }
                if hermite_max(m_old[k], d0, m_new[k], d1) < max[k] - tolerance * scale(k) {
                    continue;
                }
                let (t, v) = golden_max(|t| at(t).measures()[k], t_old, t_new);
                if v > peak[k] {
                    (peak[k], when[k]) = (v, t);
                }
            }
        }
        // The first instant on the step at which an assumption fails (false at t_old, else it
        // was recorded at the end of the step before or at the phase start).
        let rec = self.rec.forces;
        let slip = self
            .opts
            .friction
            .filter(|mu| rec.first_slip.is_none() && peak[3] > *mu);
        let slip = slip.map(|mu| first_true(|t| at(t).required_friction() > mu, t_old, when[3]));
        let lift_off = (rec.first_lift_off.is_none() && peak[4] > 0.0)
            .then(|| first_true(|t| at(t).vertical < 0.0, t_old, when[4]));
        let rec = &mut self.rec.forces;
        rec.first_slip = rec.first_slip.or(slip);
        rec.first_lift_off = rec.first_lift_off.or(lift_off);
        self.rec.forces.record(&peak, when, self.opts.friction);
        f_new
    }

    /// After the excitation in full contact: can no force extreme grow any more? Each force is
    /// affine in (u, u') there, and the vibration stays inside `ellipse`.
    pub(super) fn forces_settled(&self, ellipse: &Ellipse) -> bool {
        let max = self.rec.forces.max;
        // |M_b|, |V_b|, |M_el| and, as R_v = W in contact, the required friction |R_h| / W.
        (0..4).all(|k| {
            let (c, r) = ellipse.reach::<V>(|xc| {
                let f = self.forces_of(true, 1.0, 0.0, &contact_x::<V>(xc));
                [f.moment, f.shear, f.elastic, f.horizontal][k]
            });
            c.abs() + r <= max[k]
        })
    }

    /// The force extremes of the run, as the summary reports them.
    pub(super) fn force_summary(&self) -> Option<ForceSummary> {
        self.opts
            .forces
            .then(|| self.rec.forces.summary(|t| self.time(t)))
    }
}

/// The largest value on [0, 1] of the cubic with values `p0`, `p1` and slopes `d0`, `d1` at its
/// ends (cubic Hermite interpolation).
fn hermite_max(p0: f64, d0: f64, p1: f64, d1: f64) -> f64 {
    // p(τ) = a τ³ + b τ² + d0 τ + p0.
    let a = 2.0 * (p0 - p1) + d0 + d1;
    let b = 3.0 * (p1 - p0) - 2.0 * d0 - d1;
    let p = |t: f64| ((a * t + b) * t + d0) * t + p0;
    // p'(τ) = 3a τ² + 2b τ + d0 = 0.
    let (qa, qb, qc) = (3.0 * a, 2.0 * b, d0);
    let mut best = p0.max(p1);
    let mut consider = |t: f64| {
        if t > 0.0 && t < 1.0 {
            best = best.max(p(t));
        }
    };
    if qa.abs() < 1e-300 {
        if qb != 0.0 {
            consider(-qc / qb);
        }
    } else {
        let disc = qb * qb - 4.0 * qa * qc;
        if disc >= 0.0 {
            let r = disc.sqrt();
            consider((-qb + r) / (2.0 * qa));
            consider((-qb - r) / (2.0 * qa));
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::hermite_max;

    #[test]
    fn hermite_max_is_the_peak_of_the_interpolating_cubic() {
        // sin(π τ) on [0, 1]: values 0, slopes ±π; the cubic's peak is at τ = 1/2, value π/4.
        let pi = std::f64::consts::PI;
        let v = hermite_max(0.0, pi, 0.0, -pi);
        assert!((v - pi / 4.0).abs() < 1e-15, "{v}");
        // A monotone cubic peaks at its larger end.
        assert_eq!(hermite_max(0.0, 1.0, 1.0, 1.0), 1.0);
    }
}
