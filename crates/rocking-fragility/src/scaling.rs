//! Scaling a record to a target intensity: every IM used here is linear in
//! the acceleration, so the factor is target / IM(record).

use crate::{ArgumentError, FragilityError};
use rocking_motion::intensity::{pga, spectral_response};
use rocking_motion::Record;

/// The intensity measure a record is scaled by.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ScalingIm {
    /// Peak ground acceleration, m/s².
    Pga,
    /// Pseudo-spectral acceleration PSA(T, ζ) = ω²·Sd, m/s².
    Sa {
        /// Period T (s), e.g. the structure's first period T1.
        period: f64,
        /// Damping ratio ζ in [0, 1), e.g. 0.05.
        damping: f64,
    },
}

impl ScalingIm {
    /// Its name in messages and on axes: `PGA`, `Sa(T = 4.5 s, ζ = 5 %)`.
    pub fn name(&self) -> String {
        match *self {
            ScalingIm::Pga => "PGA".to_string(),
            ScalingIm::Sa { period, damping } => {
                format!("Sa(T = {period} s, ζ = {} %)", 100.0 * damping)
            }
        }
    }

    /// The IM of `record` (acceleration in m/s², its scale factor included).
    ///
    /// # Errors
    /// Invalid period or damping (named in the message).
    pub fn of(&self, record: &Record) -> Result<f64, FragilityError> {
        match *self {
            ScalingIm::Pga => Ok(pga(record)),
            ScalingIm::Sa { period, damping } => spectral_response(record, period, damping)
                .map(|r| r.psa_m_s2)
                .map_err(|e| ArgumentError::Intensity(e).into()),
        }
    }

    /// The factor that brings `record` (as it is, its scale included) to
    /// `target` (m/s²): multiply the record's scale by it.
    ///
    /// # Errors
    /// `target` not positive and finite, invalid period or damping, or a
    /// record whose IM is 0 (nothing to scale).
    pub fn scale_factor(&self, record: &Record, target: f64) -> Result<f64, FragilityError> {
        if !(target.is_finite() && target > 0.0) {
            return Err(ArgumentError::OutOfRange {
                function: "scale_factor",
                parameter: "target",
                index: None,
                value: target,
                allowed: "target > 0 and finite (m/s^2)".to_string(),
            }
            .into());
        }
        let im = self.of(record)?;
        if im <= 0.0 {
            return Err(ArgumentError::Unscalable {
                im: *self,
                value: im,
                target,
            }
            .into());
        }
        Ok(target / im)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scaled_record_hits_the_target() {
        let dt = 0.01;
        let a: Vec<f64> = (0..1500)
            .map(|k| (k as f64 * dt * 7.0).sin() * (-(k as f64) * dt * 0.2).exp())
            .collect();
        let record = Record::new(dt, a).unwrap();
        for im in [
            ScalingIm::Pga,
            ScalingIm::Sa {
                period: 1.5,
                damping: 0.05,
            },
        ] {
            let f = im.scale_factor(&record, 3.0).unwrap();
            let scaled = record.clone().with_scale(record.scale() * f);
            let got = im.of(&scaled).unwrap();
            assert!((got - 3.0).abs() < 1e-12, "{im:?}: {got}");
        }
        let e = ScalingIm::Sa {
            period: -1.0,
            damping: 0.05,
        }
        .scale_factor(&record, 1.0)
        .unwrap_err();
        assert!(e.to_string().contains("period"), "{e}");
        let e = ScalingIm::Pga.scale_factor(&record, f64::NAN).unwrap_err();
        assert!(e.to_string().contains("target"), "{e}");
        let zero = Record::new(dt, vec![0.0; 10]).unwrap();
        assert!(ScalingIm::Pga.scale_factor(&zero, 1.0).is_err());
    }
}
