//! The damping the codes derive from a restitution coefficient, shared by the drivers whose
//! codes use it: Thornton et al.'s fit for damped Hertz (YADE's `Ip2_FrictMat_FrictMat_MindlinPhys`
//! and Kratos' `DEM_D_Hertz_viscous_Coulomb` both take `en` through it), the `en` that makes the
//! clamped law realise a target, and the damping ratio of a clamped linear dashpot.

use std::f64::consts::PI;

use crate::model::law::DashpotLaw;
use crate::solve::dashpot::accurate_metrics;

/// The damping ratio `β_n` (Kratos: `γ`) derived from a restitution coefficient `e` for the
/// Hertz–Mindlin law: Thornton, Cummins & Cleary, Powder Technol. 233 (2013) 30–46, Eq. (B6)
/// `β = sqrt(1 / (1 - (1+e)² exp(α)) - 1)` with the polynomial fit (B7)
/// `α = Σ h_i e^i` of their Table 2, as YADE 2023.02a evaluates it. `e = 1` gives exactly zero.
// `e = 1` is compared exactly: it is the one input YADE special-cases (the fit does not vanish).
#[allow(clippy::float_cmp)]
pub fn thornton_damping_ratio(restitution: f64) -> f64 {
    const H: [f64; 10] = [
        -6.918798, -16.41105, 146.8049, -796.4559, 2928.711, -7206.864, 11494.29, -11342.18,
        6276.757, -1489.915,
    ];
    if restitution == 1.0 {
        return 0.0;
    }
    let e = restitution;
    let alpha = H.iter().rev().fold(0.0, |acc, h| e * (h + acc));
    (1.0 / (1.0 - (1.0 + e).powi(2) * alpha.exp()) - 1.0).sqrt()
}

/// The Hertz–Mindlin law YADE (and Kratos) builds from `en`, reduced to its dimensionless COR: clamped
/// damped Hertz with `c = 2 β_n(en) sqrt(1.5 M k)`. The COR depends on `en` alone.
///
/// Remembered by `en`: the inversion below evaluates it at the midpoints of a bisection, whose
/// first levels every target of a sweep shares and whose last ones, once the bracket is two
/// neighbouring numbers, repeat its ends: a pure function's results, so the inversion gives
/// the same bits with fewer integrations (a quarter fewer over a sweep of 200 targets).
fn hertz_mindlin_cor(en: f64) -> f64 {
    type Memo = std::sync::Mutex<std::collections::HashMap<u64, f64>>;
    static MEMO: std::sync::OnceLock<Memo> = std::sync::OnceLock::new();
    let memo = MEMO.get_or_init(Default::default);
    if let Some(&known) = memo
        .lock()
        .ok()
        .and_then(|m| m.get(&en.to_bits()).copied())
        .as_ref()
    {
        return known;
    }
    let cor = integrate_hertz_mindlin_cor(en);
    if let Ok(mut m) = memo.lock() {
        if m.len() >= 1_000_000 {
            m.clear();
        }
        m.insert(en.to_bits(), cor);
    }
    cor
}

fn integrate_hertz_mindlin_cor(en: f64) -> f64 {
    let beta = thornton_damping_ratio(en);
    let unit = DashpotLaw {
        mass: 1.0,
        stiffness: 1.0,
        exponent: 1.5,
        damping: 2.0 * beta * 1.5f64.sqrt(),
        damping_exponent: 0.25,
        clamp_attractive: true,
    };
    accurate_metrics(&unit, 1.0, 1e-13).map_or(f64::NAN, |m| m.cor)
}

