//! Knobs: a scene value that a sweep varies, resolved once per axis. A cell applies its value to
//! the typed scene (no `--set` string is formatted and no TOML re-parsed) and builds its setup.

use crate::scene::{Scene, SceneSpec};
use crate::setup::{build_spec, Setup};
use crate::SceneError;

type Number = fn(&mut SceneSpec) -> &mut Option<f64>;
type Text = fn(&mut SceneSpec) -> &mut Option<String>;

macro_rules! fields {
    ($ty:ty; $( $table:ident . $field:ident => $label:expr ),* $(,)?) => {
        &[ $( (
            concat!(stringify!($table), ".", stringify!($field)),
            $label,
            |s: &mut SceneSpec| &mut s.$table.get_or_insert_with(Default::default).$field,
        ) ),* ]
    };
}

/// A record's scale factor (a batch's axis).
pub const SCALE_FACTOR: &str = "scale factor";

/// The numeric keys of the scene format, each with its label in the paper's notation and its
/// field: the one list the knobs, the axis labels and the sweeps read.
const NUMBERS: &[(&str, &str, Number)] = fields!(f64;
    structure.omega_n_over_p => "ω_n/p",
    structure.alpha => "α",
    structure.gamma_mc => "γ_mc",
    structure.gamma_mb => "γ_mb",
    structure.gamma_ib => "γ_ib",
    structure.r => "R (m)",
    structure.p => "p (1/s)",
    structure.zeta => "ζ",
    structure.h => "H (m)",
    structure.b => "B (m)",
    structure.ei => "EI (N m²)",
    structure.m => "m (kg)",
    structure.m_c => "m_c (kg)",
    structure.m_b => "m_b (kg)",
    structure.i_bc => "I_bc (kg m²)",
    structure.g => "g (m/s²)",
    excitation.omega_p_over_p => "ω_p/p",
    excitation.omega_p => "ω_p (rad/s)",
    excitation.amplitude => "a_p/(g tan α)",
    excitation.amplitude_g => "a_p/g",
    excitation.a_p => "a_p (m/s²)",
    excitation.velocity_amplitude => "v_p/(g tan α/p)",
    excitation.v_p => "v_p (m/s)",
    excitation.gamma => "γ (pulse)",
    excitation.nu => "ν (pulse phase)",
    excitation.scale => SCALE_FACTOR,
    initial.theta_over_alpha => "θ₀/α",
    initial.u_over_ucr => "u₀/u_cr",
    initial.theta_dot_over_alpha_p => "θ'₀/(α p)",
    initial.u_dot_over_ucr_omega_n => "u̇₀/(u_cr ω_n)",
    initial.v_over_static => "v(0)/v₀",
    solver.tol => "tolerance",
    solver.after_excitation => "τ after the excitation",
    output.history_dt => "Δτ",
    effects.friction => "μ (ground friction)",
    effects.bearing_over_mean => "q/(W/2B) (bearing)",
    effects.bearing => "q (Pa, bearing)",
    effects.footing_length => "footing length (m)",
    ground.omega_v_over_p => "ω_v/p",
    ground.zeta_v => "ζ_v",
    ground.k => "k (N/m²)",
    ground.c => "c (N s/m²)",
    ground.k_spring => "k_spring (N/m)",
    ground.c_spring => "c_spring (N s/m)",
);

/// The text keys a sweep may vary (a batch sweeps records), with their labels.
const TEXTS: &[(&str, &str, Text)] = fields!(String;
    excitation.path => "record",
    excitation.kind => "excitation",
);

