//! Outputs: the summary as JSON, the history and event CSVs, atomic file writes.

use std::fmt::Write as _;
use std::io::Write as _;
use std::path::{Path, PathBuf};

use rocking::{Run, Time};
use serde_json::{json, Value};

use crate::model::Model;
use crate::scene::CliError;

/// Writes `bytes` to `path` atomically: a temporary file in the same directory, then a rename.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<(), CliError> {
    let dir = path.parent().unwrap_or_else(|| Path::new("."));
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| "out".into());
    let tmp = dir.join(format!(".{name}.tmp{}", std::process::id()));
    let fail = |e: std::io::Error| {
        let _ = std::fs::remove_file(&tmp);
        CliError::Internal(format!("{}: cannot write: {e}", path.display()))
    };
    let mut f = std::fs::File::create(&tmp).map_err(fail)?;
    f.write_all(bytes).map_err(fail)?;
    f.sync_all().map_err(fail)?;
    drop(f);
    std::fs::rename(&tmp, path).map_err(fail)
}

pub use rocking_scene::limits::short;

/// The files `rocking run` writes; an existing output directory holding anything else is not
/// replaced (it is not a run's directory).
pub const RUN_FILES: [&str; 5] = [
    "summary.json",
    "history.csv",
    "events.csv",
    "plot.png",
    "plot.svg",
];

/// The files `rocking ida` writes (its --out is replaced whole like a run's).
pub const IDA_FILES: [&str; 7] = [
    "records.csv",
    "ida.csv",
    "fragility.json",
    "ida.png",
    "ida.svg",
    "fragility-fit.png",
    "fragility-fit.svg",
];

/// The output directory of one run, built aside and swapped in whole: the directory always holds
/// exactly one run's files, whether the run is killed while writing (the old directory stays),
/// runs in parallel into the same `--out` (the last to finish wins, never a mix), or writes fewer
/// files than the previous run (no stale ones). The swap happens under a lock file beside the
/// directory; leftovers of killed runs are removed by the next run.
pub struct OutDir {
    target: PathBuf,
    staging: tempfile::TempDir,
    _lock: std::fs::File,
}

impl OutDir {
    /// Locks `target`'s name, removes what killed runs left, and creates the staging directory.
    pub fn begin(target: &Path) -> Result<OutDir, CliError> {
        use fs4::fs_std::FileExt as _;
        let io = |what: &str, p: &Path, e: std::io::Error| {
            CliError::Internal(format!("{}: cannot {what}: {e}", p.display()))
        };
        let name = target
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .ok_or_else(|| {
                CliError::Input(format!(
                    "{}: not a directory name for --out",
                    target.display()
                ))
            })?;
        let parent = match target.parent() {
            Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
            _ => PathBuf::from("."),
        };
        std::fs::create_dir_all(&parent).map_err(|e| io("create", &parent, e))?;
        if target.exists() {
            check_is_run_dir(target)?;
        }
        let lock_path = parent.join(format!(".{name}.lock"));
        let lock = std::fs::OpenOptions::new()
            .create(true)
            .truncate(false)
            .write(true)
            .open(&lock_path)
            .map_err(|e| io("open", &lock_path, e))?;
        lock.lock_exclusive()
            .map_err(|e| io("lock", &lock_path, e))?;
        // Under the lock no other run is staging: whatever staging directory exists is a
        // leftover of a killed run.
        let prefix = format!(".{name}.rocking-");
        if let Ok(entries) = std::fs::read_dir(&parent) {
            for e in entries.flatten() {
                if e.file_name().to_string_lossy().starts_with(&prefix) {
                    let _ = std::fs::remove_dir_all(e.path());
                }
            }
        }
        let staging = tempfile::Builder::new()
            .prefix(&prefix)
            .tempdir_in(&parent)
            .map_err(|e| io("create a directory in", &parent, e))?;
        Ok(OutDir {
            target: target.to_path_buf(),
            staging,
            _lock: lock,
        })
    }

    /// Where the files are written before the swap.
    pub fn path(&self) -> &Path {
        self.staging.path()
    }

    /// The final path of a file written into [`OutDir::path`].
    pub fn final_path(&self, staged: &Path) -> PathBuf {
        staged
            .file_name()
            .map_or_else(|| self.target.clone(), |n| self.target.join(n))
    }

