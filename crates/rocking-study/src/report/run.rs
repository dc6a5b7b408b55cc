//! Running a built scene as every study does: the one dispatch to the rigid surface or the
//! compliant ground, the fixed-base twin when asked for, and the errors worded for the scene.

use std::path::Path;

use rocking::{Run, Summary};
use rocking_scene::setup::Setup;
use rocking_scene::SceneError;

use crate::StudyError;

/// A run and, when the scene asks for it (`[output] fixed_base_reference`), the summary of its
/// fixed-base twin: the same structure under the same excitation, held in full contact.
pub struct Report {
    /// The run.
    pub run: Run,
    /// The fixed-base twin's summary.
    pub fixed_base: Option<Summary>,
}

/// Runs a built scene (and its fixed-base twin when asked for) with the command's error
/// messages: bad options are input errors, a guard that stops a run names the scene settings
/// that bound it.
pub fn simulate(m: &Setup, scene: &Path) -> Result<Report, StudyError> {
    let run = simulate_with(m, &m.options, scene)?;
    let fixed_base = if m.fixed_base_reference {
        let twin = rocking::Options {
            history: rocking::History::None,
            event_log: false,
            ..m.options.fixed_base_twin()
        };
        Some(simulate_with(m, &twin, scene)?.summary)
    } else {
        None
    };
    Ok(Report { run, fixed_base })
}

/// Runs a built scene with `options`: its variant (selected once, when the scene was built) on
/// its compliant ground when it has one, else on the rigid surface ([`rocking::run_selected`]).
/// The one dispatch of every run: `rocking run`, a sweep's cell, an IDA analysis, Python.
pub fn run_setup(m: &Setup, options: &rocking::Options) -> Result<Run, rocking::SimError> {
    rocking::run_selected(
        m.variant,
        &m.structure,
        m.ground.as_ref(),
        &m.excitation,
        options,
    )
}

fn simulate_with(m: &Setup, options: &rocking::Options, scene: &Path) -> Result<Run, StudyError> {
    run_setup(m, options).map_err(|e| {
        if e.is_invalid_input() {
            SceneError::input(format!("{}: {e}", scene.display())).into()
        } else {
            StudyError::Simulation {
                scene: scene.to_path_buf(),
                source: e,
            }
        }
    })
}
