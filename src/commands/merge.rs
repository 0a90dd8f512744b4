//! `millimpact merge`: join the shard outputs of one sweep.

use anyhow::Result;

use super::{CommandOutput, write_output};
use crate::cli::MergeArgs;
use millimpact::analysis::sweep::rows::merge as merge_rows;

pub(super) fn merge(args: &MergeArgs) -> Result<CommandOutput> {
    let shards: Vec<&std::path::Path> = args.shards.iter().map(|p| p.as_path()).collect();
    let text = merge_rows(&shards)?;
    write_output(&args.out, text.as_bytes(), "merged sweep")?;
    Ok(CommandOutput::passed(String::new()))
}
