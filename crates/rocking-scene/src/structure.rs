//! `[structure]` built into the solver's `Structure`: physical or dimensionless keys (never
//! both), the model's own parameters, and damping ratios per mode when `zeta` is a list.

use rocking::{DampingConvention, Dimensionless, ModelInfo, Structure};
use rocking_kernels::Physical;

use rocking_motion::STANDARD_GRAVITY;

use crate::check::{finite, param_err};
use crate::scene::{Source, StructureSpec};
use crate::SceneError;

/// The names of the keys that are present.
fn present_keys<'a>(keys: &[(&'a str, bool)]) -> Vec<&'a str> {
    keys.iter().filter(|(_, b)| *b).map(|(k, _)| *k).collect()
}

/// The structure of [structure], with its damping ratios per mode when `zeta` is a list.
pub(crate) fn build_structure(
    src: &Source,
    s: &StructureSpec,
    rigid: bool,
    model: &'static ModelInfo,
) -> Result<Structure, SceneError> {
    let Some(list) = &s.zeta_per_mode else {
        return structure_of(src, s, rigid, model);
    };
    let n = model.coordinates;
    let refuse = |why: String| Err(src.err("structure.zeta", format_args!("[structure] {why}")));
    if s.zeta.is_some() {
        return refuse("`zeta` is given both as one ratio and as a list".to_string());
    }
    if list.len() != 1 && list.len() != n {
        return refuse(format!(
            "`zeta` lists {} damping ratios, and model `{}` has {n} fixed-base mode{} (one per \
             deformation coordinate): give one ratio for every mode, or a list of {n}",
            list.len(),
            model.name,
            if n == 1 { "" } else { "s" }
        ));
    }
    for &z in list {
        finite(
            src,
            "structure.zeta",
            z,
            (0.0..1.0).contains(&z),
            "a damping ratio 0 <= zeta < 1",
        )?;
    }
    if list.len() > 1 && s.damping == Some(DampingConvention::Uplifted) {
        return refuse(
            "`zeta` as a list gives each fixed-base mode its own ratio: it needs damping = \
             \"fixed-base\" (damping = \"uplifted\" takes one ratio, the first uplifted mode's)"
                .to_string(),
        );
    }
    let first = StructureSpec {
        zeta: Some(list[0]),
        zeta_per_mode: None,
        ..s.clone()
    };
    structure_of(src, &first, rigid, model)?
        .with_modal_damping_ratios(list)
        .map_err(|e| param_err(src, "structure", e))
}

fn structure_of(
    src: &Source,
    s: &StructureSpec,
    rigid: bool,
    model: &'static ModelInfo,
) -> Result<Structure, SceneError> {
    crate::limits::structure_magnitudes(src, s)?;
    let physical_keys = present_keys(&[
        ("h", s.h.is_some()),
        ("b", s.b.is_some()),
        ("ei", s.ei.is_some()),
        ("m", s.m.is_some()),
        ("m_c", s.m_c.is_some()),
        ("m_b", s.m_b.is_some()),
        ("i_bc", s.i_bc.is_some()),
        ("g", s.g.is_some()),
    ]);
    let dimless_keys = present_keys(&[
        ("omega_n_over_p", s.omega_n_over_p.is_some()),
        ("alpha", s.alpha.is_some()),
        ("gamma_mc", s.gamma_mc.is_some()),
        ("gamma_mb", s.gamma_mb.is_some()),
        ("gamma_ib", s.gamma_ib.is_some()),
        ("damping", s.damping.is_some()),
        ("r", s.r.is_some()),
        ("p", s.p.is_some()),
    ]);
    if !physical_keys.is_empty() && !dimless_keys.is_empty() {
        return Err(src.err(
            &format!("structure.{}", dimless_keys[0]),
            format_args!(
                "[structure] mixes the physical form (`{}`) and the dimensionless form (`{}`); \
                 give either h, b, ei, m, m_c, m_b, i_bc, zeta, g (SI) or omega_n_over_p, alpha, \
                 gamma_mc, gamma_mb, gamma_ib, zeta, damping, r|p",
                physical_keys.join("`, `"),
                dimless_keys.join("`, `")
            ),
        ));
    }
    if !physical_keys.is_empty() {
        let need = |k: &str, v: Option<f64>| {
            v.ok_or_else(|| {
                src.err(
                    "structure",
                    format_args!(
                        "missing key `{k}` in [structure] (the physical form needs h, b, ei, m)"
                    ),
                )
            })
        };
        let h = need("h", s.h)?;
        let b = need("b", s.b)?;
        let ei = need("ei", s.ei)?;
        let m = need("m", s.m)?;
        let mut ph = Physical {
            h,
            b,
            ei,
            m,
            m_c: s.m_c.unwrap_or(0.0),
            m_b: s.m_b.unwrap_or(0.0),
            i_bc: 0.0,
            zeta: s.zeta.unwrap_or(0.0),
            g: s.g.unwrap_or(STANDARD_GRAVITY),
        };
        // Default: a thin rectangular plate (the model's kernels give its inertia, 4/3 m_b B²).
        ph.i_bc = match s.i_bc {
            Some(i) => i,
            None => rocking::plate_inertia(model, &ph),
        };
        return Structure::of_model(model, ph, &s.extra)
            .map_err(|e| param_err(src, "structure", e));
    }
    let alpha = s.alpha.ok_or_else(|| {
        src.err(
            "structure",
            "missing key `alpha` in [structure] (give the dimensionless form: omega_n_over_p, \
             alpha, ...; or the physical form: h, b, ei, m, ...)",
        )
    })?;
    let omega_n_over_p = match (s.omega_n_over_p, rigid) {
        (Some(w), _) => w,
        // A rigid column does not use it; any stiff value keeps the derived quantities finite.
        (None, true) => 1000.0,
        (None, false) => {
            return Err(src.err(
                "structure",
                "missing key `omega_n_over_p` in [structure] (needed unless [effects] flexibility = false)",
            ))
        }
    };
    let p_si = match (s.r, s.p) {
        (Some(_), Some(_)) => {
            return Err(src.err(
                "structure.p",
                "give either `r` (m) or `p` (1/s) in [structure], not both",
            ))
        }
        (Some(r), None) => Some(
            finite(src, "structure.r", r, r > 0.0, "a length R > 0 (m)")
                .map(|r| (STANDARD_GRAVITY / r).sqrt())?,
        ),
        (None, Some(p)) => Some(finite(
            src,
            "structure.p",
            p,
            p > 0.0,
            "p = sqrt(g/R) > 0 (1/s)",
        )?),
        (None, None) => None,
    };
    let d = Dimensionless {
        omega_n_over_p,
        alpha,
        gamma_mc: s.gamma_mc.unwrap_or(0.0),
        gamma_mb: s.gamma_mb.unwrap_or(0.0),
        gamma_ib: s.gamma_ib.unwrap_or(1.0),
        zeta: s.zeta.unwrap_or(0.0),
        damping: s.damping.unwrap_or(DampingConvention::FixedBase),
    };
    Structure::dimensionless_of_model(model, &d, &s.extra, p_si)
        .map_err(|e| param_err(src, "structure", e))
}
