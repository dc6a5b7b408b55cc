//! `rocking ida` and the record formats, end to end through the binary: the same record in each
//! format gives the run summary of its AT2; hunt-and-fill capacities agree with an independent
//! bisection; bad [ida] settings exit 2 naming the key and the allowed range.

mod common;

use common::{repo, rocking};
use std::path::Path;

use serde_json::Value;

fn summary(sets: &[String], out: &Path) -> Value {
    let mut args = vec![
        "run",
        "scenes/wind-turbine-elcentro.toml",
        "--json",
        "--set",
        "output.history=\"none\"",
        "--set",
        "output.plots=false",
        "--set",
        "output.events=false",
    ];
    let out_s = out.display().to_string();
    for s in sets {
        args.extend(["--set", s.as_str()]);
    }
    args.extend(["--out", &out_s]);
    let o = rocking(&args);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let mut v: Value = serde_json::from_slice(&o.stdout).unwrap();
    // What names the record (and the overrides that point at it) differs by design.
    for k in ["excitation", "scene", "title", "overrides"] {
        v.as_object_mut().unwrap().remove(k);
    }
    v
}

/// The AT2 record of the wind-turbine scene, in g.
fn at2() -> (f64, Vec<f64>) {
    let r = rocking_motion::read_at2(repo().join("scenes/records/elCentro.AT2")).unwrap();
    (r.dt, r.samples)
}

#[test]
fn same_record_in_every_format_gives_the_at2_summary() {
    let tmp = tempfile::tempdir().unwrap();
    let (dt, a) = at2();
    let reference = summary(&[], &tmp.path().join("at2"));

    // plain text, one column in g with the stated dt: the same f64 samples, the same summary
    let text = tmp.path().join("el.txt");
    let body: String = a.iter().map(|x| format!("{x:?}\n")).collect();
    std::fs::write(&text, format!("# El Centro in g\n{body}")).unwrap();
    let got = summary(
        &[
            format!("excitation.path={:?}", text.display().to_string()),
            "excitation.units=\"g\"".into(),
            format!("excitation.dt={dt:?}"),
        ],
        &tmp.path().join("text"),
    );
    assert_eq!(got, reference, "text");

    // ESM ASCII in cm/s^2 (the database's unit), an absolute unit: the same motion as the AT2
    // in g is felt by this structure (g = 9.81) when written as a x 981 cm/s^2, whatever
    // standard gravity is; the summary agrees to the rounding of the unit change
    let esm = tmp.path().join("el.ASC");
    let g_structure = 9.81;
    let k = 100.0 * g_structure;
    let mut s = format!(
        "EVENT_NAME: Imperial Valley\nNETWORK: CI\nSTATION_CODE: ELC\nDATA_TYPE: ACCELERATION\n\
         UNITS: cm/s^2\nSAMPLING_INTERVAL_S: {dt:.6}\nNDATA: {}\nUSER5:\n",
        a.len()
    );
    for x in &a {
        s.push_str(&format!("{:?}\n", x * k));
    }
    std::fs::write(&esm, s).unwrap();
    let r = rocking_motion::read_record(&esm, rocking_motion::RecordFormat::Esm, None).unwrap();
    assert_eq!(r.dt, dt);
    for (x, y) in r.samples.iter().zip(&a) {
        assert_eq!(*x, y * k); // as written, in cm/s^2
    }
    let got = summary(
        &[format!("excitation.path={:?}", esm.display().to_string())],
        &tmp.path().join("esm"),
    );
    let rel = |v: &Value, k: &str| v[k].as_f64().unwrap();
    for key in ["max_theta_over_alpha", "max_u_over_ucr", "end_time"] {
        let (x, y) = (rel(&got, key), rel(&reference, key));
        assert!((x - y).abs() <= 1e-9 * y.abs(), "esm {key}: {x} vs {y}");
    }
    assert_eq!(got["impacts"], reference["impacts"]);
    // the scene may not contradict the file's unit
    let o = rocking(&[
        "check",
        "scenes/wind-turbine-elcentro.toml",
        "--set",
        &format!("excitation.path={:?}", esm.display().to_string()),
        "--set",
        "excitation.units=\"g\"",
    ]);
    assert_eq!(o.status.code(), Some(2));
    let e = String::from_utf8_lossy(&o.stderr);
    assert!(e.contains("el.ASC") && e.contains("units"), "{e}");

    // K-NET ASCII: integer counts × scale factor, mean removed
    let knet = tmp.path().join("EL0001.NS");
    let gal = 0.01 / g_structure; // the structure's g per gal
    let factor = 7845.0 / 8223420.0; // gal per count
    let mean = a.iter().sum::<f64>() / a.len() as f64;
    let mut s = String::new();
    for l in [
        "Origin Time       1940/05/19 04:36:00",
        "Lat.              32.733",
        "Long.             -115.500",
        "Depth. (km)       16",
        "Mag.              6.9",
        "Station Code      ELC",
        "Station Lat.      32.795",
        "Station Long.     -115.548",
        "Station Height(m) 0",
        "Record Time       1940/05/19 04:36:00",
        "Sampling Freq(Hz) 50Hz",
        "Duration Time(s)  31",
        "Dir.              N-S",
        "Scale Factor      7845(gal)/8223420",
        "Max. Acc. (gal)   312.6",
        "Last Correction   1940/05/19 04:36:00",
        "Memo.",
    ] {
        s.push_str(l);
        s.push('\n');
    }
    for row in a.chunks(8) {
        for x in row {
            s.push_str(&format!(
                " {:8}",
                ((x - mean) / gal / factor).round() as i64
            ));
        }
        s.push('\n');
    }
    std::fs::write(&knet, s).unwrap();
    let r = rocking_motion::read_record(&knet, rocking_motion::RecordFormat::Knet, None).unwrap();
    assert!((r.dt - dt).abs() < 1e-15);
    for (x, y) in r.samples.iter().zip(&a) {
        // in gal: one count of quantisation, plus the mean of the rounding errors
        assert!(
            (x * gal - (y - mean)).abs() <= 1.01 * factor * gal,
            "{x} {y}"
        );
    }
    let got = summary(
        &[format!("excitation.path={:?}", knet.display().to_string())],
        &tmp.path().join("knet"),
    );
    for key in ["max_theta_over_alpha", "max_u_over_ucr"] {
        let (x, y) = (rel(&got, key), rel(&reference, key));
        assert!((x - y).abs() <= 1e-3 * y.abs(), "knet {key}: {x} vs {y}");
    }
}

