//! Time-history plots in the paper's style (Figs 3, 5, 10): θ/α, u/u_cr, E/E_ref and
//! ü_g/(g tan α) against τ in four stacked panels, impacts marked. PNG and SVG, with an embedded
//! font (DejaVu Sans, see assets/DejaVuSans-LICENSE.txt) so no system font is needed.

use std::path::{Path, PathBuf};
use std::sync::Once;

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::{register_font, FontStyle};
use rocking::{EventKind, Run};

use crate::model::Model;
use crate::report::write_atomic;
use crate::scene::CliError;

static FONT: &[u8] = include_bytes!("../assets/DejaVuSans.ttf");
static REGISTER: Once = Once::new();

const WIDTH: u32 = 900;
const HEIGHT: u32 = 1100;

fn register() {
    REGISTER.call_once(|| {
        // The font is bundled and known to be valid; a failure leaves text unrendered only.
        let _ = register_font("sans-serif", FontStyle::Normal, FONT);
    });
}

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
    let root = root
        .titled(title, ("sans-serif", 18).into_font())
        .map_err(e)?;
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
            mesh.x_desc("τ = p t");
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
pub fn plots(model: &Model, run: &Run, dir: &Path) -> Result<Vec<PathBuf>, CliError> {
    register();
    let d = model.structure.derived();
    let u = &model.units;
    let h = &run.history;
    let series = [
        Series {
            label: "θ/α",
            points: h.iter().map(|r| (r.tau, r.theta / u.alpha)).collect(),
        },
        Series {
            label: "u/u_cr",
            points: h.iter().map(|r| (r.tau, r.u / d.u_cr)).collect(),
        },
        Series {
            label: "E/E_ref",
            points: h.iter().map(|r| (r.tau, r.e_total)).collect(),
        },
        Series {
            label: "ü_g/(g tan α)",
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

    let fail = |what: &str, m: String| CliError::Internal(format!("cannot draw the {what}: {m}"));
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
fn encode_png(rgb: &[u8], w: u32, h: u32) -> Result<Vec<u8>, String> {
    use image::ImageEncoder;
    let mut out = Vec::new();
    image::codecs::png::PngEncoder::new(&mut out)
        .write_image(rgb, w, h, image::ColorType::Rgb8)
        .map_err(|e| e.to_string())?;
    Ok(out)
}
