//! `[ground]`'s keys as a scene gives them (issue 44, docs/ground.md); checked into the
//! solver's ground by `ground::ground`.

use serde::Deserialize;

/// `[ground]` (issue 44): the rigid surface (default), a tensionless Winkler bed or two springs.
/// Checked when the setup is built (`setup::ground`).
#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GroundSpec {
    pub kind: Option<GroundKindSpec>,
    /// omega_v / p, omega_v = sqrt(K_v / M): the whole structure's vertical frequency.
    pub omega_v_over_p: Option<f64>,
    /// The damping ratio of that vertical mode: C_v = 2 zeta_v sqrt(K_v M).
    pub zeta_v: Option<f64>,
    /// SI scenes, winkler: the bed's stiffness (N/m^2) and damping (N s/m^2) per unit base width.
    pub k: Option<f64>,
    pub c: Option<f64>,
    /// SI scenes, two-spring: each corner's spring (N/m) and dashpot (N s/m).
    pub k_spring: Option<f64>,
    pub c_spring: Option<f64>,
}

/// `[ground] kind`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum GroundKindSpec {
    Rigid,
    Winkler,
    TwoSpring,
}
