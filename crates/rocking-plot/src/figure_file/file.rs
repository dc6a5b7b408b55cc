//! The figure file: its format (scenes/paper/README.md), its bounds, and the checks that name
//! the file, the field and the allowed range.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use serde::Deserialize;

use crate::figure::{self as plot, Quantity};
use crate::style;
use rocking_scene::SceneError;

/// A figure file.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FigureFile {
    pub(super) title: String,
    pub(super) caption: Option<String>,
    #[serde(default = "one")]
    pub(super) columns: usize,
    /// The printed width: "double" (175 mm), "single" (85 mm) or a length in mm (default
    /// "double").
    pub(super) width: Option<toml::Value>,
    /// The PNG's resolution in pixels per inch (default 600).
    pub(super) dpi: Option<u32>,
    /// A panel's width and height: their ratio is the panels' aspect at the printed width.
    pub(super) panel: Option<[u32; 2]>,
    /// The top of the spectra's shared colour scale (default: their largest survivor).
    pub(super) colour_top: Option<f64>,
    /// Cells per ranged axis of every sweep (`start:stop:count` gets this count).
    pub(super) cells: Option<usize>,
    #[serde(default)]
    pub(super) runs: BTreeMap<String, RunSpec>,
    #[serde(default)]
    pub(super) sweeps: BTreeMap<String, SweepSpec>,
    pub(super) panels: Vec<PanelSpec>,
}

pub(super) fn one() -> usize {
    1
}

/// A run: a scene file (relative to the figure file) with overrides.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RunSpec {
    pub(super) scene: PathBuf,
    #[serde(default)]
    pub(super) set: Vec<String>,
    pub(super) label: String,
    /// A line style by name (default: the runs in order).
    pub(super) style: Option<String>,
}

/// A sweep of a scene over axes (default: the scene's `[sweep] axes`).
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct SweepSpec {
    pub(super) scene: PathBuf,
    #[serde(default)]
    pub(super) set: Vec<String>,
    pub(super) axes: Option<Vec<String>>,
    pub(super) label: String,
    pub(super) style: Option<String>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields, tag = "kind", rename_all = "lowercase")]
pub(super) enum PanelSpec {
    History {
        quantity: String,
        runs: Vec<String>,
        title: Option<String>,
        /// A τ window.
        tau: Option<[f64; 2]>,
        /// A window around an impact of a run.
        zoom: Option<Zoom>,
        /// Every run in black (the ground motion).
        #[serde(default)]
        black: bool,
        /// The time axis: "tau" (τ = p t, default) or "s" (seconds; every run's scene must
        /// know its time in seconds).
        time: Option<String>,
        /// Values of the quantity marked by a dashed grey line across the panel.
        #[serde(default)]
        lines: Vec<f64>,
        /// Runs drawn over the others as a thin solid dark grey line (a fixed-base twin).
        #[serde(default)]
        twins: Vec<String>,
        /// A smaller chart in a corner of the panel: a window of τ on its own y range.
        inset: Option<Box<InsetSpec>>,
    },
    Spectrum {
        sweep: String,
        title: Option<String>,
        /// A reference sweep whose boundary is drawn dashed.
        reference: Option<String>,
        /// A quantity of the sweep's `[sweep] report` shading the upright cells (default:
        /// max θ/α).
        quantity: Option<String>,
        /// Levels of that quantity drawn as contours (long dashes, then short).
        #[serde(default)]
        contours: Vec<f64>,
    },
    Boundaries {
        sweeps: Vec<String>,
        title: Option<String>,
        /// Bisection of each boundary point between its bracketing cells (default true).
        #[serde(default = "yes")]
        refine: bool,
    },
}

/// The most contours a spectrum panel draws: one per dash of
/// [`crate::figure::CONTOUR_DASHES`].
const MAX_CONTOURS: usize = crate::figure::CONTOUR_DASHES.len();

pub(super) fn yes() -> bool {
    true
}

/// An inset of a history panel (scenes/paper/README.md).
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct InsetSpec {
    /// Its window of τ (default: the panel's).
    pub(super) tau: Option<[f64; 2]>,
    /// Its y range (default: the runs' values in the window).
    pub(super) range: Option<[f64; 2]>,
    /// One of [`plot::CORNERS`] (default "top right").
    pub(super) corner: Option<String>,
    /// Width and height as fractions of the plotting area (default [`INSET_DEFAULT`]).
    pub(super) size: Option<[f64; 2]>,
}

/// An inset's size when the file gives none: half the plotting area's width, 0.45 of its height.
pub(super) const INSET_DEFAULT: [f64; 2] = [0.5, 0.45];

/// A τ window around the `impact`-th impact (from 1) of `run`.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct Zoom {
    pub(super) run: String,
    pub(super) impact: usize,
    pub(super) half_width: f64,
}

/// The time axes of a history panel: τ, or seconds.
pub(super) const TIMES: [&str; 2] = ["tau", "s"];

