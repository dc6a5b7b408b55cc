//! What to simulate and how accurately.

use std::f64::consts::FRAC_PI_2;

use serde::{Deserialize, Serialize};

use crate::error::OptionError;
use crate::extremes::{ForceExtremes, GroundExtremes};

/// The integration method of every phase.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Method {
    /// Dormand–Prince 5(4) (`rocking_ode::Method::Dopri5`).
    Dopri5,
    /// DOP853 (`rocking_ode::Method::Dop853`).
    Dop853,
    /// Taylor series from the generated Taylor-mode kernels (`rocking_ode::taylor`: step from
    /// the tolerance, order from a cost model), events as roots of each step's polynomials.
    /// Needs the excitation's Taylor series (`GroundMotion::accel_series`), which every motion
    /// of rocking-motion gives (pulses, Ricker, Mavroeidis–Papageorgiou, records); a motion
    /// without one runs a preset by DOP853 ([`Preset::accuracy_for`]).
    Taylor,
}

impl Method {
    /// Every method.
    pub const ALL: [Method; 3] = [Method::Dopri5, Method::Dop853, Method::Taylor];

    /// The method's name in a scene (`[solver] method`).
    pub fn name(self) -> &'static str {
        match self {
            Method::Dopri5 => "dopri5",
            Method::Dop853 => "dop853",
            Method::Taylor => "taylor",
        }
    }

    /// The Runge–Kutta method, `None` for [`Method::Taylor`].
    pub fn runge_kutta(self) -> Option<rocking_ode::Method> {
        match self {
            Method::Dopri5 => Some(rocking_ode::Method::Dopri5),
            Method::Dop853 => Some(rocking_ode::Method::Dop853),
            Method::Taylor => None,
        }
    }
}

/// Integration method and tolerance. `tol` is the relative tolerance; absolute tolerances are
/// `tol` times the natural scale of each component (α for θ, u_cr for u, α p and u_cr ω_n for
/// the rates, E_ref for the energy integrals).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Accuracy {
    /// Integration method.
    pub method: Method,
    /// Relative tolerance.
    pub tol: f64,
}

/// Named accuracy settings, chosen by the work-precision study (`cargo xtask bench`,
/// docs/accuracy.md): each is the cheapest configuration (method and tolerance) whose worst error
/// over the study's cases meets the preset's [`target`](Preset::target), among the methods
/// [`Preset::method_among`] allows (`reference` stays DOP853: the independent check). The study's report
/// compares this table ([`Preset::accuracy`], [`Preset::measured`]) with its own numbers and
/// says when it is stale; `rocking --help` prints it ([`Preset::table`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Preset {
    /// Spectra drafts.
    Fast,
    /// Everyday runs.
    Default,
    /// Results to publish.
    Accurate,
    /// Reference solutions, by DOP853: the method independent of the Taylor kernels, step rule
    /// and polynomial event roots that the other presets run, so that tests and users can hold
    /// them to it.
    Reference,
}

/// What the study measured for a preset at its method and tolerance.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Measured {
    /// The worst error over the study's cases: the worse of the absolute error of max θ/α and
    /// the relative error of the impact times.
    pub error: f64,
    /// CPU seconds per simulation, the geometric mean over the study's nine cases (one thread).
    pub seconds: f64,
}

/// One row of the presets' table: everything a preset is, in one place.
struct Row {
    target: f64,
    /// The only method the preset may be chosen from, if restricted.
    among: Option<Method>,
    accuracy: Accuracy,
    /// The DOP853 tolerance for the same target, for a motion without a Taylor series.
    dop853_tol: f64,
    measured: Measured,
}

impl Preset {
    /// Every preset, from the cheapest.
    pub const ALL: [Preset; 4] = [
        Preset::Fast,
        Preset::Default,
        Preset::Accurate,
        Preset::Reference,
    ];

