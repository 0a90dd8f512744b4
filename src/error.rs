//! The two kinds of failure a command ends with, and their exit codes: bad input (exit 2) and
//! a check that ran and disagreed (exit 1). Any other failure (a code that crashed, a disk
//! that is full) is exit 1 too, with its whole chain of causes.

use thiserror::Error;

use crate::model::case::CaseError;
use crate::solve::SolveError;

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
    /// The integration cannot be done as asked (a step beyond the stability limit).
    #[error("{case}: --timestep: {source}")]
    Unsolvable {
        /// The case file.
        case: String,
        /// Why.
        source: SolveError,
    },
}

impl UserError {
    /// An invalid option value.
    pub fn argument(option: &str, value: impl ToString, allowed: impl Into<String>) -> Self {
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
pub struct CheckFailed(pub String);

/// The exit code of a failed command: 2 for bad input, 1 for everything else.
pub fn exit_code(error: &anyhow::Error) -> u8 {
    let bad_input = error
        .chain()
        .any(|cause| cause.is::<UserError>() || cause.is::<CaseError>());
    if bad_input && !error.is::<CheckFailed>() {
        2
    } else {
        1
    }
}
