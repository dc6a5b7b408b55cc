//! Panels of one quantity against τ with one or more runs overlaid (each in its own colour, dash
//! and marker; markers at the run's impacts), as in the paper's Figs 3, 4, 5 and 10. Panels of the
//! same quantity share their y range, so overlays and neighbours compare; a zoom shows a window
//! of τ. θ/α is never scaled to π/2 by an overturning run: its line leaves the panel and an arrow
//! at the edge says it overturned.

use std::sync::Arc;

use crate::chart::{axes, fail, mark_at, pixel, rgb, styled_line, Area, LegendItem};
use crate::style::LineStyle;
use plotters::prelude::*;
use rocking::{EventKind, HistoryRow, Run};
use rocking_scene::labels;
use rocking_scene::setup::Setup;
use rocking_scene::units::Scales;
use rocking_study::report::{self, Column, Kind};

use super::clip::clip;
use super::inset::{self, Inset};
use super::Panel;

/// What a figure's caption says about the marks it shows: the impact markers, the arrow of an
/// overturning run.
pub fn caption(impacts: bool, overturned: bool) -> Option<String> {
    let mut parts = Vec::new();
    if impacts {
        parts.push(
            "Markers on a line: the run's impacts (ticks along a panel's bottom edge where a run \
             has more than 12 in it).",
        );
    }
    if overturned {
        parts.push(
            "An arrow at a panel's edge: the run overturns there (θ goes on to π/2, beyond the \
             panel).",
        );
    }
    (!parts.is_empty()).then(|| parts.join(" "))
}

/// A quantity of a run's history that a panel can show: a numeric column of history.csv
/// (`rocking_study::report::HISTORY`: its name, label and value come from there).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Quantity(&'static Column<HistoryRow>);

/// θ/α: never scaled by an overturning run (see [`HistoryPanel`]).
pub const THETA_OVER_ALPHA: Quantity = Quantity(&report::THETA_OVER_ALPHA);

/// The panels of `rocking run`'s figure, top to bottom (the paper's Figs 3, 5 and 10): history
/// columns by name.
pub const RUN_PANELS: [&str; 5] = [
    "theta_over_alpha",
    "u_over_ucr",
    "e_total_over_eref",
    "base_moment_over_wb",
    "ug_over_g_tan_alpha",
];

impl Quantity {
    /// The quantity named `name` (a numeric history.csv column).
    pub fn parse(name: &str) -> Option<Quantity> {
        report::history_column(name)
            .filter(|c| c.kind == Kind::Number)
            .map(Quantity)
    }

    /// Every quantity a panel can show, in history.csv's order.
    pub fn all() -> impl Iterator<Item = Quantity> {
        report::HISTORY
            .iter()
            .filter(|c| c.kind == Kind::Number)
            .map(Quantity)
    }

    /// Its name in history.csv and figure files.
    pub fn name(self) -> &'static str {
        self.0.name
    }

    /// Its axis label.
    pub fn label(self) -> &'static str {
        self.0.label
    }

    fn value(self, r: &HistoryRow, s: &Scales) -> f64 {
        self.0.number(r, s)
    }
}

/// One run's history with its impacts and its style.
#[derive(Clone)]
pub struct Trace {
    /// The legend text (empty: no legend entry).
    pub label: String,
    pub style: LineStyle,
    rows: Arc<Vec<HistoryRow>>,
    scales: Scales,
    /// τ of the impacts.
    pub impacts: Vec<f64>,
    /// Whether the run overturned.
    pub overturned: bool,
    /// θ_cr/α of its structure.
    pub theta_cr_over_alpha: f64,
    /// Seconds per unit of τ, where the scene knows its time in seconds (physical units, or a
    /// dimensionless structure with a length scale).
    pub seconds_per_tau: Option<f64>,
}

impl Trace {
    /// The trace of a run of `model`.
    pub fn of(model: &Setup, run: &Run, label: String, style: LineStyle) -> Trace {
        let s = model.scales;
        Trace {
            label,
            style,
            rows: Arc::new(run.history.clone()),
            scales: s,
            impacts: run
                .events
                .iter()
                .filter(|e| e.kind == EventKind::Impact)
                .map(|e| e.time.tau)
                .collect(),
            overturned: run.summary.overturned,
            theta_cr_over_alpha: s.theta_cr / s.alpha,
            seconds_per_tau: s.seconds_per_tau(),
        }
    }

    /// (τ, value) of a quantity.
    pub fn points(&self, q: Quantity) -> Vec<(f64, f64)> {
        self.rows
            .iter()
            .map(|r| (self.tau(r), q.value(r, &self.scales)))
            // A column the run does not have (the ground's on the rigid surface) draws nothing.
            .filter(|(_, v)| v.is_finite())
            .collect()
    }

