//! A user's whole mill run under two laws, and what changes (`millimpact mill`): the deck as
//! written and the deck switched between damped Hertz and the paper's law at equal COR per type
//! pair ([`MillDeck`]), each run in its own process (both at once), and per law the power the
//! drum draws, the charge's kinetic energy, the collision spectra per pair of types and against
//! the liner, and the fraction of contacts at rest, each with its standard error, and the
//! difference between the laws with its own.

mod charge;
mod contacts;
mod report;
mod stats;

use std::path::{Path, PathBuf};
use std::sync::Mutex;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Duration;

use thiserror::Error;

pub use contacts::{ContactEvent, ContactSample};
pub(crate) use report::TRACE_POINTS;
pub use report::{
    MillRecord, MillReport, MillRun, PowerBalance, ProfilePoint, QuantityRow, SpectrumRow,
    TracePoint, Verdict, difference,
};
pub use stats::{Estimate, MIN_SEEDS};

use crate::codes::deck::DeckError;
use crate::codes::liggghts::mill::{
    ATOMS_FILE, ENERGY_FILE, MAX_SEEDS, MillDeck, MillLaw, MillPlan, PAIRS_FILE, POSITIONS_FILE,
    RotatingMesh, WALLS_FILE,
};
use crate::codes::runner::locate;
use crate::codes::runner::process::{Output, Process, Step};
use crate::codes::{CodeError, CodeName};

