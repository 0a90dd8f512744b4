//! The LIGGGHTS-PUBLIC driver (tested on the Debian 12 build of 3.8.0).
//!
//! One input template, `impact.in` in this folder, serves the three scenes, and both builds
//! (the stock models here, the paper's law in [`paper`]):
//! - ball scenes run `model hertz` with `coefficientRestitution` (damped Hertz,
//!   `F = k δ^1.5 + √5 β sqrt(M k) δ^¼ δ̇`);
//! - `rod_end` runs `model hooke/stiffness absolute_damping on`, which takes the spring
//!   constant `kn` and the dashpot `gamman_abs` directly, so both are exactly the rod's.
//!
//! An oblique or spinning impact on the plate adds friction and `tangential history` (both
//! builds; `oblique.rs` in this folder says what it renders and why).
//!
//! The plate is a `wall/gran` primitive with its own atom type (type 2) whose material is mixed
//! into `E*`; the second ball is atom 2. What the installed version really does, and the
//! measurements behind each choice here, are in `reference/liggghts/CONVENTIONS.md`.

pub(crate) mod batch;
pub(crate) mod card;
pub(crate) mod deck;
pub(crate) mod gran;
pub mod mill;
mod oblique;
pub mod paper;

pub(crate) use paper::LiggghtsPaper;

use std::path::Path;

use super::deck::sphere_mass;
use super::parse::{ParseError, parse_columns};
use super::template::{exact_number, fill_template};
use super::{
    BatchRunner, CalibrationCard, CodeDriver, CodeError, CodeName, CodeSetup, Executable,
    LocateError, PaperBuild, ParsedRun, RenderedInput,
};
use crate::model::law::{CodeLaw, DashpotLaw};
use crate::model::scene::{SceneKind, reduced_mass};
use crate::solve::dashpot::CodeFrame;

const TEMPLATE: &str = include_str!("impact.in");
const INPUT_FILE: &str = "impact.in";
/// The trajectory file the template writes (one row per step, plus the initial state).
pub(crate) const TRAJECTORY_FILE: &str = "traj.txt";

/// The gap, m, left between the surfaces at `t = 0` instead of exact contact.
///
/// LIGGGHTS treats touching bodies (overlap exactly 0) as in contact, so a linear dashpot
/// pushes with `c v0` already in the set-up force evaluation, before the first step (measured:
/// rod_end peak overlap 3.6e-4 low). A gap of a millionth of the first step's travel keeps
/// that phantom force out and shifts the trajectory by about 1e-6 of a step; the floor keeps
/// the gap above the rounding of the sphere's position.
pub(crate) fn contact_gap(setup: &CodeSetup) -> f64 {
    let radius = setup.sphere.radius;
    (1e-6 * setup.impact_velocity * setup.timestep).max(1e-13 * radius)
}

/// The effective modulus LIGGGHTS uses for a ball scene, Pa: its `createYeff`,
/// `1/((1-ν1²)/E1 + (1-ν2²)/E2)` over the two atom types (the wall's type included), type 2
/// being the [`CodeSetup::partner_material`]. LIGGGHTS has no rigid wall (the wall type's
/// `(1-ν²)/E` is always added to `1/E*`) and no upper limit on E under `hard_particles yes`:
/// a rigid plate is a stiff type.
pub(crate) fn code_effective_modulus(setup: &CodeSetup) -> Option<f64> {
    let nu1 = setup.sphere.poisson_ratio?;
    let (e2, nu2) = setup.partner_material()?;
    let e1 = setup.sphere.youngs_modulus;
    Some(1.0 / ((1.0 - nu1 * nu1) / e1 + (1.0 - nu2 * nu2) / e2))
}

/// The mass the contact sees, kg: the sphere's own mass at a wall (the wall is immovable),
/// the reduced mass between two spheres.
pub fn code_effective_mass(setup: &CodeSetup) -> f64 {
    let m1 = sphere_mass(setup.sphere.radius, setup.sphere.density);
    let m2 = setup
        .other_sphere
        .map_or(f64::INFINITY, |o| sphere_mass(o.radius, o.density));
    reduced_mass(m1, m2)
}

/// The start of a run of the deck in LIGGGHTS's coordinates: sphere 1 at `r1 + gap` moving
/// down, below it the plate (the plane z = 0) or sphere 2 at `-r2`; the velocities of the
/// centre-of-mass frame and the masses as LIGGGHTS computes them, every number as the deck
/// writes it (exactly).
pub(crate) fn code_frame(setup: &CodeSetup) -> CodeFrame {
    setup.frame_below(setup.sphere.radius + contact_gap(setup), |s| {
        sphere_mass(s.radius, s.density)
    })
}