#[test]
fn text_record_without_units_and_velocity_files_are_refused() {
    let tmp = tempfile::tempdir().unwrap();
    let text = tmp.path().join("a.txt");
    std::fs::write(&text, "0 0.1\n0.01 0.2\n0.02 0\n").unwrap();
    let o = rocking(&[
        "check",
        "scenes/wind-turbine-elcentro.toml",
        "--set",
        &format!("excitation.path={:?}", text.display().to_string()),
    ]);
    assert_eq!(o.status.code(), Some(2));
    let e = String::from_utf8_lossy(&o.stderr);
    assert!(e.contains("units") && e.contains("\"m/s2\""), "{e}");
    let esm = tmp.path().join("v.ASC");
    std::fs::write(
        &esm,
        "DATA_TYPE: VELOCITY\nUNITS: cm/s\nSAMPLING_INTERVAL_S: 0.01\nNDATA: 2\n1\n2\n",
    )
    .unwrap();
    let o = rocking(&[
        "check",
        "scenes/wind-turbine-elcentro.toml",
        "--set",
        &format!("excitation.path={:?}", esm.display().to_string()),
    ]);
    assert_eq!(o.status.code(), Some(2));
    let e = String::from_utf8_lossy(&o.stderr);
    assert!(e.contains("v.ASC:1") && e.contains("acceleration"), "{e}");
    let o = rocking(&[
        "check",
        "scenes/wind-turbine-elcentro.toml",
        "--set",
        "excitation.format=\"sac\"",
    ]);
    assert_eq!(o.status.code(), Some(2));
    let e = String::from_utf8_lossy(&o.stderr);
    assert!(e.contains("`format`") && e.contains("\"knet\""), "{e}");
}

/// A record an IDA refuses is named as the study's record: the override the study set for it
/// is not the user's `--set`.
#[test]
fn a_refused_record_of_an_ida_is_named_as_the_studys() {
    let tmp = tempfile::tempdir().unwrap();
    let text = tmp.path().join("bad.AT2");
    std::fs::write(&text, "not a PEER record\n").unwrap();
    let o = rocking(&[
        "ida",
        "scenes/wind-turbine-ida.toml",
        "--records",
        text.to_str().unwrap(),
        "--out",
        tmp.path().join("out").to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2));
    let e = String::from_utf8_lossy(&o.stderr);
    let record = std::fs::canonicalize(&text).unwrap();
    assert!(
        e.starts_with(&format!(
            "error: record {} of the study: ",
            record.display()
        )),
        "{e}"
    );
    assert!(
        e.contains("cannot use the record") && !e.contains("--set"),
        "{e}"
    );
}

