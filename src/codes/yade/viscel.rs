//! `ViscElMat`'s arithmetic as YADE 2023.02a does it (`pkg/dem/ViscoelasticPM.cpp`), in its own
//! operations: two values in series, and the restitution of a clamped linear dashpot and its
//! inverse by YADE's Newton iteration.

use std::f64::consts::PI;

/// `contactParameterCalculation` of ViscoelasticPM.cpp: two values in series, a zero one left out.
pub(super) fn series(a: f64, b: f64) -> f64 {
    let inverse = (if a != 0.0 { 1.0 / a } else { 0.0 }) + (if b != 0.0 { 1.0 / b } else { 0.0 });
    if inverse != 0.0 { 1.0 / inverse } else { 0.0 }
}

/// `Ip2_ViscElMat_ViscElMat_ViscElPhys::epsilon`.
pub(super) const VISCEL_EPSILON: f64 = 1e-8;

/// `get_en_from_cn` of ViscoelasticPM.cpp: the COR of the clamped linear dashpot `cn` on mass
/// `m` and stiffness `kn`, in YADE's own operations.
// The equality branch is YADE's: it steps off the two points its formulas divide by zero at.
#[allow(clippy::float_cmp)]
pub(super) fn viscel_en_from_cn(cn: f64, m: f64, kn: f64) -> f64 {
    let beta = 0.5 * cn / m;
    let omega0 = (kn / m).sqrt();
    let omega = (omega0 * omega0 - beta * beta).sqrt();
    let big = (beta * beta - omega0 * omega0).sqrt();
    let root2 = 2f64.sqrt();
    if beta < omega0 / root2 {
        (-beta / omega * (PI - (2.0 * beta * omega / (omega * omega - beta * beta)).atan())).exp()
    } else if beta > omega0 / root2 && beta < omega0 {
        (-beta / omega * (-2.0 * beta * omega / (omega * omega - beta * beta)).atan()).exp()
    } else if beta > omega0 {
        (-beta / big * ((beta + big) / (beta - big)).ln()).exp()
    } else if beta == omega0 / root2 || beta == omega0 {
        viscel_en_from_cn(cn + VISCEL_EPSILON, m, kn)
    } else {
        0.0
    }
}

/// `find_cn_from_en` of ViscoelasticPM.cpp: YADE's Newton iteration for the `cn` whose clamped
/// law rebounds at `en`, stopped once within 1 % of it (at most 15 steps; then `cn = 0`, and
/// `None` here).
pub(super) fn viscel_cn_from_en(en: f64, m: f64, kn: f64) -> Option<f64> {
    let eps = VISCEL_EPSILON;
    let mut cn = eps;
    let mut en_temp = viscel_en_from_cn(cn, m, kn);
    let mut i = 0;
    let mut error = 1.0 / eps;
    while error > 1.0e-2 || error.is_nan() {
        if i > 15 {
            return None;
        }
        i += 1;
        let deriv = (viscel_en_from_cn(cn - eps, m, kn) - viscel_en_from_cn(cn + eps, m, kn))
            / (-2.0 * eps);
        let deriv = if deriv.abs() > 1e-15 { deriv } else { 1e-15 };
        cn -= (en_temp - en) / deriv;
        en_temp = viscel_en_from_cn(cn, m, kn);
        error = (en_temp - en).abs() / en;
    }
    Some(cn)
}

#[cfg(test)]
mod tests {
    // series() of exact inputs is exact.
    #![allow(clippy::float_cmp)]
    use super::*;

    #[test]
    fn yades_newton_iteration_lands_within_one_percent_of_en() {
        let (m, kn) = (0.5, 1e6);
        for en in [0.3, 0.5, 0.7, 0.9] {
            let cn = viscel_cn_from_en(en, m, kn).unwrap();
            let realised = viscel_en_from_cn(cn, m, kn);
            assert!(((realised - en) / en).abs() <= 1e-2, "{en}: {realised}");
            // get_en_from_cn is the clamped linear dashpot's COR (the closed form of damping.rs).
            let zeta = crate::codes::damping::clamped_linear_damping_ratio(realised).unwrap();
            let c = 2.0 * zeta * (m * kn).sqrt();
            assert!(((c - cn) / cn).abs() < 1e-9, "{en}: {c} {cn}");
        }
    }

    #[test]
    fn values_in_series_leave_a_zero_out() {
        assert_eq!(series(2.0, 2.0), 1.0);
        assert_eq!(series(0.0, 3.0), 3.0);
        assert_eq!(series(0.0, 0.0), 0.0);
    }
}
