//! `rocking`: run and check scene files of the rocking-cantilever simulator.
//!
//! ```text
//! rocking run SCENE [--set key.path=value ...] [--out DIR] [--json] [--animate]
//! rocking check SCENE [--set key.path=value ...] [--json]
//! rocking spectrum SCENE [--axis key.path=start:stop:count ...] [--set ...] [--out DIR] [--quiet]
//! rocking batch SCENE [--records FILE|DIR ...] [--scales 0.5,1,2] [--axis key.path=v1,v2,...] [--set ...] [--out DIR] [--quiet]
//! rocking spectrum|batch ... --shard K/N --out SHARD_DIR    (one shard of a job array)
//! rocking merge OUT SHARD_DIR...
//! rocking ida SCENE [--records FILE|DIR ...] [--set ...] [--out DIR] [--threads N]
//! rocking figure FIGURE.toml... [--out DIR] [--cells N] [--cache DIR] [--draft] [--quiet]
//! ```
//!
//! Exit codes: 0 ok, 2 invalid input (scene, record, arguments), 1 internal failure.
//! The scene format is described in `scenes/README.md`.
//!
//! It owns the command line, output directories and plots; it must not hold physics, scene
//! semantics or study logic (the library crates do, so Python and the tests share them).

/// `println!` that returns an error from the enclosing function instead of panicking when
/// standard output is closed (`| true`, EPIPE) or full (`> /dev/full`).
macro_rules! out {
    ($($arg:tt)*) => {{
        use std::io::Write as _;
        writeln!(std::io::stdout(), $($arg)*).map_err($crate::stdout_error)?
    }};
}

mod check;
mod convergence;
mod error;
mod figure;
mod ida;
mod merge;
mod out_dir;
mod shard;
mod sweep;

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::{Parser, Subcommand};
use rocking_scene::{models, scene, setup};
use rocking_study::report;

use error::CliError;
use rocking_plot::figure as plot;
use rocking_scene::setup::Setup;

/// Shown by `--help`: what each accuracy preset costs (`rocking::Preset::measured`).
fn presets_help() -> String {
    format!(
        "Accuracy presets ([solver] accuracy in a scene; measured by `cargo xtask bench`, \
         docs/accuracy.md):\n{}Each is the cheapest configuration whose error, the worse of max \
         θ/α and impact times over the study's standard cases, meets its target (`reference` among DOP853 \
         only: the independent check of the others); times: geometric means per simulation over \
         its nine standard cases, one thread.\nOn long records with hundreds of impacts \
         errors grow about 1e4 times larger (scenes/many-impacts.toml, the study's \
         `many-impacts` case: `default` 1.8e-4, `accurate` 3.2e-7, `reference` 2.3e-7; the \
         tight runs of the two methods differ by 2e-7 there, the answer is determined only that \
         finely): run such records at `accurate` (docs/accuracy.md, \"Each case at each \
         preset\").\nAn explicit method (\"dopri5\", \"dop853\" or \"taylor\") and \
         tol are allowed too.",
        rocking::Preset::table()
    )
}

