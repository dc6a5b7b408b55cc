//! The overturning boundaries of several structures (Fig. 9): per ω_p/p the lowest amplitude
//! that overturns, each structure in its own colour, dash and marker, and the safe bands above
//! it marked apart.

use crate::style::LineStyle;
use plotters::prelude::*;
use rocking_scene::labels;
use rocking_spectra::{Cell, Sweep};

use super::boundary::{cell_bounds, lowest_overturning, Lowest};
use super::spectrum::{grid, overturned, Axis};
use crate::chart::{axes, fail, mark_at, rgb, styled_line, Area, LegendItem};

/// One structure's overturning boundary on Fig. 9: the lowest overturning amplitude per ω_p/p
/// and the upright cells above it.
pub struct Structure {
    pub label: String,
    pub style: LineStyle,
    /// (ω_p/p, lowest overturning amplitude) by increasing ω_p/p, in pieces between the columns
    /// where nothing overturned.
    pub line: Vec<Vec<(f64, f64)>>,
    /// The band of upright cells above the line (the safe band, which in the paper's spectra
    /// lies between overturning after impacts below it and overturning without impact above):
    /// per ω_p/p where the column has an upright cell above the line, (ω_p/p, the band's bottom,
    /// its top), in pieces of neighbouring columns. The bottom is `refine`d between the lowest
    /// upright cell above the line and the overturned cell below it, the top between the highest
    /// upright cell and the overturned one above it (or that cell, at the grid's top).
    pub band: Vec<Vec<(f64, f64, f64)>>,
}

impl Structure {
    /// The boundary of the structure whose cells are `cells` (over the sweep's last two axes):
    /// per column, the lowest overturning amplitude `refine(x, upright, overturned)` finds
    /// between the cells that bracket it (or the lowest cell, when it already overturned).
    pub fn new(
        label: String,
        style: LineStyle,
        sweep: &Sweep,
        cells: &[Cell],
        mut refine: impl FnMut(f64, f64, f64) -> f64,
    ) -> Structure {
        let (x, y, grid) = grid(sweep, cells, |c| c.max_theta_over_alpha);
        let mut line = vec![Vec::new()];
        let mut band = vec![Vec::new()];
        for (i, &xv) in x.values.iter().enumerate() {
            let mut column: Vec<(f64, bool)> = grid
                .iter()
                .filter(|c| c.0 == i)
                .filter_map(|c| overturned(c.2).map(|o| (y.values[c.1], o)))
                .collect();
            column.sort_by(|a, b| a.0.total_cmp(&b.0));
            let lowest = match lowest_overturning(&column) {
                Lowest::Never => {
                    if line.last().is_some_and(|l| !l.is_empty()) {
                        line.push(Vec::new());
                    }
                    if band.last().is_some_and(|b| !b.is_empty()) {
                        band.push(Vec::new());
                    }
                    continue;
                }
                Lowest::AtOrBelow(a) => a,
                Lowest::Between(lo, hi) => refine(xv, lo, hi),
            };
            if let Some(l) = line.last_mut() {
                l.push((xv, lowest));
            }
            // The lowest and the highest upright cell above the line, each with its overturned
            // neighbour (below the lowest: the line's own cell or one above it; above the
            // highest: none at the grid's top).
            let first = column.iter().position(|c| !c.1 && c.0 > lowest);
            let last = column.iter().rposition(|c| !c.1 && c.0 > lowest);
            match (first, last) {
                (Some(a), Some(k)) => {
                    let lower = match a.checked_sub(1).map(|b| column[b]) {
                        Some(below) if below.1 => refine(xv, column[a].0, below.0),
                        _ => column[a].0,
                    };
                    let upper = match column.get(k + 1) {
                        Some(next) => refine(xv, column[k].0, next.0),
                        None => column[k].0,
                    };
                    if let Some(b) = band.last_mut() {
                        b.push((xv, lower, upper));
                    }
                }
                _ => {
                    if band.last().is_some_and(|b| !b.is_empty()) {
                        band.push(Vec::new());
                    }
                }
            }
        }
        line.retain(|l| !l.is_empty());
        band.retain(|b| !b.is_empty());
        Structure {
            label,
            style,
            line,
            band,
        }
    }
}

/// The opacity of a structure's safe band over the white panel.
const BAND_OPACITY: f64 = 0.28;
/// The band's legend box: a mid grey at that opacity over white.
const BAND_LEGEND: [u8; 3] = [200, 200, 200];

