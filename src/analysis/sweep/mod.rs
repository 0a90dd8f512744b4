//! Sweeps: grids over case keys, methods, codes and resolutions (sweep files), their rows on
//! disk, batches of code points, and a case file over a range of η (`--loss-coefficient`).

pub(crate) mod batch;
pub(crate) mod error;
pub(crate) mod eta;
pub use eta::{EtaSweep, loss_coefficient_axis};
pub(crate) mod failed;
pub(crate) mod grid;
pub use grid::{GridPoint, SweepFile};
pub(crate) mod point;
pub use point::{GridOptions, method_rows, single_point};
pub(crate) mod resume;
pub(crate) mod row;
pub use row::{AxisValue, PointFigures, PointSource, RowIdentity, RowStatus, SweepRow};
pub(crate) mod rows;
pub use rows::{EncodedRows, RowFormat, RowWriter, merge};

use std::collections::BTreeMap;
use std::ops::Range;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::mpsc;

use crate::analysis::source::Source;
pub use error::SweepError;

/// Points of our methods are computed and encoded in chunks of this many: a chunk is one
/// message to the writer, and rk4-event steps its impacts together in lanes.
pub(crate) const CHUNK: usize = 64;

/// Run `count` items in chunks of `chunk` on `jobs` threads, `work` turning each range of
/// items into a value, and hand the values to `deliver` on the calling thread in the order
/// of their ranges. Threads take the next chunk as they finish one, so at most a few chunks
/// wait for an earlier one; after `stop` is raised no chunk starts. `deliver` returning an
/// error raises `stop` and is returned; the chunks still coming are dropped.
pub(crate) fn ordered_chunks<T: Send>(
    count: usize,
    chunk: usize,
    jobs: usize,
    stop: &AtomicBool,
    work: &(dyn Fn(Range<usize>) -> T + Sync),
    deliver: &mut dyn FnMut(T) -> std::io::Result<()>,
) -> std::io::Result<()> {
    let chunk = chunk.max(1);
    let chunks = count.div_ceil(chunk);
    let jobs = jobs.max(1).min(chunks.max(1));
    let next = AtomicUsize::new(0);
    let (tx, rx) = mpsc::sync_channel::<(usize, T)>(2 * jobs);
    std::thread::scope(|scope| {
        for _ in 0..jobs {
            let tx = tx.clone();
            let next = &next;
            scope.spawn(move || {
                loop {
                    if stop.load(Ordering::Relaxed) {
                        break;
                    }
                    let k = next.fetch_add(1, Ordering::Relaxed);
                    if k >= chunks {
                        break;
                    }
                    let range = k * chunk..((k + 1) * chunk).min(count);
                    if tx.send((k, work(range))).is_err() {
                        break;
                    }
                }
            });
        }
        drop(tx);
        let mut waiting: BTreeMap<usize, T> = BTreeMap::new();
        let mut expected = 0;
        let mut failure = None;
        for (k, value) in rx {
            if failure.is_some() {
                continue;
            }
            waiting.insert(k, value);
            while let Some(value) = waiting.remove(&expected) {
                expected += 1;
                if let Err(e) = deliver(value) {
                    stop.store(true, Ordering::SeqCst);
                    failure = Some(e);
                    break;
                }
            }
        }
        // Chunks after one that never came (the sweep was stopped) are kept, in order.
        if failure.is_none() {
            for (_, value) in waiting {
                if let Err(e) = deliver(value) {
                    failure = Some(e);
                    break;
                }
            }
        }
        failure.map_or(Ok(()), Err)
    })
}

/// Run the points of `indices`: our methods on `jobs` threads, in chunks whose rows reach
/// `write` in grid order; then the codes in a pool of at most `jobs` live processes (in
/// batches where the code allows), each row as it finishes. Rows are encoded in `format` on
/// the threads that compute them; `write` runs on the calling thread alone. After `stop` is
/// raised no new point starts, and a point that failed after it is dropped (its failure may be
/// the interruption's), so that a resumed sweep runs it again. A failure of `write` raises
/// `stop` and is returned.
pub fn run_grid(
    sweep: &SweepFile,
    indices: &[usize],
    options: &GridOptions,
    stop: &AtomicBool,
    format: RowFormat,
    write: &mut dyn FnMut(EncodedRows) -> std::io::Result<()>,
    note: &(dyn Fn(String) + Sync),
) -> std::io::Result<()> {
    let is_method = |i: &usize| {
        matches!(
            sweep.sources[i % sweep.sources.len()].source,
            Source::Method(_)
        )
    };
    // A sweep of methods alone keeps one list of indices (8 MB for 10^6 points), not two.
    let (methods, codes): (std::borrow::Cow<[usize]>, Vec<usize>) = if indices.iter().all(is_method)
    {
        (std::borrow::Cow::Borrowed(indices), Vec::new())
    } else {
        let (m, c): (Vec<usize>, Vec<usize>) = indices.iter().copied().partition(is_method);
        (std::borrow::Cow::Owned(m), c)
    };
    let keep = |row: &SweepRow| row.status.is_ok() || !stop.load(Ordering::SeqCst);
    if !methods.is_empty() {
        let work = |range: Range<usize>| -> std::io::Result<EncodedRows> {
            let points: Vec<GridPoint> = methods[range].iter().map(|&i| sweep.point(i)).collect();
            let mut encoded = EncodedRows::new(format);
            method_rows(sweep, &points, options, stop, &mut |row| {
                if keep(row) {
                    encoded.push(row)?;
                }
                Ok(())
            })?;
            Ok(encoded)
        };
        ordered_chunks(
            methods.len(),
            CHUNK,
            options.jobs,
            stop,
            &work,
            &mut |encoded| write(encoded?),
        )?;
    }
    if !codes.is_empty() && !stop.load(Ordering::SeqCst) {
        let points: Vec<GridPoint> = codes.iter().map(|&i| sweep.point(i)).collect();
        let refs: Vec<&GridPoint> = points.iter().collect();
        let work = batch::plan(sweep, &refs, options);
        let next = AtomicUsize::new(0);
        let (tx, rx) = mpsc::channel::<std::io::Result<EncodedRows>>();
        return std::thread::scope(|scope| {
            for _ in 0..options.jobs.max(1).min(work.len()) {
                let tx = tx.clone();
                let (work, next) = (&work, &next);
                scope.spawn(move || {
                    let emit = |row: SweepRow| {
                        if keep(&row) {
                            let mut encoded = EncodedRows::new(format);
                            let sent = encoded.push(&row).map(|()| encoded);
                            let _ = tx.send(sent);
                        }
                    };
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
            drop(tx);
            let mut failure = None;
            for encoded in rx {
                if failure.is_none()
                    && let Err(e) = encoded.and_then(&mut *write)
                {
                    stop.store(true, Ordering::SeqCst);
                    failure = Some(e);
                }
            }
            failure.map_or(Ok(()), Err)
        });
    }
    Ok(())
}
