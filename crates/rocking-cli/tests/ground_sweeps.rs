//! Sweeps on compliant ground (issue 44): `spectrum`, `batch` and `ida` run a scene with
//! `[ground]` cell by cell as `rocking run` runs it (the same bits), the ground's keys are axes
//! (numbers through knobs, `ground.kind` as a text axis) and reported quantities, and shards of
//! a ground spectrum merge to the bytes of one run.

mod common;

use common::{repo, rocking, text, tmp_path};
use std::path::{Path, PathBuf};

use serde_json::Value;

/// The ground's summary keys, reported by every cell.
const GROUND_KEYS: [&str; 6] = [
    "max_ground_pressure_over_mean",
    "min_ground_pressure_over_mean",
    "min_contact_fraction",
    "lift_offs",
    "max_settlement_over_static",
    "ground_energy_dissipated",
];

fn report_set() -> String {
    let keys: Vec<String> = GROUND_KEYS.iter().map(|k| format!("{k:?}")).collect();
    format!("sweep.report=[{}]", keys.join(", "))
}

/// A run's summary as `rocking run --json` prints it: the parsed object and the text (numbers are
/// compared as Rust parses the printed digits, correctly rounded; serde_json's own float parser
/// is not always, off by one unit in the last place).
struct Printed {
    value: Value,
    text: String,
}

impl Printed {
    /// The printed digits of the top-level number `key`, parsed.
    fn number(&self, key: &str) -> f64 {
        let at = self
            .text
            .find(&format!("\"{key}\":"))
            .unwrap_or_else(|| panic!("no {key} in {}", self.text));
        let rest = &self.text[at + key.len() + 3..];
        let end = rest.find([',', '}']).unwrap();
        rest[..end].trim().parse().unwrap()
    }
}

/// `rocking run SCENE --json` with these overrides (plots off): the summary.
fn run_json(scene: &Path, sets: &[String], out: &Path) -> Printed {
    let scene = scene.display().to_string();
    let out = out.display().to_string();
    let mut args = vec![
        "run",
        scene.as_str(),
        "--json",
        "--out",
        out.as_str(),
        "--set",
        "output.plots=false",
    ];
    for s in sets {
        args.extend(["--set", s.as_str()]);
    }
    let o = rocking(&args);
    assert!(o.status.success(), "{}", text(&o));
    let text = String::from_utf8(o.stdout).unwrap();
    Printed {
        value: serde_json::from_str(&text).unwrap(),
        text,
    }
}

/// A table's rows as maps of column name to text.
fn rows(path: &Path) -> Vec<Vec<(String, String)>> {
    let csv = std::fs::read_to_string(path).unwrap();
    let mut lines = csv.lines();
    let head: Vec<String> = lines
        .next()
        .unwrap()
        .split(',')
        .map(str::to_string)
        .collect();
    lines
        .map(|l| {
            head.iter()
                .cloned()
                .zip(l.split(',').map(str::to_string))
                .collect()
        })
        .collect()
}

fn col<'a>(row: &'a [(String, String)], name: &str) -> &'a str {
    row.iter()
        .find(|(k, _)| k == name)
        .map(|(_, v)| v.as_str())
        .unwrap_or_else(|| panic!("no column {name} in {row:?}"))
}

/// The summary's value of `key` against a table's text, bit for bit.
fn same_number(summary: &Printed, key: &str, cell: &str, what: &str) {
    let want = summary.number(key);
    let got: f64 = cell.parse().unwrap();
    assert_eq!(
        got.to_bits(),
        want.to_bits(),
        "{what}: {key} {got} vs run {want}"
    );
}

fn ground_scene() -> PathBuf {
    repo().join("scenes/ground-winkler.toml")
}

fn spectrum(out: &Path, axes: &[&str], extra: &[&str]) -> std::process::Output {
    let scene = ground_scene().display().to_string();
    let report = report_set();
    let out = out.display().to_string();
    let mut args = vec![
        "spectrum", &scene, "--quiet", "--out", &out, "--set", &report,
    ];
    for a in axes {
        args.extend(["--axis", a]);
    }
    args.extend_from_slice(extra);
    rocking(&args)
}

