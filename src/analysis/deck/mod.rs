//! `millimpact deck`: a user's own DEM setup checked pair by pair. For each pair of particle
//! types (and each type against each wall) the single normal impact runs in the user's own code
//! with the user's own contact lines, at the user's time step, at a few impact speeds; each run
//! is set against the COR the user entered and against the code's own law (the law the lines
//! make the code integrate), exact and stepped as the code steps, so that a difference splits
//! into model (what the lines mean: a clamp, a fit, a convention), integration (the step) and
//! a remainder (what nothing explains), as `compare` splits it. Beside it: the peak overlap
//! against the radius, the steps per contact and the COR band they leave, the step against the
//! Rayleigh time, the traps the lines meet, and the paper's η for the COR realised.

pub(crate) mod speed;
pub mod tangential;

use std::collections::BTreeMap;
use std::path::Path;
use std::sync::Mutex;

use rayon::prelude::*;
use serde::ser::SerializeMap;
use serde::{Deserialize, Serialize, Serializer};
use thiserror::Error;

use super::compare::phase::{DEFAULT_PHASES, Range, over_phases};
use super::run::HERTZ_MAX_STRAIN;
use super::store::verify::REMAINDER_TOLERANCE;
use crate::codes::deck::{
    DeckBody, DeckError, DeckImpactInput, DeckOptions, DeckWall, Partner, TANGENTIAL_LINE, TypeRef,
    UserDeck, rayleigh_time,
};
use crate::codes::runner::process::Output;
use crate::codes::runner::{locate, run_rendered};
use crate::codes::{CodeDriver, CodeError, CodeName, RunOptions};
use crate::model::count::ceil_count;
use crate::model::exact;
use crate::model::figures::{Checked, Figures, Quantity, quantity};
use crate::model::law::{CodeLaw, ContactForce, DashpotLaw};
use crate::model::trajectory::{CodeTrajectory, TrajectoryMetrics, trajectory_metrics};
use crate::output::invocation::Invocation;
use crate::output::{Section, Summary, sci, signed};
use crate::solve::Method;
use crate::solve::dashpot::{CodeStepping, accurate_metrics};
pub use tangential::{DeckTangentialImpact, TangentialRun};

/// The speed the default velocities are spread around when the deck names none, m/s (the
/// canonical cases' speed, typical of a ball's fall in a mill).
pub(crate) const DEFAULT_VELOCITY: f64 = 2.0;
/// Fewest steps per contact before a warning: below it the step alone moves the COR by 1e-3
/// and more (the band printed beside it says by how much).
pub(crate) const MIN_STEPS_PER_CONTACT: f64 = 20.0;
/// Largest time step, as a fraction of the Rayleigh time, before a warning (the usual rule
/// of DEM practice is 10 to 20 %).
pub(crate) const MAX_RAYLEIGH_FRACTION: f64 = 0.2;
/// Most steps one impact may run (a step this small for the contact is a deck error).
pub(crate) const MAX_STEPS: u64 = 20_000_000;

/// The figures of one impact of one pair, in the JSON one object per pair and velocity.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct DeckImpact {
    /// The two types (a type and `"wall"` for a wall).
    pub types: [TypeRef; 2],
    /// The pair as labelled in the tables (with radii where a type has several sizes).
    pub pair: String,
    /// The run's name, `deck-CONTACT-TYPE-TYPE@VELOCITY` (its scratch directory's prefix, and
    /// its key among recorded runs).
    pub run: String,
    /// The wall's name, for a wall pair.
    pub wall: Option<String>,
    /// The walls this row stands for where several are identical for the pair (the same law,
    /// model, COR entered and material): one impact is run for all; empty for one wall.
    pub identical_walls: Vec<String>,
    /// The normal model as the deck names it.
    pub model: String,
    /// Radius of the moving particle, m.
    pub radius: f64,
    /// Radius of the other particle, m (none for a wall).
    pub partner_radius: Option<f64>,
    /// Normal approach speed, m/s.
    pub impact_velocity: f64,
    /// The COR the user entered for the pair (none for a model that takes stiffness and
    /// damping directly).
    pub cor_entered: Option<f64>,
    /// What the user's code realised with the user's lines: the COR (`cor_realised`) averaged
    /// over where the first contact falls within a step (a user's simulation meets every start
    /// phase: the run's own, at the start of a step, plus the code's own law stepped over the
    /// others), the largest overlap (`peak_overlap`, m) and the contact time by overlap and by
    /// force (s) of the run itself.
    #[serde(flatten, serialize_with = "realised_names")]
    pub realised: Figures<f64, REALISED>,
    /// The COR realised over the start phases: smallest and largest (`cor_realised` is their
    /// mean).
    pub cor_realised_band: Range,
    /// The COR of the run itself, whose first contact falls at the start of a step: one point
    /// of `cor_realised_band`.
    pub cor_realised_run: f64,
    /// The COR of the code's own law at zero step error.
    pub cor_law: f64,
    /// The COR of the code's own law stepped as the code steps, from the run's start.
    pub cor_law_stepped: f64,
    /// `cor_law − cor_entered`: what the lines mean differs from what was typed (a clamp, a
    /// fit); none without an entered COR.
    pub model_difference: Option<f64>,
    /// The step's error averaged over the start phases: the code's own law stepped as the code
    /// steps − the law exact.
    pub integration_difference: f64,
    /// `cor_realised_run − cor_law_stepped`: what nothing explains (the same at every phase).
    pub remainder: f64,
    /// The step's COR error over where the first contact falls within a step.
    pub integration_band: Range,
    /// Largest overlap over the smaller radius of the pair.
    pub peak_overlap_ratio: f64,
    /// The deck's time step, s.
    pub timestep: f64,
    /// Steps the impact ran.
    pub steps: u64,
    /// The gap between the surfaces at the start, m (the stepped law starts from it too).
    pub start_gap: f64,
    /// Contact time over the time step.
    pub steps_per_contact: f64,
    /// The smaller Rayleigh time of the pair's particles, s (none where the model takes no
    /// Young's modulus).
    pub rayleigh_time: Option<f64>,
    /// Time step over that Rayleigh time.
    pub step_over_rayleigh: Option<f64>,
    /// The paper's η that gives the COR realised (phase-averaged): `(1 − e²)/(1 + e²)`.
    pub paper_loss_coefficient: f64,
    /// The law the code integrates for the pair.
    pub law: CodeLaw,
    /// The convention traps the pair's lines meet.
    pub traps: Vec<String>,
    /// What is out of range or worth a look.
    pub warnings: Vec<String>,
    /// Why the run failed, if it did (its figures are then NaN).
    pub failure: Option<String>,
}

/// The quantities a deck's run is read for: COR, peak deformation (the overlap), contact time
/// by overlap and by force.
pub(crate) const REALISED: u8 = quantity::CHECKED | quantity::FORCE_CONTACT_TIME;

/// The realised figures of a run's trajectory.
fn realised_figures(m: &TrajectoryMetrics) -> Figures<f64, REALISED> {
    Figures {
        cor: m.cor,
        peak_deformation: m.peak_deformation,
        contact_time: m.contact_time,
        force_contact_time: m.force_contact_time,
        ..Figures::default()
    }
}

