//! Reader for PEER strong-motion `.AT2` acceleration files.

use crate::error::excerpt;
use crate::{MotionError, Record, STANDARD_GRAVITY};
use std::path::Path;

/// The acceleration unit of a record's samples.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum AccelUnit {
    /// Multiples of the standard gravity.
    G,
    /// cm/s² (gal).
    CmPerS2,
    /// m/s².
    MPerS2,
}

impl AccelUnit {
    /// Every unit, in the order of [`AccelUnit::NAMES`].
    pub const ALL: [AccelUnit; 3] = [AccelUnit::G, AccelUnit::CmPerS2, AccelUnit::MPerS2];
    /// The names accepted by [`AccelUnit::parse`] (first spelling of each unit).
    pub const NAMES: [&'static str; 3] = ["g", "cm/s2", "m/s2"];

    /// One sample in this unit, in g.
    pub fn in_g(self) -> f64 {
        match self {
            AccelUnit::G => 1.0,
            AccelUnit::CmPerS2 => 0.01 / STANDARD_GRAVITY,
            AccelUnit::MPerS2 => 1.0 / STANDARD_GRAVITY,
        }
    }

    /// The short name (`g`, `cm/s2`, `m/s2`).
    pub fn name(self) -> &'static str {
        match self {
            AccelUnit::G => "g",
            AccelUnit::CmPerS2 => "cm/s2",
            AccelUnit::MPerS2 => "m/s2",
        }
    }

    /// A unit as a user writes it: `g`, `cm/s2` (`cm/s^2`, `cm/s/s`, `gal`), `m/s2` (`m/s^2`,
    /// `m/s/s`); case and spaces ignored.
    pub fn parse(s: &str) -> Option<AccelUnit> {
        let t: String = s
            .chars()
            .filter(|c| !c.is_whitespace())
            .collect::<String>()
            .to_ascii_lowercase();
        match t.as_str() {
            "g" => Some(AccelUnit::G),
            "cm/s2" | "cm/s^2" | "cm/s/s" | "cm/sec2" | "cm/sec^2" | "cm/sec/sec" | "gal" => {
                Some(AccelUnit::CmPerS2)
            }
            "m/s2" | "m/s^2" | "m/s/s" | "m/sec2" | "m/sec^2" | "m/sec/sec" => {
                Some(AccelUnit::MPerS2)
            }
            _ => None,
        }
    }
}

/// What header line 3 says about the quantity and its unit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Declared {
    /// No unit stated (the samples are taken as g unless the user states one).
    Nothing,
    /// An acceleration unit.
    Unit(AccelUnit),
    /// A unit this reader does not know.
    Unknown,
    /// A velocity or displacement history.
    NotAcceleration,
}

/// Reads the quantity and the unit from header line 3, as the PEER files write them:
/// `ACCELERATION TIME HISTORY IN UNITS OF G`, `... IN UNITS OF CM/SEC/SEC`, `The units are (g)`,
/// `VELOCITY TIME HISTORY IN UNITS OF CM/SEC`.
pub(crate) fn declared_unit(line: &str) -> Declared {
    let up = line.to_ascii_uppercase();
    if up.contains("VELOCITY") || up.contains("DISPLACEMENT") {
        return Declared::NotAcceleration;
    }
    let compact: String = up.chars().filter(|c| !c.is_whitespace()).collect();
    // Longest spellings first: "CM/S/S" contains "M/S/S".
    const CM: [&str; 7] = [
        "CM/SEC/SEC",
        "CM/SEC^2",
        "CM/SEC**2",
        "CM/SEC2",
        "CM/S/S",
        "CM/S^2",
        "CM/S2",
    ];
    const M: [&str; 7] = [
        "M/SEC/SEC",
        "M/SEC^2",
        "M/SEC**2",
        "M/SEC2",
        "M/S/S",
        "M/S^2",
        "M/S2",
    ];
    if compact.contains("MM/S") {
        return Declared::Unknown;
    }
    if CM.iter().any(|u| compact.contains(u))
        || up
            .split(|c: char| !c.is_ascii_alphanumeric())
            .any(|w| w == "GAL" || w == "GALS")
    {
        return Declared::Unit(AccelUnit::CmPerS2);
    }
    if M.iter().any(|u| compact.contains(u)) {
        return Declared::Unit(AccelUnit::MPerS2);
    }
    for intro in ["UNITSOF", "UNITSARE", "UNITS:", "UNITS=", "UNIT:", "UNIT="] {
        if let Some(rest) = compact.find(intro).map(|i| &compact[i + intro.len()..]) {
            let rest = rest.trim_start_matches(['(', '[']);
            let after = rest.chars().nth(1);
            return if rest.starts_with('G') && !after.is_some_and(|c| c.is_ascii_alphabetic()) {
                Declared::Unit(AccelUnit::G)
            } else {
                Declared::Unknown
            };
        }
    }
    Declared::Nothing
}

