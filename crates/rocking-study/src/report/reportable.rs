//! The summary quantities a sweep may report (`[sweep] report`, a convergence study's
//! quantities), declared once with their labels: a static list, not probe runs. The test below
//! checks it against what runs of each kind serialize ([`super::quantities`]), so a new summary
//! field that is a number fails it until it is listed here.

use rocking_scene::labels;
use rocking_scene::setup::Setup;

/// Which runs report a quantity as a number.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Needs {
    /// Every run (the force maxima too: a sweep that reports one tracks the forces).
    Always,
    /// A scene whose time is known in seconds (physical units, or a length scale).
    Seconds,
    /// A scene in physical units (the force maxima in SI).
    Physical,
    /// A run on compliant ground.
    Ground,
    /// A run with the energy bookkeeping (`[effects] energy`).
    Energy,
    /// A run on compliant ground with the energy bookkeeping.
    EnergyOnGround,
}

/// A summary quantity a sweep may report.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Reportable {
    /// Its key in the summary (`a.b`: entry `b` of object `a`).
    pub key: &'static str,
    /// Its label in the paper's notation (the key where it has none).
    pub label: &'static str,
    /// Which runs report it.
    pub needs: Needs,
    /// The fixed-base twin reports it too, as `fixed_base.KEY`.
    pub twin: bool,
    /// A run tracks the section forces for it ([`rocking::Options::forces`]: a force kernel per
    /// step and searches inside steps), which a sweep's cells do only when they report such a
    /// quantity ([`needs_forces`]).
    pub forces: bool,
}

/// Whether a run must track the forces for the reported quantity `key`: a force quantity, or
/// any of the fixed-base twin's (`fixed_base.KEY`, which a run reports only with the forces).
pub fn needs_forces(key: &str) -> bool {
    key.starts_with("fixed_base.") || REPORTABLE.iter().any(|r| r.key == key && r.forces)
}

const fn q(
    key: &'static str,
    label: &'static str,
    needs: Needs,
    twin: bool,
    forces: bool,
) -> Reportable {
    Reportable {
        key,
        label,
        needs,
        twin,
        forces,
    }
}

use Needs::{Always, Energy, EnergyOnGround, Ground, Physical, Seconds};

