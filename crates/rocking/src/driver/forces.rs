//! The section forces at the column base and the ground reactions along a run: evaluated by the
//! generated force kernels at every step's end and, where a new extreme may lie inside a step, at
//! that extreme (golden-section search on the step's dense output), and the first instants at
//! which the model's no-sliding and no-jumping assumptions fail; recorded in a
//! [`ForceRecord`](super::force_record::ForceRecord).

use rocking_kernels::Array;
use rocking_motion::GroundMotion;
use rocking_ode::roots::{brent_max, first_true};

use super::force_record::{Forces, MEASURES};
use super::state::{contact_of, contact_x, Ellipse, Sim};
use crate::dense::StepView;
use crate::layout::Rocking;
use crate::results::ForceSummary;
use crate::taylor::{excitation_series, TaylorVariant};

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
        Forces::of_kernel(&f)
    }

    /// The forces under the ground acceleration `ug` of the state `x` whose rate `rate` =
    /// [θ', u', θ'', u''] the caller has (in full contact θ, θ' and their rates are 0): the
    /// accelerations are not solved again. Normalised by W and W B.
    fn forces_with_rate(&self, s: f64, ug: f64, x: &V::X, rate: &V::X) -> Forces {
        let qdd = V::Q::from_fn(|i| rate.values()[Rocking::<V>::THETA_DOT + i]);
        let f = V::section_forces(x, &qdd, ug, s, &self.p);
        Forces::of_kernel(&f).per_weight(self.weight, self.wb)
    }

    /// The forces at `t` of a step's state `x` there: from the rate the integrator has there,
    /// else solved.
    fn forces_on_step(
        &self,
        step: &impl StepView<V::X>,
        contact: bool,
        s: f64,
        t: f64,
        x: &V::X,
    ) -> Forces {
        match step.exact_rate(t) {
            Some(rate) => self.forces_with_rate(s, self.motion.accel(t), x, &rate),
            None => self.forces_at(contact, s, t, x),
        }
    }

    /// The rates of the measures `m` of the state `x` at `t` where the step has the state's
    /// first and second derivatives there (a Taylor step's start from its series, its end from
    /// the series of the step after it): a difference of `section_forces` along the tangent,
    /// over `delta`, instead of a probe of the dense output (whose forces would solve M q'' = F
    /// again).
    fn rates_at(
        &self,
        step: &impl StepView<V::X>,
        s: f64,
        (t, x): (f64, &V::X),
        delta: f64,
        m: &[f64; MEASURES],
    ) -> Option<[f64; MEASURES]> {
        let second = step.exact_second_rate(t)?;
        let rate = step.exact_rate(t)?;
        let (ug, _) = excitation_series::<M, 2>(self.motion, t);
        let along = |y: &V::X, dy: &V::X| V::X::from_fn(|i| y.values()[i] + delta * dy.values()[i]);
        let ahead = self.forces_with_rate(
            s,
            ug[0] + delta * ug[1],
            &along(x, &rate),
            &along(&rate, &second),
        );
        let m_ahead = ahead.measures();
        Some(std::array::from_fn(|k| (m_ahead[k] - m[k]) / delta))
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

    /// The forces over the step (t_old, t_new] of a phase, `old` those at t_old and, where the
    /// step before took them, the measures' rates there: the end's forces, and, for each
    /// quantity whose ends come within the step's possible overshoot of its largest so far, the
    /// extreme inside the step. Returns the forces at t_new and, where this step took them,
    /// their rates there.
    pub(super) fn extremes_forces(
        &mut self,
        step: &impl StepView<V::X>,
        contact: bool,
        s: f64,
        t_old: f64,
        old: ForcesAt,
        t_new: f64,
    ) -> ForcesAt {
        if !self.opts.forces {
            return old;
        }
        let at = |t: f64| self.forces_at(contact, s, t, &step.state(t));
        let x_new = step.state(t_new);
        let f_new = self.forces_on_step(step, contact, s, t_new, &x_new);
        let h = t_new - t_old;
        // A quantity oscillating at ω rises above its values at both ends of a step of length h
        // by at most (ω h)²/8 of its amplitude: only a step whose ends come within twice that of
        // the largest so far can hold a new largest value.
        let omega_h = self.fastest_rate * h;
        let margin = (0.25 * omega_h * omega_h).min(1.0);
        let (m_old, m_new) = (old.forces.measures(), f_new.measures());
        let (mut peak, mut when) = (m_new, [t_new; MEASURES]);
        let max = self.rec.forces.max;
        let scale = |k: usize| m_old[k].abs().max(m_new[k].abs()).max(max[k].abs());
        let searched = self.opts.force_extremes;
        let near: [bool; MEASURES] = std::array::from_fn(|k| {
            let ends = m_old[k].max(m_new[k]);
            searched.holds(k) && ends.is_finite() && ends >= max[k] - margin * scale(k)
        });
        let mut rates_new = None;
        if near.contains(&true) && h > 0.0 {
            // Slopes at both ends: a maximum inside the step rises from its start and falls to
            // its end; the cubic through the ends' values and slopes tells, to O((ω h)⁴),
            // whether it can beat the record. Each end's is a difference along the tangent
            // where the step has the state's derivatives there (a Taylor step's series at its
            // start, the next step's at its end: `rates_at`), else a one-sided difference on
            // the step's dense output; the start's is the step before's at its end where it
            // took one (the forces are smooth across a step boundary of a phase that is no kink
            // of the excitation).
            let delta = 1e-6 * h;
            let rate_old = old.rates.unwrap_or_else(|| {
                self.rates_at(step, s, (t_old, &step.state(t_old)), delta, &m_old)
                    .unwrap_or_else(|| {
                        let m_a = at(t_old + delta).measures();
                        std::array::from_fn(|k| (m_a[k] - m_old[k]) / delta)
                    })
            });
            // The end's slopes only where a near quantity rises from the start (else the step
            // after takes its start's own, where it needs them).
            let rising: [bool; MEASURES] = std::array::from_fn(|k| near[k] && rate_old[k] > 0.0);
            if rising.contains(&true) {
                let rate_new = self
                    .rates_at(step, s, (t_new, &x_new), delta, &m_new)
                    .unwrap_or_else(|| {
                        let m_b = at(t_new - delta).measures();
                        std::array::from_fn(|k| (m_new[k] - m_b[k]) / delta)
                    });
                // Kept for the next step if the ground acceleration has no kink at t_new.
                rates_new = (self.t_stop(t_old) > t_new).then_some(rate_new);
                let tolerance = (omega_h * omega_h).powi(2) / 192.0;
                for k in (0..MEASURES).filter(|&k| rising[k]) {
                    let (d0, d1) = (rate_old[k] * h, rate_new[k] * h);
                    if d1.is_nan() || d1 >= 0.0 {
                        continue;
                    }
                    if hermite_max(m_old[k], d0, m_new[k], d1) < max[k] - tolerance * scale(k) {
                        continue;
                    }
                    // Exact values, on the step's own time τ = t − t_old (the search resolves
                    // τ to √ε of its size; a force changes by (ω δτ)² of its size within δτ of
                    // its peak).
                    let (tau, v) = brent_max(|tau| at(t_old + tau).measures()[k], 0.0, h, 1e-9 * h);
                    if v > peak[k] {
                        (peak[k], when[k]) = (v, t_old + tau);
                    }
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
        ForcesAt {
            forces: f_new,
            rates: rates_new,
        }
    }

    /// After the excitation in full contact: can no force extreme grow any more? Each force is
    /// affine in (u, u') there, and the vibration stays inside `ellipse`.
    pub(super) fn forces_settled(&self, ellipse: &Ellipse) -> bool {
        let max = self.rec.forces.max;
        // |M_b|, |V_b|, |M_el| and, as R_v = W in contact, the required friction |R_h| / W: those
        // the run searches for (the others are lower bounds anyway).
        let searched = self.opts.force_extremes;
        (0..4).filter(|&k| searched.holds(k)).all(|k| {
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

/// The forces at a step boundary of a phase and, where a step took them, the rates of their
/// measures there ([`Forces::measures`], per unit time).
#[derive(Clone, Copy, Debug)]
pub(super) struct ForcesAt {
    pub(super) forces: Forces,
    pub(super) rates: Option<[f64; MEASURES]>,
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
