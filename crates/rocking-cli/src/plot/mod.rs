//! Every figure the command draws goes through [`Figure`]: panels in a grid (quantities against
//! τ for one or more runs, rocking spectra on one shared colour scale, overturning boundaries,
//! one-axis sweeps), one legend column beside them (never over the data), a title wrapped
//! between items and a caption that explains the marks. `rocking run` draws a figure of one run,
//! `rocking spectrum` one of one sweep and `rocking figure` one from a figure file: the same
//! code. plotters draws the SVG; `rocking_plot::export` makes the PNG and PDF from it, so the
//! three agree. Labels come from `rocking_scene::labels` and are drawn with real subscripts.

mod boundary;
mod history;
mod spectrum;

pub use history::{HistoryPanel, Quantity, Trace};
pub use spectrum::{BoundaryPanel, CurvePanel, LinePanel, SpectrumPanel, Structure};

use std::path::{Path, PathBuf};

use plotters::coord::types::RangedCoordf64;
use plotters::coord::Shift;
use plotters::element::DashedPathElement;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use rocking::{EventKind, Run};
use rocking_plot::style::{self, LineStyle, Marker};
use rocking_plot::text::{rich, tick, wrap_items};
use rocking_scene::labels;
use rocking_spectra::{Cell, Sweep};

use crate::out_dir::write_atomic;
use rocking_scene::setup::Setup;
use rocking_scene::SceneError;

pub(crate) use rocking_plot::register;

/// The drawing area every panel and legend draws on.
pub(crate) type Area<'a> = DrawingArea<SVGBackend<'a>, Shift>;
/// A panel's chart: f64 axes.
pub(crate) type Chart<'a, 'b> =
    ChartContext<'a, SVGBackend<'b>, Cartesian2d<RangedCoordf64, RangedCoordf64>>;

/// Font sizes (plotters' sizes: the SVG's are these / 1.24).
pub(crate) const TITLE: u32 = 22;
pub(crate) const PANEL_TITLE: u32 = 18;
pub(crate) const AXIS: u32 = 18;
pub(crate) const TICKS: u32 = 15;
pub(crate) const LEGEND: u32 = 15;
/// The width of the legend column.
const LEGEND_WIDTH: u32 = 280;

/// One panel of a figure.
pub enum Panel {
    History(HistoryPanel),
    Spectrum(SpectrumPanel),
    Boundaries(BoundaryPanel),
    Line(LinePanel),
    Curve(CurvePanel),
}

/// A figure: its title, panels in rows of `columns`, each `panel` pixels, and a caption.
pub struct Figure {
    pub title: String,
    pub caption: Option<String>,
    pub columns: usize,
    pub panel: (u32, u32),
    pub panels: Vec<Panel>,
    /// Top of the shared colour scale of the spectrum panels (default: their largest survivor).
    pub colour_top: Option<f64>,
}

/// Something the legend column shows.
pub(crate) enum LegendItem {
    /// A line with its dash and marker.
    Line(LineStyle, String),
    /// A filled box (a class), hatched where the class is.
    Fill([u8; 3], String),
    /// A line without a marker (a boundary), solid or dashed.
    Rule([u8; 3], Option<(u32, u32)>, String),
    /// A marker alone, in a colour.
    Mark(Marker, [u8; 3], bool, String),
    /// A heading.
    Heading(String),
}

pub(crate) fn rgb(c: [u8; 3]) -> RGBColor {
    RGBColor(c[0], c[1], c[2])
}

pub(crate) fn fail<E: std::fmt::Display>(e: E) -> String {
    e.to_string()
}

impl Figure {
    fn rows(&self) -> usize {
        self.panels.len().div_ceil(self.columns.max(1))
    }