/// Every summary quantity a sweep may report. The ratios to the fixed-base twin are
/// [`super::RATIOS`]; M_b, V_b the moment and shear at the column base, M_el the elastic moment,
/// R_h and R_v the ground reactions, W the total weight, B the half-width; on compliant ground p
/// the pressure under the base, v its settlement and v₀ the static one.
pub const REPORTABLE: [Reportable; 33] = [
    q(
        "max_theta_over_alpha",
        labels::MAX_THETA_OVER_ALPHA,
        Always,
        false,
        false,
    ),
    q(
        "max_theta_over_theta_cr",
        "max_theta_over_theta_cr",
        Always,
        false,
        false,
    ),
    q("max_u_over_ucr", "max |u|/u_cr", Always, true, false),
    q("impacts", "impacts", Always, false, false),
    q(
        "significant_impacts",
        "significant_impacts",
        Always,
        false,
        false,
    ),
    q(
        "energy_capped_impacts",
        "energy_capped_impacts",
        Always,
        false,
        false,
    ),
    q("end_time", "end_time", Always, false, false),
    q("end_time_s", "end_time_s", Seconds, false, false),
    q(
        "solver_stats.steps",
        "solver_stats.steps",
        Always,
        false,
        false,
    ),
    q(
        "solver_stats.rejected_steps",
        "solver_stats.rejected_steps",
        Always,
        false,
        false,
    ),
    q(
        "solver_stats.rhs_evaluations",
        "solver_stats.rhs_evaluations",
        Always,
        false,
        false,
    ),
    q(
        "solver_stats.events",
        "solver_stats.events",
        Always,
        false,
        false,
    ),
    q(
        "max_base_moment_over_wb",
        "max |M_b|/(W B)",
        Always,
        true,
        true,
    ),
    q("max_base_shear_over_w", "max |V_b|/W", Always, true, true),
    q(
        "max_elastic_base_moment_over_wb",
        "max |M_el|/(W B)",
        Always,
        true,
        true,
    ),
    q("max_required_friction", "max |R_h|/R_v", Always, true, true),
    q(
        "min_vertical_reaction_over_w",
        "min R_v/W",
        Always,
        true,
        true,
    ),
    q(
        "base_moment_ratio",
        "max |M_b|, rocking / fixed base",
        Always,
        false,
        true,
    ),
    q(
        "base_shear_ratio",
        "max |V_b|, rocking / fixed base",
        Always,
        false,
        true,
    ),
    q(
        "max_base_moment_nm",
        "max |M_b| (N m)",
        Physical,
        true,
        true,
    ),
    q("max_base_shear_n", "max |V_b| (N)", Physical, true, true),
    q(
        "max_ground_pressure_over_mean",
        "max p/(W/2B)",
        Ground,
        true,
        false,
    ),
    q(
        "min_contact_fraction",
        "min contact length/2B",
        Ground,
        true,
        false,
    ),
    q("lift_offs", "edge lift-offs", Ground, true, false),
    q(
        "max_settlement_over_static",
        "max v/v₀",
        Ground,
        true,
        false,
    ),
    q(
        "ground_energy_dissipated",
        "ground dissipation/E_ref",
        Ground,
        true,
        false,
    ),
    q(
        "energy_balance_residual",
        "energy_balance_residual",
        Energy,
        false,
        false,
    ),
    q("energy.initial", "energy.initial", Energy, false, false),
    q("energy.last", "energy.last", Energy, false, false),
    q(
        "energy.ground_work",
        "energy.ground_work",
        Energy,
        false,
        false,
    ),
    q("energy.damping", "energy.damping", Energy, false, false),
    q(
        "energy.impact_losses",
        "energy.impact_losses",
        Energy,
        false,
        false,
    ),
    q(
        "energy.ground_dissipation",
        "energy.ground_dissipation",
        EnergyOnGround,
        false,
        false,
    ),
];

impl Needs {
    /// Whether runs of `model` report what needs this.
    fn met_by(self, model: &Setup) -> bool {
        let (ground, energy) = (model.ground.is_some(), model.options.energy);
        match self {
            Always => true,
            Seconds => model.structure.p_per_second().is_some(),
            Physical => model.units.physical,
            Ground => ground,
            Energy => energy,
            EnergyOnGround => energy && ground,
        }
    }
}

/// The keys a sweep of `model` may report, sorted: the quantities its runs report as numbers,
/// and the fixed-base twin's (`fixed_base.KEY`).
pub fn reportable_keys(model: &Setup) -> Vec<String> {
    let mut keys: Vec<String> = REPORTABLE
        .iter()
        .filter(|r| r.needs.met_by(model))
        .flat_map(|r| {
            let twin = r.twin.then(|| format!("fixed_base.{}", r.key));
            std::iter::once(r.key.to_string()).chain(twin)
        })
        .collect();
    keys.sort();
    keys.dedup();
    keys
}

/// The label of a quantity a run reports (a key of its summary, as a sweep's `report` names
/// it): the paper's notation, or the key.
pub fn quantity_label(key: &str) -> &str {
    REPORTABLE
        .iter()
        .find(|r| r.key == key)
        .map_or(key, |r| r.label)
}

#[cfg(test)]
mod tests {
    use std::path::{Path, PathBuf};

    use rocking::History;
    use rocking_scene::{scene, setup};

    use super::*;
    use crate::report::{number, quantities, run_setup, si_scale, RATIOS};

