//! Every row of the bad-input table in docs/bad-input.md: the invalid input, exit code 2, and one
//! message naming the file, the line or key, the value and what is allowed. The table's row ids
//! and this test's rows must be the same set.

use std::path::{Path, PathBuf};
use std::process::Command;

const SCENE: &str = r#"[structure]
omega_n_over_p = 11.9
alpha = 0.2
gamma_mc = 0.0
gamma_mb = 1.0
gamma_ib = 1.0
zeta = 0.005
damping = "fixed-base"
r = 2.0

[excitation]
kind = "sine-pulse"
omega_p_over_p = 5.1
amplitude = 1.3

[solver]
after_excitation = 5.0
"#;

const PHYSICAL: &str = r#"[structure]
h = 30.0
b = 3.0
ei = 2.0e10
m = 1.0e5
m_c = 5.0e4
m_b = 1.0e5
zeta = 0.01
g = 9.81

[excitation]
kind = "sine-pulse"
omega_p = 3.0
amplitude_g = 0.3
"#;

/// A figure file (issue 46): its printed width and the PNG's resolution are checked before any
/// run is loaded.
const FIGURE: &str = r#"title = "t"
width = "double"
columns = 1

[runs.a]
scene = "a.toml"
label = "a"

[[panels]]
kind = "history"
quantity = "theta_over_alpha"
runs = ["a"]
"#;

const RECORD: &str = "title\nevent\nunits\nNPTS= 4, DT= .01\n0.1 0.2 0.3 0.4\n";

/// The record kind replacing the scene's pulse, and the same read as ESM or K-NET.
const PULSE: &str = "kind = \"sine-pulse\"\nomega_p_over_p = 5.1\namplitude = 1.3";
const AS_ESM: &str = "kind = \"record\"\npath = \"rec.AT2\"\nformat = \"esm\"";

/// Two periods of a 2 Hz sine of 0.1 g: a record with intensity measures.
const SINE_RECORD: &str = "title\nevent\nunits\nNPTS= 50, DT= .02\n0.000 0.025 0.048 0.068 0.084 0.095 0.100 0.098 0.090 0.077\n0.059 0.037 0.013 -0.013 -0.037 -0.059 -0.077 -0.090 -0.098 -0.100\n-0.095 -0.084 -0.068 -0.048 -0.025 -0.000 0.025 0.048 0.068 0.084\n0.095 0.100 0.098 0.090 0.077 0.059 0.037 0.013 -0.013 -0.037\n-0.059 -0.077 -0.090 -0.098 -0.100 -0.095 -0.084 -0.068 -0.048 -0.025\n";

/// A record scene with a study of its record by Sa(T = -1 s).
const IDA_SA: &str =
    "kind = \"record\"\npath = \"rec.AT2\"\n\n[ida]\nrecords = [\"rec.AT2\"]\nim = \"sa\"\nperiod = -1.0";

/// An ESM header (the keys the reader needs; `DATA_TYPE` and `NDATA` replaced per row).
macro_rules! esm {
    ($data_type:literal, $ndata:literal, $samples:literal) => {
        concat!(
            "EVENT_NAME: Test\nVS30_M/S: 580\nSAMPLING_INTERVAL_S: 0.010000\n",
            "NDATA: ",
            $ndata,
            "\nUNITS: cm/s^2\nPGA_CM/S^2: 3.0\nDATA_TYPE: ",
            $data_type,
            "\nUSER5:\n",
            $samples
        )
    };
}

/// (id, base scene, replace this, by this, record file text, expected fragments of the message).
/// The message must also name `scene.toml:LINE:` where LINE is the line of the replacement (or,
/// for a record, of its `path`; for a missing key, of its table).
type Row = (
    &'static str,
    &'static str,
    &'static str,
    &'static str,
    Option<&'static str>,
    &'static [&'static str],
);

