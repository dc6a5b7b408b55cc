//! The columns of a run's tables, history.csv and events.csv, declared once: each column's name
//! (the CSV header, Python's key, a figure file's `quantity`), its label in the paper's notation
//! (the figures' axes), its unit and how its value is computed from a raw row and the run's
//! [`Scales`]. The CSV writers, the figures and Python read these lists, so they cannot diverge;
//! a new history column is a field of `HistoryRow`, the recorder's line that fills it, and one
//! entry here.

use std::fmt::Write as _;

use rocking::{EventRecord, GroundRow, HistoryRow, Run};
use rocking_scene::labels;
use rocking_scene::setup::Setup;
use rocking_scene::units::{GroundScales, Scales};
use serde_json::Value;

use crate::{Invariant, StudyError};

/// Which runs have a column.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Group {
    /// Every run.
    Always,
    /// Runs that track the forces (`[output] forces`).
    Forces,
    /// Runs on compliant ground (`[ground]`).
    Ground,
}

/// What a column holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// Time: τ, or seconds where the scene knows them.
    Time,
    /// A finite number at every row: a figure can draw it against τ.
    Number,
    /// A number that may be unbounded (written `inf`).
    Unbounded,
    /// Text (a phase, an event's kind or branch).
    Text,
}

/// One entry of a row.
#[derive(Clone, Debug, PartialEq)]
pub enum Entry {
    /// A number (refused unless finite).
    Number(f64),
    /// +∞ (written `inf`).
    Unbounded,
    /// A count.
    Count(u64),
    /// Yes or no.
    Flag(bool),
    /// Text.
    Text(String),
    /// Nothing: an unknown time in seconds, a field that does not apply.
    Empty,
    /// The row lacks what the column needs (a defect: the column's group says which runs have it).
    Missing,
}

impl Entry {
    /// A reported quantity: its number, or nothing where the run has no value.
    pub fn of(value: Option<f64>) -> Entry {
        value.map_or(Entry::Empty, Entry::Number)
    }
}

/// One column of a table of rows `R`.
#[derive(Clone, Copy, Debug)]
pub struct Column<R: 'static> {
    /// The CSV header, Python's key and a figure file's `quantity`.
    pub name: &'static str,
    /// The label in the paper's notation.
    pub label: &'static str,
    /// The unit of the value: what the raw quantity is divided by ("1": a pure number).
    pub unit: &'static str,
    /// Which runs have it.
    pub group: Group,
    /// What it holds.
    pub kind: Kind,
    value: fn(&R, &Scales) -> Entry,
}

impl<R> Column<R> {
    /// The column's entry in `row`.
    pub fn entry(&self, row: &R, scales: &Scales) -> Entry {
        (self.value)(row, scales)
    }

    /// The column's value in `row` as a number (NaN where it is none).
    pub fn number(&self, row: &R, scales: &Scales) -> f64 {
        match self.entry(row, scales) {
            Entry::Number(x) => x,
            Entry::Unbounded => f64::INFINITY,
            _ => f64::NAN,
        }
    }
}

impl<R> PartialEq for Column<R> {
    fn eq(&self, other: &Column<R>) -> bool {
        self.name == other.name
    }
}

/// The name under which a value serializes (a phase, an event's kind).
fn serialized_name(v: impl serde::Serialize) -> Entry {
    let v = serde_json::to_value(v).unwrap_or(Value::Null);
    Entry::Text(v.as_str().unwrap_or("?").to_string())
}

const fn column<R>(
    name: &'static str,
    label: &'static str,
    unit: &'static str,
    group: Group,
    kind: Kind,
    value: fn(&R, &Scales) -> Entry,
) -> Column<R> {
    Column {
        name,
        label,
        unit,
        group,
        kind,
        value,
    }
}

use Group::{Always, Forces, Ground};
use Kind::{Number, Text, Time};

/// A ground column's value: `value` of the row's ground columns and the ground's scales, missing
/// where the run has no compliant ground.
fn ground(r: &HistoryRow, s: &Scales, value: fn(&GroundRow, &GroundScales) -> f64) -> Entry {
    match (&r.ground, &s.ground) {
        (Some(g), Some(gs)) => Entry::Number(value(g, gs)),
        _ => Entry::Missing,
    }
}

