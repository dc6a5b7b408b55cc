//! The generated Taylor-mode kernels (`rocking_kernels::taylor`) of each kernel variant, behind a
//! trait so that the hybrid driver stays generic and monomorphised as with [`Variant`].
//!
//! The generator emits the Taylor kernels as free functions per variant module; the generated
//! `for_each_variant!` binds each variant type to its module here, so a model added to the
//! derivation gets its implementation without a hand-written list.

use rocking_kernels::kernels::{self, index::power as pwr};
use rocking_kernels::taylor;
use rocking_kernels::{best_isa, Array, Variant};
use rocking_motion::GroundMotion;
use rocking_ode::taylor::{TaylorEvents, TaylorSystem};

use crate::layout::{Contact, Free};

const RIGHT: f64 = 1.0;
const LEFT: f64 = -1.0;

/// The ground's generalised forces `[Q_θ, Q_v]` one Taylor order at a time: coefficient k from
/// the series of the base's `[θ, v, θ', v']` up to order k.
pub(crate) type GroundForces<'a, const N: usize> =
    dyn FnMut(usize, &[[f64; N]; 4]) -> [f64; 2] + 'a;

/// A kernel variant's Taylor-mode kernels (see the generated `rocking_kernels::taylor::<variant>`
/// for the inputs; series hold their first N coefficients). The series are passed as slices of
/// the variant's lengths (`V::X::LEN` rows for a rocking state, `V::Xc::LEN` for a contact one):
/// each call checks the length once and hands the generated kernel its array. The rocking
/// right-hand sides, where a Taylor step spends most of its time, run in the CPU's best
/// instruction set (`rocking_kernels::best_isa!`: the same bits, 8–10 % off a Fig. 3 simulation
/// with AVX2); the contact, uplift and power kernels are short, and the call into AVX2 code cost
/// them more than it saved (a record case ran 4–12 % slower with them dispatched too).
///
/// # Panics
///
/// When a slice does not have the variant's length (a programming error).
pub trait TaylorVariant: Variant {
    /// Taylor coefficients of the rocking state `[θ, u_1..u_n, θ', u_1'..u_n']` from `x[i][0]`.
    fn rocking_series<const N: usize>(x: &mut [[f64; N]], ug: &[f64; N], s: f64, p: &Self::Params);
    /// [`rocking_series`](Self::rocking_series) with `ug` ≡ 0 (fewer series products).
    fn rocking_series_free<const N: usize>(x: &mut [[f64; N]], s: f64, p: &Self::Params);
    /// [`rocking_series`](Self::rocking_series) by a run-time solve: M(q) and F one order at
    /// a time, M₀ q''ₖ = Fₖ − Σⱼ Mⱼ q''ₖ₋ⱼ ([`crate::spd::second_order_series`]), instead of
    /// the symbolic solve's series. Equal to rounding, and dearer for every basis generated
    /// (see [`crate::rhs`]).
    fn rocking_series_solved<const N: usize>(
        x: &mut [[f64; N]],
        ug: &[f64; N],
        s: f64,
        p: &Self::Params,
    );
    /// Taylor coefficients of the contact state `[u_1..u_n, u_1'..u_n']` from `xc[i][0]`.
    fn contact_series<const N: usize>(xc: &mut [[f64; N]], ug: &[f64; N], p: &Self::Params);
    /// [`contact_series`](Self::contact_series) with `ug` ≡ 0.
    fn contact_series_free<const N: usize>(xc: &mut [[f64; N]], p: &Self::Params);
    /// The uplift function f_s along a contact series.
    fn uplift_series<const N: usize>(
        xc: &[[f64; N]],
        ug: &[f64; N],
        s: f64,
        p: &Self::Params,
    ) -> [f64; N];
    /// `[ground, damping]` power along a rocking-state series.
    fn power_series<const N: usize>(
        x: &[[f64; N]],
        ug: &[f64; N],
        s: f64,
        p: &Self::Params,
    ) -> [[f64; N]; 2];
    /// Taylor coefficients of the free base's state `[θ, v, u_1..u_n, θ', v', u_1'..u_n']` on
    /// compliant ground from `y[i][0]`: M(q) q'' = F + Q_ground solved order by order
    /// ([`crate::spd::second_order_series`]), `ground(k, base)` the k-th coefficients of
    /// `[Q_θ, Q_v]` from the series of `[θ, v, θ', v']` up to order k.
    fn free_series<const N: usize>(
        y: &mut [[f64; N]],
        ug: &[f64; N],
        s: f64,
        p: &Self::Params,
        ground: &mut GroundForces<'_, N>,
    );
    /// `[ground, damping]` power along a free-base series (without the ground's own power).
    fn free_power_series<const N: usize>(
        y: &[[f64; N]],
        ug: &[f64; N],
        s: f64,
        p: &Self::Params,
    ) -> [[f64; N]; 2];
}

