//! Why a sweep, a point of it, a resume or a merge failed.

use std::path::PathBuf;

use thiserror::Error;

use crate::analysis::run::RunError;
use crate::analysis::store::StoreError;
use crate::codes::ParseError;
use crate::error::{Blame, UserError};
use crate::model::case::CaseError;
use crate::output::OutputError;
use crate::output::csv_record::RecordError;

/// Why a sweep, a point of it, a resume or a merge failed. A point's failure becomes its
/// row's status; the others end the command.
#[derive(Debug, Error)]
pub enum SweepError {
    /// The case at a point, or the sweep file, is invalid: the user's.
    #[error(transparent)]
    Case(#[from] CaseError),
    /// An option, a row file given to resume or merge, or a value at a point is invalid: the
    /// user's.
    #[error(transparent)]
    User(#[from] UserError),
    /// A method's integration failed.
    #[error(transparent)]
    Run(#[from] RunError),
    /// A code's run failed, or its figures could not be read.
    #[error(transparent)]
    Store(#[from] StoreError),
    /// One impact of a code's batch could not be read.
    #[error(transparent)]
    BatchImpact(#[from] ParseError),
    /// A code's point was given where a method's is computed.
    #[error("point {point} is a code's, not a method's")]
    NotAMethodPoint {
        /// The point's index.
        point: usize,
    },
    /// A sweep over no value.
    #[error("a sweep has at least one value")]
    NoValues,
    /// A row file could not be read.
    #[error("reading {}", path.display())]
    Read {
        /// The file.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// The rows could not be written.
    #[error("writing the sweep's rows")]
    Write(#[from] std::io::Error),
    /// The rows could not be laid out in their format.
    #[error(transparent)]
    Output(#[from] OutputError),
    /// A row could not be encoded as CSV.
    #[error("encoding a row as CSV")]
    Record(#[from] RecordError),
    /// A row could not be encoded or read back as CSV.
    #[error("encoding a row as CSV")]
    Csv(#[from] csv::Error),
    /// A row could not be encoded as JSON.
    #[error("encoding a row as JSON")]
    Json(#[from] serde_json::Error),
}

impl Blame for SweepError {
    fn is_user_error(&self) -> bool {
        match self {
            SweepError::Case(_) | SweepError::User(_) => true,
            SweepError::Run(e) => e.is_user_error(),
            SweepError::Store(e) => e.is_user_error(),
            _ => false,
        }
    }
}
