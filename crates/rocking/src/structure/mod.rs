//! Structures of any generated model: its whole parameter set, physical (any consistent units) or
//! dimensionless (the paper's eq (34), R = g = m = 1), validated, with the derived quantities of
//! the model's own kernels.

use std::f64::consts::FRAC_PI_2;

use rocking_kernels::kernels::MAX_PARAMS;
use rocking_kernels::modes::{modal_damping, with_modal_damping, Matrices};
use rocking_kernels::{with_variant, Array, Layout, ModelInfo, Physical, Variant};
use serde::{Deserialize, Serialize};

mod derived;
mod params;

use derived::fixed_base_ratio;
pub use derived::{Derived, Frequencies};
use params::{check, check_extra, core_field, extra_values, SEVERAL_NEED_COLUMN_MASS};
pub use params::{find_model, model_names, ParamError};

/// The model of a structure that names none: the paper's (cubic shape function).
pub const PAPER_MODEL: &str = "cubic";

/// The most deformation coordinates of any generated model: the size of a structure's list of
/// damping ratios per mode.
pub const MAX_COORDINATES: usize = {
    let models = rocking_kernels::kernels::MODELS;
    let (mut most, mut k) = (1, 0);
    while k < models.len() {
        if models[k].coordinates > most {
            most = models[k].coordinates;
        }
        k += 1;
    }
    most
};

/// How the damping ratio ζ is meant.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum DampingConvention {
    /// ζ is the fixed-base damping ratio of the column (the paper's Figs 3 and 5).
    FixedBase,
    /// ζ is the uplifted damping ratio: the fixed-base ratio is ζ/S, eq (19) (the spectra, Sec. 3.1).
    /// With several deformation coordinates: the one fixed-base ratio of every mode that gives
    /// the first uplifted mode the ratio ζ.
    Uplifted,
}

/// The dimensionless groups of eq (34) that define a structure.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Dimensionless {
    /// ω_n / p, the fixed-base frequency over p = sqrt(g/R).
    pub omega_n_over_p: f64,
    /// Slenderness α = atan(B/H), rad.
    pub alpha: f64,
    /// γ_mc = m_c / m.
    pub gamma_mc: f64,
    /// γ_mb = m_b / m.
    pub gamma_mb: f64,
    /// γ_Ib = I_bc / (4/3 m_b B²), the base inertia over a thin plate's: 1 for a thin plate.
    pub gamma_ib: f64,
    /// Damping ratio, in the convention `damping`.
    pub zeta: f64,
    /// What `zeta` means.
    pub damping: DampingConvention,
}

/// A validated structure of one generated model: the fields of [`Physical`] plus the values of
/// the parameters the model adds (in the order of [`ModelInfo::extra_params`]). The solver runs in
/// the units of [`Structure::physical`]; a structure built from dimensionless groups uses
/// R = g = m = 1, so its time unit is τ = p t.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Structure {
    model: &'static ModelInfo,
    physical: Physical,
    extra: [f64; MAX_PARAMS],
    n_extra: usize,
    /// The fixed-base damping ratio of each mode, when they differ ([`Structure::with_modal_damping_ratios`]);
    /// otherwise every mode has `physical.zeta`.
    modal_zeta: Option<[f64; MAX_COORDINATES]>,
    /// p in 1/s when known (physical input, or dimensionless input with a length scale).
    p_per_second: Option<f64>,
}

fn paper_model() -> &'static ModelInfo {
    ModelInfo::find(PAPER_MODEL).expect("the paper's model is generated")
}

/// Runs `$body` with `$V` the model's full variant (its own kernels, nothing removed).
macro_rules! with_full {
    ($model:expr, $V:ident => $body:expr) => {
        with_variant!($model.full, $V, L => $body).expect("a model's full variant is generated")
    };
}

