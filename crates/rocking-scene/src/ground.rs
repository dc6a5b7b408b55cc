//! `[ground]` (issue 44): the scene's keys of a compliant ground and their checks, into the
//! solver's [`rocking::Ground`] in the structure's units (docs/ground.md).

use crate::check::{finite, formed};
use crate::ground_spec::GroundKindSpec;
use crate::scene::{SceneSpec, Source};
use crate::SceneError;

/// The compliant ground of `[ground]` in the structure's units, or `None` for the rigid surface:
/// every key checked (its kind's keys only; SI keys only in an SI scene; one form, vertical
/// frequency or the bed's own stiffness, not both). `p` is the structure's p in model units.
pub fn ground(
    spec: &SceneSpec,
    src: &Source,
    structure: &rocking::Structure,
    physical: bool,
    p: f64,
) -> Result<Option<rocking::Ground>, SceneError> {
    use rocking::{Ground, GroundKind};
    let Some(g) = spec.ground.as_ref() else {
        return Ok(None);
    };
    let kind = match g.kind.unwrap_or(GroundKindSpec::Rigid) {
        GroundKindSpec::Rigid => GroundKind::Rigid,
        GroundKindSpec::Winkler => GroundKind::Winkler,
        GroundKindSpec::TwoSpring => GroundKind::TwoSpring,
    };
    let given = [
        ("omega_v_over_p", g.omega_v_over_p),
        ("zeta_v", g.zeta_v),
        ("k", g.k),
        ("c", g.c),
        ("k_spring", g.k_spring),
        ("c_spring", g.c_spring),
    ];
    let present: Vec<&str> = given.iter().filter_map(|(k, v)| v.map(|_| *k)).collect();
    let (own, other): (&[&str], &str) = match kind {
        GroundKind::Rigid => {
            if let Some(key) = present.first() {
                return Err(src.err(
                    &format!("ground.{key}"),
                    format!(
                        "`{key}` in [ground] describes a compliant ground, and kind is \"rigid\" \
                         (the default): give kind = \"winkler\" or \"two-spring\", or remove it"
                    ),
                ));
            }
            return Ok(None);
        }
        GroundKind::Winkler => (&["k", "c"], "two-spring"),
        GroundKind::TwoSpring => (&["k_spring", "c_spring"], "winkler"),
    };
    let name = kind.name();
    for key in &present {
        let dimless = matches!(*key, "omega_v_over_p" | "zeta_v");
        if !dimless && !own.contains(key) {
            return Err(src.err(
                &format!("ground.{key}"),
                format!(
                    "`{key}` in [ground] is a key of the {other} ground, and kind is \"{name}\": \
                     give {} (SI), or omega_v_over_p and zeta_v",
                    own.join(" and ")
                ),
            ));
        }
        if !dimless && !physical {
            return Err(src.err(
                &format!("ground.{key}"),
                format!(
                    "`{key}` in [ground] is in SI units, and [structure] is dimensionless: give \
                     omega_v_over_p and zeta_v (or [structure] in SI)"
                ),
            ));
        }
    }
    let dimless: Vec<&str> = present
        .iter()
        .copied()
        .filter(|k| matches!(*k, "omega_v_over_p" | "zeta_v"))
        .collect();
    let si: Vec<&str> = present
        .iter()
        .copied()
        .filter(|k| !matches!(*k, "omega_v_over_p" | "zeta_v"))
        .collect();
    if !dimless.is_empty() && !si.is_empty() {
        return Err(src.err(
            &format!("ground.{}", dimless[0]),
            format!(
                "[ground] mixes the vertical frequency (`{}`) and the {name} ground's own SI \
                 parameters (`{}`): give either omega_v_over_p, zeta_v or {}",
                dimless.join("`, `"),
                si.join("`, `"),
                own.join(", ")
            ),
        ));
    }
    let b = structure.physical().b;
    let weight = structure.static_uplift().weight;
    let mass = weight / structure.physical().g;
    let ground = if si.is_empty() {
        let Some(w) = g.omega_v_over_p else {
            return Err(src.err(
                "ground",
                format!(
                    "missing key `omega_v_over_p` in [ground] (kind = \"{name}\" needs its \
                     stiffness: omega_v_over_p and zeta_v{})",
                    if physical {
                        format!(", or {} in SI", own.join(", "))
                    } else {
                        String::new()
                    }
                ),
            ));
        };
        let w = finite(
            src,
            "ground.omega_v_over_p",
            w,
            w > 0.0 && w <= 1e6,
            "0 < omega_v/p <= 1000000",
        )?;
        let zeta = g.zeta_v.unwrap_or(0.0);
        let zeta = finite(
            src,
            "ground.zeta_v",
            zeta,
            (0.0..1.0).contains(&zeta),
            "a damping ratio 0 <= zeta_v < 1",
        )?;
        let k_v = formed(
            src,
            "ground.omega_v_over_p",
            w,
            mass * (w * p).powi(2),
            "vertical stiffness K_v",
        )?;
        Ground::from_vertical(kind, b, k_v, 2.0 * zeta * (k_v * mass).sqrt())
    } else {
        let (k_key, c_key) = (own[0], own[1]);
        let (k, c) = match kind {
            GroundKind::TwoSpring => (g.k_spring, g.c_spring),
            _ => (g.k, g.c),
        };
        let Some(k) = k else {
            return Err(src.err(
                "ground",
                format!("missing key `{k_key}` in [ground] (given: `{c_key}`)"),
            ));
        };
        let k = finite(
            src,
            &format!("ground.{k_key}"),
            k,
            k > 0.0 && k <= 1e20,
            "a stiffness 0 < k <= 1e20",
        )?;
        let c = c.unwrap_or(0.0);
        let c = finite(
            src,
            &format!("ground.{c_key}"),
            c,
            (0.0..=1e20).contains(&c),
            "a damping 0 <= c <= 1e20",
        )?;
        Ground { kind, b, k, c }
    };
    Ok(Some(ground))
}