/// Simulator of a deformable cantilever that uplifts and rocks on a rigid surface
/// (Vassiliou, Mackie & Stojadinović 2015).
#[derive(Parser, Debug)]
#[command(name = "rocking", version, about, after_help = presets_help())]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Run a scene: write summary.json (and history.csv, events.csv, plots when asked) into DIR.
    #[command(after_help = presets_help())]
    Run {
        /// The scene file (TOML).
        scene: PathBuf,
        /// Override a scene value, e.g. `--set excitation.amplitude=1.5` (repeatable).
        #[arg(long = "set", value_name = "KEY.PATH=VALUE")]
        set: Vec<String>,
        /// Output directory (default: out/<scene-stem>/).
        #[arg(long, value_name = "DIR")]
        out: Option<PathBuf>,
        /// Print the summary on stdout as one JSON object.
        #[arg(long)]
        json: bool,
        /// Also write animation.gif: the structure rocking, as `[output] animation = true`
        /// (150 frames of 480 × 600 pixels unless the scene sets animation_frames/_width/_height).
        #[arg(long)]
        animate: bool,
    },
    /// List every model (from the derivation): variants, parameters and effect switches.
    Models {
        /// Print the list as one JSON object.
        #[arg(long)]
        json: bool,
    },
    /// Validate a scene and print the kernel variant, why, and the derived quantities.
    Check {
        /// The scene file (TOML).
        scene: PathBuf,
        /// Override a scene value (repeatable).
        #[arg(long = "set", value_name = "KEY.PATH=VALUE")]
        set: Vec<String>,
        /// Print the result as one JSON object.
        #[arg(long)]
        json: bool,
    },
    /// Sweep a scene over axes of scene values (default: the paper's ω_p/p × a_p/(g tan α)),
    /// in parallel; writes cells.csv, meta.json and the spectrum plot. An interrupted sweep
    /// resumes when run again with the same output directory.
    Spectrum {
        /// The scene file (TOML).
        scene: PathBuf,
        /// An axis `key.path=start:stop:count` or `key.path=v1,v2,...` (repeatable; the last
        /// varies fastest; three axes draw one overturning boundary per value of the first).
        #[arg(long = "axis", value_name = "KEY.PATH=START:STOP:COUNT")]
        axes: Vec<String>,
        /// Override a scene value (repeatable).
        #[arg(long = "set", value_name = "KEY.PATH=VALUE")]
        set: Vec<String>,
        /// Output directory (default: out/<scene-stem>-spectrum/).
        #[arg(long, value_name = "DIR")]
        out: Option<PathBuf>,
        /// No progress bar.
        #[arg(long)]
        quiet: bool,
        /// Number of threads (default: all cores).
        #[arg(long)]
        threads: Option<usize>,
        /// Run only shard K of N (cells whose index is K modulo N, 0 <= K < N) into --out, for
        /// `rocking merge`.
        #[arg(long, value_name = "K/N", value_parser = shard::parse_flag)]
        shard: Option<rocking_spectra::Shard>,
    },
    /// Run a record scene for every record and scale factor (and every cell of the --axis
    /// axes): per run the summary, per scale (and axis cell) the fraction that overturned
    /// (fragility-style curve).
    Batch {
        /// The scene file (TOML), with `kind = "record"` in [excitation].
        scene: PathBuf,
        /// Record files, or folders of them (.AT2, ESM .ASC, K-NET; default: `records` in [sweep]).
        #[arg(long = "records", value_name = "FILE|DIR", num_args = 1..)]
        records: Vec<PathBuf>,
        /// Scale factors, comma separated (default: `scales` in [sweep], or 1).
        #[arg(long, value_delimiter = ',')]
        scales: Vec<f64>,
        /// An axis of the batch's own, as spectrum's: `key.path=v1,v2,...` (numbers or texts,
        /// e.g. `structure.model=cubic,cantilever_modes2`) or `key.path=start:stop:count`
        /// (repeatable; runs records x scales x the axes' cells, at most 1e6; one column per axis
        /// in runs.csv and fragility.csv).
        #[arg(long = "axis", value_name = "KEY.PATH=V1,V2,...")]
        axes: Vec<String>,
        /// Override a scene value (repeatable).
        #[arg(long = "set", value_name = "KEY.PATH=VALUE")]
        set: Vec<String>,
        /// Output directory (default: out/<scene-stem>-batch/).
        #[arg(long, value_name = "DIR")]
        out: Option<PathBuf>,
        /// No progress bar.
        #[arg(long)]
        quiet: bool,
        /// Number of threads (default: all cores).
        #[arg(long)]
        threads: Option<usize>,
        /// Run only shard K of N (cells whose index is K modulo N, 0 <= K < N) into --out, for
        /// `rocking merge`.
        #[arg(long, value_name = "K/N", value_parser = shard::parse_flag)]
        shard: Option<rocking_spectra::Shard>,
    },
    /// Join the shards of a spectrum or batch (`--shard K/N`) into OUT: the same cells.csv
    /// (runs.csv), meta.json and plots as one unsharded run. Exit 2 when a shard is of another
    /// study, given twice, missing or lacks cells (they are listed); 1 when cells failed.
    Merge {
        /// Output directory (written whole, atomically).
        out: PathBuf,
        /// The shards' --out directories, all N of them.
        #[arg(required = true, num_args = 1..)]
        shards: Vec<PathBuf>,
    },
    /// Draw figures from figure files (scenes/paper/: the paper's Figs 3-10): runs and sweeps
    /// of scenes as panels (quantities against τ overlaid, spectra on one colour scale,
    /// overturning boundaries), at the printed width the file states, written as SVG, PNG and
    /// PDF named after each file, with its caption beside them (NAME.caption.md).
    Figure {
        /// The figure files (TOML).
        #[arg(required = true, num_args = 1..)]
        files: Vec<PathBuf>,
        /// Output directory (default: out/figures/).
        #[arg(long, value_name = "DIR")]
        out: Option<PathBuf>,
        /// At most N cells per ranged sweep axis (a quick draft, or CI).
        #[arg(long, value_name = "N", value_parser = clap::value_parser!(u16).range(2..))]
        cells: Option<u16>,
        /// Where sweeps are journaled and reused (default: out/figure-cache/).
        #[arg(long, value_name = "DIR")]
        cache: Option<PathBuf>,
        /// Keep the title and caption inside the image (for screens), no caption file.
        #[arg(long)]
        draft: bool,
        /// No progress bar.
        #[arg(long)]
        quiet: bool,
    },
    /// How a scene's results converge with the number of deformation coordinates: the scene
    /// run with each model of --models, in order (e.g. cubic,cantilever_modes2,cantilever_modes3),
    /// and per quantity its value per model and the first model from which it changes by less
    /// than --tolerance. Writes convergence.csv and convergence.json, prints the table.
    Convergence {
        /// The scene file (TOML).
        scene: PathBuf,
        /// The models to compare, comma separated, in order (`rocking models` lists them).
        #[arg(long, value_delimiter = ',', required = true)]
        models: Vec<String>,
        /// Summary quantities, comma separated (default: max θ/α, impacts, max u/u_cr and the
        /// base moment, shear and elastic moment).
        #[arg(long, value_delimiter = ',')]
        quantities: Vec<String>,
        /// Relative change below which a quantity counts as converged.
        #[arg(long, default_value_t = rocking_study::convergence::DEFAULT_TOLERANCE)]
        tolerance: f64,
        /// Override a scene value (repeatable).
        #[arg(long = "set", value_name = "KEY.PATH=VALUE")]
        set: Vec<String>,
        /// Output directory (default: out/<scene-stem>-convergence/).
        #[arg(long, value_name = "DIR")]
        out: Option<PathBuf>,
        /// Number of threads (default: all cores).
        #[arg(long)]
        threads: Option<usize>,
    },
    /// Incremental dynamic analysis of a record scene (settings in [ida]): per record its
    /// intensity measures and its overturning capacity by hunt-and-fill; the lognormal fragility
    /// fitted by maximum likelihood with a bootstrap band. Writes records.csv, ida.csv,
    /// fragility.json and plots (docs/records.md).
    Ida {
        /// The scene file (TOML), with `kind = "record"` in [excitation].
        scene: PathBuf,
        /// Record files, or folders of them (.AT2, ESM .ASC, K-NET; default: `records` in [ida], else
        /// in [sweep]).
        #[arg(long = "records", value_name = "FILE|DIR", num_args = 1..)]
        records: Vec<PathBuf>,
        /// Override a scene value (repeatable).
        #[arg(long = "set", value_name = "KEY.PATH=VALUE")]
        set: Vec<String>,
        /// Output directory (default: out/<scene-stem>-ida/).
        #[arg(long, value_name = "DIR")]
        out: Option<PathBuf>,
        /// Number of threads (default: all cores).
        #[arg(long)]
        threads: Option<usize>,
    },
}

