//! Errors as the user sees them: a message and an exit code.

use rbf_core::{FileError, FitError};

/// A failed command: what to print and the exit code.
#[derive(Debug)]
pub(crate) struct Failure {
    pub(crate) code: u8,
    pub(crate) message: String,
}

/// Exit code of a usage error.
pub(crate) const USAGE: u8 = 1;
/// Exit code of bad input.
pub(crate) const BAD_INPUT: u8 = 2;
/// Exit code of a numerical failure.
pub(crate) const NUMERICAL: u8 = 3;

impl Failure {
    pub(crate) fn new(code: u8, message: impl Into<String>) -> Self {
        Self {
            code,
            message: message.into(),
        }
    }

    /// A fit that failed, with the file it came from.
    pub(crate) fn fit(source: &str, e: &FitError) -> Self {
        let code = match e {
            FitError::Singular { .. }
            | FitError::IllConditioned { .. }
            | FitError::NotConverged { .. }
            | FitError::TooLarge { .. } => NUMERICAL,
            _ => BAD_INPUT,
        };
        Self::new(code, format!("{source}: {e}"))
    }

    /// A mesh that could not be read, written or used; the message names the file and line.
    pub(crate) fn mesh(e: &rbf_mesh::MeshError) -> Self {
        Self::new(BAD_INPUT, e.to_string())
    }

    /// A file that could not be read as JSON of the expected kind.
    pub(crate) fn file(source: &str, e: &FileError) -> Self {
        match e {
            FileError::Constraint(f) => Self::fit(source, f),
            other => Self::new(BAD_INPUT, format!("{source}: {other}")),
        }
    }
}
