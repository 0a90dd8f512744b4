//! `millimpact compare` (being written).

use anyhow::Result;

use crate::cli::CompareArgs;

/// Run `millimpact compare`.
pub fn compare_command(_args: &CompareArgs) -> Result<String> {
    anyhow::bail!("compare: not available yet")
}
