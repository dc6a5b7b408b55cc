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
        let record = read_at2(dir.join(file)).unwrap().to_record_si();
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
