//! Sweep panels: the rocking spectrum of a two-axis sweep (the paper's Figs 6-8: survivors shaded
//! by max θ/α on the figure's one colour scale, the overturning classes filled and hatched, a
//! line between overturned and upright cells), the overturning boundaries of several structures
//! (Fig. 9: per ω_p/p the lowest amplitude that overturns, each structure in its own colour, dash
//! and marker, the survival islands above it marked apart) and the line plot of a one-axis
//! sweep; the colour bar of the survivors with θ_cr/α marked on it.

use crate::style::{self, ClassStyle, LineStyle};
use crate::text::{rich, tick};
use plotters::prelude::*;
use plotters::style::colors::colormaps::ViridisRGB;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use rocking_scene::labels;
use rocking_spectra::{Cell, CellClass, Sweep};

use super::boundary::{cell_bounds, cell_edges, lowest_overturning, polylines, Lowest};
use crate::chart::{
    axes, fail, line_height, mark_at, rgb, styled_line, Area, LegendItem, Type, LEGEND, TICKS,
};

/// The style of a class that is not a survivor's shade.
fn class_style(class: CellClass) -> Option<ClassStyle> {
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
    fn range(&self) -> (f64, f64) {
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

fn grid(sweep: &Sweep, cells: &[Cell], value: impl Fn(&Cell) -> f64) -> Grid {
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
type Lines = Vec<Vec<(f64, f64)>>;

/// A one-axis sweep's cells: (value, class, max θ/α) by increasing value.
type LineCells = Vec<(f64, CellClass, f64)>;

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
        let value = |c: &Cell| c.reported.get(k).copied().unwrap_or(f64::NAN);
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
        let mut items: Vec<LegendItem> = [
            CellClass::NoUplift,
            CellClass::OverturnedNoImpact,
            CellClass::OverturnedOneImpact,
            CellClass::OverturnedImpacts,
            CellClass::BeyondModel,
            CellClass::Failed,
        ]
        .into_iter()
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
fn solid() -> LineStyle {
    LineStyle {
        dash: None,
        ..style::BLACK
    }
}

/// The colour bar of the shaded cells (`scale`: bottom to top, titled `label`) with `marks`
/// (θ_cr/α), at `y` in the legend column; returns the y below it.
pub(super) fn colour_bar(
    side: &Area<'_>,
    label: &str,
    scale: (f64, f64),
    marks: &[(f64, String)],
    y: i32,
) -> Result<i32, String> {
    let (bottom, top) = scale;
    let span = top - bottom;
    let height = 330;
    let (width, _) = side.dim_in_pixel();
    let area = side.clone().shrink((0, y), (width, height));
    area.draw(&Text::new(
        rich(label),
        (10, 4),
        ("sans-serif", LEGEND).into_font(),
    ))
    .map_err(fail)?;
    let bar = area.clone().shrink((10, 30), (34, height - 44));
    let mut chart = ChartBuilder::on(&bar)
        .set_label_area_size(LabelAreaPosition::Right, 0)
        .build_cartesian_2d(0.0..1.0, bottom..top)
        .map_err(fail)?;
    let steps = 120;
    chart
        .draw_series((0..steps).map(|k| {
            let (a, b) = (
                bottom + span * k as f64 / steps as f64,
                bottom + span * (k + 1) as f64 / steps as f64,
            );
            Rectangle::new(
                [(0.0, a), (1.0, b)],
                ViridisRGB
                    .get_color_normalized((a + b) / 2.0, bottom, top)
                    .filled(),
            )
        }))
        .map_err(fail)?;
    // Ticks on the right of the bar.
    let font = ("sans-serif", TICKS)
        .into_font()
        .into_text_style(&area)
        .pos(Pos::new(HPos::Left, VPos::Center));
    let (_, bar_h) = bar.dim_in_pixel();
    let to_y = |v: f64| 30 + ((top - v) / span * bar_h as f64).round() as i32;
    for v in nice_ticks(bottom, top) {
        let py = to_y(v);
        area.draw(&PathElement::new(vec![(44, py), (50, py)], BLACK))
            .map_err(fail)?;
        area.draw_text(&tick(v), &font, (54, py)).map_err(fail)?;
    }
    // Marks from the top down; a label too close to the one above moves below it.
    let mut shown: Vec<&(f64, String)> = marks
        .iter()
        .filter(|m| (bottom..=top).contains(&m.0))
        .collect();
    shown.sort_by(|a, b| b.0.total_cmp(&a.0));
    let mut last_text = i32::MIN / 2;
    for (v, text) in shown {
        let py = to_y(*v);
        let ty = py.max(last_text + line_height(LEGEND) as i32);
        last_text = ty;
        area.draw(&PathElement::new(
            vec![(6, py), (48, py)],
            BLACK.stroke_width(3),
        ))
        .map_err(fail)?;
        area.draw(&PathElement::new(
            vec![(10, py), (44, py)],
            WHITE.stroke_width(1),
        ))
        .map_err(fail)?;
        area.draw_text(&rich(text), &font, (84, ty)).map_err(fail)?;
    }
    Ok(y + height)
}

/// The width of the colour bar's block at the left of a print figure's legend band (50 mm).
pub(super) const PRINT_BAR_WIDTH: u32 = 400;

/// The height of [`colour_bar_band`] with `marks` marks.
pub(super) fn colour_bar_band_height(marks: usize) -> u32 {
    let t = Type::print();
    let line = t.line(t.legend);
    4 + line + 4 + PRINT_BAR + 4 + t.line(t.ticks) + marks as u32 * line + 6
}

/// The bar's thickness at print size (3 mm).
const PRINT_BAR: u32 = 24;

/// The colour bar at print size, across the top-left of the legend band: its title, the bar,
/// its ticks under it, and each mark (θ_cr/α) as a line across the bar, labelled under the
/// ticks from the mark rightwards (one line per mark).
pub(super) fn colour_bar_band(
    area: &Area<'_>,
    label: &str,
    scale: (f64, f64),
    marks: &[(f64, String)],
) -> Result<(), String> {
    let t = Type::print();
    let (bottom, top) = scale;
    let span = top - bottom;
    let line = t.line(t.legend) as i32;
    let (width, _) = area.dim_in_pixel();
    let left = 12;
    let right = width as i32 - 40;
    let to_x = |v: f64| left + ((v - bottom) / span * f64::from(right - left)).round() as i32;
    let text = |size: f64, h: HPos| {
        ("sans-serif", size)
            .into_font()
            .into_text_style(area)
            .pos(Pos::new(h, VPos::Top))
    };
    area.draw_text(&rich(label), &text(t.legend, HPos::Left), (left, 4))
        .map_err(fail)?;
    let y0 = 4 + line + 4;
    let y1 = y0 + PRINT_BAR as i32;
    let steps = 200;
    for k in 0..steps {
        let (a, b) = (
            left + (right - left) * k / steps,
            left + (right - left) * (k + 1) / steps,
        );
        let v = bottom + span * (f64::from(k) + 0.5) / f64::from(steps);
        area.draw(&Rectangle::new(
            [(a, y0), (b, y1)],
            ViridisRGB.get_color_normalized(v, bottom, top).filled(),
        ))
        .map_err(fail)?;
    }
    area.draw(&Rectangle::new([(left, y0), (right, y1)], BLACK))
        .map_err(fail)?;
    let ticks = text(t.ticks, HPos::Center);
    for v in nice_ticks(bottom, top) {
        let px = to_x(v);
        area.draw(&PathElement::new(vec![(px, y1), (px, y1 + 5)], BLACK))
            .map_err(fail)?;
        area.draw_text(&tick(v), &ticks, (px, y1 + 6))
            .map_err(fail)?;
    }
    let mut shown: Vec<&(f64, String)> = marks
        .iter()
        .filter(|m| (bottom..=top).contains(&m.0))
        .collect();
    shown.sort_by(|a, b| a.0.total_cmp(&b.0));
    let labels = text(t.legend, HPos::Left);
    let mut y = y1 + 6 + t.line(t.ticks) as i32;
    let char_w = 0.56 * t.legend / 1.24;
    for (v, label) in shown {
        let px = to_x(*v);
        area.draw(&PathElement::new(
            vec![(px, y0 - 3), (px, y1 + 3)],
            BLACK.stroke_width(3),
        ))
        .map_err(fail)?;
        area.draw(&PathElement::new(
            vec![(px, y0), (px, y1)],
            WHITE.stroke_width(1),
        ))
        .map_err(fail)?;
        let label = format!("↑ {label}");
        let w = (crate::text::plain(&rich(&label)).chars().count() as f64 * char_w) as i32;
        let x = (px - (char_w / 2.0) as i32)
            .min(width as i32 - w - 4)
            .max(0);
        area.draw_text(&rich(&label), &labels, (x, y))
            .map_err(fail)?;
        y += line;
    }
    Ok(())
}

/// About five round tick values from `bottom` to `top`.
fn nice_ticks(bottom: f64, top: f64) -> Vec<f64> {
    let raw = (top - bottom) / 5.0;
    let mag = 10f64.powf(raw.log10().floor());
    let step = [1.0, 2.0, 2.5, 5.0, 10.0]
        .iter()
        .map(|m| m * mag)
        .find(|s| *s >= raw)
        .unwrap_or(10.0 * mag);
    let first = (bottom / step * (1.0 - 1e-9)).ceil() as i64;
    (first..)
        .map(|k| k as f64 * step)
        .take_while(|v| *v <= top * (1.0 + 1e-9) + 1e-12 * step)
        .collect()
}

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
        for class in [
            CellClass::OverturnedNoImpact,
            CellClass::OverturnedOneImpact,
            CellClass::OverturnedImpacts,
            CellClass::BeyondModel,
            CellClass::Failed,
        ] {
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
