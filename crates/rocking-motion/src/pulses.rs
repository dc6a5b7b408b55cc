//! Analytic pulses: one-cycle sine/cosine, Ricker wavelets, Mavroeidis–Papageorgiou.

use crate::{support_next_kink, GroundMotion};
use std::f64::consts::PI;

fn check_amp_freq(what: &str, amplitude: f64, freq: f64) {
    assert!(
        amplitude.is_finite(),
        "{what}: amplitude must be finite, got {amplitude}"
    );
    assert!(
        freq.is_finite() && freq > 0.0,
        "{what}: frequency must be positive and finite, got {freq}"
    );
}

fn check_start(what: &str, start: f64) {
    assert!(
        start.is_finite(),
        "{what}: start time must be finite, got {start}"
    );
}

/// Left limit of a function given by `f` on the closed support `[s, e]` and 0 outside.
#[inline]
fn left_limit(s: f64, e: f64, t: f64, f: impl Fn(f64) -> f64) -> f64 {
    if t > s && t <= e {
        f(t)
    } else {
        0.0
    }
}

/// Right limit of a function given by `f` on the closed support `[s, e]` and 0 outside.
#[inline]
fn right_limit(s: f64, e: f64, t: f64, f: impl Fn(f64) -> f64) -> f64 {
    if t >= s && t < e {
        f(t)
    } else {
        0.0
    }
}

/// One full cycle of a sine, ü_g(t) = a·sin(ω (t − t_s)) for
/// t ∈ [t_s, t_s + 2π/ω], 0 elsewhere (the one-sine pulse of the rocking
/// literature; Housner 1963, Zhang & Makris 2001).
///
/// ü_g is continuous (it is 0 at both ends) but its derivative jumps there:
/// kinks at t_s and t_s + 2π/ω.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SinePulse {
    /// Amplitude a.
    pub amplitude: f64,
    /// Angular frequency ω (rad per time unit).
    pub omega: f64,
    /// Start time t_s (default 0).
    pub start: f64,
}

impl SinePulse {
    /// Pulse of amplitude `amplitude` and angular frequency `omega`, starting at t = 0.
    ///
    /// # Panics
    /// If `amplitude` is not finite or `omega` is not positive and finite.
    pub fn new(amplitude: f64, omega: f64) -> Self {
        check_amp_freq("SinePulse", amplitude, omega);
        SinePulse {
            amplitude,
            omega,
            start: 0.0,
        }
    }

    /// The same pulse starting at `start`.
    ///
    /// # Panics
    /// If `start` is not finite.
    pub fn with_start(self, start: f64) -> Self {
        check_start("SinePulse", start);
        SinePulse { start, ..self }
    }

    /// Duration 2π/ω of the pulse.
    pub fn period(&self) -> f64 {
        2.0 * PI / self.omega
    }
}

impl GroundMotion for SinePulse {
    fn resolution(&self) -> f64 {
        self.period() / 16.0
    }
    fn accel_series(&self, t0: f64, out: &mut [f64]) -> bool {
        out.fill(0.0);
        if t0 >= self.start && t0 < self.end() {
            let phase = (self.omega * (t0 - self.start)).sin_cos();
            add_harmonic(self.amplitude, self.omega, phase, out);
        }
        true
    }
    #[inline]
    fn accel(&self, t: f64) -> f64 {
        if t >= self.start && t <= self.end() {
            self.amplitude * (self.omega * (t - self.start)).sin()
        } else {
            0.0
        }
    }
    fn end(&self) -> f64 {
        self.start + self.period()
    }
    fn next_kink(&self, t: f64) -> Option<f64> {
        support_next_kink(self.start, self.end(), t)
    }
}

