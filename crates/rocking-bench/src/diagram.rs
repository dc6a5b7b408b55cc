//! Work-precision diagrams: a case's error against CPU time per simulation, log-log, one line
//! per integrator (the Rust methods and the peers), each point a tolerance labelled with its
//! exponent. A diagram is data ([`Diagram`], written beside its images as JSON) drawn through
//! `rocking_plot::chart` like the `rocking` command's figures: the same page, typography and
//! palette, the legend beside the panels. `rocking-bench redraw` draws the committed images
//! again from their JSON, byte for byte (a test checks it).

use std::path::{Path, PathBuf};

use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use rocking_plot::chart::{
    fail, legend, log_axes, mark_at, pixel, rgb, styled_line, text_lines, Area, LegendItem, Page,
    LEGEND, TICKS,
};
use rocking_plot::style::{self, LineStyle};
use serde::{Deserialize, Serialize};

use crate::Result;

/// The least error drawn: a smaller one (or 0) is drawn here.
pub const FLOOR: f64 = 1e-16;

/// The lines a diagram may hold, in legend order, each with its style.
pub const SERIES: [(&str, LineStyle); 5] = [
    ("dopri5 (Rust)", style::LINES[0]),
    ("dop853 (Rust)", style::LINES[1]),
    ("taylor (Rust)", style::LINES[2]),
    ("SciPy DOP853", style::LINES[3]),
    ("heyoka Taylor", style::BLACK),
];

/// A work-precision diagram of one case.
#[derive(Debug, Serialize, Deserialize)]
pub struct Diagram {
    pub title: String,
    pub panels: Vec<DiagramPanel>,
}

/// One error measure of a case.
#[derive(Debug, Serialize, Deserialize)]
pub struct DiagramPanel {
    /// The y axis label (the measure).
    pub label: String,
    pub series: Vec<Series>,
}

/// One integrator's runs.
#[derive(Debug, Serialize, Deserialize)]
pub struct Series {
    /// One of [`SERIES`].
    pub name: String,
    /// (CPU s per simulation, error, tolerance) per run.
    pub points: Vec<[f64; 3]>,
}

const X_LABEL: &str = "CPU time per simulation (s)";

impl Diagram {
    fn style(name: &str) -> Result<LineStyle> {
        SERIES
            .iter()
            .find(|(n, _)| *n == name)
            .map(|(_, s)| *s)
            .ok_or_else(|| format!("a diagram's series {name:?} is not one of {SERIES:?}").into())
    }

    /// Whether any error is drawn at the floor (in a panel that is plotted).
    fn floored(&self) -> bool {
        self.panels
            .iter()
            .filter(|p| !p.all_zero())
            .flat_map(|p| p.points())
            .any(|p| p[1] < FLOOR)
    }

    fn caption(&self) -> String {
        let mut c = "Log-log. A point: one run of the case at one tolerance, the number beside it \
                     the tolerance's exponent (−8: tol = 10⁻⁸; where labels would overlap, some \
                     are left out)."
            .to_string();
        if self.floored() {
            c.push_str(" An error below 10⁻¹⁶ (or zero) is drawn at 10⁻¹⁶.");
        }
        c
    }

    /// The diagram as SVG (before `rocking_plot::export` finishes it).
    pub fn svg(&self) -> Result<String> {
        for s in self.panels.iter().flat_map(|p| &p.series) {
            Diagram::style(&s.name)?;
        }
        let title = format!("Work-precision: {}", self.title);
        let caption = self.caption();
        let page = Page {
            title: &title,
            caption: Some(&caption),
            columns: self.panels.len().max(1),
            panels: self.panels.len(),
            panel: (560, 470),
            legend: true,
        };
        let svg = page.svg(|areas, side| {
            for (panel, area) in self.panels.iter().zip(areas) {
                panel.draw(area)?;
            }
            let items: Vec<LegendItem> = SERIES
                .iter()
                .filter(|(n, _)| {
                    self.panels.iter().any(|p| {
                        p.series
                            .iter()
                            .any(|s| s.name == *n && !s.points.is_empty())
                    })
                })
                .map(|(n, s)| LegendItem::Line(*s, n.to_string()))
                .collect();
            legend(side, 10, &items)
        })?;
        Ok(svg)
    }

    /// Writes `<name>.json` (this data), `<name>.svg` and `<name>.png` into `dir`.
    pub fn write(&self, dir: &Path, name: &str) -> Result<Vec<PathBuf>> {
        let out = rocking_plot::export::export(&self.svg()?)?;
        let json = serde_json::to_string_pretty(self)? + "\n";
        let mut written = Vec::new();
        for (ext, bytes) in [
            ("json", json.as_bytes()),
            ("svg", out.svg.as_bytes()),
            ("png", &out.png[..]),
        ] {
            let path = dir.join(format!("{name}.{ext}"));
            std::fs::write(&path, bytes).map_err(|e| format!("{}: {e}", path.display()))?;
            written.push(path);
        }
        Ok(written)
    }
}

