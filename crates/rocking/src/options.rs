//! What to simulate and how accurately.

use std::f64::consts::FRAC_PI_2;

use serde::{Deserialize, Serialize};

use crate::error::OptionError;

/// The integration method of every phase.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Method {
    /// Dormand–Prince 5(4) (`rocking_ode::Method::Dopri5`).
    Dopri5,
    /// DOP853 (`rocking_ode::Method::Dop853`).
    Dop853,
    /// Taylor series from the generated Taylor-mode kernels (`rocking_ode::taylor`: step from
    /// the tolerance, order from a cost model), events as roots of each step's polynomials.
    /// Needs the excitation's Taylor series (`GroundMotion::accel_series`): sine and cosine
    /// pulses and records, not the Ricker and Mavroeidis–Papageorgiou pulses.
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

/// Named accuracy settings, chosen from the work-precision study (`cargo xtask bench`,
/// docs/accuracy.md). What each costs and how accurate it is, as measured, is
/// [`Preset::measured`]: the one table `rocking --help` and the docs quote.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Preset {
    /// Spectra drafts.
    Fast,
    /// Everyday runs.
    Default,
    /// Results to publish. An excitation without a Taylor series runs DOP853 instead: see
    /// [`Preset::accuracy_for`].
    Accurate,
    /// Reference solutions: the independent method the tests hold the others to.
    Reference,
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

    /// What the study measured for the preset: its error (the worse of the max θ/α error and
    /// the relative impact-time error over the study's cases) and its time (geometric mean per
    /// simulation over the study's eight cases, one thread of the 2-core machine). The study
    /// recommends the Taylor method for every preset; only `accurate` is: `fast` and `default`
    /// must run every excitation as it is (the Ricker and Mavroeidis–Papageorgiou pulses have no
    /// Taylor series), and `reference` is the independent method the tests hold Taylor to.
    pub fn measured(self) -> &'static str {
        match self {
            Preset::Fast => "error in max θ/α and impact times about 4e-5, about 0.51 ms",
            Preset::Default => "error about 7e-7, about 0.69 ms",
            Preset::Accurate => {
                "error about 3e-11, about 0.58 ms (DOP853 at 1e-10 takes 1.16 ms; Taylor at \
                 1e-10 misses the 1e-9 target on the spectrum slice's impact times)"
            }
            Preset::Reference => {
                "error about 3e-12 against DOP853 at 1e-14 (2.2e-11 on the spectrum slice), \
                 about 1.7 ms"
            }
        }
    }

    /// The presets as a table of text (one line each: name, method and tolerance, what the study
    /// measured), for `--help`.
    pub fn table() -> String {
        let mut out = String::new();
        for p in Preset::ALL {
            let a = p.accuracy();
            let method = format!("{} at {:e}:", a.method.name(), a.tol);
            out += &format!("  {:<10} {method:<16} {}\n", p.name(), p.measured());
        }
        out
    }

    /// The method and tolerance of the preset.
    pub fn accuracy(self) -> Accuracy {
        match self {
            Preset::Fast => Accuracy {
                method: Method::Dop853,
                tol: 1e-5,
            },
            Preset::Default => Accuracy {
                method: Method::Dop853,
                tol: 1e-7,
            },
            Preset::Accurate => Accuracy {
                method: Method::Taylor,
                tol: 1e-11,
            },
            Preset::Reference => Accuracy {
                method: Method::Dop853,
                tol: 1e-12,
            },
        }
    }

    /// The preset's accuracy for a given excitation: [`Preset::accuracy`], except that a Taylor
    /// preset on an excitation without a Taylor series runs DOP853 at the tolerance the study
    /// found for the same error (`accurate`: 1e-10).
    pub fn accuracy_for<M: rocking_motion::GroundMotion + ?Sized>(self, motion: &M) -> Accuracy {
        let accuracy = self.accuracy();
        if accuracy.method == Method::Taylor && !motion.accel_series(0.0, &mut [0.0; 2]) {
            return Accuracy {
                method: Method::Dop853,
                tol: 1e-10,
            };
        }
        accuracy
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
    /// Coefficient of friction of the ground: the first time the required friction |R_h|/R_v
    /// exceeds it is reported (the model assumes no sliding). `None`: not checked.
    pub friction: Option<f64>,
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
            friction: None,
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
        Ok(())
    }
}
