//! Figures, each as PNG and SVG with the font embedded by `rocking_plot` (no system font is
//! needed). Here: the time history in the paper's style (Figs 3, 5, 10: θ/α, u/u_cr, E/E_ref and
//! ü_g/(g tan α) against τ in four stacked panels, impacts marked) and the fragility curve of a
//! batch; `spectrum`: rocking spectra, overturning boundaries and one-axis line plots; `contour`:
//! marching squares. The animated GIF of a run is `rocking_plot::animation` (shared with the
//! Python package). Labels come from `rocking_scene::labels`.

pub mod contour;
mod spectrum;

pub use spectrum::{spectrum_plots, Reference};

use std::path::{Path, PathBuf};

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor;
use rocking::{EventKind, Run};
use rocking_scene::labels;

use crate::out_dir::write_atomic;
use rocking_scene::setup::Setup;
use rocking_scene::SceneError;

pub(crate) use rocking_plot::{register, wrap};

const WIDTH: u32 = 900;
const HEIGHT: u32 = 1100;

struct Series<'a> {
    label: &'a str,
    points: Vec<(f64, f64)>,
}

fn range(points: &[(f64, f64)]) -> (f64, f64) {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for &(_, y) in points {
        if y.is_finite() {
            lo = lo.min(y);
            hi = hi.max(y);
        }
    }
    if !lo.is_finite() || !hi.is_finite() {
        return (-1.0, 1.0);
    }
    let pad = ((hi - lo) * 0.08).max(1e-9 + 0.05 * hi.abs().max(lo.abs()));
    let (lo, hi) = (lo - pad, hi + pad);
    if hi - lo < 1e-12 {
        (lo - 1.0, hi + 1.0)
    } else {
        (lo, hi)
    }
}

