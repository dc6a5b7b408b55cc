//! PEER AT2 reader: real files, malformed inputs, fuzzing.

use proptest::prelude::*;
use rocking_motion::{parse_at2, read_at2, AccelUnit, GroundMotion, MotionError, STANDARD_GRAVITY};
use std::path::{Path, PathBuf};

fn data_dir() -> Option<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/data/ground-motions");
    if dir.is_dir() {
        Some(dir)
    } else {
        eprintln!(
            "SKIPPED: ground-motion folder {} is absent; real-file tests not run",
            dir.display()
        );
        None
    }
}

fn at2_files(dir: &Path) -> Vec<PathBuf> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e.eq_ignore_ascii_case("at2")))
        .collect();
    files.sort();
    files
}

#[test]
fn parses_all_real_files() {
    let Some(dir) = data_dir() else { return };
    let files = at2_files(&dir);
    assert_eq!(
        files.len(),
        61,
        "expected the 61 AT2 files in {}",
        dir.display()
    );
    for path in &files {
        let rec = read_at2(path).unwrap_or_else(|e| panic!("{e}"));
        let name = path.display();
        // Every file of the suite declares its unit (g), in one of two spellings.
        assert_eq!(
            rec.declared_unit,
            Some(AccelUnit::G),
            "{name}: {}",
            rec.units
        );
        assert_eq!(rec.npts, rec.samples.len(), "{name}");
        assert!(rec.dt > 0.0 && rec.dt.is_finite(), "{name}");
        assert!(rec.dt <= 0.02 + 1e-12, "{name}: dt = {}", rec.dt);
        let pga = rec.pga();
        assert!(pga > 0.0 && pga < 5.0, "{name}: PGA {pga} g");
        assert!(rec.samples.iter().all(|a| a.abs() < 5.0));
        assert!(!rec.title.is_empty() && !rec.event.is_empty(), "{name}");
        // converts to a record with the right extent
        let r = rec.to_record_si(STANDARD_GRAVITY);
        assert_eq!(r.len(), rec.npts);
        assert!((r.end() - (rec.npts - 1) as f64 * rec.dt).abs() < 1e-9);
        assert!((r.peak() - pga * STANDARD_GRAVITY).abs() < 1e-12);
    }
}

#[test]
fn el_centro() {
    let Some(dir) = data_dir() else { return };
    let rec = read_at2(dir.join("elCentro.AT2")).unwrap();
    assert_eq!(rec.npts, 1559);
    assert_eq!(rec.samples.len(), 1559);
    assert_eq!(rec.dt, 0.02);
    assert!(rec.units.contains("(g)"));
    // values straight from the file (8F10.5)
    assert_eq!(rec.samples[0], 0.00630);
    assert_eq!(rec.samples[7], 0.00277);
    assert_eq!(rec.samples[8], -0.00128);
    assert_eq!(*rec.samples.last().unwrap(), 0.0);
    // PGA: 0.31882 g (negative peak, sample 101, t = 2.02 s)
    assert_eq!(rec.pga(), 0.31882);
    let (k, a) = rec
        .samples
        .iter()
        .enumerate()
        .max_by(|x, y| x.1.abs().total_cmp(&y.1.abs()))
        .unwrap();
    assert_eq!((k, *a), (101, -0.31882));
    assert!((rec.duration() - 31.16).abs() < 1e-9);
    // in g: felt as the structure's g
    let si = rec.to_record_si(9.81);
    assert_eq!(si.accel(2.02), -0.31882 * 9.81);
    let r = rec.to_record();
    assert_eq!(r.accel(2.02), -0.31882);
    assert_eq!(r.next_kink(2.02), Some(r.time_of(102)));
}

fn header(line4: &str) -> String {
    format!("TITLE\nEVENT\nACCELERATION IN UNITS OF G\n{line4}\n")
}

fn err(text: impl AsRef<[u8]>) -> MotionError {
    parse_at2(text, "T.AT2").expect_err("should fail")
}

#[test]
fn empty_input() {
    let e = err("");
    assert!(matches!(e, MotionError::Empty { .. }), "{e:?}");
    assert_eq!(e.line(), Some(1));
    assert!(e.to_string().starts_with("T.AT2:1: "), "{e}");
}

#[test]
fn short_header() {
    for (text, line) in [("A\n", 2), ("A\nB\n", 3), ("A\nB\nC", 4), ("\n", 2)] {
        let e = err(text);
        assert!(matches!(e, MotionError::TruncatedHeader { .. }), "{e:?}");
        assert_eq!(e.line(), Some(line), "{text:?}");
        assert!(e.to_string().contains("found end of file"), "{e}");
    }
    let e = err("A\nB\nC");
    assert_eq!(
        e.to_string(),
        "T.AT2:4: expected \"NPTS=<n>, DT=<dt>\" (header line 4 of 4), found end of file"
    );
}

