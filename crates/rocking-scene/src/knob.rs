//! Knobs: a scene value that a sweep varies, resolved once per axis. A cell applies its value to
//! the typed scene (no `--set` string is formatted and no TOML re-parsed) and builds its setup.

use crate::scene::{Scene, SceneSpec};
use crate::setup::{build_spec, Setup};
use crate::SceneError;

type Number = fn(&mut SceneSpec) -> &mut Option<f64>;
type Text = fn(&mut SceneSpec) -> &mut Option<String>;

macro_rules! fields {
    ($ty:ty; $( $table:ident . $field:ident ),* $(,)?) => {
        &[ $( (
            concat!(stringify!($table), ".", stringify!($field)),
            |s: &mut SceneSpec| &mut s.$table.get_or_insert_with(Default::default).$field,
        ) ),* ]
    };
}

/// The numeric keys of the scene format, with their fields.
const NUMBERS: &[(&str, Number)] = fields!(f64;
    structure.omega_n_over_p, structure.alpha, structure.gamma_mc, structure.gamma_mb,
    structure.gamma_ib, structure.r, structure.p, structure.zeta, structure.h, structure.b,
    structure.ei, structure.m, structure.m_c, structure.m_b, structure.i_bc, structure.g,
    excitation.omega_p_over_p, excitation.omega_p, excitation.amplitude, excitation.amplitude_g,
    excitation.a_p, excitation.velocity_amplitude, excitation.v_p, excitation.gamma,
    excitation.nu, excitation.scale,
    initial.theta_over_alpha, initial.u_over_ucr, initial.theta_dot_over_alpha_p,
    initial.u_dot_over_ucr_omega_n,
    solver.tol, solver.after_excitation, output.history_dt,
);

/// The text keys a sweep may vary (a batch sweeps records).
const TEXTS: &[(&str, Text)] = fields!(String; excitation.path, excitation.kind);

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
        let kind = if let Some((_, f)) = NUMBERS.iter().find(|(k, _)| *k == key) {
            Kind::Number(*f)
        } else if let Some((_, f)) = TEXTS.iter().find(|(k, _)| *k == key) {
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
    NUMBERS.iter().map(|(k, _)| *k)
}

/// The text keys a sweep may vary.
pub fn text_keys() -> impl Iterator<Item = &'static str> {
    TEXTS.iter().map(|(k, _)| *k)
}

impl Knob {
    /// The knob's label in the paper's notation (`crate::labels`).
    pub fn label(&self) -> String {
        crate::labels::axis_label(&self.key)
    }
}

/// The setup of `scene` with the knobs set to `values` (a sweep cell).
pub fn setup(scene: &Scene, knobs: &[(&Knob, KnobValue)]) -> Result<Setup, SceneError> {
    let mut spec = scene.spec.clone();
    for (knob, v) in knobs {
        knob.apply(&mut spec, v)?;
    }
    build_spec(&spec, &scene.src)
}
