//! Why a fit, a bootstrap or a scaling could not be done: the argument that was wrong with its
//! value and range, or why the data have no estimate, with the counts that say so.

use std::fmt;

use rocking_motion::ParameterError;

use crate::ScalingIm;

/// Why a fit, a bootstrap or a scaling could not be done.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum FragilityError {
    /// An argument is invalid.
    InvalidParameter(ArgumentError),
    /// The data have no finite maximum-likelihood estimate (no collapse, only collapses,
    /// complete separation, ...).
    NoEstimate(NoFit),
}

/// An invalid argument of a fit, a bootstrap or a scaling.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum ArgumentError {
    /// `function`'s `parameter` (element `index` of it, for a slice) outside its range.
    OutOfRange {
        /// The function (`bootstrap`, `fit_capacities`, `scale_factor`).
        function: &'static str,
        /// The argument.
        parameter: &'static str,
        /// The element of a slice argument.
        index: Option<usize>,
        /// The value given.
        value: f64,
        /// What is allowed, with the argument's name (`1 <= resamples <= 100000`).
        allowed: String,
    },
    /// Fewer elements than the fit needs.
    TooFew {
        /// The function (`fit_capacities`, `fit_stripes`).
        function: &'static str,
        /// What is counted (`capacities`, `stripes`).
        what: &'static str,
        /// The fewest the fit takes.
        needed: usize,
        /// How many were given.
        found: usize,
    },
    /// A stripe's intensity level is not positive and finite.
    StripeIm {
        /// The stripe.
        index: usize,
        /// Its intensity level.
        im: f64,
    },
    /// A stripe's counts are not 0 ≤ collapsed ≤ n, n ≥ 1.
    StripeCounts {
        /// The stripe.
        index: usize,
        /// Its collapses.
        collapsed: u32,
        /// Its runs.
        n: u32,
    },
    /// The record's intensity measure is not positive: nothing to scale.
    Unscalable {
        /// The measure.
        im: ScalingIm,
        /// The record's value of it.
        value: f64,
        /// The target it was to be scaled to.
        target: f64,
    },
    /// The intensity measure's own arguments (period, damping).
    Intensity(ParameterError),
}

/// Why data have no finite maximum-likelihood fragility fit.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum NoFit {
    /// Every capacity is the same: β = 0.
    EqualCapacities {
        /// The capacity.
        capacity: f64,
    },
    /// No run collapsed, or every run did.
    AllOrNone {
        /// The runs that collapsed.
        collapsed: u32,
        /// All runs.
        runs: u32,
    },
    /// The stripes separate survival from collapse completely: β → 0.
    Separated {
        /// The highest intensity level with a run that survived.
        max_survived: f64,
        /// The lowest intensity level with a run that collapsed.
        min_collapsed: f64,
    },
    /// Every stripe is at the same intensity level: β undetermined.
    SameIm {
        /// The level.
        im: f64,
    },
    /// The Newton iteration of the stripe fit did not converge.
    NotConverged,
    /// The fitted probability of collapse falls as the IM grows.
    Falling {
        /// The probit slope b (≤ 0 or NaN).
        slope: f64,
    },
    /// No bootstrap resample had a finite fit.
    NoResample {
        /// The resamples tried.
        resamples: usize,
    },
}

impl fmt::Display for FragilityError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            FragilityError::InvalidParameter(e) => write!(f, "invalid parameter: {e}"),
            FragilityError::NoEstimate(e) => write!(f, "no estimate: {e}"),
        }
    }
}

impl fmt::Display for ArgumentError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ArgumentError::OutOfRange {
                function,
                parameter,
                index,
                value,
                allowed,
            } => {
                write!(f, "{function}: expected {allowed}, found {parameter}")?;
                if let Some(i) = index {
                    write!(f, "[{i}]")?;
                }
                write!(f, " = {value}")
            }
            ArgumentError::TooFew {
                function,
                what,
                needed,
                found,
            } => write!(
                f,
                "{function}: expected at least {needed} {what}, found {found}"
            ),
            ArgumentError::StripeIm { index, im } => write!(
                f,
                "fit_stripes: expected stripes[{index}].im > 0 and finite, found {im}"
            ),
            ArgumentError::StripeCounts {
                index,
                collapsed,
                n,
            } => write!(
                f,
                "fit_stripes: expected 0 <= stripes[{index}].collapsed <= stripes[{index}].n, \
                 n >= 1, found collapsed = {collapsed}, n = {n}"
            ),
            ArgumentError::Unscalable { im, value, target } => write!(
                f,
                "scale_factor: the record's {im:?} is {value}: it cannot be scaled to {target}"
            ),
            ArgumentError::Intensity(e) => write!(f, "{e}"),
        }
    }
}

impl fmt::Display for NoFit {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            NoFit::EqualCapacities { .. } => {
                f.write_str("fit_capacities: all capacities are equal, so beta = 0")
            }
            NoFit::AllOrNone { collapsed, runs } => write!(
                f,
                "fit_stripes: {collapsed} of {runs} runs collapsed: no finite maximum-likelihood \
                 fit"
            ),
            NoFit::Separated {
                max_survived,
                min_collapsed,
            } => write!(
                f,
                "fit_stripes: every run up to IM {max_survived} survived and every run from \
                 {min_collapsed} collapsed: beta -> 0, no finite maximum-likelihood fit"
            ),
            NoFit::SameIm { .. } => {
                f.write_str("fit_stripes: every stripe is at the same IM: beta is undetermined")
            }
            NoFit::NotConverged => f.write_str("fit_stripes: Newton iteration did not converge"),
            NoFit::Falling { slope } => write!(
                f,
                "fit_stripes: the fitted probability of collapse falls as the IM grows \
                 (slope {slope}): not a fragility curve"
            ),
            NoFit::NoResample { resamples } => write!(
                f,
                "bootstrap: none of the {resamples} resamples had a finite fit"
            ),
        }
    }
}

impl std::error::Error for FragilityError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            FragilityError::InvalidParameter(ArgumentError::Intensity(e)) => Some(e),
            _ => None,
        }
    }
}

impl std::error::Error for ArgumentError {}

impl std::error::Error for NoFit {}

impl From<ArgumentError> for FragilityError {
    fn from(e: ArgumentError) -> Self {
        FragilityError::InvalidParameter(e)
    }
}

impl From<NoFit> for FragilityError {
    fn from(e: NoFit) -> Self {
        FragilityError::NoEstimate(e)
    }
}
