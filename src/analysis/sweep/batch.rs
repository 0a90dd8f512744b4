//! The code points of a sweep as work for the process pool: single runs, or batches of
//! impacts run in one process where the code's driver can batch them (start-up paid once).
//! A batch that cannot run, or an impact of it that cannot be read, falls back to single
//! runs, and the reason is noted.

use std::collections::BTreeMap;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Instant;

use rayon::prelude::*;

use super::error::SweepError;
use super::grid::{GridPoint, SweepFile};
use super::point::{GridOptions, single_point};
use super::row::{CodeFigures, PointFigures, SweepRow};
use crate::analysis::source::{Resolution, Source};
use crate::analysis::store::{StoreError, code_metrics, own_law};
use crate::codes::batch::run_batch;
use crate::codes::{CodeName, CodeSetup, ParsedRun, RunOptions, prepare};
use crate::error::Chain;
use crate::model::case::Case;
use crate::model::exact;

/// Most bytes of trajectory files one batch may write (about 80 bytes per step and impact).
pub(crate) const MAX_BATCH_BYTES: f64 = 2e8;

/// A code point with its case and setup.
#[derive(Clone, Debug)]
pub(crate) struct Prepared<'a> {
    /// The point.
    pub point: &'a GridPoint,
    /// Its case.
    pub case: Case,
    /// Its setup in the code.
    pub setup: CodeSetup,
    /// Wall time of sizing it (and of the build's probe, where this point's sizing made it), s.
    pub sizing_time: f64,
}

/// One unit of work for the pool: one process.
#[derive(Clone, Debug)]
pub(crate) enum WorkItem<'a> {
    /// A point run alone.
    Single(&'a GridPoint),
    /// Points run together in one process of `code`.
    Batch {
        /// The code.
        code: CodeName,
        /// The points, their cases and setups.
        items: Vec<Prepared<'a>>,
    },
}

/// Split the code points into work items: points of one code and one time step go in
/// batches of at most `options.batch` impacts (fewer when their trajectories would be
/// large), of [`balanced_sizes`] across the workers (fewer batches than workers when the
/// impacts are too few to pay each process's start: [`BatchRunner::impacts_per_start`]).
///
/// [`BatchRunner::impacts_per_start`]: crate::codes::BatchRunner::impacts_per_start
pub(crate) fn plan<'a>(
    sweep: &SweepFile,
    points: &[&'a GridPoint],
    options: &GridOptions,
) -> Vec<WorkItem<'a>> {
    let mut work = Vec::new();
    let mut groups: BTreeMap<(CodeName, u64), Vec<Prepared<'a>>> = BTreeMap::new();
    // Sizing a point's run integrates the code's law (and, for some codes, inverts a fit):
    // done on the pool's threads, in point order.
    let prepare_point = |p: &&'a GridPoint| {
        let started = Instant::now();
        let Source::Code(code) = p.source.source else {
            return None;
        };
        let steps_per_contact = Resolution::steps_per_contact(p.source.resolution);
        let driver = code.driver();
        let runner = driver.batch()?;
        if options.batch <= 1 || runner.max_batch() <= 1 {
            return None;
        }
        let case = sweep.case(p).ok()?;
        let setup = prepare(driver, &case, steps_per_contact, None, false).ok()?;
        // A point the code cannot run alone runs alone, where its error is reported.
        runner.render_batch(std::slice::from_ref(&setup)).ok()?;
        Some((
            code,
            Prepared {
                point: p,
                case,
                setup,
                sizing_time: started.elapsed().as_secs_f64(),
            },
        ))
    };
    let prepared: Vec<_> = match rayon::ThreadPoolBuilder::new()
        .num_threads(options.jobs.max(1))
        .build()
    {
        Ok(pool) => pool.install(|| points.par_iter().map(prepare_point).collect()),
        Err(_) => points.iter().map(prepare_point).collect(),
    };
    for (&p, prepared) in points.iter().zip(prepared) {
        match prepared {
            Some((code, prepared)) => groups
                .entry((code, prepared.setup.timestep.to_bits()))
                .or_default()
                .push(prepared),
            None => work.push(WorkItem::Single(p)),
        }
    }
    for ((code, _), items) in groups {
        let steps = items
            .iter()
            .map(|p| p.setup.steps)
            .max()
            .unwrap_or(1)
            .max(1);
        let by_bytes =
            crate::model::count::ceil_count((MAX_BATCH_BYTES / (80.0 * steps as f64)).max(1.0))
                .and_then(|n| usize::try_from(n).ok())
                .unwrap_or(1);
        let runner = code.driver().batch();
        let cap = options
            .batch
            .min(by_bytes)
            .min(runner.map_or(1, |b| b.max_batch()))
            .max(1);
        let least = runner.map_or(1, |b| b.impacts_per_start());
        let mut items = items.into_iter();
        for size in balanced_sizes(items.len(), cap, options.jobs, least) {
            let chunk: Vec<_> = items.by_ref().take(size).collect();
            if chunk.len() == 1 {
                work.push(WorkItem::Single(chunk[0].point));
            } else {
                work.push(WorkItem::Batch { code, items: chunk });
            }
        }
    }
    work
}

