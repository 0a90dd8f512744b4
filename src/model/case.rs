//! Case files: a TOML description of one impact, read strictly.
//!
//! A scene takes only what it needs: a key or table the scene does not use is an error, and so
//! is every value outside its physical range. Each error is one line naming the file, the key,
//! the value and what is allowed.

use std::path::{Path, PathBuf};

use thiserror::Error;
use toml::{Table, Value};

use serde::{Deserialize, Serialize};

use crate::model::exact;
use crate::model::law::PaperLaw;
use crate::model::scene::{Ball, Material, Plate, Rod, Scene, SceneKind, StiffnessConvention};
use crate::model::tangential::{Oblique, OtherBallMotion, TangentialLaw, TangentialSpring};

/// One-sided (physical impact) or two-sided (paper Eq. 14) contact.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ContactKind {
    /// The bodies separate when the approach returns to zero.
    #[default]
    Unilateral,
    /// The spring also pulls: a decaying oscillation through zero.
    Bilateral,
}

/// Largest case file read, bytes (a case is a few hundred).
pub(crate) const MAX_CASE_BYTES: u64 = 64 * 1024;

/// A rejected case file.
#[derive(Debug, Error, Clone, PartialEq)]
#[error("{}: {} = {}: {allowed}", one_line(.file), one_line(.key), one_line(.value))]
pub struct CaseError {
    /// The file.
    pub file: String,
    /// The key, dotted with its table (`ball.radius`), or `(file)` for the file as a whole.
    pub key: String,
    /// The offending value as written, or `(missing)`.
    pub value: String,
    /// What is allowed.
    pub allowed: String,
}

/// `text` on one line: a line break (a TOML multi-line string, a quoted key) written as `\n`,
/// so that a refusal stays the one line it promises.
fn one_line(text: &str) -> std::borrow::Cow<'_, str> {
    if text.contains(['\n', '\r']) {
        text.replace('\r', "\\r").replace('\n', "\\n").into()
    } else {
        text.into()
    }
}

/// An invalid case is the user's: exit code 2.
impl crate::error::Blame for CaseError {
    fn is_user_error(&self) -> bool {
        true
    }
}

impl CaseError {
    /// The rejection of `value` at `key` in `file`, with what is allowed.
    pub(crate) fn new(file: &str, key: &str, value: &str, allowed: &str) -> CaseError {
        CaseError {
            file: file.to_string(),
            key: key.to_string(),
            value: value.to_string(),
            allowed: allowed.to_string(),
        }
    }
}

/// One validated case.
#[derive(Clone, Debug, PartialEq)]
pub struct Case {
    /// The case's name: its file stem.
    pub name: String,
    /// Where it was read from.
    pub path: PathBuf,
    /// Bodies and materials.
    pub scene: Scene,
    /// Normal approach speed `v0`, m/s (relative speed for ball_ball).
    pub impact_velocity: f64,
    /// Loss coefficient `η` (given, or derived from a given restitution).
    pub loss_coefficient: f64,
    /// How the ball stiffness is computed.
    pub stiffness: StiffnessConvention,
    /// Unilateral or bilateral contact.
    pub contact: ContactKind,
    /// The tangential half of an oblique or spinning impact (ball scenes); `None` for a normal
    /// impact, which every case written before the tangential keys is.
    pub oblique: Option<Oblique>,
}

