//! Trajectories of one impact (time, overlap, approach velocity, normal force) and the figures
//! read from them, the same way for a DEM code's output and for a law stepped as a code steps.

use serde::{Deserialize, Serialize};
use thiserror::Error;

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

/// Check that a trajectory is complete enough to read figures from: at least three rows,
/// columns of one length, every value finite.
pub fn check_trajectory(t: &CodeTrajectory) -> Result<(), TrajectoryError> {
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
    Ok(())
}

/// Impact figures read from a trajectory, the way they are read from a DEM code's output.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct TrajectoryMetrics {
    /// Coefficient of restitution: approach speed after contact over approach speed before.
    pub cor: f64,
    /// Largest overlap, m.
    pub peak_deformation: f64,
    /// Largest normal force, N (NaN if the trajectory has no force column).
    pub peak_force: f64,
    /// Contact duration, s, from the zero crossings of the overlap (linearly interpolated).
    pub contact_time: f64,
}

/// Read COR, peak overlap, peak force and contact time from a trajectory.
///
/// The speed before contact is the first row's, the speed after is the first row past the
/// contact (overlap ≤ 0 after having been positive), or the last row's if the contact has not
/// ended, in which case the error says so.
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
    let crossing = |i: usize| -> f64 {
        // Overlap changes sign between rows i-1 and i.
        if i == 0 {
            return t.time[0];
        }
        let (d0, d1) = (t.overlap[i - 1], t.overlap[i]);
        let (t0, t1) = (t.time[i - 1], t.time[i]);
        // Equal overlaps only when both are zero (the signs differ): no slope to interpolate.
        if d0 - d1 == 0.0 {
            t1
        } else {
            t0 + (t1 - t0) * d0 / (d0 - d1)
        }
    };
    let start = crossing(first_in);
    let end = crossing(last_in);
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
