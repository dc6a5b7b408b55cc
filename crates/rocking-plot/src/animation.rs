//! The animated GIF of a run (`rocking run --animate`, `Result.animation()` in Python): the base
//! plate rocking on its corner, the
//! column deflected along the model's shape function ψ, the top mass, and the ground moving by
//! u_g (integrated from the history's ü_g), with τ and θ/α on each frame. The frame geometry is
//! computed by [`geometry`], which the drawing and the tests share.

use plotters::prelude::*;
use rocking::{HistoryRow, Run};
use rocking_scene::labels;
use rocking_scene::setup::{Animation, Setup};
use rocking_scene::units::Scales;
use rocking_study::report;

use crate::{register, wrap};

/// Pixels of the text band above the picture and of the margins.
const BAND: f64 = 74.0;
const MARGIN: f64 = 24.0;

/// The drawn geometry of one frame, in pixels (x right, y down), before rounding.
#[derive(Clone, Debug, PartialEq)]
pub struct Frame {
    /// τ of the frame's history row.
    pub tau: f64,
    /// θ/α of the row.
    pub theta_over_alpha: f64,
    /// Base plate corners: bottom left, bottom right, top right, top left.
    pub base: [(f64, f64); 4],
    /// The column's axis from its foot to its top.
    pub column: Vec<(f64, f64)>,
    /// Centre and radius of the top mass.
    pub mass: ((f64, f64), f64),
    /// The ground's surface row and its tick marks (moving with u_g).
    pub ground_y: f64,
    pub ticks: Vec<f64>,
}

/// The model's shape functions ψ_1(η)..ψ_n(η), from the derivation's own `shape` kernel of the
/// model's full variant (so a model with a new shape function, or several, is drawn with them,
/// with nothing re-typed here).
pub fn shape_functions(model: &rocking_kernels::ModelInfo, eta: f64) -> Vec<f64> {
    rocking_kernels::with_variant!(model.full, V, L => {
        rocking_kernels::Array::values(&<V as rocking_kernels::Variant>::shape(eta)).to_vec()
    })
    .expect("a model's full variant is generated")
}

/// Heights of the drawn column's points, as fractions η of H.
const COLUMN_POINTS: usize = 24;

/// Ground displacement at each history row, from ü_g by the trapezoidal rule twice (the ground
/// starts at rest at 0); in model units.
fn ground_displacement(history: &[HistoryRow], scales: &Scales) -> Vec<f64> {
    let tau = |r: &HistoryRow| report::TAU.number(r, scales);
    let mut out = Vec::with_capacity(history.len());
    let (mut v, mut x) = (0.0, 0.0);
    for (k, r) in history.iter().enumerate() {
        if k > 0 {
            let prev = &history[k - 1];
            let dt = (tau(r) - tau(prev)) / scales.p;
            let v_new = v + 0.5 * (prev.ug + r.ug) * dt;
            x += 0.5 * (v + v_new) * dt;
            v = v_new;
        }
        out.push(x);
    }
    out
}

/// The rows shown: `frames` rows evenly spaced in τ, the first and the last row included.
fn frame_rows(history: &[HistoryRow], scales: &Scales, frames: usize) -> Vec<usize> {
    let tau = |r: &HistoryRow| report::TAU.number(r, scales);
    let (t0, t1) = (tau(&history[0]), tau(&history[history.len() - 1]));
    let mut k = 0;
    (0..frames)
        .map(|f| {
            let t = t0 + (t1 - t0) * f as f64 / (frames - 1).max(1) as f64;
            while k + 1 < history.len()
                && (tau(&history[k + 1]) - t).abs() <= (tau(&history[k]) - t).abs()
            {
                k += 1;
            }
            if f + 1 == frames {
                history.len() - 1
            } else {
                k
            }
        })
        .collect()
}

/// World geometry of a row (x right, y up, origin at the base centre at rest): base corners,
/// column axis, top-mass centre.
struct World {
    base: [(f64, f64); 4],
    column: Vec<(f64, f64)>,
    mass: (f64, f64),
}

