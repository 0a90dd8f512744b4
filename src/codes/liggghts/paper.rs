//! The driver of LIGGGHTS with the paper's law built in (`liggghts-paper`): LIGGGHTS-PUBLIC
//! 3.8.0 from Debian's source with the normal models of `scripts/liggghts-paper/normal_model_paper.h`,
//! a serial build installed by `scripts/build-liggghts-paper.sh` into
//! `<codes>/liggghts-paper/bin/liggghts-paper`.
//!
//! It runs the stock LIGGGHTS deck (`super::render_deck`) with the contact lines changed:
//! - ball scenes run `model paper` (`F = C yⁿ (1 + η sign ẏ)`, `C = (4/3) E* sqrt(R*)` formed as
//!   `model hertz` forms its stiffness) with the per-type-pair `lossCoefficient` η;
//! - `rod_end` runs `model paper/linear` with the rod's `kn` and η.
//!
//! The styles take no settings keywords (no `limitForce`: the force never attracts, so a clamp
//! is refused), and η is given itself, not a COR: the setup carries the case's η exactly. The
//! code's own law is the paper's law ([`CodeLaw::Paper`]), so its model difference is zero by
//! construction and what it differs by is its integration: velocity Verlet with the branch
//! chosen by the sign of the half-step velocity, resolved to one step (within the velocity
//! change one step's force jump makes, the sign becomes linear in the velocity, so a contact at
//! rest carries the elastic force: `crate::solve::dashpot::paper_force_in_step`), which
//! [`crate::solve::dashpot::step_trajectory`] steps the same way.

use std::path::Path;

use super::batch::{parse_batch, render_batch};
use super::{
    ContactModel, code_effective_mass, code_frame, code_stiffness, material_properties,
    pair_property, parse_run, render_deck, validate_scene,
};
use crate::codes::batch_fns::BatchFns;
use crate::codes::paper_law::paper_law_methods;
use crate::codes::runner::locate_override_or_installed;
use crate::codes::template::exact_number;
use crate::codes::{
    CalibrationCard, CodeDriver, CodeError, CodeSetup, Executable, LocateError, ParseError,
    ParsedRun, RenderedInput,
};
use crate::codes::{paper_loss_coefficient, refuse_for_paper_law};
use crate::model::law::{CodeLaw, PaperLaw};
use crate::model::scene::SceneKind;
use crate::solve::dashpot::CodeFrame;

/// The folder under the codes' folder ([`find_codes_dir`](crate::codes::runner::find_codes_dir)) the build is installed in.
pub(crate) const INSTALL_DIR: &str = "liggghts-paper";
/// The executable inside [`INSTALL_DIR`].
pub(crate) const BINARY_PATH: &str = "bin/liggghts-paper";

/// LIGGGHTS with the paper's law.
pub struct LiggghtsPaper;

impl LiggghtsPaper {
    /// What the model refuses, reported before it is run: what every build of the paper's
    /// law refuses ([`refuse_for_paper_law`]: η outside `[0, 1)`, which the header stops the
    /// run on too, and a clamp, since the styles have no `limitForce`), and what the stock
    /// LIGGGHTS deck needs of a scene.
    fn validate(&self, setup: &CodeSetup) -> Result<(), CodeError> {
        refuse_for_paper_law(self.name(), setup, CLAMP_REFUSAL)?;
        validate_scene(self.name(), setup)
    }

    /// `model paper` with the materials for the balls, `model paper/linear` with the rod's
    /// `kn` for the rod; η per type pair, friction only in an oblique impact.
    fn contact_model(&self, setup: &CodeSetup) -> ContactModel {
        let eta = pair_property(
            "lossCoefficient",
            &exact_number(paper_loss_coefficient(setup)),
        );
        let friction = pair_property("coefficientFriction", &super::oblique::friction(setup));
        match setup.scene {
            SceneKind::RodEnd => ContactModel {
                style: "paper/linear",
                settings: String::new(),
                properties: [
                    pair_property("kn", &exact_number(code_stiffness(setup))),
                    pair_property("kt", "0"),
                    eta,
                    friction,
                ]
                .join("\n"),
            },
            SceneKind::BallPlate | SceneKind::BallBall => {
                let [young, poisson] = material_properties(setup);
                ContactModel {
                    style: "paper",
                    settings: String::new(),
                    properties: [young, poisson, eta, friction].join("\n"),
                }
            }
        }
    }
}

