//! A user's own DEM setup, read from their input (`millimpact deck`): the particle types with
//! their sizes and materials, the walls, the user's time step, and for each pair of types (and
//! each type against each wall) the contact law the user's own lines make the code integrate.
//!
//! Each code reads its own inputs ([`DeckReader`], a capability of its driver, in
//! `codes/<code>/deck.rs`) and renders the single normal impact of one pair with the user's own
//! contact lines transplanted into it. What the deck holds that the impact does not need (the
//! mill's geometry, insertion, gravity, output) is left out and said so; what the reader cannot
//! resolve or the harness cannot model is refused with the file, the line and what is supported.

use std::fmt;
use std::path::{Path, PathBuf};

use serde::{Serialize, Serializer};
use thiserror::Error;

use super::conventions::Conventions;
use super::{CodeError, CodeSetup, RenderedInput};

mod bodies;
mod contacts;
mod data;
mod impact;
mod reading;

use crate::model::law::CodeLaw;
pub(crate) use bodies::{AtomSyntax, Bodies, whole_number};
pub use bodies::{MAX_SIZES, SIZE_CLASSES};
pub(crate) use contacts::{
    OBLIQUE_SUFFIX, PairLaw, WallOrder, body_contacts, body_contacts_formed, wall_contacts,
    wall_contacts_formed,
};
pub(crate) use data::DataFile;
pub(crate) use impact::{DeckDialect, ImpactPlan};
pub(crate) use reading::{
    NEIGHBOURS, OUTPUT, ScriptReading, every_refusal, named_file, with_includes,
};

/// Where something was written in a deck: a file and a line (from 1).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SourceLine {
    /// The file.
    pub file: PathBuf,
    /// The line, from 1 (the first line of a continued command).
    pub line: usize,
}

impl fmt::Display for SourceLine {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}:{}", self.file.display(), self.line)
    }
}

impl SourceLine {
    /// An error here: `what` this line holds that is not `supported`.
    pub(crate) fn refuse(&self, what: impl Into<String>, supported: &str) -> DeckError {
        DeckError::unsupported(self, what, supported)
    }
}

impl Serialize for SourceLine {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.collect_str(self)
    }
}

/// Where something was set in a deck: a line of a script (LIGGGHTS, LAMMPS), or a field of a
/// structured file, by its path (Kratos' JSON files, which have no lines to speak of: a value
/// is found by its keys, as the code finds it).
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum DeckSource {
    /// A line of a script.
    Line(SourceLine),
    /// A field of a structured file.
    Field {
        /// The file.
        file: PathBuf,
        /// The field's path (`material_relations[1].Variables.COEFFICIENT_OF_RESTITUTION`).
        path: String,
    },
}

impl DeckSource {
    /// The field at `path` of `file`.
    pub(crate) fn field(file: &Path, path: impl Into<String>) -> Self {
        DeckSource::Field {
            file: file.to_path_buf(),
            path: path.into(),
        }
    }
}

impl DeckSource {
    /// An error here: `what` this line or field holds that is not `supported`.
    pub(crate) fn refuse(&self, what: impl Into<String>, supported: &str) -> DeckError {
        DeckError::unsupported(self, what, supported)
    }
}

impl From<SourceLine> for DeckSource {
    fn from(line: SourceLine) -> Self {
        DeckSource::Line(line)
    }
}

impl From<&SourceLine> for DeckSource {
    fn from(line: &SourceLine) -> Self {
        DeckSource::Line(line.clone())
    }
}

impl From<&DeckSource> for DeckSource {
    fn from(source: &DeckSource) -> Self {
        source.clone()
    }
}

impl fmt::Display for DeckSource {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            DeckSource::Line(line) => line.fmt(f),
            DeckSource::Field { file, path } => write!(f, "{}: {path}", file.display()),
        }
    }
}

impl Serialize for DeckSource {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.collect_str(self)
    }
}