    /// The shared colour scale's top: the given one, else the largest survivor of any panel.
    fn colour_top(&self) -> Option<f64> {
        let tops: Vec<f64> = self
            .panels
            .iter()
            .filter_map(|p| match p {
                Panel::Spectrum(s) => Some(s.top_of_survivors()),
                _ => None,
            })
            .collect();
        if tops.is_empty() {
            return None;
        }
        Some(
            self.colour_top
                .unwrap_or_else(|| tops.iter().fold(1e-9, |a, &b| a.max(b))),
        )
    }

    fn title_lines(&self, width: u32) -> Vec<String> {
        // DejaVu Sans averages about 0.55 em per character; 40 px of margin.
        let chars = ((width.saturating_sub(40)) as f64 / (0.56 * TITLE as f64)).max(10.0);
        wrap_items(&self.title, chars as usize)
    }

    fn caption_lines(&self, width: u32) -> Vec<String> {
        let chars = ((width.saturating_sub(40)) as f64 / (0.52 * LEGEND as f64)).max(10.0);
        self.caption
            .as_deref()
            .map(|c| rocking_plot::wrap(c, chars as usize))
            .unwrap_or_default()
    }

    /// The legend column's width: none when there is nothing to explain.
    fn legend_width(&self) -> u32 {
        if self.colour_top().is_some() || !self.legend().is_empty() {
            LEGEND_WIDTH
        } else {
            0
        }
    }

    /// The whole figure's size in pixels.
    pub fn size(&self) -> (u32, u32) {
        let width = self.columns as u32 * self.panel.0 + self.legend_width();
        let title = self.title_lines(width).len() as u32 * line_height(TITLE) + 16;
        let caption = match self.caption_lines(width).len() as u32 {
            0 => 0,
            n => n * line_height(LEGEND) + 16,
        };
        (width, title + self.rows() as u32 * self.panel.1 + caption)
    }

    /// Draws the figure into an SVG string (before `rocking_plot::export` finishes it).
    pub fn svg(&self) -> Result<String, String> {
        register();
        let size = self.size();
        let mut text = String::new();
        {
            let root = SVGBackend::with_string(&mut text, size).into_drawing_area();
            self.draw(&root, size)?;
            root.present().map_err(fail)?;
        }
        Ok(text)
    }

    fn draw(&self, root: &Area<'_>, size: (u32, u32)) -> Result<(), String> {
        root.fill(&WHITE).map_err(fail)?;
        let lines = self.title_lines(size.0);
        let title_h = lines.len() as u32 * line_height(TITLE) + 16;
        let (top, rest) = root.split_vertically(title_h);
        text_lines(&top, &lines, TITLE, (size.0 / 2) as i32, 8, HPos::Center)?;
        let grid_h = self.rows() as u32 * self.panel.1;
        let (grid, bottom) = rest.split_vertically(grid_h);
        let caption = self.caption_lines(size.0);
        text_lines(&bottom, &caption, LEGEND, 20, 6, HPos::Left)?;
        let (panels, side) = grid.split_horizontally(self.columns as u32 * self.panel.0);
        let top = self.colour_top();
        let areas = panels.split_evenly((self.rows(), self.columns.max(1)));
        let shared = history::shared_ranges(&self.panels);
        for (k, (p, area)) in self.panels.iter().zip(&areas).enumerate() {
            match p {
                Panel::History(h) => h.draw(area, shared[k])?,
                Panel::Spectrum(s) => s.draw(area, top.unwrap_or(1.0))?,
                Panel::Boundaries(b) => b.draw(area)?,
                Panel::Line(l) => l.draw(area)?,
                Panel::Curve(c) => c.draw(area)?,
            }
        }
        let mut y = 10;
        if let Some(top) = top {
            let marks: Vec<(f64, String)> = self
                .panels
                .iter()
                .filter_map(|p| match p {
                    Panel::Spectrum(s) => s.theta_cr_mark(),
                    _ => None,
                })
                .fold(Vec::new(), |mut all: Vec<(f64, String)>, m| {
                    // One mark per value; marks of structures that share it drop their "(α = …)".
                    match all.iter_mut().find(|(v, _)| (v - m.0).abs() < 1e-3) {
                        Some(known) if known.1 != m.1 => {
                            known.1 = known.1.split(" (").next().unwrap_or("").to_string();
                        }
                        Some(_) => {}
                        None => all.push(m),
                    }
                    all
                });
            y = spectrum::colour_bar(&side, top, &marks, y)?;
        }
        legend(&side, y, &self.legend())?;
        Ok(())
    }