/// A resolved scene key.
#[derive(Clone, Copy)]
enum Kind {
    Number(Number),
    Text(Text),
    /// A parameter the scene's model adds (`structure.m_a`).
    Extra(&'static str),
}

/// A scene key a sweep varies, resolved once.
#[derive(Clone)]
pub struct Knob {
    /// The dotted key, as given.
    pub key: String,
    kind: Kind,
}

/// A value a knob sets.
#[derive(Clone, Debug)]
pub enum KnobValue {
    /// A number.
    Number(f64),
    /// A text (a record's path).
    Text(String),
}

impl Knob {
    /// Resolves `key` for `scene`: a numeric or text key of the scene format, or a parameter the
    /// scene's model adds. Other keys (tables such as `effects.impact`) are not knobs: sweep them
    /// with `--set`.
    pub fn resolve(scene: &Scene, key: &str) -> Result<Knob, SceneError> {
        let kind = if let Some((_, _, f)) = NUMBERS.iter().find(|(k, _, _)| *k == key) {
            Kind::Number(*f)
        } else if let Some((_, _, f)) = TEXTS.iter().find(|(k, _, _)| *k == key) {
            Kind::Text(*f)
        } else {
            let model = crate::setup::scene_model(&scene.spec)
                .map_err(|e| scene.src.err("structure.model", e))?;
            match key
                .strip_prefix("structure.")
                .and_then(|p| model.extra_params().find(|q| q.name == p))
            {
                Some(p) => Kind::Extra(p.name),
                None => {
                    return Err(SceneError::input(format!(
                        "{}: `{key}` cannot be swept: not a number or text key of the scene \
                         format, nor a parameter of model `{}`",
                        scene.src.path.display(),
                        model.name
                    )))
                }
            }
        };
        // One ratio for every mode replaces a scene's list of ratios per mode, which a knob
        // (an `Option<f64>`) cannot clear: such a sweep goes through `--set`, as other tables do.
        let per_mode = scene
            .spec
            .structure
            .as_ref()
            .and_then(|s| s.zeta_per_mode.as_ref());
        if key == "structure.zeta" && per_mode.is_some() {
            return Err(scene.src.err(
                "structure.zeta",
                "`structure.zeta` replaces the scene's damping ratios per mode: not a knob",
            ));
        }
        Ok(Knob {
            key: key.to_string(),
            kind,
        })
    }

    /// Sets the knob's value in `spec`.
    pub fn apply(&self, spec: &mut SceneSpec, value: &KnobValue) -> Result<(), SceneError> {
        match (self.kind, value) {
            (Kind::Number(f), KnobValue::Number(v)) => *f(spec) = Some(*v),
            (Kind::Text(f), KnobValue::Text(t)) => *f(spec) = Some(t.clone()),
            (Kind::Extra(name), KnobValue::Number(v)) => {
                let st = spec.structure.get_or_insert_with(Default::default);
                st.extra.retain(|(k, _)| *k != name);
                st.extra.push((name, *v));
            }
            _ => {
                return Err(SceneError::input(format!(
                    "`{}`: a value of the wrong kind ({value:?})",
                    self.key
                )))
            }
        }
        Ok(())
    }
}

/// The numeric keys a sweep may vary.
pub fn number_keys() -> impl Iterator<Item = &'static str> {
    NUMBERS.iter().map(|(k, _, _)| *k)
}

/// The text keys a sweep may vary.
pub fn text_keys() -> impl Iterator<Item = &'static str> {
    TEXTS.iter().map(|(k, _, _)| *k)
}

/// The label of a key of the scene format in the paper's notation.
pub fn label(key: &str) -> Option<&'static str> {
    let numbers = NUMBERS.iter().map(|(k, l, _)| (*k, *l));
    let texts = TEXTS.iter().map(|(k, l, _)| (*k, *l));
    numbers
        .chain(texts)
        .find(|(k, _)| *k == key)
        .map(|(_, l)| l)
}

/// The setup of `scene` with the knobs set to `values` (a sweep cell).
pub fn setup(scene: &Scene, knobs: &[(&Knob, KnobValue)]) -> Result<Setup, SceneError> {
    let mut spec = scene.spec.clone();
    for (knob, v) in knobs {
        knob.apply(&mut spec, v)?;
    }
    build_spec(&spec, &scene.src)
}
