//! The COR against the impact speed, per pair of a deck checked at several speeds: the realised
//! COR beside the law's exact curve, a trap line where the law's COR depends on the speed, and
//! for viscoelastic damping (LAMMPS `damping viscoelastic`) Müller & Pöschel's closed form.

use serde::Serialize;

use super::DeckImpact;
use crate::model::law::DashpotLaw;

/// The spread of a law's exact COR over the speeds checked above which the law is said to
/// depend on the speed: far above the integration's 1e-12, far below any COR a user types.
pub(crate) const SPEED_DEPENDENCE: f64 = 1e-6;

/// Müller & Pöschel's [3/6] Padé approximant of the COR of viscoelastic spheres (Phys. Rev. E
/// 84, 021302, 2011): numerator coefficients of `x`, `x²`, `x³`.
const PADE_NUMERATOR: [f64; 3] = [1.07232, 0.574198, 0.141552];
/// Its denominator's coefficients of `x` … `x⁶`.
const PADE_DENOMINATOR: [f64; 6] = [1.07232, 1.72765, 1.37842, 1.19449, 0.467344, 0.235580];

/// The COR of the viscoelastic law `F = k δ^1.5 + c δ^0.5 δ̇` (unit-free in `x = sqrt(β) v^(1/10)`,
/// `β = (c/k) (k/m)^(2/5)`) at `impact_velocity` (m/s) by Müller & Pöschel's [3/6] Padé
/// approximant; `None` for any other law. Their series ends a collision where the force
/// vanishes, so it is the clamped law's COR.
pub(crate) fn viscoelastic_cor(law: &DashpotLaw, impact_velocity: f64) -> Option<f64> {
    // Exact exponents: the law's as the deck reader sets them, 1.5 and 0.5 and nothing near.
    #[allow(clippy::float_cmp)]
    let viscoelastic = law.exponent == 1.5 && law.damping_exponent == 0.5;
    if !viscoelastic || law.damping <= 0.0 {
        return None;
    }
    let beta = law.damping / law.stiffness * (law.stiffness / law.mass).powf(0.4);
    let x = beta.sqrt() * impact_velocity.powf(0.1);
    let powers = |n: usize| (1..=n).map(|i| x.powi(i32::try_from(i).unwrap_or(i32::MAX)));
    let numerator = 1.0
        + PADE_NUMERATOR
            .iter()
            .zip(powers(3))
            .map(|(a, p)| a * p)
            .sum::<f64>();
    let denominator = 1.0
        + PADE_DENOMINATOR
            .iter()
            .zip(powers(6))
            .map(|(b, p)| b * p)
            .sum::<f64>();
    Some(numerator / denominator)
}

/// One pair's COR over the speeds checked.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SpeedCurve {
    /// The pair, as the tables label it.
    pub pair: String,
    /// The speeds, m/s, as given.
    pub speeds: Vec<f64>,
    /// The COR realised in the code at each speed (NaN where the run failed).
    pub cor_realised: Vec<f64>,
    /// The law's exact COR at each speed.
    pub cor_law: Vec<f64>,
    /// Müller & Pöschel's closed form at each speed, for viscoelastic damping.
    pub cor_closed_form: Option<Vec<f64>>,
    /// `max − min` of the law's exact COR over the speeds.
    pub spread: f64,
    /// Whether the law's COR depends on the speed (its spread above [`SPEED_DEPENDENCE`]).
    pub depends_on_speed: bool,
}

impl SpeedCurve {
    /// The trap line of a law whose COR depends on the speed.
    pub fn trap(&self) -> Option<String> {
        if !self.depends_on_speed {
            return None;
        }
        let (first, last) = (self.speeds.first()?, self.speeds.last()?);
        let (low, high) = self
            .cor_law
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &c| {
                (lo.min(c), hi.max(c))
            });
        Some(format!(
            "the COR of this law depends on the impact speed: from {:.6} at {first} m/s to {:.6} at {last} m/s, between {low:.6} and {high:.6} over the {} speeds given (spread {:.3e}); a COR typed for it holds at one speed only",
            self.cor_law.first()?,
            self.cor_law.last()?,
            self.speeds.len(),
            self.spread
        ))
    }
}