    /// The legend: every run's line, every class and boundary the panels show, every mark.
    fn legend(&self) -> Vec<LegendItem> {
        let mut items: Vec<LegendItem> = Vec::new();
        let mut push = |item: LegendItem| {
            let key = legend_key(&item);
            if !items.iter().any(|i| legend_key(i) == key) {
                items.push(item);
            }
        };
        for p in &self.panels {
            let entries = match p {
                Panel::History(h) => h.legend(),
                Panel::Spectrum(s) => s.legend(),
                Panel::Boundaries(b) => b.legend(),
                Panel::Line(l) => l.legend(),
                Panel::Curve(c) => c.legend(),
            };
            for e in entries {
                push(e);
            }
        }
        items
    }

    /// Writes `<name>.svg`, `.png` and `.pdf` into `dir`, each atomically; returns their paths.
    pub fn write(&self, dir: &Path, name: &str) -> Result<Vec<PathBuf>, SceneError> {
        let failed =
            |m: String| SceneError::failure(format!("{}: cannot draw {name}: {m}", dir.display()));
        let svg = self.svg().map_err(failed)?;
        let out = rocking_plot::export::export(&svg).map_err(failed)?;
        let mut written = Vec::new();
        for (ext, bytes) in [
            ("svg", out.svg.as_bytes()),
            ("png", &out.png[..]),
            ("pdf", &out.pdf[..]),
        ] {
            let path = dir.join(format!("{name}.{ext}"));
            write_atomic(&path, bytes)?;
            written.push(path);
        }
        Ok(written)
    }
}

fn legend_key(item: &LegendItem) -> String {
    match item {
        LegendItem::Line(s, t) => format!("line {} {t}", s.name),
        LegendItem::Fill(c, t) => format!("fill {c:?} {t}"),
        LegendItem::Rule(c, d, t) => format!("rule {c:?} {d:?} {t}"),
        LegendItem::Mark(m, c, f, t) => format!("mark {m:?} {c:?} {f} {t}"),
        LegendItem::Heading(t) => format!("heading {t}"),
    }
}

pub(crate) fn line_height(size: u32) -> u32 {
    (size as f64 * 1.3) as u32
}

/// Lines of (rich) text from `y`, anchored at `x`.
pub(crate) fn text_lines(
    area: &Area<'_>,
    lines: &[String],
    size: u32,
    x: i32,
    y: i32,
    h: HPos,
) -> Result<(), String> {
    let style = ("sans-serif", size)
        .into_font()
        .into_text_style(area)
        .pos(Pos::new(h, VPos::Top));
    for (i, line) in lines.iter().enumerate() {
        let y = y + (i as u32 * line_height(size)) as i32;
        area.draw_text(&rich(line), &style, (x, y)).map_err(fail)?;
    }
    Ok(())
}

/// A panel's chart with its axes: ticks by [`tick`], labels with subscripts, an optional title.
pub(crate) fn axes<'a, 'b>(
    area: &'a Area<'b>,
    title: Option<&str>,
    x: (f64, f64),
    y: (f64, f64),
    labels: (&str, &str),
    grid: bool,
) -> Result<Chart<'a, 'b>, String> {
    let mut builder = ChartBuilder::on(area);
    builder
        .margin(10)
        .margin_right(18)
        .x_label_area_size(52)
        .y_label_area_size(72);
    if let Some(t) = title {
        builder.caption(rich(t), ("sans-serif", PANEL_TITLE));
    }
    let mut chart = builder
        .build_cartesian_2d(x.0..x.1, y.0..y.1)
        .map_err(fail)?;
    let (xl, yl) = (rich(labels.0), rich(labels.1));
    let mut mesh = chart.configure_mesh();
    if grid {
        mesh.light_line_style(RGBColor(236, 236, 236))
            .bold_line_style(RGBColor(222, 222, 222));
    } else {
        mesh.disable_mesh();
    }
    mesh.x_desc(xl)
        .y_desc(yl)
        .x_labels(7)
        .y_labels(7)
        .x_label_formatter(&|v| tick(*v))
        .y_label_formatter(&|v| tick(*v))
        .label_style(("sans-serif", TICKS))
        .axis_desc_style(("sans-serif", AXIS))
        .draw()
        .map_err(fail)?;
    Ok(chart)
}