/// An acceleration record read from a PEER `.AT2` file.
///
/// The format (PEER strong-motion database, both the older "Pacific
/// Engineering" and the NGA flavours) is four header lines followed by the
/// samples, several per line. Header line 3 names the unit (g, cm/s² or m/s²,
/// see [`AccelUnit`]); the samples are converted to g when read. A velocity or
/// displacement history (line 3, or a `.VT2`/`.DT2` name) is refused.
///
/// ```text
/// PEER STRONG MOTION DATABASE RECORD. PROCESSING BY PACIFIC ENGINEERING.   <- title
/// CHALFANT VALLEY 07/21/86 14:42, BENTON, 360 (CDMG STATION 54100)         <- event
/// ACCELERATION TIME HISTORY IN UNITS OF G. FILTER POINTS: HP=0.2 Hz ...    <- units
/// NPTS=  7996, DT= .00500 SEC                                              <- npts, dt
///    .4417812E-03   .4396098E-03   .4036100E-03   .3622979E-03   .3223605E-03
/// ```
///
/// Line 4 is accepted in the spellings found in practice —
/// `NPTS=  1559, DT= .02000 SEC`, `NPTS=  12000, dt=  .00500`, with or
/// without trailing text/commas, case-insensitive, and the older
/// `  2000   0.0100   NPTS, DT` form. Samples may be separated by
/// whitespace or commas, any number per line (fixed `8F10.5` or E-format),
/// and Fortran `D` exponents are accepted.
#[derive(Debug, Clone, PartialEq)]
pub struct At2Record {
    /// Name of the input (file path or the name given to [`parse_at2`]).
    pub source: String,
    /// Header line 1 (usually the database/processing title).
    pub title: String,
    /// Header line 2 (usually event, date, station, component).
    pub event: String,
    /// Header line 3 (quantity and units, e.g. `ACCELERATION TIME HISTORY IN UNITS OF G`).
    pub units: String,
    /// Number of points declared in the header (= `samples.len()`).
    pub npts: usize,
    /// Time step (s).
    pub dt: f64,
    /// The unit the header declares (`None`: not stated, the samples are taken as g; see
    /// [`At2Record::with_stated_unit`]).
    pub declared_unit: Option<AccelUnit>,
    /// Accelerations in units of g (converted from the declared unit).
    pub samples: Vec<f64>,
}

impl At2Record {
    /// The record with the unit the user states for it: the samples of a record whose header
    /// states no unit are converted from `unit`; a header that declares another unit is a
    /// contradiction and an error.
    ///
    /// # Errors
    /// [`MotionError::UnitMismatch`] when the header declares a different unit.
    pub fn with_stated_unit(mut self, unit: AccelUnit) -> Result<Self, MotionError> {
        match self.declared_unit {
            Some(d) if d == unit => Ok(self),
            Some(d) => Err(MotionError::UnitMismatch {
                file: self.source,
                declared: d.name(),
                stated: unit.name(),
            }),
            None => {
                let k = unit.in_g();
                self.samples.iter_mut().for_each(|a| *a *= k);
                self.declared_unit = Some(unit);
                Ok(self)
            }
        }
    }

