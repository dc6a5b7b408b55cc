//! Scene files: TOML text → `toml::Table` → `--set` overrides → typed [`SceneSpec`] (serde), with
//! errors that name the file, the line:column and the key.

use std::collections::HashMap;
use std::fmt;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};

use rocking::{ModelInfo, PAPER_MODEL};
use rocking_motion::{read_record, At2Record, RecordFormat};
use toml::{Table, Value};

pub use crate::ground_spec::{GroundKindSpec, GroundSpec};
pub use crate::spec::{
    EffectsSpec, ExcitationSpec, IdaSpec, InitialSpec, MassSwitches, ModelParams, OutputSpec,
    SceneSpec, SolverSpec, StructureSpec, SweepSpec,
};
use crate::{InputError, SceneError};

/// A loaded scene: the typed spec and what is needed to point at its source.
#[derive(Clone)]
pub struct Scene {
    pub spec: SceneSpec,
    pub src: Source,
}

/// Where the scene's values came from, for error messages.
#[derive(Clone)]
pub struct Source {
    /// The scene file as given.
    pub path: PathBuf,
    text: String,
    /// Byte offset of each key (dotted path) in the file.
    spans: HashMap<String, usize>,
    /// Dotted paths set (or replaced) with `--set`, and the argument that set each.
    overridden: HashMap<String, String>,
    /// Records read so far, by path: a sweep reads each once.
    records: Records,
}

/// Records read by the scenes of one sweep, by path (shared by every cell).
pub type Records = Arc<Mutex<HashMap<(PathBuf, RecordFormat), At2Record>>>;

impl Source {
    /// The record at `file`, read once per scene (and per sweep).
    pub fn record(&self, file: &Path) -> Result<At2Record, rocking_motion::MotionError> {
        self.record_as(file, RecordFormat::At2, None)
    }

    /// The record at `file` in `format` (`dt`: the step of a one-column text file), read once
    /// per scene (and per sweep).
    pub fn record_as(
        &self,
        file: &Path,
        format: RecordFormat,
        dt: Option<f64>,
    ) -> Result<At2Record, rocking_motion::MotionError> {
        let mut cache = self.records.lock().unwrap_or_else(|e| e.into_inner());
        let key = (file.to_path_buf(), format);
        if let Some(r) = cache.get(&key).filter(|r| dt.is_none_or(|d| d == r.dt)) {
            return Ok(r.clone());
        }
        let r = read_record(file, format, dt)?;
        cache.insert(key, r.clone());
        Ok(r)
    }

    /// The directory of the scene file (relative paths in the scene are relative to it).
    pub fn dir(&self) -> PathBuf {
        self.path
            .parent()
            .map(Path::to_path_buf)
            .unwrap_or_else(|| PathBuf::from("."))
    }

    fn line_col(&self, offset: usize) -> (usize, usize) {
        let before = &self.text[..offset.min(self.text.len())];
        let line = before.matches('\n').count() + 1;
        let col = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
        (line, col)
    }

    /// Where the key at `path` (or its closest ancestor present in the file) is: its line and
    /// column, or the override that gave it; `None` when it is nowhere in the file.
    fn place(&self, path: &str) -> Option<Place> {
        let mut p = path.to_string();
        loop {
            if let Some(arg) = self.overridden.get(&p) {
                return Some(Place::Set(arg.clone()));
            }
            if let Some(&off) = self.spans.get(&p) {
                let (l, c) = self.line_col(off);
                return Some(Place::At(l, c));
            }
            match p.rfind('.') {
                Some(i) => p.truncate(i),
                None => return None,
            }
        }
    }

    /// An input error about the key at `path`, placed at its line and column in the file or
    /// at the override that gave it.
    pub fn err(&self, path: &str, msg: impl fmt::Display) -> SceneError {
        let mut e = InputError {
            file: Some(self.path.clone()),
            key: Some(path.to_string()),
            detail: msg.to_string(),
            ..InputError::default()
        };
        match self.place(path) {
            Some(Place::Set(arg)) => e.set = Some(arg),
            Some(Place::At(l, c)) => (e.line, e.column) = (Some(l), Some(c)),
            None => {}
        }
        SceneError::from(e)
    }

