//! The two kinds of failure a command ends with, and their exit codes: bad input (exit 2) and
//! a check that ran and disagreed (exit 1). Any other failure (a code that crashed, a disk
//! that is full) is exit 1 too, with its whole chain of causes. Each error type says which it
//! is ([`Blame`]), in the module that defines it.

use thiserror::Error;

/// An invalid command-line value: exit code 2.
#[derive(Debug, Error)]
pub enum UserError {
    /// A command-line value is invalid.
    #[error("{option} = {value}: {allowed}")]
    Argument {
        /// The option.
        option: String,
        /// Its value.
        value: String,
        /// What is allowed.
        allowed: String,
    },
    /// A command-line value is invalid for the case it is applied to.
    #[error("{case}: {option} = {value}: {allowed}")]
    CaseArgument {
        /// The case file.
        case: String,
        /// The option.
        option: String,
        /// Its value.
        value: String,
        /// What is allowed.
        allowed: String,
    },
}

impl UserError {
    /// An invalid option value.
    pub(crate) fn argument(option: &str, value: impl ToString, allowed: impl Into<String>) -> Self {
        UserError::Argument {
            option: option.to_string(),
            value: value.to_string(),
            allowed: allowed.into(),
        }
    }
}

/// Rows that could not be written or read back as CSV: not the input's fault.
impl Blame for csv::Error {
    fn is_user_error(&self) -> bool {
        false
    }
}

/// A row or a report that could not be encoded as JSON: not the input's fault.
impl Blame for serde_json::Error {
    fn is_user_error(&self) -> bool {
        false
    }
}

/// CSV held in memory that could not be taken back: not the input's fault.
impl<W: std::fmt::Debug> Blame for csv::IntoInnerError<W> {
    fn is_user_error(&self) -> bool {
        false
    }
}

/// Text that is not UTF-8 where it was written as such: not the input's fault.
impl Blame for std::string::FromUtf8Error {
    fn is_user_error(&self) -> bool {
        false
    }
}

/// A check that ran and disagreed: exit code 1.
#[derive(Debug, Error)]
#[error("{0}")]
pub(crate) struct CheckFailed(pub String);

/// Whether a failure lies in what the user gave (bad input, exit 2) or elsewhere (exit 1).
///
/// Every error type a command can end with answers for itself, a wrapper by asking what it
/// wraps: a user error wrapped transparently (whose `source()` skips it) is still known as the
/// user's. The command line takes a failure only from a type that implements this trait, so a
/// new error type states its exit code before a command can return it.
pub trait Blame {
    /// Whether the failure is the user's: an invalid case, deck or option.
    fn is_user_error(&self) -> bool;

    /// The exit code the failure ends the command line with: 2 for the user's, else 1.
    fn exit_code(&self) -> u8 {
        if self.is_user_error() { 2 } else { 1 }
    }
}

impl Blame for UserError {
    fn is_user_error(&self) -> bool {
        true
    }
}

/// A file that cannot be read or written, a closed pipe, a full disk: not the user's input.
impl Blame for std::io::Error {
    fn is_user_error(&self) -> bool {
        false
    }
}

impl Blame for CheckFailed {
    fn is_user_error(&self) -> bool {
        false
    }
}

/// An error with its chain of causes on one line, `outer: cause: inner cause`, as a failure
/// is written into a row or a finding.
pub struct Chain<'a>(pub &'a (dyn std::error::Error + 'static));

impl std::fmt::Display for Chain<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}", self.0)?;
        let mut cause = self.0.source();
        while let Some(error) = cause {
            write!(f, ": {error}")?;
            cause = error.source();
        }
        Ok(())
    }
}
