//! A study's tables, built once from its records and analyses: records.csv (per record its
//! file, units, sampling, intensity measures and capacity) and ida.csv or stripes.csv (per
//! analysis its level, outcome and the quantities of `[sweep] report`). The command writes them
//! as CSV; Python gets the same rows ([`Study::records_json`]).

use serde_json::Value;

use crate::report::{Entry, Table};

use super::Study;

/// records.csv's columns.
const RECORD_COLUMNS: [&str; 16] = [
    "record",
    "path",
    "units",
    "dt_s",
    "npts",
    "pga_m_s2",
    "pgv_m_s",
    "pgd_m",
    "arias_m_s",
    "d5_95_s",
    "mean_period_s",
    "im_m_s2",
    "pga_over_g_tan_alpha",
    "capacity_im_m_s2",
    "survived_below_im_m_s2",
    "runs",
];

/// ida.csv's and stripes.csv's columns before the reported quantities.
const ANALYSIS_COLUMNS: [&str; 5] = [
    "record",
    "im_m_s2",
    "scale",
    "collapsed",
    "max_theta_over_alpha",
];

impl Study {
    /// records.csv: one row per record, in the order of the files; a stripe study has no
    /// capacity per record (those fields are empty).
    pub fn records_table(&self) -> Table {
        let mut t = Table::new(RECORD_COLUMNS);
        for d in &self.records {
            let m = &d.ims;
            let capacity =
                |f: fn((f64, f64)) -> f64| d.capacity.map_or(Entry::Empty, |c| Entry::Number(f(c)));
            let mut row = vec![
                Entry::Text(d.name.clone()),
                Entry::Text(d.path.clone()),
                Entry::Text(d.unit.to_string()),
            ];
            row.extend(
                [
                    d.dt,
                    d.npts as f64,
                    m.pga_m_s2,
                    m.pgv_m_s,
                    m.pgd_m,
                    m.arias_m_s,
                    m.d5_95_s,
                    m.mean_period_s,
                    d.im_unscaled,
                    d.pga_over_g_tan_alpha,
                ]
                .map(Entry::Number),
            );
            row.extend([
                capacity(|c| c.0),
                capacity(|c| c.1),
                Entry::Count(d.points.len() as u64),
            ]);
            t.rows.push(row);
        }
        t
    }

    /// ida.csv or stripes.csv: one row per analysis (by record, then IM), with the quantities
    /// of `[sweep] report` (`report`).
    pub fn analyses_table(&self, report: &[String]) -> Table {
        let mut t = Table::new(
            ANALYSIS_COLUMNS
                .iter()
                .map(|c| c.to_string())
                .chain(report.iter().cloned()),
        );
        for d in &self.records {
            for (p, values) in d.points.iter().zip(&d.reported) {
                let mut row = vec![
                    Entry::Text(d.name.clone()),
                    Entry::Number(p.im),
                    Entry::Number(p.im / d.im_unscaled),
                    Entry::Flag(p.outcome.collapsed),
                    Entry::Number(p.outcome.response),
                ];
                row.extend(values.iter().copied().map(Entry::of));
                t.rows.push(row);
            }
        }
        t
    }

    /// Per record, records.csv's row as an object, with its `analyses`: its rows of ida.csv or
    /// stripes.csv (without the record's name), as Python returns them.
    pub fn records_json(&self, report: &[String]) -> Value {
        let analyses = self.analyses_table(report);
        let mut rows = analyses.objects().into_iter();
        let records: Vec<Value> = self
            .records
            .iter()
            .zip(self.records_table().objects())
            .map(|(d, mut record)| {
                let own: Vec<Value> = rows
                    .by_ref()
                    .take(d.points.len())
                    .map(|mut a| {
                        a.remove("record");
                        Value::Object(a)
                    })
                    .collect();
                record.insert("analyses".into(), Value::Array(own));
                Value::Object(record)
            })
            .collect();
        Value::Array(records)
    }
}
