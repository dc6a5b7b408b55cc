//! The Taylor integrator: convergence against closed forms, observed order, dense output, and
//! a generated rocking kernel against DOP853.

use nalgebra::{SVector, Vector1, Vector4};
use rocking_kernels::series;
use rocking_ode::events::{locate, Direction};
use rocking_ode::taylor::{
    order_from_tol, Taylor, TaylorEvents, TaylorOptions, TaylorSystem, CAP_MARGIN, FIXED_COST,
    ORDERS,
};
use rocking_ode::{Integrator, Method, Options, Tolerances};

/// x'' = −x.
struct Oscillator;
impl TaylorSystem<2> for Oscillator {
    fn coefficients<const N: usize>(&mut self, _t0: f64, x: &mut [[f64; N]; 2]) {
        for k in 0..N - 1 {
            let kf = (k + 1) as f64;
            x[0][k + 1] = x[1][k] / kf;
            x[1][k + 1] = -x[0][k] / kf;
        }
    }
}

/// y' = −λ y.
struct Decay(f64);
impl TaylorSystem<1> for Decay {
    fn coefficients<const N: usize>(&mut self, _t0: f64, x: &mut [[f64; N]; 1]) {
        for k in 0..N - 1 {
            x[0][k + 1] = -self.0 * x[0][k] / (k + 1) as f64;
        }
    }
}

/// x'' + 2ζω x' + ω² x = A sin(Ω t): the forcing's series at t0 in closed form,
/// sin(Ω t0 + Ω τ) = Σ Ω^k/k! sin(Ω t0 + kπ/2) τ^k.
#[derive(Clone, Copy)]
struct Driven {
    zeta: f64,
    omega: f64,
    amp: f64,
    big_omega: f64,
}
impl TaylorSystem<2> for Driven {
    fn coefficients<const N: usize>(&mut self, t0: f64, x: &mut [[f64; N]; 2]) {
        let (s, c) = (self.big_omega * t0).sin_cos();
        let mut f = [0.0; N];
        let mut fact = 1.0;
        for (k, fk) in f.iter_mut().enumerate() {
            if k > 0 {
                fact *= self.big_omega / k as f64;
            }
            let phase = [s, c, -s, -c][k % 4];
            *fk = self.amp * fact * phase;
        }
        let (a, b) = (2.0 * self.zeta * self.omega, self.omega * self.omega);
        for k in 0..N - 1 {
            let kf = (k + 1) as f64;
            x[0][k + 1] = x[1][k] / kf;
            x[1][k + 1] = (f[k] - a * x[1][k] - b * x[0][k]) / kf;
        }
    }
}

impl Driven {
    fn exact(&self, t: f64, x0: f64, v0: f64) -> [f64; 2] {
        let (z, w, a, om) = (self.zeta, self.omega, self.amp, self.big_omega);
        // Particular solution C sin + D cos.
        let (p, q) = (w * w - om * om, 2.0 * z * w * om);
        let det = p * p + q * q;
        let (cs, dc) = (a * p / det, -a * q / det);
        let wd = w * (1.0 - z * z).sqrt();
        let ah = x0 - dc;
        let bh = (v0 + z * w * ah - om * cs) / wd;
        let e = (-z * w * t).exp();
        let (sd, cd) = (wd * t).sin_cos();
        let (so, co) = (om * t).sin_cos();
        let x = e * (ah * cd + bh * sd) + cs * so + dc * co;
        let v = e * (-z * w * (ah * cd + bh * sd) + wd * (-ah * sd + bh * cd))
            + om * (cs * co - dc * so);
        [x, v]
    }
}

/// θ'' = −sin θ (sin by the kernels' series recurrence).
struct Pendulum;
impl TaylorSystem<2> for Pendulum {
    fn coefficients<const N: usize>(&mut self, _t0: f64, x: &mut [[f64; N]; 2]) {
        let (mut d, mut s, mut c) = ([0.0; N], [0.0; N], [0.0; N]);
        for k in 0..N - 1 {
            series::sin_cos(&x[0], &mut d, &mut s, &mut c, k);
            let kf = (k + 1) as f64;
            x[0][k + 1] = x[1][k] / kf;
            x[1][k + 1] = -s[k] / kf;
        }
    }
}

