//! Vibration modes of a structure: the small symmetric-definite eigenproblems of its column,
//! solved once per structure (hand-written: an eigenproblem is not straight-line code).
//!
//! The kernels give the matrices ([`Matrices::of`]): M and K of the deformation coordinates u_i
//! at θ = 0 (the first outputs of `structure`), and from the mass matrix at θ = u = 0 the
//! coupling c_i = ∂²T/∂θ'∂u_i' and J0 = ∂²T/∂θ'². Then
//!
//! - fixed base: det(K − ω² M) = 0, the n frequencies ω_k and modes φ_k ([`Matrices::fixed_base`]);
//! - uplifted, rocking about a corner with gravity and the ground motion dropped as in eqs
//!   (10)–(11): θ'' = −cᵀu''/J0 eliminated, det(K − ω² (M − c cᵀ/J0)) = 0 ([`Matrices::uplifted`]);
//!   for one coordinate ω_up = ω_n sqrt(J0 / (J0 − c²/m̃)), eq (18);
//! - the modal damping matrix C = Σ_k 2 ζ_k ω_k (M φ_k)(M φ_k)ᵀ / (φ_kᵀ M φ_k), which gives the
//!   fixed-base mode k the ratio ζ_k (for one coordinate c = 2 ζ ω_n m̃, eq (19));
//!   [`with_modal_damping`] writes it into the kernels' parameters;
//! - while rocking this damping is not classical: each uplifted mode's ratio is −Re λ / |λ| of
//!   the complex eigenvalues λ of (M − c cᵀ/J0) λ² + C λ + K ([`Matrices::uplifted_damping_ratios`];
//!   for one coordinate ζ S, eq (19));
//! - u_cr along the first fixed-base mode φ_1 scaled to a unit top deflection: the top deflection
//!   at which f_+ = 0 with u' = ü_g = 0 ([`critical_deflection`]; eq (40) for one coordinate).
//!
//! The pencils are reduced by the Cholesky factor of the mass, M = L Lᵀ, to the symmetric
//! L⁻¹ K L⁻ᵀ (nalgebra's `SymmetricEigen`): pure Rust, the same numbers on every machine for a
//! given build. Modes are sorted by frequency and scaled to a unit top deflection Σ φ_i ψ_i(1).

use nalgebra::{DMatrix, DVector};

use crate::{Array, Layout, ModelInfo, Physical, Variant};

/// The matrices of a structure's small vibrations, from its kernels.
#[derive(Clone, Debug, PartialEq)]
pub struct Matrices {
    /// M of the u_i (fixed base, θ = 0).
    pub mass: DMatrix<f64>,
    /// K of the u_i.
    pub stiffness: DMatrix<f64>,
    /// c_i = ∂²T/∂θ'∂u_i' at θ = u = 0: how rocking and deflection are coupled.
    pub coupling: DVector<f64>,
    /// J0 = ∂²T/∂θ'² at θ = u = 0, the rocking inertia about a corner.
    pub j0: f64,
    /// ψ_i(1): the column's top deflection is Σ u_i ψ_i(1).
    pub top: DVector<f64>,
}

/// Frequencies and mode shapes of one eigenproblem, by ascending frequency.
#[derive(Clone, Debug, PartialEq)]
pub struct Modes {
    /// Circular frequencies ω_k.
    pub omega: Vec<f64>,
    /// The modes φ_k, each scaled to a unit top deflection (or, for a mode whose top does not
    /// move, to φᵀ M φ = 1), its sign that of the top.
    pub shapes: Vec<DVector<f64>>,
}

/// The upper triangle (row by row) of a symmetric n × n matrix, as a matrix (the kernels' layout
/// of a mass matrix and of the modal damping parameters).
pub fn symmetric(upper: &[f64], n: usize) -> DMatrix<f64> {
    let mut m = DMatrix::zeros(n, n);
    let mut k = 0;
    for i in 0..n {
        for j in i..n {
            m[(i, j)] = upper[k];
            m[(j, i)] = upper[k];
            k += 1;
        }
    }
    m
}

impl Matrices {
    /// The matrices of variant `V` with parameters `p`, from its `structure` and `mass_matrix`
    /// kernels and its shape functions at the top.
    pub fn of<V: Variant>(p: &V::Params) -> Matrices {
        let n = V::NQ;
        let t = n * (n + 1) / 2;
        let s = V::structure(p);
        let m = V::mass_matrix(&V::Q::from_fn(|_| 0.0), 1.0, p);
        let m = m.values();
        Matrices {
            mass: symmetric(&s.values()[..t], n),
            stiffness: symmetric(&s.values()[t..2 * t], n),
            coupling: DVector::from_column_slice(&m[1..=n]),
            j0: m[0],
            top: DVector::from_column_slice(V::shape(1.0).values()),
        }
    }

    /// The number of deformation coordinates.
    pub fn coordinates(&self) -> usize {
        self.top.len()
    }

