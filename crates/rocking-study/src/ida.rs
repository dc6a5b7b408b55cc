//! A record-suite fragility study from a scene's `[ida]` table, for the command (`rocking ida`)
//! and the Python package alike: per record its intensity measures (once), then either its
//! overturning capacity in the chosen IM by hunt-and-fill with its IDA curve, or with
//! `stripes` its outcome at each IM level; over the suite the lognormal fragility fitted by
//! maximum likelihood (to the capacities, or to the counts per stripe: Baker 2015) with a
//! bootstrap band. Runs in the caller's rayon pool, one record per task.

use std::path::{Path, PathBuf};

use rayon::prelude::*;
use rocking_fragility::{
    bootstrap_capacities, bootstrap_stripes, Bootstrap, BootstrapOptions, HuntFill, IdaError,
    IdaPoint, Outcome, ScalingIm, Stripe,
};
use rocking_motion::intensity::IntensityMeasures;
use rocking_motion::AccelUnit;
use rocking_scene::knob::KnobValue;
use rocking_scene::scene::{ExcitationSpec, IdaSpec, Source};
use rocking_scene::SceneError;

use serde_json::json;

use crate::plan::Base;

/// The settings of a study, from `[ida]`, checked.
pub struct Settings {
    /// The intensity measure the records are scaled to.
    pub im: ScalingIm,
    /// Hunt-and-fill (IDA).
    pub hunt: HuntFill,
    /// The IM levels of a multiple-stripe analysis, sorted (`None`: IDA by hunt-and-fill).
    pub stripes: Option<Vec<f64>>,
    /// Collapse is overturning, or max θ/α reaching this.
    pub limit: Option<f64>,
    /// The confidence band's resampling.
    pub bootstrap: BootstrapOptions,
}

/// One record of the suite: where it is, what it is, its IMs and its analyses.
pub struct RecordStudy {
    /// File name.
    pub name: String,
    /// Canonical path.
    pub path: String,
    /// Time step (s).
    pub dt: f64,
    /// Number of samples.
    pub npts: usize,
    /// The units the record was read in.
    pub unit: &'static str,
    /// Its intensity measures at scale 1, as the structure feels it (1 g = the structure's g).
    pub ims: IntensityMeasures,
    /// The scaling IM at scale 1 (m/s²).
    pub im_unscaled: f64,
    /// Every analysis of the record, sorted by IM.
    pub points: Vec<IdaPoint>,
    /// The IDA capacity and the highest survivor below it (`None` for stripes).
    pub capacity: Option<(f64, f64)>,
}

/// What the fragility was fitted to.
pub enum Evidence {
    /// One IDA capacity per record (m/s²).
    Capacities(Vec<f64>),
    /// Records run and collapsed per IM level.
    Stripes(Vec<Stripe>),
}

/// A finished study.
pub struct Study {
    /// The `[ida]` settings it ran with.
    pub settings: Settings,
    /// Per record, in the order of the files.
    pub records: Vec<RecordStudy>,
    /// The maximum-likelihood fit and its bootstrap band.
    pub fit: Bootstrap,
    /// What it was fitted to.
    pub evidence: Evidence,
}