/// The `en` to give `Ip2_FrictMat_FrictMat_MindlinPhys` (YADE) or `COEFFICIENT_OF_RESTITUTION`
/// with `DEM_D_Hertz_viscous_Coulomb` (Kratos) so that the law the code builds from it
/// realises the restitution `target`: Thornton's fit alone misses by up to 3.3e-4 for
/// `e <= 0.9` and by 1.1e-2 at 0.99, so the driver inverts the fit through the clamped law
/// (bisection; the realised COR rises monotonically with `en`). The fit does not reach zero
/// damping as `en → 1` (β_n² tends to 2.06e-5, not 0; only `en = 1` itself gives 0), so
/// restitutions between about 0.979 and 1 cannot be realised: `None` for them, and for any
/// other target no `en` in (0, 1] reaches.
// A target of exactly 1 is passed through exactly, as YADE's own `en = 1` special case.
#[allow(clippy::float_cmp)]
pub fn hertz_input_restitution(target: f64) -> Option<f64> {
    // Each inversion integrates the law some sixty times, and a run asks for it several times
    // (sizing, input, law, expected COR): remembered by target, a pure function's results.
    type Memo = std::sync::Mutex<std::collections::HashMap<u64, Option<f64>>>;
    static MEMO: std::sync::OnceLock<Memo> = std::sync::OnceLock::new();
    let memo = MEMO.get_or_init(Default::default);
    if let Some(&known) = memo
        .lock()
        .ok()
        .and_then(|m| m.get(&target.to_bits()).copied())
        .as_ref()
    {
        return known;
    }
    let found = invert_hertz_fit(target);
    if let Ok(mut m) = memo.lock() {
        if m.len() >= 100_000 {
            m.clear();
        }
        m.insert(target.to_bits(), found);
    }
    found
}

fn invert_hertz_fit(target: f64) -> Option<f64> {
    if !(target > 0.0 && target <= 1.0) {
        return None;
    }
    if target >= 1.0 {
        return Some(1.0);
    }
    let (mut lo, mut hi) = (1e-6, 1.0 - 1e-12);
    if hertz_mindlin_cor(lo) > target || hertz_mindlin_cor(hi) < target {
        return None;
    }
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if hertz_mindlin_cor(mid) < target {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Some(0.5 * (lo + hi))
}

/// The damping ratio `ζ = c / (2 sqrt(M k))` at which a linear spring–dashpot whose force is
/// clamped at zero (it never attracts) rebounds with restitution `e`, or `None` below the
/// smallest COR an underdamped clamped dashpot reaches (`e^-2`).
///
/// The force `k y + c ẏ` of the damped oscillation from `y = 0`, `ẏ = v0` first vanishes at
/// `ω t* = π - 2 atan(x)`, `x = ζ / sqrt(1 - ζ²)`, where the speed is `v0 exp(-β t*)`; the body
/// then leaves at that speed, so `-ln e = x (π - 2 atan x)`, which rises monotonically from 0
/// to 2 as `x` goes from 0 to infinity.
pub fn clamped_linear_damping_ratio(restitution: f64) -> Option<f64> {
    if !(restitution > 0.0 && restitution <= 1.0) {
        return None;
    }
    let target = -restitution.ln();
    let g = |x: f64| x * (PI - 2.0 * x.atan());
    if target >= 2.0 {
        return None;
    }
    if target == 0.0 {
        return Some(0.0);
    }
    let mut hi = 1.0;
    while g(hi) < target {
        hi *= 2.0;
    }
    let mut lo = 0.0;
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if g(mid) < target {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let x = 0.5 * (lo + hi);
    Some(x / (1.0 + x * x).sqrt())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The inversion as it was before its evaluations were remembered: every midpoint
    /// integrated afresh.
    fn bisection_afresh(target: f64) -> Option<f64> {
        let (mut lo, mut hi) = (1e-6, 1.0 - 1e-12);
        if integrate_hertz_mindlin_cor(lo) > target || integrate_hertz_mindlin_cor(hi) < target {
            return None;
        }
        for _ in 0..60 {
            let mid = 0.5 * (lo + hi);
            if integrate_hertz_mindlin_cor(mid) < target {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        Some(0.5 * (lo + hi))
    }

    #[test]
    fn remembering_the_law_s_cor_leaves_the_inversion_s_bits() {
        // Targets a sweep of η over [0, 0.9] asks for, and one the fit cannot reach.
        let canonical = crate::model::exact::restitution(0.35);
        for target in [0.2, 0.35, 0.5, canonical, 0.8, 0.9, 0.97, 0.99] {
            assert_eq!(
                invert_hertz_fit(target).map(f64::to_bits),
                bisection_afresh(target).map(f64::to_bits),
                "{target}"
            );
        }
    }
}
