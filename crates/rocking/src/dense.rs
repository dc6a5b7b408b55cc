//! The dense output of one step as the driver reads it: the rocking state
//! `x = [θ, u_1..u_n, θ', u_1'..u_n']` anywhere on the step, one component alone, and a bound of
//! a component's size over the step.
//!
//! A Runge–Kutta step offers the state only (any `Fn(f64) -> X` is a [`StepView`]); a Taylor
//! step's polynomial evaluates one component for a D-th of the cost and bounds it for free, which
//! is what the search of maxima inside a step spends most on.

use std::marker::PhantomData;

use rocking_kernels::{Array, Layout};
use rocking_ode::poly;
use rocking_ode::taylor::Taylor;

use crate::layout::Contact;

/// What the driver reads of a step's dense output, the rocking state `X` of its variant.
pub(crate) trait StepView<X: Array> {
    /// The state `[θ, u_1..u_n, θ', u_1'..u_n']` at `t` in the step.
    fn state(&self, t: f64) -> X;
    /// Component `i` of [`state`](Self::state) alone.
    fn component(&self, i: usize, t: f64) -> f64 {
        self.state(t).values()[i]
    }
    /// An upper bound of |component `i`| over the whole step (∞ when unknown): an extremum
    /// inside the step cannot raise a maximum already above it.
    fn bound(&self, _i: usize) -> f64 {
        f64::INFINITY
    }
    /// The rate of [`state`](Self::state) at `t`, `[θ', u', θ'', u'']`, where the integrator
    /// evaluated it from the equations there (a Runge–Kutta step's end): `None` elsewhere.
    fn exact_rate(&self, _t: f64) -> Option<X> {
        None
    }
    /// The second derivative of [`state`](Self::state) at `t`, `[θ'', u'', θ''', u''']`, where the
    /// integrator has it from the equations (the series of the Taylor step that starts there):
    /// `None` elsewhere.
    fn exact_second_rate(&self, _t: f64) -> Option<X> {
        None
    }
}

impl<X: Array, F: Fn(f64) -> X> StepView<X> for F {
    fn state(&self, t: f64) -> X {
        self(t)
    }
}

/// A Runge–Kutta step's dense output `dense`, with the rate the integrator evaluated at the
/// step's end `t_new` (its last stage: the first of the next step).
pub(crate) struct RkStep<F, X> {
    pub dense: F,
    pub t_new: f64,
    pub rate: X,
}

impl<X: Array, F: Fn(f64) -> X> StepView<X> for RkStep<F, X> {
    fn state(&self, t: f64) -> X {
        (self.dense)(t)
    }

    fn exact_rate(&self, t: f64) -> Option<X> {
        (t == self.t_new).then_some(self.rate)
    }
}

/// A Taylor step of a phase of variant `V` whose (scaled) state rows are the rocking state's
/// (`contact`: false) or the contact state's `[u_1..u_n, u_1'..u_n']` (θ and θ' identically 0 in
/// full contact).
pub(crate) struct TaylorStep<'a, V, const D: usize> {
    pub ode: &'a Taylor<D>,
    pub scale: [f64; D],
    pub contact: bool,
    pub variant: PhantomData<V>,
}

impl<V: Layout, const D: usize> TaylorStep<'_, V, D> {
    /// The row of the step's state that holds component `i` of the rocking state (`None`:
    /// identically 0 in the phase).
    fn row(&self, i: usize) -> Option<usize> {
        if self.contact {
            Contact::<V>::of_rocking(i)
        } else {
            Some(i)
        }
    }
}

impl<V: Layout, const D: usize> StepView<V::X> for TaylorStep<'_, V, D> {
    fn state(&self, t: f64) -> V::X {
        let y = self.ode.dense(t);
        V::X::from_fn(|i| self.row(i).map_or(0.0, |r| y[r] * self.scale[r]))
    }

    fn component(&self, i: usize, t: f64) -> f64 {
        self.row(i)
            .map_or(0.0, |r| self.ode.dense_component(r, t) * self.scale[r])
    }

    /// Σ |c_k| h^k over the step's polynomial, with a margin for its rounding.
    fn bound(&self, i: usize) -> f64 {
        let Some(r) = self.row(i) else {
            return 0.0;
        };
        let c = &self.ode.coefficients()[r][..=self.ode.order()];
        let h = self.ode.last_step_size();
        let sum = c[0].abs() + poly::abs_tail(c, h);
        sum * self.scale[r].abs() * (1.0 + 1e-12)
    }

    /// At the step's start, of a rocking phase: the series' coefficient 1.
    fn exact_rate(&self, t: f64) -> Option<V::X> {
        self.start_derivative(t, 1)
    }

    /// At the step's start, of a rocking phase: twice the series' coefficient 2.
    fn exact_second_rate(&self, t: f64) -> Option<V::X> {
        self.start_derivative(t, 2)
    }
}

impl<V: Layout, const D: usize> TaylorStep<'_, V, D> {
    /// The k-th derivative of the rocking state at the step's start, `k!` times the series'
    /// coefficient k (`None` elsewhere, in full contact, or above the step's order).
    fn start_derivative(&self, t: f64, k: usize) -> Option<V::X> {
        let exact = !self.contact && t == self.ode.t_old() && k <= self.ode.order();
        let c = self.ode.coefficients();
        let factorial = (1..=k).product::<usize>() as f64;
        exact.then(|| V::X::from_fn(|i| factorial * c[i][k] * self.scale[i]))
    }
}

/// A finished Taylor step of the rocking phase (`ode`, a copy kept past the step after it) seen
/// with the first and second derivatives of the state at its end from the series of the step
/// after it, expanded there: the exact rates [`TaylorStep`] has only at its start.
pub(crate) struct TaylorStepEnd<'a, V: Layout, const D: usize> {
    pub ode: &'a Taylor<D>,
    pub scale: [f64; D],
    pub rate: V::X,
    pub second: V::X,
}

impl<'a, V: Layout, const D: usize> TaylorStepEnd<'a, V, D> {
    /// The end's rates from `next`, the integrator after the step that starts at this one's end
    /// (that step's rates at its start).
    pub(crate) fn new(ode: &'a Taylor<D>, next: &Taylor<D>, scale: [f64; D]) -> Self {
        let after = TaylorStep::<V, D> {
            ode: next,
            scale,
            contact: false,
            variant: PhantomData,
        };
        let start = next.t_old();
        let rate = after.start_derivative(start, 1);
        let second = after.start_derivative(start, 2);
        Self {
            ode,
            scale,
            rate: rate.expect("a Taylor step runs order 3 or more"),
            second: second.expect("a Taylor step runs order 3 or more"),
        }
    }

    fn step(&self) -> TaylorStep<'_, V, D> {
        TaylorStep {
            ode: self.ode,
            scale: self.scale,
            contact: false,
            variant: PhantomData,
        }
    }
}

impl<V: Layout, const D: usize> StepView<V::X> for TaylorStepEnd<'_, V, D> {
    fn state(&self, t: f64) -> V::X {
        self.step().state(t)
    }

    fn component(&self, i: usize, t: f64) -> f64 {
        self.step().component(i, t)
    }

    fn bound(&self, i: usize) -> f64 {
        self.step().bound(i)
    }

    fn exact_rate(&self, t: f64) -> Option<V::X> {
        if t == self.ode.t() {
            Some(self.rate)
        } else {
            self.step().exact_rate(t)
        }
    }

    fn exact_second_rate(&self, t: f64) -> Option<V::X> {
        if t == self.ode.t() {
            Some(self.second)
        } else {
            self.step().exact_second_rate(t)
        }
    }
}