impl Study {
    /// "ida" or "multiple-stripe".
    pub fn method(&self) -> &'static str {
        match self.evidence {
            Evidence::Capacities(_) => "ida",
            Evidence::Stripes(_) => "multiple-stripe",
        }
    }

    /// The number of simulations run.
    pub fn analyses(&self) -> usize {
        self.records.iter().map(|r| r.points.len()).sum()
    }

    /// The fit and what it was fitted to, as `fragility.json` holds them (without the scene):
    /// method, IM, collapse definition, counts, median and β with their bootstrap intervals, and
    /// the capacities or the stripes.
    pub fn fragility_json(&self) -> serde_json::Value {
        let s = &self.settings;
        let (im_name, period, damping) = match s.im {
            ScalingIm::Pga => ("pga", None, None),
            ScalingIm::Sa { period, damping } => ("sa", Some(period), Some(damping)),
        };
        let (tl, th) = self.fit.theta_interval();
        let (bl, bh) = self.fit.beta_interval();
        let mut v = json!({
            "method": self.method(),
            "im": { "kind": im_name, "period_s": period, "damping": damping, "unit": "m/s2" },
            "collapse": match s.limit {
                Some(l) => format!("overturned or max theta/alpha >= {l}"),
                None => "overturned".to_string(),
            },
            "records": self.records.len(),
            "analyses": self.analyses(),
            "median_m_s2": self.fit.estimate.theta,
            "beta": self.fit.estimate.beta,
            "bootstrap": {
                "resamples": s.bootstrap.resamples,
                "seed": s.bootstrap.seed,
                "level": s.bootstrap.level,
                "failed_resamples": self.fit.failed,
                "median_interval_m_s2": [tl, th],
                "beta_interval": [bl, bh],
            },
        });
        match &self.evidence {
            Evidence::Capacities(c) => {
                v["tolerance"] = json!(s.hunt.tolerance);
                v["capacities_m_s2"] = json!(c);
            }
            Evidence::Stripes(stripes) => {
                v["stripes"] = stripes
                    .iter()
                    .map(|st| json!({"im_m_s2": st.im, "records": st.n, "collapsed": st.collapsed}))
                    .collect();
            }
        }
        v
    }

    /// Per record: name, path, units, dt, npts, intensity measures, the scaling IM at scale 1,
    /// the capacity (IDA) and every analysis (IM, scale, collapsed, max θ/α).
    pub fn records_json(&self) -> serde_json::Value {
        self.records
            .iter()
            .map(|r| {
                let m = &r.ims;
                json!({
                    "name": r.name, "path": r.path, "units": r.unit, "dt_s": r.dt, "npts": r.npts,
                    "pga_m_s2": m.pga_m_s2, "pgv_m_s": m.pgv_m_s, "pgd_m": m.pgd_m,
                    "arias_m_s": m.arias_m_s, "d5_95_s": m.d5_95_s,
                    "mean_period_s": m.mean_period_s, "im_m_s2": r.im_unscaled,
                    "capacity_im_m_s2": r.capacity.map(|c| c.0),
                    "survived_below_im_m_s2": r.capacity.map(|c| c.1),
                    "analyses": r.points.iter().map(|p| json!({
                        "im_m_s2": p.im, "scale": p.im / r.im_unscaled,
                        "collapsed": p.outcome.collapsed,
                        "max_theta_over_alpha": p.outcome.response,
                    })).collect::<Vec<_>>(),
                })
            })
            .collect()
    }

    /// The empirical points beside the fit: the capacities' plotting positions (i + ½)/n, or the
    /// fraction collapsed per stripe.
    pub fn empirical(&self) -> Vec<(f64, f64)> {
        match &self.evidence {
            Evidence::Capacities(c) => {
                let mut sorted = c.clone();
                sorted.sort_by(f64::total_cmp);
                let n = sorted.len() as f64;
                sorted
                    .iter()
                    .enumerate()
                    .map(|(i, &c)| (c, (i as f64 + 0.5) / n))
                    .collect()
            }
            Evidence::Stripes(s) => s
                .iter()
                .map(|st| (st.im, f64::from(st.collapsed) / f64::from(st.n)))
                .collect(),
        }
    }
}

/// Runs the study of the scene `base` (`[ida]`) over `records` (else the scene's), in the
/// current rayon pool.
pub fn run(base: &Base, records: &[PathBuf]) -> Result<Study, SceneError> {
    let spec = base.scene().spec.ida.clone().unwrap_or_default();
    let settings = settings(&spec, &base.scene().src)?;
    let files = record_files(base, records)?;
    let done: Vec<RecordStudy> = files
        .par_iter()
        .map(|f| study(base, &settings, f))
        .collect::<Result<Vec<_>, _>>()?;
    let cannot_fit = |what: String, e: rocking_fragility::FragilityError| {
        SceneError::input(format!(
            "{}: cannot fit a lognormal to {what}: {e}",
            base.path().display()
        ))
    };
    let (fit, evidence) = match &settings.stripes {
        None => {
            let capacities: Vec<f64> = done
                .iter()
                .filter_map(|d| d.capacity)
                .map(|c| c.0)
                .collect();
            let fit = bootstrap_capacities(&capacities, &settings.bootstrap)
                .map_err(|e| cannot_fit(format!("the {} capacities", capacities.len()), e))?;
            (fit, Evidence::Capacities(capacities))
        }
        Some(levels) => {
            let records = u32::try_from(done.len()).unwrap_or(u32::MAX);
            let stripes: Vec<Stripe> = levels
                .iter()
                .map(|&im| Stripe {
                    im,
                    n: records,
                    collapsed: done
                        .iter()
                        .filter(|d| d.points.iter().any(|p| p.im == im && p.outcome.collapsed))
                        .count() as u32,
                })
                .collect();
            let fit = bootstrap_stripes(&stripes, &settings.bootstrap)
                .map_err(|e| cannot_fit(format!("the {} stripes", stripes.len()), e))?;
            (fit, Evidence::Stripes(stripes))
        }
    };
    Ok(Study {
        settings,
        records: done,
        fit,
        evidence,
    })
}

