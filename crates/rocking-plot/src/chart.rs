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
use plotters::style::FontTransform;

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

/// A figure at its printed size is drawn in units of 1/8 mm (the SVG's viewBox; its `width`
/// and `height` are in mm), so that a 175 mm double column is 1400 units wide.
pub const UNITS_PER_MM: f64 = 8.0;
/// plotters writes a font of size s as `font-size` s / 1.24 in the SVG.
const PLOTTERS_FONT: f64 = 1.24;

/// The drawing units of `pt` points at the printed size.
pub fn points(pt: f64) -> f64 {
    pt * 25.4 / 72.0 * UNITS_PER_MM
}

/// Type sizes at the printed size, in points: tick labels and legends 7 pt, axis labels and
/// column/row headers 8 pt, panel letters 9 pt; subscripts are never set below 6 pt.
pub const PRINT_TICKS_PT: f64 = 7.0;
pub const PRINT_LEGEND_PT: f64 = 7.0;
pub const PRINT_AXIS_PT: f64 = 8.0;
pub const PRINT_HEADER_PT: f64 = 8.0;
pub const PRINT_LETTER_PT: f64 = 9.0;
pub const PRINT_TITLE_PT: f64 = 9.0;
pub const PRINT_MIN_PT: f64 = 6.0;

/// The type sizes a figure is set in (plotters' sizes), and whether it is laid out for print.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Type {
    pub title: f64,
    pub panel_title: f64,
    pub axis: f64,
    pub ticks: f64,
    pub legend: f64,
    pub letter: f64,
    pub print: bool,
}

impl Type {
    /// The screen figures' sizes (pixels), as before print sizes existed.
    pub const SCREEN: Type = Type {
        title: TITLE as f64,
        panel_title: PANEL_TITLE as f64,
        axis: AXIS as f64,
        ticks: TICKS as f64,
        legend: LEGEND as f64,
        letter: PANEL_TITLE as f64,
        print: false,
    };

    /// The sizes at the printed width ([`UNITS_PER_MM`]): the `PRINT_*_PT` points, rounded up
    /// to whole plotters sizes (its tick labels are drawn at a whole size).
    pub fn print() -> Type {
        let f = |pt: f64| (points(pt) * PLOTTERS_FONT).ceil();
        Type {
            title: f(PRINT_TITLE_PT),
            panel_title: f(PRINT_HEADER_PT),
            axis: f(PRINT_AXIS_PT),
            ticks: f(PRINT_TICKS_PT),
            legend: f(PRINT_LEGEND_PT),
            letter: f(PRINT_LETTER_PT),
            print: true,
        }
    }

    /// The height of a line of text of plotters' size `size`, in this type's units.
    pub fn line(&self, size: f64) -> u32 {
        if self.print {
            (size / PLOTTERS_FONT * 1.25).ceil() as u32
        } else {
            line_height(size as u32)
        }
    }
}

/// What the panel about to be drawn shows besides its data at print size: its letter, and
/// whether it draws its own axis labels (not when its row or column shares one).
#[derive(Clone, Debug, Default)]
pub struct PanelText {
    pub letter: Option<String>,
    pub hide_x_label: bool,
    pub hide_y_label: bool,
    /// Its title is a column or row header of the figure.
    pub hide_title: bool,
}

thread_local! {
    static TYPE: std::cell::Cell<Type> = const { std::cell::Cell::new(Type::SCREEN) };
    static PANEL: std::cell::RefCell<PanelText> = std::cell::RefCell::new(PanelText::default());
}

/// The type sizes of the figure being drawn on this thread ([`Page::svg`] sets them).
pub fn current() -> Type {
    TYPE.with(|t| t.get())
}

/// Sets what the next panel's [`axes`] draws besides its data (its letter, shared labels).
pub fn set_panel(text: PanelText) {
    PANEL.with(|p| *p.borrow_mut() = text);
}

/// Sets the type for the duration of a drawing, and the screen's back after it.
struct TypeGuard;

impl TypeGuard {
    fn set(t: Type) -> TypeGuard {
        TYPE.with(|c| c.set(t));
        set_panel(PanelText::default());
        TypeGuard
    }
}

impl Drop for TypeGuard {
    fn drop(&mut self) {
        TYPE.with(|c| c.set(Type::SCREEN));
        set_panel(PanelText::default());
    }
}

