//! The code points of a sweep as work for the process pool: single runs, or batches of
//! impacts run in one process where the code's driver can batch them.

use std::sync::atomic::AtomicBool;

use super::grid::{GridOptions, Point, Source, SweepFile, code_point};

/// One unit of work for the pool: one process.
#[derive(Clone, Debug)]
pub enum WorkItem<'a> {
    /// A point run alone.
    Single(&'a Point),
}

/// Split the code points into work items.
pub fn plan<'a>(
    _sweep: &SweepFile,
    points: &[&'a Point],
    _options: &GridOptions,
) -> Vec<WorkItem<'a>> {
    points
        .iter()
        .filter(|p| matches!(p.source, Source::Code { .. }))
        .map(|p| WorkItem::Single(p))
        .collect()
}

/// Run one work item and hand each row to `emit`.
pub fn run_item(
    sweep: &SweepFile,
    item: &WorkItem<'_>,
    options: &GridOptions,
    _stop: &AtomicBool,
    emit: &(dyn Fn(Vec<String>) + Sync),
) {
    match item {
        WorkItem::Single(p) => emit(code_point(sweep, p, options)),
    }
}