/// Why a mill comparison did not come to a result.
#[derive(Debug, Error)]
pub enum MillError {
    /// The deck cannot be run as the comparison needs (the user's: exit 2).
    #[error(transparent)]
    Deck(#[from] DeckError),
    /// An option does not fit the deck (the user's: exit 2).
    #[error("{deck}: {option} = {value}: {allowed}")]
    Option {
        /// The deck.
        deck: PathBuf,
        /// The option.
        option: &'static str,
        /// Its value.
        value: String,
        /// What is allowed.
        allowed: String,
    },
    /// A run of the deck failed (the code's fault or the deck's at run time: exit 1).
    #[error("the {law} run (seed {seed})")]
    Run {
        /// The law of the run.
        law: MillLaw,
        /// Its seed.
        seed: usize,
        /// Why.
        source: CodeError,
    },
    /// A run lost particles on the way (a deck that lets LIGGGHTS drop the atoms that leave the
    /// box, `thermo_modify lost ignore`): its figures would be of another charge.
    #[error("the {law} run (seed {seed}) lost {} of its {had} particles by step {step} (they left the simulation box and the deck lets LIGGGHTS drop them, as `thermo_modify lost ignore` does); its figures would be of another charge; run folder kept in {}", had - has, folder.display())]
    LostAtoms {
        /// The law of the run.
        law: MillLaw,
        /// Its seed.
        seed: usize,
        /// The step of the first frame short of particles.
        step: f64,
        /// Particles at the start of the rotation.
        had: usize,
        /// Particles in that frame.
        has: usize,
        /// The kept run folder.
        folder: PathBuf,
    },
    /// A file a run wrote cannot be read.
    #[error("the {law} run (seed {seed}): {} line {line}: {reason}; run folder kept in {}", file.display(), folder.display())]
    Output {
        /// The law of the run.
        law: MillLaw,
        /// Its seed.
        seed: usize,
        /// The file.
        file: PathBuf,
        /// The line, from 1 (0: the file as a whole).
        line: usize,
        /// What was wrong.
        reason: String,
        /// The kept run folder.
        folder: PathBuf,
    },
}

impl crate::error::Blame for MillError {
    fn is_user_error(&self) -> bool {
        matches!(self, MillError::Deck(_) | MillError::Option { .. })
    }
}

/// What the command line asks of a comparison.
#[derive(Clone, Debug, PartialEq)]
pub struct MillOptions {
    /// Rotation time run, s (`None`: the deck's own).
    pub time: Option<f64>,
    /// Runs per law, each with its own insertion seeds (1: the deck's own).
    pub seeds: usize,
    /// Rotation time left out of the power and energy means as the start-up, s (`None`: one
    /// revolution of the drum, or half the rotation if that is shorter).
    pub transient: Option<f64>,
    /// Rotation time at the end over which contacts are recorded for the spectra, s (`None`:
    /// 0.1 s, or half the rotation if that is shorter).
    pub spectra_time: Option<f64>,
    /// Contacts are recorded every this many steps.
    pub contact_every: u64,
    /// Each run is killed after this long.
    pub timeout: Duration,
    /// Runs at once.
    pub jobs: usize,
    /// A folder to keep every run's folder in (`<law>-seed<k>-…`: its input, log and the files
    /// it wrote); `None`: a run's folder is removed after it is read, kept only on a failure.
    pub keep: Option<PathBuf>,
    /// The build that runs damped Hertz (liggghts, or liggghts-paper, which has it too); the
    /// paper's law runs in liggghts-paper.
    pub hertz_code: CodeName,
}

/// Contacts are recorded every this many steps unless asked otherwise.
pub(crate) const DEFAULT_CONTACT_EVERY: u64 = 5;

impl MillOptions {
    /// What `millimpact mill DECK` runs with no option: the deck's own rotation and seeds, the
    /// default transient and spectra window, both runs at once, an hour's limit per run.
    pub fn defaults() -> MillOptions {
        MillOptions {
            time: None,
            seeds: 1,
            transient: None,
            spectra_time: None,
            contact_every: DEFAULT_CONTACT_EVERY,
            timeout: Duration::from_secs(3600),
            jobs: 2,
            keep: None,
            hertz_code: MillDeck::DEFAULT_BUILD,
        }
    }
}

/// Power and energy are averaged over this many consecutive blocks of the measured time.
pub(crate) const BLOCKS: usize = 5;

/// What one run gave.
#[derive(Clone, Debug)]
pub(crate) struct RunResult {
    /// The law.
    pub law: MillLaw,
    /// The build that ran it.
    pub code: String,
    /// The seed.
    pub seed: usize,
    /// Rotation time of each printed row, s, with the power the drum draws, W, and the
    /// kinetic energy of the charge (translational and rotational), J.
    pub series: Vec<(f64, f64, f64)>,
    /// The contacts first seen in the spectra window.
    pub events: Vec<ContactEvent>,
    /// Per recorded frame, the fraction of its contacts at rest.
    pub rest_fractions: Vec<f64>,
    /// Rotation time of each positions frame, s, with the charge's toe and shoulder angles,
    /// degrees from the bottom (empty where the deck has no gravity).
    pub angles: Vec<(f64, f64, f64)>,
    /// Rotation time of each positions frame, s, with the power the drive supplies to hold the
    /// charge's weight where it is, W (the torque balance; empty where the deck has no gravity
    /// or its rotating meshes do not all turn as one drum).
    pub weight_power: Vec<(f64, f64)>,
    /// The charge in the drum's cross-section at the end of the run (empty where the deck has
    /// no gravity).
    pub profile: Vec<ProfilePoint>,
    /// Wall time, s.
    pub wall_time: f64,
}

/// The builds that run a mill, as a refused `--code` names them.
pub(crate) fn mill_builds() -> String {
    let builds: Vec<&str> = CodeName::ALL
        .iter()
        .filter(|c| c.driver().mill_paper_build().is_some())
        .map(|c| c.name())
        .collect();
    format!("{} (mill runs LIGGGHTS decks)", builds.join(" or "))
}

/// The plan each run follows, checked against the deck.
pub fn plan(deck: &MillDeck, options: &MillOptions) -> Result<(MillPlan, f64), MillError> {
    let refuse = |option: &'static str, value: String, allowed: String| MillError::Option {
        deck: deck.path.clone(),
        option,
        value,
        allowed,
    };
    if options.hertz_code.driver().mill_paper_build().is_none() {
        return Err(refuse(
            "--code",
            options.hertz_code.to_string(),
            mill_builds(),
        ));
    }
    let written = deck.rotation_steps as f64 * deck.timestep;
    let rotation_steps = match options.time {
        None => deck.rotation_steps,
        Some(t) => {
            let steps = deck.steps_for(t);
            if t.is_nan() || t <= 0.0 || steps == 0 || steps > deck.rotation_steps {
                return Err(refuse(
                    "--time",
                    t.to_string(),
                    format!(
                        "a rotation time above one step and at most the deck's own {written} s ({} steps of {:e} s from {})",
                        deck.rotation_steps, deck.timestep, deck.rotation_from
                    ),
                ));
            }
            steps
        }
    };
    if options.seeds == 0 || options.seeds > MAX_SEEDS {
        return Err(refuse(
            "--seeds",
            options.seeds.to_string(),
            format!("1 to {MAX_SEEDS} runs per law"),
        ));
    }
    if options.seeds > 1 && deck.insertion_seeds == 0 {
        return Err(refuse(
            "--seeds",
            options.seeds.to_string(),
            "1: the deck inserts no particles with a seed (no fix insert/… or particletemplate), so every run would be the same".into(),
        ));
    }
    let rotation = rotation_steps as f64 * deck.timestep;
    let revolution = deck
        .rotating
        .iter()
        .map(|r| 2.0 * std::f64::consts::PI / r.angular_velocity.abs())
        .fold(f64::INFINITY, f64::min);
    let transient = options.transient.unwrap_or(revolution.min(rotation / 2.0));
    if !(0.0..rotation).contains(&transient) {
        return Err(refuse(
            "--transient",
            transient.to_string(),
            format!("at least 0 and below the rotation run, {rotation} s"),
        ));
    }
    let spectra_time = options.spectra_time.unwrap_or(0.1_f64.min(rotation / 2.0));
    let spectra_steps = deck.steps_for(spectra_time);
    if spectra_time.is_nan() || spectra_time < 0.0 || spectra_steps > rotation_steps {
        return Err(refuse(
            "--spectra-time",
            spectra_time.to_string(),
            format!("at least 0 and at most the rotation run, {rotation} s"),
        ));
    }
    if options.contact_every == 0 {
        return Err(refuse(
            "--contact-every",
            "0".into(),
            "a whole number of steps from 1".into(),
        ));
    }
    Ok((
        MillPlan {
            rotation_steps,
            spectra_steps,
            contact_every: options.contact_every,
            print_every: (rotation_steps / 2000).max(1),
            position_every: (rotation_steps / 200).max(1),
            seed: 0,
        },
        transient,
    ))
}

