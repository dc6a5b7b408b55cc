//! The axes of a sweep: a key path and its values, numbers or texts, and the bounds on them.

/// One axis of a sweep: a scene key path and its values, numbers or texts (`structure.model =
/// cubic, cantilever_modes2`). A text axis's cells carry the index of their text as their value,
/// so that every cell is a list of numbers; tables write the text.
#[derive(Clone, Debug, PartialEq)]
pub struct Axis {
    /// Key path in the scene, e.g. `excitation.omega_p_over_p`.
    pub key: String,
    /// Values, in sweep order (for a text axis the indices 0, 1, … of its texts).
    pub values: Vec<f64>,
    /// The texts of a text axis, in sweep order; empty for a numeric axis.
    pub texts: Vec<String>,
}

/// The most values one axis may have (each is validated and run: far more than a plot shows).
pub const MAX_AXIS_VALUES: usize = 100_000;

/// The most cells a sweep may have (its journal, cells.csv and the cells in memory grow with it).
pub const MAX_CELLS: usize = 1_000_000;

impl Axis {
    /// A numeric axis.
    pub fn numbers(key: impl Into<String>, values: Vec<f64>) -> Axis {
        Axis {
            key: key.into(),
            values,
            texts: Vec::new(),
        }
    }

    /// Whether the axis holds texts.
    pub fn is_text(&self) -> bool {
        !self.texts.is_empty()
    }

    /// The text of a text axis's cell value (its index); `None` on a numeric axis.
    pub fn text(&self, value: f64) -> Option<&str> {
        self.texts.get(value as usize).map(String::as_str)
    }

    /// A cell's value as tables write it: the text of a text axis, else the number.
    pub fn display(&self, value: f64) -> String {
        match self.text(value) {
            Some(t) => t.to_string(),
            None => value.to_string(),
        }
    }

    /// The axis as a spec [`Axis::parse`] reads back to the same axis: its texts, or its
    /// numbers written exactly (`{:?}` round-trips an f64).
    pub fn spec(&self) -> String {
        let values: Vec<String> = if self.is_text() {
            self.texts.clone()
        } else {
            self.values.iter().map(|v| format!("{v:?}")).collect()
        };
        format!("{}={}", self.key, values.join(","))
    }

    /// `key=start:stop:count` (count points from start to stop inclusive) or `key=v1,v2,...`:
    /// numbers, or texts (a list of which one is not a number: `structure.model=cubic,
    /// cantilever_modes2`; distinct, without commas).
    pub fn parse(spec: &str) -> Result<Axis, String> {
        let (key, range) = spec.split_once('=').ok_or_else(|| {
            format!("axis `{spec}`: expected key=start:stop:count or key=v1,v2,...")
        })?;
        let key = key.trim().to_string();
        if key.is_empty() {
            return Err(format!("axis `{spec}`: empty key"));
        }
        let num = |s: &str| -> Result<f64, String> {
            let v: f64 = s
                .trim()
                .parse()
                .map_err(|_| format!("axis `{spec}`: `{s}` is not a number"))?;
            if v.is_finite() {
                Ok(v)
            } else {
                Err(format!("axis `{spec}`: `{s}` is not finite"))
            }
        };
        let values = if range.contains(':') {
            let parts: Vec<&str> = range.split(':').collect();
            if parts.len() != 3 {
                return Err(format!("axis `{spec}`: expected start:stop:count"));
            }
            let (a, b) = (num(parts[0])?, num(parts[1])?);
            // A count may be written as a float (`1e4`) when it is a whole number.
            let count = parts[2].trim();
            let n: usize = count
                .parse()
                .ok()
                .or_else(|| {
                    let x: f64 = count.parse().ok()?;
                    (x.fract() == 0.0 && x >= 0.0).then(|| x.min(usize::MAX as f64) as usize)
                })
                .ok_or_else(|| {
                    format!(
                        "axis `{spec}`: count `{}` is not a positive integer",
                        parts[2]
                    )
                })?;
            if n > MAX_AXIS_VALUES {
                return Err(format!(
                    "axis `{spec}`: count {n} is too large: at most {MAX_AXIS_VALUES} values per axis"
                ));
            }
            match n {
                0 => return Err(format!("axis `{spec}`: count must be at least 1")),
                1 => vec![a],
                _ => (0..n)
                    .map(|i| a + (b - a) * i as f64 / (n - 1) as f64)
                    .collect(),
            }
        } else {
            let items: Vec<&str> = range.split(',').map(str::trim).collect();
            if items.len() > MAX_AXIS_VALUES {
                return Err(format!(
                    "axis `{}`: {} values are too many: at most {MAX_AXIS_VALUES} values per axis",
                    key,
                    items.len()
                ));
            }
            if items.iter().any(|t| t.parse::<f64>().is_err()) {
                return Axis::texts(spec, key, &items);
            }
            items.into_iter().map(num).collect::<Result<Vec<_>, _>>()?
        };
        Ok(Axis::numbers(key, values))
    }

    /// A text axis of `items` (from `spec`): each non-empty and given once.
    fn texts(spec: &str, key: String, items: &[&str]) -> Result<Axis, String> {
        for (i, t) in items.iter().enumerate() {
            if t.is_empty() {
                return Err(format!("axis `{spec}`: value {} is empty", i + 1));
            }
            if items[..i].contains(t) {
                return Err(format!("axis `{spec}`: `{t}` is given twice"));
            }
        }
        Ok(Axis {
            key,
            values: (0..items.len()).map(|i| i as f64).collect(),
            texts: items.iter().map(|t| t.to_string()).collect(),
        })
    }
}