/// Draws `marker` of `size` pixels at `at` (filled or open).
pub(crate) fn marker<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    marker: Marker,
    at: (i32, i32),
    size: i32,
    colour: RGBColor,
    filled: bool,
) -> Result<(), String> {
    let style = if filled {
        colour.filled()
    } else {
        colour.stroke_width(2)
    };
    let (x, y) = at;
    let s = size;
    let e = |e: DrawingAreaErrorKind<DB::ErrorType>| e.to_string();
    match marker {
        Marker::Circle => area.draw(&Circle::new(at, s, style)).map_err(e),
        Marker::Square => area
            .draw(&Rectangle::new([(x - s, y - s), (x + s, y + s)], style))
            .map_err(e),
        Marker::Triangle => {
            let pts = vec![(x, y - s - 1), (x - s - 1, y + s), (x + s + 1, y + s)];
            if filled {
                area.draw(&Polygon::new(pts, style)).map_err(e)
            } else {
                let mut closed = pts.clone();
                closed.push(pts[0]);
                area.draw(&PathElement::new(closed, style)).map_err(e)
            }
        }
        Marker::Diamond => {
            let s = s + 1;
            let pts = vec![(x, y - s), (x + s, y), (x, y + s), (x - s, y)];
            if filled {
                area.draw(&Polygon::new(pts, style)).map_err(e)
            } else {
                let mut closed = pts.clone();
                closed.push(pts[0]);
                area.draw(&PathElement::new(closed, style)).map_err(e)
            }
        }
        Marker::Cross => {
            let style = colour.stroke_width(2);
            area.draw(&PathElement::new(
                vec![(x - s, y - s), (x + s, y + s)],
                style,
            ))
            .map_err(e)?;
            area.draw(&PathElement::new(
                vec![(x - s, y + s), (x + s, y - s)],
                style,
            ))
            .map_err(e)
        }
    }
}

/// Draws `marker` at the data point `p` of a chart.
pub(crate) fn mark_at(
    chart: &Chart<'_, '_>,
    m: Marker,
    p: (f64, f64),
    size: i32,
    colour: RGBColor,
    filled: bool,
) -> Result<(), String> {
    let area = chart.plotting_area().strip_coord_spec();
    let (px, py) = chart.backend_coord(&p);
    let (bx, by) = area.get_base_pixel();
    marker(&area, m, (px - bx, py - by), size, colour, filled)
}

/// Draws a polyline in `style` on a chart (dashed when the style is).
pub(crate) fn styled_line(
    chart: &mut Chart<'_, '_>,
    points: Vec<(f64, f64)>,
    line: &LineStyle,
    colour: RGBColor,
    width: u32,
) -> Result<(), String> {
    if points.len() < 2 {
        return Ok(());
    }
    match line.dash {
        None => chart
            .draw_series(std::iter::once(PathElement::new(
                points,
                colour.stroke_width(width),
            )))
            .map(|_| ())
            .map_err(fail),
        Some((size, gap)) => chart
            .draw_series(std::iter::once(DashedPathElement::new(
                points,
                size,
                gap,
                colour.stroke_width(width),
            )))
            .map(|_| ())
            .map_err(fail),
    }
}

