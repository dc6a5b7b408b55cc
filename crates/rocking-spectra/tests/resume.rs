//! Sweeps resume after an interruption without losing or corrupting cells, refuse a changed
//! sweep, and give the same cells whatever the number of threads.

use std::sync::atomic::{AtomicUsize, Ordering};

use rocking::{simulate, DampingConvention, Dimensionless, Effects, Options, Structure, Summary};
use rocking_motion::SinePulse;
use rocking_spectra::{run, Axis, CellClass, CellFailure, Progress, Sweep};

/// A cell of the Fig-8 structure's spectrum (γ_mb = γ_mc = 2, ω_n/p = 5, α = 0.1, uplifted ζ = 0.01).
fn cell(values: &[f64]) -> Result<Summary, String> {
    let d = Dimensionless {
        omega_n_over_p: 5.0,
        alpha: 0.1,
        gamma_mc: 2.0,
        gamma_mb: 2.0,
        gamma_ib: 1.0,
        zeta: 0.01,
        damping: DampingConvention::Uplifted,
    };
    let s = Structure::from_dimensionless(&d, None).map_err(|e| e.to_string())?;
    let (wp, amp) = (values[0], values[1]);
    let opts = Options {
        t_end: 2.0 * std::f64::consts::PI / wp + 20.0,
        ..Options::default()
    };
    let run = simulate(
        &s,
        &SinePulse::new(amp * d.alpha.tan(), wp),
        &Effects::default(),
        &opts,
    );
    run.map(|r| r.summary).map_err(|e| e.to_string())
}

fn sweep(fingerprint: &str) -> Sweep {
    Sweep {
        axes: vec![
            Axis::parse("excitation.omega_p_over_p=1:10:6").unwrap(),
            Axis::parse("excitation.amplitude=0.5:20:8").unwrap(),
        ],
        fingerprint: fingerprint.to_string(),
        reported: Vec::new(),
    }
}

#[test]
fn interrupted_sweep_resumes_to_the_uninterrupted_result() {
    let dir = tempfile::tempdir().unwrap();
    let s = sweep("fig8-test");
    let reference = run(&s, &dir.path().join("whole"), Progress::Quiet, cell).unwrap();
    assert_eq!(reference.cells.len(), 48);
    let classes: std::collections::BTreeSet<_> = reference.cells.iter().map(|c| c.class).collect();
    assert!(classes.contains(&CellClass::NoUplift) && classes.contains(&CellClass::Survived));
    assert!(classes.iter().any(|c| matches!(
        c,
        CellClass::OverturnedNoImpact
            | CellClass::OverturnedOneImpact
            | CellClass::OverturnedImpacts
    )));

    // An interrupted sweep: the journal holds only the first cells to finish, and the process
    // died in the middle of writing the next line (the CLI's tests kill a real process).
    let out = dir.path().join("interrupted");
    std::fs::create_dir_all(&out).unwrap();
    let whole = std::fs::read_to_string(dir.path().join("whole/cells.journal")).unwrap();
    let mut text: String = whole.lines().take(21).map(|l| format!("{l}\n")).collect();
    let kept = 20;
    text.push_str("47,survived,1.2");
    let journal = out.join("cells.journal");
    std::fs::write(&journal, text).unwrap();

    let calls = AtomicUsize::new(0);
    let resumed = run(&s, &out, Progress::Quiet, |v| {
        calls.fetch_add(1, Ordering::SeqCst);
        cell(v)
    })
    .unwrap();
    assert_eq!(
        calls.load(Ordering::SeqCst),
        48 - kept,
        "only the missing cells are computed"
    );
    assert_eq!(
        resumed.cells, reference.cells,
        "resumed sweep equals the uninterrupted one"
    );

    assert!(resumed.failures.is_empty());

    // A different sweep in the same directory is refused.
    let err = run(&sweep("another-scene"), &out, Progress::Quiet, cell).unwrap_err();
    assert!(err.to_string().contains("different sweep"), "{err}");
}

