//! Sweep figures: the rocking spectrum of a two-axis sweep (the paper's Figs 6-8: max θ/α of the
//! survivors on a continuous colour scale with its colour bar, the overturning classes in their
//! own colours), the overturning boundaries of a three-axis sweep (Fig. 9: one contour per value
//! of the first axis, by marching squares) and the line plot of a one-axis sweep, each with the
//! reference structure's boundary (or line) dashed when `[sweep] reference` asks for it. Legends
//! sit beside the plot area, never on the data.

use std::path::{Path, PathBuf};

use plotters::coord::Shift;
use plotters::element::DashedPathElement;
use plotters::prelude::*;
use plotters::style::colors::colormaps::ViridisRGB;
use rocking_scene::labels;
use rocking_spectra::{Cell, CellClass, Sweep};

use super::contour::{contour, polylines, Segment};
use super::{register, render_pair, titled};
use rocking_scene::SceneError;

/// Figure size (pixels) and the width of the legend column on its right.
const SIZE: (u32, u32) = (1040, 760);
const LEGEND: u32 = 270;

/// The colour of each class that is not a survivor's shade, with its legend text.
const CLASSES: &[(CellClass, RGBColor, &str)] = &[
    (CellClass::NoUplift, RGBColor(225, 225, 225), "no uplift"),
    (
        CellClass::OverturnedNoImpact,
        RGBColor(165, 15, 35),
        "overturned, no impact",
    ),
    (
        CellClass::OverturnedOneImpact,
        RGBColor(240, 120, 60),
        "overturned after one impact",
    ),
    (
        CellClass::OverturnedImpacts,
        RGBColor(250, 190, 215),
        "overturned after impacts",
    ),
    (
        CellClass::Failed,
        RGBColor(0, 0, 0),
        "failed (see meta.json)",
    ),
];

/// Line colours of the boundaries of several structures (Fig. 9).
const LINES: &[RGBColor] = &[
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(148, 103, 189),
    RGBColor(255, 127, 14),
    RGBColor(23, 190, 207),
    RGBColor(140, 86, 75),
    RGBColor(0, 0, 0),
];

/// A reference structure's cells over the axes the figure shows (`[sweep] reference`).
pub struct Reference<'a> {
    /// Legend text, e.g. "rigid column".
    pub label: &'a str,
    pub sweep: &'a Sweep,
    pub cells: &'a [Cell],
}

/// How a legend entry is drawn.
#[derive(Clone, Copy)]
enum Swatch {
    Box,
    Line,
    Dashed,
}

/// The reference's style: black, dashed.
const DASH: (u32, u32, u32) = (9, 6, 3);

/// Draws `points` dashed in black (the reference).
fn dashed<DB: DrawingBackend>(
    chart: &mut ChartContext<
        '_,
        DB,
        Cartesian2d<plotters::coord::types::RangedCoordf64, plotters::coord::types::RangedCoordf64>,
    >,
    lines: Vec<Vec<(f64, f64)>>,
) -> Result<(), String> {
    let (size, gap, width) = DASH;
    chart
        .draw_series(
            lines
                .into_iter()
                .map(|l| DashedPathElement::new(l, size, gap, BLACK.stroke_width(width))),
        )
        .map_err(|e| e.to_string())?;
    Ok(())
}

/// Whether a class is one of the overturned ones.
fn overturned(class: CellClass) -> bool {
    matches!(
        class,
        CellClass::OverturnedNoImpact
            | CellClass::OverturnedOneImpact
            | CellClass::OverturnedImpacts
    )
}

/// The colour of a cell: a survivor's max θ/α on the viridis scale from 0 to `top`, another class
/// its own colour.
fn cell_colour(c: &Cell, top: f64) -> RGBColor {
    match c.class {
        CellClass::Survived => ViridisRGB.get_color_normalized(c.max_theta_over_alpha, 0.0, top),
        other => CLASSES
            .iter()
            .find(|(k, _, _)| *k == other)
            .map_or(RGBColor(0, 0, 0), |(_, colour, _)| *colour),
    }
}

