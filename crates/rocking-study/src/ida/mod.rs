//! A record-suite fragility study from a scene's `[ida]` table, for the command (`rocking ida`)
//! and the Python package alike: per record its intensity measures (once), then either its
//! overturning capacity in the chosen IM by hunt-and-fill with its IDA curve, or with
//! `stripes` its outcome at each IM level; over the suite the lognormal fragility fitted by
//! maximum likelihood (to the capacities, or to the counts per stripe: Baker 2015) with a
//! bootstrap band. Runs in the caller's rayon pool, one record per task.

use std::path::{Path, PathBuf};

use rayon::prelude::*;
use rocking_fragility::{
    bootstrap_capacities, bootstrap_stripes, Bootstrap, IdaError, IdaPoint, Outcome, ScalingIm,
    Stripe,
};
use rocking_motion::intensity::{pga_over_uplift, IntensityMeasures};
use rocking_motion::AccelUnit;
use rocking_scene::knob::KnobValue;
use rocking_scene::limits::{short, MAX_ACCEL_G};
use rocking_scene::scene::ExcitationSpec;
use rocking_scene::SceneError;

use serde_json::json;

use crate::plan::Base;

mod settings;
mod tables;
use crate::{Invariant, StudyError};
pub use settings::{check_table, settings, Settings, PERIODS};

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
    /// Its PGA over the structure's uplift acceleration g tan α.
    pub pga_over_g_tan_alpha: f64,
    /// Every analysis of the record, sorted by IM.
    pub points: Vec<IdaPoint>,
    /// The IDA capacity and the highest survivor below it (`None` for stripes).
    pub capacity: Option<(f64, f64)>,
    /// Per analysis (in the order of `points`), the values of `[sweep] report`.
    pub reported: Vec<Vec<Option<f64>>>,
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
    /// The maximum-likelihood fit and its bootstrap band, or why there is none (e.g. every
    /// capacity the same: no spread to fit a β to); the analyses stand either way.
    pub fit: Result<Bootstrap, String>,
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

    /// Why the band may not mean what its level says: it rests on fewer than
    /// [`MIN_BAND_RECORDS`](rocking_fragility::bootstrap::MIN_BAND_RECORDS) capacities (IDA) or
    /// records per stripe, with which a 95 % band covers the truth far less often (a point with
    /// two).
    pub fn band_warning(&self) -> Option<String> {
        self.fit.as_ref().ok()?;
        let min = rocking_fragility::bootstrap::MIN_BAND_RECORDS;
        let (n, what) = match &self.evidence {
            Evidence::Capacities(c) => (c.len(), "capacities"),
            Evidence::Stripes(_) => (self.records.len(), "records per stripe"),
        };
        (n < min).then(|| {
            format!(
                "the {} % band rests on {n} {what}: with fewer than {min} it covers the median and \
                 β less often than it says (measured: never with 2, about 2 times in 3 with 3, \
                 80-90 % of the time with 4 to 8); use it as a rough guide only",
                100.0 * self.settings.bootstrap.level
            )
        })
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
        let mut v = json!({
            "method": self.method(),
            "im": { "kind": im_name, "period_s": period, "damping": damping, "unit": "m/s2" },
            "collapse": match s.limit {
                Some(l) => format!("overturned or max theta/alpha >= {l}"),
                None => "overturned".to_string(),
            },
            "records": self.records.len(),
            "analyses": self.analyses(),
        });
        // Without a fit its fields are absent (never null) and `no_fit` says why.
        match &self.fit {
            Ok(fit) => {
                let (tl, th) = fit.theta_interval();
                let (bl, bh) = fit.beta_interval();
                v["median_m_s2"] = json!(fit.estimate.theta);
                v["beta"] = json!(fit.estimate.beta);
                v["bootstrap"] = json!({
                    "resamples": s.bootstrap.resamples,
                    "seed": s.bootstrap.seed,
                    "level": s.bootstrap.level,
                    "failed_resamples": fit.failed,
                    "median_interval_m_s2": [tl, th],
                    "beta_interval": [bl, bh],
                });
                if let Some(w) = self.band_warning() {
                    v["bootstrap"]["warning"] = json!(w);
                }
            }
            Err(why) => v["no_fit"] = json!(why),
        }
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
/// current rayon pool: [`plan`], then [`Planned::run`]; a study without a fit is an error here
/// (for callers that need the fit, as the Python package does; `rocking ida` writes it anyway).
pub fn run(base: &Base, records: &[PathBuf]) -> Result<Study, StudyError> {
    let study = plan(base, records)?.run()?;
    if let Err(why) = &study.fit {
        return Err(SceneError::input(format!("{}: {why}", base.path().display())).into());
    }
    Ok(study)
}

/// A study checked before its first analysis: the scene, the settings, and every record read
/// with its intensity measures.
pub struct Planned<'a> {
    base: &'a Base,
    settings: Settings,
    records: Vec<Prepared>,
}

