//! `rocking figure FIGURE.toml... [--out DIR]`: one figure from several runs or sweeps (scenes
//! with overrides), as panels in a grid: a quantity against τ with runs overlaid (a zoom on an
//! impact), a rocking spectrum (all of a figure's spectra on one colour scale), or overturning
//! boundaries of several structures. The file format is in scenes/paper/README.md; the paper's
//! Figs 3-10 are such files. Sweeps are journaled in a cache directory named by their
//! fingerprint, so figures that share a spectrum compute it once, and a rerun reads it back.

mod load;

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use serde::Deserialize;

use crate::out_dir::{OutDir, FIGURE_OUT};
use crate::plot::{self, Figure, HistoryPanel, Panel, Quantity, SpectrumPanel, Structure};
use load::Loader;
use rocking_plot::style;
use rocking_scene::SceneError;

/// A figure file.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct FigureFile {
    title: String,
    caption: Option<String>,
    #[serde(default = "one")]
    columns: usize,
    /// The printed width: "double" (175 mm), "single" (85 mm) or a length in mm (default
    /// "double").
    width: Option<toml::Value>,
    /// The PNG's resolution in pixels per inch (default 600).
    dpi: Option<u32>,
    /// A panel's width and height: their ratio is the panels' aspect at the printed width.
    panel: Option<[u32; 2]>,
    /// The top of the spectra's shared colour scale (default: their largest survivor).
    colour_top: Option<f64>,
    /// Cells per ranged axis of every sweep (`start:stop:count` gets this count).
    cells: Option<usize>,
    #[serde(default)]
    runs: BTreeMap<String, RunSpec>,
    #[serde(default)]
    sweeps: BTreeMap<String, SweepSpec>,
    panels: Vec<PanelSpec>,
}

fn one() -> usize {
    1
}

/// A run: a scene file (relative to the figure file) with overrides.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RunSpec {
    scene: PathBuf,
    #[serde(default)]
    set: Vec<String>,
    label: String,
    /// A line style by name (default: the runs in order).
    style: Option<String>,
}

/// A sweep of a scene over axes (default: the scene's `[sweep] axes`).
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct SweepSpec {
    scene: PathBuf,
    #[serde(default)]
    set: Vec<String>,
    axes: Option<Vec<String>>,
    label: String,
    style: Option<String>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields, tag = "kind", rename_all = "lowercase")]
enum PanelSpec {
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
    },
    Spectrum {
        sweep: String,
        title: Option<String>,
        /// A reference sweep whose boundary is drawn dashed.
        reference: Option<String>,
    },
    Boundaries {
        sweeps: Vec<String>,
        title: Option<String>,
        /// Bisection of each boundary point between its bracketing cells (default true).
        #[serde(default = "yes")]
        refine: bool,
    },
}

fn yes() -> bool {
    true
}

/// A τ window around the `impact`-th impact (from 1) of `run`.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Zoom {
    run: String,
    impact: usize,
    half_width: f64,
}

/// The time axes of a history panel: τ, or seconds.
const TIMES: [&str; 2] = ["tau", "s"];

/// Bounds of the figure layout.
const MAX_COLUMNS: usize = 8;
/// A journal's double and single column, and the lengths a printed width may be, in mm.
const DOUBLE_MM: f64 = 175.0;
const SINGLE_MM: f64 = 85.0;
const WIDTH_MM: (f64, f64) = (40.0, 250.0);
/// The PNG's resolution: the default and the allowed range, pixels per inch.
const DPI: u32 = 600;
const DPI_RANGE: (u32, u32) = (72, 1200);
const PANEL_PIXELS: (u32, u32) = (200, 2000);
/// Bisection steps of a boundary point: the bracket (one cell) shrinks 1024-fold.
const BISECTIONS: usize = 10;

/// Options of the command.
pub struct Options {
    pub out: PathBuf,
    /// The title and caption drawn inside the image (for screens), no caption file.
    pub draft: bool,
    pub cache: PathBuf,
    pub cells: Option<usize>,
    pub quiet: bool,
}

/// The name of a figure file's outputs: its stem (`fig3.toml` draws `fig3.svg`, …).
fn stem(file: &Path) -> String {
    file.file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "figure".into())
}