/// The range an axis's cells cover (half a step beyond the first and last values).
fn span(v: &[f64]) -> (f64, f64, f64) {
    let (lo, hi) = v
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| {
            (a.min(x), b.max(x))
        });
    let h = if v.len() > 1 {
        (hi - lo) / (v.len() - 1) as f64 / 2.0
    } else {
        0.5_f64.max(lo.abs() * 0.05)
    };
    (lo - h, hi + h, h)
}

/// The largest max θ/α of the survivors (the top of the colour scale).
fn top_of_survivors(cells: &[Cell]) -> f64 {
    cells
        .iter()
        .filter(|c| c.class == CellClass::Survived)
        .map(|c| c.max_theta_over_alpha)
        .fold(1e-9, f64::max)
}

/// Legend entries drawn as swatches (a filled box or a line) with text, from the top of `area`.
fn legend<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    top: i32,
    items: &[(RGBColor, String, Swatch)],
) -> Result<(), String> {
    let e = |e: DrawingAreaErrorKind<DB::ErrorType>| e.to_string();
    let width = area.dim_in_pixel().0 as usize;
    let mut y = top;
    for (colour, text, swatch) in items {
        match swatch {
            Swatch::Line => {
                area.draw(&PathElement::new(
                    vec![(8, y + 9), (34, y + 9)],
                    colour.stroke_width(3),
                ))
                .map_err(e)?;
            }
            Swatch::Dashed => {
                let (size, gap, width) = DASH;
                area.draw(&DashedPathElement::new(
                    vec![(6, y + 9), (36, y + 9)],
                    size,
                    gap,
                    colour.stroke_width(width),
                ))
                .map_err(e)?;
            }
            Swatch::Box => {
                area.draw(&Rectangle::new([(10, y), (30, y + 18)], colour.filled()))
                    .map_err(e)?;
                area.draw(&Rectangle::new([(10, y), (30, y + 18)], BLACK))
                    .map_err(e)?;
            }
        }
        let lines = super::wrap(text, (width.saturating_sub(48) / 8).max(12));
        for (k, l) in lines.iter().enumerate() {
            area.draw(&Text::new(
                l.clone(),
                (40, y + 2 + 17 * k as i32),
                ("sans-serif", 14).into_font(),
            ))
            .map_err(e)?;
        }
        y += 10 + 17 * lines.len().max(1) as i32;
    }
    Ok(())
}

/// The colour bar of the survivors' max θ/α (0 to `top`) at the top of `area`.
fn colour_bar<DB: DrawingBackend>(area: &DrawingArea<DB, Shift>, top: f64) -> Result<i32, String> {
    let e = |e: DrawingAreaErrorKind<DB::ErrorType>| e.to_string();
    let height = 330;
    let (bar, _) = area.split_vertically(height);
    let mut chart = ChartBuilder::on(&bar)
        .margin_top(30)
        .margin_bottom(10)
        .margin_left(10)
        .margin_right(150)
        .y_label_area_size(0)
        .right_y_label_area_size(50)
        .caption(
            format!("survived: {}", labels::MAX_THETA_OVER_ALPHA),
            ("sans-serif", 15),
        )
        .build_cartesian_2d(0.0..1.0, 0.0..top)
        .map_err(e)?
        .set_secondary_coord(0.0..1.0, 0.0..top);
    chart
        .configure_mesh()
        .disable_mesh()
        .disable_x_axis()
        .disable_y_axis()
        .draw()
        .map_err(e)?;
    chart
        .configure_secondary_axes()
        .label_style(("sans-serif", 13))
        .y_labels(6)
        .draw()
        .map_err(e)?;
    let steps = 120;
    chart
        .draw_series((0..steps).map(|k| {
            let (a, b) = (
                top * k as f64 / steps as f64,
                top * (k + 1) as f64 / steps as f64,
            );
            Rectangle::new(
                [(0.0, a), (1.0, b)],
                ViridisRGB
                    .get_color_normalized((a + b) / 2.0, 0.0, top)
                    .filled(),
            )
        }))
        .map_err(e)?;
    Ok(height)
}

/// A cell's position (i, j) on the grid of the last two axes.
fn grid_position(sweep: &Sweep, index: usize) -> (usize, usize) {
    let n = sweep.axes.len();
    let ny = sweep.axes[n - 1].values.len();
    let nx = sweep.axes[n - 2].values.len();
    ((index / ny) % nx, index % ny)
}