/// One record read, before its analyses.
struct Prepared {
    file: PathBuf,
    path: String,
    dt: f64,
    npts: usize,
    unit: &'static str,
    ims: IntensityMeasures,
    im_unscaled: f64,
    pga_over_g_tan_alpha: f64,
    /// The highest IM the record may be scaled to: where its PGA reaches the most a scene
    /// allows ([`MAX_ACCEL_G`] in the structure's g).
    im_max: f64,
}

/// A computed number for a message, to 5 significant digits (`1019716.2129779282` reads
/// `1019700`).
fn derived(v: f64) -> String {
    short(format!("{v:.4e}").parse().unwrap_or(v))
}

/// Plans the study of the scene `base` over `records` (else the scene's): everything a bad input
/// can be found in without an analysis is checked here (a scene that is not a record scene, the
/// `[ida]` settings, the record files, each record's intensity measures, stripe levels a record
/// cannot be scaled to), so that a command refuses it before writing or running anything. Reads
/// the records in the current rayon pool.
pub fn plan<'a>(base: &'a Base, records: &[PathBuf]) -> Result<Planned<'a>, StudyError> {
    let sc = base.scene();
    let kind = sc
        .spec
        .excitation
        .as_ref()
        .and_then(|e| e.kind.as_deref())
        .unwrap_or("none");
    if kind != "record" {
        return Err(sc
            .src
            .err(
                "excitation.kind",
                format_args!(
                    "`kind` = \"{kind}\" in [excitation]: a record-suite study scales records, so \
                 the scene needs kind = \"record\" (with a `path`, which each record of the study \
                 replaces)"
                ),
            )
            .into());
    }
    let spec = sc.spec.ida.clone().unwrap_or_default();
    let settings = settings(&spec, &sc.src)?;
    let files = record_files(base, records)?;
    let records: Vec<Prepared> = files
        .par_iter()
        .map(|f| prepare(base, &settings, f))
        .collect::<Result<_, _>>()?;
    if let Some(levels) = &settings.stripes {
        let top = levels.last().copied().unwrap_or(0.0);
        if let Some(r) = records.iter().find(|r| r.im_max < top) {
            return Err(sc
                .src
                .err(
                    "ida.stripes",
                    format_args!(
                    "`stripes` in [ida] reaches {} = {} m/s², which needs {} scaled by {}: a PGA \
                     of {} g; at most {} g, that is {} = {} m/s² for this record: lower the \
                     highest level",
                    settings.im.name(),
                    short(top),
                    r.path,
                    derived(top / r.im_unscaled),
                    derived(top / r.im_max * MAX_ACCEL_G),
                    short(MAX_ACCEL_G),
                    settings.im.name(),
                    derived(r.im_max)
                ),
                )
                .into());
        }
    }
    Ok(Planned {
        base,
        settings,
        records,
    })
}

