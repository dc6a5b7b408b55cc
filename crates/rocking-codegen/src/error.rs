use std::fmt;
use std::path::PathBuf;

/// Result type of this crate.
pub type Result<T, E = Error> = std::result::Result<T, E>;

/// Everything that can go wrong while loading or rendering IR.
///
/// Every variant names the file it concerns.
#[derive(Debug)]
pub enum Error {
    /// A file or directory could not be read.
    Io {
        /// The path involved.
        path: PathBuf,
        /// The underlying error.
        source: std::io::Error,
    },
    /// An IR file is not valid JSON or does not match the schema.
    Json {
        /// The IR file.
        file: String,
        /// The underlying error.
        source: serde_json::Error,
    },
    /// An IR file is well-formed but cannot be rendered (unknown op, bad index, ...).
    Invalid {
        /// The IR file.
        file: String,
        /// What is wrong, with the function and instruction where applicable.
        message: String,
    },
    /// A template failed to render (a bug of this crate).
    Template {
        /// The IR file being rendered.
        file: String,
        /// The underlying error, with its chain of causes.
        message: String,
    },
}

impl Error {
    pub(crate) fn invalid(file: &str, message: impl Into<String>) -> Self {
        Error::Invalid {
            file: file.to_string(),
            message: message.into(),
        }
    }

    pub(crate) fn template(file: &str, err: &tera::Error) -> Self {
        let mut message = err.to_string();
        let mut cause = std::error::Error::source(err);
        while let Some(c) = cause {
            message.push_str(": ");
            message.push_str(&c.to_string());
            cause = c.source();
        }
        Error::Template {
            file: file.to_string(),
            message,
        }
    }
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Error::Io { path, source } => write!(f, "{}: {source}", path.display()),
            Error::Json { file, source } => write!(f, "{file}: invalid IR: {source}"),
            Error::Invalid { file, message } => write!(f, "{file}: {message}"),
            Error::Template { file, message } => {
                write!(f, "{file}: template error: {message}")
            }
        }
    }
}

impl std::error::Error for Error {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            Error::Io { source, .. } => Some(source),
            Error::Json { source, .. } => Some(source),
            Error::Invalid { .. } | Error::Template { .. } => None,
        }
    }
}
