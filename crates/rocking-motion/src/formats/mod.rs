//! Record formats besides PEER `.AT2`: plain text, ESM ASCII and K-NET/KiK-net ASCII, read into
//! the same [`At2Record`] (samples as stated, the declared unit kept) so that every format shares
//! one units model ([`AccelUnit`]): a unit stated in the file is the samples' unit, a file that
//! states none takes the unit the user states ([`At2Record::with_stated_unit`]), and a file that
//! holds velocity, displacement or a response spectrum is refused. Also the one rule for which
//! files of a folder are records ([`record_files_in`]).

use crate::error::{excerpt, short_number};
use crate::input::{decode, number, read_bytes};
use crate::units::{declared_unit, Declared};
use crate::{
    parse_at2, read_at2, AccelUnit, At2Record, MotionError, ParameterError, STANDARD_GRAVITY,
};
use std::path::{Path, PathBuf};

mod esm;
mod knet;
mod text;

pub use esm::parse_esm;
pub use knet::parse_knet;
pub use text::parse_text;

/// The layout of a record file.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum RecordFormat {
    /// PEER `.AT2` (see [`At2Record`]).
    At2,
    /// Plain text: one column (the time step stated by the user) or two columns time and
    /// acceleration; `#` starts a comment. States no unit.
    Text,
    /// ESM (Engineering Strong-Motion database) ASCII: `KEY: value` header lines
    /// (`SAMPLING_INTERVAL_S`, `NDATA`, `UNITS`, `DATA_TYPE`), then one sample per line.
    Esm,
    /// K-NET / KiK-net ASCII (NIED): 17 header lines (`Sampling Freq(Hz)`, `Scale Factor
    /// 3920(gal)/6182761`, ...), then integer counts; samples = counts × scale factor in gal,
    /// with the record's mean removed as NIED prescribes.
    Knet,
}

impl RecordFormat {
    /// The names accepted by [`RecordFormat::parse`].
    pub const NAMES: [&'static str; 4] = ["at2", "text", "esm", "knet"];

    /// A format by its scene name (`at2`, `text`, `esm`, `knet`).
    pub fn parse(name: &str) -> Option<RecordFormat> {
        match name.to_ascii_lowercase().as_str() {
            "at2" => Some(RecordFormat::At2),
            "text" => Some(RecordFormat::Text),
            "esm" => Some(RecordFormat::Esm),
            "knet" => Some(RecordFormat::Knet),
            _ => None,
        }
    }

    /// The scene name.
    pub fn name(self) -> &'static str {
        match self {
            RecordFormat::At2 => "at2",
            RecordFormat::Text => "text",
            RecordFormat::Esm => "esm",
            RecordFormat::Knet => "knet",
        }
    }

    /// The format a file name implies: `.AT2`; `.txt`, `.dat`, `.csv`; `.ASC` (ESM); K-NET's
    /// component extensions `.NS`, `.EW`, `.UD` and KiK-net's `.NS1` … `.UD2`. `None` otherwise.
    /// Case is ignored.
    pub fn from_path(path: &Path) -> Option<RecordFormat> {
        let ext = path.extension()?.to_string_lossy().to_ascii_uppercase();
        match ext.as_str() {
            "AT2" => Some(RecordFormat::At2),
            "TXT" | "DAT" | "CSV" => Some(RecordFormat::Text),
            "ASC" => Some(RecordFormat::Esm),
            "NS" | "EW" | "UD" | "NS1" | "EW1" | "UD1" | "NS2" | "EW2" | "UD2" => {
                Some(RecordFormat::Knet)
            }
            _ => None,
        }
    }
}