/// One full cycle of a cosine, ü_g(t) = a·cos(ω (t − t_s)) for
/// t ∈ [t_s, t_s + 2π/ω], 0 elsewhere.
///
/// **ü_g jumps** from 0 to a at t_s and from a back to 0 at t_s + 2π/ω;
/// both are kinks. [`accel`](GroundMotion::accel) returns a at both ends
/// (closed support); use [`accel_left`](GroundMotion::accel_left) /
/// [`accel_right`](GroundMotion::accel_right) for the one-sided values.
/// (The ground velocity a/ω·sin ω(t−t_s) of this pulse returns to zero, but
/// its mean is not zero, so the ground displacement drifts.)
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CosinePulse {
    /// Amplitude a.
    pub amplitude: f64,
    /// Angular frequency ω (rad per time unit).
    pub omega: f64,
    /// Start time t_s (default 0).
    pub start: f64,
}

impl CosinePulse {
    /// Pulse of amplitude `amplitude` and angular frequency `omega`, starting at t = 0.
    ///
    /// # Panics
    /// If `amplitude` is not finite or `omega` is not positive and finite.
    pub fn new(amplitude: f64, omega: f64) -> Self {
        check_amp_freq("CosinePulse", amplitude, omega);
        CosinePulse {
            amplitude,
            omega,
            start: 0.0,
        }
    }

    /// The same pulse starting at `start`.
    ///
    /// # Panics
    /// If `start` is not finite.
    pub fn with_start(self, start: f64) -> Self {
        check_start("CosinePulse", start);
        CosinePulse { start, ..self }
    }

    /// Duration 2π/ω of the pulse.
    pub fn period(&self) -> f64 {
        2.0 * PI / self.omega
    }

    #[inline]
    fn formula(&self, t: f64) -> f64 {
        self.amplitude * (self.omega * (t - self.start)).cos()
    }
}

impl GroundMotion for CosinePulse {
    fn resolution(&self) -> f64 {
        self.period() / 16.0
    }
    fn accel_series(&self, t0: f64, out: &mut [f64]) -> bool {
        out.fill(0.0);
        if t0 >= self.start && t0 < self.end() {
            // cos x = sin(x + π/2), whose sine and cosine are cos x and −sin x.
            let (s, c) = (self.omega * (t0 - self.start)).sin_cos();
            add_harmonic(self.amplitude, self.omega, (c, -s), out);
        }
        true
    }
    #[inline]
    fn accel(&self, t: f64) -> f64 {
        if t >= self.start && t <= self.end() {
            self.formula(t)
        } else {
            0.0
        }
    }
    fn end(&self) -> f64 {
        self.start + self.period()
    }
    fn next_kink(&self, t: f64) -> Option<f64> {
        support_next_kink(self.start, self.end(), t)
    }
    fn accel_left(&self, t: f64) -> f64 {
        left_limit(self.start, self.end(), t, |t| self.formula(t))
    }
    fn accel_right(&self, t: f64) -> f64 {
        right_limit(self.start, self.end(), t, |t| self.formula(t))
    }
}

/// Adds the Taylor coefficients of `a sin(φ + ω h)` at h = 0, `a ωᵏ/k! sin(φ + kπ/2)`, to `out`,
/// given `(sin φ, cos φ)`: no transcendental function per order.
fn add_harmonic(a: f64, omega: f64, (s, c): (f64, f64), out: &mut [f64]) {
    let mut scale = a;
    for (k, o) in out.iter_mut().enumerate() {
        if k > 0 {
            scale *= omega / k as f64;
        }
        *o += scale * [s, c, -s, -c][k % 4];
    }
}

/// Overwrites `out` with the Taylor coefficients of the Gaussian e^{−β²} along β = b + c h at
/// h = 0. Its rate g' = −2cβ g is a linear ODE with a linear coefficient, so the coefficients
/// follow from one `exp` by (k+1) g_{k+1} = −2c (b g_k + c g_{k−1}) (the Hermite recurrence:
/// g_k = e^{−b²} (−c)ᵏ H_k(b)/k!).
fn gaussian_series(b: f64, c: f64, out: &mut [f64]) {
    let (mut previous, mut current) = (0.0, (-(b * b)).exp());
    for (k, o) in out.iter_mut().enumerate() {
        *o = current;
        let next = -2.0 * c * (b * current + c * previous) / (k + 1) as f64;
        (previous, current) = (current, next);
    }
}