/// The code's spring constant for `setup`: Hertz `(4/3) E* sqrt(R*)` with its own `E*` for a
/// ball scene (N/m^1.5), the rod's `k` as given (N/m).
pub fn code_stiffness(setup: &CodeSetup) -> f64 {
    match (setup.scene, code_effective_modulus(setup)) {
        (SceneKind::RodEnd, _) | (_, None) => setup.stiffness,
        (_, Some(modulus)) => 4.0 / 3.0 * modulus * setup.pair_radius().sqrt(),
    }
}

/// The contact model lines of a deck: the `model` style, its settings keywords, and the
/// per-type property lines it reads.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct ContactModel {
    /// The style after `model` (`hertz`, `paper`, ...).
    pub style: &'static str,
    /// Its settings keywords (empty for a style that takes none).
    pub settings: String,
    /// The `fix property/global` lines, one per property.
    pub properties: String,
}

/// A `fix property/global NAME peratomtypepair 2` line giving all four pairs of types 1 and 2
/// `value`.
pub(crate) fn pair_property(name: &str, value: &str) -> String {
    format!(
        "fix {name:<22} all property/global {name} peratomtypepair 2 {value} {value} {value} {value}"
    )
}

/// The per-type `youngsModulus` and `poissonsRatio` lines of a ball scene: type 1 the moving
/// sphere, type 2 the plate (or its rigid stand-in) or the second sphere.
pub(crate) fn material_properties(setup: &CodeSetup) -> [String; 2] {
    let nu1 = setup.sphere.poisson_ratio.unwrap_or_default();
    let (e2, nu2) = setup.partner_material().unwrap_or_default();
    [
        format!(
            "fix youngsModulus          all property/global youngsModulus peratomtype {} {}",
            exact_number(setup.sphere.youngs_modulus),
            exact_number(e2)
        ),
        format!(
            "fix poissonsRatio          all property/global poissonsRatio peratomtype {} {}",
            exact_number(nu1),
            exact_number(nu2)
        ),
    ]
}

/// The checks LIGGGHTS itself would fail on, whatever the contact model, and the oblique
/// impacts its tangential model cannot run as the case asks, reported before it is run by
/// `code`.
pub(crate) fn validate_scene(code: &str, setup: &CodeSetup) -> Result<(), CodeError> {
    let unsupported = |reason: String| setup.unsupported(code, reason);
    if !(setup.timestep > 0.0 && setup.impact_velocity > 0.0 && setup.steps > 0) {
        return Err(unsupported(
            "timestep, impact velocity and steps must be positive".into(),
        ));
    }
    if setup.scene == SceneKind::BallBall && setup.other_sphere.is_none() {
        return Err(unsupported("ball_ball needs other_sphere".into()));
    }
    if setup.scene != SceneKind::RodEnd {
        let nu1 = setup.sphere.poisson_ratio;
        let nu2 = setup.partner_material().map(|(_, nu)| nu);
        for nu in [nu1, nu2] {
            match nu {
                Some(nu) if (0.0..=0.5).contains(&nu) => {}
                other => {
                    return Err(unsupported(format!(
                        "LIGGGHTS requires 0 <= poissonsRatio <= 0.5, got {other:?}"
                    )));
                }
            }
        }
    }
    oblique::refuse(code, setup)
}