/// A slice of series as the array a generated kernel of layout `$l` takes (`$len`: `X` or `XC`).
macro_rules! rows {
    ($x:expr, $l:ident :: $len:ident) => {{
        let rows = $x.len();
        $x.try_into()
            .unwrap_or_else(|_| panic!("series of {rows} rows, the variant has {}", $l::$len))
    }};
}

macro_rules! taylor_variant {
    ($($ty:ident => $module:ident : $nq:ident),* $(,)?) => {$(
        impl TaylorVariant for kernels::$ty {
            fn rocking_series<const N: usize>(
                x: &mut [[f64; N]],
                ug: &[f64; N],
                s: f64,
                p: &Self::Params,
            ) {
                use kernels::layout::$nq as l;
                let x = rows!(x, l::X);
                best_isa!(taylor::$module::rocking_rhs(x, ug, s, p));
            }
            fn rocking_series_free<const N: usize>(x: &mut [[f64; N]], s: f64, p: &Self::Params) {
                use kernels::layout::$nq as l;
                let x = rows!(x, l::X);
                best_isa!(taylor::$module::rocking_rhs_free(x, s, p));
            }
            fn rocking_series_solved<const N: usize>(
                x: &mut [[f64; N]],
                ug: &[f64; N],
                s: f64,
                p: &Self::Params,
            ) {
                use kernels::layout::$nq as l;
                let mut mass = taylor::$module::mass_matrix::<N>(s, p);
                let mut forcing = taylor::$module::forcing::<N>(s, p);
                let mut q = [[0.0; N]; l::Q];
                let mut m = [[0.0; N]; l::MASS_MATRIX];
                let mut acc = [[0.0; N]; l::Q];
                crate::spd::second_order_series(x, &mut m, &mut acc, |k, x, mk, fk| {
                    let x: &[[f64; N]; l::X] = rows!(x, l::X);
                    for (qi, xi) in q.iter_mut().zip(x) {
                        qi[k] = xi[k];
                    }
                    mk.copy_from_slice(&mass(k, &q));
                    fk.copy_from_slice(&forcing(k, x, ug));
                });
            }
            fn contact_series<const N: usize>(
                xc: &mut [[f64; N]],
                ug: &[f64; N],
                p: &Self::Params,
            ) {
                use kernels::layout::$nq as l;
                taylor::$module::contact_rhs(rows!(xc, l::XC), ug, p);
            }
            fn contact_series_free<const N: usize>(xc: &mut [[f64; N]], p: &Self::Params) {
                use kernels::layout::$nq as l;
                taylor::$module::contact_rhs_free(rows!(xc, l::XC), p);
            }
            fn uplift_series<const N: usize>(
                xc: &[[f64; N]],
                ug: &[f64; N],
                s: f64,
                p: &Self::Params,
            ) -> [f64; N] {
                use kernels::layout::$nq as l;
                taylor::$module::uplift(rows!(xc, l::XC), ug, s, p)[0]
            }
            fn power_series<const N: usize>(
                x: &[[f64; N]],
                ug: &[f64; N],
                s: f64,
                p: &Self::Params,
            ) -> [[f64; N]; 2] {
                use kernels::layout::$nq as l;
                taylor::$module::power(rows!(x, l::X), ug, s, p)
            }
            fn free_series<const N: usize>(
                y: &mut [[f64; N]],
                ug: &[f64; N],
                s: f64,
                p: &Self::Params,
                ground: &mut GroundForces<'_, N>,
            ) {
                use kernels::layout::$nq as l;
                let mut mass = taylor::$module::free_mass_matrix::<N>(s, p);
                let mut forcing = taylor::$module::free_forcing::<N>(s, p);
                let mut qf = [[0.0; N]; l::QF];
                let mut base = [[0.0; N]; 4];
                let mut m = [[0.0; N]; l::FREE_MASS_MATRIX];
                let mut acc = [[0.0; N]; l::QF];
                crate::spd::second_order_series(y, &mut m, &mut acc, |k, y, mk, fk| {
                    let y: &[[f64; N]; l::Y] = rows!(y, l::Y);
                    for (i, qi) in qf.iter_mut().enumerate() {
                        qi[k] = y[i][k];
                    }
                    for (b, &r) in base.iter_mut().zip(&Free::<Self>::BASE) {
                        b[k] = y[r][k];
                    }
                    mk.copy_from_slice(&mass(k, &qf));
                    fk.copy_from_slice(&forcing(k, y, ug));
                    let [q_theta, q_v] = ground(k, &base);
                    fk[Free::<Self>::THETA] += q_theta;
                    fk[Free::<Self>::V] += q_v;
                });
            }
            fn free_power_series<const N: usize>(
                y: &[[f64; N]],
                ug: &[f64; N],
                s: f64,
                p: &Self::Params,
            ) -> [[f64; N]; 2] {
                use kernels::layout::$nq as l;
                taylor::$module::free_power(rows!(y, l::Y), ug, s, p)
            }
        }
    )*};
}

