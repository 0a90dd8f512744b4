//! Stored results of the DEM codes in `reference/`, with provenance.

use std::path::Path;

use anyhow::Result;

use crate::app::VerifyRow;
use crate::cli::ReferenceArgs;

/// Checks of the stored references for `verify`.
pub fn verify_rows(_reference: &Path, _cases: &Path) -> Result<Vec<VerifyRow>> {
    Ok(Vec::new())
}

/// Run `millimpact reference`.
pub fn reference_command(_args: &ReferenceArgs) -> Result<String> {
    anyhow::bail!("reference: not available yet")
}
