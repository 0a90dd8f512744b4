//! Trajectories of one impact (time, overlap, approach velocity, normal force) and the figures
//! read from them, the same way for a DEM code's output and for a law stepped as a code steps.

use serde::{Deserialize, Serialize};
use thiserror::Error;

use crate::model::figures::Measured;

/// Why figures cannot be read from a trajectory.
#[derive(Clone, Debug, Error, PartialEq, Eq)]
pub enum TrajectoryError {
    /// Fewer rows than an impact needs.
    #[error("trajectory has {rows} rows, at least 3 needed")]
    TooShort {
        /// Rows found.
        rows: usize,
    },
    /// The columns have different lengths.
    #[error("trajectory columns differ in length")]
    RaggedColumns,
    /// A value is NaN or infinite.
    #[error("trajectory holds a non-finite value")]
    NonFinite,
    /// Time does not increase from row to row (a file cut or mixed up).
    #[error("trajectory time does not increase at row {row}")]
    TimeNotIncreasing {
        /// The row, from 0.
        row: usize,
    },
    /// The overlap never became positive.
    #[error("the bodies never touched")]
    NeverTouched,
    /// The overlap had not returned to zero by the last row.
    #[error("the contact had not ended when the run stopped")]
    ContactNotEnded,
}

/// A trajectory read back from a code: one row per written step.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct CodeTrajectory {
    /// Time, s.
    pub time: Vec<f64>,
    /// Overlap (approach of the centres), m, positive in contact.
    pub overlap: Vec<f64>,
    /// Relative normal velocity, m/s, positive while approaching.
    pub approach_velocity: Vec<f64>,
    /// Normal contact force, N, positive when repulsive (empty if the code does not write it).
    pub normal_force: Vec<f64>,
}

impl CodeTrajectory {
    /// Append one row: time (s), overlap (m), approach rate (m/s), force (N).
    pub(crate) fn push_row(&mut self, time: f64, overlap: f64, approach_velocity: f64, force: f64) {
        self.time.push(time);
        self.overlap.push(overlap);
        self.approach_velocity.push(approach_velocity);
        self.normal_force.push(force);
    }
}

/// Check that a trajectory is complete enough to read figures from: at least three rows,
/// columns of one length, every value finite.
pub(crate) fn check_trajectory(t: &CodeTrajectory) -> Result<(), TrajectoryError> {
    let n = t.time.len();
    if n < 3 {
        return Err(TrajectoryError::TooShort { rows: n });
    }
    if t.overlap.len() != n || t.approach_velocity.len() != n {
        return Err(TrajectoryError::RaggedColumns);
    }
    let all = t.time.iter().chain(&t.overlap).chain(&t.approach_velocity);
    if all.clone().any(|x| !x.is_finite()) {
        return Err(TrajectoryError::NonFinite);
    }
    if let Some(row) = t.time.windows(2).position(|w| w[1] <= w[0]) {
        return Err(TrajectoryError::TimeNotIncreasing { row: row + 1 });
    }
    Ok(())
}

/// Impact figures read from a trajectory, the way they are read from a DEM code's output
/// (see [`trajectory_metrics`]): every quantity but the restitution time. The peak force and
/// the force contact time are NaN if the trajectory has no force column; the force contact
/// time and the compression time read as NaN from a record stored without them.
pub type TrajectoryMetrics = Measured;