/// The most IM levels `[ida] stripes` may list.
const MAX_STRIPES: usize = 1000;

fn check(
    src: &Source,
    key: &str,
    ok: bool,
    value: impl std::fmt::Display,
    allowed: &str,
) -> Result<(), SceneError> {
    if ok {
        Ok(())
    } else {
        Err(src.err(
            &format!("ida.{key}"),
            format_args!("`{key}` = {value} in [ida] is not allowed: {allowed}"),
        ))
    }
}

/// `[ida]` checked: a bad value is an input error naming the file, the key and the allowed range.
pub fn settings(spec: &IdaSpec, src: &Source) -> Result<Settings, SceneError> {
    let im = match spec.im.as_deref().unwrap_or("sa") {
        "pga" => ScalingIm::Pga,
        "sa" => {
            let period = spec.period.ok_or_else(|| {
                src.err(
                    "ida",
                    "missing key `period` in [ida] (im = \"sa\" needs T in s, > 0)",
                )
            })?;
            check(
                src,
                "period",
                period.is_finite() && period > 0.0,
                period,
                "a period > 0 (s)",
            )?;
            let damping = spec.damping.unwrap_or(0.05);
            check(
                src,
                "damping",
                (0.0..1.0).contains(&damping),
                damping,
                "0 <= damping < 1",
            )?;
            ScalingIm::Sa { period, damping }
        }
        other => {
            return Err(src.err(
                "ida.im",
                format_args!("`im` = \"{other}\" in [ida] is not allowed: one of \"sa\", \"pga\""),
            ))
        }
    };
    let positive = |key: &str, v: Option<f64>, default: f64| -> Result<f64, SceneError> {
        let v = v.unwrap_or(default);
        check(
            src,
            key,
            v.is_finite() && v > 0.0,
            v,
            "a finite value > 0 (m/s^2)",
        )?;
        Ok(v)
    };
    let first = positive("first", spec.first, 0.1)?;
    let step = positive("step", spec.step, 0.2)?;
    let step_increment = spec.step_increment.unwrap_or(0.1);
    check(
        src,
        "step_increment",
        step_increment.is_finite() && step_increment >= 0.0,
        step_increment,
        "a finite value >= 0 (m/s^2)",
    )?;
    let tolerance = spec.tolerance.unwrap_or(0.01);
    check(
        src,
        "tolerance",
        tolerance > 0.0 && tolerance < 1.0,
        tolerance,
        "0 < tolerance < 1",
    )?;
    let max_gap = spec.max_gap.unwrap_or(0.25_f64.max(tolerance));
    check(
        src,
        "max_gap",
        max_gap >= tolerance && max_gap < 1.0,
        max_gap,
        "tolerance <= max_gap < 1",
    )?;
    let max_runs = spec.max_runs.unwrap_or(80);
    check(
        src,
        "max_runs",
        (1..=10_000).contains(&max_runs),
        max_runs,
        "1 <= max_runs <= 10000",
    )?;
    if let Some(l) = spec.theta_over_alpha_limit {
        check(
            src,
            "theta_over_alpha_limit",
            l.is_finite() && l > 0.0,
            l,
            "a finite value > 0 (collapse when max θ/α reaches it)",
        )?;
    }
    if let Some(levels) = &spec.stripes {
        check(
            src,
            "stripes",
            (1..=MAX_STRIPES).contains(&levels.len()),
            format_args!("a list of {} levels", levels.len()),
            &format!("1 to {MAX_STRIPES} IM levels"),
        )?;
        if let Some(bad) = levels.iter().find(|v| !(v.is_finite() && **v > 0.0)) {
            check(
                src,
                "stripes",
                false,
                format_args!("[..., {bad}, ...]"),
                "IM levels finite and > 0 (m/s^2)",
            )?;
        }
    }
    let resamples = spec.bootstrap.unwrap_or(2000);
    let max = rocking_fragility::bootstrap::MAX_RESAMPLES;
    check(
        src,
        "bootstrap",
        (1..=max).contains(&resamples),
        resamples,
        &format!("1 <= bootstrap <= {max}"),
    )?;
    Ok(Settings {
        im,
        hunt: HuntFill {
            first,
            step,
            step_increment,
            tolerance,
            max_gap,
            max_runs,
        },
        // Sorted, each level once (a repeated level would count its records twice).
        stripes: spec.stripes.clone().map(|mut v| {
            v.sort_by(f64::total_cmp);
            v.dedup();
            v
        }),
        limit: spec.theta_over_alpha_limit,
        bootstrap: BootstrapOptions {
            resamples,
            seed: spec.seed.unwrap_or(14),
            level: 0.95,
        },
    })
}

