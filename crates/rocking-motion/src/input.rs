//! What every record reader shares: the file's text, its numbers and the range of a time step.

use std::borrow::Cow;
use std::path::Path;

use crate::error::excerpt;
use crate::MotionError;

/// The shortest time step a reader accepts, s: a sampling rate of 1 MHz, far above any
/// accelerogram's. Below it a record's slopes (Δa/dt) overflow the Taylor series of the
/// excitation (the `accurate` preset failed at dt = 1e-250 s where the others ran).
pub const MIN_DT: f64 = 1e-6;

/// The bytes of a record file, or the error naming it.
pub(crate) fn read_bytes(path: &Path) -> Result<Vec<u8>, MotionError> {
    std::fs::read(path).map_err(|source| MotionError::Io {
        path: path.to_path_buf(),
        source,
    })
}

/// The text of a record file: UTF-8 (a byte-order mark dropped), else Latin-1 byte for byte, as
/// older files write station names (`Düzce`); samples are ASCII in both. A NUL byte (a binary
/// file) or UTF-16 is not a record's text.
pub(crate) fn decode<'a>(bytes: &'a [u8], file: &str) -> Result<Cow<'a, str>, MotionError> {
    let not_text = |i: usize, found| MotionError::NotText {
        file: file.to_owned(),
        line: 1 + bytes[..i].iter().filter(|&&b| b == b'\n').count(),
        found,
    };
    if bytes.starts_with(&[0xff, 0xfe]) || bytes.starts_with(&[0xfe, 0xff]) {
        return Err(not_text(
            0,
            "UTF-16 text (a byte-order mark); save it as UTF-8 or ASCII",
        ));
    }
    if let Some(i) = bytes.iter().position(|&b| b == 0) {
        return Err(not_text(i, "a NUL byte (a binary file)"));
    }
    let text = match std::str::from_utf8(bytes) {
        Ok(t) => Cow::Borrowed(t.strip_prefix('\u{feff}').unwrap_or(t)),
        Err(_) => Cow::Owned(bytes.iter().map(|&b| char::from(b)).collect()),
    };
    // Every line end as LF: CRs before an LF (CRLF, and the CR CR LF of many PEER files) are
    // one line end, a CR alone (classic Mac OS) is one too, where `str::lines` would leave it
    // inside one long line.
    Ok(if text.contains('\r') {
        Cow::Owned(unix_line_ends(&text))
    } else {
        text
    })
}

fn unix_line_ends(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut crs = 0;
    for c in text.chars() {
        match c {
            '\r' => crs += 1,
            '\n' => {
                out.push('\n');
                crs = 0;
            }
            c => {
                out.extend(std::iter::repeat_n('\n', crs));
                crs = 0;
                out.push(c);
            }
        }
    }
    out.extend(std::iter::repeat_n('\n', crs));
    out
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

/// A finite number, or the error naming the token.
pub(crate) fn number(token: &str, file: &str, line: usize) -> Result<f64, MotionError> {
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

/// The time step `dt` (s) of a record of `n` samples, given by `key` on `line`: at least
/// [`MIN_DT`], and a finite duration (n − 1)·dt.
pub(crate) fn time_step(
    dt: f64,
    n: usize,
    file: &str,
    line: usize,
    key: &'static str,
) -> Result<f64, MotionError> {
    if dt >= MIN_DT && (n.saturating_sub(1) as f64 * dt).is_finite() && dt.is_finite() {
        Ok(dt)
    } else {
        Err(MotionError::InvalidDt {
            file: file.to_owned(),
            line,
            key,
            dt,
        })
    }
}
