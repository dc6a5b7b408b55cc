//! Plain text: one acceleration per line with the time step given, or time and acceleration.

use super::{malformed, not_blank, record};
use crate::error::excerpt;
use crate::input::{number, time_step};
use crate::{At2Record, MotionError, ParameterError};

/// Relative tolerance on the spacing of the times of a two-column text file.
const SPACING_TOL: f64 = 1e-6;

/// Plain text: one column with `dt` stated, or two columns time, acceleration (spaces, tabs or
/// commas; `#` comments and blank lines skipped). The unit is not stated.
pub fn parse_text(text: &str, file: &str, dt: Option<f64>) -> Result<At2Record, MotionError> {
    not_blank(text, file, "samples (one or two columns)")?;
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
    let n = samples.len();
    let dt = match (columns, dt) {
        (None, _) => return Err(malformed(file, 1, "samples", "only comments")),
        (Some(1), None) => {
            return Err(ParameterError::TextNeedsDt {
                file: file.to_string(),
            }
            .into())
        }
        (Some(1), Some(dt)) => time_step(dt, n, file, first_line, "dt")?,
        (Some(_), stated) => {
            if times.len() < 2 {
                return Err(malformed(file, first_line, "at least two rows", "one"));
            }
            let step = times[1].0 - times[0].0;
            let step = time_step(step, n, file, times[1].1, "t1 - t0")?;
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
                    return Err(ParameterError::DtContradicts {
                        file: file.to_string(),
                        stated: s,
                        dt,
                    }
                    .into());
                }
            }
            time_step(dt, n, file, times[1].1, "t1 - t0")?
        }
    };
    Ok(record(file, "", "", dt, samples))
}
