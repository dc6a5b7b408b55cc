//! K-NET and KiK-net ASCII (NIED): a fixed 17-line header, then the samples in counts with
//! their scale factor.

use super::{check_stated_peak, malformed, not_blank, record, stated_unit};
use crate::input::{number, time_step};
use crate::{AccelUnit, At2Record, MotionError};

/// The 17 header lines of a K-NET/KiK-net ASCII file, by label (columns 1-18).
const KNET_LABELS: [&str; 17] = [
    "Origin Time",
    "Lat.",
    "Long.",
    "Depth. (km)",
    "Mag.",
    "Station Code",
    "Station Lat.",
    "Station Long.",
    "Station Height(m)",
    "Record Time",
    "Sampling Freq(Hz)",
    "Duration Time(s)",
    "Dir.",
    "Scale Factor",
    "Max. Acc. (gal)",
    "Last Correction",
    "Memo.",
];

/// What each K-NET header line holds, for a file that ends inside the header.
const KNET_EXPECTED: [&str; 17] = [
    "the K-NET header line \"Origin Time …\"",
    "the K-NET header line \"Lat. …\"",
    "the K-NET header line \"Long. …\"",
    "the K-NET header line \"Depth. (km) …\"",
    "the K-NET header line \"Mag. …\"",
    "the K-NET header line \"Station Code …\"",
    "the K-NET header line \"Station Lat. …\"",
    "the K-NET header line \"Station Long. …\"",
    "the K-NET header line \"Station Height(m) …\"",
    "the K-NET header line \"Record Time …\"",
    "the K-NET header line \"Sampling Freq(Hz) …\"",
    "the K-NET header line \"Duration Time(s) …\"",
    "the K-NET header line \"Dir. …\"",
    "the K-NET header line \"Scale Factor …\"",
    "the K-NET header line \"Max. Acc. (gal) …\"",
    "the K-NET header line \"Last Correction …\"",
    "the K-NET header line \"Memo. …\"",
];

/// K-NET / KiK-net ASCII: 17 header lines (label in columns 1-18, value after), then integer
/// counts, 8 per line. Acceleration = counts × `Scale Factor` (`3920(gal)/6182761`: the
/// numerator is in the bracket's unit, `gal`, `cm/s2`, `cm/s^2`, `cm/s/s`, `m/s2`; a velocity or
/// displacement unit is refused) with the record's mean removed; dt = 1 / `Sampling Freq(Hz)`
/// (`100Hz`, `50 Hz`).
///
/// `Max. Acc. (gal)` (also spelled `Max Acc. (gal)`) is the peak |a| in gal of the record with
/// its mean removed, as NIED describes it ("this value is subtracted the average of whole data
/// from original value") and as the NIED files checked satisfy (54 K-NET/KiK-net files, all
/// within the last printed digit; the peak of the raw counts misses every one of them, by 0.93x
/// to 665x, the offset being most of a KiK-net borehole record). The samples must peak there (see [`PEAK_TOL`](super::PEAK_TOL)) or
/// the file is refused ([`MotionError::PeakMismatch`]); a blank value is not checked.
pub fn parse_knet(text: &str, file: &str) -> Result<At2Record, MotionError> {
    not_blank(text, file, "a K-NET header (17 lines)")?;
    let lines: Vec<&str> = text.lines().collect();
    let header = KNET_LABELS.len();
    if lines.len() < header {
        return Err(MotionError::TruncatedHeader {
            file: file.to_owned(),
            line: lines.len() + 1,
            total: header,
            expected: KNET_EXPECTED[lines.len()],
        });
    }
    let field = |label: &str| -> Result<(&str, usize), MotionError> {
        lines[..header]
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
                    &format!("a header line \"{label} ...\" among the first {header}"),
                    "none",
                )
            })
    };
    let (freq, freq_line) = field("Sampling Freq(Hz)")?;
    let hz = freq
        .strip_suffix("Hz")
        .or_else(|| freq.strip_suffix("HZ"))
        .or_else(|| freq.strip_suffix("hz"))
        .unwrap_or(freq)
        .trim();
    let hz = number(hz, file, freq_line)?;
    let (scale, scale_line) = field("Scale Factor")?;
    let bad_scale = || malformed(file, scale_line, "\"Scale Factor <a>(gal)/<b>\"", scale);
    // <a>(<unit>)/<b>: the unit may hold a `/` itself (`cm/s2`), so the bracket is found first
    // and the fraction's bar after it.
    let open = scale.find('(').ok_or_else(bad_scale)?;
    let close = open + scale[open..].find(')').ok_or_else(bad_scale)?;
    let den = scale[close + 1..]
        .trim_start()
        .strip_prefix('/')
        .ok_or_else(bad_scale)?;
    let unit = stated_unit(
        &format!("UNITS: {}", &scale[open + 1..close]),
        file,
        scale_line,
        lines[scale_line - 1],
    )?;
    let factor =
        number(scale[..open].trim(), file, scale_line)? / number(den.trim(), file, scale_line)?;
    if !(factor.is_finite() && factor != 0.0) {
        return Err(bad_scale());
    }
    let mut samples = Vec::new();
    for (i, line) in lines.iter().enumerate().skip(header) {
        for token in line.split_whitespace() {
            samples.push(number(token, file, i + 1)? * factor);
        }
    }
    if samples.is_empty() {
        return Err(malformed(file, header + 1, "samples", "none"));
    }
    let dt = time_step(
        1.0 / hz,
        samples.len(),
        file,
        freq_line,
        "1/Sampling Freq(Hz)",
    )?;
    let mean = samples.iter().sum::<f64>() / samples.len() as f64;
    samples.iter_mut().for_each(|a| *a -= mean);
    let max_acc = lines[..header].iter().enumerate().find_map(|(i, l)| {
        let l = l.trim_start();
        ["Max. Acc. (gal)", "Max Acc. (gal)"]
            .iter()
            .find_map(|label| l.strip_prefix(label).map(|v| (*label, v, i + 1)))
    });
    if let Some((label, value, line)) = max_acc {
        check_stated_peak(file, line, label, value, AccelUnit::CmPerS2, &samples, unit)?;
    }
    let text_of = |label| field(label).map(|(s, _)| s.to_owned()).unwrap_or_default();
    let event = format!("{} {}", text_of("Origin Time"), text_of("Dir."));
    let mut r = record(file, &text_of("Station Code"), event.trim(), dt, samples);
    r.units = lines[scale_line - 1].trim().to_owned();
    r.declared_unit = Some(unit);
    Ok(r)
}