/// Bounds of the figure layout.
pub(super) const MAX_COLUMNS: usize = 8;
/// A journal's double and single column, and the lengths a printed width may be, in mm.
pub(super) const DOUBLE_MM: f64 = 175.0;
pub(super) const SINGLE_MM: f64 = 85.0;
pub(super) const WIDTH_MM: (f64, f64) = (40.0, 250.0);
/// The PNG's resolution: the default and the allowed range, pixels per inch.
pub(super) const DPI: u32 = 600;
pub(super) const DPI_RANGE: (u32, u32) = (72, 1200);
pub(super) const PANEL_PIXELS: (u32, u32) = (200, 2000);
/// Bisection steps of a boundary point: the bracket (one cell) shrinks 1024-fold.
pub(super) const BISECTIONS: usize = 10;

/// Reads and checks a figure file: TOML errors name the file, the line and the field.
pub fn read(file: &Path) -> Result<FigureFile, SceneError> {
    let text = std::fs::read_to_string(file)
        .map_err(|e| SceneError::input(format!("{}: cannot read: {e}", file.display())))?;
    let de = toml::Deserializer::parse(&text)
        .map_err(|e| SceneError::input(format!("{}: {e}", file.display())))?;
    let spec: FigureFile = serde_path_to_error::deserialize(de).map_err(|e| {
        SceneError::input(format!(
            "{}: `{}`: {}",
            file.display(),
            e.path(),
            e.inner().message()
        ))
    })?;
    let texts = [
        ("title", Some(&spec.title)),
        ("caption", spec.caption.as_ref()),
    ];
    for (field, text) in texts {
        if let Some(c) = text.and_then(|t| plot::control_char(t)) {
            return bad(
                file,
                field,
                format!("holds the control character {c:?}, which a figure cannot show"),
            );
        }
    }
    width_mm(file, spec.width.as_ref())?;
    if let Some(d) = spec.dpi {
        if !(DPI_RANGE.0..=DPI_RANGE.1).contains(&d) {
            return bad(
                file,
                "dpi",
                format!(
                    "{d} is not allowed: {} <= dpi <= {} pixels per inch",
                    DPI_RANGE.0, DPI_RANGE.1
                ),
            );
        }
    }
    if !(1..=MAX_COLUMNS).contains(&spec.columns) {
        return bad(
            file,
            "columns",
            format!(
                "{} is not allowed: 1 <= columns <= {MAX_COLUMNS}",
                spec.columns
            ),
        );
    }
    if let Some(p) = spec.panel {
        if p.iter()
            .any(|&v| !(PANEL_PIXELS.0..=PANEL_PIXELS.1).contains(&v))
        {
            return bad(
                file,
                "panel",
                format!(
                    "{p:?} is not allowed: each of width and height in {}..={} pixels",
                    PANEL_PIXELS.0, PANEL_PIXELS.1
                ),
            );
        }
    }
    if let Some(t) = spec.colour_top {
        if !(t.is_finite() && t > 0.0) {
            return bad(file, "colour_top", format!("{t} is not allowed: > 0"));
        }
    }
    if spec.cells.is_some_and(|c| c < 2) {
        return bad(
            file,
            "cells",
            "fewer than 2 cells per axis is not allowed".into(),
        );
    }
    if spec.panels.is_empty() {
        return bad(file, "panels", "a figure needs at least one panel".into());
    }
    let styles = |s: &Option<String>, field: String| match s {
        Some(name) if style::line_named(name).is_none() => bad(
            file,
            &field,
            format!(
                "`{name}` is not a line style: allowed: {}",
                style::line_names().join(", ")
            ),
        ),
        _ => Ok(()),
    };
    for (name, r) in &spec.runs {
        styles(&r.style, format!("runs.{name}.style"))?;
    }
    for (name, s) in &spec.sweeps {
        styles(&s.style, format!("sweeps.{name}.style"))?;
    }
    for (k, p) in spec.panels.iter().enumerate() {
        let field = |f: &str| format!("panels[{k}].{f}");
        let run = |r: &String, f: &str| match spec.runs.contains_key(r) {
            true => Ok(()),
            false => bad(file, &field(f), format!("no run `{r}` in [runs]")),
        };
        let sweep = |s: &String, f: &str| match spec.sweeps.contains_key(s) {
            true => Ok(()),
            false => bad(file, &field(f), format!("no sweep `{s}` in [sweeps]")),
        };
        match p {
            PanelSpec::History {
                quantity,
                runs,
                tau,
                zoom,
                time,
                lines,
                twins,
                inset,
                ..
            } => {
                if let Some(i) = inset {
                    check_inset(file, &field("inset"), i)?;
                }
                if Quantity::parse(quantity).is_none() {
                    let names: Vec<&str> = Quantity::all().map(Quantity::name).collect();
                    return bad(
                        file,
                        &field("quantity"),
                        format!(
                            "`{quantity}` is not a quantity: allowed: {}",
                            names.join(", ")
                        ),
                    );
                }
                if runs.is_empty() {
                    return bad(
                        file,
                        &field("runs"),
                        "a panel needs at least one run".into(),
                    );
                }
                for r in runs {
                    run(r, "runs")?;
                }
                for r in twins {
                    run(r, "twins")?;
                }
                if let Some(t) = time.as_deref().filter(|t| !TIMES.contains(t)) {
                    return bad(
                        file,
                        &field("time"),
                        format!("`{t}` is not allowed: {}", TIMES.join(" or ")),
                    );
                }
                if let Some(v) = lines.iter().find(|v| !v.is_finite()) {
                    return bad(
                        file,
                        &field("lines"),
                        format!("{v} is not allowed: finite values"),
                    );
                }
                if let Some([a, b]) = tau {
                    if !(a.is_finite() && b.is_finite() && a < b) {
                        return bad(
                            file,
                            &field("tau"),
                            format!("[{a}, {b}] is not a window: a < b"),
                        );
                    }
                }
                if let Some(z) = zoom {
                    run(&z.run, "zoom.run")?;
                    if z.impact == 0 {
                        return bad(file, &field("zoom.impact"), "impacts count from 1".into());
                    }
                    if !(z.half_width.is_finite() && z.half_width > 0.0) {
                        return bad(
                            file,
                            &field("zoom.half_width"),
                            format!("{} is not allowed: > 0", z.half_width),
                        );
                    }
                }
            }
            PanelSpec::Spectrum {
                sweep: s,
                reference,
                quantity,
                contours,
                ..
            } => {
                sweep(s, "sweep")?;
                if let Some(r) = reference {
                    sweep(r, "reference")?;
                }
                if !contours.is_empty() && quantity.is_none() {
                    return bad(
                        file,
                        &field("contours"),
                        "contours are levels of a reported quantity: give `quantity`".into(),
                    );
                }
                if contours.len() > MAX_CONTOURS || contours.iter().any(|c| !c.is_finite()) {
                    return bad(
                        file,
                        &field("contours"),
                        format!(
                            "{contours:?} is not allowed: at most {MAX_CONTOURS} finite levels \
                             (long and short dashes)"
                        ),
                    );
                }
            }
            PanelSpec::Boundaries { sweeps, .. } => {
                if sweeps.is_empty() {
                    return bad(
                        file,
                        &field("sweeps"),
                        "a panel needs at least one sweep".into(),
                    );
                }
                for s in sweeps {
                    sweep(s, "sweeps")?;
                }
            }
        }
    }
    Ok(spec)
}

