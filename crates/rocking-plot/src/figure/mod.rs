//! Every figure the command draws goes through [`Figure`]: panels in a grid (quantities against
//! τ for one or more runs, rocking spectra on one shared colour scale, overturning boundaries,
//! one-axis sweeps, a record suite's curves), one legend column beside them (never over the
//! data), a title wrapped between items and a caption that explains the marks. `rocking run`
//! draws a figure of one run, `rocking spectrum` one of one sweep, `rocking ida` its curves and
//! `rocking figure` one from a figure file: the same code, laid out and drawn with
//! `crate::chart`. plotters draws the SVG; `crate::export` makes the PNG and PDF
//! from it, so the three agree. Labels come from `rocking_scene::labels` and are drawn with real
//! subscripts.

mod boundary;
mod boundary_panel;
mod clip;
mod colour_bar;
mod history;
mod ida;
mod inset;
mod line_panel;
mod spectrum;
mod standard;

pub use boundary_panel::{BoundaryPanel, Structure};
pub use history::{HistoryPanel, Quantity, Trace, RUN_PANELS, THETA_OVER_ALPHA};
pub use ida::{ida_plots, FitPanel, IdaPanel, Points};
pub use inset::{Corner, Inset, CORNERS, INSET_SIZE};
pub use line_panel::{CurvePanel, LinePanel};
pub use spectrum::{SpectrumPanel, CONTOUR_DASHES};
pub use standard::*;

use std::path::{Path, PathBuf};

use crate::chart::{self, legend, LegendItem, Page, PanelText, PrintLayout};
use crate::style;
use crate::text::tick;
use rocking::EventKind;
use rocking_scene::labels;

use crate::FigureError;

/// Writes `bytes` to `path` atomically ([`rocking_spectra::write_atomic`]): a figure is never
/// left half-written.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<(), FigureError> {
    rocking_spectra::write_atomic(path, bytes).map_err(|source| FigureError::Write {
        path: path.to_path_buf(),
        source,
    })
}

/// One panel of a figure.
pub enum Panel {
    History(HistoryPanel),
    Spectrum(SpectrumPanel),
    Boundaries(BoundaryPanel),
    Line(LinePanel),
    Curve(CurvePanel),
    Ida(IdaPanel),
    Fit(FitPanel),
}

impl Panel {
    /// The panel's own title.
    fn title(&self) -> Option<&str> {
        match self {
            Panel::History(h) => h.title.as_deref(),
            Panel::Spectrum(s) => s.title.as_deref(),
            Panel::Boundaries(b) => b.title.as_deref(),
            Panel::Line(l) => l.title.as_deref(),
            Panel::Curve(c) => c.title.as_deref(),
            Panel::Ida(_) | Panel::Fit(_) => None,
        }
    }

    /// The panel's axis labels (x, y), where a figure may share them between panels.
    fn axis_labels(&self) -> Option<(String, String)> {
        match self {
            Panel::History(h) => Some(h.axis_labels()),
            Panel::Spectrum(s) => Some(s.axis_labels()),
            Panel::Boundaries(b) => Some(b.axis_labels()),
            _ => None,
        }
    }
}

/// A figure: its title, panels in rows of `columns`, each `panel` pixels, and a caption.
pub struct Figure {
    pub title: String,
    pub caption: Option<String>,
    pub columns: usize,
    pub panel: (u32, u32),
    pub panels: Vec<Panel>,
    /// Top of the shared colour scale of the spectrum panels (default: their largest shaded
    /// value).
    pub colour_top: Option<f64>,
    /// At its printed size (a figure file's), else on a screen's pixels.
    pub print: Option<Print>,
}

/// A figure at its printed size: its width in mm, its PNG's resolution, and whether the title
/// and caption are drawn inside the image (`--draft`, for screens; else the caption is written
/// beside it).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Print {
    pub width_mm: f64,
    pub dpi: f64,
    pub draft: bool,
}