/// `[effects] bearing` (Pa, with `footing_length` in m) or `bearing_over_mean`: the bearing
/// pressure over the mean pressure, `Options::bearing_over_mean` (docs/ground.md, "Bearing").
///
/// The model is plane: the bed's k d is a force per metre of base (along 2B), and the whole
/// weight W rests on it, so the footing's own out-of-plane length L turns it into a pressure:
/// the mean pressure under the footing is W / (2B L) and q over it is q 2B L / W. Two springs:
/// each corner carries half the footing, its force over W / 2 is the same ratio.
pub fn bearing(
    src: &Source,
    fx: Option<&crate::scene::EffectsSpec>,
    ground: Option<&rocking::Ground>,
    structure: &rocking::Structure,
    physical: bool,
) -> Result<Option<f64>, SceneError> {
    let Some(fx) = fx else {
        return Ok(None);
    };
    let given = [
        ("bearing", fx.bearing),
        ("footing_length", fx.footing_length),
        ("bearing_over_mean", fx.bearing_over_mean),
    ];
    let Some((first, _)) = given.iter().find(|(_, v)| v.is_some()) else {
        return Ok(None);
    };
    let path = |key: &str| format!("effects.{key}");
    if ground.is_none() {
        return Err(src.err(
            &path(first),
            format!(
                "`{first}` in [effects] is checked against the pressure under the base on a \
                 compliant ground, and [ground] kind is \"rigid\" (the default; the rigid surface \
                 has no pressure distribution): give [ground] kind = \"winkler\" or \
                 \"two-spring\", or remove it"
            ),
        ));
    }
    if let Some(q) = fx.bearing_over_mean {
        if let Some((key, _)) = given[..2].iter().find(|(_, v)| v.is_some()) {
            return Err(src.err(
                &path(key),
                format!(
                    "[effects] gives both `bearing_over_mean` and `{key}`: give either \
                     bearing_over_mean or bearing (Pa) with footing_length (m)"
                ),
            ));
        }
        let q = finite(
            src,
            "effects.bearing_over_mean",
            q,
            q > 0.0,
            "a bearing pressure over the mean 0 < bearing_over_mean",
        )?;
        return Ok(Some(q));
    }
    let Some(q) = fx.bearing else {
        return Err(src.err(
            "effects.footing_length",
            "`footing_length` in [effects] turns `bearing` (Pa) into a pressure ratio, and \
             [effects] gives no bearing: give bearing, or remove it",
        ));
    };
    if !physical {
        return Err(src.err(
            "effects.bearing",
            "`bearing` in [effects] is in SI units (Pa), and [structure] is dimensionless: \
             give bearing_over_mean (against max_ground_pressure_over_mean), or [structure] in SI",
        ));
    }
    let q = finite(
        src,
        "effects.bearing",
        q,
        q > 0.0 && q <= 1e12,
        "a bearing pressure 0 < bearing <= 1e12 Pa",
    )?;
    let Some(l) = fx.footing_length else {
        return Err(src.err(
            "effects.bearing",
            "`bearing` in [effects] is a pressure (Pa), and the model is plane: give \
             footing_length (m), the footing's length out of the plane, which turns the bed's \
             force per metre of base into a pressure (docs/ground.md), or bearing_over_mean",
        ));
    };
    let l = finite(
        src,
        "effects.footing_length",
        l,
        l > 0.0 && l <= 1e6,
        "a length 0 < footing_length <= 1e6 m",
    )?;
    let area = 2.0 * structure.physical().b * l;
    let ratio = q * area / structure.static_uplift().weight;
    Ok(Some(formed(
        src,
        "effects.bearing",
        q,
        ratio,
        "bearing pressure over the mean",
    )?))
}
