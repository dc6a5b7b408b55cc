//! The summary quantities a sweep may report (`[sweep] report`, a convergence study's
//! quantities), declared once with their labels: a static list, not probe runs. The test below
//! checks it against what runs of each kind serialize ([`super::quantities`]), so a new summary
//! field that is a number fails it until it is listed here.

use rocking_scene::labels;
use rocking_scene::setup::Setup;

/// A condition under which a run reports a quantity: a quantity's conditions must all hold
/// (none: every run).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Need {
    /// A scene whose time is known in seconds (physical units, or a length scale).
    Seconds,
    /// A scene in physical units (the force maxima in SI).
    Physical,
    /// A run on compliant ground.
    Ground,
    /// A run with the energy bookkeeping (`[effects] energy`).
    Energy,
    /// A friction coefficient to check (`[effects] friction`).
    Friction,
    /// A bearing pressure to check (`[effects] bearing` or `bearing_over_mean`).
    Bearing,
}

/// A summary quantity a sweep may report.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Reportable {
    /// Its key in the summary (`a.b`: entry `b` of object `a`).
    pub key: &'static str,
    /// Its label in the paper's notation (the key where it has none).
    pub label: &'static str,
    /// Which runs report it (all of these hold).
    pub needs: &'static [Need],
    /// The fixed-base twin reports it too, as `fixed_base.KEY`.
    pub twin: bool,
    /// The force extreme it is (its own or the fixed-base twin's): a run tracks the forces
    /// for it ([`rocking::Options::forces`]: a force kernel per step) and searches for that
    /// extreme inside steps ([`rocking::Options::force_extremes`]), which a sweep's cells do only
    /// for the quantities they report ([`needs_forces`], [`force_extremes`]).
    pub extreme: Option<ForceExtreme>,
    /// The ground's extreme it is, which a run on compliant ground searches for inside steps
    /// ([`rocking::Options::ground_extremes`]) only when reported ([`ground_extremes`]).
    pub ground_extreme: Option<GroundExtreme>,
    /// It is the top's largest deflection, which a run tracks
    /// ([`rocking::Options::max_deflection`]: turning-point searches) only when reported
    /// ([`needs_deflection`]).
    pub deflection: bool,
    /// A run may have no value of it: the time of an event that did not happen (`null` in the
    /// summary, an empty field in cells.csv, NaN and masked in Python).
    pub nullable: bool,
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

/// Whether a run must track the top's largest deflection for the reported quantity `key` (its
/// own or, `fixed_base.KEY`, the twin's).
pub fn needs_deflection(key: &str) -> bool {
    entry(key).is_some_and(|r| r.deflection)
}

/// The force extremes a run must search for to report the quantities `keys`.
pub fn force_extremes<S: AsRef<str>>(keys: &[S]) -> ForceExtremes {
    keys.iter()
        .filter_map(|k| entry(k.as_ref()).and_then(|r| r.extreme))
        .fold(ForceExtremes::NONE, ForceExtremes::with)
}

/// The ground's extremes a run must search for to report the quantities `keys`.
pub fn ground_extremes<S: AsRef<str>>(keys: &[S]) -> GroundExtremes {
    keys.iter()
        .filter_map(|k| entry(k.as_ref()).and_then(|r| r.ground_extreme))
        .fold(GroundExtremes::NONE, GroundExtremes::with)
}

/// A number every run of `needs` has.
const fn q(
    key: &'static str,
    label: &'static str,
    needs: &'static [Need],
    twin: bool,
    extreme: Option<ForceExtreme>,
) -> Reportable {
    Reportable {
        key,
        label,
        needs,
        twin,
        extreme,
        ground_extreme: None,
        deflection: false,
        nullable: false,
    }
}

impl Reportable {
    /// This quantity, the ground's extreme `e`.
    const fn searching(self, e: GroundExtreme) -> Reportable {
        Reportable {
            ground_extreme: Some(e),
            ..self
        }
    }

