//! Why a run failed: one variant per thing that can go wrong, with what the caller needs to say
//! so (the scene layer adds the file and the settings that bound the run).

use rocking_ode::OdeError;

use crate::structure::ParamError;

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
    /// The structure and effects select no kernel variant of the structure's model
    /// ([`select_variant`](crate::select_variant)'s error: a mass the model cannot switch off,
    /// or no rigid or small-angle variant).
    NoVariant(ParamError),
    /// No generated kernel variant is called `name` (of the structure's model `model`, when
    /// the caller named the variant).
    UnknownVariant {
        /// The variant asked for.
        name: String,
        /// The structure's model, when the variant was asked for by name for it.
        model: Option<&'static str>,
    },
    /// On compliant ground the variant's mass matrix over (θ, v, u) is singular: point masses
    /// on the column axis alone have no rotational inertia once the base may sink.
    SingularOnGround {
        /// The variant.
        variant: &'static str,
        /// The run's relative pivot of M at rest (≤ 1e-12, or NaN); `None` when the
        /// small-vibration analysis found M not positive definite (its Cholesky factor failed).
        pivot: Option<f64>,
    },
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
            SimError::InvalidOption(_)
                | SimError::NoVariant(_)
                | SimError::UnknownVariant { .. }
                | SimError::SingularOnGround { .. }
                | SimError::NoTaylorSeries
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
            SimError::NoVariant(e) => write!(f, "{e}"),
            SimError::UnknownVariant { name, model } => {
                write!(f, "no kernel variant `{name}`")?;
                match model {
                    Some(m) => write!(f, " of model `{m}`"),
                    None => Ok(()),
                }
            }
            SimError::SingularOnGround {
                variant,
                pivot: Some(_),
            } => write!(
                f,
                "variant `{variant}` on compliant ground: its mass matrix over (θ, v, u) is \
                 singular (point masses on the column axis have no rotational inertia once the \
                 base may sink): give the base or the column a mass (gamma_mb > 0 or gamma_mc > 0)"
            ),
            SimError::SingularOnGround {
                variant,
                pivot: None,
            } => write!(
                f,
                "variant `{variant}` on compliant ground: its mass matrix over (θ, v, u) is not \
                 positive definite (point masses on the column axis have no rotational inertia \
                 once the base may sink): give the base or the column a mass"
            ),
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

impl std::error::Error for SimError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            SimError::NoVariant(e) => Some(e),
            _ => None,
        }
    }
}

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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{
        run_variant, select_variant, simulate, simulate_on_ground, DampingConvention,
        Dimensionless, Effects, Ground, GroundKind, Options, Structure,
    };
    use rocking_motion::NoMotion;

    /// R = g = m = 1, α = 0.2, ω_n/p = 20, no column mass.
    fn structure(gamma_mb: f64) -> Structure {
        let d = Dimensionless {
            omega_n_over_p: 20.0,
            alpha: 0.2,
            gamma_mc: 0.0,
            gamma_mb,
            gamma_ib: 1.0,
            zeta: 0.0,
            damping: DampingConvention::FixedBase,
        };
        Structure::from_dimensionless(&d, None).unwrap()
    }

    fn bed(s: &Structure) -> Ground {
        Ground::from_vertical(GroundKind::Winkler, s.param("b").unwrap(), 400.0, 0.0)
    }

    /// A mass the model cannot switch off: the selector's error, typed, as the source.
    #[test]
    fn a_mass_the_model_lacks_is_no_variant_with_the_selectors_error() {
        let s = structure(0.5);
        let fx = Effects::default().without_mass("m_nowhere");
        let e = simulate(&s, &NoMotion, &fx, &Options::default()).unwrap_err();
        let SimError::NoVariant(p) = &e else {
            panic!("expected NoVariant, got {e:?}");
        };
        assert_eq!(p.parameter, "m_nowhere");
        assert!(p.allowed.contains("is not a mass model"), "{}", p.allowed);
        // The words are the selector's own, and the selector's error is the source.
        let direct = select_variant(&s, &fx).unwrap_err();
        assert_eq!(e.to_string(), direct.to_string());
        let source = std::error::Error::source(&e).expect("a source");
        assert_eq!(source.to_string(), direct.to_string());
        assert!(e.is_invalid_input());
    }

    /// A variant name the registry does not hold, or another model's variant.
    #[test]
    fn an_unknown_variant_carries_its_name_and_the_model() {
        let s = structure(0.5);
        let e = run_variant("no_such_variant", &s, &NoMotion, &Options::default()).unwrap_err();
        let model = s.model().name;
        assert_eq!(
            e,
            SimError::UnknownVariant {
                name: "no_such_variant".to_string(),
                model: Some(model),
            }
        );
        assert_eq!(
            e.to_string(),
            format!("no kernel variant `no_such_variant` of model `{model}`")
        );
        assert!(e.is_invalid_input());
        let bare = SimError::UnknownVariant {
            name: "x".into(),
            model: None,
        };
        assert_eq!(bare.to_string(), "no kernel variant `x`");
    }

    /// Point masses on the column axis alone on compliant ground: the run refuses with the
    /// pivot it found, the small-vibration analysis without one; the words are today's.
    #[test]
    fn point_masses_on_compliant_ground_are_singular_with_the_variant() {
        let s = structure(0.0);
        let fx = Effects::default();
        let g = bed(&s);
        let e = simulate_on_ground(&s, &g, &NoMotion, &fx, &Options::default()).unwrap_err();
        let SimError::SingularOnGround { variant, pivot } = e else {
            panic!("expected SingularOnGround, got {e:?}");
        };
        let selected = select_variant(&s, &fx).unwrap().variant.name;
        assert_eq!(variant, selected);
        let pivot = pivot.expect("the run's pivot");
        assert!(pivot.is_nan() || pivot <= 1e-12, "pivot {pivot}");
        assert_eq!(
            e.to_string(),
            format!(
                "variant `{selected}` on compliant ground: its mass matrix over (θ, v, u) is \
                 singular (point masses on the column axis have no rotational inertia once the \
                 base may sink): give the base or the column a mass (gamma_mb > 0 or \
                 gamma_mc > 0)"
            )
        );
        let m = crate::ground_modes::small_vibrations(&s, &fx, &g).unwrap_err();
        assert_eq!(
            m,
            SimError::SingularOnGround {
                variant: selected,
                pivot: None
            }
        );
        assert_eq!(
            m.to_string(),
            format!(
                "variant `{selected}` on compliant ground: its mass matrix over (θ, v, u) is not \
                 positive definite (point masses on the column axis have no rotational inertia \
                 once the base may sink): give the base or the column a mass"
            )
        );
        assert!(e.is_invalid_input() && m.is_invalid_input());
    }
}