    /// The value `v` of the key at `path` is outside what is `allowed`.
    pub fn not_allowed(&self, path: &str, v: f64, allowed: &str) -> SceneError {
        let value = rocking_motion::short_number(v);
        self.err(
            path,
            format_args!("{} = {value} is not allowed: {allowed}", describe(path)),
        )
        .with_value(value, allowed)
    }
}

/// Where a key's value came from.
enum Place {
    /// Line and column in the file.
    At(usize, usize),
    /// An override `KEY=VALUE`.
    Set(String),
}

/// `[table]` name and key of a dotted path, for messages.
pub fn describe(path: &str) -> String {
    match path.rsplit_once('.') {
        Some((table, key)) => format!("`{key}` in [{table}]"),
        None => format!("`{path}`"),
    }
}

/// The allowed key closest to `key`, if it is close enough to be a typo.
pub fn suggest<'a>(key: &str, allowed: &[&'a str]) -> Option<&'a str> {
    let lower = key.to_lowercase();
    if lower.len() >= 3 {
        if let Some(a) = allowed.iter().find(|a| a.starts_with(&lower)) {
            return Some(a);
        }
    }
    let (best, d) = allowed
        .iter()
        .map(|a| (*a, strsim::levenshtein(&key.to_lowercase(), a)))
        .min_by_key(|&(_, d)| d)?;
    let limit = (key.chars().count().max(best.len()) / 3).max(2);
    (d <= limit).then_some(best)
}

/// Parses one override `key.path=value`: the value as TOML (number, bool, string, inline
/// table, array), a bare word as a string, and the bare word `null` (which TOML lacks) as
/// `None`: remove the key from the scene (as Helm's `--set key=null`), e.g. a rigid-surface
/// scene's `effects.impact` to put it on a compliant ground.
pub fn parse_override(arg: &str) -> Result<(Vec<String>, Option<Value>), SceneError> {
    let bad = |why: &str| {
        SceneError::from(InputError {
            set: Some(arg.to_string()),
            detail: format!("{why} (expected KEY.PATH=VALUE, e.g. structure.alpha=0.2)"),
            ..InputError::default()
        })
    };
    let (key, raw) = arg.split_once('=').ok_or_else(|| bad("no `=`"))?;
    let path: Vec<String> = key
        .trim()
        .split('.')
        .map(|s| s.trim().to_string())
        .collect();
    if path.iter().any(|s| s.is_empty()) {
        return Err(bad("empty key in the path"));
    }
    let raw = raw.trim();
    if raw.is_empty() {
        return Err(bad("empty value"));
    }
    if raw == "null" {
        return Ok((path, None));
    }
    let value = match toml::from_str::<Table>(&format!("v = {raw}")) {
        Ok(mut t) => t.remove("v").unwrap_or(Value::String(raw.to_string())),
        Err(_) => Value::String(raw.to_string()),
    };
    Ok((path, Some(value)))
}

fn collect_spans(prefix: &str, table: &toml::de::DeTable<'_>, out: &mut HashMap<String, usize>) {
    for (k, v) in table.iter() {
        let path = if prefix.is_empty() {
            k.get_ref().to_string()
        } else {
            format!("{prefix}.{}", k.get_ref())
        };
        out.entry(path.clone()).or_insert(k.span().start);
        if let Some(t) = v.get_ref().as_table() {
            collect_spans(&path, t, out);
        }
    }
}

/// Extracts "unknown field `x`, expected one of `a`, `b`" (serde's wording).
fn parse_unknown_field(msg: &str) -> Option<(String, Vec<String>)> {
    let rest = msg.strip_prefix("unknown field `")?;
    let (key, rest) = rest.split_once('`')?;
    let allowed = rest
        .split('`')
        .enumerate()
        .filter(|(i, _)| i % 2 == 1)
        .map(|(_, s)| s.to_string())
        .collect();
    Some((key.to_string(), allowed))
}

/// Reads a scene file.
pub fn read(path: &Path) -> Result<String, SceneError> {
    std::fs::read_to_string(path)
        .map_err(|e| SceneError::input(format!("{}: cannot read scene file: {e}", path.display())))
}

/// Reads, overrides and deserializes a scene file.
pub fn load(path: &Path, sets: &[String]) -> Result<Scene, SceneError> {
    load_text(path, read(path)?, sets)
}

