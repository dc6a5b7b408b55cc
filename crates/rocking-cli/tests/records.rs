//! Record files end to end (issue 30): one units model — a record in an absolute unit moves the
//! structure by its physical value whatever the structure's g, a record in g is felt as the
//! structure's g, and a dimensionless scene converts with the same g that relates its R and p;
//! a download folder is read alike by `ida` and `batch`.

mod common;

use common::{repo, rocking};
use std::path::Path;

use serde_json::Value;

/// `run --json` of `scene` (text) with the record `record` (AT2 text) beside it.
fn run(dir: &Path, scene: &str, record: &str) -> Value {
    std::fs::create_dir_all(dir).unwrap();
    std::fs::write(dir.join("scene.toml"), scene).unwrap();
    std::fs::write(dir.join("rec.AT2"), record).unwrap();
    let (s, out) = (dir.join("scene.toml"), dir.join("out"));
    let o = rocking(&[
        "run",
        "--json",
        &s.display().to_string(),
        "--out",
        &out.display().to_string(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    serde_json::from_slice(&o.stdout).unwrap()
}

/// A ramp to `peak` over 0.5 s, held for 0.5 s, in the unit `units` names (AT2 line 3).
fn ramp(units: &str, peak: f64) -> String {
    let samples: Vec<String> = (0..100)
        .map(|k| format!("{:.15e}", peak * (k.min(49) as f64 / 49.0)))
        .collect();
    format!(
        "RAMP\nSYNTHETIC, 000\nACCELERATION TIME SERIES IN UNITS OF {units}\nNPTS= 100, DT= .01 SEC\n{}\n",
        samples.join("\n")
    )
}

/// The structure's static uplift acceleration in units of its g tan α, and α.
fn uplift_level(v: &Value) -> (f64, f64) {
    let d = &v["derived"];
    (
        d["static_uplift_over_g_tan_alpha"].as_f64().unwrap(),
        d["alpha"].as_f64().unwrap(),
    )
}

fn uplifted(v: &Value) -> bool {
    !v["first_uplift_time"].is_null()
}

/// A rigid block (B/H = 0.1) at g = 20, 1.62 and 9.81 m/s² under a ramp to 1e-4 below and above
/// its uplift level: in m/s² and cm/s² the level is g tan α in m/s² (the record is absolute);
/// in g it is tan α g (the record is felt as the structure's g). The old reader converted every
/// unit to g with 9.80665 and the study multiplied by the structure's g: at g = 20 a record of
/// 0.9999 g tan α in m/s² overturned the block, at g = 9.81 it was 3.4e-4 too strong.
#[test]
fn an_absolute_record_is_absolute_at_any_g() {
    let tmp = tempfile::tempdir().unwrap();
    for g in [20.0, 1.62, 9.81] {
        let scene = format!(
            "[structure]\nh = 10.0\nb = 1.0\nei = 1.0e12\nm = 1.0e5\ng = {g:?}\n\n[effects]\n\
             flexibility = false\n\n[excitation]\nkind = \"record\"\npath = \"rec.AT2\"\n\n\
             [solver]\nafter_excitation = 0.5\n"
        );
        let probe = run(&tmp.path().join("probe"), &scene, &ramp("M/S/S", 0.0));
        let (ratio, alpha) = uplift_level(&probe);
        let level = ratio * g * alpha.tan(); // m/s²
        for (units, per_m_s2) in [("M/S/S", 1.0), ("CM/SEC/SEC", 100.0), ("G", 1.0 / g)] {
            for (factor, lifts) in [(1.0 - 1e-4, false), (1.0 + 1e-4, true)] {
                let dir = tmp.path().join(format!("{g}-{per_m_s2}-{factor}"));
                let v = run(&dir, &scene, &ramp(units, level * factor * per_m_s2));
                assert_eq!(
                    uplifted(&v),
                    lifts,
                    "g = {g}, {units}, {factor} x the uplift level: {}",
                    v["excitation"]
                );
                assert_eq!(v["overturned"], false, "g = {g}, {units}");
            }
        }
    }
}

/// A dimensionless block with R = 2 m: its p (1/s) says which g relates R and p, and the same g
/// converts a record in m/s² (the old code related them with 9.81 and converted with 9.80665).
#[test]
fn a_dimensionless_scene_converts_with_the_g_of_its_r_and_p() {
    let tmp = tempfile::tempdir().unwrap();
    let scene = "[structure]\nalpha = 0.1\nr = 2.0\n\n[effects]\nflexibility = false\n\n\
                 [excitation]\nkind = \"record\"\npath = \"rec.AT2\"\n\n[solver]\n\
                 after_excitation = 0.5\n";
    let probe = run(&tmp.path().join("probe"), scene, &ramp("M/S/S", 0.0));
    let p = probe["derived"]["p_per_second"].as_f64().unwrap();
    let g = p * p * 2.0;
    assert!((g - 9.80665).abs() < 1e-12, "g = p^2 R = {g}");
    let (ratio, alpha) = uplift_level(&probe);
    for (factor, lifts) in [(1.0 - 1e-4, false), (1.0 + 1e-4, true)] {
        let dir = tmp.path().join(format!("{factor}"));
        let v = run(
            &dir,
            scene,
            &ramp("M/S/S", ratio * g * alpha.tan() * factor),
        );
        assert_eq!(uplifted(&v), lifts, "{factor}: {}", v["excitation"]);
    }
}

/// A PEER download folder holds `_SearchResults.csv`, a README and maybe a sub-folder named like
/// a record; with an ESM file beside the AT2 files, `ida` and `batch` both run the three records
/// and nothing else (the old `ida` stopped at README.txt, the old `batch` skipped the ESM file,
/// both stopped at the sub-folder).
#[test]
fn ida_and_batch_read_a_download_folder_alike() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("PEER_download");
    std::fs::create_dir_all(dir.join("RSN9_NOTHING.AT2")).unwrap();
    std::fs::write(dir.join("RSN9_NOTHING.AT2/README.txt"), "a folder").unwrap();
    let gm = repo().join("../shared/data/ground-motions");
    for f in ["A-TIN000.AT2", "ARL360.at2"] {
        std::fs::copy(gm.join(f), dir.join(f)).unwrap();
    }
    let esm = "IT.NRC..HNE.D.EMSC-20161030_0000029.ACC.MP.ASC";
    std::fs::copy(
        repo()
            .join("crates/rocking-motion/tests/corpus/esm")
            .join(esm),
        dir.join(esm),
    )
    .unwrap();
    std::fs::write(
        dir.join("_SearchResults.csv"),
        "Record Sequence Number,Earthquake Name\n1,Imperial Valley-02\n",
    )
    .unwrap();
    std::fs::write(dir.join("README.txt"), "PEER NGA-West2 download\n").unwrap();
    let want = ["A-TIN000.AT2", "ARL360.at2", esm];
    let first_column = |csv: &Path| -> Vec<String> {
        std::fs::read_to_string(csv)
            .unwrap()
            .lines()
            .skip(1)
            .map(|l| l.split(',').next().unwrap().to_string())
            .collect()
    };
    let records = dir.display().to_string();
    let out = tmp.path().join("ida");
    let o = rocking(&[
        "ida",
        "scenes/wind-turbine-ida.toml",
        "--records",
        &records,
        "--set",
        "ida.bootstrap=200",
        "--out",
        &out.display().to_string(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert_eq!(first_column(&out.join("records.csv")), want);
    let out = tmp.path().join("batch");
    let o = rocking(&[
        "batch",
        "scenes/wind-turbine-elcentro.toml",
        "--records",
        &records,
        "--scales",
        "1",
        "--out",
        &out.display().to_string(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert_eq!(first_column(&out.join("runs.csv")), want);
}

/// A record lasting 2e300 s on a rigid block (one step per sample would do) is refused up front
/// naming its path (it failed "step size underflow" with t spelled in 301 digits), and the
/// summary spells extreme numbers short (a scale of 1e-300 was 300 digits).
#[test]
fn extreme_time_steps_and_scales_are_refused_or_spelled_short() {
    let tmp = tempfile::tempdir().unwrap();
    let scene = "[structure]\nh = 10.0\nb = 1.0\nei = 1.0e12\nm = 1.0e5\n\n[effects]\n\
                 flexibility = false\n\n[excitation]\nkind = \"record\"\npath = \"rec.AT2\"\n\
                 scale = 1e-300\n";
    let rec = "T\nE\nACCELERATION TIME SERIES IN UNITS OF G\nNPTS= 3, DT= 1e300 SEC\n0 0.5 0\n";
    let dir = tmp.path().join("long");
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("scene.toml"), scene).unwrap();
    std::fs::write(dir.join("rec.AT2"), rec).unwrap();
    let o = rocking(&["check", &dir.join("scene.toml").display().to_string()]);
    assert_eq!(o.status.code(), Some(2));
    let e = String::from_utf8_lossy(&o.stderr);
    assert!(
        e.contains("scene.toml:12:1:") && e.contains("lasts 2e300 s"),
        "{e}"
    );
    let v = run(
        &tmp.path().join("short"),
        scene,
        &rec.replace("1e300", "1e5"),
    );
    let desc = v["excitation"].as_str().unwrap();
    assert!(
        desc.contains("dt = 100000 s") && desc.contains("× 1e-300"),
        "{desc}"
    );
    assert!(!desc.contains("0000000000000000"), "{desc}");
}
