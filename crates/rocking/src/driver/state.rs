//! What one run carries between its phases: the simulation [`Sim`], where the hybrid system goes
//! [`Next`], the integrals it carries ([`Integrals`]), and the guards that turn a run that would
//! not end into an error.
//!
//! The lowest room of the driver with behaviour: the rooms with methods on [`Sim`] import from
//! here; of the driver this one imports only the values-only [`Record`].

use nalgebra::{DMatrix, SVector};
use rocking_kernels::kernels::index::{energy as en, mass_matrix as mm, power as pwr};
use rocking_kernels::{Array, Variant};
use rocking_motion::GroundMotion;
use rocking_ode::{Options as OdeOptions, Tolerances};

use super::record::Record;
use crate::error::SimError;
use crate::layout::{Contact, PreImpact, Rocking};
use crate::options::Options;
use crate::results::{Phase, SolverStats, Time};
use crate::structure::Derived;
use crate::taylor::TaylorVariant;

/// A phase's integrator state: the mechanical state, then W and D when they are carried.
pub(super) type Y<const N: usize> = SVector<f64, N>;
/// The two event functions of a phase (f_+ and f_- in contact; impact and overturning while
/// rocking).
pub(super) type G2 = SVector<f64, 2>;

/// The right corner as pivot (θ > 0).
pub(super) const RIGHT: f64 = 1.0;
/// The left corner as pivot (θ < 0).
pub(super) const LEFT: f64 = -1.0;

/// Where the hybrid system goes next.
pub(super) enum Next<V: Variant> {
    Contact {
        t: f64,
        /// `[u_1..u_n, u_1'..u_n']`.
        xc: V::Xc,
        carried: Integrals,
        /// Just come to rest: no uplift before one step has been taken (see
        /// [`Sim::contact_start`](super::Sim::contact_start)).
        settle: bool,
    },
    Rocking {
        t: f64,
        s: f64,
        /// `[θ, u_1..u_n, θ', u_1'..u_n']`.
        x: V::X,
        /// The impact event is s θ / (t − t0)^n (see the rocking phases).
        n: i32,
        carried: Integrals,
    },
    Done {
        t: f64,
        phase: Phase,
        s: f64,
        state: V::X,
        carried: Integrals,
    },
}

/// The integrals a run carries from phase to phase when the energy bookkeeping is on (zeros
/// otherwise): W, the ground acceleration's work, and D, the damping's dissipation.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(super) struct Integrals {
    pub(super) w: f64,
    pub(super) d: f64,
}

impl Integrals {
    /// The integrals of a phase's integrator state `y` from component `first` on (the
    /// mechanical state's length: the layout's `INTEGRALS`), or zeros when they are not carried.
    pub(super) fn of(y: &[f64], first: usize) -> Self {
        if y.len() >= first + 2 {
            Integrals {
                w: y[first],
                d: y[first + 1],
            }
        } else {
            Integrals::default()
        }
    }

    /// The rates W' and D' of the `power` kernel's output.
    pub(super) fn of_power(power: &[f64]) -> Self {
        Integrals {
            w: power[pwr::GROUND],
            d: power[pwr::DAMPING],
        }
    }

    /// Puts W and D into a phase's integrator state (or its rate) `y` from component `first` on.
    pub(super) fn put(self, y: &mut [f64], first: usize) {
        y[first] = self.w;
        y[first + 1] = self.d;
    }

    /// Component `i` of a phase's integrator state: the mechanical state `x`, then W and D.
    pub(super) fn after(self, x: &[f64], i: usize) -> f64 {
        match i.checked_sub(x.len()) {
            None => x[i],
            Some(0) => self.w,
            Some(_) => self.d,
        }
    }
}

/// The rocking state `[θ, u, θ', u']` of full contact at the contact state `xc = [u, u']`
/// (θ = θ' = 0); each `u` is u_1..u_n.
pub(super) fn contact_x<V: Variant>(xc: &V::Xc) -> V::X {
    let xc = xc.values();
    V::X::from_fn(|i| Contact::<V>::of_rocking(i).map_or(0.0, |j| xc[j]))
}

/// The contact state `[u, u']` of the rocking state `x`.
pub(super) fn contact_of<V: Variant>(x: &V::X) -> V::Xc {
    let x = x.values();
    V::Xc::from_fn(|i| x[Contact::<V>::in_rocking(i)])
}

/// The pre-impact state `xi = [u, u', θ']` of the rocking state `x` (θ = 0).
pub(super) fn impact_state<V: Variant>(x: &V::X) -> V::Xi {
    let x = x.values();
    V::Xi::from_fn(|i| x[PreImpact::<V>::in_rocking(i)])
}

/// The rocking state of a phase's integrator state `y` (its first `V::X::LEN` components).
pub(super) fn rocking_state<V: Variant>(y: &[f64]) -> V::X {
    V::X::from_fn(|i| y[i])
}

