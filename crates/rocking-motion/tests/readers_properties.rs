//! Property tests over every record reader: any bytes give a record, a clear error (the file and
//! a line) or a refusal — never a panic, a hang or a unit read as another.

use proptest::prelude::*;
use rocking_motion::{
    parse_record, AccelUnit, At2Record, MotionError, RecordFormat, MIN_DT, STANDARD_GRAVITY,
};
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

/// How the AT2 reader's unit rules (units.rs `declared_unit`, `unit_expression`) let a header
/// spell each unit: a length over times with powers (`/SEC/SEC`, `/S^2`, `/S**2`, `/S2`, `/S²`,
/// spaces around `/`), `GAL`, `G`. Case is varied by the test.
const UNIT_SPELLINGS: [(&str, AccelUnit); 24] = [
    ("G", AccelUnit::G),
    ("g", AccelUnit::G),
    ("CM/SEC/SEC", AccelUnit::CmPerS2),
    ("CM/S/S", AccelUnit::CmPerS2),
    ("CM/S^2", AccelUnit::CmPerS2),
    ("CM/S**2", AccelUnit::CmPerS2),
    ("CM/S2", AccelUnit::CmPerS2),
    ("CM/SEC^2", AccelUnit::CmPerS2),
    ("CM/SEC2", AccelUnit::CmPerS2),
    ("cm/s²", AccelUnit::CmPerS2),
    ("CM / SEC / SEC", AccelUnit::CmPerS2),
    ("CM/SECOND/SECOND", AccelUnit::CmPerS2),
    ("GAL", AccelUnit::CmPerS2),
    ("GALS", AccelUnit::CmPerS2),
    ("M/S/S", AccelUnit::MPerS2),
    ("M/S^2", AccelUnit::MPerS2),
    ("M/S2", AccelUnit::MPerS2),
    ("M/S**2", AccelUnit::MPerS2),
    ("M/SEC/SEC", AccelUnit::MPerS2),
    ("M/SEC^2", AccelUnit::MPerS2),
    ("METERS/SEC/SEC", AccelUnit::MPerS2),
    ("METRE/S^2", AccelUnit::MPerS2),
    ("m/s²", AccelUnit::MPerS2),
    ("M / S / S", AccelUnit::MPerS2),
];
/// The forms of AT2 line 3 that name a unit, `{u}` for the unit; `false`: the form names `G`
/// only with a `/` or as GAL (`ACCELERATION (G)` states no unit: a bare `G` in brackets is not
/// read, and such a line is left out here).
const UNIT_FORMS: [(&str, bool); 10] = [
    ("ACCELERATION TIME SERIES IN UNITS OF {u}", true),
    ("ACCELERATION TIME HISTORY IN UNITS OF {u}", true),
    ("IN UNITS OF {u}", true),
    ("ACCELERATION IN {u}", true),
    ("accel. in {u}", true),
    ("UNITS: {u}", true),
    ("UNITS ARE {u}", true),
    ("UNITS = {u}", true),
    ("The units are ({u})", true),
    ("ACCELERATION ({u})", false),
];
/// Multipliers after a unit: each must be refused, never dropped (10-1000x).
const MULTIPLIERS: [&str; 12] = [
    " X 10^-3",
    " x1000",
    " (SCALED BY 1000)",
    " TIMES 10",
    " * 100",
    " *100",
    " X10^3",
    " MULTIPLIED BY 100",
    " SCALE FACTOR 1000",
    " (x 0.001)",
    " ×1000",
    " × 10^-3",
];
/// What may follow `IN` that is no acceleration unit the readers take: refused on line 3.
const NOT_UNITS: [&str; 20] = [
    "%G",
    "MG",
    "MGAL",
    "COUNTS",
    "FEET/SEC/SEC",
    "FT/S/S",
    "KM/S/S",
    "MM/S^2",
    "IN/SEC/SEC",
    "MICRO-G",
    "MILLI-G",
    "0.001 G",
    "VOLTS",
    "DIGITS",
    "GALILEO",
    "CM/SEC",
    "KINE",
    "CM",
    "M",
    "SEC",
];
/// NPTS or DT written as an expression or with a decimal comma: refused on line 4, never read
/// as its leading number. `{n}` is the true count, `{dt}` the true step as a plain decimal.
const BAD_NPTS: [&str; 6] = ["{n}.7", "{n}/1", "{n}*1", "{n}_0", "{n},5", "{n}.0"];
const BAD_DT: [&str; 9] = [
    "1/{n}", "2*{dt}", "{dt}*1", "1_000", "0,02", "{dt}+0", "{dt}/1", "{dt}.5", "{dt}%",
];