fn draw<DB: DrawingBackend>(
    root: DrawingArea<DB, Shift>,
    title: &str,
    series: &[Series<'_>],
    impacts: &[f64],
    t_max: f64,
) -> Result<(), String> {
    let e = |e: DrawingAreaErrorKind<DB::ErrorType>| e.to_string();
    root.fill(&WHITE).map_err(e)?;
    let root = titled(root, title, 18)?;
    let panels = root.split_evenly((series.len(), 1));
    for (i, (area, s)) in panels.iter().zip(series).enumerate() {
        let (lo, hi) = range(&s.points);
        let last = i + 1 == series.len();
        let mut chart = ChartBuilder::on(area)
            .margin(8)
            .margin_right(20)
            .x_label_area_size(if last { 45 } else { 25 })
            .y_label_area_size(70)
            .build_cartesian_2d(0.0..t_max, lo..hi)
            .map_err(e)?;
        let mut mesh = chart.configure_mesh();
        mesh.light_line_style(RGBColor(235, 235, 235))
            .y_desc(s.label)
            .label_style(("sans-serif", 15))
            .axis_desc_style(("sans-serif", 18));
        if last {
            mesh.x_desc(labels::TAU);
        }
        mesh.draw().map_err(e)?;
        // Impacts: thin vertical lines in every panel.
        for &t in impacts {
            chart
                .draw_series(LineSeries::new(
                    [(t, lo), (t, hi)],
                    RGBColor(230, 140, 140).stroke_width(1),
                ))
                .map_err(e)?;
        }
        if lo < 0.0 && hi > 0.0 {
            chart
                .draw_series(LineSeries::new(
                    [(0.0, 0.0), (t_max, 0.0)],
                    BLACK.mix(0.4).stroke_width(1),
                ))
                .map_err(e)?;
        }
        chart
            .draw_series(LineSeries::new(
                s.points.iter().copied(),
                // Thick polylines render steep, dense segments (records) with artefacts.
                RGBColor(20, 60, 160).stroke_width(if s.points.len() > 5000 || i == 3 {
                    1
                } else {
                    2
                }),
            ))
            .map_err(e)?;
        if i == 0 {
            // Impacts on the θ/α panel: red dots at θ = 0, as in the paper's figures.
            chart
                .draw_series(
                    impacts
                        .iter()
                        .map(|&t| Circle::new((t, 0.0), 4, RGBColor(200, 0, 0).filled())),
                )
                .map_err(e)?;
        }
    }
    root.present().map_err(e)?;
    Ok(())
}

/// Writes plot.png and plot.svg into `dir` (atomically); returns their paths.
pub fn plots(model: &Setup, run: &Run, dir: &Path) -> Result<Vec<PathBuf>, SceneError> {
    register();
    let d = model.structure.derived();
    let u = &model.units;
    let h = &run.history;
    let series = [
        Series {
            label: labels::THETA_OVER_ALPHA,
            points: h.iter().map(|r| (r.tau, r.theta / u.alpha)).collect(),
        },
        Series {
            label: labels::U_OVER_UCR,
            points: h.iter().map(|r| (r.tau, r.u / d.u_cr)).collect(),
        },
        Series {
            label: labels::E_OVER_EREF,
            points: h.iter().map(|r| (r.tau, r.e_total)).collect(),
        },
        Series {
            label: labels::UG_OVER_G_TAN_ALPHA,
            points: h
                .iter()
                .map(|r| (r.tau, r.ug / u.accel_g_tan_alpha()))
                .collect(),
        },
    ];
    let impacts: Vec<f64> = run
        .events
        .iter()
        .filter(|e| e.kind == EventKind::Impact)
        .map(|e| e.time.tau)
        .collect();
    let t_max = h
        .last()
        .map(|r| r.tau)
        .unwrap_or(run.summary.end_time.tau)
        .max(1e-6);
    let mut title = model
        .title
        .clone()
        .unwrap_or_else(|| model.excitation_description.clone());
    title.push_str(&format!("  [{}]", run.summary.kernel_variant));

    let fail = |what: &str, m: String| SceneError::failure(format!("cannot draw the {what}: {m}"));
    let mut written = Vec::new();
    // PNG: render into a buffer, encode, write atomically.
    let mut buf = vec![0u8; (WIDTH * HEIGHT * 3) as usize];
    {
        let root = BitMapBackend::with_buffer(&mut buf, (WIDTH, HEIGHT)).into_drawing_area();
        draw(root, &title, &series, &impacts, t_max).map_err(|m| fail("PNG plot", m))?;
    }
    let png = encode_png(&buf, WIDTH, HEIGHT).map_err(|m| fail("PNG plot", m))?;
    let path = dir.join("plot.png");
    write_atomic(&path, &png)?;
    written.push(path);
    // SVG.
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (WIDTH, HEIGHT)).into_drawing_area();
        draw(root, &title, &series, &impacts, t_max).map_err(|m| fail("SVG plot", m))?;
    }
    let path = dir.join("plot.svg");
    write_atomic(&path, svg.as_bytes())?;
    written.push(path);
    Ok(written)
}

/// PNG encoding of an RGB buffer through the `image` crate that plotters' bitmap backend uses.
pub(crate) fn encode_png(rgb: &[u8], w: u32, h: u32) -> Result<Vec<u8>, String> {
    use image::ImageEncoder;
    let mut out = Vec::new();
    image::codecs::png::PngEncoder::new(&mut out)
        .write_image(rgb, w, h, image::ColorType::Rgb8)
        .map_err(|e| e.to_string())?;
    Ok(out)
}

