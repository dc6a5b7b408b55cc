//! Structures: physical (any consistent units) or dimensionless (the paper's eq (34)), converted
//! both ways, validated, with the derived quantities the reports need.

use std::f64::consts::FRAC_PI_2;
use std::fmt;

use rocking_kernels::kernels::{full::structure as st, Full};
use rocking_kernels::{Physical, Variant};
use serde::{Deserialize, Serialize};

/// How the damping ratio ζ is meant.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum DampingConvention {
    /// ζ is the fixed-base damping ratio of the column (the paper's Figs 3 and 5).
    FixedBase,
    /// ζ is the uplifted damping ratio: the fixed-base ratio is ζ/S, eq (19) (the spectra, Sec. 3.1).
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
    /// γ_Ib = I_bc / (4/3 m_b B²): 1 for a thin rectangular plate.
    pub gamma_ib: f64,
    /// Damping ratio, in the convention `damping`.
    pub zeta: f64,
    /// What `zeta` means.
    pub damping: DampingConvention,
}

/// An invalid parameter: its name, the value given and what is allowed.
#[derive(Clone, Debug, PartialEq)]
pub struct ParamError {
    /// Parameter name (as in scene files).
    pub parameter: &'static str,
    /// The value that was given.
    pub value: f64,
    /// The allowed range, in words.
    pub allowed: &'static str,
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

fn check(
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
            allowed,
        })
    }
}

/// A validated structure. The solver runs in the units of [`Structure::physical`]; a structure
/// built from dimensionless groups uses R = g = m = 1, so its time unit is τ = p t.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Structure {
    physical: Physical,
    /// p in 1/s when known (physical input, or dimensionless input with a length scale).
    p_per_second: Option<f64>,
}

/// Quantities derived from a structure by the generated `structure` kernel, in model units.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Derived {
    /// p = sqrt(g/R).
    pub p: f64,
    /// R = sqrt(B² + H²).
    pub r: f64,
    /// α = atan(B/H).
    pub alpha: f64,
    /// Fixed-base frequency ω_n, eq (35).
    pub omega_n: f64,
    /// Uplifted frequency ω_up = ω_n S, eq (18).
    pub omega_up: f64,
    /// Modal factor S of eqs (18)-(19).
    pub modal_s: f64,
    /// Fixed-base damping ratio used by the kernels.
    pub zeta_fixed_base: f64,
    /// Uplifted damping ratio ζ S, eq (19).
    pub zeta_uplifted: f64,
    /// Generalised mass m̃, eq (6).
    pub m_tilde: f64,
    /// Generalised stiffness k̃, eq (5).
    pub k_tilde: f64,
    /// Participation factor Γ̃, eq (7).
    pub gamma_tilde: f64,
    /// Critical (unstable-equilibrium) angle θ_cr of the rigid structure, eq (39).
    pub theta_cr: f64,
    /// Column displacement at static uplift, eq (40).
    pub u_cr: f64,
    /// Reference energy: the rigid structure's potential-energy barrier V_g(θ_cr) − V_g(0), with
    /// all masses (equals m g R (1 − cos α) when m_c = m_b = 0).
    pub e_ref: f64,
}

impl Structure {
    /// A structure from physical parameters (any consistent units; SI gives seconds).
    pub fn from_physical(physical: Physical) -> Result<Structure, ParamError> {
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
        let s = Structure {
            physical,
            p_per_second: None,
        };
        let p_model = s.derived().p;
        Ok(Structure {
            physical,
            p_per_second: Some(p_model),
        })
    }

    /// A structure from the dimensionless groups, with R = g = m = 1 (time in τ). `p_per_second`
    /// (p in 1/s, for example from R: p = sqrt(9.81/R)) lets results be reported in seconds too.
    pub fn from_dimensionless(
        d: &Dimensionless,
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
        let mut physical = Physical::dimensionless(
            d.alpha,
            d.omega_n_over_p,
            d.gamma_mc,
            d.gamma_mb,
            d.gamma_ib,
            d.zeta,
        );
        if d.damping == DampingConvention::Uplifted {
            let s = Full::structure(&Full::params(&physical))[st::MODAL_S];
            physical.zeta = d.zeta / s;
        }
        Ok(Structure {
            physical,
            p_per_second,
        })
    }

    /// The same structure (and time scale) with other physical parameters, validated.
    pub fn with_physical(&self, physical: Physical) -> Result<Structure, ParamError> {
        let checked = Structure::from_physical(physical)?;
        Ok(Structure {
            physical: checked.physical,
            p_per_second: self.p_per_second,
        })
    }

    /// The physical parameters the kernels run with.
    pub fn physical(&self) -> &Physical {
        &self.physical
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
            gamma_ib: if ph.m_b > 0.0 {
                ph.i_bc / (4.0 / 3.0 * ph.m_b * ph.b * ph.b)
            } else {
                1.0
            },
            zeta: ph.zeta,
            damping: DampingConvention::FixedBase,
        }
    }

    /// Derived quantities, from the generated `structure` kernel of the full model.
    pub fn derived(&self) -> Derived {
        let s = Full::structure(&Full::params(&self.physical));
        Derived {
            p: s[st::P_FREQ],
            r: s[st::R],
            alpha: s[st::ALPHA],
            omega_n: s[st::OMEGA_N],
            omega_up: s[st::OMEGA_UP],
            modal_s: s[st::MODAL_S],
            zeta_fixed_base: self.physical.zeta,
            zeta_uplifted: s[st::ZETA_UP],
            m_tilde: s[st::M_TILDE],
            k_tilde: s[st::K_TILDE],
            gamma_tilde: s[st::GAMMA_TILDE],
            theta_cr: s[st::THETA_CR],
            u_cr: s[st::U_CR],
            e_ref: s[st::E_REF],
        }
    }

    /// The smallest constant ground acceleration that uplifts the structure when applied
    /// quasi-statically (the column at its static deflection), from the generated kernels.
    pub fn static_uplift_acceleration(&self) -> f64 {
        let p = Full::params(&self.physical);
        // The contact and uplift kernels are affine in (u, ug): solve them as such.
        let acc = |u: f64, ug: f64| Full::contact_rhs(&[u, 0.0], ug, &p)[1];
        let (a0, au, ag) = (
            acc(0.0, 0.0),
            acc(1.0, 0.0) - acc(0.0, 0.0),
            acc(0.0, 1.0) - acc(0.0, 0.0),
        );
        let u_static = |ug: f64| -(a0 + ag * ug) / au;
        // Uplift about s = +1 needs a negative ug; by symmetry the magnitude is the same for s = -1.
        let f = |ug: f64| Full::uplift(&[u_static(ug), 0.0], ug, 1.0, &p);
        let (f0, f1) = (f(0.0), f(-1.0) - f(0.0));
        f0.abs() / f1
    }
}
