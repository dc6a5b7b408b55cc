//! The `[effects]` keys that choose a model of the solver's: the impact model (a name or a
//! restitution table) and the overturning angle.

use std::f64::consts::{FRAC_PI_2, PI};

use rocking::ImpactModel;
use toml::Value;

use crate::check::finite;
use crate::scene::Source;
use crate::SceneError;

pub(crate) fn impact_model(src: &Source, v: Option<&Value>) -> Result<ImpactModel, SceneError> {
    let names: Vec<&str> = ImpactModel::NAMED.iter().map(|m| m.name()).collect();
    let quoted: Vec<String> = names.iter().map(|n| format!("\"{n}\"")).collect();
    let allowed = format!(
        "expected {} or {{ restitution = r }} with 0 <= r <= 1",
        quoted.join(", ")
    );
    let path = "effects.impact";
    match v {
        None => Ok(ImpactModel::Vvel),
        Some(Value::String(s)) => {
            let wanted = s.to_lowercase();
            ImpactModel::NAMED
                .into_iter()
                .find(|m| m.name() == wanted)
                .ok_or_else(|| {
                    let hint = crate::scene::suggest(&wanted, &names)
                        .map(|s| format!("; did you mean \"{s}\"?"))
                        .unwrap_or_default();
                    src.err(
                        path,
                        format_args!("`impact` = \"{s}\" is not allowed: {allowed}{hint}"),
                    )
                    .with_value(s, allowed.clone())
                })
        }
        Some(Value::Table(t)) => {
            if let Some(k) = t.keys().find(|k| *k != "restitution") {
                return Err(src.err(
                    path,
                    format_args!("unknown key `{k}` in `impact`: {allowed}"),
                ));
            }
            let r = match t.get("restitution") {
                Some(Value::Float(r)) => *r,
                Some(Value::Integer(r)) => *r as f64,
                _ => return Err(src.err(path, format_args!("`impact`: {allowed}"))),
            };
            finite(
                src,
                "effects.impact.restitution",
                r,
                (0.0..=1.0).contains(&r),
                "a coefficient of restitution 0 <= r <= 1",
            )
            .map(ImpactModel::Restitution)
        }
        Some(other) => Err(src.err(
            path,
            format_args!("`impact` = {other} is not allowed: {allowed}"),
        )),
    }
}

pub(crate) fn overturn_angle(src: &Source, v: Option<&Value>) -> Result<f64, SceneError> {
    const ALLOWED: &str = "an angle in rad with 0 < angle <= pi/2, or \"pi/2\", \"pi/N\"";
    let path = "effects.overturn";
    let angle = match v {
        None => return Ok(FRAC_PI_2),
        Some(Value::Float(a)) => *a,
        Some(Value::Integer(a)) => *a as f64,
        Some(Value::String(s)) => {
            let t = s.trim().to_lowercase().replace(' ', "");
            if t == "pi" {
                PI
            } else if let Some(n) = t.strip_prefix("pi/").and_then(|n| n.parse::<f64>().ok()) {
                PI / n
            } else if let Ok(x) = t.parse::<f64>() {
                x
            } else {
                return Err(src.err(
                    path,
                    format_args!("`overturn` = \"{s}\" is not allowed: {ALLOWED}"),
                ));
            }
        }
        Some(other) => {
            return Err(src.err(
                path,
                format_args!("`overturn` = {other} is not allowed: {ALLOWED}"),
            ))
        }
    };
    finite(
        src,
        path,
        angle,
        angle > 0.0 && angle <= FRAC_PI_2 + 1e-12,
        ALLOWED,
    )
}