/// I_bc of a thin base plate, 4/3 m_b B², for `model` with these parameters (from its kernels):
/// the default base inertia.
pub fn plate_inertia(model: &'static ModelInfo, physical: &Physical) -> f64 {
    with_variant!(model.full, V, L => {
        V::structure_value(&V::structure(&V::params_with(physical, &[])), "i_bc_plate")
    })
    .expect("a model's full variant is generated")
}

impl Structure {
    /// A structure of the paper's model from physical parameters (any consistent units; SI gives
    /// seconds).
    pub fn from_physical(physical: Physical) -> Result<Structure, ParamError> {
        Structure::of_model(paper_model(), physical, &[])
    }

    /// A structure of `model` from physical parameters and the values of the parameters the model
    /// adds, by name (in the same units; missing ones take their defaults).
    pub fn of_model(
        model: &'static ModelInfo,
        physical: Physical,
        extra: &[(&str, f64)],
    ) -> Result<Structure, ParamError> {
        let (values, n_extra) = extra_values(model, extra)?;
        let mut s = Structure::checked(model, physical, values, n_extra, None)?;
        // Physical units: the model's time unit is the second.
        s.p_per_second = Some(s.derived().p);
        Ok(s)
    }

    fn checked(
        model: &'static ModelInfo,
        physical: Physical,
        extra: [f64; MAX_PARAMS],
        n_extra: usize,
        p_per_second: Option<f64>,
    ) -> Result<Structure, ParamError> {
        let p = physical;
        check("h", p.h, p.h > 0.0, "a column height H > 0")?;
        check("b", p.b, p.b > 0.0, "a base half-width B > 0")?;
        check("b", p.b, p.b < 1e3 * p.h, "B/H < 1000 (alpha < pi/2)")?;
        check("ei", p.ei, p.ei > 0.0, "a bending stiffness EI > 0")?;
        check("m", p.m, p.m > 0.0, "a top mass m > 0")?;
        check("m_c", p.m_c, p.m_c >= 0.0, "a column mass m_c >= 0")?;
        check("m_b", p.m_b, p.m_b >= 0.0, "a base mass m_b >= 0")?;
        let i_min = p.m_b * p.b * p.b;
        check(
            "i_bc",
            p.i_bc,
            p.i_bc >= i_min * (1.0 - 1e-12),
            "I_bc >= m_b B^2, i.e. gamma_ib >= 3/4 (the base's own inertia I_b >= 0)",
        )?;
        check(
            "zeta",
            p.zeta,
            (0.0..1.0).contains(&p.zeta),
            "a damping ratio 0 <= zeta < 1",
        )?;
        check("g", p.g, p.g > 0.0, "a gravitational acceleration g > 0")?;
        for (param, &v) in model.extra_params().zip(&extra[..n_extra]) {
            check_extra(param, v)?;
        }
        if model.coordinates > 1 {
            let weighed = with_full!(model, V => {
                Matrices::of::<V>(&V::params_with(&physical, &extra[..n_extra]))
                    .fixed_base()
                    .is_some()
            });
            check("m_c", p.m_c, weighed, SEVERAL_NEED_COLUMN_MASS)?;
        }
        Ok(Structure {
            model,
            physical,
            extra,
            n_extra,
            modal_zeta: None,
            p_per_second,
        })
    }

    /// A structure of the paper's model from the dimensionless groups, with R = g = m = 1 (time
    /// in τ). `p_per_second` (p in 1/s, for example from R: p = sqrt(9.81/R)) lets results be
    /// reported in seconds too.
    pub fn from_dimensionless(
        d: &Dimensionless,
        p_per_second: Option<f64>,
    ) -> Result<Structure, ParamError> {
        Structure::dimensionless_of_model(paper_model(), d, &[], p_per_second)
    }