/// Writes realised figures under the names the deck's outputs give them: the COR as
/// `cor_realised` (beside `cor_entered` and `cor_law`), the peak deformation as `peak_overlap`
/// (an overlap of two bodies, beside its ratio to the radius).
fn realised_names<const Q: u8, S: Serializer>(
    figures: &Figures<f64, Q>,
    serializer: S,
) -> Result<S::Ok, S::Error> {
    let mut map = serializer.serialize_map(Some(Figures::<f64, Q>::quantities().count()))?;
    for (q, value) in figures.iter() {
        let name = match q {
            Quantity::Cor => "cor_realised",
            Quantity::PeakDeformation => "peak_overlap",
            _ => q.name(),
        };
        map.serialize_entry(name, value)?;
    }
    map.end()
}

/// What `deck` reports.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct DeckReport {
    /// The deck's file.
    pub deck: String,
    /// The code (build) that read and ran it.
    pub code: CodeName,
    /// The code's version as its runs printed it.
    pub code_version: Option<String>,
    /// The deck's time step, s.
    pub timestep: f64,
    /// Where it was set.
    pub timestep_from: String,
    /// The impact speeds, m/s.
    pub velocities: Vec<f64>,
    /// Where they come from.
    pub velocities_from: String,
    /// The particles.
    pub bodies: Vec<DeckBody>,
    /// The walls.
    pub walls: Vec<DeckWall>,
    /// What the deck holds that the impacts leave out.
    pub left_out: Vec<String>,
    /// One entry per pair and velocity.
    pub impacts: Vec<DeckImpact>,
    /// One oblique impact per wall with friction, at the first speed, against Coulomb's
    /// closed form (see [`tangential`]).
    pub tangential: Vec<DeckTangentialImpact>,
    /// Per pair checked at two speeds or more: its COR against the speed, realised and exact
    /// (empty at one speed).
    pub cor_against_speed: Vec<speed::SpeedCurve>,
    /// The command line's additions, for the reproduce line.
    #[serde(skip)]
    pub given: Vec<(&'static str, String)>,
}

/// A finished impact run as the check reads it.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ImpactRun {
    /// The trajectory the code wrote.
    pub trajectory: CodeTrajectory,
    /// The code's version as it printed it.
    pub code_version: String,
    /// What an oblique impact's run printed after its steps: the motions along the contact
    /// plane (none for a normal impact).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tangential: Option<TangentialRun>,
}

/// Runs the impacts of a deck: the installed code ([`LiveRunner`]), or runs recorded from it
/// ([`RecordedRuns`]).
pub trait ImpactRunner: Sync {
    /// Run `impact` of `code`, whose law is `law`.
    fn run(
        &self,
        code: CodeName,
        impact: &DeckImpactInput,
        law: &CodeLaw,
    ) -> Result<ImpactRun, CodeError>;
}

/// The installed codes, run under the runner's time limit and scratch rules.
#[derive(Clone, Debug, Default)]
pub struct LiveRunner {
    /// Time limit and scratch location.
    pub options: RunOptions,
}

impl ImpactRunner for LiveRunner {
    fn run(
        &self,
        code: CodeName,
        impact: &DeckImpactInput,
        _law: &CodeLaw,
    ) -> Result<ImpactRun, CodeError> {
        let driver = code.driver();
        let executable = locate(driver)?;
        // A deck's faults stop LIGGGHTS by MPI_Abort (too many sorting bins, a particle lost):
        // line-buffered, its log keeps the line that says why.
        let run = run_rendered(
            driver,
            &executable,
            &impact.setup,
            &impact.input,
            &self.options,
            Output::LineBuffered,
        )?;
        Ok(ImpactRun {
            trajectory: run.trajectory,
            code_version: run.code_version,
            tangential: TangentialRun::from_log(&run.log, TANGENTIAL_LINE),
        })
    }
}

/// Runs recorded from a live check, keyed by impact, to check a deck again without the code
/// (the snapshot tests read them).
#[derive(Debug, Default, Serialize, Deserialize)]
pub struct RecordedRuns {
    /// `case@velocity` → the run.
    pub runs: BTreeMap<String, ImpactRun>,
}

fn record_key(impact: &DeckImpactInput) -> String {
    format!(
        "{}@{}",
        impact.setup.case_name, impact.setup.impact_velocity
    )
}

impl ImpactRunner for RecordedRuns {
    fn run(
        &self,
        code: CodeName,
        impact: &DeckImpactInput,
        _law: &CodeLaw,
    ) -> Result<ImpactRun, CodeError> {
        self.runs
            .get(&record_key(impact))
            .cloned()
            .ok_or_else(|| CodeError::Unsupported {
                code: code.name().into(),
                case: impact.setup.case_name.clone(),
                reason: format!("no recorded run {}", record_key(impact)),
            })
    }
}

/// A runner that keeps what another returns, to be written as [`RecordedRuns`].
pub struct Recording<'a> {
    /// The runner that runs.
    pub inner: &'a dyn ImpactRunner,
    /// What it returned.
    pub runs: Mutex<RecordedRuns>,
}

impl ImpactRunner for Recording<'_> {
    fn run(
        &self,
        code: CodeName,
        impact: &DeckImpactInput,
        law: &CodeLaw,
    ) -> Result<ImpactRun, CodeError> {
        let run = self.inner.run(code, impact, law)?;
        if let Ok(mut runs) = self.runs.lock() {
            runs.runs.insert(record_key(impact), run.clone());
        }
        Ok(run)
    }
}

/// Read the deck at `path` with the reader of `code`, or of the first code that recognises it.
pub fn read_deck(
    path: &Path,
    code: Option<CodeName>,
    options: &DeckOptions,
) -> Result<(CodeName, UserDeck), DeckError> {
    let readers: Vec<CodeName> = match code {
        Some(c) => vec![c],
        None => CodeName::ALL.to_vec(),
    };
    let supported = || {
        CodeName::ALL
            .iter()
            // The paper builds read with their stock build's reader, named once (as it).
            .filter(|c| {
                !CodeName::ALL
                    .iter()
                    .any(|s| s.driver().paper_build().is_some_and(|p| p.code == **c))
            })
            .filter_map(|c| c.driver().deck().map(|d| format!("{c}: {}", d.reads())))
            .collect::<Vec<_>>()
            .join("; ")
    };
    if let Some(c) = code.filter(|c| c.driver().deck().is_none()) {
        return Err(DeckError::NoReader {
            path: path.to_path_buf(),
            code: c.to_string(),
            readers: CodeName::ALL
                .iter()
                .filter(|c| c.driver().deck().is_some())
                .map(|c| c.name())
                .collect::<Vec<_>>()
                .join(", "),
        });
    }
    let text = std::fs::read_to_string(path).map_err(|source| DeckError::Read {
        path: path.to_path_buf(),
        source,
    })?;
    for c in readers {
        let Some(reader) = c.driver().deck() else {
            continue;
        };
        if code.is_some() || reader.recognises(path, &text) {
            // A polydisperse pack is checked by size classes, whichever code reads it.
            return build_for(c, code, reader.read(path, options)?.in_size_classes());
        }
    }
    Err(DeckError::Unrecognised {
        path: path.to_path_buf(),
        supported: supported(),
    })
}

/// The build that runs `deck`, read by `read_by`'s reader: a deck whose lines select the
/// paper's law (LIGGGHTS' `model paper`, the LAMMPS plugin's styles) runs in the reader's
/// paper build, the build that has the law ([`CodeDriver::paper_build`]); asked for the stock
/// build (`asked`), such a deck is refused, since the stock build stops on the unknown style.
fn build_for(
    read_by: CodeName,
    asked: Option<CodeName>,
    deck: UserDeck,
) -> Result<(CodeName, UserDeck), DeckError> {
    let paper = deck
        .contacts
        .iter()
        .find(|c| matches!(c.law, CodeLaw::Paper(_)));
    match (read_by.driver().paper_build(), paper) {
        (Some(build), Some(c)) if asked == Some(read_by) => Err(DeckError::unsupported(
            c.lines[0].clone(),
            build.refusal(read_by, &c.model),
            build.instead,
        )),
        (Some(build), Some(_)) => Ok((build.code, deck)),
        _ => Ok((read_by, deck)),
    }
}

