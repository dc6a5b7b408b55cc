//! Horizontal ground-motion excitations ü_g(t) for rocking-structure simulations.
//!
//! The crate is **unit-agnostic**: every motion is a plain function of time
//! and the caller decides what the numbers mean — seconds and m/s², or the
//! dimensionless time τ = p·t with accelerations in units of g. (The one
//! exception is a record file, whose samples are in the unit the file states;
//! [`AccelUnit`] holds the one units model that converts them for a structure,
//! and [`At2Record::to_record_si`] applies it.)
//!
//! # Kinks
//!
//! A rocking simulator integrates a non-smooth ODE; an adaptive integrator
//! that steps *across* a point where ü_g or one of its derivatives jumps
//! loses its error control. Every motion therefore reports its **kinks**
//! through [`GroundMotion::next_kink`]: the start and end of a pulse, every
//! sample of a piecewise-linear record. The intended integration loop is
//!
//! ```text
//! t = t0
//! loop:
//!     t_stop = min(next_kink(t), t_final)      // never step past a kink
//!     integrate [t, t_stop], evaluating accel_right(t) at the left end,
//!                            accel_left(t_stop) at the right end,
//!                            accel(s) strictly inside
//!     t = t_stop
//! ```
//!
//! At a kink where ü_g itself jumps (the ends of a [`CosinePulse`], the ends
//! of a [`Record`], the truncation window of a [`Ricker`]) the one-sided
//! limits [`GroundMotion::accel_left`] / [`GroundMotion::accel_right`] give
//! the values on either side; [`GroundMotion::accel`] itself returns the
//! value of the formula on the *closed* support (so a record is exact at its
//! last sample).
//!
//! # Motions
//!
//! | type | ü_g(t) |
//! |------|--------|
//! | [`NoMotion`] | 0 (free vibration) |
//! | [`SinePulse`] | one cycle a·sin ω(t−t_s) |
//! | [`CosinePulse`] | one cycle a·cos ω(t−t_s) (jumps at both ends) |
//! | [`Ricker`] | symmetric / antisymmetric Ricker wavelet, truncated |
//! | [`MavroeidisPapageorgiou`] | derivative of the MP (2003) velocity pulse |
//! | [`Record`] | piecewise-linear, equally spaced samples |
//! | [`Scaled`] | factor × any motion |
//!
//! # Taylor series
//!
//! Every motion gives the Taylor coefficients of the piece that starts at a
//! time t0 ([`GroundMotion::accel_series`]), to any order, for Taylor-series
//! integrators (which, like the others, never step past a kink): without
//! allocating, and with a fixed number of transcendental calls whatever the
//! order. Sine and cosine pulses: closed form, one `sin_cos`; the
//! Mavroeidis–Papageorgiou pulse: the same for each of the three harmonics its
//! products of sines and cosines sum to; Ricker wavelets: the Gaussian's
//! coefficients from one `exp` by the recurrence of its linear ODE
//! g' = −2cβ g, times the polynomial factor's; records: the line of the
//! sample interval (every sample is a kink, so a step ends at the next one).
//!
//! All implement the [`GroundMotion`] trait (use it as a generic bound for
//! static dispatch); the closed enum [`Excitation`] wraps them when the kind
//! of motion is only known at run time — its methods are a `match`, still
//! without dynamic dispatch.
//!
//! # Example
//!
//! ```
//! use rocking_motion::{parse_at2, Excitation, GroundMotion, SinePulse};
//! use std::f64::consts::PI;
//!
//! // The paper's one-sine pulse: amplitude 0.5 (units of g), ω = 2π rad/s.
//! let pulse = SinePulse::new(0.5, 2.0 * PI);
//! assert!((pulse.accel(0.25) - 0.5).abs() < 1e-12); // quarter period: peak
//! assert_eq!(pulse.accel(1.5), 0.0); // after the single cycle
//! assert_eq!(pulse.end(), 1.0);
//! let kinks: Vec<f64> = pulse.kinks(-1.0, 10.0).collect();
//! assert_eq!(kinks, vec![0.0, 1.0]);
//!
//! // A (tiny) PEER AT2 record: 4 header lines, then samples in g.
//! let text = "PEER NGA STRONG MOTION DATABASE RECORD\n\
//!             SOME EVENT, SOME STATION, 090\n\
//!             ACCELERATION TIME SERIES IN UNITS OF G\n\
//!             NPTS=     4, DT=   .0100 SEC\n\
//!             0.0  0.1  -0.2  0.0\n";
//! let at2 = parse_at2(text, "demo.AT2")?;
//! assert_eq!((at2.npts, at2.dt), (4, 0.01));
//! // In g: felt as the structure's g (here standard gravity), in m/s².
//! let record = at2.to_record_si(rocking_motion::STANDARD_GRAVITY);
//! assert!((record.accel(0.015) - (-0.05 * 9.80665)).abs() < 1e-12); // midpoint
//! assert_eq!(record.next_kink(0.015), Some(0.02));
//!
//! // Mixed collections via the enum (static dispatch through `match`).
//! let motions: Vec<Excitation> = vec![pulse.into(), record.into(), Excitation::None];
//! assert_eq!(motions[2].accel(0.3), 0.0);
//! # Ok::<(), rocking_motion::MotionError>(())
//! ```
#![warn(missing_docs)]
#![forbid(unsafe_code)]