/// A deck that cannot be checked as written: bad input (exit 2), and nothing is run.
#[derive(Debug, Error)]
pub enum DeckError {
    /// A line (or a field) holds something unsupported or unresolvable.
    #[error("{at}: {what}; supported: {supported}")]
    Unsupported {
        /// Where.
        at: DeckSource,
        /// What was found, with its value.
        what: String,
        /// What is supported there.
        supported: String,
    },
    /// The deck lacks something every check needs (no time step, no particle size).
    #[error("{}: {what}; {supported}", file.display())]
    Lacking {
        /// The deck.
        file: PathBuf,
        /// What is missing.
        what: String,
        /// How to give it.
        supported: String,
    },
    /// A file the deck names (an include, a mesh, a data file, an `.mdpa`, a materials file)
    /// does not exist: the code would stop at that line, so nothing is run.
    #[error("{at}: {what} `{name}` does not exist ({} looked for; the code stops here, so nothing was run)", path.display())]
    Missing {
        /// The line (or field) that names it.
        at: DeckSource,
        /// What the file is (`include`, `mesh file`, `data file`).
        what: String,
        /// The file as the deck names it.
        name: String,
        /// The file as the code would look for it.
        path: PathBuf,
    },
    /// Several lines (or fields) the check cannot honour, found in one pass: each its own
    /// line, in the deck's order (the units first).
    #[error("{}", join_lines(.0))]
    Several(Vec<DeckError>),
    /// A file of the deck cannot be read.
    #[error("cannot read {}: {source}", path.display())]
    Read {
        /// The file.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// The code that reads the deck stopped it with an error of the deck's own (an exception
    /// a YADE script raises while YADE sets it up), in the code's own words.
    #[error("{at}: {code} stops the deck here: {message}")]
    Raised {
        /// Where in the deck.
        at: DeckSource,
        /// The code.
        code: String,
        /// The code's own message.
        message: String,
    },
    /// The code that reads the deck (YADE runs its scripts' set-up) could not run it: missing,
    /// crashed or past its time limit.
    #[error("reading {} in {code}", path.display())]
    Reader {
        /// The deck.
        path: PathBuf,
        /// The code.
        code: String,
        /// Why.
        source: Box<CodeError>,
    },
    /// The build named with `--code` reads no decks: its law is one a user's own lines cannot
    /// select (a hook the harness adds), so a deck of its code is read by the stock build.
    #[error("{}: --code {code} reads no decks (its law is added by the harness, not selected by a deck's lines); the builds that read decks: {readers}", path.display())]
    NoReader {
        /// The deck.
        path: PathBuf,
        /// The build named.
        code: String,
        /// The builds that read decks.
        readers: String,
    },
    /// No reader takes the file.
    #[error("{}: not a deck of any code this build reads; supported: {supported}", path.display())]
    Unrecognised {
        /// The file.
        path: PathBuf,
        /// What is read.
        supported: String,
    },
}

/// A deck that cannot be checked as written is the user's (exit 2); a code that reads the deck
/// and could not run is not (exit 1).
impl crate::error::Blame for DeckError {
    fn is_user_error(&self) -> bool {
        !matches!(self, DeckError::Reader { .. })
    }
}

/// Each error on a line of its own.
fn join_lines(errors: &[DeckError]) -> String {
    let lines: Vec<String> = errors.iter().map(ToString::to_string).collect();
    lines.join("\n")
}

impl DeckError {
    /// The file `path` that the line (or field) `at` names as `what` is missing.
    /// `name`: as the deck writes it.
    pub(crate) fn missing(at: impl Into<DeckSource>, what: &str, name: &str, path: &Path) -> Self {
        DeckError::Missing {
            at: at.into(),
            what: what.into(),
            name: name.into(),
            path: path.to_path_buf(),
        }
    }

    /// `errors` as one error: none is `Ok`, one itself, more [`DeckError::Several`] (each
    /// [`DeckError::Several`] among them flattened).
    pub(crate) fn all(errors: Vec<DeckError>) -> Result<(), DeckError> {
        let mut flat = Vec::new();
        for e in errors {
            match e {
                DeckError::Several(inner) => flat.extend(inner),
                e => flat.push(e),
            }
        }
        match flat.len() {
            0 => Ok(()),
            1 => Err(flat.remove(0)),
            _ => Err(DeckError::Several(flat)),
        }
    }

    /// A deck (`path`) that lacks `what`, naming what is `supported`.
    pub(crate) fn lacking(path: &Path, what: &str, supported: &str) -> Self {
        DeckError::Lacking {
            file: path.to_path_buf(),
            what: what.into(),
            supported: supported.into(),
        }
    }

    /// An unsupported or unresolvable line (or field).
    pub(crate) fn unsupported(
        at: impl Into<DeckSource>,
        what: impl Into<String>,
        supported: &str,
    ) -> Self {
        DeckError::Unsupported {
            at: at.into(),
            what: what.into(),
            supported: supported.to_string(),
        }
    }
}

/// One side of a pair: a particle type, or a wall.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum TypeRef {
    /// A particle type (LIGGGHTS/LAMMPS atom type, Kratos material id).
    Type(u32),
    /// A wall.
    Wall,
}