    /// The last τ of the history.
    pub fn end(&self) -> f64 {
        self.rows.last().map_or(0.0, |r| self.tau(r))
    }

    /// τ of a history row.
    fn tau(&self, r: &HistoryRow) -> f64 {
        report::TAU.number(r, &self.scales)
    }

    /// The value of `q` at τ, interpolated between history rows.
    fn at(&self, q: Quantity, tau: f64) -> Option<f64> {
        let i = self.rows.partition_point(|r| self.tau(r) < tau);
        let b = self.rows.get(i)?;
        let vb = q.value(b, &self.scales);
        if i == 0 {
            return Some(vb);
        }
        let a = &self.rows[i - 1];
        let va = q.value(a, &self.scales);
        let (ta, tb) = (self.tau(a), self.tau(b));
        let w = if tb > ta { (tau - ta) / (tb - ta) } else { 0.0 };
        Some(va + w * (vb - va))
    }
}

/// A panel: one quantity, the runs overlaid.
pub struct HistoryPanel {
    pub quantity: Quantity,
    pub traces: Vec<Trace>,
    /// A window of τ (a zoom); else the whole runs.
    pub window: Option<(f64, f64)>,
    pub title: Option<String>,
    /// Every run drawn in black in its own dash (the ground motion, as the paper's Fig. 10).
    pub black: bool,
    /// Time drawn in seconds (this many per unit of τ), else in τ.
    pub seconds_per_tau: Option<f64>,
    /// Values of the quantity marked by a dashed grey line across the panel (M_b/(W B) = ±1:
    /// the moment that uplifts the base); the panel's range includes them.
    pub rules: Vec<f64>,
    /// Runs drawn over the others as a thin solid grey line, without impact marks (the
    /// fixed-base twin of a rocking run, as the paper's Fig. 5 compares them); the panel's range
    /// includes them.
    pub twins: Vec<Trace>,
    /// A smaller chart inside the panel: a window of τ on its own y range, where the panel's
    /// range (shared with its row) flattens a run's curve.
    pub inset: Option<Inset>,
}

/// The grey of a twin's line.
pub const TWIN_GREY: [u8; 3] = [70, 70, 70];
/// A run with more impacts than this in a panel's window marks them as ticks along the panel's
/// bottom edge (a rug), not as markers on its line, where they would merge into a bar.
pub const RUG_ABOVE: usize = 12;
/// A rug tick's length and the rows' spacing, in pixels (1/8 mm at print size).
const RUG_TICK: i32 = 10;

/// The label of time in seconds.
pub const TIME_S: &str = "t (s)";
/// The dash of a rule across a history panel.
const RULE_DASH: (u32, u32) = (10, 6);

impl HistoryPanel {
    pub fn new(quantity: Quantity, traces: Vec<Trace>) -> HistoryPanel {
        HistoryPanel {
            quantity,
            traces,
            window: None,
            title: None,
            black: false,
            seconds_per_tau: None,
            rules: Vec::new(),
            twins: Vec::new(),
            inset: None,
        }
    }

    /// The style a run is drawn in: solid where it is the panel's only run (a dash on a fast
    /// oscillation prints as a bar code), else its own.
    fn drawn_style(&self, t: &Trace) -> LineStyle {
        if self.traces.len() == 1 && !self.black {
            LineStyle {
                dash: None,
                ..t.style
            }
        } else {
            t.style
        }
    }

