//! What every figure is drawn with, the `rocking` command's and the work-precision diagrams
//! alike: a [`Page`] (a title wrapped between items, panels in a grid, a legend column beside
//! them so that no legend covers data, and a caption under them that explains the marks), a
//! panel's axes ([`axes`]: tick labels by [`tick`], or powers of ten by [`log_axes`], axis
//! labels with subscripts), lines in their style's dash, markers, and the legend's entries.
//! plotters draws into an SVG string; [`crate::export`] makes the PNG and the PDF from it.

use plotters::coord::types::RangedCoordf64;
use plotters::coord::Shift;
use plotters::element::DashedPathElement;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use crate::style::{LineStyle, Marker};
use crate::text::{power_of_ten, rich, tick, wrap_items};

/// The drawing area every panel and legend draws on.
pub type Area<'a> = DrawingArea<SVGBackend<'a>, Shift>;
/// A panel's chart: f64 axes (for a logarithmic axis, the log10 of the values).
pub type Chart<'a, 'b> =
    ChartContext<'a, SVGBackend<'b>, Cartesian2d<RangedCoordf64, RangedCoordf64>>;

/// Font sizes (plotters' sizes: the SVG's are these / 1.24).
pub const TITLE: u32 = 22;
pub const PANEL_TITLE: u32 = 18;
pub const AXIS: u32 = 18;
pub const TICKS: u32 = 15;
pub const LEGEND: u32 = 15;
/// The width of the legend column.
pub const LEGEND_WIDTH: u32 = 280;

/// The layout of a figure: its title, `panels` panels in rows of `columns`, each `panel` pixels,
/// a legend column on the right when `legend`, and a caption under the panels.
pub struct Page<'a> {
    pub title: &'a str,
    pub caption: Option<&'a str>,
    pub columns: usize,
    pub panels: usize,
    pub panel: (u32, u32),
    pub legend: bool,
}

impl Page<'_> {
    fn columns(&self) -> usize {
        self.columns.max(1)
    }

    fn rows(&self) -> usize {
        self.panels.div_ceil(self.columns())
    }

    fn width(&self) -> u32 {
        self.columns() as u32 * self.panel.0 + if self.legend { LEGEND_WIDTH } else { 0 }
    }

    fn title_lines(&self) -> Vec<String> {
        // DejaVu Sans averages about 0.55 em per character; 40 px of margin.
        let chars = ((self.width().saturating_sub(40)) as f64 / (0.56 * TITLE as f64)).max(10.0);
        wrap_items(self.title, chars as usize)
    }

    fn caption_lines(&self) -> Vec<String> {
        let chars = ((self.width().saturating_sub(40)) as f64 / (0.52 * LEGEND as f64)).max(10.0);
        self.caption
            .map(|c| crate::wrap(c, chars as usize))
            .unwrap_or_default()
    }

    /// The whole figure's size in pixels.
    pub fn size(&self) -> (u32, u32) {
        let title = self.title_lines().len() as u32 * line_height(TITLE) + 16;
        let caption = match self.caption_lines().len() as u32 {
            0 => 0,
            n => n * line_height(LEGEND) + 16,
        };
        (
            self.width(),
            title + self.rows() as u32 * self.panel.1 + caption,
        )
    }

    /// Draws the title and the caption, then `draw(panels, legend column)` with one area per
    /// panel (row by row); returns the SVG that plotters wrote (finished by
    /// [`crate::export::export`]).
    pub fn svg(
        &self,
        draw: impl FnOnce(&[Area<'_>], &Area<'_>) -> Result<(), String>,
    ) -> Result<String, String> {
        crate::register();
        let size = self.size();
        let mut text = String::new();
        {
            let root = SVGBackend::with_string(&mut text, size).into_drawing_area();
            root.fill(&WHITE).map_err(fail)?;
            let lines = self.title_lines();
            let title_h = lines.len() as u32 * line_height(TITLE) + 16;
            let (top, rest) = root.split_vertically(title_h);
            text_lines(&top, &lines, TITLE, (size.0 / 2) as i32, 8, HPos::Center)?;
            let (grid, bottom) = rest.split_vertically(self.rows() as u32 * self.panel.1);
            text_lines(&bottom, &self.caption_lines(), LEGEND, 20, 6, HPos::Left)?;
            let (panels, side) = grid.split_horizontally(self.columns() as u32 * self.panel.0);
            let mut areas = panels.split_evenly((self.rows(), self.columns()));
            areas.truncate(self.panels);
            draw(&areas, &side)?;
            root.present().map_err(fail)?;
        }
        Ok(text)
    }
}

/// Something the legend column shows.
pub enum LegendItem {
    /// A line with its dash and marker.
    Line(LineStyle, String),
    /// A filled box (a class), hatched where the class is.
    Fill([u8; 3], String),
    /// A line without a marker (a boundary), solid or dashed.
    Rule([u8; 3], Option<(u32, u32)>, String),
    /// A marker alone, in a colour, filled or open.
    Mark(Marker, [u8; 3], bool, String),
    /// A heading.
    Heading(String),
}

impl LegendItem {
    /// What the entry shows: two entries with the same key are one.
    pub fn key(&self) -> String {
        match self {
            LegendItem::Line(s, t) => format!("line {} {t}", s.name),
            LegendItem::Fill(c, t) => format!("fill {c:?} {t}"),
            LegendItem::Rule(c, d, t) => format!("rule {c:?} {d:?} {t}"),
            LegendItem::Mark(m, c, f, t) => format!("mark {m:?} {c:?} {f} {t}"),
            LegendItem::Heading(t) => format!("heading {t}"),
        }
    }
}