mod at2;
mod error;
pub mod formats;
mod input;
pub mod intensity;
mod pulses;
mod record;
mod units;

pub use at2::{parse_at2, read_at2, At2Record};
pub use error::{short_number, MotionError, ParameterError};
pub use formats::{parse_record, read_record, record_files_in, RecordFormat};
pub use input::MIN_DT;
pub use pulses::{
    CosinePulse, MavroeidisPapageorgiou, Ricker, RickerKind, SinePulse, ANTISYMMETRIC_RICKER_NORM,
    RICKER_HALF_WIDTH_PERIODS,
};
pub use record::Record;
pub use units::AccelUnit;

/// Standard gravity g₀ = 9.80665 m/s² (exact, CGPM 1901): the one value of g, for a structure
/// that does not set its own and for the intensity measures (Arias).
pub const STANDARD_GRAVITY: f64 = 9.80665;

/// A horizontal ground acceleration history ü_g(t).
///
/// Implementations must be cheap to evaluate (no allocation, O(1) per call)
/// because the integrator calls [`accel`](Self::accel) at every stage.
pub trait GroundMotion {
    /// Ground acceleration at time `t`; 0 outside the support.
    ///
    /// On the closed support the defining formula is used, so at a kink
    /// where ü_g jumps this is the limit from *inside* the support. Use
    /// [`accel_left`](Self::accel_left) / [`accel_right`](Self::accel_right)
    /// for one-sided values at kinks. A NaN time gives 0.
    fn accel(&self, t: f64) -> f64;

    /// Time after which the acceleration is zero for good.
    fn end(&self) -> f64;

    /// The smallest kink time strictly greater than `t`, or `None` if there
    /// is none (or `t` is NaN). A kink is a time where ü_g or one of its
    /// derivatives jumps.
    fn next_kink(&self, t: f64) -> Option<f64>;

    /// Left limit lim_{s↑t} ü_g(s). Equals [`accel`](Self::accel) except at
    /// jumps of ü_g; the default implementation is for continuous motions.
    fn accel_left(&self, t: f64) -> f64 {
        self.accel(t)
    }

    /// Right limit lim_{s↓t} ü_g(s). Equals [`accel`](Self::accel) except at
    /// jumps of ü_g; the default implementation is for continuous motions.
    fn accel_right(&self, t: f64) -> f64 {
        self.accel(t)
    }

    /// The longest time step that resolves the motion between two kinks: a
    /// sixteenth of the shortest period of a smooth pulse, infinite for a
    /// motion that is linear between kinks (a record). A simulator uses it to
    /// bound its steps where nothing else does (a rigid body in full contact),
    /// so that no excursion of the excitation falls between two steps.
    fn resolution(&self) -> f64 {
        f64::INFINITY
    }

    /// Taylor coefficients `out[k] = ü_g⁽ᵏ⁾(t0⁺) / k!` of the smooth piece of the motion that
    /// starts at `t0` and lasts to the next kink, for as many orders as `out` holds, for
    /// Taylor-series integrators; `false` when the motion cannot give them exactly (every motion
    /// of this crate can). The default serves motions linear between kinks (infinite
    /// [`resolution`](Self::resolution)): the value from the right at `t0` and the slope to the
    /// left limit at the next kink.
    fn accel_series(&self, t0: f64, out: &mut [f64]) -> bool {
        if self.resolution() != f64::INFINITY || out.is_empty() {
            return false;
        }
        out.fill(0.0);
        out[0] = self.accel_right(t0);
        if let (Some(k), Some(slope)) = (self.next_kink(t0), out.get_mut(1)) {
            *slope = (self.accel_left(k) - self.accel_right(t0)) / (k - t0);
        }
        true
    }

    /// Iterator over the kinks in the open-closed interval `(from, to]`, in
    /// increasing order.
    fn kinks(&self, from: f64, to: f64) -> Kinks<'_, Self>
    where
        Self: Sized,
    {
        Kinks {
            motion: self,
            t: from,
            to,
        }
    }

    /// This motion multiplied by `factor`.
    fn scaled(self, factor: f64) -> Scaled<Self>
    where
        Self: Sized,
    {
        Scaled::new(self, factor)
    }
}