/// An inset's window, range, corner and size, each named in the message that refuses it.
fn check_inset(file: &Path, field: &str, i: &InsetSpec) -> Result<(), SceneError> {
    for (key, pair) in [("tau", i.tau), ("range", i.range)] {
        if let Some([a, b]) = pair {
            if !(a.is_finite() && b.is_finite() && a < b) {
                return bad(
                    file,
                    &format!("{field}.{key}"),
                    format!("[{a}, {b}] is not allowed: finite a < b"),
                );
            }
        }
    }
    if let Some(c) = i
        .corner
        .as_deref()
        .filter(|c| plot::Corner::parse(c).is_none())
    {
        return bad(
            file,
            &format!("{field}.corner"),
            format!("`{c}` is not allowed: {}", plot::CORNERS.join(", ")),
        );
    }
    let (lo, hi) = plot::INSET_SIZE;
    if let Some(v) = i.size.iter().flatten().find(|v| !(lo..=hi).contains(*v)) {
        return bad(
            file,
            &format!("{field}.size"),
            format!("{v} is not allowed: {lo} <= width, height <= {hi} (fractions of the plotting area)"),
        );
    }
    Ok(())
}

/// The printed width a figure file states, in mm: "double", "single" or a length in mm.
pub(super) fn width_mm(file: &Path, width: Option<&toml::Value>) -> Result<f64, SceneError> {
    let allowed = format!(
        "\"double\" ({DOUBLE_MM} mm), \"single\" ({SINGLE_MM} mm) or a length in mm, {} <= width <= {}",
        WIDTH_MM.0, WIDTH_MM.1
    );
    let mm = match width {
        None => return Ok(DOUBLE_MM),
        Some(toml::Value::String(s)) if s == "double" => return Ok(DOUBLE_MM),
        Some(toml::Value::String(s)) if s == "single" => return Ok(SINGLE_MM),
        Some(toml::Value::Float(v)) => *v,
        Some(toml::Value::Integer(v)) => *v as f64,
        Some(other) => {
            return bad(file, "width", format!("{other} is not allowed: {allowed}"));
        }
    };
    if !(mm.is_finite() && (WIDTH_MM.0..=WIDTH_MM.1).contains(&mm)) {
        return bad(file, "width", format!("{mm} is not allowed: {allowed}"));
    }
    Ok(mm)
}

/// A refused value of a figure file: the file, the field and why.
pub(super) fn bad<T>(file: &Path, field: &str, why: String) -> Result<T, SceneError> {
    Err(SceneError::input(format!(
        "{}: `{field}`: {why}",
        file.display()
    )))
}