/// Multiplies the series in `out` in place by the polynomial `p[0] + p[1] h + …` (Cauchy
/// product, truncated to `out`'s length; from the top so that each order reads lower orders not
/// yet overwritten).
fn multiply_by_polynomial(p: &[f64], out: &mut [f64]) {
    for k in (0..out.len()).rev() {
        out[k] = p
            .iter()
            .take(k + 1)
            .enumerate()
            .map(|(j, pj)| pj * out[k - j])
            .sum();
    }
}

/// Half-width of the [`Ricker`] truncation window, in periods T_p = 2π/ω_p.
///
/// At β = ω_p·1.5·T_p/2 = 1.5π ≈ 4.71 the symmetric wavelet is
/// ≈ 9.8·10⁻⁹·a and the antisymmetric one ≈ 4.5·10⁻⁸·a, and both decay
/// monotonically beyond, so the truncation error is < 10⁻⁶·a.
pub const RICKER_HALF_WIDTH_PERIODS: f64 = 1.5;

/// Peak of |β (2β² − 3) e^{−β²}|, used to normalise the antisymmetric
/// Ricker wavelet to peak amplitude a.
///
/// The extremum is at β₁ = √((3 − √6)/2) ≈ 0.524648, where the value is
/// β₁·√6·e^{−β₁²} ≈ 0.975892 (a larger secondary lobe does not exist: the
/// other extremum, at β² = (3 + √6)/2, has magnitude ≈ 0.265).
pub const ANTISYMMETRIC_RICKER_NORM: f64 = 0.975_891_536_384_975_6;

/// Which Ricker wavelet.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RickerKind {
    /// ψ(β) = (1 − 2β²) e^{−β²}: one main positive lobe flanked by two
    /// negative lobes; peak +a at t_s.
    Symmetric,
    /// ψ(β) = β (2β² − 3) e^{−β²} / [`ANTISYMMETRIC_RICKER_NORM`]: the time
    /// derivative of the symmetric wavelet (up to a positive factor),
    /// normalised so that its extreme values are exactly ±a: +a at
    /// β = −β₁, −a at β = +β₁ (β₁ ≈ 0.524648).
    Antisymmetric,
}

/// Ricker (1943) wavelet, the acceleration pulse used for rocking blocks by
/// Vassiliou & Makris (2011, *Earthquake Engng Struct. Dyn.* 40(10)).
///
/// With peak angular frequency ω_p (rad per time unit), period
/// T_p = 2π/ω_p and β = ω_p (t − t_s)/2 (so β² = π² f_p² (t − t_s)²):
///
/// * symmetric: ü_g(t) = a (1 − 2β²) e^{−β²}, i.e.
///   a (1 − ω_p² τ²/2) e^{−ω_p² τ²/4} with τ = t − t_s; zero crossings at
///   τ = ±√2/ω_p;
/// * antisymmetric: ü_g(t) = a β (2β² − 3) e^{−β²} / C with
///   C = [`ANTISYMMETRIC_RICKER_NORM`] ≈ 0.975892; zero crossings at τ = 0
///   and τ = ±√6/ω_p.
///
/// The wavelet is truncated to the window
/// [t_start, t_start + 2·[`RICKER_HALF_WIDTH_PERIODS`]·T_p] centred at
/// t_s = t_start + 1.5 T_p (t_start = 0 by default), so the truncation error
/// is below 10⁻⁶·a. The window ends are kinks (with a jump of order
/// 10⁻⁸·a).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ricker {
    /// Peak amplitude a.
    pub amplitude: f64,
    /// Peak angular frequency ω_p (rad per time unit).
    pub omega_p: f64,
    /// Start of the truncation window (default 0).
    pub start: f64,
    /// Symmetric or antisymmetric.
    pub kind: RickerKind,
}

impl Ricker {
    /// Symmetric Ricker wavelet with peak `amplitude` and peak angular
    /// frequency `omega_p`, window starting at t = 0.
    ///
    /// # Panics
    /// If `amplitude` is not finite or `omega_p` is not positive and finite.
    pub fn symmetric(amplitude: f64, omega_p: f64) -> Self {
        check_amp_freq("Ricker", amplitude, omega_p);
        Ricker {
            amplitude,
            omega_p,
            start: 0.0,
            kind: RickerKind::Symmetric,
        }
    }