/// Why `--clamp` is refused for this build.
const CLAMP_REFUSAL: &str = "model paper has no limitForce: its force C y^n (1 - eta) never \
                             attracts, so there is nothing to clamp";

impl CodeDriver for LiggghtsPaper {
    fn name(&self) -> &'static str {
        "liggghts-paper"
    }

    fn binary(&self) -> &'static str {
        "liggghts-paper"
    }

    /// `MILLIMPACT_LIGGGHTS_PAPER_BINARY` if set (a user's own build), else the project's
    /// build in the codes' folder.
    fn locate(&self) -> Result<Executable, LocateError> {
        locate_override_or_installed(self, |codes, missing| {
            let folder = codes.path.join(INSTALL_DIR);
            let program = folder.join(BINARY_PATH);
            if program.is_file() {
                Ok(Executable::plain(program))
            } else {
                Err(missing(BINARY_PATH, folder))
            }
        })
    }

    fn render(&self, setup: &CodeSetup) -> Result<RenderedInput, CodeError> {
        self.validate(setup)?;
        render_deck(self.name(), setup, &self.contact_model(setup))
    }

    fn parse(&self, setup: &CodeSetup, workdir: &Path, log: &str) -> Result<ParsedRun, ParseError> {
        parse_run(setup, workdir, log)
    }

    /// The paper's law with LIGGGHTS's own effective values (its `E*` with the wall type mixed
    /// in, its sphere masses) and the setup's η.
    fn law(&self, setup: &CodeSetup) -> CodeLaw {
        CodeLaw::Paper(PaperLaw {
            mass: code_effective_mass(setup),
            stiffness: code_stiffness(setup),
            exponent: setup.exponent,
            loss_coefficient: paper_loss_coefficient(setup),
        })
    }

    fn frame(&self, setup: &CodeSetup) -> Option<CodeFrame> {
        Some(code_frame(setup))
    }

    paper_law_methods!(CLAMP_REFUSAL, PAPER_BATCH, LiggghtsPaperCard);

    /// The paper's normal law beside LIGGGHTS' own `tangential history` (the Mindlin spring
    /// `model paper` hands it, no dashpot), as the stock build renders it.
    fn runs_oblique(&self) -> bool {
        true
    }

    /// A LIGGGHTS user's deck, read as the stock build's (this build runs the stock models as
    /// Debian's does, and the paper's).
    fn deck(&self) -> Option<&dyn crate::codes::deck::DeckReader> {
        Some(&super::deck::LiggghtsDeck)
    }

    fn mill_paper_build(&self) -> Option<crate::codes::CodeName> {
        Some(crate::codes::CodeName::LiggghtsPaper)
    }
}

/// The paper build's batches: many impacts in one process, its single inputs in sequence (as
/// the stock build's), each with its own η.
static PAPER_BATCH: BatchFns = BatchFns::new(
    super::batch::MAX_BATCH,
    |setups| render_batch(&LiggghtsPaper, setups),
    parse_batch,
);

/// The paper build's calibration card: the lines that select the paper's law.
pub(crate) struct LiggghtsPaperCard;

impl CalibrationCard for LiggghtsPaperCard {
    fn setting_keys(&self, _scene: SceneKind) -> &'static [&'static str] {
        &[
            "hard_particles",
            "pair_style",
            "wall/gran",
            "youngsModulus",
            "poissonsRatio",
            "lossCoefficient",
            "property/global kn ",
        ]
    }

    fn traps(&self, setup: &CodeSetup) -> Vec<String> {
        let mut t = vec![
            "lossCoefficient is η itself, not a COR: e = sqrt((1 − η)/(1 + η)); 0 <= η < 1 for every type pair, or the first run stops".into(),
            "the styles take no settings keywords: limitForce and tangential_damping are refused (the force never attracts)".into(),
        ];
        if setup.scene == SceneKind::BallPlate {
            t.push("wall modulus: the wall's atom type's E and ν are mixed into E*, as for model hertz: give the plate's own (a rigid plate: E = 1e30), and hard_particles yes for any E above 1e9 Pa".into());
        }
        if setup.scene == SceneKind::RodEnd {
            t.push("rod: model paper/linear with the rod's kn per type pair (and kt)".into());
        }
        t.push("time step: the loading stiffness is C (1 + η) and the contact lasts J(n) (y_max/v0)(1 + 1/e), longer than Hertz's at large η".into());
        t
    }
}
