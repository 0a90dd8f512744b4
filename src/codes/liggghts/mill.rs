//! A user's whole LIGGGHTS mill deck run under two normal laws (`millimpact mill`): the deck as
//! written, and the same deck with every contact line switched between `model hertz` and the
//! paper's `model paper` at the loss coefficient giving each type pair's COR (tangential and
//! rolling models kept), instrumented for what the mill's comparison measures.
//!
//! The deck is read by the deck reader's parser ([`ScriptReader`], the `variable` lines kept,
//! so that `v_NAME` references still resolve) and checked by `LiggghtsDeck` first, so a deck
//! `millimpact deck` refuses is refused here in the same words. Rotation starts at the first
//! `run` after the first `fix move/mesh … rotate`; everything before it (insertion, settling) is
//! run as written.

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use super::deck::LiggghtsDeck;
use super::gran::{read_model, read_settings, read_wall};
use crate::codes::CodeName;
use crate::codes::deck::{DeckError, DeckOptions, DeckReader, SourceLine};
use crate::codes::script::{Command, ScriptReader};
use crate::model::exact;

/// The combinations of models liggghts-paper is built with
/// (`scripts/liggghts-paper/style_contact_model_user.whitelist`): what the switch to the paper's
/// law can express.
const PAPER_WHITELIST: &str =
    include_str!("../../../scripts/liggghts-paper/style_contact_model_user.whitelist");

/// The files the instrumented deck writes in its scratch folder.
pub(crate) const ENERGY_FILE: &str = "millimpact_energy.txt";
/// The per-atom file (id, type, mass, radius) written at the start of rotation.
pub(crate) const ATOMS_FILE: &str = "millimpact_atoms.txt";
/// Particle–particle contacts, every few steps over the spectra window.
pub(crate) const PAIRS_FILE: &str = "millimpact_pairs.txt";
/// Particle–wall contacts (the last mesh wall/gran fix), every few steps over the window.
pub(crate) const WALLS_FILE: &str = "millimpact_walls.txt";
/// Particle positions (id, x, y, z, radius), at [`MillPlan::position_every`] steps through
/// the rotation, where the deck has gravity: the charge's toe and shoulder.
pub(crate) const POSITIONS_FILE: &str = "millimpact_positions.txt";

/// Seeds (primes above 10000, as LIGGGHTS's random seeds must be) that replace a deck's
/// insertion seeds for its second and later seeds, six for each.
const SEEDS: [u64; (MAX_SEEDS - 1) * 6] = [
    10007, 10009, 10037, 10039, 10061, 10067, 10069, 10079, 10091, 10093, 10099, 10103, 10111,
    10133, 10139, 10141, 10151, 10159, 10163, 10169, 10177, 10181, 10193, 10211, 10223, 10243,
    10247, 10253, 10259, 10267, 10271, 10273, 10289, 10301, 10303, 10313, 10321, 10331, 10333,
    10337, 10343, 10357, 10369, 10391, 10399, 10427, 10429, 10433, 10453, 10457, 10459, 10463,
    10477, 10487, 10499, 10501, 10513, 10529, 10531, 10559, 10567, 10589, 10597, 10601, 10607,
    10613, 10627, 10631, 10639, 10651, 10657, 10663, 10667, 10687, 10691, 10709, 10711, 10723,
    10729, 10733, 10739, 10753, 10771, 10781, 10789, 10799, 10831, 10837, 10847, 10853,
];

/// The most seeds a mill comparison takes (each needs its own insertion seeds): enough for a
/// difference between the laws to be resolved at Student's t with the degrees of freedom
/// of more than four runs per law.
pub(crate) const MAX_SEEDS: usize = 16;

/// A normal contact law the mill comparison runs.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum MillLaw {
    /// LIGGGHTS's damped Hertz, `model hertz` with `coefficientRestitution` (stock LIGGGHTS).
    Hertz,
    /// The paper's law, `model paper` with `lossCoefficient` (liggghts-paper).
    Paper,
}

impl MillLaw {
    /// The model's name in a `model …` specification.
    pub fn model(self) -> &'static str {
        match self {
            MillLaw::Hertz => "hertz",
            MillLaw::Paper => "paper",
        }
    }

    /// The property its deck gives each type pair (`coefficientRestitution` of the Hertz
    /// model, `lossCoefficient` of the paper's).
    fn property(self) -> &'static str {
        match self {
            MillLaw::Hertz => "coefficientRestitution",
            MillLaw::Paper => "lossCoefficient",
        }
    }

    /// The other law.
    pub(crate) fn other(self) -> MillLaw {
        match self {
            MillLaw::Hertz => MillLaw::Paper,
            MillLaw::Paper => MillLaw::Hertz,
        }
    }
}