/// Draws the legend column's entries from `y` down.
pub(crate) fn legend(area: &Area<'_>, top: i32, items: &[LegendItem]) -> Result<(), String> {
    let width = area.dim_in_pixel().0 as usize;
    let chars = (width.saturating_sub(56) as f64 / (0.55 * LEGEND as f64)) as usize;
    let font = ("sans-serif", LEGEND).into_font();
    let mut y = top;
    for item in items {
        let (text, indent) = match item {
            LegendItem::Heading(t) => (t.as_str(), 8),
            LegendItem::Line(_, t)
            | LegendItem::Fill(_, t)
            | LegendItem::Rule(_, _, t)
            | LegendItem::Mark(_, _, _, t) => (t.as_str(), 52),
        };
        let cy = y + 9;
        match item {
            LegendItem::Line(s, _) => {
                let points = vec![(8, cy), (44, cy)];
                let c = rgb(s.colour);
                match s.dash {
                    None => area.draw(&PathElement::new(points, c.stroke_width(2))),
                    Some((a, b)) => {
                        area.draw(&DashedPathElement::new(points, a, b, c.stroke_width(2)))
                    }
                }
                .map_err(fail)?;
                marker(area, s.marker, (26, cy), 4, c, true)?;
            }
            LegendItem::Fill(c, _) => {
                area.draw(&Rectangle::new([(12, y), (40, y + 18)], rgb(*c).filled()))
                    .map_err(fail)?;
                area.draw(&Rectangle::new([(12, y), (40, y + 18)], BLACK))
                    .map_err(fail)?;
            }
            LegendItem::Rule(c, dash, _) => {
                let points = vec![(8, cy), (44, cy)];
                let c = rgb(*c);
                match dash {
                    None => area.draw(&PathElement::new(points, c.stroke_width(2))),
                    Some((a, b)) => {
                        area.draw(&DashedPathElement::new(points, *a, *b, c.stroke_width(2)))
                    }
                }
                .map_err(fail)?;
            }
            LegendItem::Mark(m, c, filled, _) => marker(area, *m, (26, cy), 5, rgb(*c), *filled)?,
            LegendItem::Heading(_) => {}
        }
        // Between items first; an item longer than the column then between words.
        let lines: Vec<String> = wrap_items(text, chars.max(12))
            .into_iter()
            .flat_map(|l| rocking_plot::wrap(&l, chars.max(12)))
            .collect();
        for (k, l) in lines.iter().enumerate() {
            area.draw(&Text::new(
                rich(l),
                (indent, y + 1 + (line_height(LEGEND) * k as u32) as i32),
                font.clone(),
            ))
            .map_err(fail)?;
        }
        y += 8 + (line_height(LEGEND) * lines.len().max(1) as u32) as i32;
    }
    Ok(())
}

/// `rocking run`'s figure: θ/α, u/u_cr, E/E_ref and ü_g/(g tan α) against τ, stacked, impacts
/// marked (the paper's Figs 3, 5 and 10 style), written as plot.svg, plot.png and plot.pdf.
pub fn plots(model: &Setup, run: &Run, dir: &Path) -> Result<Vec<PathBuf>, SceneError> {
    let trace = Trace::of(model, run, String::new(), style::LINES[0]);
    let panels = [
        Quantity::ThetaOverAlpha,
        Quantity::UOverUcr,
        Quantity::ETotal,
        Quantity::Ug,
    ]
    .into_iter()
    .map(|q| Panel::History(HistoryPanel::new(q, vec![trace.clone()])))
    .collect();
    let title = model
        .title
        .clone()
        .unwrap_or_else(|| model.excitation_description.clone());
    let impacts = run
        .events
        .iter()
        .filter(|e| e.kind == EventKind::Impact)
        .count();
    let figure = Figure {
        title,
        caption: (impacts > 0 || run.summary.overturned).then(|| history::CAPTION.to_string()),
        columns: 1,
        panel: (860, 270),
        panels,
        colour_top: None,
    };
    figure.write(dir, "plot")
}

