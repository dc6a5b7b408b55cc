//! Hunt-and-fill capacities equal a bisection of the same response to the
//! stated tolerance, on synthetic responses: monotone ones with many
//! thresholds, and non-monotone ones with a resurrection.

use rocking_fragility::{HuntFill, IdaError, Outcome};
use std::convert::Infallible;

const TOL: f64 = 0.01;

fn settings() -> HuntFill {
    HuntFill {
        first: 0.05,
        step: 0.1,
        step_increment: 0.05,
        tolerance: TOL,
        max_gap: 0.05,
        max_runs: 200,
    }
}

/// The lowest collapsing IM of `collapses` by bisection on [lo, hi]
/// (lo survives, hi collapses, one threshold in between), to `TOL`.
fn bisection(collapses: impl Fn(f64) -> bool, mut lo: f64, mut hi: f64) -> f64 {
    assert!(!collapses(lo) && collapses(hi));
    while hi - lo > TOL * hi * 1e-3 {
        let mid = 0.5 * (lo + hi);
        if collapses(mid) {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    hi
}

/// A response that grows with the IM and collapses at 1 (max θ/α style).
fn outcome(im: f64, threshold: f64, collapses: bool) -> Outcome {
    Outcome {
        collapsed: collapses,
        response: if collapses {
            f64::INFINITY
        } else {
            (im / threshold).powf(1.5)
        },
    }
}

#[test]
fn monotone_capacities_equal_bisection() {
    let mut worst = 0.0f64;
    let mut max_runs = 0;
    for i in 0..200 {
        let threshold = 0.03 * 1.031f64.powi(i); // 0.03 .. 13
        let collapses = |im: f64| im >= threshold;
        let mut calls = 0;
        let ida = settings()
            .run(|im| {
                calls += 1;
                Ok::<_, Infallible>(outcome(im, threshold, collapses(im)))
            })
            .unwrap();
        let reference = bisection(collapses, 0.0, 1e3);
        let err = (ida.capacity - reference).abs() / reference;
        assert!(
            err <= TOL,
            "threshold {threshold}: {} vs {reference}",
            ida.capacity
        );
        assert!(ida.survived_below < threshold && threshold <= ida.capacity);
        assert_eq!(calls, ida.runs());
        // the curve: sorted, survivors below the capacity, response rising
        assert!(ida.points.windows(2).all(|w| w[0].im < w[1].im));
        let below: Vec<_> = ida.points.iter().filter(|p| p.im < ida.capacity).collect();
        assert!(below.iter().all(|p| !p.outcome.collapsed));
        assert!(below
            .windows(2)
            .all(|w| w[0].outcome.response < w[1].outcome.response));
        worst = worst.max(err);
        max_runs = max_runs.max(ida.runs());
    }
    println!("monotone: worst |hunt-and-fill − bisection|/bisection {worst:.2e} (tolerance {TOL}), at most {max_runs} runs");
}

#[test]
fn resurrection_reports_the_first_collapse() {
    // collapse on [1.0, 1.12), survival (resurrection) on [1.12, 2.0), collapse above
    let collapses = |im: f64| (1.0..1.12).contains(&im) || im >= 2.0;
    let response = |im: f64| {
        Ok::<_, Infallible>(Outcome {
            collapsed: collapses(im),
            // non-monotone: the response dips in the resurrection band
            response: if collapses(im) {
                f64::INFINITY
            } else if im < 1.0 {
                im
            } else {
                0.5
            },
        })
    };
    // the hunt steps over the first band (0.05, 0.15, 0.3, 0.5, 0.75, 1.05 …):
    // start where it lands in the gap instead
    let hf = HuntFill {
        first: 0.9,
        step: 0.3,
        ..settings()
    }; // 0.9, 1.2, 1.55, 1.95, 2.4
    let ida = hf.run(response).unwrap();
    let reference = bisection(collapses, 0.5, 1.05);
    let err = (ida.capacity - reference).abs() / reference;
    println!(
        "resurrection: capacity {:.5} vs bisection {reference:.5} ({err:.1e}), {} runs, survivors above the capacity {}",
        ida.capacity,
        ida.runs(),
        ida.points.iter().filter(|p| p.im > ida.capacity && !p.outcome.collapsed).count()
    );
    assert!(err <= TOL);
    // the resurrection is on the curve: survivors above the capacity
    assert!(ida
        .points
        .iter()
        .any(|p| p.im > 1.12 && p.im < 2.0 && !p.outcome.collapsed));
    // a band narrower than the fill gap (max_gap × capacity) can be missed: documented
    let coarse = HuntFill { max_gap: 0.5, ..hf };
    let missed = coarse.run(response).unwrap();
    assert!(missed.capacity >= 2.0 * (1.0 - TOL), "{}", missed.capacity);
}

#[test]
fn budget_and_errors() {
    let never = |_im: f64| {
        Ok::<_, Infallible>(Outcome {
            collapsed: false,
            response: 0.0,
        })
    };
    match settings().run(never) {
        Err(IdaError::RunBudget { stage, points }) => {
            assert!(stage.contains("hunt"));
            assert_eq!(points.len(), 200);
        }
        other => panic!("{other:?}"),
    }
    let tight = HuntFill {
        max_runs: 8,
        ..settings()
    };
    let e = tight
        .run(|im| Ok::<_, Infallible>(outcome(im, 1.0, im >= 1.0)))
        .unwrap_err();
    assert!(matches!(e, IdaError::RunBudget { .. }), "{e}");
    let failing = settings().run(|im| {
        if im > 0.3 {
            Err("diverged")
        } else {
            Ok(outcome(im, 1.0, false))
        }
    });
    match failing {
        Err(IdaError::Analysis { im, source }) => assert!(im > 0.3 && source == "diverged"),
        other => panic!("{other:?}"),
    }
    for (hf, word) in [
        (
            HuntFill {
                first: 0.0,
                ..settings()
            },
            "first",
        ),
        (
            HuntFill {
                step: f64::NAN,
                ..settings()
            },
            "step",
        ),
        (
            HuntFill {
                tolerance: 0.0,
                ..settings()
            },
            "tolerance",
        ),
        (
            HuntFill {
                max_gap: 0.001,
                ..settings()
            },
            "max_gap",
        ),
        (
            HuntFill {
                max_runs: 0,
                ..settings()
            },
            "max_runs",
        ),
    ] {
        let e = hf.run(never).unwrap_err();
        let text = e.to_string();
        assert!(
            text.starts_with("invalid parameter: HuntFill: expected "),
            "{text}"
        );
        match e {
            IdaError::InvalidParameter(p) => {
                assert_eq!(p.field, word, "{text}");
                assert!(p.allowed.starts_with(word), "{text}");
                let value = match word {
                    "first" => hf.first,
                    "step" => hf.step,
                    "tolerance" => hf.tolerance,
                    "max_gap" => hf.max_gap,
                    _ => hf.max_runs as f64,
                };
                assert!(
                    p.value == value || (p.value.is_nan() && value.is_nan()),
                    "{text}"
                );
            }
            other => panic!("{word}: {other}"),
        }
    }
}