/// A ground spectrum over the bed's stiffness (a knob) and the pulse's amplitude: every cell is
/// the separate `rocking run` of its values to the last bit (class inputs and the ground's
/// keys), the stiffness changes the answer, and two shards merge to the same bytes.
#[test]
fn a_ground_spectrum_cell_is_the_run_of_that_cell_and_shards_merge_to_the_same_bytes() {
    let axes = [
        "ground.omega_v_over_p=20,200",
        "excitation.amplitude=0.8,1.3",
    ];
    let out = tmp_path("ground-spectrum");
    let o = spectrum(&out, &axes, &[]);
    assert!(o.status.success(), "{}", text(&o));
    let table = rows(&out.join("cells.csv"));
    assert_eq!(table.len(), 4);
    let scratch = tmp_path("ground-spectrum-run");
    let mut pressures = Vec::new();
    for r in &table {
        let sets = vec![
            format!("ground.omega_v_over_p={}", col(r, "ground.omega_v_over_p")),
            format!("excitation.amplitude={}", col(r, "excitation.amplitude")),
        ];
        let s = run_json(&ground_scene(), &sets, &scratch);
        let what = format!("{sets:?}");
        same_number(
            &s,
            "max_theta_over_alpha",
            col(r, "max_theta_over_alpha"),
            &what,
        );
        assert_eq!(col(r, "impacts"), s.value["impacts"].to_string(), "{what}");
        for k in GROUND_KEYS {
            same_number(&s, k, col(r, k), &what);
        }
        // The stiffer bed's pressure under the lifted base is not the softer bed's.
        pressures.push(col(r, "max_ground_pressure_over_mean").to_string());
        if s.value["overturned"] == Value::Bool(false) && s.value["first_uplift_time"].is_null() {
            assert_eq!(col(r, "class"), "no-uplift", "{what}");
        }
    }
    assert_ne!(pressures[0], pressures[2], "ω_v/p is not ignored");
    assert_ne!(pressures[1], pressures[3], "ω_v/p is not ignored");
    let meta: Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("meta.json")).unwrap()).unwrap();
    assert_eq!(meta["axes"][0]["key"], "ground.omega_v_over_p", "{meta}");

    let (s0, s1, merged) = (
        tmp_path("ground-s0"),
        tmp_path("ground-s1"),
        tmp_path("ground-merged"),
    );
    for (dir, shard) in [(&s0, "0/2"), (&s1, "1/2")] {
        let o = spectrum(dir, &axes, &["--shard", shard]);
        assert!(o.status.success(), "{}", text(&o));
    }
    let m = rocking(&[
        "merge",
        merged.to_str().unwrap(),
        s0.to_str().unwrap(),
        s1.to_str().unwrap(),
    ]);
    assert!(m.status.success(), "{}", text(&m));
    for f in ["cells.csv", "meta.json"] {
        assert_eq!(
            std::fs::read(merged.join(f)).unwrap(),
            std::fs::read(out.join(f)).unwrap(),
            "{f}"
        );
    }
    // The journal's fingerprint follows the [ground] table: another bed in the same directory
    // is another sweep, refused (exit 2) instead of mixing cells.
    let o = spectrum(&out, &axes, &["--set", "ground.zeta_v=0.1"]);
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert!(text(&o).contains("different sweep"), "{}", text(&o));
}

/// `ground.kind` as a text axis: the bed and the two springs, each cell its run.
#[test]
fn the_ground_kind_is_a_text_axis() {
    let out = tmp_path("ground-kind");
    let o = spectrum(
        &out,
        &["ground.kind=winkler,two-spring", "excitation.amplitude=1.3"],
        &[],
    );
    assert!(o.status.success(), "{}", text(&o));
    let table = rows(&out.join("cells.csv"));
    assert_eq!(
        table
            .iter()
            .map(|r| col(r, "ground.kind"))
            .collect::<Vec<_>>(),
        ["winkler", "two-spring"]
    );
    let scratch = tmp_path("ground-kind-run");
    for r in &table {
        let sets = vec![format!("ground.kind={:?}", col(r, "ground.kind"))];
        let s = run_json(&ground_scene(), &sets, &scratch);
        for k in GROUND_KEYS {
            same_number(&s, k, col(r, k), &sets[0]);
        }
    }
    assert_ne!(
        col(&table[0], "lift_offs").to_string() + col(&table[0], "max_ground_pressure_over_mean"),
        col(&table[1], "lift_offs").to_string() + col(&table[1], "max_ground_pressure_over_mean"),
    );
}

