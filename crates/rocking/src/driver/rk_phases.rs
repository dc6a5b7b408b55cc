//! The two phases integrated by a Runge–Kutta method (DOPRI5 or DOP853 of `rocking-ode`): full
//! contact (state [u, u'] and the carried integrals) and rocking about a corner (state
//! [θ, u, θ', u'] and the integrals), each to its first event.

use rocking_kernels::Array;
use rocking_motion::GroundMotion;
use rocking_ode::events::{locate, refine, Direction};
use rocking_ode::roots::grazing;
use rocking_ode::{Integrator, Options as OdeOptions};

use super::recorder::Step;
use super::state::{
    contact_state, contact_x, rocking_state, Integrals, Next, Sim, G2, LEFT, RIGHT, Y,
};
use crate::dense::RkStep;
use crate::layout::{Contact, Rocking};
use crate::options::History;
use crate::results::Phase;
use crate::taylor::TaylorVariant;
use crate::SimError;

impl<V: TaylorVariant, M: GroundMotion + ?Sized, const NR: usize, const NC: usize>
    Sim<'_, V, M, NR, NC>
{
    /// Full contact from `t0` (see [`Sim::contact_start`] for `settling`; `f0`: the uplift
    /// functions at the start): uplift when f_+ or f_- rises through zero (or touches it inside
    /// a step) and the base really lifts; or the end of the run.
    pub(super) fn contact_rk(
        &mut self,
        t0: f64,
        xc0: V::Xc,
        carried: Integrals,
        settling: bool,
        f0: G2,
    ) -> Result<Next<V>, SimError> {
        let mut settling = settling;
        let full_history = !matches!(self.opts.history, History::None);
        let may_stop = self.opts.stop_when_known && !full_history;
        let (p, motion) = (self.p, self.motion);
        let nc = Contact::<V>::INTEGRALS;
        let mut rhs = |t: f64, y: &Y<NC>| -> Y<NC> {
            let ug = motion.accel(t);
            let xc = contact_state::<V>(y.as_slice());
            let dx = V::contact_rhs(&xc, ug, &p);
            let mut out = Y::<NC>::zeros();
            out.as_mut_slice()[..nc].copy_from_slice(dx.values());
            if Self::ENERGY {
                let pw = V::power(&contact_x::<V>(&xc), ug, RIGHT, &p);
                Integrals::of_power(&pw).put(out.as_mut_slice(), nc);
            }
            out
        };
        let mut g = |t: f64, y: &Y<NC>| -> G2 {
            let ug = motion.accel(t);
            let xc = contact_state::<V>(y.as_slice());
            G2::new(V::uplift(&xc, ug, RIGHT, &p), V::uplift(&xc, ug, LEFT, &p))
        };
        let options = OdeOptions {
            h_max: self.contact_h_max(t0),
            ..self.ode_options
        };
        let mut ode = Integrator::new(options, self.contact_tol)?;
        let y0 = Y::<NC>::from_fn(|i, _| carried.after(xc0.values(), i));
        ode.reset(t0, y0, &mut rhs)?;
        let mut g_old = f0;
        let dirs = [Direction::Rising, Direction::Rising];
        let excitation_end = motion.end();
        let mut rec = self.start_phase(Phase::Contact, RIGHT, t0, &contact_x::<V>(&xc0));
        let mut t_stop = self.t_stop(t0);
        loop {
            let info = ode.step(&mut rhs, t_stop)?;
            let step = Step {
                t_old: info.t_old,
                t_new: info.t_new,
                attempts: ode.stats().steps + ode.stats().rejected,
            };
            let (t_old, t_new) = (info.t_old, info.t_new);
            let g_new = g(t_new, ode.y());
            let located = if self.opts.uplift {
                locate(&mut ode, &mut g, &dirs, &g_old, &g_new)
                    .map(|ev| refine(&mut ode, &mut rhs, &mut g, ev))
                    .map(|ev| (ev.t, ev.index, t_new))
            } else {
                None
            };
            // In the settling step, an f_s that started above zero and is still there at its end
            // lifts at the end; a rising crossing of one that started below zero is an uplift.
            let crossing = if std::mem::take(&mut settling) {
                located.or_else(|| (0..2).find(|&k| g_new[k] > 0.0).map(|k| (t_new, k, t_new)))
            } else if self.opts.uplift {
                located.or_else(|| grazing(|t| g(t, &ode.dense(t)), t_old, t_new, &g_old, &g_new))
            } else {
                None
            };
            let dense = |t| contact_x::<V>(&contact_state::<V>(ode.dense(t).as_slice()));
            let lift = crossing.and_then(|(t_up, index, t_far)| {
                let s = if index == 0 { RIGHT } else { LEFT };
                self.first_lift(dense, s, t_up, t_far).map(|t| (t, s))
            });
            if let Some((t_up, s)) = lift {
                self.record_step(&mut rec, &dense, step, t_up)?;
                let y = ode.step_state(&mut rhs, t_up);
                self.stats.add(ode.take_stats());
                let carried = Integrals::of(y.as_slice(), nc);
                return self.uplift(t_up, s, &contact_state::<V>(y.as_slice()), carried);
            }
            // The end's rate is the derivative the integrator evaluated there.
            let contact_rate = |y: &Y<NC>| contact_x::<V>(&contact_state::<V>(y.as_slice()));
            let view = RkStep {
                dense,
                t_new,
                rate: contact_rate(ode.dy()),
            };
            t_stop = self.record_step(&mut rec, &view, step, t_new)?;
            g_old = g_new;
            let y = *ode.y();
            let xc = contact_state::<V>(y.as_slice());
            let done = t_new >= self.opts.t_end
                || (may_stop && t_new >= excitation_end && self.settled(&xc));
            if done {
                self.stats.add(ode.take_stats());
                return Ok(Next::Done {
                    t: t_new,
                    phase: Phase::Contact,
                    s: RIGHT,
                    state: contact_x::<V>(&xc),
                    carried: Integrals::of(y.as_slice(), nc),
                });
            }
        }
    }

    /// Rocking about `s` from `t0` at `x0` = [θ, u, θ', u']: to the impact (s θ / (t − t0)^n
    /// falling through zero, regularised so that it cannot fire at t0), the overturning
    /// (s θ = θ_over), or the end of the run.
    pub(super) fn rocking_rk(
        &mut self,
        t0: f64,
        s: f64,
        x0: V::X,
        n: i32,
        carried: Integrals,
    ) -> Result<Next<V>, SimError> {
        let (p, motion) = (self.p, self.motion);
        let over = self.opts.overturn_angle;
        let nx = Rocking::<V>::INTEGRALS;
        let mut rhs = |t: f64, y: &Y<NR>| -> Y<NR> {
            let ug = motion.accel(t);
            let x = rocking_state::<V>(y.as_slice());
            let dx = V::rocking_rhs(&x, ug, s, &p);
            let mut out = Y::<NR>::zeros();
            out.as_mut_slice()[..nx].copy_from_slice(dx.values());
            if Self::ENERGY {
                let pw = V::power(&x, ug, s, &p);
                Integrals::of_power(&pw).put(out.as_mut_slice(), nx);
            }
            out
        };
        let x0v = x0.values();
        // The impact event s θ / (t − t0)^n, with its limit at t0 (equations.md §5, note 4).
        let start_limit = if n == 0 {
            s * x0v[Rocking::<V>::THETA]
        } else if n == 1 {
            s * x0v[Rocking::<V>::THETA_DOT]
        } else {
            let rate = V::rocking_rhs(&x0, motion.accel_right(t0), s, &p);
            s * rate.values()[Rocking::<V>::THETA_DDOT] / 2.0
        };
        // An uplift exactly at f_s = 0 has θ'' = 0: keep the event armed (it fires at once if θ
        // turns back, which ends the zero-length rocking phase with an impact).
        let start_limit = start_limit.max(f64::MIN_POSITIVE);
        let theta = Rocking::<V>::THETA;
        let mut g = |t: f64, y: &Y<NR>| -> G2 {
            let dt = t - t0;
            let impact = if dt > 0.0 {
                s * y[theta] / dt.powi(n)
            } else {
                start_limit
            };
            G2::new(impact, s * y[theta] - over)
        };
        let y0 = Y::<NR>::from_fn(|i, _| carried.after(x0v, i));
        let mut ode = Integrator::new(self.ode_options, self.rocking_tol)?;
        ode.reset(t0, y0, &mut rhs)?;
        let mut g_old = g(t0, &y0);
        let dirs = [Direction::Falling, Direction::Rising];
        let phase = Phase::rocking(s);
        let mut rec = self.start_phase(phase, s, t0, &x0);
        let mut t_stop = self.t_stop(t0);
        loop {
            let info = ode
                .step(&mut rhs, t_stop)
                .map_err(|e| self.explain_failure(e, ode.y().as_slice(), s))?;
            let step = Step {
                t_old: info.t_old,
                t_new: info.t_new,
                attempts: ode.stats().steps + ode.stats().rejected,
            };
            let t_new = info.t_new;
            let g_new = g(t_new, ode.y());
            if let Some(ev) = locate(&mut ode, &mut g, &dirs, &g_old, &g_new) {
                let ev = refine(&mut ode, &mut rhs, &mut g, ev);
                let dense = |t| rocking_state::<V>(ode.dense(t).as_slice());
                self.record_step(&mut rec, &dense, step, ev.t)?;
                self.stats.add(ode.take_stats());
                let y = ev.y;
                let carried = Integrals::of(y.as_slice(), nx);
                let x = rocking_state::<V>(y.as_slice());
                return self.rocking_event(ev.index, ev.t, s, x, carried);
            }
            let view = RkStep {
                dense: |t| rocking_state::<V>(ode.dense(t).as_slice()),
                t_new,
                rate: rocking_state::<V>(ode.dy().as_slice()),
            };
            t_stop = self.record_step(&mut rec, &view, step, t_new)?;
            g_old = g_new;
            if t_new >= self.opts.t_end {
                let y = *ode.y();
                self.stats.add(ode.take_stats());
                return Ok(Next::Done {
                    t: t_new,
                    phase,
                    s,
                    state: rocking_state::<V>(y.as_slice()),
                    carried: Integrals::of(y.as_slice(), nx),
                });
            }
        }
    }
}
