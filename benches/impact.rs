//! The cost of one impact by each method at its default settings on each canonical case; of one
//! impact at COR error ≤ 1e-10 (rk4-event at 400 steps per period, dopri5 at rtol 1e-10); and of
//! a sweep of 10^4 loss coefficients over [0, 1) at that accuracy, on one thread and on two.
//! rk4-event's COR error grows with η (8.3e-11 at 400 steps per period and η = 0.35, 2.0e-10 at
//! η → 1 on ball_plate), so its sweep runs at 480 steps per period (largest error 7.9e-11);
//! dopri5 at rtol 1e-10 stays below 2.4e-11 over the whole range.
//!
//! Kept short (2 s of measurement, 20 samples per benchmark) because the machine is shared:
//! one impact takes microseconds, so even 20 samples of many iterations pin it down well.
//!
//! Two more ways to run this binary, chosen by environment variables (criterion's command line
//! is left alone):
//!
//! - `MILLIMPACT_BENCH_REPORT=1`: print, for every point benchmarked here, its errors against
//!   the closed forms, its work and the median time per impact of a plain timed loop, then the
//!   sweep's largest COR error and wall time. `scripts/peer/compare.sh` prints this beside
//!   scipy's figure.
//! - `MILLIMPACT_BENCH_LOOP=CASE,METHOD,KNOB,COUNT` (KNOB: steps per period or rtol, `-` for the
//!   default): solve that impact COUNT times and print the figures, for an instruction count
//!   under `valgrind --tool=callgrind` (the difference of two counts over the difference of
//!   their COUNTs is the cost of one impact).

use std::hint::black_box;
use std::path::PathBuf;
use std::time::{Duration, Instant};

use criterion::{BenchmarkId, Criterion, SamplingMode, criterion_group};
use millimpact::model::case::Case;
use millimpact::model::exact;
use millimpact::model::law::PaperLaw;
use millimpact::solve::Method;
use millimpact::solve::paper::{self, Settings};

const CASES: [&str; 3] = ["ball_plate", "ball_ball", "rod_end"];

/// Loss coefficients in the sweep: 10^4 of them, evenly over [0, 1).
const SWEEP_POINTS: usize = 10_000;

fn load(name: &str) -> Case {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let path = root.join("cases").join(format!("{name}.toml"));
    Case::load(&path).unwrap_or_else(|e| panic!("{e}"))
}