/// The deck (the template in this folder) for `setup` with `contact`'s model, as run by `code`.
pub(crate) fn render_deck(
    code: &str,
    setup: &CodeSetup,
    contact: &ContactModel,
) -> Result<RenderedInput, CodeError> {
    let (v1, v2) = setup.centre_of_mass_velocities();
    let gap = contact_gap(setup);
    let r1 = setup.sphere.radius;
    // Sphere 1 sits above the contact point at z = 0 and moves down (-z); the plate is
    // the plane z = 0, the second sphere hangs below it.
    let z1 = r1 + gap;
    let sphere_lines = |id: u32, z: f64, radius: f64, density: f64, vz: f64| {
        format!(
            "create_atoms    {id} single 0 0 {} units box\nset             atom {id} diameter {} density {} vz {}",
            exact_number(z),
            exact_number(2.0 * radius),
            exact_number(density),
            exact_number(vz)
        )
    };
    let mut atoms = sphere_lines(1, z1, r1, setup.sphere.density, -v1);
    if let Some(line) = oblique::motion_line(setup) {
        atoms.push('\n');
        atoms.push_str(&line);
    }
    let tangential = oblique::tangential_model(setup);
    let model = contact.style;
    let settings = &contact.settings;
    let (wall, overlap, approach, reach) = match setup.other_sphere {
        Some(other) if setup.scene == SceneKind::BallBall => {
            let r2 = other.radius;
            atoms.push('\n');
            atoms.push_str(&sphere_lines(2, -r2, r2, other.density, -v2));
            (
                "# No wall: the second sphere is atom 2.".to_string(),
                format!("{}-(z[1]-z[2])", exact_number(r1 + r2)),
                "vz[2]-vz[1]".to_string(),
                r1 + r2,
            )
        }
        _ => (
            format!(
                "fix             plate all wall/gran model {model} tangential {tangential} primitive type 2 zplane 0.0 {settings}"
            )
            .trim_end()
            .to_string(),
            format!("{}-z[1]", exact_number(r1)),
            "-vz[1]".to_string(),
            r1,
        ),
    };
    let half = 4.0 * reach
        + setup.impact_velocity * setup.duration()
        + gap
        + oblique::plane_speed_bound(setup) * setup.duration();
    let h = exact_number(half);
    let domain = format!("-{h} {h} -{h} {h} -{h} {h}");
    let values = [
        ("case_name", setup.case_name.clone()),
        ("code", code.to_string()),
        ("scene", setup.scene.name().to_string()),
        ("kind", oblique::kind(setup).to_string()),
        ("about", oblique::about(setup).to_string()),
        ("domain", domain),
        ("skin", exact_number(reach)),
        ("properties", contact.properties.clone()),
        ("model", model.to_string()),
        ("tangential", tangential.to_string()),
        ("settings", settings.clone()),
        ("wall", wall),
        ("timestep", exact_number(setup.timestep)),
        ("atoms", atoms),
        ("overlap", overlap),
        ("approach", approach),
        ("force", "fz[1]".to_string()),
        ("steps", setup.steps.to_string()),
    ];
    let mut text = fill_template(TEMPLATE, &values)
        .map_err(|reason| setup.unsupported(code, reason.to_string()))?;
    if let Some(line) = oblique::printed_line(setup) {
        text.push_str(&line);
        text.push('\n');
    }
    // A style without settings leaves no trailing blank on its lines.
    let lines: Vec<&str> = text.lines().map(str::trim_end).collect();
    Ok(input_file(lines.join("\n") + "\n"))
}

/// The input file holding `text` and the arguments that run it (`-log none`: the default
/// log.liggghts would duplicate the screen output).
fn input_file(text: String) -> RenderedInput {
    RenderedInput {
        file_name: INPUT_FILE.to_string(),
        text,
        args: ["-in", INPUT_FILE, "-log", "none", "-echo", "none"]
            .map(String::from)
            .to_vec(),
    }
}

/// Read a run of the deck in `workdir` (its trajectory file and screen `log`), refusing a run
/// that stopped short of `setup`'s steps.
pub(crate) fn parse_run(
    setup: &CodeSetup,
    workdir: &Path,
    log: &str,
) -> Result<ParsedRun, ParseError> {
    parse_trajectory_file(setup, &workdir.join(TRAJECTORY_FILE), log)
}

/// [`parse_run`] of the trajectory at `path`, with the screen `log` of its run.
pub(crate) fn parse_trajectory_file(
    setup: &CodeSetup,
    path: &Path,
    log: &str,
) -> Result<ParsedRun, ParseError> {
    let text = super::parse::read_output(path.to_path_buf())?;
    let parsed = parse_output(&text, log)?;
    if let Some(ran) = loop_steps(log)
        && ran != setup.steps
    {
        return Err(ParseError::StepCount {
            ran,
            asked: setup.steps,
        });
    }
    Ok(parsed)
}

/// The LIGGGHTS-PUBLIC 3.8.0 driver.
pub struct Liggghts;

impl Liggghts {
    /// The checks LIGGGHTS itself would fail on, reported before it is run.
    fn validate(&self, setup: &CodeSetup) -> Result<(), CodeError> {
        let e = setup.target_restitution;
        if !(e > 0.05 && e <= 1.0) {
            return Err(setup.unsupported(
                self.name(),
                format!("LIGGGHTS requires 0.05 < coefficientRestitution <= 1, got {e}"),
            ));
        }
        validate_scene(self.name(), setup)
    }