    /// Antisymmetric Ricker wavelet with extreme values ±`amplitude` and
    /// peak angular frequency `omega_p`, window starting at t = 0.
    ///
    /// # Panics
    /// If `amplitude` is not finite or `omega_p` is not positive and finite.
    pub fn antisymmetric(amplitude: f64, omega_p: f64) -> Self {
        Ricker {
            kind: RickerKind::Antisymmetric,
            ..Ricker::symmetric(amplitude, omega_p)
        }
    }

    /// The same wavelet with its truncation window starting at `start`.
    ///
    /// # Panics
    /// If `start` is not finite.
    pub fn with_start(self, start: f64) -> Self {
        check_start("Ricker", start);
        Ricker { start, ..self }
    }

    /// Period T_p = 2π/ω_p.
    pub fn period(&self) -> f64 {
        2.0 * PI / self.omega_p
    }

    /// Centre t_s of the wavelet (= start + 1.5 T_p).
    pub fn center(&self) -> f64 {
        self.start + RICKER_HALF_WIDTH_PERIODS * self.period()
    }

    /// The untruncated wavelet.
    #[inline]
    pub fn untruncated(&self, t: f64) -> f64 {
        let b = self.beta(t);
        self.amplitude * self.shape(b) * (-(b * b)).exp()
    }

    /// β = ω_p (t − t_s)/2.
    #[inline]
    fn beta(&self, t: f64) -> f64 {
        0.5 * self.omega_p * (t - self.center())
    }

    /// The polynomial factor of the wavelet at β (without the amplitude).
    #[inline]
    fn shape(&self, b: f64) -> f64 {
        match self.kind {
            RickerKind::Symmetric => 1.0 - 2.0 * b * b,
            RickerKind::Antisymmetric => b * (2.0 * b * b - 3.0) / ANTISYMMETRIC_RICKER_NORM,
        }
    }

    /// Taylor coefficients, in h, of the polynomial factor times the amplitude along
    /// β = b + c h: `a P⁽ʲ⁾(b) cʲ / j!` (degree 2 or 3).
    fn shape_series(&self, b: f64, c: f64) -> [f64; 4] {
        let a = self.amplitude;
        match self.kind {
            RickerKind::Symmetric => [
                a * self.shape(b),
                a * (-4.0 * b * c),
                a * (-2.0 * c * c),
                0.0,
            ],
            RickerKind::Antisymmetric => {
                let n = a / ANTISYMMETRIC_RICKER_NORM;
                [
                    a * self.shape(b),
                    n * (6.0 * b * b - 3.0) * c,
                    n * 6.0 * b * c * c,
                    n * 2.0 * c * c * c,
                ]
            }
        }
    }
}

impl GroundMotion for Ricker {
    fn resolution(&self) -> f64 {
        self.period() / 16.0
    }
    /// The Gaussian's series ([`gaussian_series`]) times the polynomial factor's: one `exp`
    /// and a few products per order.
    fn accel_series(&self, t0: f64, out: &mut [f64]) -> bool {
        if !(t0 >= self.start && t0 < self.end()) {
            out.fill(0.0);
            return true;
        }
        let (b, c) = (self.beta(t0), 0.5 * self.omega_p);
        gaussian_series(b, c, out);
        multiply_by_polynomial(&self.shape_series(b, c), out);
        true
    }
    #[inline]
    fn accel(&self, t: f64) -> f64 {
        if t >= self.start && t <= self.end() {
            self.untruncated(t)
        } else {
            0.0
        }
    }
    fn end(&self) -> f64 {
        self.start + 2.0 * RICKER_HALF_WIDTH_PERIODS * self.period()
    }
    fn next_kink(&self, t: f64) -> Option<f64> {
        support_next_kink(self.start, self.end(), t)
    }
    fn accel_left(&self, t: f64) -> f64 {
        left_limit(self.start, self.end(), t, |t| self.untruncated(t))
    }
    fn accel_right(&self, t: f64) -> f64 {
        right_limit(self.start, self.end(), t, |t| self.untruncated(t))
    }
}