/// Iterator over the kinks of a motion in `(from, to]`; see
/// [`GroundMotion::kinks`].
#[derive(Debug, Clone)]
pub struct Kinks<'a, M: GroundMotion + ?Sized> {
    motion: &'a M,
    t: f64,
    to: f64,
}

impl<M: GroundMotion + ?Sized> Iterator for Kinks<'_, M> {
    type Item = f64;
    fn next(&mut self) -> Option<f64> {
        let k = self.motion.next_kink(self.t)?;
        if k > self.to {
            self.t = f64::INFINITY;
            return None;
        }
        self.t = k;
        Some(k)
    }
}

impl<M: GroundMotion + ?Sized> GroundMotion for &M {
    fn accel(&self, t: f64) -> f64 {
        (**self).accel(t)
    }
    fn end(&self) -> f64 {
        (**self).end()
    }
    fn next_kink(&self, t: f64) -> Option<f64> {
        (**self).next_kink(t)
    }
    fn accel_left(&self, t: f64) -> f64 {
        (**self).accel_left(t)
    }
    fn accel_right(&self, t: f64) -> f64 {
        (**self).accel_right(t)
    }
    fn resolution(&self) -> f64 {
        (**self).resolution()
    }
    fn accel_series(&self, t0: f64, out: &mut [f64]) -> bool {
        (**self).accel_series(t0, out)
    }
}

impl<M: GroundMotion + ?Sized> GroundMotion for Box<M> {
    fn accel(&self, t: f64) -> f64 {
        (**self).accel(t)
    }
    fn end(&self) -> f64 {
        (**self).end()
    }
    fn next_kink(&self, t: f64) -> Option<f64> {
        (**self).next_kink(t)
    }
    fn accel_left(&self, t: f64) -> f64 {
        (**self).accel_left(t)
    }
    fn accel_right(&self, t: f64) -> f64 {
        (**self).accel_right(t)
    }
    fn resolution(&self) -> f64 {
        (**self).resolution()
    }
    fn accel_series(&self, t0: f64, out: &mut [f64]) -> bool {
        (**self).accel_series(t0, out)
    }
}

/// No ground motion: ü_g ≡ 0, for free-vibration runs. `end()` is 0 and
/// there are no kinks.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct NoMotion;

impl GroundMotion for NoMotion {
    fn accel(&self, _t: f64) -> f64 {
        0.0
    }
    fn end(&self) -> f64 {
        0.0
    }
    fn next_kink(&self, _t: f64) -> Option<f64> {
        None
    }
}

/// `factor × inner`: rescales any motion (e.g. to a target PGA, or from g to
/// m/s²). Kinks and `end` are those of `inner`.
#[derive(Debug, Clone, PartialEq)]
pub struct Scaled<M> {
    /// The motion being scaled.
    pub inner: M,
    /// Amplitude factor.
    pub factor: f64,
}

impl<M> Scaled<M> {
    /// Wrap `inner`, multiplying its acceleration by `factor`.
    pub fn new(inner: M, factor: f64) -> Self {
        Scaled { inner, factor }
    }
}

impl<M: GroundMotion> GroundMotion for Scaled<M> {
    fn accel(&self, t: f64) -> f64 {
        self.factor * self.inner.accel(t)
    }
    fn end(&self) -> f64 {
        self.inner.end()
    }
    fn next_kink(&self, t: f64) -> Option<f64> {
        self.inner.next_kink(t)
    }
    fn accel_left(&self, t: f64) -> f64 {
        self.factor * self.inner.accel_left(t)
    }
    fn accel_right(&self, t: f64) -> f64 {
        self.factor * self.inner.accel_right(t)
    }
    fn resolution(&self) -> f64 {
        self.inner.resolution()
    }
    fn accel_series(&self, t0: f64, out: &mut [f64]) -> bool {
        let ok = self.inner.accel_series(t0, out);
        out.iter_mut().for_each(|c| *c *= self.factor);
        ok
    }
}

/// Closed set of all motions in this crate, for when the kind is chosen at
/// run time (configuration files, parameter sweeps). Dispatch is a `match`.
#[derive(Debug, Clone, PartialEq, Default)]
pub enum Excitation {
    /// No ground motion (free vibration).
    #[default]
    None,
    /// One-cycle sine pulse.
    Sine(SinePulse),
    /// One-cycle cosine pulse.
    Cosine(CosinePulse),
    /// Symmetric or antisymmetric Ricker wavelet.
    Ricker(Ricker),
    /// Mavroeidis–Papageorgiou pulse.
    MavroeidisPapageorgiou(MavroeidisPapageorgiou),
    /// Sampled record.
    Record(Record),
    /// A scaled excitation.
    Scaled(Box<Scaled<Excitation>>),
}

impl Excitation {
    /// This excitation multiplied by `factor` (boxed, so the enum stays
    /// small).
    pub fn scale(self, factor: f64) -> Excitation {
        Excitation::Scaled(Box::new(Scaled::new(self, factor)))
    }
}