/// The fragility-style curve of a record suite (fraction of the records that overturn against
/// the scale factor), as fragility.svg, .png and .pdf.
pub fn fragility_plots(
    points: &[(f64, f64)],
    records: usize,
    dir: &Path,
) -> Result<Vec<PathBuf>, SceneError> {
    let figure = Figure {
        title: format!("Fraction of {records} records that overturn"),
        caption: None,
        columns: 1,
        panel: (760, 520),
        panels: vec![Panel::Curve(CurvePanel {
            title: None,
            labels: (
                labels::SCALE_FACTOR.to_string(),
                labels::FRACTION_OVERTURNED.to_string(),
            ),
            points: points.to_vec(),
            y: (0.0, 1.05),
        })],
        colour_top: None,
    };
    figure.write(dir, "fragility")
}

/// A reference structure's cells over the axes a sweep's figure shows (`[sweep] reference`).
pub struct Reference<'a> {
    /// Legend text, e.g. "rigid column".
    pub label: &'a str,
    pub sweep: &'a Sweep,
    pub cells: &'a [Cell],
}

/// The figure of a sweep: `line` for one axis, `spectrum` for two (classes and max θ/α, with the
/// structure's θ_cr/α on the colour bar), `spectrum` with one overturning boundary per value of
/// the leading axes for three or more (each the midpoint between the cells that bracket the
/// lowest overturning amplitude). Returns the figure and the file name.
pub fn sweep_figure(
    title: &str,
    sweep: &Sweep,
    cells: &[Cell],
    reference: Option<&Reference>,
    theta_cr: Option<f64>,
) -> (Figure, &'static str) {
    let n = sweep.axes.len();
    let (panel, name, caption) = match n {
        1 => {
            let mut p = LinePanel::new(sweep, cells);
            if let Some(r) = reference {
                p = p.with_reference(r.label, r.sweep, r.cells);
            }
            (Panel::Line(p), "line", None)
        }
        2 => {
            let mut p = SpectrumPanel::new(sweep, cells);
            if let Some(r) = reference {
                p = p.with_reference(r.label, r.sweep, r.cells);
            }
            p.theta_cr =
                theta_cr.map(|v| (v, format!("θ_cr/α = {}", tick((v * 100.0).round() / 100.0))));
            (Panel::Spectrum(p), "spectrum", None)
        }
        _ => {
            let per = sweep.axes[n - 2].values.len() * sweep.axes[n - 1].values.len();
            let leading = &sweep.axes[..n - 2];
            let count = cells.len().div_ceil(per.max(1));
            let mut structures = Vec::new();
            for s in 0..count {
                let mine: Vec<Cell> = cells
                    .iter()
                    .filter(|c| c.index / per == s)
                    .copied()
                    .collect();
                let Some(first) = mine.first() else { continue };
                let values = sweep.values(first.index);
                let label = leading
                    .iter()
                    .zip(&values)
                    .map(|(a, &v)| labels::axis_value(&a.key, v))
                    .collect::<Vec<_>>()
                    .join(", ");
                let style = style::LINES[s % style::LINES.len()];
                structures.push(Structure::new(label, style, sweep, &mine, |_, lo, hi| {
                    (lo + hi) / 2.0
                }));
            }
            if let Some(r) = reference {
                structures.push(Structure::new(
                    r.label.to_string(),
                    style::BLACK,
                    r.sweep,
                    r.cells,
                    |_, lo, hi| (lo + hi) / 2.0,
                ));
            }
            let p = BoundaryPanel::over(sweep, structures, BOUNDARY_HEADING.to_string());
            (
                Panel::Boundaries(p),
                "spectrum",
                Some(GRID_CAPTION.to_string()),
            )
        }
    };
    let figure = Figure {
        title: title.to_string(),
        caption,
        columns: 1,
        panel: (760, 700),
        panels: vec![panel],
        colour_top: None,
    };
    (figure, name)
}

