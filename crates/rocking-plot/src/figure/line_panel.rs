//! The panels of a one-axis sweep: max θ/α of the upright cells against the axis value, the
//! others marked by class ([`LinePanel`]), and a curve of points ([`CurvePanel`]).

use crate::style;
use plotters::prelude::*;
use rocking_scene::labels;
use rocking_spectra::{Cell, CellClass, Sweep};

use super::spectrum::{class_style, overturned, Axis, LineCells, Lines};
use crate::chart::{axes, fail, mark_at, rgb, styled_line, Area, LegendItem};

/// A one-axis sweep: max θ/α of the cells that stayed upright against the axis value, the
/// others marked by class at the top.
pub struct LinePanel {
    pub title: Option<String>,
    pub axis: Axis,
    /// (value, class, max θ/α) by increasing value.
    pub cells: LineCells,
    /// A reference structure's line, with its legend text.
    pub reference: Option<(String, LineCells)>,
}

impl LinePanel {
    /// The panel of a one-axis sweep.
    pub fn new(sweep: &Sweep, cells: &[Cell]) -> LinePanel {
        LinePanel {
            title: None,
            axis: Axis {
                key: sweep.axes[0].key.clone(),
                values: sweep.axes[0].values.clone(),
            },
            cells: line_cells(sweep, cells),
            reference: None,
        }
    }

    pub fn with_reference(mut self, label: &str, sweep: &Sweep, cells: &[Cell]) -> LinePanel {
        self.reference = Some((label.to_string(), line_cells(sweep, cells)));
        self
    }

    fn top(&self) -> f64 {
        self.cells
            .iter()
            .filter(|c| overturned(c.1) == Some(false))
            .map(|c| c.2)
            .fold(1e-3, f64::max)
            * 1.12
    }

    pub(super) fn legend(&self) -> Vec<LegendItem> {
        let mut items = vec![LegendItem::Line(
            style::LINES[0],
            format!("upright: {}", labels::MAX_THETA_OVER_ALPHA),
        )];
        if let Some((label, _)) = &self.reference {
            items.push(LegendItem::Line(
                style::BLACK,
                format!("{label}: {}", labels::MAX_THETA_OVER_ALPHA),
            ));
        }
        // Every class but the upright ones (the line is their max θ/α).
        for class in CellClass::ALL
            .into_iter()
            .filter(|c| c.overturned() != Some(false))
        {
            if let (Some(s), true) = (class_style(class), self.cells.iter().any(|c| c.1 == class)) {
                items.push(LegendItem::Fill(s.fill, format!("{} (top row)", s.label)));
            }
        }
        let over = self
            .cells
            .iter()
            .filter(|c| overturned(c.1) == Some(true))
            .count();
        let done = self.cells.iter().filter(|c| c.1.has_result()).count();
        items.push(LegendItem::Heading(format!(
            "{} = {over}/{done}",
            labels::FRACTION_OVERTURNED
        )));
        items
    }

    pub(super) fn draw(&self, area: &Area<'_>) -> Result<(), String> {
        let top = self.top();
        let mut chart = axes(
            area,
            self.title.as_deref(),
            self.axis.range(),
            (0.0, top),
            (
                &labels::axis_label(&self.axis.key),
                labels::MAX_THETA_OVER_ALPHA,
            ),
            true,
        )?;
        let line = style::LINES[0];
        for run in upright_runs(&self.cells) {
            styled_line(&mut chart, run, &line, rgb(line.colour), 2)?;
        }
        if let Some((_, cells)) = &self.reference {
            for run in upright_runs(cells) {
                styled_line(&mut chart, run, &style::BLACK, BLACK, 2)?;
            }
        }
        let (x0, x1) = self.axis.range();
        let half = (x1 - x0) / self.cells.len().max(1) as f64 / 2.0;
        for &(x, class, theta) in &self.cells {
            match class_style(class).filter(|_| class != CellClass::NoUplift) {
                // Overturned or failed: a box of its class in the top row.
                Some(s) => {
                    let y = top / 1.12;
                    chart
                        .draw_series(std::iter::once(Rectangle::new(
                            [(x - half, y * 1.02), (x + half, y * 1.09)],
                            rgb(s.fill).filled(),
                        )))
                        .map_err(fail)?;
                }
                None => {
                    mark_at(&chart, line.marker, (x, theta), 4, rgb(line.colour), true)?;
                }
            }
        }
        Ok(())
    }
}

fn line_cells(sweep: &Sweep, cells: &[Cell]) -> LineCells {
    let mut out: LineCells = cells
        .iter()
        .map(|c| (sweep.values(c.index)[0], c.class, c.max_theta_over_alpha))
        .collect();
    out.sort_by(|a, b| a.0.total_cmp(&b.0));
    out
}

/// The (value, max θ/α) runs of cells that stayed upright, split where a cell between them did
/// not.
fn upright_runs(cells: &[(f64, CellClass, f64)]) -> Lines {
    let mut runs = vec![Vec::new()];
    for &(x, class, theta) in cells {
        if overturned(class) == Some(false) {
            if let Some(run) = runs.last_mut() {
                run.push((x, theta));
            }
        } else if runs.last().is_some_and(|r| !r.is_empty()) {
            runs.push(Vec::new());
        }
    }
    runs.retain(|r| r.len() > 1);
    runs
}

/// A curve of points (a batch's fraction overturned against the scale factor).
pub struct CurvePanel {
    pub title: Option<String>,
    pub labels: (String, String),
    pub points: Vec<(f64, f64)>,
    pub y: (f64, f64),
}

impl CurvePanel {
    pub(super) fn legend(&self) -> Vec<LegendItem> {
        Vec::new()
    }

    pub(super) fn draw(&self, area: &Area<'_>) -> Result<(), String> {
        let x_hi = self.points.iter().map(|p| p.0).fold(0.0, f64::max) * 1.05;
        let mut chart = axes(
            area,
            self.title.as_deref(),
            (0.0, x_hi.max(1e-9)),
            self.y,
            (&self.labels.0, &self.labels.1),
            true,
        )?;
        let line = style::LINES[0];
        styled_line(&mut chart, self.points.clone(), &line, rgb(line.colour), 2)?;
        for &p in &self.points {
            mark_at(&chart, line.marker, p, 4, rgb(line.colour), true)?;
        }
        Ok(())
    }
}