/// Adaptive run to `t1`; returns (max error over the step ends, steps, order).
fn run<S: TaylorSystem<D>, const D: usize>(
    sys: &mut S,
    tol: f64,
    y0: [f64; D],
    t1: f64,
    err: impl Fn(f64, &[f64; D]) -> f64,
) -> (f64, u64, usize) {
    let mut ode = Taylor::<D>::new(TaylorOptions::new(tol)).unwrap();
    ode.reset(0.0, y0).unwrap();
    let mut e: f64 = 0.0;
    loop {
        let info = ode.step(sys, t1).unwrap();
        e = e.max(err(ode.t(), ode.y()));
        if info.reached {
            break;
        }
    }
    assert_eq!(ode.t(), t1);
    assert_eq!(ode.stats().rejected, 0);
    (e, ode.stats().steps, ode.order())
}

const TOLS: [f64; 5] = [1e-6, 1e-9, 1e-12, 1e-15, f64::EPSILON];

/// Errors at every tolerance: below `factor` × tol (plus a rounding floor) and falling.
fn check_sweep(name: &str, res: &[(f64, u64, usize)], factor: f64, floor: f64) {
    let line: Vec<_> = TOLS
        .iter()
        .zip(res)
        .map(|(t, (e, n, p))| format!("{t:.0e}:{e:.2e}(p{p},{n} steps)"))
        .collect();
    println!("{name}: {}", line.join(" "));
    for (t, (e, _, _)) in TOLS.iter().zip(res) {
        assert!(*e <= factor * t + floor, "{name}: error {e:e} at tol {t:e}");
    }
    assert!(res[2].0 < 1e-3 * res[0].0, "{name}: {res:?}");
}

#[test]
fn harmonic_oscillator_against_cos() {
    let res: Vec<_> = TOLS
        .iter()
        .map(|&tol| {
            run(&mut Oscillator, tol, [1.0, 0.0], 20.0, |t, y| {
                (y[0] - t.cos()).abs().max((y[1] + t.sin()).abs())
            })
        })
        .collect();
    check_sweep("oscillator on [0, 20]", &res, 10.0, 1e-14);
}

#[test]
fn exponential_decay() {
    let lam = 3.0;
    let res: Vec<_> = TOLS
        .iter()
        .map(|&tol| {
            run(&mut Decay(lam), tol, [2.0], 5.0, |t, y| {
                (y[0] - 2.0 * (-lam * t).exp()).abs()
            })
        })
        .collect();
    check_sweep("y' = -3y, y0 = 2 on [0, 5]", &res, 10.0, 1e-15);
}

#[test]
fn driven_damped_oscillator_against_closed_form() {
    let d = Driven {
        zeta: 0.05,
        omega: 5.0,
        amp: 3.0,
        big_omega: 4.0,
    };
    let (x0, v0) = (0.1, -0.2);
    let res: Vec<_> = TOLS
        .iter()
        .map(|&tol| {
            let mut sys = d;
            run(&mut sys, tol, [x0, v0], 10.0, |t, y| {
                let e = d.exact(t, x0, v0);
                (y[0] - e[0]).abs().max((y[1] - e[1]).abs() / d.omega)
            })
        })
        .collect();
    check_sweep("driven oscillator on [0, 10]", &res, 10.0, 1e-14);
}

#[test]
fn pendulum_conserves_energy() {
    let y0: [f64; 2] = [2.5, 0.0]; // a large swing
    let e0 = -y0[0].cos();
    let res: Vec<_> = TOLS
        .iter()
        .map(|&tol| {
            run(&mut Pendulum, tol, y0, 50.0, |_t, y| {
                (0.5 * y[1] * y[1] - y[0].cos() - e0).abs()
            })
        })
        .collect();
    check_sweep("pendulum energy drift on [0, 50]", &res, 10.0, 1e-14);
}

#[test]
fn order_minimises_the_cost_per_unit_time() {
    // The order of ORDERS minimising (FIXED_COST + (p+1)²) / tol^(1/p), checked against every
    // other order by brute force and pinned at the study's tolerances (module docs).
    for (tol, p) in [
        (1e-3, 8),
        (1e-6, 12),
        (1e-9, 16),
        (1e-12, 20),
        (f64::EPSILON, 20),
    ] {
        assert_eq!(order_from_tol(tol), p, "tol {tol:e}");
        let cost = |q: usize| (FIXED_COST + ((q + 1) * (q + 1)) as f64) / tol.powf(1.0 / q as f64);
        for q in ORDERS {
            assert!(
                cost(q) >= cost(p),
                "tol {tol:e}: order {q} cheaper than {p}"
            );
        }
    }
    // Higher orders for tighter tolerances, never lower.
    let orders: Vec<usize> = (1..=16).map(|e| order_from_tol(10f64.powi(-e))).collect();
    assert!(orders.windows(2).all(|w| w[0] <= w[1]), "{orders:?}");
    let run = |tol: f64| Taylor::<2>::new(TaylorOptions::new(tol)).unwrap().order();
    assert_eq!(run(1e-12), 20);
    assert_eq!(run(1e-9), 16);
    assert!(Taylor::<2, 17>::new(TaylorOptions::new(1e-12)).is_err()); // needs 21 coefficients
}