/// Run one law with one seed in a scratch folder (kept, with its `log.txt`, when anything
/// fails), and read what it wrote.
fn run_one(
    deck: &MillDeck,
    law: MillLaw,
    plan: &MillPlan,
    options: &MillOptions,
) -> Result<RunResult, MillError> {
    let seed = plan.seed;
    let code = match law {
        MillLaw::Hertz => options.hertz_code,
        // A build that runs no mill is refused by `plan` before any run.
        MillLaw::Paper => options
            .hertz_code
            .driver()
            .mill_paper_build()
            .unwrap_or(options.hertz_code),
    };
    let fail = |source: CodeError| MillError::Run { law, seed, source };
    let executable = locate(code.driver()).map_err(fail)?;
    let input = deck.render(law, plan);
    let args = ["-in", "in.mill", "-log", "none"].map(String::from);
    let prefix = format!("{law}-seed{seed}-");
    let parent = options.keep.clone().unwrap_or_else(std::env::temp_dir);
    let (ran, _) = Process::new(
        &executable,
        &args,
        ("in.mill", &input),
        options.timeout,
        &prefix,
    )
    .in_folder(&parent)
    .output(Output::LineBuffered)
    .run()
    .map_err(|e| {
        e.code_error_saying(code.name(), |step| match step {
            Step::Parent => Some("creating the folder for the runs"),
            Step::Scratch => Some("creating a scratch folder"),
            Step::DuplicateLog => Some("duplicating the log"),
            _ => None,
        })
    })
    .and_then(|ran| ran.succeeded(code.name()))
    .map_err(fail)?;
    match read_run(deck, law, plan, ran.folder()) {
        Ok(mut result) => {
            result.wall_time = ran.wall_time;
            result.code = code.name().to_string();
            if options.keep.is_some() {
                let _ = ran.keep();
            }
            Ok(result)
        }
        Err(mut error) => {
            let kept = ran.keep();
            if let MillError::Output { folder, .. } | MillError::LostAtoms { folder, .. } =
                &mut error
            {
                *folder = kept;
            }
            Err(error)
        }
    }
}

