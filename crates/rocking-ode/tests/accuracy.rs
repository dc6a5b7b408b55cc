//! Convergence order, dense-output order and tolerance proportionality.

use nalgebra::{SVector, Vector1, Vector2};
use rocking_ode::{Integrator, Method, Options, Tolerances};

/// Options forcing `n` equal steps on `[t0, t1]`: h_init = h_max = h and a
/// tolerance so loose that no step is ever rejected or shortened.
fn fixed_step<const N: usize>(method: Method, t0: f64, t1: f64, n: u64) -> Integrator<N> {
    let h = (t1 - t0) / n as f64;
    let opts = Options {
        method,
        h_max: h,
        h_init: Some(h),
        max_steps: 10 * n + 10,
    };
    Integrator::new(opts, Tolerances::uniform(0.0, 1e30)).unwrap()
}

/// Least-squares slope of log(err) against log(h).
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

struct Problem<const N: usize> {
    name: &'static str,
    t1: f64,
    f: fn(f64, &SVector<f64, N>) -> SVector<f64, N>,
    exact: fn(f64) -> SVector<f64, N>,
}

fn oscillator() -> Problem<2> {
    Problem {
        name: "harmonic oscillator",
        t1: 10.0,
        f: |_t, y| Vector2::new(y[1], -y[0]),
        exact: |t| Vector2::new(t.cos(), -t.sin()),
    }
}

fn riccati() -> Problem<1> {
    // y' = -2 t y^2, y(0) = 1  =>  y = 1 / (1 + t^2)
    Problem {
        name: "y' = -2ty^2",
        t1: 2.0,
        f: |t, y| Vector1::new(-2.0 * t * y[0] * y[0]),
        exact: |t| Vector1::new(1.0 / (1.0 + t * t)),
    }
}

fn exp_sin() -> Problem<1> {
    // y' = y cos t, y(0) = 1  =>  y = exp(sin t)
    Problem {
        name: "y' = y cos t",
        t1: 10.0,
        f: |t, y| Vector1::new(y[0] * t.cos()),
        exact: |t| Vector1::new(t.sin().exp()),
    }
}

/// Runs `n` fixed steps; returns (h, max global error over the grid points
/// including t1, max dense-output error inside the steps).
fn run_fixed<const N: usize>(p: &Problem<N>, method: Method, n: u64) -> (f64, f64, f64) {
    let mut ode = fixed_step::<N>(method, 0.0, p.t1, n);
    let mut f = p.f;
    ode.reset(0.0, (p.exact)(0.0), &mut f).unwrap();
    let mut dense_err: f64 = 0.0;
    let mut grid_err: f64 = 0.0;
    loop {
        let info = ode.step(&mut f, p.t1).unwrap();
        for theta in [0.13, 0.31, 0.5, 0.77, 0.94] {
            let t = info.t_old + theta * (info.t_new - info.t_old);
            dense_err = dense_err.max((ode.dense(t) - (p.exact)(t)).amax());
        }
        grid_err = grid_err.max((ode.y() - (p.exact)(info.t_new)).amax());
        if info.reached {
            break;
        }
    }
    assert_eq!(ode.stats().steps, n, "{}: not fixed steps", p.name);
    assert_eq!(ode.stats().rejected, 0);
    assert_eq!(ode.t(), p.t1);
    (p.t1 / n as f64, grid_err, dense_err)
}