/// Mavroeidis & Papageorgiou (2003) near-fault pulse, *A mathematical
/// representation of near-fault ground motions*, Bull. Seismol. Soc. Am.
/// 93(3), 1099–1131.
///
/// The model is a **velocity** pulse: with τ = t − t₀, Ω = 2π f_p,
///
/// v(t) = (A/2) [1 + cos(Ω τ/γ)] cos(Ω τ + ν)  for |τ| ≤ γ/(2 f_p), 0 otherwise,
///
/// where A is the velocity amplitude, f_p the prevailing frequency, γ > 1
/// the oscillatory character (number of half cycles, roughly), ν the phase
/// (radians) and t₀ the time of the envelope peak. This type provides the
/// **acceleration**, the analytic derivative
///
/// ü_g(t) = −(A Ω / 2) [ (1/γ) sin(Ω τ/γ) cos(Ω τ + ν)
///                        + (1 + cos(Ω τ/γ)) sin(Ω τ + ν) ]
///        = −π f_p A [ (1/γ) sin(Ω τ/γ) cos(Ω τ + ν) + (1 + cos(Ω τ/γ)) sin(Ω τ + ν) ],
///
/// evaluated as the equal sum of three harmonics (sums of angles instead of products), which
/// also gives its Taylor series in closed form.
///
/// Both v and ü_g vanish at the ends τ = ±γ/(2 f_p) (there Ω τ/γ = ±π), so
/// ü_g is continuous; its derivative jumps, and the ends are the kinks.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MavroeidisPapageorgiou {
    /// Velocity amplitude A (velocity units = acceleration units × time units).
    pub amplitude: f64,
    /// Prevailing frequency f_p (Hz, i.e. cycles per time unit).
    pub f_p: f64,
    /// Oscillatory character γ > 1.
    pub gamma: f64,
    /// Phase ν (radians).
    pub nu: f64,
    /// Time t₀ of the envelope peak.
    pub t0: f64,
}

impl MavroeidisPapageorgiou {
    /// MP pulse with velocity amplitude `amplitude`, frequency `f_p`,
    /// oscillatory character `gamma`, phase `nu` (rad), envelope peak at `t0`.
    ///
    /// # Panics
    /// If `f_p` is not positive and finite, `gamma` is not finite and > 1,
    /// or `amplitude`, `nu`, `t0` are not finite.
    pub fn new(amplitude: f64, f_p: f64, gamma: f64, nu: f64, t0: f64) -> Self {
        check_amp_freq("MavroeidisPapageorgiou", amplitude, f_p);
        assert!(
            gamma.is_finite() && gamma > 1.0,
            "MavroeidisPapageorgiou: gamma must be finite and > 1, got {gamma}"
        );
        assert!(
            nu.is_finite(),
            "MavroeidisPapageorgiou: nu must be finite, got {nu}"
        );
        check_start("MavroeidisPapageorgiou", t0);
        MavroeidisPapageorgiou {
            amplitude,
            f_p,
            gamma,
            nu,
            t0,
        }
    }

    /// MP pulse whose support starts at `start`, i.e. t₀ = start + γ/(2 f_p).
    ///
    /// # Panics
    /// As [`new`](Self::new).
    pub fn starting_at(amplitude: f64, f_p: f64, gamma: f64, nu: f64, start: f64) -> Self {
        let mut p = Self::new(amplitude, f_p, gamma, nu, start);
        p.t0 = start + p.half_duration();
        p
    }

    /// Half duration γ/(2 f_p) of the pulse.
    pub fn half_duration(&self) -> f64 {
        self.gamma / (2.0 * self.f_p)
    }

    /// Start t₀ − γ/(2 f_p) of the support.
    pub fn start(&self) -> f64 {
        self.t0 - self.half_duration()
    }

    /// On the closed support, bounded as the kinks are (so the series agrees with `accel` there).
    fn on_support(&self, t: f64) -> bool {
        t >= self.start() && t <= self.end()
    }

