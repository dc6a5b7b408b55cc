//! `rocking ida`: incremental dynamic analysis of a record scene over a suite of records. Per
//! record its intensity measures (once), its overturning capacity in the chosen IM by
//! hunt-and-fill, and its IDA curve; over the suite the lognormal fragility fitted by maximum
//! likelihood with a bootstrap band. With `[ida] stripes` a multiple-stripe analysis instead:
//! every record at each IM level, the fit from the fraction collapsed per level (Baker 2015).
//! Not resumable: the whole study is rerun (see docs/records.md).

use std::path::{Path, PathBuf};
use std::time::Instant;

use rayon::prelude::*;
use rocking_fragility::{
    bootstrap_capacities, bootstrap_stripes, BootstrapOptions, HuntFill, IdaError, IdaPoint,
    Outcome, ScalingIm, Stripe,
};
use rocking_motion::intensity::{pga_over_uplift, IntensityMeasures};
use rocking_motion::{AccelUnit, Record, RecordFormat};
use rocking_scene::knob::KnobValue;
use rocking_scene::scene::{IdaSpec, Source};
use rocking_spectra::plan::Base;
use serde_json::json;

use crate::ida_plot;
use crate::report::{write_atomic, OutDir};
use crate::scene::CliError;

/// The settings of a study, from `[ida]`, checked.
struct Settings {
    im: ScalingIm,
    hunt: HuntFill,
    /// The IM levels of a multiple-stripe analysis (`None`: IDA by hunt-and-fill).
    stripes: Option<Vec<f64>>,
    limit: Option<f64>,
    bootstrap: BootstrapOptions,
}

/// One record of the suite: where it is, what it is, its IMs and its IDA.
struct Done {
    name: String,
    path: String,
    dt: f64,
    npts: usize,
    unit: &'static str,
    ims: IntensityMeasures,
    im_unscaled: f64,
    /// Every analysis of the record, sorted by IM.
    points: Vec<IdaPoint>,
    /// The IDA capacity and the highest survivor below it (`None` for stripes).
    capacity: Option<(f64, f64)>,
}

/// The most IM levels `[ida] stripes` may list.
const MAX_STRIPES: usize = 1000;

fn check(
    src: &Source,
    key: &str,
    ok: bool,
    value: impl std::fmt::Display,
    allowed: &str,
) -> Result<(), CliError> {
    if ok {
        Ok(())
    } else {
        Err(src.err(
            &format!("ida.{key}"),
            format_args!("`{key}` = {value} in [ida] is not allowed: {allowed}"),
        ))
    }
}