impl std::fmt::Display for MillLaw {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.model())
    }
}

/// A mesh turned by `fix move/mesh … rotate`.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RotatingMesh {
    /// The `fix mesh/surface` ID.
    pub mesh: String,
    /// A point on the axis, m.
    pub origin: [f64; 3],
    /// The axis, a unit vector.
    pub axis: [f64; 3],
    /// Angular velocity about `axis` (right-handed), rad/s: 2π / period.
    pub angular_velocity: f64,
    /// Where the rotation is set.
    pub from: SourceLine,
}

/// How the instrumented deck is run: what is cut and what is recorded.
#[derive(Clone, Debug, PartialEq)]
pub struct MillPlan {
    /// Rotation steps run (the deck's own, or fewer when cut).
    pub rotation_steps: u64,
    /// Steps at the end of the rotation over which contacts are recorded (0: none).
    pub spectra_steps: u64,
    /// Contacts are recorded every this many steps.
    pub contact_every: u64,
    /// Power and kinetic energy are printed every this many steps.
    pub print_every: u64,
    /// Particle positions are dumped every this many steps (where the deck has gravity).
    pub position_every: u64,
    /// Which seed: 0 runs the deck's own insertion seeds, k > 0 replaces them.
    pub seed: usize,
}

/// A LIGGGHTS mill deck, read for the two-law comparison.
#[derive(Clone, Debug)]
pub struct MillDeck {
    /// The deck.
    pub path: PathBuf,
    /// The deck's own normal law.
    pub law: MillLaw,
    /// The number of atom types (the property tables' size).
    pub types: u32,
    /// Each type pair's COR (row-major `types × types`): `coefficientRestitution` of a Hertz
    /// deck, `sqrt((1 − η)/(1 + η))` of a paper deck's `lossCoefficient`.
    pub restitution: Vec<f64>,
    /// The time step in force when rotation starts, s.
    pub timestep: f64,
    /// The meshes that rotate.
    pub rotating: Vec<RotatingMesh>,
    /// The mesh fixes of the last mesh `wall/gran` fix: the wall LIGGGHTS's `wall/gran/local`
    /// records (it attaches to that fix alone).
    pub recorded_wall_meshes: Vec<String>,
    /// Steps run before rotation starts (insertion and settling, as written).
    pub settling_steps: u64,
    /// Rotation steps as written.
    pub rotation_steps: u64,
    /// Where rotation starts: the first `run` after the first `fix move/mesh … rotate`.
    pub rotation_from: SourceLine,
    /// Tangential and rolling models of the contact lines, as written (`tangential history,
    /// rolling_friction cdt`).
    pub tangential_and_rolling: String,
    /// The number of insertion seeds the deck has (what `--seeds` replaces).
    pub insertion_seeds: usize,
    /// What of the deck the instrumented runs leave out (its own output files), with lines,
    /// and the particle–wall spectra where LIGGGHTS cannot record them.
    pub left_out: Vec<String>,
    /// Gravity's acceleration (`fix … gravity G vector X Y Z`: `G` along the unit vector of
    /// `X Y Z`), m/s², where set.
    pub gravity: Option<[f64; 3]>,
    commands: Vec<Command>,
    first_run: usize,
    rotation_start: usize,
    /// The steps each `run` line runs (by its index among the commands), `upto` resolved.
    run_lengths: std::collections::HashMap<usize, u64>,
}

fn unit(v: [f64; 3]) -> Option<[f64; 3]> {
    let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    (n.is_finite() && n > 0.0).then(|| [v[0] / n, v[1] / n, v[2] / n])
}

/// A whole number of steps written at word `k` of `c` (`what` names it).
fn whole_steps(c: &Command, k: usize, what: &str) -> Result<u64, DeckError> {
    let n = c.number(k, what)?;
    if n < 0.0 || n.fract() != 0.0 || n > 1e15 {
        return Err(c.refuse(format!("{} {n}", c.name()), "a whole number of steps"));
    }
    // A whole number below 1e15: exact.
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    Ok(n as u64)
}

