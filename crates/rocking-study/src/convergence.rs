//! How many deformation coordinates a result needs: one scene run with each model of a list (a
//! sweep over the text axis `structure.model`), and for every quantity asked for, its value per
//! model, its change from the model before, and the first model from which it changes by less
//! than a tolerance. The answer a designer reads: "the peak base moment is converged to 1 % from
//! n = 4 on" (docs/modes.md), or "not converged within the list".

use std::path::Path;

use rocking::ModelInfo;
use rocking_scene::SceneError;

use crate::StudyError;
use rocking_spectra::{Axis, Outcome};

use crate::plan::{Base, Plan};

/// The quantities of a report when none are asked for: the rocking, the deflection and the
/// design forces (docs/design-forces.md).
pub const DEFAULT_QUANTITIES: &[&str] = &[
    "max_theta_over_alpha",
    "impacts",
    "max_u_over_ucr",
    "max_base_moment_over_wb",
    "max_base_shear_over_w",
    "max_elastic_base_moment_over_wb",
];

/// The default relative tolerance (1 %).
pub const DEFAULT_TOLERANCE: f64 = 0.01;

/// The most models one report compares (each is a whole run).
pub const MAX_MODELS: usize = 64;

/// The quantities every cell has without a report (the sweep's own columns).
const CELL_QUANTITIES: &[&str] = &["max_theta_over_alpha", "impacts"];

/// A planned report: the sweep over the models and what it reports.
pub struct Study {
    /// The sweep: one cell per model.
    pub plan: Plan,
    /// The models, in the order given, with their numbers of deformation coordinates.
    pub models: Vec<(String, usize)>,
    /// The quantities, in the order given.
    pub quantities: Vec<String>,
    /// The relative tolerance.
    pub tolerance: f64,
}

/// One quantity's convergence.
#[derive(Clone, Debug, PartialEq)]
pub struct Quantity {
    /// Its key, as in a run's summary.
    pub name: String,
    /// Its value per model (none where the run has no result).
    pub values: Vec<Option<f64>>,
    /// |v_k − v_{k−1}| / max(|v_k|, |v_{k−1}|) per model (none for the first, and next to a
    /// missing value; 0 when both are equal, 0 or both unbounded; 1 when one of them is
    /// unbounded and the other not).
    pub changes: Vec<Option<f64>>,
    /// The first model (its index) from which every later change is below the tolerance; none
    /// when the last change is not, or a value is missing after it.
    pub converged_at: Option<usize>,
}

/// A finished report.
#[derive(Clone, Debug)]
pub struct Report {
    /// The models with their numbers of deformation coordinates.
    pub models: Vec<(String, usize)>,
    /// Per quantity, in the order asked.
    pub quantities: Vec<Quantity>,
    /// The relative tolerance.
    pub tolerance: f64,
    /// The models whose run has no result, with why (failed, or beyond the model).
    pub without_result: Vec<(String, String)>,
}

/// Plans the report of the scene file `scene` whose text is `text` (with overrides `sets`) over
/// `models`: each must exist, at least two, distinct, at most [`MAX_MODELS`]; `quantities`
/// (default [`DEFAULT_QUANTITIES`]) must be numbers a run reports; 0 < `tolerance` < 1.
pub fn plan(
    scene: &Path,
    text: String,
    sets: &[String],
    models: &[String],
    quantities: &[String],
    tolerance: f64,
) -> Result<Study, StudyError> {
    let bad = |what: &str, value: String, allowed: &str| {
        SceneError::input(format!(
            "{}: {what} = {value} is not allowed: {allowed}",
            scene.display()
        ))
    };
    if !(tolerance > 0.0 && tolerance < 1.0) {
        return Err(bad(
            "the tolerance",
            tolerance.to_string(),
            "a relative change 0 < tolerance < 1 (0.01 is 1 %)",
        )
        .into());
    }
    if models.len() < 2 || models.len() > MAX_MODELS {
        return Err(bad(
            "the models",
            models.join(","),
            &format!("from 2 to {MAX_MODELS} models, in the order to compare"),
        )
        .into());
    }
    let quantities: Vec<String> = if quantities.is_empty() {
        DEFAULT_QUANTITIES.iter().map(|q| q.to_string()).collect()
    } else {
        quantities.to_vec()
    };
    if let Some((i, q)) = quantities
        .iter()
        .enumerate()
        .find(|(i, q)| quantities[..*i].contains(q))
    {
        return Err(bad(
            &format!("quantity {}", i + 1),
            q.clone(),
            "each quantity once",
        )
        .into());
    }
    // The quantities beyond the cell's own are the sweep's report, checked by the plan.
    let report: Vec<&String> = quantities
        .iter()
        .filter(|q| !CELL_QUANTITIES.contains(&q.as_str()))
        .collect();
    let mut sets = sets.to_vec();
    sets.push(format!("sweep.report={}", serde_json::json!(report)));
    let axis = Axis {
        key: "structure.model".into(),
        values: (0..models.len()).map(|i| i as f64).collect(),
        texts: models.to_vec(),
    };
    // The plan runs the scene with every model before any cell: an unknown one is refused
    // there, naming the models there are.
    let plan = Plan::spectrum(Base::from_text(scene, text, &sets)?, &[axis.spec()])?;
    let listed = models
        .iter()
        .map(|m| match ModelInfo::find(m) {
            Some(info) => Ok((m.clone(), info.coordinates)),
            None => Err(bad("a model", m.clone(), "a model of `rocking models`")),
        })
        .collect::<Result<Vec<_>, _>>()?;
    Ok(Study {
        plan,
        models: listed,
        quantities,
        tolerance,
    })
}

