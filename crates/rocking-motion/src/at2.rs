//! Reader for PEER strong-motion `.AT2` acceleration files, and the record every reader gives.

use crate::error::excerpt;
use crate::input::{decode, parse_number, read_bytes, time_step};
use crate::units::{declared_unit, unit_expression, Declared, Quantity};
use crate::{AccelUnit, MotionError, Record};
use std::path::Path;

/// An acceleration record as a reader gives it: a PEER `.AT2` file, or any other format
/// ([`read_record`](crate::read_record)).
///
/// The PEER format (strong-motion database, the older "Pacific Engineering" and the NGA
/// flavours) is four header lines followed by the samples, several per line. Header line 3
/// names the unit (see [`AccelUnit`] and its units model); the samples are kept as the file
/// states them. A velocity or displacement history (line 3, or a `.VT2`/`.DT2` name) is
/// refused.
///
/// ```text
/// PEER NGA STRONG MOTION DATABASE RECORD                                  <- title
/// Imperial Valley-06, 10/15/1979, El Centro Array #6, 140                  <- event
/// ACCELERATION TIME SERIES IN UNITS OF G                                  <- units
/// NPTS=  7807, DT=   .0050 SEC                                            <- npts, dt
///   .1234567E-02  .2345678E-02 -.3456789E-02  .4567890E-02  .5678901E-02
/// ```
///
/// Line 3 is read as a unit expression after `UNITS OF` (`G`, `CM/SEC/SEC`, `M/S^2`, `gal`;
/// an explanation after it such as `(1 G = 980.665 CM/SEC/SEC)` is not read). Line 4 is
/// accepted in the spellings found in practice — `NPTS=  1559, DT= .02000 SEC`,
/// `NPTS=  12000, dt=  .00500`, `DT= 20 MSEC` (a time unit after DT is applied), with or without
/// trailing text/commas, case-insensitive, and the older `  2000   0.0100   NPTS, DT` form.
/// Samples may be separated by whitespace or commas, any number per line (fixed `8F10.5` or
/// E-format), and Fortran `D` exponents are accepted.
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
    /// Time step (s), at least [`MIN_DT`](crate::MIN_DT).
    pub dt: f64,
    /// The unit the header declares (`None`: not stated, the samples are taken as g; see
    /// [`At2Record::with_stated_unit`]).
    pub declared_unit: Option<AccelUnit>,
    /// Accelerations as the file states them, in [`unit`](At2Record::unit).
    pub samples: Vec<f64>,
}

impl At2Record {
    /// The record with the unit the user states for it: a record whose header states no unit
    /// takes `unit`; a header that declares another unit is a contradiction and an error.
    ///
    /// # Errors
    /// [`MotionError::UnitMismatch`] when the header declares a different unit.
    pub fn with_stated_unit(mut self, unit: AccelUnit) -> Result<Self, MotionError> {
        match self.declared_unit {
            Some(d) if d != unit => Err(MotionError::UnitMismatch {
                file: self.source,
                declared: d.name(),
                stated: unit.name(),
            }),
            _ => {
                self.declared_unit = Some(unit);
                Ok(self)
            }
        }
    }

    /// The unit of the samples: the declared one, g when none is declared or stated.
    pub fn unit(&self) -> AccelUnit {
        self.declared_unit.unwrap_or(AccelUnit::G)
    }

    /// Duration (npts − 1)·dt of the record.
    pub fn duration(&self) -> f64 {
        self.samples.len().saturating_sub(1) as f64 * self.dt
    }

    /// Peak ground acceleration max |a| in the record's [`unit`](At2Record::unit).
    pub fn pga(&self) -> f64 {
        self.samples.iter().fold(0.0f64, |m, x| m.max(x.abs()))
    }

    /// Piecewise-linear [`Record`] of the samples as stated, in the record's unit (time in s).
    pub fn to_record(&self) -> Record {
        self.clone().into_record()
    }

    /// Piecewise-linear [`Record`] in m/s² (time in s) as a structure whose g is `g_si` m/s²
    /// feels it: the units model of [`AccelUnit`] (a record in g is scaled by `g_si`, an absolute
    /// one is not).
    pub fn to_record_si(&self, g_si: f64) -> Record {
        self.to_record().with_scale(self.unit().in_m_s2(g_si))
    }