/// The steps a `run N` line runs when the step counter stands at `step` (only `N`, `upto`
/// and `pre`/`post` settings are taken). `run N upto` runs until step `N`, as LIGGGHTS reads
/// it: `N − step` steps, and LIGGGHTS stops at an `N` below the step reached ("Invalid run
/// command upto value").
fn run_steps(c: &Command, step: u64) -> Result<u64, DeckError> {
    let n = whole_steps(c, 1, "the number of steps")?;
    let upto = c.words[2..].iter().any(|w| w == "upto");
    let extra: Vec<&String> = c.words[2..].iter().filter(|w| *w != "upto").collect();
    let settings_only = extra.len().is_multiple_of(2)
        && extra
            .chunks(2)
            .all(|p| (p[0] == "pre" || p[0] == "post") && (p[1] == "yes" || p[1] == "no"));
    if !settings_only {
        return Err(c.refuse(
            format!("`{}`: a run the mill comparison cannot cut", c.text),
            "run N [upto] [pre yes|no] [post yes|no]",
        ));
    }
    if !upto {
        return Ok(n);
    }
    n.checked_sub(step).ok_or_else(|| {
        c.refuse(
            format!(
                "run {n} upto at step {step}: LIGGGHTS stops at it (Invalid run command upto value)"
            ),
            "run N upto with N at or after the step the runs above reach",
        )
    })
}

/// The `N×N` table of a `fix … property/global NAME peratomtypepair N …` line.
fn pair_table(c: &Command, name: &str, types: u32) -> Result<Vec<f64>, DeckError> {
    let n = c.number(6, "the number of columns")?;
    // A count written in the deck: whole, compared exactly.
    #[allow(clippy::float_cmp)]
    let other = n != f64::from(types);
    if other {
        return Err(c.refuse(
            format!("{name} is a {n}×{n} table, the deck has {types} types"),
            "peratomtypepair N with N the number of atom types",
        ));
    }
    let values = (7..c.words.len())
        .map(|k| c.number(k, name))
        .collect::<Result<Vec<_>, _>>()?;
    let cells = (types * types) as usize;
    if values.len() != cells {
        return Err(c.refuse(
            format!("{name} has {} values", values.len()),
            &format!("{cells} values (peratomtypepair {types})"),
        ));
    }
    Ok(values)
}

fn is_property(c: &Command, name: &str) -> bool {
    c.name() == "fix"
        && c.words.get(3).is_some_and(|w| w == "property/global")
        && c.words.get(4).is_some_and(|w| w == name)
}

/// The commands that write the deck's own output (left out of the instrumented runs).
const OUTPUT_COMMANDS: [&str; 9] = [
    "dump",
    "dump_modify",
    "undump",
    "restart",
    "write_restart",
    "write_data",
    "write_dump",
    "log",
    "shell",
];

/// The compute that records particle–wall contacts (before the first run, after a mesh
/// `wall/gran` fix: LIGGGHTS stops otherwise).
const WALL_COMPUTE: &str = "compute millimpact_walls all wall/gran/local pos vel id force_normal";

/// A fix style that takes an insertion seed.
fn is_insertion(style: &str) -> bool {
    style.starts_with("insert/")
        || style.starts_with("particletemplate/")
        || style.starts_with("particledistribution/")
}

fn is_mesh_fix(c: &Command) -> bool {
    c.name() == "fix"
        && c.words
            .get(3)
            .is_some_and(|w| w.starts_with("mesh/surface"))
}

/// Settings a Hertz line may carry that the paper's styles (which take none) leave as they
/// are: `tangential_damping` (the paper defines no tangential damping, so it is off there
/// whatever the deck says: said in the report) and `limitForce off`.
fn droppable(key: &str, value: &str) -> bool {
    key == "tangential_damping" || (key == "limitForce" && value == "off")
}

/// A `fix … mesh/surface… file FILE` line whose file is not there (relative to the deck's
/// `folder`, as LIGGGHTS reads it from there) is refused.
fn check_mesh_file(c: &Command, style: &str, folder: &Path) -> Result<(), DeckError> {
    let k = c.words.iter().position(|w| w == "file").ok_or_else(|| {
        c.refuse(
            format!("fix {style} without `file`"),
            "fix ID group mesh/surface file FILE type T …",
        )
    })?;
    let file = c.word(k + 1, "the mesh file")?;
    let resolved = folder.join(file);
    if resolved.is_file() {
        return Ok(());
    }
    Err(c.refuse(
        format!(
            "mesh file `{file}` does not exist ({} looked for)",
            resolved.display()
        ),
        "a mesh file (STL or VTK) at its path relative to the deck's folder",
    ))
}