    /// The label of the time axis.
    fn time_label(&self) -> &'static str {
        if self.seconds_per_tau.is_some() {
            TIME_S
        } else {
            labels::TAU
        }
    }

    fn x_range(&self) -> (f64, f64) {
        self.window.unwrap_or_else(|| {
            let end = self.traces.iter().map(Trace::end).fold(1e-6, f64::max);
            (0.0, end)
        })
    }

    /// The largest |θ/α| the panel shows: an overturning run is followed up to this and no
    /// further (the survivors' largest, at least 1.3 θ_cr/α).
    fn theta_limit(&self) -> f64 {
        let survivors = self
            .traces
            .iter()
            .filter(|t| !t.overturned)
            .flat_map(|t| t.points(THETA_OVER_ALPHA))
            .fold(0.0, |m: f64, p| m.max(p.1.abs()));
        let critical = self
            .traces
            .iter()
            .map(|t| t.theta_cr_over_alpha)
            .fold(0.0, f64::max);
        survivors.max(1.3 * critical)
    }

    /// The lowest and highest value in the panel's window (θ/α bounded by [`Self::theta_limit`]).
    fn data_range(&self) -> Option<(f64, f64)> {
        self.range_in(self.x_range())
    }

    /// The lowest and highest value in the τ window `(x0, x1)`, as [`Self::data_range`].
    fn range_in(&self, (x0, x1): (f64, f64)) -> Option<(f64, f64)> {
        let limit = (self.quantity == THETA_OVER_ALPHA).then(|| self.theta_limit());
        let mut range: Option<(f64, f64)> = None;
        for t in self.traces.iter().chain(&self.twins) {
            for (x, y) in t.points(self.quantity) {
                if x < x0 || x > x1 || !y.is_finite() {
                    continue;
                }
                if limit.is_some_and(|l| y.abs() > l) {
                    break;
                }
                range = Some(match range {
                    None => (y, y),
                    Some((a, b)) => (a.min(y), b.max(y)),
                });
            }
        }
        for &y in &self.rules {
            range = range.map(|(a, b)| (a.min(y), b.max(y)));
        }
        range
    }

    /// The panel's axis labels (x, y).
    pub(super) fn axis_labels(&self) -> (String, String) {
        (
            self.time_label().to_string(),
            self.quantity.label().to_string(),
        )
    }

    /// The panel's legend entries: each labelled run's line.
    pub(super) fn legend(&self) -> Vec<LegendItem> {
        // A panel in black (the ground motion) is explained by the caption, not the legend.
        let twins = self
            .twins
            .iter()
            .filter(|t| !t.label.is_empty())
            .map(|t| LegendItem::Rule(TWIN_GREY, None, t.label.clone()));
        self.traces
            .iter()
            .filter(|t| !t.label.is_empty() && !self.black)
            .map(|t| LegendItem::Line(self.drawn_style(t), t.label.clone()))
            .chain(twins)
            .collect()
    }

    pub(super) fn draw(&self, area: &Area<'_>, y: Option<(f64, f64)>) -> Result<(), String> {
        // Time in τ, or in seconds: every abscissa times `k`.
        let k = self.seconds_per_tau.unwrap_or(1.0);
        let x = self.x_range();
        let x = (x.0 * k, x.1 * k);
        let (lo, hi) = padded(y.or_else(|| self.data_range()).unwrap_or((-1.0, 1.0)));
        let mut chart = axes(
            area,
            self.title.as_deref(),
            x,
            (lo, hi),
            (self.time_label(), self.quantity.label()),
            true,
        )?;
        for &v in &self.rules {
            styled_line(
                &mut chart,
                vec![(x.0, v), (x.1, v)],
                &LineStyle {
                    dash: Some(RULE_DASH),
                    ..crate::style::BLACK
                },
                RGBColor(90, 90, 90),
                1,
            )?;
        }
        if lo < 0.0 && hi > 0.0 {
            chart
                .draw_series(std::iter::once(PathElement::new(
                    vec![(x.0, 0.0), (x.1, 0.0)],
                    RGBColor(120, 120, 120).stroke_width(1),
                )))
                .map_err(fail)?;
        }
        let frame = (x, (lo, hi));
        let mut rug_rows = 0;
        for t in &self.traces {
            let (points, style, colour, width) = self.line_of(t, k);
            for piece in clip(&points, frame) {
                styled_line(&mut chart, piece, &style, colour, width)?;
            }
            let shown: Vec<f64> = t
                .impacts
                .iter()
                .map(|tau| tau * k)
                .filter(|at| (x.0..=x.1).contains(at))
                .collect();
            let rug = shown.len() > RUG_ABOVE;
            if rug {
                // A rug: one tick per impact along the bottom edge, a row per such run.
                let area = chart.plotting_area().strip_coord_spec();
                let bottom = area.dim_in_pixel().1 as i32 - 1 - rug_rows * (RUG_TICK + 2);
                rug_rows += 1;
                let mut drawn = std::collections::HashSet::new();
                for at in shown {
                    let (px, _) = pixel(&chart, (at, lo));
                    if drawn.insert(px) {
                        area.draw(&PathElement::new(
                            vec![(px, bottom), (px, bottom - RUG_TICK)],
                            colour.stroke_width(1),
                        ))
                        .map_err(fail)?;
                    }
                }
            }
            // Impacts: the run's marker on its line; with more impacts than the panel has pixel
            // columns (a chattering run has hundreds of thousands, which no SVG reader would
            // hold), one per pixel: the same drawing.
            let columns = chart.plotting_area().dim_in_pixel().0 as usize;
            let thin = t.impacts.len() > columns;
            let mut drawn = std::collections::HashSet::new();
            for &tau in t.impacts.iter().filter(|_| !rug) {
                let at = tau * k;
                if at < x.0 || at > x.1 {
                    continue;
                }
                let v = if self.quantity == THETA_OVER_ALPHA {
                    Some(0.0)
                } else {
                    t.at(self.quantity, tau)
                };
                let tau = at;
                if let Some(v) = v.filter(|v| (lo..=hi).contains(v)) {
                    if thin && !drawn.insert(pixel(&chart, (tau, v))) {
                        continue;
                    }
                    mark_at(&chart, t.style.marker, (tau, v), 4, colour, true)?;
                }
            }
            // Overturning: an arrow where θ/α leaves the panel.
            if t.overturned && self.quantity == THETA_OVER_ALPHA {
                if let Some(&(tau, v)) = points
                    .iter()
                    .find(|p| p.0 >= x.0 && p.0 <= x.1 && !(lo..=hi).contains(&p.1))
                {
                    let edge = if v > 0.0 { hi } else { lo };
                    let area = chart.plotting_area().strip_coord_spec();
                    let (px, py) = pixel(&chart, (tau, edge));
                    let dir = if v > 0.0 { 1 } else { -1 };
                    let tip = (px, py + dir * 2);
                    area.draw(&Polygon::new(
                        vec![tip, (px - 7, py + dir * 14), (px + 7, py + dir * 14)],
                        colour.filled(),
                    ))
                    .map_err(fail)?;
                }
            }
        }
        // The twins over the runs (a stiff run's fast oscillation would hide them).
        let twins: Vec<_> = self.twins.iter().map(|t| self.twin_line(t, k)).collect();
        for (points, solid, colour, width) in &twins {
            for piece in clip(points, frame) {
                styled_line(&mut chart, piece, solid, *colour, *width)?;
            }
        }
        if let Some(i) = &self.inset {
            let window = i.window.unwrap_or(self.x_range());
            let range = i.range.or_else(|| self.range_in(window));
            let range = padded(range.unwrap_or((-1.0, 1.0)));
            let mut lines: Vec<_> = self.traces.iter().map(|t| self.line_of(t, k)).collect();
            lines.extend(twins);
            inset::draw(i, &mut chart, (window.0 * k, window.1 * k), range, &lines)?;
        }
        Ok(())
    }

    /// A run's line as drawn: its points (time in the panel's unit, `k` per τ), style, colour
    /// and width.
    fn line_of(&self, t: &Trace, k: f64) -> inset::Line {
        let style = self.drawn_style(t);
        let colour = if self.black {
            BLACK
        } else {
            rgb(t.style.colour)
        };
        let mut points = t.points(self.quantity);
        if k != 1.0 {
            points.iter_mut().for_each(|p| p.0 *= k);
        }
        // Many short segments (a record) draw thinner.
        let width = if points.len() > 5000 { 1 } else { 2 };
        (points, style, colour, width)
    }

    /// A twin's line: thin, solid, dark grey.
    fn twin_line(&self, t: &Trace, k: f64) -> inset::Line {
        let mut points = t.points(self.quantity);
        points.iter_mut().for_each(|p| p.0 *= k);
        let solid = LineStyle {
            dash: None,
            ..t.style
        };
        (points, solid, rgb(TWIN_GREY), 1)
    }
}

