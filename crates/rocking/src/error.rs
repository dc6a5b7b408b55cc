//! Why a run failed: one variant per thing that can go wrong, with what the caller needs to say
//! so (the scene layer adds the file and the settings that bound the run).

use rocking_ode::OdeError;

/// An option outside its allowed range ([`Options::validate`](crate::Options::validate)).
#[derive(Debug, Clone, PartialEq)]
pub struct OptionError {
    /// The field, as `Options::<field>` names it (e.g. `accuracy.tol`).
    pub field: String,
    /// The value given.
    pub value: f64,
    /// What is allowed.
    pub allowed: String,
}

impl std::fmt::Display for OptionError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "Options::{} = {:e} is not allowed: {}",
            self.field, self.value, self.allowed
        )
    }
}

/// Why a run failed.
#[derive(Debug, Clone, PartialEq)]
pub enum SimError {
    /// The integrator failed (step-size underflow, non-finite state, too many steps).
    Integration(OdeError),
    /// More events than `Options::max_events` by `tau`: the run does not settle.
    TooManyEvents {
        /// The guard's limit.
        max_events: u64,
        /// When it fired (τ).
        tau: f64,
    },
    /// More integrator step attempts than `Options::max_steps` by `tau`: the run does not end.
    TooManySteps {
        /// The guard's limit.
        max_steps: u64,
        /// When it fired (τ).
        tau: f64,
    },
    /// An option is outside its allowed range.
    InvalidOption(OptionError),
    /// The structure's model has no kernel variant for what was asked (the reason in words).
    NoVariant(String),
    /// The Taylor method was asked for a ground motion that gives no Taylor series.
    NoTaylorSeries,
    /// The mass matrix became singular while rocking: the integrator failed there (`cause`).
    SingularMassMatrix {
        /// When (τ).
        tau: f64,
        /// det M / (M_θθ M_uu) at the failure.
        conditioning: f64,
        /// u / u_cr at the failure.
        u_over_ucr: f64,
        /// The integrator's failure.
        cause: OdeError,
    },
}

impl SimError {
    /// Whether the run stopped on a guard of the options (`max_events`, `max_steps`).
    pub fn is_guard(&self) -> bool {
        matches!(
            self,
            SimError::TooManyEvents { .. } | SimError::TooManySteps { .. }
        )
    }

    /// Whether the caller asked for something invalid (options, variant, method), rather than
    /// the run failing.
    pub fn is_invalid_input(&self) -> bool {
        matches!(
            self,
            SimError::InvalidOption(_) | SimError::NoVariant(_) | SimError::NoTaylorSeries
        )
    }
}

impl std::fmt::Display for SimError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            SimError::Integration(e) => write!(f, "{e}"),
            SimError::TooManyEvents { max_events, tau } => write!(
                f,
                "more than {max_events} events by τ = {tau:.6}: the run does not settle (raise \
                 max_events, or the rest rate)"
            ),
            SimError::TooManySteps { max_steps, tau } => write!(
                f,
                "more than {max_steps} integrator steps by τ = {tau:.6}: the run does not end \
                 (raise max_steps)"
            ),
            SimError::InvalidOption(e) => write!(f, "{e}"),
            SimError::NoVariant(why) => f.write_str(why),
            SimError::NoTaylorSeries => f.write_str(
                "method = taylor needs the excitation's Taylor series, which this motion does not \
                 give (a motion whose GroundMotion::accel_series returns false): use dop853, or \
                 Preset::accuracy_for, which does for this motion",
            ),
            SimError::SingularMassMatrix {
                tau,
                conditioning,
                u_over_ucr,
                cause,
            } => write!(
                f,
                "the mass matrix became singular at τ = {tau:.6} (det M / (M_θθ M_uu) = \
                 {conditioning:.1e}, u/u_cr = {u_over_ucr:.1}): with a massless column the top \
                 mass is then above the pivot and θ and u cannot be told apart; such deflections \
                 are far outside the model's validity ({cause})"
            ),
        }
    }
}

impl std::error::Error for SimError {}

impl From<OdeError> for SimError {
    fn from(e: OdeError) -> Self {
        SimError::Integration(e)
    }
}

impl From<OptionError> for SimError {
    fn from(e: OptionError) -> Self {
        SimError::InvalidOption(e)
    }
}