    /// The preset's name in a scene (`[solver] accuracy`).
    pub fn name(self) -> &'static str {
        match self {
            Preset::Fast => "fast",
            Preset::Default => "default",
            Preset::Accurate => "accurate",
            Preset::Reference => "reference",
        }
    }

    /// The table (module docs of the type): targets, the study's cheapest configurations and
    /// what it measured (`cargo xtask bench`, docs/accuracy.md).
    fn row(self) -> Row {
        let taylor = |tol| Accuracy {
            method: Method::Taylor,
            tol,
        };
        let dop853 = |tol| Accuracy {
            method: Method::Dop853,
            tol,
        };
        let row = |target, among, accuracy, dop853_tol, error, seconds| Row {
            target,
            among,
            accuracy,
            dop853_tol,
            measured: Measured { error, seconds },
        };
        // `cargo xtask bench` of 2026-11-29 02:27 UTC (1820 s; 2-core VM with three other
        // builds running, so the times are up to 30 % high; nine standard cases, docs/accuracy.md;
        // the first with DOP853's events on its own steps). The choices are those of the study of
        // 2026-11-26 14:27 UTC (376 s, quiet): `fast` is Taylor 1e-7 like `default`: on
        // `long-record` (a record with 147 impacts that amplifies errors, bench/NOTES.md) Taylor
        // 1e-3 to 1e-6 take other branches (max θ/α off by 0.09-0.33), and Taylor 1e-7 is the
        // cheapest configuration within 1e-3 there and on every other case. `accurate` from the
        // study of 2026-11-27 03:32 UTC, the first with 3e-k between the decades: Taylor 3e-11
        // meets 1e-9 on every case and costs 8 % less than 1e-11; Taylor 1e-10 and 3e-10 miss it
        // on the spectrum slice. `reference`'s independence costs 4.19× Taylor 1e-13 here.
        // The DOP853 tolerances (`accuracy_for`) are that study's cheapest DOP853 per target:
        // `accurate`'s 1e-10 of earlier studies gave 1.2e-9 on the spectrum slice once DOP853's
        // events were located on its own steps, 3e-11 gives 3.1e-10.
        // On the hard classes (`many-impacts`, `chatter`) the errors are per class in
        // docs/accuracy.md: there the presets are not chosen.
        match self {
            Preset::Fast => row(1e-3, None, taylor(1e-7), 3e-4, 7.5e-4, 290e-6),
            Preset::Default => row(1e-6, None, taylor(1e-7), 3e-7, 7.5e-7, 290e-6),
            Preset::Accurate => row(1e-9, None, taylor(3e-11), 3e-11, 4.2e-11, 412e-6),
            Preset::Reference => row(
                1e-11,
                Some(Method::Dop853),
                dop853(1e-13),
                1e-13,
                8.7e-13,
                2.03e-3,
            ),
        }
    }

    /// The error the preset is chosen to meet on every case of the study (the worse of the
    /// absolute error of max θ/α and the relative error of the impact times).
    pub fn target(self) -> f64 {
        self.row().target
    }

    /// The only method the study may choose the preset from, if restricted: DOP853 for
    /// `reference`, the independent check of the others.
    pub fn method_among(self) -> Option<Method> {
        self.row().among
    }

    /// The method and tolerance of the preset.
    pub fn accuracy(self) -> Accuracy {
        self.row().accuracy
    }

    /// What the study measured for the preset.
    pub fn measured(self) -> Measured {
        self.row().measured
    }

    /// The presets as a table of text (one line each: name, method and tolerance, target and what
    /// the study measured), for `--help`.
    pub fn table() -> String {
        let mut out = String::new();
        for p in Preset::ALL {
            let (a, m) = (p.accuracy(), p.measured());
            let method = format!("{} at {:e}:", a.method.name(), a.tol);
            out += &format!(
                "  {:<10} {method:<16} target {:.0e}, error about {:.0e}, about {:.2} ms\n",
                p.name(),
                p.target(),
                m.error,
                m.seconds * 1e3
            );
        }
        out
    }

    /// The DOP853 tolerance the study found for the preset's target ([`Preset::accuracy_for`]).
    pub fn dop853_tol(self) -> f64 {
        self.row().dop853_tol
    }

    /// The preset's accuracy for a given excitation: [`Preset::accuracy`], except that a motion
    /// without a Taylor series (whose `GroundMotion::accel_series` returns false: none of
    /// rocking-motion's) runs DOP853 at the tolerance the study found for the same target.
    pub fn accuracy_for<M: rocking_motion::GroundMotion + ?Sized>(self, motion: &M) -> Accuracy {
        let row = self.row();
        if row.accuracy.method == Method::Taylor && !motion.accel_series(0.0, &mut [0.0; 2]) {
            return Accuracy {
                method: Method::Dop853,
                tol: row.dop853_tol,
            };
        }
        row.accuracy
    }
}

