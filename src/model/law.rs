//! Contact laws: the paper's hysteretic law and the viscous laws the DEM codes run.
//!
//! Sign convention (used everywhere in the crate): `y` is the approach of the two centres of
//! mass, positive in compression; `ẏ > 0` while the bodies approach. A force is positive when it
//! pushes the bodies apart, so the equation of motion is `M ÿ = -F(y, ẏ)`.

use serde::{Deserialize, Serialize};

/// The paper's law: `F = C |y|^n (1 + η sign(ẏ))` while in contact.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct PaperLaw {
    /// Reduced mass `M`, kg.
    pub mass: f64,
    /// Contact stiffness `C`, N/m^n.
    pub stiffness: f64,
    /// Exponent `n` of the elastic force (1.5 Hertz, 1 linear).
    pub exponent: f64,
    /// Loss coefficient `η`, dimensionless, in [0, 1).
    pub loss_coefficient: f64,
}

impl PaperLaw {
    /// Elastic peak deformation `δ0 = [(n+1) M v0² / (2C)]^(1/(n+1))`, m: the length scale of
    /// the dimensionless form.
    pub fn elastic_peak(&self, impact_velocity: f64) -> f64 {
        let n = self.exponent;
        ((n + 1.0) * self.mass * impact_velocity * impact_velocity / (2.0 * self.stiffness))
            .powf(1.0 / (n + 1.0))
    }

    /// Total contact force, N, at approach `y` (m) and approach rate `v` (m/s), unilateral.
    pub fn force(&self, y: f64, v: f64) -> f64 {
        if y <= 0.0 {
            return 0.0;
        }
        let elastic = self.stiffness * y.powf(self.exponent);
        elastic * (1.0 + self.loss_coefficient * v.signum())
    }
}

/// A viscoelastic (spring–dashpot) law, the family the DEM codes use:
/// `F = k y^n + c y^m ẏ`, optionally clamped so that it never attracts.
///
/// Damped Hertz (LIGGGHTS `hertz`, YADE Hertz–Mindlin, LAMMPS `hertz/material`) has `n = 1.5`,
/// `m = 0.25`; the linear spring–dashpot has `n = 1`, `m = 0`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct DashpotLaw {
    /// Mass the dynamics sees, kg (the reduced mass of the pair).
    pub mass: f64,
    /// Spring constant `k`, N/m^n.
    pub stiffness: f64,
    /// Exponent `n` of the spring force.
    pub exponent: f64,
    /// Dashpot coefficient `c`, N·s/m^(1+m).
    pub damping: f64,
    /// Exponent `m` of the overlap factor of the dashpot.
    pub damping_exponent: f64,
    /// Whether the code cuts the force at zero instead of letting it attract.
    pub clamp_attractive: bool,
}

impl DashpotLaw {
    /// Total contact force, N, at approach `y` (m) and approach rate `v` (m/s).
    pub fn force(&self, y: f64, v: f64) -> f64 {
        if y <= 0.0 {
            return 0.0;
        }
        let f = self.stiffness * y.powf(self.exponent)
            + self.damping * y.powf(self.damping_exponent) * v;
        if self.clamp_attractive { f.max(0.0) } else { f }
    }

    /// Elastic peak deformation of the undamped spring at speed `v0`, m.
    pub(crate) fn elastic_peak(&self, impact_velocity: f64) -> f64 {
        let n = self.exponent;
        ((n + 1.0) * self.mass * impact_velocity * impact_velocity / (2.0 * self.stiffness))
            .powf(1.0 / (n + 1.0))
    }

    /// Damping ratio `β = -ln e / sqrt(ln² e + π²)` that the damped-Hertz and linear dashpot
    /// laws use to realise a restitution `e` (0 < e ≤ 1).
    pub fn damping_ratio(restitution: f64) -> f64 {
        let l = restitution.ln();
        -l / (l * l + std::f64::consts::PI * std::f64::consts::PI).sqrt()
    }

    /// The damped Hertz law that realises restitution `e` without a clamp:
    /// `c = √5 β sqrt(M k)` (LIGGGHTS' `2 sqrt(5/6) β sqrt(S_n m*)` with `S_n = 2 E* sqrt(R* δ)`).
    pub fn damped_hertz(mass: f64, stiffness: f64, restitution: f64) -> Self {
        let beta = Self::damping_ratio(restitution);
        DashpotLaw {
            mass,
            stiffness,
            exponent: 1.5,
            damping: 5f64.sqrt() * beta * (mass * stiffness).sqrt(),
            damping_exponent: 0.25,
            clamp_attractive: false,
        }
    }

