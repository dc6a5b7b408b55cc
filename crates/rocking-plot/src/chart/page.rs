//! A figure's page: its title, panels in a grid, the legend column or band and the caption, on
//! screen and at print size (the panels' geometry and the shared labels and headers).

use super::*;

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