/// The settings of the cheapest impacts at COR error ≤ 1e-10 (the book's "Accuracy and cost",
/// `docs/src/accuracy-and-cost.md`).
fn accurate_points(case: &Case) -> [(&'static str, Settings); 2] {
    let base = Settings {
        contact: case.contact,
        ..Settings::default()
    };
    [
        (
            "rk4-event-400",
            Settings {
                method: Method::Rk4Event,
                steps_per_period: 400,
                ..base
            },
        ),
        (
            "dopri5-rtol-1e-10",
            Settings {
                method: Method::Dopri5,
                rtol: 1e-10,
                ..base
            },
        ),
    ]
}

/// The solver's defaults for `method`: 1000 steps per period, rtol 1e-12.
fn default_point(case: &Case, method: Method) -> Settings {
    Settings {
        method,
        contact: case.contact,
        ..Settings::default()
    }
}

/// The sweep's settings: COR error ≤ 1e-10 at every η of [0, 1).
fn sweep_points(case: &Case) -> [(&'static str, Settings); 2] {
    let [(_, rk4_event), dopri5] = accurate_points(case);
    [
        (
            "rk4-event-480",
            Settings {
                steps_per_period: 480,
                ..rk4_event
            },
        ),
        dopri5,
    ]
}

fn sweep_etas() -> Vec<f64> {
    (0..SWEEP_POINTS)
        .map(|i| i as f64 / SWEEP_POINTS as f64)
        .collect()
}

/// The COR of `law` at each of `etas`.
fn sweep(law: &PaperLaw, v0: f64, etas: &[f64], settings: &Settings) -> Vec<f64> {
    etas.iter()
        .map(|&eta| {
            let law = PaperLaw {
                loss_coefficient: eta,
                ..*law
            };
            paper::solve(&law, v0, settings)
                .expect("sweep point solves")
                .figures
                .cor
        })
        .collect()
}

/// The same sweep on `threads` threads of the standard library, in interleaved shares.
fn sweep_parallel(
    law: &PaperLaw,
    v0: f64,
    etas: &[f64],
    settings: &Settings,
    threads: usize,
) -> Vec<f64> {
    let shares: Vec<Vec<f64>> = (0..threads)
        .map(|k| etas.iter().skip(k).step_by(threads).copied().collect())
        .collect();
    let results: Vec<Vec<f64>> = std::thread::scope(|scope| {
        let handles: Vec<_> = shares
            .iter()
            .map(|share| scope.spawn(move || sweep(law, v0, share, settings)))
            .collect();
        handles
            .into_iter()
            .map(|h| h.join().expect("sweep thread"))
            .collect()
    });
    let mut out = vec![0.0; etas.len()];
    for (k, part) in results.into_iter().enumerate() {
        for (j, cor) in part.into_iter().enumerate() {
            out[k + j * threads] = cor;
        }
    }
    out
}

fn impact(c: &mut Criterion) {
    for name in CASES {
        let case = load(name);
        let law = case.law();
        let mut group = c.benchmark_group(name);
        for method in [
            Method::Rk4,
            Method::Rk4Event,
            Method::Dopri5,
            Method::Verlet,
            Method::Exact,
        ] {
            let settings = default_point(&case, method);
            group.bench_function(method.name(), |b| {
                b.iter(|| {
                    paper::solve(black_box(&law), black_box(case.impact_velocity), &settings)
                        .expect("canonical case solves")
                })
            });
        }
        group.finish();
    }
}

fn accurate_impact(c: &mut Criterion) {
    let mut group = c.benchmark_group("cor-1e-10");
    for name in CASES {
        let case = load(name);
        let law = case.law();
        for (label, settings) in accurate_points(&case) {
            group.bench_with_input(BenchmarkId::new(label, name), &settings, |b, settings| {
                b.iter(|| {
                    paper::solve(black_box(&law), black_box(case.impact_velocity), settings)
                        .expect("canonical case solves")
                })
            });
        }
    }
    group.finish();
}

fn eta_sweep(c: &mut Criterion) {
    let case = load("ball_plate");
    let law = case.law();
    let etas = sweep_etas();
    let mut group = c.benchmark_group("sweep-1e4-eta");
    // One iteration is milliseconds: ten samples of one iteration each.
    group.sampling_mode(SamplingMode::Flat);
    group.sample_size(10);
    for (label, settings) in sweep_points(&case) {
        group.bench_function(BenchmarkId::new(label, "1-thread"), |b| {
            b.iter(|| sweep(black_box(&law), case.impact_velocity, &etas, &settings))
        });
        group.bench_function(BenchmarkId::new(label, "2-threads"), |b| {
            b.iter(|| sweep_parallel(black_box(&law), case.impact_velocity, &etas, &settings, 2))
        });
    }
    group.finish();
}

/// Median over `repeats` batches of the time per call of `f`, each batch at least `batch_time`.
fn median_time(mut f: impl FnMut(), batch_time: Duration, repeats: usize) -> f64 {
    let started = Instant::now();
    f();
    let single = started.elapsed().max(Duration::from_nanos(50));
    let batch =
        millimpact::model::count::ceil_count(batch_time.as_secs_f64() / single.as_secs_f64())
            .unwrap_or(1)
            .clamp(1, 10_000_000);
    let mut times: Vec<f64> = (0..repeats)
        .map(|_| {
            let t0 = Instant::now();
            for _ in 0..batch {
                f();
            }
            t0.elapsed().as_secs_f64() / batch as f64
        })
        .collect();
    times.sort_by(f64::total_cmp);
    times[times.len() / 2]
}

fn relative(got: f64, want: f64) -> f64 {
    (got - want) / want
}

fn report() {
    println!(
        "| case | method | knob | COR error | peak error | contact-time error | rhs evals | time per impact |"
    );
    println!("|---|---|---|---|---|---|---|---|");
    for name in CASES {
        let case = load(name);
        let law = case.law();
        let v0 = case.impact_velocity;
        let exact = exact::paper_impact(&law, v0);
        let mut points: Vec<Settings> = accurate_points(&case).map(|(_, s)| s).to_vec();
        for method in [
            Method::Rk4,
            Method::Rk4Event,
            Method::Dopri5,
            Method::Verlet,
        ] {
            points.push(default_point(&case, method));
        }
        for settings in points {
            let outcome = paper::solve(&law, v0, &settings).expect("canonical case solves");
            let f = outcome.figures;
            let time = median_time(
                || {
                    black_box(paper::solve(black_box(&law), black_box(v0), &settings).ok());
                },
                Duration::from_millis(20),
                15,
            );
            let knob = match settings.method {
                Method::Dopri5 => format!("rtol {:e}", settings.rtol),
                _ => format!("{} /period", settings.steps_per_period),
            };
            println!(
                "| {name} | {} | {knob} | {:.2e} | {:.2e} | {:.2e} | {} | {:.3} µs |",
                settings.method.name(),
                relative(f.cor, exact.cor),
                relative(f.peak_deformation, exact.peak_deformation),
                relative(f.contact_time, exact.contact_time),
                outcome.stats.rhs_evaluations,
                time * 1e6,
            );
        }
    }
    let case = load("ball_plate");
    let law = case.law();
    let etas = sweep_etas();
    println!();
    println!(
        "| sweep of {SWEEP_POINTS} η in [0, 1), ball_plate | largest COR error (abs.) | wall, 1 thread | wall, 2 threads |"
    );
    println!("|---|---|---|---|");
    for (label, settings) in sweep_points(&case) {
        let cors = sweep(&law, case.impact_velocity, &etas, &settings);
        let worst = etas
            .iter()
            .zip(&cors)
            .map(|(&eta, &cor)| relative(cor, exact::restitution(eta)).abs())
            .fold(0.0f64, f64::max);
        let one = median_time(
            || {
                black_box(sweep(&law, case.impact_velocity, &etas, &settings));
            },
            Duration::ZERO,
            5,
        );
        let two = median_time(
            || {
                black_box(sweep_parallel(
                    &law,
                    case.impact_velocity,
                    &etas,
                    &settings,
                    2,
                ));
            },
            Duration::ZERO,
            5,
        );
        println!(
            "| {label} | {worst:.2e} | {:.1} ms | {:.1} ms |",
            one * 1e3,
            two * 1e3
        );
    }
}

/// `CASE,METHOD,KNOB,COUNT`: solve one impact COUNT times.
fn run_loop(spec: &str) {
    let parts: Vec<&str> = spec.split(',').collect();
    let [name, method, knob, count] = parts[..] else {
        panic!("MILLIMPACT_BENCH_LOOP={spec}: expected CASE,METHOD,KNOB,COUNT");
    };
    let case = load(name);
    let method = Method::ALL
        .iter()
        .copied()
        .find(|m| m.name() == method)
        .unwrap_or_else(|| panic!("unknown method {method}"));
    let mut settings = default_point(&case, method);
    if knob != "-" {
        match method {
            Method::Dopri5 => settings.rtol = knob.parse().expect("rtol"),
            _ => settings.steps_per_period = knob.parse().expect("steps per period"),
        }
    }
    let count: u64 = count.parse().expect("count");
    let law = case.law();
    let mut last = None;
    for _ in 0..count {
        last = Some(
            paper::solve(black_box(&law), black_box(case.impact_velocity), &settings)
                .expect("solves"),
        );
    }
    if let Some(outcome) = last {
        println!("{:?} {:?}", outcome.figures, outcome.stats);
    }
}

criterion_group! {
    name = benches;
    config = Criterion::default()
        .sample_size(20)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2));
    targets = impact, accurate_impact, eta_sweep
}

fn main() {
    if let Ok(spec) = std::env::var("MILLIMPACT_BENCH_LOOP") {
        run_loop(&spec);
        return;
    }
    if std::env::var_os("MILLIMPACT_BENCH_REPORT").is_some() {
        report();
        return;
    }
    benches();
    Criterion::default().configure_from_args().final_summary();
}