/// `rocking figure`: every figure is drawn into a staging directory that replaces `--out` at
/// the end, under its lock ([`OutDir`]), keeping the figures of other files already there; two
/// files of one name would write the same outputs and are refused before anything is drawn.
pub fn figure(files: &[PathBuf], opts: &Options) -> Result<(), SceneError> {
    let mut seen: BTreeMap<String, &PathBuf> = BTreeMap::new();
    for file in files {
        if let Some(first) = seen.insert(stem(file), file) {
            return Err(SceneError::input(format!(
                "{} and {}: both would be drawn as {}/{}.svg (.png, .pdf): draw them into \
                 different --out directories, or rename one",
                first.display(),
                file.display(),
                opts.out.display(),
                stem(file)
            )));
        }
    }
    let specs = files
        .iter()
        .map(|f| read(f))
        .collect::<Result<Vec<_>, _>>()?;
    let dir = OutDir::begin(&opts.out, FIGURE_OUT)?;
    let mut loader = Loader::new(&opts.cache, opts.quiet);
    let mut listed = Vec::new();
    for (file, spec) in files.iter().zip(&specs) {
        let mut figure = build(file, spec, &mut loader, opts.cells)?;
        if let Some(p) = &mut figure.print {
            p.draft = opts.draft;
        }
        if let Some((top, n)) = figure.above_colour_top() {
            eprintln!(
                "note: {}: {n} shaded cells lie above colour_top = {top} and are drawn in its \
                 colour (raise colour_top to tell them apart)",
                file.display()
            );
        }
        let written = figure.write(dir.path(), &stem(file))?;
        listed.push((file, written));
    }
    let listed: Vec<_> = listed
        .into_iter()
        .map(|(f, w)| (f, w.iter().map(|p| dir.final_path(p)).collect::<Vec<_>>()))
        .collect();
    dir.commit()?;
    for (file, written) in listed {
        out!("{}:", file.display());
        for p in written {
            out!("  {}", p.display());
        }
    }
    Ok(())
}