/// Whether a sweep's figure can be drawn: plotters' tick search does not end on a range near the
/// f64 limit, or one too narrow for its magnitude (x + step == x); such a sweep is not drawn (its
/// cells are in cells.csv) and a note says so.
pub fn drawable(sweep: &Sweep) -> bool {
    if sweep.axes.is_empty() || sweep.is_empty() {
        return false;
    }
    let n = sweep.axes.len();
    let ok = |v: &[f64]| {
        let (lo, hi) = v
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| {
                (a.min(x), b.max(x))
            });
        let big = lo.abs().max(hi.abs());
        big <= 1e15 && (v.len() < 2 || hi - lo >= 1e-9 * big)
    };
    match sweep.axes[n.saturating_sub(2)..]
        .iter()
        .find(|a| !ok(&a.values))
    {
        None => true,
        Some(a) => {
            eprintln!(
                "note: the sweep plot is not drawn: the values of `{}` span a range a plot cannot \
                 show (beyond ±1e15, or too narrow for their size); the cells are in cells.csv",
                a.key
            );
            false
        }
    }
}

/// The legend heading of overturning boundaries.
pub const BOUNDARY_HEADING: &str = "lowest amplitude that overturns:";
/// How `rocking spectrum` finds a boundary point.
const GRID_CAPTION: &str = "Each line joins, per value of the horizontal axis, the midpoints \
                            between the highest upright cell below the lowest overturned cell and \
                            that cell (the grid's resolution); `rocking figure` refines them by \
                            bisection.";

#[cfg(test)]
mod tests {
    use super::*;
    use plotters::style::colors::colormaps::ViridisRGB;
    use rocking_spectra::CellClass;

    fn sweep() -> Sweep {
        Sweep {
            axes: vec![
                rocking_spectra::Axis {
                    key: "excitation.omega_p_over_p".into(),
                    values: vec![1.0, 2.0],
                },
                rocking_spectra::Axis {
                    key: "excitation.amplitude".into(),
                    values: vec![1.0, 2.0],
                },
            ],
            fingerprint: "test".into(),
        }
    }

    fn cells(thetas: [f64; 3]) -> Vec<Cell> {
        let mut cells: Vec<Cell> = thetas
            .iter()
            .enumerate()
            .map(|(index, &t)| Cell {
                index,
                class: CellClass::Survived,
                max_theta_over_alpha: t,
                impacts: 1,
            })
            .collect();
        cells.push(Cell {
            index: 3,
            class: CellClass::OverturnedOneImpact,
            max_theta_over_alpha: 15.7,
            impacts: 1,
        });
        cells
    }

    #[test]
    fn spectra_of_one_figure_share_one_colour_bar_and_its_range() {
        let s = sweep();
        let low = cells([0.2, 0.65, 1.3]);
        let high = cells([0.5, 1.0, 3.6]);
        let figure = Figure {
            title: "two panels".into(),
            caption: None,
            columns: 2,
            panel: (300, 300),
            panels: vec![
                Panel::Spectrum(SpectrumPanel::new(&s, &low)),
                Panel::Spectrum(SpectrumPanel::new(&s, &high)),
            ],
            colour_top: None,
        };
        let svg = figure.svg().unwrap();
        assert_eq!(
            svg.matches("survived: max |θ|/α").count(),
            1,
            "one colour bar"
        );
        // The 0.65 cell of the first panel is shaded on the shared 0..3.6 scale, not its own.
        let hex = |c: RGBColor| format!("fill=\"#{:02X}{:02X}{:02X}\"", c.0, c.1, c.2);
        let shared = hex(ViridisRGB.get_color_normalized(0.65, 0.0, 3.6));
        let own = hex(ViridisRGB.get_color_normalized(0.65, 0.0, 1.3));
        assert!(svg.contains(&shared), "{shared} missing");
        assert!(!svg.contains(&own), "{own}: shaded on its own scale");
        // The bar's ticks reach the shared top's range (0 .. 3.6: ticks 0, 1, 2, 3).
        assert!(
            svg.contains(">3</text>") && !svg.contains(">4</text>"),
            "ticks"
        );
    }
}