/// τ = p t of a history row.
pub const TAU: Column<HistoryRow> = column("tau", labels::TAU, "1/p", Always, Time, |r, s| {
    Entry::Number(r.t * s.p)
});

/// θ/α of a history row.
pub const THETA_OVER_ALPHA: Column<HistoryRow> = column(
    "theta_over_alpha",
    labels::THETA_OVER_ALPHA,
    "α",
    Always,
    Number,
    |r, s| Entry::Number(r.theta / s.alpha),
);

/// history.csv's columns in order (then, with n > 1 deformation coordinates, u_1..u_n and
/// u_dot_1..u_dot_n in the model's units: [`history_csv`]).
pub const HISTORY: [Column<HistoryRow>; 19] = [
    TAU,
    // From τ, as the events' seconds are.
    column("t_s", "t (s)", "s", Always, Time, |r, s| {
        match s.p_per_second {
            Some(p) => Entry::Number(r.t * s.p / p),
            None => Entry::Empty,
        }
    }),
    THETA_OVER_ALPHA,
    column(
        "u_over_ucr",
        labels::U_OVER_UCR,
        "u_cr",
        Always,
        Number,
        |r, s| Entry::Number(r.u / s.u_cr),
    ),
    column(
        "theta_dot_over_alpha_p",
        "θ\u{307}/(α p)",
        "α p",
        Always,
        Number,
        |r, s| Entry::Number(r.theta_dot / (s.alpha * s.p)),
    ),
    column(
        "u_dot_over_ucr_omega_n",
        "u\u{307}/(u_cr ω_n)",
        "u_cr ω_n",
        Always,
        Number,
        |r, s| Entry::Number(r.u_dot / (s.u_cr * s.omega_n)),
    ),
    column("phase", "phase", "", Always, Text, |r, _| {
        serialized_name(r.phase)
    }),
    column(
        "e_kin_over_eref",
        "E_kin/E_ref",
        "E_ref",
        Always,
        Number,
        |r, s| Entry::Number(r.e_kin / s.e_ref),
    ),
    column(
        "e_total_over_eref",
        labels::E_OVER_EREF,
        "E_ref",
        Always,
        Number,
        |r, s| Entry::Number(r.e_total / s.e_ref),
    ),
    column(
        "ug_over_g_tan_alpha",
        labels::UG_OVER_G_TAN_ALPHA,
        "g tan α",
        Always,
        Number,
        |r, s| Entry::Number(r.ug / s.g_tan_alpha),
    ),
    column(
        "base_moment_over_wb",
        "M_b/(W B)",
        "W B",
        Forces,
        Number,
        |r, s| Entry::Number(r.base_moment / s.uplift_moment),
    ),
    column("base_shear_over_w", "V_b/W", "W", Forces, Number, |r, s| {
        Entry::Number(r.base_shear / s.weight)
    }),
    column(
        "elastic_base_moment_over_wb",
        "M_el/(W B)",
        "W B",
        Forces,
        Number,
        |r, s| Entry::Number(r.elastic_base_moment / s.uplift_moment),
    ),
    // Where R_v <= 0 no friction holds the structure: unbounded. Of the reactions over W, as
    // the summary's largest demand is.
    column(
        "required_friction",
        "|R_h|/R_v",
        "1",
        Forces,
        Kind::Unbounded,
        |r, s| match rocking::required_friction(
            r.horizontal_reaction / s.weight,
            r.vertical_reaction / s.weight,
        ) {
            f if f.is_finite() => Entry::Number(f),
            _ => Entry::Unbounded,
        },
    ),
    column(
        "vertical_reaction_over_w",
        "R_v/W",
        "W",
        Forces,
        Number,
        |r, s| Entry::Number(r.vertical_reaction / s.weight),
    ),
    column(
        "settlement_over_static",
        "v/v₀",
        "v₀",
        Ground,
        Number,
        |r, s| ground(r, s, |g, gs| g.settlement / gs.settlement),
    ),
    column(
        "contact_fraction",
        "contact length/2B",
        "2B",
        Ground,
        Number,
        |r, s| ground(r, s, |g, _| g.contact_fraction),
    ),
    column(
        "ground_pressure_over_mean",
        "p/(W/2B)",
        "W/(2B)",
        Ground,
        Number,
        |r, s| ground(r, s, |g, gs| g.ground_pressure / gs.mean_pressure),
    ),
    column(
        "least_ground_pressure_over_mean",
        "p_min/(W/2B)",
        "W/(2B)",
        Ground,
        Number,
        |r, s| ground(r, s, |g, gs| g.least_pressure / gs.mean_pressure),
    ),
];