    /// Duration (npts − 1)·dt of the record.
    pub fn duration(&self) -> f64 {
        self.samples.len().saturating_sub(1) as f64 * self.dt
    }

    /// Peak ground acceleration max |a| in g.
    pub fn pga(&self) -> f64 {
        self.samples.iter().fold(0.0f64, |m, x| m.max(x.abs()))
    }

    /// Samples converted to m/s²: `samples × 9.80665` ([`STANDARD_GRAVITY`]).
    pub fn samples_si(&self) -> Vec<f64> {
        self.samples.iter().map(|a| a * STANDARD_GRAVITY).collect()
    }

    /// Piecewise-linear [`Record`] in units of g (time in s).
    pub fn to_record(&self) -> Record {
        self.clone().into_record()
    }

    /// Piecewise-linear [`Record`] in m/s² (scale factor
    /// [`STANDARD_GRAVITY`]; time in s).
    pub fn to_record_si(&self) -> Record {
        self.to_record().with_scale(STANDARD_GRAVITY)
    }

    /// Consume into a [`Record`] in units of g without copying the samples.
    pub fn into_record(self) -> Record {
        // Invariants established by the parser: dt > 0 finite, ≥ 1 finite sample.
        Record::new(self.dt, self.samples).expect("parser validated the record")
    }
}

/// Read and parse a PEER `.AT2` file; see [`parse_at2`]. Errors name the
/// file by `path` as given.
///
/// # Errors
/// [`MotionError::Io`] if the file cannot be read, otherwise as
/// [`parse_at2`].
pub fn read_at2(path: impl AsRef<Path>) -> Result<At2Record, MotionError> {
    let path = path.as_ref();
    if let Some(ext) = path
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_uppercase())
    {
        if ext == "VT2" || ext == "DT2" {
            return Err(MotionError::NotAcceleration {
                file: path.display().to_string(),
                found: format!(
                    "a PEER {} file (.{ext})",
                    if ext == "VT2" {
                        "velocity"
                    } else {
                        "displacement"
                    }
                ),
            });
        }
    }
    let bytes = std::fs::read(path).map_err(|source| MotionError::Io {
        path: path.to_path_buf(),
        source,
    })?;
    parse_at2(bytes, &path.display().to_string())
}

