//! The runs and sweeps of a figure, loaded through the scene and study libraries (the one
//! place `rocking figure` calls them). A sweep is journaled in `<cache>/<fingerprint>/`, so the
//! figures that share it, and a later invocation, read its cells back instead of computing them
//! again (a changed scene, override, axis or program has another fingerprint).

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::rc::Rc;

use crate::style::LineStyle;
use rocking_spectra::{Cell, CellClass, Progress};
use rocking_study::plan::{Base, Plan, DEFAULT_AXES};

use crate::figure::Trace;
use rocking_scene::SceneError;
use rocking_study::StudyError;

/// A sweep's plan and cells, and θ_cr/α of its structure.
pub struct Swept {
    pub plan: Plan,
    pub cells: Vec<Cell>,
    pub theta_cr: Option<f64>,
    /// α of its structure.
    pub alpha: f64,
}

/// Loads runs and sweeps, each sweep once per invocation and once per cache.
pub struct Loader {
    cache: PathBuf,
    progress: Progress,
    swept: HashMap<String, Rc<Swept>>,
}

impl Loader {
    pub fn new(cache: &Path, quiet: bool) -> Loader {
        Loader {
            cache: cache.to_path_buf(),
            progress: if quiet {
                Progress::Quiet
            } else {
                Progress::Auto
            },
            swept: HashMap::new(),
        }
    }

    /// The run of a scene with overrides, with its history (a 0.01 τ grid unless the scene asks
    /// for another), its events and its energies.
    pub fn run(
        &mut self,
        scene: &Path,
        set: &[String],
        label: String,
        style: LineStyle,
    ) -> Result<Trace, StudyError> {
        let mut sets = set.to_vec();
        sets.push("output.plots=true".into());
        let sc = rocking_scene::scene::load(scene, &sets)?;
        let mut m = rocking_scene::setup::build(&sc)?;
        m.options.event_log = true;
        m.options.energy = true;
        let run = rocking_study::report::simulate(&m, scene)?.run;
        Ok(Trace::of(&m, &run, label, style))
    }

    /// The cells of a two-axis sweep of a scene: `axes`, else the scene's `[sweep] axes`, else
    /// the paper's; each `start:stop:count` axis at most `cells` values.
    pub fn sweep(
        &mut self,
        scene: &Path,
        set: &[String],
        axes: Option<&[String]>,
        cells: Option<usize>,
    ) -> Result<Rc<Swept>, StudyError> {
        let base = Base::load(scene, set)?;
        let specs: Vec<String> = match axes {
            Some(a) => a.to_vec(),
            None => base
                .scene()
                .spec
                .sweep
                .as_ref()
                .and_then(|s| s.axes.clone())
                .unwrap_or_else(|| DEFAULT_AXES.iter().map(|s| s.to_string()).collect()),
        };
        let specs: Vec<String> = specs.iter().map(|s| capped(s, cells)).collect();
        let plan = Plan::spectrum(base, &specs)?;
        if plan.sweep.axes.len() != 2 {
            return Err(SceneError::input(format!(
                "{}: a figure's sweep has two axes (the panel's x and y), not {}",
                scene.display(),
                plan.sweep.axes.len()
            ))
            .into());
        }
        if let Some(s) = self.swept.get(&plan.sweep.fingerprint) {
            return Ok(s.clone());
        }
        let dir = self.cache.join(&plan.sweep.fingerprint);
        let outcome = rocking_spectra::run(&plan.sweep, &dir, self.progress, |v| plan.run_cell(v))?;
        if let Some((_, first)) = outcome.failures.first() {
            eprintln!(
                "note: {} of {} cells of {} failed (drawn black); first: {first}",
                outcome.failures.len(),
                outcome.cells.len(),
                scene.display()
            );
        }
        let theta_cr = theta_cr_over_alpha(&plan)?;
        let alpha = plan.base.model(&[])?.structure.derived().alpha;
        let swept = Rc::new(Swept {
            alpha,
            cells: outcome.cells,
            theta_cr,
            plan,
        });
        self.swept
            .insert(swept.plan.sweep.fingerprint.clone(), swept.clone());
        Ok(swept)
    }
}

/// An axis `key=start:stop:count` with its count at most `cells`; other axes as given.
fn capped(spec: &str, cells: Option<usize>) -> String {
    let (Some(cap), Some((key, range))) = (cells, spec.split_once('=')) else {
        return spec.to_string();
    };
    let parts: Vec<&str> = range.split(':').collect();
    match (
        parts.as_slice(),
        parts.get(2).and_then(|c| c.trim().parse::<usize>().ok()),
    ) {
        ([a, b, _], Some(count)) if count > cap => format!("{key}={a}:{b}:{cap}"),
        _ => spec.to_string(),
    }
}

/// The lowest overturning amplitude at `x` between `upright` and `overturned`, by `steps`
/// bisections of the sweep's own cell (the plan runs [x, amplitude]); a failed run ends it.
pub fn bisect(plan: &Plan, x: f64, upright: f64, overturned: f64, steps: usize) -> f64 {
    let (mut lo, mut hi) = (upright, overturned);
    for _ in 0..steps {
        let mid = 0.5 * (lo + hi);
        match plan.run_cell(&[x, mid]) {
            Ok(cell) => match CellClass::of(&cell.summary).overturned() {
                Some(true) => hi = mid,
                _ => lo = mid,
            },
            Err(_) => break,
        }
    }
    0.5 * (lo + hi)
}

/// θ_cr/α of a sweep's structure, when no axis changes it (the axes of the figure's grid are
/// the pulse's, or the structure's stiffness or damping).
pub fn theta_cr_over_alpha(plan: &Plan) -> Result<Option<f64>, SceneError> {
    let keeps = |k: &str| {
        !k.starts_with("structure.") || k == "structure.omega_n_over_p" || k == "structure.zeta"
    };
    if !plan.sweep.axes.iter().all(|a| keeps(&a.key)) {
        return Ok(None);
    }
    let d = plan.base.model(&[])?.structure.derived();
    Ok(Some(d.theta_cr / d.alpha))
}

#[cfg(test)]
mod tests {
    use super::capped;

    #[test]
    fn a_cap_lowers_the_count_of_ranged_axes_only() {
        assert_eq!(capped("a.b=1:10:100", Some(8)), "a.b=1:10:8");
        assert_eq!(capped("a.b=1:10:5", Some(8)), "a.b=1:10:5");
        assert_eq!(capped("a.b=1,2,3", Some(2)), "a.b=1,2,3");
        assert_eq!(capped("a.b=1:10:100", None), "a.b=1:10:100");
    }
}
