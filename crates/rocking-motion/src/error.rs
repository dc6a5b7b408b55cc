//! The crate's error type.

use std::fmt;
use std::path::PathBuf;

/// Longest excerpt of offending input quoted in an error message.
const MAX_QUOTE: usize = 60;

/// Quote at most [`MAX_QUOTE`] characters of `s` for an error message, control characters
/// escaped (a message stays one line whatever the bytes).
pub(crate) fn excerpt(s: &str) -> String {
    let s = s.trim_end();
    let mut out = String::new();
    for (k, c) in s.chars().enumerate() {
        if k == MAX_QUOTE {
            out.push('…');
            break;
        }
        if c.is_control() {
            out.extend(c.escape_default());
        } else {
            out.push(c);
        }
    }
    out
}

/// A number for a message: as written for ordinary magnitudes, in exponent form (`1e-250`, not
/// 250 digits) for very large or very small ones.
pub fn short_number(x: f64) -> String {
    let a = x.abs();
    if x == 0.0 || !x.is_finite() || (1e-4..1e9).contains(&a) {
        format!("{x}")
    } else {
        format!("{x:e}")
    }
}

/// Everything that can go wrong when reading or building a ground motion.
///
/// Parse errors carry the name of the file (`file`) and the 1-based line
/// number (`line`); their [`Display`](fmt::Display) form is
/// `FILE:LINE: expected …, found …`, like a compiler diagnostic.
#[derive(Debug)]
#[non_exhaustive]
pub enum MotionError {
    /// The file could not be read.
    Io {
        /// Path of the file.
        path: PathBuf,
        /// Underlying I/O error.
        source: std::io::Error,
    },
    /// The input is not text (a NUL byte, or UTF-16).
    NotText {
        /// Name of the input.
        file: String,
        /// Line of the first offending byte.
        line: usize,
        /// What it is instead.
        found: &'static str,
    },
    /// The input is empty (no header at all).
    Empty {
        /// Name of the input.
        file: String,
        /// What the format starts with.
        expected: &'static str,
    },
    /// The input ended inside a header of a fixed number of lines.
    TruncatedHeader {
        /// Name of the input.
        file: String,
        /// The missing header line (1-based).
        line: usize,
        /// The number of header lines of the format.
        total: usize,
        /// What that line should have contained.
        expected: &'static str,
    },
    /// Header line 4 does not have the form `NPTS=<n>, DT=<dt>`.
    BadHeader {
        /// Name of the input.
        file: String,
        /// Line number (4).
        line: usize,
        /// The offending line (possibly shortened).
        found: String,
    },
    /// `NPTS` in the header is zero.
    InvalidNpts {
        /// Name of the input.
        file: String,
        /// Line number of the header line.
        line: usize,
        /// The value read.
        npts: usize,
    },
    /// The time step is outside [`MIN_DT`](crate::MIN_DT) … ∞, or the record's duration
    /// overflows.
    InvalidDt {
        /// Name of the input.
        file: String,
        /// Line number of the header line.
        line: usize,
        /// The header key or field that gives it (`DT`, `SAMPLING_INTERVAL_S`, ...).
        key: &'static str,
        /// The time step read (s).
        dt: f64,
    },
    /// A data token is not a number.
    BadToken {
        /// Name of the input.
        file: String,
        /// Line of the token.
        line: usize,
        /// The token (possibly shortened).
        token: String,
    },
    /// A data token parsed to NaN or ±∞.
    NonFiniteSample {
        /// Name of the input.
        file: String,
        /// Line of the token.
        line: usize,
        /// The token (possibly shortened).
        token: String,
    },
    /// The number of samples differs from the declared count.
    CountMismatch {
        /// Name of the input.
        file: String,
        /// Where the mismatch shows: the line of the first surplus sample,
        /// or the last line of the file when samples are missing.
        line: usize,
        /// The header key of the count (`NPTS`, `NDATA`).
        key: &'static str,
        /// The count in the header.
        declared: usize,
        /// Number of samples actually present.
        found: usize,
    },
    /// A header names a unit this reader does not convert.
    UnknownUnits {
        /// Name of the input.
        file: String,
        /// Line number of the header line.
        line: usize,
        /// The offending line (possibly shortened).
        found: String,
        /// The unit in m/s², when it is an acceleration unit the readers do not take.
        m_s2: Option<f64>,
    },
    /// A velocity or displacement history, or a response spectrum: not an acceleration history.
    NotAcceleration {
        /// Name of the input.
        file: String,
        /// The header line that says so, if a line does.
        line: Option<usize>,
        /// What it is.
        found: String,
    },
    /// The user states a unit for a record whose header declares another.
    UnitMismatch {
        /// Name of the input.
        file: String,
        /// The unit in the header.
        declared: &'static str,
        /// The unit the user stated.
        stated: &'static str,
    },
    /// The header states the record's peak acceleration (ESM `PGA_CM/S^2`, K-NET `Max. Acc.
    /// (gal)`) and the samples, as read, peak elsewhere: a unit or scale factor not applied.
    PeakMismatch {
        /// Name of the input.
        file: String,
        /// Line of the header field.
        line: usize,
        /// The field as the header names it (`PGA_CM/S^2`, `Max. Acc. (gal)`).
        key: String,
        /// The stated peak as written, in the field's unit (and in the samples' unit when
        /// that differs).
        stated: String,
        /// The samples' peak with their unit.
        found: String,
    },
    /// A text, ESM or K-NET file does not have the layout of its format.
    Malformed {
        /// Name of the input.
        file: String,
        /// Line (1-based).
        line: usize,
        /// What the format needs there.
        expected: String,
        /// What was found (possibly shortened).
        found: String,
    },
    /// Parameters of a programmatically built motion, a record's stated time step or an
    /// intensity measure's arguments are invalid (e.g. a [`Record`](crate::Record) with
    /// `dt <= 0` or no samples).
    InvalidParameter(ParameterError),
}