impl Study {
    /// The report from the sweep's outcome (its cells in model order).
    pub fn report(&self, outcome: &Outcome) -> Report {
        let reported = self.plan.base.report();
        let value = |k: usize, q: &str| -> Option<f64> {
            let c = outcome.cells.get(k)?;
            if !c.class.has_result() {
                return None;
            }
            match q {
                "max_theta_over_alpha" => Some(c.max_theta_over_alpha),
                "impacts" => Some(c.impacts as f64),
                _ => reported
                    .iter()
                    .position(|r| r == q)
                    .and_then(|i| c.reported.get(i).copied().flatten()),
            }
        };
        let quantities = self
            .quantities
            .iter()
            .map(|q| {
                let values: Vec<Option<f64>> =
                    (0..self.models.len()).map(|k| value(k, q)).collect();
                converge(q, values, self.tolerance)
            })
            .collect();
        let mut without_result = Vec::new();
        for (i, m) in outcome.failures.iter().chain(&outcome.beyond_model) {
            without_result.push((self.models[*i].0.clone(), m.clone()));
        }
        without_result.sort();
        Report {
            models: self.models.clone(),
            quantities,
            tolerance: self.tolerance,
            without_result,
        }
    }
}

/// The changes of `values` and the first index from which all later ones stay below `tol`.
pub fn converge(name: &str, values: Vec<Option<f64>>, tol: f64) -> Quantity {
    let changes: Vec<Option<f64>> = (0..values.len())
        .map(|k| {
            let (a, b) = (values[k.checked_sub(1)?]?, values[k]?);
            let scale = a.abs().max(b.abs());
            // Two unbounded values (an `inf` max_required_friction) are the same answer; one
            // unbounded beside a finite one is the limit 1 of the relative change.
            Some(if scale == 0.0 || a == b {
                0.0
            } else if !scale.is_finite() {
                1.0
            } else {
                (b - a).abs() / scale
            })
        })
        .collect();
    // Walk back from the last model while the changes stay below the tolerance.
    let mut converged_at = None;
    for k in (1..values.len()).rev() {
        match changes[k] {
            Some(c) if c < tol => converged_at = Some(k - 1),
            _ => break,
        }
    }
    Quantity {
        name: name.to_string(),
        values,
        changes,
        converged_at,
    }
}

impl Report {
    /// `convergence.csv`: one row per quantity: its value per model (columns named by the
    /// models), the converged model and its n (empty when not converged) and the last change.
    pub fn csv(&self) -> String {
        let mut out = String::from("quantity");
        for (m, _) in &self.models {
            out.push(',');
            out.push_str(m);
        }
        out.push_str(",converged_model,converged_n,last_change,tolerance\n");
        let num = |v: Option<f64>| v.map_or(String::new(), |x| x.to_string());
        for q in &self.quantities {
            out.push_str(&q.name);
            for v in &q.values {
                out.push(',');
                out.push_str(&num(*v));
            }
            let (model, n) = match q.converged_at {
                Some(k) => (self.models[k].0.clone(), self.models[k].1.to_string()),
                None => (String::new(), String::new()),
            };
            let last = q.changes.last().copied().flatten();
            out.push_str(&format!(",{model},{n},{},{}\n", num(last), self.tolerance));
        }
        out
    }

