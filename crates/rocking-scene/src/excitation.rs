//! Ground motions a scene names: each excitation kind is one entry of [`KINDS`] (its name, what
//! it is, the keys it reads and how it is built from them), which the parser, the checks, the
//! knobs' labels and `rocking models` read. A new kind is a motion in `rocking-motion` and an
//! entry here.

use std::f64::consts::PI;
use std::path::Path;

use rocking_motion::{
    AccelUnit, At2Record, CosinePulse, Excitation, GroundMotion, MavroeidisPapageorgiou, Record,
    RecordFormat, Ricker, SinePulse,
};

use crate::check::{finite, formed};
use crate::scene::{ExcitationSpec, SceneSpec, Source};
use crate::units::Units;
use crate::SceneError;

/// A ground motion as a scene built it.
pub struct Built {
    /// The motion, in model units.
    pub motion: Excitation,
    /// What it is, in words (with its amplitude and frequency in the paper's terms).
    pub description: String,
    /// When it ends (model time).
    pub end: f64,
}

/// One excitation kind a scene can name (`kind` in [excitation]).
pub struct Kind {
    /// The name in a scene.
    pub name: &'static str,
    /// What it is.
    pub doc: &'static str,
    /// The keys it reads besides `kind`.
    pub keys: &'static [&'static str],
    build: fn(&Source, &ExcitationSpec, &Units) -> Result<Built, SceneError>,
}

/// A pulse's frequency and acceleration amplitude, each given one way of several.
const PULSE: &[&str] = &[
    "omega_p_over_p",
    "omega_p",
    "amplitude",
    "amplitude_g",
    "a_p",
];

/// Every excitation kind, in the order `rocking models` lists them.
pub const KINDS: &[Kind] = &[
    Kind {
        name: "none",
        doc: "no ground motion (free rocking from the initial state)",
        keys: &[],
        build: |_, _, _| {
            Ok(Built {
                motion: Excitation::None,
                description: "none (free rocking)".into(),
                end: 0.0,
            })
        },
    },
    Kind {
        name: "sine-pulse",
        doc: "one cycle of a sine, a_p sin(ω_p t) (the paper's pulse)",
        keys: PULSE,
        build: |src, e, u| harmonic(src, e, u, "sine-pulse", |a, w| SinePulse::new(a, w).into()),
    },
    Kind {
        name: "cosine-pulse",
        doc: "one cycle of a cosine, a_p cos(ω_p t)",
        keys: PULSE,
        build: |src, e, u| {
            harmonic(src, e, u, "cosine-pulse", |a, w| {
                CosinePulse::new(a, w).into()
            })
        },
    },
    Kind {
        name: "ricker",
        doc: "a Ricker wavelet, symmetric or antisymmetric (`shape`)",
        keys: &[
            "omega_p_over_p",
            "omega_p",
            "amplitude",
            "amplitude_g",
            "a_p",
            "shape",
        ],
        build: ricker,
    },
    Kind {
        name: "mp-pulse",
        doc: "the Mavroeidis–Papageorgiou near-fault pulse (velocity amplitude, γ, ν)",
        keys: &[
            "omega_p_over_p",
            "omega_p",
            "velocity_amplitude",
            "v_p",
            "gamma",
            "nu",
        ],
        build: mp_pulse,
    },
    Kind {
        name: "record",
        doc: "a recorded ground motion (PEER AT2, ESM, K-NET/KiK-net or text), scaled",
        keys: &["path", "scale", "units", "format", "dt"],
        build: record,
    },
];

/// The ground motion of a typed scene: its kind's entry of [`KINDS`], the keys it may read, and
/// the motion built from them.
pub fn build(spec: &SceneSpec, src: &Source, u: &Units) -> Result<Built, SceneError> {
    let default = ExcitationSpec::default();
    let e = spec.excitation.as_ref().unwrap_or(&default);
    let kind = e.kind.as_deref().unwrap_or("none");
    let names: Vec<&str> = KINDS.iter().map(|k| k.name).collect();
    let Some(entry) = KINDS.iter().find(|k| k.name == kind) else {
        let hint = crate::scene::suggest(kind, &names)
            .map(|s| format!("; did you mean \"{s}\"?"))
            .unwrap_or_default();
        let allowed = format!("one of \"{}\"", names.join("\", \""));
        return Err(src
            .err(
                "excitation.kind",
                format_args!("`kind` = \"{kind}\" in [excitation] is not allowed: {allowed}{hint}"),
            )
            .with_value(kind, allowed));
    };
    if let Some(k) = present(e)
        .into_iter()
        .find(|k| *k != "kind" && !entry.keys.contains(&k.as_str()))
    {
        let mut keys = vec!["kind"];
        keys.extend(entry.keys);
        return Err(src.err(
            &format!("excitation.{k}"),
            format_args!(
                "key `{k}` in [excitation] is not used by kind = \"{kind}\" (its keys: {})",
                keys.join(", ")
            ),
        ));
    }
    (entry.build)(src, e, u)
}