    /// The stock contact model of the scene: damped Hertz from `coefficientRestitution` for
    /// the balls, `hooke/stiffness` with the rod's `kn` and dashpot for the rod.
    fn contact_model(&self, setup: &CodeSetup) -> ContactModel {
        let e = exact_number(setup.target_restitution);
        let limit_force = if setup.clamp_attractive { "on" } else { "off" };
        match setup.scene {
            SceneKind::RodEnd => {
                let law = self.dashpot_law(setup);
                let lines = [
                    pair_property("kn", &exact_number(law.stiffness)),
                    pair_property("kt", "0"),
                    pair_property("gamman_abs", &exact_number(law.damping)),
                    pair_property("gammat_abs", "0"),
                    pair_property("coefficientFriction", &oblique::friction(setup)),
                ];
                ContactModel {
                    style: "hooke/stiffness",
                    settings: format!(
                        "absolute_damping on tangential_damping off limitForce {limit_force}"
                    ),
                    properties: lines.join("\n"),
                }
            }
            SceneKind::BallPlate | SceneKind::BallBall => {
                let [young, poisson] = material_properties(setup);
                let lines = [
                    young,
                    poisson,
                    pair_property("coefficientRestitution", &e),
                    pair_property("coefficientFriction", &oblique::friction(setup)),
                ];
                ContactModel {
                    style: "hertz",
                    settings: format!("tangential_damping off limitForce {limit_force}"),
                    properties: lines.join("\n"),
                }
            }
        }
    }

    /// What LIGGGHTS integrates: its own `E*` (wall type mixed in), `R*`, effective mass and
    /// damping; the force is not clamped (`limitForce off`, its default, confirmed by run)
    /// unless the setup asks for `limitForce on`.
    pub fn dashpot_law(&self, setup: &CodeSetup) -> DashpotLaw {
        let mass = code_effective_mass(setup);
        let stiffness = code_stiffness(setup);
        let law = match setup.scene {
            SceneKind::RodEnd => DashpotLaw::linear(mass, stiffness, setup.target_restitution),
            SceneKind::BallPlate | SceneKind::BallBall => {
                DashpotLaw::damped_hertz(mass, stiffness, setup.target_restitution)
            }
        };
        if setup.clamp_attractive {
            law.clamped()
        } else {
            law
        }
    }
}

impl CodeDriver for Liggghts {
    fn card(&self) -> Option<&dyn CalibrationCard> {
        Some(&card::LiggghtsCard)
    }

    fn deck(&self) -> Option<&dyn super::deck::DeckReader> {
        Some(&deck::LiggghtsDeck)
    }

    /// A deck that selects `model paper` (or `paper/linear`) runs in liggghts-paper, the build
    /// that has the model: the stock build stops on it.
    fn paper_build(&self) -> Option<PaperBuild> {
        Some(PaperBuild {
            code: CodeName::LiggghtsPaper,
            selection: "normal model ",
            lacks: "the stock liggghts build lacks the paper's model",
            instead: "--code liggghts-paper, or no --code (a deck that selects model paper runs in liggghts-paper)",
        })
    }

    fn mill_paper_build(&self) -> Option<CodeName> {
        Some(CodeName::LiggghtsPaper)
    }

    fn name(&self) -> &'static str {
        "liggghts"
    }

    fn binary(&self) -> &'static str {
        "liggghts"
    }

    /// The executable as the default locates it, started without Open MPI's daemon
    /// (`Executable::open_mpi_alone`).
    fn locate(&self) -> Result<Executable, LocateError> {
        super::runner::locate_override_or_path(self.name(), self.binary())
            .map(Executable::open_mpi_alone)
    }

    fn render(&self, setup: &CodeSetup) -> Result<RenderedInput, CodeError> {
        self.validate(setup)?;
        render_deck(self.name(), setup, &self.contact_model(setup))
    }

    fn parse(&self, setup: &CodeSetup, workdir: &Path, log: &str) -> Result<ParsedRun, ParseError> {
        parse_run(setup, workdir, log)
    }

    fn batch(&self) -> Option<&dyn BatchRunner> {
        Some(&batch::LIGGGHTS_BATCH)
    }

    /// A ball on the plate with `tangential history` (the Mindlin spring, no dashpot): the
    /// lines in `oblique.rs`.
    fn runs_oblique(&self) -> bool {
        true
    }

    fn law(&self, setup: &CodeSetup) -> CodeLaw {
        self.dashpot_law(setup).into()
    }

    fn frame(&self, setup: &CodeSetup) -> Option<CodeFrame> {
        Some(code_frame(setup))
    }
}