/// The contact state of a contact phase's integrator state `y`.
pub(super) fn contact_state<V: Variant>(y: &[f64]) -> V::Xc {
    V::Xc::from_fn(|i| y[i])
}

/// One run: `NR` and `NC` are the sizes of the rocking and contact states (`V::X::LEN` and
/// `V::Xc::LEN`, 2n + 2 and 2n, or two more each with the energy integrals).
pub(super) struct Sim<
    'a,
    V: TaylorVariant,
    M: GroundMotion + ?Sized,
    const NR: usize,
    const NC: usize,
> {
    pub(super) p: V::Params,
    pub(super) motion: &'a M,
    pub(super) opts: &'a Options,
    pub(super) derived: Derived,
    pub(super) p_seconds: Option<f64>,
    /// |θ'| below which an impact or a rocking start ends in full contact.
    pub(super) rest_rate: f64,
    /// |θ'| from which an impact counts as significant.
    pub(super) significant_rate: f64,
    /// The potential energy at rest (the zero of the reported total energy).
    pub(super) v_rest: f64,
    pub(super) ode_options: OdeOptions,
    pub(super) contact_tol: Tolerances<NC>,
    pub(super) rocking_tol: Tolerances<NR>,
    /// Natural scales of the phase states (the Taylor method integrates the state over them).
    pub(super) contact_scale: [f64; NC],
    pub(super) rocking_scale: [f64; NR],
    pub(super) stats: SolverStats,
    /// Events so far (the guard `max_events`).
    pub(super) events: u64,
    /// The total weight W and the uplift moment W B (the forces' units).
    pub(super) weight: f64,
    pub(super) wb: f64,
    /// The fastest rate of the dynamics (the larger of the column's fixed-base and uplifted
    /// frequencies, the rocking time scale p and the excitation's): how much a quantity can
    /// change inside a step.
    pub(super) fastest_rate: f64,
    /// ψ_i(1): the column's top deflection is Σ u_i ψ_i(1) (u itself for one coordinate).
    pub(super) top: V::Shape,
    /// The first fixed-base mode φ_1 with a unit top deflection: the direction of the initial
    /// `u` and `u'` of several coordinates (u_cr is measured along it).
    pub(super) first_mode: V::Shape,
    /// The column's stiffness and mass in full contact, for the settle test.
    pub(super) metric: Metric,
    pub(super) rec: Record,
}

/// K and M of the u_i (k̃ and m̃ for one coordinate), inverted once per run: the norms of the
/// free vibration's energy ellipse.
pub(super) struct Metric {
    pub(super) k: f64,
    pub(super) m: f64,
    pub(super) k_inv: DMatrix<f64>,
    pub(super) m_inv: DMatrix<f64>,
}

impl<V: TaylorVariant, M: GroundMotion + ?Sized, const NR: usize, const NC: usize>
    Sim<'_, V, M, NR, NC>
{
    /// Whether W and D are carried (the energy bookkeeping was asked for).
    pub(super) const ENERGY: bool = NR > V::X::LEN;

    pub(super) fn time(&self, t: f64) -> Time {
        let tau = t * self.derived.p;
        Time {
            tau,
            seconds: self.p_seconds.map(|ps| tau / ps),
        }
    }

    /// Kinetic plus potential energy, from zero at rest.
    pub(super) fn total_energy(&self, x: &V::X, s: f64) -> f64 {
        let e = V::energy(x, s, &self.p);
        e[en::KINETIC] + e[en::GRAVITY] + e[en::STRAIN] - self.v_rest
    }

    /// Counts an event at `t`; the guard `max_events`.
    pub(super) fn count_event(&mut self, t: f64) -> Result<(), SimError> {
        self.events += 1;
        if self.events > self.opts.max_events {
            return Err(SimError::TooManyEvents {
                max_events: self.opts.max_events,
                tau: self.time(t).tau,
            });
        }
        Ok(())
    }

    /// The guard on the total number of step attempts of a run, given the running phase's
    /// attempts at `t` (a count, not the integrator's counters: read as a pair of just-stored
    /// fields they cost a store-forwarding stall on every step).
    pub(super) fn guard_steps(&self, attempts: u64, t: f64) -> Result<(), SimError> {
        let steps = self.stats.steps + self.stats.rejected_steps + attempts;
        if steps > self.opts.max_steps {
            return Err(SimError::TooManySteps {
                max_steps: self.opts.max_steps,
                tau: self.time(t).tau,
            });
        }
        Ok(())
    }

    /// Where the next step must end: the next kink of the excitation, or the run's end.
    pub(super) fn t_stop(&self, t: f64) -> f64 {
        self.motion
            .next_kink(t)
            .map_or(self.opts.t_end, |k| k.min(self.opts.t_end))
    }

    /// The longest contact step from `t0`: the excitation's resolution while it lasts. A rigid
    /// column in contact gives the error control nothing to follow, so no excursion of f_s may
    /// fall between steps.
    pub(super) fn contact_h_max(&self, t0: f64) -> f64 {
        if t0 < self.motion.end() {
            self.motion.resolution()
        } else {
            f64::INFINITY
        }
    }

    /// The column's top deflection Σ u_i ψ_i(1) of the rocking state `x` (`rate`: of its rate,
    /// from the u_i'); u itself for one coordinate.
    pub(super) fn top(&self, x: &V::X, rate: bool) -> f64 {
        self.top_by(|i| x.values()[i], Rocking::<V>::us(rate).start)
    }

    /// Σ ψ_i(1) c(first + i): the top deflection (`first` u_1's component) or its rate (u_1''s)
    /// from the components `c` of a state.
    pub(super) fn top_by(&self, c: impl Fn(usize) -> f64, first: usize) -> f64 {
        if V::NQ == 1 {
            return c(first);
        }
        let psi = self.top.values();
        (0..V::NQ).map(|i| psi[i] * c(first + i)).sum()
    }

    /// An integration failure while rocking, explained when the mass matrix became singular:
    /// its conditioning is the smallest pivot of its Cholesky factorisation over the diagonal
    /// entry (1 − m_tu²/(m_tt m_uu) for one coordinate).
    pub(super) fn explain_failure(&self, e: rocking_ode::OdeError, y: &[f64], s: f64) -> SimError {
        let q = V::Q::from_fn(|i| y[i]);
        let m = V::mass_matrix(&q, s, &self.p);
        let conditioning = if V::NQ == 1 {
            let [mtt, mtu, muu] = [mm::M_TT, mm::M_TU, mm::M_UU].map(|k| m.values()[k]);
            (mtt * muu - mtu * mtu) / (mtt * muu)
        } else {
            smallest_pivot_ratio(m.values(), V::Q::LEN)
        };
        if conditioning.is_finite() && conditioning > 1e-8 {
            return SimError::Integration(e);
        }
        SimError::SingularMassMatrix {
            tau: self.time(e.t).tau,
            conditioning,
            u_over_ucr: self.top(&rocking_state::<V>(y), false) / self.derived.u_cr,
            cause: e,
        }
    }
}

