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

/// Grey of a survivor with max θ/α = `theta`, on a scale that ends at `top` (black).
fn grey(theta: f64, top: f64) -> RGBColor {
    let v = (1.0 - (theta / top).clamp(0.0, 1.0)) * 225.0 + 20.0;
    RGBColor(v as u8, v as u8, v as u8)
}

/// Colour of a spectrum cell: the overturning classes as regions (as in the paper's Figs 6-8),
/// survivors shaded by max θ/α (white = 0, black = the largest survivor of the sweep).
fn cell_colour(c: &rocking_spectra::Cell, top: f64) -> RGBColor {
    use rocking_spectra::CellClass::*;
    match c.class {
        NoUplift => RGBColor(236, 240, 244),
        Survived => grey(c.max_theta_over_alpha, top),
        OverturnedNoImpact => RGBColor(60, 110, 200),
        OverturnedOneImpact => RGBColor(150, 90, 40),
        OverturnedImpacts => RGBColor(230, 150, 40),
        Failed => RGBColor(220, 30, 30),
    }
}

fn draw_spectrum<DB: DrawingBackend>(
    root: DrawingArea<DB, Shift>,
    title: &str,
    sweep: &rocking_spectra::Sweep,
    cells: &[rocking_spectra::Cell],
) -> Result<(), String> {
    let e = |e: DrawingAreaErrorKind<DB::ErrorType>| e.to_string();
    let top = cells
        .iter()
        .filter(|c| c.class == rocking_spectra::CellClass::Survived)
        .map(|c| c.max_theta_over_alpha)
        .fold(1e-9, f64::max);
    root.fill(&WHITE).map_err(e)?;
    let (plot_area, legend) = root.split_horizontally(WIDTH - 230);
    let n = sweep.axes.len();
    let (ax, ay) = (&sweep.axes[n - 2], &sweep.axes[n - 1]);
    let span = |v: &[f64]| {
        let (lo, hi) = (v[0].min(v[v.len() - 1]), v[0].max(v[v.len() - 1]));
        let h = if v.len() > 1 {
            (hi - lo) / (v.len() - 1) as f64 / 2.0
        } else {
            0.5
        };
        (lo - h, hi + h, h)
    };
    let (x0, x1, hx) = span(&ax.values);
    let (y0, y1, hy) = span(&ay.values);
    let mut chart = ChartBuilder::on(&plot_area)
        .caption(title, ("sans-serif", 17))
        .margin(12)
        .x_label_area_size(45)
        .y_label_area_size(60)
        .build_cartesian_2d(x0..x1, y0..y1)
        .map_err(e)?;
    chart
        .configure_mesh()
        .disable_mesh()
        .x_desc(ax.key.as_str())
        .y_desc(ay.key.as_str())
        .label_style(("sans-serif", 14))
        .draw()
        .map_err(e)?;
    if n == 2 {
        chart
            .draw_series(cells.iter().map(|c| {
                let v = sweep.values(c.index);
                Rectangle::new(
                    [(v[0] - hx, v[1] - hy), (v[0] + hx, v[1] + hy)],
                    cell_colour(c, top).filled(),
                )
            }))
            .map_err(e)?;
        let items = [
            ("no uplift".to_string(), RGBColor(236, 240, 244)),
            ("survived, max θ/α = 0".to_string(), grey(0.0, top)),
            (
                format!("survived, max θ/α = {:.2}", top / 2.0),
                grey(top / 2.0, top),
            ),
            (format!("survived, max θ/α = {top:.2}"), grey(top, top)),
            ("overturned, no impact".to_string(), RGBColor(60, 110, 200)),
            ("overturned, one impact".to_string(), RGBColor(150, 90, 40)),
            ("overturned, impacts".to_string(), RGBColor(230, 150, 40)),
            ("failed (see meta.json)".to_string(), RGBColor(220, 30, 30)),
        ];
        for (i, (label, colour)) in items.iter().enumerate() {
            let y = 60 + 30 * i as i32;
            legend
                .draw(&Rectangle::new([(10, y), (30, y + 18)], colour.filled()))
                .map_err(e)?;
            legend
                .draw(&Rectangle::new([(10, y), (30, y + 18)], BLACK))
                .map_err(e)?;
            legend
                .draw(&Text::new(
                    label.clone(),
                    (38, y + 2),
                    ("sans-serif", 14).into_font(),
                ))
                .map_err(e)?;
        }
    } else {
        let palette = [
            BLUE,
            RED,
            GREEN,
            MAGENTA,
            CYAN,
            BLACK,
            RGBColor(150, 90, 40),
            RGBColor(230, 150, 40),
        ];
        for (i, (family, pts)) in crate::sweep::boundary(sweep, cells).into_iter().enumerate() {
            let colour = palette[i % palette.len()];
            chart
                .draw_series(LineSeries::new(pts, colour.stroke_width(2)))
                .map_err(e)?
                .label(format!("{} = {family}", sweep.axes[n - 3].key))
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], colour.stroke_width(2))
                });
        }
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.8))
            .border_style(BLACK)
            .label_font(("sans-serif", 13))
            .draw()
            .map_err(e)?;
    }
    root.present().map_err(e)
}

