//! Property tests over every record reader: any bytes give a record, a clear error (the file and
//! a line) or a refusal — never a panic, a hang or a unit read as another.

use proptest::prelude::*;
use rocking_motion::{parse_record, AccelUnit, At2Record, MotionError, RecordFormat, MIN_DT};
use std::path::Path;

const FORMATS: [RecordFormat; 4] = [
    RecordFormat::At2,
    RecordFormat::Text,
    RecordFormat::Esm,
    RecordFormat::Knet,
];

/// What any input may give: a record whose invariants hold, or one error naming the input on one
/// line (with the line of the file, unless it is about the file as a whole).
fn outcome(got: Result<At2Record, MotionError>, name: &str) -> Result<(), TestCaseError> {
    match got {
        Ok(r) => {
            prop_assert!(r.npts >= 1 && r.npts == r.samples.len());
            prop_assert!(r.dt >= MIN_DT && r.dt.is_finite());
            prop_assert!(r.duration().is_finite());
            prop_assert!(r.samples.iter().all(|a| a.is_finite()));
            // a record always converts (the readers' invariants are Record's)
            prop_assert_eq!(r.to_record().len(), r.npts);
        }
        Err(e) => {
            let msg = e.to_string();
            prop_assert!(!msg.contains('\n'), "one line: {}", msg);
            match e {
                MotionError::InvalidParameter(_) => prop_assert!(msg.contains(name), "{}", msg),
                _ => {
                    prop_assert!(msg.starts_with(name), "{}", msg);
                    prop_assert!(e.line().is_some(), "{}", msg);
                }
            }
        }
    }
    Ok(())
}

fn corpus_files() -> Vec<Vec<u8>> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/corpus");
    let mut files = Vec::new();
    for sub in ["peer", "esm", "knet", "text"] {
        let mut paths: Vec<_> = std::fs::read_dir(dir.join(sub))
            .unwrap()
            .map(|e| e.unwrap().path())
            .collect();
        paths.sort();
        files.extend(paths.iter().map(|p| std::fs::read(p).unwrap()));
    }
    files
}

/// Spellings of a unit as headers write them, and the unit they mean (None: refused).
const SPELLINGS: [(&str, Option<AccelUnit>); 14] = [
    ("G", Some(AccelUnit::G)),
    ("g", Some(AccelUnit::G)),
    ("(g)", Some(AccelUnit::G)),
    ("CM/SEC/SEC", Some(AccelUnit::CmPerS2)),
    ("cm/s^2", Some(AccelUnit::CmPerS2)),
    ("CM/S**2", Some(AccelUnit::CmPerS2)),
    ("gal", Some(AccelUnit::CmPerS2)),
    ("M/S/S", Some(AccelUnit::MPerS2)),
    ("m/s^2", Some(AccelUnit::MPerS2)),
    ("M/SEC2", Some(AccelUnit::MPerS2)),
    ("KM/S/S", None),
    ("FT/S/S", None),
    ("MM/S^2", None),
    ("IN/SEC/SEC", None),
];
/// What precedes a unit on a header line.
const PREFIXES: [&str; 6] = [
    "ACCELERATION TIME SERIES IN UNITS OF ",
    "ACCELERATION TIME HISTORY IN UNITS OF ",
    "UNITS: ",
    "The units are ",
    "accel. in ",
    "UNITS ARE ",
];
/// What follows a unit: explanations in other units, filter points.
const SUFFIXES: [&str; 7] = [
    "",
    ".",
    ". FILTER POINTS: HP=0.1 Hz LP=25.0 Hz",
    " (1 G = 980.665 CM/SEC/SEC)",
    " (9.81 m/s/s)",
    " (= 0.01 M/S/S)",
    ", COMPONENT 090",
];

