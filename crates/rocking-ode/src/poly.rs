//! Real roots of a polynomial on one step, for events located on a Taylor step.
//!
//! Isolation is Descartes' rule of signs in the Bernstein basis with bisection by de Casteljau
//! subdivision (the Vincent–Collins–Akritas method in its Bernstein form, e.g. Mourrain, Rouillier
//! & Roy, J. Symbolic Comput. 39, 2005): the number of sign changes of the Bernstein coefficients
//! on an interval bounds the number of roots there and has the same parity, so an interval with no
//! change has no root and one with a single change has exactly one. Intervals are split in halves,
//! left first, so roots come out in time order. Why not Sturm sequences: they need divisions that
//! lose accuracy at double roots; de Casteljau is a sequence of convex combinations (stable).
//!
//! A pair of roots closer than the subdivision limit (2⁻⁵⁰ of the step), a double root or a tangency
//! with zero within rounding is a *cluster*: the polynomial reaches zero there, so it is reported
//! (a grazing contact that touches the threshold counts as reaching it, as `g >= 0` does in
//! [`Direction`]). "Within rounding" is a bound of the Bernstein coefficients' rounding error,
//! 8 (n + 1) ε Σ|c_k h^k|: an interval without a sign change is still searched while one of its
//! coefficients is that close to zero and g is not monotone there (a monotone piece comes closest
//! at an end: the step start, moving away from a restart on the surface, is not a touch). A touch
//! is placed at the extremum of g (Newton on g'), or where |g| first falls below the bound.
//!
//! An isolated simple root is polished by the Illinois method on the power form (Horner), to a
//! bracket of 2 ulp.

use crate::events::Direction;

/// Highest polynomial degree handled (coefficient arrays live on the stack).
pub const MAX_DEGREE: usize = 32;

/// Subdivision limit, as a fraction of the step: below it an interval with sign changes is a
/// cluster (about 50 bisections).
const MIN_WIDTH: f64 = 1.0 / (1u64 << 50) as f64;

/// Binomial coefficients C(i, k), i, k <= MAX_DEGREE (exact in f64).
const BINOM: [[f64; MAX_DEGREE + 1]; MAX_DEGREE + 1] = {
    let mut t = [[0.0; MAX_DEGREE + 1]; MAX_DEGREE + 1];
    let mut i = 0;
    while i <= MAX_DEGREE {
        t[i][0] = 1.0;
        let mut k = 1;
        while k <= i {
            t[i][k] = t[i - 1][k - 1] + t[i - 1][k];
            k += 1;
        }
        i += 1;
    }
    t
};

/// `C(i, k) / C(n, k)` at `[n][i][k]` for k <= i <= n <= MAX_DEGREE: the power-to-Bernstein
/// conversion's factors, divided once at compile time instead of at every search (the divisions
/// were most of [`first_root`]'s cost; the same IEEE quotients, so the same coefficients).
static BERNSTEIN: [[[f64; MAX_DEGREE + 1]; MAX_DEGREE + 1]; MAX_DEGREE + 1] = {
    let mut t = [[[0.0; MAX_DEGREE + 1]; MAX_DEGREE + 1]; MAX_DEGREE + 1];
    let mut n = 0;
    while n <= MAX_DEGREE {
        let mut i = 0;
        while i <= n {
            let mut k = 0;
            while k <= i {
                t[n][i][k] = BINOM[i][k] / BINOM[n][k];
                k += 1;
            }
            i += 1;
        }
        n += 1;
    }
    t
};

/// A root of `g(τ) = Σ c_k τ^k` on `(0, h]`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Root {
    /// Offset from the step start: the first point found on the far side (g crossed or is 0).
    pub tau: f64,
    /// Last point before the crossing (`tau_before < tau`, at most 2 ulp apart for a simple
    /// root, the predecessor of `tau` where g(tau) is exactly 0, at most 2⁻⁵⁰ h for a cluster).
    pub tau_before: f64,
    /// `true` when `g < 0` just before the root (a rising crossing, or a touch from below).
    pub rising: bool,
    /// `true` for a cluster (double root, grazing, or two roots closer than 2⁻⁵⁰ h).
    pub cluster: bool,
}