/// Parse the contents of a PEER `.AT2` file (see [`At2Record`] for the
/// format). `source_name` is used in error messages, which have the form
/// `NAME:LINE: expected …, found …`.
///
/// Validation: the input must be UTF-8 (in practice ASCII), have the four
/// header lines, `NPTS ≥ 1`, `DT > 0` and finite, every data token must be
/// a finite number, and the number of samples must equal `NPTS`. Never
/// panics, whatever the bytes.
///
/// # Errors
/// [`MotionError::NotUtf8`], [`MotionError::Empty`],
/// [`MotionError::TruncatedHeader`], [`MotionError::BadHeader`],
/// [`MotionError::InvalidNpts`], [`MotionError::InvalidDt`],
/// [`MotionError::BadToken`], [`MotionError::NonFiniteSample`],
/// [`MotionError::CountMismatch`].
pub fn parse_at2(text: impl AsRef<[u8]>, source_name: &str) -> Result<At2Record, MotionError> {
    let bytes = text.as_ref();
    let file = || source_name.to_owned();
    let text = std::str::from_utf8(bytes).map_err(|e| MotionError::NotUtf8 {
        file: file(),
        line: 1 + bytes[..e.valid_up_to()]
            .iter()
            .filter(|&&b| b == b'\n')
            .count(),
    })?;
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    if text.is_empty() {
        return Err(MotionError::Empty { file: file() });
    }

    let mut lines = text.lines();
    const EXPECTED: [&str; 4] = [
        "a title line",
        "an event/station line",
        "a units line",
        "\"NPTS=<n>, DT=<dt>\"",
    ];
    let mut header = [""; 4];
    for (i, slot) in header.iter_mut().enumerate() {
        *slot = lines.next().ok_or(MotionError::TruncatedHeader {
            file: file(),
            line: i + 1,
            expected: EXPECTED[i],
        })?;
    }

    let declared_unit = match declared_unit(header[2]) {
        Declared::Nothing => None,
        Declared::Unit(u) => Some(u),
        Declared::Unknown => {
            return Err(MotionError::UnknownUnits {
                file: file(),
                line: 3,
                found: excerpt(header[2]),
            })
        }
        Declared::NotAcceleration => {
            return Err(MotionError::NotAcceleration {
                file: format!("{}:3", file()),
                found: format!("\"{}\"", excerpt(header[2])),
            })
        }
    };
    const HEADER_LINE: usize = 4;
    let (npts, dt) = parse_npts_dt(header[3]).ok_or_else(|| MotionError::BadHeader {
        file: file(),
        line: HEADER_LINE,
        found: excerpt(header[3]),
    })?;
    if npts == 0 {
        return Err(MotionError::InvalidNpts {
            file: file(),
            line: HEADER_LINE,
            npts,
        });
    }
    if !(dt.is_finite() && dt > 0.0) {
        return Err(MotionError::InvalidDt {
            file: file(),
            line: HEADER_LINE,
            dt,
        });
    }

    // Never trust NPTS for the allocation size: each sample needs ≥ 2 bytes.
    let mut samples = Vec::with_capacity(npts.min(text.len() / 2 + 1));
    let mut found = 0usize;
    let mut surplus_line = None;
    let mut last_line = HEADER_LINE;
    for (idx, line) in lines.enumerate() {
        let line_no = HEADER_LINE + 1 + idx;
        last_line = line_no;
        for token in line
            .split(|c: char| c.is_whitespace() || c == ',')
            .filter(|s| !s.is_empty())
        {
            let value = parse_number(token).ok_or_else(|| MotionError::BadToken {
                file: file(),
                line: line_no,
                token: excerpt(token),
            })?;
            if !value.is_finite() {
                return Err(MotionError::NonFiniteSample {
                    file: file(),
                    line: line_no,
                    token: excerpt(token),
                });
            }
            found += 1;
            if found <= npts {
                samples.push(value * declared_unit.map_or(1.0, AccelUnit::in_g));
            } else if surplus_line.is_none() {
                surplus_line = Some(line_no);
            }
        }
    }
    if found != npts {
        return Err(MotionError::CountMismatch {
            file: file(),
            line: surplus_line.unwrap_or(last_line),
            declared: npts,
            found,
        });
    }

    Ok(At2Record {
        source: file(),
        title: header[0].trim().to_owned(),
        event: header[1].trim().to_owned(),
        units: header[2].trim().to_owned(),
        declared_unit,
        npts,
        dt,
        samples,
    })
}

/// Parse a number, accepting Fortran `D` exponents (`1.0D-03`).
pub(crate) fn parse_number(token: &str) -> Option<f64> {
    token.parse::<f64>().ok().or_else(|| {
        if token.contains(['d', 'D']) {
            token.replace(['d', 'D'], "e").parse::<f64>().ok()
        } else {
            None
        }
    })
}

