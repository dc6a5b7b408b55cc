//! The crate's error type.

use std::fmt;
use std::path::PathBuf;

/// Longest excerpt of offending input quoted in an error message.
const MAX_QUOTE: usize = 60;

/// Quote at most [`MAX_QUOTE`] characters of `s` for an error message.
pub(crate) fn excerpt(s: &str) -> String {
    let s = s.trim_end();
    if s.chars().count() <= MAX_QUOTE {
        s.to_owned()
    } else {
        let mut out: String = s.chars().take(MAX_QUOTE).collect();
        out.push('…');
        out
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
    /// The input is not valid UTF-8.
    NotUtf8 {
        /// Name of the input.
        file: String,
        /// Line containing the first invalid byte.
        line: usize,
    },
    /// The input is empty (no header at all).
    Empty {
        /// Name of the input.
        file: String,
    },
    /// The input ended inside the 4-line header.
    TruncatedHeader {
        /// Name of the input.
        file: String,
        /// The missing header line (1-based).
        line: usize,
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
    /// `DT` in the header is not strictly positive and finite.
    InvalidDt {
        /// Name of the input.
        file: String,
        /// Line number of the header line.
        line: usize,
        /// The value read.
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
    /// The number of samples differs from the declared `NPTS`.
    CountMismatch {
        /// Name of the input.
        file: String,
        /// Where the mismatch shows: the line of the first surplus sample,
        /// or the last line of the file when samples are missing.
        line: usize,
        /// `NPTS` from the header.
        declared: usize,
        /// Number of samples actually present.
        found: usize,
    },
    /// Header line 3 names a unit this reader does not know.
    UnknownUnits {
        /// Name of the input.
        file: String,
        /// Line number (3).
        line: usize,
        /// The offending line (possibly shortened).
        found: String,
    },
    /// A velocity or displacement history, not an acceleration.
    NotAcceleration {
        /// Name of the input (with the line, when the header says so).
        file: String,
        /// What gave it away.
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
    /// Parameters of a programmatically built motion are invalid
    /// (e.g. a [`Record`](crate::Record) with `dt <= 0` or no samples).
    InvalidParameter(String),
}

impl MotionError {
    /// The 1-based line number the error refers to, if any.
    pub fn line(&self) -> Option<usize> {
        match self {
            MotionError::Io { .. }
            | MotionError::InvalidParameter(_)
            | MotionError::NotAcceleration { .. }
            | MotionError::UnitMismatch { .. } => None,
            MotionError::UnknownUnits { line, .. } => Some(*line),
            MotionError::Empty { .. } => Some(1),
            MotionError::NotUtf8 { line, .. }
            | MotionError::TruncatedHeader { line, .. }
            | MotionError::BadHeader { line, .. }
            | MotionError::InvalidNpts { line, .. }
            | MotionError::InvalidDt { line, .. }
            | MotionError::BadToken { line, .. }
            | MotionError::NonFiniteSample { line, .. }
            | MotionError::Malformed { line, .. }
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
            MotionError::NotUtf8 { file, line } => write!(
                f,
                "{file}:{line}: expected UTF-8/ASCII text, found invalid byte sequence"
            ),
            MotionError::Empty { file } => write!(
                f,
                "{file}:1: expected a PEER AT2 header (4 lines), found an empty file"
            ),
            MotionError::TruncatedHeader {
                file,
                line,
                expected,
            } => write!(
                f,
                "{file}:{line}: expected {expected} (header line {line} of 4), found end of file"
            ),
            MotionError::BadHeader { file, line, found } => write!(
                f,
                "{file}:{line}: expected \"NPTS=<n>, DT=<dt>\" in the header, found \"{found}\""
            ),
            MotionError::InvalidNpts { file, line, npts } => {
                write!(f, "{file}:{line}: expected NPTS >= 1, found NPTS = {npts}")
            }
            MotionError::InvalidDt { file, line, dt } => write!(
                f,
                "{file}:{line}: expected DT > 0 and finite, found DT = {dt}"
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
                declared,
                found,
            } => write!(
                f,
                "{file}:{line}: expected {declared} samples (NPTS in the header), found {found}"
            ),
            MotionError::UnknownUnits { file, line, found } => write!(
                f,
                "{file}:{line}: expected the units of g, cm/s2 (CM/SEC/SEC) or m/s2 (M/S/S), \
                 found \"{found}\""
            ),
            MotionError::NotAcceleration { file, found } => write!(
                f,
                "{file}: expected an acceleration history, found {found}; only PEER \
                 acceleration files (.AT2) can be used"
            ),
            MotionError::UnitMismatch {
                file,
                declared,
                stated,
            } => write!(
                f,
                "{file}: the header declares the units {declared}, but the scene states \
                 `units` = \"{stated}\"; remove `units` or make it agree"
            ),
            MotionError::Malformed {
                file,
                line,
                expected,
                found,
            } => write!(f, "{file}:{line}: expected {expected}, found {found}"),
            MotionError::InvalidParameter(msg) => write!(f, "invalid parameter: {msg}"),
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
