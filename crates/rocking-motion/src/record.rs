//! Piecewise-linear sampled records.

use crate::{GroundMotion, MotionError, ParameterError};

/// A sampled acceleration history: piecewise-linear interpolation between
/// equally spaced samples `samples[k]` at t_k = k·dt, multiplied by `scale`.
///
/// ü_g is 0 before t = 0 and after the last sample t_{n−1} = (n−1)·dt
/// (= [`end`](GroundMotion::end)); on the closed interval [0, (n−1)·dt] it
/// interpolates, so it is exact at every sample including the last one.
/// Every sample time is a kink (the slope changes); at t = 0 and at the end
/// ü_g also jumps unless the first/last sample is 0 — see
/// [`accel_left`](GroundMotion::accel_left) and
/// [`accel_right`](GroundMotion::accel_right).
///
/// Because the samples are equally spaced the segment is found by a
/// division, so [`accel`](GroundMotion::accel) and
/// [`next_kink`](GroundMotion::next_kink) are O(1) for queries in *any*
/// order, never allocate, and need no interior mutability (the type is
/// `Sync` and can be shared between threads running parallel simulations).
#[derive(Debug, Clone, PartialEq)]
pub struct Record {
    dt: f64,
    samples: Vec<f64>,
    scale: f64,
}

impl Record {
    /// Record with time step `dt` and the given samples, scale factor 1.
    ///
    /// # Errors
    /// [`MotionError::InvalidParameter`] if `dt` is not positive and finite,
    /// `samples` is empty, the duration (n − 1)·dt overflows, or a sample is not finite.
    pub fn new(dt: f64, samples: Vec<f64>) -> Result<Self, MotionError> {
        if !(dt.is_finite() && dt > 0.0) {
            return Err(ParameterError::RecordDt { dt }.into());
        }
        if samples.is_empty() {
            return Err(ParameterError::RecordEmpty.into());
        }
        if !((samples.len() - 1) as f64 * dt).is_finite() {
            return Err(ParameterError::RecordDuration {
                samples: samples.len(),
                dt,
            }
            .into());
        }
        if let Some(k) = samples.iter().position(|x| !x.is_finite()) {
            return Err(ParameterError::RecordSample {
                index: k,
                value: samples[k],
            }
            .into());
        }
        Ok(Record {
            dt,
            samples,
            scale: 1.0,
        })
    }

    /// The same record with scale factor `scale` (replacing the old one).
    ///
    /// # Panics
    /// If `scale` is not finite.
    pub fn with_scale(self, scale: f64) -> Self {
        assert!(
            scale.is_finite(),
            "Record: scale must be finite, got {scale}"
        );
        Record { scale, ..self }
    }

    /// Time step between samples.
    pub fn dt(&self) -> f64 {
        self.dt
    }

    /// The raw (unscaled) samples.
    pub fn samples(&self) -> &[f64] {
        &self.samples
    }

    /// Scale factor applied to the samples.
    pub fn scale(&self) -> f64 {
        self.scale
    }

    /// Number of samples.
    pub fn len(&self) -> usize {
        self.samples.len()
    }

    /// Always `false` (a record has at least one sample); provided for
    /// symmetry with [`len`](Self::len).
    pub fn is_empty(&self) -> bool {
        self.samples.is_empty()
    }

    /// Time of sample `k`, computed as `k as f64 * dt` (the same expression
    /// used for kinks and [`end`](GroundMotion::end)).
    #[inline]
    pub fn time_of(&self, k: usize) -> f64 {
        k as f64 * self.dt
    }

    /// The index of the first sample after `t`, `None` from the last one on (or for a NaN).
    fn next_sample(&self, t: f64) -> Option<usize> {
        if t.is_nan() {
            return None;
        }
        if t < 0.0 {
            return Some(0);
        }
        let n = self.samples.len();
        // The smallest k with time_of(k) > t, from one division: the roundings of t/dt and of
        // k·dt (relative 2⁻⁵³ each) put the guess at most one sample off, either way, below
        // 2⁵¹ samples. (Search loops here were vectorised into a costly prologue for the one
        // step they take: 12 % of a Taylor step on a record.)
        let mut k = ((t / self.dt) as usize).saturating_add(1).min(n);
        if k > 0 && self.time_of(k - 1) > t {
            k -= 1;
        } else if k < n && self.time_of(k) <= t {
            k += 1;
        }
        (k < n).then_some(k)
    }

