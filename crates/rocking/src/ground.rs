//! The ground under the base (issue 44): the rigid surface (the default, the paper's), a
//! tensionless Winkler bed or the two-spring foundation. The physics is the generated kernels of
//! [`rocking_kernels::ground`] (`derive/rocking_derive/ground.py`); this file only scales them:
//! the ground is given by the whole structure's vertical stiffness K_v and damping C_v (or by the
//! bed's own k, c), and the kernels say how K_v and C_v follow from k and c.
//!
//! The solver runs a compliant ground through [`crate::simulate_on_ground`] (the driver's
//! `ground_phases`); the sweeps do not take one yet (docs/ground.md).

use rocking_kernels::ground as kernels;

/// The kind of ground under the base.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum GroundKind {
    /// The rigid surface: rocking about a corner and impacts (the paper's).
    #[default]
    Rigid,
    /// A tensionless Winkler bed: springs and dashpots spread uniformly over the base width.
    Winkler,
    /// One spring and one dashpot at each corner (the two-spring foundation).
    TwoSpring,
}

impl GroundKind {
    /// The name scenes give it.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            GroundKind::Rigid => "rigid",
            GroundKind::Winkler => "winkler",
            GroundKind::TwoSpring => "two-spring",
        }
    }
}

/// A compliant ground, in the structure's units: its kind and the kernels' stiffness `k` and
/// damping `c` (the bed's per unit base length, or each corner's).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ground {
    /// Winkler or two springs (never rigid).
    pub kind: GroundKind,
    /// Half-width B of the base.
    pub b: f64,
    /// Stiffness: of the bed per unit base length, or of each corner's spring.
    pub k: f64,
    /// Damping: of the bed per unit base length, or of each corner's dashpot.
    pub c: f64,
}

/// The statics of a structure of weight W on its ground (the derivation's `*_statics` kernels).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GroundStatics {
    /// The whole ground's vertical stiffness K_v.
    pub k_v: f64,
    /// The static settlement v0 = W / K_v.
    pub settlement: f64,
    /// The rotational stiffness dM/dθ at θ = 0 in full contact.
    pub k_rot: f64,
    /// The rotation at which the first edge (corner) lifts off under W.
    pub theta_lift_off: f64,
    /// The moment at that rotation.
    pub moment_lift_off: f64,
}

impl Ground {
    /// The ground of the given kind whose whole vertical stiffness is `k_v` and damping `c_v`,
    /// under a base of half-width `b`: k and c scaled from the kernels' own K_v and C_v at unit
    /// k and c (full contact, a vertical motion).
    #[must_use]
    pub fn from_vertical(kind: GroundKind, b: f64, k_v: f64, c_v: f64) -> Ground {
        let unit = Ground {
            kind,
            b,
            k: 1.0,
            c: 1.0,
        };
        let per_k = unit.statics(1.0).k_v;
        let per_c = -unit.full(&[0.0, 0.0, 0.0, 1.0])[kernels::winkler_full::Q_V];
        Ground {
            kind,
            b,
            k: k_v / per_k,
            c: c_v / per_c,
        }
    }

    /// The kernels' parameter vector.
    #[must_use]
    pub fn params(&self) -> kernels::Params {
        let mut p = [0.0; 3];
        p[kernels::param::B] = self.b;
        p[kernels::param::K] = self.k;
        p[kernels::param::C] = self.c;
        p
    }

    /// The full-contact kernel of this kind at y = [θ, v, θ', v'].
    #[must_use]
    pub fn full(&self, y: &[f64; 4]) -> [f64; 9] {
        match self.kind {
            GroundKind::TwoSpring => kernels::two_spring_full(y, 1.0, &self.params()),
            _ => kernels::winkler_full(y, 1.0, &self.params()),
        }
    }

    /// The kernel outputs (indices of [`kernels::winkler_full`], the same in every kind and
    /// state) at `y` = [θ, v, θ', v'] in the contact state where the left and right corners
    /// press as given: both (full contact), one (one edge lifted) or none (flight).
    #[must_use]
    pub fn state(&self, y: &[f64; 4], left: bool, right: bool) -> [f64; 9] {
        let p = self.params();
        let two = self.kind == GroundKind::TwoSpring;
        match (left, right) {
            (true, true) if two => kernels::two_spring_full(y, 1.0, &p),
            (true, true) => kernels::winkler_full(y, 1.0, &p),
            (false, false) => kernels::flight(y, &p),
            (left, _) => {
                let s = if left { -1.0 } else { 1.0 };
                if two {
                    kernels::two_spring_edge(y, s, &p)
                } else {
                    kernels::winkler_edge(y, s, &p)
                }
            }
        }
    }

