//! The extremes inside a step that its ends do not show, as the rigid surface's recorder finds
//! them: the turning points of θ, v and the top deflection (where their rates change sign), and
//! the peaks of the ground pressure, the section forces, and the dips of the contact length, the
//! least pressure and R_v (where their slopes turn inside the step and its ends come near the
//! record so far). Each point found is observed as a state of its own, so every maximum and
//! minimum of the run takes it; the bearing pressure's first exceedance is the crossing before the
//! first point over it.
//! Sampled at the steps' ends alone, a bed's maxima came out low by up to 3.8 % (the settlement)
//! and 1.1 % (the base moment) at ω_v/p = 200 (docs/ground.md).

use super::*;
use crate::{ForceExtreme, GroundExtreme, GroundKind};
use rocking_kernels::kernels::index::free_forces as ff;
use rocking_ode::roots::{brent_max, first_true, turning_point};

/// The measures searched for extremes at one state, each signed so that its record is a maximum
/// and over its summary's scale: the larger end pressure, |M_b|, |V_b|, |M_el|, and the negated
/// contact fraction, least end pressure and R_v.
pub(super) type Peaked = [f64; 7];

/// Positions in [`Peaked`].
const PRESSURE: usize = 0;
const MOMENT: usize = 1;
const SHEAR: usize = 2;
const ELASTIC: usize = 3;
const CONTACT: usize = 4;
const LEAST: usize = 5;
const REACTION_V: usize = 6;

