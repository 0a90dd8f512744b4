//! The damping the codes derive from a restitution coefficient, shared by the drivers whose
//! codes use it: Thornton et al.'s fit for damped Hertz (YADE's `Ip2_FrictMat_FrictMat_MindlinPhys`
//! and Kratos' `DEM_D_Hertz_viscous_Coulomb` both take `en` through it), the `en` that makes the
//! clamped law realise a target, and the damping ratio of a clamped linear dashpot; and the
//! clamped laws those two codes build from them, with what the codes refuse and what they
//! realise.

use std::collections::HashMap;
use std::f64::consts::PI;
use std::sync::{Mutex, OnceLock};

use super::{CodeError, CodeSetup};
use crate::model::law::DashpotLaw;
use crate::model::scene::SceneKind;
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
/// Remembered by `en`: every inversion below starts by checking the ends of the domain, the
/// same two values for every target, and the root finder reads its bracket's ends again.
fn hertz_mindlin_cor(en: f64) -> f64 {
    static MEMO: Memo<f64> = OnceLock::new();
    remembered(&MEMO, en, 1_000_000, integrate_hertz_mindlin_cor)
}

/// A pure function's results kept by the bits of its argument.
type Memo<T> = OnceLock<Mutex<HashMap<u64, T>>>;

/// `compute(x)`, kept in `memo` by the bits of `x` and read from it when asked again; a memo
/// that holds `most` results is emptied before it takes another.
fn remembered<T: Copy>(memo: &Memo<T>, x: f64, most: usize, compute: impl FnOnce(f64) -> T) -> T {
    let memo = memo.get_or_init(Default::default);
    if let Some(known) = memo.lock().ok().and_then(|m| m.get(&x.to_bits()).copied()) {
        return known;
    }
    let value = compute(x);
    if let Ok(mut m) = memo.lock() {
        if m.len() >= most {
            m.clear();
        }
        m.insert(x.to_bits(), value);
    }
    value
}

fn integrate_hertz_mindlin_cor(en: f64) -> f64 {
    let unit = clamped_hertz_law(1.0, 1.0, thornton_damping_ratio(en));
    accurate_metrics(&unit, 1.0, INVERSION_RTOL).map_or(f64::NAN, |m| m.cor)
}

/// The relative tolerance the law's COR is integrated at while the fit is inverted.
const INVERSION_RTOL: f64 = 1e-13;

/// The inversion's domain: the smallest and largest `en` tried (the fit is not used at 0;
/// at 1 exactly YADE switches the damping off, see [`thornton_damping_ratio`]).
const EN_DOMAIN: (f64, f64) = (1e-6, 1.0 - 1e-12);

/// How narrow the bracket on `en` gets before the inversion stops: below what the integration
/// at [`INVERSION_RTOL`] resolves (its COR moves by about 1e-13 between neighbouring
/// tolerances' runs, and the COR rises with `en` at a slope of about one or less).
const EN_TOLERANCE: f64 = 1e-14;

/// Stops the root finder once its bracket is [`EN_TOLERANCE`] wide (or it hits the target's
/// COR exactly), or after as many steps as halving the domain to it would take twice over.
struct BracketWidth;

impl roots::Convergency<f64> for BracketWidth {
    // An exact zero of the miss is the one value that ends the search on `y` alone.
    #[allow(clippy::float_cmp)]
    fn is_root_found(&mut self, miss: f64) -> bool {
        miss == 0.0
    }

    fn is_converged(&mut self, a: f64, b: f64) -> bool {
        (a - b).abs() <= EN_TOLERANCE
    }

    fn is_iteration_limit_reached(&mut self, iterations: usize) -> bool {
        iterations >= 100
    }
}

/// The `en` to give `Ip2_FrictMat_FrictMat_MindlinPhys` (YADE) or `COEFFICIENT_OF_RESTITUTION`
/// with `DEM_D_Hertz_viscous_Coulomb` (Kratos) so that the law the code builds from it
/// realises the restitution `target`: Thornton's fit alone misses by up to 3.3e-4 for
/// `e <= 0.9` and by 1.1e-2 at 0.99, so the driver inverts the fit through the clamped law
/// (the realised COR rises monotonically with `en`). The fit does not reach zero
/// damping as `en → 1` (β_n² tends to 2.06e-5, not 0; only `en = 1` itself gives 0), so
/// restitutions between about 0.985 and 1 cannot be realised: `None` for them, and for any
/// other target no `en` in (0, 1] reaches.
// A target of exactly 1 is passed through exactly, as YADE's own `en = 1` special case.
#[allow(clippy::float_cmp)]
pub fn hertz_input_restitution(target: f64) -> Option<f64> {
    // Each inversion integrates the law some eight times, and a run asks for it several times
    // (sizing, input, law, expected COR): remembered by target, a pure function's results.
    static MEMO: Memo<Option<f64>> = OnceLock::new();
    remembered(&MEMO, target, 100_000, invert_hertz_fit)
}

