//! A phase on compliant ground by the Taylor method: the free base's series from the generated
//! kernels of `Mode::Orders` (M(q) and F + Q_ground one order at a time, solved at run time by
//! [`crate::spd::second_order_series`]), the events as roots of each step's polynomials (θ's,
//! and the corners' depths from the generated depth series), so none inside a step is missed.
//! The bookkeeping of a step, the events' meaning and their order are those of the Runge–Kutta
//! phase ([`GroundSim::phase`]).

use rocking_ode::taylor::{Taylor, TaylorEvents, TaylorOptions, TaylorSystem};

use crate::taylor::{excitation_series, TaylorVariant};

use super::*;

/// The state on the ground as the Taylor integrator sees it: `[y, W, D, E_ground]`, each
/// divided by its natural scale (the Runge–Kutta path's absolute tolerances over `tol`), so
/// that one tolerance serves all.
struct GroundSeries<'a, V: TaylorVariant, M: ?Sized, const N: usize> {
    k: Kin<V>,
    motion: &'a M,
    s: f64,
    c: Contact,
    over: f64,
    scale: [f64; N],
    /// The phase's start and, when the event that started it is not strictly past its surface,
    /// that event function and the least value on this phase's side it starts at (a return
    /// across the surface in the first step is then a crossing, as on the Runge–Kutta path).
    pin: (f64, Option<(usize, f64)>),
}

impl<V: TaylorVariant, M: GroundMotion + ?Sized, const N: usize> TaylorSystem<N>
    for GroundSeries<'_, V, M, N>
{
    fn coefficients<const K: usize>(&mut self, t0: f64, x: &mut [[f64; K]; N]) {
        let ny = Free::<V>::INTEGRALS;
        let (ug, _) = excitation_series::<M, K>(self.motion, t0);
        let first: [f64; N] = std::array::from_fn(|i| x[i][0]);
        for (xi, sc) in x[..ny].iter_mut().zip(&self.scale) {
            xi[0] *= sc;
        }
        let mut dissipation = [0.0; K];
        let (s, p) = (self.s, self.k.p);
        self.k
            .ground
            .state_orders::<K, _>(self.c.left, self.c.right, |ground| {
                let mut forces = |k: usize, base: &[[f64; K]; 4]| {
                    let g = ground(k, base);
                    dissipation[k] = g[go::DISSIPATION];
                    [g[go::Q_THETA], g[go::Q_V]]
                };
                V::free_series(&mut x[..ny], &ug, s, &p, &mut forces);
            });
        let pw = V::free_power_series(&x[..ny], &ug, s, &p);
        for i in 0..ny {
            let inv = 1.0 / self.scale[i];
            for c in &mut x[i][1..] {
                *c *= inv;
            }
            x[i][0] = first[i];
        }
        let rates = [&pw[POWER_GROUND], &pw[POWER_DAMPING], &dissipation];
        for (j, rate) in rates.into_iter().enumerate() {
            let row = ny + j;
            for k in 0..K - 1 {
                x[row][k + 1] = rate[k] / ((k + 1) as f64 * self.scale[row]);
            }
        }
    }
}

/// `[s θ, d(−B), d(B), s θ − θ_over]`, the Runge–Kutta phase's event functions, along a step.
impl<V: TaylorVariant, M: GroundMotion + ?Sized, const N: usize> TaylorEvents<N, 4>
    for GroundSeries<'_, V, M, N>
{
    fn event_coefficients<const K: usize>(&mut self, t0: f64, x: &[[f64; K]; N]) -> [[f64; K]; 4] {
        let unscaled = |row: usize| x[row].map(|c| c * self.scale[row]);
        let theta = unscaled(Free::<V>::THETA).map(|c| self.s * c);
        let depths = if self.k.bilateral {
            [std::array::from_fn(|k| if k == 0 { 1.0 } else { 0.0 }); 2]
        } else {
            let base = Free::<V>::BASE.map(unscaled);
            self.k.ground.depth_series::<K>(&base)
        };
        let mut over = theta;
        over[0] -= self.over;
        let mut g = [theta, depths[0], depths[1], over];
        if let (start, Some((i, value))) = self.pin {
            if t0 == start {
                g[i][0] = value;
            }
        }
        g
    }
}

