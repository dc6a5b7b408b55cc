//! The typed invalid-parameter errors (issue 43): each built from a real bad input, its variant
//! and fields checked, and its message the words users read before the errors were typed.

use rocking_motion::intensity::{
    mean_period, pga_over_uplift, significant_duration, spectral_response, MEAN_PERIOD_BAND_HZ,
};
use rocking_motion::{parse_record, MotionError, ParameterError, Record, RecordFormat};

fn invalid(e: MotionError) -> ParameterError {
    assert_eq!(e.line(), None, "{e}");
    match e {
        MotionError::InvalidParameter(p) => p,
        other => panic!("expected an invalid parameter, got {other}"),
    }
}

#[test]
fn a_record_built_in_code_names_what_is_wrong_with_its_value() {
    let e = Record::new(0.0, vec![1.0]).unwrap_err();
    assert_eq!(
        e.to_string(),
        "invalid parameter: Record: expected dt > 0 and finite, found 0"
    );
    assert_eq!(invalid(e), ParameterError::RecordDt { dt: 0.0 });

    let e = invalid(Record::new(0.01, vec![]).unwrap_err());
    assert_eq!(e, ParameterError::RecordEmpty);

    let e = Record::new(f64::MAX, vec![0.0; 3]).unwrap_err();
    assert_eq!(
        e.to_string(),
        format!(
            "invalid parameter: Record: expected a finite duration (n - 1) dt, found 3 samples \
             of dt = {}",
            f64::MAX
        )
    );
    assert_eq!(
        invalid(e),
        ParameterError::RecordDuration {
            samples: 3,
            dt: f64::MAX
        }
    );

    let e = Record::new(0.01, vec![0.0, 1.0, f64::INFINITY]).unwrap_err();
    assert_eq!(
        e.to_string(),
        "invalid parameter: Record: expected finite samples, found inf at index 2"
    );
    assert_eq!(
        invalid(e),
        ParameterError::RecordSample {
            index: 2,
            value: f64::INFINITY
        }
    );
}

#[test]
fn a_records_stated_time_step_is_checked_against_its_format() {
    let e = parse_record("0.1\n0.2\n0.3\n", RecordFormat::Text, "one.txt", None).unwrap_err();
    assert_eq!(
        e.to_string(),
        "invalid parameter: one.txt: a one-column text record needs its time step: give `dt` \
         (s) in [excitation]"
    );
    assert_eq!(
        invalid(e),
        ParameterError::TextNeedsDt {
            file: "one.txt".into()
        }
    );

    let two = "0.00 0.1\n0.01 0.2\n0.02 0.3\n";
    let e = parse_record(two, RecordFormat::Text, "two.txt", Some(0.5)).unwrap_err();
    let ParameterError::DtContradicts { file, stated, dt } = invalid(e) else {
        panic!("expected DtContradicts");
    };
    assert_eq!((file.as_str(), stated), ("two.txt", 0.5));
    assert!((dt - 0.01).abs() < 1e-15, "the time column's step {dt}");

    let e = parse_record("", RecordFormat::Esm, "rec.ASC", Some(0.01)).unwrap_err();
    assert_eq!(
        e.to_string(),
        "invalid parameter: rec.ASC: a esm file states its own time step; `dt` is for \
         one-column text files"
    );
    assert_eq!(
        invalid(e),
        ParameterError::DtNotTaken {
            file: "rec.ASC".into(),
            format: "esm"
        }
    );
}

#[test]
fn intensity_measures_name_the_argument_its_value_and_range() {
    let rec = Record::new(0.01, (0..400).map(|i| (0.1 * i as f64).sin()).collect()).unwrap();
    let e = spectral_response(&rec, -1.0, 0.05).unwrap_err();
    assert_eq!(
        e.to_string(),
        "spectral_response: expected period > 0 and finite (s), found period = -1"
    );
    assert_eq!(
        e,
        ParameterError::OutOfRange {
            function: "spectral_response",
            parameter: "period",
            value: -1.0,
            allowed: "period > 0 and finite (s)",
        }
    );
    // Through `?` it is the motion error's invalid parameter, with the words of before.
    let wrapped: MotionError = spectral_response(&rec, 1.0, 1.5).unwrap_err().into();
    assert_eq!(
        wrapped.to_string(),
        "invalid parameter: spectral_response: expected damping in [0, 1), found damping = 1.5"
    );
    let e = pga_over_uplift(1.0, 2.0).unwrap_err();
    assert!(
        matches!(e, ParameterError::OutOfRange { function: "pga_over_uplift", parameter: "alpha", value, .. } if value == 2.0),
        "{e:?}"
    );

    assert_eq!(
        significant_duration(&rec, 0.9, 0.1).unwrap_err(),
        ParameterError::DurationFractions { from: 0.9, to: 0.1 }
    );
    let still = Record::new(0.01, vec![0.0; 50]).unwrap();
    assert_eq!(
        significant_duration(&still, 0.05, 0.95).unwrap_err(),
        ParameterError::NoMotion
    );
    // Two samples 0.01 s apart: the first DFT frequency, 50 Hz, is above the band.
    let short = Record::new(0.01, vec![1.0, -1.0]).unwrap();
    let e = mean_period(&short).unwrap_err();
    assert_eq!(
        e,
        ParameterError::NoFourierAmplitude {
            lo_hz: MEAN_PERIOD_BAND_HZ.0,
            hi_hz: MEAN_PERIOD_BAND_HZ.1,
            samples: 2,
            dt: 0.01
        }
    );
    assert_eq!(
        e.to_string(),
        "mean_period: record has no Fourier amplitude in 0.25-20 Hz (n = 2, dt = 0.01 s)"
    );
}