/// The bearing pressure as an axis, with the times of events reported: a cell whose pressure
/// never exceeds the bearing (or that never uplifts) leaves that time empty, every other cell
/// holds its run's time to the last bit, the empty fields survive the journal (shards merge to
/// the same bytes), and Python masks them.
#[test]
fn a_bearing_axis_reports_the_first_exceedance_empty_where_there_is_none() {
    let times = ["first_bearing_exceeded_time", "first_uplift_time"];
    let report = format!(
        "sweep.report=[\"{}\", \"{}\", \"max_ground_pressure_over_mean\"]",
        times[0], times[1]
    );
    let axes = [
        "effects.bearing_over_mean=2,50",
        "excitation.amplitude=0.3,1.3",
    ];
    let scene = ground_scene().display().to_string();
    let sweep = |out: &Path, extra: &[&str]| {
        let out = out.display().to_string();
        let mut args = vec![
            "spectrum",
            &scene,
            "--quiet",
            "--out",
            &out,
            "--set",
            &report,
            "--set",
            "effects.bearing_over_mean=3",
        ];
        for a in &axes {
            args.extend(["--axis", a]);
        }
        args.extend_from_slice(extra);
        let o = rocking(&args);
        assert!(o.status.success(), "{}", text(&o));
    };
    let out = tmp_path("bearing-axis");
    sweep(&out, &[]);
    let table = rows(&out.join("cells.csv"));
    assert_eq!(table.len(), 4);
    let scratch = tmp_path("bearing-axis-run");
    let (mut empty, mut numbers) = (0, 0);
    for r in &table {
        let sets = vec![
            format!(
                "effects.bearing_over_mean={}",
                col(r, "effects.bearing_over_mean")
            ),
            format!("excitation.amplitude={}", col(r, "excitation.amplitude")),
        ];
        let s = run_json(&ground_scene(), &sets, &scratch);
        let what = format!("{sets:?}");
        for k in times {
            if s.value[k].is_null() {
                assert_eq!(col(r, k), "", "{what}: {k}");
                empty += 1;
            } else {
                same_number(&s, k, col(r, k), &what);
                numbers += 1;
            }
        }
        // The bearing is first exceeded exactly where the largest pressure is above it.
        let bearing: f64 = col(r, "effects.bearing_over_mean").parse().unwrap();
        let max: f64 = col(r, "max_ground_pressure_over_mean").parse().unwrap();
        assert_eq!(col(r, times[0]).is_empty(), max <= bearing, "{what}");
    }
    assert!(
        empty >= 2 && numbers >= 2,
        "{empty} empty, {numbers} numbers"
    );

    let (s0, s1, merged) = (
        tmp_path("bearing-s0"),
        tmp_path("bearing-s1"),
        tmp_path("bearing-merged"),
    );
    sweep(&s0, &["--shard", "0/2"]);
    sweep(&s1, &["--shard", "1/2"]);
    let m = rocking(&[
        "merge",
        merged.to_str().unwrap(),
        s0.to_str().unwrap(),
        s1.to_str().unwrap(),
    ]);
    assert!(m.status.success(), "{}", text(&m));
    assert_eq!(
        std::fs::read(merged.join("cells.csv")).unwrap(),
        std::fs::read(out.join("cells.csv")).unwrap()
    );
    // A resumed sweep reads the empty fields back from its journal.
    sweep(&out, &[]);
    assert_eq!(
        rows(&out.join("cells.csv")),
        table,
        "resumed from the journal"
    );
}

/// The wind turbine's record scene on a Winkler bed (no rigid-surface impact map), written
/// beside its record.
fn turbine_on_ground(dir: &Path) -> PathBuf {
    let text = std::fs::read_to_string(repo().join("scenes/wind-turbine-msa.toml")).unwrap();
    let record = repo()
        .join("scenes/records/elCentro.AT2")
        .canonicalize()
        .unwrap();
    let text = text.replace("[effects]\nimpact = \"vvel\"\n", "").replace(
        "path = \"records/elCentro.AT2\"",
        &format!("path = {:?}", record.display().to_string()),
    );
    assert!(!text.contains("vvel"), "{text}");
    let text = format!(
        "{text}\n[ground]\nkind = \"winkler\"\nomega_v_over_p = 30.0\nzeta_v = 0.05\n\n\
         [output]\nforces = true\n"
    );
    std::fs::create_dir_all(dir).unwrap();
    let path = dir.join("turbine-ground.toml");
    std::fs::write(&path, text).unwrap();
    path
}