/// The keys of `[excitation]` the scene gives (from the typed table itself: a key is a field).
fn present(e: &ExcitationSpec) -> Vec<String> {
    match serde_json::to_value(e) {
        Ok(serde_json::Value::Object(map)) => map
            .into_iter()
            .filter(|(_, v)| !v.is_null())
            .map(|(k, _)| k)
            .collect(),
        _ => Vec::new(),
    }
}

/// A one-cycle harmonic pulse from its frequency and amplitude keys.
fn harmonic(
    src: &Source,
    e: &ExcitationSpec,
    u: &Units,
    kind: &str,
    make: fn(f64, f64) -> Excitation,
) -> Result<Built, SceneError> {
    let w = omega(src, kind, e, u)?;
    let a = accel_amplitude(src, kind, e, u)?;
    let description = format!(
        "{kind}: a_p/(g tan α) = {:.4}, ω_p/p = {:.4}",
        a / u.accel_g_tan_alpha(),
        w / u.p_model
    );
    let motion = make(a, w);
    let end = motion.end();
    Ok(Built {
        motion,
        description,
        end,
    })
}

fn ricker(src: &Source, e: &ExcitationSpec, u: &Units) -> Result<Built, SceneError> {
    let ga = u.accel_g_tan_alpha();
    let w = omega(src, "ricker", e, u)?;
    let a = accel_amplitude(src, "ricker", e, u)?;
    let shape = e.shape.as_deref().unwrap_or("symmetric");
    let r = match shape {
        "symmetric" => Ricker::symmetric(a, w),
        "antisymmetric" => Ricker::antisymmetric(a, w),
        other => {
            return Err(src.err(
                "excitation.shape",
                format_args!(
                    "`shape` = \"{other}\" in [excitation] is not allowed: \
                         \"symmetric\" or \"antisymmetric\""
                ),
            ))
        }
    };
    let desc = format!(
        "ricker ({shape}): a_p/(g tan α) = {:.4}, ω_p/p = {:.4}",
        a / ga,
        w / u.p_model
    );
    let end = r.end();
    Ok(Built {
        motion: r.into(),
        description: desc,
        end,
    })
}

fn mp_pulse(src: &Source, e: &ExcitationSpec, u: &Units) -> Result<Built, SceneError> {
    let ga = u.accel_g_tan_alpha();
    let w = omega(src, "mp-pulse", e, u)?;
    let (k, v) = one_of(
        src,
        "mp-pulse",
        &[("velocity_amplitude", e.velocity_amplitude), ("v_p", e.v_p)],
    )?;
    finite(
        src,
        &format!("excitation.{k}"),
        v,
        true,
        "a finite amplitude",
    )?;
    // Velocity unit of the model: (g tan α)/p for `velocity_amplitude`, m/s for `v_p`.
    let a_vel = match k {
        "velocity_amplitude" => v * ga / u.p_model,
        _ => v * u.g_model / (u.g_si * need_seconds(src, k, u)?),
    };
    let path = format!("excitation.{k}");
    let a_vel = formed(src, &path, v, a_vel, "ground velocity in model units")?;
    // The pulse's peak acceleration is of order A ω_p.
    crate::limits::acceleration(src, &path, v, a_vel * w / u.g_model)?;
    let gamma = e.gamma.unwrap_or(2.0);
    finite(
        src,
        "excitation.gamma",
        gamma,
        gamma > 1.0,
        "an oscillatory character gamma > 1",
    )?;
    let nu = e.nu.unwrap_or(0.0);
    finite(src, "excitation.nu", nu, true, "a finite phase (rad)")?;
    let mp = MavroeidisPapageorgiou::starting_at(a_vel, w / (2.0 * PI), gamma, nu, 0.0);
    let desc = format!(
        "mp-pulse: A p/(g tan α) = {:.4}, ω_p/p = {:.4}, γ = {gamma}, ν = {nu}",
        a_vel * u.p_model / ga,
        w / u.p_model
    );
    let end = mp.end();
    Ok(Built {
        motion: mp.into(),
        description: desc,
        end,
    })
}

