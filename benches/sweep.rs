//! A sweep of 10^4 loss coefficients at COR error ≤ 1e-10 (`sweeps/eta.toml`), side by side in
//! one run, on two threads:
//!
//! - `per-point`: the path a sweep took before chunks: each point's case read anew from the
//!   base's TOML table, run alone (`single_point`), its row written through one CSV writer
//!   behind a mutex.
//! - `chunked`: the path `millimpact sweep` takes now (`run_grid`): the case edited in place,
//!   impacts stepped four at a time in lanes, rows encoded on the workers and written in grid
//!   order by one writer.
//! - `case-over-eta`: `sweep CASE --loss-coefficient ... --tolerance 1e-10`: the same grid, its
//!   rows `run`'s records.
//! - `floor`: the hand-written floor: the same impacts in lanes on two threads, their COR summed,
//!   no case, no row, no output.
//! - `floor-single-chain`: the same without lanes, one impact after another.
//!
//! Rows go to `std::io::sink()`.
//!
//! And the rows' encoding alone, the same 10^4 rows of that sweep on one thread:
//!
//! - `csv-writer`: through the csv crate's serde writer, its lines counted after (how rows were
//!   written before `CsvRecords`).
//! - `csv-records`: through `CsvRecords`, the same bytes.
//!
//! `cargo bench --bench sweep`; the wall time a user gets from the command line is measured by
//! `bash benches/sweep_wall.sh`.

use std::hint::black_box;
use std::path::PathBuf;
use std::sync::Mutex;
use std::sync::atomic::AtomicBool;
use std::time::Duration;

use criterion::{Criterion, SamplingMode, criterion_group, criterion_main};
use millimpact::analysis::run::IntegrationOptions;
use millimpact::analysis::source::Resolution;
use millimpact::analysis::sweep::SweepRow;
use millimpact::analysis::sweep::run_grid;
use millimpact::analysis::sweep::{EtaSweep, loss_coefficient_axis};
use millimpact::analysis::sweep::{GridOptions, method_rows, single_point};
use millimpact::analysis::sweep::{GridPoint, SweepFile};
use millimpact::analysis::sweep::{RowFormat, RowWriter};
use millimpact::model::law::PaperLaw;
use millimpact::output::CsvRecords;
use millimpact::output::Format;
use millimpact::solve::paper::{self, Settings};
use rayon::prelude::*;

const THREADS: usize = 2;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn options() -> GridOptions {
    GridOptions {
        jobs: THREADS,
        timeout: Duration::from_secs(60),
        periods: 3.0,
        batch: 1,
        timestep: None,
    }
}

/// Before: a point at a time, its row through a shared writer.
fn per_point(sweep: &SweepFile, points: &[GridPoint], pool: &rayon::ThreadPool) {
    let writer = RowWriter::new(
        std::io::sink(),
        RowFormat::Csv,
        &sweep.columns(),
        false,
        Duration::from_millis(50),
        0,
    )
    .expect("a sink takes the header");
    let writer = Mutex::new(writer);
    pool.install(|| {
        points.par_iter().with_min_len(64).for_each(|p| {
            let row = single_point(sweep, p, &options());
            let _ = writer.lock().expect("no panic").write(&row);
        })
    });
}

/// Now: the chunked path of `millimpact sweep`.
fn chunked(sweep: &SweepFile, indices: &[usize]) {
    let mut out = std::io::sink();
    let mut write = |rows: millimpact::analysis::sweep::EncodedRows| {
        std::io::Write::write_all(&mut out, &rows.into_bytes())
    };
    run_grid(
        sweep,
        indices,
        &options(),
        &AtomicBool::new(false),
        RowFormat::Csv,
        &mut write,
        &|_| {},
    )
    .expect("the sweep runs");
}

/// A case file over 10^4 values of η, streamed.
fn case_over_eta(sweep: &SweepFile, settings: &Settings) {
    let options = IntegrationOptions {
        method: settings.method,
        steps_per_period: Some(settings.steps_per_period),
        ..IntegrationOptions::default()
    };
    let case = &sweep.base_case;
    let axis = loss_coefficient_axis("0:0.99995:0.0001", &case.path.display().to_string())
        .expect("a range of 10^4 values");
    EtaSweep::new(
        case.clone(),
        sweep.base.clone(),
        axis,
        options,
        THREADS,
        String::new(),
    )
    .write(Format::Csv, &mut std::io::sink(), false)
    .expect("the sweep runs");
}