/// The energy-loss model at impact (equations.md 1.5).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ImpactModel {
    /// Vertical Velocity Energy Loss, eqs (31)-(32): the paper's choice.
    Vvel,
    /// Acikgoz–DeJong extended, eqs (26)-(30).
    Adjex,
    /// Housner's angular-momentum rule: immediate rocking about the impacting corner.
    Housner,
    /// A fixed coefficient of restitution r: θ' after = r θ' before, u' kept.
    Restitution(f64),
}

impl ImpactModel {
    /// The models named by a word alone (a restitution also takes its coefficient, in a scene
    /// `{ restitution = r }`).
    pub const NAMED: [ImpactModel; 3] =
        [ImpactModel::Vvel, ImpactModel::Adjex, ImpactModel::Housner];

    /// What the model does at an impact, in words (`rocking models`).
    pub fn doc(self) -> &'static str {
        match self {
            ImpactModel::Vvel => {
                "VVEL, eqs (31)-(32): the vertical velocities' kinetic energy is lost, full \
                 contact follows (the paper's choice)"
            }
            ImpactModel::Adjex => {
                "ADJex, eqs (26)-(30): full contact or immediate rocking, whichever keeps less \
                 energy, else the horizontal-momentum fallback"
            }
            ImpactModel::Housner => {
                "Housner: angular momentum about the impacting corner kept, rocking goes on"
            }
            ImpactModel::Restitution(_) => "a fixed restitution r: θ' after = r θ' before, u' kept",
        }
    }

    /// The model's name (in a scene, the event log's branches, the study's cases).
    pub fn name(self) -> &'static str {
        match self {
            ImpactModel::Vvel => "vvel",
            ImpactModel::Adjex => "adjex",
            ImpactModel::Housner => "housner",
            ImpactModel::Restitution(_) => "restitution",
        }
    }
}

/// Per-step output.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum History {
    /// Nothing stored per step (summary only).
    None,
    /// One row per accepted integrator step and per event.
    Steps,
    /// One row every `dt` (model time units), from the dense output.
    Grid(f64),
}

/// The initial state (full contact unless θ ≠ 0).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Initial {
    /// Initial rotation θ (rad); its sign is the pivot.
    pub theta: f64,
    /// Initial column displacement u.
    pub u: f64,
    /// Initial rotation rate θ'.
    pub theta_dot: f64,
    /// Initial column velocity u'.
    pub u_dot: f64,
    /// Initial settlement v of the base centre on compliant ground (model units; `None`: at
    /// rest in vertical equilibrium at θ). The rigid surface has no v.
    pub v: Option<f64>,
}

