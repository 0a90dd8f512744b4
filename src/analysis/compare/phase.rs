//! The start-phase band (physics.md §6): a fixed-step run's figures depend on where the first
//! contact falls within a step. Stepping a code's own law from a gap `φ v0 Δt` before touch,
//! `φ` over one step, gives the band its integration offset spans; a stored run is one point
//! in it.

use serde::Serialize;

use crate::analysis::store::ReferenceRecord;
use crate::model::exact::ImpactFigures;
use crate::model::figures::{Figures, quantity};
use crate::model::trajectory::{TrajectoryError, TrajectoryMetrics, trajectory_metrics};

/// Start phases swept by default.
pub(crate) const DEFAULT_PHASES: usize = 32;

/// The smallest and largest value of one offset over the start phases.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Range {
    /// Smallest.
    pub min: f64,
    /// Largest.
    pub max: f64,
}

/// The empty range, which the first value added makes a point.
impl Default for Range {
    fn default() -> Range {
        Range {
            min: f64::INFINITY,
            max: f64::NEG_INFINITY,
        }
    }
}

impl Range {
    pub(crate) fn add(&mut self, x: f64) {
        if x.is_finite() {
            self.min = self.min.min(x);
            self.max = self.max.max(x);
        }
    }

    /// Whether `x` lies in the band, allowing `slack` (absolute) at either end.
    pub fn contains(&self, x: f64, slack: f64) -> bool {
        x >= self.min - slack && x <= self.max + slack
    }
}

/// The quantities an offset is given for: all a trajectory gives but the compression time.
pub(crate) const OFFSET_QUANTITIES: u8 = quantity::COR
    | quantity::PEAK_DEFORMATION
    | quantity::PEAK_FORCE
    | quantity::CONTACT_TIME
    | quantity::FORCE_CONTACT_TIME;

/// Relative offsets of a figure set from another, per figure, relative to the paper's law.
pub(crate) type Offsets = Figures<f64, OFFSET_QUANTITIES>;

impl Offsets {
    /// `(a − b)` relative to the paper's figures (the force time relative to the paper's
    /// contact time, which is also its force's duration).
    pub(crate) fn between(
        a: &TrajectoryMetrics,
        b: &TrajectoryMetrics,
        paper: &ImpactFigures,
    ) -> Offsets {
        let paper = paper.metrics();
        Offsets::from_fn(|q| (a.get(q) - b.get(q)) / paper.get(q))
    }
}

/// The integration offset of a code's own law, stepped as the code steps, over start phases.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct PhaseBand {
    /// Start phases swept (φ = k / phases).
    pub phases: usize,
    /// Each figure's offset band.
    #[serde(flatten)]
    pub ranges: Figures<Range, OFFSET_QUANTITIES>,
}

impl PhaseBand {
    /// Whether every figure of `point` lies in its band (within `slack`).
    pub fn contains(&self, point: &Offsets, slack: f64) -> bool {
        self.ranges
            .iter()
            .all(|(q, range)| range.contains(*point.get(q), slack))
    }
}

/// The figures of `record`'s own law stepped as its code steps, started at phase `phi`
/// (a gap of `φ v0 Δt` before the run's own start gap; `φ = 0` is the stored run's own start).
pub(crate) fn stepped_at_phase(
    record: &ReferenceRecord,
    phi: f64,
) -> Result<TrajectoryMetrics, TrajectoryError> {
    let v0 = record.setup.impact_velocity;
    let dt = record.timestep;
    let trajectory =
        record
            .stepping()
            .trajectory(&record.law, v0, dt, record.steps + 2, phi * v0 * dt);
    trajectory_metrics(&trajectory)
}

/// The mean of `at(φ)` over `phases` start phases `φ = k / phases` (uniform over one step:
/// where a user's run meets its first contact), with its range; a phase whose value is not
/// finite is left out of both (the mean is NaN where none is).
pub(crate) fn over_phases(phases: usize, mut at: impl FnMut(f64) -> f64) -> (f64, Range) {
    let mut range = Range::default();
    let (mut sum, mut n) = (0.0, 0usize);
    for k in 0..phases {
        let x = at(k as f64 / phases as f64);
        range.add(x);
        if x.is_finite() {
            sum += x;
            n += 1;
        }
    }
    (if n > 0 { sum / n as f64 } else { f64::NAN }, range)
}

/// The integration offset (own law stepped − own law exact, relative to the paper's law) of
/// `record`'s own law over `phases` start phases, against its own law at zero step error
/// `exact`.
pub(crate) fn start_phase_band(
    record: &ReferenceRecord,
    exact: &TrajectoryMetrics,
    phases: usize,
) -> Result<PhaseBand, TrajectoryError> {
    let mut band = PhaseBand {
        phases,
        ranges: Figures::default(),
    };
    for k in 0..phases {
        let m = stepped_at_phase(record, k as f64 / phases as f64)?;
        let o = Offsets::between(&m, exact, &record.paper_exact);
        for (q, x) in o.iter() {
            band.ranges.get_mut(q).add(*x);
        }
    }
    Ok(band)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_band_holds_a_point_only_if_every_figure_lies_in_its_range() {
        let mut band = PhaseBand {
            phases: 2,
            ranges: Figures::default(),
        };
        for x in [-1.0, f64::NAN, 1.0] {
            for q in Offsets::quantities() {
                band.ranges.get_mut(q).add(x);
            }
        }
        assert_eq!(
            band.ranges.contact_time,
            Range {
                min: -1.0,
                max: 1.0
            }
        );
        let inside = Offsets::splat(0.5);
        assert!(band.contains(&inside, 0.0));
        for (q, _) in inside.iter() {
            let mut outside = inside;
            *outside.get_mut(q) = 1.25;
            assert!(!band.contains(&outside, 0.0), "{q}");
            assert!(band.contains(&outside, 0.5), "{q} within the slack");
        }
    }

    #[test]
    fn an_empty_band_holds_nothing_and_writes_its_figures_by_name() {
        let band = PhaseBand {
            phases: 0,
            ranges: Figures::default(),
        };
        assert!(!band.contains(&Offsets::splat(0.0), 1.0));
        let json = serde_json::to_value(band).unwrap();
        let keys: Vec<&String> = json.as_object().unwrap().keys().collect();
        assert_eq!(
            keys,
            [
                "contact_time",
                "cor",
                "force_contact_time",
                "peak_deformation",
                "peak_force",
                "phases"
            ]
        );
    }
}