/// The label of a body: its type, with its radius where the type has several sizes.
fn body_label(deck: &UserDeck, body: usize) -> String {
    let b = &deck.bodies[body];
    if deck
        .bodies
        .iter()
        .filter(|o| o.type_id == b.type_id)
        .count()
        > 1
    {
        format!("{} (R {})", b.type_id, b.radius)
    } else {
        b.type_id.to_string()
    }
}

fn pair_label(deck: &UserDeck, contact: usize) -> String {
    let c = &deck.contacts[contact];
    let first = body_label(deck, c.body);
    match c.partner {
        Partner::Body(o) => format!("{first}–{}", body_label(deck, o)),
        Partner::Wall(w) if deck.walls.len() > 1 => format!("{first}–wall {}", deck.walls[w].name),
        Partner::Wall(_) => format!("{first}–wall"),
    }
}

/// Per contact, the contacts it stands for: itself and each later contact of the same
/// particle against a wall identical for it (the same law, model, COR entered and wall
/// material: their traps differ only by the wall's name), which is then run no more (a deck
/// with seven identical mesh walls checks one); empty for a contact another stands for.
fn identical_wall_groups(deck: &UserDeck) -> Vec<Vec<usize>> {
    let same = |a: &crate::codes::deck::DeckContact, b: &crate::codes::deck::DeckContact| {
        let (Partner::Wall(x), Partner::Wall(y)) = (a.partner, b.partner) else {
            return false;
        };
        let (x, y) = (&deck.walls[x], &deck.walls[y]);
        a.body == b.body
            && a.law == b.law
            && a.model == b.model
            && a.cor_entered == b.cor_entered
            && x.type_id == y.type_id
            && x.youngs_modulus == y.youngs_modulus
            && x.poisson_ratio == y.poisson_ratio
    };
    let mut groups: Vec<Vec<usize>> = vec![Vec::new(); deck.contacts.len()];
    let mut taken = vec![false; deck.contacts.len()];
    for (k, c) in deck.contacts.iter().enumerate() {
        if taken[k] {
            continue;
        }
        groups[k].push(k);
        for (j, other) in deck.contacts.iter().enumerate().skip(k + 1) {
            if !taken[j] && same(c, other) {
                taken[j] = true;
                groups[k].push(j);
            }
        }
    }
    groups
}

/// The label of a row that stands for the contacts `group`: the first's, with `×n` where it
/// stands for `n` identical walls.
fn group_label(deck: &UserDeck, group: &[usize]) -> String {
    let label = pair_label(deck, group[0]);
    if group.len() > 1 {
        format!("{label} ×{}", group.len())
    } else {
        label
    }
}

/// The names of the walls a row stands for (empty for one).
fn group_walls(deck: &UserDeck, group: &[usize]) -> Vec<String> {
    if group.len() < 2 {
        return Vec::new();
    }
    group
        .iter()
        .filter_map(|&k| match deck.contacts[k].partner {
            Partner::Wall(w) => Some(deck.walls[w].name.clone()),
            Partner::Body(_) => None,
        })
        .collect()
}

/// The impact speeds: the given ones, else half, once and twice a representative speed (the
/// deck's own, else `DEFAULT_VELOCITY`), with where they come from.
pub fn velocities(deck: &UserDeck, given: &[f64]) -> (Vec<f64>, String) {
    if !given.is_empty() {
        let mut given = given.to_vec();
        given.sort_by(f64::total_cmp);
        given.dedup_by(|a, b| a.total_cmp(b).is_eq());
        return (given, GIVEN.into());
    }
    let (v, from) = match &deck.representative_velocity {
        Some((v, from)) => (*v, format!("around the deck's {from}")),
        None => (
            DEFAULT_VELOCITY,
            format!("default: around {DEFAULT_VELOCITY} m/s; --impact-velocity to choose"),
        ),
    };
    (vec![0.5 * v, v, 2.0 * v], from)
}

/// One impact planned: its contact (with those it stands for), speed and input.
struct Planned {
    contact: usize,
    group: Vec<usize>,
    velocity: f64,
    steps: u64,
    impact: DeckImpactInput,
}

/// An impact as planned: run, or not run because its own law ends no contact.
enum Plan {
    /// Run in the code.
    Run(Box<Planned>),
    /// Not run: the law never separates the bodies (damping ratio ζ ≥ 1).
    NeverSeparates {
        contact: usize,
        group: Vec<usize>,
        velocity: f64,
        zeta: f64,
    },
}