/// An invalid parameter: what was wrong, with the value given and what is allowed.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum ParameterError {
    /// [`Record::new`](crate::Record::new): `dt` not positive and finite.
    RecordDt {
        /// The time step given (s).
        dt: f64,
    },
    /// [`Record::new`](crate::Record::new): no samples.
    RecordEmpty,
    /// [`Record::new`](crate::Record::new): the duration (n − 1)·dt overflows.
    RecordDuration {
        /// The number of samples.
        samples: usize,
        /// The time step (s).
        dt: f64,
    },
    /// [`Record::new`](crate::Record::new): a sample is not finite.
    RecordSample {
        /// Its index.
        index: usize,
        /// Its value.
        value: f64,
    },
    /// A one-column text record without a stated time step.
    TextNeedsDt {
        /// Name of the input.
        file: String,
    },
    /// The stated time step contradicts a text file's time column.
    DtContradicts {
        /// Name of the input.
        file: String,
        /// The stated `dt` (s).
        stated: f64,
        /// The time column's mean step (s).
        dt: f64,
    },
    /// A time step stated for a format that states its own.
    DtNotTaken {
        /// Name of the input.
        file: String,
        /// The format (`at2`, `esm`, `knet`).
        format: &'static str,
    },
    /// An argument of an intensity measure outside its range.
    OutOfRange {
        /// The function (`spectral_response`, `pga_over_uplift`, ...).
        function: &'static str,
        /// The argument.
        parameter: &'static str,
        /// The value given.
        value: f64,
        /// What is allowed, with the argument's name (`period > 0 and finite (s)`).
        allowed: &'static str,
    },
    /// [`significant_duration`](crate::intensity::significant_duration): not
    /// 0 ≤ from < to ≤ 1.
    DurationFractions {
        /// The lower fraction given.
        from: f64,
        /// The upper fraction given.
        to: f64,
    },
    /// [`significant_duration`](crate::intensity::significant_duration) of a record with zero
    /// Arias intensity.
    NoMotion,
    /// [`mean_period`](crate::intensity::mean_period): no Fourier amplitude in the band.
    NoFourierAmplitude {
        /// The band's lower frequency (Hz).
        lo_hz: f64,
        /// The band's upper frequency (Hz).
        hi_hz: f64,
        /// The number of samples.
        samples: usize,
        /// The time step (s).
        dt: f64,
    },
}

impl fmt::Display for ParameterError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ParameterError::RecordDt { dt } => {
                write!(f, "Record: expected dt > 0 and finite, found {dt}")
            }
            ParameterError::RecordEmpty => {
                f.write_str("Record: expected at least one sample, found none")
            }
            ParameterError::RecordDuration { samples, dt } => write!(
                f,
                "Record: expected a finite duration (n - 1) dt, found {samples} samples of \
                 dt = {dt}"
            ),
            ParameterError::RecordSample { index, value } => write!(
                f,
                "Record: expected finite samples, found {value} at index {index}"
            ),
            ParameterError::TextNeedsDt { file } => write!(
                f,
                "{file}: a one-column text record needs its time step: give `dt` (s) in \
                 [excitation]"
            ),
            ParameterError::DtContradicts { file, stated, dt } => write!(
                f,
                "{file}: the stated `dt` = {stated} s contradicts the file's time column \
                 (dt = {dt} s)"
            ),
            ParameterError::DtNotTaken { file, format } => write!(
                f,
                "{file}: a {format} file states its own time step; `dt` is for one-column text \
                 files"
            ),
            ParameterError::OutOfRange {
                function,
                parameter,
                value,
                allowed,
            } => write!(
                f,
                "{function}: expected {allowed}, found {parameter} = {value}"
            ),
            ParameterError::DurationFractions { from, to } => write!(
                f,
                "significant_duration: expected 0 <= from < to <= 1, found from = {from}, \
                 to = {to}"
            ),
            ParameterError::NoMotion => {
                f.write_str("significant_duration: record has zero Arias intensity (no motion)")
            }
            ParameterError::NoFourierAmplitude {
                lo_hz,
                hi_hz,
                samples,
                dt,
            } => write!(
                f,
                "mean_period: record has no Fourier amplitude in {lo_hz}-{hi_hz} Hz \
                 (n = {samples}, dt = {dt} s)"
            ),
        }
    }
}

