//! The two phases integrated by the Taylor method generated from the derivation: full contact
//! and rocking about a corner, each to its first event. Events are roots of each step's
//! polynomial (the uplift functions' series in contact, θ's series while rocking), so none inside
//! a step is missed.

use std::marker::PhantomData;

use rocking_motion::GroundMotion;
use rocking_ode::events::Direction;
use rocking_ode::poly;
use rocking_ode::taylor::{Taylor, TaylorOptions};

use rocking_kernels::Array;

use super::recorder::Step;
use super::state::{contact_state, contact_x, rocking_state, Integrals, Next, Sim, LEFT, RIGHT};
use crate::dense::{StepView, TaylorStep, TaylorStepEnd};
use crate::layout::{Contact, Rocking};
use crate::options::History;
use crate::results::Phase;
use crate::taylor::{ContactSystem, RockingSystem, TaylorVariant};
use crate::SimError;

impl<'a, V: TaylorVariant, M: GroundMotion + ?Sized, const NR: usize, const NC: usize>
    Sim<'a, V, M, NR, NC>
{
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

    /// Full contact from `t0` with the Taylor method (see [`Sim::contact_rk`]; the uplift
    /// functions' series along each step are the event polynomials).
    pub(super) fn contact_taylor(
        &mut self,
        t0: f64,
        xc0: V::Xc,
        carried: Integrals,
        settling: bool,
    ) -> Result<Next<V>, SimError> {
        let mut settling = settling;
        let scale = self.contact_scale;
        let nc = Contact::<V>::INTEGRALS;
        let y0: [f64; NC] = std::array::from_fn(|i| carried.after(xc0.values(), i) / scale[i]);
        let mut ode = self.taylor(self.contact_h_max(t0), t0, y0, nc)?;
        let mut sys = ContactSystem::<V, M, NC> {
            p: self.p,
            motion: self.motion,
            scale,
        };
        let unscale = |y: [f64; NC]| -> [f64; NC] { std::array::from_fn(|i| y[i] * scale[i]) };
        let may_stop = self.opts.stop_when_known && matches!(self.opts.history, History::None);
        let excitation_end = self.motion.end();
        let mut rec = self.start_phase(Phase::Contact, RIGHT, t0, &contact_x::<V>(&xc0));
        let mut t_stop = self.t_stop(t0);
        loop {
            ode.step(&mut sys, t_stop)?;
            let (t_old, t_new) = (ode.t_old(), ode.t());
            let step_span = Step {
                t_old,
                t_new,
                // A Taylor step is never rejected: its attempts are its steps.
                attempts: ode.stats().steps,
            };
            let dirs = [Direction::Rising, Direction::Rising];
            let rising = if self.opts.uplift {
                ode.locate(&mut sys, &dirs).map(|ev| (ev.t, ev.index))
            } else {
                None
            };
            // A rising root inside the settling step comes after f_s fell below zero: a real
            // uplift, as on any step (missed when only the end was looked at, once steps grew to
            // a fraction of the period).
            let crossing = if std::mem::take(&mut settling) && rising.is_none() && self.opts.uplift
            {
                let y = unscale(*ode.y());
                let xc = contact_state::<V>(&y);
                let g_new = self.uplift_functions(&xc, self.motion.accel(t_new));
                (0..2).find(|&k| g_new[k] > 0.0).map(|k| (t_new, k))
            } else {
                rising
            };
            let step = TaylorStep {
                ode: &ode,
                scale,
                contact: true,
                variant: PhantomData::<V>,
            };
            let dense = |t: f64| -> V::X { step.state(t) };
            let lift = crossing.and_then(|(t_up, index)| {
                let s = if index == 0 { RIGHT } else { LEFT };
                self.first_lift(dense, s, t_up, t_new).map(|t| (t, s))
            });
            if let Some((t_up, s)) = lift {
                self.record_step(&mut rec, &step, step_span, t_up)?;
                self.stats.add(ode.take_stats());
                let y = unscale(ode.dense(t_up));
                let carried = Integrals::of(&y, nc);
                return self.uplift(t_up, s, &contact_state::<V>(&y), carried);
            }
            t_stop = self.record_step(&mut rec, &step, step_span, t_new)?;
            let y = unscale(*ode.y());
            let xc = contact_state::<V>(&y);
            let done = t_new >= self.opts.t_end
                || (may_stop && t_new >= excitation_end && self.settled(&xc));
            if done {
                self.stats.add(ode.take_stats());
                return Ok(Next::Done {
                    t: t_new,
                    phase: Phase::Contact,
                    s: RIGHT,
                    state: contact_x::<V>(&xc),
                    carried: Integrals::of(&y, nc),
                });
            }
        }
    }

    /// The rocking phase about `s` as the Taylor integrator sees it.
    pub(super) fn rocking_system(&self, s: f64) -> RockingSystem<'a, V, M, NR> {
        RockingSystem {
            p: self.p,
            motion: self.motion,
            s,
            scale: self.rocking_scale,
        }
    }

    /// The scaled Taylor state of `[θ, u, θ', u']` and the carried integrals.
    pub(super) fn rocking_start(&self, x: &V::X, carried: Integrals) -> [f64; NR] {
        std::array::from_fn(|i| carried.after(x.values(), i) / self.rocking_scale[i])
    }

    /// Rocking about `s` from `t0` with the Taylor method (see [`Sim::rocking_rk`]). The impact is
    /// the first falling root of s θ's polynomial on a step, the overturning the first rising root
    /// of s θ − θ_over's. The start guard of the RK path is exact here: at the phase start θ and,
    /// after an uplift, θ' are exactly 0, so the polynomial's factor τ^n is exact and
    /// [`poly::first_root`] divides it out before it looks for a root.
    pub(super) fn rocking_taylor(
        &mut self,
        t0: f64,
        s: f64,
        x0: V::X,
        n: i32,
        carried: Integrals,
    ) -> Result<Next<V>, SimError> {
        let scale = self.rocking_scale;
        let nx = Rocking::<V>::INTEGRALS;
        let theta_row = Rocking::<V>::THETA;
        let y0 = self.rocking_start(&x0, carried);
        let mut ode = self.taylor(f64::INFINITY, t0, y0, nx)?;
        let mut sys = self.rocking_system(s);
        let unscale = |y: [f64; NR]| -> [f64; NR] { std::array::from_fn(|i| y[i] * scale[i]) };
        let over = self.opts.overturn_angle / scale[theta_row];
        let phase = Phase::rocking(s);
        let mut rec = self.start_phase(phase, s, t0, &x0);
        let mut t_stop = self.t_stop(t0);
        // The step before (`before`, from `waiting`) when its forces wait for this step's
        // series: the exact rates at its end.
        let mut before = ode;
        let mut waiting = None;
        loop {
            ode.step(&mut sys, t_stop)
                .map_err(|e| self.explain_failure(e, &unscale(*ode.y()), s))?;
            if let Some(t_prev) = waiting.take() {
                let end = TaylorStepEnd::<V, NR>::new(&before, &ode, scale);
                self.record_step_forces(&mut rec, &end, t_prev, before.t());
            }
            let (t_old, t_new) = (ode.t_old(), ode.t());
            let step_span = Step {
                t_old,
                t_new,
                attempts: ode.stats().steps,
            };
            let h = t_new - t_old;
            let order = ode.order();
            let theta = &ode.coefficients()[theta_row][..=order];
            // An uplift exactly at f_s = 0 (θ'' = 0) that turns back at once: an impact at t0,
            // as the RK path's armed event fires at its first step.
            let first = t_old == t0 && n > 0;
            let turns_back = first
                && theta
                    .iter()
                    .find(|c| **c != 0.0)
                    .is_some_and(|c| s * c < 0.0);
            // One bound of θ's change over the step rules out both events on most steps, before
            // their polynomials (s θ, s θ − θ_over) are formed.
            let tail = poly::abs_tail(theta, h);
            let root = |shift: f64, dir| {
                let g0 = s * theta[0] - shift;
                if poly::far_from_zero(g0, tail, order) {
                    return None;
                }
                let mut g = [0.0; 21];
                for (gk, &c) in g.iter_mut().zip(theta) {
                    *gk = s * c;
                }
                g[0] = g0;
                poly::first_root(&g[..=order], h, dir).map(|r| r.tau)
            };
            let roots: [Option<f64>; 2] = if turns_back {
                [Some(0.0), None]
            } else {
                [root(0.0, Direction::Falling), root(over, Direction::Rising)]
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
                contact: false,
                variant: PhantomData::<V>,
            };
            if let Some((index, tau)) = event {
                // Strictly after t_old for a root inside the step, even below t_old's ulp.
                let t = if tau >= h {
                    t_new
                } else if tau == 0.0 {
                    t_old
                } else {
                    (t_old + tau).max(after(t_old)).min(t_new)
                };
                self.record_step(&mut rec, &step, step_span, t)?;
                self.stats.add(ode.take_stats());
                self.stats.events += 1;
                let y = unscale(ode.dense(t));
                let carried = Integrals::of(&y, nx);
                return self.rocking_event(index, t, s, rocking_state::<V>(&y), carried);
            }
            // The forces of a step that ends at no kink of the excitation wait for the next
            // step's series (the rates at the end are then exact, not solved again).
            let last = t_new >= self.opts.t_end;
            let smooth = self.t_stop(t_old) > t_new;
            if self.opts.forces && smooth && !last {
                t_stop = self.record_step_but_forces(&mut rec, &step, step_span, t_new)?;
                before = ode;
                waiting = Some(t_old);
            } else {
                t_stop = self.record_step(&mut rec, &step, step_span, t_new)?;
            }
            if last {
                let y = unscale(*ode.y());
                self.stats.add(ode.take_stats());
                return Ok(Next::Done {
                    t: t_new,
                    phase,
                    s,
                    state: rocking_state::<V>(&y),
                    carried: Integrals::of(&y, nx),
                });
            }
        }
    }
}

/// The next f64 after a time `t >= 0`.
fn after(t: f64) -> f64 {
    f64::from_bits(t.to_bits() + 1)
}