    /// The linear spring–dashpot that realises restitution `e` without a clamp:
    /// `c = 2 ζ sqrt(M k)`, `e = exp(-π ζ / sqrt(1 - ζ²))`.
    pub fn linear(mass: f64, stiffness: f64, restitution: f64) -> Self {
        let zeta = Self::damping_ratio(restitution);
        DashpotLaw {
            mass,
            stiffness,
            exponent: 1.0,
            damping: 2.0 * zeta * (mass * stiffness).sqrt(),
            damping_exponent: 0.0,
            clamp_attractive: false,
        }
    }

    /// The same law with the attractive force cut at zero.
    pub fn clamped(self) -> Self {
        DashpotLaw {
            clamp_attractive: true,
            ..self
        }
    }

    /// The damping ratio `ζ = c/(2√(M k))` of a linear spring with a constant dashpot, not
    /// clamped, damped at or beyond critical (`ζ ≥ 1`): from touch such a pair approaches and
    /// then creeps back towards zero overlap without ever reaching it, so its bodies never
    /// separate and its contact has no end. `None` for any other law.
    pub fn never_separates(&self) -> Option<f64> {
        let linear = (self.exponent - 1.0).abs() < 1e-12 && self.damping_exponent.abs() < 1e-12;
        let zeta = self.damping / (2.0 * (self.mass * self.stiffness).sqrt());
        (linear && !self.clamp_attractive && zeta >= 1.0).then_some(zeta)
    }
}

impl PaperLaw {
    /// The force, N, as a DEM code's contact model evaluates it (LIGGGHTS `model paper` of
    /// scripts/liggghts-paper): `C yⁿ (1 + η sign ẏ)` with `sign(0) = 0`, so that a velocity of
    /// exactly zero gives the elastic force alone, the mean of the two branches (where
    /// [`PaperLaw::force`] follows `f64::signum`, which has no zero).
    pub(crate) fn force_as_coded(&self, y: f64, v: f64) -> f64 {
        if y <= 0.0 {
            return 0.0;
        }
        let branch = if v > 0.0 {
            1.0 + self.loss_coefficient
        } else if v < 0.0 {
            1.0 - self.loss_coefficient
        } else {
            1.0
        };
        self.stiffness * y.powf(self.exponent) * branch
    }
}

/// A contact force as a DEM code evaluates it, and the mass it acts on: what stepping a law
/// the way a code steps needs.
pub trait ContactForce {
    /// Force, N (positive repulsive), at approach `y` (m) and approach rate `v` (m/s).
    fn force(&self, y: f64, v: f64) -> f64;
    /// Mass the dynamics sees, kg.
    fn mass(&self) -> f64;
}

impl ContactForce for DashpotLaw {
    fn force(&self, y: f64, v: f64) -> f64 {
        DashpotLaw::force(self, y, v)
    }

    fn mass(&self) -> f64 {
        self.mass
    }
}

/// The law a DEM code integrates, as its driver reads it: a spring–dashpot (the codes' own
/// damping), or the paper's law where the code has it built in (liggghts-paper).
///
/// Serialised as the inner law alone (a stored record's `law` object keeps its shape); the two
/// are told apart by their fields (`damping` against `loss_coefficient`).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(untagged)]
pub enum CodeLaw {
    /// `F = k yⁿ + c yᵐ ẏ`, clamped or not.
    Dashpot(DashpotLaw),
    /// `F = C yⁿ (1 + η sign ẏ)`, evaluated as `PaperLaw::force_as_coded`.
    Paper(PaperLaw),
}

impl From<DashpotLaw> for CodeLaw {
    fn from(law: DashpotLaw) -> Self {
        CodeLaw::Dashpot(law)
    }
}

impl From<PaperLaw> for CodeLaw {
    fn from(law: PaperLaw) -> Self {
        CodeLaw::Paper(law)
    }
}

impl ContactForce for CodeLaw {
    fn force(&self, y: f64, v: f64) -> f64 {
        match self {
            CodeLaw::Dashpot(law) => law.force(y, v),
            CodeLaw::Paper(law) => law.force_as_coded(y, v),
        }
    }

    fn mass(&self) -> f64 {
        match self {
            CodeLaw::Dashpot(law) => law.mass,
            CodeLaw::Paper(law) => law.mass,
        }
    }
}

impl CodeLaw {
    /// Spring constant `k` (or `C`), N/m^n.
    pub(crate) fn stiffness(&self) -> f64 {
        match self {
            CodeLaw::Dashpot(law) => law.stiffness,
            CodeLaw::Paper(law) => law.stiffness,
        }
    }