    /// ü_g on the support as three harmonics `a sin(φ + ω h)` at h = 0, each as
    /// `(a, ω, (sin φ, cos φ))`: the products of the formula are sums of angles,
    /// ü_g = −(AΩ/2) [sin C + ½(1 + 1/γ) sin(C + E) + ½(1 − 1/γ) sin(C − E)] with C = Ωτ + ν
    /// and E = Ωτ/γ, so that ü_g and its Taylor series are one expression.
    fn harmonics(&self, t: f64) -> [(f64, f64, (f64, f64)); 3] {
        let w = 2.0 * PI * self.f_p;
        let we = w / self.gamma;
        let tau = t - self.t0;
        let (c, e) = (w * tau + self.nu, we * tau);
        let a = -0.5 * self.amplitude * w;
        let r = 1.0 / self.gamma;
        [
            (a, w, c.sin_cos()),
            (0.5 * a * (1.0 + r), w + we, (c + e).sin_cos()),
            (0.5 * a * (1.0 - r), w - we, (c - e).sin_cos()),
        ]
    }

    /// Ground velocity v(t) of the MP model (0 outside the support).
    pub fn velocity(&self, t: f64) -> f64 {
        if !self.on_support(t) {
            return 0.0;
        }
        let w = 2.0 * PI * self.f_p;
        let tau = t - self.t0;
        0.5 * self.amplitude * (1.0 + (w * tau / self.gamma).cos()) * (w * tau + self.nu).cos()
    }
}

impl GroundMotion for MavroeidisPapageorgiou {
    fn resolution(&self) -> f64 {
        1.0 / (16.0 * self.f_p)
    }
    /// The sum of the three [`harmonics`](Self::harmonics)' series: no series products.
    fn accel_series(&self, t0: f64, out: &mut [f64]) -> bool {
        out.fill(0.0);
        if t0 >= self.start() && t0 < self.end() {
            for (a, omega, phase) in self.harmonics(t0) {
                add_harmonic(a, omega, phase, out);
            }
        }
        true
    }
    #[inline]
    fn accel(&self, t: f64) -> f64 {
        if !self.on_support(t) {
            return 0.0;
        }
        self.harmonics(t).iter().map(|(a, _, (s, _))| a * s).sum()
    }
    fn end(&self) -> f64 {
        self.t0 + self.half_duration()
    }
    fn next_kink(&self, t: f64) -> Option<f64> {
        support_next_kink(self.start(), self.end(), t)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: f64, b: f64, tol: f64) -> bool {
        (a - b).abs() <= tol
    }

    #[test]
    fn sine_pulse_values_and_kinks() {
        let (a, w) = (0.3, 4.0);
        let p = SinePulse::new(a, w);
        let tp = 2.0 * PI / w;
        assert!(close(p.accel(tp / 4.0), a, 1e-15));
        assert!(close(p.accel(3.0 * tp / 4.0), -a, 1e-15));
        assert!(close(p.accel(tp / 2.0), 0.0, 1e-15));
        assert!(close(p.accel(0.0), 0.0, 0.0));
        assert!(close(p.accel(tp), 0.0, 1e-15));
        assert_eq!(p.accel(-1e-9), 0.0);
        assert_eq!(p.accel(tp * (1.0 + 1e-12)), 0.0);
        assert_eq!(p.accel(f64::NAN), 0.0);
        assert_eq!(p.end(), tp);
        assert_eq!(p.next_kink(-3.0), Some(0.0));
        assert_eq!(p.next_kink(0.0), Some(tp));
        assert_eq!(p.next_kink(0.5 * tp), Some(tp));
        assert_eq!(p.next_kink(tp), None);
        assert_eq!(p.kinks(-1.0, 100.0).collect::<Vec<_>>(), vec![0.0, tp]);

        let q = p.with_start(2.0);
        assert!(close(q.accel(2.0 + tp / 4.0), a, 1e-15));
        assert_eq!(q.accel(1.9), 0.0);
        assert_eq!(q.next_kink(0.0), Some(2.0));
        assert_eq!(q.next_kink(2.0), Some(2.0 + tp));
        assert_eq!(q.end(), 2.0 + tp);
    }