/// Whether mesh `r` turns with `drum`: the same speed about the same axis (any point of it).
fn turns_as_one(r: &RotatingMesh, drum: &RotatingMesh) -> bool {
    let close = |a: f64, b: f64| (a - b).abs() <= 1e-9 * (1.0 + a.abs().max(b.abs()));
    let offset: Vec<f64> = (0..3).map(|j| r.origin[j] - drum.origin[j]).collect();
    let along: f64 = (0..3).map(|j| offset[j] * drum.axis[j]).sum();
    close(r.angular_velocity, drum.angular_velocity)
        && (0..3).all(|k| close(r.axis[k], drum.axis[k]))
        && (0..3).all(|k| close(offset[k] - along * drum.axis[k], 0.0))
}

/// The energy file's rows after the rotation's first print, as (rotation time, s; power the
/// drive supplies, W; kinetic energy, J), or the line and reason of a row that cannot be read.
fn energy_series(
    deck: &MillDeck,
    plan: &MillPlan,
    start_step: f64,
    text: &str,
) -> Result<Vec<(f64, f64, f64)>, charge::ReadFault> {
    let mut series = Vec::new();
    for (k, line) in text.lines().enumerate() {
        if line.starts_with('#') || line.trim().is_empty() {
            continue;
        }
        let values: Vec<f64> = line
            .split_whitespace()
            .map(str::parse)
            .collect::<Result<_, _>>()
            .map_err(|e| (k + 1, format!("`{line}`: {e}")))?;
        if values.len() != 3 + 3 * deck.rotating.len() {
            return Err((
                k + 1,
                format!(
                    "{} values, expected {} (step, ke, rotational ke, three torque components per rotating mesh)",
                    values.len(),
                    3 + 3 * deck.rotating.len()
                ),
            ));
        }
        // Each torque is a mean over the steps since the print before; the first print
        // after the rotation starts has no full interval behind it (LIGGGHTS writes 0).
        if values[0] - start_step < plan.print_every as f64 {
            continue;
        }
        let time = (values[0] - start_step) * deck.timestep;
        // The torque on the mesh is what the charge exerts; the drive supplies its opposite.
        let power: f64 = deck
            .rotating
            .iter()
            .enumerate()
            .map(|(m, r)| {
                let t = &values[3 + 3 * m..6 + 3 * m];
                -(t[0] * r.axis[0] + t[1] * r.axis[1] + t[2] * r.axis[2]) * r.angular_velocity
            })
            .sum();
        series.push((time, power, values[1] + values[2]));
    }
    Ok(series)
}

/// Read the files of a finished run in `folder`.
fn read_run(
    deck: &MillDeck,
    law: MillLaw,
    plan: &MillPlan,
    folder: &Path,
) -> Result<RunResult, MillError> {
    let seed = plan.seed;
    let output = |file: &str, line: usize, reason: String| MillError::Output {
        law,
        seed,
        file: PathBuf::from(file),
        line,
        reason,
        folder: folder.to_path_buf(),
    };
    let read = |file: &str| {
        std::fs::read_to_string(folder.join(file)).map_err(|e| output(file, 0, e.to_string()))
    };
    let atoms = contacts::read_atoms(&read(ATOMS_FILE)?)
        .map_err(|(line, reason)| output(ATOMS_FILE, line, reason))?;
    let series = energy_series(deck, plan, atoms.start_step, &read(ENERGY_FILE)?)
        .map_err(|(line, reason)| output(ENERGY_FILE, line, reason))?;
    let (events, rest_fractions) = if plan.spectra_steps > 0 {
        let recorded = contacts::Recorded {
            atoms: &atoms,
            deck,
        };
        let pairs = contacts::read_frames(&read(PAIRS_FILE)?)
            .map_err(|(line, reason)| output(PAIRS_FILE, line, reason))?;
        let walls = if deck.recorded_wall_meshes.is_empty() {
            Vec::new()
        } else {
            contacts::read_frames(&read(WALLS_FILE)?)
                .map_err(|(line, reason)| output(WALLS_FILE, line, reason))?
        };
        recorded
            .track(&pairs, &walls)
            .map_err(|unknown| output(PAIRS_FILE, 0, unknown.to_string()))?
    } else {
        (Vec::new(), Vec::new())
    };
    let mut angles = Vec::new();
    let mut weight_power = Vec::new();
    let mut profile = Vec::new();
    if let (Some(gravity), Some(drum)) = (deck.gravity, deck.rotating.first()) {
        let frames = charge::read_positions(&read(POSITIONS_FILE)?)
            .map_err(|(line, reason)| output(POSITIONS_FILE, line, reason))?;
        // The torque balance holds for the charge as a whole only where every rotating mesh
        // turns with the drum.
        let one_drum = deck.rotating.iter().all(|r| turns_as_one(r, drum));
        if let Some(last) = frames.last() {
            profile = charge::section(drum, gravity, &last.particles)
                .unwrap_or_default()
                .into_iter()
                .map(|[across, up]| ProfilePoint { across, up })
                .collect();
        }
        for frame in frames {
            if frame.ids.len() < atoms.by_id.len() {
                return Err(MillError::LostAtoms {
                    law,
                    seed,
                    step: frame.step,
                    had: atoms.by_id.len(),
                    has: frame.ids.len(),
                    folder: folder.to_path_buf(),
                });
            }
            let time = (frame.step - atoms.start_step) * deck.timestep;
            if let Some((toe, shoulder)) = charge::toe_and_shoulder(drum, gravity, &frame.particles)
            {
                angles.push((time, toe, shoulder));
            }
            if one_drum {
                let charge = frame
                    .ids
                    .iter()
                    .zip(&frame.particles)
                    .map(|(id, p)| {
                        atoms
                            .by_id
                            .get(id)
                            .map(|&(_, mass)| (mass, [p[0], p[1], p[2]]))
                    })
                    .collect::<Option<Vec<_>>>()
                    .ok_or_else(|| {
                        output(
                            POSITIONS_FILE,
                            0,
                            format!(
                                "step {}: a particle that is not in {ATOMS_FILE}",
                                frame.step
                            ),
                        )
                    })?;
                weight_power.push((time, charge::weight_power(drum, gravity, &charge)));
            }
        }
    }
    Ok(RunResult {
        law,
        code: String::new(),
        angles,
        weight_power,
        profile,
        seed,
        series,
        events,
        rest_fractions,
        wall_time: 0.0,
    })
}

