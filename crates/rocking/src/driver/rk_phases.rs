//! The two phases integrated by a Runge–Kutta method (DOPRI5 or DOP853 of `rocking-ode`): full
//! contact (state [u, u'] and the carried integrals) and rocking about a corner (state
//! [θ, u, θ', u'] and the integrals), each to its first event.

use rocking_kernels::kernels::index::{power as pwr, rocking_rhs as rr};
use rocking_motion::GroundMotion;
use rocking_ode::events::{locate, Direction};
use rocking_ode::roots::grazing;
use rocking_ode::{Integrator, Options as OdeOptions};

use super::state::{carried, rocking_state, Next, Sim, G2, LEFT, RIGHT, Y};
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
        [u, u_dot, w, d]: [f64; 4],
        settling: bool,
        f0: G2,
    ) -> Result<Next, SimError> {
        let mut settling = settling;
        let full_history = !matches!(self.opts.history, History::None);
        let may_stop = self.opts.stop_when_known && !full_history;
        let (p, motion) = (self.p, self.motion);
        let mut rhs = |t: f64, y: &Y<NC>| -> Y<NC> {
            let ug = motion.accel(t);
            let dx = V::contact_rhs(&[y[0], y[1]], ug, &p);
            let mut out = Y::<NC>::zeros();
            out[0] = dx[0];
            out[1] = dx[1];
            if Self::ENERGY {
                let pw = V::power(&[0.0, y[0], 0.0, y[1]], ug, RIGHT, &p);
                out[2] = pw[pwr::GROUND];
                out[3] = pw[pwr::DAMPING];
            }
            out
        };
        let mut g = |t: f64, y: &Y<NC>| -> G2 {
            let ug = motion.accel(t);
            G2::new(
                V::uplift(&[y[0], y[1]], ug, RIGHT, &p),
                V::uplift(&[y[0], y[1]], ug, LEFT, &p),
            )
        };
        let options = OdeOptions {
            h_max: self.contact_h_max(t0),
            ..self.ode_options
        };
        let mut ode = Integrator::new(options, self.contact_tol)?;
        ode.reset(t0, Y::<NC>::from_fn(|i, _| [u, u_dot, w, d][i]), &mut rhs)?;
        let mut g_old = f0;
        let dirs = [Direction::Rising, Direction::Rising];
        let excitation_end = motion.end();
        let mut f_prev = self.forces_start(true, RIGHT, t0, &[0.0, u, 0.0, u_dot]);
        loop {
            let t_stop = self.t_stop(ode.t());
            let info = ode.step(&mut rhs, t_stop)?;
            self.guard_steps(ode.stats(), ode.t())?;
            let (t_old, t_new) = (info.t_old, info.t_new);
            let g_new = g(t_new, ode.y());
            let located = if self.opts.uplift {
                locate(&mut ode, &mut g, &dirs, &g_old, &g_new).map(|ev| (ev.t, ev.index, t_new))
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
            let dense = |t| contact_state(&ode.dense(t));
            let lift = crossing.and_then(|(t_up, index, t_far)| {
                let s = if index == 0 { RIGHT } else { LEFT };
                self.first_lift(dense, s, t_up, t_far).map(|t| (t, s))
            });
            if let Some((t_up, s)) = lift {
                self.extremes_contact(&dense, t_old, t_up);
                self.extremes_forces(&dense, true, RIGHT, t_old, f_prev, t_up);
                let y = ode.dense(t_up);
                self.step_history(t_old, t_up, dense, Phase::Contact, RIGHT);
                self.stats.add(ode.take_stats());
                let (w, d) = carried(y.as_slice(), 2);
                return self.uplift(t_up, s, y[0], y[1], w, d);
            }
            self.extremes_contact(&dense, t_old, t_new);
            f_prev = self.extremes_forces(&dense, true, RIGHT, t_old, f_prev, t_new);
            self.step_history(t_old, t_new, dense, Phase::Contact, RIGHT);
            g_old = g_new;
            let y = *ode.y();
            let done = t_new >= self.opts.t_end
                || (may_stop && t_new >= excitation_end && self.settled(y[0], y[1]));
            if done {
                self.stats.add(ode.take_stats());
                let (w, d) = carried(y.as_slice(), 2);
                return Ok(Next::Done {
                    t: t_new,
                    phase: Phase::Contact,
                    s: RIGHT,
                    state: [0.0, y[0], 0.0, y[1]],
                    w,
                    d,
                });
            }
        }
    }

    /// Rocking about `s` from `t0` at `x0` = [θ, u, θ', u']: to the impact (s θ / (t − t0)^n
    /// falling through zero, regularised so that it cannot fire at t0), the overturning
    /// (s θ = θ_over), or the end of the run.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn rocking_rk(
        &mut self,
        t0: f64,
        s: f64,
        x0: [f64; 4],
        n: i32,
        w: f64,
        d: f64,
    ) -> Result<Next, SimError> {
        let (p, motion) = (self.p, self.motion);
        let over = self.opts.overturn_angle;
        let mut rhs = |t: f64, y: &Y<NR>| -> Y<NR> {
            let ug = motion.accel(t);
            let x = [y[0], y[1], y[2], y[3]];
            let dx = V::rocking_rhs(&x, ug, s, &p);
            let mut out = Y::<NR>::zeros();
            out.fixed_rows_mut::<4>(0).copy_from_slice(&dx);
            if Self::ENERGY {
                let pw = V::power(&x, ug, s, &p);
                out[4] = pw[pwr::GROUND];
                out[5] = pw[pwr::DAMPING];
            }
            out
        };
        // The impact event s θ / (t − t0)^n, with its limit at t0 (equations.md §5, note 4).
        let start_limit = if n == 0 {
            s * x0[0]
        } else if n == 1 {
            s * x0[2]
        } else {
            s * V::rocking_rhs(&x0, motion.accel_right(t0), s, &p)[rr::THETA_DDOT] / 2.0
        };
        // An uplift exactly at f_s = 0 has θ'' = 0: keep the event armed (it fires at once if θ
        // turns back, which ends the zero-length rocking phase with an impact).
        let start_limit = start_limit.max(f64::MIN_POSITIVE);
        let mut g = |t: f64, y: &Y<NR>| -> G2 {
            let dt = t - t0;
            let impact = if dt > 0.0 {
                s * y[0] / dt.powi(n)
            } else {
                start_limit
            };
            G2::new(impact, s * y[0] - over)
        };
        let y0 = Y::<NR>::from_fn(|i, _| [x0[0], x0[1], x0[2], x0[3], w, d][i]);
        let mut ode = Integrator::new(self.ode_options, self.rocking_tol)?;
        ode.reset(t0, y0, &mut rhs)?;
        let mut g_old = g(t0, &y0);
        let dirs = [Direction::Falling, Direction::Rising];
        let phase = Phase::rocking(s);
        let mut f_prev = self.forces_start(false, s, t0, &x0);
        loop {
            let t_stop = self.t_stop(ode.t());
            let info = ode
                .step(&mut rhs, t_stop)
                .map_err(|e| self.explain_failure(e, ode.y().as_slice(), s))?;
            self.guard_steps(ode.stats(), ode.t())?;
            let (t_old, t_new) = (info.t_old, info.t_new);
            let g_new = g(t_new, ode.y());
            if let Some(ev) = locate(&mut ode, &mut g, &dirs, &g_old, &g_new) {
                let dense = |t| rocking_state(ode.dense(t).as_slice());
                self.extremes_rocking(&dense, t_old, ev.t);
                self.extremes_forces(&dense, false, s, t_old, f_prev, ev.t);
                self.step_history(t_old, ev.t, dense, phase, s);
                self.stats.add(ode.take_stats());
                let y = ev.y;
                let (w, d) = carried(y.as_slice(), 4);
                return self.rocking_event(ev.index, ev.t, s, rocking_state(y.as_slice()), w, d);
            }
            let dense = |t| rocking_state(ode.dense(t).as_slice());
            self.extremes_rocking(&dense, t_old, t_new);
            f_prev = self.extremes_forces(&dense, false, s, t_old, f_prev, t_new);
            self.step_history(t_old, t_new, dense, phase, s);
            g_old = g_new;
            if t_new >= self.opts.t_end {
                let y = *ode.y();
                self.stats.add(ode.take_stats());
                let (w, d) = carried(y.as_slice(), 4);
                return Ok(Next::Done {
                    t: t_new,
                    phase,
                    s,
                    state: [y[0], y[1], y[2], y[3]],
                    w,
                    d,
                });
            }
        }
    }
}

fn contact_state<const N: usize>(y: &Y<N>) -> [f64; 4] {
    [0.0, y[0], 0.0, y[1]]
}
