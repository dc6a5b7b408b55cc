//! Why a scene could not be loaded or built: invalid input, with where it is and what is allowed
//! as fields (the message is what the user reads). Failures that are not the input's fault
//! belong to the crates that run and write (`rocking_study::StudyError`).

use std::fmt;
use std::path::PathBuf;

/// Invalid input: the message the user reads, and the parts of it a caller may want alone.
/// Each part is there when the place that refused the input knew it.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct InputError {
    /// The file (a scene, a record, a record folder).
    pub file: Option<PathBuf>,
    /// Line and column (1-based) of the key in the file.
    pub line: Option<usize>,
    /// Column (1-based; characters) of the key in the file.
    pub column: Option<usize>,
    /// The `--set KEY=VALUE` argument the value came from, when it came from the command line.
    pub set: Option<String>,
    /// The key, as a dotted path (`structure.alpha`).
    pub key: Option<String>,
    /// The value given, as written in the message.
    pub value: Option<String>,
    /// What is allowed.
    pub allowed: Option<String>,
    /// The whole message.
    pub message: String,
}

/// Why a scene could not be loaded or built: always invalid input, which the user can fix.
/// What goes wrong later (a run, a write) is the error of the crate that does it.
#[derive(Clone, Debug, PartialEq)]
pub struct SceneError(Box<InputError>);

impl SceneError {
    /// Invalid input known only by its message.
    pub fn input(message: impl Into<String>) -> Self {
        SceneError(Box::new(InputError {
            message: message.into(),
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
        self.0.message = format!("{what}: {}", self.0.message);
        self
    }

    /// Its parts: file, place, key, value, allowed range and the whole message.
    pub fn fields(&self) -> &InputError {
        &self.0
    }

    /// Its parts, to be reworded by a caller that knows more (a study naming its record).
    pub fn fields_mut(&mut self) -> &mut InputError {
        &mut self.0
    }

    /// The message.
    pub fn message(&self) -> &str {
        &self.0.message
    }
}

impl From<InputError> for SceneError {
    fn from(e: InputError) -> Self {
        SceneError(Box::new(e))
    }
}

impl fmt::Display for SceneError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.message())
    }
}

impl std::error::Error for SceneError {}
