//! Figure files: one figure from several runs or sweeps (scenes with overrides), as panels in a
//! grid: a quantity against τ with runs overlaid (a zoom on an impact), a rocking spectrum (all of
//! a figure's spectra on one colour scale), or overturning boundaries of several structures. The
//! file format is in scenes/paper/README.md; the paper's Figs 3-10 are such files. Sweeps are
//! journaled in a cache directory named by their fingerprint ([`Loader`]), so figures that share
//! a spectrum compute it once, and a rerun reads it back. `rocking figure` and Python's
//! `rocking.figure` draw through [`draw`].

mod file;
mod load;

pub use file::{read, FigureFile};
pub use load::{theta_cr_over_alpha, Loader};

use file::{bad, width_mm, PanelSpec, BISECTIONS, DPI, INSET_DEFAULT};

use std::collections::BTreeMap;
use std::path::Path;

use crate::figure::{
    self as plot, reported_panel, Figure, HistoryPanel, Panel, Quantity, SpectrumPanel, Structure,
};
use crate::style;
use rocking_scene::SceneError;
use rocking_study::StudyError;

/// The name of a figure file's outputs: its stem (`fig3.toml` draws `fig3.svg`, …).
pub fn stem(file: &Path) -> String {
    file.file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "figure".into())
}

/// The figure of a figure file read with [`read`]: its runs and sweeps loaded through `loader`,
/// each sweep at most `cells` cells per ranged axis (a quick draft of a large grid), its title
/// and caption inside the image when `draft`. Notes a colour scale that clips cells on stderr.
pub fn draw(
    file: &Path,
    spec: &FigureFile,
    loader: &mut Loader,
    cells: Option<usize>,
    draft: bool,
) -> Result<Figure, StudyError> {
    let mut figure = build(file, spec, loader, cells)?;
    if let Some(p) = &mut figure.print {
        p.draft = draft;
    }
    if let Some((top, n)) = figure.above_colour_top() {
        eprintln!(
            "note: {}: {n} shaded cells lie above colour_top = {top} and are drawn in its \
             colour (raise colour_top to tell them apart)",
            file.display()
        );
    }
    Ok(figure)
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
) -> Result<Figure, StudyError> {
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
    // Structures by label: one of the same label in several panels (small multiples) keeps its
    // line style, so the legend holds it once.
    let mut structure_labels: Vec<&str> = Vec::new();
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
                inset,
            } => {
                let q = Quantity::parse(quantity).unwrap_or(plot::THETA_OVER_ALPHA);
                let mut panel =
                    HistoryPanel::new(q, runs.iter().map(|r| traces[r].clone()).collect());
                panel.title = title.clone();
                panel.black = *black;
                panel.rules = lines.clone();
                panel.twins = twins.iter().map(|r| traces[r].clone()).collect();
                panel.inset = inset.as_ref().map(|i| {
                    let [w, h] = i.size.unwrap_or(INSET_DEFAULT);
                    plot::Inset {
                        window: i.tau.map(|[a, b]| (a, b)),
                        range: i.range.map(|[a, b]| (a, b)),
                        corner: i
                            .corner
                            .as_deref()
                            .and_then(plot::Corner::parse)
                            .unwrap_or(plot::Corner::TopRight),
                        size: (w, h),
                    }
                });
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
                quantity,
                contours,
            } => {
                let s = &sweeps[sweep];
                let reported = match quantity {
                    Some(q) => Some(reported_index(file, sweep, &s.plan.sweep, q)?),
                    None => None,
                };
                let mut panel = match reported {
                    Some(k) => reported_panel(&s.plan.sweep, &s.cells, k, contours),
                    None => SpectrumPanel::new(&s.plan.sweep, &s.cells),
                };
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
                // θ_cr/α marks the colour bar of max θ/α; a reported quantity keeps its own.
                if reported.is_none() {
                    let alpha = crate::text::tick(s.alpha);
                    panel.mark = s.theta_cr.map(|v| {
                        let v2 = crate::text::tick((v * 100.0).round() / 100.0);
                        (v, format!("θ_cr/α = {v2} (α = {alpha})"))
                    });
                }
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
                    let k = match structure_labels.iter().position(|l| *l == sspec.label) {
                        Some(k) => k,
                        None => {
                            structure_labels.push(&sspec.label);
                            structure_labels.len() - 1
                        }
                    };
                    let style = line_style(&sspec.style, k);
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
                let mut panel = plot::BoundaryPanel::over(&first.plan.sweep, structures, method);
                panel.title = title.clone();
                Panel::Boundaries(panel)
            }
        });
    }
    let lines = traces.len().max(structure_labels.len());
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

/// The index of `quantity` among the quantities sweep `name` reports, or an input error naming
/// the panel's field and what the sweep's scene reports.
fn reported_index(
    file: &Path,
    name: &str,
    sweep: &rocking_spectra::Sweep,
    quantity: &str,
) -> Result<usize, StudyError> {
    sweep
        .reported
        .iter()
        .position(|r| r == quantity)
        .ok_or_else(|| {
            SceneError::input(format!(
                "{}: `quantity` = \"{quantity}\" in a spectrum panel is not reported by sweep \
                 `{name}`: its scene's [sweep] report lists {}",
                file.display(),
                if sweep.reported.is_empty() {
                    "nothing".to_string()
                } else {
                    sweep.reported.join(", ")
                }
            ))
            .into()
        })
}