impl DiagramPanel {
    fn points(&self) -> impl Iterator<Item = &[f64; 3]> {
        self.series.iter().flat_map(|s| &s.points)
    }

    /// Whether every error is below the floor: nothing to show on a log axis.
    fn all_zero(&self) -> bool {
        self.points().all(|p| p[1] < FLOOR)
    }

    fn draw(&self, area: &Area<'_>) -> std::result::Result<(), String> {
        let points = || self.points();
        let (mut x0, mut x1, mut y0, mut y1) = (f64::INFINITY, f64::NEG_INFINITY, 0.0, 0.0);
        let mut any = false;
        for p in points() {
            let (x, y) = (p[0].log10(), p[1].max(FLOOR).log10());
            if !any {
                (y0, y1) = (y, y);
                any = true;
            }
            (x0, x1, y0, y1) = (x0.min(x), x1.max(x), y0.min(y), y1.max(y));
        }
        if !any {
            return Ok(());
        }
        if self.all_zero() {
            return self.note(area, "every run: error 0 (below 10⁻¹⁶)");
        }
        // Whole decades, and a little room for the labels.
        let x = ((x0 - 0.05).floor(), (x1 + 0.05).ceil());
        let y = ((y0 - 0.05).floor(), (y1 + 0.05).ceil());
        let mut chart = log_axes(area, None, x, y, (X_LABEL, &self.label))?;
        // Markers and lines first, then the labels where they cover neither nor each other.
        let mut taken: Vec<(i32, i32, i32, i32)> = Vec::new();
        for s in &self.series {
            let style = Diagram::style(&s.name).map_err(|e| e.to_string())?;
            let xy: Vec<(f64, f64)> = s
                .points
                .iter()
                .map(|p| (p[0].log10(), p[1].max(FLOOR).log10()))
                .collect();
            styled_line(&mut chart, xy.clone(), &style, rgb(style.colour), 2)?;
            for &q in &xy {
                mark_at(&chart, style.marker, q, 4, rgb(style.colour), true)?;
                let (px, py) = pixel(&chart, q);
                taken.push((px - 5, py - 5, px + 5, py + 5));
            }
        }
        let plot = chart.plotting_area().strip_coord_spec();
        let (w, h) = plot.dim_in_pixel();
        let font = ("sans-serif", TICKS - 3)
            .into_font()
            .into_text_style(&plot)
            .pos(Pos::new(HPos::Left, VPos::Center));
        for s in &self.series {
            let style = Diagram::style(&s.name).map_err(|e| e.to_string())?;
            for p in &s.points {
                let (px, py) = pixel(&chart, (p[0].log10(), p[1].max(FLOOR).log10()));
                let text = exponent(p[2]);
                let width = 7 * text.chars().count() as i32;
                // Right of the point, else left of it, else above or below on the right.
                let free = [(7, 0), (-7 - width, 0), (5, -13), (5, 13)]
                    .into_iter()
                    .map(|(dx, dy)| (px + dx, py + dy - 7, px + dx + width, py + dy + 7))
                    .find(|r| {
                        r.0 >= 0
                            && r.2 <= w as i32
                            && r.1 >= 0
                            && r.3 <= h as i32
                            && !taken.iter().any(|t| overlap(*t, *r))
                    });
                let Some(rect) = free else { continue };
                taken.push(rect);
                let colour = rgb(style.colour);
                plot.draw_text(&text, &font.color(&colour), (rect.0, rect.1 + 7))
                    .map_err(fail)?;
            }
        }
        Ok(())
    }

    /// A panel with nothing to plot on log axes: its measure and why, in a frame.
    fn note(&self, area: &Area<'_>, why: &str) -> std::result::Result<(), String> {
        let (w, h) = area.dim_in_pixel();
        area.draw(&Rectangle::new(
            [(82, 10), (w as i32 - 18, h as i32 - 62)],
            RGBColor(200, 200, 200),
        ))
        .map_err(fail)?;
        let lines = [format!("{}:", self.label), why.to_string()];
        text_lines(
            area,
            &lines,
            LEGEND,
            (w as i32 + 64) / 2,
            h as i32 / 2 - 30,
            HPos::Center,
        )
    }
}

/// The label of a tolerance: its exponent ("−8" for 1e-8), or the tolerance itself when it is
/// not a power of ten.
fn exponent(tol: f64) -> String {
    let e = tol.log10();
    if (e - e.round()).abs() < 1e-9 {
        let k = e.round() as i32;
        if k < 0 {
            format!("\u{2212}{}", -k)
        } else {
            k.to_string()
        }
    } else {
        rocking_plot::text::tick(tol)
    }
}