fn axes_chart<'a, DB: DrawingBackend>(
    area: &'a DrawingArea<DB, Shift>,
    sweep: &Sweep,
) -> Result<
    ChartContext<
        'a,
        DB,
        Cartesian2d<plotters::coord::types::RangedCoordf64, plotters::coord::types::RangedCoordf64>,
    >,
    String,
> {
    let e = |e: DrawingAreaErrorKind<DB::ErrorType>| e.to_string();
    let n = sweep.axes.len();
    let (ax, ay) = (&sweep.axes[n - 2], &sweep.axes[n - 1]);
    let (x0, x1, _) = span(&ax.values);
    let (y0, y1, _) = span(&ay.values);
    let mut chart = ChartBuilder::on(area)
        .margin(12)
        .margin_right(24)
        .x_label_area_size(55)
        .y_label_area_size(70)
        .build_cartesian_2d(x0..x1, y0..y1)
        .map_err(e)?;
    chart
        .configure_mesh()
        .disable_mesh()
        .x_desc(labels::axis_label(&ax.key))
        .y_desc(labels::axis_label(&ay.key))
        .label_style(("sans-serif", 15))
        .axis_desc_style(("sans-serif", 19))
        .draw()
        .map_err(e)?;
    Ok(chart)
}

fn draw_spectrum<DB: DrawingBackend>(
    root: DrawingArea<DB, Shift>,
    title: &str,
    sweep: &Sweep,
    cells: &[Cell],
    reference: Option<&Reference>,
) -> Result<(), String> {
    let e = |e: DrawingAreaErrorKind<DB::ErrorType>| e.to_string();
    root.fill(&WHITE).map_err(e)?;
    let root = titled(root, title, 19)?;
    let (plot_area, side) = root.split_horizontally(SIZE.0 - LEGEND);
    let n = sweep.axes.len();
    let (_, _, hx) = span(&sweep.axes[n - 2].values);
    let (_, _, hy) = span(&sweep.axes[n - 1].values);
    let top = top_of_survivors(cells);
    let mut chart = axes_chart(&plot_area, sweep)?;
    chart
        .draw_series(cells.iter().map(|c| {
            let v = sweep.values(c.index);
            Rectangle::new(
                [(v[0] - hx, v[1] - hy), (v[0] + hx, v[1] + hy)],
                cell_colour(c, top).filled(),
            )
        }))
        .map_err(e)?;
    if let Some(r) = reference {
        dashed(&mut chart, reference_boundary(r))?;
    }
    let below = colour_bar(&side, top)?;
    let mut present: Vec<(RGBColor, String, Swatch)> = CLASSES
        .iter()
        .filter(|(k, _, _)| cells.iter().any(|c| c.class == *k))
        .map(|(_, colour, text)| (*colour, text.to_string(), Swatch::Box))
        .collect();
    if let Some(r) = reference {
        present.push((
            BLACK,
            format!("overturning boundary, {}", r.label),
            Swatch::Dashed,
        ));
    }
    legend(&side, below + 10, &present)?;
    root.present().map_err(e)
}

/// The overturning boundary of a reference's two-axis sweep, as polylines.
fn reference_boundary(r: &Reference) -> Vec<Vec<(f64, f64)>> {
    boundaries(r.sweep, r.cells)
        .into_iter()
        .flat_map(|(_, segments)| polylines(&segments))
        .collect()
}

/// The overturning contour of each structure (value of the leading axes) of a sweep of two or
/// more axes, with its legend text (empty for two axes: one structure).
pub fn boundaries(sweep: &Sweep, cells: &[Cell]) -> Vec<(String, Vec<Segment>)> {
    let n = sweep.axes.len();
    let (xs, ys) = (&sweep.axes[n - 2].values, &sweep.axes[n - 1].values);
    let per_structure = xs.len() * ys.len();
    let mut grids: Vec<(String, Vec<Vec<bool>>)> = Vec::new();
    for c in cells {
        let s = c.index / per_structure;
        if grids.len() <= s {
            grids.resize_with(s + 1, || {
                (String::new(), vec![vec![false; ys.len()]; xs.len()])
            });
        }
        let v = sweep.values(c.index);
        grids[s].0 = sweep.axes[..n - 2]
            .iter()
            .zip(&v)
            .map(|(a, &x)| labels::axis_value(&a.key, x))
            .collect::<Vec<_>>()
            .join(", ");
        let (i, j) = grid_position(sweep, c.index);
        grids[s].1[i][j] = overturned(c.class);
    }
    grids
        .into_iter()
        .map(|(name, g)| (name, contour(&g, xs, ys)))
        .collect()
}