    /// A structure of `model` from the dimensionless groups and the values of the parameters the
    /// model adds, in R = g = m = 1 units (a mass relative to m, a length relative to R). EI is
    /// set so that this model's ω_n/p is `d.omega_n_over_p`, from the model's own kernels.
    pub fn dimensionless_of_model(
        model: &'static ModelInfo,
        d: &Dimensionless,
        extra: &[(&str, f64)],
        p_per_second: Option<f64>,
    ) -> Result<Structure, ParamError> {
        check(
            "alpha",
            d.alpha,
            d.alpha > 0.0 && d.alpha < FRAC_PI_2,
            "a slenderness 0 < alpha < pi/2 rad",
        )?;
        check(
            "omega_n_over_p",
            d.omega_n_over_p,
            d.omega_n_over_p > 0.0,
            "omega_n/p > 0",
        )?;
        check(
            "gamma_mc",
            d.gamma_mc,
            d.gamma_mc >= 0.0,
            "gamma_mc = m_c/m >= 0",
        )?;
        check(
            "gamma_mb",
            d.gamma_mb,
            d.gamma_mb >= 0.0,
            "gamma_mb = m_b/m >= 0",
        )?;
        check(
            "gamma_ib",
            d.gamma_ib,
            d.gamma_ib >= 0.75,
            "gamma_ib = I_bc/(4/3 m_b B^2) >= 3/4 (I_b >= 0)",
        )?;
        check(
            "zeta",
            d.zeta,
            (0.0..1.0).contains(&d.zeta),
            "a damping ratio 0 <= zeta < 1",
        )?;
        if let Some(p) = p_per_second {
            check("p", p, p > 0.0, "p = sqrt(g/R) > 0 (1/s)")?;
        }
        let (values, n_extra) = extra_values(model, extra)?;
        let ex = &values[..n_extra];
        let mut physical = with_full!(model, V => Physical::dimensionless_with::<V>(
            d.alpha,
            d.omega_n_over_p,
            d.gamma_mc,
            d.gamma_mb,
            d.gamma_ib,
            d.zeta,
            ex,
        ));
        // EI follows the first fixed-base frequency, which a singular mass matrix does not have.
        if model.coordinates > 1 && physical.ei.is_nan() {
            check("gamma_mc", d.gamma_mc, false, SEVERAL_NEED_COLUMN_MASS)?;
        }
        if d.damping == DampingConvention::Uplifted {
            physical.zeta = with_full!(model, V => fixed_base_ratio::<V>(&physical, ex, d.zeta));
            check(
                "zeta",
                d.zeta,
                (0.0..1.0).contains(&physical.zeta),
                "an uplifted damping ratio that one fixed-base ratio 0 <= zeta < 1 of every mode \
                 gives the first uplifted mode (damping = \"uplifted\")",
            )?;
        }
        Structure::checked(model, physical, values, n_extra, p_per_second)
    }

    /// The same structure (model, extra parameters and time scale) with other physical
    /// parameters, validated. Damping ratios per mode are kept while `zeta` stays the first
    /// one's.
    pub fn with_physical(&self, physical: Physical) -> Result<Structure, ParamError> {
        let mut s = Structure::checked(
            self.model,
            physical,
            self.extra,
            self.n_extra,
            self.p_per_second,
        )?;
        if physical.zeta == self.physical.zeta {
            s.modal_zeta = self.modal_zeta;
        }
        Ok(s)
    }

    /// The same structure with the fixed-base damping ratio of each mode given, `zeta[k]` for the
    /// k-th fixed-base mode by ascending frequency (the modal damping of
    /// [`rocking_kernels::modes`]); `zeta` of [`Structure::physical`] becomes the first one. One
    /// ratio sets every mode's, as `with_param("zeta", ..)` does.
    pub fn with_modal_damping_ratios(&self, zeta: &[f64]) -> Result<Structure, ParamError> {
        let n = self.model.coordinates;
        if zeta.len() != 1 && zeta.len() != n {
            return Err(ParamError {
                parameter: "zeta",
                value: zeta.len() as f64,
                allowed: format!(
                    "one damping ratio, or one per fixed-base mode: model `{}` has {n} \
                     deformation coordinate{}, and {} ratios were given",
                    self.model.name,
                    if n == 1 { "" } else { "s" },
                    zeta.len()
                ),
            });
        }
        let mut s = self.with_param("zeta", zeta[0])?;
        if zeta.len() > 1 {
            for &z in zeta {
                check(
                    "zeta",
                    z,
                    (0.0..1.0).contains(&z),
                    "a damping ratio 0 <= zeta < 1",
                )?;
            }
            let mut modal = [0.0; MAX_COORDINATES];
            modal[..n].copy_from_slice(zeta);
            s.modal_zeta = Some(modal);
        }
        Ok(s)
    }