    /// Consume into a [`Record`] in the record's unit without copying the samples.
    pub fn into_record(self) -> Record {
        // Invariants established by the readers: dt >= MIN_DT, finite duration, >= 1 finite
        // sample.
        Record::new(self.dt, self.samples).expect("the reader validated the record")
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
                line: None,
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
    parse_at2(read_bytes(path)?, &path.display().to_string())
}

/// The lines of the PEER header.
const HEADER: [&str; 4] = [
    "a title line",
    "an event/station line",
    "a units line",
    "\"NPTS=<n>, DT=<dt>\"",
];

/// Parse the contents of a PEER `.AT2` file (see [`At2Record`] for the
/// format). `source_name` is used in error messages, which have the form
/// `NAME:LINE: expected …, found …`.
///
/// Validation: the input must be text (ASCII, UTF-8 or Latin-1), have the four header lines, a
/// unit the readers convert (or none), `NPTS ≥ 1`, `DT ≥` [`MIN_DT`](crate::MIN_DT) with a
/// finite duration, every data token must be a finite number, and the number of samples must
/// equal `NPTS`. Never panics, whatever the bytes.
///
/// # Errors
/// [`MotionError::NotText`], [`MotionError::Empty`], [`MotionError::TruncatedHeader`],
/// [`MotionError::UnknownUnits`], [`MotionError::NotAcceleration`],
/// [`MotionError::BadHeader`], [`MotionError::InvalidNpts`], [`MotionError::InvalidDt`],
/// [`MotionError::BadToken`], [`MotionError::NonFiniteSample`],
/// [`MotionError::CountMismatch`].
pub fn parse_at2(text: impl AsRef<[u8]>, source_name: &str) -> Result<At2Record, MotionError> {
    let file = || source_name.to_owned();
    let text = decode(text.as_ref(), source_name)?;
    if text.is_empty() {
        return Err(MotionError::Empty {
            file: file(),
            expected: "a PEER AT2 header (4 lines)",
        });
    }

    let mut lines = text.lines();
    let mut header = [""; 4];
    for (i, slot) in header.iter_mut().enumerate() {
        *slot = lines.next().ok_or(MotionError::TruncatedHeader {
            file: file(),
            line: i + 1,
            total: HEADER.len(),
            expected: HEADER[i],
        })?;
    }

    let declared_unit = match declared_unit(header[2]) {
        Declared::Nothing => None,
        Declared::Unit(u) => Some(u),
        Declared::Unknown(m_s2) => {
            return Err(MotionError::UnknownUnits {
                file: file(),
                line: 3,
                found: excerpt(header[2]),
                m_s2,
            })
        }
        Declared::NotAcceleration => {
            return Err(MotionError::NotAcceleration {
                file: file(),
                line: Some(3),
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
    let dt = time_step(dt, npts, source_name, HEADER_LINE, "DT")?;

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
            let value = crate::input::number(token, source_name, line_no)?;
            found += 1;
            if found <= npts {
                samples.push(value);
            } else if surplus_line.is_none() {
                surplus_line = Some(line_no);
            }
        }
    }
    if found != npts {
        return Err(MotionError::CountMismatch {
            file: file(),
            line: surplus_line.unwrap_or(last_line),
            key: "NPTS",
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

/// The value at the start of `r` and what follows it: up to a space, or a comma that separates
/// (one not followed by a digit: `0,02` stays one token, to be refused).
fn token(r: &str) -> (&str, &str) {
    let b = r.as_bytes();
    let end = (0..b.len())
        .find(|&i| {
            b[i].is_ascii_whitespace()
                || (b[i] == b',' && !b.get(i + 1).is_some_and(u8::is_ascii_digit))
        })
        .unwrap_or(b.len());
    r.split_at(end)
}

/// Parse header line 4: `NPTS = n [,] DT = dt [unit] [anything]` (any case; the unit a time
/// such as `SEC` or `MSEC`, seconds when absent), or the older `n dt NPTS, DT`. Returns `None`
/// if it has neither form or names a unit of DT that is not a time.
fn parse_npts_dt(line: &str) -> Option<(usize, f64)> {
    let up = line.to_ascii_uppercase();
    let npts_at = up.find("NPTS")?;
    if let Some(r) = up[npts_at + 4..].trim_start().strip_prefix(['=', ':']) {
        // NPTS= 1559, DT= .02000 SEC. Each value is read whole, up to a space or a separating
        // comma: `5.7`, `5/2`, `1/50`, `2*0.01`, `1_000` or a decimal comma `0,02` are refused,
        // never read as their leading number.
        let r = r.trim_start();
        let (npts, r) = token(r);
        let npts = npts.parse::<usize>().ok()?;
        let r = &r[r.find("DT")? + 2..];
        let r = r.trim_start().strip_prefix(['=', ':'])?.trim_start();
        let (dt, rest) = token(r);
        // A unit may follow the number at once (`.02SEC`) or after a space.
        let len = dt
            .bytes()
            .take_while(|b| b.is_ascii_digit() || b"+-.ED".contains(b))
            .count();
        let glued = &dt[len..];
        if !glued.bytes().all(|b| b.is_ascii_alphabetic()) {
            return None;
        }
        let dt = parse_number(&dt[..len])?;
        let unit: String = if glued.is_empty() {
            rest.trim_start()
                .chars()
                .take_while(char::is_ascii_alphabetic)
                .collect()
        } else {
            glued.to_string()
        };
        let seconds = match unit.as_str() {
            "" => 1.0,
            u => match unit_expression(u)? {
                Quantity::Time(s) => s,
                _ => return None,
            },
        };
        Some((npts, dt * seconds))
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

    /// CRLF and lone-CR line ends read as LF ones (a lone CR was one long line, reported as
    /// "found end of file").
    #[test]
    fn every_line_end_reads_alike() {
        let lf = "title\nevent\nIN UNITS OF G\nNPTS= 3, DT= .01 SEC\n0.1 0.2\n0.3\n";
        let want = parse_at2(lf, "lf.AT2").unwrap();
        for end in ["\r\n", "\r\r\n", "\r"] {
            let text = lf.replace('\n', end);
            let got = parse_at2(&text, "x.AT2").unwrap();
            assert_eq!(
                (got.npts, got.dt, &got.samples),
                (want.npts, want.dt, &want.samples)
            );
            assert_eq!(got.units, want.units);
        }
    }

    #[test]
    fn header_spellings() {
        let cases = [
            ("NPTS=  1559, DT= .02000 SEC", (1559, 0.02)),
            ("NPTS=  12000, dt=  .00500", (12000, 0.005)),
            ("NPTS=   2364, dt=   .0100 SEC", (2364, 0.01)),
            ("NPTS=  5590, DT=   .0050 SEC,", (5590, 0.005)),
            ("NPTS=  7807  DT=  0.0050 SEC,", (7807, 0.005)),
            ("npts = 10,dt=0.01", (10, 0.01)),
            ("NPTS=10 DT=1.0D-02 SEC", (10, 0.01)),
            ("NPTS=10, DT= 20 MSEC", (10, 0.02)),
            ("NPTS=10, DT= 5 ms", (10, 0.005)),
            ("NPTS=10, DT=.005SEC", (10, 0.005)),
            ("NPTS=10, DT= .01 SECONDS FORMAT (5E15.7)", (10, 0.01)),
            ("  2000    0.0100    NPTS, DT", (2000, 0.01)),
            ("NPTS=  3, DT= -.01 SEC", (3, -0.01)),
        ];
        for (line, want) in cases {
            assert_eq!(parse_npts_dt(line), Some(want), "{line}");
        }
        for bad in [
            // A value is read whole or refused, never as its leading number (issue 47).
            "NPTS= 5.7, DT= .01 SEC",
            "NPTS= 5/2, DT= .01 SEC",
            "NPTS= 10, DT= 1/50 SEC",
            "NPTS= 10, DT= 2*0.01 SEC",
            "NPTS= 10, DT= 1_000 MSEC",
            "NPTS= 10, DT= 0,02 SEC",
            "",
            "NPTS=, DT=.01",
            "NPTS= 10",
            "NPTS=10, DT=",
            "NPTS=10, DT= SEC",
            "NPTS=10, DT= .01 HZ",
            "NPTS=10, DT= .01 CM",
            "DT=.01 NPTS=10",
            "1 2 3 NPTS DT",
            "NPTS=99999999999999999999999999, DT=.01",
            "ÄNPTS=é",
        ] {
            assert_eq!(parse_npts_dt(bad), None, "{bad}");
        }
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