fn slope(data: &[(f64, f64)]) -> f64 {
    let n = data.len() as f64;
    let xs: Vec<f64> = data.iter().map(|d| d.0.ln()).collect();
    let ys: Vec<f64> = data.iter().map(|d| d.1.ln()).collect();
    let mx = xs.iter().sum::<f64>() / n;
    let my = ys.iter().sum::<f64>() / n;
    let sxy: f64 = xs.iter().zip(&ys).map(|(x, y)| (x - mx) * (y - my)).sum();
    let sxx: f64 = xs.iter().map(|x| (x - mx) * (x - mx)).sum();
    sxy / sxx
}

#[test]
fn observed_order_of_fixed_order_fixed_step_runs() {
    // Global error at t = 10 after n equal steps (oscillator) and the largest energy error over
    // the run (pendulum), both slope p, and the error of one step (slope p + 1), orders 3 to 8.
    for (p, ns) in [
        (3usize, [40u64, 56, 80, 113, 160]),
        (4, [30, 42, 60, 85, 120]),
        (6, [24, 30, 36, 44, 52]),
        (8, [16, 19, 22, 26, 30]),
    ] {
        let mut opts = TaylorOptions::<2>::new(1e-3);
        opts.order = Some(p);
        let t1: f64 = 10.0;
        let mut glob = Vec::new();
        let mut glob_pend = Vec::new();
        let mut local = Vec::new();
        let y0: [f64; 2] = [1.0, 0.0];
        for &n in &ns {
            let h = t1 / n as f64;
            let mut ode = Taylor::<2>::new(opts).unwrap();
            assert_eq!(ode.order(), p);
            ode.reset(0.0, [1.0, 0.0]).unwrap();
            while !ode.step_fixed(&mut Oscillator, h, t1).unwrap().reached {}
            assert_eq!(ode.stats().steps, n);
            let e = (ode.y()[0] - t1.cos())
                .abs()
                .max((ode.y()[1] + t1.sin()).abs());
            glob.push((h, e));
            ode.reset(0.0, y0).unwrap();
            let energy = |y: &[f64; 2]| 0.5 * y[1] * y[1] - y[0].cos();
            let mut e: f64 = 0.0;
            loop {
                let done = ode.step_fixed(&mut Pendulum, h, t1).unwrap().reached;
                e = e.max((energy(ode.y()) - energy(&y0)).abs());
                if done {
                    break;
                }
            }
            glob_pend.push((h, e));
            // One step of 4h from the start.
            ode.reset(0.0, [1.0, 0.0]).unwrap();
            ode.step_fixed(&mut Oscillator, 4.0 * h, t1).unwrap();
            let hh = ode.last_step_size();
            let e = (ode.y()[0] - hh.cos())
                .abs()
                .max((ode.y()[1] + hh.sin()).abs());
            local.push((hh, e));
        }
        let (s, sp, sl) = (slope(&glob), slope(&glob_pend), slope(&local));
        let fmt = |d: &[(f64, f64)]| {
            d.iter()
                .map(|(h, e)| format!("{h:.3}:{e:.2e}"))
                .collect::<Vec<_>>()
                .join(" ")
        };
        println!(
            "order {p}: oscillator global [{}] slope {s:.3}; pendulum max energy error [{}] slope {sp:.3}; \
             one step [{}] slope {sl:.3}",
            fmt(&glob),
            fmt(&glob_pend),
            fmt(&local)
        );
        let pf = p as f64;
        assert!((s - pf).abs() < 0.3, "order {p}: oscillator slope {s}");
        assert!((sp - pf).abs() < 0.4, "order {p}: pendulum slope {sp}");
        assert!((sl - (pf + 1.0)).abs() < 0.3, "order {p}: local slope {sl}");
    }
}