    /// The fixed-base damping ratios as given: one per mode, or the one ratio of every mode.
    pub fn modal_damping_ratios(&self) -> &[f64] {
        match &self.modal_zeta {
            Some(z) => &z[..self.model.coordinates],
            None => std::slice::from_ref(&self.physical.zeta),
        }
    }

    /// The same structure with the parameter `name` (a field of [`Physical`] or one the model
    /// adds) set to `value`, validated. `zeta` sets the ratio of every mode.
    pub fn with_param(&self, name: &str, value: f64) -> Result<Structure, ParamError> {
        let (mut ph, mut extra) = (self.physical, self.extra);
        match core_field(&mut ph, name) {
            Some(f) => *f = value,
            None => match self.model.extra_params().position(|p| p.name == name) {
                Some(k) => extra[k] = value,
                None => return extra_values(self.model, &[(name, value)]).map(|_| *self),
            },
        }
        let mut s = Structure::checked(self.model, ph, extra, self.n_extra, self.p_per_second)?;
        if name != "zeta" {
            s.modal_zeta = self.modal_zeta;
        }
        Ok(s)
    }

    /// The value of the parameter `name` (a field of [`Physical`], one the model adds, or one
    /// derived from them: the entries of a modal damping matrix).
    pub fn param(&self, name: &str) -> Option<f64> {
        let mut ph = self.physical;
        match core_field(&mut ph, name) {
            Some(f) => Some(*f),
            None => match self.model.extra_params().position(|p| p.name == name) {
                Some(k) => Some(self.extra[k]),
                // A parameter derived from the others (the modal damping matrix): as the kernels
                // get it, from the full variant's parameter vector, in the model's order.
                None => {
                    let k = self.model.params.iter().position(|p| p.name == name)?;
                    with_full!(self.model, V => self.params::<V>().as_ref().get(k).copied())
                }
            },
        }
    }