impl std::error::Error for ParameterError {}

impl From<ParameterError> for MotionError {
    fn from(e: ParameterError) -> Self {
        MotionError::InvalidParameter(e)
    }
}

impl MotionError {
    /// The 1-based line number the error refers to, if any.
    pub fn line(&self) -> Option<usize> {
        match self {
            MotionError::Io { .. }
            | MotionError::InvalidParameter(_)
            | MotionError::UnitMismatch { .. } => None,
            MotionError::NotAcceleration { line, .. } => *line,
            MotionError::Empty { .. } => Some(1),
            MotionError::NotText { line, .. }
            | MotionError::TruncatedHeader { line, .. }
            | MotionError::BadHeader { line, .. }
            | MotionError::InvalidNpts { line, .. }
            | MotionError::InvalidDt { line, .. }
            | MotionError::BadToken { line, .. }
            | MotionError::NonFiniteSample { line, .. }
            | MotionError::Malformed { line, .. }
            | MotionError::UnknownUnits { line, .. }
            | MotionError::PeakMismatch { line, .. }
            | MotionError::CountMismatch { line, .. } => Some(*line),
        }
    }
}

impl fmt::Display for MotionError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            MotionError::Io { path, source } => {
                write!(f, "{}: cannot read file: {source}", path.display())
            }
            MotionError::NotText { file, line, found } => write!(
                f,
                "{file}:{line}: expected text (ASCII, UTF-8 or Latin-1), found {found}"
            ),
            MotionError::Empty { file, expected } => {
                write!(f, "{file}:1: expected {expected}, found an empty file")
            }
            MotionError::TruncatedHeader {
                file,
                line,
                total,
                expected,
            } => write!(
                f,
                "{file}:{line}: expected {expected} (header line {line} of {total}), found end \
                 of file"
            ),
            MotionError::BadHeader { file, line, found } => write!(
                f,
                "{file}:{line}: expected \"NPTS=<n>, DT=<dt> [SEC|MSEC]\" in the header, found \
                 \"{found}\""
            ),
            MotionError::InvalidNpts { file, line, npts } => {
                write!(f, "{file}:{line}: expected NPTS >= 1, found NPTS = {npts}")
            }
            MotionError::InvalidDt {
                file,
                line,
                key,
                dt,
            } => write!(
                f,
                "{file}:{line}: expected a time step {key} >= {} s (sampled at 1 MHz at most) \
                 with a finite duration, found {key} = {} s",
                short_number(crate::MIN_DT),
                short_number(*dt)
            ),
            MotionError::BadToken { file, line, token } => {
                write!(f, "{file}:{line}: expected a number, found \"{token}\"")
            }
            MotionError::NonFiniteSample { file, line, token } => write!(
                f,
                "{file}:{line}: expected a finite sample, found \"{token}\""
            ),
            MotionError::CountMismatch {
                file,
                line,
                key,
                declared,
                found,
            } => write!(
                f,
                "{file}:{line}: expected {declared} samples ({key} in the header), found {found}"
            ),
            MotionError::UnknownUnits {
                file,
                line,
                found,
                m_s2,
            } => {
                write!(
                    f,
                    "{file}:{line}: expected the units of g, cm/s2 (CM/SEC/SEC) or m/s2 \
                     (M/S/S), found \"{found}\""
                )?;
                match m_s2 {
                    Some(v) => write!(
                        f,
                        ", an acceleration of {} m/s2 per unit that the readers do not convert",
                        short_number(*v)
                    ),
                    None => Ok(()),
                }
            }
            MotionError::NotAcceleration { file, line, found } => {
                write!(f, "{file}")?;
                if let Some(l) = line {
                    write!(f, ":{l}")?;
                }
                write!(f, ": expected an acceleration history, found {found}")
            }
            MotionError::UnitMismatch {
                file,
                declared,
                stated,
            } => write!(
                f,
                "{file}: the header declares the units {declared}, but the scene states \
                 `units` = \"{stated}\"; remove `units` or make it agree"
            ),
            MotionError::PeakMismatch {
                file,
                line,
                key,
                stated,
                found,
            } => write!(
                f,
                "{file}:{line}: the header states {key} = {stated} but the samples peak at \
                 {found} (a unit or scale the reader did not apply?)"
            ),
            MotionError::Malformed {
                file,
                line,
                expected,
                found,
            } => write!(f, "{file}:{line}: expected {expected}, found {found}"),
            MotionError::InvalidParameter(e) => write!(f, "invalid parameter: {e}"),
        }
    }
}

impl std::error::Error for MotionError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            MotionError::Io { source, .. } => Some(source),
            _ => None,
        }
    }
}