/// A print layout: the printed width, whether the title and caption are drawn in the image
/// (`--draft`), the height of the band above the panels that holds the legend and colour bar,
/// column and row headers (a grid of spectra: its parameters instead of a title per panel), and
/// the axis labels shared by a whole column (x) or row (y), drawn once beside the grid.
#[derive(Clone, Debug, Default)]
pub struct PrintLayout {
    pub width_mm: f64,
    pub draft: bool,
    pub band: u32,
    pub column_headers: Vec<String>,
    pub row_headers: Vec<String>,
    pub shared_x: Vec<Option<String>>,
    pub shared_y: Vec<Option<String>>,
}

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

/// A print page's parts, in drawing units (top to bottom: the title when drafting, the legend
/// band, the column headers, the rows of panels between the shared y labels (left) and the row
/// headers (right), the shared x labels, the caption when drafting).
#[derive(Clone, Copy, Debug)]
pub struct PrintGeometry {
    pub width: u32,
    pub height: u32,
    pub title: u32,
    pub band: u32,
    pub headers: u32,
    pub left: u32,
    pub right: u32,
    pub panel: (u32, u32),
    pub bottom: u32,
    pub caption: u32,
}

/// A panel's margins at print size: the letter's line above, room for the last tick label on
/// the right.
const PRINT_MARGIN_RIGHT: u32 = 20;
const PRINT_MARGIN: u32 = 4;

/// A panel's label areas at print size (x: below, y: left): tick labels, and the axis label
/// where the panel draws its own.
pub(crate) fn print_label_areas(t: &Type, hide_x: bool, hide_y: bool) -> (u32, u32) {
    let tick_h = t.line(t.ticks) + 6;
    let tick_w = (4.6 * 0.6 * t.ticks / PLOTTERS_FONT).ceil() as u32 + 10;
    let axis = t.line(t.axis) + 4;
    (
        tick_h + if hide_x { 0 } else { axis },
        tick_w + if hide_y { 0 } else { axis },
    )
}

