//! Intensity measures against an independent implementation (numpy/SciPy,
//! `bench/im_reference.py`, fixture `tests/fixtures/im_reference.json`) on
//! six of the real PEER records: every value to ≤ 1e-6 relative.

use rocking_motion::intensity::{spectral_response, IntensityMeasures};
use rocking_motion::read_at2;
use serde_json::Value;
use std::collections::BTreeMap;
use std::path::Path;

const TOL: f64 = 1e-6;

#[test]
fn intensity_measures_match_scipy_reference_on_real_records() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let fixture: Value = serde_json::from_str(
        &std::fs::read_to_string(root.join("tests/fixtures/im_reference.json")).unwrap(),
    )
    .unwrap();
    let dir = root.join("../../../shared/data/ground-motions");
    assert!(
        dir.is_dir(),
        "the reference comparison needs the shared records at {}",
        dir.display()
    );
    // worst relative error per intensity measure
    let mut worst: BTreeMap<&str, (f64, String)> = BTreeMap::new();
    let mut check = |name: &'static str, ours: f64, reference: &Value, at: String| {
        let r = reference.as_f64().unwrap();
        let rel = (ours - r).abs() / r.abs();
        assert!(
            rel <= TOL,
            "{at} {name}: ours {ours:e}, reference {r:e}, relative error {rel:e}"
        );
        let w = worst.entry(name).or_insert((0.0, String::new()));
        if rel >= w.0 {
            *w = (rel, at);
        }
    };
    let records = fixture["records"].as_array().unwrap();
    assert!(records.len() >= 5);
    for rec in records {
        let file = rec["file"].as_str().unwrap();
        let record = read_at2(dir.join(file))
            .unwrap()
            .to_record_si(rocking_motion::STANDARD_GRAVITY);
        let im = IntensityMeasures::of(&record).unwrap();
        check("PGA", im.pga_m_s2, &rec["pga_m_s2"], file.into());
        check("PGV", im.pgv_m_s, &rec["pgv_m_s"], file.into());
        check("PGD", im.pgd_m, &rec["pgd_m"], file.into());
        check("Arias", im.arias_m_s, &rec["arias_m_s"], file.into());
        check("D5-95", im.d5_95_s, &rec["d5_95_s"], file.into());
        check("Tm", im.mean_period_s, &rec["mean_period_s"], file.into());
        for s in rec["spectral"].as_array().unwrap() {
            let (t, z) = (
                s["period"].as_f64().unwrap(),
                s["damping"].as_f64().unwrap(),
            );
            let ours = spectral_response(&record, t, z).unwrap();
            let at = format!("{file} T={t} zeta={z}");
            check("Sd", ours.sd_m, &s["sd_m"], at.clone());
            check("Sv", ours.sv_m_s, &s["sv_m_s"], at.clone());
            check("Sa (absolute)", ours.sa_m_s2, &s["sa_m_s2"], at.clone());
            check("PSA", ours.psa_m_s2, &s["psa_m_s2"], at);
        }
    }
    println!("worst relative error against the SciPy reference (tolerance {TOL:e}):");
    for (name, (rel, at)) in &worst {
        println!("  {name:14} {rel:.2e}  ({at})");
    }
}

/// Every one of the 61 records: the IMs exist and obey what they must
/// (PGA as the reader's peak in g, D5-95 within the duration, T_m inside
/// the band's periods, Arias and PGV consistent with the PGA bound), and
/// all are linear (or, for Arias, quadratic) in the record's scale.
#[test]
fn intensity_measures_of_all_records_are_consistent() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/data/ground-motions");
    assert!(
        dir.is_dir(),
        "needs the shared records at {}",
        dir.display()
    );
    let mut files: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e.eq_ignore_ascii_case("at2")))
        .collect();
    files.sort();
    assert_eq!(files.len(), 61);
    let (mut lo, mut hi) = (f64::INFINITY, 0.0f64);
    for f in &files {
        let at2 = read_at2(f).unwrap();
        let record = at2.to_record_si(rocking_motion::STANDARD_GRAVITY);
        let im = IntensityMeasures::of(&record).unwrap();
        let name = f.file_name().unwrap().to_string_lossy();
        let g = rocking_motion::STANDARD_GRAVITY;
        assert!(
            (im.pga_m_s2 - at2.pga() * g).abs() <= 1e-15 * im.pga_m_s2,
            "{name}"
        );
        assert!(im.d5_95_s > 0.0 && im.d5_95_s < at2.duration(), "{name}");
        assert!(
            im.mean_period_s > 0.05 && im.mean_period_s < 4.0,
            "{name}: {}",
            im.mean_period_s
        );
        // |v(t)| ≤ PGA·t and I_A ≤ π/(2g)·PGA²·duration
        assert!(im.pgv_m_s <= im.pga_m_s2 * at2.duration(), "{name}");
        let bound = std::f64::consts::PI / (2.0 * g) * im.pga_m_s2.powi(2) * at2.duration();
        assert!(im.arias_m_s > 0.0 && im.arias_m_s <= bound, "{name}");
        // scaling: ×2.5 scales every amplitude by 2.5, Arias by 6.25, durations not at all
        let s = IntensityMeasures::of(&record.clone().with_scale(record.scale() * 2.5)).unwrap();
        let close = |a: f64, b: f64| (a - b).abs() <= 1e-12 * b.abs();
        assert!(close(s.pga_m_s2, 2.5 * im.pga_m_s2) && close(s.pgv_m_s, 2.5 * im.pgv_m_s));
        assert!(close(s.pgd_m, 2.5 * im.pgd_m) && close(s.arias_m_s, 6.25 * im.arias_m_s));
        assert!(close(s.d5_95_s, im.d5_95_s) && close(s.mean_period_s, im.mean_period_s));
        lo = lo.min(at2.pga());
        hi = hi.max(at2.pga());
    }
    println!("61 records: PGA from {lo:.4} g to {hi:.4} g");
}