fn draw_fragility<DB: DrawingBackend>(
    root: DrawingArea<DB, Shift>,
    points: &[(f64, f64)],
    records: usize,
) -> Result<(), String> {
    let e = |e: DrawingAreaErrorKind<DB::ErrorType>| e.to_string();
    root.fill(&WHITE).map_err(e)?;
    let x_hi = points.iter().map(|p| p.0).fold(0.0, f64::max) * 1.05;
    let root = titled(
        root,
        &format!("Fraction of {records} records that overturn"),
        20,
    )?;
    let mut chart = ChartBuilder::on(&root)
        .margin(12)
        .x_label_area_size(45)
        .y_label_area_size(60)
        .build_cartesian_2d(0.0..x_hi.max(1e-9), 0.0..1.05)
        .map_err(e)?;
    chart
        .configure_mesh()
        .x_desc(labels::SCALE_FACTOR)
        .y_desc(labels::FRACTION_OVERTURNED)
        .label_style(("sans-serif", 14))
        .draw()
        .map_err(e)?;
    chart
        .draw_series(LineSeries::new(points.to_vec(), BLUE.stroke_width(2)))
        .map_err(e)?;
    chart
        .draw_series(points.iter().map(|&p| Circle::new(p, 4, BLUE.filled())))
        .map_err(e)?;
    root.present().map_err(e)
}

/// The fragility-style curve of a record suite, as PNG and SVG.
pub fn fragility_plots(
    points: &[(f64, f64)],
    records: usize,
    dir: &Path,
) -> Result<Vec<PathBuf>, SceneError> {
    register();
    render_pair(
        dir,
        "fragility",
        (800, 560),
        |r| draw_fragility(r, points, records),
        |r| draw_fragility(r, points, records),
    )
}

/// Renders a figure to `<name>.png` and `<name>.svg` in `dir`, each written atomically.
pub(crate) fn render_pair(
    dir: &Path,
    name: &str,
    size: (u32, u32),
    png: impl FnOnce(DrawingArea<BitMapBackend<'_>, Shift>) -> Result<(), String>,
    svg: impl FnOnce(DrawingArea<SVGBackend<'_>, Shift>) -> Result<(), String>,
) -> Result<Vec<PathBuf>, SceneError> {
    let fail = |what: &str, m: String| {
        SceneError::failure(format!("{}: cannot draw the {what}: {m}", dir.display()))
    };
    let mut pixels = vec![255u8; (size.0 * size.1 * 3) as usize];
    png(BitMapBackend::with_buffer(&mut pixels, size).into_drawing_area())
        .map_err(|m| fail("PNG", m))?;
    let bytes = encode_png(&pixels, size.0, size.1).map_err(|m| fail("PNG", m))?;
    let png_path = dir.join(format!("{name}.png"));
    write_atomic(&png_path, &bytes)?;
    let mut text = String::new();
    svg(SVGBackend::with_string(&mut text, size).into_drawing_area())
        .map_err(|m| fail("SVG", m))?;
    let svg_path = dir.join(format!("{name}.svg"));
    write_atomic(&svg_path, text.as_bytes())?;
    Ok(vec![png_path, svg_path])
}

/// Draws `title` centred at the top of `root`, wrapped to its width (never cut), and returns the
/// area below it.
pub(crate) fn titled<DB: DrawingBackend>(
    root: DrawingArea<DB, Shift>,
    title: &str,
    size: u32,
) -> Result<DrawingArea<DB, Shift>, String> {
    let e = |e: DrawingAreaErrorKind<DB::ErrorType>| e.to_string();
    let width = root.dim_in_pixel().0;
    // DejaVu Sans averages about 0.55 em per character; 40 px of margin.
    let chars = ((width.saturating_sub(40)) as f64 / (0.58 * size as f64)).max(10.0) as usize;
    let lines = wrap(title, chars);
    let line_height = (size as f64 * 1.35) as u32;
    let (top, rest) = root.split_vertically(line_height * lines.len() as u32 + 12);
    let style = ("sans-serif", size)
        .into_font()
        .into_text_style(&top)
        .pos(text_anchor::Pos::new(
            text_anchor::HPos::Center,
            text_anchor::VPos::Top,
        ));
    for (i, line) in lines.iter().enumerate() {
        top.draw_text(
            line,
            &style,
            ((width / 2) as i32, 8 + (i as u32 * line_height) as i32),
        )
        .map_err(e)?;
    }
    Ok(rest)
}
