//! The checks every numeric key goes through: finite and in its range, and finite once formed
//! into model units (an accepted input times a large scale can overflow).

use rocking::ParamError;

use crate::scene::{describe, Source};
use crate::SceneError;

/// A finite number check with the scene path in the message.
pub(crate) fn finite(
    src: &Source,
    path: &str,
    v: f64,
    cond: bool,
    allowed: &str,
) -> Result<f64, SceneError> {
    if v.is_finite() && cond {
        Ok(v)
    } else {
        Err(src.not_allowed(path, v, allowed))
    }
}

/// A value formed from the key `path` (a product with the structure's scales) must be finite:
/// an accepted input times a large scale can overflow.
pub(crate) fn formed(
    src: &Source,
    path: &str,
    given: f64,
    v: f64,
    what: &str,
) -> Result<f64, SceneError> {
    if v.is_finite() {
        Ok(v)
    } else {
        Err(src.err(
            path,
            format_args!(
                "{} = {} is too large: the {what} it gives overflows (not finite)",
                describe(path),
                crate::limits::short(given)
            ),
        ))
    }
}

/// A model parameter the solver refused, as an input error at its key.
pub(crate) fn param_err(src: &Source, table: &str, e: ParamError) -> SceneError {
    // ParamError's own Display prints 1e308 with 309 digits: the value in short form here.
    let value = crate::limits::short(e.value);
    src.err(
        &format!("{table}.{}", e.parameter),
        format_args!(
            "[{table}] `{}` = {value} is not allowed: {}",
            e.parameter, e.allowed
        ),
    )
    .with_value(value, e.allowed)
}