/// events.csv's columns in order: one row per uplift, impact, rest, overturning (and on
/// compliant ground lift-off, landing, pivot switch).
pub const EVENTS: [Column<EventRecord>; 10] = [
    column("tau", labels::TAU, "1/p", Always, Time, |e, _| {
        Entry::Number(e.time.tau)
    }),
    column("t_s", "t (s)", "s", Always, Time, |e, _| {
        e.time.seconds.map_or(Entry::Empty, Entry::Number)
    }),
    column("kind", "event", "", Always, Text, |e, _| {
        serialized_name(e.kind)
    }),
    column("branch", "impact branch", "", Always, Text, |e, _| {
        Entry::Text(e.branch.to_string())
    }),
    column("phase_after", "phase after", "", Always, Text, |e, _| {
        serialized_name(e.phase_after)
    }),
    column(
        "theta_dot_over_alpha_p",
        "θ\u{307}/(α p) before",
        "α p",
        Always,
        Number,
        |e, s| Entry::Number(e.theta_dot / (s.alpha * s.p)),
    ),
    column(
        "u_over_ucr",
        labels::U_OVER_UCR,
        "u_cr",
        Always,
        Number,
        |e, s| Entry::Number(e.u / s.u_cr),
    ),
    column(
        "u_dot_over_ucr_omega_n",
        "u\u{307}/(u_cr ω_n) before",
        "u_cr ω_n",
        Always,
        Number,
        |e, s| Entry::Number(e.u_dot / (s.u_cr * s.omega_n)),
    ),
    column(
        "e_kin_before_over_eref",
        "E_kin/E_ref before",
        "E_ref",
        Always,
        Number,
        |e, _| Entry::Number(e.energy_before),
    ),
    column(
        "e_kin_after_over_eref",
        "E_kin/E_ref after",
        "E_ref",
        Always,
        Number,
        |e, _| Entry::Number(e.energy_after),
    ),
];

/// The history columns a run of `model` has, in order.
pub fn history_columns(model: &Setup) -> impl Iterator<Item = &'static Column<HistoryRow>> {
    let (forces, ground) = (model.options.forces, model.ground.is_some());
    HISTORY.iter().filter(move |c| match c.group {
        Always => true,
        Forces => forces,
        Ground => ground,
    })
}

/// The history column named `name`.
pub fn history_column(name: &str) -> Option<&'static Column<HistoryRow>> {
    HISTORY.iter().find(|c| c.name == name)
}

/// One CSV row of `row` in `columns`, a non-finite number refused with the column's name.
fn write_row<'a, R: 'static>(
    out: &mut String,
    columns: impl IntoIterator<Item = &'a Column<R>>,
    row: &R,
    scales: &Scales,
) -> Result<(), StudyError> {
    for (i, c) in columns.into_iter().enumerate() {
        if i > 0 {
            out.push(',');
        }
        match c.entry(row, scales) {
            Entry::Number(x) => write_number(out, c.name, x)?,
            Entry::Unbounded => out.push_str(rocking::UNBOUNDED),
            Entry::Count(n) => {
                let _ = write!(out, "{n}");
            }
            Entry::Flag(b) => {
                let _ = write!(out, "{b}");
            }
            Entry::Text(t) => out.push_str(&t),
            Entry::Empty => {}
            Entry::Missing => return Err(StudyError::Internal(Invariant::GroundColumns)),
        }
    }
    Ok(())
}

fn write_number(out: &mut String, name: &str, x: f64) -> Result<(), StudyError> {
    if !x.is_finite() {
        return Err(StudyError::NonFinite {
            quantity: name.to_string(),
            detail: x.to_string(),
        });
    }
    let _ = write!(out, "{x}");
    Ok(())
}