fn check_orders<const N: usize>(
    p: &Problem<N>,
    method: Method,
    ns: &[u64],
    order: f64,
    dense_order: f64,
) {
    let runs: Vec<_> = ns.iter().map(|&n| run_fixed(p, method, n)).collect();
    let glob: Vec<_> = runs.iter().map(|r| (r.0, r.1)).collect();
    let dense: Vec<_> = runs.iter().map(|r| (r.0, r.2)).collect();
    let (s, sd) = (slope(&glob), slope(&dense));
    let fmt = |d: &[(f64, f64)]| {
        d.iter()
            .map(|(h, e)| format!("{h:.4}:{e:.2e}"))
            .collect::<Vec<_>>()
            .join(" ")
    };
    println!(
        "{method:?} {}: global [{}] slope {s:.3}; dense [{}] slope {sd:.3}",
        p.name,
        fmt(&glob),
        fmt(&dense)
    );
    assert!(
        (s - order).abs() < 0.4,
        "{method:?} {}: observed order {s}",
        p.name
    );
    assert!(
        (sd - dense_order).abs() < 0.4,
        "{method:?} {}: dense order {sd}",
        p.name
    );
}

#[test]
fn dopri5_order_5_and_dense_order_5() {
    let ns = [40, 56, 80, 113, 160, 226, 320];
    check_orders(&oscillator(), Method::Dopri5, &ns, 5.0, 5.0);
    check_orders(
        &riccati(),
        Method::Dopri5,
        &[32, 45, 64, 90, 128, 181],
        5.0,
        5.0,
    );
    check_orders(
        &exp_sin(),
        Method::Dopri5,
        &[80, 113, 160, 226, 320, 452],
        5.0,
        5.0,
    );
}

#[test]
fn dop853_order_8_and_dense_order_8() {
    let ns = [20, 24, 28, 34, 40, 48];
    check_orders(&oscillator(), Method::Dop853, &ns, 8.0, 8.0);
    check_orders(
        &riccati(),
        Method::Dop853,
        &[14, 17, 20, 24, 28, 34],
        8.0,
        8.0,
    );
    check_orders(&exp_sin(), Method::Dop853, &ns, 8.0, 8.0);
}

/// Adaptive run to `t1` at `rtol`, `atol = rtol`; returns (max error over the
/// accepted steps, number of steps).
fn run_adaptive<const N: usize>(p: &Problem<N>, method: Method, rtol: f64) -> (f64, u64) {
    let mut ode = Integrator::new(Options::new(method), Tolerances::uniform(rtol, rtol)).unwrap();
    let mut f = p.f;
    ode.reset(0.0, (p.exact)(0.0), &mut f).unwrap();
    let mut err: f64 = 0.0;
    loop {
        let info = ode.step(&mut f, p.t1).unwrap();
        err = err.max((ode.y() - (p.exact)(info.t_new)).amax());
        if info.reached {
            break;
        }
    }
    assert_eq!(ode.t(), p.t1);
    (err, ode.stats().steps)
}

fn check_proportionality<const N: usize>(p: &Problem<N>, method: Method) {
    let rtols = [1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10];
    let res: Vec<_> = rtols.iter().map(|&r| run_adaptive(p, method, r)).collect();
    let line: Vec<_> = rtols
        .iter()
        .zip(&res)
        .map(|(r, (e, n))| format!("{r:.0e}:{e:.2e}({n})"))
        .collect();
    println!("{method:?} {} tolerance sweep: {}", p.name, line.join(" "));
    for (r, (e, _)) in rtols.iter().zip(&res) {
        assert!(
            *e <= 100.0 * r,
            "{method:?} {}: error {e} at rtol {r}",
            p.name
        );
    }
    for w in res.windows(3) {
        // Monotone within reason: single lucky/unlucky steps happen at loose
        // tolerances (DOP853 on y' = y cos t at rtol 1e-8 has one step with
        // a local error ~9x the scale), so compare two decades apart.
        assert!(w[2].0 < w[0].0, "{method:?} {}: {res:?}", p.name);
        assert!(w[1].1 >= w[0].1, "more steps for tighter tolerance");
    }
    assert!(res[6].0 < 1e-4 * res[0].0, "{method:?} {}: {res:?}", p.name);
}

#[test]
fn tolerance_proportionality() {
    for m in [Method::Dopri5, Method::Dop853] {
        check_proportionality(&oscillator(), m);
        check_proportionality(&riccati(), m);
        check_proportionality(&exp_sin(), m);
    }
}
