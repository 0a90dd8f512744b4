//! One point of a sweep computed alone: by a method, or by a code in a process of its own
//! with the fault containment of `reference`.

use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Duration;

use super::error::SweepError;
use super::grid::{GridPoint, PointCases, SweepFile};
use super::row::{CodeFigures, PointFigures, RowStatus, SweepRow};
use crate::analysis::run::{IntegrationOptions, run_case, solve_failure};
use crate::analysis::source::{Resolution, Source};
use crate::analysis::store::{ReferenceOptions, run_reference};
use crate::error::Chain;
use crate::model::law::PaperLaw;
use crate::solve::paper::{Outcome, Settings, solve_many};

/// How to run a sweep.
#[derive(Clone, Debug)]
pub struct GridOptions {
    /// Worker threads for our methods, and most live code processes.
    pub jobs: usize,
    /// Time limit of one code process.
    pub timeout: Duration,
    /// Bilateral contact: undamped periods to follow.
    pub periods: f64,
    /// Most impacts per code process (1: no batching).
    pub batch: usize,
    /// Fixed-step methods: a step in seconds instead of steps per period (`sweep CASE
    /// --loss-coefficient --timestep`; a sweep file gives steps per period).
    pub timestep: Option<f64>,
}

/// The solver settings of a method point on `case`.
pub(crate) fn method_settings(
    point: &GridPoint,
    case: &crate::model::case::Case,
    options: &GridOptions,
) -> Result<Settings, SweepError> {
    let Source::Method(method) = point.source.source else {
        return Err(SweepError::NotAMethodPoint { point: point.index });
    };
    let integration = IntegrationOptions {
        method,
        steps_per_period: Resolution::steps_per_period(point.source.resolution),
        rtol: Resolution::rtol(point.source.resolution),
        periods: options.periods,
        timestep: options.timestep,
    };
    Ok(integration.settings(case, false)?)
}

/// A method point's law and speed with its solution.
pub(crate) type Solved = (PaperLaw, f64, Outcome);

/// Method points solved, in their order: each point's law and speed with its solution, or its
/// error. The case is edited in place from point to point where the axes allow, and the
/// impacts of one setting are solved together ([`solve_many`]: rk4-event in lanes; a wall time
/// is then the batch's divided among its impacts). After `stop` is raised the points left are
/// not run (and not in the answer).
pub(crate) fn solve_points(
    sweep: &SweepFile,
    points: &[GridPoint],
    options: &GridOptions,
    stop: &AtomicBool,
) -> Vec<Result<Solved, SweepError>> {
    let mut cases = PointCases::new(sweep);
    // Each point's solution or error (set here if it had no settings), and the points that
    // have settings: their place, law, speed and settings.
    let mut outcomes: Vec<Option<Result<Solved, SweepError>>> = Vec::new();
    let mut pending: Vec<(usize, PaperLaw, f64, Settings)> = Vec::new();
    for point in points {
        if stop.load(Ordering::Relaxed) {
            break;
        }
        let ready = (|| -> Result<_, SweepError> {
            let case = cases.case(point)?;
            let settings = method_settings(point, case, options)?;
            Ok((outcomes.len(), case.law(), case.impact_velocity, settings))
        })();
        match ready {
            Ok(ready) => {
                pending.push(ready);
                outcomes.push(None);
            }
            Err(e) => outcomes.push(Some(Err(e))),
        }
    }
    while let Some(&(_, _, _, settings)) = pending.first() {
        let (same, rest): (Vec<_>, Vec<_>) = pending.into_iter().partition(|p| p.3 == settings);
        pending = rest;
        let items: Vec<(PaperLaw, f64)> = same.iter().map(|&(_, law, v0, _)| (law, v0)).collect();
        for (&(i, law, v0, _), solved) in same.iter().zip(solve_many(&items, &settings)) {
            outcomes[i] = Some(
                solved
                    .map(|o| (law, v0, o))
                    .map_err(|e| solve_failure(&sweep.base_case.path, e).into()),
            );
        }
    }
    outcomes
        .into_iter()
        .map(|outcome| outcome.expect("every prepared point was solved"))
        .collect()
}

