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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn admits_each_difference_up_to_its_own_tolerance_and_no_nan() {
        let tolerance = Tolerance {
            cor: 1e-3,
            peak_deformation: 2e-3,
            contact_time: 5e-3,
            ..Tolerance::default()
        };
        let at_the_bounds = Differences {
            cor: -1e-3,
            peak_deformation: 2e-3,
            contact_time: -5e-3,
            // Outside the checked set: never judged.
            peak_force: 1.0,
            ..Differences::default()
        };
        assert!(tolerance.admits(&at_the_bounds));
        for q in Differences::quantities() {
            let mut beyond = at_the_bounds;
            *beyond.get_mut(q) *= 1.01;
            assert!(!tolerance.admits(&beyond), "{q} beyond its tolerance");
            let mut missing = at_the_bounds;
            *missing.get_mut(q) = f64::NAN;
            assert!(!tolerance.admits(&missing), "{q} NaN");
        }
    }

    #[test]
    fn a_method_s_rule_sets_every_checked_quantity() {
        let uniform = Tolerance::for_method(Method::Dopri5, None, 1e-4);
        let values: Vec<u64> = uniform.iter().map(|(_, x)| x.to_bits()).collect();
        assert_eq!(values.len(), 3);
        assert!(values.iter().all(|&x| x == values[0]) && uniform.cor > 0.0);
        let one_step = Tolerance::for_method(Method::Rk4, Some(1e-7), 1e-4);
        assert_eq!(one_step.contact_time.to_bits(), (1e-7f64 / 1e-4).to_bits());
        assert_eq!(one_step.cor.to_bits(), one_step.peak_deformation.to_bits());
    }
}