fn record(src: &Source, e: &ExcitationSpec, u: &Units) -> Result<Built, SceneError> {
    let scale = e.scale.unwrap_or(1.0);
    let allowed = "a finite, nonzero scale factor (a negative one reverses the record)";
    finite(src, "excitation.scale", scale, true, allowed)?;
    if scale == 0.0 {
        return Err(src.err(
            "excitation.scale",
            format_args!("`scale` in [excitation] = 0 is not allowed: {allowed}"),
        ));
    }
    let at2 = scene_record(src, e)?;
    let spu = u.sec_per_unit.ok_or_else(|| {
        src.err(
            "excitation.path",
            "a record is sampled in seconds, but the structure has no time scale: \
                 give `r` (m) or `p` (1/s) in [structure], or a physical structure",
        )
    })?;
    let unit = at2.unit();
    let unit_name = match at2.declared_unit {
        Some(u) => u.name(),
        None => "g (not stated)",
    };
    let per_unit = unit.in_model_units(u.g_model, u.g_si);
    let pga = at2.pga();
    let (dt, npts) = (at2.dt, at2.npts);
    let pga_model = formed(
        src,
        "excitation.scale",
        scale,
        pga * per_unit * scale,
        "peak ground acceleration in model units",
    )?;
    if e.scale.is_some() {
        crate::limits::acceleration(src, "excitation.scale", scale, pga_model / u.g_model)?;
    } else if (pga_model / u.g_model).abs() > crate::limits::MAX_ACCEL_G {
        // No scale given: the record itself is out of range; name it and its peak.
        return Err(src.err(
            "excitation.path",
            format_args!(
                "the record {} peaks at {} {unit_name}, a peak ground acceleration of {} g; at \
                 most {} g (is its unit line right?)",
                at2.source,
                crate::limits::short(pga),
                crate::limits::short((pga_model / u.g_model).abs()),
                crate::limits::short(crate::limits::MAX_ACCEL_G)
            ),
        ));
    }
    let rec = Record::new(dt / spu, at2.samples)
        .map_err(|err| src.err("excitation.path", err))?
        .with_scale(scale * per_unit);
    let short = crate::limits::short;
    // The PGA in the structure's g, and as the file states it when that is not g.
    let stated = match unit {
        AccelUnit::G => String::new(),
        absolute => format!(" = {pga:.4} {}", absolute.name()),
    };
    let desc = format!(
        "record {} ({npts} samples, dt = {} s, units {unit_name}, PGA = {:.4} g{stated}) \
             × {}: PGA/(g tan α) = {:.4}",
        file_of(src, e)?.display(),
        short(dt),
        pga * per_unit / u.g_model,
        short(scale),
        pga_model / u.accel_g_tan_alpha()
    );
    let end = rec.end();
    Ok(Built {
        motion: rec.into(),
        description: desc,
        end,
    })
}

fn need_seconds(src: &Source, key: &str, u: &Units) -> Result<f64, SceneError> {
    u.sec_per_unit.ok_or_else(|| {
        src.err(
            &format!("excitation.{key}"),
            format_args!(
                "`{key}` in [excitation] is in seconds, but the structure has no time scale: \
                 give `r` (m) or `p` (1/s) in [structure], or a physical structure"
            ),
        )
    })
}