    #[test]
    fn cosine_pulse_jumps() {
        let (a, w) = (-0.7, PI); // period 2
        let p = CosinePulse::new(a, w).with_start(1.0);
        assert!(close(p.accel(1.0), a, 1e-15));
        assert!(close(p.accel(2.0), -a, 1e-15));
        assert!(close(p.accel(1.5), 0.0, 1e-15));
        assert!(close(p.accel(3.0), a, 1e-15));
        assert_eq!(p.accel(0.999), 0.0);
        assert_eq!(p.accel(3.001), 0.0);
        assert_eq!(p.accel_left(1.0), 0.0);
        assert!(close(p.accel_right(1.0), a, 1e-15));
        assert!(close(p.accel_left(3.0), a, 1e-15));
        assert_eq!(p.accel_right(3.0), 0.0);
        assert!(close(p.accel_left(2.0), p.accel_right(2.0), 0.0));
        assert_eq!(p.kinks(0.0, 10.0).collect::<Vec<_>>(), vec![1.0, 3.0]);
        assert_eq!(p.end(), 3.0);
    }

    #[test]
    fn ricker_symmetric() {
        let (a, w) = (0.4, 2.0 * PI * 1.5);
        let r = Ricker::symmetric(a, w).with_start(0.5);
        let tp = 2.0 * PI / w;
        let ts = r.center();
        assert!(close(ts, 0.5 + 1.5 * tp, 1e-15));
        assert!(close(r.accel(ts), a, 1e-15)); // peak
        for z in [ts - 2f64.sqrt() / w, ts + 2f64.sqrt() / w] {
            assert!(close(r.accel(z), 0.0, 1e-15), "zero crossing");
        }
        // minima at β² = 3/2: value −2 e^{−3/2} a
        let tm = ts + 2.0 * 1.5f64.sqrt() / w;
        assert!(close(r.accel(tm), -2.0 * (-1.5f64).exp() * a, 1e-15));
        // symmetry
        assert!(close(r.accel(ts - 0.1), r.accel(ts + 0.1), 1e-15));
        // window and kinks
        assert_eq!(r.end(), 0.5 + 3.0 * tp);
        assert_eq!(r.accel(0.49), 0.0);
        assert_eq!(r.accel(r.end() + 1e-9), 0.0);
        assert_eq!(r.kinks(0.0, 100.0).collect::<Vec<_>>(), vec![0.5, r.end()]);
        // truncation error < 1e-6 a: the tail outside the window is tiny
        for k in 0..200 {
            let t = r.end() + k as f64 * 0.01 * tp;
            assert!(r.untruncated(t).abs() < 1e-6 * a);
            let t = r.start - k as f64 * 0.01 * tp;
            assert!(r.untruncated(t).abs() < 1e-6 * a);
        }
        assert!(r.accel_right(r.start).abs() < 1e-6 * a);
        assert_eq!(r.accel_left(r.start), 0.0);
    }

    #[test]
    fn ricker_antisymmetric() {
        let b1 = ((3.0 - 6f64.sqrt()) / 2.0).sqrt();
        let norm = b1 * 6f64.sqrt() * (-b1 * b1).exp();
        assert!(close(norm, ANTISYMMETRIC_RICKER_NORM, 1e-15));

        let (a, w) = (1.3, 3.0);
        let r = Ricker::antisymmetric(a, w);
        let ts = r.center();
        let tpk = 2.0 * b1 / w;
        assert!(close(r.accel(ts - tpk), a, 1e-14));
        assert!(close(r.accel(ts + tpk), -a, 1e-14));
        // it really is the maximum: scan
        let n = 20_000;
        let mut max = 0.0f64;
        for i in 0..=n {
            let t = r.end() * i as f64 / n as f64;
            max = max.max(r.accel(t).abs());
        }
        assert!(max <= a * (1.0 + 1e-12) && max > a * (1.0 - 1e-6));
        // zero crossings
        assert!(close(r.accel(ts), 0.0, 1e-15));
        let z = 2.0 * 1.5f64.sqrt() / w;
        assert!(close(r.accel(ts + z), 0.0, 1e-14));
        assert!(close(r.accel(ts - z), 0.0, 1e-14));
        // antisymmetry
        assert!(close(r.accel(ts - 0.3), -r.accel(ts + 0.3), 1e-14));
        // proportional to the time derivative of the symmetric wavelet
        let s = Ricker::symmetric(a, w);
        let h = 1e-5;
        let t = ts + 0.2;
        let ds = (s.accel(t + h) - s.accel(t - h)) / (2.0 * h);
        // d/dt[a(1-2β²)e^{-β²}] = a (ω/2) 2β(2β²-3) e^{-β²} = ω C · antisymmetric
        assert!(close(ds / r.accel(t), w * ANTISYMMETRIC_RICKER_NORM, 1e-6));
        // truncation
        assert!(r.untruncated(r.end()).abs() < 1e-6 * a);
        assert!(r.untruncated(r.start).abs() < 1e-6 * a);
        assert_eq!(r.kinks(-1.0, 1e9).count(), 2);
    }

