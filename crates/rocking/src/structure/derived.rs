//! What follows from a structure's parameters, from its model's own kernels: the column's
//! natural frequencies and the derived quantities (p, ω_n, u_cr, θ_cr, E_ref, …).

use nalgebra::DVector;
use rocking_kernels::kernels::index::structure as st;
use rocking_kernels::modes::{critical_deflection, modal_damping, Matrices, RigidBody};
use rocking_kernels::{Array, Layout, Physical, Variant};
use serde::Serialize;

/// The natural circular frequencies of a structure's column, ascending, in model units
/// ([`Structure::frequencies`]).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Frequencies {
    /// Fixed base: the roots of det(K − ω² M) = 0.
    pub fixed_base: Vec<f64>,
    /// Rocking about a corner (gravity and ground motion dropped, as in eqs (10)–(11)).
    pub uplifted: Vec<f64>,
    /// The damping ratio of each fixed-base mode, read back from the damping matrix the kernels
    /// run with (φ_kᵀ C φ_k / (2 ω_k φ_kᵀ M φ_k); ζ for one coordinate).
    pub fixed_base_damping: Vec<f64>,
    /// The damping ratio of each uplifted mode, −Re λ / |λ| of the complex eigenvalues under the
    /// structure's damping (not classical while rocking for several coordinates); ζ S, eq (19),
    /// for one coordinate.
    pub uplifted_damping: Vec<f64>,
}

/// Quantities derived from a structure by its model's generated `structure` kernel, in model units.
/// With several deformation coordinates the column's quantities are its first modes' (see
/// [`Derived::of_modes`]).
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
    /// I_bc of a thin base plate, 4/3 m_b B²: the unit of γ_Ib.
    pub i_bc_plate: f64,
}

impl Derived {
    /// The quantities of one evaluation of a variant's `structure` kernel.
    pub fn from_kernel(s: &[f64; 15], zeta_fixed_base: f64) -> Derived {
        Derived {
            p: s[st::P_FREQ],
            r: s[st::R],
            alpha: s[st::ALPHA],
            omega_n: s[st::OMEGA_N],
            omega_up: s[st::OMEGA_UP],
            modal_s: s[st::MODAL_S],
            zeta_fixed_base,
            zeta_uplifted: s[st::ZETA_UP],
            m_tilde: s[st::M_TILDE],
            k_tilde: s[st::K_TILDE],
            gamma_tilde: s[st::GAMMA_TILDE],
            theta_cr: s[st::THETA_CR],
            u_cr: s[st::U_CR],
            e_ref: s[st::E_REF],
            i_bc_plate: s[st::I_BC_PLATE],
        }
    }
}

impl Derived {
    /// The quantities of a variant of several deformation coordinates: ω_n and ω_up the first
    /// fixed-base and uplifted frequencies ([`rocking_kernels::modes`]), S = ω_up/ω_n, ζ_uplifted
    /// the first uplifted mode's damping ratio under the modal damping matrix in `p`, m̃, k̃ and
    /// Γ̃ the first fixed-base mode's generalised mass, stiffness and participation factor with
    /// φ_1 scaled to a unit top deflection (φ_1ᵀMφ_1, φ_1ᵀKφ_1, φ_1ᵀΓ/m̃), u_cr along φ_1
    /// ([`critical_deflection`]), and the rigid body's θ_cr, E_ref, R, α, p by name. NaN where
    /// the column's mass matrix is singular.
    pub fn of_modes<V: Variant>(p: &V::Params, s: &V::Structure, zeta_fixed_base: f64) -> Derived {
        let n = V::NQ;
        let rigid = RigidBody::of::<V>(s);
        let mats = Matrices::of::<V>(p);
        let fixed = mats.fixed_base();
        let phi = fixed.as_ref().map_or_else(
            || DVector::from_element(n, f64::NAN),
            |f| f.shapes[0].clone(),
        );
        let omega_n = fixed.as_ref().map_or(f64::NAN, |f| f.omega[0]);
        let omega_up = mats.uplifted().map_or(f64::NAN, |u| u.omega[0]);
        let m_phi = &mats.mass * &phi;
        let m_tilde = phi.dot(&m_phi);
        let k_tilde = phi.dot(&(&mats.stiffness * &phi));
        // Γ̃_i = (M⁻¹Γ)_i from the kernel, so φ_1ᵀΓ = (Mφ_1)ᵀ Γ̃.
        let gamma = DVector::from_fn(n, |i, _| {
            <V as Layout>::structure_value(s, &format!("gamma_tilde_{}", i + 1))
        });
        let damping = modal_damping::<V>(p);
        let zeta_uplifted = mats
            .uplifted_damping_ratios(&damping)
            .map_or(f64::NAN, |r| r[0]);
        Derived {
            p: rigid.p,
            r: rigid.r,
            alpha: rigid.alpha,
            omega_n,
            omega_up,
            modal_s: omega_up / omega_n,
            zeta_fixed_base,
            zeta_uplifted,
            m_tilde,
            k_tilde,
            gamma_tilde: m_phi.dot(&gamma) / m_tilde,
            theta_cr: rigid.theta_cr,
            u_cr: critical_deflection::<V>(p, &phi),
            e_ref: rigid.e_ref,
            i_bc_plate: rigid.i_bc_plate,
        }
    }
}

/// The fixed-base damping ratio ζ (common to every fixed-base mode) that gives the first uplifted
/// mode the ratio `zeta_uplifted`: ζ_uplifted / S for one coordinate, eq (19); for several the
/// uplifted ratio is not proportional to ζ (the modal damping is not classical while rocking), so
/// ζ is found by the fixed-point iteration ζ ← ζ ζ_uplifted / ζ_1^up(ζ) from ζ_uplifted / S (a few
/// iterations: ζ_1^up is nearly proportional to ζ). NaN where the ratio cannot be reached.
pub(super) fn fixed_base_ratio<V: Variant>(
    physical: &Physical,
    extra: &[f64],
    zeta_uplifted: f64,
) -> f64 {
    let ratio_at = |zeta: f64| {
        let ph = Physical { zeta, ..*physical };
        let p = V::params_with(&ph, extra);
        let s = V::structure(&p);
        if V::NQ == 1 {
            (s.values()[st::MODAL_S], f64::NAN)
        } else {
            let d = Derived::of_modes::<V>(&p, &s, zeta);
            (d.modal_s, d.zeta_uplifted)
        }
    };
    let (modal_s, _) = ratio_at(physical.zeta);
    let mut zeta = zeta_uplifted / modal_s;
    if V::NQ == 1 || zeta_uplifted == 0.0 {
        return zeta;
    }
    // The uplifted ratio is nearly proportional to ζ: the iteration gains digits fast, down to
    // the round-off of the complex eigenvalues (~1e-11 of the ratio): done at 1e-9.
    for _ in 0..30 {
        let (_, up) = ratio_at(zeta);
        if (up / zeta_uplifted - 1.0).abs() <= 1e-9 {
            return zeta;
        }
        zeta *= zeta_uplifted / up;
        if !zeta.is_finite() {
            return f64::NAN;
        }
    }
    f64::NAN
}