#[test]
fn dense_output_is_the_step_polynomial() {
    let mut ode = Taylor::<2>::new(TaylorOptions::new(1e-10)).unwrap();
    ode.reset(0.0, [2.0, 0.3]).unwrap();
    let mut y_prev = *ode.y();
    for _ in 0..30 {
        let info = ode.step(&mut Pendulum, 100.0).unwrap();
        let (h, p) = (ode.last_step_size(), ode.order());
        let c = ode.coefficients();
        for i in 0..2 {
            // The end state is the polynomial at h to rounding (evaluated in two halves, not
            // by Horner's rule): a few ulp of its terms' sum; the start its constant term.
            let terms: f64 = (0..=p).map(|k| (c[i][k] * h.powi(k as i32)).abs()).sum();
            let horner = rocking_ode::poly::horner(&c[i][..=p], h);
            assert!(
                (horner - ode.y()[i]).abs() <= 4.0 * f64::EPSILON * terms,
                "{horner:e} vs {:e}",
                ode.y()[i]
            );
            assert_eq!(c[i][0], y_prev[i]);
        }
        assert_eq!(ode.dense(info.t_new), *ode.y());
        assert_eq!(ode.dense(info.t_old), y_prev);
        // Inside the step: against a tight reference from the same start.
        let tm = info.t_old + 0.37 * h;
        let mut r = Taylor::<2>::new(TaylorOptions::new(1e-16)).unwrap();
        r.reset(info.t_old, y_prev).unwrap();
        while !r.step(&mut Pendulum, tm).unwrap().reached {}
        let d = ode.dense(tm);
        assert!((d[0] - r.y()[0]).abs() < 1e-10 && (d[1] - r.y()[1]).abs() < 1e-10);
        // The derivative of the polynomial is the right-hand side to the same accuracy.
        let dd = ode.dense_derivative(tm);
        assert!((dd[0] - d[1]).abs() < 1e-9 && (dd[1] + d[0].sin()).abs() < 1e-9);
        y_prev = *ode.y();
    }
}

#[test]
fn steps_stop_at_t_stop() {
    let mut ode = Taylor::<2>::new(TaylorOptions::new(1e-12)).unwrap();
    ode.reset(0.0, [1.0, 0.0]).unwrap();
    for kink in [0.1, 0.35, 1.0, 1.0 + 1e-9, 4.0] {
        loop {
            let info = ode.step(&mut Oscillator, kink).unwrap();
            assert!(info.t_new <= kink);
            if info.reached {
                assert_eq!(ode.t(), kink);
                break;
            }
        }
    }
    assert!((ode.y()[0] - 4.0f64.cos()).abs() < 1e-12);
}

/// [`Oscillator`] with the order choice refused, as a system with an input its state does not
/// reflect answers.
struct Refusing;
impl TaylorSystem<2> for Refusing {
    fn coefficients<const N: usize>(&mut self, t0: f64, x: &mut [[f64; N]; 2]) {
        Oscillator.coefficients(t0, x);
    }
    fn may_lower_order(&mut self, _t0: f64) -> bool {
        false
    }
}

/// Runs to t = 10 with a stop every `dt` (a record's samples): the largest error against cos
/// over the step ends, the highest order of a step after the first, and the steps.
fn stopped_run<S: TaylorSystem<2>>(
    sys: &mut S,
    opts: TaylorOptions<2>,
    dt: f64,
) -> (f64, usize, u64) {
    let mut ode = Taylor::<2>::new(opts).unwrap();
    ode.reset(0.0, [1.0, 0.0]).unwrap();
    let (mut e, mut p, mut n) = (0.0f64, 0, 0usize);
    while ode.t() < 10.0 {
        let stop = ((n + 1) as f64 * dt).min(10.0);
        if ode.step(sys, stop).unwrap().reached {
            n += 1;
        }
        if ode.stats().steps > 1 {
            p = p.max(ode.order());
        }
        let t = ode.t();
        e = e.max(
            (ode.y()[0] - t.cos())
                .abs()
                .max((ode.y()[1] + t.sin()).abs()),
        );
    }
    (e, p, ode.stats().steps)
}

#[test]
fn steps_capped_by_t_stop_run_a_lower_order_at_the_same_accuracy() {
    // Stops every 0.02 on a unit-frequency oscillator: the tolerance's order 20 would step
    // ~0.6 at 1e-12; a step to the next stop needs order 6 or so (module docs, CAP_MARGIN).
    for tol in [1e-9, 1e-12] {
        let opts = TaylorOptions::new(tol);
        let lowered = stopped_run(&mut Oscillator, opts, 0.02);
        let highest = stopped_run(&mut Refusing, opts, 0.02);
        let fixed = stopped_run(
            &mut Oscillator,
            TaylorOptions {
                order: Some(order_from_tol(tol)),
                ..opts
            },
            0.02,
        );
        println!("tol {tol:e}: lowered (error, order, steps) {lowered:?}, refused {highest:?}, fixed {fixed:?}");
        assert_eq!(lowered.2, 500, "one step per stop");
        assert!(lowered.1 <= 8, "order {} for steps of 0.02", lowered.1);
        assert_eq!(
            highest.1,
            order_from_tol(tol),
            "the system refused a lower order"
        );
        assert_eq!(fixed.1, order_from_tol(tol), "a fixed order is kept");
        // The accuracy is the rule's, at any order: within 10 tol over 500 steps.
        assert!(
            lowered.0 <= 10.0 * tol,
            "error {:e} at tol {tol:e}",
            lowered.0
        );
    }
    // A step capped by h_max (an input's resolution) keeps the highest order.
    let opts = TaylorOptions {
        h_max: 0.02,
        ..TaylorOptions::new(1e-12)
    };
    assert_eq!(stopped_run(&mut Oscillator, opts, 1.0).1, 20);
}