/// Overturning boundaries of several structures on shared axes.
pub struct BoundaryPanel {
    pub title: Option<String>,
    pub x: Axis,
    pub y: Axis,
    pub structures: Vec<Structure>,
    /// How the lines were found, for the legend's heading.
    pub method: String,
}

impl BoundaryPanel {
    /// The panel's axis labels (x, y).
    pub(super) fn axis_labels(&self) -> (String, String) {
        (
            labels::axis_label(&self.x.key),
            labels::axis_label(&self.y.key),
        )
    }

    pub(super) fn legend(&self) -> Vec<LegendItem> {
        let mut items = vec![LegendItem::Heading(self.method.clone())];
        for s in &self.structures {
            items.push(LegendItem::Line(s.style, s.label.clone()));
        }
        if self.structures.iter().any(|s| !s.band.is_empty()) {
            items.push(LegendItem::Fill(
                BAND_LEGEND,
                "tinted band: upright above the line (the safe band)".to_string(),
            ));
        }
        items
    }

    pub(super) fn draw(&self, area: &Area<'_>) -> Result<(), String> {
        let mut chart = axes(
            area,
            self.title.as_deref(),
            self.x.range(),
            self.y.range(),
            (
                &labels::axis_label(&self.x.key),
                &labels::axis_label(&self.y.key),
            ),
            true,
        )?;
        let n = self.structures.len().max(1);
        for s in &self.structures {
            let colour = rgb(s.style.colour);
            for piece in &s.band {
                // One column alone is a band half a cell wide either side.
                let half = if piece.len() == 1 {
                    let v = &self.x.values;
                    let (a, b) =
                        cell_bounds(v, v.iter().position(|&x| x == piece[0].0).unwrap_or(0));
                    (b - a) / 2.0
                } else {
                    0.0
                };
                let mut outline: Vec<(f64, f64)> = Vec::new();
                if half > 0.0 {
                    let (x, lo, hi) = piece[0];
                    outline.extend([
                        (x - half, lo),
                        (x + half, lo),
                        (x + half, hi),
                        (x - half, hi),
                    ]);
                } else {
                    outline.extend(piece.iter().map(|p| (p.0, p.1)));
                    outline.extend(piece.iter().rev().map(|p| (p.0, p.2)));
                }
                chart
                    .draw_series(std::iter::once(Polygon::new(
                        outline,
                        colour.mix(BAND_OPACITY).filled(),
                    )))
                    .map_err(fail)?;
                // Its borders: thin solid lines in the structure's colour.
                let thin = LineStyle {
                    dash: None,
                    ..s.style
                };
                for k in [1, 2] {
                    let edge: Vec<(f64, f64)> = if half > 0.0 {
                        let p = piece[0];
                        let v = if k == 1 { p.1 } else { p.2 };
                        vec![(p.0 - half, v), (p.0 + half, v)]
                    } else {
                        piece
                            .iter()
                            .map(|p| (p.0, if k == 1 { p.1 } else { p.2 }))
                            .collect()
                    };
                    styled_line(&mut chart, edge, &thin, colour, 1)?;
                }
            }
        }
        for (k, s) in self.structures.iter().enumerate() {
            let colour = rgb(s.style.colour);
            for piece in &s.line {
                styled_line(&mut chart, piece.clone(), &s.style, colour, 2)?;
            }
            // Markers along the line, staggered between structures so they do not cover each
            // other.
            let all: Vec<(f64, f64)> = s.line.iter().flatten().copied().collect();
            let every = (all.len() / 7).max(1);
            let offset = k * every / n;
            for &p in all.iter().skip(offset).step_by(every) {
                mark_at(&chart, s.style.marker, p, 5, colour, true)?;
            }
        }
        Ok(())
    }
}

impl BoundaryPanel {
    /// The panel of structures drawn over the axes of `sweep`'s last two.
    pub fn over(sweep: &Sweep, structures: Vec<Structure>, method: String) -> BoundaryPanel {
        let n = sweep.axes.len();
        let axis = |a: &rocking_spectra::Axis| Axis {
            key: a.key.clone(),
            values: a.values.clone(),
        };
        BoundaryPanel {
            title: None,
            x: axis(&sweep.axes[n - 2]),
            y: axis(&sweep.axes[n - 1]),
            structures,
            method,
        }
    }
}