impl Planned<'_> {
    /// The settings.
    pub fn settings(&self) -> &Settings {
        &self.settings
    }

    /// The number of records.
    pub fn records(&self) -> usize {
        self.records.len()
    }

    /// Runs every record's analyses (one record per task of the current rayon pool) and fits.
    pub fn run(self) -> Result<Study, StudyError> {
        let Planned {
            base,
            settings,
            records,
        } = self;
        let done: Vec<RecordStudy> = records
            .into_par_iter()
            .map(|r| study(base, &settings, r))
            .collect::<Result<Vec<_>, _>>()?;
        let cannot_fit = |what: String, e: rocking_fragility::FragilityError| {
            format!("no lognormal fitted to {what}: {e}")
        };
        let (fit, evidence) = match &settings.stripes {
            None => {
                let capacities: Vec<f64> = done
                    .iter()
                    .filter_map(|d| d.capacity)
                    .map(|c| c.0)
                    .collect();
                let fit = bootstrap_capacities(&capacities, &settings.bootstrap)
                    .map_err(|e| cannot_fit(format!("the {} capacities", capacities.len()), e));
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
                    .map_err(|e| cannot_fit(format!("the {} stripes", stripes.len()), e));
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
}

/// The record files: the arguments, else `[ida] records`, else `[sweep] records`; a folder
/// stands for its files of a known record format, sorted.
pub fn record_files(base: &Base, given: &[PathBuf]) -> Result<Vec<PathBuf>, StudyError> {
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
        return Err(StudyError::NoRecords {
            scene: base.path().to_path_buf(),
            table: "ida",
        });
    }
    Ok(files)
}

/// Reads one record as the study scales it: its intensity measures as the structure feels it,
/// the scaling IM at scale 1 and the highest IM a scene allows.
fn prepare(base: &Base, s: &Settings, file: &Path) -> Result<Prepared, SceneError> {
    let path = std::fs::canonicalize(file)
        .unwrap_or_else(|_| file.to_path_buf())
        .display()
        .to_string();
    // Validates the record against the scene (format, units, length), as `run` would.
    let injected = [
        format!("excitation.path={path:?}"),
        "excitation.scale=1.0".to_string(),
    ];
    let model = base
        .model(&injected)
        .map_err(|e| on_the_record(e, &injected, &path))?;
    let sc = base.scene();
    let exc = ExcitationSpec {
        path: Some(path.clone()),
        ..sc.spec.excitation.clone().unwrap_or_default()
    };
    let rec = rocking_scene::excitation::scene_record(&sc.src, &exc)?;
    let unit = rec.declared_unit.map_or("g (not stated)", AccelUnit::name);
    let (dt, npts) = (rec.dt, rec.npts);
    // The record as the structure feels it (the units model of `AccelUnit`), in m/s².
    let g_si = model.units.g_si;
    let si = rec.to_record_si(g_si);
    let bad = |e: &dyn std::fmt::Display| SceneError::input(format!("{path}: {e}"));
    let ims = IntensityMeasures::of(&si).map_err(|e| bad(&e))?;
    let im_unscaled = s.im.of(&si).map_err(|e| bad(&e))?;
    if !(im_unscaled.is_finite() && im_unscaled > 0.0) {
        return Err(bad(&format_args!(
            "its {} at scale 1 is {}: a record without motion there cannot be scaled to a level",
            s.im.name(),
            derived(im_unscaled)
        )));
    }
    let pga_over_g_tan_alpha = pga_over_uplift(
        ims.pga_m_s2 / g_si * rocking_motion::STANDARD_GRAVITY,
        model.units.alpha,
    )
    .map_err(|e| bad(&e))?;
    Ok(Prepared {
        file: file.to_path_buf(),
        path,
        dt,
        npts,
        unit,
        im_max: im_unscaled * MAX_ACCEL_G * g_si / ims.pga_m_s2,
        pga_over_g_tan_alpha,
        ims,
        im_unscaled,
    })
}

/// An error about a value the study set (a record's path or scale), as the user reads it: about
/// the record, not about an override the user never gave.
fn on_the_record(mut e: SceneError, injected: &[String], record: &str) -> SceneError {
    let input = e.fields_mut();
    if input.set.take_if(|a| injected.contains(a)).is_some() {
        input.file = None;
        input.context.push(format!("record {record} of the study"));
    }
    e
}

/// Runs one record's IDA, or its stripes.
fn study(base: &Base, s: &Settings, r: Prepared) -> Result<RecordStudy, StudyError> {
    let path = r.path.clone();
    let knobs = base
        .knobs(&["excitation.path", "excitation.scale"])
        .ok_or(StudyError::Internal(Invariant::RecordKnobs))?;
    let im_name = s.im.name();
    // The reported quantities of each analysis, by IM level, matched to the points after.
    let reported = std::cell::RefCell::new(Vec::new());
    let run_at = |im: f64| -> Result<Outcome, StudyError> {
        let scale = im / r.im_unscaled;
        if im > r.im_max {
            // Only a hunt gets here (stripes are checked when planned): the structure stood
            // at every level up to the strongest a scene allows.
            let hint = match s.im {
                ScalingIm::Sa { period, .. } => format!(
                    " (its {im_name} at scale 1 is {} m/s²: is `period` = {} s in [ida] the \
                     structure's?)",
                    derived(r.im_unscaled),
                    short(period)
                ),
                ScalingIm::Pga => String::new(),
            };
            return Err(base
                .scene()
                .src
                .err(
                    "ida",
                    format_args!(
                    "record {path}: the hunt for its capacity reached {im_name} = {} m/s², which \
                     needs a scale factor of {}, a PGA of {} g; at most {} g: the structure \
                     stands up to the strongest version of this record a scene allows{hint}",
                    short(im),
                    derived(scale),
                    derived(im / r.im_max * MAX_ACCEL_G),
                    short(MAX_ACCEL_G)
                ),
                )
                .into());
        }
        let cell = [
            (&knobs[0], KnobValue::Text(path.clone())),
            (&knobs[1], KnobValue::Number(scale)),
        ];
        let run = base.run_knobs(&cell).map_err(|e| {
            e.context(format_args!(
                "record {path}, the analysis at {im_name} = {} m/s² (scale {})",
                short(im),
                derived(scale)
            ))
        })?;
        reported.borrow_mut().push((im, run.reported));
        let sum = run.summary;
        let resp = sum.max_theta_over_alpha;
        Ok(Outcome {
            collapsed: sum.overturned || s.limit.is_some_and(|l| resp >= l),
            response: resp,
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
                budget @ IdaError::RunBudget { .. } => SceneError::input(format!(
                    "{path}: {budget}; raise `max_runs` in [ida] (1 <= max_runs <= 10000) or `step`"
                ))
                .into(),
                // `settings` checked what the hunt checks.
                _ => StudyError::Internal(Invariant::HuntSettings),
            })?;
            (ida.points, Some((ida.capacity, ida.survived_below)))
        }
    };
    let reported = reported.into_inner();
    let reported = points
        .iter()
        .map(|p| {
            reported
                .iter()
                .find(|(im, _)| *im == p.im)
                .map(|(_, v)| v.clone())
                .unwrap_or_default()
        })
        .collect();
    let name = r
        .file
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    Ok(RecordStudy {
        name,
        path,
        dt: r.dt,
        npts: r.npts,
        unit: r.unit,
        ims: r.ims,
        im_unscaled: r.im_unscaled,
        pga_over_g_tan_alpha: r.pga_over_g_tan_alpha,
        points,
        capacity,
        reported,
    })
}