/// The order the module docs give a step capped at `cap` after a step of `prev`: the lowest of
/// ORDERS below the highest whose step by the rule, predicted from the last step's radius of
/// convergence, reaches `cap` with CAP_MARGIN; else the highest. Computed here from the public
/// coefficients with the logarithms the rule is written in.
fn documented_order(prev: &Taylor<2>, tol: f64, cap: f64) -> usize {
    let (c, p) = (prev.coefficients(), prev.order());
    let norm = |k: usize| c.iter().map(|ci| ci[k].abs()).fold(0.0, f64::max);
    let a = norm(0).max(1.0);
    let ln_rho = ((a / norm(p - 1)).ln() / (p - 1) as f64).min((a / norm(p)).ln() / p as f64);
    let ln_cap = (cap * CAP_MARGIN).ln();
    ORDERS
        .into_iter()
        .take_while(|&q| q < prev.max_order())
        .find(|&q| {
            let q = q as f64;
            ln_rho + (tol.ln() / q - 0.7 / (q - 1.0)) >= ln_cap
        })
        .unwrap_or(prev.max_order())
}

#[test]
fn a_capped_step_runs_the_documented_order_at_every_cap() {
    // Caps from far below the highest order's step to far beyond it, densely, and on both sides
    // of each order's threshold to the last bits: the integrator's shortcuts (no logarithm where
    // the cap is beyond the highest order's step) must choose what the rule says.
    for tol in [1e-3, 1e-7, 1e-11] {
        let mut ode = Taylor::<2>::new(TaylorOptions::new(tol)).unwrap();
        ode.reset(0.0, [1.0, 0.3]).unwrap();
        ode.step(&mut Oscillator, 100.0).unwrap();
        assert_eq!(ode.order(), ode.max_order());
        let h = ode.last_step_size();
        let mut caps: Vec<f64> = (0..400).map(|j| h * 1e-3 * 1.02f64.powi(j)).collect();
        let ln_fac = |q: usize| tol.ln() / q as f64 - 0.7 / (q as f64 - 1.0);
        for q in ORDERS.into_iter().filter(|&q| q <= ode.max_order()) {
            // Where the cap meets order q's predicted step (the highest order's is h).
            let edge = h * (ln_fac(q) - ln_fac(ode.max_order())).exp() / CAP_MARGIN;
            for ulps in -3i64..=3 {
                caps.push(f64::from_bits((edge.to_bits() as i64 + ulps) as u64));
            }
        }
        let mut lowered = 0;
        for cap in caps {
            let mut next = ode;
            let t_stop = next.t() + cap;
            next.step(&mut Oscillator, t_stop).unwrap();
            let want = documented_order(&ode, tol, t_stop - ode.t());
            assert_eq!(next.order(), want, "tol {tol:e}, cap {cap:e} (h {h:e})");
            lowered += usize::from(want < ode.max_order());
        }
        assert!(
            lowered > 50,
            "tol {tol:e}: only {lowered} caps ran a lower order"
        );
    }
}

// --- a generated kernel: free rocking of a rigid block, impact against DOP853 ---------------

use rocking_kernels::kernels::rigid as kr;
use rocking_kernels::taylor::rigid as tr;

struct Rigid {
    p: kr::Params,
    ug: f64,
    s: f64,
}

impl TaylorSystem<4> for Rigid {
    fn coefficients<const N: usize>(&mut self, _t0: f64, x: &mut [[f64; N]; 4]) {
        let mut ug = [0.0; N];
        ug[0] = self.ug; // constant ground acceleration: one nonzero coefficient
        tr::rocking_rhs::<N>(x, &ug, self.s, &self.p);
    }
}

/// Impact: θ falls through 0.
struct Theta;
impl TaylorEvents<4, 1> for Theta {
    fn event_coefficients<const N: usize>(&mut self, _t0: f64, x: &[[f64; N]; 4]) -> [[f64; N]; 1] {
        [x[0]]
    }
}

