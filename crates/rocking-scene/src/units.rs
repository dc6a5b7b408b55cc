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

/// What a run's quantities are normalised by: computed once when the scene is built, so that
/// every table, figure and the animation divide by the same numbers (the report's column list,
/// `rocking_study::report`, says which quantity uses which).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Scales {
    /// The slenderness α (rad).
    pub alpha: f64,
    /// The frequency parameter p = sqrt(g/R), model units.
    pub p: f64,
    /// The column's top deflection at static uplift.
    pub u_cr: f64,
    /// The fixed-base frequency ω_n, model units.
    pub omega_n: f64,
    /// The critical angle θ_cr of the rigid structure.
    pub theta_cr: f64,
    /// The reference energy E_ref.
    pub e_ref: f64,
    /// The total weight W.
    pub weight: f64,
    /// W B, the base moment at which the base uplifts.
    pub uplift_moment: f64,
    /// g tan α, the rigid block's uplift acceleration, model units.
    pub g_tan_alpha: f64,
    /// p in 1/s, when the scene has a time scale.
    pub p_per_second: Option<f64>,
    /// Seconds per model time unit, when known ([`Units::sec_per_unit`]).
    sec_per_unit: Option<f64>,
    /// On compliant ground, its settlement and pressure scales.
    pub ground: Option<GroundScales>,
}

/// What a compliant ground's history columns are normalised by.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GroundScales {
    /// The static settlement v₀ = W / K_v.
    pub settlement: f64,
    /// The mean pressure W / (2B) (two springs: the corner force W / 2).
    pub mean_pressure: f64,
}

impl Scales {
    /// The scales of `structure` (its derived quantities `d`) measured in `units`, on `ground`
    /// (`None`: the rigid surface).
    pub fn of(
        structure: &rocking::Structure,
        d: &rocking::Derived,
        units: &Units,
        ground: Option<&rocking::Ground>,
    ) -> Scales {
        let lift = structure.static_uplift();
        Scales {
            alpha: units.alpha,
            p: d.p,
            u_cr: d.u_cr,
            omega_n: d.omega_n,
            theta_cr: d.theta_cr,
            e_ref: d.e_ref,
            weight: lift.weight,
            uplift_moment: lift.moment,
            g_tan_alpha: units.accel_g_tan_alpha(),
            p_per_second: structure.p_per_second(),
            sec_per_unit: units.sec_per_unit,
            ground: ground.map(|g| GroundScales {
                settlement: g.statics(lift.weight).settlement,
                mean_pressure: g.mean_pressure(lift.weight),
            }),
        }
    }

    /// Seconds per unit of τ, when the scene knows its time in seconds.
    pub fn seconds_per_tau(&self) -> Option<f64> {
        self.sec_per_unit.map(|s| s / self.p)
    }
}
