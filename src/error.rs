//! Errors: every failure a user can cause or a solver can detect is a value, never a panic.

use thiserror::Error;

/// What went wrong, with enough context to act on it.
#[derive(Debug, Error)]
pub enum Error {
    /// A scene field breaks a rule (`b >= a`, negative modulus, unknown key, ...).
    #[error("invalid scene: `{field}` {rule}")]
    InvalidScene { field: String, rule: String },

    /// A scene file could not be read.
    #[error("cannot read scene file `{path}`: {message}")]
    SceneFile { path: String, message: String },

    /// A mesh file is unreadable or breaks a rule the solver relies on.
    #[error("mesh `{path}`: {message}")]
    InvalidMesh { path: String, message: String },

    /// The method cannot treat this kind of scene at all.
    #[error("method `{method}` cannot solve this scene: {reason}")]
    Unsupported { method: String, reason: String },

    /// The requested state lies outside the range where the method (or reference) is valid.
    #[error("method `{method}` is not valid here: {reason}")]
    OutOfRange { method: String, reason: String },

    /// An iteration or refinement did not reach the requested tolerance.
    #[error("method `{method}` did not converge: {reason}")]
    NoConvergence { method: String, reason: String },
}

/// Shorthand for results in this crate.
pub type Result<T> = std::result::Result<T, Error>;

impl Error {
    /// Helper for [`Error::InvalidScene`].
    pub fn invalid(field: &str, rule: impl Into<String>) -> Self {
        Error::InvalidScene {
            field: field.to_string(),
            rule: rule.into(),
        }
    }
}