fn draw_boundaries<DB: DrawingBackend>(
    root: DrawingArea<DB, Shift>,
    title: &str,
    sweep: &Sweep,
    cells: &[Cell],
    reference: Option<&Reference>,
) -> Result<(), String> {
    let e = |e: DrawingAreaErrorKind<DB::ErrorType>| e.to_string();
    root.fill(&WHITE).map_err(e)?;
    let root = titled(root, title, 19)?;
    let (plot_area, side) = root.split_horizontally(SIZE.0 - LEGEND);
    let mut chart = axes_chart(&plot_area, sweep)?;
    let mut items = Vec::new();
    for (k, (name, segments)) in boundaries(sweep, cells).into_iter().enumerate() {
        let colour = LINES[k % LINES.len()];
        chart
            .draw_series(
                polylines(&segments)
                    .into_iter()
                    .map(|l| PathElement::new(l, colour.stroke_width(3))),
            )
            .map_err(e)?;
        items.push((colour, name, Swatch::Line));
    }
    if let Some(r) = reference {
        dashed(&mut chart, reference_boundary(r))?;
        items.push((BLACK, r.label.to_string(), Swatch::Dashed));
    }
    side.draw(&Text::new(
        "overturning boundary (overturned above):",
        (8, 40),
        ("sans-serif", 14).into_font(),
    ))
    .map_err(e)?;
    legend(&side, 70, &items)?;
    root.present().map_err(e)
}

fn draw_line<DB: DrawingBackend>(
    root: DrawingArea<DB, Shift>,
    title: &str,
    sweep: &Sweep,
    cells: &[Cell],
    reference: Option<&Reference>,
) -> Result<(), String> {
    let e = |e: DrawingAreaErrorKind<DB::ErrorType>| e.to_string();
    root.fill(&WHITE).map_err(e)?;
    let root = titled(root, title, 19)?;
    let (plot_area, side) = root.split_horizontally(SIZE.0 - LEGEND);
    let axis = &sweep.axes[0];
    let (x0, x1, _) = span(&axis.values);
    let top = top_of_survivors(cells).max(1e-3) * 1.12;
    let mut chart = ChartBuilder::on(&plot_area)
        .margin(12)
        .margin_right(24)
        .x_label_area_size(55)
        .y_label_area_size(70)
        .build_cartesian_2d(x0..x1, 0.0..top)
        .map_err(e)?;
    chart
        .configure_mesh()
        .light_line_style(RGBColor(235, 235, 235))
        .x_desc(labels::axis_label(&axis.key))
        .y_desc(labels::MAX_THETA_OVER_ALPHA)
        .label_style(("sans-serif", 15))
        .axis_desc_style(("sans-serif", 19))
        .draw()
        .map_err(e)?;
    let mut sorted: Vec<&Cell> = cells.iter().collect();
    sorted.sort_by(|a, b| sweep.values(a.index)[0].total_cmp(&sweep.values(b.index)[0]));
    let blue = LINES[0];
    chart
        .draw_series(
            survivor_runs(sweep, cells)
                .into_iter()
                .map(|run| PathElement::new(run, blue.stroke_width(2))),
        )
        .map_err(e)?;
    chart
        .draw_series(sorted.iter().map(|c| {
            let x = sweep.values(c.index)[0];
            let colour = cell_colour(c, 1.0);
            let y = if matches!(c.class, CellClass::Survived | CellClass::NoUplift) {
                c.max_theta_over_alpha
            } else {
                top / 1.12 * 1.06
            };
            let colour = if c.class == CellClass::Survived {
                blue
            } else {
                colour
            };
            Circle::new((x, y), 5, colour.filled())
        }))
        .map_err(e)?;
    let over = cells.iter().filter(|c| overturned(c.class)).count();
    let done = cells
        .iter()
        .filter(|c| c.class != CellClass::Failed)
        .count();
    if let Some(r) = reference {
        dashed(&mut chart, survivor_runs(r.sweep, r.cells))?;
    }
    let mut items = vec![(
        blue,
        format!("survived: {}", labels::MAX_THETA_OVER_ALPHA),
        Swatch::Box,
    )];
    if let Some(r) = reference {
        items.push((
            BLACK,
            format!("{}: {}", r.label, labels::MAX_THETA_OVER_ALPHA),
            Swatch::Dashed,
        ));
    }
    items.extend(
        CLASSES
            .iter()
            .filter(|(k, _, _)| cells.iter().any(|c| c.class == *k))
            .map(|(_, colour, text)| (*colour, text.to_string(), Swatch::Box)),
    );
    items.push((
        WHITE,
        format!("{} = {over}/{done}", labels::FRACTION_OVERTURNED),
        Swatch::Box,
    ));
    legend(&side, 40, &items)?;
    root.present().map_err(e)
}

