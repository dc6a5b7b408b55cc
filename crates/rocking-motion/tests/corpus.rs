//! Every reader over a corpus of record files written in the layouts the databases publish
//! (tests/corpus/, samples of our own; see its README): each file is read by its own reader as
//! the table below says, and refused by every other reader with a message that names the file and
//! a line — a file is never silently read in another format or another unit.

use rocking_motion::{
    read_record, record_files_in, AccelUnit, GroundMotion, MotionError, RecordFormat,
    STANDARD_GRAVITY,
};
use std::path::{Path, PathBuf};

/// What reading a corpus file with its own reader gives.
enum Expect {
    /// A record: NPTS, DT (s), the declared unit, the second sample and the PGA in that unit.
    Record {
        npts: usize,
        dt: f64,
        unit: Option<AccelUnit>,
        second: f64,
        pga: f64,
    },
    /// A refusal on `line` (None: the file as a whole), saying `says`.
    Refused {
        line: Option<usize>,
        says: &'static str,
    },
}
use Expect::*;

const G: Option<AccelUnit> = Some(AccelUnit::G);
const CM: Option<AccelUnit> = Some(AccelUnit::CmPerS2);
const M: Option<AccelUnit> = Some(AccelUnit::MPerS2);

/// The corpus: file, its format, the `dt` a scene states (one-column text), what it reads as.
const CORPUS: &[(&str, RecordFormat, Option<f64>, Expect)] = &[
    // PEER NGA-West2: 5E15.7, "NPTS=   12, DT=   .0100 SEC"
    (
        "peer/RSN6_IMPVALL.I_I-ELC180.AT2",
        RecordFormat::At2,
        None,
        Record {
            npts: 12,
            dt: 0.01,
            unit: G,
            second: 0.02028951,
            pga: 0.17810049,
        },
    ),
    (
        "peer/RSN6_IMPVALL.I_I-ELC180.VT2",
        RecordFormat::At2,
        None,
        Refused {
            line: None,
            says: "found a PEER velocity file (.VT2)",
        },
    ),
    (
        "peer/RSN6_IMPVALL.I_I-ELC180.DT2",
        RecordFormat::At2,
        None,
        Refused {
            line: None,
            says: "found a PEER displacement file (.DT2)",
        },
    ),
    // PEER "Pacific Engineering": filter points after the unit
    (
        "peer/CHALFANT.A-BEN360.AT2",
        RecordFormat::At2,
        None,
        Record {
            npts: 10,
            dt: 0.005,
            unit: G,
            second: 0.010181048,
            pga: 0.087276434,
        },
    ),
    // 8F10.5 and "The units are (g)", as the El Centro file of the scenes
    (
        "peer/elcentro-8f10.AT2",
        RecordFormat::At2,
        None,
        Record {
            npts: 11,
            dt: 0.02,
            unit: G,
            second: 0.0402,
            pga: 0.20502,
        },
    ),
    (
        "peer/old-npts-dt.AT2",
        RecordFormat::At2,
        None,
        Record {
            npts: 9,
            dt: 0.02,
            unit: G,
            second: 0.040203881,
            pga: 0.20501835,
        },
    ),
    // g, explained in other units after it
    (
        "peer/g-explained.AT2",
        RecordFormat::At2,
        None,
        Record {
            npts: 8,
            dt: 0.005,
            unit: G,
            second: 0.010181048,
            pga: 0.06901074,
        },
    ),
    (
        "peer/units-colon-g.AT2",
        RecordFormat::At2,
        None,
        Record {
            npts: 8,
            dt: 0.005,
            unit: G,
            second: 0.010181048,
            pga: 0.06901074,
        },
    ),
    (
        "peer/cm-sec-sec.AT2",
        RecordFormat::At2,
        None,
        Record {
            npts: 8,
            dt: 0.005,
            unit: CM,
            second: 9.984197,
            pga: 67.676417,
        },
    ),
    (
        "peer/m-s2.AT2",
        RecordFormat::At2,
        None,
        Record {
            npts: 8,
            dt: 0.005,
            unit: M,
            second: 0.09984197,
            pga: 0.67676417,
        },
    ),
    (
        "peer/dt-msec.AT2",
        RecordFormat::At2,
        None,
        Record {
            npts: 6,
            dt: 0.02,
            unit: G,
            second: 0.040203881,
            pga: 0.16790786,
        },
    ),
    (
        "peer/duzce-crlf-latin1.AT2",
        RecordFormat::At2,
        None,
        Record {
            npts: 7,
            dt: 0.01,
            unit: G,
            second: 0.02028951,
            pga: 0.11290218,
        },
    ),
    (
        "peer/duzce-utf8-bom.AT2",
        RecordFormat::At2,
        None,
        Record {
            npts: 7,
            dt: 0.01,
            unit: G,
            second: 0.02028951,
            pga: 0.11290218,
        },
    ),
    (
        "peer/km-s-s.AT2",
        RecordFormat::At2,
        None,
        Refused {
            line: Some(3),
            says: "1000 m/s2 per unit that the readers do not convert",
        },
    ),
    // ESM ASCII with the full DYNA 1.2 header (64 lines)
    (
        "esm/IT.NRC..HNE.D.EMSC-20161030_0000029.ACC.MP.ASC",
        RecordFormat::Esm,
        None,
        Record {
            npts: 10,
            dt: 0.01,
            unit: CM,
            second: 19.897212,
            pga: 153.18993,
        },
    ),
    (
        "esm/TK.8101..HNN.D.19991112.165716.ACC.MP.ASC",
        RecordFormat::Esm,
        None,
        Record {
            npts: 10,
            dt: 0.01,
            unit: CM,
            second: 19.897212,
            pga: 153.18993,
        },
    ),
    (
        "esm/IT.NRC..HNE.D.EMSC-20161030_0000029.SA.MP.ASC",
        RecordFormat::Esm,
        None,
        Refused {
            line: Some(49),
            says: "a response spectrum, not a time history",
        },
    ),
    (
        "esm/IT.NRC..HNE.D.EMSC-20161030_0000029.VEL.MP.ASC",
        RecordFormat::Esm,
        None,
        Refused {
            line: Some(50),
            says: "a velocity history (\"DATA_TYPE: VELOCITY\")",
        },
    ),
    (
        "esm/IT.NRC..HNE.D.EMSC-20161030_0000029.DIS.MP.ASC",
        RecordFormat::Esm,
        None,
        Refused {
            line: Some(50),
            says: "a displacement history",
        },
    ),
    // K-NET and KiK-net ASCII: 17 header lines, counts (gal = counts × scale, mean removed)
    (
        "knet/MYG0041103111446.NS",
        RecordFormat::Knet,
        None,
        Record {
            npts: 20,
            dt: 0.01,
            unit: CM,
            second: -116.44527032502145,
            pga: 136.34274978444097,
        },
    ),
    (
        "knet/FKS0161103111446.EW",
        RecordFormat::Knet,
        None,
        Record {
            npts: 16,
            dt: 0.02,
            unit: CM,
            second: -99.30638431600381,
            pga: 138.73297706315998,
        },
    ),
    (
        "knet/IWTH251103111446.UD2",
        RecordFormat::Knet,
        None,
        Record {
            npts: 20,
            dt: 0.01,
            unit: CM,
            second: -116.44552946090698,
            pga: 136.34275197982788,
        },
    ),
    (
        "knet/IWTH251103111446.NS1",
        RecordFormat::Knet,
        None,
        Record {
            npts: 20,
            dt: 0.01,
            unit: CM,
            second: -116.44552946090698,
            pga: 136.34275197982788,
        },
    ),
    (
        "knet/truncated.EW",
        RecordFormat::Knet,
        None,
        Refused {
            line: Some(3),
            says: "\"Long. …\" (header line 3 of 17)",
        },
    ),
    // text with comments: two columns; one column with the scene's dt
    (
        "text/two-columns.csv",
        RecordFormat::Text,
        None,
        Record {
            npts: 8,
            dt: 0.01,
            unit: None,
            second: 0.198972,
            pga: 1.261244,
        },
    ),
    (
        "text/one-column.txt",
        RecordFormat::Text,
        Some(0.01),
        Record {
            npts: 8,
            dt: 0.01,
            unit: None,
            second: 0.0202895,
            pga: 0.1286111,
        },
    ),
];