fn settings(spec: &IdaSpec, src: &Source) -> Result<Settings, CliError> {
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
    let positive = |key: &str, v: Option<f64>, default: f64| -> Result<f64, CliError> {
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
fn record_files(base: &Base, given: &[PathBuf]) -> Result<Vec<PathBuf>, CliError> {
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
    let files =
        rocking_spectra::plan::expand_records(given, |p| RecordFormat::from_path(p).is_some())?;
    if files.is_empty() {
        return Err(CliError::Input(format!(
            "{}: no records: give --records FILE|DIR or `records = [...]` in [ida]",
            base.path().display()
        )));
    }
    Ok(files)
}

/// Runs one record's IDA, or its stripes.
fn study(base: &Base, s: &Settings, file: &Path) -> Result<Done, CliError> {
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
    let exc = sc.spec.excitation.clone().unwrap_or_default();
    let format = match exc.format.as_deref() {
        Some(f) => RecordFormat::parse(f).unwrap_or(RecordFormat::At2),
        None => RecordFormat::from_path(file).unwrap_or(RecordFormat::At2),
    };
    let mut rec = sc
        .src
        .record_as(Path::new(&path), format, exc.dt)
        .map_err(|e| CliError::Input(e.to_string()))?;
    if let Some(u) = exc.units.as_deref().and_then(AccelUnit::parse) {
        rec = rec
            .with_stated_unit(u)
            .map_err(|e| CliError::Input(e.to_string()))?;
    }
    let unit = rec.declared_unit.map_or("g (not stated)", AccelUnit::name);
    let (dt, npts) = (rec.dt, rec.npts);
    // The record as the structure feels it: 1 g is the structure's g.
    let si = Record::new(dt, rec.samples)
        .map_err(|e| CliError::Input(format!("{path}: {e}")))?
        .with_scale(model.units.g_si);
    let bad = |e: &dyn std::fmt::Display| CliError::Input(format!("{path}: {e}"));
    let ims = IntensityMeasures::of(&si).map_err(|e| bad(&e))?;
    let im_unscaled = s.im.of(&si).map_err(|e| bad(&e))?;
    if !(im_unscaled.is_finite() && im_unscaled > 0.0) {
        return Err(bad(
            &"the record's intensity measure is 0: it cannot be scaled",
        ));
    }
    let knobs = base
        .knobs(&["excitation.path", "excitation.scale"])
        .ok_or_else(|| CliError::Internal("record path and scale are not knobs".into()))?;
    let run_at = |im: f64| -> Result<Outcome, CliError> {
        let cell = [
            (&knobs[0], KnobValue::Text(path.clone())),
            (&knobs[1], KnobValue::Number(im / im_unscaled)),
        ];
        let sum = base.run_knobs(&cell)?;
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
                IdaError::InvalidParameter(m) => CliError::Internal(m),
                budget => CliError::Input(format!(
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
    Ok(Done {
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

fn csv_err(e: csv::Error) -> CliError {
    CliError::Internal(format!("cannot write a table: {e}"))
}

fn records_csv(done: &[Done], alpha: f64, g_si: f64) -> Result<Vec<u8>, CliError> {
    let mut w = csv::Writer::from_writer(Vec::new());
    w.write_record([
        "record",
        "path",
        "units",
        "dt_s",
        "npts",
        "pga_m_s2",
        "pgv_m_s",
        "pgd_m",
        "arias_m_s",
        "d5_95_s",
        "mean_period_s",
        "im_m_s2",
        "pga_over_g_tan_alpha",
        "capacity_im_m_s2",
        "survived_below_im_m_s2",
        "runs",
    ])
    .map_err(csv_err)?;
    for d in done {
        let m = &d.ims;
        let norm = pga_over_uplift(m.pga_m_s2 / g_si * rocking_motion::STANDARD_GRAVITY, alpha)
            .map_err(|e| CliError::Internal(e.to_string()))?;
        let mut row = vec![d.name.clone(), d.path.clone(), d.unit.to_string()];
        row.extend(
            [
                d.dt,
                d.npts as f64,
                m.pga_m_s2,
                m.pgv_m_s,
                m.pgd_m,
                m.arias_m_s,
                m.d5_95_s,
                m.mean_period_s,
                d.im_unscaled,
                norm,
            ]
            .iter()
            .map(|x| x.to_string()),
        );
        // A stripe study has no capacity per record: those fields stay empty.
        let (capacity, below) = d.capacity.map_or((String::new(), String::new()), |(c, b)| {
            (c.to_string(), b.to_string())
        });
        row.extend([capacity, below, d.points.len().to_string()]);
        w.write_record(&row).map_err(csv_err)?;
    }
    w.into_inner()
        .map_err(|e| CliError::Internal(e.to_string()))
}

fn ida_csv(done: &[Done]) -> Result<Vec<u8>, CliError> {
    let mut w = csv::Writer::from_writer(Vec::new());
    w.write_record([
        "record",
        "im_m_s2",
        "scale",
        "collapsed",
        "max_theta_over_alpha",
    ])
    .map_err(csv_err)?;
    for d in done {
        for p in &d.points {
            w.write_record([
                d.name.clone(),
                p.im.to_string(),
                (p.im / d.im_unscaled).to_string(),
                p.outcome.collapsed.to_string(),
                p.outcome.response.to_string(),
            ])
            .map_err(csv_err)?;
        }
    }
    w.into_inner()
        .map_err(|e| CliError::Internal(e.to_string()))
}

/// The intensity measure's axis label, e.g. "Sa(T = 4.5 s, ζ = 5 %) (m/s²)".
fn im_label(im: &ScalingIm) -> String {
    match *im {
        ScalingIm::Pga => "PGA (m/s²)".to_string(),
        ScalingIm::Sa { period, damping } => {
            format!("Sa(T = {period} s, ζ = {} %) (m/s²)", 100.0 * damping)
        }
    }
}

/// `rocking ida`: IDA by hunt-and-fill, or with `[ida] stripes` a multiple-stripe analysis.
pub fn ida(
    scene_path: &Path,
    sets: &[String],
    records: &[PathBuf],
    out: Option<PathBuf>,
    threads: Option<usize>,
) -> Result<(), CliError> {
    let start = Instant::now();
    let base = Base::load(scene_path, sets)?;
    let spec = base.scene().spec.ida.clone().unwrap_or_default();
    let s = settings(&spec, &base.scene().src)?;
    let files = record_files(&base, records)?;
    let model = base.model(&[])?;
    let (alpha, g_si) = (model.units.alpha, model.units.g_si);
    let mut pool = rayon::ThreadPoolBuilder::new();
    if let Some(n) = threads {
        if !(1..=1024).contains(&n) {
            return Err(CliError::Input(format!(
                "--threads {n} is not allowed: 1 <= threads <= 1024"
            )));
        }
        pool = pool.num_threads(n);
    }
    let pool = pool
        .build()
        .map_err(|e| CliError::Internal(format!("cannot start the thread pool: {e}")))?;
    let done: Vec<Done> = pool.install(|| {
        files
            .par_iter()
            .map(|f| study(&base, &s, f))
            .collect::<Result<Vec<_>, _>>()
    })?;
    let runs: usize = done.iter().map(|d| d.points.len()).sum();
    let cannot_fit = |what: String, e: rocking_fragility::FragilityError| {
        CliError::Input(format!(
            "{}: cannot fit a lognormal to {what}: {e}",
            scene_path.display()
        ))
    };
    // The fit, what it was fitted to (for fragility.json) and its empirical points (for the plot).
    let (method, fit, evidence, empirical) = match &s.stripes {
        None => {
            let capacities: Vec<f64> = done
                .iter()
                .filter_map(|d| d.capacity)
                .map(|c| c.0)
                .collect();
            let fit = bootstrap_capacities(&capacities, &s.bootstrap)
                .map_err(|e| cannot_fit(format!("the {} capacities", capacities.len()), e))?;
            let mut sorted = capacities.clone();
            sorted.sort_by(f64::total_cmp);
            let n = sorted.len() as f64;
            let empirical: Vec<(f64, f64)> = sorted
                .iter()
                .enumerate()
                .map(|(i, &c)| (c, (i as f64 + 0.5) / n))
                .collect();
            let evidence = json!({
                "tolerance": s.hunt.tolerance,
                "capacities_m_s2": capacities,
            });
            ("ida", fit, evidence, empirical)
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
            let fit = bootstrap_stripes(&stripes, &s.bootstrap)
                .map_err(|e| cannot_fit(format!("the {} stripes", stripes.len()), e))?;
            let empirical: Vec<(f64, f64)> = stripes
                .iter()
                .map(|st| (st.im, f64::from(st.collapsed) / f64::from(st.n)))
                .collect();
            let evidence = json!({
                "stripes": stripes.iter().map(|st| json!({
                    "im_m_s2": st.im, "records": st.n, "collapsed": st.collapsed,
                })).collect::<Vec<_>>(),
            });
            ("multiple-stripe", fit, evidence, empirical)
        }
    };
    let (im_name, period, damping) = match s.im {
        ScalingIm::Pga => ("pga", None, None),
        ScalingIm::Sa { period, damping } => ("sa", Some(period), Some(damping)),
    };
    let (tl, th) = fit.theta_interval();
    let (bl, bh) = fit.beta_interval();
    let mut json = json!({
        "scene": scene_path.display().to_string(),
        "overrides": sets,
        "method": method,
        "im": { "kind": im_name, "period_s": period, "damping": damping, "unit": "m/s2" },
        "collapse": match s.limit {
            Some(l) => format!("overturned or max theta/alpha >= {l}"),
            None => "overturned".to_string(),
        },
        "records": done.len(),
        "analyses": runs,
        "median_m_s2": fit.estimate.theta,
        "beta": fit.estimate.beta,
        "bootstrap": {
            "resamples": s.bootstrap.resamples,
            "seed": s.bootstrap.seed,
            "level": s.bootstrap.level,
            "failed_resamples": fit.failed,
            "median_interval_m_s2": [tl, th],
            "beta_interval": [bl, bh],
        },
        "elapsed_s": start.elapsed().as_secs_f64(),
    });
    if let (Some(j), Some(e)) = (json.as_object_mut(), evidence.as_object()) {
        j.extend(e.clone());
    }
    let target = out.unwrap_or_else(|| {
        let stem = scene_path
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_else(|| "scene".into());
        Path::new("out").join(format!("{stem}-ida"))
    });
    let dir = OutDir::begin_for(&target, crate::report::IDA_OUT)?;
    write_atomic(
        &dir.path().join("records.csv"),
        &records_csv(&done, alpha, g_si)?,
    )?;
    let table = if s.stripes.is_some() {
        "stripes.csv"
    } else {
        "ida.csv"
    };
    write_atomic(&dir.path().join(table), &ida_csv(&done)?)?;
    let text = serde_json::to_string_pretty(&json)
        .map_err(|e| CliError::Internal(format!("cannot write fragility.json: {e}")))?;
    write_atomic(&dir.path().join("fragility.json"), text.as_bytes())?;
    let curves: Vec<(String, ida_plot::Points)> = done
        .iter()
        .map(|d| {
            let pts = d
                .points
                .iter()
                .map(|p| (p.outcome.response, p.im, p.outcome.collapsed));
            (d.name.clone(), pts.collect())
        })
        .collect();
    let im_label = im_label(&s.im);
    ida_plot::ida_curves(&curves, &im_label, dir.path())?;
    ida_plot::fragility_fit(&empirical, done.len(), &fit, &im_label, dir.path())?;
    dir.commit()?;
    out!(
        "{} records, {runs} analyses ({method}) in {:.2} s: median capacity {:.4} m/s2 ({:.4} g), \
         beta {:.3} (95 % band: median {:.4}..{:.4}, beta {:.3}..{:.3}); outputs in {}",
        done.len(),
        start.elapsed().as_secs_f64(),
        fit.estimate.theta,
        fit.estimate.theta / g_si,
        fit.estimate.beta,
        tl,
        th,
        bl,
        bh,
        target.display()
    );
    Ok(())
}