    /// The numeric keys a run of `m` and its twin serialize: a run that ends at once with the
    /// forces tracked or not (`forces`), as a sweep's cell runs.
    fn serialized_numbers(m: &Setup, forces: bool) -> Vec<String> {
        let probe = rocking::Options {
            t_end: 1e-9,
            forces,
            history: History::None,
            event_log: false,
            ..m.options
        };
        let run = |o: &rocking::Options| run_setup(m, o).expect("the probe runs").summary;
        let twin = run(&probe.fixed_base_twin());
        let q = quantities(&run(&probe), Some(&twin), si_scale(m)).expect("finite quantities");
        let mut keys: Vec<String> = Vec::new();
        for (k, v) in &q {
            match v {
                serde_json::Value::Object(o) => keys.extend(
                    o.iter()
                        .filter(|(_, x)| number(x).is_some())
                        .map(|(j, _)| format!("{k}.{j}")),
                ),
                v if number(v).is_some() => keys.push(k.clone()),
                _ => {}
            }
        }
        if forces {
            keys.extend(RATIOS.iter().map(|r| r.to_string()));
        }
        keys.sort();
        keys.dedup();
        keys
    }

    fn scene_file(rel: &str) -> PathBuf {
        Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../..")
            .join(rel)
    }

    /// Rigid and compliant ground, with and without the energy bookkeeping, dimensionless with
    /// and without seconds, and physical: the static list is what the runs serialize.
    #[test]
    fn the_static_list_is_what_runs_of_every_kind_report() {
        let cases: [(&str, &[&str]); 6] = [
            ("scenes/spectra/fig8.toml", &[]),
            ("scenes/spectra/fig8.toml", &["effects.energy=true"]),
            ("scenes/spectra/fig8-winkler.toml", &[]),
            ("scenes/spectra/fig8-winkler.toml", &["effects.energy=true"]),
            ("scenes/wind-turbine-elcentro.toml", &[]),
            ("scenes/ground-winkler.toml", &["effects.energy=true"]),
        ];
        let mut kinds = std::collections::BTreeSet::new();
        for (file, sets) in cases {
            let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
            let sc = scene::load(&scene_file(file), &sets).expect("the scene loads");
            let m = setup::build(&sc).expect("the scene builds");
            kinds.insert((
                m.ground.is_some(),
                m.options.energy,
                m.units.physical,
                m.structure.p_per_second().is_some(),
            ));
            assert_eq!(
                reportable_keys(&m),
                serialized_numbers(&m, true),
                "{file} {sets:?}: the static list differs from what a run reports"
            );
        }
        assert!(kinds.len() >= 5, "the cases cover too few kinds: {kinds:?}");
    }

    /// The quantities marked as needing the forces are exactly those a run reports only when it
    /// tracks them, so a cell that skips the forces can still report everything else.
    #[test]
    fn a_cell_tracks_the_forces_for_exactly_the_quantities_that_need_them() {
        for file in [
            "scenes/spectra/fig8.toml",
            "scenes/wind-turbine-elcentro.toml",
            "scenes/spectra/fig8-winkler.toml",
        ] {
            let sc = scene::load(&scene_file(file), &[]).expect("the scene loads");
            let m = setup::build(&sc).expect("the scene builds");
            let without = serialized_numbers(&m, false);
            for key in serialized_numbers(&m, true) {
                assert_eq!(
                    needs_forces(&key),
                    !without.contains(&key),
                    "{file}: {key} is reported {} the forces",
                    if without.contains(&key) {
                        "without"
                    } else {
                        "only with"
                    }
                );
            }
        }
        assert!(!needs_forces("no_such_key"));
    }

    #[test]
    fn reported_quantities_are_labelled_in_the_papers_notation() {
        assert_eq!(quantity_label("max_base_moment_over_wb"), "max |M_b|/(W B)");
        assert_eq!(quantity_label("impacts"), "impacts");
        assert_eq!(quantity_label("no_such_key"), "no_such_key");
    }
}