fn corpus() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/corpus")
}

const FORMATS: [RecordFormat; 4] = [
    RecordFormat::At2,
    RecordFormat::Text,
    RecordFormat::Esm,
    RecordFormat::Knet,
];

#[test]
fn every_reader_over_the_whole_corpus() {
    let dir = corpus();
    let mut listed: Vec<&str> = Vec::new();
    for (name, own, dt, expect) in CORPUS {
        let path = dir.join(name);
        listed.push(name);
        if !matches!(expect, Refused { line: None, .. }) {
            assert_eq!(
                RecordFormat::from_path(&path),
                Some(*own),
                "{name}: extension"
            );
        }
        for format in FORMATS {
            let given_dt = if format == RecordFormat::Text {
                *dt
            } else {
                None
            };
            let got = read_record(&path, format, given_dt);
            let shown = path.display().to_string();
            if format != *own {
                let e = got.expect_err(&format!("{name} read as {}", format.name()));
                assert!(
                    e.to_string().starts_with(&shown),
                    "{name} as {}: {e}",
                    format.name()
                );
                assert!(e.line().is_some(), "{name} as {}: {e}", format.name());
                continue;
            }
            match expect {
                Record {
                    npts,
                    dt,
                    unit,
                    second,
                    pga,
                } => {
                    let r = got.unwrap_or_else(|e| panic!("{name}: {e}"));
                    assert_eq!((r.npts, r.samples.len()), (*npts, *npts), "{name}");
                    assert!((r.dt - dt).abs() <= 1e-12 * dt, "{name}: dt {}", r.dt);
                    assert_eq!(r.declared_unit, *unit, "{name}");
                    let close = |a: f64, b: f64| (a - b).abs() <= 1e-9 * b.abs();
                    assert!(close(r.samples[1], *second), "{name}: {}", r.samples[1]);
                    assert!(close(r.pga(), *pga), "{name}: PGA {}", r.pga());
                }
                Refused { line, says } => {
                    let e = got.expect_err(name);
                    assert_eq!(e.line(), *line, "{name}: {e}");
                    let msg = e.to_string();
                    assert!(
                        msg.starts_with(&shown) && msg.contains(says),
                        "{name}: {msg}"
                    );
                }
            }
        }
    }
    // The table covers the corpus, file for file.
    let mut on_disk: Vec<String> = Vec::new();
    for sub in ["peer", "esm", "knet", "text"] {
        for e in std::fs::read_dir(dir.join(sub)).unwrap() {
            on_disk.push(format!(
                "{sub}/{}",
                e.unwrap().file_name().to_string_lossy()
            ));
        }
    }
    on_disk.sort();
    listed.sort();
    assert_eq!(on_disk, listed);
}