/// Gravity's acceleration from `fix … gravity G vector X Y Z` (`None`: not a `vector` form).
fn gravity_of(c: &Command) -> Result<Option<[f64; 3]>, DeckError> {
    let Some(k) = c.words.iter().position(|w| w == "vector") else {
        return Ok(None);
    };
    let magnitude = c.number(4, "gravity's magnitude")?;
    Ok(unit([
        c.number(k + 1, "gravity's direction")?,
        c.number(k + 2, "gravity's direction")?,
        c.number(k + 3, "gravity's direction")?,
    ])
    .map(|direction| direction.map(|x| x * magnitude)))
}

/// Each type pair's COR under the deck's own `law`, from the last table of the property it
/// takes (`coefficientRestitution` for Hertz, `lossCoefficient` for the paper's law).
fn restitution_of(
    path: &Path,
    law: MillLaw,
    tables: &[(&str, Vec<f64>, SourceLine)],
) -> Result<Vec<f64>, DeckError> {
    let wanted = law.property();
    let (_, table, _) = tables
        .iter()
        .rev()
        .find(|(name, ..)| *name == wanted)
        .ok_or_else(|| DeckError::Lacking {
            file: path.to_path_buf(),
            what: format!("model {law} needs {wanted}, which no fix property/global sets"),
            supported: format!("fix ID all property/global {wanted} peratomtypepair N …"),
        })?;
    Ok(match law {
        MillLaw::Hertz => table.clone(),
        MillLaw::Paper => table.iter().map(|&eta| exact::restitution(eta)).collect(),
    })
}

impl MillDeck {
    /// The build that runs a mill deck's damped Hertz unless asked otherwise: the stock
    /// LIGGGHTS build (its paper's law runs in the build's
    /// [`CodeDriver::mill_paper_build`](crate::codes::CodeDriver::mill_paper_build)).
    pub const DEFAULT_BUILD: CodeName = CodeName::Liggghts;

