//! The start-phase band (physics.md §6): a fixed-step run's figures depend on where the first
//! contact falls within a step. Stepping a code's own law from a gap `φ v0 Δt` before touch,
//! `φ` over one step, gives the band its integration offset spans; a stored run is one point
//! in it.

use serde::Serialize;

use crate::analysis::store::ReferenceRecord;
use crate::model::exact::ImpactFigures;
use crate::model::trajectory::{TrajectoryError, TrajectoryMetrics, trajectory_metrics};

/// Start phases swept by default.
pub const DEFAULT_PHASES: usize = 32;

/// The smallest and largest value of one offset over the start phases.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Range {
    /// Smallest.
    pub min: f64,
    /// Largest.
    pub max: f64,
}

impl Range {
    fn new() -> Range {
        Range {
            min: f64::INFINITY,
            max: f64::NEG_INFINITY,
        }
    }

    fn add(&mut self, x: f64) {
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

/// Relative offsets of a figure set from another, per figure, relative to the paper's law.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Offsets {
    /// COR.
    pub cor: f64,
    /// Peak deformation.
    pub peak_deformation: f64,
    /// Peak force.
    pub peak_force: f64,
    /// Contact time by overlap.
    pub contact_time: f64,
    /// Contact time by force.
    pub force_contact_time: f64,
}

impl Offsets {
    /// `(a − b)` relative to the paper's figures (the force time relative to the paper's
    /// contact time, which is also its force's duration).
    pub fn between(a: &TrajectoryMetrics, b: &TrajectoryMetrics, paper: &ImpactFigures) -> Offsets {
        Offsets {
            cor: (a.cor - b.cor) / paper.cor,
            peak_deformation: (a.peak_deformation - b.peak_deformation) / paper.peak_deformation,
            peak_force: (a.peak_force - b.peak_force) / paper.peak_force,
            contact_time: (a.contact_time - b.contact_time) / paper.contact_time,
            force_contact_time: (a.force_contact_time - b.force_contact_time) / paper.contact_time,
        }
    }
}

/// The integration offset of a code's own law, stepped as the code steps, over start phases.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct PhaseBand {
    /// Start phases swept (φ = k / phases).
    pub phases: usize,
    /// COR offset band.
    pub cor: Range,
    /// Peak deformation offset band.
    pub peak_deformation: Range,
    /// Peak force offset band.
    pub peak_force: Range,
    /// Overlap contact time offset band.
    pub contact_time: Range,
    /// Force contact time offset band.
    pub force_contact_time: Range,
}

impl PhaseBand {
    /// Whether every figure of `point` lies in its band (within `slack`).
    pub fn contains(&self, point: &Offsets, slack: f64) -> bool {
        self.cor.contains(point.cor, slack)
            && self
                .peak_deformation
                .contains(point.peak_deformation, slack)
            && self.peak_force.contains(point.peak_force, slack)
            && self.contact_time.contains(point.contact_time, slack)
            && self
                .force_contact_time
                .contains(point.force_contact_time, slack)
    }
}

/// The figures of `record`'s own law stepped as its code steps, started at phase `phi`
/// (a gap of `φ v0 Δt` before the run's own start gap; `φ = 0` is the stored run's own start).
pub fn stepped_at_phase(
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

/// The integration offset (own law stepped − own law exact, relative to the paper's law) of
/// `record`'s own law over `phases` start phases, against its own law at zero step error
/// `exact`.
pub fn start_phase_band(
    record: &ReferenceRecord,
    exact: &TrajectoryMetrics,
    phases: usize,
) -> Result<PhaseBand, TrajectoryError> {
    let mut band = PhaseBand {
        phases,
        cor: Range::new(),
        peak_deformation: Range::new(),
        peak_force: Range::new(),
        contact_time: Range::new(),
        force_contact_time: Range::new(),
    };
    for k in 0..phases {
        let m = stepped_at_phase(record, k as f64 / phases as f64)?;
        let o = Offsets::between(&m, exact, &record.paper_exact);
        band.cor.add(o.cor);
        band.peak_deformation.add(o.peak_deformation);
        band.peak_force.add(o.peak_force);
        band.contact_time.add(o.contact_time);
        band.force_contact_time.add(o.force_contact_time);
    }
    Ok(band)
}
