//! Where each quantity sits in the states the driver integrates, for a variant of n deformation
//! coordinates: named once here, beside the generated array types and sizes
//! ([`rocking_kernels::Layout`]) and output indices (`kernels::index`), so that no other file
//! counts offsets into `[θ, u_1..u_n, θ', u_1'..u_n']`.
//!
//! Each layout is a zero-sized type over the variant; its positions are constants of the
//! monomorphised code (`V::NQ` is a constant), so naming them costs nothing.

use std::marker::PhantomData;
use std::ops::Range;

use rocking_kernels::kernels::index::rocking_rhs as rr;
use rocking_kernels::{Array, Layout};

/// What component `i` of a state is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Part {
    Theta,
    /// u_k (k from 0).
    U(usize),
    ThetaDot,
    /// u_k'.
    UDot(usize),
    /// The carried integral k (k from 0: W, then D) after the mechanical state.
    Integral(usize),
}

/// The rocking state `x = [θ, u_1..u_n, θ', u_1'..u_n']` (also its rate, the output of
/// `rocking_rhs`), and in a phase's integrator state the carried integrals W, D after it.
pub(crate) struct Rocking<V>(PhantomData<V>);

impl<V: Layout> Rocking<V> {
    pub(crate) const THETA: usize = 0;
    pub(crate) const THETA_DOT: usize = V::NQ + 1;
    /// θ'' in `rocking_rhs`'s output, the rate of x (`index::rocking_rhs::THETA_DDOT` for one
    /// coordinate).
    pub(crate) const THETA_DDOT: usize = rr::THETA_DDOT + (V::NQ - 1);
    /// The first carried integral (W, then D): the mechanical state's length.
    pub(crate) const INTEGRALS: usize = 2 * V::NQ + 2;

    /// u_i (i from 0).
    pub(crate) const fn u(i: usize) -> usize {
        1 + i
    }

    /// u_i'.
    pub(crate) const fn u_dot(i: usize) -> usize {
        V::NQ + 2 + i
    }

    /// u_1..u_n (`rate`: u_1'..u_n').
    pub(crate) const fn us(rate: bool) -> Range<usize> {
        let first = if rate { Self::u_dot(0) } else { Self::u(0) };
        first..first + V::NQ
    }

    /// Whether component `i` is a velocity (θ' or a u_k').
    pub(crate) const fn is_rate(i: usize) -> bool {
        i >= Self::THETA_DOT && i < Self::INTEGRALS
    }

    /// What component `i` is.
    pub(crate) const fn part(i: usize) -> Part {
        if i == Self::THETA {
            Part::Theta
        } else if i < Self::THETA_DOT {
            Part::U(i - Self::u(0))
        } else if i == Self::THETA_DOT {
            Part::ThetaDot
        } else if i < Self::INTEGRALS {
            Part::UDot(i - Self::u_dot(0))
        } else {
            Part::Integral(i - Self::INTEGRALS)
        }
    }
}

/// The contact state `xc = [u_1..u_n, u_1'..u_n']` (θ ≡ θ' ≡ 0; also its rate), and in a
/// phase's integrator state the carried integrals W, D after it.
pub(crate) struct Contact<V>(PhantomData<V>);

impl<V: Layout> Contact<V> {
    /// The first carried integral: the mechanical state's length.
    pub(crate) const INTEGRALS: usize = 2 * V::NQ;

    /// u_i (i from 0).
    pub(crate) const fn u(i: usize) -> usize {
        i
    }

    /// u_i'.
    pub(crate) const fn u_dot(i: usize) -> usize {
        V::NQ + i
    }

    /// u_1..u_n (`rate`: u_1'..u_n').
    pub(crate) const fn us(rate: bool) -> Range<usize> {
        let first = if rate { Self::u_dot(0) } else { Self::u(0) };
        first..first + V::NQ
    }

    /// What component `i` is.
    pub(crate) const fn part(i: usize) -> Part {
        if i < Self::u_dot(0) {
            Part::U(i - Self::u(0))
        } else if i < Self::INTEGRALS {
            Part::UDot(i - Self::u_dot(0))
        } else {
            Part::Integral(i - Self::INTEGRALS)
        }
    }