/// `x` with the ASCII letters' case set by `upper` (cycled).
fn with_case(x: &str, upper: &[bool]) -> String {
    x.chars()
        .zip(upper.iter().cycle())
        .map(|(c, &u)| {
            if u {
                c.to_ascii_uppercase()
            } else {
                c.to_ascii_lowercase()
            }
        })
        .collect()
}

/// m × 10^e (m ≥ 1, e ≤ 0) written in one of the spellings of a plain number: `0.005`,
/// `.005`, `0.00500`, `+0.005`, `5E-3`, `5.0e-03`, `5D-3`, `0.5E-2`.
fn spell_decimal(m: u32, e: i32, style: usize, zeros: usize) -> String {
    let digits = m.to_string();
    let point = digits.len() as i32 + e; // digits before the point
    let plain = if point > 0 {
        let (a, b) = digits.split_at(point as usize);
        format!("{a}.{b}{}", "0".repeat(zeros))
    } else {
        format!(
            "0.{}{digits}{}",
            "0".repeat((-point) as usize),
            "0".repeat(zeros)
        )
    };
    match style {
        0 => plain,
        1 => plain.trim_start_matches('0').to_string(), // .005 (5. for a whole number)
        2 => format!("+{plain}"),
        3 => format!("{m}E{e}"),
        4 => format!("{m}.0e{e:+03}"),
        5 => format!("{m}D{e}"),
        _ => format!(
            "{}.{}E{}",
            &digits[..1],
            &digits[1..],
            e + digits.len() as i32 - 1
        ),
    }
}

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

