//! The conventions of a build that decide its equivalent setup and its law, where builds of one
//! code differ (a code's release changes the modulus of its wall, adds a damping, rescales a
//! fit): what a build's probe ([`crate::codes::Prober`]) measures and a setup carries
//! ([`crate::codes::CodeSetup::conventions`]). What each convention means for a code's own
//! input, and which builds follow which, lives with the code that has them.

use serde::{Deserialize, Serialize};

/// The effective modulus a wall of Young's modulus `E` and Poisson's ratio `ν` makes with a
/// particle of the same material.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum WallModulus {
    /// `E* = E / (2(1 − ν))` (LAMMPS 29 Sep 2021).
    HalfOverOneMinusNu,
    /// `E* = E / (2(1 − ν²))`, the particle's material on both sides (LAMMPS 22 Jul 2025).
    HalfOverOneMinusNuSquared,
}

/// The damping ratio a Tsuji damping applies for the number `e_in` it is given: a polynomial
/// in `e_in` (Marshall's fit), with or without a factor.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum TsujiFit {
    /// `α = poly(e_in)`, Marshall's fit without the √2 (LAMMPS up to at least 22 Jul 2025).
    Polynomial,
    /// `α = √2 · poly(e_in)` (newer LAMMPS source, lammps PR #5113).
    Sqrt2Polynomial,
}

/// The velocity the dashpot sees in a step.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum DampingVelocity {
    /// `v(n+½)`, after the first half kick (velocity Verlet as LAMMPS writes it).
    HalfStep,
    /// `v(n+1)`.
    FullStep,
}

/// The conventions of one build that decide its equivalent setup and its law.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Conventions {
    /// The wall's effective modulus.
    pub wall_modulus: WallModulus,
    /// Whether the build has a damping given by a coefficient of restitution that applies
    /// `√5 β(e)` (Hertz; LAMMPS' `damping coeff_restitution`).
    pub coeff_restitution: bool,
    /// What the build's Tsuji damping applies.
    pub tsuji_fit: TsujiFit,
    /// Whether a wall started exactly touching (overlap 0) is in contact.
    pub touching_is_contact: bool,
    /// The velocity the dashpot sees.
    pub damping_velocity: DampingVelocity,
}
