//! Shards: every split into N interleaved shards merges back to the whole sweep's outcome; the
//! merge refuses a duplicate, a missing or an incomplete shard (listing the missing cells with
//! their owner); a killed shard resumes from its own journal; failed cells survive the merge.

use rocking::{simulate, DampingConvention, Dimensionless, Effects, Options, Structure, Summary};
use rocking_motion::SinePulse;
use rocking_spectra::shard::{
    merge, MergeError, ShardSpecError, ShardSpecProblem, LISTED, MAX_SHARDS,
};
use rocking_spectra::{run, run_shard, Axis, CellClass, CellFailure, Progress, Shard, Sweep};

/// A cell of the Fig-8 structure's spectrum (γ_mb = γ_mc = 2, ω_n/p = 5, α = 0.1), failing on
/// purpose at one cell so that failures travel through the shards too.
fn cell(values: &[f64]) -> Result<Summary, CellFailure> {
    let (wp, amp) = (values[0], values[1]);
    if wp == 1.0 && amp == 20.0 {
        return Err("model singular\nat u = s B".to_string().into());
    }
    if wp == 10.0 && amp == 20.0 {
        return Err(CellFailure {
            class: CellClass::BeyondModel,
            message: "beyond the model".into(),
        });
    }
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
    let opts = Options {
        t_end: 2.0 * std::f64::consts::PI / wp + 20.0,
        ..Options::default()
    };
    let excitation = SinePulse::new(amp * d.alpha.tan(), wp);
    simulate(&s, &excitation, &Effects::default(), &opts)
        .map(|r| r.summary)
        .map_err(|e| e.to_string().into())
}

fn sweep() -> Sweep {
    Sweep {
        axes: vec![
            Axis::parse("excitation.omega_p_over_p=1:10:5").unwrap(),
            Axis::parse("excitation.amplitude=0.5:20:7").unwrap(),
        ],
        fingerprint: "shard-test".into(),
        reported: Vec::new(),
    }
}

fn run_all_shards(s: &Sweep, root: &std::path::Path, n: usize) -> Vec<(std::path::PathBuf, Shard)> {
    (0..n)
        .map(|k| {
            let shard = Shard { k, n };
            let dir = root.join(format!("{n}-{k}"));
            let part = run_shard(s, shard, &dir, Progress::Quiet, cell).unwrap();
            assert_eq!(part.cells.len(), shard.len(s.len()), "shard {shard}");
            assert!(
                part.cells.iter().all(|c| shard.owns(c.index)),
                "shard {shard}"
            );
            (dir, shard)
        })
        .collect()
}

#[test]
fn every_split_merges_to_the_whole_sweep() {
    let dir = tempfile::tempdir().unwrap();
    let s = sweep();
    let whole = run(&s, &dir.path().join("whole"), Progress::Quiet, cell).unwrap();
    assert_eq!(whole.cells.len(), 35);
    assert_eq!(whole.failures.len(), 1);
    // More shards than cells too: the empty shards merge as well.
    for n in [1, 3, 4, 7, 40] {
        let shards = run_all_shards(&s, dir.path(), n);
        let merged = merge(&s, &shards).unwrap();
        assert_eq!(merged.cells, whole.cells, "N = {n}");
        assert_eq!(
            merged.failures, whole.failures,
            "N = {n}: failures and messages"
        );
        assert_eq!(
            merged.beyond_model, whole.beyond_model,
            "N = {n}: cells beyond the model and messages"
        );
        // The order the directories are given in does not matter.
        let reversed: Vec<_> = shards.iter().rev().cloned().collect();
        assert_eq!(merge(&s, &reversed).unwrap().cells, whole.cells, "N = {n}");
    }
    let failed = whole
        .cells
        .iter()
        .find(|c| c.class == CellClass::Failed)
        .unwrap();
    assert_eq!(
        whole.failures[0],
        (failed.index, "model singular at u = s B".to_string()),
        "a fresh failure reads as the journal keeps it"
    );
    assert_eq!(whole.failures.len(), 1);
    let beyond = whole
        .cells
        .iter()
        .find(|c| c.class == CellClass::BeyondModel)
        .unwrap();
    assert_eq!(
        whole.beyond_model,
        vec![(beyond.index, "beyond the model".to_string())]
    );
}

#[test]
fn shards_interleave_and_balance() {
    for n in 1..=9 {
        for len in [0, 1, 8, 35, 36] {
            let sizes: Vec<usize> = (0..n).map(|k| Shard { k, n }.len(len)).collect();
            assert_eq!(sizes.iter().sum::<usize>(), len, "n {n} len {len}");
            let (lo, hi) = (sizes.iter().min().unwrap(), sizes.iter().max().unwrap());
            assert!(hi - lo <= 1, "balanced: {sizes:?}");
            for i in 0..len {
                let owners = (0..n).filter(|&k| Shard { k, n }.owns(i)).count();
                assert_eq!(owners, 1, "cell {i} has exactly one owner");
                assert!(Shard::owner(i, n).owns(i));
            }
        }
    }
}