    /// The model of this structure.
    pub fn model(&self) -> &'static ModelInfo {
        self.model
    }

    /// The physical parameters the kernels run with.
    pub fn physical(&self) -> &Physical {
        &self.physical
    }

    /// The values of the parameters the model adds, in order.
    pub fn extra(&self) -> &[f64] {
        &self.extra[..self.n_extra]
    }

    /// The parameter array of variant `V` (which must be a variant of this structure's model).
    pub fn params<V: Variant>(&self) -> V::Params {
        debug_assert_eq!(V::MODEL, self.model.name);
        let p = V::params_with(&self.physical, self.extra());
        match self.modal_zeta {
            Some(_) => with_modal_damping::<V>(p, self.modal_damping_ratios()),
            None => p,
        }
    }

    /// p in 1/s, when the structure has a time scale in seconds.
    pub fn p_per_second(&self) -> Option<f64> {
        self.p_per_second
    }

    /// The dimensionless groups (damping in the fixed-base convention).
    pub fn dimensionless(&self) -> Dimensionless {
        let d = self.derived();
        let ph = &self.physical;
        Dimensionless {
            omega_n_over_p: d.omega_n / d.p,
            alpha: d.alpha,
            gamma_mc: ph.m_c / ph.m,
            gamma_mb: ph.m_b / ph.m,
            gamma_ib: if d.i_bc_plate > 0.0 {
                ph.i_bc / d.i_bc_plate
            } else {
                1.0
            },
            zeta: ph.zeta,
            damping: DampingConvention::FixedBase,
        }
    }

    /// Derived quantities, from the generated `structure` kernel of the structure's own model
    /// (its full variant: a specialised variant gives the same numbers, since the masses it
    /// removes are zero when it runs).
    pub fn derived(&self) -> Derived {
        with_full!(self.model, V => self.derived_by::<V>())
    }

    /// The natural circular frequencies of the column, ascending, in model units: fixed base
    /// (det(K − ω² M) = 0) and uplifted (det(K − ω² (M − c cᵀ/J0)) = 0, the zero rigid-rocking
    /// root excluded; eq (18) for one coordinate), from the full variant's kernels by
    /// [`rocking_kernels::modes`], and each uplifted mode's damping ratio. Empty where a mass
    /// matrix is singular (no column mass to weigh a coordinate).
    pub fn frequencies(&self) -> Frequencies {
        with_variant!(self.model.full, V, L => {
            let m = Matrices::of::<V>(&self.params::<V>());
            let omega = |modes: Option<rocking_kernels::modes::Modes>| {
                modes.map(|m| m.omega).unwrap_or_default()
            };
            let (fixed_base_damping, uplifted_damping) = if V::NQ == 1 {
                (vec![self.physical.zeta], vec![self.derived_by::<V>().zeta_uplifted])
            } else {
                let c = modal_damping::<V>(&self.params::<V>());
                (
                    m.fixed_base_damping_ratios(&c).unwrap_or_default(),
                    m.uplifted_damping_ratios(&c).unwrap_or_default(),
                )
            };
            Frequencies {
                fixed_base: omega(m.fixed_base()),
                uplifted: omega(m.uplifted()),
                fixed_base_damping,
                uplifted_damping,
            }
        })
        .expect("a model's full variant is generated")
    }

    /// Derived quantities from the `structure` kernel of the variant `V` of this model (and, for
    /// several deformation coordinates, its modes: [`Derived::of_modes`]).
    pub fn derived_by<V: Variant>(&self) -> Derived {
        let p = self.params::<V>();
        let s = V::structure(&p);
        match s.values().try_into() {
            Ok(one) if V::NQ == 1 => Derived::from_kernel(one, self.physical.zeta),
            _ => Derived::of_modes::<V>(&p, &s, self.physical.zeta),
        }
    }

    /// The smallest constant ground acceleration that uplifts the structure when applied
    /// quasi-statically (the column at its static deflection), from the model's kernels.
    pub fn static_uplift_acceleration(&self) -> f64 {
        self.static_uplift().ground_acceleration
    }

    /// The weight, the uplift moment W B and the quasi-static uplift point of the structure,
    /// from its model's `static_uplift` kernel.
    pub fn static_uplift(&self) -> StaticUplift {
        use rocking_kernels::kernels::index::static_uplift as su;
        with_full!(self.model, V => {
            let k = V::static_uplift(&self.params::<V>());
            let k = k.values();
            // u_uplift is u_1..u_n with several coordinates: M_el follows them.
            let n = V::NQ;
            let top = V::shape(1.0);
            let deflection: f64 = (0..n)
                .map(|i| k[su::U_UPLIFT + i] * if n == 1 { 1.0 } else { top.values()[i] })
                .sum();
            StaticUplift {
                weight: k[su::WEIGHT],
                moment: k[su::MOMENT_UPLIFT],
                ground_acceleration: k[su::UG_UPLIFT].abs(),
                deflection: deflection.abs(),
                elastic_moment: k[su::MOMENT_ELASTIC_UPLIFT + n - 1].abs(),
            }
        })
    }
}

/// A structure's weight and quasi-static uplift (the derivation's `static_uplift` kernel, about
/// either corner: magnitudes), in the structure's units.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct StaticUplift {
    /// The total weight W.
    pub weight: f64,
    /// W B: the base moment at which the base uplifts.
    pub moment: f64,
    /// The constant ground acceleration that uplifts the structure applied quasi-statically.
    pub ground_acceleration: f64,
    /// The column's top deflection at that uplift.
    pub deflection: f64,
    /// The elastic base moment M_el at that uplift (below W B by P-Δ and the shape's error).
    pub elastic_moment: f64,
}