/// Thornton's fit inverted through the clamped law: a bracket around the fit's own answer,
/// narrowed by the Illinois variant of regula falsi (superlinear, and it keeps the root
/// bracketed however noisy the last digits of the integrated COR are).
// Exact zeros of the miss end the search: the one value whose sign is no guide.
#[allow(clippy::float_cmp)]
fn invert_hertz_fit(target: f64) -> Option<f64> {
    if !(target > 0.0 && target <= 1.0) {
        return None;
    }
    if target >= 1.0 {
        return Some(1.0);
    }
    let (lo, hi) = EN_DOMAIN;
    if !(hertz_mindlin_cor(lo) <= target && hertz_mindlin_cor(hi) >= target) {
        return None;
    }
    let miss = |en: f64| hertz_mindlin_cor(en) - target;
    // The fit's own answer misses by a few 1e-4 (by 1e-2 towards 0.98): from there, step
    // against the miss by twice it, four times farther each time, until the miss changes
    // sign. It does within the domain, whose ends bracket the target; each step at least
    // quadruples, so a few dozen reach across it from any miss a double holds.
    let mut a = target.clamp(lo, hi);
    let mut at_a = miss(a);
    let mut step = 2.0 * at_a.abs();
    let b = loop {
        if at_a == 0.0 {
            return Some(a);
        }
        if !at_a.is_finite() || step > 4.0 {
            return None;
        }
        let b = (a - at_a.signum() * step).clamp(lo, hi);
        let at_b = miss(b);
        if at_b.is_finite() && at_b.signum() != at_a.signum() {
            break b;
        }
        (a, at_a, step) = (b, at_b, 4.0 * step.max(f64::EPSILON));
    };
    roots::find_root_regula_falsi(a, b, miss, &mut BracketWidth).ok()
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
    let x = bisect(0.0, hi, 200, |x| g(x) < target);
    Some(x / (1.0 + x * x).sqrt())
}