/// The files of `dir` that a folder of records stands for, sorted: its regular files whose
/// extension names a format that describes itself in a header (`.AT2`, ESM `.ASC`, K-NET and
/// KiK-net), not hidden. Text records (`.txt`, `.dat`, `.csv`) are given by name: they say
/// nothing of themselves and share their extensions with the READMEs and tables that download
/// folders hold (PEER's `_SearchResults.csv`). Sub-folders are not entered (a folder named
/// `RSN1.AT2` is not a record).
///
/// # Errors
/// [`MotionError::Io`] when the folder cannot be listed.
pub fn record_files_in(dir: &Path) -> Result<Vec<PathBuf>, MotionError> {
    let io = |source| MotionError::Io {
        path: dir.to_path_buf(),
        source,
    };
    let mut files = Vec::new();
    for entry in std::fs::read_dir(dir).map_err(io)? {
        let path = entry.map_err(io)?.path();
        let hidden = path
            .file_name()
            .is_some_and(|n| n.to_string_lossy().starts_with('.'));
        let described = RecordFormat::from_path(&path).is_some_and(|f| f != RecordFormat::Text);
        if described && !hidden && path.is_file() {
            files.push(path);
        }
    }
    files.sort();
    Ok(files)
}

/// What [`record_files_in`] lists, for messages about an empty folder.
pub const FOLDER_RULE: &str = "a folder stands for its .AT2, ESM .ASC and K-NET/KiK-net files; \
                               give text records (.txt, .dat, .csv) by name";

/// Reads a record file in `format`; `dt` is the time step of a one-column text file (s) and
/// must agree with the times of a two-column one; other formats state their own and refuse it.
///
/// # Errors
/// The file cannot be read, or does not have the layout of its format (the error names the file
/// and the line).
pub fn read_record(
    path: impl AsRef<Path>,
    format: RecordFormat,
    dt: Option<f64>,
) -> Result<At2Record, MotionError> {
    let path = path.as_ref();
    if format == RecordFormat::At2 {
        refuse_dt(format, dt, &path.display().to_string())?;
        return read_at2(path);
    }
    parse_record(read_bytes(path)?, format, &path.display().to_string(), dt)
}

/// [`read_record`] of the bytes of a file called `name` (for messages).
///
/// # Errors
/// As [`read_record`].
pub fn parse_record(
    bytes: impl AsRef<[u8]>,
    format: RecordFormat,
    name: &str,
    dt: Option<f64>,
) -> Result<At2Record, MotionError> {
    refuse_dt(format, dt, name)?;
    if format == RecordFormat::At2 {
        return parse_at2(bytes, name);
    }
    let text = decode(bytes.as_ref(), name)?;
    match format {
        RecordFormat::Text => parse_text(&text, name, dt),
        RecordFormat::Esm => parse_esm(&text, name),
        RecordFormat::Knet => parse_knet(&text, name),
        RecordFormat::At2 => unreachable!("parsed above"),
    }
}

/// A time step stated for a format that states its own is an error.
fn refuse_dt(format: RecordFormat, dt: Option<f64>, name: &str) -> Result<(), MotionError> {
    if format != RecordFormat::Text && dt.is_some() {
        return Err(ParameterError::DtNotTaken {
            file: name.to_string(),
            format: format.name(),
        }
        .into());
    }
    Ok(())
}

/// `Empty` unless `text` has something besides blanks.
fn not_blank(text: &str, file: &str, expected: &'static str) -> Result<(), MotionError> {
    if text.trim().is_empty() {
        Err(MotionError::Empty {
            file: file.to_owned(),
            expected,
        })
    } else {
        Ok(())
    }
}

fn malformed(file: &str, line: usize, expected: &str, found: &str) -> MotionError {
    MotionError::Malformed {
        file: file.to_owned(),
        line,
        expected: expected.to_owned(),
        found: found.to_owned(),
    }
}

fn record(file: &str, title: &str, event: &str, dt: f64, samples: Vec<f64>) -> At2Record {
    At2Record {
        source: file.to_owned(),
        title: title.to_owned(),
        event: event.to_owned(),
        units: String::new(),
        npts: samples.len(),
        dt,
        declared_unit: None,
        samples,
    }
}