/// Exactly one of several alternative keys.
fn one_of<'a>(
    src: &Source,
    kind: &str,
    opts: &[(&'a str, Option<f64>)],
) -> Result<(&'a str, f64), SceneError> {
    let given: Vec<_> = opts.iter().filter(|(_, v)| v.is_some()).collect();
    let names: Vec<String> = opts.iter().map(|(k, _)| format!("`{k}`")).collect();
    match given.as_slice() {
        [(k, Some(v))] => Ok((k, *v)),
        [] => Err(src.err(
            "excitation",
            format_args!(
                "missing key in [excitation]: kind = \"{kind}\" needs one of {}",
                names.join(", ")
            ),
        )),
        _ => Err(src.err(
            &format!("excitation.{}", given[1].0),
            format_args!(
                "give only one of {} in [excitation] (found `{}` and `{}`)",
                names.join(", "),
                given[0].0,
                given[1].0
            ),
        )),
    }
}

/// Angular frequency in model units from `omega_p_over_p` or `omega_p` (rad/s).
fn omega(src: &Source, kind: &str, e: &ExcitationSpec, u: &Units) -> Result<f64, SceneError> {
    let (k, v) = one_of(
        src,
        kind,
        &[("omega_p_over_p", e.omega_p_over_p), ("omega_p", e.omega_p)],
    )?;
    let path = format!("excitation.{k}");
    finite(src, &path, v, v > 0.0, "a frequency > 0")?;
    let w = match k {
        "omega_p_over_p" => v * u.p_model,
        _ => v * need_seconds(src, k, u)?,
    };
    formed(src, &path, v, w, "frequency in model units")?;
    crate::limits::frequency(src, &path, v, w / u.p_model)?;
    Ok(w)
}

/// Acceleration amplitude in model units from `amplitude` (g tan α), `amplitude_g` (g) or `a_p`
/// (m/s²).
fn accel_amplitude(
    src: &Source,
    kind: &str,
    e: &ExcitationSpec,
    u: &Units,
) -> Result<f64, SceneError> {
    let (k, v) = one_of(
        src,
        kind,
        &[
            ("amplitude", e.amplitude),
            ("amplitude_g", e.amplitude_g),
            ("a_p", e.a_p),
        ],
    )?;
    finite(
        src,
        &format!("excitation.{k}"),
        v,
        true,
        "a finite amplitude",
    )?;
    let a = match k {
        "amplitude" => v * u.accel_g_tan_alpha(),
        "amplitude_g" => v * u.g_model,
        _ => v / u.g_si * u.g_model,
    };
    let path = format!("excitation.{k}");
    formed(src, &path, v, a, "ground acceleration in model units")?;
    crate::limits::acceleration(src, &path, v, a / u.g_model)?;
    Ok(a)
}

/// The record file a scene names (`excitation.path`, relative to the scene).
pub(crate) fn file_of(src: &Source, e: &ExcitationSpec) -> Result<std::path::PathBuf, SceneError> {
    let rel = e.path.as_deref().ok_or_else(|| {
        src.err(
            "excitation",
            "missing key `path` in [excitation] (kind = \"record\" needs a record file)",
        )
    })?;
    Ok(src.dir().join(rel))
}

/// The record a scene's `[excitation]` names, read in its format and with the unit the scene
/// states (`units`, required for a text file, refused when the file declares another): what
/// `run` simulates and what a record study measures.
pub fn scene_record(src: &Source, e: &ExcitationSpec) -> Result<At2Record, SceneError> {
    let file = file_of(src, e)?;
    let format = record_format(src, e, &file)?;
    let at2 = src.record_as(&file, format, e.dt).map_err(|err| {
        src.err(
            "excitation.path",
            format_args!("cannot use the record: {err}"),
        )
    })?;
    match e.units.as_deref() {
        None if format == RecordFormat::Text => Err(src.err(
            "excitation.units",
            "a text record states no unit: give `units` in [excitation], one of \
             \"g\", \"cm/s2\", \"m/s2\"",
        )),
        None => Ok(at2),
        Some(name) => {
            let unit = AccelUnit::parse(name).ok_or_else(|| {
                src.err(
                    "excitation.units",
                    format_args!(
                        "`units` = \"{name}\" in [excitation] is not allowed: one of \"{}\"",
                        AccelUnit::NAMES.join("\", \"")
                    ),
                )
            })?;
            at2.with_stated_unit(unit).map_err(|err| {
                src.err(
                    "excitation.units",
                    format_args!("cannot use the record: {err}"),
                )
            })
        }
    }
}

/// The record format a scene names (`excitation.format`), else the one the file's extension
/// implies.
fn record_format(
    src: &Source,
    e: &ExcitationSpec,
    file: &Path,
) -> Result<RecordFormat, SceneError> {
    let allowed = RecordFormat::NAMES.join("\", \"");
    match e.format.as_deref() {
        Some(name) => RecordFormat::parse(name).ok_or_else(|| {
            src.err(
                "excitation.format",
                format_args!(
                    "`format` = \"{name}\" in [excitation] is not allowed: one of \"{allowed}\""
                ),
            )
        }),
        // PEER AT2 unless the extension names another format (as before formats were added)
        None => Ok(RecordFormat::from_path(file).unwrap_or(RecordFormat::At2)),
    }
}
