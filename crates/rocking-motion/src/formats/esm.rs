//! ESM ASCII (the Engineering Strong-Motion database): a header of `KEY: value` lines, then
//! the samples.

use super::{check_stated_peak, malformed, not_blank, record, stated_unit};
use crate::error::excerpt;
use crate::input::{number, time_step};
use crate::{AccelUnit, At2Record, MotionError};

/// An ESM header line `KEY: value`: a key of one word that starts with a letter (`VS30_M/S`,
/// `PGA_CM/S^2`, `LATE/NORMAL_TRIGGERED`), the value after the first colon.
fn esm_field(line: &str) -> Option<(&str, &str)> {
    let (key, value) = line.split_once(':')?;
    let key = key.trim();
    (key.starts_with(|c: char| c.is_ascii_alphabetic()) && !key.contains(char::is_whitespace))
        .then(|| (key, value.trim()))
}

/// What an ESM `DATA_TYPE` that is not `ACCELERATION` holds.
fn esm_data_type(value: &str) -> &'static str {
    let up = value.to_ascii_uppercase();
    if up.contains("SPECTRUM") {
        "a response spectrum, not a time history"
    } else if up.contains("VELOCITY") {
        "a velocity history"
    } else if up.contains("DISPLACEMENT") {
        "a displacement history"
    } else {
        "another quantity"
    }
}

/// ESM ASCII (the database's converted and processed files, `*.ASC`, DYNA 1.2 header): header
/// lines `KEY: value` until the samples, one per line. `DATA_TYPE` must be `ACCELERATION` (a
/// velocity, displacement or response-spectrum file is refused as such), `UNITS` gives the unit
/// (cm/s^2 in the database), `SAMPLING_INTERVAL_S` the time step and `NDATA` the count.
///
/// A `PGA_<unit>` field (`PGA_CM/S^2: 153.189930`, the signed sample of largest |a|) is the
/// record's peak: the samples must peak there (see [`PEAK_TOL`](super::PEAK_TOL)) or the file is refused
/// ([`MotionError::PeakMismatch`]); a blank one, or one in a unit the readers do not know, is not
/// checked.
pub fn parse_esm(text: &str, file: &str) -> Result<At2Record, MotionError> {
    not_blank(text, file, "an ESM header (KEY: value lines)")?;
    // The header: `KEY: value` lines up to the first other non-blank line.
    let lines: Vec<(usize, &str)> = text
        .lines()
        .enumerate()
        .map(|(i, l)| (i + 1, l))
        .filter(|(_, l)| !l.trim().is_empty())
        .collect();
    let fields: Vec<(&str, &str, usize, &str)> = lines
        .iter()
        .map_while(|&(n, raw)| esm_field(raw.trim()).map(|(k, v)| (k, v, n, raw)))
        .collect();
    let header_end = fields.last().map_or(0, |f| f.2);
    let field = |key: &str| fields.iter().find(|f| f.0 == key).copied();
    let need = |key: &str, form: &str| {
        field(key).ok_or_else(|| {
            malformed(
                file,
                header_end.max(1),
                &format!("a header line \"{key}: {form}\" (the ESM header)"),
                "none",
            )
        })
    };
    let (_, kind, line, raw) = need("DATA_TYPE", "ACCELERATION")?;
    if !kind.eq_ignore_ascii_case("ACCELERATION") {
        return Err(MotionError::NotAcceleration {
            file: file.to_owned(),
            line: Some(line),
            found: format!("{} (\"{}\")", esm_data_type(kind), excerpt(raw)),
        });
    }
    let (_, units, line, raw) = need("UNITS", "cm/s^2")?;
    let unit = stated_unit(&format!("UNITS: {units}"), file, line, raw)?;
    let (_, count, ndata_line, raw) = need("NDATA", "<count>")?;
    let ndata = count
        .parse::<usize>()
        .ok()
        .filter(|&n| n >= 1)
        .ok_or_else(|| {
            malformed(
                file,
                ndata_line,
                "\"NDATA: <count >= 1>\"",
                &format!("\"{}\"", excerpt(raw)),
            )
        })?;
    let (_, interval, line, _) = need("SAMPLING_INTERVAL_S", "<seconds>")?;
    let dt = time_step(
        number(interval, file, line)?,
        ndata,
        file,
        line,
        "SAMPLING_INTERVAL_S",
    )?;
    let mut samples = Vec::with_capacity(ndata.min(text.len() / 2 + 1));
    for &(line_no, raw) in &lines[fields.len()..] {
        let mut tokens = raw.split_whitespace();
        let value = number(tokens.next().unwrap_or(""), file, line_no)?;
        if tokens.next().is_some() {
            return Err(malformed(
                file,
                line_no,
                "one sample per line (an ESM time history)",
                &format!("\"{}\"", excerpt(raw)),
            ));
        }
        samples.push(value);
    }
    if ndata != samples.len() {
        return Err(MotionError::CountMismatch {
            file: file.to_owned(),
            line: ndata_line,
            key: "NDATA",
            declared: ndata,
            found: samples.len(),
        });
    }
    for &(key, value, line, _) in &fields {
        let stated_unit = key.strip_prefix("PGA_").and_then(AccelUnit::parse);
        if let Some(stated_unit) = stated_unit {
            check_stated_peak(file, line, key, value, stated_unit, &samples, unit)?;
        }
    }
    let value = |key: &str| field(key).map_or("", |f| f.1);
    let title = [value("EVENT_NAME"), value("EVENT_ID")]
        .into_iter()
        .find(|s| !s.is_empty())
        .unwrap_or("");
    let event = format!(
        "{}.{} {}",
        value("NETWORK"),
        value("STATION_CODE"),
        value("STREAM")
    );
    let mut r = record(file, title, event.trim(), dt, samples);
    r.units = format!("UNITS: {units}");
    r.declared_unit = Some(unit);
    Ok(r)
}