/// The same motion in g (with an explanation in cm/s² after the unit), in cm/s² and in m/s²
/// reads as the same accelerations in m/s²: the unit line is not matched by substring.
#[test]
fn one_motion_in_three_units_is_one_motion() {
    let dir = corpus();
    let si = |f: &str| {
        let r = read_record(dir.join(f), RecordFormat::At2, None).unwrap();
        r.to_record_si(STANDARD_GRAVITY)
    };
    let g = si("peer/g-explained.AT2");
    for other in [
        "peer/units-colon-g.AT2",
        "peer/cm-sec-sec.AT2",
        "peer/m-s2.AT2",
    ] {
        let o = si(other);
        for k in 0..g.len() {
            let (a, b) = (g.accel(g.time_of(k)), o.accel(o.time_of(k)));
            assert!(
                (a - b).abs() <= 1e-7 * g.peak(),
                "{other} sample {k}: {a} vs {b}"
            );
        }
    }
    // The ESM and K-NET files of the corpus carry the same wave (0.25 g peak envelope) in gal.
    let esm = read_record(
        dir.join("esm/IT.NRC..HNE.D.EMSC-20161030_0000029.ACC.MP.ASC"),
        RecordFormat::Esm,
        None,
    )
    .unwrap();
    let peak = esm.to_record_si(20.0).peak();
    assert!((peak - 1.5318993).abs() < 1e-9, "absolute at any g: {peak}");
}

/// A folder of the corpus stands for its self-describing record files only.
#[test]
fn folders_list_their_records() {
    let dir = corpus();
    let names = |sub: &str| -> Vec<String> {
        record_files_in(&dir.join(sub))
            .unwrap()
            .iter()
            .map(|p| p.file_name().unwrap().to_string_lossy().into_owned())
            .collect()
    };
    let peer = names("peer");
    assert_eq!(peer.len(), 12, "{peer:?}");
    assert!(peer.iter().all(|n| n.ends_with(".AT2")), "{peer:?}");
    assert_eq!(names("esm").len(), 5);
    assert_eq!(names("knet").len(), 5);
    assert!(names("text").is_empty(), "text records are given by name");
    let e = record_files_in(&dir.join("absent")).unwrap_err();
    assert!(matches!(e, MotionError::Io { .. }), "{e:?}");
}