/// Why a deck's check could not be planned (a run that fails is a row of the report, not this).
#[derive(Debug, Error)]
pub enum DeckCheckError {
    /// The code has no deck reader.
    #[error("{0} reads no decks")]
    NoReader(CodeName),
    /// A pair's own law could not be integrated at zero step error.
    #[error(transparent)]
    Law(#[from] crate::solve::SolveError),
    /// A speed or step the check cannot take (the user's to change).
    #[error(transparent)]
    User(#[from] crate::error::UserError),
    /// An impact's input could not be rendered.
    #[error(transparent)]
    Render(#[from] CodeError),
}

impl crate::error::Blame for DeckCheckError {
    fn is_user_error(&self) -> bool {
        matches!(self, DeckCheckError::User(_))
    }
}

/// Check `deck` (read by `code`) at `velocities`, running each impact with `runner`. Every
/// input is rendered before the first run, so that a deck that cannot be rendered runs nothing.
pub fn check_deck(
    code: CodeName,
    deck: &UserDeck,
    velocities: (Vec<f64>, String),
    runner: &dyn ImpactRunner,
) -> Result<DeckReport, DeckCheckError> {
    let reader = code.driver().deck().ok_or(DeckCheckError::NoReader(code))?;
    let driver = code.driver();
    let dt = deck.timestep;
    let mut planned = Vec::new();
    let groups = identical_wall_groups(deck);
    for (k, contact) in deck.contacts.iter().enumerate() {
        let group = &groups[k];
        if group.is_empty() {
            continue;
        }
        for &v in &velocities.0 {
            // A contact with no end has no step count and nothing a run could measure.
            if let Some(zeta) = contact.law.dashpot().and_then(DashpotLaw::never_separates) {
                planned.push(Plan::NeverSeparates {
                    contact: k,
                    group: group.clone(),
                    velocity: v,
                    zeta,
                });
                continue;
            }
            let exact = law_metrics(&contact.law, v, 1e-12)?;
            refuse_speed(deck, k, v, exact.peak_deformation, &velocities.1)?;
            let steps = ceil_count(1.05 * exact.contact_time / dt)
                .map_or(u64::MAX, |n| n.saturating_add(3));
            if steps > MAX_STEPS {
                let pair = pair_label(deck, k);
                let contact_time = exact.contact_time;
                return Err(if velocities.1 == GIVEN {
                    crate::error::UserError::argument(
                        "--impact-velocity",
                        format!("{v} m/s"),
                        format!("the contact of {pair} at this speed lasts {contact_time:.6e} s, {} steps of the deck's Δt = {dt:e} s, beyond the check's limit of {MAX_STEPS} steps; give a faster --impact-velocity", sci_steps(contact_time / dt)),
                    )
                } else {
                    crate::error::UserError::argument(
                        "timestep",
                        format!("{dt:e} s ({})", deck.timestep_from),
                        format!("a step that resolves the contact of {pair} at {v} m/s ({contact_time:e} s) in at most {MAX_STEPS} steps"),
                    )
                }
                .into());
            }
            let impact = reader.render(deck, k, v, steps)?;
            planned.push(Plan::Run(Box::new(Planned {
                contact: k,
                group: group.clone(),
                velocity: v,
                steps,
                impact,
            })));
        }
    }
    let oblique = plan_oblique(deck, &groups, reader, &velocities.0)?;
    // Each impact runs and is read on its own; the rows keep the plan's order.
    let rows: Vec<(DeckImpact, Option<String>)> = planned
        .par_iter()
        .map(|plan| match plan {
            Plan::Run(p) => match runner.run(code, &p.impact, &deck.contacts[p.contact].law) {
                Ok(run) => (
                    impact_row(deck, p, driver, Ok(&run.trajectory)),
                    Some(run.code_version),
                ),
                Err(e) => (impact_row(deck, p, driver, Err(&e)), None),
            },
            Plan::NeverSeparates {
                contact,
                group,
                velocity,
                zeta,
            } => (
                never_separating_row(deck, *contact, group, *velocity, *zeta),
                None,
            ),
        })
        .collect();
    let tangential: Vec<DeckTangentialImpact> = oblique
        .par_iter()
        .map(|o| {
            let run = runner.run(code, &o.impact, &deck.contacts[o.contact].law);
            let row = tangential::ObliqueRow {
                deck,
                contact: o.contact,
                pair: group_label(deck, &o.group),
                run: record_key(&o.impact),
                velocity: o.velocity,
                tangential_velocity: o.tangential_velocity,
            };
            row.row(run.as_ref())
        })
        .collect();
    let version = rows.iter().find_map(|(_, v)| v.clone());
    let mut impacts: Vec<DeckImpact> = rows.into_iter().map(|(row, _)| row).collect();
    let cor_against_speed = speed::speed_curves(&impacts);
    for curve in &cor_against_speed {
        if let Some(trap) = curve.trap() {
            for impact in impacts.iter_mut().filter(|i| i.pair == curve.pair) {
                impact.traps.push(trap.clone());
            }
        }
    }
    Ok(DeckReport {
        deck: deck.path.display().to_string(),
        code,
        code_version: version,
        timestep: dt,
        timestep_from: deck.timestep_from.clone(),
        velocities: velocities.0,
        velocities_from: velocities.1,
        bodies: deck.bodies.clone(),
        walls: deck.walls.clone(),
        left_out: tangential_left_out(deck, reader.reads_friction(), code),
        impacts,
        tangential,
        cor_against_speed,
        given: Vec::new(),
    })
}

/// One oblique impact planned: its contact (with those it stands for), speeds and input.
struct Oblique {
    contact: usize,
    group: Vec<usize>,
    velocity: f64,
    tangential_velocity: f64,
    impact: DeckImpactInput,
}

/// The oblique impacts of a deck: per wall contact whose lines give friction (μ > 0), one at
/// the first speed `v_n` with the slip `14 μ v_n` ([`tangential::SLIP_OVER_FRICTION`]), run as
/// long as the normal impact at that speed. A pair of balls has none yet (their contact normal
/// turns as they slide past each other, which the closed form of a fixed plane leaves out).
fn plan_oblique(
    deck: &UserDeck,
    groups: &[Vec<usize>],
    reader: &dyn crate::codes::deck::DeckReader,
    velocities: &[f64],
) -> Result<Vec<Oblique>, DeckCheckError> {
    let Some(&v) = velocities.first() else {
        return Ok(Vec::new());
    };
    let mut planned = Vec::new();
    for (k, contact) in deck.contacts.iter().enumerate() {
        let Some(friction) = &contact.friction else {
            continue;
        };
        if groups[k].is_empty()
            || !matches!(contact.partner, Partner::Wall(_))
            || contact
                .law
                .dashpot()
                .and_then(DashpotLaw::never_separates)
                .is_some()
        {
            continue;
        }
        let exact = law_metrics(&contact.law, v, 1e-12)?;
        let steps = ceil_count(1.05 * exact.contact_time / deck.timestep)
            .map_or(u64::MAX, |n| n.saturating_add(3));
        if steps > MAX_STEPS {
            // The normal impact at this speed is refused with the reason already.
            continue;
        }
        let slip = tangential::SLIP_OVER_FRICTION * friction.coefficient * v;
        if let Some(impact) = reader.render_oblique(deck, k, v, slip, steps)? {
            planned.push(Oblique {
                contact: k,
                group: groups[k].clone(),
                velocity: v,
                tangential_velocity: slip,
                impact,
            });
        }
    }
    Ok(planned)
}

/// The deck's left-out lines, and where its reader reads no friction, that no oblique impact
/// is run.
fn tangential_left_out(deck: &UserDeck, reads_friction: bool, code: CodeName) -> Vec<String> {
    let mut left_out = deck.left_out.clone();
    if !reads_friction {
        left_out.push(format!(
            "friction: the {code} deck reader reads no tangential lines, so no oblique impact is run"
        ));
    }
    left_out
}

/// Where given speeds come from (see [`velocities`]).
const GIVEN: &str = "given";

/// A step count to three digits (`2.50e7`).
fn sci_steps(steps: f64) -> String {
    format!("{steps:.2e}")
}

/// Refuse a speed at which the pair's own law presses the surfaces together by more than the
/// smaller radius (`peak`, m, the law's peak overlap at `velocity`): no run of it means anything,
/// and the codes stop or blow up without a word the check could read.
fn refuse_speed(
    deck: &UserDeck,
    contact: usize,
    velocity: f64,
    peak: f64,
    from: &str,
) -> Result<(), crate::error::UserError> {
    let c = &deck.contacts[contact];
    let body = &deck.bodies[c.body];
    let radius = match c.partner {
        Partner::Body(o) => body.radius.min(deck.bodies[o].radius),
        Partner::Wall(_) => body.radius,
    };
    if peak <= radius {
        return Ok(());
    }
    let pair = pair_label(deck, contact);
    // The largest speed the law takes: the peak overlap grows as a power of the speed, so
    // one bisection on the law's own peak finds it.
    let limit = largest_speed(&c.law, radius, velocity);
    let what = format!(
        "the law of {pair} presses the surfaces {peak:.3e} m together at this speed, beyond the radius {radius} m (the peak overlap {:.3e} × R){}",
        peak / radius,
        limit.map_or(String::new(), |v| format!("; it takes at most {v:.3e} m/s"))
    );
    Err(if from == GIVEN {
        crate::error::UserError::argument(
            "--impact-velocity",
            format!("{velocity} m/s"),
            format!("{what}: give a slower --impact-velocity"),
        )
    } else {
        crate::error::UserError::argument(
            "the default impact speed",
            format!("{velocity} m/s ({from})"),
            format!("{what}: give --impact-velocity"),
        )
    })
}

/// The speed at which `law`'s peak overlap is `radius` (m), below `above` (m/s), to three
/// digits; none where the law's figures cannot be computed.
fn largest_speed(law: &CodeLaw, radius: f64, above: f64) -> Option<f64> {
    let peak = |v: f64| law_metrics(law, v, 1e-9).ok().map(|m| m.peak_deformation);
    let (mut low, mut high) = (above, above);
    while peak(low)? > radius {
        high = low;
        low /= 10.0;
        if low < 1e-12 {
            return None;
        }
    }
    for _ in 0..60 {
        let mid = (low * high).sqrt();
        if peak(mid)? > radius {
            high = mid;
        } else {
            low = mid;
        }
        if high / low < 1.0 + 1e-4 {
            break;
        }
    }
    Some(low)
}

/// The figures of `law`'s impact at `impact_velocity` (m/s) at zero step error: a
/// spring–dashpot's solved to `rtol`, the paper's law's in closed form.
fn law_metrics(
    law: &CodeLaw,
    impact_velocity: f64,
    rtol: f64,
) -> Result<TrajectoryMetrics, crate::solve::SolveError> {
    match law {
        CodeLaw::Dashpot(law) => accurate_metrics(law, impact_velocity, rtol),
        CodeLaw::Paper(law) => Ok(exact::paper_impact(law, impact_velocity).metrics()),
    }
}

/// The COR of `law` stepped as the code steps the run `impact`, started a further `phase` (m)
/// away than the run itself.
fn stepped_cor(
    law: &CodeLaw,
    stepping: &CodeStepping,
    impact: &DeckImpactInput,
    steps: u64,
    phase: f64,
) -> f64 {
    let setup = &impact.setup;
    // A code stepped in its own frame starts where the run starts (the frame holds the gap);
    // one stepped in the relative motion starts from touch, so the run's gap is added.
    let gap = if stepping.frame.is_some() {
        phase
    } else {
        impact.start_gap + phase
    };
    let trajectory = stepping.trajectory(law, setup.impact_velocity, setup.timestep, steps, gap);
    trajectory_metrics(&trajectory).map_or(f64::NAN, |m| m.cor)
}

/// `ω Δt` at the contact's stiffest, its peak overlap `peak` (m): `ω² = (dF/dy)/M` of the
/// law's elastic force `k yⁿ`, whose stiffness `n k yⁿ⁻¹` grows with the overlap.
fn step_stability(law: &CodeLaw, peak: f64, timestep: f64) -> f64 {
    let n = law.exponent();
    let stiffness = n * law.stiffness() * peak.powf(n - 1.0);
    (stiffness / ContactForce::mass(law)).sqrt() * timestep
}

/// An impact speed, m/s, to four significant digits with no trailing zeros (`0.5`, `1.235`):
/// a speed derived from a deck's own (half of it, twice it) is not printed to 16 digits.
pub(crate) fn speed_text(v: f64) -> String {
    if !v.is_normal() {
        return v.to_string();
    }
    // Digits after the point for four significant ones, none below zero.
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    let decimals = (3.0 - v.abs().log10().floor()).clamp(0.0, 15.0) as usize;
    let text = format!("{v:.decimals$}");
    if text.contains('.') {
        text.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        text
    }
}

/// A COR or η to six decimals, never `-0.000000` (a value that rounds to zero is zero).
fn fixed(x: f64) -> String {
    let text = format!("{x:.6}");
    match text.strip_prefix('-') {
        Some(rest) if rest.bytes().all(|b| b == b'0' || b == b'.') => rest.to_string(),
        _ => text,
    }
}

/// The smaller Rayleigh time of a pair's particles, s (none where a particle has no Young's
/// modulus).
fn smallest_rayleigh_time(body: &DeckBody, partner: Option<&DeckBody>) -> Option<f64> {
    [Some(body), partner]
        .into_iter()
        .flatten()
        .map(|b| match (b.youngs_modulus, b.poisson_ratio) {
            (Some(e), Some(nu)) => Some(rayleigh_time(b.radius, b.density, e, nu)),
            _ => None,
        })
        .collect::<Option<Vec<f64>>>()
        .map(|t| t.into_iter().fold(f64::INFINITY, f64::min))
}

/// The row of an impact not run because its law never separates the bodies: the law and the
/// traps, the figures NaN, and why.
fn never_separating_row(
    deck: &UserDeck,
    contact: usize,
    group: &[usize],
    velocity: f64,
    zeta: f64,
) -> DeckImpact {
    let c = &deck.contacts[contact];
    let body = &deck.bodies[c.body];
    let partner_body = match c.partner {
        Partner::Body(o) => Some(&deck.bodies[o]),
        Partner::Wall(_) => None,
    };
    let nan = f64::NAN;
    let rayleigh = smallest_rayleigh_time(body, partner_body);
    let pair = group_label(deck, group);
    DeckImpact {
        types: c.types,
        run: format!("{pair}@{velocity} (not run)"),
        pair,
        wall: match c.partner {
            Partner::Wall(w) => Some(deck.walls[w].name.clone()),
            Partner::Body(_) => None,
        },
        identical_walls: group_walls(deck, group),
        model: c.model.clone(),
        radius: body.radius,
        partner_radius: partner_body.map(|o| o.radius),
        impact_velocity: velocity,
        cor_entered: c.cor_entered,
        realised: Figures {
            contact_time: f64::INFINITY,
            force_contact_time: f64::INFINITY,
            ..Figures::splat(nan)
        },
        cor_realised_band: Range { min: nan, max: nan },
        cor_realised_run: nan,
        cor_law: 0.0,
        cor_law_stepped: nan,
        model_difference: c.cor_entered.map(|e| -e),
        integration_difference: nan,
        remainder: nan,
        integration_band: Range { min: nan, max: nan },
        peak_overlap_ratio: nan,
        timestep: deck.timestep,
        steps: 0,
        start_gap: 0.0,
        steps_per_contact: f64::INFINITY,
        rayleigh_time: rayleigh,
        step_over_rayleigh: rayleigh.map(|t| deck.timestep / t),
        paper_loss_coefficient: nan,
        law: c.law,
        traps: c.traps.clone(),
        warnings: Vec::new(),
        failure: Some(format!(
            "not run: the law these lines make the code integrate is a linear spring with a dashpot of damping ratio ζ = {zeta:.4e} ≥ 1, overdamped: the bodies approach and creep back without ever separating (COR 0, no end of contact to run to)"
        )),
    }
}

fn impact_row(
    deck: &UserDeck,
    p: &Planned,
    driver: &dyn CodeDriver,
    run: Result<&CodeTrajectory, &CodeError>,
) -> DeckImpact {
    let c = &deck.contacts[p.contact];
    let body = &deck.bodies[c.body];
    let partner_body = match c.partner {
        Partner::Body(o) => Some(&deck.bodies[o]),
        Partner::Wall(_) => None,
    };
    let v = p.velocity;
    let dt = deck.timestep;
    let law = c.law;
    let exact = law_metrics(&law, v, 1e-12).ok();
    let cor_law = exact.map_or(f64::NAN, |m| m.cor);
    let rayleigh = smallest_rayleigh_time(body, partner_body);
    let smaller_radius = partner_body.map_or(body.radius, |o| o.radius.min(body.radius));
    let (metrics, failure) = match run {
        Ok(t) => match trajectory_metrics(t) {
            Ok(m) => (Some(m), None),
            Err(e) => (None, Some(format!("the run's trajectory: {e}"))),
        },
        Err(e) => (None, Some(e.to_string())),
    };
    let nan = f64::NAN;
    // A failed run has no figures: not even the law stepped, which would read as the run's.
    let mut band = Range { min: nan, max: nan };
    let (mut cor_law_stepped, mut integration) = (nan, nan);
    if metrics.is_some() {
        let stepping = driver.stepping(&p.impact.setup);
        cor_law_stepped = stepped_cor(&law, &stepping, &p.impact, p.steps, 0.0);
        // A gap of φ v0 Δt more puts the first contact a fraction φ of a step earlier; one
        // step more covers it.
        (integration, band) = over_phases(DEFAULT_PHASES, |phi| {
            stepped_cor(&law, &stepping, &p.impact, p.steps + 1, phi * v * dt) - cor_law
        });
    }
    let mut realised = metrics
        .as_ref()
        .map_or(Figures::splat(nan), realised_figures);
    let cor_realised_run = realised.cor;
    // What the code does beyond its law stepped does not depend on where the contact falls
    // within a step: the run's own remainder, carried to every phase.
    let remainder = cor_realised_run - cor_law_stepped;
    realised.cor = cor_law + integration + remainder;
    let cor_realised_band = Range {
        min: cor_law + band.min + remainder,
        max: cor_law + band.max + remainder,
    };
    let cor_realised = realised.cor;
    let steps_per_contact = realised.contact_time / dt;
    let mut warnings = Vec::new();
    let ratio = realised.peak_deformation / smaller_radius;
    if ratio > HERTZ_MAX_STRAIN {
        warnings.push(format!(
            "small strain: the peak overlap is {:.2} % of the radius, beyond Hertz's small-strain range (δ/R ≤ {} %); the law's force and the contact time are not the material's there",
            100.0 * ratio,
            100.0 * HERTZ_MAX_STRAIN
        ));
    }
    if steps_per_contact < MIN_STEPS_PER_CONTACT {
        warnings.push(format!(
            "resolution: {steps_per_contact:.1} steps per contact (below {MIN_STEPS_PER_CONTACT}): the step alone moves the COR by {} to {}",
            signed(band.min),
            signed(band.max)
        ));
    }
    let stiffest = exact.map_or(nan, |m| step_stability(&law, m.peak_deformation, dt));
    // The step's own predicted error: the code's law stepped as the code steps, at its worst
    // start phase; a run that stays within it (COR 1 to 2e-10 at thousands of steps per
    // contact) gains nothing the step does not explain.
    let predicted = band.min.abs().max(band.max.abs());
    // Velocity Verlet's and leap-frog's limit: beyond it a step multiplies the energy of an
    // oscillation instead of keeping it.
    let limit = Method::Verlet.stability_limit().unwrap_or(f64::INFINITY);
    if stiffest > limit {
        warnings.push(format!(
            "unstable: at the peak overlap the contact's stiffness gives ω Δt = {stiffest:.2}, beyond the stability limit {limit} of the code's step (velocity Verlet or leap-frog): the step ({} s, {steps_per_contact:.1} steps per contact) integrates this contact unstably, and the COR it gives ({}) is the step's, not the law's",
            sci(dt),
            fixed(cor_realised)
        ));
    } else if cor_realised - 1.0 > predicted + REMAINDER_TOLERANCE {
        warnings.push(format!(
            "energy gain: the phase-averaged COR {} exceeds 1 by {:.2e}, beyond the step's own predicted error {predicted:.2e} (the code's law stepped as it steps, at its worst start phase): the bodies leave faster than they came by more than the step explains",
            fixed(cor_realised),
            cor_realised - 1.0
        ));
    }
    let step_over_rayleigh = rayleigh.map(|t| dt / t);
    if let Some(f) = step_over_rayleigh.filter(|f| *f > MAX_RAYLEIGH_FRACTION) {
        warnings.push(format!(
            "time step: {:.0} % of the Rayleigh time {} s (the usual rule keeps it below {:.0} %)",
            100.0 * f,
            sci(rayleigh.unwrap_or(nan)),
            100.0 * MAX_RAYLEIGH_FRACTION
        ));
    }
    let model_difference = c.cor_entered.map(|e| cor_law - e);
    if let Some(d) = model_difference.filter(|d| d.abs() > 1e-6) {
        warnings.push(format!(
            "model: these lines realise a COR of {cor_law:.6} at zero step error, {} from the {:.6} entered (see the traps)",
            signed(d),
            c.cor_entered.unwrap_or(nan)
        ));
    }
    if (remainder / cor_law_stepped).abs() > REMAINDER_TOLERANCE {
        warnings.push(format!(
            "remainder: the run differs from the code's own law stepped as it steps by {} in COR (more than {REMAINDER_TOLERANCE:e}): the code does something its lines, as read, do not say",
            signed(remainder)
        ));
    }
    DeckImpact {
        types: c.types,
        pair: group_label(deck, &p.group),
        run: record_key(&p.impact),
        wall: match c.partner {
            Partner::Wall(w) => Some(deck.walls[w].name.clone()),
            Partner::Body(_) => None,
        },
        identical_walls: group_walls(deck, &p.group),
        model: c.model.clone(),
        radius: body.radius,
        partner_radius: partner_body.map(|o| o.radius),
        impact_velocity: v,
        cor_entered: c.cor_entered,
        realised,
        cor_realised_band,
        cor_realised_run,
        cor_law,
        cor_law_stepped,
        model_difference,
        integration_difference: integration,
        remainder,
        integration_band: band,
        peak_overlap_ratio: ratio,
        timestep: dt,
        steps: p.steps,
        start_gap: p.impact.start_gap,
        steps_per_contact,
        rayleigh_time: rayleigh,
        step_over_rayleigh,
        paper_loss_coefficient: exact::loss_coefficient(cor_realised),
        law,
        traps: c.traps.clone(),
        warnings,
        failure,
    }
}

/// One impact as a CSV row.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct DeckImpactRecord {
    /// The deck.
    pub deck: String,
    /// The code.
    pub code: CodeName,
    /// The pair's label.
    pub pair: String,
    /// The first type.
    pub first_type: String,
    /// The second type, or `wall`.
    pub second_type: String,
    /// Impact speed, m/s.
    pub impact_velocity: f64,
    /// The COR entered.
    pub cor_entered: Option<f64>,
    /// The COR realised (`cor_realised`), the peak overlap (`peak_overlap`, m) and the contact
    /// time (s).
    #[serde(flatten, serialize_with = "realised_names")]
    pub realised: Checked,
    /// The own law's COR, exact.
    pub cor_law: f64,
    /// The own law's COR, stepped.
    pub cor_law_stepped: f64,
    /// Model difference.
    pub model_difference: Option<f64>,
    /// Integration difference.
    pub integration_difference: f64,
    /// Remainder.
    pub remainder: f64,
    /// Peak overlap over the smaller radius.
    pub peak_overlap_ratio: f64,
    /// Time step, s.
    pub timestep: f64,
    /// Steps per contact.
    pub steps_per_contact: f64,
    /// Time step over the Rayleigh time.
    pub step_over_rayleigh: Option<f64>,
    /// The paper's η for the COR realised.
    pub paper_loss_coefficient: f64,
    /// Warnings, joined by ` | `.
    pub warnings: String,
    /// The smallest COR realised over the start phases (`cor_realised` is the mean).
    pub cor_realised_min: f64,
    /// The largest.
    pub cor_realised_max: f64,
    /// The COR of the run itself (first contact at the start of a step).
    pub cor_realised_run: f64,
    /// The oblique impact's tangential speed at the start, m/s, on the row of the pair and
    /// speed where one was run (a wall with friction, at the first speed); the columns after it
    /// are that impact's, each empty elsewhere.
    pub tangential_velocity: Option<f64>,
    /// The tangential damping of the lines the oblique run turned off.
    pub tangential_damping_off: Option<String>,
    /// Coulomb's μ of the lines.
    pub friction_coefficient: Option<f64>,
    /// The ball's tangential velocity after, as the code gives it, m/s.
    pub tangential_velocity_out: Option<f64>,
    /// Its spin after, as the code gives it, rad/s.
    pub angular_velocity_out: Option<f64>,
    /// The tangential velocity after, from Coulomb sliding throughout, m/s.
    pub tangential_velocity_closed_form: Option<f64>,
    /// The spin after, from Coulomb sliding throughout, rad/s.
    pub angular_velocity_closed_form: Option<f64>,
    /// The code's change of tangential velocity less the closed form's, m/s.
    pub tangential_difference: Option<f64>,
    /// What it may be, m/s.
    pub tangential_tolerance: Option<f64>,
    /// Whether the tangential row failed.
    pub tangential_failed: Option<bool>,
}

fn percent(x: f64) -> String {
    if x.is_nan() {
        "n/a".into()
    } else {
        format!("{:.3} %", 100.0 * x)
    }
}

impl Summary for DeckReport {
    type Record = DeckImpactRecord;

    /// The pair and the speed.
    fn key_columns(&self) -> usize {
        2
    }

    fn records(&self) -> Vec<DeckImpactRecord> {
        self.impacts
            .iter()
            .map(|i| {
                let t = self.tangential.iter().find(|t| {
                    t.pair == i.pair && t.impact_velocity.total_cmp(&i.impact_velocity).is_eq()
                });
                DeckImpactRecord {
                    deck: self.deck.clone(),
                    code: self.code,
                    pair: i.pair.clone(),
                    first_type: i.types[0].to_string(),
                    second_type: i.types[1].to_string(),
                    impact_velocity: i.impact_velocity,
                    cor_entered: i.cor_entered,
                    realised: i.realised.select(),
                    cor_law: i.cor_law,
                    cor_law_stepped: i.cor_law_stepped,
                    model_difference: i.model_difference,
                    integration_difference: i.integration_difference,
                    remainder: i.remainder,
                    peak_overlap_ratio: i.peak_overlap_ratio,
                    timestep: i.timestep,
                    steps_per_contact: i.steps_per_contact,
                    step_over_rayleigh: i.step_over_rayleigh,
                    paper_loss_coefficient: i.paper_loss_coefficient,
                    warnings: i.warnings.join(" | "),
                    cor_realised_min: i.cor_realised_band.min,
                    cor_realised_max: i.cor_realised_band.max,
                    cor_realised_run: i.cor_realised_run,
                    tangential_velocity: t.map(|t| t.tangential_velocity),
                    tangential_damping_off: t.and_then(|t| t.tangential_damping_off.clone()),
                    friction_coefficient: t.map(|t| t.friction_coefficient),
                    tangential_velocity_out: t.map(|t| t.tangential_velocity_out),
                    angular_velocity_out: t.map(|t| t.angular_velocity_out),
                    tangential_velocity_closed_form: t.map(|t| t.tangential_velocity_closed_form),
                    angular_velocity_closed_form: t.map(|t| t.angular_velocity_closed_form),
                    tangential_difference: t.map(|t| t.difference),
                    tangential_tolerance: t.map(|t| t.tolerance),
                    tangential_failed: t.map(|t| t.failed || t.failure.is_some()),
                }
            })
            .collect()
    }

    fn sections(&self) -> Vec<Section> {
        let speeds: Vec<String> = self.velocities.iter().map(|&v| speed_text(v)).collect();
        let mut table = Section::new(
            Some(format!(
                "{}: {} ({}), Δt = {} s ({}); impact speeds {} m/s ({})",
                self.deck,
                self.code,
                self.code_version.as_deref().unwrap_or("not run"),
                sci(self.timestep),
                self.timestep_from,
                speeds.join(", "),
                self.velocities_from
            )),
            &[
                "pair",
                "v0 (m/s)",
                "COR entered",
                "COR realised, phase-averaged [band]",
                "model / integration / remainder",
                "contact time (s)",
                "steps per contact [step's COR band]",
                "peak overlap / R",
                "Δt / Rayleigh time",
                "paper's η",
            ],
        );
        for i in &self.impacts {
            if i.failure.is_some() {
                // No figures for a run that failed: why is under warnings.
                let mut row = vec![
                    i.pair.clone(),
                    speed_text(i.impact_velocity),
                    i.cor_entered.map_or("—".into(), |e| format!("{e}")),
                    // A planned impact with no steps was never run (its law never separates).
                    if i.steps == 0 {
                        "not run (see warnings)"
                    } else {
                        "failed (see warnings)"
                    }
                    .to_string(),
                ];
                row.resize(table.headers.len(), "—".to_string());
                table.rows.push(row);
                continue;
            }
            table.rows.push(vec![
                i.pair.clone(),
                speed_text(i.impact_velocity),
                i.cor_entered.map_or("—".into(), |e| format!("{e}")),
                format!(
                    "{} [{}, {}]",
                    fixed(i.realised.cor),
                    fixed(i.cor_realised_band.min),
                    fixed(i.cor_realised_band.max)
                ),
                format!(
                    "{} / {} / {}",
                    i.model_difference.map_or("—".into(), signed),
                    signed(i.integration_difference),
                    signed(i.remainder)
                ),
                sci(i.realised.contact_time),
                format!(
                    "{:.1} [{}, {}]",
                    i.steps_per_contact,
                    signed(i.integration_band.min),
                    signed(i.integration_band.max)
                ),
                percent(i.peak_overlap_ratio),
                i.step_over_rayleigh.map_or("—".into(), percent),
                fixed(i.paper_loss_coefficient),
            ]);
        }
        table.notes.push(format!("COR realised, phase-averaged: a user's run meets its first contacts anywhere within a step, so the COR is averaged over {DEFAULT_PHASES} start phases (the run's own at the start of a step, the code's law stepped from the others plus the run's remainder), in brackets its smallest and largest"));
        table.notes.push("model: the COR of the code's own law (what these lines make it integrate) − the COR entered; integration: that law stepped as the code steps − the law exact, phase-averaged; remainder: the run − the law stepped from the run's start; the step's COR band: the step's COR error over the start phases".into());
        let mut merged: Vec<String> = self
            .impacts
            .iter()
            .filter(|i| !i.identical_walls.is_empty())
            .map(|i| format!("{}: walls {}", i.pair, i.identical_walls.join(", ")))
            .collect();
        merged.dedup();
        if !merged.is_empty() {
            table.notes.push(format!(
                "identical walls (the same law, model, COR entered and material for the particle), one row and one impact for all: {}",
                merged.join("; ")
            ));
        }
        let mut out = vec![table];
        if !self.tangential.is_empty() {
            out.push(tangential_section(&self.tangential));
        }
        if !self.cor_against_speed.is_empty() {
            out.push(speed_section(&self.cor_against_speed));
        }
        let material = |e: Option<f64>, nu: Option<f64>| match (e, nu) {
            (Some(e), Some(nu)) => format!(", E = {e:e} Pa, ν = {nu}"),
            _ => String::new(),
        };
        let mut bodies = vec!["particles:".to_string()];
        for b in &self.bodies {
            bodies.push(format!(
                "  type {}: R = {} m, ρ = {} kg/m³, m = {} kg{} (from {})",
                b.type_id,
                b.radius,
                b.density,
                sci(b.mass),
                material(b.youngs_modulus, b.poisson_ratio),
                b.from
            ));
        }
        for w in &self.walls {
            let t = w.type_id.map_or(String::new(), |t| format!(" type {t}"));
            let material = material(w.youngs_modulus, w.poisson_ratio);
            bodies.push(format!("  wall {}{t}{material} ({})", w.name, w.from));
        }
        out.push(Section::text(bodies));
        let mut traps = vec!["traps of these lines:".to_string()];
        let mut seen = std::collections::HashSet::new();
        for i in self.impacts.iter().filter(|i| seen.insert(&i.pair)) {
            traps.push(format!("  {} (model {}):", i.pair, i.model));
            traps.extend(i.traps.iter().map(|t| format!("    {t}")));
        }
        out.push(Section::text(traps));
        let warned: Vec<String> = self
            .impacts
            .iter()
            .flat_map(|i| {
                let at = format!("{} at {} m/s", i.pair, speed_text(i.impact_velocity));
                i.failure
                    .iter()
                    .map(|f| format!("failed: {f}"))
                    .chain(i.warnings.iter().cloned())
                    .map(move |w| format!("  {at}: {w}"))
            })
            .chain(
                self.tangential
                    .iter()
                    .filter_map(tangential_failure)
                    .map(|f| format!("  {f}")),
            )
            .collect();
        if !warned.is_empty() {
            let mut lines = vec!["warnings:".to_string()];
            lines.extend(warned);
            out.push(Section::text(lines));
        }
        if !self.left_out.is_empty() {
            let mut lines = vec![
                "left out of the impacts (the deck's own run needs them; one impact does not):"
                    .to_string(),
            ];
            lines.extend(self.left_out.iter().map(|l| format!("  {l}")));
            out.push(Section::text(lines));
        }
        out
    }

    fn footer(&self) -> Vec<String> {
        vec![format!("reproduce: {}", self.reproduce())]
    }
}

/// The tangential rows: per wall with friction, the oblique impact against Coulomb's closed
/// form.
fn tangential_section(rows: &[DeckTangentialImpact]) -> Section {
    let mut section = Section::new(
        Some("tangential: one oblique impact per wall with friction, in gross sliding".to_string()),
        &[
            "pair",
            "tangential model",
            "v_n, v_t (m/s)",
            "COR realised",
            "v_t' code / closed form (m/s)",
            "ω' code / closed form (rad/s)",
            "Δv_t code − closed [tolerance] (m/s)",
            "check",
        ],
    );
    for t in rows {
        let mut row = vec![
            t.pair.clone(),
            match &t.tangential_damping_off {
                Some(d) => format!("{} ({d} off)", t.tangential_model),
                None => t.tangential_model.clone(),
            },
            format!(
                "{}, {}",
                speed_text(t.impact_velocity),
                speed_text(t.tangential_velocity)
            ),
        ];
        if t.failure.is_some() {
            row.push("failed (see warnings)".into());
            row.resize(section.headers.len(), "—".to_string());
            section.rows.push(row);
            continue;
        }
        row.extend([
            fixed(t.cor_realised),
            format!(
                "{} / {}",
                fixed(t.tangential_velocity_out),
                fixed(t.tangential_velocity_closed_form)
            ),
            format!(
                "{:.3} / {:.3}",
                t.angular_velocity_out, t.angular_velocity_closed_form
            ),
            format!("{} [{}]", signed(t.difference), sci(t.tolerance)),
            if t.failed { "FAILED" } else { "ok" }.to_string(),
        ]);
        section.rows.push(row);
    }
    section.notes.push(format!(
        "the deck's first speed v_n with the ball sliding along the plane at v_t = {} μ v_n (twice the rigid-body bound (7/2) μ (1+e) v_n at e = 1: Coulomb sliding throughout), the wall's own lines with their tangential damping off (\"off\": a damped history spring lags its bound by what its build decides, which the closed form does not hold; Coulomb's bound is what is checked); closed form: the tangential impulse μ (1+e) M* v_n against the slip, e the normal COR this run realised; tolerance: {} of the closed form's change (the history spring reaches the bound within the first steps), plus the friction of the run's attractive tail where a code bounds by μ|F_n|",
        tangential::SLIP_OVER_FRICTION,
        percent(tangential::RELATIVE_TOLERANCE)
    ));
    section
}

/// The COR against the speed, per pair: realised, the law's exact curve, Müller & Pöschel's
/// closed form where the law is viscoelastic.
fn speed_section(curves: &[speed::SpeedCurve]) -> Section {
    let mut section = Section::new(
        Some("COR against impact speed".to_string()),
        &[
            "pair",
            "v0 (m/s)",
            "COR realised",
            "law, exact",
            "realised − law",
            "Müller & Pöschel",
            "closed form − law",
        ],
    );
    for curve in curves {
        for (k, &v) in curve.speeds.iter().enumerate() {
            let closed = curve.cor_closed_form.as_ref().map(|c| c[k]);
            let (realised, law) = (curve.cor_realised[k], curve.cor_law[k]);
            section.rows.push(vec![
                curve.pair.clone(),
                speed_text(v),
                if realised.is_finite() {
                    fixed(realised)
                } else {
                    "—".into()
                },
                format!("{law:.6}"),
                if realised.is_finite() {
                    signed(realised - law)
                } else {
                    "—".into()
                },
                closed.map_or("—".into(), |c| format!("{c:.6}")),
                closed.map_or("—".into(), |c| signed(c - law)),
            ]);
        }
    }
    section.notes.push(format!(
        "law, exact: the pair's own law integrated at zero step error at each speed; a law whose COR spreads by more than {:e} over the speeds is named under traps; Müller & Pöschel: their [3/6] Padé approximant of the viscoelastic COR (Phys. Rev. E 84, 021302, 2011), which ends a collision where the force vanishes, i.e. the clamped law's (`limit_damping`)",
        speed::SPEED_DEPENDENCE
    ));
    section
}

impl DeckReport {
    /// The `deck` command that checks the deck again, as this check did.
    pub(crate) fn reproduce(&self) -> Invocation {
        let mut command = Invocation::new("deck")
            .arg(&self.deck)
            .option("--code", self.code);
        for v in &self.velocities {
            command = command.option("--impact-velocity", v);
        }
        for (option, value) in &self.given {
            command = command.option(option, value);
        }
        command
    }
}

/// The failures of a report's runs, one line each (empty when every run finished and every
/// tangential row met its closed form).
pub(crate) fn failures(report: &DeckReport) -> Vec<String> {
    report
        .impacts
        .iter()
        .filter_map(|i| {
            i.failure
                .as_ref()
                .map(|f| format!("{} at {} m/s: {f}", i.pair, speed_text(i.impact_velocity)))
        })
        .chain(report.tangential.iter().filter_map(tangential_failure))
        .collect()
}

/// The failure of a tangential row, naming its wall and "tangential".
fn tangential_failure(t: &DeckTangentialImpact) -> Option<String> {
    let at = format!(
        "{} tangential ({}, {}{}) at {} m/s",
        t.wall
            .as_ref()
            .map_or_else(|| t.pair.clone(), |w| format!("wall {w}")),
        t.pair,
        t.tangential_model,
        t.tangential_damping_off
            .as_ref()
            .map_or(String::new(), |d| format!(", {d} off")),
        speed_text(t.impact_velocity)
    );
    if let Some(f) = &t.failure {
        return Some(format!("{at}: {f}"));
    }
    t.failed.then(|| {
        format!(
            "{at}: the ball leaves at v_t' = {:.6} m/s, ω' = {:.2} rad/s where Coulomb sliding throughout gives {:.6} m/s, {:.2} rad/s (μ(1+e)v_n with the run's own e = {:.6}): the code delivers {:.1} % of its friction, off by {} m/s beyond the tolerance {} m/s",
            t.tangential_velocity_out,
            t.angular_velocity_out,
            t.tangential_velocity_closed_form,
            t.angular_velocity_closed_form,
            t.cor_realised,
            100.0 * (t.tangential_velocity - t.tangential_velocity_out)
                / (t.tangential_velocity - t.tangential_velocity_closed_form),
            signed(t.difference),
            sci(t.tolerance)
        )
    })
}