pub fn rgb(c: [u8; 3]) -> RGBColor {
    RGBColor(c[0], c[1], c[2])
}

/// A drawing error as the message a figure's error carries.
pub fn fail<E: std::fmt::Display>(e: E) -> String {
    e.to_string()
}

/// The height of a line of text of `size`.
pub fn line_height(size: u32) -> u32 {
    (size as f64 * 1.3) as u32
}

/// Lines of (rich) text from `y`, anchored at `x`.
pub fn text_lines(
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
pub fn axes<'a, 'b>(
    area: &'a Area<'b>,
    title: Option<&str>,
    x: (f64, f64),
    y: (f64, f64),
    labels: (&str, &str),
    grid: bool,
) -> Result<Chart<'a, 'b>, String> {
    let linear = |v: &f64| tick(*v);
    frame(area, title, x, y, labels, grid, &linear)
}

/// A log-log panel's chart: its coordinates are the log10 of the values (`x` and `y` are such
/// ranges), its ticks the powers of ten (10⁻⁵), unlabelled between them.
pub fn log_axes<'a, 'b>(
    area: &'a Area<'b>,
    title: Option<&str>,
    x: (f64, f64),
    y: (f64, f64),
    labels: (&str, &str),
) -> Result<Chart<'a, 'b>, String> {
    let powers = |v: &f64| {
        let k = v.round();
        if (v - k).abs() < 1e-9 {
            power_of_ten(k as i32)
        } else {
            String::new()
        }
    };
    frame(area, title, x, y, labels, true, &powers)
}

fn frame<'a, 'b>(
    area: &'a Area<'b>,
    title: Option<&str>,
    x: (f64, f64),
    y: (f64, f64),
    labels: (&str, &str),
    grid: bool,
    ticks: &dyn Fn(&f64) -> String,
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
        .x_label_formatter(ticks)
        .y_label_formatter(ticks)
        .label_style(("sans-serif", TICKS))
        .axis_desc_style(("sans-serif", AXIS))
        .draw()
        .map_err(fail)?;
    Ok(chart)
}

/// A marker's polygon, filled or outlined.
fn polygon<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    pts: Vec<(i32, i32)>,
    style: ShapeStyle,
    filled: bool,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    if filled {
        area.draw(&Polygon::new(pts, style))
    } else {
        let mut closed = pts.clone();
        closed.push(pts[0]);
        area.draw(&PathElement::new(closed, style))
    }
}

/// Draws `marker` of `size` pixels at `at` (filled or open).
pub fn marker<DB: DrawingBackend>(
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
            polygon(area, pts, style, filled).map_err(e)
        }
        Marker::TriangleDown => {
            let pts = vec![(x, y + s + 1), (x - s - 1, y - s), (x + s + 1, y - s)];
            polygon(area, pts, style, filled).map_err(e)
        }
        Marker::Diamond => {
            let s = s + 1;
            let pts = vec![(x, y - s), (x + s, y), (x, y + s), (x - s, y)];
            polygon(area, pts, style, filled).map_err(e)
        }
        Marker::Pentagon => {
            let r = f64::from(s) + 1.0;
            let pts = (0..5)
                .map(|k| {
                    let a = std::f64::consts::TAU * f64::from(k) / 5.0;
                    (
                        x + (r * a.sin()).round() as i32,
                        y - (r * a.cos()).round() as i32,
                    )
                })
                .collect();
            polygon(area, pts, style, filled).map_err(e)
        }
        Marker::Plus => {
            let style = colour.stroke_width(2);
            let s = s + 1;
            area.draw(&PathElement::new(vec![(x - s, y), (x + s, y)], style))
                .map_err(e)?;
            area.draw(&PathElement::new(vec![(x, y - s), (x, y + s)], style))
                .map_err(e)
        }
        Marker::Asterisk => {
            let style = colour.stroke_width(1);
            let s = s + 1;
            for (dx, dy) in [
                (s, 0),
                (0, s),
                (s * 2 / 3, s * 2 / 3),
                (s * 2 / 3, -s * 2 / 3),
            ] {
                area.draw(&PathElement::new(
                    vec![(x - dx, y - dy), (x + dx, y + dy)],
                    style,
                ))
                .map_err(e)?;
            }
            Ok(())
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

/// The pixel of the data point `p` of a chart, in its plotting area's pixels.
pub fn pixel(chart: &Chart<'_, '_>, p: (f64, f64)) -> (i32, i32) {
    let area = chart.plotting_area().strip_coord_spec();
    let (px, py) = chart.backend_coord(&p);
    let (bx, by) = area.get_base_pixel();
    (px - bx, py - by)
}

/// Draws `marker` at the data point `p` of a chart.
pub fn mark_at(
    chart: &Chart<'_, '_>,
    m: Marker,
    p: (f64, f64),
    size: i32,
    colour: RGBColor,
    filled: bool,
) -> Result<(), String> {
    let area = chart.plotting_area().strip_coord_spec();
    marker(&area, m, pixel(chart, p), size, colour, filled)
}

/// Draws a polyline in `style` on a chart (dashed when the style is).
pub fn styled_line(
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

/// Draws the legend column's entries from `top` down.
pub fn legend(area: &Area<'_>, top: i32, items: &[LegendItem]) -> Result<(), String> {
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
            .flat_map(|l| crate::wrap(&l, chars.max(12)))
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