    /// Read the deck at `path`: refused in one line (file, line, what, what is allowed) when it
    /// has no rotating mesh, a mesh file that is not there, or a law the switch cannot express.
    pub fn read(path: &Path) -> Result<MillDeck, DeckError> {
        // The deck reader's own checks first: units, materials, the models and their settings.
        let checked = LiggghtsDeck.read(path, &DeckOptions::default())?;
        let commands = ScriptReader::read_whole(path, ("LIGGGHTS 3.8", &["ternary"]))?;
        let folder = path.parent().unwrap_or(Path::new(".")).to_path_buf();
        let types = checked.transplant.types;
        let mut law = None;
        let mut tangential_and_rolling = None;
        let mut meshes: Vec<(String, SourceLine)> = Vec::new();
        let mut wall_meshes: Vec<String> = Vec::new();
        let mut rotating: Vec<RotatingMesh> = Vec::new();
        let mut first_run = None;
        let mut rotation_start = None;
        let mut timestep = checked.timestep;
        let mut settling_steps = 0;
        let mut rotation_steps = 0;
        let mut insertion_seeds = 0;
        let mut left_out: Vec<String> = Vec::new();
        let mut gravity = None;
        let mut tables: Vec<(&str, Vec<f64>, SourceLine)> = Vec::new();
        let mut step = 0u64;
        let mut run_lengths = std::collections::HashMap::new();
        let mut first_wall: Option<(usize, String, SourceLine)> = None;
        // Other motions (`linear`, `wiggle`, …) before the rotation, by fix ID, while in force.
        let mut moving: Vec<(String, String, SourceLine)> = Vec::new();
        for (index, c) in commands.iter().enumerate() {
            let style = c.words.get(3).map(String::as_str).unwrap_or_default();
            match c.name() {
                "label" | "jump" | "next" | "if" => {
                    return Err(c.refuse(
                        format!("`{}`: a loop or branch of the deck", c.text),
                        "a deck that runs straight through (the mill comparison cuts its runs by step counts)",
                    ));
                }
                "timestep" => timestep = c.number(1, "the time step")?,
                "reset_timestep" => step = whole_steps(c, 1, "the step")?,
                "unfix" => moving.retain(|(id, ..)| c.words.get(1) != Some(id)),
                "run" => {
                    let n = run_steps(c, step)?;
                    step += n;
                    run_lengths.insert(index, n);
                    first_run.get_or_insert(index);
                    if rotation_start.is_some() {
                        rotation_steps += n;
                    } else if rotating.is_empty() {
                        settling_steps += n;
                    } else {
                        if let Some((id, motion, at)) = moving.first() {
                            return Err(at.refuse(
                                format!(
                                    "fix {id} move/mesh {motion} still moves its mesh when the rotation starts ({}): a motion whose power the comparison does not measure",
                                    c.at
                                ),
                                "moves before the rotation ended by `unfix ID` before its first run",
                            ));
                        }
                        rotation_start = Some(index);
                        rotation_steps += n;
                    }
                }
                "pair_style" => {
                    let (mut model, k) = read_model(c, 2)?;
                    read_settings(c, k, &mut model)?;
                    law = Some(Self::law_of(c, &model, law)?);
                    tangential_and_rolling = Some(format!(
                        "tangential {}, rolling_friction {}",
                        model.tangential, model.rolling
                    ));
                }
                "fix" if style == "wall/gran" => {
                    let known = meshes
                        .iter()
                        .map(|(m, at)| (m.clone(), (1, at.clone())))
                        .collect();
                    let wall = read_wall(c, &known)?;
                    law = Some(Self::law_of(c, &wall.model, law)?);
                    if !wall.meshes.is_empty() {
                        wall_meshes = wall.meshes.clone();
                        first_wall.get_or_insert((index, c.text.clone(), c.at.clone()));
                    }
                }
                "fix" if style.starts_with("mesh/surface") => {
                    check_mesh_file(c, style, &folder)?;
                    meshes.push((c.words[1].clone(), c.at.clone()));
                }
                "fix" if style == "move/mesh" => {
                    if rotation_start.is_some() {
                        return Err(c.refuse(
                            "a fix move/mesh after rotation has started",
                            "every fix move/mesh before the first run of the rotation",
                        ));
                    }
                    // A motion other than a rotation, before the rotation starts, runs as
                    // written (as the settling does).
                    match c.words.get(6).map(String::as_str) {
                        Some(motion) if motion != "rotate" && rotating.is_empty() => {
                            moving.push((c.words[1].clone(), motion.to_string(), c.at.clone()));
                        }
                        _ => rotating.push(Self::rotation(c, &meshes)?),
                    }
                }
                "fix" if is_insertion(style) => insertion_seeds += 1,
                "fix" if style == "gravity" => gravity = gravity_of(c)?.or(gravity),
                "fix" => {
                    for law in [MillLaw::Hertz, MillLaw::Paper] {
                        if is_property(c, law.property()) {
                            let name = law.property();
                            tables.push((name, pair_table(c, name, types)?, c.at.clone()));
                        }
                    }
                }
                _ if OUTPUT_COMMANDS.contains(&c.name()) => {
                    left_out.push(format!("{} ({})", c.text, c.at))
                }
                _ => {}
            }
        }
        let law = law.ok_or_else(|| DeckError::Lacking {
            file: path.to_path_buf(),
            what: "no pair_style gran line".into(),
            supported: "pair_style gran model hertz|paper …".into(),
        })?;
        let Some(rotation_start) = rotation_start else {
            return Err(match rotating.first() {
                None => DeckError::Lacking {
                    file: path.to_path_buf(),
                    what: "no rotating mesh (no `fix … move/mesh mesh ID rotate …` before a run)"
                        .into(),
                    supported: "a mill deck turns its drum with `fix ID all move/mesh mesh MESH rotate origin X Y Z axis X Y Z period T` and runs after it".into(),
                },
                Some(m) => m.from.refuse(
                    "no `run` after the drum starts turning",
                    "a `run` after the fix move/mesh (the rotation)",
                ),
            });
        };
        let restitution = restitution_of(path, law, &tables)?;
        let rotation_from = commands[rotation_start].at.clone();
        let first_run = first_run.unwrap_or(rotation_start);
        // LIGGGHTS defines `wall/gran/local` only before the first run ("Need to define this
        // compute before first run") and only after a mesh wall/gran fix ("This fix has to come
        // before the compute"); at each run it records the last such fix. A deck with none
        // before its first run leaves the particle–wall spectra out.
        if let Some((_, text, at)) = first_wall.filter(|(index, ..)| *index > first_run) {
            left_out.push(format!(
                "the particle–wall collision spectra of {text} ({at}): LIGGGHTS records a mesh wall's contacts (compute wall/gran/local) only where a mesh wall/gran fix comes before the first run ({})",
                commands[first_run].at
            ));
            wall_meshes.clear();
        }
        Ok(MillDeck {
            path: path.to_path_buf(),
            law,
            types,
            restitution,
            timestep,
            rotating,
            recorded_wall_meshes: wall_meshes,
            settling_steps,
            rotation_steps,
            rotation_from,
            tangential_and_rolling: tangential_and_rolling.unwrap_or_default(),
            insertion_seeds,
            left_out,
            gravity,
            commands,
            first_run,
            rotation_start,
            run_lengths,
        })
    }