impl Serialize for TypeRef {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        match self {
            TypeRef::Type(t) => serializer.serialize_u32(*t),
            TypeRef::Wall => serializer.serialize_str("wall"),
        }
    }
}

impl fmt::Display for TypeRef {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            TypeRef::Type(t) => write!(f, "{t}"),
            TypeRef::Wall => f.write_str("wall"),
        }
    }
}

/// A particle of the deck: one size of one type.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct DeckBody {
    /// Its type.
    pub type_id: u32,
    /// Radius, m.
    pub radius: f64,
    /// Density, kg/m³.
    pub density: f64,
    /// Mass, kg, as the code forms it from radius and density.
    pub mass: f64,
    /// Young's modulus of its type, Pa, where the model uses one.
    pub youngs_modulus: Option<f64>,
    /// Poisson's ratio of its type, where the model uses one.
    pub poisson_ratio: Option<f64>,
    /// Where its size was read (a line, or the command-line flag).
    pub from: String,
}

/// A wall of the deck.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct DeckWall {
    /// The wall's name in the deck (a fix ID, a model part).
    pub name: String,
    /// Its material's type, where the code gives walls one.
    pub type_id: Option<u32>,
    /// Young's modulus of its material, Pa, where the model uses one.
    pub youngs_modulus: Option<f64>,
    /// Poisson's ratio of its material, where the model uses one.
    pub poisson_ratio: Option<f64>,
    /// Where it is defined.
    pub from: DeckSource,
}

/// The other body of a pair.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Partner {
    /// A second particle: the index of its [`DeckBody`].
    Body(usize),
    /// A wall: the index of its [`DeckWall`].
    Wall(usize),
}

/// One pair of the deck and the contact law the user's lines give it.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct DeckContact {
    /// The moving particle: the index of its [`DeckBody`].
    pub body: usize,
    /// What it hits.
    pub partner: Partner,
    /// The two types (a type and `"wall"` for a wall).
    pub types: [TypeRef; 2],
    /// The normal model as the deck names it (`hertz`, `hooke/stiffness`, …).
    pub model: String,
    /// The COR the user entered for this pair, where the model takes one.
    pub cor_entered: Option<f64>,
    /// The law the code integrates with the user's lines: its `E*`, `R*`, mass, damping formula
    /// and clamp, as measured for the installed code (`reference/<code>/CONVENTIONS.md`); the
    /// paper's law itself where the lines select it (LIGGGHTS `model paper`, run in
    /// liggghts-paper).
    pub law: CodeLaw,
    /// The convention traps these lines meet.
    pub traps: Vec<String>,
    /// The lines (or fields) that set this pair's contact.
    pub lines: Vec<DeckSource>,
    /// The friction the lines give the pair, where the reader reads it (`None`: no friction
    /// read, and no tangential impact run).
    pub friction: Option<DeckFriction>,
}

/// A pair's friction as its lines write it: Coulomb's μ and the tangential model.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct DeckFriction {
    /// Coulomb's friction coefficient μ.
    pub coefficient: f64,
    /// The tangential model as written (`tangential mindlin NULL 1.0 0.4`; for a classic
    /// style `hooke/history: xmu 0.4, dampflag 1`).
    pub model: String,
    /// The tangential damping the lines set (`dampflag 1`, `damping coefficient 1.0`), which
    /// the check's oblique run turns off; `None` where they set none.
    pub damping: Option<String>,
}

/// The lines of the user's deck an impact input carries, as the code will read them
/// (variables substituted).
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Transplant {
    /// Lines that must come before the simulation box (atom style, particle hardness).
    pub before_box: Vec<String>,
    /// Lines every impact carries (units, styles, the material properties, the pair lines).
    pub common: Vec<String>,
    /// Per wall (in the order of [`UserDeck::walls`]): its contact line, made a flat plane.
    pub walls: Vec<String>,
    /// The number of particle types the deck declares (its property tables are that size).
    pub types: u32,
}

/// A user's deck as read.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct UserDeck {
    /// The file.
    pub path: PathBuf,
    /// The user's time step, s.
    pub timestep: f64,
    /// Where the time step was set.
    pub timestep_from: String,
    /// The particles (one per size of each type).
    pub bodies: Vec<DeckBody>,
    /// The walls.
    pub walls: Vec<DeckWall>,
    /// Each pair of bodies, and each body against each wall.
    pub contacts: Vec<DeckContact>,
    /// The deck's own impact speed (an insertion's `vel`, `velocity … set`, YADE's
    /// `state.vel`), else a speed it names as typical (LIGGGHTS' `characteristicVelocity`),
    /// m/s, with where.
    pub representative_velocity: Option<(f64, String)>,
    /// What the deck holds that the impacts leave out.
    pub left_out: Vec<String>,
    /// The user's lines each impact carries.
    pub transplant: Transplant,
}