fn header<'a, R: 'static>(columns: impl IntoIterator<Item = &'a Column<R>>) -> String {
    let names: Vec<&str> = columns.into_iter().map(|c| c.name).collect();
    names.join(",")
}

/// history.csv: the [`HISTORY`] columns the run has ([`history_columns`]); with n > 1
/// deformation coordinates then u_1..u_n and u_1'..u_n' (`u_dot_i`) in the model's units.
pub fn history_csv(model: &Setup, run: &Run) -> Result<String, StudyError> {
    let columns: Vec<_> = history_columns(model).collect();
    let mut out = header(columns.iter().copied());
    // Several deformation coordinates: u_1..u_n and their rates, in the model's units.
    let n = run.coordinate_count();
    for name in ["u", "u_dot"] {
        for i in 1..=n {
            let _ = write!(out, ",{name}_{i}");
        }
    }
    out.push('\n');
    for (k, r) in run.history.iter().enumerate() {
        write_row(&mut out, columns.iter().copied(), r, &model.scales)?;
        for &c in run.coordinates_of(k) {
            out.push(',');
            write_number(&mut out, "u_i", c)?;
        }
        out.push('\n');
    }
    Ok(out)
}

/// events.csv: the [`EVENTS`] columns, one row per event.
pub fn events_csv(model: &Setup, run: &Run) -> Result<String, StudyError> {
    let mut out = header(&EVENTS);
    out.push('\n');
    for e in &run.events {
        write_row(&mut out, &EVENTS, e, &model.scales)?;
        out.push('\n');
    }
    Ok(out)
}

/// A study's table (records.csv, ida.csv, stripes.csv): named columns and rows of entries,
/// built once by the study; the command writes it as CSV ([`Entry::text`]) and Python reads
/// the same rows as objects ([`Table::objects`]).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Table {
    /// The column names (the CSV header, Python's keys).
    pub columns: Vec<String>,
    /// The rows, one entry per column.
    pub rows: Vec<Vec<Entry>>,
}

impl Entry {
    /// The entry as a CSV field: a number as Rust prints it (`inf`, `NaN` included), empty for
    /// nothing.
    pub fn text(&self) -> String {
        match self {
            Entry::Number(x) => x.to_string(),
            Entry::Unbounded => rocking::UNBOUNDED.to_string(),
            Entry::Count(n) => n.to_string(),
            Entry::Flag(b) => b.to_string(),
            Entry::Text(t) => t.clone(),
            Entry::Empty | Entry::Missing => String::new(),
        }
    }

    /// The entry as JSON: `null` for nothing and for a number that JSON cannot hold.
    pub fn json(&self) -> Value {
        match self {
            Entry::Number(x) => serde_json::json!(x),
            Entry::Unbounded => Value::String(rocking::UNBOUNDED.to_string()),
            Entry::Count(n) => serde_json::json!(n),
            Entry::Flag(b) => Value::Bool(*b),
            Entry::Text(t) => Value::String(t.clone()),
            Entry::Empty | Entry::Missing => Value::Null,
        }
    }
}

impl Table {
    /// An empty table with these columns.
    pub fn new(columns: impl IntoIterator<Item = impl Into<String>>) -> Table {
        Table {
            columns: columns.into_iter().map(Into::into).collect(),
            rows: Vec::new(),
        }
    }

    /// Each row as a JSON object keyed by the column names, in the columns' order.
    pub fn objects(&self) -> Vec<serde_json::Map<String, Value>> {
        self.rows
            .iter()
            .map(|row| {
                self.columns
                    .iter()
                    .zip(row)
                    .map(|(c, e)| (c.clone(), e.json()))
                    .collect()
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn column_names_are_unique_within_a_table() {
        fn unique<R>(cols: &[Column<R>]) {
            for (i, c) in cols.iter().enumerate() {
                assert!(
                    !cols[..i].iter().any(|d| d.name == c.name),
                    "{} twice",
                    c.name
                );
            }
        }
        unique(&HISTORY);
        unique(&EVENTS);
        assert_eq!(history_column("theta_over_alpha"), Some(&THETA_OVER_ALPHA));
    }
}
