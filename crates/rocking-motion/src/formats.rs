//! Record formats besides PEER `.AT2`: plain text, ESM ASCII and K-NET/KiK-net ASCII, read into
//! the same [`At2Record`] (samples in g, the declared unit kept) so that every format shares the
//! units model of the AT2 reader: a unit stated in the file converts the samples, a file that
//! states none takes the unit the user states ([`At2Record::with_stated_unit`]), and a file that
//! holds velocity or displacement is refused.

use crate::at2::{declared_unit, parse_number, Declared};
use crate::error::excerpt;
use crate::{read_at2, At2Record, MotionError};
use std::path::Path;

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
    let name = path.display().to_string();
    if format != RecordFormat::Text && dt.is_some() {
        return Err(MotionError::InvalidParameter(format!(
            "{name}: a {} file states its own time step; `dt` is for one-column text files",
            format.name()
        )));
    }
    if format == RecordFormat::At2 {
        return read_at2(path);
    }
    let bytes = std::fs::read(path).map_err(|source| MotionError::Io {
        path: path.to_path_buf(),
        source,
    })?;
    let text = utf8(&bytes, &name)?;
    match format {
        RecordFormat::Text => parse_text(text, &name, dt),
        RecordFormat::Esm => parse_esm(text, &name),
        RecordFormat::Knet => parse_knet(text, &name),
        RecordFormat::At2 => unreachable!("read above"),
    }
}

fn utf8<'a>(bytes: &'a [u8], file: &str) -> Result<&'a str, MotionError> {
    let text = std::str::from_utf8(bytes).map_err(|e| MotionError::NotUtf8 {
        file: file.to_owned(),
        line: 1 + bytes[..e.valid_up_to()]
            .iter()
            .filter(|&&b| b == b'\n')
            .count(),
    })?;
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    if text.trim().is_empty() {
        return Err(MotionError::Empty {
            file: file.to_owned(),
        });
    }
    Ok(text)
}

fn malformed(file: &str, line: usize, expected: &str, found: &str) -> MotionError {
    MotionError::Malformed {
        file: file.to_owned(),
        line,
        expected: expected.to_owned(),
        found: found.to_owned(),
    }
}

/// A finite number, or the error naming the token.
fn number(token: &str, file: &str, line: usize) -> Result<f64, MotionError> {
    let v = parse_number(token).ok_or_else(|| MotionError::BadToken {
        file: file.to_owned(),
        line,
        token: excerpt(token),
    })?;
    if v.is_finite() {
        Ok(v)
    } else {
        Err(MotionError::NonFiniteSample {
            file: file.to_owned(),
            line,
            token: excerpt(token),
        })
    }
}

fn positive_dt(dt: f64, file: &str, line: usize) -> Result<f64, MotionError> {
    if dt.is_finite() && dt > 0.0 {
        Ok(dt)
    } else {
        Err(MotionError::InvalidDt {
            file: file.to_owned(),
            line,
            dt,
        })
    }
}

fn record(file: &str, title: &str, units: &str, dt: f64, samples: Vec<f64>) -> At2Record {
    At2Record {
        source: file.to_owned(),
        title: title.to_owned(),
        event: String::new(),
        units: units.to_owned(),
        npts: samples.len(),
        dt,
        declared_unit: None,
        samples,
    }
}

/// Relative tolerance on the spacing of the times of a two-column text file.
const SPACING_TOL: f64 = 1e-6;

/// Plain text: one column with `dt` stated, or two columns time, acceleration (spaces, tabs or
/// commas; `#` comments and blank lines skipped). The unit is not stated.
pub fn parse_text(text: &str, file: &str, dt: Option<f64>) -> Result<At2Record, MotionError> {
    let mut columns = None;
    let mut times = Vec::new();
    let mut samples = Vec::new();
    let mut first_line = 0;
    for (i, raw) in text.lines().enumerate() {
        let line_no = i + 1;
        let line = raw.split('#').next().unwrap_or("");
        let tokens: Vec<&str> = line
            .split(|c: char| c.is_whitespace() || c == ',' || c == ';')
            .filter(|s| !s.is_empty())
            .collect();
        if tokens.is_empty() {
            continue;
        }
        let n = *columns.get_or_insert_with(|| {
            first_line = line_no;
            tokens.len()
        });
        if n > 2 || tokens.len() != n {
            return Err(malformed(
                file,
                line_no,
                &format!(
                    "{} column(s) on every line (one: acceleration; two: time, acceleration)",
                    n.min(2)
                ),
                &format!("{} in \"{}\"", tokens.len(), excerpt(raw)),
            ));
        }
        if n == 2 {
            times.push((number(tokens[0], file, line_no)?, line_no));
        }
        samples.push(number(tokens[n - 1], file, line_no)?);
    }
    let dt = match (columns, dt) {
        (None, _) => return Err(malformed(file, 1, "samples", "only comments")),
        (Some(1), None) => {
            return Err(MotionError::InvalidParameter(format!(
                "{file}: a one-column text record needs its time step: give `dt` (s) in \
                 [excitation]"
            )))
        }
        (Some(1), Some(dt)) => positive_dt(dt, file, first_line)?,
        (Some(_), stated) => {
            if times.len() < 2 {
                return Err(malformed(file, first_line, "at least two rows", "one"));
            }
            let step = positive_dt(times[1].0 - times[0].0, file, times[1].1)?;
            let t0 = times[0].0;
            for (k, &(t, line)) in times.iter().enumerate() {
                let want = t0 + k as f64 * step;
                if (t - want).abs() > SPACING_TOL * step * (k as f64).max(1.0) {
                    return Err(malformed(
                        file,
                        line,
                        &format!("equally spaced times (t = {want} at this row)"),
                        &format!("t = {t}"),
                    ));
                }
            }
            // the mean step over the record: the times are rounded in print
            let dt = (times[times.len() - 1].0 - t0) / (times.len() - 1) as f64;
            if let Some(s) = stated {
                if (s - dt).abs() > SPACING_TOL * dt {
                    return Err(MotionError::InvalidParameter(format!(
                        "{file}: the stated `dt` = {s} s contradicts the file's time column \
                         (dt = {dt} s)"
                    )));
                }
            }
            dt
        }
    };
    Ok(record(file, "", "", dt, samples))
}