/// The next f64 below a finite `x >= 0` (`f64::next_down` is newer than the MSRV).
fn next_down(x: f64) -> f64 {
    if x > 0.0 {
        f64::from_bits(x.to_bits() - 1)
    } else {
        -f64::from_bits(1)
    }
}

fn accepts(dir: Direction, rising: bool) -> bool {
    match dir {
        Direction::Rising => rising,
        Direction::Falling => !rising,
        Direction::Either => true,
    }
}

/// Value of `Σ c_k τ^k` (Horner).
#[inline]
pub fn horner(c: &[f64], tau: f64) -> f64 {
    c.iter().rev().fold(0.0, |acc, &ck| acc * tau + ck)
}

/// `Σ_{k≥1} |c_k| h^k`: how far a polynomial can move from `c[0]` over a step of `h` (the `tail`
/// of [`far_from_zero`]). In two halves, `lo(h) + h^m hi(h)`, each by Horner's rule, that the
/// CPU runs side by side: one chain of 16 dependent add-multiply pairs at order 16 held up the
/// step that asks it.
#[must_use]
pub fn abs_tail(c: &[f64], h: f64) -> f64 {
    let t = c.get(1..).unwrap_or_default();
    let (lo, hi) = t.split_at(t.len().div_ceil(2));
    let horner_abs = |s: &[f64]| s.iter().rev().fold(0.0, |acc, v| (acc + v.abs()) * h);
    let mut h_m = 1.0;
    for _ in 0..lo.len() {
        h_m *= h;
    }
    horner_abs(lo) + h_m * horner_abs(hi)
}

/// Forward differences of Bernstein coefficients (the signs of g's derivative's coefficients).
fn diffs(b: &[f64; MAX_DEGREE + 1], n: usize) -> [f64; MAX_DEGREE + 1] {
    let mut d = [0.0; MAX_DEGREE + 1];
    for i in 0..n {
        d[i] = b[i + 1] - b[i];
    }
    d
}

/// Sign changes of a sequence, zeros skipped, and the signs of its first and last nonzero terms.
fn variations(b: &[f64]) -> (usize, f64, f64) {
    let (mut v, mut first, mut last) = (0, 0.0, 0.0);
    for &x in b {
        if x != 0.0 {
            let s = x.signum();
            if last != 0.0 && s != last {
                v += 1;
            }
            if first == 0.0 {
                first = s;
            }
            last = s;
        }
    }
    (v, first, last)
}

/// Rounding bound of the Bernstein coefficients of a polynomial of degree `n` with
/// `Σ |c_k h^k| = scale` (conversion and ~50 subdivisions): values within it of zero are zero as
/// far as f64 can tell.
fn rounding_bound(scale: f64, n: usize) -> f64 {
    8.0 * (n + 1) as f64 * f64::EPSILON * scale
}

/// Whether a polynomial of degree at most `n` with value `d0` at the step start and
/// `Σ_{k≥1} |c_k| h^k = tail` surely has no root and no touch on the step, so that
/// [`first_root`] returns `None` without a search. Most steps are far from an event: every
/// Bernstein coefficient lies within `tail` of d0 (C(i,k) ≤ C(n,k)), so when that keeps them all
/// beyond twice the rounding bound on d0's side, the search would find no sign change and no
/// coefficient within the bound. Callers with several events on one polynomial (θ against 0 and
/// against the overturning angle) test them all with one `tail`.
#[must_use]
pub fn far_from_zero(d0: f64, tail: f64, n: usize) -> bool {
    d0.abs() - tail > 2.0 * rounding_bound(d0.abs() + tail, n)
}