fn load(scene: &Path, set: &[String]) -> Result<(scene::Scene, Setup), CliError> {
    let sc = scene::load(scene, set)?;
    check_title(&sc)?;
    let model = setup::build(&sc)?;
    Ok((sc, model))
}

/// A scene's `title` is drawn on its plots (SVG, which holds no control character): one is
/// refused before the run, not after it when the plots are drawn.
pub(crate) fn check_title(sc: &scene::Scene) -> Result<(), CliError> {
    match sc.spec.title.as_deref().and_then(plot::control_char) {
        Some(c) => Err(sc
            .src
            .err(
                "title",
                format_args!(
                    "`title` holds the control character {c:?}, which a plot cannot show: \
                 printable text only"
                ),
            )
            .into()),
        None => Ok(()),
    }
}

/// A study's scene ([`rocking_study::plan::Base::load`]) with its title checked.
pub(crate) fn load_base(
    scene: &Path,
    set: &[String],
) -> Result<rocking_study::plan::Base, CliError> {
    let base = rocking_study::plan::Base::load(scene, set)?;
    check_title(base.scene())?;
    Ok(base)
}

/// `rocking models`: the generated registry, as text or JSON.
fn models_command(json: bool) -> Result<(), CliError> {
    if json {
        out!("{}", models::json());
    } else {
        out!("{}", models::text().trim_end());
    }
    Ok(())
}

