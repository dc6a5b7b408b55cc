//! Plots of `rocking ida`: the IDA curves (IM against max θ/α, one line per record, collapses
//! marked) and the fitted fragility curve with its bootstrap band and the empirical capacities.
//! PNG and SVG with the embedded font of the other plots.

use std::path::{Path, PathBuf};

use plotters::coord::Shift;
use plotters::prelude::*;
use rocking_fragility::Bootstrap;
use rocking_plot::register;

use crate::out_dir::write_atomic;
use rocking_scene::SceneError;

const SIZE: (u32, u32) = (800, 560);
/// Where the IDA curves put a collapse: max θ/α of an overturned run is not a response.
const COLLAPSE_X: f64 = 1.1;

/// One record's IDA curve: (max θ/α, IM, collapsed) per analysis.
pub type Points = Vec<(f64, f64, bool)>;

fn draw_ida<DB: DrawingBackend>(
    root: DrawingArea<DB, Shift>,
    curves: &[(String, Points)],
    im_label: &str,
) -> Result<(), String> {
    let e = |e: DrawingAreaErrorKind<DB::ErrorType>| e.to_string();
    root.fill(&WHITE).map_err(e)?;
    let y_hi = curves
        .iter()
        .flat_map(|c| c.1.iter().map(|p| p.1))
        .fold(0.0, f64::max)
        * 1.05;
    let mut chart = ChartBuilder::on(&root)
        .caption(
            format!(
                "IDA curves of {} records (x at {COLLAPSE_X}: overturned)",
                curves.len()
            ),
            ("sans-serif", 20),
        )
        .margin(12)
        .x_label_area_size(45)
        .y_label_area_size(60)
        .build_cartesian_2d(0.0..COLLAPSE_X + 0.05, 0.0..y_hi.max(1e-9))
        .map_err(e)?;
    chart
        .configure_mesh()
        .x_desc("max θ/α")
        .y_desc(im_label)
        .label_style(("sans-serif", 14))
        .draw()
        .map_err(e)?;
    for (k, (_, pts)) in curves.iter().enumerate() {
        let colour = Palette99::pick(k).mix(0.8);
        let xy: Vec<(f64, f64)> = pts
            .iter()
            .map(|&(r, im, c)| (if c { COLLAPSE_X } else { r.min(COLLAPSE_X) }, im))
            .collect();
        // the curve up to the first collapse
        let end = pts.iter().position(|p| p.2).map_or(xy.len(), |i| i + 1);
        chart
            .draw_series(LineSeries::new(xy[..end].to_vec(), colour.stroke_width(1)))
            .map_err(e)?;
        chart
            .draw_series(xy.iter().map(|&p| Circle::new(p, 2, colour.filled())))
            .map_err(e)?;
    }
    root.present().map_err(e)
}