    /// M − c cᵀ / J0: the column's mass while rocking, θ'' eliminated.
    pub fn uplifted_mass(&self) -> DMatrix<f64> {
        &self.mass - &self.coupling * self.coupling.transpose() / self.j0
    }

    /// The fixed-base modes: det(K − ω² M) = 0. `None` when M is not positive definite (a
    /// basis on which the masses do not weigh every coordinate: a massless column with several).
    pub fn fixed_base(&self) -> Option<Modes> {
        self.modes_of(&self.mass)
    }

    /// The uplifted modes, rocking about a corner (gravity and the ground motion dropped as in
    /// eqs (10)–(11); the zero rigid-rocking root excluded): det(K − ω² (M − c cᵀ/J0)) = 0.
    pub fn uplifted(&self) -> Option<Modes> {
        self.modes_of(&self.uplifted_mass())
    }

    /// The modes of det(K − ω² mass) = 0, by the Cholesky factor of `mass`.
    fn modes_of(&self, mass: &DMatrix<f64>) -> Option<Modes> {
        let l = mass.clone().cholesky()?.l();
        let l_inv = l.clone().try_inverse()?;
        let reduced = &l_inv * &self.stiffness * l_inv.transpose();
        let reduced = (&reduced + reduced.transpose()) * 0.5;
        let eig = reduced.symmetric_eigen();
        let mut order: Vec<usize> = (0..eig.eigenvalues.len()).collect();
        order.sort_by(|&a, &b| eig.eigenvalues[a].total_cmp(&eig.eigenvalues[b]));
        let mut modes = Modes {
            omega: Vec::new(),
            shapes: Vec::new(),
        };
        for k in order {
            let phi = l_inv.transpose() * eig.eigenvectors.column(k);
            modes.omega.push(eig.eigenvalues[k].max(0.0).sqrt());
            modes.shapes.push(self.scaled(phi, mass));
        }
        Some(modes)
    }

    /// `phi` scaled to a unit top deflection, or where the top does not move to a unit
    /// generalised mass with its largest entry positive.
    fn scaled(&self, phi: DVector<f64>, mass: &DMatrix<f64>) -> DVector<f64> {
        let top = self.top.dot(&phi);
        let norm = phi.dot(&(mass * &phi)).sqrt();
        if top.abs() > 1e-9 * norm * self.top.norm() {
            phi / top
        } else {
            let largest = phi
                .iter()
                .fold(0.0, |a: f64, &v| if v.abs() > a.abs() { v } else { a });
            phi / (norm * largest.signum())
        }
    }

    /// The modal damping matrix C = Σ_k 2 ζ_k ω_k (M φ_k)(M φ_k)ᵀ / (φ_kᵀ M φ_k) of the fixed-base
    /// `modes`, with `zeta` one ratio for every mode or one per mode.
    ///
    /// # Panics
    ///
    /// When `zeta` has neither one entry nor one per mode.
    pub fn damping(&self, modes: &Modes, zeta: &[f64]) -> DMatrix<f64> {
        let n = modes.omega.len();
        assert!(
            zeta.len() == 1 || zeta.len() == n,
            "{} damping ratios for {n} modes: give one for every mode or one per mode",
            zeta.len()
        );
        let mut c = DMatrix::zeros(n, n);
        for (k, (omega, phi)) in modes.omega.iter().zip(&modes.shapes).enumerate() {
            let m_phi = &self.mass * phi;
            let zeta_k = zeta[if zeta.len() == 1 { 0 } else { k }];
            c += &m_phi * m_phi.transpose() * (2.0 * zeta_k * omega / phi.dot(&m_phi));
        }
        c
    }

    /// The damping ratio of each fixed-base mode under the damping matrix `c`, by ascending
    /// frequency: φ_kᵀ C φ_k / (2 ω_k φ_kᵀ M φ_k), read back from `c` (for the modal damping of
    /// [`Matrices::damping`] these are its ratios ζ_k). `None` when the mass is singular.
    pub fn fixed_base_damping_ratios(&self, c: &DMatrix<f64>) -> Option<Vec<f64>> {
        let modes = self.fixed_base()?;
        Some(
            modes
                .omega
                .iter()
                .zip(&modes.shapes)
                .map(|(omega, phi)| {
                    phi.dot(&(c * phi)) / (2.0 * omega * phi.dot(&(&self.mass * phi)))
                })
                .collect(),
        )
    }