#[test]
fn header_only() {
    let e = err(header("NPTS=  3, DT= .01000 SEC"));
    match e {
        MotionError::CountMismatch {
            line,
            declared,
            found,
            ..
        } => assert_eq!((line, declared, found), (4, 3, 0)),
        other => panic!("{other:?}"),
    }
}

#[test]
fn bad_header_line() {
    let e = err(header("NPTS: lots, DT: small"));
    assert_eq!(
        e.to_string(),
        "T.AT2:4: expected \"NPTS=<n>, DT=<dt> [SEC|MSEC]\" in the header, found \"NPTS: lots, \
         DT: small\""
    );
    let e = err(header("1.0 2.0 3.0"));
    assert!(matches!(e, MotionError::BadHeader { line: 4, .. }), "{e:?}");
}

#[test]
fn npts_mismatch_both_directions() {
    // too few
    let e = err(header("NPTS= 5, DT= .01") + "1 2 3\n4\n");
    match &e {
        MotionError::CountMismatch {
            line,
            declared,
            found,
            ..
        } => assert_eq!((*line, *declared, *found), (6, 5, 4)),
        other => panic!("{other:?}"),
    }
    let msg = e.to_string();
    assert!(
        msg.contains('5') && msg.contains('4') && msg.starts_with("T.AT2:6:"),
        "{msg}"
    );
    // too many: points at the first surplus sample, reports the total
    let e = err(header("NPTS= 3, DT= .01") + "1 2\n3\n4 5\n");
    match &e {
        MotionError::CountMismatch {
            line,
            declared,
            found,
            ..
        } => assert_eq!((*line, *declared, *found), (7, 3, 5)),
        other => panic!("{other:?}"),
    }
    assert_eq!(
        e.to_string(),
        "T.AT2:7: expected 3 samples (NPTS in the header), found 5"
    );
}

#[test]
fn npts_zero() {
    let e = err(header("NPTS= 0, DT= .01"));
    assert!(
        matches!(
            e,
            MotionError::InvalidNpts {
                line: 4,
                npts: 0,
                ..
            }
        ),
        "{e:?}"
    );
}

#[test]
fn dt_zero_negative_infinite() {
    for (dt, shown) in [
        ("0.0", "0"),
        (".00000", "0"),
        ("-.01", "-0.01"),
        ("1e999", "inf"),
        ("1e-250", "1e-250"),
        ("9.9e-7", "9.9e-7"),
        ("5e-4 MSEC", "5e-7"),
    ] {
        let e = err(header(&format!("NPTS= 1, DT= {dt} SEC")) + "0.1\n");
        assert!(matches!(e, MotionError::InvalidDt { line: 4, .. }), "{e:?}");
        assert_eq!(
            e.to_string(),
            format!(
                "T.AT2:4: expected a time step DT >= 1e-6 s (sampled at 1 MHz at most) with a \
                 finite duration, found DT = {shown} s"
            )
        );
    }
    // the duration (NPTS - 1) DT overflows
    let e = err(header("NPTS= 3, DT= 1e308 SEC") + "0.1 0.2 0.3\n");
    assert!(matches!(e, MotionError::InvalidDt { line: 4, .. }), "{e:?}");
    // the shortest step is accepted
    let r = parse_at2(header("NPTS= 2, DT= 1e-6 SEC") + "0.1 0.2\n", "T.AT2").unwrap();
    assert_eq!(r.dt, 1e-6);
}

#[test]
fn garbage_token() {
    let e = err(header("NPTS= 4, DT= .01") + "0.1 0.2\n0.3 0.4x\n");
    assert!(matches!(e, MotionError::BadToken { line: 6, .. }), "{e:?}");
    assert_eq!(e.to_string(), "T.AT2:6: expected a number, found \"0.4x\"");
}

#[test]
fn non_finite_sample() {
    for tok in ["NaN", "inf", "-Infinity", "1e400"] {
        let e = err(header("NPTS= 2, DT= .01") + &format!("0.1\n{tok}\n"));
        assert!(
            matches!(e, MotionError::NonFiniteSample { line: 6, .. }),
            "{e:?}"
        );
        assert!(e.to_string().contains(tok), "{e}");
    }
}