impl<V: TaylorVariant, M: GroundMotion + ?Sized, const N: usize> GroundSim<'_, V, M, N> {
    /// [`phase`](Self::phase) by the Taylor method.
    pub(super) fn phase_taylor(
        &mut self,
        t0: f64,
        y0: V::Y,
        s: f64,
        c: Contact,
        carried: [f64; 3],
        fired: Option<usize>,
    ) -> Result<PhaseEnd<V>, SimError> {
        let integrals = Free::<V>::INTEGRALS;
        let theta = Free::<V>::THETA;
        let tol = self.opts.accuracy.tol;
        let scale: [f64; N] = std::array::from_fn(|i| {
            let a = self.tol.atol[i] / tol;
            if a.is_finite() {
                a
            } else {
                1.0
            }
        });
        let z0: [f64; N] = std::array::from_fn(|i| match Free::<V>::part(i) {
            FreePart::Integral(k) => carried[k] / scale[i],
            _ => y0.values()[i] / scale[i],
        });
        let unscale =
            |z: [f64; N]| -> SVector<f64, N> { SVector::<f64, N>::from_fn(|i, _| z[i] * scale[i]) };
        let dirs = self.directions(c);
        let g_at = |k: &Kin<V>, y: &V::Y| -> [f64; 4] {
            let [l, r] = k.depths(y);
            let st = s * y.values()[theta];
            [st, l, r, st - self.opts.overturn_angle]
        };
        // As on the Runge–Kutta path: the event that started the phase starts on this phase's
        // side, at the least margin when `past` could not move it there.
        let g0 = g_at(&self.k, &y0);
        let pin = fired.and_then(|i| start_margin(dirs[i], g0[i]).map(|m| (i, m)));
        let mut sys = GroundSeries::<V, M, N> {
            k: self.k,
            motion: self.motion,
            s,
            c,
            over: self.opts.overturn_angle,
            scale,
            pin: (t0, pin),
        };
        let opts = TaylorOptions {
            max_steps: self.opts.max_steps,
            controlled: std::array::from_fn(|i| i < integrals),
            ..TaylorOptions::new(tol)
        };
        let mut ode = Taylor::<N>::new(opts)?;
        ode.reset(t0, z0)?;
        let mut first_on_zero = fired != Some(0) && y0.values()[theta] == 0.0;
        let (t_old, t, z, event) = loop {
            let t_stop = self
                .motion
                .next_kink(ode.t())
                .map_or(self.opts.t_end, |k| k.min(self.opts.t_end));
            ode.step(&mut sys, t_stop)?;
            let (t_old, t_new) = (ode.t_old(), ode.t());
            self.guard_steps(ode.stats().steps, t_new)?;
            if first_on_zero && s * ode.y()[theta] < 0.0 {
                self.rec.stats.add(ode.take_stats());
                return Ok(PhaseEnd::other_corner_leads(t0, y0, carried));
            }
            first_on_zero = false;
            if let Some(ev) = ode.locate(&mut sys, &dirs) {
                // Past the surface by more than its rounding, as `past` does on the Runge–Kutta
                // path; here the step's polynomial is the state at every t of the step.
                let y_at = |t: f64| {
                    let z = unscale(ode.dense(t));
                    V::Y::from_fn(|i| z[i])
                };
                let noise = self.event_noise(ev.y[Free::<V>::V] * scale[Free::<V>::V], ev.index);
                let g = |t: f64| g_at(&self.k, &y_at(t))[ev.index];
                let te = past_on_polynomial(g, ev.t, t_new, dirs[ev.index], noise);
                ode.truncate_at(te);
                break (t_old, te, unscale(*ode.y()), Some(ev.index));
            }
            let z = unscale(*ode.y());
            if t_new >= self.opts.t_end {
                break (t_old, t_new, z, None);
            }
            let y = V::Y::from_fn(|i| z[i]);
            self.record_step(|t| unscale(ode.dense(t)), t_old, t_new, &y, s, c);
        };
        let y = V::Y::from_fn(|i| z[i]);
        self.record_step(|t| unscale(ode.dense(t)), t_old, t, &y, s, c);
        self.rec.stats.add(ode.take_stats());
        Ok(PhaseEnd {
            t,
            y,
            carried: std::array::from_fn(|k| z[integrals + k]),
            event,
        })
    }
}