/// The spectrum plot of a 2-axis sweep (regions and θ/α shading) or the overturning boundaries
/// of a 3-axis sweep (one line per value of the first axis: the smallest overturning amplitude),
/// as PNG and SVG.
pub fn spectrum_plots(
    title: &str,
    sweep: &rocking_spectra::Sweep,
    cells: &[rocking_spectra::Cell],
    dir: &Path,
) -> Result<Vec<PathBuf>, CliError> {
    if sweep.axes.len() < 2 || cells.is_empty() {
        return Ok(Vec::new());
    }
    // plotters' tick search does not end on a range near the f64 limit, or one too narrow for
    // its magnitude (x + step == x): such a spectrum is not drawn (its cells are in cells.csv).
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
    if let Some(a) = sweep.axes[n - 2..].iter().find(|a| !drawable(&a.values)) {
        eprintln!(
            "note: the spectrum plot is not drawn: the values of `{}` span a range a plot cannot \
             show (beyond ±1e15, or too narrow for their size); the cells are in cells.csv",
            a.key
        );
        return Ok(Vec::new());
    }
    register();
    let size = (WIDTH + 130, 720);
    render_pair(
        dir,
        "spectrum",
        size,
        |root| draw_spectrum(root, title, sweep, cells),
        |root| draw_spectrum(root, title, sweep, cells),
    )
}

fn draw_fragility<DB: DrawingBackend>(
    root: DrawingArea<DB, Shift>,
    points: &[(f64, f64)],
    records: usize,
) -> Result<(), String> {
    let e = |e: DrawingAreaErrorKind<DB::ErrorType>| e.to_string();
    root.fill(&WHITE).map_err(e)?;
    let x_hi = points.iter().map(|p| p.0).fold(0.0, f64::max) * 1.05;
    let mut chart = ChartBuilder::on(&root)
        .caption(
            format!("Fraction of {records} records that overturn"),
            ("sans-serif", 20),
        )
        .margin(12)
        .x_label_area_size(45)
        .y_label_area_size(60)
        .build_cartesian_2d(0.0..x_hi.max(1e-9), 0.0..1.05)
        .map_err(e)?;
    chart
        .configure_mesh()
        .x_desc("scale factor")
        .y_desc("fraction overturned")
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
) -> Result<Vec<PathBuf>, CliError> {
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
fn render_pair(
    dir: &Path,
    name: &str,
    size: (u32, u32),
    png: impl FnOnce(DrawingArea<BitMapBackend<'_>, Shift>) -> Result<(), String>,
    svg: impl FnOnce(DrawingArea<SVGBackend<'_>, Shift>) -> Result<(), String>,
) -> Result<Vec<PathBuf>, CliError> {
    let fail = |what: &str, m: String| {
        CliError::Internal(format!("{}: cannot draw the {what}: {m}", dir.display()))
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