/// A Latin-1 byte (a station name) is text; a byte inside a number is a bad number; NUL bytes
/// and UTF-16 are not text.
#[test]
fn latin1_text_binary_bytes() {
    let mut bytes =
        b"TITLE\nD\xfczce, 1999, 270\nACCELERATION IN UNITS OF G\nNPTS= 2, DT= .01\n".to_vec();
    bytes.extend_from_slice(b"0.1 0.2\n");
    let r = parse_at2(&bytes, "T.AT2").unwrap();
    assert_eq!(r.event, "Düzce, 1999, 270");
    let mut bytes = header("NPTS= 2, DT= .01").into_bytes();
    bytes.extend_from_slice(b"0.1\n0.\xff2\n");
    let e = err(&bytes);
    assert!(matches!(e, MotionError::BadToken { line: 6, .. }), "{e:?}");
    assert_eq!(e.to_string(), "T.AT2:6: expected a number, found \"0.ÿ2\"");
    let e = err(b"TITLE\nE\x00\n");
    assert!(matches!(e, MotionError::NotText { line: 2, .. }), "{e:?}");
    assert_eq!(
        e.to_string(),
        "T.AT2:2: expected text (ASCII, UTF-8 or Latin-1), found a NUL byte (a binary file)"
    );
    let e = err(b"\xff\xfeT\x00");
    assert!(matches!(e, MotionError::NotText { line: 1, .. }), "{e:?}");
}

#[test]
fn accepts_variants() {
    // CRLF, commas, blank lines, trailing spaces, D exponents, short last line
    let text = "T\r\nE\r\nU\r\nNPTS=  12000, dt=  .00500\r\n";
    let mut text = text.replace("12000", "7");
    text.push_str("  1.0D-01, 2.0E-01   \r\n\r\n .3 .4 .5\r\n-.6 7e-1\r\n");
    let rec = parse_at2(&text, "v.AT2").unwrap();
    assert_eq!(rec.npts, 7);
    assert_eq!(rec.dt, 0.005);
    assert_eq!(rec.samples, vec![0.1, 0.2, 0.3, 0.4, 0.5, -0.6, 0.7]);
    assert_eq!((rec.title.as_str(), rec.event.as_str()), ("T", "E"));
    let rec = parse_at2(header("  3   0.0100   NPTS, DT") + "1 2 3", "old.AT2").unwrap();
    assert_eq!((rec.npts, rec.dt), (3, 0.01));
}

#[test]
fn io_error_names_the_file() {
    let e = read_at2("/nonexistent/dir/NOPE.AT2").unwrap_err();
    assert!(matches!(e, MotionError::Io { .. }));
    assert!(e.to_string().contains("NOPE.AT2"), "{e}");
    assert!(std::error::Error::source(&e).is_some());
}

fn el_centro_bytes() -> Vec<u8> {
    data_dir()
        .and_then(|d| std::fs::read(d.join("elCentro.AT2")).ok())
        .unwrap_or_else(|| (header("NPTS= 3, DT= .02 SEC") + "0.1 -0.2\n0.3\n").into_bytes())
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 256, ..ProptestConfig::default() })]

    #[test]
    fn never_panics_on_arbitrary_bytes(bytes in proptest::collection::vec(any::<u8>(), 0..512)) {
        let _ = parse_at2(&bytes, "fuzz.AT2");
    }

    #[test]
    fn never_panics_on_arbitrary_text(s in "(NPTS|DT|=|,|[0-9]|\\.|-|E|\\s|\n|x){0,200}") {
        let _ = parse_at2(&s, "fuzz.AT2");
    }

    #[test]
    fn never_panics_on_mutated_real_file(
        edits in proptest::collection::vec((any::<prop::sample::Index>(), any::<u8>(), 0u8..3), 1..8)
    ) {
        let mut bytes = el_centro_bytes();
        for (idx, byte, op) in edits {
            if bytes.is_empty() { break; }
            let i = idx.index(bytes.len());
            match op {
                0 => bytes[i] = byte,            // overwrite
                1 => { bytes.remove(i); }        // delete
                _ => bytes.insert(i, byte),      // insert
            }
        }
        match parse_at2(&bytes, "mut.AT2") {
            Ok(rec) => {
                prop_assert_eq!(rec.npts, rec.samples.len());
                prop_assert!(rec.dt > 0.0 && rec.dt.is_finite());
                prop_assert!(rec.samples.iter().all(|a| a.is_finite()));
            }
            Err(e) => {
                prop_assert!(e.line().is_some());
                prop_assert!(e.to_string().starts_with("mut.AT2:"));
            }
        }
    }

    #[test]
    fn truncated_real_file_is_an_error_with_line(cut in 0usize..60_000) {
        let bytes = el_centro_bytes();
        let cut = cut % bytes.len();
        // cutting inside the data loses samples, unless the cut only removes
        // blanks or part of the last token
        let cuts_within_last_token = !bytes[cut..].trim_ascii().iter().any(u8::is_ascii_whitespace);
        match parse_at2(&bytes[..cut], "cut.AT2") {
            Ok(_) => prop_assert!(cuts_within_last_token),
            Err(e) => prop_assert!(e.line().is_some()),
        }
    }
}