    /// [`state`](Self::state) one Taylor order at a time (the generated
    /// `rocking_kernels::taylor::ground` kernels), handed to `f`: the closure returns the k-th
    /// coefficients of the outputs when called with k = 0, 1, 2, ... in turn and the series of
    /// `[θ, v, θ', v']` up to order k.
    pub(crate) fn state_orders<const N: usize, R>(
        &self,
        left: bool,
        right: bool,
        f: impl FnOnce(&mut dyn FnMut(usize, &[[f64; N]; 4]) -> [f64; 9]) -> R,
    ) -> R {
        use rocking_kernels::taylor::ground as series;
        let p = self.params();
        let two = self.kind == GroundKind::TwoSpring;
        match (left, right) {
            (true, true) if two => f(&mut series::two_spring_full::<N>(1.0, &p)),
            (true, true) => f(&mut series::winkler_full::<N>(1.0, &p)),
            // In flight the ground exerts nothing.
            (false, false) => f(&mut |_, _| [0.0; 9]),
            (left, _) => {
                let s = if left { -1.0 } else { 1.0 };
                if two {
                    f(&mut series::two_spring_edge::<N>(s, &p))
                } else {
                    f(&mut series::winkler_edge::<N>(s, &p))
                }
            }
        }
    }

    /// The series of the corners' depths `[d(−B), d(B)]` along the series of `[θ, v, θ', v']`.
    pub(crate) fn depth_series<const N: usize>(&self, y: &[[f64; N]; 4]) -> [[f64; N]; 2] {
        let g = rocking_kernels::taylor::ground::flight::<N>(y, &self.params());
        [
            g[kernels::flight::DEPTH_LEFT],
            g[kernels::flight::DEPTH_RIGHT],
        ]
    }

    /// The corners' depths `[d(−B), d(B)]` at `y` (> 0: the corner presses).
    #[must_use]
    pub fn depths(&self, y: &[f64; 4]) -> [f64; 2] {
        let g = kernels::flight(y, &self.params());
        [
            g[kernels::flight::DEPTH_LEFT],
            g[kernels::flight::DEPTH_RIGHT],
        ]
    }

    /// The kernel outputs at `y` in the contact state its depths give (a corner at depth 0 does
    /// not press).
    #[must_use]
    pub fn at(&self, y: &[f64; 4]) -> [f64; 9] {
        let [l, r] = self.depths(y);
        self.state(y, l > 0.0, r > 0.0)
    }

    /// The mean pressure under the vertical load `weight`: W / 2B on the bed, each corner's
    /// force W / 2 on two springs (the scale of `max_ground_pressure_over_mean` and of
    /// `bearing_over_mean`). It is the full-contact kernel's pressure at rest (θ = 0, v = v0)
    /// up to rounding (`tests/tests/ground_statics.rs`); written as the quotient so that the
    /// outputs keep their bits.
    #[must_use]
    pub fn mean_pressure(&self, weight: f64) -> f64 {
        match self.kind {
            GroundKind::TwoSpring => weight / 2.0,
            _ => weight / (2.0 * self.b),
        }
    }

    /// The statics under the vertical load `weight`.
    #[must_use]
    pub fn statics(&self, weight: f64) -> GroundStatics {
        let p = self.params();
        let st = match self.kind {
            GroundKind::TwoSpring => kernels::two_spring_statics(weight, &p),
            _ => kernels::winkler_statics(weight, &p),
        };
        use kernels::winkler_statics as i;
        GroundStatics {
            k_v: st[i::K_V],
            settlement: st[i::SETTLEMENT],
            k_rot: st[i::K_ROT],
            theta_lift_off: st[i::THETA_LIFT_OFF],
            moment_lift_off: st[i::MOMENT_LIFT_OFF],
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// K_v = 2 k B (bed), 2 k (springs); C_v likewise: the scaling recovers the K_v and C_v it
    /// was given, and the settlement is W / K_v.
    #[test]
    fn vertical_stiffness_and_damping_round_trip() {
        for kind in [GroundKind::Winkler, GroundKind::TwoSpring] {
            let g = Ground::from_vertical(kind, 0.7, 3.0e4, 120.0);
            let factor = if kind == GroundKind::Winkler {
                1.4
            } else {
                2.0
            };
            assert!((g.k * factor - 3.0e4).abs() < 1e-9, "{g:?}");
            assert!((g.c * factor - 120.0).abs() < 1e-12, "{g:?}");
            let st = g.statics(600.0);
            assert!((st.settlement - 0.02).abs() < 1e-15, "{st:?}");
        }
    }
}