proptest! {
    #![proptest_config(ProptestConfig { cases: 256, ..ProptestConfig::default() })]

    /// An AT2 header whose line 3 names (a) a unit the reader takes, in any spelling and case,
    /// possibly followed by a multiplier, or (b) something else after IN, and whose line 4
    /// writes NPTS and DT (c) as plain numbers in any spelling or (d) as expressions. The reader
    /// returns the record exactly when (a) without a multiplier and (c): its declared unit is
    /// the one written, its DT the number written, its samples those written, and in m/s² they
    /// are the written ones times the unit's factor. Otherwise it refuses on line 3 (the unit)
    /// or 4 (NPTS, DT), naming the file: never another unit, a dropped multiplier or a
    /// truncated number.
    #[test]
    fn unit_lines_and_time_steps_are_read_exactly_or_refused(
        unit in 0usize..UNIT_SPELLINGS.len(),
        form in 0usize..UNIT_FORMS.len(),
        multiplier in proptest::option::weighted(0.3, 0usize..MULTIPLIERS.len()),
        not_unit in proptest::option::weighted(0.2, 0usize..NOT_UNITS.len()),
        case in proptest::collection::vec(any::<bool>(), 1..12),
        (m, e, style, zeros) in (1u32..100_000, -6i32..=0, 0usize..7, 0usize..3),
        dt_unit in prop::sample::select(vec!["", " SEC", "SEC", " sec", " SECONDS"]),
        bad_npts in proptest::option::weighted(0.1, 0usize..BAD_NPTS.len()),
        bad_dt in proptest::option::weighted(0.1, 0usize..BAD_DT.len()),
        samples in proptest::collection::vec(-1e3f64..1e3, 1..7),
    ) {
        let (spelling, want) = UNIT_SPELLINGS[unit];
        // a bare G in brackets states no unit (not generated, see UNIT_FORMS)
        let form = if want == AccelUnit::G && !UNIT_FORMS[form].1 { 0 } else { form };
        let named = not_unit.map_or(spelling, |k| NOT_UNITS[k]);
        let template = if not_unit.is_some() { "ACCELERATION IN {u}" } else { UNIT_FORMS[form].0 };
        let line3 = format!(
            "{}{}",
            template.replace("{u}", named),
            multiplier.map_or("", |k| MULTIPLIERS[k])
        );
        let line3 = with_case(&line3, &case);
        let n = samples.len();
        let dt_text = spell_decimal(m, e, style, zeros);
        let dt: f64 = format!("{m}e{e}").parse().unwrap();
        let npts_token = bad_npts.map_or(n.to_string(), |k| BAD_NPTS[k].replace("{n}", &n.to_string()));
        let dt_token = bad_dt.map_or(dt_text.clone(), |k| {
            BAD_DT[k].replace("{n}", &n.to_string()).replace("{dt}", &spell_decimal(m, e, 0, 0))
        });
        let line4 = with_case(&format!("NPTS= {npts_token}, DT= {dt_token}{dt_unit}"), &case);
        let data: Vec<String> = samples.iter().map(|x| format!("{x:e}")).collect();
        let text = format!("TITLE\nEVENT\n{line3}\n{line4}\n{}\n", data.join(" "));
        let name = "prop.AT2";
        let got = parse_record(&text, RecordFormat::At2, name, None);
        let unit_refused = multiplier.is_some() || not_unit.is_some();
        let step_refused = bad_npts.is_some() || bad_dt.is_some();
        match got {
            Ok(r) => {
                prop_assert!(!unit_refused && !step_refused, "read, should be refused:\n{}\n{:?}", text, r);
                prop_assert_eq!(r.declared_unit, Some(want), "{}", text);
                prop_assert_eq!(r.dt, dt, "{}", text);
                prop_assert_eq!(r.npts, n);
                prop_assert_eq!(&r.samples, &samples, "{}", text);
                // in m/s² at two g's: g follows the structure, an absolute unit does not
                for g in [STANDARD_GRAVITY, 1.62] {
                    let factor = match want {
                        AccelUnit::G => g,
                        AccelUnit::CmPerS2 => 0.01,
                        AccelUnit::MPerS2 => 1.0,
                    };
                    let si = r.to_record_si(g);
                    for (k, (&a, &x)) in si.samples().iter().zip(&samples).enumerate() {
                        let (got, want) = (a * si.scale(), x * factor);
                        prop_assert!(
                            (got - want).abs() <= 1e-12 * want.abs(),
                            "sample {}: {} m/s², want {}\n{}", k, got, want, text
                        );
                    }
                }
            }
            Err(err) => {
                let msg = err.to_string();
                prop_assert!(unit_refused || step_refused, "refused, should be read:\n{}\n{}", text, msg);
                prop_assert!(msg.starts_with(name) && !msg.contains('\n'), "{}", msg);
                // line 3 is read first: a unit problem is reported there
                let line = if unit_refused { 3 } else { 4 };
                prop_assert_eq!(err.line(), Some(line), "{}\n{}", text, msg);
                prop_assert!(msg.starts_with(&format!("{name}:{line}: expected")), "{}", msg);
                if unit_refused {
                    prop_assert!(matches!(
                        err,
                        MotionError::UnknownUnits { .. } | MotionError::NotAcceleration { .. }
                    ), "{}", msg);
                } else {
                    prop_assert!(matches!(err, MotionError::BadHeader { .. }), "{}", msg);
                }
            }
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