/// Everything that controls a run besides the structure and the excitation.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Options {
    /// Method and tolerance.
    pub accuracy: Accuracy,
    /// Impact model.
    pub impact: ImpactModel,
    /// |θ| at which the structure is overturned (default π/2: lying on the ground).
    pub overturn_angle: f64,
    /// End of the simulation, in model time units.
    pub t_end: f64,
    /// Integrate the ground work and the damping dissipation, for the energy balance.
    pub energy: bool,
    /// Per-step output.
    pub history: History,
    /// Keep the log of events (uplifts, impacts with their branch and energies).
    pub event_log: bool,
    /// Stop as soon as the answer is known: overturned, or at rest in full contact after the
    /// excitation with too little energy to uplift again. Off when a full history is asked.
    pub stop_when_known: bool,
    /// Rest rule: a rocking phase that starts with |θ'| below `rest_rate` α p ends at once in
    /// full contact (this resolves the Zeno accumulation of impacts of free rocking). The default,
    /// 1e-4, leaves a rocking energy of order 1e-8 E_ref, below the accuracy of every preset.
    pub rest_rate: f64,
    /// Guard: at most this many events (uplifts + impacts) before the run fails with an error.
    pub max_events: u64,
    /// Guard: at most this many integrator steps.
    pub max_steps: u64,
    /// Initial state.
    pub initial: Initial,
    /// The base may uplift (false: the fixed-base twin, held in full contact for the whole run
    /// with no uplift check, under the same excitation).
    pub uplift: bool,
    /// Track the section forces at the column base and the ground reactions ([`ForceSummary`]
    /// in the summary; about one force kernel per step). A sweep that reports none may skip them.
    ///
    /// [`ForceSummary`]: crate::ForceSummary
    pub forces: bool,
    /// The force extremes whose peaks inside steps the run searches for, with
    /// [`forces`](Self::forces) on: all of them by default. The others are only recorded at each
    /// step's end and event, a lower bound of their extremes: a sweep that reports one force
    /// searches for that one alone.
    pub force_extremes: ForceExtremes,
    /// The ground's extremes whose peaks inside steps a run on compliant ground searches for: all
    /// of them by default; the others are recorded at each step's end, event and the points the
    /// other searches find (a bound of their extremes).
    pub ground_extremes: GroundExtremes,
    /// Track the largest top deflection |u| ([`Summary::max_u_over_ucr`]; NaN, left out of the
    /// summary, when off): a turning-point search on the steps where the top's rate changes
    /// sign, and a rest that waits until u can no longer exceed it. A sweep's cells skip it
    /// unless they report it.
    ///
    /// [`Summary::max_u_over_ucr`]: crate::Summary::max_u_over_ucr
    pub max_deflection: bool,
    /// Coefficient of friction of the ground: the first time the required friction |R_h|/R_v
    /// exceeds it is reported (the model assumes no sliding). `None`: not checked.
    pub friction: Option<f64>,
    /// The ground's bearing pressure over the mean pressure W / (2B) (two springs: a corner's
    /// force over W / 2), on compliant ground: the first time the largest pressure under the base
    /// exceeds it is reported (`GroundSummary::first_bearing_exceeded_time`; the bed does not
    /// yield). `None`: not checked. The rigid surface has no pressure distribution: ignored there.
    pub bearing_over_mean: Option<f64>,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            accuracy: Preset::Default.accuracy(),
            impact: ImpactModel::Vvel,
            overturn_angle: FRAC_PI_2,
            t_end: 40.0,
            energy: false,
            history: History::None,
            event_log: false,
            stop_when_known: true,
            rest_rate: 1e-4,
            max_events: 1_000_000,
            max_steps: 50_000_000,
            initial: Initial::default(),
            uplift: true,
            forces: true,
            force_extremes: ForceExtremes::ALL,
            ground_extremes: GroundExtremes::ALL,
            max_deflection: true,
            friction: None,
            bearing_over_mean: None,
        }
    }
}

/// The most rows a [`History`] may ask for (each row is 80 bytes in memory): a grid's rows up to
/// `t_end`, or `max_steps` when every step is recorded.
pub const MAX_HISTORY_ROWS: f64 = 5e7;