fn run(scene: &Path, set: &[String], out: Option<PathBuf>, json: bool) -> Result<(), CliError> {
    let (_, mut m) = load(scene, set)?;
    let events_csv = m.options.event_log;
    if m.plots {
        m.options.event_log = true; // impacts are marked on the plots
    }
    let dir = out.unwrap_or_else(|| {
        let stem = scene
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_else(|| "scene".into());
        Path::new("out").join(stem)
    });
    // Everything is written into a staging directory that replaces `dir` whole at the end; an
    // --out that cannot be replaced is refused before the run.
    let out_dir = out_dir::OutDir::begin(&dir, out_dir::RUN_OUT)?;
    let report = report::simulate(&m, scene)?;
    let summary = report::summary_json(&m, scene, set, &report)?;
    let warnings = report::warnings(&m, &report.run.summary);
    let run = report.run;
    let history = if m.history_csv {
        Some(report::history_csv(&m, &run)?)
    } else {
        None
    };
    let events = if events_csv {
        Some(report::events_csv(&m, &run)?)
    } else {
        None
    };
    let stage = out_dir.path().to_path_buf();
    let mut written = Vec::new();
    let text = serde_json::to_string_pretty(&summary).map_err(|source| CliError::Json {
        name: "summary.json",
        source,
    })?;
    let write = |name: &str, bytes: &[u8]| {
        let path = stage.join(name);
        std::fs::write(&path, bytes)
            .map_err(|e| CliError::io("write", dir.join(name), e))
            .map(|()| path)
    };
    written.push(write("summary.json", (text + "\n").as_bytes())?);
    if let Some(h) = history {
        written.push(write("history.csv", h.as_bytes())?);
    }
    if let Some(e) = events {
        written.push(write("events.csv", e.as_bytes())?);
    }
    if m.plots {
        written.extend(plot::plots(&m, &run, &stage)?);
    }
    let mut animation_note = None;
    if let Some(spec) = &m.animation {
        let path = stage.join("animation.gif");
        let (gif, frames) =
            rocking_plot::animation::render(&m, &run, spec).map_err(|e| CliError::Animation {
                path: path.clone(),
                detail: e.to_string(),
            })?;
        out_dir::write_atomic(&path, &gif)?;
        let bytes = gif.len();
        animation_note = Some(format!(
            "  animation: {frames} frames of {} × {} pixels, {:.2} MB",
            spec.width,
            spec.height,
            bytes as f64 / 1e6
        ));
        written.push(path);
    }
    let written: Vec<PathBuf> = written.iter().map(|p| out_dir.final_path(p)).collect();
    out_dir.commit()?;
    for w in warnings {
        eprintln!("warning: {}: {w}", scene.display());
    }
    if json {
        out!("{summary}");
        return Ok(());
    }
    let s = &run.summary;
    let t = |x: Option<rocking::Time>| match x {
        Some(t) => match t.seconds {
            Some(sec) => format!("τ = {:.4} ({sec:.4} s)", t.tau),
            None => format!("τ = {:.4}", t.tau),
        },
        None => "never".into(),
    };
    out!("{}: kernel variant {}", scene.display(), s.kernel_variant);
    if let Some(note) = animation_note {
        out!("{note}");
    }
    out!("  excitation: {}", m.excitation_description);
    out!(
        "  max θ/α = {:.4}, max u/u_cr = {:.4}",
        s.max_theta_over_alpha,
        s.max_u_over_ucr
    );
    out!(
        "  impacts: {} ({} significant); first uplift {}; first impact {}",
        s.impacts,
        s.significant_impacts,
        t(s.first_uplift_time),
        t(s.first_impact_time)
    );
    if s.energy_capped_impacts > 0 {
        out!(
            "  {} impacts kept the pre-impact kinetic energy: the impact model would have created \
             energy (branch *-energy-capped in events.csv)",
            s.energy_capped_impacts
        );
    }
    if s.overturned {
        out!("  OVERTURNED at {}", t(s.overturn_time));
    } else {
        out!("  not overturned (final phase {:?})", s.final_phase);
    }
    if let Some(r) = s.energy_balance_residual {
        out!("  energy balance residual: {r:.3e} E_ref");
    }
    out!(
        "  solver: {} steps, {} rejected, {} events",
        s.solver_stats.steps,
        s.solver_stats.rejected_steps,
        s.solver_stats.events
    );
    out!("  wrote:");
    for p in written {
        out!("    {}", p.display());
    }
    Ok(())
}