/// The rows of method points, in their order, each handed to `emit`: the same rows
/// [`single_point`] gives each, solved as `solve_points` solves them (a row's wall time may
/// be a batch's share). One row is filled point after point, its storage reused. After `stop`
/// is raised the points left are not run. An error of `emit` ends it and is returned.
pub fn method_rows(
    sweep: &SweepFile,
    points: &[GridPoint],
    options: &GridOptions,
    stop: &AtomicBool,
    emit: &mut dyn FnMut(&SweepRow) -> std::io::Result<()>,
) -> std::io::Result<()> {
    let mut row = SweepRow::default();
    for (point, outcome) in points
        .iter()
        .zip(solve_points(sweep, points, options, stop))
    {
        sweep.set_point(&mut row, point);
        match outcome {
            Ok((law, v0, outcome)) => {
                row.figures
                    .set_solution(&sweep.base_case.name, &law, v0, &outcome);
                row.status.set_ok();
            }
            Err(e) => {
                row.figures = PointFigures::default();
                row.status = RowStatus::failed(&Chain(&e).to_string());
            }
        }
        emit(&row)?;
    }
    Ok(())
}

/// Evaluate one point alone, whoever computes it.
pub fn single_point(sweep: &SweepFile, point: &GridPoint, options: &GridOptions) -> SweepRow {
    let outcome = (|| -> Result<PointFigures, SweepError> {
        let case = sweep.case(point)?;
        match point.source.source {
            Source::Method(_) => {
                let settings = method_settings(point, &case, options)?;
                Ok(PointFigures::of_method(&run_case(&case, &settings)?.0))
            }
            Source::Code(code) => {
                let reference = ReferenceOptions {
                    steps_per_contact: Resolution::steps_per_contact(point.source.resolution),
                    timeout: options.timeout,
                    ..ReferenceOptions::default()
                };
                let record = run_reference(code, &case, &reference)?;
                Ok(PointFigures::of_code(&CodeFigures::from_record(
                    &case, &record,
                )))
            }
        }
    })();
    sweep.outcome_row(point, outcome)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The rows of the chunked path (case edited in place, impacts solved together) are those
    /// of points run alone, errors included, but for the wall time.
    #[test]
    fn method_rows_are_the_rows_of_single_points() {
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("sweeps");
        let text = r#"
            base = "../cases/ball_plate.toml"
            [axes]
            impact_velocity = [2.0, 0, -1.0, 1e300, 3]
            restitution = [0.5, 1.5, "x", 0.9999, 1e-9, nan]
            method = ["rk4-event", "dopri5", "exact"]
        "#;
        let table: toml::Table = text.parse().unwrap();
        let sweep = SweepFile::from_table(&dir.join("t.toml"), &table).unwrap();
        assert!(sweep.in_place);
        let options = GridOptions {
            jobs: 1,
            timeout: Duration::from_secs(1),
            periods: 3.0,
            batch: 1,
            timestep: None,
        };
        let points: Vec<GridPoint> = (0..sweep.len()).map(|i| sweep.point(i)).collect();
        let stop = AtomicBool::new(false);
        let mut together = Vec::new();
        method_rows(&sweep, &points, &options, &stop, &mut |row| {
            together.push(row.clone());
            Ok(())
        })
        .unwrap();
        assert_eq!(together.len(), points.len());
        let mut failed = 0;
        for (point, mut row) in points.iter().zip(together) {
            let mut alone = single_point(&sweep, point, &options);
            row.figures.wall_time = None;
            alone.figures.wall_time = None;
            failed += usize::from(!row.status.is_ok());
            // By their text: a NaN axis value is not equal to itself.
            assert_eq!(
                format!("{row:?}"),
                format!("{alone:?}"),
                "point {}",
                point.index
            );
        }
        assert!(failed > 40 && failed < points.len(), "{failed}");
    }
}