impl Options {
    /// Checks every field, so that a library caller gets an error naming the field instead of a
    /// run to nonsense (an overturning angle of NaN, a restitution of 2, a start beyond π/2) or an
    /// unbounded allocation (`History::Grid(0)`). Called by every entry point that simulates.
    ///
    /// # Errors
    /// The first field out of range (`Options::FIELD = VALUE is not allowed: RANGE`).
    pub fn validate(&self) -> Result<(), OptionError> {
        fn check(field: &str, v: f64, ok: bool, allowed: &str) -> Result<(), OptionError> {
            if ok && v.is_finite() {
                Ok(())
            } else {
                Err(OptionError {
                    field: field.to_string(),
                    value: v,
                    allowed: allowed.to_string(),
                })
            }
        }
        let tol = self.accuracy.tol;
        check("accuracy.tol", tol, tol > 0.0 && tol < 1.0, "0 < tol < 1")?;
        check("t_end", self.t_end, self.t_end > 0.0, "0 < t_end < inf")?;
        let a = self.overturn_angle;
        check(
            "overturn_angle",
            a,
            a > 0.0 && a <= FRAC_PI_2 + 1e-12,
            "0 < overturn_angle <= pi/2",
        )?;
        if let ImpactModel::Restitution(r) = self.impact {
            check(
                "impact (restitution)",
                r,
                (0.0..=1.0).contains(&r),
                "a coefficient of restitution 0 <= r <= 1",
            )?;
        }
        if self.history == History::Steps {
            // One row per integrator step: the step guard bounds the rows up front.
            let steps = self.max_steps as f64;
            check(
                "max_steps (with History::Steps)",
                steps,
                steps <= MAX_HISTORY_ROWS,
                &format!("at most {MAX_HISTORY_ROWS:e} steps when every step is recorded"),
            )?;
        }
        if let History::Grid(dt) = self.history {
            check("history (grid step)", dt, dt > 0.0, "a grid step > 0")?;
            check(
                "history (grid step)",
                dt,
                self.t_end / dt <= MAX_HISTORY_ROWS,
                &format!(
                    "at most {MAX_HISTORY_ROWS:e} rows up to t_end = {:e}",
                    self.t_end
                ),
            )?;
        }
        check(
            "rest_rate",
            self.rest_rate,
            self.rest_rate >= 0.0,
            "rest_rate >= 0",
        )?;
        for (field, n) in [
            ("max_events", self.max_events),
            ("max_steps", self.max_steps),
        ] {
            check(field, n as f64, n >= 1, "at least 1")?;
        }
        if let Some(mu) = self.friction {
            check("friction", mu, mu >= 0.0, "a coefficient of friction >= 0")?;
        }
        if let Some(q) = self.bearing_over_mean {
            check("bearing_over_mean", q, q > 0.0, "a bearing pressure > 0")?;
        }
        let i = &self.initial;
        check(
            "initial.theta",
            i.theta,
            i.theta.abs() < a,
            "|theta| < overturn_angle (rad)",
        )?;
        check("initial.u", i.u, true, "a finite displacement")?;
        check("initial.theta_dot", i.theta_dot, true, "a finite rate")?;
        check("initial.u_dot", i.u_dot, true, "a finite rate")?;
        // Held down, the base cannot start tilted or rotating: that run would rock until its
        // first impact, which is not the fixed-base structure.
        let held = "0 when uplift = false (the base is held in full contact from t = 0)";
        check(
            "initial.theta",
            i.theta,
            self.uplift || i.theta == 0.0,
            held,
        )?;
        check(
            "initial.theta_dot",
            i.theta_dot,
            self.uplift || i.theta_dot == 0.0,
            held,
        )?;
        Ok(())
    }

    /// The fixed-base twin of a run with these options: the same structure held in full contact
    /// from t = 0, so without the run's initial θ and θ' (its initial u and u' are kept).
    pub fn fixed_base_twin(&self) -> Options {
        Options {
            uplift: false,
            initial: Initial {
                theta: 0.0,
                theta_dot: 0.0,
                ..self.initial
            },
            ..*self
        }
    }
}

#[cfg(test)]
mod tests {
    use super::{Initial, Options};

    #[test]
    fn a_held_down_run_cannot_start_tilted_and_the_twin_starts_upright() {
        let tilted = Options {
            initial: Initial {
                theta: 0.1,
                u: 0.2,
                theta_dot: 0.3,
                u_dot: 0.4,
                v: None,
            },
            ..Options::default()
        };
        assert!(tilted.validate().is_ok());
        let e = Options {
            uplift: false,
            ..tilted
        }
        .validate()
        .unwrap_err();
        assert_eq!(e.field, "initial.theta");
        assert!(e.allowed.contains("uplift = false"), "{e}");
        let twin = tilted.fixed_base_twin();
        assert!(!twin.uplift);
        assert_eq!(
            (twin.initial.theta, twin.initial.theta_dot),
            (0.0, 0.0),
            "no tilt, no rotation"
        );
        assert_eq!(
            (twin.initial.u, twin.initial.u_dot),
            (0.2, 0.4),
            "the column's start kept"
        );
        assert!(twin.validate().is_ok());
    }
}