/// The frame of history row `row` whose deformation coordinates are `u` (u_1..u_n; for one
/// coordinate, u), with `psi[k]` the shape functions at η = k / COLUMN_POINTS.
fn world(row: &HistoryRow, u: &[f64], ug: f64, h: f64, b: f64, psi: &[Vec<f64>]) -> World {
    // θ > 0 is clockwise about the right corner (s = +1), θ < 0 about the left one; a body point
    // (X, Y) from the base centre goes to pivot + R(θ)(X - sB, Y).
    let s = if row.theta >= 0.0 { 1.0 } else { -1.0 };
    let (sin, cos) = row.theta.sin_cos();
    let place = |x: f64, y: f64| {
        let xr = x - s * b;
        (s * b + ug + xr * cos + y * sin, -xr * sin + y * cos)
    };
    // The plate's thickness is drawn, not modelled (a thin plate): a third of B.
    let t = b.min(h) / 3.0;
    let column: Vec<(f64, f64)> = psi
        .iter()
        .enumerate()
        .map(|(k, psi)| {
            let eta = k as f64 / COLUMN_POINTS as f64;
            let deflection: f64 = u.iter().zip(psi).map(|(u, p)| u * p).sum();
            place(deflection, t + eta * (h - t))
        })
        .collect();
    World {
        base: [place(-b, 0.0), place(b, 0.0), place(b, t), place(-b, t)],
        mass: place(row.u, h),
        column,
    }
}

/// The frames of an animation of `run` at `size` pixels: geometry in pixels, one per shown row.
pub fn geometry(model: &Setup, run: &Run, spec: &Animation) -> Result<Vec<Frame>, String> {
    let h = &run.history;
    if h.len() < 2 {
        return Err(
            "the run has fewer than two history rows (a scene with `[output] animation = true` \
             records them)"
                .into(),
        );
    }
    let phys = model.structure.physical();
    let (hh, b) = (phys.h, phys.b);
    let shape = model.structure.model();
    let psi: Vec<Vec<f64>> = (0..=COLUMN_POINTS)
        .map(|k| shape_functions(shape, k as f64 / COLUMN_POINTS as f64))
        .collect();
    let n = shape.coordinates;
    if n > 1 && run.coordinate_count() != n {
        return Err(format!(
            "the run recorded {} deformation coordinates per history row, and model `{}` has {n}",
            run.coordinate_count(),
            shape.name
        ));
    }
    let ug = ground_displacement(h, &model.scales);
    let rows = frame_rows(h, &model.scales, spec.frames);
    let worlds: Vec<World> = rows
        .iter()
        .map(|&k| {
            // u_1..u_n of the row (the run records them for several coordinates), or u.
            let u = if n == 1 {
                std::slice::from_ref(&h[k].u)
            } else {
                &run.coordinates_of(k)[..n]
            };
            world(&h[k], u, ug[k], hh, b, &psi)
        })
        .collect();
    let radius = 0.06 * hh;
    // One scale for every frame: the box of everything drawn, x centred on the rest position.
    let (mut x_reach, mut y_top) = (b, hh + radius);
    for w in &worlds {
        for &(x, y) in w.base.iter().chain(&w.column).chain([&w.mass]) {
            x_reach = x_reach.max(x.abs() + radius);
            y_top = y_top.max(y + radius);
        }
    }
    let (wpx, hpx) = (spec.width as f64, spec.height as f64);
    let scale = ((wpx - 2.0 * MARGIN) / (2.0 * x_reach)).min((hpx - BAND - 2.0 * MARGIN) / y_top);
    let ground_y = hpx - MARGIN - 12.0;
    let to_px = |(x, y): (f64, f64)| (wpx / 2.0 + scale * x, ground_y - scale * y);
    let tick = (wpx / 12.0) / scale;
    Ok(rows
        .iter()
        .zip(&worlds)
        .map(|(&k, w)| {
            let first = ((-wpx / 2.0 / scale - ug[k]) / tick).floor() as i64;
            let last = ((wpx / 2.0 / scale - ug[k]) / tick).ceil() as i64;
            Frame {
                tau: report::TAU.number(&h[k], &model.scales),
                theta_over_alpha: report::THETA_OVER_ALPHA.number(&h[k], &model.scales),
                base: w.base.map(to_px),
                column: w.column.iter().map(|&p| to_px(p)).collect(),
                mass: (to_px(w.mass), radius * scale),
                ground_y,
                ticks: (first..=last)
                    .map(|i| to_px((ug[k] + i as f64 * tick, 0.0)).0)
                    .collect(),
            }
        })
        .collect())
}

