//! The dense output of one step as the driver reads it: the state `[θ, u, θ', u']` anywhere on
//! the step, one component alone, and a bound of a component's size over the step.
//!
//! A Runge–Kutta step offers the state only (any `Fn(f64) -> [f64; 4]` is a [`StepView`]); a
//! Taylor step's polynomial evaluates one component for a D-th of the cost and bounds it for
//! free, which is what the search of maxima inside a step spends most on.

use rocking_ode::taylor::Taylor;

/// What the driver reads of a step's dense output.
pub(crate) trait StepView {
    /// The state `[θ, u, θ', u']` at `t` in the step.
    fn state(&self, t: f64) -> [f64; 4];
    /// Component `i` of [`state`](Self::state) alone.
    fn component(&self, i: usize, t: f64) -> f64 {
        self.state(t)[i]
    }
    /// An upper bound of |component `i`| over the whole step (∞ when unknown): an extremum
    /// inside the step cannot raise a maximum already above it.
    fn bound(&self, _i: usize) -> f64 {
        f64::INFINITY
    }
}

impl<F: Fn(f64) -> [f64; 4]> StepView for F {
    fn state(&self, t: f64) -> [f64; 4] {
        self(t)
    }
}

/// A Taylor step of a phase whose (scaled) state rows map onto `[θ, u, θ', u']` by `rows`
/// (`None`: identically 0 in the phase, as θ and θ' in full contact).
pub(crate) struct TaylorStep<'a, const D: usize> {
    pub ode: &'a Taylor<D>,
    pub scale: [f64; D],
    pub rows: [Option<usize>; 4],
}

impl<const D: usize> StepView for TaylorStep<'_, D> {
    fn state(&self, t: f64) -> [f64; 4] {
        let y = self.ode.dense(t);
        self.rows.map(|r| r.map_or(0.0, |r| y[r] * self.scale[r]))
    }

    fn component(&self, i: usize, t: f64) -> f64 {
        self.rows[i].map_or(0.0, |r| self.ode.dense_component(r, t) * self.scale[r])
    }

    /// Σ |c_k| h^k over the step's polynomial, with a margin for its rounding.
    fn bound(&self, i: usize) -> f64 {
        let Some(r) = self.rows[i] else {
            return 0.0;
        };
        let c = &self.ode.coefficients()[r][..=self.ode.order()];
        let h = self.ode.last_step_size();
        let sum = c.iter().rev().fold(0.0, |acc, v| acc * h + v.abs());
        sum * self.scale[r].abs() * (1.0 + 1e-12)
    }
}
