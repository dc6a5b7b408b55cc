//! Roots and extrema inside one step, on any dense output given as a function of time.
//!
//! [`locate`](crate::events::locate) finds sign changes between the ends of a step; these
//! helpers find what the ends do not show: a turning point of a component (where its rate
//! changes sign), a function that touches zero and turns back inside the step (grazing), and
//! the first point of an interval where a condition holds.

use nalgebra::SVector;

/// The zero of a rate inside (a, b) where it changes sign, `ra` being its value at `a`
/// (Illinois method; to 1e-14 relative in t, or after 60 iterations at the bracket's middle).
pub fn turning_point(rate: impl Fn(f64) -> f64, a: f64, b: f64, ra: f64) -> f64 {
    let (mut a, mut b, mut fa, mut fb) = (a, b, ra, rate(b));
    let mut side = 0;
    for _ in 0..60 {
        let m = (a * fb - b * fa) / (fb - fa);
        let m = if m > a && m < b { m } else { 0.5 * (a + b) };
        let fm = rate(m);
        if fm == 0.0 || (b - a) <= 1e-14 * b.abs().max(1.0) {
            return m;
        }
        if (fm < 0.0) == (fa < 0.0) {
            a = m;
            fa = fm;
            if side == -1 {
                fb *= 0.5;
            }
            side = -1;
        } else {
            b = m;
            fb = fm;
            if side == 1 {
                fa *= 0.5;
            }
            side = 1;
        }
    }
    0.5 * (a + b)
}

/// A component of `g` negative at both ends of the step (t_old, t_new) can still touch zero
/// inside it (grazing). Where it rises just after the start and falls just before the end, a
/// golden-section search towards its maximum looks for a positive point; if there is one, the
/// crossing is the first positive point before it (bisection to a few ulp). Returns the earliest
/// such crossing over the components as (time, component, the positive point), or `None`.
pub fn grazing<const M: usize>(
    mut g: impl FnMut(f64) -> SVector<f64, M>,
    t_old: f64,
    t_new: f64,
    g_old: &SVector<f64, M>,
    g_new: &SVector<f64, M>,
) -> Option<(f64, usize, f64)> {
    let delta = (t_new - t_old) * 1e-4;
    let mut at = |t: f64, k: usize| g(t)[k];
    let mut best: Option<(f64, usize, f64)> = None;
    for k in 0..M {
        if g_old[k] >= 0.0 || g_new[k] >= 0.0 {
            continue;
        }
        if !(at(t_old + delta, k) > g_old[k] && at(t_new - delta, k) > g_new[k]) {
            continue;
        }
        let r = 0.5 * (5f64.sqrt() - 1.0);
        let (mut a, mut b) = (t_old, t_new);
        let (mut c, mut d) = (b - r * (b - a), a + r * (b - a));
        let (mut fc, mut fd) = (at(c, k), at(d, k));
        while b - a > 4.0 * f64::EPSILON * b.abs().max(1.0) && fc.max(fd) <= 0.0 {
            if fc > fd {
                (b, d, fd) = (d, c, fc);
                c = b - r * (b - a);
                fc = at(c, k);
            } else {
                (a, c, fc) = (c, d, fd);
                d = a + r * (b - a);
                fd = at(d, k);
            }
        }
        let (t_max, f_max) = if fc > fd { (c, fc) } else { (d, fd) };
        if f_max <= 0.0 {
            continue;
        }
        let t_up = first_true(|t| at(t, k) > 0.0, t_old, t_max);
        if best.is_none_or(|(t, _, _)| t_up < t) {
            best = Some((t_up, k, t_max));
        }
    }
    best
}

