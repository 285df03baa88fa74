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

    /// A file other than a scene could not be read, parsed or written.
    #[error("cannot {action} `{path}`: {message}")]
    File {
        action: String,
        path: String,
        message: String,
    },

    /// A computed state is not physically possible (non-finite, `eps` outside `[0, 1)`, force and
    /// depth of opposite signs): a defect or an input beyond the method's range, never printed.
    #[error("method `{method}` produced an impossible state ({state}): {reason}")]
    Implausible {
        method: String,
        state: String,
        reason: String,
    },

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

    /// A plan of jobs, a job id or a job's result is malformed, missing or failed.
    #[error("plan: {0}")]
    Plan(String),
}

/// A number for a message: plain up to 10 significant digits where that is short, else
/// scientific with 7 (never 300 digits).
pub fn show(x: f64) -> String {
    if x == 0.0 || !x.is_finite() {
        return format!("{x}");
    }
    let magnitude = x.abs();
    if (1e-4..1e9).contains(&magnitude) {
        let text = format!("{x:.10}");
        let text = text.trim_end_matches('0').trim_end_matches('.');
        text.to_string()
    } else {
        format!("{x:.6e}")
    }
}

/// Shorthand for results in this crate.
pub type Result<T> = std::result::Result<T, Error>;

impl Error {
    /// Helper for [`Error::File`]: `action` is what was attempted (`read`, `parse`, `write`).
    pub fn file(action: &str, path: &std::path::Path, message: impl std::fmt::Display) -> Self {
        Error::File {
            action: action.to_string(),
            path: path.display().to_string(),
            message: message.to_string(),
        }
    }

    /// Helper for [`Error::InvalidScene`].
    pub fn invalid(field: &str, rule: impl Into<String>) -> Self {
        Error::InvalidScene {
            field: field.to_string(),
            rule: rule.into(),
        }
    }
}