impl Case {
    /// Refuse a case whose derived quantities (mass, stiffness, the elastic peak δ0, the time
    /// scale δ0/v0, the force scale) cannot be represented in double precision: each valid
    /// on its own, a radius of 1e308 or a density of 1e-308 still overflows or underflows
    /// them, and the run would print inf or NaN. The error names the keys they come from.
    fn check_representable(&self, file: &str) -> Result<(), CaseError> {
        let keys = match self.scene.kind() {
            SceneKind::BallPlate | SceneKind::BallBall => {
                "ball.radius, ball.density, ball.youngs_modulus, impact_velocity"
            }
            SceneKind::RodEnd => {
                "rod.diameter, rod.length, rod.density, rod.youngs_modulus, impact_velocity"
            }
        };
        let law = self.law();
        let peak = law.elastic_peak(self.impact_velocity);
        let quantities = [
            ("mass", law.mass),
            ("stiffness", law.stiffness),
            ("elastic peak δ0", peak),
            ("time scale δ0/v0", peak / self.impact_velocity),
            (
                "force scale C δ0^n",
                law.stiffness * peak.powf(law.exponent),
            ),
            (
                "impact energy",
                0.5 * law.mass * self.impact_velocity.powi(2),
            ),
        ];
        for (what, value) in quantities {
            if !(value.is_normal() && value > 0.0) {
                return Err(CaseError {
                    file: file.to_string(),
                    key: keys.to_string(),
                    value: format!("{what} = {value:e}"),
                    allowed: "values whose derived quantities are finite, positive numbers in double precision".to_string(),
                });
            }
        }
        Ok(())
    }

    /// The key that makes the case oblique and its value: the tangential velocity, else the
    /// spin (a spin alone names the spin), else μ; `None` for a normal case.
    fn oblique_key(&self) -> Option<(&'static str, f64)> {
        let o = self.oblique.as_ref()?;
        Some(if o.tangential_velocity != 0.0 {
            ("tangential_velocity", o.tangential_velocity)
        } else if o.angular_velocity != 0.0 {
            ("angular_velocity", o.angular_velocity)
        } else {
            ("friction_coefficient", o.friction_coefficient)
        })
    }

    /// Refuse an oblique case where `what` would run only its normal half (the commands that
    /// run many impacts or store them take normal impacts only): one line naming the file and
    /// the first tangential key.
    pub fn refuse_oblique(&self, what: &str) -> Result<(), CaseError> {
        match self.oblique_key() {
            None => Ok(()),
            Some((key, value)) => Err(CaseError::new(
                &self.path.display().to_string(),
                key,
                &value.to_string(),
                &format!(
                    "a normal case: {what} takes normal impacts only (`millimpact run` \
                     integrates an oblique case, `millimpact reference --code CODE` runs it in a \
                     DEM code)"
                ),
            )),
        }
    }

    /// Refuse an oblique case that the DEM code `code` cannot run: one of two balls (their
    /// contact normal turns, and the codes' trajectories are read along a fixed line), or one
    /// in a build that does not render oblique impacts (`builds` names those that do).
    pub fn refuse_oblique_in(
        &self,
        code: &str,
        runs_oblique: bool,
        builds: &[&str],
    ) -> Result<(), CaseError> {
        let Some((key, value)) = self.oblique_key() else {
            return Ok(());
        };
        let file = self.path.display().to_string();
        if self.scene.kind() != SceneKind::BallPlate {
            return Err(CaseError::new(
                &file,
                "scene",
                self.scene.kind().name(),
                "ball_plate for an oblique case in a DEM code (two balls' contact normal turns, \
                 and the codes' trajectories are read along the line of the centres at the \
                 start; `millimpact run` integrates it)",
            ));
        }
        if !runs_oblique {
            return Err(CaseError::new(
                &file,
                key,
                &value.to_string(),
                &format!(
                    "a normal case in {code}, which does not run an oblique impact (the builds that do: {})",
                    builds.join(", ")
                ),
            ));
        }
        Ok(())
    }

    /// The paper's law for this case.
    pub fn law(&self) -> PaperLaw {
        PaperLaw {
            mass: self.scene.reduced_mass(),
            stiffness: self.scene.stiffness(self.stiffness),
            exponent: self.scene.exponent(),
            loss_coefficient: self.loss_coefficient,
        }
    }

    /// The target COR `e(η)`.
    pub fn restitution(&self) -> f64 {
        exact::restitution(self.loss_coefficient)
    }

    /// The same case at another loss coefficient.
    pub fn with_loss_coefficient(&self, loss_coefficient: f64) -> Case {
        Case {
            loss_coefficient,
            ..self.clone()
        }
    }