fn round((x, y): (f64, f64)) -> (i32, i32) {
    (x.round() as i32, y.round() as i32)
}

/// Colours of the drawing (exact entries of the GIF palette, so tests can find them).
pub const BASE: RGBColor = RGBColor(51, 51, 153);
pub const COLUMN: RGBColor = RGBColor(204, 51, 0);
pub const MASS: RGBColor = RGBColor(0, 0, 0);
const GROUND: RGBColor = RGBColor(153, 102, 51);

fn draw_frame(
    area: &DrawingArea<BitMapBackend<'_>, plotters::coord::Shift>,
    f: &Frame,
    title: &[String],
) -> Result<(), String> {
    let e = |e: DrawingAreaErrorKind<_>| format!("{e}");
    area.fill(&WHITE).map_err(e)?;
    let (w, _) = area.dim_in_pixel();
    let gy = f.ground_y.round() as i32;
    area.draw(&Rectangle::new(
        [(0, gy), (w as i32, gy + 10)],
        GROUND.mix(0.35).filled(),
    ))
    .map_err(e)?;
    area.draw(&PathElement::new(
        vec![(0, gy), (w as i32, gy)],
        GROUND.stroke_width(2),
    ))
    .map_err(e)?;
    for &x in &f.ticks {
        let x = x.round() as i32;
        area.draw(&PathElement::new(
            vec![(x, gy), (x - 8, gy + 10)],
            GROUND.stroke_width(2),
        ))
        .map_err(e)?;
    }
    area.draw(&Polygon::new(f.base.map(round).to_vec(), BASE.filled()))
        .map_err(e)?;
    area.draw(&PathElement::new(
        f.column.iter().map(|&p| round(p)).collect::<Vec<_>>(),
        COLUMN.stroke_width(4),
    ))
    .map_err(e)?;
    let (c, r) = f.mass;
    area.draw(&Circle::new(
        round(c),
        r.round().max(3.0) as i32,
        MASS.filled(),
    ))
    .map_err(e)?;
    let font = ("sans-serif", 16).into_font();
    for (i, line) in title.iter().enumerate() {
        area.draw(&Text::new(
            line.clone(),
            (10, 6 + 19 * i as i32),
            font.clone(),
        ))
        .map_err(e)?;
    }
    let state = format!(
        "{} = {:6.2}    {} = {:+.3}",
        labels::TAU.split(' ').next().unwrap_or("τ"),
        f.tau,
        labels::THETA_OVER_ALPHA,
        f.theta_over_alpha
    );
    let below = 6 + 19 * title.len() as i32 + 4;
    area.draw(&Text::new(state, (10, below), font)).map_err(e)?;
    Ok(())
}

/// The global palette: a 6×6×6 colour cube and 40 greys (256 entries), and a pixel's index.
fn palette() -> Vec<u8> {
    let mut p = Vec::with_capacity(768);
    for r in 0..6u8 {
        for g in 0..6u8 {
            for b in 0..6u8 {
                p.extend([r * 51, g * 51, b * 51]);
            }
        }
    }
    for k in 0..40u32 {
        let v = (k * 255 / 39) as u8;
        p.extend([v, v, v]);
    }
    p
}

fn index_of(r: u8, g: u8, b: u8) -> u8 {
    let (lo, hi) = (r.min(g).min(b), r.max(g).max(b));
    if hi - lo < 12 {
        let v = (r as u32 + g as u32 + b as u32) / 3;
        216 + ((v * 39 + 127) / 255) as u8
    } else {
        let q = |c: u8| ((c as u32 + 25) / 51) as u8;
        q(r) * 36 + q(g) * 6 + q(b)
    }
}