/// The (axis value, max θ/α) lines of a one-axis sweep's cells that did not overturn, split where
/// a cell between them did.
fn survivor_runs(sweep: &Sweep, cells: &[Cell]) -> Vec<Vec<(f64, f64)>> {
    let mut sorted: Vec<&Cell> = cells.iter().collect();
    sorted.sort_by(|a, b| sweep.values(a.index)[0].total_cmp(&sweep.values(b.index)[0]));
    let mut runs = vec![Vec::new()];
    for c in sorted {
        if matches!(c.class, CellClass::Survived | CellClass::NoUplift) {
            let x = sweep.values(c.index)[0];
            if let Some(run) = runs.last_mut() {
                run.push((x, c.max_theta_over_alpha));
            }
        } else if runs.last().is_some_and(|r| !r.is_empty()) {
            runs.push(Vec::new());
        }
    }
    runs.retain(|r| !r.is_empty());
    runs
}

/// The figure of a sweep, as PNG and SVG: `line` for one axis, `spectrum` for two (regions and
/// max θ/α), `spectrum` with the overturning boundaries for three or more.
pub fn spectrum_plots(
    title: &str,
    sweep: &Sweep,
    cells: &[Cell],
    reference: Option<&Reference>,
    dir: &Path,
) -> Result<Vec<PathBuf>, SceneError> {
    if sweep.axes.is_empty() || cells.is_empty() {
        return Ok(Vec::new());
    }
    // plotters' tick search does not end on a range near the f64 limit, or one too narrow for
    // its magnitude (x + step == x): such a sweep is not drawn (its cells are in cells.csv).
    let n = sweep.axes.len();
    let drawable = |v: &[f64]| {
        let (lo, hi) = v
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| {
                (a.min(x), b.max(x))
            });
        let big = lo.abs().max(hi.abs());
        big <= 1e15 && (v.len() < 2 || hi - lo >= 1e-9 * big)
    };
    let shown = &sweep.axes[n.saturating_sub(2)..];
    if let Some(a) = shown.iter().find(|a| !drawable(&a.values)) {
        eprintln!(
            "note: the sweep plot is not drawn: the values of `{}` span a range a plot cannot \
             show (beyond ±1e15, or too narrow for their size); the cells are in cells.csv",
            a.key
        );
        return Ok(Vec::new());
    }
    register();
    match n {
        1 => render_pair(
            dir,
            "line",
            SIZE,
            |r| draw_line(r, title, sweep, cells, reference),
            |r| draw_line(r, title, sweep, cells, reference),
        ),
        2 => render_pair(
            dir,
            "spectrum",
            SIZE,
            |r| draw_spectrum(r, title, sweep, cells, reference),
            |r| draw_spectrum(r, title, sweep, cells, reference),
        ),
        _ => render_pair(
            dir,
            "spectrum",
            SIZE,
            |r| draw_boundaries(r, title, sweep, cells, reference),
            |r| draw_boundaries(r, title, sweep, cells, reference),
        ),
    }
}