const ROWS: &[Row] = &[
    (
        "zero-frequency",
        SCENE,
        "omega_p_over_p = 5.1",
        "omega_p_over_p = 0",
        None,
        &["omega_p_over_p", "0", "> 0"],
    ),
    (
        "negative-zeta",
        SCENE,
        "zeta = 0.005",
        "zeta = -0.1",
        None,
        &["zeta", "-0.1", "0 <= zeta < 1"],
    ),
    (
        "zeta-list-length",
        SCENE,
        "zeta = 0.005",
        "zeta = [0.005, 0.02]",
        None,
        &["zeta", "lists 2 damping ratios", "model `cubic` has 1 fixed-base mode", "a list of 1"],
    ),
    (
        "zeta-list-not-a-number",
        SCENE,
        "zeta = 0.005",
        "zeta = [0.005, \"high\"]",
        None,
        &["zeta", "\"high\" is not a number", "one per fixed-base mode"],
    ),
    (
        "zeta-list-out-of-range",
        SCENE,
        "zeta = 0.005\ndamping = \"fixed-base\"",
        "model = \"polynomial2\"\ndamping = \"fixed-base\"\nzeta = [0.005, 1.5]",
        None,
        &["zeta", "1.5", "0 <= zeta < 1"],
    ),
    (
        "zeta-list-uplifted",
        SCENE,
        "zeta = 0.005\ndamping = \"fixed-base\"",
        "model = \"polynomial2\"\ndamping = \"uplifted\"\nzeta = [0.005, 0.02]",
        None,
        &["zeta", "as a list", "damping = \"fixed-base\""],
    ),
    (
        "alpha-too-large",
        SCENE,
        "alpha = 0.2",
        "alpha = 1.5708",
        None,
        &["alpha", "1.5708", "pi/2"],
    ),
    (
        "alpha-zero",
        SCENE,
        "alpha = 0.2",
        "alpha = 0.0",
        None,
        &["alpha", "0 < alpha"],
    ),
    (
        "negative-omega-n",
        SCENE,
        "omega_n_over_p = 11.9",
        "omega_n_over_p = -2",
        None,
        &["omega_n_over_p", "-2", "> 0"],
    ),
    (
        "negative-gamma",
        SCENE,
        "gamma_mb = 1.0",
        "gamma_mb = -1.0",
        None,
        &["gamma_mb", ">= 0"],
    ),
    (
        "gamma-ib-too-small",
        SCENE,
        "gamma_ib = 1.0",
        "gamma_ib = 0.5",
        None,
        &["gamma_ib", "0.5", "3/4"],
    ),
    (
        "nan",
        SCENE,
        "alpha = 0.2",
        "alpha = nan",
        None,
        &["alpha", "NaN"],
    ),
    (
        "infinite",
        SCENE,
        "amplitude = 1.3",
        "amplitude = inf",
        None,
        &["amplitude", "inf"],
    ),
    (
        "negative-length-scale",
        SCENE,
        "r = 2.0",
        "r = -2.0",
        None,
        &["-2", "r"],
    ),
    (
        "missing-key",
        SCENE,
        "alpha = 0.2\n",
        "",
        None,
        &["missing key `alpha`"],
    ),
    (
        "unknown-key",
        SCENE,
        "zeta = 0.005",
        "zeeta = 0.005",
        None,
        &["unknown key `zeeta`", "did you mean `zeta`?"],
    ),
    (
        "unknown-table",
        SCENE,
        "[solver]",
        "[solvr]",
        None,
        &["unknown key `solvr`", "did you mean `solver`?"],
    ),
    (
        "wrong-type",
        SCENE,
        "alpha = 0.2",
        "alpha = \"steep\"",
        None,
        &["alpha", "string"],
    ),
    (
        "bad-enum",
        SCENE,
        "damping = \"fixed-base\"",
        "damping = \"fixed\"",
        None,
        &["damping", "fixed-base"],
    ),
    (
        "toml-syntax",
        SCENE,
        "alpha = 0.2",
        "alpha = ",
        None,
        &["invalid TOML"],
    ),
    (
        "physical-negative-mass",
        PHYSICAL,
        "m = 1.0e5",
        "m = -1.0e5",
        None,
        &["`m`", "-100000", "m > 0"],
    ),
    (
        "physical-zero-stiffness",
        PHYSICAL,
        "ei = 2.0e10",
        "ei = 0.0",
        None,
        &["ei", "EI > 0"],
    ),
    (
        "physical-base-inertia",
        PHYSICAL,
        "m_b = 1.0e5",
        "m_b = 1.0e5\ni_bc = 1.0",
        None,
        &["i_bc", "gamma_ib >= 3/4"],
    ),
    (
        "mixed-forms",
        SCENE,
        "alpha = 0.2",
        "alpha = 0.2\nh = 3.0",
        None,
        &["either"],
    ),
    (
        "record-missing-file",
        SCENE,
        "kind = \"sine-pulse\"\nomega_p_over_p = 5.1\namplitude = 1.3",
        "kind = \"record\"\npath = \"nowhere.AT2\"",
        None,
        &["nowhere.AT2", "cannot read"],
    ),
    (
        "record-empty",
        SCENE,
        "kind = \"sine-pulse\"\nomega_p_over_p = 5.1\namplitude = 1.3",
        "kind = \"record\"\npath = \"rec.AT2\"",
        Some(""),
        &["rec.AT2", "empty"],
    ),
    (
        "record-truncated-header",
        SCENE,
        "kind = \"sine-pulse\"\nomega_p_over_p = 5.1\namplitude = 1.3",
        "kind = \"record\"\npath = \"rec.AT2\"",
        Some("title\nevent\n"),
        &["rec.AT2:", "header"],
    ),
    (
        "record-npts-too-many",
        SCENE,
        "kind = \"sine-pulse\"\nomega_p_over_p = 5.1\namplitude = 1.3",
        "kind = \"record\"\npath = \"rec.AT2\"",
        Some("title\nevent\nunits\nNPTS= 5, DT= .01\n0.1 0.2 0.3 0.4\n"),
        &["rec.AT2:", "5", "4"],
    ),
    (
        "record-npts-too-few",
        SCENE,
        "kind = \"sine-pulse\"\nomega_p_over_p = 5.1\namplitude = 1.3",
        "kind = \"record\"\npath = \"rec.AT2\"",
        Some("title\nevent\nunits\nNPTS= 3, DT= .01\n0.1 0.2 0.3 0.4\n"),
        &["rec.AT2:5", "3"],
    ),
    (
        "record-dt-zero",
        SCENE,
        "kind = \"sine-pulse\"\nomega_p_over_p = 5.1\namplitude = 1.3",
        "kind = \"record\"\npath = \"rec.AT2\"",
        Some("title\nevent\nunits\nNPTS= 4, DT= 0\n0.1 0.2 0.3 0.4\n"),
        &["rec.AT2:4", "DT"],
    ),
    (
        "record-dt-negative",
        SCENE,
        "kind = \"sine-pulse\"\nomega_p_over_p = 5.1\namplitude = 1.3",
        "kind = \"record\"\npath = \"rec.AT2\"",
        Some("title\nevent\nunits\nNPTS= 4, DT= -.01\n0.1 0.2 0.3 0.4\n"),
        &["rec.AT2:4", "DT"],
    ),
    (
        "record-bad-number",
        SCENE,
        "kind = \"sine-pulse\"\nomega_p_over_p = 5.1\namplitude = 1.3",
        "kind = \"record\"\npath = \"rec.AT2\"",
        Some("title\nevent\nunits\nNPTS= 4, DT= .01\n0.1 0.2 x 0.4\n"),
        &["rec.AT2:5", "\"x\""],
    ),
    (
        "record-velocity",
        SCENE,
        "kind = \"sine-pulse\"\nomega_p_over_p = 5.1\namplitude = 1.3",
        "kind = \"record\"\npath = \"rec.AT2\"",
        Some("title\nevent\nVELOCITY TIME HISTORY IN UNITS OF CM/SEC\nNPTS= 4, DT= .01\n0.1 0.2 0.3 0.4\n"),
        &["rec.AT2:3", "expected an acceleration history", "VELOCITY"],
    ),
    (
        "record-unknown-units",
        SCENE,
        "kind = \"sine-pulse\"\nomega_p_over_p = 5.1\namplitude = 1.3",
        "kind = \"record\"\npath = \"rec.AT2\"",
        Some("title\nevent\nACCELERATION IN UNITS OF FT/S/S\nNPTS= 4, DT= .01\n0.1 0.2 0.3 0.4\n"),
        &["rec.AT2:3", "FT/S/S", "g, cm/s2"],
    ),
    (
        "record-units-contradiction",
        SCENE,
        "kind = \"sine-pulse\"\nomega_p_over_p = 5.1\namplitude = 1.3",
        "kind = \"record\"\npath = \"rec.AT2\"\nunits = \"cm/s2\"",
        Some("title\nevent\nACCELERATION IN UNITS OF G\nNPTS= 4, DT= .01\n0.1 0.2 0.3 0.4\n"),
        &["rec.AT2", "declares the units g", "\"cm/s2\""],
    ),
    (
        "record-bad-units",
        SCENE,
        "kind = \"sine-pulse\"\nomega_p_over_p = 5.1\namplitude = 1.3",
        "kind = \"record\"\npath = \"rec.AT2\"\nunits = \"ft/s2\"",
        Some(RECORD),
        &["units", "ft/s2", "\"g\", \"cm/s2\", \"m/s2\""],
    ),
    (
        "huge-omega-n",
        SCENE,
        "omega_n_over_p = 11.9",
        "omega_n_over_p = 1e308",
        None,
        &["omega_n_over_p", "1e308", "<= 1000000"],
    ),
    (
        "alpha-near-pi-2",
        SCENE,
        "alpha = 0.2",
        "alpha = 1.57",
        None,
        &["alpha", "1.57", "1.5698"],
    ),
    (
        "huge-amplitude",
        SCENE,
        "amplitude = 1.3",
        "amplitude = 1e308",
        None,
        &["amplitude", "1e308", "at most 10000 g"],
    ),
    (
        "huge-frequency",
        SCENE,
        "omega_p_over_p = 5.1",
        "omega_p_over_p = 1e308",
        None,
        &["omega_p_over_p", "1e308", "at most 1000000"],
    ),
    (
        "physical-huge-height",
        PHYSICAL,
        "h = 30.0",
        "h = 1e308",
        None,
        &["`h`", "1e308", "1e20"],
    ),
    (
        "too-many-plot-rows",
        SCENE,
        "after_excitation = 5.0",
        "after_excitation = 1e6\n\n[output]\nplots = true",
        None,
        &["plots", "at most 5e6"],
    ),
    (
        "bad-max-steps",
        SCENE,
        "after_excitation = 5.0",
        "after_excitation = 5.0\nmax_steps = 0.5",
        None,
        &["max_steps", "0.5", "1 <= n <= 1e12"],
    ),
    (
        "steps-history-too-long",
        SCENE,
        "after_excitation = 5.0",
        "after_excitation = 5.0\nmax_steps = 1e9\n\n[output]\nhistory = \"steps\"",
        None,
        &["max_steps", "1e9", "history = \"steps\"", "at most 5e7"],
    ),
    (
        "record-km-units",
        SCENE,
        PULSE,
        "kind = \"record\"\npath = \"rec.AT2\"",
        Some("title\nevent\nACCELERATION TIME SERIES IN UNITS OF KM/S/S\nNPTS= 4, DT= .01\n0.1 0.2 0.3 0.4\n"),
        &["rec.AT2:3", "KM/S/S", "1000 m/s2", "do not convert"],
    ),
    (
        "record-binary",
        SCENE,
        PULSE,
        "kind = \"record\"\npath = \"rec.AT2\"",
        Some("title\nevent\u{0}\n"),
        &["rec.AT2:2", "expected text", "NUL"],
    ),
    (
        "record-dt-too-small",
        SCENE,
        PULSE,
        "kind = \"record\"\npath = \"rec.AT2\"",
        Some("title\nevent\nunits\nNPTS= 4, DT= 1e-250\n0.1 0.2 0.3 0.4\n"),
        &["rec.AT2:4", "DT = 1e-250 s", ">= 1e-6 s"],
    ),
    (
        "record-too-long",
        SCENE,
        PULSE,
        "kind = \"record\"\npath = \"rec.AT2\"",
        Some("title\nevent\nunits\nNPTS= 3, DT= 1e300\n0.1 0.2 0.3\n"),
        &["rec.AT2", "lasts 2e300 s", "at most 1e9 τ", "DT"],
    ),
    (
        "record-too-many-steps",
        SCENE,
        PULSE,
        "kind = \"record\"\npath = \"rec.AT2\"",
        Some("title\nevent\nunits\nNPTS= 3, DT= 1e7\n0.1 0.2 0.3\n"),
        &["rec.AT2", "lasts 20000000 s", "integrator steps", "`max_steps` = 50000000"],
    ),
    (
        "record-esm-spectrum",
        SCENE,
        PULSE,
        AS_ESM,
        Some(esm!("ACCELERATION RESPONSE SPECTRUM", "3", "0.05 3.0\n0.10 4.0\n0.15 3.5\n")),
        &["rec.AT2:7", "a response spectrum, not a time history"],
    ),
    (
        "record-esm-velocity",
        SCENE,
        PULSE,
        AS_ESM,
        Some(esm!("VELOCITY", "3", "1.0\n2.0\n3.0\n")),
        &["rec.AT2:7", "a velocity history"],
    ),
    (
        "record-esm-ndata",
        SCENE,
        PULSE,
        AS_ESM,
        Some(esm!("ACCELERATION", "4", "1.0\n2.0\n3.0\n")),
        &["rec.AT2:4", "expected 4 samples (NDATA in the header), found 3"],
    ),
    (
        "record-esm-peak-mismatch",
        SCENE,
        PULSE,
        AS_ESM,
        Some(esm!("ACCELERATION", "3", "100.0\n-300.0\n200.0\n")),
        &[
            "rec.AT2:6",
            "the header states PGA_CM/S^2 = 3.0 but the samples peak at 300 cm/s²",
        ],
    ),
    (
        "record-knet-short-header",
        SCENE,
        PULSE,
        "kind = \"record\"\npath = \"rec.AT2\"\nformat = \"knet\"",
        Some("Origin Time       2011/03/11 14:46:00\nLat.              38.103\n"),
        &["rec.AT2:3", "\"Long. …\"", "header line 3 of 17"],
    ),
    (
        "record-zero-scale",
        SCENE,
        "kind = \"sine-pulse\"\nomega_p_over_p = 5.1\namplitude = 1.3",
        "kind = \"record\"\npath = \"rec.AT2\"\nscale = 0.0",
        Some(RECORD),
        &["scale", "= 0", "nonzero"],
    ),
    (
        "ida-period-negative",
        SCENE,
        PULSE,
        IDA_SA,
        Some(RECORD),
        &["`period` = -1 in [ida]", "0.001 s <= period <= 100 s"],
    ),
    (
        "ida-period-huge",
        SCENE,
        PULSE,
        "kind = \"record\"\npath = \"rec.AT2\"\n\n[ida]\nrecords = [\"rec.AT2\"]\nim = \"sa\"\nperiod = 1e300",
        Some(RECORD),
        &["`period` = 1e300 in [ida]", "period <= 100 s"],
    ),
    (
        "ida-tolerance",
        SCENE,
        PULSE,
        "kind = \"record\"\npath = \"rec.AT2\"\n\n[ida]\nrecords = [\"rec.AT2\"]\nim = \"pga\"\ntolerance = 1.0",
        Some(RECORD),
        &["`tolerance` = 1 in [ida]", "0 < tolerance < 1"],
    ),
    (
        "ida-unknown-im",
        SCENE,
        PULSE,
        "kind = \"record\"\npath = \"rec.AT2\"\n\n[ida]\nrecords = [\"rec.AT2\"]\nim = \"pgv\"",
        Some(RECORD),
        &["`im` = \"pgv\" in [ida]", "\"sa\", \"pga\""],
    ),
    (
        "ida-no-stripes",
        SCENE,
        PULSE,
        "kind = \"record\"\npath = \"rec.AT2\"\n\n[ida]\nrecords = [\"rec.AT2\"]\nim = \"pga\"\nstripes = []",
        Some(RECORD),
        &["`stripes` = a list of 0 different levels in [ida]", "2 to 1000"],
    ),
    (
        "ida-one-stripe",
        SCENE,
        PULSE,
        "kind = \"record\"\npath = \"rec.AT2\"\n\n[ida]\nrecords = [\"rec.AT2\"]\nim = \"pga\"\nstripes = [2.0]",
        Some(RECORD),
        &["`stripes` = a list of 1 different levels in [ida]", "a median and a β need two"],
    ),
    (
        "ida-stripe-too-high",
        SCENE,
        PULSE,
        "kind = \"record\"\npath = \"rec.AT2\"\n\n[ida]\nrecords = [\"rec.AT2\"]\nim = \"pga\"\nstripes = [1.0, 1e6]",
        Some(SINE_RECORD),
        &["`stripes` in [ida] reaches PGA = 1000000 m/s²", "rec.AT2", "at most 10000 g"],
    ),
    (
        "ida-bootstrap-one",
        SCENE,
        PULSE,
        "kind = \"record\"\npath = \"rec.AT2\"\n\n[ida]\nrecords = [\"rec.AT2\"]\nim = \"pga\"\nbootstrap = 1",
        Some(RECORD),
        &["`bootstrap` = 1 in [ida]", "200 <= bootstrap <= 100000"],
    ),
    (
        "ida-pulse-scene",
        SCENE,
        "[solver]",
        "[ida]\nim = \"pga\"\n\n[solver]",
        None,
        &["`kind` = \"sine-pulse\" in [excitation]", "kind = \"record\""],
    ),
    (
        "title-control-char",
        SCENE,
        "",
        "title = \"bell \\u0007\"\n",
        None,
        &["`title`", "'\\u{7}'", "printable text only"],
    ),
    (
        "uplift-false-tilted-start",
        SCENE,
        "",
        "[effects]\nuplift = false\n\n[initial]\ntheta_over_alpha = 0.5\n",
        None,
        &["`theta_over_alpha` in [initial]", "`uplift = false`", "give 0"],
    ),
    (
        "friction-without-forces",
        SCENE,
        "",
        "[output]\nforces = false\n\n[effects]\nfriction = 0.2\n",
        None,
        &["`friction` in [effects]", "`forces = false` in [output]", "no friction"],
    ),
    (
        "record-peak-too-high",
        SCENE,
        PULSE,
        "kind = \"record\"\npath = \"rec.AT2\"",
        Some("title\nevent\nIN UNITS OF G\nNPTS= 4, DT= .01\n0.1 20000 0.3 0.4\n"),
        &["rec.AT2 peaks at 20000 g", "at most 10000 g", "unit line"],
    ),
    (
        "figure-width-unknown",
        FIGURE,
        "width = \"double\"",
        "width = \"triple\"",
        None,
        &["`width`", "\"triple\"", "\"double\" (175 mm)", "40 <= width <= 250"],
    ),
    (
        "figure-width-too-narrow",
        FIGURE,
        "width = \"double\"",
        "width = 20",
        None,
        &["`width`", "20 is not allowed", "40 <= width <= 250"],
    ),
    (
        "figure-dpi-too-low",
        FIGURE,
        "columns = 1",
        "columns = 1\ndpi = 10",
        None,
        &["`dpi`", "10 is not allowed", "72 <= dpi <= 1200"],
    ),
    (
        "figure-time-unknown",
        FIGURE,
        "runs = [\"a\"]",
        "runs = [\"a\"]\ntime = \"seconds\"",
        None,
        &["`panels[0].time`", "`seconds` is not allowed", "tau or s"],
    ),
    (
        "figure-inset-too-large",
        FIGURE,
        "runs = [\"a\"]",
        "runs = [\"a\"]\ninset = { size = [0.9, 0.4] }",
        None,
        &[
            "`panels[0].inset.size`",
            "0.9 is not allowed",
            "0.25 <= width, height <= 0.8",
        ],
    ),
    (
        "figure-contours-without-quantity",
        FIGURE,
        "kind = \"history\"\nquantity = \"theta_over_alpha\"\nruns = [\"a\"]",
        "kind = \"spectrum\"\nsweep = \"s\"\ncontours = [0.5]\n\n[sweeps.s]\nscene = \"a.toml\"\nlabel = \"s\"",
        None,
        &["`panels[0].contours`", "levels of a reported quantity", "give `quantity`"],
    ),
    (
        "ground-zero-stiffness",
        SCENE,
        "",
        "[ground]\nkind = \"winkler\"\nzeta_v = 0.05\nomega_v_over_p = 0\n",
        None,
        &["`omega_v_over_p` in [ground] = 0", "0 < omega_v/p <= 1000000"],
    ),
    (
        "ground-negative-stiffness",
        PHYSICAL,
        "",
        "[ground]\nkind = \"winkler\"\nk = -1e7\n",
        None,
        &["`k` in [ground] = -10000000", "a stiffness 0 < k <= 1e20"],
    ),
    (
        "ground-zeta-v-one",
        SCENE,
        "",
        "[ground]\nkind = \"two-spring\"\nomega_v_over_p = 40.0\nzeta_v = 1.0\n",
        None,
        &["`zeta_v` in [ground] = 1", "0 <= zeta_v < 1"],
    ),
    (
        "ground-with-impact-map",
        SCENE,
        "",
        "[ground]\nkind = \"winkler\"\nomega_v_over_p = 40.0\n\n[effects]\nimpact = \"housner\"\n",
        None,
        &["`impact` in [effects]", "has no impacts", "kind = \"rigid\""],
    ),
    (
        "ground-mixed-forms",
        PHYSICAL,
        "",
        "[ground]\nkind = \"winkler\"\nk = 1e8\nomega_v_over_p = 40.0\n",
        None,
        &["[ground] mixes", "`omega_v_over_p`", "`k`", "either omega_v_over_p, zeta_v or k, c"],
    ),
    (
        "initial-settlement-on-rigid",
        SCENE,
        "",
        "[initial]\nv_over_static = 1.5\n",
        None,
        &["`v_over_static` in [initial]", "the rigid surface has none", "[ground]"],
    ),
    (
        "initial-settlement-too-large",
        SCENE,
        "",
        "[ground]\nkind = \"winkler\"\nomega_v_over_p = 40.0\n\n[initial]\nv_over_static = 1e4\n",
        None,
        &["`v_over_static` in [initial] = 10000", "|v/v₀| <= 1000"],
    ),
    (
        "ground-si-key-dimensionless",
        SCENE,
        "",
        "[ground]\nkind = \"winkler\"\nk = 1e8\n",
        None,
        &["`k` in [ground] is in SI units", "omega_v_over_p and zeta_v"],
    ),
    (
        "ground-key-of-other-kind",
        PHYSICAL,
        "",
        "[ground]\nkind = \"winkler\"\nk_spring = 1e8\n",
        None,
        &["`k_spring` in [ground] is a key of the two-spring ground", "give k and c"],
    ),
    (
        "ground-key-on-rigid",
        SCENE,
        "",
        "[ground]\nomega_v_over_p = 40.0\n",
        None,
        &["`omega_v_over_p` in [ground]", "kind is \"rigid\"", "\"two-spring\""],
    ),
    (
        "bearing-over-mean-zero",
        SCENE,
        "",
        "[ground]\nkind = \"winkler\"\nomega_v_over_p = 40.0\n\n[effects]\nbearing_over_mean = 0.0\n",
        None,
        &["`bearing_over_mean` in [effects] = 0", "0 < bearing_over_mean"],
    ),
    (
        "bearing-negative",
        PHYSICAL,
        "",
        "[ground]\nkind = \"winkler\"\nk = 1e8\n\n[effects]\nfooting_length = 10.0\nbearing = -3e5\n",
        None,
        &["`bearing` in [effects] = -300000", "0 < bearing <= 1e12 Pa"],
    ),
    (
        "bearing-on-rigid",
        SCENE,
        "",
        "[effects]\nbearing_over_mean = 4.0\n",
        None,
        &["`bearing_over_mean` in [effects]", "kind is \"rigid\"", "\"two-spring\""],
    ),
    (
        "bearing-without-footing-length",
        PHYSICAL,
        "",
        "[ground]\nkind = \"winkler\"\nk = 1e8\n\n[effects]\nbearing = 3e5\n",
        None,
        &["`bearing` in [effects] is a pressure (Pa)", "give footing_length (m)"],
    ),
    (
        "bearing-si-dimensionless",
        SCENE,
        "",
        "[ground]\nkind = \"winkler\"\nomega_v_over_p = 40.0\n\n[effects]\nfooting_length = 10.0\nbearing = 3e5\n",
        None,
        &["`bearing` in [effects] is in SI units (Pa)", "give bearing_over_mean"],
    ),
    (
        "batch-axis-on-scale",
        SCENE,
        PULSE,
        BATCH_SCENE,
        Some(RECORD),
        &["--axis `excitation.scale=1,2`", "from its scale factors", "any other numeric or text key"],
    ),
    (
        "batch-axis-twice",
        SCENE,
        PULSE,
        BATCH_SCENE,
        Some(RECORD),
        &["--axis `structure.model=cantilever_modes2`", "two axes on `structure.model`", "one axis"],
    ),
    (
        "batch-axis-too-many-values",
        SCENE,
        PULSE,
        BATCH_SCENE,
        Some(RECORD),
        &["structure.zeta=0:0.5:200000", "count 200000 is too large", "at most 100000 values per axis"],
    ),
    (
        "batch-axis-too-many-runs",
        SCENE,
        PULSE,
        BATCH_SCENE,
        Some(RECORD),
        &["records x scales x axes", "1001000 cells (1 x 1 x 1001 x 1000)", "at most 1000000 cells"],
    ),
    (
        "batch-axis-unknown-model",
        SCENE,
        PULSE,
        BATCH_SCENE,
        Some(RECORD),
        &["cantilever_modes9"],
    ),
    (
        "batch-axis-value-out-of-range",
        SCENE,
        PULSE,
        BATCH_SCENE,
        Some(RECORD),
        &["1.5", "0 <= zeta < 1"],
    ),
];

