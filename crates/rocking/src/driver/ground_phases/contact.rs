//! Which corners press, and what the structure's and the ground's kernels give at a state in a
//! contact state: the base's coordinates, the corners' depths, the ground's outputs and the
//! accelerations.

use super::*;

/// Which corners press.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct Contact {
    pub(super) left: bool,
    pub(super) right: bool,
}

impl Contact {
    pub(super) fn phase(self, overturned: bool) -> Phase {
        match (overturned, self.left, self.right) {
            (true, _, _) => Phase::Overturned,
            (false, true, true) => Phase::Contact,
            (false, false, true) => Phase::RockingRight,
            (false, true, false) => Phase::RockingLeft,
            (false, false, false) => Phase::Flight,
        }
    }
}

/// The kernels' parameters: the structure's and the ground (Copy, for the right-hand side).
#[derive(Clone, Copy)]
pub(super) struct Kin<V: Variant> {
    pub(super) p: V::Params,
    pub(super) ground: Ground,
    /// The linear-foundation twin (`Options::uplift` false): springs that also pull, the
    /// full-contact kernels at every state, no contact events (docs/ground.md).
    pub(super) bilateral: bool,
}

impl<V: Variant> Kin<V> {
    /// `[θ, v, θ', v']` of the ground's kernels.
    pub(super) fn base(&self, y: &V::Y) -> [f64; 4] {
        let y = y.values();
        Free::<V>::BASE.map(|i| y[i])
    }

    /// The ground's outputs in contact state `c`.
    pub(super) fn ground(&self, y: &V::Y, c: Contact) -> [f64; 9] {
        self.ground.state(&self.base(y), c.left, c.right)
    }

    /// The corners' depths `[d(−B), d(B)]`; on the bilateral twin 1 (both press, always).
    pub(super) fn depths(&self, y: &V::Y) -> [f64; 2] {
        if self.bilateral {
            return [1.0; 2];
        }
        self.ground.depths(&self.base(y))
    }

    /// The contact state from the depths (a corner at depth 0 does not press).
    pub(super) fn contact_of(&self, y: &V::Y) -> Contact {
        let [l, r] = self.depths(y);
        Contact {
            left: l > 0.0,
            right: r > 0.0,
        }
    }

    /// The accelerations `[θ'', v'', u'']` and the ground's outputs.
    pub(super) fn accelerations(&self, y: &V::Y, ug: f64, s: f64, c: Contact) -> (V::Qf, [f64; 9]) {
        let q = V::Qf::from_fn(|i| y.values()[i]);
        let m = V::free_mass_matrix(&q, s, &self.p);
        let mut f = V::free_forcing(y, ug, s, &self.p);
        let g = self.ground(y, c);
        f.values_mut()[Free::<V>::THETA] += g[go::Q_THETA];
        f.values_mut()[Free::<V>::V] += g[go::Q_V];
        let _ = solve_upper(m.values(), &mut f.values_mut()[..Free::<V>::NQ]);
        (f, g)
    }
}

/// The kernels' contact length over 2B, reported in [0, 1]: a lift-off is located to the event
/// tolerance, so the one-edge state can hold a step end or event slightly past it, where its
/// length is below zero (down to -1.0e-8 on Study 1's spectra, docs/ground.md) or -0 (the edge's
/// sign times 0); `+ 0.0` turns -0 into 0.
pub(super) fn contact_fraction(g: &[f64]) -> f64 {
    g[go::CONTACT_FRACTION].clamp(0.0, 1.0) + 0.0
}