#[test]
fn cells_do_not_depend_on_the_number_of_threads() {
    let dir = tempfile::tempdir().unwrap();
    let s = sweep("threads");
    let one = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    let two = rayon::ThreadPoolBuilder::new()
        .num_threads(2)
        .build()
        .unwrap();
    let a = one
        .install(|| run(&s, &dir.path().join("1"), Progress::Quiet, cell))
        .unwrap();
    let b = two
        .install(|| run(&s, &dir.path().join("2"), Progress::Quiet, cell))
        .unwrap();
    assert_eq!(a.cells, b.cells);
}

#[test]
fn a_failing_cell_is_recorded_and_the_others_are_unaffected() {
    let dir = tempfile::tempdir().unwrap();
    let s = sweep("failures");
    let good = run(&s, &dir.path().join("good"), Progress::Quiet, cell).unwrap();
    let out = run(&s, &dir.path().join("bad"), Progress::Quiet, |v| {
        if v[0] == 1.0 && v[1] == 20.0 {
            Err("model singular".to_string())
        } else {
            cell(v)
        }
    })
    .unwrap();
    assert_eq!(out.failures.len(), 1);
    assert_eq!(out.failures[0].1, "model singular");
    for (a, b) in good.cells.iter().zip(&out.cells) {
        if b.index == out.failures[0].0 {
            assert_eq!(b.class, CellClass::Failed);
        } else {
            assert_eq!(a, b);
        }
    }
}

/// A resumed sweep reports the cells that failed before, with their messages (it used to empty
/// the failure list).
#[test]
fn failures_are_reported_again_on_resume() {
    let dir = tempfile::tempdir().unwrap();
    let s = sweep("failures-resume");
    let failing = |v: &[f64]| {
        if v[1] == 20.0 {
            Err(format!("model singular at ω_p/p = {}", v[0]))
        } else {
            cell(v)
        }
    };
    let first = run(&s, dir.path(), Progress::Quiet, failing).unwrap();
    assert_eq!(first.failures.len(), 6);
    let calls = AtomicUsize::new(0);
    let resumed = run(&s, dir.path(), Progress::Quiet, |v| {
        calls.fetch_add(1, Ordering::SeqCst);
        cell(v)
    })
    .unwrap();
    assert_eq!(calls.load(Ordering::SeqCst), 0, "nothing recomputed");
    assert_eq!(resumed.computed, 0);
    assert_eq!(
        resumed.failures, first.failures,
        "failures kept with their messages"
    );
    assert_eq!(resumed.cells, first.cells);
}

/// A `cells.journal` that is a directory or binary is reported as not a journal (not as "the
/// cells of a different sweep"); an empty one (a sweep killed before it wrote) starts afresh.
#[test]
fn a_journal_that_is_not_one_is_reported_as_such() {
    let dir = tempfile::tempdir().unwrap();
    let s = sweep("not-a-journal");
    let as_dir = dir.path().join("dir");
    std::fs::create_dir_all(as_dir.join("cells.journal")).unwrap();
    let binary = dir.path().join("binary");
    std::fs::create_dir_all(&binary).unwrap();
    std::fs::write(
        binary.join("cells.journal"),
        [0xffu8, 0xfe, 0x00, 0x13, 0x80],
    )
    .unwrap();
    let other = dir.path().join("other");
    std::fs::create_dir_all(&other).unwrap();
    std::fs::write(other.join("cells.journal"), "index,class\n1,2\n").unwrap();
    for (d, why) in [
        (&as_dir, "directory"),
        (&binary, "not text"),
        (&other, "not a sweep header"),
    ] {
        let e = run(&s, d, Progress::Quiet, cell).unwrap_err();
        let msg = e.to_string();
        assert!(
            msg.contains("not a journal") && msg.contains(why) && !msg.contains("different sweep"),
            "{}: {msg}",
            d.display()
        );
    }
    let empty = dir.path().join("empty");
    std::fs::create_dir_all(&empty).unwrap();
    std::fs::write(empty.join("cells.journal"), "").unwrap();
    let out = run(&s, &empty, Progress::Quiet, cell).unwrap();
    assert_eq!(out.computed, 48, "an empty journal holds no cells");
}

