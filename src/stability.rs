//! `millimpact stability` (being written).

use anyhow::Result;

use crate::cli::StabilityArgs;

/// Run `millimpact stability`.
pub fn stability_command(_args: &StabilityArgs) -> Result<String> {
    anyhow::bail!("stability: not available yet")
}