    /// The deck's normal law from one contact line, refused where the switch cannot express it
    /// or where the lines disagree (`before`: the law of the lines above).
    fn law_of(
        c: &Command,
        model: &super::gran::GranModel,
        before: Option<MillLaw>,
    ) -> Result<MillLaw, DeckError> {
        let law = match model.normal.as_str() {
            "hertz" => MillLaw::Hertz,
            "paper" => MillLaw::Paper,
            // Its damping is set by coefficientRestitution as Hertz's is, but its spring is
            // linear (from characteristicVelocity): switched to the paper's law, Hertzian, the
            // two runs would differ in the spring as well as the damping, and the difference
            // could not be laid on the damping law.
            "hooke" => {
                return Err(c.refuse(
                    "model hooke: a linear spring (its stiffness from characteristicVelocity), which the paper's law, a Hertzian spring, cannot stand in for: the runs would differ in the spring, not only the damping",
                    "model hertz (switched to model paper at the η of each pair's coefficientRestitution) or model paper (switched to model hertz)",
                ));
            }
            other => {
                return Err(c.refuse(
                    format!(
                        "model {other}: a law the switch cannot express (its stiffness or damping is not set by a COR)"
                    ),
                    "model hertz (switched to model paper at the η of each pair's coefficientRestitution) or model paper (switched to model hertz)",
                ));
            }
        };
        if let Some((key, value)) = model.settings.iter().find(|(k, v)| !droppable(k, v)) {
            return Err(c.refuse(
                format!("{key} {value}: a setting the paper's law has no counterpart for"),
                "no settings, or tangential_damping on|off and limitForce off (the paper's styles take none)",
            ));
        }
        let combination = format!(
            "GRAN_MODEL(PAPER, TANGENTIAL_{}, COHESION_OFF, ROLLING_{}, SURFACE_DEFAULT)",
            model.tangential.to_ascii_uppercase(),
            model.rolling.to_ascii_uppercase()
        );
        if !PAPER_WHITELIST.lines().any(|l| l.trim() == combination) {
            return Err(c.refuse(
                format!(
                    "tangential {} with rolling_friction {}: liggghts-paper is not built with model paper in that combination",
                    model.tangential, model.rolling
                ),
                "tangential off|no_history|history with rolling_friction off, or tangential history with rolling_friction cdt|epsd2",
            ));
        }
        if let Some(before) = before.filter(|b| *b != law) {
            return Err(c.refuse(
                format!("model {law} where the lines above use model {before}"),
                "one normal law for the particles and the walls (model hertz, or model paper)",
            ));
        }
        Ok(law)
    }

    /// A `fix ID group move/mesh mesh M rotate origin … axis … period T` line.
    fn rotation(c: &Command, meshes: &[(String, SourceLine)]) -> Result<RotatingMesh, DeckError> {
        let supported = "fix ID group move/mesh mesh MESH rotate origin X Y Z axis X Y Z period T";
        if c.word(4, "`mesh`")? != "mesh" {
            return Err(c.refuse(format!("`{}`", c.text), supported));
        }
        let mesh = c.word(5, "the mesh's ID")?.to_string();
        if !meshes.iter().any(|(m, _)| *m == mesh) {
            return Err(c.refuse(
                format!("move/mesh of `{mesh}`, which no fix mesh/surface above defines"),
                supported,
            ));
        }
        let motion = c.word(6, "the motion")?;
        if motion != "rotate" {
            return Err(c.refuse(
                format!("move/mesh {motion}: a motion whose power the comparison does not measure"),
                supported,
            ));
        }
        let after = |key: &str| -> Result<[f64; 3], DeckError> {
            let k = c
                .words
                .iter()
                .position(|w| w == key)
                .ok_or_else(|| c.refuse(format!("rotate without `{key}`"), supported))?;
            Ok([
                c.number(k + 1, key)?,
                c.number(k + 2, key)?,
                c.number(k + 3, key)?,
            ])
        };
        let origin = after("origin")?;
        let axis =
            unit(after("axis")?).ok_or_else(|| c.refuse("a zero rotation axis", supported))?;
        let k = c
            .words
            .iter()
            .position(|w| w == "period")
            .ok_or_else(|| c.refuse("rotate without a constant `period`", supported))?;
        let period = c.number(k + 1, "the period")?;
        if period.is_nan() || period == 0.0 {
            return Err(c.refuse(format!("period {period}"), "a non-zero period, s"));
        }
        Ok(RotatingMesh {
            mesh,
            origin,
            axis,
            angular_velocity: 2.0 * std::f64::consts::PI / period,
            from: c.at.clone(),
        })
    }