fn rigid_params() -> kr::Params {
    let phys = rocking_kernels::Physical::dimensionless(0.2, 11.9, 0.0, 0.0, 1.0, 0.0);
    kr::params(&phys)
}

fn impact_taylor(tol: f64, theta0: f64, ug: f64) -> (f64, [f64; 4], u64) {
    let mut sys = Rigid {
        p: rigid_params(),
        ug,
        s: 1.0,
    };
    let mut ode = Taylor::<4>::new(TaylorOptions::new(tol)).unwrap();
    ode.reset(0.0, [theta0, 0.0, 0.0, 0.0]).unwrap();
    loop {
        ode.step(&mut sys, 100.0).unwrap();
        if let Some(ev) = ode.locate(&mut Theta, &[Direction::Falling]) {
            return (ev.t, ev.y, ode.stats().steps);
        }
    }
}

fn impact_dop853(rtol: f64, theta0: f64, ug: f64) -> (f64, SVector<f64, 4>, u64) {
    let p = rigid_params();
    let mut f = |_t: f64, y: &SVector<f64, 4>| {
        Vector4::from(kr::rocking_rhs(&[y[0], y[1], y[2], y[3]], ug, 1.0, &p))
    };
    let mut g = |_t: f64, y: &SVector<f64, 4>| Vector1::new(y[0]);
    let mut ode = Integrator::new(
        Options::new(Method::Dop853),
        Tolerances::uniform(rtol, rtol),
    )
    .unwrap();
    ode.reset(0.0, Vector4::new(theta0, 0.0, 0.0, 0.0), &mut f)
        .unwrap();
    let mut g_old = g(ode.t(), ode.y());
    loop {
        ode.step(&mut f, 100.0).unwrap();
        let g_new = g(ode.t(), ode.y());
        if let Some(ev) = locate(&mut ode, &mut g, &[Direction::Falling], &g_old, &g_new) {
            return (ev.t, ev.y, ode.stats().steps);
        }
        g_old = g_new;
    }
}

#[test]
fn rigid_block_free_rocking_impact_matches_dop853() {
    // α = 0.2: released from rest at θ0 = α/2 with a small constant ground acceleration.
    for (theta0, ug) in [(0.1, 0.0), (0.1, 0.05), (0.15, -0.02)] {
        let (t_d, y_d, n_d) = impact_dop853(1e-12, theta0, ug);
        let (t_ref, _, _) = impact_dop853(1e-14, theta0, ug);
        for tol in [1e-12, 1e-15] {
            let (t_t, y_t, n_t) = impact_taylor(tol, theta0, ug);
            println!(
                "rigid block θ0 {theta0} ug {ug}: impact Taylor(tol {tol:.0e}, {n_t} steps) \
                 {t_t:.15}, DOP853(1e-12, {n_d} steps) {t_d:.15}: difference {:.2e}, vs \
                 DOP853(1e-14) {:.2e}; θ' at impact differs by {:.2e}",
                t_t - t_d,
                t_t - t_ref,
                y_t[2] - y_d[2]
            );
            assert!(
                (t_t - t_d).abs() <= 1e-10,
                "impact times differ by {:e}",
                t_t - t_d
            );
            assert!((y_t[2] - y_d[2]).abs() <= 1e-10);
            assert!(y_t[0].abs() <= 1e-15);
        }
    }
}

/// g = x for the oscillator.
struct X;
impl TaylorEvents<2, 1> for X {
    fn event_coefficients<const N: usize>(&mut self, _t0: f64, x: &[[f64; N]; 2]) -> [[f64; N]; 1] {
        [x[0]]
    }
}