rocking_kernels::for_each_variant!(taylor_variant, layout);

/// The rocking phase about `s` as a [`TaylorSystem`]: state `[θ, u_1..u_n, θ', u_1'..u_n']`, then
/// `[W, D]` when `D` exceeds its length, each divided by its natural scale so that one tolerance
/// serves all (as the Runge–Kutta path's absolute tolerances do).
pub(crate) struct RockingSystem<'a, V: TaylorVariant, M: ?Sized, const D: usize> {
    pub p: V::Params,
    pub motion: &'a M,
    pub s: f64,
    pub scale: [f64; D],
}

impl<V: TaylorVariant, M: GroundMotion + ?Sized, const D: usize> TaylorSystem<D>
    for RockingSystem<'_, V, M, D>
{
    fn coefficients<const N: usize>(&mut self, t0: f64, x: &mut [[f64; N]; D]) {
        let nx = V::X::LEN;
        let (ug, free) = excitation_series::<M, N>(self.motion, t0);
        // The kernels run on the mechanical rows of `x` itself, unscaled in place and scaled
        // back after (no second array to zero and copy per step); the first coefficients are
        // put back as they came, not rounded through the scale.
        let y0: [f64; D] = std::array::from_fn(|i| x[i][0]);
        for (xi, sc) in x[..nx].iter_mut().zip(&self.scale) {
            xi[0] *= sc;
        }
        if free {
            V::rocking_series_free(&mut x[..nx], self.s, &self.p);
        } else {
            V::rocking_series(&mut x[..nx], &ug, self.s, &self.p);
        }
        let pw = (D > nx).then(|| V::power_series(&x[..nx], &ug, self.s, &self.p));
        for i in 0..nx {
            let inv = 1.0 / self.scale[i];
            for c in &mut x[i][1..] {
                *c *= inv;
            }
            x[i][0] = y0[i];
        }
        if let Some(pw) = pw {
            integrate_power(x, nx, &pw, &self.scale);
        }
    }
}

/// Full contact as a [`TaylorSystem`]: state `[u_1..u_n, u_1'..u_n']`, then `[W, D]` when `D`
/// exceeds its length, scaled as in [`RockingSystem`].
pub(crate) struct ContactSystem<'a, V: TaylorVariant, M: ?Sized, const D: usize> {
    pub p: V::Params,
    pub motion: &'a M,
    pub scale: [f64; D],
}

impl<V: TaylorVariant, M: GroundMotion + ?Sized, const D: usize> ContactSystem<'_, V, M, D> {
    /// The unscaled contact series (its first `V::Xc::LEN` rows) from the first coefficients of
    /// `x`, or all of them (`all`), and ü_g's.
    fn contact<const N: usize>(&self, t0: f64, x: &[[f64; N]; D], all: bool) -> Series<N, D> {
        let ug = excitation_series::<M, N>(self.motion, t0);
        let mut q = [[0.0; N]; D];
        for i in 0..V::Xc::LEN {
            let upto = if all { N } else { 1 };
            for k in 0..upto {
                q[i][k] = x[i][k] * self.scale[i];
            }
        }
        (q, ug)
    }
}