/// The animated GIF of `run` (its bytes) and its number of frames; the error says what failed.
pub fn render(model: &Setup, run: &Run, spec: &Animation) -> Result<(Vec<u8>, usize), String> {
    register();
    let frames = geometry(model, run, spec)?;
    let title = model
        .title
        .clone()
        .unwrap_or_else(|| model.excitation_description.clone());
    // At most two lines of title above the state line; a longer title ends in "…".
    let mut title = wrap(&title, (spec.width as usize / 9).max(10));
    if title.len() > 2 {
        title.truncate(2);
        title[1].push_str(" …");
    }
    let (w, h) = (spec.width, spec.height);
    let mut bytes = Vec::new();
    {
        let mut enc = gif::Encoder::new(&mut bytes, w as u16, h as u16, &palette())
            .map_err(|e| e.to_string())?;
        enc.set_repeat(gif::Repeat::Infinite)
            .map_err(|e| e.to_string())?;
        // About 8 s for the whole run, 2..10 hundredths of a second per frame.
        let delay = (800 / frames.len()).clamp(2, 10) as u16;
        let mut rgb = vec![255u8; (w * h * 3) as usize];
        for f in &frames {
            {
                let area = BitMapBackend::with_buffer(&mut rgb, (w, h)).into_drawing_area();
                draw_frame(&area, f, &title)?;
                area.present().map_err(|e| e.to_string())?;
            }
            let indexed: Vec<u8> = rgb
                .chunks_exact(3)
                .map(|p| index_of(p[0], p[1], p[2]))
                .collect();
            let frame = gif::Frame {
                width: w as u16,
                height: h as u16,
                delay,
                buffer: std::borrow::Cow::Owned(indexed),
                ..gif::Frame::default()
            };
            enc.write_frame(&frame).map_err(|e| e.to_string())?;
        }
    }
    Ok((bytes, frames.len()))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Runs the scene `name` of scenes/ with the overrides `sets` and an animation, and draws
    /// its frames at `spec`.
    fn animate(name: &str, sets: &[&str], spec: &Animation) -> (Setup, Run, Vec<Frame>) {
        let scene = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../scenes")
            .join(name);
        let sets: Vec<String> = std::iter::once("output.animation=true")
            .chain(sets.iter().copied())
            .map(String::from)
            .collect();
        let sc = rocking_scene::scene::load(&scene, &sets).expect("scene");
        let m = rocking_scene::setup::build(&sc).expect("model");
        let run =
            rocking::simulate(&m.structure, &m.excitation, &m.effects, &m.options).expect("run");
        let frames = geometry(&m, &run, spec).expect("frames");
        (m, run, frames)
    }

    #[test]
    fn every_models_shape_functions_come_from_its_kernel() {
        for m in rocking_kernels::kernels::MODELS {
            let at = |eta: f64| shape_functions(m, eta);
            assert_eq!(at(0.5).len(), m.coordinates, "{}", m.name);
            // Clamped at the base; for one coordinate ψ(1) = 1 (u is the top deflection).
            assert!(
                at(0.0).iter().all(|p| p.abs() < 1e-15),
                "{}: {:?}",
                m.name,
                at(0.0)
            );
            if m.coordinates == 1 {
                assert!(
                    (at(1.0)[0] - 1.0).abs() < 1e-15,
                    "{}: ψ(1) = {:?}",
                    m.name,
                    at(1.0)
                );
                // The column bends smoothly and monotonically between them.
                let mut last = 0.0;
                for k in 1..=10 {
                    let v = at(k as f64 / 10.0)[0];
                    assert!(
                        v > last && v <= 1.0 + 1e-12,
                        "{}: ψ({}) = {v}",
                        m.name,
                        k as f64 / 10.0
                    );
                    last = v;
                }
            } else {
                // Several functions: none is the straight line the drawing used to show.
                for (i, p) in at(0.5).iter().enumerate() {
                    assert!(
                        (p - 0.5 * at(1.0)[i]).abs() > 1e-3,
                        "{}: ψ_{i} is linear",
                        m.name
                    );
                }
            }
        }
    }

    /// With several coordinates the drawn column is Σ u_i ψ_i(η) of the recorded coordinates:
    /// its body-frame offsets from the undeformed axis, read back from the pixels, match the
    /// history's u_1..u_n at every height, and its top is the mass at the top deflection u.
    #[test]
    fn the_drawn_column_bends_with_every_coordinate() {
        let spec = Animation {
            frames: 40,
            width: 500,
            height: 800,
        };
        let (m, run, frames) = animate(
            "wind-turbine-elcentro.toml",
            &[
                "structure.model=\"cantilever_modes3\"",
                "excitation.scale=6.0",
            ],
            &spec,
        );
        let rows = frame_rows(&run.history, &m.scales, spec.frames);
        let phys = m.structure.physical();
        let psi: Vec<Vec<f64>> = (0..=COLUMN_POINTS)
            .map(|k| shape_functions(m.structure.model(), k as f64 / COLUMN_POINTS as f64))
            .collect();
        let (mut curved, mut largest) = (0.0f64, 0.0f64);
        for (f, &k) in frames.iter().zip(&rows) {
            let u = &run.coordinates_of(k)[..3];
            let [(x0, y0), (x1, y1), ..] = f.base;
            let scale = (x1 - x0).hypot(y1 - y0) / (2.0 * phys.b);
            // Body axes on the screen: along the plate (x) and up the column (y down: negated).
            let (ex, ey) = (
                (x1 - x0) / (2.0 * phys.b * scale),
                (y1 - y0) / (2.0 * phys.b * scale),
            );
            let foot = f.column[0];
            for (j, &(x, y)) in f.column.iter().enumerate() {
                let offset = ((x - foot.0) * ex + (y - foot.1) * ey) / scale;
                let want: f64 = u.iter().zip(&psi[j]).map(|(a, b)| a * b).sum();
                assert!(
                    (offset - want).abs() <= 1e-9 * phys.h,
                    "τ = {}, η = {j}/{COLUMN_POINTS}: drawn {offset}, Σ u_i ψ_i = {want}",
                    f.tau
                );
                // How far the drawn column is from the straight line to its top.
                let eta = j as f64 / COLUMN_POINTS as f64;
                curved = curved.max((want - eta * run.history[k].u).abs());
            }
            let top = run.history[k].u;
            largest = largest.max(top.abs());
            let want_top: f64 = u.iter().zip(&psi[COLUMN_POINTS]).map(|(a, b)| a * b).sum();
            assert!(
                (want_top - top).abs() <= 1e-9 * top.abs().max(1e-12),
                "{want_top} vs {top}"
            );
        }
        // The first cantilever mode alone is 0.34 of its top deflection at mid-height, not 0.5.
        assert!(
            curved > 0.05 * largest,
            "the column is drawn straight: {curved} of {largest}"
        );
    }

    #[test]
    fn the_drawn_frames_show_the_simulated_angles_and_deflections() {
        let spec = Animation {
            frames: 25,
            width: 500,
            height: 400,
        };
        let (m, run, frames) = animate("fig10-overturns.toml", &["output.history_dt=0.01"], &spec);
        assert_eq!(frames.len(), 25);
        let tau = |r: &HistoryRow| report::TAU.number(r, &m.scales);
        assert_eq!(frames[0].tau, tau(&run.history[0]));
        assert_eq!(frames[24].tau, tau(run.history.last().unwrap()));
        let phys = m.structure.physical();
        for f in &frames {
            // θ read back from the plate's bottom edge (y down on the screen: clockwise > 0).
            let [(x0, y0), (x1, y1), ..] = f.base;
            let theta = (y1 - y0).atan2(x1 - x0);
            assert!(
                (theta - f.theta_over_alpha * m.units.alpha).abs() < 1e-9,
                "τ = {}: drawn θ = {theta}, simulated {}",
                f.tau,
                f.theta_over_alpha * m.units.alpha
            );
            // The plate is 2B long, the column's top is the mass, the frame holds everything.
            let scale = (x1 - x0).hypot(y1 - y0) / (2.0 * phys.b);
            let top = f.column[f.column.len() - 1];
            assert!((top.0 - f.mass.0 .0).abs() < 1e-9 && (top.1 - f.mass.0 .1).abs() < 1e-9);
            assert!((f.mass.1 - 0.06 * phys.h * scale).abs() < 1e-9);
            for &(x, y) in f.base.iter().chain(&f.column) {
                assert!(
                    (0.0..=500.0).contains(&x) && (0.0..=400.0).contains(&y),
                    "({x}, {y})"
                );
            }
        }
        assert!(
            frames[24].theta_over_alpha.abs() * m.units.alpha > 1.0,
            "it overturns"
        );
    }

    #[test]
    fn palette_indices_keep_the_drawing_colours_exact() {
        let p = palette();
        for c in [BASE, COLUMN, MASS, WHITE] {
            let i = index_of(c.0, c.1, c.2) as usize;
            assert_eq!(&p[3 * i..3 * i + 3], &[c.0, c.1, c.2], "{c:?}");
        }
    }
}
