//! `rocking ida`: the record-suite study of `rocking_study::ida` (IDA by hunt-and-fill, or
//! multiple stripes with `[ida] stripes`) written out: records.csv, ida.csv or stripes.csv,
//! fragility.json and the plots. Not resumable: the whole study is rerun (see docs/records.md).

use std::path::{Path, PathBuf};
use std::time::Instant;

use crate::sweep::table_csv;
use rocking_fragility::ScalingIm;
use serde_json::json;

use crate::error::CliError;
use crate::out_dir::{write_atomic, OutDir};
use rocking_plot::figure as plot;
use rocking_scene::SceneError;

/// The intensity measure's axis label, e.g. "Sa(T = 4.5 s, ζ = 5 %) (m/s²)".
fn im_label(im: &ScalingIm) -> String {
    format!("{} (m/s²)", im.name())
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
    let base = crate::load_base(scene_path, sets)?;
    let model = base.model(&[])?;
    let g_si = model.units.g_si;
    let mut pool = rayon::ThreadPoolBuilder::new();
    if let Some(n) = threads {
        if !(1..=1024).contains(&n) {
            return Err(SceneError::input(format!(
                "--threads {n} is not allowed: 1 <= threads <= 1024"
            ))
            .into());
        }
        pool = pool.num_threads(n);
    }
    let pool = pool.build().map_err(CliError::ThreadPool)?;
    let target = out.unwrap_or_else(|| {
        let stem = scene_path
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_else(|| "scene".into());
        Path::new("out").join(format!("{stem}-ida"))
    });
    // Everything that can be refused is, before the first analysis: the scene, the settings and
    // the records (planned), and an --out that could not be replaced (it was refused after the
    // whole study).
    let planned = pool.install(|| rocking_study::ida::plan(&base, records))?;
    let dir = OutDir::begin(&target, crate::out_dir::IDA_OUT)?;
    let st = pool.install(|| planned.run())?;
    let done = &st.records;
    let runs = st.analyses();
    let empirical = st.empirical();
    let mut json = json!({
        "scene": scene_path.display().to_string(),
        "overrides": sets,
    });
    if let (Some(j), serde_json::Value::Object(f)) = (json.as_object_mut(), st.fragility_json()) {
        j.extend(f);
    }
    let method = st.method();
    write_atomic(
        &dir.path().join("records.csv"),
        &table_csv(&st.records_table(), "records.csv")?,
    )?;
    let table = if st.settings.stripes.is_some() {
        "stripes.csv"
    } else {
        "ida.csv"
    };
    write_atomic(
        &dir.path().join(table),
        &table_csv(&st.analyses_table(base.report()), table)?,
    )?;
    let text = serde_json::to_string_pretty(&json).map_err(|source| CliError::Json {
        name: "fragility.json",
        source,
    })?;
    write_atomic(&dir.path().join("fragility.json"), (text + "\n").as_bytes())?;
    // What the study took, apart: fragility.json is a function of the study alone (the same
    // bytes on every run), as a spectrum's meta.json is.
    let timing = json!({
        "seconds": start.elapsed().as_secs_f64(),
        "threads": pool.current_num_threads(),
        "analyses": runs,
    });
    write_atomic(
        &dir.path().join("timing.json"),
        (serde_json::to_string_pretty(&timing).unwrap_or_default() + "\n").as_bytes(),
    )?;
    let curves: Vec<(String, plot::Points)> = done
        .iter()
        .map(|d| {
            let pts = d
                .points
                .iter()
                .map(|p| (p.outcome.response, p.im, p.outcome.collapsed));
            (d.name.clone(), pts.collect())
        })
        .collect();
    let im_label = im_label(&st.settings.im);
    let empirical_label = if st.settings.stripes.is_some() {
        "fraction overturned per stripe"
    } else {
        "a record's capacity at (i + ½)/n"
    };
    plot::ida_plots(
        plot::IdaPanel {
            curves,
            im_label: im_label.clone(),
            stripes: st.settings.stripes.is_some(),
        },
        st.fit.as_ref().ok().map(|fit| plot::FitPanel {
            fit: fit.clone(),
            empirical,
            empirical_label: empirical_label.to_string(),
            im_label,
            unit: "m/s²".to_string(),
        }),
        dir.path(),
    )?;
    dir.commit()?;
    if let Some(w) = st.band_warning() {
        eprintln!("warning: {w}");
    }
    let fit = match &st.fit {
        Ok(fit) => {
            let (tl, th) = fit.theta_interval();
            let (bl, bh) = fit.beta_interval();
            format!(
                "median capacity {:.4} m/s2 ({:.4} g), beta {:.3} (95 % band: median \
                 {tl:.4}..{th:.4}, beta {bl:.3}..{bh:.3})",
                fit.estimate.theta,
                fit.estimate.theta / g_si,
                fit.estimate.beta,
            )
        }
        Err(why) => {
            eprintln!(
                "warning: {}: {why}; the analyses are written, fragility.json has no fit \
                 (`no_fit` says why) and there is no fragility-fit plot",
                scene_path.display()
            );
            "no fragility fitted".to_string()
        }
    };
    out!(
        "{} records, {runs} analyses ({method}) in {:.2} s: {fit}; outputs in {}",
        done.len(),
        start.elapsed().as_secs_f64(),
        target.display()
    );
    Ok(())
}