/// The smallest ratio d_k / M_kk of the pivots d_k of the LDLᵀ factorisation of the symmetric
/// n × n matrix whose upper triangle (row by row) is `upper`: 1 for a diagonal matrix, 0 for a
/// singular one.
fn smallest_pivot_ratio(upper: &[f64], n: usize) -> f64 {
    let mut a = DMatrix::zeros(n, n);
    let mut k = 0;
    for i in 0..n {
        for j in i..n {
            a[(i, j)] = upper[k];
            a[(j, i)] = upper[k];
            k += 1;
        }
    }
    let diag = a.diagonal();
    let mut ratio = f64::INFINITY;
    for k in 0..n {
        let d = a[(k, k)];
        ratio = ratio.min(d / diag[k]);
        for i in k + 1..n {
            let f = a[(i, k)] / d;
            for j in k + 1..n {
                a[(i, j)] -= f * a[(k, j)];
            }
        }
    }
    ratio
}

/// The free vibration of the column in full contact with no ground motion: it stays inside the
/// ellipsoid of its energy `vib` (kinetic + strain), ½ u'ᵀ M u' + ½ uᵀ K u <= vib.
pub(super) struct Ellipse<'a> {
    pub(super) vib: f64,
    pub(super) metric: &'a Metric,
}

impl Ellipse<'_> {
    /// For g(xc) = c + aᵀu + bᵀu' (affine in the contact state xc = [u, u']): (c, the largest
    /// |aᵀu + bᵀu'| on the ellipsoid) = (c, sqrt(2 vib (aᵀK⁻¹a + bᵀM⁻¹b))).
    pub(super) fn reach<V: Variant>(&self, g: impl Fn(&V::Xc) -> f64) -> (f64, f64) {
        let n = V::NQ;
        let c = g(&V::Xc::from_fn(|_| 0.0));
        let unit = |j: usize| g(&V::Xc::from_fn(|i| if i == j { 1.0 } else { 0.0 })) - c;
        let Metric { k, m, .. } = *self.metric;
        let norm = if n == 1 {
            let (a, b) = (unit(Contact::<V>::u(0)), unit(Contact::<V>::u_dot(0)));
            a * a / k + b * b / m
        } else {
            let ab = V::Xc::from_fn(unit);
            let (a, b) = (
                &ab.values()[Contact::<V>::us(false)],
                &ab.values()[Contact::<V>::us(true)],
            );
            quadratic(&self.metric.k_inv, a) + quadratic(&self.metric.m_inv, b)
        };
        (c, (2.0 * self.vib * norm).sqrt())
    }
}

/// vᵀ A v.
fn quadratic(a: &DMatrix<f64>, v: &[f64]) -> f64 {
    let mut sum = 0.0;
    for (i, vi) in v.iter().enumerate() {
        for (j, vj) in v.iter().enumerate() {
            sum += vi * a[(i, j)] * vj;
        }
    }
    sum
}
