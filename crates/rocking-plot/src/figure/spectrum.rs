//! The rocking spectrum of a two-axis sweep (the paper's Figs 6-8): survivors shaded by max θ/α
//! on the figure's one colour scale (colour_bar.rs), the overturning classes filled and hatched,
//! a line between overturned and upright cells. The boundaries of several structures are in
//! boundary_panel.rs, one-axis sweeps in line_panel.rs.

use crate::style::{self, ClassStyle, LineStyle};
use plotters::prelude::*;
use plotters::style::colors::colormaps::ViridisRGB;
use rocking_scene::labels;
use rocking_spectra::{Cell, CellClass, Sweep};

use super::boundary::{cell_bounds, cell_edges, polylines};
use crate::chart::{axes, fail, rgb, styled_line, Area, LegendItem};

/// The style of a class that is not a survivor's shade.
pub(super) fn class_style(class: CellClass) -> Option<ClassStyle> {
    match class {
        CellClass::NoUplift => Some(style::NO_UPLIFT),
        CellClass::OverturnedNoImpact => Some(style::OVERTURNED_NO_IMPACT),
        CellClass::OverturnedOneImpact => Some(style::OVERTURNED_ONE_IMPACT),
        CellClass::OverturnedImpacts => Some(style::OVERTURNED_IMPACTS),
        CellClass::BeyondModel => Some(style::BEYOND_MODEL),
        CellClass::Failed => Some(style::FAILED),
        CellClass::Survived => None,
    }
}

/// Whether a class is one of the overturned ones (`None` for a cell without a result: neither).
pub fn overturned(class: CellClass) -> Option<bool> {
    class.overturned()
}

/// An axis of a panel: its scene key (for the label) and its values.
#[derive(Clone, Debug)]
pub struct Axis {
    pub key: String,
    pub values: Vec<f64>,
}

impl Axis {
    pub(super) fn range(&self) -> (f64, f64) {
        let n = self.values.len();
        (
            cell_bounds(&self.values, 0).0,
            cell_bounds(&self.values, n - 1).1,
        )
    }
}

/// The (x, y) axes of the grid of a sweep's last two axes, each cell's grid position, class and
/// shaded value.
type Grid = (Axis, Axis, Vec<(usize, usize, CellClass, f64)>);

/// What a spectrum's shaded cells show on the figure's colour scale.
#[derive(Clone, Debug, PartialEq)]
pub struct Shade {
    /// The colour bar's title.
    pub label: String,
    /// Whether the cells that never uplift are shaded too (else filled as their class).
    pub no_uplift: bool,
}

impl Shade {
    /// The paper's shade: the survivors' max θ/α.
    pub fn theta() -> Shade {
        Shade {
            label: format!("survived: {}", labels::MAX_THETA_OVER_ALPHA),
            no_uplift: false,
        }
    }

    fn shades(&self, class: CellClass) -> bool {
        class == CellClass::Survived || (self.no_uplift && class == CellClass::NoUplift)
    }
}

pub(super) fn grid(sweep: &Sweep, cells: &[Cell], value: impl Fn(&Cell) -> f64) -> Grid {
    let n = sweep.axes.len();
    let (ax, ay) = (&sweep.axes[n - 2], &sweep.axes[n - 1]);
    let (nx, ny) = (ax.values.len(), ay.values.len());
    let cells = cells
        .iter()
        .map(|c| ((c.index / ny) % nx, c.index % ny, c.class, value(c)))
        .collect();
    let axis = |a: &rocking_spectra::Axis| Axis {
        key: a.key.clone(),
        values: a.values.clone(),
    };
    (axis(ax), axis(ay), cells)
}

/// Polylines in the axes' values.
pub(super) type Lines = Vec<Vec<(f64, f64)>>;

/// A one-axis sweep's cells: (value, class, max θ/α) by increasing value.
pub(super) type LineCells = Vec<(f64, CellClass, f64)>;

/// The lines between the cells of a grid on which `side` differs (`None`: a cell on neither).
fn boundary_lines(g: &Grid, side: impl Fn(CellClass) -> Option<bool>) -> Lines {
    let (x, y, cells) = g;
    let mut sides = vec![vec![None; y.values.len()]; x.values.len()];
    for &(i, j, class, _) in cells {
        sides[i][j] = side(class);
    }
    polylines(&cell_edges(&sides, &x.values, &y.values))
}

/// Whether a cell uplifted (`None` for a failed cell), for the line around the cells that never
/// did.
fn uplifted(class: CellClass) -> Option<bool> {
    match class {
        CellClass::BeyondModel | CellClass::Failed => None,
        CellClass::NoUplift => Some(false),
        _ => Some(true),
    }
}

/// The line between the cells that uplifted and those that never did (dotted).
const UPLIFT_LINE: LineStyle = LineStyle {
    dash: Some((3, 4)),
    ..style::BLACK
};

/// The legend's entry for the shaded cells whose value is unbounded.
pub const UNBOUNDED_LABEL: &str = "unbounded (inf): top of the colour bar";