macro_rules! dispatch {
    ($self:ident, $m:ident => $e:expr, $none:expr) => {
        match $self {
            Excitation::None => $none,
            Excitation::Sine($m) => $e,
            Excitation::Cosine($m) => $e,
            Excitation::Ricker($m) => $e,
            Excitation::MavroeidisPapageorgiou($m) => $e,
            Excitation::Record($m) => $e,
            Excitation::Scaled($m) => $e,
        }
    };
}

impl GroundMotion for Excitation {
    fn accel(&self, t: f64) -> f64 {
        dispatch!(self, m => m.accel(t), 0.0)
    }
    fn end(&self) -> f64 {
        dispatch!(self, m => m.end(), 0.0)
    }
    fn next_kink(&self, t: f64) -> Option<f64> {
        dispatch!(self, m => m.next_kink(t), None)
    }
    fn accel_left(&self, t: f64) -> f64 {
        dispatch!(self, m => m.accel_left(t), 0.0)
    }
    fn accel_right(&self, t: f64) -> f64 {
        dispatch!(self, m => m.accel_right(t), 0.0)
    }
    fn resolution(&self) -> f64 {
        dispatch!(self, m => m.resolution(), f64::INFINITY)
    }
    fn accel_series(&self, t0: f64, out: &mut [f64]) -> bool {
        dispatch!(self, m => m.accel_series(t0, out), NoMotion.accel_series(t0, out))
    }
}

impl From<NoMotion> for Excitation {
    fn from(_: NoMotion) -> Self {
        Excitation::None
    }
}
impl From<SinePulse> for Excitation {
    fn from(m: SinePulse) -> Self {
        Excitation::Sine(m)
    }
}
impl From<CosinePulse> for Excitation {
    fn from(m: CosinePulse) -> Self {
        Excitation::Cosine(m)
    }
}
impl From<Ricker> for Excitation {
    fn from(m: Ricker) -> Self {
        Excitation::Ricker(m)
    }
}
impl From<MavroeidisPapageorgiou> for Excitation {
    fn from(m: MavroeidisPapageorgiou) -> Self {
        Excitation::MavroeidisPapageorgiou(m)
    }
}
impl From<Record> for Excitation {
    fn from(m: Record) -> Self {
        Excitation::Record(m)
    }
}
impl From<Scaled<Excitation>> for Excitation {
    fn from(m: Scaled<Excitation>) -> Self {
        Excitation::Scaled(Box::new(m))
    }
}

/// Kinks of a motion supported on the closed interval `[start, end]`.
pub(crate) fn support_next_kink(start: f64, end: f64, t: f64) -> Option<f64> {
    if t < start {
        Some(start)
    } else if t < end {
        Some(end)
    } else {
        None // also for NaN
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    #[test]
    fn no_motion() {
        let m = NoMotion;
        assert_eq!(m.accel(1.0), 0.0);
        assert_eq!(m.end(), 0.0);
        assert_eq!(m.next_kink(-5.0), None);
        assert_eq!(Excitation::None.next_kink(-5.0), None);
        assert_eq!(Excitation::from(NoMotion).accel(0.0), 0.0);
    }

    #[test]
    fn scaled_and_enum() {
        let s = SinePulse::new(1.0, PI).scaled(3.0);
        assert!((s.accel(0.5) - 3.0).abs() < 1e-12);
        assert_eq!(s.end(), 2.0);
        assert_eq!(s.kinks(-1.0, 5.0).collect::<Vec<_>>(), vec![0.0, 2.0]);
        let e = Excitation::from(CosinePulse::new(2.0, PI)).scale(-0.5);
        assert!((e.accel(0.0) + 1.0).abs() < 1e-12);
        assert_eq!(e.accel_left(0.0), 0.0);
        assert!((e.accel_right(0.0) + 1.0).abs() < 1e-12);
        assert_eq!(e.end(), 2.0);
        assert_eq!(e.next_kink(0.0), Some(2.0));
        // trait objects and references work too
        let b: Box<dyn GroundMotion> = Box::new(SinePulse::new(1.0, PI));
        assert_eq!(b.next_kink(0.0), Some(2.0));
        let r = &e;
        assert_eq!(r.end(), 2.0);
    }

    #[test]
    fn kinks_iterator_bounds() {
        let s = SinePulse::new(1.0, PI).with_start(1.0); // support [1, 3]
        assert_eq!(s.kinks(0.0, 2.0).collect::<Vec<_>>(), vec![1.0]);
        assert_eq!(s.kinks(1.0, 3.0).collect::<Vec<_>>(), vec![3.0]);
        assert_eq!(s.kinks(3.0, 9.0).count(), 0);
        assert_eq!(s.next_kink(f64::NAN), None);
    }
}