fn ground_motions(names: &[&str]) -> Vec<String> {
    let gm = repo().join("../shared/data/ground-motions");
    names
        .iter()
        .map(|r| gm.join(r).canonicalize().unwrap().display().to_string())
        .collect()
}

/// A batch and a multiple-stripe IDA of a record scene on compliant ground: each run of
/// runs.csv and each analysis of stripes.csv is the separate run of its record and scale.
#[test]
fn a_ground_batch_and_ida_equal_their_separate_runs() {
    let dir = tmp_path("ground-records");
    let scene = turbine_on_ground(&dir);
    let scene_s = scene.display().to_string();
    let recs = ground_motions(&["A-ELC180.AT2", "A-BEN360.AT2"]);
    let report = report_set();
    let check = |table: &[Vec<(String, String)>]| {
        let scratch = dir.join("run");
        for r in table {
            let path = recs.iter().find(|p| p.ends_with(col(r, "record"))).unwrap();
            let sets = vec![
                format!("excitation.path={path:?}"),
                format!("excitation.scale={}", col(r, "scale")),
            ];
            let s = run_json(&scene, &sets, &scratch);
            let what = format!("{sets:?}");
            same_number(
                &s,
                "max_theta_over_alpha",
                col(r, "max_theta_over_alpha"),
                &what,
            );
            for k in GROUND_KEYS {
                same_number(&s, k, col(r, k), &what);
            }
        }
    };

    let out = dir.join("batch");
    let out_s = out.display().to_string();
    let mut args = vec!["batch", scene_s.as_str(), "--records"];
    args.extend(recs.iter().map(String::as_str));
    args.extend([
        "--scales", "1,40", "--quiet", "--set", &report, "--out", &out_s,
    ]);
    let o = rocking(&args);
    assert!(o.status.success(), "{}", text(&o));
    let table = rows(&out.join("runs.csv"));
    assert_eq!(table.len(), 4);
    check(&table);
    // At scale 40 the base lifts off the bed: the runs are not all in full contact.
    assert!(
        table.iter().any(|r| col(r, "lift_offs") != "0"),
        "{table:?}"
    );

    let out = dir.join("msa");
    let out_s = out.display().to_string();
    let mut args = vec!["ida", scene_s.as_str(), "--records"];
    args.extend(recs.iter().map(String::as_str));
    args.extend([
        "--set",
        "ida.stripes=[2.0, 12.0]",
        "--set",
        "ida.bootstrap=200",
        "--set",
        &report,
        "--out",
        &out_s,
    ]);
    let o = rocking(&args);
    assert!(o.status.success(), "{}", text(&o));
    let table = rows(&out.join("stripes.csv"));
    assert_eq!(table.len(), 4);
    check(&table);
}

/// On compliant ground the twin is the linear foundation (the same bed with springs that also
/// pull): a ratio to it in `[sweep] report` and the twin's ground keys are a cell's, bit for bit
/// those of `rocking run` with `fixed_base_reference`, which reports them under `fixed_base`.
#[test]
fn a_twin_ratio_on_ground_is_the_runs_ratio_to_its_linear_foundation() {
    let out = tmp_path("ground-twin");
    let scene = ground_scene().display().to_string();
    let report = "sweep.report=[\"base_moment_ratio\", \"fixed_base.max_ground_pressure_over_mean\", \"fixed_base.lift_offs\"]";
    let o = rocking(&[
        "spectrum",
        &scene,
        "--quiet",
        "--out",
        out.to_str().unwrap(),
        "--set",
        report,
        "--axis",
        "excitation.amplitude=1.3",
    ]);
    assert!(o.status.success(), "{}", text(&o));
    let table = rows(&out.join("cells.csv"));
    assert_eq!(table.len(), 1);
    let s = run_json(
        &ground_scene(),
        &["output.fixed_base_reference=true".to_string()],
        &tmp_path("ground-twin-run"),
    );
    same_number(
        &s,
        "base_moment_ratio",
        col(&table[0], "base_moment_ratio"),
        "ratio",
    );
    let twin = &s.value["fixed_base"];
    let pressure = twin["max_ground_pressure_over_mean"].as_f64().unwrap();
    let cell: f64 = col(&table[0], "fixed_base.max_ground_pressure_over_mean")
        .parse()
        .unwrap();
    assert!(
        (cell - pressure).abs() <= 4.0 * f64::EPSILON * pressure,
        "{cell} {pressure}"
    );
    assert_eq!(col(&table[0], "fixed_base.lift_offs"), "0");
    assert_eq!(twin["lift_offs"], 0, "{twin}");
    assert_eq!(twin["min_contact_fraction"], 1.0, "{twin}");
    assert!(
        s.value["lift_offs"].as_u64().unwrap() > 0,
        "the run itself lifts off"
    );
}