    /// The component of the rocking state that component `i` of xc is.
    pub(crate) const fn in_rocking(i: usize) -> usize {
        match Self::part(i) {
            Part::U(k) => Rocking::<V>::u(k),
            Part::UDot(k) => Rocking::<V>::u_dot(k),
            _ => Rocking::<V>::INTEGRALS + (i - Self::INTEGRALS),
        }
    }

    /// The component of xc that component `i` of the rocking state is (`None`: θ or θ',
    /// identically 0 in full contact).
    pub(crate) const fn of_rocking(i: usize) -> Option<usize> {
        match Rocking::<V>::part(i) {
            Part::Theta | Part::ThetaDot => None,
            Part::U(k) => Some(Self::u(k)),
            Part::UDot(k) => Some(Self::u_dot(k)),
            Part::Integral(k) => Some(Self::INTEGRALS + k),
        }
    }
}

/// The pre-impact state `xi = [u_1..u_n, u_1'..u_n', θ']` (θ = 0).
pub(crate) struct PreImpact<V>(PhantomData<V>);

impl<V: Layout> PreImpact<V> {
    pub(crate) const THETA_DOT: usize = 2 * V::NQ;

    /// u_1..u_n (`rate`: u_1'..u_n').
    pub(crate) const fn us(rate: bool) -> Range<usize> {
        Contact::<V>::us(rate)
    }

    /// The component of the rocking state that component `i` of xi is.
    pub(crate) const fn in_rocking(i: usize) -> usize {
        if i == Self::THETA_DOT {
            Rocking::<V>::THETA_DOT
        } else {
            Contact::<V>::in_rocking(i)
        }
    }
}

/// The state on compliant ground `y = [θ, v, u_1..u_n, θ', v', u_1'..u_n']` (`q = [θ, v, u]`
/// has `V::Qf::LEN` entries; a rigid column keeps its frozen u), and in a phase's integrator
/// state the carried integrals (ground work, damping, the ground's dissipation) after it.
pub(crate) struct Free<V>(PhantomData<V>);

impl<V: Layout> Free<V> {
    /// The number of coordinates q = [θ, v, u].
    pub(crate) const NQ: usize = V::Qf::LEN;
    pub(crate) const THETA: usize = 0;
    /// The settlement v of the base centre.
    pub(crate) const V: usize = 1;
    pub(crate) const THETA_DOT: usize = Self::NQ;
    pub(crate) const V_DOT: usize = Self::NQ + 1;
    /// The first carried integral: the mechanical state's length.
    pub(crate) const INTEGRALS: usize = 2 * Self::NQ;
    /// Where the base's `[θ, v, θ', v']`, the ground kernels' input, sits.
    pub(crate) const BASE: [usize; 4] = [Self::THETA, Self::V, Self::THETA_DOT, Self::V_DOT];

    /// The rate of coordinate q_i (i from 0).
    pub(crate) const fn rate(i: usize) -> usize {
        Self::NQ + i
    }

    /// u_i (i from 0).
    pub(crate) const fn u(i: usize) -> usize {
        2 + i
    }

    /// u_i'.
    pub(crate) const fn u_dot(i: usize) -> usize {
        Self::rate(Self::u(i))
    }

    /// u_1..u_n (`rate`: u_1'..u_n').
    pub(crate) const fn us(rate: bool) -> Range<usize> {
        let first = if rate { Self::u_dot(0) } else { Self::u(0) };
        first..first + (Self::NQ - 2)
    }

    /// What component `i` is.
    pub(crate) const fn part(i: usize) -> FreePart {
        if i == Self::THETA {
            FreePart::Theta
        } else if i == Self::V {
            FreePart::V
        } else if i < Self::THETA_DOT {
            FreePart::U(i - Self::u(0))
        } else if i == Self::THETA_DOT {
            FreePart::ThetaDot
        } else if i == Self::V_DOT {
            FreePart::VDot
        } else if i < Self::INTEGRALS {
            FreePart::UDot(i - Self::u_dot(0))
        } else {
            FreePart::Integral(i - Self::INTEGRALS)
        }
    }
}

/// What component `i` of the state on compliant ground is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum FreePart {
    Theta,
    /// The settlement v.
    V,
    /// u_k (k from 0).
    U(usize),
    ThetaDot,
    VDot,
    /// u_k'.
    UDot(usize),
    /// The carried integral k (k from 0).
    Integral(usize),
}