/// The earliest root of `g(τ) = Σ c[k] τ^k` in `(0, h]` whose direction `dir` accepts, or `None`.
///
/// Semantics match [`Direction::triggers`]: a root at τ = 0 never counts (g is divided by its
/// exact factor τ^m first, which leaves the sign on `(0, h]` unchanged), a root at τ = h does.
/// Panics when `c` has more than `MAX_DEGREE + 1` coefficients or `h` is not finite and positive.
pub fn first_root(c: &[f64], h: f64, dir: Direction) -> Option<Root> {
    assert!(c.len() <= MAX_DEGREE + 1, "degree above MAX_DEGREE");
    assert!(h > 0.0 && h.is_finite(), "step {h} must be finite and > 0");
    let lead = c.iter().take_while(|&&v| v == 0.0).count();
    let c = &c[lead..];
    let n = c.iter().rposition(|&v| v != 0.0)?;
    let c = &c[..=n];
    if n == 0 {
        return None;
    }
    // Scaled to s = τ/h in [0, 1], then to the Bernstein basis of degree n:
    // b_i = Σ_{k<=i} C(i,k)/C(n,k) d_k.
    let mut d = [0.0; MAX_DEGREE + 1];
    let mut hk = 1.0;
    for k in 0..=n {
        d[k] = c[k] * hk;
        hk *= h;
    }
    let tail: f64 = d[1..=n].iter().map(|v| v.abs()).sum();
    if far_from_zero(d[0], tail, n) {
        return None;
    }
    let delta = rounding_bound(d[0].abs() + tail, n);
    let ratio = &BERNSTEIN[n];
    let mut b = [0.0; MAX_DEGREE + 1];
    for i in 0..=n {
        b[i] = (0..=i).map(|k| ratio[i][k] * d[k]).sum();
    }
    let ctx = Ctx {
        c,
        h,
        n,
        dir,
        delta,
    };
    ctx.search(&b, 0.0, 1.0)
}

struct Ctx<'a> {
    c: &'a [f64],
    h: f64,
    n: usize,
    dir: Direction,
    delta: f64,
}

