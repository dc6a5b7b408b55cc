//! The figures the commands draw on their own, without a figure file: `rocking run`'s stacked
//! histories, a sweep's spectrum or line with its boundaries, a reported quantity's map (the
//! friction map with its contours), and a record batch's fragility curves.

use std::path::{Path, PathBuf};

use crate::FigureError;
use rocking::Run;
use rocking_scene::setup::Setup;
use rocking_spectra::{Cell, Sweep};

use super::*;
/// `rocking run`'s figure: θ/α, u/u_cr, E/E_ref and ü_g/(g tan α) against τ, stacked, impacts
/// marked (the paper's Figs 3, 5 and 10 style), written as plot.svg, plot.png and plot.pdf.
pub fn plots(model: &Setup, run: &Run, dir: &Path) -> Result<Vec<PathBuf>, FigureError> {
    let trace = Trace::of(model, run, String::new(), style::LINES[0]);
    let panels = RUN_PANELS
        .into_iter()
        .filter_map(Quantity::parse)
        .map(|q| Panel::History(HistoryPanel::new(q, vec![trace.clone()])))
        .collect();
    let title = model
        .title
        .clone()
        .unwrap_or_else(|| model.excitation_description.clone());
    let impacts = run
        .events
        .iter()
        .filter(|e| e.kind == EventKind::Impact)
        .count();
    let figure = Figure {
        title,
        caption: history::caption(impacts > 0, run.summary.overturned),
        columns: 1,
        panel: (860, 270),
        panels,
        colour_top: None,
        print: None,
    };
    figure.write(dir, "plot")
}

/// The fragility-style curve of a record suite (fraction of the records that overturn against
/// the scale factor), as fragility.svg, .png and .pdf.
pub fn fragility_plots(
    points: &[(f64, f64)],
    records: usize,
    dir: &Path,
) -> Result<Vec<PathBuf>, FigureError> {
    let figure = Figure {
        title: format!("Fraction of {records} records that overturn"),
        caption: None,
        columns: 1,
        panel: (760, 520),
        panels: vec![Panel::Curve(CurvePanel {
            title: None,
            labels: (
                labels::SCALE_FACTOR.to_string(),
                labels::FRACTION_OVERTURNED.to_string(),
            ),
            points: points.to_vec(),
            y: (0.0, 1.05),
        })],
        colour_top: None,
        print: None,
    };
    figure.write(dir, "fragility")
}

/// The names of the figures a sweep may write: [`sweep_figure`]'s and [`fragility_plots`]'.
pub const SWEEP_FIGURES: [&str; 3] = ["line", "spectrum", "fragility"];

/// A reference structure's cells over the axes a sweep's figure shows (`[sweep] reference`).
pub struct Reference<'a> {
    /// Legend text, e.g. "rigid column".
    pub label: &'a str,
    pub sweep: &'a Sweep,
    pub cells: &'a [Cell],
}

/// The figure of a sweep: `line` for one axis, `spectrum` for two (classes and max θ/α, with the
/// structure's θ_cr/α on the colour bar), `spectrum` with one overturning boundary per value of
/// the leading axes for three or more (each the midpoint between the cells that bracket the
/// lowest overturning amplitude). Returns the figure and the file name.
pub fn sweep_figure(
    title: &str,
    sweep: &Sweep,
    cells: &[Cell],
    reference: Option<&Reference>,
    theta_cr: Option<f64>,
) -> (Figure, &'static str) {
    let n = sweep.axes.len();
    let (panel, name, caption) = match n {
        1 => {
            let mut p = LinePanel::new(sweep, cells);
            if let Some(r) = reference {
                p = p.with_reference(r.label, r.sweep, r.cells);
            }
            (Panel::Line(p), "line", None)
        }
        2 => {
            let mut p = SpectrumPanel::new(sweep, cells);
            if let Some(r) = reference {
                p = p.with_reference(r.label, r.sweep, r.cells);
            }
            p.mark =
                theta_cr.map(|v| (v, format!("θ_cr/α = {}", tick((v * 100.0).round() / 100.0))));
            (Panel::Spectrum(p), "spectrum", None)
        }
        _ => {
            let per = sweep.axes[n - 2].values.len() * sweep.axes[n - 1].values.len();
            let leading = &sweep.axes[..n - 2];
            let count = cells.len().div_ceil(per.max(1));
            let mut structures = Vec::new();
            for s in 0..count {
                let mine: Vec<Cell> = cells
                    .iter()
                    .filter(|c| c.index / per == s)
                    .cloned()
                    .collect();
                let Some(first) = mine.first() else { continue };
                let values = sweep.values(first.index);
                let label = leading
                    .iter()
                    .zip(&values)
                    .map(|(a, &v)| match a.text(v) {
                        Some(t) => format!("{} = {t}", a.key),
                        None => labels::axis_value(&a.key, v),
                    })
                    .collect::<Vec<_>>()
                    .join(", ");
                let style = style::LINES[s % style::LINES.len()];
                structures.push(Structure::new(label, style, sweep, &mine, |_, lo, hi| {
                    (lo + hi) / 2.0
                }));
            }
            if let Some(r) = reference {
                structures.push(Structure::new(
                    r.label.to_string(),
                    style::BLACK,
                    r.sweep,
                    r.cells,
                    |_, lo, hi| (lo + hi) / 2.0,
                ));
            }
            let p = BoundaryPanel::over(sweep, structures, BOUNDARY_HEADING.to_string());
            (
                Panel::Boundaries(p),
                "spectrum",
                Some(GRID_CAPTION.to_string()),
            )
        }
    };
    let figure = Figure {
        title: title.to_string(),
        caption,
        columns: 1,
        panel: (760, 700),
        panels: vec![panel],
        colour_top: None,
        print: None,
    };
    (figure, name)
}