    /// Largest |scaled sample| (peak ground acceleration).
    pub fn peak(&self) -> f64 {
        self.samples.iter().fold(0.0f64, |m, x| m.max(x.abs())) * self.scale.abs()
    }
}

impl GroundMotion for Record {
    #[inline]
    fn accel(&self, t: f64) -> f64 {
        let n = self.samples.len();
        // also rejects NaN
        if !(t >= 0.0 && t <= self.end()) {
            return 0.0;
        }
        let x = t / self.dt;
        let i = x as usize; // floor, since x >= 0 (saturating)
        if i >= n - 1 {
            return self.scale * self.samples[n - 1];
        }
        let f = x - i as f64;
        let (y0, y1) = (self.samples[i], self.samples[i + 1]);
        self.scale * (y0 + f * (y1 - y0))
    }

    fn end(&self) -> f64 {
        self.time_of(self.samples.len() - 1)
    }

    fn next_kink(&self, t: f64) -> Option<f64> {
        self.next_sample(t).map(|k| self.time_of(k))
    }

    /// The line of the sample interval that starts at or before `t0`: the interpolated value
    /// and the interval's own slope. (The trait's default takes the slope from two values,
    /// which loses digits as `t0` nears the next sample, where an event can end a step.)
    fn accel_series(&self, t0: f64, out: &mut [f64]) -> bool {
        out.fill(0.0);
        let Some(k) = self.next_sample(t0).filter(|&k| k > 0) else {
            return true; // before the record or from its end on
        };
        if let Some(value) = out.first_mut() {
            *value = self.accel_right(t0);
        }
        if let Some(slope) = out.get_mut(1) {
            *slope = self.scale * (self.samples[k] - self.samples[k - 1]) / self.dt;
        }
        true
    }

    fn accel_left(&self, t: f64) -> f64 {
        if t <= 0.0 {
            0.0
        } else {
            self.accel(t)
        }
    }