/// The acceleration unit a header field states (`UNITS: cm/s^2`, K-NET's `(gal)`), or the error
/// saying what it is instead.
fn stated_unit(field: &str, file: &str, line: usize, raw: &str) -> Result<AccelUnit, MotionError> {
    match declared_unit(field) {
        Declared::Unit(u) => Ok(u),
        Declared::NotAcceleration => Err(MotionError::NotAcceleration {
            file: file.to_owned(),
            line: Some(line),
            found: format!("a velocity or displacement unit (\"{}\")", excerpt(raw)),
        }),
        Declared::Unknown(m_s2) => Err(MotionError::UnknownUnits {
            file: file.to_owned(),
            line,
            found: excerpt(raw),
            m_s2,
        }),
        Declared::Nothing => Err(MotionError::UnknownUnits {
            file: file.to_owned(),
            line,
            found: excerpt(raw),
            m_s2: None,
        }),
    }
}

/// The allowance on a stated peak beyond its printed precision, relative: 1 %. The headers print
/// the peak of the very samples of the file (ESM: the signed sample of largest |a|; K-NET: the
/// counts × scale factor with the mean removed), so a file read right matches to the last printed
/// digit (54 NIED K-NET/KiK-net files and 6 ESM files checked: within half a unit in that digit);
/// 1 % leaves room for a provider that computes its peak before rounding the samples or takes its
/// g as 9.81 (0.03 %), while a unit or scale the reader did not apply is off by 9.8x (g and
/// m/s²) or more, 100x (cm/s² and m/s²), 980x (g and cm/s²).
pub const PEAK_TOL: f64 = 0.01;

/// Half a unit in the last printed digit of a number as written (`350.2` → 0.05, `136.343` →
/// 0.0005, `1.5E+02` → 5, `48` → 0.5): how far the printed value may be from the one it rounds.
fn printed_half_unit(value: &str) -> f64 {
    let v = value.trim().trim_start_matches(['+', '-']);
    let (mantissa, exponent) = match v.find(['e', 'E', 'd', 'D']) {
        Some(i) => (&v[..i], v[i + 1..].parse::<i32>().unwrap_or(0)),
        None => (v, 0),
    };
    let decimals = mantissa.split_once('.').map_or(0, |(_, d)| d.len() as i32);
    0.5 * 10f64.powi(exponent - decimals)
}

/// `x` to six significant digits, for a message.
fn six_digits(x: f64) -> String {
    short_number(format!("{x:.5e}").parse().unwrap_or(x))
}