/// The middle of `[lo, hi]` after `halvings` halvings towards where `below` changes from true
/// (below the root) to false.
fn bisect(mut lo: f64, mut hi: f64, halvings: usize, below: impl Fn(f64) -> bool) -> f64 {
    for _ in 0..halvings {
        let mid = 0.5 * (lo + hi);
        if below(mid) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

/// Clamped damped Hertz of damping ratio `beta` (Thornton's `β_n`, Kratos' `γ`):
/// `F = k y^1.5 + 2 β sqrt(1.5 M k) y^0.25 ẏ`, never attractive, as YADE's
/// `Law2_ScGeom_MindlinPhys_Mindlin` and Kratos' `DEM_D_Hertz_viscous_Coulomb` integrate it.
pub(crate) fn clamped_hertz_law(mass: f64, stiffness: f64, beta: f64) -> DashpotLaw {
    DashpotLaw {
        mass,
        stiffness,
        exponent: 1.5,
        // β times the critical damping of the tangent stiffness 1.5 k y^0.5.
        damping: 2.0 * beta * (1.5 * mass * stiffness).sqrt(),
        damping_exponent: 0.25,
        clamp_attractive: true,
    }
}

/// The linear spring–dashpot `F = k y + 2 ζ sqrt(M k) ẏ` of damping ratio `zeta`, never
/// attractive (YADE's `ViscElPhys`, Kratos' `DEM_D_Linear_Custom_Constants`).
pub(crate) fn clamped_linear_law(mass: f64, stiffness: f64, zeta: f64) -> DashpotLaw {
    DashpotLaw {
        damping: 2.0 * zeta * (mass * stiffness).sqrt(),
        ..DashpotLaw::linear(mass, stiffness, 1.0).clamped()
    }
}

/// The damping ratio of the clamped linear dashpot that realises `setup`'s target
/// ([`clamped_linear_damping_ratio`]), saturated at 1 for a restitution it cannot reach (which
/// [`refuse_for_clamped_law`] refuses before a run).
pub(crate) fn rod_damping_ratio(setup: &CodeSetup) -> f64 {
    clamped_linear_damping_ratio(setup.target_restitution).unwrap_or(1.0)
}

/// The `en` a code with Thornton's fit is given for `setup` ([`hertz_input_restitution`]), or
/// the target itself where no `en` realises it.
pub(crate) fn hertz_input_or_target(setup: &CodeSetup) -> f64 {
    hertz_input_restitution(setup.target_restitution).unwrap_or(setup.target_restitution)
}

/// What a code whose clamped laws take their damping from the restitution (YADE, Kratos)
/// refuses before it runs as `code`: a restitution outside `(0, 1]`, no positive time step or
/// no steps, a ball pair without its second ball, and a rod's restitution below what its
/// clamped linear law (`linear_law`, as the code names it) reaches.
pub(crate) fn refuse_for_clamped_law(
    code: &str,
    setup: &CodeSetup,
    linear_law: &str,
) -> Result<(), CodeError> {
    let e = setup.target_restitution;
    if !(e > 0.0 && e <= 1.0) {
        return Err(setup.unsupported(code, format!("restitution {e} outside (0, 1]")));
    }
    setup.refuse_unrunnable(code)?;
    match setup.scene {
        SceneKind::RodEnd if clamped_linear_damping_ratio(e).is_none() => Err(setup.unsupported(
            code,
            format!(
                "{linear_law} clamps its force, and an underdamped clamped linear dashpot \
                     cannot rebound with e = {e} < exp(-2)"
            ),
        )),
        _ => Ok(()),
    }
}

/// How far the COR of a law built through Thornton's fit may lie from the target before
/// [`fit_restitution`] reports it: the fit is good to a few 1e-4 for `e ≤ 0.9` and fails
/// towards `e → 1`.
pub(crate) const RESTITUTION_FIT_TOLERANCE: f64 = 1e-3;

/// The COR `law`, the code's law for `setup`, realises where it lies more than
/// [`RESTITUTION_FIT_TOLERANCE`] from the target (the `CodeDriver::expected_restitution` of YADE
/// and Kratos): for a ball scene, whose damping comes through Thornton's fit; never for the
/// rod, whose damping is solved for the clamped law and realises the target.
pub(crate) fn fit_restitution(setup: &CodeSetup, law: &DashpotLaw) -> Option<f64> {
    if setup.scene == SceneKind::RodEnd {
        return None;
    }
    let cor = accurate_metrics(law, setup.impact_velocity, 1e-10)
        .ok()?
        .cor;
    ((cor - setup.target_restitution).abs() > RESTITUTION_FIT_TOLERANCE).then_some(cor)
}

#[cfg(test)]
mod tests {
    use super::*;
    use rayon::prelude::*;

    /// The inversion as it was before: sixty halvings of the whole domain, every midpoint
    /// integrated afresh.
    fn bisection(target: f64) -> Option<f64> {
        let (lo, hi) = EN_DOMAIN;
        if integrate_hertz_mindlin_cor(lo) > target || integrate_hertz_mindlin_cor(hi) < target {
            return None;
        }
        Some(bisect(lo, hi, 60, |en| {
            integrate_hertz_mindlin_cor(en) < target
        }))
    }

    /// The COR of the law a code builds from `en` for a steel ball on a plate, integrated
    /// apart from the inversion: at its own scale and speed, at relative tolerance 1e-15,
    /// where the COR has converged to about 1e-13.
    fn realised_cor(en: f64) -> f64 {
        let law = clamped_hertz_law(0.26, 2.0e10, thornton_damping_ratio(en));
        accurate_metrics(&law, 1.3, 1e-15).unwrap().cor
    }

    /// The inversion's own miss (the COR it integrates at the `en` it returns against the
    /// target) is below 1e-13; against a converged integration the miss is the integration's
    /// own error at [`INVERSION_RTOL`], up to about 4e-12 (measured: 3.7e-12 near e = 0.95),
    /// which the sixty halvings shared.
    #[test]
    fn the_returned_en_realises_every_reachable_target() {
        let (lo, hi) = EN_DOMAIN;
        let (least, most) = (
            integrate_hertz_mindlin_cor(lo),
            integrate_hertz_mindlin_cor(hi),
        );
        assert!(
            least < 0.03 && (0.98..0.99).contains(&most),
            "{least} {most}"
        );
        // 300 targets across all the fit reaches, its ends included.
        let worst = (0..=300)
            .into_par_iter()
            .map(|i| {
                let target = least + (most - least) * f64::from(i) / 300.0;
                let en = invert_hertz_fit(target).unwrap();
                assert!((lo..=hi).contains(&en), "{target}: {en}");
                (
                    (integrate_hertz_mindlin_cor(en) - target).abs(),
                    (realised_cor(en) - target).abs(),
                )
            })
            .reduce(|| (0.0, 0.0), |a, b| (a.0.max(b.0), a.1.max(b.1)));
        assert!(
            worst.0 <= 1e-13,
            "worst miss of the inversion's own COR {:e}",
            worst.0
        );
        assert!(
            worst.1 <= 5e-12,
            "worst miss of the converged COR {:e}",
            worst.1
        );
    }

    #[test]
    fn the_inversion_agrees_with_sixty_halvings() {
        // Targets a sweep of η over [0, 0.9] asks for, and near the top of the fit's reach.
        let canonical = crate::model::exact::restitution(0.35);
        [0.2, 0.35, 0.5, canonical, 0.8, 0.9, 0.97, 0.98]
            .into_par_iter()
            .for_each(|target| {
                let (found, halved) = (
                    invert_hertz_fit(target).unwrap(),
                    bisection(target).unwrap(),
                );
                assert!(
                    (found - halved).abs() <= 1e-12,
                    "{target}: {found} against {halved}"
                );
            });
    }

    #[test]
    fn targets_the_fit_cannot_reach_have_no_en() {
        let (_, hi) = EN_DOMAIN;
        let most = integrate_hertz_mindlin_cor(hi);
        for target in [
            0.0,
            -0.5,
            1.5,
            f64::NAN,
            0.5 * (most + 1.0),
            0.99,
            0.999_999,
        ] {
            assert_eq!(invert_hertz_fit(target), None, "{target}");
        }
        assert_eq!(invert_hertz_fit(1.0), Some(1.0));
        assert_eq!(
            invert_hertz_fit(integrate_hertz_mindlin_cor(EN_DOMAIN.0) / 2.0),
            None
        );
    }
}