/// Overturns at this Sa level (m/s²)? `sa1`: the record's Sa at scale 1.
fn overturns(record: &str, sa: f64, sa1: f64, out: &Path) -> bool {
    let o = rocking(&[
        "run",
        "scenes/wind-turbine-ida.toml",
        "--json",
        "--set",
        &format!("excitation.path={record:?}"),
        "--set",
        &format!("excitation.scale={:?}", sa / sa1),
        "--set",
        "output.history=\"none\"",
        "--out",
        &out.display().to_string(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let v: Value = serde_json::from_slice(&o.stdout).unwrap();
    v["overturned"].as_bool().unwrap()
}

#[test]
fn ida_capacities_agree_with_a_bisection_and_the_fit_is_written() {
    let tmp = tempfile::tempdir().unwrap();
    let gm = repo().join("../shared/data/ground-motions");
    let recs: Vec<String> = ["A-ELC180.AT2", "A-PEL180.AT2", "A-BEN360.AT2"]
        .iter()
        .map(|r| gm.join(r).canonicalize().unwrap().display().to_string())
        .collect();
    let out = tmp.path().join("ida");
    let mut args = vec!["ida", "scenes/wind-turbine-ida.toml", "--records"];
    args.extend(recs.iter().map(String::as_str));
    let out_s = out.display().to_string();
    args.extend(["--set", "ida.bootstrap=200", "--out", &out_s]);
    let o = rocking(&args);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let json = std::fs::read_to_string(out.join("fragility.json")).unwrap();
    assert!(!json.contains("null") && !json.contains("NaN"), "{json}");
    let fit: Value = serde_json::from_str(&json).unwrap();
    let median = fit["median_m_s2"].as_f64().unwrap();
    let band = &fit["bootstrap"]["median_interval_m_s2"];
    assert!(band[0].as_f64().unwrap() <= median && median <= band[1].as_f64().unwrap());
    for f in [
        "ida.csv",
        "ida.svg",
        "ida.png",
        "ida.pdf",
        "fragility-fit.svg",
        "fragility-fit.png",
        "fragility-fit.pdf",
    ] {
        assert!(out.join(f).is_file(), "{f}");
    }
    // The IDA figure draws every analysis of ida.csv: a dot per upright one, a square (the
    // overturned marker, red) per overturned one; one more of each in the legend.
    let analyses = std::fs::read_to_string(out.join("ida.csv")).unwrap();
    let overturned = analyses.lines().filter(|l| l.contains(",true,")).count();
    let upright = analyses.lines().filter(|l| l.contains(",false,")).count();
    assert!(overturned >= 3, "each record overturns: {analyses}");
    let svg = std::fs::read_to_string(out.join("ida.svg")).unwrap();
    assert_eq!(svg.matches("<circle").count(), upright + 1);
    assert_eq!(
        svg.split("<rect")
            .filter(|r| r.split('>').next().unwrap().contains("fill=\"#AC2000\""))
            .count(),
        overturned + 1
    );
    let mut table = csv::Reader::from_path(out.join("records.csv")).unwrap();
    let heads = table.headers().unwrap().clone();
    let col = |n: &str| heads.iter().position(|h| h == n).unwrap();
    let rows: Vec<csv::StringRecord> = table.records().map(Result::unwrap).collect();
    assert_eq!(rows.len(), 3);
    let tol = 0.01;
    let row = &rows[0];
    let num = |c: &str| row[col(c)].parse::<f64>().unwrap();
    let (sa1, cap, below) = (
        num("im_m_s2"),
        num("capacity_im_m_s2"),
        num("survived_below_im_m_s2"),
    );
    assert!(cap - below <= tol * cap + 1e-12, "{below} .. {cap}");
    let path = &row[col("path")];
    // an independent bisection on [0, 2 × capacity] to the same tolerance
    let scratch = tmp.path().join("run");
    let (mut lo, mut hi) = (0.0, 2.0 * cap);
    assert!(overturns(path, hi, sa1, &scratch));
    assert!(overturns(path, cap, sa1, &scratch));
    assert!(!overturns(path, below, sa1, &scratch));
    while hi - lo > tol * hi {
        let mid = 0.5 * (lo + hi);
        if overturns(path, mid, sa1, &scratch) {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    // both bracket the same threshold: the intervals (lo, hi] and (below, cap] overlap
    assert!(
        lo < cap && below < hi,
        "bisection ({lo}, {hi}] vs IDA ({below}, {cap}]"
    );
    assert!(
        (hi - cap).abs() <= 2.0 * tol * cap,
        "bisection {hi} vs IDA {cap}"
    );
}

#[test]
fn bad_ida_settings_exit_2_naming_the_key_and_range() {
    for (set, key, allowed) in [
        ("ida.tolerance=2.0", "`tolerance`", "0 < tolerance < 1"),
        ("ida.im=\"pgv\"", "`im`", "\"pga\""),
        ("ida.period=-1.0", "`period`", "0.001 s <= period <= 100 s"),
        ("ida.period=1e300", "`period`", "0.001 s <= period <= 100 s"),
        ("ida.max_gap=0.001", "`max_gap`", "tolerance <= max_gap < 1"),
        ("ida.stripes=[1.0, -2.0]", "`stripes`", "finite and > 0"),
        (
            "ida.stripes=[]",
            "`stripes`",
            "2 to 1000 different IM levels",
        ),
        (
            "ida.stripes=[5.0]",
            "`stripes`",
            "2 to 1000 different IM levels",
        ),
    ] {
        let o = rocking(&["ida", "scenes/wind-turbine-ida.toml", "--set", set]);
        assert_eq!(o.status.code(), Some(2), "{set}");
        let e = String::from_utf8_lossy(&o.stderr);
        assert!(e.contains(key) && e.contains(allowed), "{set}: {e}");
        assert!(e.contains("wind-turbine-ida.toml"), "{set}: {e}");
    }
}

/// Log-likelihood of stripe counts under a lognormal fragility (Baker 2015, eq. 11).
fn stripe_log_likelihood(stripes: &[(f64, f64, f64)], theta: f64, beta: f64) -> f64 {
    // Φ by Simpson's rule on the normal density from -12 to x (about 1e-12 with 20000 panels;
    // std has no erf), independent of the library's own Φ.
    fn phi(x: f64) -> f64 {
        let (a, n) = (-12.0_f64, 20_000);
        if x <= a {
            return 0.0;
        }
        let h = (x - a) / n as f64;
        let f = |t: f64| (-0.5 * t * t).exp() / (2.0 * std::f64::consts::PI).sqrt();
        let mut sum = f(a) + f(x);
        for k in 1..n {
            sum += f(a + k as f64 * h) * if k % 2 == 1 { 4.0 } else { 2.0 };
        }
        (sum * h / 3.0).min(1.0)
    }
    stripes
        .iter()
        .map(|&(im, n, z)| {
            let p = phi((im / theta).ln() / beta).clamp(1e-300, 1.0 - 1e-16);
            z * p.ln() + (n - z) * (1.0 - p).ln()
        })
        .sum()
}

#[test]
fn multiple_stripes_count_the_runs_and_fit_by_maximum_likelihood() {
    let tmp = tempfile::tempdir().unwrap();
    let gm = repo().join("../shared/data/ground-motions");
    let recs: Vec<String> = [
        "A-ELC180.AT2",
        "A-PEL180.AT2",
        "A-BEN360.AT2",
        "A-BPL160.AT2",
    ]
    .iter()
    .map(|r| gm.join(r).canonicalize().unwrap().display().to_string())
    .collect();
    let out = tmp.path().join("msa");
    let out_s = out.display().to_string();
    let mut args = vec!["ida", "scenes/wind-turbine-ida.toml", "--records"];
    args.extend(recs.iter().map(String::as_str));
    // Unsorted, with a repeated level: each level is run once.
    let levels = "ida.stripes=[30.0, 4.0, 8.0, 12.0, 16.0, 20.0, 8.0]";
    args.extend([
        "--set",
        levels,
        "--set",
        "ida.bootstrap=200",
        "--out",
        &out_s,
    ]);
    let o = rocking(&args);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(
        !out.join("ida.csv").exists(),
        "a stripe study writes stripes.csv"
    );
    let json = std::fs::read_to_string(out.join("fragility.json")).unwrap();
    assert!(!json.contains("null") && !json.contains("NaN"), "{json}");
    let fit: Value = serde_json::from_str(&json).unwrap();
    assert_eq!(fit["method"], "multiple-stripe");
    assert_eq!(fit["analyses"], 4 * 6);
    // The counts are those of stripes.csv, level by level, and every run is at its level.
    let mut table = csv::Reader::from_path(out.join("stripes.csv")).unwrap();
    let rows: Vec<csv::StringRecord> = table.records().map(Result::unwrap).collect();
    assert_eq!(rows.len(), 4 * 6);
    let mut counts: Vec<(f64, f64, f64)> = Vec::new();
    for st in fit["stripes"].as_array().unwrap() {
        let im = st["im_m_s2"].as_f64().unwrap();
        let at: Vec<&csv::StringRecord> = rows
            .iter()
            .filter(|r| r[1].parse::<f64>().unwrap() == im)
            .collect();
        assert_eq!(at.len(), 4, "level {im}");
        let collapsed = at.iter().filter(|r| &r[3] == "true").count();
        assert_eq!(
            st["collapsed"].as_u64().unwrap() as usize,
            collapsed,
            "level {im}"
        );
        counts.push((im, 4.0, collapsed as f64));
    }
    let levels: Vec<f64> = counts.iter().map(|c| c.0).collect();
    assert_eq!(levels, [4.0, 8.0, 12.0, 16.0, 20.0, 30.0]);
    let total: f64 = counts.iter().map(|c| c.2).sum();
    assert!(
        total > 0.0 && total < 24.0,
        "the levels bracket the capacities: {counts:?}"
    );
    // The fit maximises the likelihood: every nearby (θ, β) is less likely.
    let (theta, beta) = (
        fit["median_m_s2"].as_f64().unwrap(),
        fit["beta"].as_f64().unwrap(),
    );
    let best = stripe_log_likelihood(&counts, theta, beta);
    for (dt, db) in [
        (1.02, 1.0),
        (0.98, 1.0),
        (1.0, 1.03),
        (1.0, 0.97),
        (1.02, 1.03),
    ] {
        let other = stripe_log_likelihood(&counts, theta * dt, beta * db);
        assert!(
            other < best,
            "L({dt} θ, {db} β) = {other} >= L(θ, β) = {best}"
        );
    }
    let band = &fit["bootstrap"]["median_interval_m_s2"];
    assert!(band[0].as_f64().unwrap() <= theta && theta <= band[1].as_f64().unwrap());
    for f in ["fragility-fit.svg", "ida.svg"] {
        let svg = std::fs::read_to_string(out.join(f)).unwrap();
        assert!(svg.contains("Sa(T = 4.5 s, ζ = 5 %)"), "{f} names the IM");
    }
}

/// fragility.json is a function of the study alone (issue 30, item 17): two runs of one study
/// write the same bytes (it held `elapsed_s`), and what the study took is in timing.json; a
/// band on three records says it is a rough guide (item 4).
#[test]
fn fragility_json_is_the_same_on_every_run_and_timing_is_apart() {
    let tmp = tempfile::tempdir().unwrap();
    let gm = repo().join("../shared/data/ground-motions");
    let recs: Vec<String> = ["A-BEN360.AT2", "A-BPL160.AT2", "A-ELC180.AT2"]
        .iter()
        .map(|r| gm.join(r).canonicalize().unwrap().display().to_string())
        .collect();
    let outs = [tmp.path().join("a"), tmp.path().join("b")];
    for (out, threads) in outs.iter().zip(["1", "2"]) {
        let out_s = out.display().to_string();
        let mut args = vec![
            "ida",
            "scenes/wind-turbine-msa.toml",
            "--set",
            "ida.stripes=[5.0, 13.0, 20.0, 60.0]",
            "--set",
            "ida.bootstrap=200",
            "--threads",
            threads,
            "--out",
            &out_s,
            "--records",
        ];
        args.extend(recs.iter().map(String::as_str));
        let o = rocking(&args);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let timing: Value =
            serde_json::from_slice(&std::fs::read(out.join("timing.json")).unwrap()).unwrap();
        assert!(timing["seconds"].as_f64().unwrap() > 0.0, "{timing}");
        assert_eq!(timing["analyses"], 12, "{timing}");
        // Three records per stripe: the band is written, and said to be a rough guide (issue
        // 30, item 4), in fragility.json and on stderr.
        let fit: Value =
            serde_json::from_slice(&std::fs::read(out.join("fragility.json")).unwrap()).unwrap();
        let warning = fit["bootstrap"]["warning"].as_str().unwrap_or_default();
        assert!(
            warning.contains("rests on 3 records per stripe") && warning.contains("fewer than 10"),
            "{fit}"
        );
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert!(stderr.contains(&format!("warning: {warning}")), "{stderr}");
    }
    let [a, b] = outs.map(|o| std::fs::read(o.join("fragility.json")).unwrap());
    assert!(!String::from_utf8_lossy(&a).contains("elapsed"));
    assert!(
        a == b,
        "fragility.json differs between two runs of one study"
    );
}

/// `[sweep] report` in a record suite (issue 47, item 9: validated, then written nowhere): the
/// batch's runs.csv and the study's stripes.csv hold a column per reported quantity, a finite
/// number in every row of a finished run.
#[test]
fn batch_and_ida_write_the_reported_columns() {
    let tmp = tempfile::tempdir().unwrap();
    let report = "sweep.report=[\"max_base_moment_over_wb\", \"impacts\"]";
    let gm = repo().join("../shared/data/ground-motions");
    let recs: Vec<String> = ["A-ELC180.AT2", "A-BEN360.AT2"]
        .iter()
        .map(|r| gm.join(r).canonicalize().unwrap().display().to_string())
        .collect();
    let columns = |file: &Path, rows: usize| {
        let mut table = csv::Reader::from_path(file).unwrap();
        let heads = table.headers().unwrap().clone();
        let records: Vec<csv::StringRecord> = table.records().map(Result::unwrap).collect();
        assert_eq!(records.len(), rows, "{}", file.display());
        for q in ["max_base_moment_over_wb", "impacts"] {
            let c = heads
                .iter()
                .position(|h| h == q)
                .unwrap_or_else(|| panic!("{}: no column {q} in {heads:?}", file.display()));
            for r in &records {
                let v: f64 = r[c].parse().unwrap();
                assert!(v.is_finite() && v >= 0.0, "{q} = {v}");
            }
        }
    };
    let out = tmp.path().join("batch");
    let mut args = vec!["batch", "scenes/wind-turbine-ida.toml", "--records"];
    args.extend(recs.iter().map(String::as_str));
    let out_s = out.display().to_string();
    args.extend([
        "--scales", "0.5,1", "--quiet", "--set", report, "--out", &out_s,
    ]);
    let o = rocking(&args);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    columns(&out.join("runs.csv"), 4);
    let out = tmp.path().join("msa");
    let mut args = vec!["ida", "scenes/wind-turbine-msa.toml", "--records"];
    args.extend(recs.iter().map(String::as_str));
    let out_s = out.display().to_string();
    args.extend([
        "--set",
        "ida.stripes=[5.0, 20.0]",
        "--set",
        report,
        "--out",
        &out_s,
    ]);
    let o = rocking(&args);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    columns(&out.join("stripes.csv"), 4);
}

/// An IDA whose capacities all coincide (one record under two names; issue 47, item 10: every
/// analysis ran, then exit 2 and nothing written): the analyses are written, a warning says
/// why there is no fit, and fragility.json has no fit fields (no null, no NaN) but `no_fit`.
#[test]
fn an_ida_with_coinciding_capacities_writes_its_analyses_without_a_fit() {
    let tmp = tempfile::tempdir().unwrap();
    let rec = repo().join("../shared/data/ground-motions/A-ELC180.AT2");
    let (one, two) = (tmp.path().join("one.AT2"), tmp.path().join("two.AT2"));
    std::fs::copy(&rec, &one).unwrap();
    std::fs::copy(&rec, &two).unwrap();
    let out = tmp.path().join("ida");
    let o = rocking(&[
        "ida",
        "scenes/wind-turbine-ida.toml",
        "--records",
        one.to_str().unwrap(),
        two.to_str().unwrap(),
        "--set",
        "ida.bootstrap=200",
        "--out",
        out.to_str().unwrap(),
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{err}");
    assert!(
        err.contains("warning:") && err.contains("all capacities are equal"),
        "{err}"
    );
    let json = std::fs::read_to_string(out.join("fragility.json")).unwrap();
    assert!(!json.contains("null") && !json.contains("NaN"), "{json}");
    let fit: Value = serde_json::from_str(&json).unwrap();
    assert!(
        fit.get("median_m_s2").is_none() && fit.get("beta").is_none(),
        "{json}"
    );
    assert!(
        fit["no_fit"].as_str().unwrap().contains("capacities"),
        "{json}"
    );
    assert_eq!(fit["capacities_m_s2"].as_array().unwrap().len(), 2);
    let rows = std::fs::read_to_string(out.join("records.csv")).unwrap();
    assert_eq!(rows.lines().count(), 3, "{rows}");
    assert!(out.join("ida.csv").is_file() && out.join("ida.svg").is_file());
    assert!(!out.join("fragility-fit.svg").exists());
}
