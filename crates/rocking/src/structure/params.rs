//! A structure's parameters checked: the error that names one and its allowed range, the
//! registry's models by name, and the values of the parameters a model adds, by their role.

use std::fmt;

use rocking_kernels::kernels::MAX_PARAMS;
use rocking_kernels::{ModelInfo, ParamInfo, Physical, Role};

/// An invalid parameter: its name, the value given and what is allowed.
#[derive(Clone, Debug, PartialEq)]
pub struct ParamError {
    /// Parameter name (as in scene files).
    pub parameter: &'static str,
    /// The value that was given.
    pub value: f64,
    /// The allowed range, in words.
    pub allowed: String,
}

impl fmt::Display for ParamError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "`{}` = {} is not allowed: {}",
            self.parameter, self.value, self.allowed
        )
    }
}

impl std::error::Error for ParamError {}

pub(super) fn check(
    parameter: &'static str,
    value: f64,
    ok: bool,
    allowed: &'static str,
) -> Result<(), ParamError> {
    if ok && value.is_finite() {
        Ok(())
    } else {
        Err(ParamError {
            parameter,
            value,
            allowed: allowed.to_string(),
        })
    }
}

/// The generated model called `name`.
pub fn find_model(name: &str) -> Result<&'static ModelInfo, ParamError> {
    ModelInfo::find(name).ok_or_else(|| ParamError {
        parameter: "model",
        value: f64::NAN,
        allowed: format!(
            "`{name}` is not a generated model; the models are {}",
            model_names().join(", ")
        ),
    })
}

/// The names of every generated model.
pub fn model_names() -> Vec<&'static str> {
    rocking_kernels::kernels::MODELS
        .iter()
        .map(|m| m.name)
        .collect()
}

/// Why a model of several deformation coordinates needs a column mass.
pub(super) const SEVERAL_NEED_COLUMN_MASS: &str =
    "a column mass m_c > 0 for a model of several deformation \
    coordinates (without it only the top mass weighs them: their mass matrix is singular)";

/// Checks the value of a parameter a model adds, by its role.
pub(super) fn check_extra(p: &'static ParamInfo, v: f64) -> Result<(), ParamError> {
    match p.role {
        Role::Mass { .. } => check(p.name, v, v >= 0.0, "a mass >= 0"),
        Role::InertiaOf(_) => check(p.name, v, v >= 0.0, "an inertia >= 0"),
        Role::HeightOf(_) => check(
            p.name,
            v,
            (0.0..=1.0).contains(&v),
            "a height 0 <= eta <= 1 (a fraction of the column height H)",
        ),
        Role::Other | Role::ModalDamping => check(p.name, v, true, "a finite value"),
    }
}

/// The values of the parameters `model` adds: the `given` (name, value) pairs, defaults for the
/// rest. A name the model does not add is an error.
pub(super) fn extra_values(
    model: &'static ModelInfo,
    given: &[(&str, f64)],
) -> Result<([f64; MAX_PARAMS], usize), ParamError> {
    if let Some((k, v)) = given
        .iter()
        .find(|(k, _)| model.extra_params().all(|p| p.name != *k))
    {
        return Err(ParamError {
            parameter: "model",
            value: *v,
            allowed: format!(
                "model `{}` has no parameter `{k}` of its own (it adds: {})",
                model.name,
                model
                    .extra_params()
                    .map(|p| p.name)
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
        });
    }
    let mut out = [0.0; MAX_PARAMS];
    let mut n = 0;
    for p in model.extra_params() {
        out[n] = p.default.unwrap_or(0.0);
        if let Some(&(_, v)) = given.iter().find(|(k, _)| *k == p.name) {
            check_extra(p, v)?;
            out[n] = v;
        }
        n += 1;
    }
    Ok((out, n))
}

/// The field of [`Physical`] called `name`.
pub(super) fn core_field<'a>(ph: &'a mut Physical, name: &str) -> Option<&'a mut f64> {
    Some(match name {
        "h" => &mut ph.h,
        "b" => &mut ph.b,
        "ei" => &mut ph.ei,
        "m" => &mut ph.m,
        "m_c" => &mut ph.m_c,
        "m_b" => &mut ph.m_b,
        "i_bc" => &mut ph.i_bc,
        "zeta" => &mut ph.zeta,
        "g" => &mut ph.g,
        _ => return None,
    })
}