/// Overrides and deserializes the text of the scene file `path`.
pub fn load_text(path: &Path, text: String, sets: &[String]) -> Result<Scene, SceneError> {
    parse_text(path, text)?.load(sets)
}

/// A parsed scene file, before overrides: parse once, then [`Parsed::load`] it with different
/// overrides (as the cells of a sweep do).
#[derive(Clone, Debug)]
pub struct Parsed {
    path: PathBuf,
    text: String,
    table: Table,
    spans: HashMap<String, usize>,
    records: Records,
}

/// Parses the text of the scene file `path`.
pub fn parse_text(path: &Path, text: String) -> Result<Parsed, SceneError> {
    let table: Table = toml::from_str(&text).map_err(|e| {
        let at = e
            .span()
            .map(|s| {
                let before = &text[..s.start.min(text.len())];
                let line = before.matches('\n').count() + 1;
                let col = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
                format!(":{line}:{col}")
            })
            .unwrap_or_default();
        SceneError::input(format!(
            "{}{at}: invalid TOML: {}",
            path.display(),
            e.message().trim()
        ))
    })?;
    let mut spans = HashMap::new();
    if let Ok(de) = toml::de::DeTable::parse(&text) {
        collect_spans("", de.get_ref(), &mut spans);
    }
    Ok(Parsed {
        path: path.to_path_buf(),
        text,
        table,
        spans,
        records: Records::default(),
    })
}

impl Parsed {
    /// Applies the overrides `KEY=VALUE` and deserializes the scene.
    pub fn load(&self, sets: &[String]) -> Result<Scene, SceneError> {
        let path = self.path.as_path();
        let mut table = self.table.clone();
        let mut src = Source {
            path: self.path.clone(),
            text: self.text.clone(),
            spans: self.spans.clone(),
            overridden: HashMap::new(),
            records: self.records.clone(),
        };
        finish(path, &mut table, &mut src, sets)?;
        let spec = deserialize(path, table, &src)?;
        Ok(Scene { spec, src })
    }
}

fn finish(
    path: &Path,
    table: &mut Table,
    src: &mut Source,
    sets: &[String],
) -> Result<(), SceneError> {
    for arg in sets {
        let (keys, value) = parse_override(arg)?;
        let Some(value) = value else {
            remove(path, table, &keys, arg)?;
            continue;
        };
        let mut t = &mut *table;
        for (i, k) in keys[..keys.len() - 1].iter().enumerate() {
            let entry = t
                .entry(k.clone())
                .or_insert_with(|| Value::Table(Table::new()));
            t = match entry {
                Value::Table(t) => t,
                _ => {
                    return Err(SceneError::from(InputError {
                        file: Some(path.to_path_buf()),
                        set: Some(arg.clone()),
                        detail: format!("`{}` is a value, not a table", keys[..=i].join(".")),
                        ..InputError::default()
                    }))
                }
            };
        }
        t.insert(keys[keys.len() - 1].clone(), value);
        src.overridden.insert(keys.join("."), arg.clone());
    }
    Ok(())
}

/// Removes the key `keys` from the scene (`key.path=null`); a key the scene does not have is
/// refused, so that a misspelt one does not pass unnoticed.
fn remove(path: &Path, table: &mut Table, keys: &[String], arg: &str) -> Result<(), SceneError> {
    let (last, parents) = keys.split_last().expect("a key path is never empty");
    let parent = parents
        .iter()
        .try_fold(&mut *table, |t, k| match t.get_mut(k) {
            Some(Value::Table(t)) => Some(t),
            _ => None,
        });
    match parent.and_then(|t| t.remove(last)) {
        Some(_) => Ok(()),
        None => Err(SceneError::from(InputError {
            file: Some(path.to_path_buf()),
            set: Some(arg.to_string()),
            detail: format!(
                "`{}` is not in the scene: there is nothing to remove",
                keys.join(".")
            ),
            ..InputError::default()
        })),
    }
}