/// The comparison from runs already made and kept (`MillOptions::keep`): each run's law, seed
/// and folder. What the fast tests read instead of running the codes.
pub fn report_from_folders(
    deck: &MillDeck,
    options: &MillOptions,
    folders: &[(MillLaw, usize, String, PathBuf)],
) -> Result<MillReport, MillError> {
    let (base, transient) = plan(deck, options)?;
    let mut runs = Vec::new();
    for (law, seed, code, folder) in folders {
        let plan = MillPlan {
            seed: *seed,
            ..base.clone()
        };
        let mut run = read_run(deck, *law, &plan, folder)?;
        run.code = code.clone();
        runs.push(run);
    }
    runs.sort_by_key(|r| (r.seed, r.law != deck.law));
    Ok(report::summarise(deck, &base, transient, options, &runs))
}

/// Run the comparison: both laws, every seed, `options.jobs` runs at once; `progress` is told
/// of each finished run.
pub(crate) fn run_mill(
    deck: &MillDeck,
    options: &MillOptions,
    progress: &(dyn Fn(&RunResult) + Sync),
) -> Result<MillReport, MillError> {
    let (base, transient) = plan(deck, options)?;
    let laws = [deck.law, deck.law.other()];
    let jobs: Vec<(MillLaw, MillPlan)> = (0..options.seeds)
        .flat_map(|seed| laws.iter().map(move |&law| (law, seed)))
        .map(|(law, seed)| {
            (
                law,
                MillPlan {
                    seed,
                    ..base.clone()
                },
            )
        })
        .collect();
    let next = AtomicUsize::new(0);
    let results: Mutex<Vec<Result<RunResult, MillError>>> = Mutex::new(Vec::new());
    std::thread::scope(|scope| {
        for _ in 0..options.jobs.max(1) {
            scope.spawn(|| {
                loop {
                    let k = next.fetch_add(1, Ordering::SeqCst);
                    let Some((law, plan)) = jobs.get(k) else {
                        break;
                    };
                    let result = run_one(deck, *law, plan, options);
                    if let Ok(run) = &result {
                        progress(run);
                    }
                    results
                        .lock()
                        .unwrap_or_else(|e| e.into_inner())
                        .push(result);
                }
            });
        }
    });
    let mut runs = Vec::new();
    for result in results.into_inner().unwrap_or_else(|e| e.into_inner()) {
        runs.push(result?);
    }
    runs.sort_by_key(|r| (r.seed, r.law != deck.law));
    Ok(report::summarise(deck, &base, transient, options, &runs))
}
