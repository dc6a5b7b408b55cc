//! The journal of a sweep: one checksummed line per finished cell, so an interrupted sweep
//! resumes where it stopped.

use crate::{Cell, CellClass};

/// The 64-bit FNV-1a hash of `bytes` (the `fnv` crate's), to fingerprint sweeps and check journal
/// lines.
pub fn fnv1a(bytes: &[u8]) -> u64 {
    use std::hash::Hasher as _;
    let mut h = fnv::FnvHasher::default();
    h.write(bytes);
    h.finish()
}

pub(crate) const JOURNAL: &str = "cells.journal";

/// A reported quantity without a value in a journal line (an empty field would read as no
/// quantities at all).
const NO_VALUE: &str = "none";

/// A journal line: the cell, for a failed cell its error message (so that a resumed sweep still
/// reports it), and a checksum that rejects a torn line.
pub(crate) fn journal_line(c: &Cell, message: Option<&str>) -> String {
    let reported: Vec<String> = c
        .reported
        .iter()
        .map(|v| v.map_or_else(|| NO_VALUE.to_string(), |v| format!("{v:e}")))
        .collect();
    let mut body = format!(
        "{},{},{:e},{},{}",
        c.index,
        c.class.as_str(),
        c.max_theta_over_alpha,
        c.impacts,
        reported.join(";")
    );
    if let Some(m) = message {
        body.push(',');
        body.push_str(&m.replace(['\n', '\r'], " "));
    }
    format!("{body},{:016x}\n", fnv1a(body.as_bytes()))
}

pub(crate) fn parse_journal_line(line: &str) -> Option<(Cell, Option<String>)> {
    let (body, sum) = line.rsplit_once(',')?;
    if format!("{:016x}", fnv1a(body.as_bytes())) != sum {
        return None;
    }
    let f: Vec<&str> = body.splitn(6, ',').collect();
    if f.len() < 5 {
        return None;
    }
    let reported = if f[4].is_empty() {
        Vec::new()
    } else {
        f[4].split(';')
            .map(|v| match v {
                NO_VALUE => Some(None),
                v => v.parse().ok().map(Some),
            })
            .collect::<Option<Vec<Option<f64>>>>()?
    };
    let cell = Cell {
        index: f[0].parse().ok()?,
        class: CellClass::parse(f[1])?,
        max_theta_over_alpha: f[2].parse().ok()?,
        impacts: f[3].parse().ok()?,
        reported,
    };
    Some((cell, f.get(5).map(|m| m.to_string())))
}