/// The first point of (a, b] where `holds` is true, given that it is false at `a` and true at
/// `b`: bisection until the bracket is a few ulp wide; returns its upper end.
pub fn first_true(mut holds: impl FnMut(f64) -> bool, a: f64, b: f64) -> f64 {
    let (mut lo, mut hi) = (a, b);
    while hi - lo > 4.0 * f64::EPSILON * hi.abs().max(1.0) {
        let mid = 0.5 * (lo + hi);
        if holds(mid) {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    hi
}

/// The largest value of `f` on [a, b] where it is unimodal, the time to `xtol` (plus √ε of
/// its size: a flat maximum is not located more finely by its values): the time and the value.
/// Brent's method (Brent 1973, *Algorithms for minimization without derivatives*, ch. 5):
/// parabolic interpolation through the three best points, a golden-section step where the
/// parabola does not shrink the bracket fast enough. On a smooth maximum it converges
/// superlinearly: about 10 evaluations where golden sections alone take 35 to 40 (a step of a
/// force's dense output is evaluated at every one). Outside unimodality it finds a local maximum.
pub fn brent_max(mut f: impl FnMut(f64) -> f64, a: f64, b: f64, xtol: f64) -> (f64, f64) {
    // (3 − √5) / 2: the golden section's smaller part.
    const GOLDEN: f64 = 0.381_966_011_250_105_1;
    let (mut a, mut b) = (a, b);
    // The best point x, the second best w, the previous w in v; minimises g = −f.
    let mut x = a + GOLDEN * (b - a);
    let mut gx = -f(x);
    let (mut w, mut gw, mut v, mut gv) = (x, gx, x, gx);
    // The step taken last (d) and the one before (e).
    let (mut d, mut e) = (0.0_f64, 0.0_f64);
    for _ in 0..200 {
        let m = 0.5 * (a + b);
        let tol = f64::EPSILON.sqrt() * x.abs() + xtol / 3.0;
        if (x - m).abs() <= 2.0 * tol - 0.5 * (b - a) {
            break;
        }
        let mut parabolic = false;
        if e.abs() > tol {
            let r = (x - w) * (gx - gv);
            let q = (x - v) * (gx - gw);
            let mut p = (x - v) * q - (x - w) * r;
            let mut q = 2.0 * (q - r);
            if q > 0.0 {
                p = -p;
            } else {
                q = -q;
            }
            let e_before = e;
            e = d;
            // The parabola's vertex, if it lies inside the bracket and the step is less than
            // half the one before last.
            if p.abs() < (0.5 * q * e_before).abs() && p > q * (a - x) && p < q * (b - x) {
                d = p / q;
                let u = x + d;
                if u - a < 2.0 * tol || b - u < 2.0 * tol {
                    d = if x < m { tol } else { -tol };
                }
                parabolic = true;
            }
        }
        if !parabolic {
            e = if x < m { b - x } else { a - x };
            d = GOLDEN * e;
        }
        let u = if d.abs() >= tol {
            x + d
        } else {
            x + tol.copysign(d)
        };
        let gu = -f(u);
        if gu <= gx {
            if u < x {
                b = x;
            } else {
                a = x;
            }
            (v, gv, w, gw, x, gx) = (w, gw, x, gx, u, gu);
        } else {
            if u < x {
                a = u;
            } else {
                b = u;
            }
            if gu <= gw || w == x {
                (v, gv, w, gw) = (w, gw, u, gu);
            } else if gu <= gv || v == x || v == w {
                (v, gv) = (u, gu);
            }
        }
    }
    (x, -gx)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn turning_point_of_a_sine_is_its_zero() {
        // d/dt sin(t) = cos(t) changes sign at π/2.
        let t = turning_point(f64::cos, 1.0, 2.0, 1f64.cos());
        assert!((t - std::f64::consts::FRAC_PI_2).abs() < 1e-13, "{t}");
    }

    #[test]
    fn a_grazing_touch_inside_a_step_is_found() {
        // g = 1e-6 − (t − 0.3)² is negative at both ends of [0, 1] and positive near 0.3.
        let g = |t: f64| SVector::<f64, 2>::new(1e-6 - (t - 0.3).powi(2), -1.0);
        let (g0, g1) = (g(0.0), g(1.0));
        let (t_up, k, t_max) = grazing(g, 0.0, 1.0, &g0, &g1).expect("the touch is found");
        assert_eq!(k, 0);
        assert!((t_up - (0.3 - 1e-3)).abs() < 1e-12, "{t_up}");
        // The search towards the maximum stops at the first positive point it meets.
        assert!(g(t_max)[0] > 0.0 && t_max > t_up, "{t_max}");
    }

    #[test]
    fn a_function_that_stays_negative_does_not_graze() {
        let g = |t: f64| SVector::<f64, 1>::new(-1e-6 - (t - 0.3).powi(2));
        assert_eq!(grazing(g, 0.0, 1.0, &g(0.0), &g(1.0)), None);
    }

    #[test]
    fn brent_max_finds_the_peak_of_a_cosine_in_few_evaluations() {
        // The value is found to rounding; the time to where cos stops changing (~1e-8 from it).
        let mut calls = 0;
        let (t, v) = brent_max(
            |t| {
                calls += 1;
                (t - 0.3).cos()
            },
            0.0,
            1.0,
            1e-8,
        );
        assert!((t - 0.3).abs() < 1e-7 && (v - 1.0).abs() < 1e-16, "{t} {v}");
        assert!(calls <= 15, "{calls} evaluations");
        // A peak at an end of the interval: the search closes in on it.
        let (t, v) = brent_max(|t| t.sin(), 0.0, 1.0, 1e-10);
        assert!(1.0 - t < 1e-7 && (v - 1f64.sin()).abs() < 1e-7, "{t} {v}");
    }

    #[test]
    fn brent_max_locates_a_sharp_peak_to_the_tolerance() {
        // A quartic peak (flat to fourth order) and a skewed one, at 0.7 of [0, 1].
        for f in [
            (|t: f64| 1.0 - (t - 0.7).powi(4)) as fn(f64) -> f64,
            |t: f64| (t - 0.7) * (-(t - 0.7) * 3.0).exp() - (t - 0.7).abs().powi(3),
        ] {
            let (t, v) = brent_max(f, 0.0, 1.0, 1e-9);
            let best = (0..=100_000)
                .map(|i| f(i as f64 * 1e-5))
                .fold(f64::NEG_INFINITY, f64::max);
            assert!(v >= best - 1e-15, "{t} {v} against {best}");
        }
    }

    #[test]
    fn first_true_brackets_the_switch_to_a_few_ulp() {
        let t = first_true(|t| t >= 0.25, 0.0, 1.0);
        assert!(t >= 0.25 && t - 0.25 < 1e-15, "{t}");
    }
}