    /// Swaps the staged directory in for the target (the old one is removed).
    pub fn commit(self) -> Result<(), CliError> {
        let fail = |e: std::io::Error| {
            CliError::Internal(format!("{}: cannot replace: {e}", self.target.display()))
        };
        let parent = self.staging.path().parent().unwrap_or(Path::new("."));
        let old = tempfile::Builder::new()
            .prefix(&format!(
                ".{}.rocking-old-",
                self.target
                    .file_name()
                    .unwrap_or_default()
                    .to_string_lossy()
            ))
            .tempdir_in(parent)
            .map_err(fail)?;
        let had_target = self.target.exists();
        if had_target {
            check_is_run_dir(&self.target)?;
            // rename() replaces an empty directory: the old run moves into the (empty) `old`.
            std::fs::rename(&self.target, old.path()).map_err(fail)?;
        }
        let staged = self.staging.keep();
        std::fs::rename(&staged, &self.target).map_err(|e| {
            let _ = std::fs::remove_dir_all(&staged);
            fail(e)
        })?;
        drop(old); // removes the previous run's files
        Ok(())
    }
}

/// An existing `--out` must be a directory of run outputs only (never a user's folder).
fn check_is_run_dir(target: &Path) -> Result<(), CliError> {
    if !target.is_dir() {
        return Err(CliError::Input(format!(
            "{}: --out exists and is not a directory",
            target.display()
        )));
    }
    let entries = std::fs::read_dir(target)
        .map_err(|e| CliError::Internal(format!("{}: cannot read: {e}", target.display())))?;
    for e in entries.flatten() {
        let n = e.file_name().to_string_lossy().into_owned();
        // `.summary.json.tmp123`: a temporary file an older version left when killed.
        let leftover = RUN_FILES
            .iter()
            .chain(&IDA_FILES)
            .any(|f| n.starts_with(&format!(".{f}.tmp")));
        if !RUN_FILES.contains(&n.as_str()) && !IDA_FILES.contains(&n.as_str()) && !leftover {
            return Err(CliError::Input(format!(
                "{}: --out holds `{n}`, which `rocking run` does not write; the run replaces the \
                 whole directory, so give an --out that holds only a previous run's outputs",
                target.display()
            )));
        }
    }
    Ok(())
}

fn finite(name: &str, x: f64) -> Result<f64, CliError> {
    if x.is_finite() {
        Ok(x)
    } else {
        Err(CliError::Internal(format!(
            "the run produced a non-finite {name} ({x}); no results written"
        )))
    }
}

fn tau(t: Option<Time>) -> Value {
    t.map_or(Value::Null, |t| json!(t.tau))
}

fn seconds(t: Option<Time>) -> Value {
    t.and_then(|t| t.seconds).map_or(Value::Null, |s| json!(s))
}

/// Derived quantities of the structure, for `check` and the summary. A non-finite value would be
/// written as `null`: it is an error instead (the model checks them when it is built).
pub fn derived_json(model: &Model) -> Result<Value, CliError> {
    let d = model.structure.derived();
    let u = &model.units;
    let v = json!({
        "p": d.p,
        "p_per_second": model.structure.p_per_second(),
        "omega_n": d.omega_n,
        "omega_n_over_p": d.omega_n / d.p,
        "omega_up": d.omega_up,
        "modal_s": d.modal_s,
        "alpha": d.alpha,
        "r": d.r,
        "zeta_fixed_base": d.zeta_fixed_base,
        "zeta_uplifted": d.zeta_uplifted,
        "u_cr": d.u_cr,
        "theta_cr": d.theta_cr,
        "e_ref": d.e_ref,
        "static_uplift_over_g_tan_alpha":
            model.structure.static_uplift_acceleration() / u.accel_g_tan_alpha(),
        "units": if u.physical { "SI (s, m, kg)" } else { "model (R = g = m = 1, time τ)" },
    });
    if let Some((k, _)) = v
        .as_object()
        .into_iter()
        .flatten()
        .find(|(k, x)| x.is_null() && k.as_str() != "p_per_second")
    {
        return Err(CliError::Input(format!(
            "the derived quantity {k} is not finite: the structure's values are out of range"
        )));
    }
    Ok(v)
}