/// The figure of a two-axis sweep's reported quantity `k` (of [`Sweep::reported`]): every upright
/// cell shaded by its value, the overturned ones filled by class; a ratio to the fixed-base twin
/// marks 1 on the colour bar. Returns the figure and its file name, `spectrum-<quantity>`.
pub fn reported_figure(title: &str, sweep: &Sweep, cells: &[Cell], k: usize) -> (Figure, String) {
    let key = &sweep.reported[k];
    let label = rocking_study::report::quantity_label(key);
    let friction = key == REQUIRED_FRICTION;
    let contours: &[f64] = if friction { &FRICTION_CONTOURS } else { &[] };
    let panel = reported_panel(sweep, cells, k, contours);
    let mut caption =
        "Upright cells shaded by the quantity, overturned cells filled by class; the \
                       dotted line surrounds the cells that never uplift."
            .to_string();
    if friction {
        caption.push_str(&format!(
            " Dashed on white: the contours of the required friction at μ = {} (long dashes) and \
             {} (short), the friction a footing can count on: the cells on the higher side need more, and there \
             the no-sliding assumption of the model fails.",
            tick(FRICTION_CONTOURS[0]),
            tick(FRICTION_CONTOURS[1])
        ));
    }
    let figure = Figure {
        title: format!("{title}: {label}"),
        caption: Some(caption),
        columns: 1,
        panel: (760, 700),
        panels: vec![Panel::Spectrum(panel)],
        colour_top: None,
        print: None,
    };
    (figure, format!("{REPORTED_FIGURE}{key}"))
}

/// The panel of a sweep's reported quantity `k`: upright cells shaded by it, a ratio to the
/// fixed-base twin marked at 1 on the colour bar, and its contours at `levels`.
pub fn reported_panel(sweep: &Sweep, cells: &[Cell], k: usize, levels: &[f64]) -> SpectrumPanel {
    let key = &sweep.reported[k];
    let label = rocking_study::report::quantity_label(key);
    let mut panel = SpectrumPanel::reported(sweep, cells, k, label);
    if rocking_study::report::RATIOS.contains(&key.as_str()) {
        panel.mark = Some((1.0, "fixed base".to_string()));
    }
    for &level in levels {
        panel = panel.with_contour(level, &format!("{label} = {}", tick(level)));
    }
    panel
}

/// The reported quantity whose map carries the friction contours.
pub const REQUIRED_FRICTION: &str = "max_required_friction";
/// The friction coefficients a footing can count on (soil or concrete on soil, about 0.5-0.7):
/// the contours of the required-friction map.
pub const FRICTION_CONTOURS: [f64; 2] = [0.5, 0.7];

/// The start of the name of a reported quantity's figure.
const REPORTED_FIGURE: &str = "spectrum-";

/// Whether `file` is one of the figures a sweep writes ([`SWEEP_FIGURES`], [`reported_figure`]).
pub fn is_sweep_figure(file: &str) -> bool {
    let name = file.rsplit_once('.').map_or(file, |(name, _)| name);
    let ours = SWEEP_FIGURES.contains(&name)
        || name
            .strip_prefix(REPORTED_FIGURE)
            .is_some_and(|quantity| !quantity.is_empty());
    ours && is_figure_file(file, name)
}

/// Whether a sweep's figure can be drawn: its plotted axes (the last two) are numeric, and
/// plotters' tick search does not end on a range near the f64 limit, or one too narrow for its
/// magnitude (x + step == x); such a sweep is not drawn (its cells are in cells.csv) and a note
/// says so. A text axis before them labels the structures of an overturning-boundaries figure.
pub fn drawable(sweep: &Sweep) -> bool {
    if sweep.axes.is_empty() || sweep.is_empty() {
        return false;
    }
    let n = sweep.axes.len();
    if let Some(a) = sweep.axes[n.saturating_sub(2)..]
        .iter()
        .find(|a| a.is_text())
    {
        eprintln!(
            "note: the sweep plot is not drawn: `{}` is a text axis, and the plot's axes are the \
             last two (give it first, before two numeric axes, for a figure of one boundary per \
             text); the cells are in cells.csv",
            a.key
        );
        return false;
    }
    let ok = |v: &[f64]| {
        let (lo, hi) = v
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| {
                (a.min(x), b.max(x))
            });
        let big = lo.abs().max(hi.abs());
        big <= 1e15 && (v.len() < 2 || hi - lo >= 1e-9 * big)
    };
    match sweep.axes[n.saturating_sub(2)..]
        .iter()
        .find(|a| !ok(&a.values))
    {
        None => true,
        Some(a) => {
            eprintln!(
                "note: the sweep plot is not drawn: the values of `{}` span a range a plot cannot \
                 show (beyond ±1e15, or too narrow for their size); the cells are in cells.csv",
                a.key
            );
            false
        }
    }
}

/// The legend heading of overturning boundaries.
pub const BOUNDARY_HEADING: &str = "lowest amplitude that overturns:";
/// How `rocking spectrum` finds a boundary point.
const GRID_CAPTION: &str = "Each line joins, per value of the horizontal axis, the midpoints \
                            between the highest upright cell below the lowest overturned cell and \
                            that cell (the grid's resolution); `rocking figure` refines them by \
                            bisection.";