/// Parse the trajectory file written by the template and the screen log of a LIGGGHTS run.
///
/// Each trajectory row is `time overlap approach_velocity normal_force`; the log gives the
/// version (first line, `LIGGGHTS (Version …)`) and the `Loop time of` figure.
pub(crate) fn parse_output(trajectory: &str, log: &str) -> Result<ParsedRun, ParseError> {
    let out = parse_columns(trajectory, TRAJECTORY_FILE)?;
    if out.time.is_empty() {
        return Err(ParseError::Empty {
            file: TRAJECTORY_FILE.to_string(),
        });
    }
    Ok(ParsedRun {
        trajectory: out,
        loop_time: loop_time(log),
        version: version(log),
    })
}

/// The version as LIGGGHTS prints it on its first line, e.g.
/// `LIGGGHTS-PUBLIC 3.8.0, compiled 2022-01-26-19:42:32 by buildd, git commit unknown`.
pub(crate) fn version(log: &str) -> Option<String> {
    let start = log.find("LIGGGHTS (Version ")? + "LIGGGHTS (Version ".len();
    let rest = &log[start..];
    let end = rest.find(")\n").or_else(|| rest.find(')'))?;
    Some(rest[..end].trim().to_string())
}

/// The `Loop time of <seconds> on <n> procs for <steps> steps` figure, s.
pub(crate) fn loop_time(log: &str) -> Option<f64> {
    loop_line(log)?.first()?.parse().ok()
}

fn loop_steps(log: &str) -> Option<u64> {
    let words = loop_line(log)?;
    let at = words.iter().position(|w| *w == "for")?;
    words.get(at + 1)?.parse().ok()
}

/// The words after `Loop time of` on the last such line.
fn loop_line(log: &str) -> Option<Vec<&str>> {
    let line = log.lines().rev().find(|l| l.starts_with("Loop time of "))?;
    Some(line["Loop time of ".len()..].split_whitespace().collect())
}

#[cfg(test)]
mod tests {
    use super::{loop_time, parse_output};
    use crate::model::trajectory::trajectory_metrics;

    // The parser, on a recorded run (tests/data/liggghts: ball on a rigid plate, e = 0.693889,
    // 40 steps per contact time, input impact.in as rendered by the driver).

    const SAMPLE_TRAJECTORY: &str = include_str!("../../../tests/data/liggghts/traj.txt");
    const SAMPLE_LOG: &str = include_str!("../../../tests/data/liggghts/log.txt");

    // The recorded first row is written exactly: t = 0, v = v0, F = 0.
    #[allow(clippy::float_cmp)]
    #[test]
    fn parser_reads_the_recorded_sample() {
        let parsed = parse_output(SAMPLE_TRAJECTORY, SAMPLE_LOG).unwrap();
        let t = &parsed.trajectory;
        assert_eq!(t.time.len(), 47);
        assert_eq!(t.overlap.len(), 47);
        assert_eq!(t.approach_velocity.len(), 47);
        assert_eq!(t.normal_force.len(), 47);
        assert_eq!(t.time[0], 0.0);
        assert_eq!(t.approach_velocity[0], 2.0);
        assert_eq!(t.normal_force[0], 0.0);
        assert!(
            t.overlap[0] < 0.0 && t.overlap[0] > -1e-11,
            "start gap {}",
            t.overlap[0]
        );
        assert_eq!(
            parsed.version.as_deref(),
            Some(
                "LIGGGHTS-PUBLIC 3.8.0, compiled 2022-01-26-19:42:32 by buildd, git commit unknown"
            )
        );
        assert_eq!(parsed.loop_time, Some(0.000_179_447));
        let m = trajectory_metrics(t).unwrap();
        // Coarse steps (40 per contact) still give the target COR to a few 1e-3.
        assert!(
            (m.cor - (0.65f64 / 1.35).sqrt()).abs() < 5e-3,
            "COR {}",
            m.cor
        );
        assert!(m.peak_deformation > 5.4e-5 && m.peak_deformation < 5.6e-5);
    }

    #[test]
    fn parser_rejects_a_short_row() {
        let err = parse_output("0 0 2 0\n1e-7 2e-7 1.99\n", SAMPLE_LOG)
            .unwrap_err()
            .to_string();
        assert!(err.contains("expected 4 columns"), "{err}");
        assert!(parse_output("", SAMPLE_LOG).is_err());
        assert_eq!(loop_time("no loop here"), None);
    }
}