/// The summary object printed by `--json` and written to summary.json.
pub fn summary_json(model: &Model, scene: &Path, run: &Run) -> Result<Value, CliError> {
    let s = &run.summary;
    let energy = match s.energy {
        Some(e) => json!({
            "initial": finite("energy", e.initial)?,
            "last": finite("energy", e.last)?,
            "ground_work": finite("energy", e.ground_work)?,
            "damping": finite("energy", e.damping)?,
            "impact_losses": finite("energy", e.impact_losses)?,
        }),
        None => Value::Null,
    };
    let residual = match s.energy_balance_residual {
        Some(r) => json!(finite("energy balance residual", r)?),
        None => Value::Null,
    };
    Ok(json!({
        "scene": scene.display().to_string(),
        "title": model.title,
        "kernel_variant": s.kernel_variant,
        "variant_reasons": model.reasons,
        "excitation": model.excitation_description,
        "max_theta_over_alpha": finite("max θ/α", s.max_theta_over_alpha)?,
        "max_theta_over_theta_cr": finite("max θ/θ_cr", s.max_theta_over_theta_cr)?,
        "max_u_over_ucr": finite("max u/u_cr", s.max_u_over_ucr)?,
        "overturned": s.overturned,
        "overturn_time": tau(s.overturn_time),
        "overturn_time_s": seconds(s.overturn_time),
        "impacts": s.impacts,
        "significant_impacts": s.significant_impacts,
        "energy_capped_impacts": s.energy_capped_impacts,
        "first_uplift_time": tau(s.first_uplift_time),
        "first_uplift_time_s": seconds(s.first_uplift_time),
        "first_impact_time": tau(s.first_impact_time),
        "first_impact_time_s": seconds(s.first_impact_time),
        "final_phase": s.final_phase,
        "end_time": s.end_time.tau,
        "end_time_s": s.end_time.seconds,
        "energy_balance_residual": residual,
        "energy": energy,
        "solver_stats": s.solver_stats,
        "derived": derived_json(model)?,
    }))
}

fn num(out: &mut String, x: f64) -> Result<(), CliError> {
    let x = finite("history value", x)?;
    let _ = write!(out, ",{x}");
    Ok(())
}

/// history.csv: τ, seconds (when known), normalised state, phase, energies, ground acceleration.
pub fn history_csv(model: &Model, run: &Run) -> Result<String, CliError> {
    let d = model.structure.derived();
    let u = &model.units;
    let ps = model.structure.p_per_second();
    let mut out = String::from(
        "tau,t_s,theta_over_alpha,u_over_ucr,theta_dot_over_alpha_p,u_dot_over_ucr_omega_n,\
         phase,e_kin_over_eref,e_total_over_eref,ug_over_g_tan_alpha\n",
    );
    for r in &run.history {
        let _ = write!(out, "{}", finite("τ", r.tau)?);
        match ps {
            Some(p) => num(&mut out, r.tau / p)?,
            None => out.push(','),
        }
        num(&mut out, r.theta / u.alpha)?;
        num(&mut out, r.u / d.u_cr)?;
        num(&mut out, r.theta_dot / (u.alpha * d.p))?;
        num(&mut out, r.u_dot / (d.u_cr * d.omega_n))?;
        let phase = serde_json::to_value(r.phase).unwrap_or(Value::Null);
        let _ = write!(out, ",{}", phase.as_str().unwrap_or("?"));
        num(&mut out, r.e_kin)?;
        num(&mut out, r.e_total)?;
        num(&mut out, r.ug / u.accel_g_tan_alpha())?;
        out.push('\n');
    }
    Ok(out)
}

/// events.csv: one row per uplift, impact, rest or overturning.
pub fn events_csv(model: &Model, run: &Run) -> Result<String, CliError> {
    let d = model.structure.derived();
    let u = &model.units;
    let mut out = String::from(
        "tau,t_s,kind,branch,phase_after,theta_dot_over_alpha_p,u_over_ucr,\
         u_dot_over_ucr_omega_n,e_kin_before_over_eref,e_kin_after_over_eref\n",
    );
    for e in &run.events {
        let _ = write!(out, "{}", finite("τ", e.time.tau)?);
        match e.time.seconds {
            Some(s) => num(&mut out, s)?,
            None => out.push(','),
        }
        let kind = serde_json::to_value(e.kind).unwrap_or(Value::Null);
        let phase = serde_json::to_value(e.phase_after).unwrap_or(Value::Null);
        let _ = write!(
            out,
            ",{},{},{}",
            kind.as_str().unwrap_or("?"),
            e.branch,
            phase.as_str().unwrap_or("?")
        );
        num(&mut out, e.theta_dot / (u.alpha * d.p))?;
        num(&mut out, e.u / d.u_cr)?;
        num(&mut out, e.u_dot / (d.u_cr * d.omega_n))?;
        num(&mut out, e.energy_before)?;
        num(&mut out, e.energy_after)?;
        out.push('\n');
    }
    Ok(out)
}
