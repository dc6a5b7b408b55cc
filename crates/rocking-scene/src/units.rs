//! How a scene's model units relate to τ, g tan α, g and seconds.

/// How model units relate to τ, g tan α and seconds.
#[derive(Clone, Copy, Debug)]
pub struct Units {
    /// Physical (SI) structure.
    pub physical: bool,
    /// g in model units (1 for a dimensionless structure).
    pub g_model: f64,
    /// g in m/s²: the structure's g, or standard gravity for a dimensionless one (it relates its
    /// R and p, and converts a record in absolute units).
    pub g_si: f64,
    /// p in model units (1/model time).
    pub p_model: f64,
    /// Seconds per model time unit, when known.
    pub sec_per_unit: Option<f64>,
    /// tan α.
    pub tan_alpha: f64,
    /// α.
    pub alpha: f64,
}

impl Units {
    /// Setup acceleration of `a` in units of g tan α.
    pub fn accel_g_tan_alpha(&self) -> f64 {
        self.g_model * self.tan_alpha
    }
}
