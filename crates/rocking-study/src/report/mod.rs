//! What a run reports, as the `rocking` command writes it and the Python package returns it:
//! the summary object (`--json`, summary.json) and the derived quantities ([`summary`]),
//! history.csv and events.csv from one column list each ([`tables`]), and which summary
//! quantities a sweep may report ([`reportable`]). One implementation, so that both print the
//! same numbers.

mod reportable;
mod run;
mod summary;
mod tables;

pub use reportable::{
    force_extremes, ground_extremes, needs_deflection, needs_forces, nullable, quantity_label,
    reportable_keys, unmet_needs, Need, Reportable, REPORTABLE,
};
pub use run::{run_setup, simulate, Report};
pub use summary::{
    derived_json, number, quantities, si_scale, summary_json, warnings, SiScale, RATIOS, SI_MAXIMA,
};
pub use tables::{
    events_csv, history_column, history_columns, history_csv, Column, Entry, Group, Kind, Table,
    EVENTS, HISTORY, TAU, THETA_OVER_ALPHA,
};

/// The tables' columns and the reportable summary quantities with their labels and units, as
/// Python's `rocking.columns()` returns them: `{"history": [..], "events": [..], "reportable":
/// [..]}`, each column `{name, label, unit, group, kind}`, each quantity `{key, label, needs,
/// twin, forces, nullable}` (`needs`: the conditions a run must meet to report it, none for
/// every run).
pub fn catalogue() -> serde_json::Value {
    fn columns<R>(cols: &[Column<R>]) -> Vec<serde_json::Value> {
        cols.iter()
            .map(|c| {
                serde_json::json!({
                    "name": c.name,
                    "label": c.label,
                    "unit": c.unit,
                    "group": format!("{:?}", c.group).to_lowercase(),
                    "kind": format!("{:?}", c.kind).to_lowercase(),
                })
            })
            .collect()
    }
    let reportable: Vec<_> = REPORTABLE
        .iter()
        .map(|r| {
            serde_json::json!({
                "key": r.key,
                "label": r.label,
                "needs": r.needs.iter().map(|n| format!("{n:?}").to_lowercase()).collect::<Vec<_>>(),
                "twin": r.twin,
                "forces": r.extreme.is_some(),
                "nullable": r.nullable,
            })
        })
        .collect();
    serde_json::json!({
        "history": columns(&HISTORY),
        "events": columns(&EVENTS),
        "reportable": reportable,
    })
}