/// ESM ASCII (the database's converted and processed files, `*.ASC`): header lines `KEY: value`
/// until the samples, one per line. `SAMPLING_INTERVAL_S` gives dt, `NDATA` the count, `UNITS`
/// the unit (cm/s^2 in the database), `DATA_TYPE` must be an acceleration.
pub fn parse_esm(text: &str, file: &str) -> Result<At2Record, MotionError> {
    let mut dt = None;
    let mut ndata = None;
    let mut unit = None;
    let mut title = String::new();
    let mut samples = Vec::new();
    let mut header_lines = 0;
    for (i, raw) in text.lines().enumerate() {
        let line_no = i + 1;
        let line = raw.trim();
        if line.is_empty() {
            continue;
        }
        if samples.is_empty() {
            if let Some((key, value)) = line.split_once(':') {
                if key.chars().all(|c| c.is_ascii_alphanumeric() || c == '_') {
                    header_lines = line_no;
                    let value = value.trim();
                    match key {
                        "EVENT_NAME" | "EVENT_ID" if title.is_empty() => title = value.to_owned(),
                        "SAMPLING_INTERVAL_S" => {
                            dt = Some((number(value, file, line_no)?, line_no));
                        }
                        "NDATA" => {
                            let n = value.parse::<usize>().map_err(|_| {
                                malformed(file, line_no, "NDATA: <count>", &excerpt(value))
                            })?;
                            ndata = Some((n, line_no));
                        }
                        "DATA_TYPE" => {
                            let up = value.to_ascii_uppercase();
                            if !up.contains("ACCELERATION") {
                                return Err(MotionError::NotAcceleration {
                                    file: format!("{file}:{line_no}"),
                                    found: format!("\"{}\"", excerpt(raw)),
                                });
                            }
                        }
                        "UNITS" => {
                            unit = Some(match declared_unit(&format!("UNITS: {value}")) {
                                Declared::Unit(u) => u,
                                Declared::NotAcceleration => {
                                    return Err(MotionError::NotAcceleration {
                                        file: format!("{file}:{line_no}"),
                                        found: format!("\"{}\"", excerpt(raw)),
                                    })
                                }
                                _ => {
                                    return Err(MotionError::UnknownUnits {
                                        file: file.to_owned(),
                                        line: line_no,
                                        found: excerpt(raw),
                                    })
                                }
                            });
                        }
                        _ => {}
                    }
                    continue;
                }
            }
        }
        for token in line.split_whitespace() {
            samples.push(number(token, file, line_no)?);
        }
    }
    let (dt, dt_line) = dt.ok_or_else(|| {
        malformed(
            file,
            header_lines.max(1),
            "a header line \"SAMPLING_INTERVAL_S: <dt>\"",
            "none",
        )
    })?;
    let dt = positive_dt(dt, file, dt_line)?;
    let unit = unit.ok_or_else(|| {
        malformed(
            file,
            header_lines.max(1),
            "a header line \"UNITS: cm/s^2\" (or g, m/s^2)",
            "none",
        )
    })?;
    if let Some((n, line)) = ndata {
        if n != samples.len() {
            return Err(MotionError::CountMismatch {
                file: file.to_owned(),
                line,
                declared: n,
                found: samples.len(),
            });
        }
    }
    if samples.is_empty() {
        return Err(malformed(file, header_lines + 1, "samples", "none"));
    }
    let k = unit.in_g();
    samples.iter_mut().for_each(|a| *a *= k);
    let mut r = record(file, &title, unit.name(), dt, samples);
    r.declared_unit = Some(unit);
    Ok(r)
}

/// Number of header lines of a K-NET/KiK-net ASCII file.
const KNET_HEADER: usize = 17;