    /// Set top-level keys of [`IN_PLACE_KEYS`] in place, exactly as reading the case's table
    /// with them set would: the same checks in the reader's order and the same errors, which
    /// name `file`. A sweep edits its base case so for every point instead of reading it anew.
    /// `edits` are applied in order (η and restitution name one number: the last given wins).
    pub(crate) fn apply(&mut self, edits: &[(&str, &Value)], file: &str) -> Result<(), CaseError> {
        let reader = Reader { file };
        let mut velocity = None;
        let mut eta: Option<(Option<&Value>, Option<&Value>)> = None;
        for &(key, value) in edits {
            match key {
                "impact_velocity" => velocity = Some(value),
                "loss_coefficient" => eta = Some((Some(value), None)),
                "restitution" => eta = Some((None, Some(value))),
                other => {
                    return Err(reader.error(
                        other,
                        &value.to_string(),
                        &format!("not editable in place; keys: {}", IN_PLACE_KEYS.join(", ")),
                    ));
                }
            }
        }
        if let Some(v) = velocity {
            let x = reader.number_of("impact_velocity", Some(v))?;
            if x <= 0.0 {
                return Err(reader.error(
                    "impact_velocity",
                    &x.to_string(),
                    "must be a finite number > 0",
                ));
            }
            self.impact_velocity = x;
        }
        if let Some((loss, restitution)) = eta {
            self.loss_coefficient = reader.loss_coefficient(loss, restitution)?;
        }
        if velocity.is_some() {
            self.check_representable(file)?;
        }
        Ok(())
    }

    /// Read and validate a case file.
    ///
    /// ```
    /// use millimpact::Case;
    ///
    /// let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("cases/rod_end.toml");
    /// let case = Case::load(&path)?;
    /// assert_eq!(case.name, "rod_end");
    /// assert_eq!((case.impact_velocity, case.loss_coefficient), (2.0, 0.35));
    /// assert_eq!(case.law().exponent, 1.0); // a rod's end: linear contact
    /// # Ok::<(), millimpact::model::case::CaseError>(())
    /// ```
    pub fn load(path: &Path) -> Result<Case, CaseError> {
        let file = path.display().to_string();
        let fail =
            |key: &str, value: &str, allowed: &str| CaseError::new(&file, key, value, allowed);
        // A device or a FIFO would be read without end or block: only a regular file of a case's
        // size is read.
        let meta = std::fs::metadata(path)
            .map_err(|e| fail("(file)", "(unreadable)", &format!("cannot read it: {e}")))?;
        if !meta.is_file() {
            return Err(fail(
                "(file)",
                "(not a regular file)",
                "a case is a regular TOML file",
            ));
        }
        if meta.len() > MAX_CASE_BYTES {
            return Err(fail(
                "(file)",
                &format!("{} bytes", meta.len()),
                &format!("a case file is at most {MAX_CASE_BYTES} bytes"),
            ));
        }
        let text = std::fs::read_to_string(path)
            .map_err(|e| fail("(file)", "(unreadable)", &format!("cannot read it: {e}")))?;
        Case::parse(&text, path)
    }

    /// Read a case from the text of its file at `path` (which names it in errors and gives its
    /// name), as strictly as [`Case::load`].
    pub fn parse(text: &str, path: &Path) -> Result<Case, CaseError> {
        let file = path.display().to_string();
        let fail =
            |key: &str, value: &str, allowed: &str| CaseError::new(&file, key, value, allowed);
        let table: Table = text.parse().map_err(|e: toml::de::Error| {
            let message = e.message().replace('\n', " ");
            let place = match e.span() {
                Some(span) => {
                    let before = &text[..span.start.min(text.len())];
                    let line = before.matches('\n').count() + 1;
                    let column = before.chars().rev().take_while(|c| *c != '\n').count() + 1;
                    format!(" at line {line}, column {column}")
                }
                None => String::new(),
            };
            fail(
                "(file)",
                "(not TOML)",
                &format!("invalid TOML{place}: {message}"),
            )
        })?;
        let name = path
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_else(|| "case".to_string());
        Reader { file: &file }.case(&table, name, path)
    }