    /// The number of steps a rotation time (s) takes at the deck's step, rounded.
    pub(crate) fn steps_for(&self, seconds: f64) -> u64 {
        let steps = (seconds / self.timestep).round();
        // Bounded by the caller's check against the deck's own rotation.
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let steps = steps.max(0.0) as u64;
        steps
    }

    /// The deck under `law`, instrumented as `plan` says: the input LIGGGHTS reads in the
    /// scratch folder (mesh files named by their absolute paths).
    pub fn render(&self, law: MillLaw, plan: &MillPlan) -> String {
        // A deck named without a folder (`in.mill`) is in the working folder: its parent is
        // the empty path, which names no folder to make absolute.
        let folder = match self.path.parent() {
            Some(parent) if !parent.as_os_str().is_empty() => parent,
            _ => Path::new("."),
        };
        let folder = std::fs::canonicalize(folder).unwrap_or_else(|_| folder.to_path_buf());
        let n = self.types;
        let mut out = vec![format!(
            "# {} under model {law}, written by millimpact mill (rotation {} steps, contacts recorded over the last {} every {}, seed {})",
            self.path.display(),
            plan.rotation_steps,
            plan.spectra_steps,
            plan.contact_every,
            plan.seed
        )];
        let mut seeds = SEEDS[(plan.seed.saturating_sub(1)) * 6..].iter();
        let mut rotation_done = 0u64;
        for (index, c) in self.commands.iter().enumerate() {
            if index == self.first_run {
                out.push(
                    "compute millimpact_pairs all pair/gran/local pos vel id force_normal".into(),
                );
                if !self.recorded_wall_meshes.is_empty() {
                    out.push(WALL_COMPUTE.into());
                }
            }
            if index == self.rotation_start {
                out.extend(self.recording(plan));
            }
            let style = c.words.get(3).map(String::as_str).unwrap_or_default();
            match c.name() {
                _ if OUTPUT_COMMANDS.contains(&c.name()) => {
                    out.push(format!("# left out (output): {}", c.text))
                }
                "pair_style" => {
                    if law != self.law {
                        let table: Vec<String> = (self.restitution.iter())
                            .map(|&e| match law {
                                MillLaw::Hertz => e,
                                MillLaw::Paper => exact::loss_coefficient(e),
                            })
                            .map(|v| format!("{v:e}"))
                            .collect();
                        out.push(format!(
                            "fix millimpact_law all property/global {} peratomtypepair {n} {}",
                            law.property(),
                            table.join(" ")
                        ));
                    }
                    out.push(self.switched(c, law));
                }
                "fix" if style == "wall/gran" => out.push(self.switched(c, law)),
                "fix" if law != self.law && is_property(c, law.property()) => {
                    out.push(format!("# replaced by millimpact_law: {}", c.text));
                }
                "fix" if is_mesh_fix(c) => out.push(self.mesh_line(c, &folder)),
                "fix" if plan.seed > 0 && is_insertion(style) => {
                    let mut words = c.words.clone();
                    let k = if style.starts_with("insert/") {
                        words.iter().position(|w| w == "seed").map(|k| k + 1)
                    } else {
                        Some(4)
                    };
                    if let (Some(k), Some(seed)) = (k, seeds.next())
                        && k < words.len()
                    {
                        words[k] = seed.to_string();
                    }
                    out.push(join_quoted(&words, c));
                }
                "run" if index >= self.rotation_start => {
                    let n = self.run_lengths.get(&index).copied().unwrap_or(0);
                    let start = rotation_done;
                    let end = (start + n).min(plan.rotation_steps);
                    let split = plan.rotation_steps - plan.spectra_steps;
                    if start < split && end > split {
                        out.push(format!("run {}", split - start));
                        out.extend(self.contact_dumps(plan));
                        out.push(format!("run {}", end - split));
                    } else {
                        if start == split && plan.spectra_steps > 0 {
                            out.extend(self.contact_dumps(plan));
                        }
                        out.push(format!("run {}", end - start));
                    }
                    rotation_done = end;
                    if rotation_done >= plan.rotation_steps {
                        out.push("# the rotation is cut here (millimpact mill --time)".into());
                        break;
                    }
                }
                _ => out.push(c.text.clone()),
            }
        }
        out.join("\n") + "\n"
    }