/// The unscaled contact series and ü_g's with whether it vanishes ([`excitation_series`]).
type Series<const N: usize, const D: usize> = ([[f64; N]; D], ([f64; N], bool));

impl<V: TaylorVariant, M: GroundMotion + ?Sized, const D: usize> TaylorSystem<D>
    for ContactSystem<'_, V, M, D>
{
    fn coefficients<const N: usize>(&mut self, t0: f64, x: &mut [[f64; N]; D]) {
        let nc = V::Xc::LEN;
        let (mut q, (ug, free)) = self.contact(t0, x, false);
        if free {
            V::contact_series_free(&mut q[..nc], &self.p);
        } else {
            V::contact_series(&mut q[..nc], &ug, &self.p);
        }
        for i in 0..nc {
            let inv = 1.0 / self.scale[i];
            for k in 1..N {
                x[i][k] = q[i][k] * inv;
            }
        }
        if D > nc {
            // The rocking state of full contact: θ ≡ θ' ≡ 0.
            let mut full = [[[0.0; N]; D]; 2];
            let full = &mut full.as_flattened_mut()[..V::X::LEN];
            for (i, qi) in q[..nc].iter().enumerate() {
                full[Contact::<V>::in_rocking(i)] = *qi;
            }
            let pw = V::power_series(full, &ug, RIGHT, &self.p);
            integrate_power(x, nc, &pw, &self.scale);
        }
    }
    /// The uplift functions follow ü_g even where the state does not (a rigid column in contact
    /// does not move): a step may run a lower order only where ü_g is at most linear up to the
    /// next kink (a record's sample interval, or no excitation), which every order keeps exact.
    fn may_lower_order(&mut self, t0: f64) -> bool {
        let mut ug = [0.0; 4];
        self.motion.accel_series(t0, &mut ug);
        ug[2] == 0.0 && ug[3] == 0.0
    }
}

/// The uplift functions `[f_+, f_-]` along a contact step are the events of full contact.
impl<V: TaylorVariant, M: GroundMotion + ?Sized, const D: usize> TaylorEvents<D, 2>
    for ContactSystem<'_, V, M, D>
{
    fn event_coefficients<const N: usize>(&mut self, t0: f64, x: &[[f64; N]; D]) -> [[f64; N]; 2] {
        let (q, (ug, _)) = self.contact(t0, x, true);
        let q = &q[..V::Xc::LEN];
        [RIGHT, LEFT].map(|s| V::uplift_series(q, &ug, s, &self.p))
    }
}

/// ü_g's series on the piece of the motion from `t0`, and whether it vanishes (after the
/// excitation, or on a piece of zero acceleration): then the kernels' `_free` twins apply.
#[inline]
pub(crate) fn excitation_series<M: GroundMotion + ?Sized, const N: usize>(
    motion: &M,
    t0: f64,
) -> ([f64; N], bool) {
    let mut ug = [0.0; N];
    // From the motion's end on, ü_g ≡ 0 without asking the motion, nor reading back as vectors
    // the N coefficients it has just stored one by one (a store-forwarding stall on every step
    // after a pulse: 1.5 % of Fig. 3's time).
    if t0 >= motion.end() {
        return (ug, true);
    }
    motion.accel_series(t0, &mut ug);
    let free = ug.iter().all(|&a| a == 0.0);
    (ug, free)
}

/// `W' = P_ground`, `D' = P_damping`: coefficient k + 1 of an integral is coefficient k of its
/// rate over k + 1 (W and D sit from component `first` on).
fn integrate_power<const N: usize, const D: usize>(
    x: &mut [[f64; N]; D],
    first: usize,
    pw: &[[f64; N]; 2],
    scale: &[f64; D],
) {
    for (j, rate) in [pwr::GROUND, pwr::DAMPING].into_iter().enumerate() {
        for k in 0..N - 1 {
            x[first + j][k + 1] = pw[rate][k] / ((k + 1) as f64 * scale[first + j]);
        }
    }
}
