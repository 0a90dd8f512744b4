//! The one rule by which a figure is judged: a tolerance per quantity, and `admits`.

use crate::model::figures::{Checked, Figures};
use crate::solve::{Method, ToleranceRule};

/// The agreement a source must reach on each checked quantity (COR, peak deformation, contact
/// time; relative unless said otherwise).
pub type Tolerance = Checked;

/// Differences of one source from another on each checked quantity.
pub type Differences = Checked;

impl<const Q: u8> Figures<f64, Q> {
    /// Whether every difference in `d` is within its tolerance in `self` (a NaN difference is
    /// not).
    pub(crate) fn admits(&self, d: &Figures<f64, Q>) -> bool {
        self.iter()
            .all(|(q, tolerance)| d.get(q).abs() <= *tolerance)
    }
}

impl Tolerance {
    /// The stated tolerance of `method` for a run at fixed step `timestep` (s, if any) whose
    /// exact contact time is `contact_time` (s), from the method's descriptor.
    pub fn for_method(method: Method, timestep: Option<f64>, contact_time: f64) -> Tolerance {
        match method.descriptor().tolerance {
            ToleranceRule::Uniform(x) => Tolerance::splat(x),
            ToleranceRule::OneStepEnd { figures } => Tolerance {
                cor: figures,
                peak_deformation: figures,
                contact_time: timestep.unwrap_or(0.0) / contact_time,
                ..Tolerance::default()
            },
        }
    }
}
