//! From a typed scene to what the solver runs: structure, excitation, effects, options.

use rocking::{
    find_model, select_variant, Accuracy, Effects, History, Initial, Method, ModelInfo, Options,
    ParamError, Preset, Selection, Structure, VariantInfo, PAPER_MODEL,
};
use rocking_motion::{Excitation, STANDARD_GRAVITY};

use crate::check::{finite, formed, param_err};
use crate::effects::{impact_model, overturn_angle};
pub use crate::ground::ground;
use crate::scene::{OutputSpec, Scene, SceneSpec, Source};
use crate::structure::build_structure;
pub use crate::units::{Scales, Units};
use crate::SceneError;

/// The most history rows a run may ask for (about 80 bytes each in memory and in history.csv).
const MAX_ROWS: f64 = 5e6;

/// Everything a run or a check needs.
pub struct Setup {
    pub title: Option<String>,
    pub structure: Structure,
    pub effects: Effects,
    pub options: Options,
    pub excitation: Excitation,
    pub excitation_description: String,
    /// End of the excitation, model time.
    pub excitation_end: f64,
    pub variant: &'static VariantInfo,
    pub reasons: Vec<String>,
    pub units: Units,
    /// What the run's quantities are normalised by (computed once here).
    pub scales: Scales,
    pub plots: bool,
    /// History rows were asked for in the scene (written to history.csv).
    pub history_csv: bool,
    /// The animated GIF asked for (`[output] animation = true`).
    pub animation: Option<Animation>,
    /// Run the fixed-base twin too (`[output] fixed_base_reference = true`).
    pub fixed_base_reference: bool,
    /// A compliant ground (`[ground]`, issue 44); `None`: the rigid surface.
    pub ground: Option<rocking::Ground>,
}

/// The frame count and size (pixels) of an animated GIF of a run: bounded so that a GIF stays a
/// few MB (400 frames of 800 × 600 at most).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Animation {
    pub frames: usize,
    pub width: u32,
    pub height: u32,
}