/// K-NET / KiK-net ASCII: 17 header lines (label in columns 1-18, value after), then integer
/// counts, 8 per line. Acceleration (gal) = counts × `Scale Factor` (`3920(gal)/6182761`) with
/// the record's mean removed; dt = 1 / `Sampling Freq(Hz)`.
pub fn parse_knet(text: &str, file: &str) -> Result<At2Record, MotionError> {
    let lines: Vec<&str> = text.lines().collect();
    if lines.len() < KNET_HEADER {
        return Err(MotionError::TruncatedHeader {
            file: file.to_owned(),
            line: lines.len() + 1,
            expected: "a K-NET header line (17 in all)",
        });
    }
    let field = |label: &str| -> Result<(&str, usize), MotionError> {
        lines[..KNET_HEADER]
            .iter()
            .enumerate()
            .find_map(|(i, l)| {
                l.trim_start()
                    .strip_prefix(label)
                    .map(|rest| (rest.trim(), i + 1))
            })
            .ok_or_else(|| {
                malformed(
                    file,
                    1,
                    &format!("a header line \"{label} ...\" among the first {KNET_HEADER}"),
                    "none",
                )
            })
    };
    let (freq, freq_line) = field("Sampling Freq(Hz)")?;
    let hz = number(
        freq.trim_end_matches(|c: char| c.is_ascii_alphabetic()),
        file,
        freq_line,
    )?;
    let dt = positive_dt(1.0 / hz, file, freq_line)?;
    let (scale, scale_line) = field("Scale Factor")?;
    let bad_scale = || malformed(file, scale_line, "\"Scale Factor <a>(gal)/<b>\"", scale);
    let (num, den) = scale.split_once('/').ok_or_else(bad_scale)?;
    let unit_start = num.find('(').ok_or_else(bad_scale)?;
    let unit = match declared_unit(&format!(
        "UNITS: {}",
        num[unit_start..].trim_matches(['(', ')'])
    )) {
        Declared::Unit(u) => u,
        _ => {
            return Err(MotionError::UnknownUnits {
                file: file.to_owned(),
                line: scale_line,
                found: excerpt(scale),
            })
        }
    };
    let factor =
        number(num[..unit_start].trim(), file, scale_line)? / number(den.trim(), file, scale_line)?;
    if !(factor.is_finite() && factor != 0.0) {
        return Err(bad_scale());
    }
    let title = field("Station Code")
        .map(|(s, _)| s.to_owned())
        .unwrap_or_default();
    let mut samples = Vec::new();
    for (i, line) in lines.iter().enumerate().skip(KNET_HEADER) {
        for token in line.split_whitespace() {
            samples.push(number(token, file, i + 1)? * factor);
        }
    }
    if samples.is_empty() {
        return Err(malformed(file, KNET_HEADER + 1, "samples", "none"));
    }
    let mean = samples.iter().sum::<f64>() / samples.len() as f64;
    let k = unit.in_g();
    samples.iter_mut().for_each(|a| *a = (*a - mean) * k);
    let mut r = record(file, &title, unit.name(), dt, samples);
    r.declared_unit = Some(unit);
    Ok(r)
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
        assert!((r.samples[1] + 2.0 * AccelUnit::CmPerS2.in_g()).abs() < 1e-18);
        let e = parse_esm(&format!("{head}1.0\n"), "e.ASC").unwrap_err();
        assert!(e.to_string().contains("expected 3 samples"), "{e}");
        let v = head.replace("ACCELERATION", "VELOCITY");
        let e = parse_esm(&format!("{v}1\n2\n3\n"), "e.ASC").unwrap_err();
        assert!(matches!(e, MotionError::NotAcceleration { .. }), "{e}");
        let u = head.replace("cm/s^2", "cm/s");
        let e = parse_esm(&format!("{u}1\n2\n3\n"), "e.ASC").unwrap_err();
        assert!(e.to_string().starts_with("e.ASC:3:"), "{e}");
        let n = head.replace("UNITS: cm/s^2\n", "");
        let e = parse_esm(&format!("{n}1\n2\n3\n"), "e.ASC").unwrap_err();
        assert!(e.to_string().contains("UNITS"), "{e}");
    }

    #[test]
    fn knet_counts() {
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
            "Scale Factor      3920(gal)/6182761",
            "Max. Acc. (gal)   2699.995",
            "Last Correction   2011/03/11 14:46:42",
            "Memo.",
        ] {
            text.push_str(label);
            text.push('\n');
        }
        text.push_str("  10  20  30\n");
        let r = parse_knet(&text, "k.NS").unwrap();
        let f = 3920.0 / 6182761.0 * AccelUnit::CmPerS2.in_g();
        assert_eq!(r.dt, 0.01);
        assert!((r.samples[0] + 10.0 * f).abs() < 1e-15 && r.samples[1].abs() < 1e-15);
        let e = parse_knet(&text.replace("3920(gal)", "3920(kine)"), "k.NS").unwrap_err();
        assert!(e.to_string().starts_with("k.NS:14:"), "{e}");
        let e = parse_knet("Origin Time x\n", "k.NS").unwrap_err();
        assert!(e.to_string().starts_with("k.NS:2:"), "{e}");
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
    }
}