/// A rocking spectrum panel.
pub struct SpectrumPanel {
    pub title: Option<String>,
    grid: Grid,
    shade: Shade,
    boundary: Lines,
    /// Around the cells that never uplift, where their class is not filled (dotted).
    uplift: Lines,
    /// A reference structure's boundary (dashed), with its legend text.
    reference: Option<(String, Lines)>,
    /// A value marked on the colour bar, with its text: θ_cr/α of the structure, or 1 for a
    /// ratio to the fixed base.
    pub mark: Option<(f64, String)>,
    /// Contours of the shaded value: the level, its legend text, its dash, and the cell edges
    /// between shaded cells below the level and those at or above it.
    contours: Vec<(f64, String, (u32, u32), Lines)>,
}

/// The dashes of a spectrum's contours, in order (the overturning boundary is solid, the
/// no-uplift line dotted 3/4): long dashes, then short.
pub const CONTOUR_DASHES: [(u32, u32); 2] = [(14, 6), (6, 4)];

impl SpectrumPanel {
    /// The panel of a sweep's cells over its last two axes, survivors shaded by max θ/α.
    pub fn new(sweep: &Sweep, cells: &[Cell]) -> SpectrumPanel {
        SpectrumPanel::shaded(
            grid(sweep, cells, |c| c.max_theta_over_alpha),
            Shade::theta(),
        )
    }

    /// The panel of a sweep's reported quantity `k` (of [`Sweep::reported`], labelled `label`):
    /// every upright cell shaded by its value, a dotted line around those that never uplift.
    pub fn reported(sweep: &Sweep, cells: &[Cell], k: usize, label: &str) -> SpectrumPanel {
        let value = |c: &Cell| c.reported.get(k).copied().flatten().unwrap_or(f64::NAN);
        let shade = Shade {
            label: label.to_string(),
            no_uplift: true,
        };
        let mut panel = SpectrumPanel::shaded(grid(sweep, cells, value), shade);
        panel.uplift = boundary_lines(&panel.grid, uplifted);
        panel
    }

    fn shaded(grid: Grid, shade: Shade) -> SpectrumPanel {
        SpectrumPanel {
            title: None,
            boundary: boundary_lines(&grid, overturned),
            uplift: Vec::new(),
            grid,
            shade,
            reference: None,
            mark: None,
            contours: Vec::new(),
        }
    }

    /// Adds the contour of the shaded value at `level` (`label` in the legend): the cell edges
    /// between shaded cells whose value is below it and those at or above it (an unbounded value
    /// is above every level; a cell not shaded or without a value borders nothing). The `k`-th
    /// contour takes the `k`-th of [`CONTOUR_DASHES`].
    pub fn with_contour(mut self, level: f64, label: &str) -> SpectrumPanel {
        let (x, y, cells) = &self.grid;
        let mut sides = vec![vec![None; y.values.len()]; x.values.len()];
        for &(i, j, class, value) in cells {
            if self.shade.shades(class) && !value.is_nan() {
                sides[i][j] = Some(value >= level);
            }
        }
        let lines = polylines(&cell_edges(&sides, &x.values, &y.values));
        let dash = CONTOUR_DASHES[self.contours.len() % CONTOUR_DASHES.len()];
        self.contours.push((level, label.to_string(), dash, lines));
        self
    }

    /// The contour lines at `level`, if the panel has that contour.
    #[cfg(test)]
    pub fn contour(&self, level: f64) -> Option<&Lines> {
        self.contours.iter().find(|c| c.0 == level).map(|c| &c.3)
    }

    /// Draws a reference structure's overturning boundary over it, dashed.
    pub fn with_reference(mut self, label: &str, sweep: &Sweep, cells: &[Cell]) -> SpectrumPanel {
        let lines = boundary_lines(&grid(sweep, cells, |_| 0.0), overturned);
        self.reference = Some((label.to_string(), lines));
        self
    }