#[test]
fn shard_specs_are_parsed_with_their_bounds() {
    assert_eq!(Shard::parse("0/1"), Ok(Shard { k: 0, n: 1 }));
    assert_eq!(Shard::parse("3/4"), Ok(Shard { k: 3, n: 4 }));
    assert_eq!(Shard::parse("3/4").unwrap().to_string(), "3/4");
    for (bad, says) in [
        ("4/4", "0 ≤ K < N = 4"),
        ("5/4", "0 ≤ K < N = 4"),
        ("0/0", "1 ≤ N ≤ 100000"),
        ("0/100001", "1 ≤ N ≤ 100000"),
        ("-1/4", "K `-1` is not a whole number"),
        ("1", "expected K/N"),
        ("1/2/3", "N `2/3` is not a whole number"),
        ("a/4", "K `a`"),
        ("", "expected K/N"),
    ] {
        let e = Shard::parse(bad).unwrap_err();
        assert_eq!(e.text, bad);
        let e = e.to_string();
        assert!(e.contains(says) && e.contains(bad), "{bad}: {e}");
        assert!(!e.contains("--"), "the library names no flag: {e}");
    }
    assert!(Shard::parse(&format!("0/{MAX_SHARDS}")).is_ok());
    let problem = |text: &str| Shard::parse(text).unwrap_err().problem;
    assert_eq!(problem("5/4"), ShardSpecProblem::Number { k: 5, n: 4 });
    assert_eq!(problem("0/100001"), ShardSpecProblem::Count { n: 100_001 });
    assert_eq!(problem("1"), ShardSpecProblem::NotKOverN);
    assert_eq!(
        Shard::parse("1/2/3"),
        Err(ShardSpecError {
            text: "1/2/3".into(),
            problem: ShardSpecProblem::NotWhole {
                part: "N",
                found: "2/3".into()
            }
        })
    );
}

fn shards_error(r: Result<rocking_spectra::Outcome, MergeError>) -> MergeError {
    match r {
        Err(MergeError::Journal(e)) => panic!("expected a shard-set error, got {e}"),
        Err(e) => e,
        Ok(_) => panic!("expected an error, the merge succeeded"),
    }
}

#[test]
fn incomplete_or_inconsistent_shard_sets_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let s = sweep();
    let shards = run_all_shards(&s, dir.path(), 4);

    // None given.
    let e = shards_error(merge(&s, &[]));
    assert!(matches!(e, MergeError::NoShards), "{e}");
    assert_eq!(e.to_string(), "no shard directory given");
    // A missing shard: its cells are listed with their owner and axis values.
    let e = shards_error(merge(
        &s,
        &[shards[0].clone(), shards[1].clone(), shards[3].clone()],
    ));
    let MergeError::Incomplete { gaps } = &e else {
        panic!("expected missing cells, got {e}");
    };
    assert_eq!(gaps.len(), 1, "{e}");
    let g = &gaps[0];
    assert_eq!(
        (g.shard, &g.dir, g.missing, g.cells),
        (Shard { k: 2, n: 4 }, &None, 9, 9)
    );
    let indices: Vec<usize> = g.first.iter().map(|c| c.index).collect();
    assert_eq!(indices, (2..35).step_by(4).collect::<Vec<_>>());
    assert_eq!(g.first[0].values.len(), 2);
    assert_eq!(
        g.first[0].values[0],
        ("excitation.omega_p_over_p".to_string(), 1.0)
    );
    assert_eq!(g.first[0].values[1].1, s.values(2)[1]);
    let e = e.to_string();
    assert!(
        e.contains("shard 2/4 (not given): 9 of its 9 cells missing"),
        "{e}"
    );
    assert!(
        e.contains("2 (excitation.omega_p_over_p=1, excitation.amplitude=6.999999999999999)")
            || e.contains("2 (excitation.omega_p_over_p=1, excitation.amplitude=7)"),
        "{e}"
    );
    // A duplicate shard.
    let e = shards_error(merge(
        &s,
        &[shards[0].clone(), shards[1].clone(), shards[1].clone()],
    ));
    match &e {
        MergeError::Duplicate { dir, shard, other } => {
            assert_eq!(
                (dir, *shard, other),
                (&shards[1].0, shards[1].1, &shards[1].0)
            );
        }
        other => panic!("expected a duplicate, got {other}"),
    }
    assert!(e.to_string().contains("shard 1/4 is given twice"), "{e}");
    // Shards of different splits.
    let three = run_all_shards(&s, dir.path(), 3);
    let e = shards_error(merge(&s, &[shards[0].clone(), three[1].clone()]));
    match &e {
        MergeError::MixedSplits {
            dir,
            shard,
            first_dir,
            first,
        } => assert_eq!(
            (dir, *shard, first_dir, *first),
            (
                &three[1].0,
                Shard { k: 1, n: 3 },
                &shards[0].0,
                Shard { k: 0, n: 4 }
            )
        ),
        other => panic!("expected mixed splits, got {other}"),
    }
    assert!(e.to_string().contains("split into 3 shards"), "{e}");
    // A shard given with a directory where it never ran.
    let never = dir.path().join("never-ran");
    let e = shards_error(merge(
        &s,
        &[
            shards[0].clone(),
            shards[1].clone(),
            (never.clone(), Shard { k: 2, n: 4 }),
            shards[3].clone(),
        ],
    ));
    match &e {
        MergeError::NoJournal { shard, path } => {
            assert_eq!(
                (*shard, path),
                (Shard { k: 2, n: 4 }, &never.join("cells.journal"))
            );
        }
        other => panic!("expected no journal, got {other}"),
    }
    assert_eq!(
        e.to_string(),
        format!(
            "{}: shard 2/4 has no journal (it never ran here)",
            never.join("cells.journal").display()
        )
    );
    // A journal of shard 1 presented as shard 2 (its header names the shard).
    let e = merge(
        &s,
        &[
            shards[0].clone(),
            shards[1].clone(),
            (shards[1].0.clone(), Shard { k: 2, n: 4 }),
            shards[3].clone(),
        ],
    )
    .unwrap_err();
    assert!(
        matches!(e, MergeError::Journal(_)) && e.to_string().contains("different sweep"),
        "{e}"
    );
    // Shards of another sweep.
    let other = Sweep {
        fingerprint: "another".into(),
        ..sweep()
    };
    let e = merge(&other, &shards).unwrap_err();
    assert!(e.to_string().contains("different sweep"), "{e}");
    assert!(
        e.to_string().contains("4-0"),
        "names the shard directory: {e}"
    );
}