/// The letter of the `k`-th panel (from 0): (a), (b), ..., (z), (aa), ...
pub fn letter(k: usize) -> String {
    let mut k = k;
    let mut s = String::new();
    loop {
        s.insert(0, (b'a' + (k % 26) as u8) as char);
        if k < 26 {
            break;
        }
        k = k / 26 - 1;
    }
    format!("({s})")
}

/// The formats (file extensions) every figure is written in, by [`Figure::write`].
pub const FORMATS: [&str; 3] = ["svg", "png", "pdf"];

/// The caption a print figure is written with, beside its image: `NAME.caption.md`.
pub const CAPTION_EXT: &str = "caption.md";

/// The first control character of a text drawn on a figure, if any: SVG cannot hold one.
pub fn control_char(text: &str) -> Option<char> {
    text.chars().find(|c| c.is_control())
}

/// Whether `file` is one of the files [`Figure::write`] writes for the figure `name`.
pub fn is_figure_file(file: &str, name: &str) -> bool {
    file.strip_prefix(name)
        .and_then(|rest| rest.strip_prefix('.'))
        .is_some_and(|ext| FORMATS.contains(&ext) || ext == CAPTION_EXT)
}

impl Figure {
    /// The shared colour scale's top: the given one, else the largest shaded value of any panel.
    fn colour_top(&self) -> Option<f64> {
        let tops: Vec<f64> = self
            .panels
            .iter()
            .filter_map(|p| match p {
                Panel::Spectrum(s) => Some(s.top_of_shaded()),
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

    /// The stated top of the shared colour scale (`colour_top`) and how many shaded cells of the
    /// figure lie above it (each drawn in the top colour), if any do.
    pub fn above_colour_top(&self) -> Option<(f64, usize)> {
        let top = self.colour_top?;
        let n: usize = self
            .panels
            .iter()
            .map(|p| match p {
                Panel::Spectrum(s) => s.count_above(top),
                _ => 0,
            })
            .sum();
        (n > 0).then_some((top, n))
    }

    /// The shared colour scale's bottom: 0, or the lowest shaded value where it is negative.
    fn colour_bottom(&self) -> f64 {
        self.panels
            .iter()
            .filter_map(|p| match p {
                Panel::Spectrum(s) => Some(s.bottom_of_shaded()),
                _ => None,
            })
            .fold(0.0, f64::min)
    }

    fn page(&self) -> Page<'_> {
        Page {
            title: &self.title,
            caption: self.caption.as_deref(),
            columns: self.columns,
            panels: self.panels.len(),
            panel: self.panel,
            // No legend column when there is nothing to explain.
            legend: self.print.is_none()
                && (self.colour_top().is_some() || !self.legend().is_empty()),
        }
    }

    /// The rows of panels and their columns.
    fn grid(&self) -> (usize, usize) {
        let columns = self.columns.max(1);
        (self.panels.len().div_ceil(columns), columns)
    }

    /// Column and row headers instead of a title per panel, where the panels' titles allow:
    /// titles of items ("α = 0.1, ω_n/p = 2.5") whose every item is the same along each column
    /// (a column header) or along each row (a row header) of a full grid; or titles on the first
    /// row only (column headers).
    pub fn headers(&self) -> Option<(Vec<String>, Vec<String>)> {
        let (rows, columns) = self.grid();
        let titles: Vec<Option<&str>> = self.panels.iter().map(Panel::title).collect();
        if titles.iter().all(Option::is_none) || self.panels.len() < 2 {
            return None;
        }
        let first_row_only = titles
            .iter()
            .enumerate()
            .all(|(k, t)| t.is_some() == (k < columns));
        if first_row_only && rows > 1 {
            let heads = titles[..columns]
                .iter()
                .map(|t| t.unwrap_or("").to_string());
            return Some((heads.collect(), Vec::new()));
        }
        if titles.len() != rows * columns || titles.iter().any(Option::is_none) {
            return None;
        }
        let items: Vec<Vec<&str>> = titles
            .iter()
            .map(|t| t.unwrap_or("").split(", ").collect())
            .collect();
        let n = items[0].len();
        if items.iter().any(|i| i.len() != n) {
            return None;
        }
        let at = |r: usize, c: usize, i: usize| items[r * columns + c][i];
        let (mut heads, mut sides) = (vec![Vec::new(); columns], vec![Vec::new(); rows]);
        for i in 0..n {
            let down = (0..columns).all(|c| (0..rows).all(|r| at(r, c, i) == at(0, c, i)));
            let across = (0..rows).all(|r| (0..columns).all(|c| at(r, c, i) == at(r, 0, i)));
            if down && (!across || rows == 1 || columns > 1) {
                (0..columns).for_each(|c| heads[c].push(at(0, c, i)));
            } else if across {
                (0..rows).for_each(|r| sides[r].push(at(r, 0, i)));
            } else {
                return None;
            }
        }
        let join = |v: Vec<Vec<&str>>| -> Vec<String> {
            if v.iter().all(Vec::is_empty) {
                Vec::new()
            } else {
                v.into_iter().map(|h| h.join(", ")).collect()
            }
        };
        Some((join(heads), join(sides)))
    }

    /// The axis labels a whole column (x) or row (y) shares, drawn once beside the grid.
    fn shared_labels(&self) -> (Vec<Option<String>>, Vec<Option<String>>) {
        let (rows, columns) = self.grid();
        let labels: Vec<Option<(String, String)>> =
            self.panels.iter().map(Panel::axis_labels).collect();
        let get = |r: usize, c: usize| labels.get(r * columns + c).cloned().flatten();
        let shared = |cells: Vec<Option<(String, String)>>,
                      pick: fn(&(String, String)) -> &String| {
            let first = cells.first().cloned().flatten()?;
            cells
                .iter()
                .all(|l| l.as_ref().is_some_and(|l| pick(l) == pick(&first)))
                .then(|| pick(&first).clone())
        };
        // A column that stops short of the last row (5 panels in 2 rows of 3) keeps its own x
        // label: a shared one would sit under the empty slot.
        let xs = (0..columns)
            .map(|c| {
                if (rows - 1) * columns + c >= self.panels.len() {
                    return None;
                }
                let cells: Vec<_> = (0..rows)
                    .filter(|r| r * columns + c < self.panels.len())
                    .map(|r| get(r, c))
                    .collect();
                shared(cells, |l| &l.0)
            })
            .collect();
        let ys = (0..rows)
            .map(|r| {
                let cells: Vec<_> = (0..columns)
                    .filter(|c| r * columns + c < self.panels.len())
                    .map(|c| get(r, c))
                    .collect();
                shared(cells, |l| &l.1)
            })
            .collect();
        (xs, ys)
    }

    /// The print layout: headers, shared labels, and the legend band's height.
    fn print_layout(&self, p: Print) -> PrintLayout {
        let (column_headers, row_headers) = self.headers().unwrap_or_default();
        let (shared_x, shared_y) = self.shared_labels();
        let width = (p.width_mm * chart::UNITS_PER_MM).round() as u32;
        let bar = self.colour_top().is_some() && self.shade_label().is_some();
        let (bar_h, legend_w) = if bar {
            (
                colour_bar::colour_bar_band_height(self.colour_bar_marks().len()),
                width.saturating_sub(colour_bar::PRINT_BAR_WIDTH),
            )
        } else {
            (0, width)
        };
        let band = bar_h.max(chart::legend_band_height(legend_w, &self.legend()));
        PrintLayout {
            width_mm: p.width_mm,
            draft: p.draft,
            band,
            column_headers,
            row_headers,
            shared_x,
            shared_y,
        }
    }

    /// What panel `k` shows besides its data at print size.
    fn panel_text(&self, k: usize, layout: &PrintLayout) -> PanelText {
        let (_, columns) = self.grid();
        let headed = !layout.column_headers.is_empty() || !layout.row_headers.is_empty();
        PanelText {
            letter: (self.panels.len() > 1).then(|| letter(k)),
            hide_x_label: layout.shared_x[k % columns].is_some(),
            hide_y_label: layout.shared_y[k / columns].is_some(),
            hide_title: headed,
        }
    }

    /// Draws the figure into an SVG string (before `crate::export` finishes it).
    pub fn svg(&self) -> Result<String, String> {
        let page = self.page();
        let layout = self.print.map(|p| self.print_layout(p));
        let draw = |areas: &[crate::chart::Area<'_>], side: &crate::chart::Area<'_>| {
            let top = self.colour_top();
            let bottom = self.colour_bottom();
            let shared = history::shared_ranges(&self.panels);
            for (k, (p, area)) in self.panels.iter().zip(areas).enumerate() {
                if let Some(l) = &layout {
                    chart::set_panel(self.panel_text(k, l));
                }
                match p {
                    Panel::History(h) => h.draw(area, shared[k])?,
                    Panel::Spectrum(s) => s.draw(area, (bottom, top.unwrap_or(1.0)))?,
                    Panel::Boundaries(b) => b.draw(area)?,
                    Panel::Line(l) => l.draw(area)?,
                    Panel::Curve(c) => c.draw(area)?,
                    Panel::Ida(i) => i.draw(area)?,
                    Panel::Fit(f) => f.draw(area)?,
                }
            }
            if layout.is_some() {
                let band = match (top, self.shade_label()) {
                    (Some(top), Some(label)) => {
                        let (bar, rest) = side.split_horizontally(colour_bar::PRINT_BAR_WIDTH);
                        colour_bar::colour_bar_band(
                            &bar,
                            label,
                            (bottom, top),
                            &self.colour_bar_marks(),
                        )?;
                        rest
                    }
                    _ => side.clone(),
                };
                return chart::legend_band(&band, &self.legend());
            }
            let mut y = 10;
            if let (Some(top), Some(label)) = (top, self.shade_label()) {
                y = colour_bar::colour_bar(
                    side,
                    label,
                    (bottom, top),
                    &self.colour_bar_marks(),
                    y,
                )?;
            }
            legend(side, y, &self.legend())
        };
        match &layout {
            Some(l) => page.print_svg(l, draw),
            None => page.svg(draw),
        }
    }

    /// The caption written beside a print figure (`NAME.caption.md`): the title in bold, the
    /// caption, and what each panel letter shows.
    pub fn caption_text(&self) -> String {
        let mut out = format!("**{}.**", self.title.trim_end_matches('.'));
        if let Some(c) = &self.caption {
            out.push(' ');
            out.push_str(c);
        }
        if self.panels.len() > 1 {
            let (rows, columns) = self.grid();
            let headers = self.headers();
            // A y label every panel shares is the axes' and said once (the figure's own
            // caption says so); only labels that differ tell the panels apart.
            let y_labels: Vec<Option<String>> = self
                .panels
                .iter()
                .map(|p| p.axis_labels().map(|(_, y)| y))
                .collect();
            let shared_y = y_labels.windows(2).all(|w| w[0] == w[1]);
            let parts: Vec<String> = (0..self.panels.len())
                .map(|k| {
                    let (r, c) = (k / columns, k % columns);
                    let mut what: Vec<String> = Vec::new();
                    if let Some((heads, sides)) = &headers {
                        what.extend(heads.get(c).cloned());
                        what.extend(sides.get(r).cloned());
                    } else if let Some(t) = self.panels[k].title() {
                        what.push(t.to_string());
                    }
                    if let Some(y) = &y_labels[k] {
                        if !shared_y && !matches!(self.panels[k], Panel::Spectrum(_)) {
                            what.push(y.clone());
                        }
                    }
                    format!("{} {}", letter(k), what.join(", "))
                })
                .collect();
            let _ = rows;
            out.push_str(&format!(" Panels: {}.", parts.join("; ")));
        }
        out.push('\n');
        out
    }

    /// The title of the shared colour scale: what the first spectrum panel shades (the panels of
    /// one figure shade one quantity).
    fn shade_label(&self) -> Option<&str> {
        self.panels.iter().find_map(|p| match p {
            Panel::Spectrum(s) => Some(s.shade().label.as_str()),
            _ => None,
        })
    }

    /// The marks of the spectrum panels for the colour bar (θ_cr/α): one per value; marks of
    /// structures that share it drop their "(α = …)".
    fn colour_bar_marks(&self) -> Vec<(f64, String)> {
        self.panels
            .iter()
            .filter_map(|p| match p {
                Panel::Spectrum(s) => s.colour_bar_mark(),
                _ => None,
            })
            .fold(Vec::new(), |mut all: Vec<(f64, String)>, m| {
                match all.iter_mut().find(|(v, _)| (v - m.0).abs() < 1e-3) {
                    Some(known) if known.1 != m.1 => {
                        known.1 = known.1.split(" (").next().unwrap_or("").to_string();
                    }
                    Some(_) => {}
                    None => all.push(m),
                }
                all
            })
    }

    /// The legend: every run's line, every class and boundary the panels show, every mark.
    fn legend(&self) -> Vec<LegendItem> {
        let mut items: Vec<LegendItem> = Vec::new();
        for p in &self.panels {
            let entries = match p {
                Panel::History(h) => h.legend(),
                Panel::Spectrum(s) => s.legend(),
                Panel::Boundaries(b) => b.legend(),
                Panel::Line(l) => l.legend(),
                Panel::Curve(c) => c.legend(),
                Panel::Ida(i) => i.legend(),
                Panel::Fit(f) => f.legend(),
            };
            for e in entries {
                if !items.iter().any(|i| i.key() == e.key()) {
                    items.push(e);
                }
            }
        }
        items
    }

    /// The figure's files as bytes, each with its extension: SVG, PNG and PDF (one SVG exported),
    /// and at print size (not a draft) the caption as Markdown.
    pub fn files(&self) -> Result<Vec<(&'static str, Vec<u8>)>, String> {
        let svg = self.svg()?;
        let out = match self.print {
            Some(p) => crate::export::export_print(
                &svg,
                crate::export::Print {
                    width_mm: p.width_mm,
                    dpi: p.dpi,
                },
            ),
            None => crate::export::export(&svg),
        }?;
        let mut files: Vec<(&'static str, Vec<u8>)> = FORMATS
            .into_iter()
            .zip([out.svg.into_bytes(), out.png, out.pdf])
            .collect();
        if self.print.is_some_and(|p| !p.draft) {
            files.push((CAPTION_EXT, self.caption_text().into_bytes()));
        }
        Ok(files)
    }

    /// Writes [`Figure::files`] into `dir` as `<name>.<extension>`, each atomically; returns
    /// their paths.
    pub fn write(&self, dir: &Path, name: &str) -> Result<Vec<PathBuf>, FigureError> {
        let files = self.files().map_err(|detail| FigureError::Draw {
            dir: dir.to_path_buf(),
            name: name.to_string(),
            detail,
        })?;
        let mut written = Vec::new();
        for (ext, bytes) in files {
            let path = dir.join(format!("{name}.{ext}"));
            write_atomic(&path, &bytes)?;
            written.push(path);
        }
        Ok(written)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use plotters::prelude::*;
    use plotters::style::colors::colormaps::ViridisRGB;
    use rocking_spectra::CellClass;
    use rocking_spectra::{Cell, Sweep};

    fn sweep() -> Sweep {
        Sweep {
            axes: vec![
                rocking_spectra::Axis::numbers("excitation.omega_p_over_p", vec![1.0, 2.0]),
                rocking_spectra::Axis::numbers("excitation.amplitude", vec![1.0, 2.0]),
            ],
            fingerprint: "test".into(),
            reported: Vec::new(),
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
                reported: Vec::new(),
            })
            .collect();
        cells.push(Cell {
            index: 3,
            class: CellClass::OverturnedOneImpact,
            max_theta_over_alpha: 15.7,
            impacts: 1,
            reported: Vec::new(),
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
            print: None,
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
        let texts: Vec<&str> = svg
            .split("</text>")
            .filter_map(|t| t.rsplit_once('>').map(|(_, v)| v.trim()))
            .collect();
        assert!(
            texts.contains(&"3") && !texts.contains(&"4"),
            "ticks: {texts:?}"
        );
    }

    #[test]
    fn a_reported_quantity_shades_every_upright_cell_on_its_own_range() {
        let mut s = sweep();
        s.reported = vec!["min_vertical_reaction_over_w".into()];
        let mut c = cells([0.2, 0.65, 1.3]);
        c[0].class = CellClass::NoUplift;
        for (cell, v) in c.iter_mut().zip([1.0, 0.4, -0.3, 0.1]) {
            cell.reported = vec![Some(v)];
        }
        let (figure, name) = reported_figure("t", &s, &c, 0);
        assert_eq!(name, "spectrum-min_vertical_reaction_over_w");
        assert!(is_sweep_figure(&format!("{name}.pdf")) && is_sweep_figure("spectrum.png"));
        assert!(!is_sweep_figure("spectrum-.svg") && !is_sweep_figure("cells.csv"));
        let svg = figure.svg().unwrap();
        let hex = |c: RGBColor| format!("fill=\"#{:02X}{:02X}{:02X}\"", c.0, c.1, c.2);
        // The scale runs from the lowest value (-0.3) to the highest (1.0, the no-uplift cell,
        // shaded too, not filled by its class); the overturned cell keeps its class.
        for v in [1.0, 0.4, -0.3] {
            let shade = hex(ViridisRGB.get_color_normalized(v, -0.3, 1.0));
            assert!(svg.contains(&shade), "{v}: {shade} missing");
        }
        assert!(!svg.contains(&hex(rgb_of(style::NO_UPLIFT.fill))));
        assert!(
            svg.contains("min R<tspan") || svg.contains("min R"),
            "colour bar title"
        );
        assert!(
            svg.contains("uplift | no uplift"),
            "the line around the no-uplift cells"
        );
    }

    /// An unbounded value (`inf`: the required friction of a run whose R_v falls below zero) is
    /// drawn in the top colour of a scale that the finite values set, and the legend says so.
    #[test]
    fn an_unbounded_reported_value_is_the_top_of_the_colour_bar_and_in_the_legend() {
        let mut s = sweep();
        s.reported = vec!["max_required_friction".into()];
        let mut c = cells([0.2, 0.65, 1.3]);
        for (cell, v) in c.iter_mut().zip([0.3, 0.6, f64::INFINITY, 2.0]) {
            cell.reported = vec![Some(v)];
        }
        let svg = reported_figure("t", &s, &c, 0).0.svg().unwrap();
        let hex = |c: RGBColor| format!("fill=\"#{:02X}{:02X}{:02X}\"", c.0, c.1, c.2);
        // The scale runs 0 .. 0.6 (the overturned cell's 2.0 is not shaded): 0.3 is its middle.
        let middle = hex(ViridisRGB.get_color_normalized(0.3, 0.0, 0.6));
        let top = hex(ViridisRGB.get_color_normalized(1.0, 0.0, 1.0));
        assert!(
            svg.contains(&middle),
            "{middle}: not on the finite values' scale"
        );
        // The top colour: the 0.6 cell, the unbounded cell and the legend's box.
        assert!(svg.matches(&top).count() >= 3, "{top}");
        // The legend wraps its text: its first words.
        let entry = &spectrum::UNBOUNDED_LABEL[..16];
        assert_eq!(entry, "unbounded (inf):");
        assert!(svg.contains(entry), "legend entry");
        // Without an unbounded cell, no such entry.
        c[2].reported = vec![Some(0.5)];
        let svg = reported_figure("t", &s, &c, 0).0.svg().unwrap();
        assert!(!svg.contains(entry));
    }

    /// A shaded cell whose run has no value (the time of an event that did not happen) is drawn
    /// crossed, off the colour scale, and the legend names it; the scale is the values'.
    #[test]
    fn a_cell_without_a_value_is_crossed_and_in_the_legend() {
        let mut s = sweep();
        s.reported = vec!["first_uplift_time".into()];
        let mut c = cells([0.2, 0.65, 1.3]);
        for (cell, v) in c.iter_mut().zip([Some(0.3), Some(0.6), None, Some(2.0)]) {
            cell.reported = vec![v];
        }
        let svg = reported_figure("t", &s, &c, 0).0.svg().unwrap();
        let hex = |c: RGBColor| format!("fill=\"#{:02X}{:02X}{:02X}\"", c.0, c.1, c.2);
        let middle = hex(ViridisRGB.get_color_normalized(0.3, 0.0, 0.6));
        assert!(svg.contains(&middle), "{middle}: the values' scale");
        // The cell and the legend's box, in the fill the hatching finds (style::hatch_svg).
        let no_value = "fill=\"#FFFFFD\"";
        assert_eq!(style::NO_VALUE.fill, [0xFF, 0xFF, 0xFD]);
        assert_eq!(svg.matches(no_value).count(), 2, "{svg}");
        let entry = &style::NO_VALUE.label[..9];
        assert_eq!(entry, "no value ");
        assert!(svg.contains(entry), "legend entry");
        c[2].reported = vec![Some(0.5)];
        let svg = reported_figure("t", &s, &c, 0).0.svg().unwrap();
        assert!(!svg.contains(entry));
        assert!(!svg.contains(no_value));
    }

    /// The friction map carries the contours at μ = 0.5 and 0.7 along the cell edges between
    /// upright cells below and at or above each level (an unbounded value is above both; an
    /// overturned cell borders neither), each in the legend and the caption.
    #[test]
    fn the_required_friction_map_has_contours_at_the_friction_a_footing_can_count_on() {
        let mut s = sweep();
        s.reported = vec![REQUIRED_FRICTION.into()];
        // Cells (ω_p/p, amplitude): (1, 1) 0.3, (1, 2) 0.6, (2, 1) inf, (2, 2) overturned.
        let mut c = cells([0.2, 0.65, 1.3]);
        for (cell, v) in c.iter_mut().zip([0.3, 0.6, f64::INFINITY, 5.0]) {
            cell.reported = vec![Some(v)];
        }
        let (figure, _) = reported_figure("t", &s, &c, 0);
        let Panel::Spectrum(panel) = &figure.panels[0] else {
            panic!("a spectrum panel")
        };
        // μ = 0.5: between 0.3 and both its neighbours (0.6 above, inf to the right).
        assert_eq!(
            panel.contour(0.5).unwrap(),
            &vec![vec![(1.5, 0.5), (1.5, 1.5), (0.5, 1.5)]]
        );
        // μ = 0.7: between 0.3 and inf only; 0.6 borders the overturned cell, not a contour.
        assert_eq!(
            panel.contour(0.7).unwrap(),
            &vec![vec![(1.5, 0.5), (1.5, 1.5)]]
        );
        let legend: Vec<String> = panel.legend().iter().map(LegendItem::key).collect();
        for (mu, dash) in [
            ("0.5", spectrum::CONTOUR_DASHES[0]),
            ("0.7", spectrum::CONTOUR_DASHES[1]),
        ] {
            let entry = format!("rule [0, 0, 0] Some({dash:?}) max |R_h|/R_v = {mu}");
            assert!(legend.contains(&entry), "{entry} not in {legend:?}");
        }
        figure.svg().unwrap();
        assert!(figure.caption.as_deref().unwrap().contains("μ = 0.5"));
        // Another quantity has none.
        s.reported = vec!["base_moment_ratio".into()];
        let (figure, _) = reported_figure("t", &s, &c, 0);
        let Panel::Spectrum(panel) = &figure.panels[0] else {
            panic!("a spectrum panel")
        };
        assert!(panel.contour(0.5).is_none());
    }

    /// A stated colour_top shades every panel on it even where the panels' values stay below it,
    /// and the survivors above it are counted (the command notes them).
    #[test]
    fn a_stated_colour_top_is_the_scale_of_every_panel_and_cells_above_it_are_counted() {
        let s = sweep();
        let low = cells([0.2, 0.65, 1.3]);
        let figure = |top: f64| Figure {
            title: "t".into(),
            caption: None,
            columns: 1,
            panel: (300, 300),
            panels: vec![Panel::Spectrum(SpectrumPanel::new(&s, &low))],
            colour_top: Some(top),
            print: None,
        };
        let hex = |c: RGBColor| format!("fill=\"#{:02X}{:02X}{:02X}\"", c.0, c.1, c.2);
        let svg = figure(4.0).svg().unwrap();
        let shared = hex(ViridisRGB.get_color_normalized(0.65, 0.0, 4.0));
        assert!(svg.contains(&shared), "{shared}: not on the stated scale");
        assert_eq!(figure(4.0).above_colour_top(), None);
        assert_eq!(figure(0.5).above_colour_top(), Some((0.5, 2)));
    }

    /// Fig. 9's safe band: per ω_p/p, from the lowest to the highest upright cell above the
    /// lowest overturning amplitude, each border refined between the upright cell and its
    /// overturned neighbour; a column without an upright cell above its line has none.
    #[test]
    fn the_safe_band_runs_between_its_overturned_neighbours() {
        let sweep = Sweep {
            axes: vec![
                rocking_spectra::Axis::numbers("excitation.omega_p_over_p", vec![1.0, 2.0]),
                rocking_spectra::Axis::numbers(
                    "excitation.amplitude",
                    vec![1.0, 2.0, 3.0, 4.0, 5.0, 6.0],
                ),
            ],
            fingerprint: "band".into(),
            reported: Vec::new(),
        };
        use CellClass::*;
        let first = [
            Survived,
            OverturnedOneImpact,
            Survived,
            Survived,
            OverturnedNoImpact,
            OverturnedNoImpact,
        ];
        let second = [
            Survived,
            OverturnedOneImpact,
            OverturnedOneImpact,
            OverturnedNoImpact,
            OverturnedNoImpact,
            OverturnedNoImpact,
        ];
        let cells: Vec<Cell> = first
            .iter()
            .chain(&second)
            .enumerate()
            .map(|(index, &class)| Cell {
                index,
                class,
                max_theta_over_alpha: 0.5,
                impacts: 1,
                reported: Vec::new(),
            })
            .collect();
        let mut asked = Vec::new();
        let s = Structure::new("s".into(), style::LINES[0], &sweep, &cells, |x, a, b| {
            asked.push((x, a, b));
            (a + b) / 2.0
        });
        assert_eq!(s.line, vec![vec![(1.0, 1.5), (2.0, 1.5)]]);
        assert_eq!(s.band, vec![vec![(1.0, 2.5, 4.5)]]);
        // The line's bracket, the band's bottom (upright 3 over overturned 2) and top (4, 5).
        assert_eq!(
            asked,
            vec![
                (1.0, 1.0, 2.0),
                (1.0, 3.0, 2.0),
                (1.0, 4.0, 5.0),
                (2.0, 1.0, 2.0)
            ]
        );
        let panel = BoundaryPanel::over(&sweep, vec![s], BOUNDARY_HEADING.into());
        assert!(panel
            .legend()
            .iter()
            .any(|i| i.key().contains("the safe band")));
    }

    fn rgb_of(c: [u8; 3]) -> RGBColor {
        RGBColor(c[0], c[1], c[2])
    }
}
