//! The one rule by which a figure is judged: a tolerance per quantity, and `admits`.

use serde::Serialize;

use crate::solve::{Method, ToleranceRule};

/// The agreement a source must reach, per quantity (relative unless said otherwise).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Tolerance {
    /// On the COR.
    pub cor: f64,
    /// On the peak deformation.
    pub peak_deformation: f64,
    /// On the contact time.
    pub contact_time: f64,
}

/// Differences of one source from another, per quantity.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Differences {
    /// Of the COR.
    pub cor: f64,
    /// Of the peak deformation.
    pub peak_deformation: f64,
    /// Of the contact time.
    pub contact_time: f64,
}

impl Tolerance {
    /// Whether every difference is within its tolerance.
    pub(crate) fn admits(&self, d: &Differences) -> bool {
        d.cor.abs() <= self.cor
            && d.peak_deformation.abs() <= self.peak_deformation
            && d.contact_time.abs() <= self.contact_time
    }

    /// The stated tolerance of `method` for a run at fixed step `timestep` (s, if any) whose
    /// exact contact time is `contact_time` (s), from the method's descriptor.
    pub fn for_method(method: Method, timestep: Option<f64>, contact_time: f64) -> Tolerance {
        match method.descriptor().tolerance {
            ToleranceRule::Uniform(x) => Tolerance {
                cor: x,
                peak_deformation: x,
                contact_time: x,
            },
            ToleranceRule::OneStepEnd { figures } => Tolerance {
                cor: figures,
                peak_deformation: figures,
                contact_time: timestep.unwrap_or(0.0) / contact_time,
            },
        }
    }
}
