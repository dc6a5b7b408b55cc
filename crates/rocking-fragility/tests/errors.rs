//! The typed errors of fits, bootstraps and scaling (issue 43): each built from a real bad
//! input, its variant and fields checked, and its message the words of before the typing.

use rocking_fragility::{
    bootstrap_capacities, fit_capacities, fit_stripes, ArgumentError, BootstrapOptions,
    FragilityError, NoFit, ScalingIm, Stripe,
};
use rocking_motion::{ParameterError, Record};

fn argument(e: FragilityError) -> ArgumentError {
    match e {
        FragilityError::InvalidParameter(a) => a,
        other => panic!("expected an invalid parameter, got {other}"),
    }
}

fn no_fit(e: FragilityError) -> NoFit {
    match e {
        FragilityError::NoEstimate(n) => n,
        other => panic!("expected no estimate, got {other}"),
    }
}

fn stripes(rows: &[(f64, u32, u32)]) -> Vec<Stripe> {
    rows.iter()
        .map(|&(im, n, collapsed)| Stripe { im, n, collapsed })
        .collect()
}

#[test]
fn bad_arguments_carry_the_argument_its_value_and_range() {
    let e = fit_capacities(&[1.0]).unwrap_err();
    assert_eq!(
        e.to_string(),
        "invalid parameter: fit_capacities: expected at least 2 capacities, found 1"
    );
    assert_eq!(
        argument(e),
        ArgumentError::TooFew {
            function: "fit_capacities",
            what: "capacities",
            needed: 2,
            found: 1
        }
    );
    let e = fit_capacities(&[1.0, -2.0, 3.0]).unwrap_err();
    assert_eq!(
        e.to_string(),
        "invalid parameter: fit_capacities: expected capacities > 0 and finite, found \
         capacities[1] = -2"
    );
    assert!(matches!(
        argument(e),
        ArgumentError::OutOfRange { parameter: "capacities", index: Some(1), value, .. }
            if value == -2.0
    ));

    let e = fit_stripes(&stripes(&[(1.0, 5, 1), (0.0, 5, 2)])).unwrap_err();
    assert_eq!(
        e.to_string(),
        "invalid parameter: fit_stripes: expected stripes[1].im > 0 and finite, found 0"
    );
    assert_eq!(argument(e), ArgumentError::StripeIm { index: 1, im: 0.0 });
    let e = fit_stripes(&stripes(&[(1.0, 5, 1), (2.0, 3, 4)])).unwrap_err();
    assert_eq!(
        argument(e),
        ArgumentError::StripeCounts {
            index: 1,
            collapsed: 4,
            n: 3
        }
    );

    let options = BootstrapOptions {
        resamples: 0,
        ..BootstrapOptions::default()
    };
    let e = bootstrap_capacities(&[1.0, 2.0, 3.0], &options).unwrap_err();
    assert_eq!(
        e.to_string(),
        "invalid parameter: bootstrap: expected 1 <= resamples <= 100000, found resamples = 0"
    );
    assert!(matches!(
        argument(e),
        ArgumentError::OutOfRange { function: "bootstrap", parameter: "resamples", index: None, value, .. }
            if value == 0.0
    ));
    let options = BootstrapOptions {
        level: 1.5,
        ..BootstrapOptions::default()
    };
    let e = argument(bootstrap_capacities(&[1.0, 2.0, 3.0], &options).unwrap_err());
    assert!(
        matches!(e, ArgumentError::OutOfRange { parameter: "level", value, .. } if value == 1.5),
        "{e:?}"
    );
}

#[test]
fn scaling_errors_carry_the_measure_and_the_intensitys_own_error() {
    let rec = Record::new(0.01, (0..300).map(|i| (0.2 * i as f64).sin()).collect()).unwrap();
    let bad_period = ScalingIm::Sa {
        period: -1.0,
        damping: 0.05,
    };
    let e = bad_period.scale_factor(&rec, 1.0).unwrap_err();
    assert_eq!(
        e.to_string(),
        "invalid parameter: spectral_response: expected period > 0 and finite (s), found \
         period = -1"
    );
    assert!(std::error::Error::source(&e).is_some());
    assert!(matches!(
        argument(e),
        ArgumentError::Intensity(ParameterError::OutOfRange { parameter: "period", value, .. })
            if value == -1.0
    ));
    let e = argument(ScalingIm::Pga.scale_factor(&rec, -3.0).unwrap_err());
    assert!(
        matches!(e, ArgumentError::OutOfRange { function: "scale_factor", parameter: "target", value, .. } if value == -3.0),
        "{e:?}"
    );
    let still = Record::new(0.01, vec![0.0; 10]).unwrap();
    let e = ScalingIm::Pga.scale_factor(&still, 2.0).unwrap_err();
    assert_eq!(
        e.to_string(),
        "invalid parameter: scale_factor: the record's Pga is 0: it cannot be scaled to 2"
    );
    assert_eq!(
        argument(e),
        ArgumentError::Unscalable {
            im: ScalingIm::Pga,
            value: 0.0,
            target: 2.0
        }
    );
}

#[test]
fn data_without_an_estimate_say_why_with_their_counts() {
    let e = fit_capacities(&[2.0, 2.0, 2.0]).unwrap_err();
    assert_eq!(
        e.to_string(),
        "no estimate: fit_capacities: all capacities are equal, so beta = 0"
    );
    assert_eq!(no_fit(e), NoFit::EqualCapacities { capacity: 2.0 });

    let e = fit_stripes(&stripes(&[(1.0, 5, 0), (2.0, 5, 0)])).unwrap_err();
    assert_eq!(
        e.to_string(),
        "no estimate: fit_stripes: 0 of 10 runs collapsed: no finite maximum-likelihood fit"
    );
    assert_eq!(
        no_fit(e),
        NoFit::AllOrNone {
            collapsed: 0,
            runs: 10
        }
    );
    let e = fit_stripes(&stripes(&[(1.0, 5, 0), (2.0, 5, 5)])).unwrap_err();
    assert_eq!(
        no_fit(e),
        NoFit::Separated {
            max_survived: 1.0,
            min_collapsed: 2.0
        }
    );
    let e = fit_stripes(&stripes(&[(1.5, 5, 2), (1.5, 5, 3)])).unwrap_err();
    assert_eq!(no_fit(e), NoFit::SameIm { im: 1.5 });
    let e = fit_stripes(&stripes(&[(1.0, 10, 8), (2.0, 10, 5), (4.0, 10, 2)])).unwrap_err();
    let NoFit::Falling { slope } = no_fit(e.clone()) else {
        panic!("expected a falling curve: {e}");
    };
    assert!(slope < 0.0, "slope {slope}");

    // Two capacities: a resample of one drawn twice has no fit; among 64 seeds some single
    // resample is such a one, and the error counts it.
    let refused = (0..64)
        .filter_map(|seed| {
            let options = BootstrapOptions {
                resamples: 1,
                seed,
                ..BootstrapOptions::default()
            };
            bootstrap_capacities(&[1.0, 2.0], &options).err()
        })
        .collect::<Vec<_>>();
    assert!(!refused.is_empty());
    for e in refused {
        assert_eq!(
            e.to_string(),
            "no estimate: bootstrap: none of the 1 resamples had a finite fit"
        );
        assert_eq!(no_fit(e), NoFit::NoResample { resamples: 1 });
    }
}