/// The curve of each pair of `impacts` checked at two speeds or more, in the order the pairs
/// first appear.
pub(crate) fn speed_curves(impacts: &[DeckImpact]) -> Vec<SpeedCurve> {
    crate::analysis::groups(impacts, |i| i.pair.as_str())
        .into_iter()
        .filter_map(|(pair, rows)| {
            if rows.len() < 2 {
                return None;
            }
            let cor_law: Vec<f64> = rows.iter().map(|r| r.cor_law).collect();
            let finite = cor_law.iter().copied().filter(|c| c.is_finite());
            let (low, high) = finite.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), c| {
                (lo.min(c), hi.max(c))
            });
            let spread = if high >= low { high - low } else { 0.0 };
            let cor_closed_form = rows
                .iter()
                .map(|r| {
                    r.law
                        .dashpot()
                        .and_then(|law| viscoelastic_cor(law, r.impact_velocity))
                })
                .collect::<Option<Vec<f64>>>();
            Some(SpeedCurve {
                pair: pair.to_string(),
                speeds: rows.iter().map(|r| r.impact_velocity).collect(),
                cor_realised: rows.iter().map(|r| r.realised.cor).collect(),
                cor_law,
                cor_closed_form,
                spread,
                depends_on_speed: spread > SPEED_DEPENDENCE,
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::solve::dashpot::accurate_metrics;

    /// The Padé approximant against the harness's own integration of the viscoelastic law,
    /// clamped (their series ends a collision where the force vanishes) and not, for damping
    /// from 0.001 to 1 and speeds 0.1 to 10 (unit mass and stiffness): within 5e-7 of the
    /// clamped law where its COR is above 0.8, 1.1e-5 above 0.6 and 1e-4 above 0.3 (measured
    /// 4.4e-7, 1.06e-5, 9.8e-5); the unclamped law, LAMMPS' without `limit_damping`, lies below
    /// it by up to 0.10 (at a clamped COR of 0.27). Its coefficients expand to the series' known first
    /// terms (`1 − 1.15345 x² + 0.79827 x⁴`).
    #[test]
    fn the_pade_approximant_meets_the_clamped_law_integrated() {
        let mut unclamped_worst: f64 = 0.0;
        for damping in [0.001, 0.01, 0.03, 0.1, 0.3, 0.6, 1.0] {
            let law = DashpotLaw {
                mass: 1.0,
                stiffness: 1.0,
                exponent: 1.5,
                damping,
                damping_exponent: 0.5,
                clamp_attractive: true,
            };
            for v in [0.1, 1.0, 10.0] {
                let clamped = accurate_metrics(&law, v, 1e-11).unwrap().cor;
                let closed = viscoelastic_cor(&law, v).unwrap();
                let bound = if clamped > 0.8 {
                    5e-7
                } else if clamped > 0.6 {
                    1.1e-5
                } else if clamped > 0.3 {
                    1e-4
                } else {
                    3e-4
                };
                assert!(
                    (closed - clamped).abs() < bound,
                    "c = {damping}, v = {v}: {closed} against {clamped}"
                );
                let free = DashpotLaw {
                    clamp_attractive: false,
                    ..law
                };
                let unclamped = accurate_metrics(&free, v, 1e-11).unwrap().cor;
                assert!(unclamped <= clamped + 1e-12);
                unclamped_worst = unclamped_worst.max(closed - unclamped);
            }
        }
        assert!(
            unclamped_worst > 5e-2 && unclamped_worst < 0.11,
            "{unclamped_worst}"
        );
        // The expansion: e1 = a1 − b1, e2 = a2 − b2, e3, e4 as the series has them.
        let (a, b) = (PADE_NUMERATOR, PADE_DENOMINATOR);
        let e2 = a[1] - b[1];
        let e3 = a[2] - b[2] - b[0] * e2;
        let e4 = -b[3] - b[0] * e3 - b[1] * e2;
        assert!((a[0] - b[0]).abs() < 1e-12);
        assert!((e2 + 1.153_44).abs() < 2e-5, "{e2}");
        assert!(e3.abs() < 2e-5, "{e3}");
        assert!((e4 - 0.798_27).abs() < 1e-3, "{e4}");
    }

    /// A deck whose law's COR does not depend on the speed gets no speed trap however many speeds
    /// are asked: the LAMMPS granular example's tsuji law (damped Hertz, speed-free) from its
    /// recorded runs would need runs at several speeds, so the check is on the curve itself.
    #[test]
    fn a_speed_free_law_has_no_speed_trap() {
        let curve = SpeedCurve {
            pair: "1–1".into(),
            speeds: vec![1.0, 2.0],
            cor_realised: vec![0.5, 0.5],
            cor_law: vec![0.5, 0.5 + 1e-12],
            cor_closed_form: None,
            spread: 1e-12,
            depends_on_speed: 1e-12 > SPEED_DEPENDENCE,
        };
        assert_eq!(curve.trap(), None);
    }
}