/// The in-memory run (no journal) gives the journaled run's cells and failures.
#[test]
fn an_in_memory_run_equals_the_journaled_one() {
    let dir = tempfile::tempdir().unwrap();
    let s = sweep("in-memory");
    let failing = |v: &[f64]| {
        if v[0] == 1.0 && v[1] == 20.0 {
            Err("model singular".to_string())
        } else {
            cell(v)
        }
    };
    let journaled = run(&s, dir.path(), Progress::Quiet, failing).unwrap();
    let memory = rocking_spectra::run_in_memory(&s, failing).unwrap();
    assert_eq!(memory.cells, journaled.cells);
    assert_eq!(memory.failures, journaled.failures);
    assert_eq!(memory.computed, 48);
    assert_eq!(
        std::fs::read_dir(dir.path()).unwrap().count(),
        1,
        "only the journaled run writes"
    );
}

/// A cell beyond the model is a class of its own: not a failure, with its message kept apart,
/// written as such in cells.csv with no values, and kept on resume and in memory alike.
#[test]
fn a_cell_beyond_the_model_is_its_own_class_through_resume_and_memory() {
    let dir = tempfile::tempdir().unwrap();
    let s = sweep("beyond-model");
    let singular = |v: &[f64]| -> Result<Summary, CellFailure> {
        if v[1] == 20.0 {
            Err(CellFailure {
                class: CellClass::BeyondModel,
                message: format!("M singular at ω_p/p = {}", v[0]),
            })
        } else if v[0] == 1.0 && v[1] == 0.5 {
            Err("integration failed".to_string().into())
        } else {
            cell(v).map_err(CellFailure::from)
        }
    };
    let first = run(&s, dir.path(), Progress::Quiet, singular).unwrap();
    assert_eq!(
        first.beyond_model.len(),
        6,
        "one per ω_p/p at the top amplitude"
    );
    assert_eq!(first.beyond_model[0].1, "M singular at ω_p/p = 1");
    assert_eq!(
        first.failures,
        vec![(0, "integration failed".to_string())],
        "a failure stays a failure"
    );
    for c in &first.cells {
        let beyond = first.beyond_model.iter().any(|b| b.0 == c.index);
        assert_eq!(
            c.class == CellClass::BeyondModel,
            beyond,
            "cell {}",
            c.index
        );
        assert_eq!(c.class.has_result(), c.index != 0 && !beyond);
    }
    let csv = rocking_spectra::cells_csv(&s, &first.cells);
    assert_eq!(csv.matches(",beyond-model,,\n").count(), 6, "{csv}");
    let calls = AtomicUsize::new(0);
    let resumed = run(&s, dir.path(), Progress::Quiet, |v| {
        calls.fetch_add(1, Ordering::SeqCst);
        cell(v)
    })
    .unwrap();
    assert_eq!(calls.load(Ordering::SeqCst), 0, "nothing recomputed");
    assert_eq!(resumed.cells, first.cells);
    assert_eq!(
        resumed.beyond_model, first.beyond_model,
        "kept with messages"
    );
    assert_eq!(resumed.failures, first.failures);
    let memory = rocking_spectra::run_in_memory(&s, singular).unwrap();
    assert_eq!(memory.cells, first.cells);
    assert_eq!(memory.beyond_model, first.beyond_model);
    assert_eq!(memory.failures, first.failures);
}

/// A run cannot claim a class with a result as its failure: such a cell is a failure.
#[test]
fn a_failure_with_a_class_that_has_a_result_is_a_failure() {
    let s = sweep("claimed-class");
    let out = rocking_spectra::run_in_memory(&s, |_: &[f64]| -> Result<Summary, CellFailure> {
        Err(CellFailure {
            class: CellClass::Survived,
            message: "no summary".into(),
        })
    })
    .unwrap();
    assert!(out.cells.iter().all(|c| c.class == CellClass::Failed));
    assert_eq!(out.failures.len(), 48);
    assert!(out.beyond_model.is_empty());
}
