//! Which extremes a run searches for inside its steps: each search costs evaluations of the
//! forces or the ground's kernels per step, so a sweep asks only for those it reports.

use std::marker::PhantomData;

/// One of the force extremes a run tracks, in the order of [`ForceSummary`](crate::ForceSummary)'s
/// maxima.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ForceExtreme {
    /// max |M_b|.
    BaseMoment,
    /// max |V_b|.
    BaseShear,
    /// max |M_el|.
    ElasticMoment,
    /// max |R_h| / R_v.
    RequiredFriction,
    /// min R_v.
    VerticalReaction,
}

/// One of the ground's extremes a run on compliant ground searches for inside steps
/// ([`GroundSummary`](crate::GroundSummary)'s).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum GroundExtreme {
    /// max pressure.
    MaxPressure,
    /// min pressure (at an end of the contact).
    LeastPressure,
    /// min contact length.
    ContactFraction,
}

/// A kind of extreme: an enum whose discriminants index an [`Extremes`] set.
pub trait Extreme: Copy {
    /// How many there are.
    const COUNT: usize;
    /// Its position in the set.
    fn index(self) -> usize;
}

impl Extreme for ForceExtreme {
    const COUNT: usize = 5;
    fn index(self) -> usize {
        self as usize
    }
}

impl Extreme for GroundExtreme {
    const COUNT: usize = 3;
    fn index(self) -> usize {
        self as usize
    }
}

// Each kind's count is its number of variants (the last one's index + 1).
const _: () = assert!(ForceExtreme::VerticalReaction as usize + 1 == ForceExtreme::COUNT);
const _: () = assert!(GroundExtreme::ContactFraction as usize + 1 == GroundExtreme::COUNT);

/// A set of extremes of one kind ([`crate::Options::force_extremes`],
/// [`crate::Options::ground_extremes`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Extremes<E> {
    set: [bool; 8],
    kind: PhantomData<E>,
}

/// The force extremes a run searches for.
pub type ForceExtremes = Extremes<ForceExtreme>;
/// The ground's extremes a run searches for.
pub type GroundExtremes = Extremes<GroundExtreme>;

impl<E: Extreme> Extremes<E> {
    /// Every extreme.
    pub const ALL: Extremes<E> = {
        let mut set = [false; 8];
        let mut k = 0;
        while k < E::COUNT {
            set[k] = true;
            k += 1;
        }
        Extremes {
            set,
            kind: PhantomData,
        }
    };
    /// None.
    pub const NONE: Extremes<E> = Extremes {
        set: [false; 8],
        kind: PhantomData,
    };

    /// This set and `extreme`.
    #[must_use]
    pub fn with(self, extreme: E) -> Extremes<E> {
        let mut set = self.set;
        set[extreme.index()] = true;
        Extremes { set, ..self }
    }

    /// Whether the set holds `extreme`.
    pub fn contains(self, extreme: E) -> bool {
        self.set[extreme.index()]
    }

    /// Whether the set holds the extreme of index `k` (the order of `E`).
    pub(crate) fn holds(self, k: usize) -> bool {
        self.set[k]
    }
}
