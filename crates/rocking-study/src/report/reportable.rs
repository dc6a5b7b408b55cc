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
    /// The force extreme it is (its own or the fixed-base twin's): a run tracks the forces
    /// for it ([`rocking::Options::forces`]: a force kernel per step) and searches for that
    /// extreme inside steps ([`rocking::Options::force_extremes`]), which a sweep's cells do only
    /// for the quantities they report ([`needs_forces`], [`force_extremes`]).
    pub extreme: Option<ForceExtreme>,
}

/// The entry of a reported quantity `key` (`fixed_base.KEY`: `KEY`'s).
fn entry(key: &str) -> Option<&'static Reportable> {
    let key = key.strip_prefix("fixed_base.").unwrap_or(key);
    REPORTABLE.iter().find(|r| r.key == key)
}

/// Whether a run must track the forces for the reported quantity `key`: a force quantity, or
/// any of the fixed-base twin's (`fixed_base.KEY`, which a run reports only with the forces).
pub fn needs_forces(key: &str) -> bool {
    key.starts_with("fixed_base.") || entry(key).is_some_and(|r| r.extreme.is_some())
}

/// The force extremes a run must search for to report the quantities `keys`.
pub fn force_extremes<S: AsRef<str>>(keys: &[S]) -> ForceExtremes {
    keys.iter()
        .filter_map(|k| entry(k.as_ref()).and_then(|r| r.extreme))
        .fold(ForceExtremes::NONE, ForceExtremes::with)
}

const fn q(
    key: &'static str,
    label: &'static str,
    needs: Needs,
    twin: bool,
    extreme: Option<ForceExtreme>,
) -> Reportable {
    Reportable {
        key,
        label,
        needs,
        twin,
        extreme,
    }
}

use rocking::{ForceExtreme, ForceExtremes};
use ForceExtreme::{BaseMoment, BaseShear, ElasticMoment, RequiredFriction, VerticalReaction};
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
        None,
    ),
    q(
        "max_theta_over_theta_cr",
        "max_theta_over_theta_cr",
        Always,
        false,
        None,
    ),
    q("max_u_over_ucr", "max |u|/u_cr", Always, true, None),
    q("impacts", "impacts", Always, false, None),
    q(
        "significant_impacts",
        "significant_impacts",
        Always,
        false,
        None,
    ),
    q(
        "energy_capped_impacts",
        "energy_capped_impacts",
        Always,
        false,
        None,
    ),
    q("end_time", "end_time", Always, false, None),
    q("end_time_s", "end_time_s", Seconds, false, None),
    q(
        "solver_stats.steps",
        "solver_stats.steps",
        Always,
        false,
        None,
    ),
    q(
        "solver_stats.rejected_steps",
        "solver_stats.rejected_steps",
        Always,
        false,
        None,
    ),
    q(
        "solver_stats.rhs_evaluations",
        "solver_stats.rhs_evaluations",
        Always,
        false,
        None,
    ),
    q(
        "solver_stats.events",
        "solver_stats.events",
        Always,
        false,
        None,
    ),
    q(
        "max_base_moment_over_wb",
        "max |M_b|/(W B)",
        Always,
        true,
        Some(BaseMoment),
    ),
    q(
        "max_base_shear_over_w",
        "max |V_b|/W",
        Always,
        true,
        Some(BaseShear),
    ),
    q(
        "max_elastic_base_moment_over_wb",
        "max |M_el|/(W B)",
        Always,
        true,
        Some(ElasticMoment),
    ),
    q(
        "max_required_friction",
        "max |R_h|/R_v",
        Always,
        true,
        Some(RequiredFriction),
    ),
    q(
        "min_vertical_reaction_over_w",
        "min R_v/W",
        Always,
        true,
        Some(VerticalReaction),
    ),
    q(
        "base_moment_ratio",
        "max |M_b|, rocking / fixed base",
        Always,
        false,
        Some(BaseMoment),
    ),
    q(
        "base_shear_ratio",
        "max |V_b|, rocking / fixed base",
        Always,
        false,
        Some(BaseShear),
    ),
    q(
        "max_base_moment_nm",
        "max |M_b| (N m)",
        Physical,
        true,
        Some(BaseMoment),
    ),
    q(
        "max_base_shear_n",
        "max |V_b| (N)",
        Physical,
        true,
        Some(BaseShear),
    ),
    q(
        "max_ground_pressure_over_mean",
        "max p/(W/2B)",
        Ground,
        true,
        None,
    ),
    q(
        "min_contact_fraction",
        "min contact length/2B",
        Ground,
        true,
        None,
    ),
    q("lift_offs", "edge lift-offs", Ground, true, None),
    q("max_settlement_over_static", "max v/v₀", Ground, true, None),
    q(
        "ground_energy_dissipated",
        "ground dissipation/E_ref",
        Ground,
        true,
        None,
    ),
    q(
        "energy_balance_residual",
        "energy_balance_residual",
        Energy,
        false,
        None,
    ),
    q("energy.initial", "energy.initial", Energy, false, None),
    q("energy.last", "energy.last", Energy, false, None),
    q(
        "energy.ground_work",
        "energy.ground_work",
        Energy,
        false,
        None,
    ),
    q("energy.damping", "energy.damping", Energy, false, None),
    q(
        "energy.impact_losses",
        "energy.impact_losses",
        Energy,
        false,
        None,
    ),
    q(
        "energy.ground_dissipation",
        "energy.ground_dissipation",
        EnergyOnGround,
        false,
        None,
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
    fn a_cell_searches_for_the_force_extremes_it_reports() {
        use rocking::ForceExtreme::{BaseMoment, BaseShear, VerticalReaction};
        let keys = [
            "max_base_moment_over_wb",
            "fixed_base.max_base_shear_over_w",
            "min_vertical_reaction_over_w",
            "impacts",
        ];
        let want = ForceExtremes::NONE
            .with(BaseMoment)
            .with(BaseShear)
            .with(VerticalReaction);
        assert_eq!(force_extremes(&keys), want);
        assert_eq!(
            force_extremes(&["base_moment_ratio"]),
            ForceExtremes::NONE.with(BaseMoment)
        );
        // The twin's deflection needs the forces (the twin runs only with them), no extreme.
        assert!(needs_forces("fixed_base.max_u_over_ucr"));
        assert_eq!(
            force_extremes(&["fixed_base.max_u_over_ucr"]),
            ForceExtremes::NONE
        );
    }

    #[test]
    fn reported_quantities_are_labelled_in_the_papers_notation() {
        assert_eq!(quantity_label("max_base_moment_over_wb"), "max |M_b|/(W B)");
        assert_eq!(quantity_label("impacts"), "impacts");
        assert_eq!(quantity_label("no_such_key"), "no_such_key");
    }
}