#[test]
fn oscillator_zero_crossings_by_polynomial_roots() {
    // x = sin t from x = 0 exactly (a restart on the event surface: no event at t = 0), with
    // restarts at every event as a hybrid driver does; h_max = 4 lets a step hold two crossings.
    for dir in [Direction::Either, Direction::Falling, Direction::Rising] {
        let mut opts = TaylorOptions::<2>::new(1e-15);
        opts.h_max = 4.0;
        let mut ode = Taylor::<2>::new(opts).unwrap();
        ode.reset(0.0, [0.0, 1.0]).unwrap();
        let mut times = Vec::new();
        loop {
            let info = ode.step(&mut Oscillator, 20.0).unwrap();
            if let Some(ev) = ode.locate(&mut X, &[dir]) {
                assert!(ev.t > info.t_old && ev.t <= info.t_new);
                assert!(
                    ev.root.tau - ev.root.tau_before <= 2.0 * f64::EPSILON * ev.root.tau,
                    "{:?} {}",
                    ev.root,
                    ode.last_step_size()
                );
                times.push(ev.t);
                ode.truncate_at(ev.t);
                // The driver's map puts the state on the surface exactly (as an impact sets
                // θ = 0): a zero at the step start never triggers.
                let y = [0.0, ode.y()[1]];
                ode.reset(ev.t, y).unwrap();
                continue;
            }
            if info.reached {
                break;
            }
        }
        let pi = std::f64::consts::PI;
        let want: Vec<f64> = (1..=6)
            .map(|k| k as f64 * pi)
            .filter(|t| match dir {
                Direction::Either => true,
                Direction::Falling => (t / pi).round() as i64 % 2 == 1,
                Direction::Rising => (t / pi).round() as i64 % 2 == 0,
            })
            .collect();
        assert_eq!(times.len(), want.len(), "{dir:?}: {times:?}");
        let dev = times
            .iter()
            .zip(&want)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max);
        println!("{dir:?}: zero crossings of sin t on [0, 20] within {dev:.2e}");
        assert!(dev <= 1e-13, "{dir:?}: {dev:e}");
        assert_eq!(ode.stats().events, want.len() as u64);
    }
}

/// The oscillator with a carried integral w' = x² (like the driver's work and damping integrals).
struct OscillatorWithIntegral(f64);
impl TaylorSystem<3> for OscillatorWithIntegral {
    fn coefficients<const N: usize>(&mut self, _t0: f64, x: &mut [[f64; N]; 3]) {
        for k in 0..N - 1 {
            let kf = (k + 1) as f64;
            x[0][k + 1] = x[1][k] / kf;
            x[1][k + 1] = -x[0][k] / kf;
            x[2][k + 1] = self.0 * series::sq(&x[0], k) / kf;
        }
    }
}

#[test]
fn uncontrolled_components_do_not_change_the_steps() {
    // A carried integral scaled by 1e6 is left out of the step rule: the steps are those of the
    // plain oscillator, bit for bit, and the integral is still accurate, though not to ε: its rate
    // cos² oscillates twice as fast as the controlled components, so its series' last terms are
    // about 2^p times theirs (measured: 1.2e-10 relative at ε = 1e-12, order 20).
    let tol = 1e-12;
    let mut a = Taylor::<2>::new(TaylorOptions::new(tol)).unwrap();
    let mut opts = TaylorOptions::<3>::new(tol);
    opts.controlled = [true, true, false];
    let mut b = Taylor::<3>::new(opts).unwrap();
    a.reset(0.0, [1.0, 0.0]).unwrap();
    b.reset(0.0, [1.0, 0.0, 0.0]).unwrap();
    let mut sys = OscillatorWithIntegral(1e6);
    loop {
        let ia = a.step(&mut Oscillator, 10.0).unwrap();
        let ib = b.step(&mut sys, 10.0).unwrap();
        assert_eq!(ia, ib);
        assert_eq!(a.y()[..], b.y()[..2]);
        if ia.reached {
            break;
        }
    }
    // ∫ cos² = t/2 + sin 2t / 4.
    let want = 1e6 * (5.0 + 20.0f64.sin() / 4.0);
    println!(
        "carried integral: relative error {:.2e}",
        (b.y()[2] - want) / want
    );
    assert!(((b.y()[2] - want) / want).abs() < 1e-9);
}

#[test]
fn locate_after_truncate_searches_the_remaining_step_only() {
    let mut opts = TaylorOptions::<2>::new(1e-15);
    opts.h_max = 4.0;
    let mut ode = Taylor::<2>::new(opts).unwrap();
    ode.reset(0.0, [0.0, 1.0]).unwrap();
    let mut first = None;
    while first.is_none() {
        ode.step(&mut Oscillator, 20.0).unwrap();
        first = ode.locate(&mut X, &[Direction::Either]);
    }
    let ev = first.unwrap();
    assert!((ev.t - std::f64::consts::PI).abs() < 1e-14);
    ode.truncate_at(ev.t - 0.5);
    assert!(ode.locate(&mut X, &[Direction::Either]).is_none());
}

// --- grazing uplift with the generated uplift series ----------------------------------------

/// A sine ground acceleration's series at t0 (closed form).
fn sine_series<const N: usize>(amp: f64, om: f64, t0: f64) -> [f64; N] {
    let (s, c) = (om * t0).sin_cos();
    let mut f = [0.0; N];
    let mut fact = amp;
    for (k, fk) in f.iter_mut().enumerate() {
        if k > 0 {
            fact *= om / k as f64;
        }
        *fk = fact * [s, c, -s, -c][k % 4];
    }
    f
}