/// One record written in g, cm/s² and m/s² (as PEER headers spell them) keeps its samples and
/// reads as the same accelerations in m/s² under standard gravity; velocity and displacement
/// histories are refused naming the file.
#[test]
fn units_are_read_and_converted() {
    let g = [0.0, 0.3, 0.0, -0.3, 0.0];
    let file = |units: &str, k: f64| {
        let body: Vec<String> = g.iter().map(|a| format!("{:.10e}", a * k)).collect();
        format!("T\nE\n{units}\nNPTS= 5, DT= .01 SEC\n{}\n", body.join(" "))
    };
    let cases = [
        ("ACCELERATION TIME HISTORY IN UNITS OF G", 1.0, AccelUnit::G),
        (
            "ACCELERATION TIME SERIES IN UNITS OF G (1 G = 980.665 CM/SEC/SEC)",
            1.0,
            AccelUnit::G,
        ),
        ("UNITS: g (9.81 m/s/s)", 1.0, AccelUnit::G),
        (
            "ACCELERATION TIME HISTORY IN UNITS OF CM/SEC/SEC",
            100.0 * STANDARD_GRAVITY,
            AccelUnit::CmPerS2,
        ),
        (
            "ACCELERATION TIME SERIES IN UNITS OF M/S^2",
            STANDARD_GRAVITY,
            AccelUnit::MPerS2,
        ),
        (
            "ACCELERATION TIME HISTORY IN UNITS OF M/S/S",
            STANDARD_GRAVITY,
            AccelUnit::MPerS2,
        ),
    ];
    for (units, k, unit) in cases {
        let rec = parse_at2(file(units, k), "u.AT2").unwrap();
        assert_eq!(rec.declared_unit, Some(unit), "{units}");
        let si = rec.to_record_si(STANDARD_GRAVITY);
        for (i, want) in g.iter().enumerate() {
            let a = si.accel(si.time_of(i));
            let want = want * STANDARD_GRAVITY;
            assert!((a - want).abs() <= 1e-12, "{units}: {a} m/s2, want {want}");
        }
        assert!(
            (rec.pga() - 0.3 * k).abs() <= 1e-12 * k,
            "{units}: PGA {}",
            rec.pga()
        );
    }
    // No unit in the header: the scene states it; a stated unit that contradicts the header is
    // an error.
    let bare = parse_at2(file("no unit here", 100.0 * STANDARD_GRAVITY), "b.AT2").unwrap();
    assert_eq!(bare.declared_unit, None);
    assert_eq!(bare.unit(), AccelUnit::G);
    let stated = bare.with_stated_unit(AccelUnit::CmPerS2).unwrap();
    assert_eq!(stated.unit(), AccelUnit::CmPerS2);
    let peak = stated.to_record_si(20.0).peak();
    assert!((peak - 0.3 * STANDARD_GRAVITY).abs() <= 1e-12, "{peak}");
    let in_g = parse_at2(file("IN UNITS OF G", 1.0), "g.AT2").unwrap();
    let e = in_g.with_stated_unit(AccelUnit::MPerS2).unwrap_err();
    assert!(matches!(e, MotionError::UnitMismatch { .. }), "{e:?}");
    assert!(e.to_string().contains("g.AT2"), "{e}");

    for bad in [
        "VELOCITY TIME HISTORY IN UNITS OF CM/SEC",
        "DISPLACEMENT TIME HISTORY IN UNITS OF CM",
    ] {
        let e = parse_at2(file(bad, 1.0), "v.AT2").unwrap_err();
        assert!(matches!(e, MotionError::NotAcceleration { .. }), "{e:?}");
        assert!(e.to_string().starts_with("v.AT2:3:"), "{e}");
    }
    let e = parse_at2(file("ACCELERATION IN UNITS OF FT/S/S", 1.0), "f.AT2").unwrap_err();
    assert!(
        matches!(e, MotionError::UnknownUnits { line: 3, .. }),
        "{e:?}"
    );
    let e = parse_at2(file("ACCELERATION IN UNITS OF KM/S/S", 1.0), "k.AT2").unwrap_err();
    assert_eq!(
        e.to_string(),
        "k.AT2:3: expected the units of g, cm/s2 (CM/SEC/SEC) or m/s2 (M/S/S), found \
         \"ACCELERATION IN UNITS OF KM/S/S\", an acceleration of 1000 m/s2 per unit that the \
         readers do not convert"
    );

    let dir = std::env::temp_dir().join(format!("at2-units-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for ext in ["VT2", "dt2"] {
        let path = dir.join(format!("rec.{ext}"));
        std::fs::write(&path, file("IN UNITS OF G", 1.0)).unwrap();
        let e = read_at2(&path).unwrap_err();
        assert!(matches!(e, MotionError::NotAcceleration { .. }), "{e:?}");
        assert!(e.to_string().contains(&*path.to_string_lossy()), "{e}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}