    /// This quantity, the top's largest deflection.
    const fn deflection(self) -> Reportable {
        Reportable {
            deflection: true,
            ..self
        }
    }
}

/// The time of an event, which a run of `needs` reports (`null` where it did not happen).
const fn time(
    key: &'static str,
    label: &'static str,
    needs: &'static [Need],
    extreme: Option<ForceExtreme>,
) -> Reportable {
    Reportable {
        key,
        label,
        needs,
        twin: false,
        extreme,
        ground_extreme: None,
        deflection: false,
        nullable: true,
    }
}

use rocking::{ForceExtreme, ForceExtremes, GroundExtreme, GroundExtremes};
use ForceExtreme::{BaseMoment, BaseShear, ElasticMoment, RequiredFriction, VerticalReaction};
use Need::{Bearing, Energy, Friction, Ground, Physical, Seconds};

/// Every run.
const ALWAYS: &[Need] = &[];
const SECONDS: &[Need] = &[Seconds];
const PHYSICAL: &[Need] = &[Physical];
const GROUND: &[Need] = &[Ground];
const ENERGY: &[Need] = &[Energy];

/// Every summary quantity a sweep may report. The ratios to the fixed-base twin are
/// [`super::RATIOS`]; M_b, V_b the moment and shear at the column base, M_el the elastic moment,
/// R_h and R_v the ground reactions, W the total weight, B the half-width; on compliant ground p
/// the pressure under the base, v its settlement and v₀ the static one.
pub const REPORTABLE: [Reportable; 46] = [
    q(
        "max_theta_over_alpha",
        labels::MAX_THETA_OVER_ALPHA,
        ALWAYS,
        false,
        None,
    ),
    q(
        "max_theta_over_theta_cr",
        "max_theta_over_theta_cr",
        ALWAYS,
        false,
        None,
    ),
    q("max_u_over_ucr", "max |u|/u_cr", ALWAYS, true, None).deflection(),
    q("impacts", "impacts", ALWAYS, false, None),
    q(
        "significant_impacts",
        "significant_impacts",
        ALWAYS,
        false,
        None,
    ),
    q(
        "energy_capped_impacts",
        "energy_capped_impacts",
        ALWAYS,
        false,
        None,
    ),
    q("end_time", "end_time", ALWAYS, false, None),
    q("end_time_s", "end_time_s", SECONDS, false, None),
    q(
        "solver_stats.steps",
        "solver_stats.steps",
        ALWAYS,
        false,
        None,
    ),
    q(
        "solver_stats.rejected_steps",
        "solver_stats.rejected_steps",
        ALWAYS,
        false,
        None,
    ),
    q(
        "solver_stats.rhs_evaluations",
        "solver_stats.rhs_evaluations",
        ALWAYS,
        false,
        None,
    ),
    q(
        "solver_stats.events",
        "solver_stats.events",
        ALWAYS,
        false,
        None,
    ),
    q(
        "max_base_moment_over_wb",
        "max |M_b|/(W B)",
        ALWAYS,
        true,
        Some(BaseMoment),
    ),
    q(
        "max_base_shear_over_w",
        "max |V_b|/W",
        ALWAYS,
        true,
        Some(BaseShear),
    ),
    q(
        "max_elastic_base_moment_over_wb",
        "max |M_el|/(W B)",
        ALWAYS,
        true,
        Some(ElasticMoment),
    ),
    q(
        "max_required_friction",
        "max |R_h|/R_v",
        ALWAYS,
        true,
        Some(RequiredFriction),
    ),
    q(
        "min_vertical_reaction_over_w",
        "min R_v/W",
        ALWAYS,
        true,
        Some(VerticalReaction),
    ),
    q(
        "base_moment_ratio",
        "max |M_b|, rocking / fixed base",
        ALWAYS,
        false,
        Some(BaseMoment),
    ),
    q(
        "base_shear_ratio",
        "max |V_b|, rocking / fixed base",
        ALWAYS,
        false,
        Some(BaseShear),
    ),
    q(
        "max_base_moment_nm",
        "max |M_b| (N m)",
        PHYSICAL,
        true,
        Some(BaseMoment),
    ),
    q(
        "max_base_shear_n",
        "max |V_b| (N)",
        PHYSICAL,
        true,
        Some(BaseShear),
    ),
    q(
        "max_ground_pressure_over_mean",
        "max p/(W/2B)",
        GROUND,
        true,
        None,
    )
    .searching(GroundExtreme::MaxPressure),
    q(
        "min_ground_pressure_over_mean",
        "min p/(W/2B)",
        GROUND,
        true,
        None,
    )
    .searching(GroundExtreme::LeastPressure),
    q(
        "min_contact_fraction",
        "min contact length/2B",
        GROUND,
        true,
        None,
    )
    .searching(GroundExtreme::ContactFraction),
    q("lift_offs", "edge lift-offs", GROUND, true, None),
    q("max_settlement_over_static", "max v/v₀", GROUND, true, None),
    q(
        "ground_energy_dissipated",
        "ground dissipation/E_ref",
        GROUND,
        true,
        None,
    ),
    q(
        "energy_balance_residual",
        "energy_balance_residual",
        ENERGY,
        false,
        None,
    ),
    q("energy.initial", "energy.initial", ENERGY, false, None),
    q("energy.last", "energy.last", ENERGY, false, None),
    q(
        "energy.ground_work",
        "energy.ground_work",
        ENERGY,
        false,
        None,
    ),
    q("energy.damping", "energy.damping", ENERGY, false, None),
    q(
        "energy.impact_losses",
        "energy.impact_losses",
        ENERGY,
        false,
        None,
    ),
    q(
        "energy.ground_dissipation",
        "energy.ground_dissipation",
        &[Energy, Ground],
        false,
        None,
    ),
    // The times of events, in τ and (`_s`) in seconds.
    time("first_uplift_time", "τ at first uplift", ALWAYS, None),
    time(
        "first_uplift_time_s",
        "t at first uplift (s)",
        SECONDS,
        None,
    ),
    time("first_impact_time", "τ at first impact", ALWAYS, None),
    time(
        "first_impact_time_s",
        "t at first impact (s)",
        SECONDS,
        None,
    ),
    time("overturn_time", "τ at overturning", ALWAYS, None),
    time("overturn_time_s", "t at overturning (s)", SECONDS, None),
    time(
        "first_slip_time",
        "τ at first slip (|R_h|/R_v > μ)",
        &[Friction],
        Some(RequiredFriction),
    ),
    time(
        "first_slip_time_s",
        "t at first slip (s)",
        &[Friction, Seconds],
        Some(RequiredFriction),
    ),
    time(
        "first_lift_off_time",
        "τ at first lift-off (R_v < 0)",
        ALWAYS,
        Some(VerticalReaction),
    ),
    time(
        "first_lift_off_time_s",
        "t at first lift-off (s)",
        SECONDS,
        Some(VerticalReaction),
    ),
    time(
        "first_bearing_exceeded_time",
        "τ when p first exceeds the bearing",
        &[Ground, Bearing],
        None,
    ),
    time(
        "first_bearing_exceeded_time_s",
        "t when p first exceeds the bearing (s)",
        &[Ground, Bearing, Seconds],
        None,
    ),
];