/// Reads and checks a figure file: TOML errors name the file, the line and the field.
fn read(file: &Path) -> Result<FigureFile, SceneError> {
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
                ..
            } => {
                if Quantity::parse(quantity).is_none() {
                    let names: Vec<&str> = plot::QUANTITIES.iter().map(|q| q.name).collect();
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
                ..
            } => {
                sweep(s, "sweep")?;
                if let Some(r) = reference {
                    sweep(r, "reference")?;
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

/// The printed width a figure file states, in mm: "double", "single" or a length in mm.
fn width_mm(file: &Path, width: Option<&toml::Value>) -> Result<f64, SceneError> {
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
fn bad<T>(file: &Path, field: &str, why: String) -> Result<T, SceneError> {
    Err(SceneError::input(format!(
        "{}: `{field}`: {why}",
        file.display()
    )))
}

/// The seconds per unit of τ that the runs of a panel drawn in seconds share: each run's scene
/// must know its time in seconds, and all the same.
fn seconds_per_tau(
    file: &Path,
    runs: &[String],
    traces: &BTreeMap<String, plot::Trace>,
) -> Result<f64, SceneError> {
    let mut shared: Option<f64> = None;
    for r in runs {
        let Some(s) = traces[r].seconds_per_tau else {
            return bad(
                file,
                "time",
                format!(
                    "\"s\": run `{r}` has no time in seconds (a dimensionless scene without a                      length scale): draw it against \"tau\""
                ),
            );
        };
        match shared {
            Some(v) if (v - s).abs() > 1e-12 * v.abs() => {
                return bad(
                    file,
                    "time",
                    format!(
                        "\"s\": the runs of one panel have different time scales ({v} and {s}                          s per τ): one τ axis cannot show them in seconds"
                    ),
                );
            }
            _ => shared = Some(s),
        }
    }
    shared.ok_or_else(|| SceneError::input(format!("{}: a panel without runs", file.display())))
}

/// The line style of the `k`-th run or sweep, or the one it names.
fn line_style(named: &Option<String>, k: usize) -> style::LineStyle {
    named
        .as_deref()
        .and_then(style::line_named)
        .unwrap_or(style::LINES[k % style::LINES.len()])
}

fn build(
    file: &Path,
    spec: &FigureFile,
    loader: &mut Loader,
    cells: Option<usize>,
) -> Result<Figure, SceneError> {
    let dir = file.parent().unwrap_or(Path::new("."));
    let cells = match (spec.cells, cells) {
        (Some(a), Some(b)) => Some(a.min(b)),
        (a, b) => a.or(b),
    };
    // Runs and sweeps in the order the panels use them (so default styles follow that order).
    let mut run_names: Vec<&String> = Vec::new();
    let mut sweep_names: Vec<&String> = Vec::new();
    for p in &spec.panels {
        match p {
            PanelSpec::History { runs, twins, .. } => run_names.extend(runs.iter().chain(twins)),
            PanelSpec::Spectrum {
                sweep, reference, ..
            } => sweep_names.extend(std::iter::once(sweep).chain(reference)),
            PanelSpec::Boundaries { sweeps, .. } => sweep_names.extend(sweeps),
        }
    }
    let mut traces = BTreeMap::new();
    for name in run_names {
        if traces.contains_key(name) {
            continue;
        }
        let r = &spec.runs[name];
        let style = line_style(&r.style, traces.len());
        let trace = loader.run(&dir.join(&r.scene), &r.set, r.label.clone(), style)?;
        traces.insert(name.clone(), trace);
    }
    let mut sweeps = BTreeMap::new();
    for name in sweep_names {
        if sweeps.contains_key(name) {
            continue;
        }
        let s = &spec.sweeps[name];
        let swept = loader.sweep(&dir.join(&s.scene), &s.set, s.axes.as_deref(), cells)?;
        sweeps.insert(name.clone(), swept);
    }
    let mut panels = Vec::new();
    let mut structure_count = 0;
    for p in &spec.panels {
        panels.push(match p {
            PanelSpec::History {
                quantity,
                runs,
                title,
                tau,
                zoom,
                black,
                time,
                lines,
                twins,
            } => {
                let q = Quantity::parse(quantity).unwrap_or(plot::THETA_OVER_ALPHA);
                let mut panel =
                    HistoryPanel::new(q, runs.iter().map(|r| traces[r].clone()).collect());
                panel.title = title.clone();
                panel.black = *black;
                panel.rules = lines.clone();
                panel.twins = twins.iter().map(|r| traces[r].clone()).collect();
                if time.as_deref() == Some("s") {
                    panel.seconds_per_tau = Some(seconds_per_tau(file, runs, &traces)?);
                }
                panel.window = tau.map(|[a, b]| (a, b));
                if let Some(z) = zoom {
                    let t = &traces[&z.run];
                    let at = t.impacts.get(z.impact - 1).ok_or_else(|| {
                        SceneError::input(format!(
                            "{}: `zoom.impact` = {}: run `{}` has {} impacts",
                            file.display(),
                            z.impact,
                            z.run,
                            t.impacts.len()
                        ))
                    })?;
                    panel.window = Some((at - z.half_width, at + z.half_width));
                }
                Panel::History(panel)
            }
            PanelSpec::Spectrum {
                sweep,
                title,
                reference,
            } => {
                let s = &sweeps[sweep];
                let mut panel = SpectrumPanel::new(&s.plan.sweep, &s.cells);
                if let Some(name) = reference {
                    let r = &sweeps[name];
                    // The legend names the reference by what differs from the panel's own
                    // sweep ("rigid" beside "α = 0.1, ω_n/p = 5"): one entry for every row.
                    let own: Vec<&str> = spec.sweeps[sweep].label.split(", ").collect();
                    let label = &spec.sweeps[name].label;
                    let differs: Vec<&str> =
                        label.split(", ").filter(|i| !own.contains(i)).collect();
                    let label = if differs.is_empty() {
                        label.clone()
                    } else {
                        differs.join(", ")
                    };
                    panel = panel.with_reference(&label, &r.plan.sweep, &r.cells);
                }
                panel.title = Some(
                    title
                        .clone()
                        .unwrap_or_else(|| spec.sweeps[sweep].label.clone()),
                );
                let alpha = rocking_plot::text::tick(s.alpha);
                panel.mark = s.theta_cr.map(|v| {
                    let v2 = rocking_plot::text::tick((v * 100.0).round() / 100.0);
                    (v, format!("θ_cr/α = {v2} (α = {alpha})"))
                });
                Panel::Spectrum(panel)
            }
            PanelSpec::Boundaries {
                sweeps: names,
                title,
                refine,
            } => {
                let mut structures = Vec::new();
                for name in names {
                    let s = &sweeps[name];
                    let sspec = &spec.sweeps[name];
                    let style = line_style(&sspec.style, structure_count);
                    structure_count += 1;
                    structures.push(Structure::new(
                        sspec.label.clone(),
                        style,
                        &s.plan.sweep,
                        &s.cells,
                        |x, lo, hi| {
                            if *refine {
                                load::bisect(&s.plan, x, lo, hi, BISECTIONS)
                            } else {
                                (lo + hi) / 2.0
                            }
                        },
                    ));
                }
                let first = &sweeps[&names[0]];
                let method = if *refine {
                    format!("{} (bisection)", plot::BOUNDARY_HEADING)
                } else {
                    plot::BOUNDARY_HEADING.to_string()
                };
                let mut panel =
                    crate::plot::BoundaryPanel::over(&first.plan.sweep, structures, method);
                panel.title = title.clone();
                Panel::Boundaries(panel)
            }
        });
    }
    let lines = traces.len().max(structure_count);
    if lines > style::LINES.len() {
        eprintln!(
            "warning: {}: {lines} runs or structures share the {} line styles: the {}th looks \
             like the first (give `style` to each, or split the figure)",
            file.display(),
            style::LINES.len(),
            style::LINES.len() + 1
        );
    }
    let panel = spec.panel.map_or((560, 400), |[w, h]| (w, h));
    Ok(Figure {
        title: spec.title.clone(),
        caption: spec.caption.clone(),
        columns: spec.columns,
        panel,
        panels,
        colour_top: spec.colour_top,
        print: Some(plot::Print {
            width_mm: width_mm(file, spec.width.as_ref())?,
            dpi: f64::from(spec.dpi.unwrap_or(DPI)),
            draft: false,
        }),
    })
}