    /// A contact line (`pair_style gran`, `fix wall/gran`) under `law`.
    fn switched(&self, c: &Command, law: MillLaw) -> String {
        if law == self.law {
            return c.text.clone();
        }
        let mut words: Vec<String> = Vec::new();
        let mut k = 0;
        while k < c.words.len() {
            let word = &c.words[k];
            if k > 0 && c.words[k - 1] == "model" {
                words.push(law.model().to_string());
            } else if let Some(value) = c.words.get(k + 1).filter(|v| droppable(word, v)) {
                let _ = value;
                k += 2;
                continue;
            } else {
                words.push(word.clone());
            }
            k += 1;
        }
        join_quoted(&words, c)
    }

    /// A mesh/surface line: absolute file path; a rotating mesh made `mesh/surface/stress`
    /// with its `reference_point` on the axis (the torque about the axis, not the physics).
    fn mesh_line(&self, c: &Command, folder: &Path) -> String {
        let mut words = c.words.clone();
        if let Some(k) = words.iter().position(|w| w == "file")
            && let Some(file) = words.get_mut(k + 1)
        {
            *file = folder.join(&*file).display().to_string();
        }
        if let Some(rotation) = self.rotating.iter().find(|r| r.mesh == c.words[1]) {
            words[3] = "mesh/surface/stress".into();
            if let Some(k) = words.iter().position(|w| w == "reference_point") {
                words.drain(k..(k + 4).min(words.len()));
            }
            words.push("reference_point".into());
            words.extend(rotation.origin.iter().map(|x| format!("{x:e}")));
        }
        join_quoted(&words, c)
    }

    /// What records power and kinetic energy from the start of rotation.
    fn recording(&self, plan: &MillPlan) -> Vec<String> {
        // The torque on a mesh is a train of impacts, each a few tens of steps long: a value
        // every `print_every` steps only samples it, so each printed torque is the mean over
        // every step since the last print.
        let torques: Vec<String> = self
            .rotating
            .iter()
            .flat_map(|r| (4..=6).map(move |k| format!("f_{}[{k}]", r.mesh)))
            .collect();
        let averaged: Vec<String> = (1..=torques.len())
            .map(|k| format!("$(f_millimpact_torque[{k}])"))
            .collect();
        let mut lines = vec![
            "compute millimpact_rke all erotate/sphere".into(),
            format!("dump millimpact_atoms all custom 1000000000 {ATOMS_FILE} id type mass radius"),
            "dump_modify millimpact_atoms first yes".into(),
            format!(
                "fix millimpact_torque all ave/time 1 {every} {every} {}",
                torques.join(" "),
                every = plan.print_every
            ),
            format!(
                "fix millimpact_energy all print {} \"$(step) $(ke) $(c_millimpact_rke) {}\" file {ENERGY_FILE} screen no",
                plan.print_every,
                averaged.join(" ")
            ),
        ];
        if self.gravity.is_some() {
            lines.push(format!(
                "dump millimpact_positions all custom {} {POSITIONS_FILE} id x y z radius",
                plan.position_every
            ));
        }
        lines
    }

    /// The contact dumps of the spectra window.
    fn contact_dumps(&self, plan: &MillPlan) -> Vec<String> {
        let columns = |compute: &str| {
            (1..=18)
                .map(|k| format!("c_{compute}[{k}]"))
                .collect::<Vec<_>>()
                .join(" ")
        };
        let mut lines = vec![format!(
            "dump millimpact_pairs all local {} {PAIRS_FILE} {}",
            plan.contact_every,
            columns("millimpact_pairs")
        )];
        if !self.recorded_wall_meshes.is_empty() {
            lines.push(format!(
                "dump millimpact_walls all local {} {WALLS_FILE} {}",
                plan.contact_every,
                columns("millimpact_walls")
            ));
        }
        lines
    }
}

/// `words` as a line LIGGGHTS reads as `c` (quotes put back where the original had them).
fn join_quoted(words: &[String], c: &Command) -> String {
    if c.text.contains('"') || c.text.contains('\'') {
        // A quoted word keeps its quotes only in the text: the words of such a line are left
        // as written but for the ones the switch changes, which are never quoted.
        let original: Vec<&str> = c.text.split_whitespace().collect();
        if original.len() == c.words.len() && original.len() == words.len() {
            return original
                .iter()
                .zip(words.iter().zip(&c.words))
                .map(|(o, (new, old))| {
                    if new == old {
                        (*o).to_string()
                    } else {
                        new.clone()
                    }
                })
                .collect::<Vec<_>>()
                .join(" ");
        }
    }
    words.join(" ")
}
