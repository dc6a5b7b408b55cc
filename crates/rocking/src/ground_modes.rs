//! Small vibrations of a structure on compliant ground (issue 44, docs/ground.md): the linear
//! eigenproblem K φ = ω² M φ in q = (θ, v, u₁..uₙ) about the static equilibrium at rest
//! (θ = 0, v = v0, u = 0), in full contact.
//!
//! M is the variant's `free_mass_matrix` kernel there. K = −∂(F + Q)/∂q is the Jacobian of the
//! variant's `free_forcing` (velocities and ground motion zero) plus the ground's full-contact
//! Q_θ, Q_v, by the fourth-order central difference
//! D(h) = [8 (G(q + h) − G(q − h)) − (G(q + 2h) − G(q − 2h))] / (12 h) with h = 10⁻³ of each
//! coordinate's scale (θ: the lift-off rotation, v: v0, u: u_cr), so that every probe stays in
//! full contact. Its truncation error is estimated by |D(h) − D(2h)| / 15 (the h⁴ term) and
//! reported with the result, as is the residual of the equilibrium.

use nalgebra::DMatrix;
use rocking_kernels::ground::winkler_full as go;
use rocking_kernels::modes::symmetric;
use rocking_kernels::{with_variant, Array, Variant};

use crate::error::SimError;
use crate::ground::Ground;
use crate::structure::Structure;
use crate::{select_variant, Effects};

/// The coordinate a mode moves most (its largest share of the kinetic energy).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Coordinate {
    /// θ: rocking on the ground.
    Rotation,
    /// v: the vertical motion on the ground.
    Settlement,
    /// u_i (0-based): the column's deformation coordinate i.
    Deformation(usize),
}

impl Coordinate {
    /// A short name: `rocking`, `vertical`, `u1`, `u2`, …
    #[must_use]
    pub fn name(self) -> String {
        match self {
            Coordinate::Rotation => "rocking".into(),
            Coordinate::Settlement => "vertical".into(),
            Coordinate::Deformation(i) => format!("u{}", i + 1),
        }
    }
}

/// The small vibrations on the ground: the typed result of [`small_vibrations`].
#[derive(Clone, Debug, PartialEq)]
pub struct GroundModes {
    /// The kernel variant that was linearised.
    pub variant: &'static str,
    /// Circular frequencies (in the structure's time unit), ascending. A negative ω² (the
    /// structure is statically unstable on the ground) is reported as −√|ω²|.
    pub omega: Vec<f64>,
    /// The modes over q = (θ, v, u₁..uₙ), each with φᵀ M φ = 1.
    pub shapes: Vec<Vec<f64>>,
    /// The coordinate each mode moves most.
    pub dominant: Vec<Coordinate>,
    /// The estimated relative error of K: max |D(h) − D(2h)| / 15 and K's asymmetry, over the
    /// largest entry of K.
    pub stiffness_error: f64,
    /// max |F + Q| at the equilibrium over the weight (0 up to rounding).
    pub equilibrium_residual: f64,
}

/// The small vibrations of `structure` (the variant `effects` select) on `ground` at rest.
///
/// # Errors
///
/// No variant for the structure and effects, or a mass matrix that is not positive definite
/// (point masses on the column axis alone: docs/ground.md).
pub fn small_vibrations(
    structure: &Structure,
    effects: &Effects,
    ground: &Ground,
) -> Result<GroundModes, SimError> {
    let sel = select_variant(structure, effects).map_err(SimError::NoVariant)?;
    let name = sel.variant.name;
    with_variant!(name, V, L => modes_of::<V>(&sel.structure, ground)).unwrap_or_else(|| {
        Err(SimError::UnknownVariant {
            name: name.to_string(),
            model: None,
        })
    })
}

fn modes_of<V: Variant>(structure: &Structure, ground: &Ground) -> Result<GroundModes, SimError> {
    let p = structure.params::<V>();
    let derived = structure.derived_by::<V>();
    let weight =
        V::static_uplift(&p).values()[rocking_kernels::kernels::index::static_uplift::WEIGHT];
    let st = ground.statics(weight);
    let nf = V::Qf::LEN;
    // The rigid variant's u row is u'' = 0: not a coordinate.
    let n = if V::RIGID { 2 } else { nf };
    let q0: Vec<f64> = (0..nf)
        .map(|i| if i == 1 { st.settlement } else { 0.0 })
        .collect();
    let forcing = |q: &[f64]| -> Vec<f64> {
        let y = V::Y::from_fn(|i| if i < nf { q[i] } else { 0.0 });
        let mut f = V::free_forcing(&y, 0.0, 1.0, &p).values().to_vec();
        let g = ground.full(&[q[0], q[1], 0.0, 0.0]);
        f[0] += g[go::Q_THETA];
        f[1] += g[go::Q_V];
        f
    };
    let scale = |j: usize| match j {
        0 => st.theta_lift_off,
        1 => st.settlement,
        _ => derived.u_cr,
    };
    let jacobian = |h_rel: f64| -> DMatrix<f64> {
        let mut k = DMatrix::zeros(n, n);
        for j in 0..n {
            let h = h_rel * scale(j);
            let at = |step: f64| {
                let mut q = q0.clone();
                q[j] += step * h;
                forcing(&q)
            };
            let (p1, m1, p2, m2) = (at(1.0), at(-1.0), at(2.0), at(-2.0));
            for i in 0..n {
                let d = (8.0 * (p1[i] - m1[i]) - (p2[i] - m2[i])) / (12.0 * h);
                k[(i, j)] = -d;
            }
        }
        k
    };
    let k = jacobian(1e-3);
    let k2 = jacobian(2e-3);
    let largest = k.amax();
    let asym = (&k - k.transpose()).amax();
    let stiffness_error = ((&k - &k2).amax() / 15.0).max(asym) / largest;
    let k = (&k + k.transpose()) * 0.5;
    let residual = forcing(&q0)[..n].iter().fold(0.0f64, |a, x| a.max(x.abs())) / weight;
    let qf = V::Qf::from_fn(|i| q0[i]);
    let m_all = symmetric(V::free_mass_matrix(&qf, 1.0, &p).values(), nf);
    let m = m_all.view((0, 0), (n, n)).into_owned();
    let singular = || SimError::SingularOnGround {
        variant: V::NAME,
        pivot: None,
    };
    let l = m.clone().cholesky().ok_or_else(singular)?.l();
    let l_inv = l.try_inverse().ok_or_else(singular)?;
    let reduced = &l_inv * &k * l_inv.transpose();
    let reduced = (&reduced + reduced.transpose()) * 0.5;
    let eig = reduced.symmetric_eigen();
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&a, &b| eig.eigenvalues[a].total_cmp(&eig.eigenvalues[b]));
    let mut out = GroundModes {
        variant: V::NAME,
        omega: Vec::new(),
        shapes: Vec::new(),
        dominant: Vec::new(),
        stiffness_error,
        equilibrium_residual: residual,
    };
    for j in order {
        let lambda = eig.eigenvalues[j];
        let phi = l_inv.transpose() * eig.eigenvectors.column(j);
        let m_phi = &m * &phi;
        let share = (0..n)
            .max_by(|&a, &b| (phi[a] * m_phi[a]).total_cmp(&(phi[b] * m_phi[b])))
            .unwrap_or(0);
        out.omega.push(lambda.signum() * lambda.abs().sqrt());
        out.shapes.push(phi.iter().copied().collect());
        out.dominant.push(match share {
            0 => Coordinate::Rotation,
            1 => Coordinate::Settlement,
            i => Coordinate::Deformation(i - 2),
        });
    }
    Ok(out)
}