/// The record scene of the `batch-axis-` rows: its record is also its batch's (`[sweep] records`).
const BATCH_SCENE: &str =
    "kind = \"record\"\npath = \"rec.AT2\"\n\n[sweep]\nrecords = [\"rec.AT2\"]";

/// The `--axis` flags of the `batch-axis-` rows (run by `rocking batch` on their record scene).
const BATCH_AXES: &[(&str, &[&str])] = &[
    ("batch-axis-on-scale", &["excitation.scale=1,2"]),
    (
        "batch-axis-twice",
        &["structure.model=cubic", "structure.model=cantilever_modes2"],
    ),
    (
        "batch-axis-too-many-values",
        &["structure.zeta=0:0.5:200000"],
    ),
    (
        "batch-axis-too-many-runs",
        &["structure.zeta=0:0.5:1001", "structure.alpha=0.1:0.3:1000"],
    ),
    (
        "batch-axis-unknown-model",
        &["structure.model=cubic,cantilever_modes9"],
    ),
    (
        "batch-axis-value-out-of-range",
        &["structure.zeta=0.01,1.5"],
    ),
];

fn doc_ids() -> Vec<String> {
    let doc = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../docs/bad-input.md");
    let text = std::fs::read_to_string(&doc).unwrap();
    text.lines()
        .filter_map(|l| l.strip_prefix("| `"))
        .filter_map(|l| l.split('`').next())
        .map(String::from)
        .collect()
}

