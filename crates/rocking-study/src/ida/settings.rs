//! A study's `[ida]` table checked into its [`Settings`]: the intensity measure, hunt-and-fill,
//! stripes, the collapse limit and the bootstrap; a bad value is an input error naming the file,
//! the key and the allowed range.

use rocking_fragility::{BootstrapOptions, HuntFill, ScalingIm};
use rocking_scene::limits::short;
use rocking_scene::scene::{IdaSpec, Source};
use rocking_scene::SceneError;

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

/// Everything a study would refuse in the scene's `[ida]` table, checked without one: `rocking
/// check` refuses what `rocking ida` refuses.
pub fn check_table(base: &Base) -> Result<(), SceneError> {
    match &base.scene().spec.ida {
        Some(spec) => settings(spec, &base.scene().src).map(|_| ()),
        None => Ok(()),
    }
}

/// The most IM levels `[ida] stripes` may list.
const MAX_STRIPES: usize = 1000;

/// The spectral periods `[ida] period` may name (s): Sa(T) is published and used from about
/// 0.01 s, where it is the PGA, to 10-20 s; far outside, it is the PGA or the ground displacement
/// times (2π/T)² (the 1e300 s of a typo gave "intensity measure is 0").
pub const PERIODS: (f64, f64) = (1e-3, 100.0);

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
            let (lo, hi) = PERIODS;
            check(
                src,
                "period",
                (lo..=hi).contains(&period),
                short(period),
                &format!(
                    "a spectral period {} s <= period <= {} s (beyond, Sa is the PGA or the \
                     ground displacement times (2π/T)², not an intensity measure to scale to)",
                    short(lo),
                    short(hi)
                ),
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
    // Sorted, each level once (a repeated level would count its records twice).
    let stripes = spec.stripes.clone().map(|mut v| {
        v.sort_by(f64::total_cmp);
        v.dedup();
        v
    });
    if let Some(levels) = &stripes {
        if let Some(bad) = levels.iter().find(|v| !(v.is_finite() && **v > 0.0)) {
            check(
                src,
                "stripes",
                false,
                format_args!("[..., {bad}, ...]"),
                "IM levels finite and > 0 (m/s^2)",
            )?;
        }
        // A lognormal has two parameters: the counts at one level cannot fix both.
        check(
            src,
            "stripes",
            (2..=MAX_STRIPES).contains(&levels.len()),
            format_args!("a list of {} different levels", levels.len()),
            &format!("2 to {MAX_STRIPES} different IM levels (a median and a β need two)"),
        )?;
    }
    let resamples = spec.bootstrap.unwrap_or(2000);
    let (min, max) = (
        rocking_fragility::bootstrap::MIN_RESAMPLES,
        rocking_fragility::bootstrap::MAX_RESAMPLES,
    );
    check(
        src,
        "bootstrap",
        (min..=max).contains(&resamples),
        resamples,
        &format!(
            "{min} <= bootstrap <= {max} (the band's ends are its 2.5 % and 97.5 % percentiles: \
             fewer resamples move them by chance)"
        ),
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
        stripes,
        limit: spec.theta_over_alpha_limit,
        bootstrap: BootstrapOptions {
            resamples,
            seed: spec.seed.unwrap_or(14),
            level: 0.95,
        },
    })
}