/// A little room around a data range (a flat one gets ±1).
fn padded((lo, hi): (f64, f64)) -> (f64, f64) {
    if hi - lo < 1e-12 * hi.abs().max(lo.abs()).max(1e-300) {
        return (lo - 1.0, hi + 1.0);
    }
    let pad = 0.06 * (hi - lo);
    (lo - pad, hi + pad)
}

/// The y range of each history panel: panels of the same quantity that show whole runs share
/// one (the union of their data), a zoom keeps its own.
pub(super) fn shared_ranges(panels: &[Panel]) -> Vec<Option<(f64, f64)>> {
    fn whole(p: &Panel) -> Option<&HistoryPanel> {
        match p {
            Panel::History(h) if h.window.is_none() => Some(h),
            _ => None,
        }
    }
    panels
        .iter()
        .map(|p| {
            let h = whole(p)?;
            panels
                .iter()
                .filter_map(whole)
                .filter(|o| o.quantity == h.quantity)
                .filter_map(HistoryPanel::data_range)
                .reduce(|a, b| (a.0.min(b.0), a.1.max(b.1)))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_run_figures_panels_are_drawable_history_columns() {
        for name in RUN_PANELS {
            let q = Quantity::parse(name).expect("a numeric history column");
            assert_eq!(q.name(), name);
        }
        assert_eq!(Quantity::parse("theta_over_alpha"), Some(THETA_OVER_ALPHA));
        // Time and text columns are not quantities a panel draws against τ.
        for name in ["tau", "t_s", "phase", "required_friction", "nope"] {
            assert!(Quantity::parse(name).is_none(), "{name}");
        }
    }
}
