//! `millimpact merge`: join the shard outputs of one sweep.

use super::Result;

use super::{CommandOutput, write_output};
use crate::cli::MergeArgs;
use millimpact::analysis::sweep::rows::merge as merge_rows;

pub(super) fn merge(args: &MergeArgs) -> Result<CommandOutput> {
    let shards: Vec<&std::path::Path> = args.shards.iter().map(|p| p.as_path()).collect();
    let merged = merge_rows(&shards)?;
    write_output(&args.out, merged.text.as_bytes(), "merged sweep")?;
    let mut output = CommandOutput::passed(String::new());
    if !merged.failed.is_empty() {
        // The shards' own runs failed loudly; the merge says where the failures went.
        output.warnings.push(
            merged
                .failed
                .summary(merged.points, &args.out.display().to_string()),
        );
    }
    Ok(output)
}