/// The record files: the arguments, else `[ida] records`, else `[sweep] records`; a folder
/// stands for its files of a known record format, sorted.
pub fn record_files(base: &Base, given: &[PathBuf]) -> Result<Vec<PathBuf>, SceneError> {
    let spec = &base.scene().spec;
    let dir = base.scene().src.dir();
    let listed = spec
        .ida
        .as_ref()
        .and_then(|i| i.records.clone())
        .or_else(|| spec.sweep.as_ref().and_then(|s| s.records.clone()))
        .unwrap_or_default();
    let given: Vec<PathBuf> = if given.is_empty() {
        listed.iter().map(|r| dir.join(r)).collect()
    } else {
        given.to_vec()
    };
    let files = crate::plan::expand_records(given)?;
    if files.is_empty() {
        return Err(SceneError::input(format!(
            "{}: no records: give --records FILE|DIR or `records = [...]` in [ida] ({})",
            base.path().display(),
            rocking_motion::formats::FOLDER_RULE
        )));
    }
    Ok(files)
}

/// Runs one record's IDA, or its stripes.
fn study(base: &Base, s: &Settings, file: &Path) -> Result<RecordStudy, SceneError> {
    let path = std::fs::canonicalize(file)
        .unwrap_or_else(|_| file.to_path_buf())
        .display()
        .to_string();
    // Validates the record against the scene (format, units, scale), as `run` would.
    let model = base.model(&[
        format!("excitation.path={path:?}"),
        "excitation.scale=1.0".into(),
    ])?;
    let sc = base.scene();
    let exc = ExcitationSpec {
        path: Some(path.clone()),
        ..sc.spec.excitation.clone().unwrap_or_default()
    };
    let rec = rocking_scene::excitation::scene_record(&sc.src, &exc)?;
    let unit = rec.declared_unit.map_or("g (not stated)", AccelUnit::name);
    let (dt, npts) = (rec.dt, rec.npts);
    // The record as the structure feels it (the units model of `AccelUnit`), in m/s².
    let si = rec.to_record_si(model.units.g_si);
    let bad = |e: &dyn std::fmt::Display| SceneError::input(format!("{path}: {e}"));
    let ims = IntensityMeasures::of(&si).map_err(|e| bad(&e))?;
    let im_unscaled = s.im.of(&si).map_err(|e| bad(&e))?;
    if !(im_unscaled.is_finite() && im_unscaled > 0.0) {
        return Err(bad(
            &"the record's intensity measure is 0: it cannot be scaled",
        ));
    }
    let knobs = base
        .knobs(&["excitation.path", "excitation.scale"])
        .ok_or_else(|| SceneError::failure("record path and scale are not knobs"))?;
    let run_at = |im: f64| -> Result<Outcome, SceneError> {
        let cell = [
            (&knobs[0], KnobValue::Text(path.clone())),
            (&knobs[1], KnobValue::Number(im / im_unscaled)),
        ];
        let sum = base.run_knobs(&cell)?.summary;
        let r = sum.max_theta_over_alpha;
        Ok(Outcome {
            collapsed: sum.overturned || s.limit.is_some_and(|l| r >= l),
            response: r,
        })
    };
    let (points, capacity) = match &s.stripes {
        Some(levels) => {
            let mut points = levels
                .iter()
                .map(|&im| run_at(im).map(|outcome| IdaPoint { im, outcome }))
                .collect::<Result<Vec<_>, _>>()?;
            points.sort_by(|a, b| a.im.total_cmp(&b.im));
            (points, None)
        }
        None => {
            let ida = s.hunt.run(run_at).map_err(|e| match e {
                IdaError::Analysis { source, .. } => source,
                IdaError::InvalidParameter(m) => SceneError::failure(m),
                budget => SceneError::input(format!(
                    "{path}: {budget}; raise `max_runs` in [ida] (1 <= max_runs <= 10000) or `step`"
                )),
            })?;
            (ida.points, Some((ida.capacity, ida.survived_below)))
        }
    };
    let name = file
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    Ok(RecordStudy {
        name,
        path,
        dt,
        npts,
        unit,
        ims,
        im_unscaled,
        points,
        capacity,
    })
}