#[test]
fn the_documented_table_and_the_tested_rows_are_the_same() {
    let mut doc = doc_ids();
    let mut rows: Vec<String> = ROWS.iter().map(|r| r.0.to_string()).collect();
    doc.sort();
    rows.sort();
    assert_eq!(
        doc, rows,
        "docs/bad-input.md and tests/bad_input.rs must list the same cases"
    );
}

/// Rows refused by their command only: a pulse scene is a scene to run and check (not to study),
/// and a stripe level is too high for the study's records, which `check` does not read.
const NOT_BY_CHECK: [&str; 2] = ["ida-pulse-scene", "ida-stripe-too-high"];

/// Each row through its command (`rocking ida` for an `ida-` row, else `rocking run`) and through
/// `rocking check`, which refuses what they refuse with the same message (issue 30, item 13).
#[test]
fn every_bad_input_exits_2_with_one_clear_message() {
    let root = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("bad-input");
    for (id, base, from, to, record, needles) in ROWS {
        let dir = root.join(id);
        std::fs::create_dir_all(&dir).unwrap();
        assert!(base.contains(from), "{id}: the base scene has no `{from}`");
        std::fs::write(dir.join("scene.toml"), base.replacen(from, to, 1)).unwrap();
        if let Some(r) = record {
            std::fs::write(dir.join("rec.AT2"), r).unwrap();
        }
        let command = if id.starts_with("ida-") {
            "ida"
        } else if id.starts_with("figure-") {
            "figure"
        } else if id.starts_with("batch-axis-") {
            "batch"
        } else {
            "run"
        };
        let axes: &[&str] = BATCH_AXES
            .iter()
            .find(|(i, _)| i == id)
            .map_or(&[], |(_, a)| a);
        assert_eq!(
            command == "batch",
            !axes.is_empty(),
            "{id}: its --axis flags"
        );
        let out = Command::new(env!("CARGO_BIN_EXE_rocking"))
            .args([command, "--out"])
            .arg(dir.join("out"))
            .arg(dir.join("scene.toml"))
            .args(axes.iter().flat_map(|a| ["--axis", a]))
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(
            out.status.code(),
            Some(2),
            "{id}: exit {:?}: {err}",
            out.status.code()
        );
        assert_eq!(
            err.trim().lines().count(),
            1,
            "{id}: one message, got: {err}"
        );
        eprintln!(
            "BAD|{id}|{}",
            err.trim().replace(dir.to_str().unwrap(), "DIR")
        );
        for n in *needles {
            assert!(err.contains(n), "{id}: `{n}` not in: {err}");
        }
        // A bad --axis of a batch is named with the scene it was given for (it is a flag, not a
        // line of the scene; `rocking check` takes no axes).
        if command == "batch" {
            assert!(err.contains("scene.toml: "), "{id}: the scene: {err}");
            assert!(!dir.join("out").exists(), "{id}: no output on bad input");
            continue;
        }
        // A figure file's message names the file and the key (a figure file is not a scene:
        // `rocking check` does not read it).
        if command == "figure" {
            assert!(
                err.contains("scene.toml: `"),
                "{id}: the file and key: {err}"
            );
            assert!(!dir.join("out").exists(), "{id}: no output on bad input");
            continue;
        }
        let text = base.replacen(from, to, 1);
        let anchor = if *id == "record-zero-scale" {
            "scale ="
        } else if *id == "steps-history-too-long" {
            "max_steps =" // the guard the message names, not the history key after it
        } else if *id == "ida-pulse-scene" {
            "kind =" // the study needs a record scene
        } else if id.starts_with("ida-") {
            to.lines().last().unwrap()
        } else if to.contains("units =") {
            "units ="
        } else if *id == "mixed-forms" {
            "omega_n_over_p" // the table's first key: the message names both forms' keys
        } else if record.is_some() || id.starts_with("record") {
            "path ="
        } else if to.is_empty() {
            "[structure]"
        } else {
            to.lines().last().unwrap()
        };
        let line = text
            .lines()
            .position(|l| l.contains(anchor.trim()))
            .unwrap()
            + 1;
        let place = format!("scene.toml:{line}:");
        assert!(err.contains(&place), "{id}: `{place}` not in: {err}");
        assert!(!dir.join("out").exists(), "{id}: no output on bad input");
        if NOT_BY_CHECK.contains(id) {
            continue;
        }
        let checked = Command::new(env!("CARGO_BIN_EXE_rocking"))
            .arg("check")
            .arg(dir.join("scene.toml"))
            .output()
            .unwrap();
        assert_eq!(
            (
                checked.status.code(),
                String::from_utf8_lossy(&checked.stderr)
            ),
            (Some(2), err.clone()),
            "{id}: `rocking check` refuses what `rocking {command}` refuses"
        );
    }
}