fn overlap(a: (i32, i32, i32, i32), b: (i32, i32, i32, i32)) -> bool {
    a.0 < b.2 && b.0 < a.2 && a.1 < b.3 && b.1 < a.3
}

/// Draws `DOCS/img/accuracy-*.svg` and `.png` again from their `.json`; returns the files.
pub fn redraw(docs: &Path) -> Result<Vec<PathBuf>> {
    let mut written = Vec::new();
    for (name, diagram) in committed(docs)? {
        written.extend(diagram.write(&docs.join("img"), &name)?);
    }
    Ok(written)
}

/// The diagrams whose data is in `DOCS/img/accuracy-*.json`, by name, sorted.
pub fn committed(docs: &Path) -> Result<Vec<(String, Diagram)>> {
    let img = docs.join("img");
    let mut out = Vec::new();
    for entry in std::fs::read_dir(&img).map_err(|e| format!("{}: {e}", img.display()))? {
        let path = entry?.path();
        let name = path
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_default();
        if !(name.starts_with("accuracy-") && path.extension().is_some_and(|e| e == "json")) {
            continue;
        }
        let text = std::fs::read_to_string(&path)?;
        let diagram: Diagram =
            serde_json::from_str(&text).map_err(|e| format!("{}: {e}", path.display()))?;
        out.push((name, diagram));
    }
    out.sort_by(|a, b| a.0.cmp(&b.0));
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The committed work-precision images are what their committed data draws.
    #[test]
    fn the_committed_diagrams_are_redrawn_byte_for_byte() {
        let docs = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../docs");
        let diagrams = committed(&docs).unwrap();
        assert!(diagrams.len() >= 8, "{} diagrams", diagrams.len());
        for (name, d) in diagrams {
            let out = rocking_plot::export::export(&d.svg().unwrap()).unwrap();
            let img = docs.join("img");
            let svg = std::fs::read_to_string(img.join(format!("{name}.svg"))).unwrap();
            assert!(svg == out.svg, "{name}.svg differs from a redraw");
            let png = std::fs::read(img.join(format!("{name}.png"))).unwrap();
            assert!(png == out.png, "{name}.png differs from a redraw");
        }
    }

    fn diagram(errors: &[f64]) -> Diagram {
        Diagram {
            title: "test: ω_n/p = 5".into(),
            panels: vec![DiagramPanel {
                label: "error in max |θ|/α".into(),
                series: vec![Series {
                    name: "dopri5 (Rust)".into(),
                    points: errors
                        .iter()
                        .enumerate()
                        .map(|(k, &e)| [1e-4 * (1.0 + k as f64), e, 10f64.powi(-3 - k as i32)])
                        .collect(),
                }],
            }],
        }
    }

    #[test]
    fn ticks_are_powers_of_ten_and_points_are_explained() {
        let svg = diagram(&[1e-5, 1e-7, 1e-9]).svg().unwrap();
        let texts: Vec<&str> = svg
            .split("</text>")
            .filter_map(|t| t.rsplit_once('>').map(|(_, v)| v.trim()))
            .collect();
        for t in ["10⁻⁴", "10⁻⁶", "10⁻⁸", "\u{2212}3", "\u{2212}5"] {
            assert!(texts.contains(&t), "{t} not in {texts:?}");
        }
        // No tick in the old "1e-5" style, no "-0", no ".0".
        for t in &texts {
            assert!(!t.contains("e-") && !t.ends_with(".0") && *t != "-0", "{t}");
        }
        assert!(
            svg.contains("the number beside it the tolerance"),
            "the labels are explained"
        );
        // The legend is in its column, right of the panels (x beyond their 560 pixels).
        let legend = svg.find(">\ndopri5 (Rust)\n<").unwrap();
        let x: i32 = svg[..legend]
            .rsplit_once(" x=\"")
            .and_then(|(_, r)| r.split('"').next())
            .and_then(|v| v.parse().ok())
            .unwrap();
        assert!(x > 560, "legend at x = {x}");
    }

    #[test]
    fn an_all_zero_measure_is_said_not_plotted() {
        let svg = diagram(&[0.0, 0.0, 0.0]).svg().unwrap();
        assert!(svg.contains("every run: error 0"), "{svg}");
        assert!(!svg.contains("10⁻¹⁶<"), "no log axis at the floor");
    }

    #[test]
    fn an_unknown_series_is_refused() {
        let mut d = diagram(&[1e-5]);
        d.panels[0].series[0].name = "rk4".into();
        assert!(d.svg().unwrap_err().to_string().contains("rk4"));
    }
}