impl Page<'_> {
    fn print_title_lines(&self, p: &PrintLayout, t: &Type) -> Vec<String> {
        if !p.draft {
            return Vec::new();
        }
        let width = p.width_mm * UNITS_PER_MM;
        let chars = (width / (0.56 * t.title / PLOTTERS_FONT)).max(10.0);
        wrap_items(self.title, chars as usize)
    }

    fn print_caption_lines(&self, p: &PrintLayout, t: &Type) -> Vec<String> {
        if !p.draft {
            return Vec::new();
        }
        let width = p.width_mm * UNITS_PER_MM - 16.0;
        let chars = (width / (0.55 * t.legend / PLOTTERS_FONT)).max(10.0);
        self.caption
            .map(|c| crate::wrap(c, chars as usize))
            .unwrap_or_default()
    }

    /// The parts of the print page `p` (the panels share the width; their height follows
    /// `panel`'s aspect ratio).
    pub fn print_geometry(&self, p: &PrintLayout) -> PrintGeometry {
        let t = Type::print();
        let width = (p.width_mm * UNITS_PER_MM).round() as u32;
        let lines = |n: usize, size: f64| match n {
            0 => 0,
            n => n as u32 * t.line(size) + 8,
        };
        let title = lines(self.print_title_lines(p, &t).len(), t.title);
        let caption = lines(self.print_caption_lines(p, &t).len(), t.legend);
        let strip = t.line(t.axis) + 6;
        let left = if p.shared_y.iter().any(Option::is_some) {
            strip
        } else {
            0
        };
        let right = if p.row_headers.is_empty() { 0 } else { strip };
        let headers = if p.column_headers.is_empty() {
            0
        } else {
            t.line(t.panel_title) + 4
        };
        let bottom = if p.shared_x.iter().any(Option::is_some) {
            strip
        } else {
            0
        };
        let pw = width.saturating_sub(left + right) / self.columns() as u32;
        let ph = (f64::from(pw) * f64::from(self.panel.1) / f64::from(self.panel.0.max(1))).round()
            as u32;
        PrintGeometry {
            width,
            height: title + p.band + headers + self.rows() as u32 * ph + bottom + caption,
            title,
            band: p.band,
            headers,
            left,
            right,
            panel: (pw, ph),
            bottom,
            caption,
        }
    }

    /// [`Page::svg`] at the printed size `p` (`panel` is then the panels' aspect ratio, width
    /// to height; the second area of `draw` is the legend band above the panels).
    pub fn print_svg(
        &self,
        p: &PrintLayout,
        draw: impl FnOnce(&[Area<'_>], &Area<'_>) -> Result<(), String>,
    ) -> Result<String, String> {
        crate::register();
        let _type = TypeGuard::set(Type::print());
        let t = current();
        let g = self.print_geometry(p);
        let (xa, ya) = print_label_areas(&t, true, true);
        let mut text = String::new();
        {
            let root = SVGBackend::with_string(&mut text, (g.width, g.height)).into_drawing_area();
            root.fill(&WHITE).map_err(fail)?;
            let (top, rest) = root.split_vertically(g.title);
            let title = self.print_title_lines(p, &t);
            sized_lines(&top, &title, t.title, (g.width / 2) as i32, 4, HPos::Center)?;
            let (band, rest) = rest.split_vertically(g.band);
            let (heads, rest) = rest.split_vertically(g.headers);
            let (grid, rest) = rest.split_vertically(self.rows() as u32 * g.panel.1);
            let (strip, bottom) = rest.split_vertically(g.bottom);
            let caption = self.print_caption_lines(p, &t);
            sized_lines(&bottom, &caption, t.legend, 8, 4, HPos::Left)?;
            let (pw, ph) = (g.panel.0 as i32, g.panel.1 as i32);
            // The middle of a panel's plotting area, across and down.
            let mid_x = |c: usize| {
                let plot = pw - ya as i32 - (PRINT_MARGIN_RIGHT + PRINT_MARGIN) as i32;
                g.left as i32 + c as i32 * pw + PRINT_MARGIN as i32 + ya as i32 + plot / 2
            };
            let mid_y = |r: usize| {
                let top = t.line(t.letter) as i32;
                let plot = ph - top - (xa + PRINT_MARGIN) as i32;
                r as i32 * ph + top + plot / 2
            };
            let header = |size: f64, h: HPos, v: VPos, rotate: FontTransform| {
                ("sans-serif", size)
                    .into_font()
                    .transform(rotate)
                    .into_text_style(&root)
                    .pos(Pos::new(h, v))
            };
            let across = header(t.panel_title, HPos::Center, VPos::Top, FontTransform::None);
            for (c, h) in p.column_headers.iter().enumerate() {
                heads
                    .draw_text(&rich(h), &across, (mid_x(c), 2))
                    .map_err(fail)?;
            }
            let labels = header(t.axis, HPos::Center, VPos::Top, FontTransform::None);
            for (c, l) in p.shared_x.iter().enumerate() {
                if let Some(l) = l {
                    strip
                        .draw_text(&rich(l), &labels, (mid_x(c), 2))
                        .map_err(fail)?;
                }
            }
            let (left, rest) = grid.split_horizontally(g.left);
            let (panels, right) = rest.split_horizontally(self.columns() as u32 * g.panel.0);
            let up = header(t.axis, HPos::Center, VPos::Center, FontTransform::Rotate270);
            for (r, l) in p.shared_y.iter().enumerate() {
                if let Some(l) = l {
                    left.draw_text(&rich(l), &up, ((g.left / 2) as i32, mid_y(r)))
                        .map_err(fail)?;
                }
            }
            let down = header(
                t.panel_title,
                HPos::Center,
                VPos::Center,
                FontTransform::Rotate90,
            );
            for (r, h) in p.row_headers.iter().enumerate() {
                right
                    .draw_text(&rich(h), &down, ((g.right / 2) as i32, mid_y(r)))
                    .map_err(fail)?;
            }
            let mut areas = panels.split_evenly((self.rows(), self.columns()));
            areas.truncate(self.panels);
            draw(&areas, &band)?;
            root.present().map_err(fail)?;
        }
        Ok(text)
    }
}