    /// Exponent `n` of the elastic force.
    pub(crate) fn exponent(&self) -> f64 {
        match self {
            CodeLaw::Dashpot(law) => law.exponent,
            CodeLaw::Paper(law) => law.exponent,
        }
    }

    /// Whether the code cuts the force at zero (the paper's law never attracts: no clamp).
    pub fn clamp_attractive(&self) -> bool {
        match self {
            CodeLaw::Dashpot(law) => law.clamp_attractive,
            CodeLaw::Paper(_) => false,
        }
    }

    /// The same law with the attractive force cut at zero (the paper's law as it is: its
    /// force never attracts).
    pub(crate) fn clamped(self) -> Self {
        match self {
            CodeLaw::Dashpot(law) => CodeLaw::Dashpot(law.clamped()),
            paper @ CodeLaw::Paper(_) => paper,
        }
    }

    /// The spring–dashpot, if this is one.
    pub fn dashpot(&self) -> Option<&DashpotLaw> {
        match self {
            CodeLaw::Dashpot(law) => Some(law),
            CodeLaw::Paper(_) => None,
        }
    }

    /// Whether two laws are of one kind with every parameter equal to `rtol` (relative).
    pub(crate) fn agrees_with(&self, other: &CodeLaw, rtol: f64) -> bool {
        let same = |a: f64, b: f64| (a - b).abs() <= rtol * a.abs().max(b.abs());
        match (self, other) {
            (CodeLaw::Dashpot(a), CodeLaw::Dashpot(b)) => {
                same(a.mass, b.mass)
                    && same(a.stiffness, b.stiffness)
                    && same(a.exponent, b.exponent)
                    && same(a.damping, b.damping)
                    && same(a.damping_exponent, b.damping_exponent)
                    && a.clamp_attractive == b.clamp_attractive
            }
            (CodeLaw::Paper(a), CodeLaw::Paper(b)) => {
                same(a.mass, b.mass)
                    && same(a.stiffness, b.stiffness)
                    && same(a.exponent, b.exponent)
                    && same(a.loss_coefficient, b.loss_coefficient)
            }
            _ => false,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn paper() -> PaperLaw {
        PaperLaw {
            mass: 2.0,
            stiffness: 8.0,
            exponent: 1.5,
            loss_coefficient: 0.25,
        }
    }

    // Powers of two and small integers: every force here is exact.
    #[allow(clippy::float_cmp)]
    #[test]
    fn the_coded_force_has_a_sign_that_vanishes_at_rest() {
        let law = paper();
        // y = 4: C y^1.5 = 64.
        assert_eq!(law.force_as_coded(4.0, 1.0), 80.0);
        assert_eq!(law.force_as_coded(4.0, -1.0), 48.0);
        assert_eq!(law.force_as_coded(4.0, 0.0), 64.0);
        assert_eq!(law.force_as_coded(4.0, -0.0), 64.0);
        assert_eq!(law.force_as_coded(0.0, 1.0), 0.0);
        assert_eq!(law.force_as_coded(-1.0, 1.0), 0.0);
        // Away from rest it is the law's own force.
        assert_eq!(law.force_as_coded(4.0, -3.0), law.force(4.0, -3.0));
        let coded = CodeLaw::from(law);
        assert_eq!(ContactForce::force(&coded, 4.0, 0.0), 64.0);
        assert_eq!(coded.mass(), 2.0);
    }

    #[test]
    fn a_code_law_is_stored_as_its_inner_law_and_read_back_as_its_kind() {
        let dashpot = CodeLaw::from(DashpotLaw::damped_hertz(1.0, 2.0, 0.7));
        let paper = CodeLaw::from(paper());
        for law in [dashpot, paper] {
            let json = serde_json::to_value(law).unwrap();
            assert!(json.get("mass").is_some(), "{json}");
            assert_eq!(serde_json::from_value::<CodeLaw>(json).unwrap(), law);
        }
        assert!(
            serde_json::to_value(paper)
                .unwrap()
                .get("damping")
                .is_none()
        );
        assert!(paper.agrees_with(&paper, 0.0));
        assert!(!paper.agrees_with(&dashpot, 1.0));
        let other = CodeLaw::Paper(PaperLaw {
            loss_coefficient: 0.25 * (1.0 + 1e-9),
            ..self::paper()
        });
        assert!(!paper.agrees_with(&other, 1e-12) && paper.agrees_with(&other, 1e-8));
        // The paper's law never attracts: clamping leaves it as it is.
        assert_eq!(paper.clamped(), paper);
        assert!(!paper.clamp_attractive() && dashpot.clamped().clamp_attractive());
    }
}
