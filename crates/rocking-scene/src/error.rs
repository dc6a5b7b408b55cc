//! Why a scene could not be loaded, built, run or reported: invalid input, with where it is and
//! what is allowed as fields (the message is what the user reads), or a failure that is not the
//! input's fault.

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

/// Why a scene could not be loaded, built, run or reported.
#[derive(Debug)]
pub enum SceneError {
    /// Invalid input (a scene, a record, an argument): the user can fix it (exit code 2).
    Input(Box<InputError>),
    /// Not the input's fault: a run that failed, an output that could not be written (exit
    /// code 1).
    Failure(String),
}

impl SceneError {
    /// Invalid input known only by its message.
    pub fn input(message: impl Into<String>) -> Self {
        SceneError::Input(Box::new(InputError {
            message: message.into(),
            ..InputError::default()
        }))
    }

    /// A failure that is not the input's fault.
    pub fn failure(message: impl Into<String>) -> Self {
        SceneError::Failure(message.into())
    }

    /// The value given and what is allowed, for an input error (a failure is returned as is).
    pub fn with_value(mut self, value: impl fmt::Display, allowed: impl Into<String>) -> Self {
        if let SceneError::Input(e) = &mut self {
            e.value = Some(value.to_string());
            e.allowed = Some(allowed.into());
        }
        self
    }

    /// The same error with `what` it happened in before its message ("WHAT: MESSAGE"), its
    /// kind and fields kept.
    pub fn context(mut self, what: impl fmt::Display) -> Self {
        match &mut self {
            SceneError::Input(e) => e.message = format!("{what}: {}", e.message),
            SceneError::Failure(m) => *m = format!("{what}: {m}"),
        }
        self
    }

    /// The input error, if it is one.
    pub fn as_input(&self) -> Option<&InputError> {
        match self {
            SceneError::Input(e) => Some(e),
            SceneError::Failure(_) => None,
        }
    }

    /// The message.
    pub fn message(&self) -> &str {
        match self {
            SceneError::Input(e) => &e.message,
            SceneError::Failure(m) => m,
        }
    }

    /// The process exit code of a command that stops on this error: 2 for invalid input, 1 else.
    pub fn exit_code(&self) -> u8 {
        match self {
            SceneError::Input(_) => 2,
            SceneError::Failure(_) => 1,
        }
    }
}

impl fmt::Display for SceneError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.message())
    }
}

impl std::error::Error for SceneError {}