/// The model a scene names in `[structure] model` (default: the paper's).
fn scene_model(table: &Table, src: &Source) -> Result<&'static ModelInfo, SceneError> {
    let name = match table.get("structure").and_then(|s| s.get("model")) {
        None => return Ok(rocking::find_model(PAPER_MODEL).expect("the paper's model")),
        Some(Value::String(name)) => name,
        Some(other) => {
            return Err(src.err(
                "structure.model",
                format_args!(
                    "invalid value for `model` in [structure]: {other} is not a model name (a \
                     string: {})",
                    rocking::model_names().join(", ")
                ),
            ))
        }
    };
    let model = rocking::find_model(name).map_err(|_| {
        let names = rocking::model_names();
        let hint = match suggest(name, &names) {
            Some(s) => format!("; did you mean \"{s}\"?"),
            None => String::new(),
        };
        src.err(
            "structure.model",
            format_args!(
                "`model` = \"{name}\" in [structure] is not a model: one of \"{}\" (`rocking \
                 models` lists them){hint}",
                names.join("\", \"")
            ),
        )
    })?;
    Ok(model)
}

/// Takes the keys that are data of the model out of `table`: its own parameters in [structure]
/// and its removable masses as switches in [effects].
fn take_model_keys(
    model: &'static ModelInfo,
    table: &mut Table,
    src: &Source,
) -> Result<(ModelParams, MassSwitches), SceneError> {
    let mut extra = Vec::new();
    if let Some(Value::Table(st)) = table.get_mut("structure") {
        for p in model.extra_params() {
            let path = format!("structure.{}", p.name);
            match st.remove(p.name) {
                None => {}
                Some(Value::Float(v)) => extra.push((p.name, v)),
                Some(Value::Integer(v)) => extra.push((p.name, v as f64)),
                Some(other) => {
                    return Err(src.err(
                        &path,
                        format_args!(
                            "invalid value for {}: {other} is not a number ({})",
                            describe(&path),
                            p.doc
                        ),
                    ))
                }
            }
        }
    }
    let mut masses = Vec::new();
    if let Some(Value::Table(fx)) = table.get_mut("effects") {
        for m in model.removable_masses() {
            let path = format!("effects.{m}");
            match fx.remove(m) {
                None => {}
                Some(Value::Boolean(on)) => masses.push((m, on)),
                Some(other) => {
                    return Err(src.err(
                        &path,
                        format_args!(
                            "invalid value for {}: {other} is not true or false (switches the \
                             mass `{m}` on or off)",
                            describe(&path)
                        ),
                    ))
                }
            }
        }
    }
    Ok((extra, masses))
}

/// A key of `table_name` that belongs to another model, as a hint.
fn other_model_hint(table_name: &str, key: &str, model: &ModelInfo) -> Option<String> {
    let other = rocking_kernels::kernels::MODELS.iter().find(|m| {
        m.name != model.name
            && match table_name {
                "structure" => m.extra_params().any(|p| p.name == key),
                "effects" => m.removable_masses().any(|p| p == key),
                _ => false,
            }
    })?;
    Some(format!(
        "; `{key}` belongs to model `{}`, and this scene's model is `{}` (set `model = \"{}\"` \
         in [structure])",
        other.name, model.name, other.name
    ))
}

/// Takes `zeta` out of [structure] when it is a list (one damping ratio per mode): its numbers.
fn take_zeta_per_mode(table: &mut Table, src: &Source) -> Result<Option<Vec<f64>>, SceneError> {
    let Some(Value::Table(st)) = table.get_mut("structure") else {
        return Ok(None);
    };
    let Some(Value::Array(list)) = st.get("zeta") else {
        return Ok(None);
    };
    let list = list.clone();
    st.remove("zeta");
    let invalid = |what: &dyn fmt::Display| {
        src.err(
            "structure.zeta",
            format_args!(
                "invalid value for `zeta` in [structure]: {what} (give one damping ratio, or a \
                 list of one per fixed-base mode, e.g. zeta = [0.02, 0.05])"
            ),
        )
    };
    if list.is_empty() {
        return Err(invalid(&"an empty list"));
    }
    list.iter()
        .map(|v| match v {
            Value::Float(x) => Ok(*x),
            Value::Integer(i) => Ok(*i as f64),
            other => Err(invalid(&format_args!("{other} is not a number"))),
        })
        .collect::<Result<Vec<_>, _>>()
        .map(Some)
}