impl Need {
    /// Whether runs of `model` meet this condition.
    fn met_by(self, model: &Setup) -> bool {
        let o = &model.options;
        match self {
            Seconds => model.structure.p_per_second().is_some(),
            Physical => model.units.physical,
            Ground => model.ground.is_some(),
            Energy => o.energy,
            Friction => o.friction.is_some(),
            Bearing => o.bearing_over_mean.is_some(),
        }
    }
}

impl Need {
    /// What a scene must have to meet it, in its own words.
    fn wanted(self) -> &'static str {
        match self {
            Seconds => "a time in seconds (physical units, or `r` or `p` in [structure])",
            Physical => "physical units",
            Ground => "compliant ground ([ground] kind)",
            Energy => "the energy bookkeeping ([effects] energy = true)",
            Friction => "a friction coefficient ([effects] friction)",
            Bearing => "a bearing pressure ([effects] bearing or bearing_over_mean)",
        }
    }
}

impl Reportable {
    /// Whether runs of `model` report it.
    pub fn reported_by(&self, model: &Setup) -> bool {
        self.needs.iter().all(|n| n.met_by(model))
    }
}

/// What the scene of `model` lacks for its runs to report `key` (`fixed_base.KEY`: `KEY`), in
/// words; `None` for a key no run reports or one they do.
pub fn unmet_needs(key: &str, model: &Setup) -> Option<String> {
    let wanted: Vec<&str> = entry(key)?
        .needs
        .iter()
        .filter(|n| !n.met_by(model))
        .map(|n| n.wanted())
        .collect();
    (!wanted.is_empty()).then(|| wanted.join(" and "))
}