/// The floor: impacts alone, in lanes or one after another, on two threads.
fn floor(
    laws: &[(PaperLaw, f64)],
    settings: &Settings,
    lanes: bool,
    pool: &rayon::ThreadPool,
) -> f64 {
    pool.install(|| {
        laws.par_chunks(64)
            .map(|chunk| {
                if lanes {
                    paper::solve_many(chunk, settings)
                        .into_iter()
                        .map(|o| o.expect("solves").figures.cor)
                        .sum::<f64>()
                } else {
                    chunk
                        .iter()
                        .map(|(law, v0)| {
                            paper::solve(law, *v0, settings)
                                .expect("solves")
                                .figures
                                .cor
                        })
                        .sum::<f64>()
                }
            })
            .sum()
    })
}

/// The rows through the csv crate's writer, and their lines counted.
fn by_csv_writer(rows: &[SweepRow]) -> (usize, usize) {
    let mut writer = csv::WriterBuilder::new()
        .has_headers(false)
        .terminator(csv::Terminator::Any(b'\n'))
        .from_writer(Vec::with_capacity(640 * rows.len()));
    for row in rows {
        writer.serialize(row.record()).expect("rows serialise");
    }
    let bytes = writer.into_inner().expect("into memory");
    let lines = bytes.iter().filter(|&&b| b == b'\n').count();
    (bytes.len(), lines)
}

/// The rows through `CsvRecords`.
fn by_csv_records(rows: &[SweepRow]) -> (usize, usize) {
    let mut records = CsvRecords::with_capacity(640 * rows.len());
    for row in rows {
        row.write_csv(&mut records).expect("rows serialise");
    }
    (records.as_bytes().len(), records.lines())
}

fn rows_1e4(c: &mut Criterion) {
    let sweep = SweepFile::load(&root().join("sweeps/eta.toml")).expect("sweeps/eta.toml");
    let points: Vec<GridPoint> = sweep.points(None);
    let mut rows = Vec::with_capacity(points.len());
    method_rows(
        &sweep,
        &points,
        &options(),
        &AtomicBool::new(false),
        &mut |row| {
            rows.push(row.clone());
            Ok(())
        },
    )
    .expect("the sweep runs");
    assert_eq!(by_csv_writer(&rows), by_csv_records(&rows));
    let mut group = c.benchmark_group("rows-1e4-csv-1-thread");
    group.sample_size(20);
    group.bench_function("csv-writer", |b| b.iter(|| black_box(by_csv_writer(&rows))));
    group.bench_function("csv-records", |b| {
        b.iter(|| black_box(by_csv_records(&rows)))
    });
    group.finish();
}

fn sweep_1e4(c: &mut Criterion) {
    let sweep = SweepFile::load(&root().join("sweeps/eta.toml")).expect("sweeps/eta.toml");
    let choice = sweep.tolerance.expect("eta.toml asks for a tolerance");
    let steps_per_period =
        Resolution::steps_per_period(Some(choice.resolution)).expect("a fixed-step method");
    let indices = sweep.indices(None);
    let points: Vec<GridPoint> = indices.iter().map(|&i| sweep.point(i)).collect();
    let case = sweep.base_case.clone();
    let settings = Settings {
        method: choice.method,
        steps_per_period,
        ..Settings::default()
    };
    let laws: Vec<(PaperLaw, f64)> = points
        .iter()
        .map(|p| {
            let eta = p.values[0].as_float().expect("η");
            (case.with_loss_coefficient(eta).law(), case.impact_velocity)
        })
        .collect();
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(THREADS)
        .build()
        .expect("a pool");
    let mut group = c.benchmark_group("sweep-1e4-cor-1e-10-2-threads");
    group.sampling_mode(SamplingMode::Flat);
    group.sample_size(15);
    group.bench_function("per-point", |b| {
        b.iter(|| per_point(&sweep, &points, &pool))
    });
    group.bench_function("chunked", |b| b.iter(|| chunked(&sweep, &indices)));
    group.bench_function("case-over-eta", |b| {
        b.iter(|| case_over_eta(&sweep, &settings))
    });
    group.bench_function("floor", |b| {
        b.iter(|| black_box(floor(&laws, &settings, true, &pool)))
    });
    group.bench_function("floor-single-chain", |b| {
        b.iter(|| black_box(floor(&laws, &settings, false, &pool)))
    });
    group.finish();
}

criterion_group! {
    name = benches;
    config = Criterion::default()
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(3));
    targets = sweep_1e4, rows_1e4
}
criterion_main!(benches);