fn deserialize(path: &Path, mut table: Table, src: &Source) -> Result<SceneSpec, SceneError> {
    let model = scene_model(&table, src)?;
    let (extra, masses) = take_model_keys(model, &mut table, src)?;
    let zeta_per_mode = take_zeta_per_mode(&mut table, src)?;
    let de = Value::Table(table);
    let mut spec: SceneSpec = deserialize_spec(path, de, src, model)?;
    if zeta_per_mode.is_some() {
        spec.structure
            .get_or_insert_with(Default::default)
            .zeta_per_mode = zeta_per_mode;
    }
    if !extra.is_empty() {
        spec.structure.get_or_insert_with(Default::default).extra = extra;
    }
    if !masses.is_empty() {
        spec.effects.get_or_insert_with(Default::default).masses = masses;
    }
    Ok(spec)
}

fn deserialize_spec(
    path: &Path,
    de: Value,
    src: &Source,
    model: &'static ModelInfo,
) -> Result<SceneSpec, SceneError> {
    serde_path_to_error::deserialize(de).map_err(|e| {
        let p = e.path().to_string();
        let p = if p == "." { String::new() } else { p };
        let inner = e.into_inner();
        let msg = inner.message().trim().to_string();
        if let Some((key, allowed)) = parse_unknown_field(&msg) {
            // The path may or may not end with the unknown key itself.
            let p = match p.strip_suffix(key.as_str()) {
                Some("") => String::new(),
                Some(t) if t.ends_with('.') => t[..t.len() - 1].to_string(),
                _ => p,
            };
            let full = if p.is_empty() {
                key.clone()
            } else {
                format!("{p}.{key}")
            };
            // The model's own keys are allowed too.
            let mut allowed = allowed;
            match p.as_str() {
                "structure" => allowed.extend(model.extra_params().map(|q| q.name.to_string())),
                "effects" => {
                    let own: Vec<String> = model
                        .removable_masses()
                        .filter(|m| !allowed.iter().any(|a| a == m))
                        .map(str::to_string)
                        .collect();
                    allowed.extend(own);
                }
                _ => {}
            }
            let allowed_ref: Vec<&str> = allowed.iter().map(String::as_str).collect();
            let place = if p.is_empty() {
                "at the top level".to_string()
            } else {
                format!("in [{p}]")
            };
            let hint = match (
                other_model_hint(&p, &key, model),
                suggest(&key, &allowed_ref),
            ) {
                (Some(h), _) => h,
                (None, Some(s)) => format!("; did you mean `{s}`?"),
                (None, None) => format!("; allowed keys: {}", allowed.join(", ")),
            };
            return src.err(&full, format_args!("unknown key `{key}` {place}{hint}"));
        }
        if p.is_empty() {
            return SceneError::input(format!("{}: {msg}", path.display()));
        }
        src.err(
            &p,
            format_args!("invalid value for {}: {msg}", describe(&p)),
        )
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn suggestions() {
        let allowed = ["omega_n_over_p", "alpha", "gamma_mc", "gamma_mb", "zeta"];
        assert_eq!(suggest("omega_n_ovr_p", &allowed), Some("omega_n_over_p"));
        assert_eq!(suggest("alpah", &allowed), Some("alpha"));
        assert_eq!(suggest("gama_mc", &allowed), Some("gamma_mc"));
        assert_eq!(suggest("completely_else", &allowed), None);
        assert_eq!(suggest("sine", &["none", "sine-pulse"]), Some("sine-pulse"));
    }

    #[test]
    fn overrides_parse() {
        let (p, v) = parse_override("structure.alpha=0.3").unwrap();
        assert_eq!(p, ["structure", "alpha"]);
        assert_eq!(v, Some(Value::Float(0.3)));
        let (_, v) = parse_override("effects.impact=housner").unwrap();
        assert_eq!(v, Some(Value::String("housner".into())));
        let (_, v) = parse_override("effects.impact={ restitution = 0.9 }").unwrap();
        assert!(v.unwrap().is_table());
        let (p, v) = parse_override("effects.impact = null").unwrap();
        assert_eq!((p, v), (vec!["effects".into(), "impact".into()], None));
        // A quoted "null" is the string.
        let (_, v) = parse_override("structure.model=\"null\"").unwrap();
        assert_eq!(v, Some(Value::String("null".into())));
        assert!(parse_override("alpha").is_err());
        assert!(parse_override("a..b=1").is_err());
    }

    /// `key=null` removes a key: a rigid-surface scene goes on a bed without its impact map;
    /// removing a key the scene lacks is refused with the override named.
    #[test]
    fn an_override_of_null_removes_the_key() {
        let text = "[structure]\nomega_n_over_p = 5.0\nalpha = 0.2\nzeta = 0.01\n\n\
                    [excitation]\nkind = \"sine-pulse\"\nomega_p_over_p = 4.0\namplitude = 2.0\n\n\
                    [effects]\nimpact = \"vvel\"\n";
        let load = |sets: &[&str]| {
            let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
            load_text(Path::new("s.toml"), text.to_string(), &sets)
                .and_then(|sc| crate::setup::build(&sc))
        };
        let bed = ["ground.kind=winkler", "ground.omega_v_over_p=50"];
        let refused = load(&bed).err().expect("refused").to_string();
        assert!(refused.contains("effects.impact"), "{refused}");
        let setup = load(&[bed[0], bed[1], "effects.impact=null"]).expect("on the bed");
        assert!(setup.ground.is_some());
        let missing = load(&["effects.impcat=null"])
            .err()
            .expect("refused")
            .to_string();
        assert!(
            missing.contains("effects.impcat=null") && missing.contains("nothing to remove"),
            "{missing}"
        );
        assert!(load(&["nosuch.key=null"]).is_err());
    }

    /// An input error carries its parts as fields, and its message is built from them.
    #[test]
    fn a_refused_value_names_its_file_line_key_value_and_range() {
        let text = "[structure]\nomega_n_over_p = 5.0\nalpha = 2.0\nzeta = 0.01\n\n\
                    [excitation]\nkind = \"sine-pulse\"\nomega_p_over_p = 4.0\namplitude = 2.0\n";
        let sc = load_text(Path::new("dir/s.toml"), text.to_string(), &[]).expect("parses");
        let err = crate::setup::build(&sc)
            .err()
            .expect("alpha = 2 is refused");
        let e = err.fields();
        assert_eq!(e.file.as_deref(), Some(Path::new("dir/s.toml")));
        assert_eq!((e.line, e.column), (Some(3), Some(1)));
        assert_eq!(e.key.as_deref(), Some("structure.alpha"));
        assert_eq!(e.value.as_deref(), Some("2"));
        assert_eq!(
            e.allowed.as_deref(),
            Some("a slenderness 0 < alpha < pi/2 rad")
        );
        assert_eq!(
            err.to_string(),
            "dir/s.toml:3:1: [structure] `alpha` = 2 is not allowed: a slenderness 0 < alpha < \
             pi/2 rad"
        );
        // The same value given as an override names the override instead of a line.
        let sc = load_text(
            Path::new("dir/s.toml"),
            text.replace("alpha = 2.0", "alpha = 0.2"),
            &["structure.alpha=3".to_string()],
        )
        .expect("parses");
        let err = crate::setup::build(&sc)
            .err()
            .expect("alpha = 3 is refused");
        let e = err.fields();
        assert_eq!(
            (e.set.as_deref(), e.line),
            (Some("structure.alpha=3"), None)
        );
        assert!(
            err.to_string()
                .starts_with("dir/s.toml: override structure.alpha=3: "),
            "{err}"
        );
        // A caller names the override its own way (the command: `--set`).
        assert!(
            err.describe("--set")
                .starts_with("dir/s.toml: --set structure.alpha=3: "),
            "{err}"
        );
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(512))]

        /// The scene parser and the model builder never panic on arbitrary text: they answer
        /// with a scene or an input error.
        #[test]
        fn arbitrary_text_never_panics(text in "\\PC{0,300}") {
            let path = Path::new("fuzz.toml");
            if let Ok(sc) = load_text(path, text, &[]) {
                let _ = crate::setup::build(&sc);
            }
        }

        /// Nor on a valid scene with one byte range replaced by arbitrary text.
        #[test]
        fn mutated_scenes_never_panic(start in 0usize..400, len in 0usize..20, insert in "\\PC{0,12}") {
            let base = include_str!("../../../scenes/fig5-flexible.toml");
            let mut text: String = base.chars().collect();
            let chars: Vec<char> = text.chars().collect();
            let a = start.min(chars.len());
            let b = (a + len).min(chars.len());
            text = chars[..a].iter().collect::<String>() + &insert + &chars[b..].iter().collect::<String>();
            let path = Path::new("fuzz.toml");
            if let Ok(sc) = load_text(path, text, &[]) {
                let _ = crate::setup::build(&sc);
            }
        }
    }
}