impl Animation {
    /// Defaults and bounds: (key, default, lowest, highest).
    pub const FRAMES: (&'static str, i64, i64, i64) = ("animation_frames", 150, 2, 400);
    pub const WIDTH: (&'static str, i64, i64, i64) = ("animation_width", 480, 160, 800);
    pub const HEIGHT: (&'static str, i64, i64, i64) = ("animation_height", 600, 120, 600);
}

impl Default for Animation {
    fn default() -> Self {
        Animation {
            frames: Self::FRAMES.1 as usize,
            width: Self::WIDTH.1 as u32,
            height: Self::HEIGHT.1 as u32,
        }
    }
}

/// `[output] animation` and its frame count and size, checked against their bounds.
fn animation(src: &Source, out: Option<&OutputSpec>) -> Result<Option<Animation>, SceneError> {
    let Some(o) = out.filter(|o| o.animation == Some(true)) else {
        return Ok(None);
    };
    let pick = |given: Option<i64>, (key, default, lo, hi): (&str, i64, i64, i64)| match given {
        None => Ok(default),
        Some(v) if (lo..=hi).contains(&v) => Ok(v),
        Some(v) => Err(src
            .err(
                &format!("output.{key}"),
                format_args!("`{key}` = {v} in [output] is not allowed: {lo} <= {key} <= {hi}"),
            )
            .with_value(v, format!("{lo} <= {key} <= {hi}"))),
    };
    Ok(Some(Animation {
        frames: pick(o.animation_frames, Animation::FRAMES)? as usize,
        width: pick(o.animation_width, Animation::WIDTH)? as u32,
        height: pick(o.animation_height, Animation::HEIGHT)? as u32,
    }))
}

/// A run guard (`max_steps`, `max_events` in [solver]): a whole number from 1 to 1e12.
fn guard(src: &Source, path: &str, v: Option<f64>, default: u64) -> Result<u64, SceneError> {
    match v {
        None => Ok(default),
        Some(x) => finite(
            src,
            path,
            x,
            (1.0..=1e12).contains(&x) && x.fract() == 0.0,
            "a whole number 1 <= n <= 1e12",
        )
        .map(|x| x as u64),
    }
}

/// The model a typed scene names (default: the paper's).
pub fn scene_model(spec: &SceneSpec) -> Result<&'static ModelInfo, ParamError> {
    let name = spec.structure.as_ref().and_then(|s| s.model.as_deref());
    find_model(name.unwrap_or(PAPER_MODEL))
}

/// Builds the model of a scene.
pub fn build(scene: &Scene) -> Result<Setup, SceneError> {
    build_spec(&scene.spec, &scene.src)
}

/// Builds the model of a typed scene (as a sweep cell does after applying its knobs); `src`
/// places error messages.
pub fn build_spec(spec: &SceneSpec, src: &Source) -> Result<Setup, SceneError> {
    let fx = spec.effects.as_ref();
    let st = spec
        .structure
        .as_ref()
        .ok_or_else(|| src.err("", "missing table [structure]"))?;
    let model = scene_model(spec).map_err(|e| param_err(src, "structure", e))?;
    let mut effects = Effects {
        flexibility: fx.and_then(|f| f.flexibility).unwrap_or(true),
        damping: fx.and_then(|f| f.damping).unwrap_or(true),
        large_rotations: fx.and_then(|f| f.large_rotations).unwrap_or(true),
        ..Effects::default()
    };
    // `column_mass` and `base_mass` are the older names of the switches `m_c` and `m_b`.
    let aliases = [
        ("m_c", fx.and_then(|f| f.column_mass)),
        ("m_b", fx.and_then(|f| f.base_mass)),
    ];
    let switches = fx.map(|f| f.masses.as_slice()).unwrap_or_default();
    for (name, on) in aliases
        .iter()
        .filter_map(|&(n, on)| Some((n, on?)))
        .chain(switches.iter().copied())
    {
        if !on {
            effects = effects.without_mass(name);
        }
    }
    let structure = build_structure(src, st, !effects.flexibility, model)?;
    // The structure with the switched-off effects removed: what is simulated and reported.
    let Selection {
        structure,
        variant,
        reasons,
    } = select_variant(&structure, &effects).map_err(|e| {
        let switch = matches!(e.parameter, "flexibility" | "large_rotations")
            || effects.masses_off.contains(e.parameter);
        param_err(src, if switch { "effects" } else { "structure" }, e)
    })?;
    let physical = st.h.is_some();
    let derived = structure.derived();
    crate::limits::derived_quantities(src, &structure, &derived, physical)?;
    let ph = structure.physical();
    let units = Units {
        physical,
        g_model: ph.g,
        g_si: if physical { ph.g } else { STANDARD_GRAVITY },
        p_model: derived.p,
        sec_per_unit: structure.p_per_second().map(|ps| derived.p / ps),
        tan_alpha: derived.alpha.tan(),
        alpha: derived.alpha,
    };
    let crate::excitation::Built {
        motion: excitation,
        description: excitation_description,
        end: excitation_end,
    } = crate::excitation::build(spec, src, &units)?;

    let ground = ground(spec, src, &structure, physical, derived.p)?;
    let scales = Scales::of(&structure, &derived, &units, ground.as_ref());
    if ground.is_some() {
        if let Some(key) = fx.and_then(|f| f.impact.as_ref().map(|_| "effects.impact")) {
            return Err(src.err(
                key,
                "`impact` in [effects] chooses the rigid surface's impact map: a compliant \
                 [ground] has no impacts (the contact is resolved in time): remove it (the \
                 override `effects.impact=null` removes it), or give [ground] kind = \"rigid\"",
            ));
        }
    }
    let impact = impact_model(src, fx.and_then(|f| f.impact.as_ref()))?;
    let overturn = overturn_angle(src, fx.and_then(|f| f.overturn.as_ref()))?;
    let energy = fx.and_then(|f| f.energy).unwrap_or(false);
    let uplift = fx.and_then(|f| f.uplift).unwrap_or(true);
    let friction = match fx.and_then(|f| f.friction) {
        Some(mu) => Some(finite(
            src,
            "effects.friction",
            mu,
            mu >= 0.0,
            "a coefficient of friction >= 0",
        )?),
        None => None,
    };

    let sv = spec.solver.as_ref();
    let mut accuracy: Accuracy = sv
        .and_then(|s| s.accuracy)
        .unwrap_or(Preset::Default)
        .accuracy_for(&excitation);
    if let Some(m) = sv.and_then(|s| s.method.as_deref()) {
        let wanted = m.to_lowercase();
        accuracy.method = Method::ALL
            .into_iter()
            .find(|method| method.name() == wanted)
            .ok_or_else(|| {
                let names: Vec<String> = Method::ALL
                    .iter()
                    .map(|m| format!("\"{}\"", m.name()))
                    .collect();
                let allowed = format!(
                    "{} or {}",
                    names[..names.len() - 1].join(", "),
                    names[names.len() - 1]
                );
                src.err(
                    "solver.method",
                    format_args!("`method` = \"{wanted}\" in [solver] is not allowed: {allowed}"),
                )
                .with_value(&wanted, allowed)
            })?;
    }
    if let Some(tol) = sv.and_then(|s| s.tol) {
        accuracy.tol = finite(
            src,
            "solver.tol",
            tol,
            (1e-14..=1e-2).contains(&tol),
            "a relative tolerance 1e-14 <= tol <= 1e-2",
        )?;
    }
    let after = sv.and_then(|s| s.after_excitation).unwrap_or(40.0);
    finite(
        src,
        "solver.after_excitation",
        after,
        (0.0..=1e6).contains(&after),
        "a duration 0 <= τ <= 1e6 after the excitation ends",
    )?;
    let t_end = excitation_end + after / units.p_model;
    formed(
        src,
        "solver.after_excitation",
        after,
        t_end,
        "end time in model units",
    )?;
    if t_end <= 0.0 {
        return Err(src.err(
            "solver.after_excitation",
            "nothing to simulate: the excitation has no duration and `after_excitation` = 0",
        ));
    }

    let mut initial = Initial::default();
    if let Some(i) = spec.initial.as_ref() {
        if let Some(x) = i.theta_over_alpha {
            let limit = overturn / units.alpha;
            finite(
                src,
                "initial.theta_over_alpha",
                x,
                x.abs() < limit,
                &format!("|θ/α| < {limit:.4} (the overturning angle / α)"),
            )?;
            initial.theta = x * units.alpha;
        }
        if let Some(x) = i.u_over_ucr {
            finite(
                src,
                "initial.u_over_ucr",
                x,
                x.abs() <= 1e3,
                "|u/u_cr| <= 1000",
            )?;
            initial.u = x * derived.u_cr;
        }
        if let Some(x) = i.theta_dot_over_alpha_p {
            finite(
                src,
                "initial.theta_dot_over_alpha_p",
                x,
                x.abs() <= 1e3,
                "|θ'/(α p)| <= 1000",
            )?;
            initial.theta_dot = x * units.alpha * units.p_model;
        }
        if let Some(x) = i.u_dot_over_ucr_omega_n {
            finite(
                src,
                "initial.u_dot_over_ucr_omega_n",
                x,
                x.abs() <= 1e3,
                "|u'/(u_cr ω_n)| <= 1000",
            )?;
            initial.u_dot = x * derived.u_cr * derived.omega_n;
        }
        if let Some(x) = i.v_over_static {
            let Some(g) = scales.ground.as_ref() else {
                return Err(src.err(
                    "initial.v_over_static",
                    "`v_over_static` in [initial] is the base's settlement on a compliant \
                     [ground]: the rigid surface has none (give [ground] kind = \"winkler\" or \
                     \"two-spring\", or remove it)",
                ));
            };
            finite(
                src,
                "initial.v_over_static",
                x,
                x.abs() <= 1e3,
                "|v/v₀| <= 1000",
            )?;
            initial.v = Some(x * g.settlement);
        }
    }

    let out = spec.output.as_ref();
    let plots = out.and_then(|o| o.plots).unwrap_or(false);
    let history = match (
        out.and_then(|o| o.history.as_deref()),
        out.and_then(|o| o.history_dt),
    ) {
        // `history = "none"` switches a grid off too (handy with --set).
        (Some("none"), _) | (None, None) => History::None,
        (Some("steps"), Some(_)) => {
            return Err(src.err(
                "output.history_dt",
                "give either `history = \"steps\"` or `history_dt` in [output], not both",
            ))
        }
        (Some("steps"), None) => History::Steps,
        (Some(other), _) => {
            return Err(src.err(
                "output.history",
                format_args!(
                    "`history` = \"{other}\" in [output] is not allowed: \"none\" or \"steps\" \
                     (or a grid: history_dt = τ step)"
                ),
            ))
        }
        (None, Some(dt)) => {
            finite(
                src,
                "output.history_dt",
                dt,
                dt > 0.0 && t_end * units.p_model / dt <= MAX_ROWS,
                "a grid step τ > 0 giving at most 5e6 rows",
            )?;
            History::Grid(dt / units.p_model)
        }
    };
    let history_csv = history != History::None;
    let animation = animation(src, out)?;
    // Plots and animations need a history: a 0.01 τ grid unless the scene asked for one.
    let history = if (plots || animation.is_some()) && history == History::None {
        let rows = t_end * units.p_model / 0.01;
        if rows > MAX_ROWS {
            return Err(src.err(
                "output.plots",
                format_args!(
                    "`plots` = true in [output] samples the run every 0.01 τ: τ = 0 .. {} gives \
                     {} rows, at most {MAX_ROWS:e}; give a coarser history_dt or a shorter run",
                    crate::limits::short(t_end * units.p_model),
                    crate::limits::short(rows.ceil())
                ),
            ));
        }
        History::Grid(0.01 / units.p_model)
    } else {
        history
    };

    let defaults = Options::default();
    let max_steps = guard(
        src,
        "solver.max_steps",
        sv.and_then(|s| s.max_steps),
        defaults.max_steps,
    )?;
    if let (Excitation::Record(record), Some(spu)) = (&excitation, units.sec_per_unit) {
        let omega_n = (!variant.rigid).then_some(derived.omega_n);
        let name = crate::excitation::file_of(
            src,
            spec.excitation.as_ref().unwrap_or(&Default::default()),
        )?;
        let name = name.display().to_string();
        let p = units.p_model;
        crate::limits::record_length(src, &name, record, p, omega_n, spu, max_steps)?;
    }
    if history == History::Steps && max_steps as f64 > rocking::MAX_HISTORY_ROWS {
        return Err(src.err(
            "solver.max_steps",
            format_args!(
                "`max_steps` = {} in [solver] is not allowed with history = \"steps\" (one row \
                 per step): at most {:e}; give a grid (history_dt) for longer runs",
                crate::limits::short(max_steps as f64),
                rocking::MAX_HISTORY_ROWS
            ),
        ));
    }
    let max_events = guard(
        src,
        "solver.max_events",
        sv.and_then(|s| s.max_events),
        defaults.max_events,
    )?;
    let options = Options {
        accuracy,
        max_steps,
        max_events,
        impact,
        overturn_angle: overturn,
        t_end,
        energy,
        history,
        event_log: out.and_then(|o| o.events).unwrap_or(false),
        initial,
        uplift,
        forces: out.and_then(|o| o.forces).unwrap_or(true),
        friction,
        bearing_over_mean: crate::ground::bearing(src, fx, ground.as_ref(), &structure, physical)?,
        ..Options::default()
    };
    if !uplift {
        let given = [
            ("initial.theta_over_alpha", initial.theta),
            ("initial.theta_dot_over_alpha_p", initial.theta_dot),
        ];
        if let Some((key, _)) = given.iter().find(|(_, v)| *v != 0.0) {
            return Err(src.err(
                key,
                format!(
                    "`{}` in [initial] starts the base tilted or rotating, and `uplift = false` \
                     in [effects] holds it in full contact from t = 0: give 0, or let it uplift \
                     (the fixed-base twin of a tilted start is `fixed_base_reference = true`, \
                     which starts the twin upright)",
                    key.trim_start_matches("initial.")
                ),
            ));
        }
    }
    if friction.is_some() && !options.forces {
        return Err(src.err(
            "effects.friction",
            "`friction` in [effects] is checked against the ground reactions R_h and R_v, which \
             `forces = false` in [output] does not track: give `forces = true`, or no friction",
        ));
    }
    let fixed_base_reference = out.and_then(|o| o.fixed_base_reference).unwrap_or(false);
    if fixed_base_reference {
        check_twin(
            src,
            "output.fixed_base_reference",
            "`fixed_base_reference` in [output]",
            &options,
        )?;
    }
    if let Some(g) = &ground {
        // What a compliant ground does not run yet (issue 44, docs/ground.md), refused by name.
        if animation.is_some() {
            return Err(src.err(
                "output.animation",
                format!(
                    "`animation` in [output] with [ground] kind = \"{}\": the animation draws \
                     the rigid surface's motion, not the settlement (docs/ground.md): remove it",
                    g.kind.name()
                ),
            ));
        }
    }
    Ok(Setup {
        title: spec.title.clone(),
        structure,
        effects,
        options,
        excitation,
        excitation_description,
        excitation_end,
        variant,
        reasons,
        units,
        scales,
        plots,
        history_csv,
        fixed_base_reference,
        animation,
        ground,
    })
}

/// What a comparison with the fixed-base twin (`[output] fixed_base_reference`, a ratio in
/// `[sweep] report`) needs of the run itself, for `run` and the sweeps alike: that it may
/// uplift (else the twin is the run, and every ratio 1) and that it track the forces.
/// `subject` names the setting (`key` is its path in the scene).
pub fn check_twin(
    src: &Source,
    key: &str,
    subject: &str,
    options: &Options,
) -> Result<(), SceneError> {
    if !options.uplift {
        return Err(src.err(
            key,
            format!(
                "{subject} compares the run with its fixed-base twin: it needs the run itself to \
                 uplift (`uplift = true` in [effects])"
            ),
        ));
    }
    if !options.forces {
        return Err(src.err(
            key,
            format!(
                "{subject} compares the forces of the run and of its fixed-base twin: it needs \
                 `forces = true` in [output]"
            ),
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `omega_v_over_p` and `zeta_v` give K_v = M (omega_v)^2 and C_v = 2 zeta_v sqrt(K_v M):
    /// the settlement is g / omega_v^2 and the kernels' k, c are K_v / 2B, C_v / 2B (bed) or
    /// K_v / 2, C_v / 2 (two springs); SI scenes give k, c as they are.
    #[test]
    fn ground_from_the_vertical_frequency_and_in_si() {
        let base =
            "[structure]\nomega_n_over_p = 11.9\nalpha = 0.2\ngamma_mc = 0.5\ngamma_mb = 1.0\n\
                    gamma_ib = 1.0\nzeta = 0.005\n\n[excitation]\nkind = \"sine-pulse\"\n\
                    omega_p_over_p = 5.1\namplitude = 1.3\n";
        for (kind, per) in [("winkler", 2.0 * 0.2f64.sin()), ("two-spring", 2.0)] {
            let text = format!(
                "{base}\n[ground]\nkind = \"{kind}\"\nomega_v_over_p = 40.0\nzeta_v = 0.05\n"
            );
            let sc = crate::scene::load_text(std::path::Path::new("g.toml"), text, &[]).unwrap();
            let model = scene_model(&sc.spec).unwrap();
            let st = build_structure(&sc.src, sc.spec.structure.as_ref().unwrap(), false, model)
                .unwrap();
            let d = st.derived();
            let g = ground(&sc.spec, &sc.src, &st, false, d.p).unwrap().unwrap();
            let w = st.static_uplift().weight;
            let m = w / st.physical().g;
            let omega_v = 40.0 * d.p;
            // R = 1: B = sin(alpha).
            assert!((g.b - 0.2f64.sin()).abs() < 1e-15);
            let k_v = m * omega_v * omega_v;
            assert!((g.k * per - k_v).abs() < 1e-12 * k_v, "{kind}: {g:?}");
            let c_v = 2.0 * 0.05 * (k_v * m).sqrt();
            assert!((g.c * per - c_v).abs() < 1e-12 * c_v, "{kind}: {g:?}");
            let settlement = g.statics(w).settlement;
            let want = st.physical().g / (omega_v * omega_v);
            assert!(
                (settlement - want).abs() < 1e-14 * want,
                "{kind}: {settlement}"
            );
        }
        let si = "[structure]\nh = 30.0\nb = 3.0\nei = 2.0e10\nm = 1.0e5\nm_c = 5.0e4\nm_b = 1.0e5\n\
                  zeta = 0.01\ng = 9.81\n\n[excitation]\nkind = \"sine-pulse\"\nomega_p = 3.0\n\
                  amplitude_g = 0.3\n\n[ground]\nkind = \"two-spring\"\nk_spring = 2e9\nc_spring = 1e6\n";
        let sc = crate::scene::load_text(std::path::Path::new("g.toml"), si.into(), &[]).unwrap();
        let model = scene_model(&sc.spec).unwrap();
        let st =
            build_structure(&sc.src, sc.spec.structure.as_ref().unwrap(), false, model).unwrap();
        let g = ground(&sc.spec, &sc.src, &st, true, st.derived().p)
            .unwrap()
            .unwrap();
        assert_eq!((g.k, g.c, g.b), (2e9, 1e6, 3.0));
    }
}