/// The sizes of the batches `count` impacts of one code run in: no batch above `cap`, as many
/// batches as that needs rounded up to a multiple of the `jobs` workers (each worker gets the
/// same number), and sizes that differ by at most one, so that the workers finish together
/// (200 impacts at most 64 a batch on 2 workers: 50 + 50 + 50 + 50, not 64 + 64 + 64 + 8).
/// But when the impacts are too few to give every worker a batch of at least `least` (the
/// impacts whose steps cost what a process's start does), they run in fewer batches, each of
/// at least `least` where the cap allows (one if all are fewer): a process started for fewer
/// would spend more on its start than on its impacts, and on a loaded machine the CPU it
/// takes is what the others wait for.
pub(crate) fn balanced_sizes(count: usize, cap: usize, jobs: usize, least: usize) -> Vec<usize> {
    if count == 0 {
        return Vec::new();
    }
    let jobs = jobs.max(1);
    let needed = count.div_ceil(cap.max(1));
    let worth_a_start = (count / least.max(1)).max(needed).max(1);
    let batches = if worth_a_start < jobs {
        worth_a_start
    } else {
        needed.div_ceil(jobs).saturating_mul(jobs)
    }
    .clamp(1, count);
    let (size, larger) = (count / batches, count % batches);
    (0..batches)
        .map(|b| size + usize::from(b < larger))
        .collect()
}

/// The figures of one impact of a batch, read as `reference` reads a single run.
fn batch_figures(
    code: CodeName,
    case: &Case,
    setup: &CodeSetup,
    run: &ParsedRun,
    wall_time: f64,
    batch: usize,
) -> Result<CodeFigures, StoreError> {
    let driver = code.driver();
    let metrics = code_metrics(code, &run.trajectory)?;
    let (_, at_step, own_exact) = own_law(code, setup)?;
    let paper = case.law();
    Ok(CodeFigures {
        case: case.name.clone(),
        loss_coefficient: paper.loss_coefficient,
        reduced_mass: paper.mass,
        contact_stiffness: paper.stiffness,
        exponent: paper.exponent,
        measured: CodeFigures::measured(&metrics),
        reference: CodeFigures::reference(
            driver
                .expected_restitution(setup)
                .unwrap_or(setup.target_restitution),
            &exact::paper_impact(&paper, case.impact_velocity),
        ),
        steps: setup.steps,
        timestep: setup.timestep,
        wall_time,
        loop_time: run.loop_time,
        // Set by the caller, once the whole batch is read.
        whole_wall_time: f64::NAN,
        own_law_cor: own_exact.cor,
        own_law_stepped_cor: at_step.cor,
        code_version: run.version.clone().unwrap_or_else(|| "unknown".to_string()),
        batch,
    })
}