/// Parse header line 4: `NPTS = n [,] DT = dt [anything]` (any case), or
/// the older `n dt NPTS, DT`. Returns `None` if it has neither form.
fn parse_npts_dt(line: &str) -> Option<(usize, f64)> {
    let up = line.to_ascii_uppercase();
    let npts_at = up.find("NPTS")?;
    if let Some(r) = up[npts_at + 4..].trim_start().strip_prefix(['=', ':']) {
        // NPTS= 1559, DT= .02000 SEC
        let r = r.trim_start();
        let ndig = r.bytes().take_while(u8::is_ascii_digit).count();
        let npts = r[..ndig].parse::<usize>().ok()?;
        let r = &r[ndig..];
        let r = &r[r.find("DT")? + 2..];
        let r = r.trim_start().strip_prefix(['=', ':'])?.trim_start();
        let len = r
            .bytes()
            .take_while(|b| b.is_ascii_digit() || b"+-.ED".contains(b))
            .count();
        Some((npts, parse_number(&r[..len])?))
    } else {
        // 2000   0.0100   NPTS, DT
        let mut tokens = up[..npts_at]
            .split(|c: char| c.is_whitespace() || c == ',')
            .filter(|s| !s.is_empty());
        let npts = tokens.next()?.parse::<usize>().ok()?;
        let dt = parse_number(tokens.next()?)?;
        (tokens.next().is_none() && up[npts_at..].contains("DT")).then_some((npts, dt))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn header_spellings() {
        let cases = [
            ("NPTS=  1559, DT= .02000 SEC", (1559, 0.02)),
            ("NPTS=  12000, dt=  .00500", (12000, 0.005)),
            ("NPTS=   2364, dt=   .0100 SEC", (2364, 0.01)),
            ("NPTS=  5590, DT=   .0050 SEC,", (5590, 0.005)),
            ("npts = 10,dt=0.01", (10, 0.01)),
            ("NPTS=10 DT=1.0D-02 SEC", (10, 0.01)),
            ("  2000    0.0100    NPTS, DT", (2000, 0.01)),
            ("NPTS=  3, DT= -.01 SEC", (3, -0.01)),
        ];
        for (line, want) in cases {
            assert_eq!(parse_npts_dt(line), Some(want), "{line}");
        }
        for bad in [
            "",
            "NPTS=, DT=.01",
            "NPTS= 10",
            "NPTS=10, DT=",
            "NPTS=10, DT= SEC",
            "DT=.01 NPTS=10",
            "1 2 3 NPTS DT",
            "NPTS=99999999999999999999999999, DT=.01",
            "ÄNPTS=é",
        ] {
            assert_eq!(parse_npts_dt(bad), None, "{bad}");
        }
    }

    #[test]
    fn units_lines() {
        use Declared::*;
        let g = Unit(AccelUnit::G);
        let cm = Unit(AccelUnit::CmPerS2);
        let m = Unit(AccelUnit::MPerS2);
        for (line, want) in [
            (
                "ACCELERATION TIME HISTORY IN UNITS OF G. FILTER POINTS: HP=0.2 Hz",
                g,
            ),
            ("The units are (g)", g),
            ("ACCELERATION TIME SERIES IN UNITS OF G", g),
            ("ACCELERATION TIME HISTORY IN UNITS OF CM/SEC/SEC", cm),
            ("ACCELERATION IN UNITS OF CM/S^2", cm),
            ("accel. in gal", cm),
            ("ACCELERATION TIME HISTORY IN UNITS OF M/S/S", m),
            ("ACCELERATION IN M/S^2", m),
            ("units", Nothing),
            ("U", Nothing),
            ("ACCELERATION IN UNITS OF FT/S/S", Unknown),
            ("ACCELERATION IN UNITS OF GALILEO", Unknown),
            ("ACCELERATION IN MM/S/S", Unknown),
            ("VELOCITY TIME HISTORY IN UNITS OF CM/SEC", NotAcceleration),
            ("DISPLACEMENT TIME HISTORY IN UNITS OF CM", NotAcceleration),
        ] {
            assert_eq!(declared_unit(line), want, "{line}");
        }
        for (name, u) in AccelUnit::NAMES.iter().zip(AccelUnit::ALL) {
            assert_eq!(AccelUnit::parse(name), Some(u));
        }
        assert_eq!(AccelUnit::parse("CM/S^2"), Some(AccelUnit::CmPerS2));
        assert_eq!(AccelUnit::parse("ft/s2"), None);
    }

    #[test]
    fn numbers() {
        assert_eq!(parse_number(".4417812E-03"), Some(0.4417812e-3));
        assert_eq!(parse_number("-.7877265E-04"), Some(-0.7877265e-4));
        assert_eq!(parse_number("1.5D+01"), Some(15.0));
        assert_eq!(parse_number("abc"), None);
        assert_eq!(parse_number("1.2.3"), None);
    }
}