/// A rigid block in full contact under ug = A sin(Ω t).
struct RigidContact {
    p: kr::Params,
    amp: f64,
    om: f64,
    s: f64,
}

impl TaylorSystem<2> for RigidContact {
    fn coefficients<const N: usize>(&mut self, t0: f64, x: &mut [[f64; N]; 2]) {
        tr::contact_rhs::<N>(x, &sine_series::<N>(self.amp, self.om, t0), &self.p);
    }
}

impl TaylorEvents<2, 1> for RigidContact {
    fn event_coefficients<const N: usize>(&mut self, t0: f64, x: &[[f64; N]; 2]) -> [[f64; N]; 1] {
        tr::uplift::<N>(x, &sine_series::<N>(self.amp, self.om, t0), self.s, &self.p)
    }
}

#[test]
fn grazing_uplift_at_one_plus_minus_1e9_of_the_threshold() {
    // f_s is affine in ug for the rigid block: uplift about s when ug crosses ug* (the
    // pointwise kernel gives ug*). A = ug* (1 ± 1e-9): the peak of the sine grazes the threshold.
    let p = rigid_params();
    let (s, ug_star) = [1.0, -1.0]
        .into_iter()
        .map(|s| {
            let (f0, f1) = (
                kr::uplift(&[0.0; 2], 0.0, s, &p),
                kr::uplift(&[0.0; 2], 1.0, s, &p),
            );
            (s, -f0 / (f1 - f0))
        })
        .find(|&(_, u)| u > 0.0)
        .unwrap();
    let om = 2.0;
    for rel in [1e-9, -1e-9, 1e-6] {
        let amp = ug_star * (1.0 + rel);
        let mut sys = RigidContact { p, amp, om, s };
        let period = 2.0 * std::f64::consts::PI / om;
        // A rigid column in contact does not move: the step rule sees zero coefficients, so the
        // step is bounded by the excitation's resolution, as the driver bounds its RK steps.
        let mut opts = TaylorOptions::new(1e-15);
        opts.h_max = period / 16.0;
        let mut ode = Taylor::<2>::new(opts).unwrap();
        ode.reset(0.0, [0.0, 0.0]).unwrap();
        let mut found = None;
        loop {
            let info = ode.step(&mut sys, period).unwrap();
            let mut ev = RigidContact { p, amp, om, s };
            if let Some(e) = ode.locate(&mut ev, &[Direction::Rising]) {
                found = Some(e.t);
                break;
            }
            if info.reached {
                break;
            }
        }
        let want = (ug_star / amp).asin() / om;
        match found {
            Some(t) => {
                println!(
                    "ug* = {ug_star:.6}, A = ug* (1 + {rel:e}): uplift at {t:.15}, closed form \
                     {want:.15}, difference {:.2e} ({} steps)",
                    t - want,
                    ode.stats().steps
                );
                assert!(rel > 0.0, "uplift below the threshold");
                assert!((t - want).abs() <= 1e-9 * want, "{t} vs {want}");
            }
            None => {
                println!(
                    "ug* = {ug_star:.6}, A = ug* (1 {rel:e}): no uplift over a period ({} steps)",
                    ode.stats().steps
                );
                assert!(rel < 0.0, "grazing uplift missed");
            }
        }
    }
}

/// The oscillator with one coefficient of order `k` of x poisoned (NaN or ∞).
struct Poisoned {
    k: usize,
    value: f64,
}
impl TaylorSystem<2> for Poisoned {
    fn coefficients<const N: usize>(&mut self, t0: f64, x: &mut [[f64; N]; 2]) {
        Oscillator.coefficients(t0, x);
        x[0][self.k] = self.value;
    }
}

/// A non-finite coefficient anywhere in the series is reported as one, not as the step-size
/// underflow or the non-finite end state it causes (the step looks for it only on the way to
/// an error).
#[test]
fn a_non_finite_coefficient_is_reported_as_such_at_every_order() {
    let p = order_from_tol(1e-10);
    for k in 1..=p {
        for value in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            let mut ode = Taylor::<2>::new(TaylorOptions::new(1e-10)).unwrap();
            ode.reset(0.0, [1.0, 0.0]).unwrap();
            let e = ode
                .step(&mut Poisoned { k, value }, 10.0)
                .expect_err("a non-finite coefficient must fail the step");
            assert_eq!(
                e.kind,
                rocking_ode::OdeErrorKind::NonFinite,
                "order {k}, {value}"
            );
            assert!(
                e.message.contains("non-finite Taylor coefficient"),
                "order {k}, {value}: {}",
                e.message
            );
        }
    }
}