    /// The report as JSON (`convergence.json`; Python's dictionary).
    pub fn json(&self) -> serde_json::Value {
        serde_json::json!({
            "models": self.models.iter().map(|(m, n)| serde_json::json!({"name": m, "n": n})).collect::<Vec<_>>(),
            "tolerance": self.tolerance,
            "quantities": self.quantities.iter().map(|q| serde_json::json!({
                "name": q.name,
                // JSON has no infinity: an unbounded value is "inf", as in the run's summary.
                "values": q.values.iter().map(|v| match v {
                    Some(x) if x.is_infinite() => serde_json::json!(rocking::UNBOUNDED),
                    v => serde_json::json!(v),
                }).collect::<Vec<_>>(),
                "changes": q.changes,
                "converged_model": q.converged_at.map(|k| &self.models[k].0),
                "converged_n": q.converged_at.map(|k| self.models[k].1),
            })).collect::<Vec<_>>(),
            "without_result": self.without_result.iter().map(|(m, why)| serde_json::json!({"model": m, "message": why})).collect::<Vec<_>>(),
        })
    }

    /// The table printed on stdout: a row per quantity, a column per model (n in the header),
    /// then where it converged.
    pub fn text(&self) -> String {
        let mut rows: Vec<Vec<String>> = Vec::new();
        let mut head = vec!["quantity".to_string()];
        head.extend(self.models.iter().map(|(m, n)| format!("{m} (n={n})")));
        head.push(format!("converged to {} % from", self.tolerance * 100.0));
        rows.push(head);
        for q in &self.quantities {
            let mut r = vec![q.name.clone()];
            r.extend(q.values.iter().map(|v| match v {
                None => "-".to_string(),
                Some(x) if x.fract() == 0.0 && x.abs() < 1e15 => format!("{x}"),
                Some(x) => format!("{x:.4}"),
            }));
            r.push(match q.converged_at {
                Some(k) => format!("n = {} ({})", self.models[k].1, self.models[k].0),
                None => "not converged".to_string(),
            });
            rows.push(r);
        }
        let widths: Vec<usize> = (0..rows[0].len())
            .map(|j| rows.iter().map(|r| r[j].chars().count()).max().unwrap_or(0))
            .collect();
        let mut out = String::new();
        for r in &rows {
            let cells: Vec<String> = r
                .iter()
                .zip(&widths)
                .map(|(c, w)| format!("{c:<w$}"))
                .collect();
            out.push_str(cells.join("  ").trim_end());
            out.push('\n');
        }
        for (m, why) in &self.without_result {
            out.push_str(&format!("no result for {m}: {why}\n"));
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::converge;

    #[test]
    fn converged_from_the_first_model_after_which_every_change_is_below_the_tolerance() {
        let q = converge(
            "m",
            vec![Some(1.0), Some(1.5), Some(1.52), Some(1.521), Some(1.5211)],
            0.01,
        );
        assert_eq!(q.converged_at, Some(2));
        assert_eq!(q.changes[0], None);
        assert!((q.changes[1].unwrap() - 0.5 / 1.5).abs() < 1e-15);
        // A late jump: not converged, whatever came before.
        let q = converge("m", vec![Some(1.0), Some(1.001), Some(1.2)], 0.01);
        assert_eq!(q.converged_at, None);
        // A missing value breaks the chain after it only.
        let q = converge("m", vec![Some(1.0), None, Some(2.0), Some(2.001)], 0.01);
        assert_eq!(q.converged_at, Some(2));
        assert_eq!(q.changes[1..3], [None, None]);
        // Zeros do not change.
        let q = converge("m", vec![Some(0.0), Some(0.0)], 0.01);
        assert_eq!(q.changes[1], Some(0.0));
        assert_eq!(q.converged_at, Some(0));
        // An unbounded value (max_required_friction after a lift-off): the same as another
        // unbounded one, a whole change from a finite one; never NaN.
        let inf = f64::INFINITY;
        let q = converge("f", vec![Some(0.5), Some(inf), Some(inf)], 0.01);
        assert_eq!(q.changes[1..], [Some(1.0), Some(0.0)]);
        assert_eq!(q.converged_at, Some(1));
    }
}