/// Study 3's scene (docs/ground.md): the wind turbine on a bed matched to its footing rocks, and
/// its peak base moment is well below its linear foundation's (0.595 measured) while its shear is
/// above (1.21); the edge pressure (6.0 times the mean) exceeds the scene's 400 kPa bearing,
/// which the summary and the warning say; the energy balance closes to the preset's tolerance.
#[test]
fn the_turbine_on_its_footing_rocks_below_its_linear_foundations_moment() {
    let out = tmp_path("turbine-footing");
    let s = run_json(
        &repo().join("scenes/ground/turbine-elcentro.toml"),
        &[],
        &out,
    );
    let v = &s.value;
    let ratio = v["base_moment_ratio"].as_f64().unwrap();
    let shear = v["base_shear_ratio"].as_f64().unwrap();
    assert!((0.55..0.65).contains(&ratio), "{ratio}");
    assert!((1.1..1.3).contains(&shear), "{shear}");
    assert!(v["lift_offs"].as_u64().unwrap() > 10 && v["overturned"] == false);
    let pressure = v["max_ground_pressure_over_mean"].as_f64().unwrap();
    // 400 kPa over the mean pressure W / (2 B L) = 11.772 MN / 144 m² = 81.75 kPa.
    let bearing = 4.0e5 / (11.772e6 / 144.0);
    assert!(pressure > bearing, "{pressure} against {bearing}");
    assert!(v["first_bearing_exceeded_time_s"].as_f64().unwrap() > 0.0);
    assert!(v["warnings"].to_string().contains("bearing pressure"));
    assert!(v["fixed_base"]["min_contact_fraction"] == 1.0);
    let residual = v["energy_balance_residual"].as_f64().unwrap().abs();
    assert!(residual < 1e-6, "{residual:e}");
    let _ = std::fs::remove_dir_all(out);
}

/// A rigid-surface scene goes on a bed by overrides alone: `effects.impact=null` removes its
/// impact map (refused on a bed), and the run is the same, bit for bit, as that of a copy of the
/// file without the line and with the `[ground]` table. Removing a key the scene lacks exits 2.
#[test]
fn a_rigid_scene_goes_on_a_bed_by_overrides() {
    let scene = repo().join("scenes/fig5-flexible.toml");
    let bed: Vec<String> = [
        "ground.kind=winkler",
        "ground.omega_v_over_p=50",
        "ground.zeta_v=0.05",
    ]
    .map(String::from)
    .to_vec();
    let with = |extra: &str| {
        let mut sets = bed.clone();
        sets.push(extra.to_string());
        sets
    };
    let by_overrides = run_json(
        &scene,
        &with("effects.impact=null"),
        &tmp_path("bed-overrides"),
    );
    let copy = tmp_path("bed-copy.toml");
    let text_of = std::fs::read_to_string(&scene).unwrap();
    assert!(text_of.lines().any(|l| l.starts_with("impact")));
    let kept: Vec<&str> = text_of
        .lines()
        .filter(|l| !l.starts_with("impact"))
        .collect();
    std::fs::write(
        &copy,
        kept.join("\n") + "\n\n[ground]\nkind = \"winkler\"\nomega_v_over_p = 50\nzeta_v = 0.05\n",
    )
    .unwrap();
    let by_copy = run_json(&copy, &[], &tmp_path("bed-copy"));
    assert!(by_overrides.value["lift_offs"].as_u64().unwrap() > 0);
    // The same run: every field but the scene's path and the overrides it lists.
    let strip = |p: &Printed| {
        let mut v = p.value.clone();
        let map = v.as_object_mut().unwrap();
        assert!(map.remove("scene").is_some() && map.remove("overrides").is_some());
        v
    };
    assert_eq!(strip(&by_overrides), strip(&by_copy));
    let s = scene.display().to_string();
    let o = rocking(&["check", &s, "--set", "effects.impcat=null"]);
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert!(
        text(&o).contains("`effects.impcat` is not in the scene"),
        "{}",
        text(&o)
    );
}