    fn accel_right(&self, t: f64) -> f64 {
        if t >= self.end() {
            0.0
        } else {
            self.accel(t)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rec() -> Record {
        Record::new(0.1, vec![1.0, 3.0, -2.0, 0.5, 4.0]).unwrap()
    }

    #[test]
    fn exact_at_samples_and_midpoints() {
        let r = rec().with_scale(2.0);
        let s = [1.0, 3.0, -2.0, 0.5, 4.0];
        for (k, y) in s.iter().enumerate() {
            let t = r.time_of(k);
            assert!((r.accel(t) - 2.0 * y).abs() < 1e-12, "sample {k}");
        }
        for k in 0..4 {
            let t = (k as f64 + 0.5) * 0.1;
            let mid = 0.5 * (s[k] + s[k + 1]);
            assert!((r.accel(t) - 2.0 * mid).abs() < 1e-12, "midpoint {k}");
        }
        // quarter point
        assert!((r.accel(0.125) - 2.0 * (3.0 - 0.25 * 5.0)).abs() < 1e-12);
        assert_eq!(r.accel(-1e-12), 0.0);
        assert_eq!(r.accel(0.4 + 1e-9), 0.0);
        assert_eq!(r.accel(f64::NAN), 0.0);
        assert_eq!(r.accel(f64::INFINITY), 0.0);
        assert_eq!(r.end(), 4.0 * 0.1);
        assert_eq!(r.peak(), 8.0);
    }

    #[test]
    fn any_query_order() {
        let r = rec();
        // reference: search for the segment by a linear scan
        let reference = |t: f64| {
            let s = r.samples();
            (0..s.len() - 1)
                .find(|&i| t >= r.time_of(i) && t <= r.time_of(i + 1))
                .map_or(0.0, |i| {
                    let f = (t - r.time_of(i)) / r.dt();
                    s[i] + f * (s[i + 1] - s[i])
                })
        };
        // backwards, jumping around, repeated
        let ts = [0.4, 0.35, 0.05, 0.39, 0.0, 0.2, 0.11, 0.07, 0.11, -0.1, 0.5];
        for t in ts {
            assert!((r.accel(t) - reference(t)).abs() < 1e-12, "t={t}");
        }
    }

    #[test]
    fn one_sided_limits() {
        let r = rec();
        assert_eq!(r.accel_left(0.0), 0.0);
        assert_eq!(r.accel_right(0.0), 1.0);
        assert_eq!(r.accel_left(r.end()), 4.0);
        assert_eq!(r.accel_right(r.end()), 0.0);
        assert_eq!(r.accel_left(0.15), r.accel_right(0.15));
    }

    #[test]
    fn next_kink_is_every_sample() {
        let r = rec();
        assert_eq!(r.next_kink(-5.0), Some(0.0));
        assert_eq!(r.next_kink(0.0), Some(0.1));
        assert_eq!(r.next_kink(0.05), Some(0.1));
        assert_eq!(r.next_kink(r.time_of(1)), Some(r.time_of(2)));
        assert_eq!(r.next_kink(r.time_of(3)), Some(r.end()));
        assert_eq!(r.next_kink(r.end()), None);
        assert_eq!(r.next_kink(1e300), None);
        assert_eq!(r.next_kink(f64::NAN), None);
        let all: Vec<f64> = r.kinks(-1.0, 10.0).collect();
        assert_eq!(all, (0..5).map(|k| r.time_of(k)).collect::<Vec<_>>());
    }

    #[test]
    fn next_kink_long_record_with_awkward_dt() {
        // dt not representable exactly: check strictness and minimality
        let n = 10_000;
        let r = Record::new(0.00244, vec![0.0; n]).unwrap();
        for k in 0..n - 1 {
            let tk = r.time_of(k);
            assert_eq!(r.next_kink(tk), Some(r.time_of(k + 1)), "k={k}");
            let just_below = f64::from_bits(r.time_of(k + 1).to_bits() - 1);
            if just_below > tk {
                assert_eq!(r.next_kink(just_below), Some(r.time_of(k + 1)));
            }
        }
        assert_eq!(r.kinks(-1.0, 1e9).count(), n);
    }

    /// The one-step correction of the guess holds far into a long record, at and just below
    /// every sample time checked, with a step that is not a binary fraction.
    #[test]
    fn next_kink_far_into_a_long_record() {
        let n = 3_000_000;
        let r = Record::new(0.0123, vec![0.0; n]).unwrap();
        for k in (0..n - 1).step_by(997).chain(n - 1000..n - 1) {
            let tk = r.time_of(k);
            assert_eq!(r.next_kink(tk), Some(r.time_of(k + 1)), "k={k}");
            let below = f64::from_bits(r.time_of(k + 1).to_bits() - 1);
            let above = f64::from_bits(tk.to_bits() + 1);
            assert_eq!(r.next_kink(below.max(tk)), Some(r.time_of(k + 1)), "k={k}");
            assert_eq!(r.next_kink(above), Some(r.time_of(k + 1)), "k={k}");
        }
        assert_eq!(r.next_kink(r.end()), None);
        assert_eq!(
            r.next_kink(f64::from_bits(r.end().to_bits() - 1)),
            Some(r.end())
        );
    }

    #[test]
    fn single_sample() {
        let r = Record::new(0.5, vec![2.0]).unwrap();
        assert_eq!(r.end(), 0.0);
        assert_eq!(r.accel(0.0), 2.0);
        assert_eq!(r.accel(0.1), 0.0);
        assert_eq!(r.next_kink(-1.0), Some(0.0));
        assert_eq!(r.next_kink(0.0), None);
    }

    #[test]
    fn invalid_records() {
        assert!(Record::new(0.0, vec![1.0]).is_err());
        assert!(Record::new(-0.1, vec![1.0]).is_err());
        assert!(Record::new(f64::NAN, vec![1.0]).is_err());
        assert!(Record::new(0.1, vec![]).is_err());
        assert!(Record::new(1e308, vec![0.0; 3]).is_err());
        assert!(Record::new(1e308, vec![0.0]).is_ok());
        let e = Record::new(0.1, vec![1.0, f64::INFINITY]).unwrap_err();
        assert!(e.to_string().contains("index 1"), "{e}");
    }
}