    /// Validate an already parsed case table as strictly as [`Case::load`]; errors name
    /// `file`, and the case is called `name` with `path` as its origin.
    pub(crate) fn from_table(
        table: &Table,
        file: &str,
        name: &str,
        path: &Path,
    ) -> Result<Case, CaseError> {
        Reader { file }.case(table, name.to_string(), path)
    }
}

struct Reader<'a> {
    file: &'a str,
}

/// The keys of a ball's table (`[ball]`, `[other_ball]`).
const BALL_KEYS: [&str; 4] = ["radius", "density", "youngs_modulus", "poisson_ratio"];
/// The keys of `[plate]`.
const PLATE_KEYS: [&str; 3] = ["rigid", "youngs_modulus", "poisson_ratio"];
/// The keys of `[rod]`.
const ROD_KEYS: [&str; 4] = ["diameter", "length", "density", "youngs_modulus"];
/// The body tables and their keys.
const TABLES: [(&str, &[&str]); 4] = [
    ("ball", &BALL_KEYS),
    ("other_ball", &BALL_KEYS),
    ("plate", &PLATE_KEYS),
    ("rod", &ROD_KEYS),
];

/// Every key a case file may set, as a sweep axis names it: the top-level keys, then
/// `table.key` for each body table's keys. The one list the case reader reads by.
pub(crate) fn case_keys() -> Vec<String> {
    let mut keys: Vec<String> = TOP_KEYS.iter().map(|k| k.to_string()).collect();
    for (table, table_keys) in TABLES {
        keys.extend(table_keys.iter().map(|k| format!("{table}.{k}")));
    }
    keys
}

/// The keys `Case::apply` sets in place; the others change a scene's bodies, and a sweep
/// reads the case anew for them.
pub(crate) const IN_PLACE_KEYS: [&str; 3] = ["impact_velocity", "loss_coefficient", "restitution"];

/// The top-level keys of an oblique or spinning case (ball scenes), apart from the sweep's
/// axes: a sweep edits normal impacts only.
const OBLIQUE_KEYS: [&str; 4] = [
    "tangential_velocity",
    "angular_velocity",
    "friction_coefficient",
    "other_ball_motion",
];

/// The keys of `[tangential]`.
const TANGENTIAL_KEYS: [&str; 4] = ["spring", "stiffness", "stiffness_ratio", "damping_ratio"];

const TOP_KEYS: [&str; 6] = [
    "scene",
    "impact_velocity",
    "loss_coefficient",
    "restitution",
    "stiffness",
    "contact",
];

