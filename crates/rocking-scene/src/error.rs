//! Why a scene could not be loaded or built: invalid input, with where it is and what is allowed
//! as fields (the message is what the user reads). Failures that are not the input's fault
//! belong to the crates that run and write (`rocking_study::StudyError`).

use std::fmt;
use std::path::PathBuf;

/// Invalid input: the parts of the message the user reads, each there when the place that
/// refused the input knew it. The message is "CONTEXT: PLACE: DETAIL"; the place names an
/// override in the caller's words ([`SceneError::describe`]), so no flag is spelled here.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct InputError {
    /// The file (a scene, a record, a record folder).
    pub file: Option<PathBuf>,
    /// Line and column (1-based) of the key in the file.
    pub line: Option<usize>,
    /// Column (1-based; characters) of the key in the file.
    pub column: Option<usize>,
    /// The override `KEY=VALUE` the value came from, when it was given on top of the file.
    pub set: Option<String>,
    /// The key, as a dotted path (`structure.alpha`).
    pub key: Option<String>,
    /// The value given, as written in the message.
    pub value: Option<String>,
    /// What is allowed.
    pub allowed: Option<String>,
    /// What is wrong: the message after its place.
    pub detail: String,
    /// What it happened in, outermost first (a record, an intensity level).
    pub context: Vec<String>,
}

impl InputError {
    /// The message, with `set` as the caller's name for an override (`--set` on the command
    /// line): "CONTEXT: FILE:LINE:COL: DETAIL", "FILE: SET KEY=VALUE: DETAIL", ...
    pub fn describe(&self, set: &str) -> String {
        let mut parts: Vec<String> = self.context.clone();
        let file = self.file.as_ref().map(|f| f.display().to_string());
        match (file, &self.set, self.line, self.column) {
            (Some(f), Some(arg), ..) => parts.push(format!("{f}: {set} {arg}")),
            (Some(f), None, Some(l), Some(c)) => parts.push(format!("{f}:{l}:{c}")),
            (Some(f), None, ..) => parts.push(f),
            (None, Some(arg), ..) => parts.push(format!("{set} {arg}")),
            (None, None, ..) => {}
        }
        parts.push(self.detail.clone());
        parts.join(": ")
    }
}

/// How this crate's own `Display` names an override.
const OVERRIDE: &str = "override";

/// Why a scene could not be loaded or built: always invalid input, which the user can fix.
/// What goes wrong later (a run, a write) is the error of the crate that does it.
#[derive(Clone, Debug, PartialEq)]
pub struct SceneError(Box<InputError>);

impl SceneError {
    /// Invalid input known only by its message.
    pub fn input(message: impl Into<String>) -> Self {
        SceneError(Box::new(InputError {
            detail: message.into(),
            ..InputError::default()
        }))
    }

    /// The value given and what is allowed.
    pub fn with_value(mut self, value: impl fmt::Display, allowed: impl Into<String>) -> Self {
        self.0.value = Some(value.to_string());
        self.0.allowed = Some(allowed.into());
        self
    }

    /// The same error with `what` it happened in before its message ("WHAT: MESSAGE"), its
    /// fields kept.
    pub fn context(mut self, what: impl fmt::Display) -> Self {
        self.0.context.insert(0, what.to_string());
        self
    }

    /// Its parts: file, place, key, value, allowed range, context and what is wrong.
    pub fn fields(&self) -> &InputError {
        &self.0
    }

    /// Its parts, to be reworded by a caller that knows more (a study naming its record).
    pub fn fields_mut(&mut self) -> &mut InputError {
        &mut self.0
    }

    /// The message, with `set` as the caller's name for an override (see
    /// [`InputError::describe`]).
    pub fn describe(&self, set: &str) -> String {
        self.0.describe(set)
    }
}

impl From<InputError> for SceneError {
    fn from(e: InputError) -> Self {
        SceneError(Box::new(e))
    }
}

impl fmt::Display for SceneError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.describe(OVERRIDE))
    }
}

impl std::error::Error for SceneError {}