/// Whether a run may have no value of the reported quantity `key` (the time of an event).
pub fn nullable(key: &str) -> bool {
    entry(key).is_some_and(|r| r.nullable)
}

/// The keys a sweep of `model` may report, sorted: the quantities its runs report as numbers
/// (or, for the times of events, as numbers or `null`), and the fixed-base twin's
/// (`fixed_base.KEY`).
pub fn reportable_keys(model: &Setup) -> Vec<String> {
    let mut keys: Vec<String> = REPORTABLE
        .iter()
        .filter(|r| r.reported_by(model))
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

    /// The keys a run of `m` and its twin serialize as numbers, and the times they serialize as
    /// `null` (`*_time`, `*_time_s`; a `null` object such as `energy` is an absent group): a run that ends at once with the forces tracked or not (`forces`), as a sweep's
    /// cell runs.
    fn serialized_keys(m: &Setup, forces: bool, deflection: bool) -> (Vec<String>, Vec<String>) {
        let probe = rocking::Options {
            t_end: 1e-9,
            forces,
            max_deflection: deflection,
            history: History::None,
            event_log: false,
            ..m.options
        };
        let run = |o: &rocking::Options| run_setup(m, o).expect("the probe runs").summary;
        let twin = run(&probe.fixed_base_twin());
        let q = quantities(&run(&probe), Some(&twin), si_scale(m)).expect("finite quantities");
        let (mut numbers, mut nulls) = (Vec::new(), Vec::new());
        let mut sort = |key: String, v: &serde_json::Value| {
            if number(v).is_some() {
                numbers.push(key);
            } else if v.is_null() && (key.ends_with("_time") || key.ends_with("_time_s")) {
                nulls.push(key);
            }
        };
        for (k, v) in &q {
            match v {
                serde_json::Value::Object(o) => {
                    o.iter().for_each(|(j, x)| sort(format!("{k}.{j}"), x));
                }
                v => sort(k.clone(), v),
            }
        }
        if forces {
            numbers.extend(RATIOS.iter().map(|r| r.to_string()));
        }
        for keys in [&mut numbers, &mut nulls] {
            keys.sort();
            keys.dedup();
        }
        (numbers, nulls)
    }

    /// The numeric keys a run of `m` and its twin serialize.
    fn serialized_numbers(m: &Setup, forces: bool, deflection: bool) -> Vec<String> {
        serialized_keys(m, forces, deflection).0
    }

    fn scene_file(rel: &str) -> PathBuf {
        Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../..")
            .join(rel)
    }

    /// Rigid and compliant ground, with and without the energy bookkeeping, dimensionless with
    /// and without seconds, and physical, with and without friction and a bearing pressure: the
    /// static list is what the runs serialize, the numbers and the times of the events (`null`
    /// in these runs, which end at once), and every `null` a run writes is a time the list has.
    #[test]
    fn the_static_list_is_what_runs_of_every_kind_report() {
        let cases: [(&str, &[&str]); 8] = [
            ("scenes/spectra/fig8.toml", &[]),
            ("scenes/spectra/fig8.toml", &["effects.energy=true"]),
            ("scenes/spectra/fig8.toml", &["effects.friction=0.5"]),
            ("scenes/spectra/fig8-winkler.toml", &[]),
            ("scenes/spectra/fig8-winkler.toml", &["effects.energy=true"]),
            (
                "scenes/spectra/fig8-winkler.toml",
                &["effects.bearing_over_mean=3.0", "effects.friction=0.6"],
            ),
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
                m.options.friction.is_some(),
                m.options.bearing_over_mean.is_some(),
            ));
            let (numbers, nulls) = serialized_keys(&m, true, true);
            for key in &nulls {
                assert!(
                    entry(key).is_some_and(|r| r.nullable || !r.reported_by(&m)),
                    "{file} {sets:?}: a run writes `{key}` as null, which the list does not \
                     have as a time of an event"
                );
            }
            let mut want: Vec<String> = numbers
                .into_iter()
                .chain(nulls.into_iter().filter(|k| nullable(k)))
                .filter(|k| entry(k).is_none_or(|r| r.reported_by(&m)))
                .collect();
            want.sort();
            assert_eq!(
                reportable_keys(&m),
                want,
                "{file} {sets:?}: the static list differs from what a run reports"
            );
        }
        assert!(kinds.len() >= 7, "the cases cover too few kinds: {kinds:?}");
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
            let without = serialized_numbers(&m, false, true);
            for key in serialized_numbers(&m, true, true) {
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

    /// Likewise the top's largest deflection: a run that does not track it leaves out exactly
    /// the quantities marked as needing it (its own and the twin's), and reports the rest.
    #[test]
    fn a_cell_tracks_the_deflection_for_exactly_the_quantities_that_need_it() {
        for file in [
            "scenes/spectra/fig8.toml",
            "scenes/wind-turbine-elcentro.toml",
        ] {
            let sc = scene::load(&scene_file(file), &[]).expect("the scene loads");
            let m = setup::build(&sc).expect("the scene builds");
            let without = serialized_numbers(&m, true, false);
            let with = serialized_numbers(&m, true, true);
            for key in &with {
                assert_eq!(
                    needs_deflection(key),
                    !without.contains(key),
                    "{file}: {key}"
                );
            }
            assert!(with.iter().any(|k| needs_deflection(k)), "{file}: {with:?}");
        }
        assert!(needs_deflection("fixed_base.max_u_over_ucr"));
        assert!(!needs_deflection("max_base_moment_over_wb"));
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
    fn a_cell_on_the_ground_searches_for_the_ground_extremes_it_reports() {
        use rocking::GroundExtreme::{ContactFraction, LeastPressure, MaxPressure};
        let keys = [
            "min_contact_fraction",
            "fixed_base.min_ground_pressure_over_mean",
        ];
        let want = GroundExtremes::NONE
            .with(ContactFraction)
            .with(LeastPressure);
        assert_eq!(ground_extremes(&keys), want);
        assert!(!want.contains(MaxPressure));
        // Settlement maxima are turning points of v, found whatever is reported.
        let keys = ["max_settlement_over_static", "lift_offs", "impacts"];
        assert_eq!(ground_extremes(&keys), GroundExtremes::NONE);
        // Every searched measure of the driver is some quantity's.
        let all = REPORTABLE.iter().filter_map(|r| r.ground_extreme);
        assert_eq!(
            all.fold(GroundExtremes::NONE, GroundExtremes::with),
            GroundExtremes::ALL
        );
    }

    #[test]
    fn reported_quantities_are_labelled_in_the_papers_notation() {
        assert_eq!(quantity_label("max_base_moment_over_wb"), "max |M_b|/(W B)");
        assert_eq!(quantity_label("impacts"), "impacts");
        assert_eq!(quantity_label("no_such_key"), "no_such_key");
    }
}
