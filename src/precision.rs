//! `millimpact precision` (being written).

use anyhow::Result;

use crate::cli::PrecisionArgs;

/// Run `millimpact precision`.
pub fn precision_command(_args: &PrecisionArgs) -> Result<String> {
    anyhow::bail!("precision: not available yet")
}
