//! What the mill's verdicts rest on: Student's t at an estimate's degrees of freedom (a
//! difference of two laws' means takes Welch–Satterthwaite's), and the lag-1 autocorrelation
//! of one run's block means, which says whether the blocks are as independent as their
//! standard error assumes.

use serde::{Deserialize, Serialize};
use statrs::distribution::{ContinuousCDF, Normal, StudentsT};

/// A mean with its standard error.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Estimate {
    /// The mean.
    pub mean: f64,
    /// Its standard error.
    pub standard_error: f64,
    /// The degrees of freedom of the standard error: runs − 1 over seeds, blocks − 1 within one
    /// run, Welch–Satterthwaite's for a difference (`None`: a Poisson count's, taken as normal).
    #[serde(default)]
    pub degrees_of_freedom: Option<f64>,
    /// The lag-1 autocorrelation of the block means the standard error is taken from (one run
    /// only; `None` over seeds, whose runs are independent): well above zero, the blocks are
    /// not independent and the standard error is too small.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub lag1_autocorrelation: Option<f64>,
}

/// The two-sided confidence a difference must clear to be resolved: 95 %.
pub(crate) const CONFIDENCE: f64 = 0.95;

/// The fewest runs per law a difference can be called resolved with: four runs give three
/// degrees of freedom per law, where one unlucky seed moves the spread by a factor of two
/// (the example mill's power was "resolved" at three seeds and not at four).
pub const MIN_SEEDS: usize = 5;

/// The factor a difference must exceed, in standard errors, at `degrees_of_freedom`
/// (`None`: a Poisson count's error, taken as normal); infinite where there is no freedom
/// at all (one value), so that nothing is resolved from it.
pub(crate) fn t_factor(degrees_of_freedom: Option<f64>) -> f64 {
    let p = 0.5 + CONFIDENCE / 2.0;
    match degrees_of_freedom {
        None => Normal::standard().inverse_cdf(p),
        Some(df) => StudentsT::new(0.0, 1.0, df).map_or(f64::INFINITY, |t| t.inverse_cdf(p)),
    }
}

/// The degrees of freedom of `a`'s and `b`'s errors summed in quadrature
/// (Welch–Satterthwaite: `s⁴ / Σ sᵢ⁴/νᵢ`); a Poisson error counts as unbounded freedom.
pub(crate) fn welch(a: Estimate, b: Estimate) -> Option<f64> {
    let terms = [a, b];
    if terms.iter().all(|e| e.degrees_of_freedom.is_none()) {
        return None;
    }
    let mut sum = 0.0;
    for e in terms {
        if let Some(df) = e.degrees_of_freedom {
            if df <= 0.0 || df.is_nan() {
                return Some(0.0);
            }
            sum += e.standard_error.powi(4) / df;
        }
    }
    let s2 = a.standard_error.powi(2) + b.standard_error.powi(2);
    if sum > 0.0 {
        Some(s2 * s2 / sum)
    } else {
        // Both errors zero: the smaller freedom is the honest one.
        terms
            .iter()
            .filter_map(|e| e.degrees_of_freedom)
            .reduce(f64::min)
    }
}

/// The lag-1 autocorrelation of `values` (`None` with fewer than three or no spread): near
/// zero for independent blocks; well above it, the blocks' standard error is too small.
pub(crate) fn lag1(values: &[f64]) -> Option<f64> {
    if values.len() < 3 {
        return None;
    }
    let mean = values.iter().sum::<f64>() / values.len() as f64;
    let variance: f64 = values.iter().map(|v| (v - mean).powi(2)).sum();
    let covariance: f64 = values
        .windows(2)
        .map(|w| (w[0] - mean) * (w[1] - mean))
        .sum();
    (variance > 0.0).then(|| covariance / variance)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn estimate(standard_error: f64, degrees_of_freedom: Option<f64>) -> Estimate {
        Estimate {
            mean: 0.0,
            standard_error,
            degrees_of_freedom,
            lag1_autocorrelation: None,
        }
    }

    #[test]
    fn the_t_factor_falls_to_the_normal_ones_with_freedom() {
        // Tabled two-sided 95 % values of Student's t.
        for (df, t) in [(2.0, 4.303), (4.0, 2.776), (9.0, 2.262), (30.0, 2.042)] {
            assert!((t_factor(Some(df)) - t).abs() < 1e-3, "{df}");
        }
        assert!((t_factor(None) - 1.960).abs() < 1e-3);
        assert!(t_factor(Some(1e6)) - t_factor(None) < 1e-5);
        assert!(t_factor(Some(0.0)).is_infinite());
    }

    #[test]
    fn welch_gives_the_pooled_freedom_for_equal_errors_and_the_smaller_for_a_dominant_one() {
        let same = welch(estimate(1.0, Some(4.0)), estimate(1.0, Some(4.0))).unwrap();
        assert!((same - 8.0).abs() < 1e-12);
        let one = welch(estimate(10.0, Some(4.0)), estimate(1e-3, Some(100.0))).unwrap();
        assert!((one - 4.0).abs() < 1e-6, "{one}");
        assert_eq!(welch(estimate(1.0, None), estimate(2.0, None)), None);
        assert_eq!(
            welch(estimate(0.0, Some(3.0)), estimate(0.0, Some(5.0))),
            Some(3.0)
        );
    }

    #[test]
    fn a_difference_is_resolved_beyond_t_and_only_from_enough_seeds() {
        use super::super::report::{Verdict, difference};
        let at = |mean: f64, df: f64| Estimate {
            mean,
            ..estimate(1.0, Some(df))
        };
        // 2.5 standard errors of the difference (√2 each) at four seeds per law: beyond t at
        // Welch's six degrees of freedom (2.447), but from too few seeds to conclude.
        let (d, verdict) = difference(at(0.0, 3.0), at(2.5 * 2f64.sqrt(), 3.0), 4);
        assert!((d.degrees_of_freedom.unwrap() - 6.0).abs() < 1e-12);
        assert_eq!(verdict, Verdict::TooFewSeeds);
        // Within t at two seeds' one degree of freedom per law (t = 4.30 at two).
        let (_, verdict) = difference(at(0.0, 1.0), at(2.5 * 2f64.sqrt(), 1.0), 2);
        assert_eq!(verdict, Verdict::NotResolved);
        // Beyond t with five seeds per law: resolved; within it: not.
        let (_, verdict) = difference(at(0.0, 4.0), at(2.5 * 2f64.sqrt(), 4.0), 5);
        assert_eq!(verdict, Verdict::Resolved);
        let (_, verdict) = difference(at(0.0, 4.0), at(2.2 * 2f64.sqrt(), 4.0), 5);
        assert_eq!(verdict, Verdict::NotResolved);
    }

    #[test]
    fn lag1_is_near_one_for_a_trend_and_negative_for_an_alternation() {
        let trend = lag1(&[1.0, 2.0, 3.0, 4.0, 5.0]).unwrap();
        assert!(trend > 0.3, "{trend}");
        let alternation = lag1(&[1.0, -1.0, 1.0, -1.0, 1.0]).unwrap();
        assert!(alternation < -0.7, "{alternation}");
        assert_eq!(lag1(&[2.0, 2.0, 2.0]), None);
        assert_eq!(lag1(&[1.0, 2.0]), None);
    }
}