/// Run one work item and hand each row to `emit`; reasons for falling back to single runs go
/// to `note`. Once `stop` is raised nothing falls back: what did not finish runs on resume.
pub(crate) fn run_item(
    sweep: &SweepFile,
    item: &WorkItem<'_>,
    options: &GridOptions,
    stop: &AtomicBool,
    emit: &(dyn Fn(SweepRow) + Sync),
    note: &(dyn Fn(String) + Sync),
) {
    match item {
        WorkItem::Single(p) => emit(single_point(sweep, p, options)),
        WorkItem::Batch { code, items } => {
            let started = Instant::now();
            let setups: Vec<CodeSetup> = items.iter().map(|p| p.setup.clone()).collect();
            let run_options = RunOptions {
                timeout: options.timeout,
                ..RunOptions::default()
            };
            match run_batch(code.driver(), &setups, &run_options) {
                // An interrupted batch's impacts run again on resume, not now.
                Err(_) if stop.load(Ordering::SeqCst) => {}
                Err(e) => {
                    note(format!(
                        "{code}: a batch of {} ran as single runs: {e}",
                        items.len()
                    ));
                    for p in items {
                        emit(single_point(sweep, p.point, options));
                    }
                }
                Ok(batch) => {
                    let n = items.len();
                    let figures: Vec<Result<CodeFigures, SweepError>> = items
                        .iter()
                        .zip(batch.runs)
                        .map(|(p, run)| {
                            run.map_err(SweepError::from).and_then(|run| {
                                batch_figures(
                                    *code,
                                    &p.case,
                                    &p.setup,
                                    &run,
                                    batch.wall_time / n as f64,
                                    n,
                                )
                                .map_err(SweepError::from)
                            })
                        })
                        .collect();
                    // The batch's whole time (its process, reading and checking every
                    // impact), shared, plus each point's own sizing.
                    let share = started.elapsed().as_secs_f64() / n as f64;
                    for (p, figures) in items.iter().zip(figures) {
                        match figures {
                            Ok(mut f) => {
                                f.whole_wall_time = p.sizing_time + share;
                                emit(sweep.outcome_row(p.point, Ok(PointFigures::of_code(&f))));
                            }
                            Err(_) if stop.load(Ordering::SeqCst) => {}
                            Err(e) => {
                                note(format!(
                                    "{code}: point {} of a batch ran alone: {}{}",
                                    p.point.index,
                                    Chain(&e),
                                    batch
                                        .kept
                                        .as_ref()
                                        .map(|k| format!(" (batch kept in {})", k.display()))
                                        .unwrap_or_default()
                                ));
                                emit(single_point(sweep, p.point, options));
                            }
                        }
                    }
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::balanced_sizes;
    use proptest::prelude::*;

    #[test]
    fn batches_are_even_across_the_workers() {
        assert_eq!(balanced_sizes(200, 64, 2, 1), [50, 50, 50, 50]);
        assert_eq!(balanced_sizes(200, 100, 2, 1), [100, 100]);
        assert_eq!(balanced_sizes(200, 31, 2, 1), [25; 8]);
        assert_eq!(balanced_sizes(201, 64, 2, 1), [51, 50, 50, 50]);
        assert_eq!(balanced_sizes(3, 64, 2, 1), [2, 1]);
        assert_eq!(balanced_sizes(1, 64, 4, 1), [1]);
        assert_eq!(balanced_sizes(5, 64, 8, 1), [1; 5]);
        assert_eq!(balanced_sizes(0, 64, 2, 1), Vec::<usize>::new());
        assert_eq!(balanced_sizes(10, 0, 0, 0), [1; 10]);
    }

    #[test]
    fn impacts_too_few_to_pay_each_worker_s_start_run_in_fewer_batches() {
        // YADE's start costs some 350 impacts: 200 run in one process, not two of 100.
        assert_eq!(balanced_sizes(200, 256, 2, 350), [200]);
        assert_eq!(balanced_sizes(700, 256, 4, 350), [234, 233, 233]);
        assert_eq!(balanced_sizes(1000, 512, 4, 300), [334, 333, 333]);
        // Enough for every worker: even across them, as without.
        assert_eq!(balanced_sizes(700, 256, 2, 350), [175; 4]);
        assert_eq!(balanced_sizes(1000, 256, 2, 350), [250; 4]);
        // The cap still holds.
        assert_eq!(balanced_sizes(600, 256, 4, 350), [200; 3]);
        assert_eq!(balanced_sizes(300, 64, 2, 350), [50; 6]);
    }

    proptest! {
        #[test]
        fn every_impact_runs_once_in_batches_within_the_cap_and_one_apart(
            count in 0usize..5000,
            cap in 1usize..300,
            jobs in 1usize..17,
            least in 1usize..500,
        ) {
            let sizes = balanced_sizes(count, cap, jobs, least);
            prop_assert_eq!(sizes.iter().sum::<usize>(), count);
            prop_assert!(sizes.iter().all(|&s| (1..=cap).contains(&s)));
            let (lo, hi) = (sizes.iter().min(), sizes.iter().max());
            if let (Some(lo), Some(hi)) = (lo, hi) {
                prop_assert!(hi - lo <= 1, "{:?}", sizes);
            }
            // Every worker has the same number of batches unless there are too few impacts,
            // or too few to pay each worker's start; then each batch pays its own, unless the
            // cap asks for more batches or all are fewer than one start's worth.
            let needed = count.div_ceil(cap);
            prop_assert!(
                sizes.len().is_multiple_of(jobs)
                    || sizes.len() == count
                    || (sizes.len() < jobs
                        && (sizes.len() == needed.max(1)
                            || sizes.iter().all(|&s| s >= least))),
                "{:?}", sizes
            );
        }
    }
}
