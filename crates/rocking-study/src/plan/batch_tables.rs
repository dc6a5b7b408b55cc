//! A record batch's tables, built once from its outcome: runs.csv (per run its record, scale,
//! cell of the batch's own axes, class, max θ/α, impacts, the quantities of `[sweep] report`,
//! and the message of a run without a result) and fragility.csv (per axis cell and scale the
//! runs, the failed ones, those beyond the model, the completed ones, the overturned ones and
//! the fraction overturned of the completed ones). The command writes them; Python's `Batch`
//! gets the same fragility rows.

use std::collections::BTreeMap;

use rocking_spectra::{CellClass, Outcome};

use crate::report::{Entry, Table};
use crate::{Invariant, StudyError};

use super::{Plan, Records};

/// What the runs at one scale factor (and one cell of the batch's axes) gave.
#[derive(Clone, Debug, PartialEq)]
pub struct ScaleTally {
    /// The cell of the batch's own axes as `key=value` (empty without axes).
    pub axes: Vec<String>,
    /// The scale factor.
    pub scale: f64,
    /// Runs.
    pub runs: usize,
    /// Runs that failed (no result).
    pub failed: usize,
    /// Runs beyond the model's validity (no result; docs/spectra.md).
    pub beyond_model: usize,
    /// Runs that overturned.
    pub overturned: usize,
}

impl ScaleTally {
    /// The runs with a result.
    pub fn completed(&self) -> usize {
        self.runs - self.failed - self.beyond_model
    }

    /// The fraction overturned of the runs with a result; none when no run has one.
    pub fn fraction(&self) -> Option<f64> {
        let n = self.completed();
        (n > 0).then(|| self.overturned as f64 / n as f64)
    }
}

/// A batch's tables and its tally (per axis cell, then per scale factor in the order of the
/// scales; per scale factor alone without axes).
pub struct BatchTables {
    /// runs.csv.
    pub runs: Table,
    /// fragility.csv.
    pub fragility: Table,
    /// The tally fragility.csv is made of.
    pub tally: Vec<ScaleTally>,
}

impl Plan {
    /// The tables of a record batch's `outcome`. A failed run (or one beyond the model) has no
    /// result: its fields are empty, never a made-up "survived"; the fraction overturned is of
    /// the runs with a result, and a scale with no result has none (an empty field).
    pub fn batch_tables(&self, outcome: &Outcome) -> Result<BatchTables, StudyError> {
        let sweep = &self.sweep;
        let Some(Records { names, scales, .. }) = &self.records else {
            return Err(StudyError::Internal(Invariant::BatchRecords));
        };
        let own = &sweep.axes[2..];
        // The cells of the batch's own axes (1 without them): the fastest-varying part of an
        // index.
        let own_cells: usize = own.iter().map(|a| a.values.len()).product();
        let own_values = |mut a: usize| -> Vec<String> {
            let mut out = vec![String::new(); own.len()];
            for (k, axis) in own.iter().enumerate().rev() {
                let n = axis.values.len();
                out[k] = axis.display(axis.values[a % n]);
                a /= n;
            }
            out
        };
        let messages: BTreeMap<usize, &str> = outcome
            .failures
            .iter()
            .chain(&outcome.beyond_model)
            .map(|(i, m)| (*i, m.as_str()))
            .collect();
        let mut tally: Vec<ScaleTally> = (0..own_cells)
            .flat_map(|a| {
                let values = own_values(a);
                scales.iter().map(move |&scale| ScaleTally {
                    axes: own
                        .iter()
                        .zip(&values)
                        .map(|(ax, v)| format!("{}={v}", ax.key))
                        .collect(),
                    scale,
                    runs: 0,
                    failed: 0,
                    beyond_model: 0,
                    overturned: 0,
                })
            })
            .collect();
        // The quantities of `[sweep] report` after the run's own, as in a spectrum's cells.csv.
        let mut runs = Table::new(
            ["record", "scale"]
                .into_iter()
                .chain(own.iter().map(|a| a.key.as_str()))
                .chain(["class", "overturned", "max_theta_over_alpha", "impacts"])
                .chain(sweep.reported.iter().map(String::as_str))
                .chain(["message"]),
        );
        for c in &outcome.cells {
            let v = sweep.values(c.index);
            let (a, k) = (c.index % own_cells, (c.index / own_cells) % scales.len());
            let t = &mut tally[a * scales.len() + k];
            t.runs += 1;
            let mut row = vec![
                Entry::Text(names[v[0] as usize].clone()),
                Entry::Number(v[1]),
            ];
            row.extend(own_values(a).into_iter().map(Entry::Text));
            row.push(Entry::Text(c.class.as_str().into()));
            if c.class.has_result() {
                let over = c.class.overturned() == Some(true);
                t.overturned += usize::from(over);
                row.extend([
                    Entry::Flag(over),
                    Entry::Number(c.max_theta_over_alpha),
                    Entry::Count(c.impacts),
                ]);
                row.extend(c.reported.iter().copied().map(Entry::of));
                row.push(Entry::Empty);
            } else {
                if c.class == CellClass::BeyondModel {
                    t.beyond_model += 1;
                } else {
                    t.failed += 1;
                }
                let m = messages.get(&c.index).copied().unwrap_or("failed");
                row.extend(std::iter::repeat_n(Entry::Empty, 3 + sweep.reported.len()));
                row.push(Entry::Text(m.to_string()));
            }
            runs.rows.push(row);
        }
        let mut fragility = Table::new(own.iter().map(|a| a.key.as_str()).chain([
            "scale",
            "runs",
            "failed",
            "beyond_model",
            "completed",
            "overturned",
            "fraction_overturned",
        ]));
        for (i, t) in tally.iter().enumerate() {
            let mut row: Vec<Entry> = own_values(i / scales.len())
                .into_iter()
                .map(Entry::Text)
                .collect();
            row.push(Entry::Number(t.scale));
            row.extend(
                [
                    t.runs,
                    t.failed,
                    t.beyond_model,
                    t.completed(),
                    t.overturned,
                ]
                .map(|n| Entry::Count(n as u64)),
            );
            row.push(t.fraction().map_or(Entry::Empty, Entry::Number));
            fragility.rows.push(row);
        }
        Ok(BatchTables {
            runs,
            fragility,
            tally,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_fraction_is_of_the_runs_with_a_result_and_none_without_one() {
        let t = |runs, failed, beyond_model, overturned| ScaleTally {
            axes: Vec::new(),
            scale: 1.0,
            runs,
            failed,
            beyond_model,
            overturned,
        };
        assert_eq!(t(4, 1, 1, 1).completed(), 2);
        assert_eq!(t(4, 1, 1, 1).fraction(), Some(0.5));
        assert_eq!(t(3, 2, 1, 0).fraction(), None);
        assert_eq!(t(2, 0, 0, 2).fraction(), Some(1.0));
    }
}