/// A particle size and density given on the command line, for a deck that computes them.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GivenParticle {
    /// The type.
    pub type_id: u32,
    /// Radius, m.
    pub radius: f64,
    /// Density, kg/m³.
    pub density: f64,
}

/// What the command line adds to a deck.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct DeckOptions {
    /// Particles given with flags (they replace the deck's own sizes for their types).
    pub particles: Vec<GivenParticle>,
    /// Variables defined before the deck is read (`-var NAME VALUE`).
    pub variables: Vec<(String, String)>,
    /// How long a code that reads the deck itself (YADE runs the script's set-up) may take;
    /// `None`: the YADE reader's own limit, 120 s.
    pub time_limit: Option<std::time::Duration>,
}

/// One impact of one pair, ready to run: the input with the user's lines, the setup the run
/// is read with, and where the stepped law starts.
#[derive(Clone, Debug, PartialEq)]
pub struct DeckImpactInput {
    /// The input.
    pub input: RenderedInput,
    /// The setup (bodies, time step, steps, velocity) the run is parsed with.
    pub setup: CodeSetup,
    /// The gap between the surfaces at `t = 0`, m (the code's law is stepped from it).
    pub start_gap: f64,
}

/// Which elastic constants of its bodies a deck's impact setup carries.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum BodyElasticity {
    /// The deck's own Young's modulus and Poisson's ratio of each type, where it gives them.
    FromDeck,
    /// None: the setup's law is the deck's contact lines alone, so no convention the driver
    /// forms from a sphere's own constants (its calibration card's traps) applies.
    Withheld,
}

/// A code's capability to read its users' decks and run one pair's impact with their lines.
pub trait DeckReader: Send + Sync {
    /// Whether `text` (the file at `path`) is an input of this code.
    fn recognises(&self, path: &Path, text: &str) -> bool;
    /// What this reader reads, for an error that names it.
    fn reads(&self) -> &'static str;
    /// Read the deck at `path`.
    fn read(&self, path: &Path, options: &DeckOptions) -> Result<UserDeck, DeckError>;
    /// The input of the impact of `deck.contacts[contact]` at `velocity` (m/s), run for `steps`
    /// steps of the deck's own time step.
    fn render(
        &self,
        deck: &UserDeck,
        contact: usize,
        velocity: f64,
        steps: u64,
    ) -> Result<DeckImpactInput, CodeError>;
    /// The oblique impact of `deck.contacts[contact]`: normal speed `velocity` (m/s), the moving
    /// body's centre along the contact plane at `tangential_velocity` (m/s), the same lines and
    /// steps as [`DeckReader::render`], its run printing the tangential velocity and spin it
    /// leaves with (see [`TANGENTIAL_LINE`]); `None` where the reader renders no oblique impact.
    fn render_oblique(
        &self,
        deck: &UserDeck,
        contact: usize,
        velocity: f64,
        tangential_velocity: f64,
        steps: u64,
    ) -> Result<Option<DeckImpactInput>, CodeError>;
    /// Whether the reader reads a pair's friction (and renders its oblique impact).
    fn reads_friction(&self) -> bool;
}

/// The word that starts the line an oblique impact's run prints after its steps:
/// `MILLIMPACT_TANGENTIAL VT OMEGA [VT2 OMEGA2]`, the ball's centre velocity along the contact
/// plane (m/s) and its spin (rad/s, the sign of [`crate::model::tangential`]), then the
/// partner's for a pair.
pub const TANGENTIAL_LINE: &str = "MILLIMPACT_TANGENTIAL";

/// The mass of a sphere, kg, as the codes form it from radius (m) and density (kg/m³).
pub(crate) fn sphere_mass(radius: f64, density: f64) -> f64 {
    4.0 * std::f64::consts::PI / 3.0 * radius * radius * radius * density
}

/// The Rayleigh time of a particle, s: `π R sqrt(ρ/G) / (0.1631 ν + 0.8766)`, `G = E/(2(1+ν))`,
/// the time a Rayleigh wave takes across it, from which DEM codes pick their step.
pub(crate) fn rayleigh_time(
    radius: f64,
    density: f64,
    youngs_modulus: f64,
    poisson_ratio: f64,
) -> f64 {
    let shear = youngs_modulus / (2.0 * (1.0 + poisson_ratio));
    std::f64::consts::PI * radius * (density / shear).sqrt() / (0.1631 * poisson_ratio + 0.8766)
}