fn draw_fit<DB: DrawingBackend>(
    root: DrawingArea<DB, Shift>,
    empirical: &[(f64, f64)],
    records: usize,
    fit: &Bootstrap,
    im_label: &str,
) -> Result<(), String> {
    let e = |e: DrawingAreaErrorKind<DB::ErrorType>| e.to_string();
    root.fill(&WHITE).map_err(e)?;
    let x_hi = empirical.iter().map(|p| p.0).fold(0.0, f64::max) * 1.2;
    let mut chart = ChartBuilder::on(&root)
        .caption(
            format!(
                "Fragility: median {:.3} m/s², β = {:.3} ({} records)",
                fit.estimate.theta, fit.estimate.beta, records
            ),
            ("sans-serif", 20),
        )
        .margin(12)
        .x_label_area_size(45)
        .y_label_area_size(60)
        .build_cartesian_2d(0.0..x_hi.max(1e-9), 0.0..1.02)
        .map_err(e)?;
    chart
        .configure_mesh()
        .x_desc(im_label)
        .y_desc("P(overturning | IM)")
        .label_style(("sans-serif", 14))
        .draw()
        .map_err(e)?;
    let xs: Vec<f64> = (1..=200).map(|i| x_hi * i as f64 / 200.0).collect();
    let band: Vec<(f64, f64)> = xs
        .iter()
        .map(|&x| fit.band(x))
        .map(|(a, b)| (a.min(b), a.max(b)))
        .collect();
    let mut poly: Vec<(f64, f64)> = xs.iter().zip(&band).map(|(&x, b)| (x, b.0)).collect();
    poly.extend(xs.iter().zip(&band).rev().map(|(&x, b)| (x, b.1)));
    chart
        .draw_series(std::iter::once(Polygon::new(poly, BLUE.mix(0.15).filled())))
        .map_err(e)?;
    chart
        .draw_series(LineSeries::new(
            xs.iter().map(|&x| (x, fit.estimate.probability(x))),
            BLUE.stroke_width(2),
        ))
        .map_err(e)?;
    chart
        .draw_series(
            empirical
                .iter()
                .map(|&(x, p)| Circle::new((x, p), 3, BLACK.filled())),
        )
        .map_err(e)?;
    root.present().map_err(e)
}

fn encode_png(rgb: &[u8], w: u32, h: u32) -> Result<Vec<u8>, String> {
    use image::ImageEncoder;
    let mut out = Vec::new();
    image::codecs::png::PngEncoder::new(&mut out)
        .write_image(rgb, w, h, image::ColorType::Rgb8)
        .map_err(|e| e.to_string())?;
    Ok(out)
}

/// Writes `<name>.png` and `<name>.svg` into `dir`, each atomically.
fn pair(
    dir: &Path,
    name: &str,
    png: impl FnOnce(DrawingArea<BitMapBackend<'_>, Shift>) -> Result<(), String>,
    svg: impl FnOnce(DrawingArea<SVGBackend<'_>, Shift>) -> Result<(), String>,
) -> Result<Vec<PathBuf>, SceneError> {
    register();
    let fail =
        |m: String| SceneError::failure(format!("{}: cannot draw {name}: {m}", dir.display()));
    let mut pixels = vec![255u8; (SIZE.0 * SIZE.1 * 3) as usize];
    png(BitMapBackend::with_buffer(&mut pixels, SIZE).into_drawing_area()).map_err(fail)?;
    let png_path = dir.join(format!("{name}.png"));
    write_atomic(
        &png_path,
        &encode_png(&pixels, SIZE.0, SIZE.1).map_err(fail)?,
    )?;
    let mut text = String::new();
    svg(SVGBackend::with_string(&mut text, SIZE).into_drawing_area()).map_err(fail)?;
    let svg_path = dir.join(format!("{name}.svg"));
    write_atomic(&svg_path, text.as_bytes())?;
    Ok(vec![png_path, svg_path])
}

/// `ida.png`/`ida.svg`: per record (name, [(max θ/α, IM, collapsed)]) sorted by IM.
pub fn ida_curves(
    curves: &[(String, Points)],
    im_label: &str,
    dir: &Path,
) -> Result<Vec<PathBuf>, SceneError> {
    pair(
        dir,
        "ida",
        |r| draw_ida(r, curves, im_label),
        |r| draw_ida(r, curves, im_label),
    )
}

/// `fragility-fit.png`/`.svg`: the fitted curve, its band and the empirical points (the
/// capacities' empirical CDF for IDA, the fraction collapsed per stripe for stripes).
pub fn fragility_fit(
    empirical: &[(f64, f64)],
    records: usize,
    fit: &Bootstrap,
    im_label: &str,
    dir: &Path,
) -> Result<Vec<PathBuf>, SceneError> {
    pair(
        dir,
        "fragility-fit",
        |r| draw_fit(r, empirical, records, fit, im_label),
        |r| draw_fit(r, empirical, records, fit, im_label),
    )
}