    /// The finite values of the shaded cells.
    fn shaded_values(&self) -> impl Iterator<Item = f64> + '_ {
        self.grid
            .2
            .iter()
            .filter(|c| self.shade.shades(c.2) && c.3.is_finite())
            .map(|c| c.3)
    }

    /// The largest finite value of the shaded cells.
    pub(super) fn top_of_shaded(&self) -> f64 {
        self.shaded_values().fold(1e-9, f64::max)
    }

    /// How many shaded cells lie above `top` (drawn in the top colour of a scale set below them).
    pub(super) fn count_above(&self, top: f64) -> usize {
        self.shaded_values().filter(|&v| v > top).count()
    }

    /// The bottom of the colour scale: 0, or the lowest shaded value where it is negative.
    pub(super) fn bottom_of_shaded(&self) -> f64 {
        self.shaded_values().fold(0.0, f64::min)
    }

    pub(super) fn shade(&self) -> &Shade {
        &self.shade
    }

    pub(super) fn colour_bar_mark(&self) -> Option<(f64, String)> {
        self.mark.clone()
    }

    pub(super) fn legend(&self) -> Vec<LegendItem> {
        // Survivors are on the colour bar.
        let mut items: Vec<LegendItem> = CellClass::ALL
            .into_iter()
            .filter(|k| *k != CellClass::Survived)
            .filter(|k| !self.shade.shades(*k) && self.grid.2.iter().any(|c| c.2 == *k))
            .filter_map(class_style)
            .map(|s| LegendItem::Fill(s.fill, s.label.to_string()))
            .collect();
        // An unbounded value (`inf` in cells.csv: the required friction once R_v < 0) is drawn
        // in the colour of the bar's top, above every finite value.
        if self
            .grid
            .2
            .iter()
            .any(|c| self.shade.shades(c.2) && c.3 == f64::INFINITY)
        {
            let top = ViridisRGB.get_color_normalized(1.0, 0.0, 1.0);
            items.push(LegendItem::Fill(
                [top.0, top.1, top.2],
                UNBOUNDED_LABEL.to_string(),
            ));
        }
        if self
            .grid
            .2
            .iter()
            .any(|c| self.shade.shades(c.2) && c.3.is_nan())
        {
            items.push(LegendItem::Fill(
                style::NO_VALUE.fill,
                style::NO_VALUE.label.to_string(),
            ));
        }
        if !self.boundary.is_empty() {
            items.push(LegendItem::Rule(
                [0, 0, 0],
                None,
                "overturned | upright".to_string(),
            ));
        }
        if !self.uplift.is_empty() {
            items.push(LegendItem::Rule(
                [0, 0, 0],
                UPLIFT_LINE.dash,
                "uplift | no uplift".to_string(),
            ));
        }
        if let Some((label, _)) = &self.reference {
            items.push(LegendItem::Rule(
                [0, 0, 0],
                style::BLACK.dash,
                format!("overturned | upright, {label}"),
            ));
        }
        for (_, label, dash, lines) in &self.contours {
            if !lines.is_empty() {
                items.push(LegendItem::Rule([0, 0, 0], Some(*dash), label.clone()));
            }
        }
        items
    }

    /// The panel's axis labels (x, y).
    pub(super) fn axis_labels(&self) -> (String, String) {
        (
            labels::axis_label(&self.grid.0.key),
            labels::axis_label(&self.grid.1.key),
        )
    }

    /// Draws the panel, shading on the colour scale `scale` (bottom, top).
    pub(super) fn draw(&self, area: &Area<'_>, scale: (f64, f64)) -> Result<(), String> {
        let (bottom, top) = scale;
        let (x, y, cells) = &self.grid;
        let mut chart = axes(
            area,
            self.title.as_deref(),
            x.range(),
            y.range(),
            (&labels::axis_label(&x.key), &labels::axis_label(&y.key)),
            false,
        )?;
        // Cells of one class next to each other in a column are one rectangle.
        let mut sorted = cells.clone();
        sorted.sort_by_key(|c| (c.0, c.1));
        let mut k = 0;
        while k < sorted.len() {
            let (i, j, class, value) = sorted[k];
            let mut last = j;
            let shaded = self.shade.shades(class);
            if !shaded {
                while k + 1 < sorted.len()
                    && sorted[k + 1].0 == i
                    && sorted[k + 1].1 == last + 1
                    && sorted[k + 1].2 == class
                {
                    k += 1;
                    last += 1;
                }
            }
            let fill = match class_style(class) {
                Some(s) if !shaded => rgb(s.fill),
                // A shaded cell whose run has no value (an event that did not happen).
                _ if value.is_nan() => rgb(style::NO_VALUE.fill),
                _ => ViridisRGB.get_color_normalized(value.clamp(bottom, top), bottom, top),
            };
            let (x0, x1) = cell_bounds(&x.values, i);
            let (y0, _) = cell_bounds(&y.values, j);
            let (_, y1) = cell_bounds(&y.values, last);
            chart
                .draw_series(std::iter::once(Rectangle::new(
                    [(x0, y0), (x1, y1)],
                    fill.filled(),
                )))
                .map_err(fail)?;
            k += 1;
        }
        for line in &self.boundary {
            styled_line(&mut chart, line.clone(), &solid(), BLACK, 2)?;
        }
        for line in &self.uplift {
            styled_line(&mut chart, line.clone(), &UPLIFT_LINE, BLACK, 2)?;
        }
        if let Some((_, lines)) = &self.reference {
            for line in lines {
                styled_line(&mut chart, line.clone(), &style::BLACK, BLACK, 2)?;
            }
        }
        // Contours: black dashes on a white halo, to read on every shade.
        for (_, _, dash, lines) in &self.contours {
            for line in lines {
                styled_line(&mut chart, line.clone(), &solid(), WHITE, 4)?;
                let dashed = LineStyle {
                    dash: Some(*dash),
                    ..style::BLACK
                };
                styled_line(&mut chart, line.clone(), &dashed, BLACK, 2)?;
            }
        }
        Ok(())
    }
}

/// A solid black line (the overturning boundary of a spectrum).
pub(super) fn solid() -> LineStyle {
    LineStyle {
        dash: None,
        ..style::BLACK
    }
}
