//! The transitions between phases: uplift from full contact (and the test that decides it),
//! the rocking phase's events (impact, overturning), and the impact as the policy decides it.

use rocking_kernels::kernels::index::energy as en;
use rocking_motion::GroundMotion;
use rocking_ode::roots::first_true;
use rocking_ode::taylor::TaylorSystem;

use rocking_kernels::{Array, Variant};

use super::impact::{self, After};
use super::state::{
    contact_of, contact_x, impact_state, Ellipse, Integrals, Next, Sim, G2, LEFT, RIGHT,
};
use crate::error::SimError;
use crate::layout::{Contact, Rocking};
use crate::options::Method;
use crate::results::{EventKind, Phase};
use crate::taylor::TaylorVariant;

/// How a contact phase starts: the uplift functions checked at once.
pub(super) enum ContactStart<V: Variant> {
    /// The base lifts at the phase start (after an impact: the rigid limit).
    Lifted(Next<V>),
    /// Full contact; `settling`: the first step is taken before an uplift is possible; `f0`:
    /// the uplift functions at the start.
    Contact { settling: bool, f0: G2 },
}

impl<V: TaylorVariant, M: GroundMotion + ?Sized, const NR: usize, const NC: usize>
    Sim<'_, V, M, NR, NC>
{
    /// The uplift functions [f_+, f_-] (eq 24) in full contact.
    pub(super) fn uplift_functions(&self, xc: &V::Xc, ug: f64) -> G2 {
        G2::new(
            V::uplift(xc, ug, RIGHT, &self.p),
            V::uplift(xc, ug, LEFT, &self.p),
        )
    }

    /// The start of full contact at `t0`. The uplift functions are checked at once (after an
    /// impact this is how the rigid limit works), except when the structure has just come to rest
    /// (`settle`): then, if an f_s is already above zero (a grazing excursion that would make the
    /// run chatter at one instant), a first step is taken before an uplift is possible. With
    /// every f_s below zero the first step looks for crossings inside it as every step does
    /// (placing a crossing of the first step at its end delayed a near-rigid column's uplift by a
    /// tenth of its period: `an_uplift_after_a_rest_is_located_inside_the_first_step`).
    pub(super) fn contact_start(
        &mut self,
        t0: f64,
        xc: V::Xc,
        carried: Integrals,
        settle: bool,
    ) -> Result<ContactStart<V>, SimError> {
        let ug0 = self.motion.accel_right(t0);
        let f0 = self.uplift_functions(&xc, ug0);
        for (k, s) in [(0, RIGHT), (1, LEFT)] {
            if self.opts.uplift && !settle && f0[k] > 0.0 && self.lifts(s, t0, &xc, ug0) {
                return self.uplift(t0, s, &xc, carried).map(ContactStart::Lifted);
            }
        }
        Ok(ContactStart::Contact {
            settling: settle && f0.iter().any(|g| *g > 0.0),
            f0,
        })
    }

    /// In full contact after the excitation, with the column at (u, u'): can nothing the run
    /// reports change any more? The base can never uplift (unless it is held down), and no
    /// tracked maximum (|u|, the forces) can grow: each is affine in (u, u') while the free
    /// vibration stays inside its energy ellipse.
    pub(super) fn settled(&self, xc: &V::Xc) -> bool {
        let e = V::energy(&contact_x::<V>(xc), RIGHT, &self.p);
        let ellipse = Ellipse {
            vib: e[en::KINETIC] + e[en::STRAIN],
            metric: &self.metric,
        };
        if self.opts.uplift {
            // f_s is affine in (u, u'): the base can never uplift when its largest reachable value
            // stays below zero.
            let (c, r) = ellipse.reach::<V>(|xc| V::uplift(xc, 0.0, RIGHT, &self.p));
            if c + r >= 0.0 {
                return false;
            }
        }
        // The top deflection Σ u_i ψ_i(1), where its maximum is tracked.
        if !V::RIGID && self.opts.max_deflection {
            let first = Contact::<V>::us(false).start;
            let (_, r_u) = ellipse.reach::<V>(|xc| self.top_by(|i| xc.values()[i], first));
            if r_u > self.rec.max_u {
                return false;
            }
        }
        !self.opts.forces || self.forces_settled(&ellipse)
    }

    /// Whether the base really lifts about `s` at `t` from full contact: the rocking equations
    /// give s θ'' > 0. It is equivalent to f_s > 0 (equations.md 1.2) except within rounding of
    /// f_s = 0, where it decides consistently with the integrator that will follow: with the
    /// Taylor method, θ'' is that integrator's first coefficient, computed as its first step
    /// will (the Taylor-mode kernel regroups the tape, so the pointwise θ'' may differ from it
    /// in the last bits and a lift decided on it could turn back at once); `ug` is ü_g(t) for
    /// the Runge–Kutta methods.
    fn lifts(&self, s: f64, t: f64, xc: &V::Xc, ug: f64) -> bool {
        let x = contact_x::<V>(xc);
        if self.opts.accuracy.method == Method::Taylor {
            let y0 = self.rocking_start(&x, Integrals::default());
            let mut x: [[f64; 2]; NR] = std::array::from_fn(|i| [y0[i], 0.0]);
            self.rocking_system(s).coefficients::<2>(t, &mut x);
            return s * x[Rocking::<V>::THETA_DOT][1] > 0.0;
        }
        s * V::rocking_rhs(&x, ug, s, &self.p).values()[Rocking::<V>::THETA_DDOT] > 0.0
    }

    /// The first time in [t_a, t_b] at which the base lifts about `s`, given that f_s rises
    /// through zero at t_a (`dense`: the contact phase's state); `None` when it lifts nowhere in
    /// (t_a, t_b] (a rounding-level excursion of f_s).
    pub(super) fn first_lift(
        &self,
        dense: impl Fn(f64) -> V::X,
        s: f64,
        t_a: f64,
        t_b: f64,
    ) -> Option<f64> {
        let lifts_at = |t: f64| {
            let xc = contact_of::<V>(&dense(t));
            self.lifts(s, t, &xc, self.motion.accel(t))
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
        Some(first_true(lifts_at, t_a, t_b))
    }

    /// The base lifts about `s` at `t` from full contact with the column at `xc` = (u, u').
    pub(super) fn uplift(
        &mut self,
        t: f64,
        s: f64,
        xc: &V::Xc,
        carried: Integrals,
    ) -> Result<Next<V>, SimError> {
        self.count_event(t)?;
        self.rec.uplift(t);
        let x = contact_x::<V>(xc);
        let e = V::energy(&x, s, &self.p)[en::KINETIC];
        self.log_event(t, EventKind::Uplift, "", Phase::rocking(s), &x, (e, e));
        Ok(Next::Rocking {
            t,
            s,
            x,
            n: 2,
            carried,
        })
    }

    /// The event `index` (0 impact, 1 overturning) of a rocking phase about `s` at `t`, state `x`.
    pub(super) fn rocking_event(
        &mut self,
        index: usize,
        t: f64,
        s: f64,
        x: V::X,
        carried: Integrals,
    ) -> Result<Next<V>, SimError> {
        if index == 0 {
            return self.impact(t, s, &x, carried);
        }
        self.count_event(t)?;
        let (theta, u) = (x.values()[Rocking::<V>::THETA], self.top(&x, false));
        self.rec.overturn(t, theta, u);
        let e = V::energy(&x, s, &self.p)[en::KINETIC];
        self.log_event(t, EventKind::Overturn, "", Phase::Overturned, &x, (e, e));
        Ok(Next::Done {
            t,
            phase: Phase::Overturned,
            s,
            state: x,
            carried,
        })
    }

    /// The impact at θ = 0 while rocking about `s` (pre-impact rocking state `x`): the policy
    /// ([`impact::resolve`]) decides, the run records it and goes on from its choice.
    fn impact(
        &mut self,
        t: f64,
        s: f64,
        x: &V::X,
        carried: Integrals,
    ) -> Result<Next<V>, SimError> {
        self.count_event(t)?;
        let significant = x.values()[Rocking::<V>::THETA_DOT].abs() >= self.significant_rate;
        let xi = impact_state::<V>(x);
        let out = impact::resolve::<V>(self.opts.impact, &xi, s, &self.p, self.rest_rate);
        self.rec.impact(t, significant, &out);
        let (e_before, e_after) = (out.energy_before, out.energy_after());
        match out.after {
            After::Contact { x: after, .. } => {
                self.log_event(
                    t,
                    out.kind,
                    out.branch,
                    Phase::Contact,
                    x,
                    (e_before, e_after),
                );
                Ok(Next::Contact {
                    t,
                    xc: contact_of::<V>(&after),
                    carried,
                    settle: out.kind == EventKind::Rest,
                })
            }
            After::Rocking { x: after, .. } => {
                let s2 = -s;
                self.log_event(
                    t,
                    out.kind,
                    out.branch,
                    Phase::rocking(s2),
                    x,
                    (e_before, e_after),
                );
                Ok(Next::Rocking {
                    t,
                    s: s2,
                    x: after,
                    n: 1,
                    carried,
                })
            }
        }
    }
}