    #[test]
    fn mp_support_and_values() {
        let p = MavroeidisPapageorgiou::new(0.8, 0.5, 2.5, 0.3, 4.0);
        let half = 2.5 / (2.0 * 0.5);
        assert_eq!(p.half_duration(), half);
        assert_eq!(p.start(), 4.0 - half);
        assert_eq!(p.end(), 4.0 + half);
        assert_eq!(
            p.kinks(0.0, 100.0).collect::<Vec<_>>(),
            vec![4.0 - half, 4.0 + half]
        );
        assert_eq!(p.next_kink(4.0), Some(4.0 + half));
        // at t0: v = A cos(ν)
        assert!(close(p.velocity(4.0), 0.8 * 0.3f64.cos(), 1e-15));
        // at t0: a = -π f_p A [0 + 2 sin ν]
        assert!(close(
            p.accel(4.0),
            -PI * 0.5 * 0.8 * 2.0 * 0.3f64.sin(),
            1e-14
        ));
        // continuous (zero) at the ends, zero outside
        assert!(p.accel(p.start()).abs() < 1e-14 && p.accel(p.end()).abs() < 1e-14);
        assert!(p.velocity(p.start()).abs() < 1e-14);
        assert_eq!(p.accel(p.end() + 1e-9), 0.0);
        assert_eq!(p.accel(p.start() - 1e-9), 0.0);

        let q = MavroeidisPapageorgiou::starting_at(1.0, 2.0, 1.5, 0.0, 0.0);
        assert!(close(q.start(), 0.0, 1e-15));
        assert_eq!(q.next_kink(-1.0), Some(q.start()));
    }

    #[test]
    fn mp_accel_matches_finite_difference_of_velocity() {
        let cases = [
            (1.0, 0.5, 2.0, 0.0, 3.0),
            (0.35, 1.2, 1.8, PI / 2.0, 1.0),
            (2.0, 0.3, 3.5, -1.0, 10.0),
            (0.1, 4.0, 1.01, 2.5, 0.2),
        ];
        for (amp, fp, g, nu, t0) in cases {
            let p = MavroeidisPapageorgiou::new(amp, fp, g, nu, t0);
            let peak = 2.0 * PI * fp * amp; // scale of |a|
            let h = 1e-5 / fp;
            let n = 400;
            for i in 1..n {
                let t = p.start() + (p.end() - p.start()) * i as f64 / n as f64;
                let fd = (p.velocity(t + h) - p.velocity(t - h)) / (2.0 * h);
                let an = p.accel(t);
                assert!(
                    (fd - an).abs() <= 1e-6 * peak.max(an.abs()),
                    "t={t}: fd={fd} analytic={an}"
                );
            }
        }
    }

    #[test]
    #[should_panic(expected = "gamma")]
    fn mp_rejects_gamma_le_1() {
        let _ = MavroeidisPapageorgiou::new(1.0, 1.0, 1.0, 0.0, 0.0);
    }

    #[test]
    #[should_panic(expected = "frequency")]
    fn sine_rejects_zero_omega() {
        let _ = SinePulse::new(1.0, 0.0);
    }
}