impl<V: TaylorVariant, M: GroundMotion + ?Sized, const N: usize> GroundSim<'_, V, M, N> {
    /// The measures searched for extremes at one state (the forces 0 where the run records none).
    fn peaked(&self, t: f64, y: &V::Y, s: f64, c: Contact) -> Peaked {
        let ug = self.motion.accel(t);
        let (acc, g) = self.k.accelerations(y, ug, s, c);
        let mean = self.mean_pressure;
        let mut m = [0.0; 7];
        m[PRESSURE] = g[go::PRESSURE_LO].max(g[go::PRESSURE_HI]) / mean;
        m[CONTACT] = -contact_fraction(&g);
        m[LEAST] = -g[go::PRESSURE_LO].min(g[go::PRESSURE_HI]) / mean;
        if self.opts.forces {
            let f = V::free_forces(y, &acc, ug, s, &self.p);
            m[MOMENT] = f[ff::MOMENT].abs() / self.wb;
            m[SHEAR] = f[ff::SHEAR].abs() / self.weight;
            m[ELASTIC] = f[ff::MOMENT_ELASTIC].abs() / self.wb;
            m[REACTION_V] = -f[ff::REACTION_V] / self.weight;
        }
        m
    }

    /// Whether measure `k` is searched for inside a step of contact state `c`: those the run
    /// asks for ([`Options::force_extremes`], [`Options::ground_extremes`]; the largest pressure
    /// also for the bearing check), the pressures and R_v not in flight, the contact length only
    /// while one edge of a bed is lifted and above its least so far (it can fall no lower than 0).
    fn searched(&self, k: usize, c: Contact) -> bool {
        let (o, pressed) = (self.opts, c.left || c.right);
        let force = |e: ForceExtreme| o.forces && o.force_extremes.contains(e);
        let ground = |e: GroundExtreme| o.ground_extremes.contains(e);
        match k {
            PRESSURE => {
                pressed && (ground(GroundExtreme::MaxPressure) || o.bearing_over_mean.is_some())
            }
            LEAST => pressed && ground(GroundExtreme::LeastPressure),
            CONTACT => {
                c.left != c.right
                    && self.k.ground.kind == GroundKind::Winkler
                    && !self.k.bilateral
                    && self.rec.min_contact > 0.0
                    && ground(GroundExtreme::ContactFraction)
            }
            MOMENT => force(ForceExtreme::BaseMoment),
            SHEAR => force(ForceExtreme::BaseShear),
            ELASTIC => force(ForceExtreme::ElasticMoment),
            _ => pressed && force(ForceExtreme::VerticalReaction),
        }
    }

    /// Observes the points inside the step (t_old, t_new) of one phase (`at` its state at a
    /// time, `c` its contact state) where a recorded quantity peaks, in time order.
    pub(super) fn peaks_inside(
        &mut self,
        at: &impl Fn(f64) -> V::Y,
        t_old: f64,
        t_new: f64,
        s: f64,
        c: Contact,
    ) {
        let h = t_new - t_old;
        if h <= 0.0 {
            return;
        }
        let (a, b) = (at(t_old), at(t_new));
        let mut found: Vec<f64> = Vec::new();
        // θ', v' and the top deflection's rate (a rigid column has none).
        let rate = |y: &V::Y, k: usize| match k {
            0 => y.values()[Free::<V>::THETA_DOT],
            1 => y.values()[Free::<V>::V_DOT],
            _ => self.top(y, true),
        };
        for k in 0..if V::RIGID { 2 } else { 3 } {
            let (ra, rb) = (rate(&a, k), rate(&b, k));
            if ra * rb < 0.0 {
                found.push(turning_point(|t| rate(&at(t), k), t_old, t_new, ra));
            }
        }
        // A quantity oscillating at ω rises above its values at both ends of a step of length h
        // by at most (ω h)²/8 of its amplitude: only a step whose ends come within twice that
        // of the largest so far can hold a new largest value (as `driver::forces`).
        let omega_h = self.fastest_rate * h;
        let margin = (0.25 * omega_h * omega_h).min(1.0);
        // The step before ended where this one starts (in the same contact state): its end's.
        let m_old = match self.rec.last_peaked {
            Some((t, c_then, m)) if t == t_old && c_then == c => m,
            _ => self.peaked(t_old, &a, s, c),
        };
        let m_new = self.peaked(t_new, &b, s, c);
        self.rec.last_peaked = Some((t_new, c, m_new));
        let r = &self.rec;
        let record = [
            r.max_pressure,
            r.max_moment,
            r.max_shear,
            r.max_elastic,
            -r.min_contact,
            -r.min_pressure,
            -r.min_rv,
        ];
        let delta = 1e-6 * h;
        let mut slopes: Option<(Peaked, Peaked)> = None;
        for k in (0..record.len()).filter(|&k| self.searched(k, c)) {
            let ends = m_old[k].max(m_new[k]);
            // The quantity's amplitude: for the maxima (of measures >= 0) their largest value;
            // the contact fraction's is at most 1; the least pressure and R_v / W swing with the
            // largest pressure over the mean (R_v <= 2B p_max = W p_max / mean).
            let scale = match k {
                CONTACT => 1.0,
                LEAST | REACTION_V => ends
                    .abs()
                    .max(record[k].abs())
                    .max(record[PRESSURE])
                    .max(1.0),
                _ => ends.max(record[k]),
            };
            if !ends.is_finite() || ends < record[k] - margin * scale {
                continue;
            }
            let (d0, d1) = *slopes.get_or_insert_with(|| {
                let after = self.peaked(t_old + delta, &at(t_old + delta), s, c);
                let before = self.peaked(t_new - delta, &at(t_new - delta), s, c);
                (
                    std::array::from_fn(|j| after[j] - m_old[j]),
                    std::array::from_fn(|j| m_new[j] - before[j]),
                )
            });
            if d0[k] > 0.0 && d1[k] < 0.0 {
                let peak = |tau: f64| self.peaked(t_old + tau, &at(t_old + tau), s, c)[k];
                found.push(t_old + brent_max(peak, 0.0, h, 1e-9 * h).0);
            }
        }
        found.sort_by(f64::total_cmp);
        // The bearing pressure's first exceedance: the crossing before the first point over it.
        let bearing = self.opts.bearing_over_mean;
        if let Some(q) = bearing.filter(|_| self.rec.first_bearing.is_none()) {
            let over = |t: f64| self.peaked(t, &at(t), s, c)[PRESSURE] > q;
            if let Some(t_hi) = found.iter().copied().chain([t_new]).find(|&t| over(t)) {
                self.rec.first_bearing = Some(first_true(over, t_old, t_hi));
            }
        }
        for t in found {
            self.observe(t, &at(t), s, c);
        }
    }
}

/// The fastest rate of a run on the ground: ω_v, the column's ω_n, ω_up and highest fixed-base
/// frequency, p, and the excitation's (a sixteenth of its shortest period, as on the rigid
/// surface).
pub(super) fn fastest_rate<V: Variant, M: GroundMotion + ?Sized>(
    p: &V::Params,
    derived: &Derived,
    omega_v: f64,
    motion: &M,
) -> f64 {
    let excitation = 2.0 * std::f64::consts::PI / (16.0 * motion.resolution());
    let highest = Matrices::of::<V>(p)
        .fixed_base()
        .and_then(|m| m.omega.last().copied())
        .unwrap_or(f64::NAN);
    [
        omega_v,
        derived.omega_n,
        derived.omega_up,
        highest,
        derived.p,
        excitation,
    ]
    .into_iter()
    .filter(|w| w.is_finite())
    .fold(0.0, f64::max)
}