proptest! {
    #![proptest_config(ProptestConfig { cases: 512, ..ProptestConfig::default() })]

    #[test]
    fn any_bytes_with_any_reader(
        bytes in proptest::collection::vec(any::<u8>(), 0..1024),
        format in 0usize..4,
        dt in proptest::option::of(prop_oneof![Just(0.01), Just(0.0), Just(1e-300), Just(1e300), Just(f64::NAN)]),
    ) {
        let format = FORMATS[format];
        let dt = dt.filter(|_| format == RecordFormat::Text);
        outcome(parse_record(&bytes, format, dt_name(format), dt), dt_name(format))?;
    }

    /// Header-shaped text (keys, colons, numbers, units) reaches deeper than random bytes.
    #[test]
    fn header_shaped_text_with_any_reader(
        s in "((NPTS|DT|NDATA|UNITS|DATA_TYPE|SAMPLING_INTERVAL_S|Scale Factor|Sampling Freq\\(Hz\\)|ACCELERATION|G|CM/S\\^2|MSEC|SEC|Hz|gal|\\(|\\)|/|=|:|,|\\.|-|E|[0-9]{1,3}|99999999999|1e300|1e-300| |\n)){0,120}",
        format in 0usize..4,
    ) {
        let format = FORMATS[format];
        outcome(parse_record(&s, format, dt_name(format), None), dt_name(format))?;
    }

    #[test]
    fn mutated_corpus_files_with_any_reader(
        file in any::<prop::sample::Index>(),
        edits in proptest::collection::vec((any::<prop::sample::Index>(), any::<u8>(), 0u8..3), 1..8),
        format in 0usize..4,
    ) {
        let files = corpus_files();
        let mut bytes = files[file.index(files.len())].clone();
        for (idx, byte, op) in edits {
            if bytes.is_empty() { break; }
            let i = idx.index(bytes.len());
            match op {
                0 => bytes[i] = byte,
                1 => { bytes.remove(i); }
                _ => bytes.insert(i, byte),
            }
        }
        let format = FORMATS[format];
        let dt = (format == RecordFormat::Text).then_some(0.01);
        outcome(parse_record(&bytes, format, dt_name(format), dt), dt_name(format))?;
    }

    /// A unit on an AT2 header line or an ESM `UNITS` line is read as itself, whatever precedes
    /// or follows it, or refused: never as another unit.
    #[test]
    fn a_unit_is_read_as_itself_or_refused(
        prefix in 0usize..PREFIXES.len(),
        spelling in 0usize..SPELLINGS.len(),
        suffix in 0usize..SUFFIXES.len(),
    ) {
        let (unit, want) = SPELLINGS[spelling];
        let line = format!("{}{unit}{}", PREFIXES[prefix], SUFFIXES[suffix]);
        let at2 = format!("T\nE\n{line}\nNPTS= 2, DT= .01 SEC\n1.0 2.0\n");
        let esm = format!(
            "DATA_TYPE: ACCELERATION\nUNITS: {unit}{}\nSAMPLING_INTERVAL_S: 0.01\nNDATA: 2\n1.0\n2.0\n",
            SUFFIXES[suffix]
        );
        for (text, format) in [(at2, RecordFormat::At2), (esm, RecordFormat::Esm)] {
            match (parse_record(&text, format, "u", None), want) {
                (Ok(r), Some(u)) => prop_assert_eq!(r.declared_unit, Some(u), "{}", text),
                (Err(MotionError::UnknownUnits { .. }), None) => {}
                (got, _) => prop_assert!(false, "{}: {:?}", text, got),
            }
        }
    }

    /// `DT= x UNIT` is x seconds, or x milliseconds for MSEC and ms.
    #[test]
    fn a_time_step_is_read_in_its_unit(
        x in 1e-5f64..10.0,
        unit in prop::sample::select(vec![("", 1.0), ("SEC", 1.0), ("sec", 1.0), ("S", 1.0), ("SECONDS", 1.0), ("MSEC", 1e-3), ("ms", 1e-3)]),
    ) {
        let text = format!("T\nE\nUNITS OF G\nNPTS= 2, DT= {x} {}\n1.0 2.0\n", unit.0);
        let dt = x * unit.1;
        match parse_record(&text, RecordFormat::At2, "t", None) {
            Ok(r) => prop_assert_eq!(r.dt, dt),
            Err(e) => prop_assert!(dt < MIN_DT && matches!(e, MotionError::InvalidDt { .. }), "{}", e),
        }
    }
}

fn dt_name(format: RecordFormat) -> &'static str {
    match format {
        RecordFormat::At2 => "fuzz.AT2",
        RecordFormat::Text => "fuzz.txt",
        RecordFormat::Esm => "fuzz.ASC",
        RecordFormat::Knet => "fuzz.NS",
    }
}