    /// The damping ratio of each uplifted mode under the damping matrix `c`, by ascending
    /// frequency: −Re λ / |λ| of the complex eigenvalues of (M − c cᵀ/J0) λ² + C λ + K = 0 (one
    /// per conjugate pair; an overdamped pair of real roots gives the ratio of their product
    /// and sum, as a critically damped one would: ≥ 1). `None` when the uplifted mass is
    /// singular.
    pub fn uplifted_damping_ratios(&self, c: &DMatrix<f64>) -> Option<Vec<f64>> {
        let n = self.coordinates();
        let mass_inv = self.uplifted_mass().try_inverse()?;
        let mut a = DMatrix::zeros(2 * n, 2 * n);
        a.view_mut((0, n), (n, n)).fill_with_identity();
        a.view_mut((n, 0), (n, n))
            .copy_from(&(-&mass_inv * &self.stiffness));
        a.view_mut((n, n), (n, n)).copy_from(&(-&mass_inv * c));
        let mut roots: Vec<_> = a.complex_eigenvalues().iter().copied().collect();
        roots.sort_by(|x, y| x.norm().total_cmp(&y.norm()));
        // Conjugate pairs, or pairs of real roots, by ascending modulus: ω² = λ1 λ2, 2 ζ ω = −(λ1 + λ2).
        Some(
            roots
                .chunks(2)
                .map(|pair| {
                    let (sum, product) = (pair[0] + pair[1], pair[0] * pair[1]);
                    -sum.re / (2.0 * product.re.sqrt())
                })
                .collect(),
        )
    }
}

/// u_cr along `shape` (a deflection with unit top deflection, the first fixed-base mode for
/// u_cr): the top deflection a with f_+(a shape) = 0 at u' = ü_g = 0, about the right corner. The
/// uplift function is affine in u there, so two evaluations of the `uplift` kernel give it.
pub fn critical_deflection<V: Variant>(p: &V::Params, shape: &DVector<f64>) -> f64 {
    let n = V::NQ;
    let at = |a: f64| {
        let xc = V::Xc::from_fn(|i| if i < n { a * shape[i] } else { 0.0 });
        V::uplift(&xc, 0.0, 1.0, p)
    };
    let f0 = at(0.0);
    -f0 / (at(1.0) - f0)
}

/// `p` with the modal damping matrix of its fixed-base modes written in: `zeta` one ratio for
/// every mode or one per mode. A variant of one coordinate takes its damping from ζ itself (eq
/// (19)): its `zeta` parameter is set to the ratio. Where the fixed-base modes do not exist (a
/// mass matrix that is not positive definite) the entries are NaN.
///
/// # Panics
///
/// When `zeta` has neither one entry nor one per mode.
pub fn with_modal_damping<V: Variant>(mut p: V::Params, zeta: &[f64]) -> V::Params {
    let n = V::NQ;
    let model = ModelInfo::find(V::MODEL).expect("a variant's model is registered");
    let Some(first) = model.modal_damping() else {
        assert!(zeta.len() == 1, "one coordinate: one damping ratio");
        let k = V::PARAM_NAMES.iter().position(|name| *name == "zeta");
        p.as_mut()[k.expect("every model has zeta")] = zeta[0];
        return p;
    };
    let m = Matrices::of::<V>(&p);
    let c = m.fixed_base().map_or_else(
        || DMatrix::from_element(n, n, f64::NAN),
        |modes| m.damping(&modes, zeta),
    );
    let mut k = first;
    for i in 0..n {
        for j in i..n {
            p.as_mut()[k] = c[(i, j)];
            k += 1;
        }
    }
    p
}

/// The modal damping matrix that [`with_modal_damping`] wrote into `p` (zeros for a variant of one
/// coordinate, whose damping is its `zeta` parameter).
pub fn modal_damping<V: Variant>(p: &V::Params) -> DMatrix<f64> {
    let n = V::NQ;
    let model = ModelInfo::find(V::MODEL).expect("a variant's model is registered");
    match model.modal_damping() {
        Some(first) => symmetric(&p.as_ref()[first..first + n * (n + 1) / 2], n),
        None => DMatrix::zeros(n, n),
    }
}

/// The parameters the solver derives from the others, filled in: the modal damping matrix with
/// the fixed-base ratio ζ for every mode (the generated `params_with` of a variant of several
/// coordinates calls this).
pub fn fill_derived<V: Variant>(p: V::Params, phys: &Physical) -> V::Params {
    with_modal_damping::<V>(p, &[phys.zeta])
}

/// The reference quantities every variant's `structure` kernel gives by the same names, whatever
/// its number of coordinates.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RigidBody {
    /// θ_cr, eq (39).
    pub theta_cr: f64,
    /// E_ref, the rigid structure's potential-energy barrier.
    pub e_ref: f64,
    /// R.
    pub r: f64,
    /// α.
    pub alpha: f64,
    /// p = sqrt(g/R).
    pub p: f64,
    /// The thin-plate base inertia 4/3 m_b B².
    pub i_bc_plate: f64,
}

impl RigidBody {
    /// From one evaluation of `V`'s `structure` kernel.
    pub fn of<V: Variant>(s: &V::Structure) -> RigidBody {
        let get = |name| <V as Layout>::structure_value(s, name);
        RigidBody {
            theta_cr: get("theta_cr"),
            e_ref: get("e_ref"),
            r: get("r"),
            alpha: get("alpha"),
            p: get("p_freq"),
            i_bc_plate: get("i_bc_plate"),
        }
    }
}