impl Ctx<'_> {
    fn search(&self, b: &[f64; MAX_DEGREE + 1], lo: f64, hi: f64) -> Option<Root> {
        let n = self.n;
        let (v, first, _) = variations(&b[..=n]);
        let end_root = b[n] == 0.0;
        if v == 0 {
            if end_root && first != 0.0 {
                let rising = first < 0.0;
                let tau = if hi == 1.0 { self.h } else { self.h * hi };
                return accepts(self.dir, rising).then_some(Root {
                    tau,
                    tau_before: next_down(tau),
                    rising,
                    cluster: false,
                });
            }
            // No sign change, but a touch within rounding of zero (a double root whose computed
            // maximum came out a few ulp below zero) still reaches the threshold: search on
            // while some coefficient is within the rounding bound.
            let rising = first < 0.0;
            if !(accepts(self.dir, rising) && b[..=n].iter().any(|x| x.abs() <= self.delta)) {
                return None;
            }
            let (dv, dfirst, _) = variations(&diffs(b, n)[..n]);
            if dv == 0 {
                // Monotone here, so closest to zero at an end. At `lo` that is the step start
                // (moving away from a restart on the surface) or the left neighbour's end,
                // already searched; at `hi` it is a touch if g is within the bound there.
                let toward_hi = dfirst * first < 0.0;
                if toward_hi && b[n].abs() <= self.delta {
                    let tau_hi = if hi == 1.0 { self.h } else { self.h * hi };
                    let tau = self.extremum(tau_hi).unwrap_or(tau_hi);
                    return Some(Root {
                        tau,
                        tau_before: next_down(tau),
                        rising,
                        cluster: true,
                    });
                }
                return None;
            }
        }
        if v == 1 && !end_root && b[0] != 0.0 {
            let rising = b[0] < 0.0;
            if !accepts(self.dir, rising) {
                return None;
            }
            if let Some(r) = self.polish(lo, hi, rising) {
                return Some(r);
            }
        }
        if hi - lo <= MIN_WIDTH {
            let rising = first < 0.0;
            let tau = if end_root && hi == 1.0 {
                self.h
            } else {
                self.h * 0.5 * (lo + hi)
            };
            if !accepts(self.dir, rising) {
                return None;
            }
            let tau = if v % 2 == 0 && !end_root {
                self.extremum(tau).unwrap_or(tau)
            } else {
                tau
            };
            return Some(Root {
                tau,
                tau_before: (self.h * lo).min(tau),
                rising,
                cluster: v != 1,
            });
        }
        // de Casteljau at 1/2: left gets the first entries of each column, right the last.
        let mut w = *b;
        let mut left = [0.0; MAX_DEGREE + 1];
        let mut right = [0.0; MAX_DEGREE + 1];
        left[0] = w[0];
        right[n] = w[n];
        for r in 1..=n {
            for i in 0..=n - r {
                w[i] = 0.5 * (w[i] + w[i + 1]);
            }
            left[r] = w[0];
            right[n - r] = w[n - r];
        }
        let mid = 0.5 * (lo + hi);
        self.search(&left, lo, mid)
            .or_else(|| self.search(&right, mid, hi))
    }

    /// A touch is first met where |g| falls below the rounding bound, ~√ε before the extremum:
    /// Newton on g' from there finds the extremum, kept if it stays in the step, not before
    /// `tau0`'s interval, and where g is still within the bound.
    fn extremum(&self, tau0: f64) -> Option<f64> {
        let c = self.c;
        let mut tau = tau0;
        for _ in 0..8 {
            let (mut d1, mut d2) = (0.0, 0.0);
            for k in (1..c.len()).rev() {
                d2 = d2 * tau + d1;
                d1 = d1 * tau + k as f64 * c[k];
            }
            if d2 == 0.0 {
                break;
            }
            let next = tau - d1 / d2;
            if !(next >= tau0 - MIN_WIDTH * self.h && next <= self.h) {
                return None;
            }
            if next == tau {
                break;
            }
            tau = next;
        }
        (horner(c, tau).abs() <= self.delta).then_some(tau)
    }

    /// Illinois (modified regula falsi) on the power form in τ, bisection after 40 iterations,
    /// to a bracket of 2 ulp; `None` when rounding hides the sign change at the bracket ends (the
    /// caller subdivides further).
    fn polish(&self, lo: f64, hi: f64, rising: bool) -> Option<Root> {
        let s0 = if rising { -1.0 } else { 1.0 };
        let mut a = self.h * lo;
        let mut b = if hi == 1.0 { self.h } else { self.h * hi };
        let (mut fa, mut fb) = (horner(self.c, a), horner(self.c, b));
        if !(fa * s0 > 0.0 && fb * s0 <= 0.0) {
            return None;
        }
        let mut side = 0i8;
        for iter in 0..200 {
            if fb == 0.0 || b - a <= 2.0 * f64::EPSILON * b.abs() {
                break;
            }
            let mid = 0.5 * (a + b);
            let mut x = if iter < 40 {
                b - fb * (b - a) / (fb - fa)
            } else {
                mid
            };
            if !(x > a && x < b) {
                x = mid;
                if !(x > a && x < b) {
                    break;
                }
            }
            let f = horner(self.c, x);
            if f * s0 <= 0.0 {
                b = x;
                fb = f;
                if side == 1 {
                    fa *= 0.5;
                }
                side = 1;
            } else {
                a = x;
                fa = f;
                if side == -1 {
                    fb *= 0.5;
                }
                side = -1;
            }
        }
        if fb == 0.0 {
            // g exactly 0 at b: the crossing is there.
            a = a.max(next_down(b));
        }
        Some(Root {
            tau: b,
            tau_before: a,
            rising,
            cluster: false,
        })
    }
}
