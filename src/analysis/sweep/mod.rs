//! Sweeps: grids over case keys, methods, codes and resolutions (sweep files), their rows on
//! disk, batches of code points, and the legacy one-axis form.

pub mod batch;
pub mod failed;
pub mod grid;
pub mod legacy;
pub mod point;
pub mod resume;
pub mod row;
pub mod rows;

use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

use rayon::prelude::*;

use crate::analysis::source::Source;
use grid::{Point, SweepFile};
use point::{GridOptions, single_point};
use row::SweepRow;

/// Run `points`: methods on `jobs` threads, then codes in a pool of at most `jobs` live
/// processes (in batches where the code allows). Each finished row goes to `sink` at once;
/// after `stop` is raised no new point starts, and a point that failed after it is dropped
/// (its failure may be the interruption's), so that a resumed sweep runs it again.
pub fn run_grid(
    sweep: &SweepFile,
    points: &[Point],
    options: &GridOptions,
    stop: &AtomicBool,
    sink: &(dyn Fn(SweepRow) + Sync),
    note: &(dyn Fn(String) + Sync),
) -> anyhow::Result<()> {
    let (methods, codes): (Vec<&Point>, Vec<&Point>) = points
        .iter()
        .partition(|p| matches!(p.source.source, Source::Method(_)));
    let emit = |row: SweepRow| {
        if row.status.is_ok() || !stop.load(Ordering::SeqCst) {
            sink(row);
        }
    };
    if !methods.is_empty() {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(options.jobs.max(1))
            .build()?;
        pool.install(|| {
            methods.par_iter().with_min_len(64).for_each(|p| {
                if !stop.load(Ordering::Relaxed) {
                    emit(single_point(sweep, p, options));
                }
            })
        });
    }
    if !codes.is_empty() {
        let work = batch::plan(sweep, &codes, options);
        let next = AtomicUsize::new(0);
        std::thread::scope(|scope| {
            for _ in 0..options.jobs.max(1).min(work.len()) {
                scope.spawn(|| {
                    loop {
                        if stop.load(Ordering::SeqCst) {
                            break;
                        }
                        let i = next.fetch_add(1, Ordering::SeqCst);
                        let Some(item) = work.get(i) else { break };
                        batch::run_item(sweep, item, options, stop, &emit, note);
                    }
                });
            }
        });
    }
    Ok(())
}
