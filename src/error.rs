//! The two kinds of failure a command ends with, and their exit codes: bad input (exit 2) and
//! a check that ran and disagreed (exit 1). Any other failure (a code that crashed, a disk
//! that is full) is exit 1 too, with its whole chain of causes.

use thiserror::Error;

use crate::model::case::CaseError;

/// An error in what the user asked for: exit code 2.
#[derive(Debug, Error)]
pub enum UserError {
    /// A case file is invalid.
    #[error(transparent)]
    Case(#[from] CaseError),
    /// A user's deck cannot be checked as written.
    #[error(transparent)]
    Deck(#[from] crate::codes::deck::DeckError),
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

/// A check that ran and disagreed: exit code 1.
#[derive(Debug, Error)]
#[error("{0}")]
pub(crate) struct CheckFailed(pub String);

/// Whether a failure lies in what the user gave (bad input, exit 2) or elsewhere (exit 1).
///
/// Each library error type that can hold a user error answers for itself, a wrapper by asking
/// what it wraps: a user error wrapped transparently (whose `source()` skips it) is still known
/// as the user's. The binary's exit code asks each error in a failure's chain.
pub trait Blame {
    /// Whether the failure is the user's: an invalid case, deck or option.
    fn is_user_error(&self) -> bool;
}

impl Blame for UserError {
    fn is_user_error(&self) -> bool {
        true
    }
}

impl Blame for CaseError {
    fn is_user_error(&self) -> bool {
        true
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