/// A failed write to standard output.
pub(crate) fn stdout_error(e: std::io::Error) -> CliError {
    CliError::Stdout(e)
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Run {
            scene,
            set,
            out,
            json,
            animate,
        } => {
            // `--animate` is the scene key, set last (so a scene's frame count and size stay).
            let mut set = set;
            if animate {
                set.push("output.animation=true".into());
            }
            run(&scene, &set, out, json)
        }
        Command::Check { scene, set, json } => check::check(&scene, &set, json),
        Command::Models { json } => models_command(json),
        Command::Spectrum {
            scene,
            axes,
            set,
            out,
            quiet,
            threads,
            shard,
        } => sweep::spectrum(&scene, &set, &axes, out, quiet, threads, shard),
        Command::Batch {
            scene,
            records,
            scales,
            axes,
            set,
            out,
            quiet,
            threads,
            shard,
        } => sweep::batch(
            &scene, &set, &records, &scales, &axes, out, quiet, threads, shard,
        ),
        Command::Merge { out, shards } => merge::merge(&out, &shards),
        Command::Figure {
            files,
            out,
            cells,
            cache,
            draft,
            quiet,
        } => figure::figure(
            &files,
            &figure::Options {
                draft,
                out: out.unwrap_or_else(|| PathBuf::from("out/figures")),
                cache: cache.unwrap_or_else(|| PathBuf::from("out/figure-cache")),
                cells: cells.map(usize::from),
                quiet,
            },
        ),
        Command::Ida {
            scene,
            records,
            set,
            out,
            threads,
        } => ida::ida(&scene, &set, &records, out, threads),
        Command::Convergence {
            scene,
            models,
            quantities,
            tolerance,
            set,
            out,
            threads,
        } => convergence::convergence(convergence::Args {
            scene: &scene,
            sets: &set,
            models: &models,
            quantities: &quantities,
            tolerance,
            out,
            threads,
        }),
    };
    // Buffered output reaches a closed or full stdout only here.
    let result = result.and_then(|()| {
        use std::io::Write as _;
        std::io::stdout().flush().map_err(stdout_error)
    });
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::from(e.exit_code())
        }
    }
}
