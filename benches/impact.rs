//! The cost of one impact by each method at its default settings on each canonical case.
//!
//! Kept short (2 s of measurement, 20 samples per benchmark) because the machine is shared:
//! one impact takes microseconds, so even 20 samples of many iterations pin it down well.

use std::hint::black_box;
use std::path::PathBuf;
use std::time::Duration;

use criterion::{Criterion, criterion_group, criterion_main};
use millimpact::model::case::Case;
use millimpact::solve::Method;
use millimpact::solve::paper::{self, Settings};

fn impact(c: &mut Criterion) {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    for name in ["ball_plate", "ball_ball", "rod_end"] {
        let path = root.join("cases").join(format!("{name}.toml"));
        let case = Case::load(&path).unwrap_or_else(|e| panic!("{e}"));
        let law = case.law();
        let mut group = c.benchmark_group(name);
        for method in [
            Method::Rk4,
            Method::Rk4Event,
            Method::Dopri5,
            Method::Verlet,
            Method::Exact,
        ] {
            // The solver's defaults: 1000 steps per period, rtol 1e-12.
            let settings = Settings {
                method,
                contact: case.contact,
                ..Settings::default()
            };
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

criterion_group! {
    name = benches;
    config = Criterion::default()
        .sample_size(20)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2));
    targets = impact
}
criterion_main!(benches);