#[test]
fn a_killed_shard_is_refused_then_resumes_to_the_same_merge() {
    let dir = tempfile::tempdir().unwrap();
    let s = sweep();
    let whole = run(&s, &dir.path().join("whole"), Progress::Quiet, cell).unwrap();
    let shards = run_all_shards(&s, dir.path(), 3);
    // Shard 1 killed: its journal keeps the header, 4 cells and a torn line.
    let journal = shards[1].0.join("cells.journal");
    let text = std::fs::read_to_string(&journal).unwrap();
    let mut kept: String = text.lines().take(5).map(|l| format!("{l}\n")).collect();
    kept.push_str(&text.lines().nth(5).unwrap()[..7]);
    std::fs::write(&journal, kept).unwrap();
    let e = shards_error(merge(&s, &shards));
    let owned = Shard { k: 1, n: 3 }.len(s.len());
    let MergeError::Incomplete { gaps } = &e else {
        panic!("expected missing cells, got {e}");
    };
    assert_eq!(gaps.len(), 1, "{e}");
    let g = &gaps[0];
    assert_eq!(
        (g.shard, g.dir.as_ref(), g.missing, g.cells),
        (shards[1].1, Some(&shards[1].0), owned - 4, owned)
    );
    assert_eq!(g.first.len(), (owned - 4).min(LISTED));
    assert!(g.first.iter().all(|c| shards[1].1.owns(c.index)));
    let e = e.to_string();
    assert!(
        e.contains(&format!(
            "shard 1/3 ({}): {} of its {owned} cells missing",
            shards[1].0.display(),
            owned - 4
        )),
        "{e}"
    );
    assert!(e.contains("nothing merged"), "{e}");
    // Resumed: only the missing cells run, and the merge equals the whole sweep.
    let calls = std::sync::atomic::AtomicUsize::new(0);
    let resumed = run_shard(&s, shards[1].1, &shards[1].0, Progress::Quiet, |v| {
        calls.fetch_add(1, std::sync::atomic::Ordering::SeqCst);
        cell(v)
    })
    .unwrap();
    assert_eq!(calls.into_inner(), owned - 4);
    assert_eq!(resumed.computed, owned - 4);
    let merged = merge(&s, &shards).unwrap();
    assert_eq!(merged.cells, whole.cells);
    assert_eq!(merged.failures, whole.failures);
    // A shard directory is not resumed as another shard or as the whole sweep.
    let e = run_shard(
        &s,
        Shard { k: 2, n: 3 },
        &shards[1].0,
        Progress::Quiet,
        cell,
    )
    .unwrap_err();
    assert!(e.to_string().contains("different sweep"), "{e}");
    let e = run(&s, &shards[1].0, Progress::Quiet, cell).unwrap_err();
    assert!(e.to_string().contains("different sweep"), "{e}");
}