/// Lines of (rich) text of plotters' size `size` from `y`, anchored at `x`.
fn sized_lines(
    area: &Area<'_>,
    lines: &[String],
    size: f64,
    x: i32,
    y: i32,
    h: HPos,
) -> Result<(), String> {
    let t = current();
    let style = ("sans-serif", size)
        .into_font()
        .into_text_style(area)
        .pos(Pos::new(h, VPos::Top));
    for (i, line) in lines.iter().enumerate() {
        let y = y + (i as u32 * t.line(size)) as i32;
        area.draw_text(&rich(line), &style, (x, y)).map_err(fail)?;
    }
    Ok(())
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
    let t = current();
    if t.print {
        return print_frame(area, title, x, y, labels, grid, ticks, &t);
    }
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

/// A panel's frame at print size: the letter above its top-left corner, tick labels and axis
/// labels in points, axis labels only where no row or column shares them, no minor grid (a dense
/// one prints as a grey tint), as many ticks as fit.
#[allow(clippy::too_many_arguments)]
fn print_frame<'a, 'b>(
    area: &'a Area<'b>,
    title: Option<&str>,
    x: (f64, f64),
    y: (f64, f64),
    labels: (&str, &str),
    grid: bool,
    ticks: &dyn Fn(&f64) -> String,
    t: &Type,
) -> Result<Chart<'a, 'b>, String> {
    let panel = PANEL.with(|p| p.borrow().clone());
    let (xa, ya) = print_label_areas(t, panel.hide_x_label, panel.hide_y_label);
    if let Some(letter) = &panel.letter {
        let style = ("sans-serif", t.letter)
            .into_font()
            .into_text_style(area)
            .pos(Pos::new(HPos::Left, VPos::Top));
        area.draw_text(letter, &style, (0, 0)).map_err(fail)?;
    }
    let (w, h) = area.dim_in_pixel();
    let mut builder = ChartBuilder::on(area);
    builder
        .margin(PRINT_MARGIN)
        .margin_top(t.line(t.letter))
        .margin_right(PRINT_MARGIN_RIGHT)
        .x_label_area_size(xa)
        .y_label_area_size(ya);
    if let Some(title) = title.filter(|_| !panel.hide_title) {
        builder.caption(rich(title), ("sans-serif", t.panel_title));
    }
    let mut chart = builder
        .build_cartesian_2d(x.0..x.1, y.0..y.1)
        .map_err(fail)?;
    let mut mesh = chart.configure_mesh();
    if grid {
        mesh.max_light_lines(0)
            .bold_line_style(RGBColor(226, 226, 226));
    } else {
        mesh.disable_mesh();
    }
    if !panel.hide_x_label {
        mesh.x_desc(rich(labels.0));
    }
    if !panel.hide_y_label {
        mesh.y_desc(rich(labels.1));
    }
    // A tick label every 12 mm across and 7 mm down at most.
    let fit = |len: u32, per_mm: f64| {
        ((f64::from(len) / (per_mm * UNITS_PER_MM)).floor() as usize).clamp(3, 7)
    };
    mesh.x_labels(fit(w.saturating_sub(ya), 12.0))
        .y_labels(fit(h.saturating_sub(xa), 7.0))
        .x_label_formatter(ticks)
        .y_label_formatter(ticks)
        .label_style(("sans-serif", t.ticks))
        .axis_desc_style(("sans-serif", t.axis))
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

/// The sample of a legend entry at print size: 9 mm, long enough to show a dash pattern.
const BAND_SAMPLE: u32 = 72;

/// The legend above the panels at print size: the entries in reading order in as many columns
/// as fit unwrapped (at most six), each entry's text wrapped to its column where none fit.
/// Returns the column width and each row's entries' lines.
fn band_layout(width: u32, items: &[LegendItem]) -> (u32, Vec<Vec<Vec<String>>>) {
    let t = Type::print();
    let char_w = 0.56 * t.legend / PLOTTERS_FONT;
    let text = |item: &LegendItem| match item {
        LegendItem::Heading(s)
        | LegendItem::Line(_, s)
        | LegendItem::Fill(_, s)
        | LegendItem::Rule(_, _, s)
        | LegendItem::Mark(_, _, _, s) => crate::text::plain(&rich(s)),
    };
    let need = |item: &LegendItem| {
        let sample = match item {
            LegendItem::Heading(_) => 0,
            _ => BAND_SAMPLE,
        };
        sample + (text(item).chars().count() as f64 * char_w).ceil() as u32 + 16
    };
    let widest = items.iter().map(need).max().unwrap_or(0);
    let columns = (1..=items.len().clamp(1, 6))
        .rev()
        .find(|&k| widest <= width / k as u32)
        .unwrap_or(1);
    let col_w = width / columns as u32;
    let chars = ((col_w.saturating_sub(BAND_SAMPLE + 8)) as f64 / char_w).max(12.0) as usize;
    let rows = items
        .chunks(columns)
        .map(|row| {
            row.iter()
                .map(|item| {
                    let s = match item {
                        LegendItem::Heading(s)
                        | LegendItem::Line(_, s)
                        | LegendItem::Fill(_, s)
                        | LegendItem::Rule(_, _, s)
                        | LegendItem::Mark(_, _, _, s) => s,
                    };
                    wrap_items(s, chars)
                        .into_iter()
                        .flat_map(|l| crate::wrap(&l, chars))
                        .collect()
                })
                .collect()
        })
        .collect();
    (col_w, rows)
}

/// The height of the legend band at print size for `items` in `width` units.
pub fn legend_band_height(width: u32, items: &[LegendItem]) -> u32 {
    if items.is_empty() {
        return 0;
    }
    let t = Type::print();
    let (_, rows) = band_layout(width, items);
    rows.iter()
        .map(|row| row.iter().map(Vec::len).max().unwrap_or(1) as u32 * t.line(t.legend) + 6)
        .sum::<u32>()
        + 8
}

/// Draws the legend band at print size ([`legend_band_height`] tall).
pub fn legend_band(area: &Area<'_>, items: &[LegendItem]) -> Result<(), String> {
    let t = Type::print();
    let (width, _) = area.dim_in_pixel();
    let (col_w, rows) = band_layout(width, items);
    let line = t.line(t.legend) as i32;
    let font = ("sans-serif", t.legend)
        .into_font()
        .into_text_style(area)
        .pos(Pos::new(HPos::Left, VPos::Top));
    let mut y = 4;
    let mut k = 0;
    for row in rows {
        let mut tallest = 1;
        for (c, lines) in row.iter().enumerate() {
            let item = &items[k];
            k += 1;
            let x0 = c as i32 * col_w as i32;
            let cy = y + line / 2;
            let sample = vec![(x0 + 4, cy), (x0 + BAND_SAMPLE as i32 - 8, cy)];
            let mid = (x0 + (BAND_SAMPLE as i32 - 4) / 2, cy);
            let indent = match item {
                LegendItem::Heading(_) => 4,
                LegendItem::Line(s, _) => {
                    let c = rgb(s.colour);
                    match s.dash {
                        None => area.draw(&PathElement::new(sample, c.stroke_width(2))),
                        Some((a, b)) => {
                            area.draw(&DashedPathElement::new(sample, a, b, c.stroke_width(2)))
                        }
                    }
                    .map_err(fail)?;
                    marker(area, s.marker, mid, 5, c, true)?;
                    BAND_SAMPLE
                }
                LegendItem::Fill(c, _) => {
                    let bx = [
                        (x0 + 10, y + 1),
                        (x0 + BAND_SAMPLE as i32 - 14, y + line - 2),
                    ];
                    area.draw(&Rectangle::new(bx, rgb(*c).filled()))
                        .map_err(fail)?;
                    area.draw(&Rectangle::new(bx, BLACK)).map_err(fail)?;
                    BAND_SAMPLE
                }
                LegendItem::Rule(c, dash, _) => {
                    let c = rgb(*c);
                    match dash {
                        None => area.draw(&PathElement::new(sample, c.stroke_width(2))),
                        Some((a, b)) => {
                            area.draw(&DashedPathElement::new(sample, *a, *b, c.stroke_width(2)))
                        }
                    }
                    .map_err(fail)?;
                    BAND_SAMPLE
                }
                LegendItem::Mark(m, c, filled, _) => {
                    marker(area, *m, mid, 6, rgb(*c), *filled)?;
                    BAND_SAMPLE
                }
            };
            for (j, l) in lines.iter().enumerate() {
                area.draw_text(&rich(l), &font, (x0 + indent as i32, y + j as i32 * line))
                    .map_err(fail)?;
            }
            tallest = tallest.max(lines.len());
        }
        y += tallest as i32 * line + 6;
    }
    Ok(())
}