/// The stated-peak check: a header field `key` (on `line`) that states the record's peak as
/// `value` in `stated_unit` must agree with the peak |a| of `samples` (in `unit`), compared in the
/// samples' unit within the printed precision of `value` plus [`PEAK_TOL`]. The sign of `value`
/// is not read (ESM writes the signed sample). A blank value is no check; a value that is not a
/// number is refused.
fn check_stated_peak(
    file: &str,
    line: usize,
    key: &str,
    value: &str,
    stated_unit: AccelUnit,
    samples: &[f64],
    unit: AccelUnit,
) -> Result<(), MotionError> {
    let value = value.trim();
    if value.is_empty() {
        return Ok(());
    }
    let stated = number(value, file, line)?;
    // the stated unit in the samples' unit (g as standard gravity: within 0.03 % of any
    // provider's)
    let k = stated_unit.in_m_s2(STANDARD_GRAVITY) / unit.in_m_s2(STANDARD_GRAVITY);
    let want = stated.abs() * k;
    let tol = printed_half_unit(value) * k + PEAK_TOL * want;
    let peak = samples.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    if (peak - want).abs() <= tol {
        return Ok(());
    }
    let stated = if stated_unit == unit {
        value.to_owned()
    } else {
        format!("{value} (= {} {})", six_digits(want), unit.symbol())
    };
    Err(MotionError::PeakMismatch {
        file: file.to_owned(),
        line,
        key: key.to_owned(),
        stated,
        found: format!("{} {}", six_digits(peak), unit.symbol()),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::AccelUnit;

    #[test]
    fn text_columns() {
        let one = parse_text("# a\n0.1\n-0.2\n\n0.3 # c\n", "f", Some(0.01)).unwrap();
        assert_eq!(one.samples, vec![0.1, -0.2, 0.3]);
        assert_eq!(one.dt, 0.01);
        assert_eq!(one.declared_unit, None);
        let two = parse_text("0.00 1\n0.01, 2\n0.02\t3\n", "f", None).unwrap();
        assert_eq!(two.samples, vec![1.0, 2.0, 3.0]);
        assert!((two.dt - 0.01).abs() < 1e-15);
        let e = parse_text("0.1\n0.2\n", "f.txt", None).unwrap_err();
        assert!(e.to_string().contains("`dt`"), "{e}");
        let e = parse_text("0 1\n0.01 2\n0.03 3\n", "f.txt", None).unwrap_err();
        assert!(
            e.to_string()
                .starts_with("f.txt:3: expected equally spaced"),
            "{e}"
        );
        let e = parse_text("0 1\n0.01\n", "f.txt", None).unwrap_err();
        assert!(e.to_string().starts_with("f.txt:2:"), "{e}");
        let e = parse_text("0 1\n0.01 2\n", "f.txt", Some(0.02)).unwrap_err();
        assert!(e.to_string().contains("contradicts"), "{e}");
        let e = parse_text("0 1\n0.01 x\n", "f.txt", None).unwrap_err();
        assert!(
            e.to_string().starts_with("f.txt:2: expected a number"),
            "{e}"
        );
    }

    #[test]
    fn esm_header() {
        let head = "EVENT_NAME: Test\nDATA_TYPE: ACCELERATION\nUNITS: cm/s^2\n\
                    SAMPLING_INTERVAL_S: 0.010000\nNDATA: 3\nUSER5:\n";
        let r = parse_esm(&format!("{head}1.0\n-2.0\n3.0\n"), "e.ASC").unwrap();
        assert_eq!(r.declared_unit, Some(AccelUnit::CmPerS2));
        assert_eq!(r.dt, 0.01);
        assert_eq!(r.samples, vec![1.0, -2.0, 3.0]);
        let e = parse_esm(&format!("{head}1.0\n"), "e.ASC").unwrap_err();
        assert_eq!(
            e.to_string(),
            "e.ASC:5: expected 3 samples (NDATA in the header), found 1"
        );
        // two columns (a spectrum's period and Sa) are not a time history
        let e = parse_esm(&format!("{head}1.0\n-2.0 1\n3.0\n"), "e.ASC").unwrap_err();
        assert!(
            e.to_string()
                .starts_with("e.ASC:8: expected one sample per line"),
            "{e}"
        );
        let v = head.replace("ACCELERATION", "VELOCITY");
        let e = parse_esm(&format!("{v}1\n2\n3\n"), "e.ASC").unwrap_err();
        assert!(matches!(e, MotionError::NotAcceleration { .. }), "{e}");
        assert_eq!(
            e.to_string(),
            "e.ASC:2: expected an acceleration history, found a velocity history \
             (\"DATA_TYPE: VELOCITY\")"
        );
        let u = head.replace("cm/s^2", "cm/s");
        let e = parse_esm(&format!("{u}1\n2\n3\n"), "e.ASC").unwrap_err();
        assert!(matches!(e, MotionError::NotAcceleration { .. }), "{e}");
        assert!(e.to_string().starts_with("e.ASC:3:"), "{e}");
        let n = head.replace("UNITS: cm/s^2\n", "");
        let e = parse_esm(&format!("{n}1\n2\n3\n"), "e.ASC").unwrap_err();
        assert!(e.to_string().contains("UNITS"), "{e}");
    }

    /// A K-NET file of `counts` with the given scale factor and `Max. Acc. (gal)` value.
    fn knet_text(scale: &str, max_acc: &str, counts: &str) -> String {
        let mut text = String::new();
        for label in [
            "Origin Time       2011/03/11 14:46:00",
            "Lat.              38.103",
            "Long.             142.860",
            "Depth. (km)       24",
            "Mag.              9.0",
            "Station Code      MYG004",
            "Station Lat.      38.7312",
            "Station Long.     141.0214",
            "Station Height(m) 230",
            "Record Time       2011/03/11 14:46:57",
            "Sampling Freq(Hz) 100Hz",
            "Duration Time(s)  300",
            "Dir.              N-S",
            &format!("Scale Factor      {scale}"),
            &format!("Max. Acc. (gal)   {max_acc}"),
            "Last Correction   2011/03/11 14:46:42",
            "Memo.",
        ] {
            text.push_str(label);
            text.push('\n');
        }
        text.push_str(counts);
        text.push('\n');
        text
    }

    #[test]
    fn knet_counts() {
        let text = knet_text("3920(gal)/6182761", "0.006", "  10  20  30");
        let r = parse_knet(&text, "k.NS").unwrap();
        let f = 3920.0 / 6182761.0;
        assert_eq!(r.dt, 0.01);
        assert_eq!(r.declared_unit, Some(AccelUnit::CmPerS2));
        assert!((r.samples[0] + 10.0 * f).abs() < 1e-15 && r.samples[1].abs() < 1e-15);
        for freq in ["100 Hz", "100", "100HZ"] {
            let r = parse_knet(&text.replace("100Hz", freq), "k.NS").unwrap();
            assert_eq!(r.dt, 0.01, "{freq}");
        }
        let e = parse_knet(&text.replace("3920(gal)", "3920(kine)"), "k.NS").unwrap_err();
        assert!(matches!(e, MotionError::NotAcceleration { .. }), "{e}");
        assert!(e.to_string().starts_with("k.NS:14:"), "{e}");
        let e = parse_knet("Origin Time x\nLat.  1\n", "k.NS").unwrap_err();
        assert_eq!(
            e.to_string(),
            "k.NS:3: expected the K-NET header line \"Long. …\" (header line 3 of 17), found \
             end of file"
        );
    }

    /// The bracket of `Scale Factor <a>(<unit>)/<b>` may hold a unit with a `/`: `cm/s2` is an
    /// acceleration (it was split at its own `/` and read as `cm`, refused as a displacement),
    /// and the numerator is in that unit. A velocity or displacement unit is still refused.
    #[test]
    fn knet_scale_factor_units() {
        let counts = "  0  100000  200000";
        let gal = parse_knet(&knet_text("3920(gal)/6182761", "", counts), "k.NS").unwrap();
        for unit in [
            "cm/s2",
            "cm/s^2",
            "cm/s/s",
            "Gal",
            "GAL",
            "cm/sec/sec",
            " cm/s2 ",
        ] {
            let text = knet_text(&format!("3920({unit})/6182761"), "", counts);
            let r = parse_knet(&text, "k.NS").unwrap_or_else(|e| panic!("{unit}: {e}"));
            assert_eq!(r.declared_unit, Some(AccelUnit::CmPerS2), "{unit}");
            assert_eq!(r.samples, gal.samples, "{unit}");
        }
        // m/s2: the same numbers, in m/s²
        for unit in ["m/s2", "M/S^2", "m/s/s"] {
            let text = knet_text(&format!("3920({unit})/6182761"), "", counts);
            let r = parse_knet(&text, "k.NS").unwrap_or_else(|e| panic!("{unit}: {e}"));
            assert_eq!(r.declared_unit, Some(AccelUnit::MPerS2), "{unit}");
            assert_eq!(r.samples, gal.samples, "{unit}");
        }
        for unit in ["cm/s", "kine", "cm", "m"] {
            let text = knet_text(&format!("3920({unit})/6182761"), "", counts);
            let e = parse_knet(&text, "k.NS").unwrap_err();
            assert!(
                matches!(e, MotionError::NotAcceleration { .. }),
                "{unit}: {e}"
            );
            assert!(
                e.to_string()
                    .starts_with("k.NS:14: expected an acceleration"),
                "{e}"
            );
        }
        for scale in [
            "3920(gal/6182761",
            "3920(gal)6182761",
            "3920 gal/6182761",
            "(gal)/1",
        ] {
            let e = parse_knet(&knet_text(scale, "", counts), "k.NS").unwrap_err();
            assert!(
                e.to_string().starts_with("k.NS:14: expected"),
                "{scale}: {e}"
            );
        }
    }

    /// `Max. Acc. (gal)` is the peak |a| of the record with its mean removed; it must agree with
    /// the samples within its printed digits + 1 %, or the file is refused on its line (15).
    #[test]
    fn knet_stated_peak() {
        // counts 0, 1e5, 2e5: the mean removed, ±1e5 counts = ±63.4021 gal; 126.804 raw.
        let counts = "  0  100000  200000";
        let read =
            |scale: &str, max_acc: &str| parse_knet(&knet_text(scale, max_acc, counts), "k.NS");
        for ok in ["63.402", "63.40", "63.4", "63", "6.3402E+01", "63.9", ""] {
            assert!(read("3920(gal)/6182761", ok).is_ok(), "{ok}");
        }
        // the header in gal, the samples in m/s²: compared in m/s² (6340.21 gal)
        assert!(read("3920(m/s2)/6182761", "6340.21").is_ok());
        let e = read("3920(m/s2)/6182761", "63.402").unwrap_err();
        assert_eq!(
            e.to_string(),
            "k.NS:15: the header states Max. Acc. (gal) = 63.402 (= 0.63402 m/s²) but the \
             samples peak at 63.4021 m/s² (a unit or scale the reader did not apply?)"
        );
        for (bad, found) in [
            ("634.021", "63.4021 cm/s²"),
            ("6340.21", "63.4021 cm/s²"),
            ("6.340", "63.4021 cm/s²"),
            ("126.804", "63.4021 cm/s²"), // the peak of the raw counts, not NIED's
            ("64.1", "63.4021 cm/s²"),
        ] {
            let e = read("3920(gal)/6182761", bad).unwrap_err();
            assert!(
                matches!(e, MotionError::PeakMismatch { line: 15, .. }),
                "{bad}: {e}"
            );
            assert_eq!(
                e.to_string(),
                format!(
                    "k.NS:15: the header states Max. Acc. (gal) = {bad} but the samples peak \
                     at {found} (a unit or scale the reader did not apply?)"
                )
            );
        }
        let e = read("3920(gal)/6182761", "n/a").unwrap_err();
        assert!(
            e.to_string().starts_with("k.NS:15: expected a number"),
            "{e}"
        );
        // NIED's own format page spells it `Max Acc. (gal)`
        let text = knet_text("3920(gal)/6182761", "634.021", counts)
            .replace("Max. Acc. (gal)", "Max Acc. (gal) ");
        let e = parse_knet(&text, "k.NS").unwrap_err();
        assert!(
            e.to_string()
                .starts_with("k.NS:15: the header states Max Acc. (gal)"),
            "{e}"
        );
    }

    /// `PGA_CM/S^2` (the signed sample of largest |a|) must agree with the samples, or the file
    /// is refused on its line; blank or absent, nothing is checked.
    #[test]
    fn esm_stated_peak() {
        let head = "EVENT_NAME: Test\nDATA_TYPE: ACCELERATION\nUNITS: cm/s^2\n\
                    SAMPLING_INTERVAL_S: 0.010000\nNDATA: 3\nPGA_CM/S^2: PEAK\nUSER5:\n";
        let read = |units: &str, pga: &str| {
            let text = head.replace("cm/s^2", units).replace("PEAK", pga);
            parse_esm(&format!("{text}1.0\n-3.502\n3.0\n"), "e.ASC")
        };
        for ok in ["-3.502000", "3.502000", "3.5", "3.52", ""] {
            assert!(read("cm/s^2", ok).is_ok(), "{ok}");
        }
        assert!(parse_esm(
            &format!(
                "{}1.0\n-3.502\n3.0\n",
                head.replace("PGA_CM/S^2: PEAK\n", "")
            ),
            "e.ASC"
        )
        .is_ok());
        // samples in m/s², the peak in cm/s²: 350.2 cm/s² is 3.502 m/s²
        assert!(read("m/s^2", "-350.200000").is_ok());
        for (units, pga, stated) in [
            ("cm/s^2", "35.020000", "35.020000"),
            ("cm/s^2", "350.200000", "350.200000"),
            ("cm/s^2", "0.350200", "0.350200"),
            ("m/s^2", "3.502000", "3.502000 (= 0.03502 m/s²)"),
            ("g", "3.434", "3.434 (= 0.00350171 g)"),
        ] {
            let e = read(units, pga).unwrap_err();
            assert!(
                matches!(e, MotionError::PeakMismatch { line: 6, .. }),
                "{pga}: {e}"
            );
            let unit = match units {
                "g" => "g",
                "m/s^2" => "m/s²",
                _ => "cm/s²",
            };
            assert_eq!(
                e.to_string(),
                format!(
                    "e.ASC:6: the header states PGA_CM/S^2 = {stated} but the samples peak at \
                     3.502 {unit} (a unit or scale the reader did not apply?)"
                )
            );
        }
    }

    #[test]
    fn formats_by_name_and_extension() {
        for n in RecordFormat::NAMES {
            assert_eq!(RecordFormat::parse(n).unwrap().name(), n);
        }
        let f = |p: &str| RecordFormat::from_path(Path::new(p));
        assert_eq!(f("a/RSN1.AT2"), Some(RecordFormat::At2));
        assert_eq!(f("x.txt"), Some(RecordFormat::Text));
        assert_eq!(f("EMSC.HNE.ASC"), Some(RecordFormat::Esm));
        assert_eq!(f("MYG0041103111446.NS"), Some(RecordFormat::Knet));
        assert_eq!(f("IWTH251103111446.EW2"), Some(RecordFormat::Knet));
        assert_eq!(f("x.VT2"), None);
        assert_eq!(f("x.asc"), Some(RecordFormat::Esm));
    }

    /// A PEER download folder: records, `_SearchResults.csv`, a README and a sub-folder named
    /// like a record; only the records are listed.
    #[test]
    fn folder_lists_its_records() {
        let dir = std::env::temp_dir().join(format!("record-folder-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(dir.join("RSN9.AT2")).unwrap();
        for f in [
            "RSN2_B.AT2",
            "RSN1_A.at2",
            "_SearchResults.csv",
            "README.txt",
            "notes.dat",
            ".hidden.AT2",
            "EMSC.HNE.ASC",
            "MYG0041103111446.NS",
            "RSN1_A.VT2",
        ] {
            std::fs::write(dir.join(f), "x").unwrap();
        }
        let names: Vec<String> = record_files_in(&dir)
            .unwrap()
            .iter()
            .map(|p| p.file_name().unwrap().to_string_lossy().into_owned())
            .collect();
        assert_eq!(
            names,
            [
                "EMSC.HNE.ASC",
                "MYG0041103111446.NS",
                "RSN1_A.at2",
                "RSN2_B.AT2"
            ]
        );
        let e = record_files_in(&dir.join("nowhere")).unwrap_err();
        assert!(e.to_string().contains("nowhere"), "{e}");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