impl Reader<'_> {
    fn error(&self, key: &str, value: &str, allowed: &str) -> CaseError {
        CaseError::new(self.file, key, value, allowed)
    }

    fn case(&self, t: &Table, name: String, path: &Path) -> Result<Case, CaseError> {
        let scene_name = match t.get("scene") {
            None => {
                return Err(self.error(
                    "scene",
                    "(missing)",
                    "required: \"ball_plate\", \"ball_ball\" or \"rod_end\"",
                ));
            }
            Some(Value::String(s)) => s.as_str(),
            Some(v) => {
                return Err(self.error(
                    "scene",
                    &v.to_string(),
                    "must be \"ball_plate\", \"ball_ball\" or \"rod_end\"",
                ));
            }
        };
        let kind = match scene_name {
            "ball_plate" => SceneKind::BallPlate,
            "ball_ball" => SceneKind::BallBall,
            "rod_end" => SceneKind::RodEnd,
            other => {
                return Err(self.error(
                    "scene",
                    &format!("\"{other}\""),
                    "unknown scene; allowed: \"ball_plate\", \"ball_ball\", \"rod_end\"",
                ));
            }
        };
        let tables: &[&str] = match kind {
            SceneKind::BallPlate => &["ball", "plate"],
            SceneKind::BallBall => &["ball", "other_ball"],
            SceneKind::RodEnd => &["rod"],
        };
        for (key, value) in t {
            let known_table = TABLES.iter().any(|(name, _)| name == key);
            if known_table && !tables.contains(&key.as_str()) {
                return Err(self.error(
                    &format!("[{key}]"),
                    "(table)",
                    &format!(
                        "not used by scene \"{scene_name}\", which takes {}",
                        tables
                            .iter()
                            .map(|t| format!("[{t}]"))
                            .collect::<Vec<_>>()
                            .join(" and ")
                    ),
                ));
            }
            if key == "stiffness" && kind == SceneKind::RodEnd {
                return Err(self.error(
                    key,
                    &value.to_string(),
                    "not used by scene \"rod_end\" (its stiffness is the rod's, π D² E / (4H))",
                ));
            }
            let oblique_key = OBLIQUE_KEYS.contains(&key.as_str()) || key == "tangential";
            if oblique_key && kind == SceneKind::RodEnd {
                return Err(self.error(
                    key,
                    &value.to_string(),
                    "not used by scene \"rod_end\": a rod's end strikes the plate normally (oblique and spinning impacts are ball scenes)",
                ));
            }
            if !known_table && !oblique_key && !TOP_KEYS.contains(&key.as_str()) {
                return Err(self.error(
                    key,
                    &value.to_string(),
                    &format!(
                        "unknown key; allowed at top level: {}, and for the ball scenes {} and [tangential]",
                        TOP_KEYS.join(", "),
                        OBLIQUE_KEYS.join(", ")
                    ),
                ));
            }
        }
        let impact_velocity = self.positive(t, "", "impact_velocity")?;
        let loss_coefficient =
            self.loss_coefficient(t.get("loss_coefficient"), t.get("restitution"))?;
        let stiffness = match t.get("stiffness") {
            None => StiffnessConvention::Hertz,
            Some(Value::String(s)) if s == "hertz" => StiffnessConvention::Hertz,
            Some(Value::String(s)) if s == "paper" => StiffnessConvention::Paper,
            Some(v) => {
                return Err(self.error(
                    "stiffness",
                    &v.to_string(),
                    "must be \"hertz\" or \"paper\"",
                ));
            }
        };
        let contact = match t.get("contact") {
            None => ContactKind::Unilateral,
            Some(Value::String(s)) if s == "unilateral" => ContactKind::Unilateral,
            Some(Value::String(s)) if s == "bilateral" => ContactKind::Bilateral,
            Some(v) => {
                return Err(self.error(
                    "contact",
                    &v.to_string(),
                    "must be \"unilateral\" or \"bilateral\"",
                ));
            }
        };
        let scene = match kind {
            SceneKind::BallPlate => Scene::BallPlate {
                ball: self.ball(t, "ball", None)?,
                plate: self.plate(t)?,
            },
            SceneKind::BallBall => {
                let ball = self.ball(t, "ball", None)?;
                let other = match t.get("other_ball") {
                    None => ball,
                    Some(_) => self.ball(t, "other_ball", Some(&ball))?,
                };
                Scene::BallBall { ball, other }
            }
            SceneKind::RodEnd => Scene::RodEnd { rod: self.rod(t)? },
        };
        let oblique = self.oblique(t, kind)?;
        if oblique.is_some() && contact == ContactKind::Bilateral {
            return Err(self.error(
                "contact",
                "\"bilateral\"",
                "an oblique case is a unilateral impact (the bodies separate once)",
            ));
        }
        let case = Case {
            name,
            path: path.to_path_buf(),
            scene,
            impact_velocity,
            loss_coefficient,
            stiffness,
            contact,
            oblique,
        };
        case.check_representable(self.file)?;
        Ok(case)
    }

    /// The tangential half, if the case has any of its keys; `friction_coefficient` is then
    /// required.
    fn oblique(&self, t: &Table, kind: SceneKind) -> Result<Option<Oblique>, CaseError> {
        let given = OBLIQUE_KEYS.iter().any(|k| t.contains_key(*k)) || t.contains_key("tangential");
        if !given {
            return Ok(None);
        }
        let friction_coefficient = match t.get("friction_coefficient") {
            None => {
                return Err(self.error(
                    "friction_coefficient",
                    "(missing)",
                    "required by an oblique or spinning case: Coulomb's μ, a finite number >= 0",
                ));
            }
            v => self.number_of("friction_coefficient", v)?,
        };
        if friction_coefficient < 0.0 {
            return Err(self.error(
                "friction_coefficient",
                &friction_coefficient.to_string(),
                "must be a finite number >= 0",
            ));
        }
        let signed = |key: &str| -> Result<f64, CaseError> {
            match t.get(key) {
                None => Ok(0.0),
                v => self.number_of(key, v),
            }
        };
        let tangential_velocity = signed("tangential_velocity")?;
        let angular_velocity = signed("angular_velocity")?;
        let other_ball = match t.get("other_ball_motion") {
            None => OtherBallMotion::AtRest,
            Some(v) if kind != SceneKind::BallBall => {
                return Err(self.error(
                    "other_ball_motion",
                    &v.to_string(),
                    "used by scene \"ball_ball\" only",
                ));
            }
            Some(Value::String(s)) if s == "at_rest" => OtherBallMotion::AtRest,
            Some(Value::String(s)) if s == "opposed" => OtherBallMotion::Opposed,
            Some(Value::String(s)) if s == "mirrored" => OtherBallMotion::Mirrored,
            Some(v) => {
                return Err(self.error(
                    "other_ball_motion",
                    &v.to_string(),
                    "must be \"at_rest\", \"opposed\" (centre at -tangential_velocity, the same spin) or \"mirrored\" (centre at tangential_velocity, the opposite spin)",
                ));
            }
        };
        let law = match t.get("tangential") {
            None => TangentialLaw::default(),
            Some(Value::Table(table)) => self.tangential_law(table)?,
            Some(v) => return Err(self.error("tangential", &v.to_string(), "must be a table")),
        };
        Ok(Some(Oblique {
            tangential_velocity,
            angular_velocity,
            friction_coefficient,
            other_ball,
            law,
        }))
    }

    /// The `[tangential]` table: `spring` ("mindlin", default; "linear" with `stiffness`;
    /// "proportional" with `stiffness_ratio`, default 2/7) and `damping_ratio` (default 0).
    fn tangential_law(&self, table: &Table) -> Result<TangentialLaw, CaseError> {
        self.only_keys(table, "tangential", &TANGENTIAL_KEYS)?;
        let spring_name = match table.get("spring") {
            None => "mindlin",
            Some(Value::String(s)) => s.as_str(),
            Some(v) => {
                return Err(self.error(
                    "tangential.spring",
                    &v.to_string(),
                    "must be \"mindlin\", \"linear\" or \"proportional\"",
                ));
            }
        };
        let refuse_key = |key: &str, spring: &str| -> Result<(), CaseError> {
            match table.get(key) {
                Some(v) => Err(self.error(
                    &format!("tangential.{key}"),
                    &v.to_string(),
                    &format!("not used by spring \"{spring}\""),
                )),
                None => Ok(()),
            }
        };
        let spring = match spring_name {
            "mindlin" => {
                refuse_key("stiffness", "mindlin")?;
                refuse_key("stiffness_ratio", "mindlin")?;
                TangentialSpring::Mindlin
            }
            "linear" => {
                refuse_key("stiffness_ratio", "linear")?;
                TangentialSpring::Linear {
                    stiffness: self.positive(table, "tangential", "stiffness")?,
                }
            }
            "proportional" => {
                refuse_key("stiffness", "proportional")?;
                TangentialSpring::Proportional {
                    ratio: match table.get("stiffness_ratio") {
                        None => 2.0 / 7.0,
                        Some(_) => self.positive(table, "tangential", "stiffness_ratio")?,
                    },
                }
            }
            other => {
                return Err(self.error(
                    "tangential.spring",
                    &format!("\"{other}\""),
                    "must be \"mindlin\", \"linear\" or \"proportional\"",
                ));
            }
        };
        let damping_ratio = match table.get("damping_ratio") {
            None => 0.0,
            v => self.number_of("tangential.damping_ratio", v)?,
        };
        if damping_ratio < 0.0 {
            return Err(self.error(
                "tangential.damping_ratio",
                &damping_ratio.to_string(),
                "must be a finite number >= 0 (a negative dashpot creates energy)",
            ));
        }
        if damping_ratio > 0.0 && !matches!(spring, TangentialSpring::Linear { .. }) {
            // γ_t = 2 ζ sqrt(k_t M*) grows as δ^¼ from first contact while the bound μ F_n grows
            // as δ^1.5: the dashpot alone exceeds the bound there, and the law (a spring that
            // must cancel it) has no regime the integration can start from.
            return Err(self.error(
                "tangential.damping_ratio",
                &damping_ratio.to_string(),
                &format!(
                    "a dashpot is taken with spring = \"linear\" only (on the \"{spring_name}\" spring, which vanishes at first contact, it outgrows the Coulomb bound there); use 0"
                ),
            ));
        }
        Ok(TangentialLaw {
            spring,
            damping_ratio,
        })
    }

    /// η from the case's `loss_coefficient` or `restitution` (exactly one given).
    fn loss_coefficient(
        &self,
        loss: Option<&Value>,
        restitution: Option<&Value>,
    ) -> Result<f64, CaseError> {
        let eta = match (loss, restitution) {
            (Some(_), Some(_)) => {
                return Err(self.error(
                    "loss_coefficient",
                    &loss.map(Value::to_string).unwrap_or_default(),
                    "give exactly one of loss_coefficient and restitution, not both",
                ));
            }
            (None, None) => {
                return Err(self.error(
                    "loss_coefficient",
                    "(missing)",
                    "give exactly one of loss_coefficient (η in [0, 1)) and restitution (e in (0, 1])",
                ));
            }
            (Some(_), None) => {
                let eta = self.number_of("loss_coefficient", loss)?;
                if !(0.0..1.0).contains(&eta) {
                    return Err(self.error(
                        "loss_coefficient",
                        &eta.to_string(),
                        "must be in [0, 1): η = 1 never separates, η < 0 creates energy",
                    ));
                }
                eta
            }
            (None, Some(_)) => {
                let e = self.number_of("restitution", restitution)?;
                if !(e > 0.0 && e <= 1.0) {
                    return Err(self.error("restitution", &e.to_string(), "must be in (0, 1]"));
                }
                let eta = exact::loss_coefficient(e);
                if eta >= 1.0 {
                    // e² below half an ulp of 1 makes η = (1 - e²)/(1 + e²) exactly 1: the
                    // bodies would never separate and no integration would end.
                    return Err(self.error(
                        "restitution",
                        &e.to_string(),
                        "must be in (0, 1] and at least about 1.1e-8 (a smaller e gives η = 1 in double precision: the bodies never separate)",
                    ));
                }
                eta
            }
        };
        Ok(eta)
    }

    fn table<'t>(&self, t: &'t Table, name: &str) -> Result<&'t Table, CaseError> {
        match t.get(name) {
            Some(Value::Table(table)) => Ok(table),
            Some(v) => Err(self.error(name, &v.to_string(), "must be a table")),
            None => Err(self.error(&format!("[{name}]"), "(missing)", "required by this scene")),
        }
    }

    fn only_keys(&self, t: &Table, table: &str, allowed: &[&str]) -> Result<(), CaseError> {
        for (key, value) in t {
            if !allowed.contains(&key.as_str()) {
                return Err(self.error(
                    &format!("{table}.{key}"),
                    &value.to_string(),
                    &format!(
                        "unknown or unused key; [{table}] takes {}",
                        allowed.join(", ")
                    ),
                ));
            }
        }
        Ok(())
    }

    fn number(&self, t: &Table, table: &str, key: &str) -> Result<f64, CaseError> {
        let full = if table.is_empty() {
            key.to_string()
        } else {
            format!("{table}.{key}")
        };
        self.number_of(&full, t.get(key))
    }

    /// The number `value` at key `full`.
    fn number_of(&self, full: &str, value: Option<&Value>) -> Result<f64, CaseError> {
        let x = match value {
            Some(Value::Float(x)) => *x,
            Some(Value::Integer(i)) => *i as f64,
            Some(v) => return Err(self.error(full, &v.to_string(), "must be a number")),
            None => return Err(self.error(full, "(missing)", "required")),
        };
        if !x.is_finite() {
            return Err(self.error(full, &x.to_string(), "must be finite"));
        }
        Ok(x)
    }

    fn positive(&self, t: &Table, table: &str, key: &str) -> Result<f64, CaseError> {
        let x = self.number(t, table, key)?;
        if x <= 0.0 {
            let full = if table.is_empty() {
                key.to_string()
            } else {
                format!("{table}.{key}")
            };
            return Err(self.error(&full, &x.to_string(), "must be a finite number > 0"));
        }
        Ok(x)
    }

    fn poisson(&self, t: &Table, table: &str) -> Result<f64, CaseError> {
        let nu = self.number(t, table, "poisson_ratio")?;
        if !(nu > -1.0 && nu < 0.5) {
            return Err(self.error(
                &format!("{table}.poisson_ratio"),
                &nu.to_string(),
                "must be in (-1, 0.5)",
            ));
        }
        Ok(nu)
    }

    fn ball(&self, t: &Table, name: &str, defaults: Option<&Ball>) -> Result<Ball, CaseError> {
        let table = self.table(t, name)?;
        self.only_keys(table, name, &BALL_KEYS)?;
        let pick = |key: &str, fallback: Option<f64>| -> Result<f64, CaseError> {
            match (table.get(key), fallback) {
                (None, Some(x)) => Ok(x),
                _ if key == "poisson_ratio" => self.poisson(table, name),
                _ => self.positive(table, name, key),
            }
        };
        Ok(Ball {
            radius: pick("radius", defaults.map(|b| b.radius))?,
            density: pick("density", defaults.map(|b| b.density))?,
            material: Material {
                youngs_modulus: pick(
                    "youngs_modulus",
                    defaults.map(|b| b.material.youngs_modulus),
                )?,
                poisson_ratio: pick("poisson_ratio", defaults.map(|b| b.material.poisson_ratio))?,
            },
        })
    }

    fn plate(&self, t: &Table) -> Result<Plate, CaseError> {
        let table = self.table(t, "plate")?;
        let rigid = match table.get("rigid") {
            None => false,
            Some(Value::Boolean(b)) => *b,
            Some(v) => {
                return Err(self.error("plate.rigid", &v.to_string(), "must be true or false"));
            }
        };
        if rigid {
            self.only_keys(table, "plate", &["rigid"])?;
            return Ok(Plate::Rigid);
        }
        self.only_keys(table, "plate", &PLATE_KEYS)?;
        Ok(Plate::Elastic(Material {
            youngs_modulus: self.positive(table, "plate", "youngs_modulus")?,
            poisson_ratio: self.poisson(table, "plate")?,
        }))
    }

    fn rod(&self, t: &Table) -> Result<Rod, CaseError> {
        let table = self.table(t, "rod")?;
        self.only_keys(table, "rod", &ROD_KEYS)?;
        Ok(Rod {
            diameter: self.positive(table, "rod", "diameter")?,
            length: self.positive(table, "rod", "length")?,
            density: self.positive(table, "rod", "density")?,
            youngs_modulus: self.positive(table, "rod", "youngs_modulus")?,
        })
    }
}