/// Read COR, peak overlap, peak force, both contact times and the compression time from a
/// trajectory.
///
/// The speed before contact is the first row's, the speed after is the first row past the
/// contact (overlap ≤ 0 after having been positive); a contact that has not ended by the last
/// row is an error. The force-based end is the first row after touch whose force is ≤ 0 once
/// the force has been positive, interpolated linearly to the zero; the end of compression is
/// the approach speed's first zero crossing, interpolated the same way.
pub fn trajectory_metrics(t: &CodeTrajectory) -> Result<TrajectoryMetrics, TrajectoryError> {
    check_trajectory(t)?;
    let first_in = t
        .overlap
        .iter()
        .position(|&d| d > 0.0)
        .ok_or(TrajectoryError::NeverTouched)?;
    let last_in = t.overlap[first_in..]
        .iter()
        .position(|&d| d <= 0.0)
        .map(|k| first_in + k)
        .ok_or(TrajectoryError::ContactNotEnded)?;
    // The column changes sign between rows i-1 and i: the linearly interpolated zero.
    let zero = |column: &[f64], i: usize| -> f64 {
        if i == 0 {
            return t.time[0];
        }
        let (d0, d1) = (column[i - 1], column[i]);
        let (t0, t1) = (t.time[i - 1], t.time[i]);
        // Equal overlaps only when both are zero (the signs differ): no slope to interpolate.
        if d0 - d1 == 0.0 {
            t1
        } else {
            t0 + (t1 - t0) * d0 / (d0 - d1)
        }
    };
    let crossing = |i: usize| zero(&t.overlap, i);
    let start = crossing(first_in);
    let end = crossing(last_in);
    let force_end = if t.normal_force.len() == t.time.len() {
        let f = &t.normal_force;
        f[first_in..=last_in]
            .iter()
            .position(|&x| x > 0.0)
            .map(|k| first_in + k)
            .and_then(|pushing| {
                f[pushing..]
                    .iter()
                    .position(|&x| x <= 0.0)
                    .map(|k| zero(f, pushing + k))
            })
            .unwrap_or(f64::NAN)
    } else {
        f64::NAN
    };
    let turn = t.approach_velocity[first_in..=last_in]
        .iter()
        .position(|&v| v <= 0.0)
        .map(|k| zero(&t.approach_velocity, first_in + k))
        .unwrap_or(f64::NAN);
    let v_in = t.approach_velocity[0];
    let v_out = -t.approach_velocity[last_in];
    let peak_deformation = t.overlap.iter().cloned().fold(f64::MIN, f64::max);
    let peak_force = if t.normal_force.is_empty() {
        f64::NAN
    } else {
        t.normal_force.iter().cloned().fold(f64::MIN, f64::max)
    };
    Ok(TrajectoryMetrics {
        cor: v_out / v_in,
        peak_deformation,
        peak_force,
        contact_time: end - start,
        force_contact_time: force_end - start,
        compression_time: turn - start,
        ..TrajectoryMetrics::default()
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    // Every value here is a small binary fraction, computed without rounding: exact.
    #[allow(clippy::float_cmp)]
    #[test]
    fn trajectory_metrics_interpolates_the_zero_crossings() {
        // Overlap rises from -1 to 3 and falls to -1: zero crossings at t = 0.25 and t = 3.75.
        let t = CodeTrajectory {
            time: vec![0.0, 1.0, 2.0, 3.0, 4.0],
            overlap: vec![-1.0, 3.0, 4.0, 3.0, -1.0],
            approach_velocity: vec![2.0, 1.0, 0.0, -1.0, -1.5],
            normal_force: vec![0.0, 10.0, 20.0, 10.0, 0.0],
        };
        let m = trajectory_metrics(&t).unwrap();
        assert_eq!(m.contact_time, 3.5);
        assert_eq!(m.cor, 0.75);
        assert_eq!(m.peak_deformation, 4.0);
        assert_eq!(m.peak_force, 20.0);
        // Force zero at t = 4 (the last row), speed zero crossing at t = 2.
        assert_eq!(m.force_contact_time, 3.75);
        assert_eq!(m.compression_time, 1.75);
    }

    #[test]
    fn a_trajectory_whose_time_does_not_increase_is_refused() {
        let t = CodeTrajectory {
            time: vec![0.0, 1.0, 1.0, 3.0, 4.0],
            overlap: vec![-1.0, 3.0, 4.0, 3.0, -1.0],
            approach_velocity: vec![2.0, 1.0, 0.0, -1.0, -1.5],
            normal_force: vec![0.0, 10.0, 20.0, 10.0, 0.0],
        };
        assert!(matches!(
            trajectory_metrics(&t),
            Err(TrajectoryError::TimeNotIncreasing { row: 2 })
        ));
    }

    #[test]
    fn the_force_based_end_is_where_the_force_first_reaches_zero() {
        // The force turns attractive at t = 2.5 while the overlap closes at t = 3.5.
        let t = CodeTrajectory {
            time: vec![0.0, 1.0, 2.0, 3.0, 4.0],
            overlap: vec![0.0, 2.0, 2.0, 1.0, -1.0],
            approach_velocity: vec![2.0, 1.0, -1.0, -1.0, -1.0],
            normal_force: vec![0.0, 10.0, 4.0, -4.0, 0.0],
        };
        let m = trajectory_metrics(&t).unwrap();
        // Crossings of straight segments through grid points: exact in binary floating point.
        #[allow(clippy::float_cmp)]
        {
            assert_eq!(m.contact_time, 3.5);
            assert_eq!(m.force_contact_time, 2.5);
            assert_eq!(m.compression_time, 1.5);
        }
    }

    #[test]
    fn records_stored_without_the_new_times_still_load() {
        let old = r#"{"cor":0.7,"peak_deformation":1e-5,"peak_force":100.0,"contact_time":1e-4}"#;
        let m: TrajectoryMetrics = serde_json::from_str(old).unwrap();
        assert!(m.force_contact_time.is_nan() && m.compression_time.is_nan());
        let back: TrajectoryMetrics =
            serde_json::from_str(&serde_json::to_string(&m).unwrap()).unwrap();
        assert!(back.force_contact_time.is_nan());
    }

    #[test]
    fn trajectory_metrics_refuses_an_unfinished_contact() {
        let t = CodeTrajectory {
            time: vec![0.0, 1.0, 2.0],
            overlap: vec![0.0, 1.0, 2.0],
            approach_velocity: vec![1.0, 1.0, 1.0],
            normal_force: vec![],
        };
        assert_eq!(
            trajectory_metrics(&t).unwrap_err(),
            TrajectoryError::ContactNotEnded
        );
    }
}
