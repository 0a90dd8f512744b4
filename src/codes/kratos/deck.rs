//! A Kratos DEM user's setup (`millimpact deck`): `MaterialsDEM.json` (the materials with their
//! `Variables`, the `material_relations` with each pair's constitutive law and restitution, the
//! `material_assignation_table` that says which model parts are particles and which are walls)
//! and `ProjectParametersDEM.json` beside it (the time step `MaxTimeStep`, the scheme, the
//! problem name of the `.mdpa` files); the particles' radii from the `DEM.mdpa`'s nodal
//! `RADIUS`, an inlet's `RADIUS`, or `--particle ID:RADIUS:DENSITY`. Both JSON files are read as
//! the typed records of `files.rs` (a wrong type is refused there, with the field's path); what a
//! field means for a pair, and whether the pair needs it, is decided here. The impact of one pair
//! is rendered with the user's materials transplanted (`deck.py`): the file's own materials and
//! relations, read by Kratos' own `MaterialsAssignationUtility`, so that Kratos derives the
//! damping from the user's restitution exactly as in the user's run.
//!
//! What each law integrates in the installed 10.4.4, as measured (the live test holds every
//! pair's run to its law stepped): `DEM_D_Hertz_viscous_Coulomb` as the driver's ball scenes
//! ([`super::Kratos::dashpot_law`]); `DEM_D_Linear_viscous_Coulomb` `F = k y + 2 γ sqrt(M k) ẏ`
//! with `k = 1.432 π E* (0.31225 R*)` between particles and `π E* (0.31225 R)` at a wall (no
//! 1.432); `DEM_D_Linear_Custom_Constants` the relation's `K_NORMAL` with the same dashpot; the
//! linear laws' `γ` from Kratos' bisection ([`super::linear_damping_gamma`]); every law's total
//! normal force clamped at zero. `reference/kratos/CONVENTIONS.md` has the measurements.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

use serde_json::Value;

use super::files::{
    self, LawName, MaterialId, MaterialRef, MaterialVariable, MaterialsFile, Number, ProjectFile,
    SteppedLaw,
};
use super::{
    LOWEST_RESTITUTION, SCHEME, SCRIPT, UNDAMPED_ABOVE, hertz_damping_gamma, linear_damping_gamma,
    mixed_modulus, particle_mass,
};
use crate::codes::damping::hertz_input_restitution;
use crate::codes::deck::{
    DeckBody, DeckContact, DeckDialect, DeckError, DeckImpactInput, DeckOptions, DeckSource,
    DeckWall, ImpactPlan, PairLaw, Partner, SourceLine, Transplant, UserDeck, WallOrder,
    body_contacts, wall_contacts,
};
use crate::codes::template::{exact_number, fill_template};
use crate::codes::{CodeError, RenderedInput};
use crate::model::law::DashpotLaw;

/// The Python template of one impact with a user's materials.
pub(super) const TEMPLATE: &str = include_str!("deck.py");

/// The project parameters file a materials file is read with, in its folder.
pub(crate) const PROJECT_FILE: &str = "ProjectParametersDEM.json";

/// The materials file a project names when it names none (`sphere_strategy.py`'s default).
pub(crate) const MATERIALS_FILE: &str = "MaterialsDEM.json";

/// Most radii one material's particles may have in the `.mdpa` for each to be checked; a
/// distribution of more is given with `--particle`.
pub(crate) const MAX_SIZES: usize = 3;

/// The constitutive laws whose force the harness steps.
pub(crate) const LAWS: &str =
    "DEM_D_Hertz_viscous_Coulomb, DEM_D_Linear_viscous_Coulomb, DEM_D_Linear_Custom_Constants";

/// Kratos 10.4.4's own defaults for what a project may leave out
/// (`dem_default_input_parameters.py`): the step, the scheme, the search frequency, gravity.
const DEFAULT_MAX_TIME_STEP: f64 = 5e-5;
const DEFAULT_NEIGHBOUR_SEARCH_FREQUENCY: f64 = 50.0;

/// `DEM_D_Linear_viscous_Coulomb`'s stiffness factor between particles (`beta`), absent at a
/// wall.
pub(crate) const LINEAR_PARTICLE_FACTOR: f64 = 1.432;
/// `DEM_D_Linear_viscous_Coulomb`'s "modified radius" over the contact radius.
pub(crate) const LINEAR_RADIUS_FACTOR: f64 = 0.31225;

/// Kratos' deck reader.
pub(crate) struct KratosDeck;

/// A field the check needs that is not in the file: where it belongs and what it must hold.
fn missing(file: &Path, path: String, key: &str, supported: &str) -> DeckError {
    DeckError::unsupported(
        DeckSource::field(file, path),
        format!("no {key}"),
        supported,
    )
}

/// Read a JSON file, or say where it is not JSON.
fn read_json(path: &Path) -> Result<Value, DeckError> {
    let text = std::fs::read_to_string(path).map_err(|source| DeckError::Read {
        path: path.to_path_buf(),
        source,
    })?;
    serde_json::from_str(&text).map_err(|e| {
        DeckError::unsupported(
            SourceLine {
                file: path.to_path_buf(),
                line: e.line(),
            },
            format!("not JSON: {e}"),
            "a JSON file as Kratos reads it",
        )
    })
}

/// Which of a Kratos DEM setup's files a JSON value is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum FileKind {
    Materials,
    Project,
}

fn kind_of(value: &Value) -> Option<FileKind> {
    let has = |key: &str| value.get(key).is_some();
    if value.get("materials").is_some_and(Value::is_array)
        && (has("material_relations") || has("material_assignation_table"))
    {
        Some(FileKind::Materials)
    } else if value.is_object()
        && (has("MaxTimeStep")
            || has("ElementType")
            || value
                .pointer("/solver_settings/material_import_settings")
                .is_some())
    {
        Some(FileKind::Project)
    } else {
        None
    }
}

/// A material of the materials file and where it is.
#[derive(Clone, Copy, Debug)]
struct Material<'f> {
    file: &'f Path,
    index: usize,
    typed: &'f files::Material,
}

impl Material<'_> {
    fn id(&self) -> MaterialId {
        self.typed.material_id
    }

    fn label(&self) -> String {
        match &self.typed.material_name {
            Some(n) => format!("{} ({n})", self.id()),
            None => self.id().to_string(),
        }
    }

    fn at(&self) -> DeckSource {
        DeckSource::field(self.file, format!("materials[{}]", self.index))
    }

    fn variable(&self, variable: MaterialVariable, supported: &str) -> Result<f64, DeckError> {
        self.typed.variables.get(variable).ok_or_else(|| {
            missing(
                self.file,
                format!("materials[{}].Variables.{}", self.index, variable.name()),
                variable.name(),
                supported,
            )
        })
    }
}

/// A material relation (the contact settings of two materials) and where it is.
#[derive(Clone, Copy, Debug)]
struct Relation<'f> {
    file: &'f Path,
    index: usize,
    typed: &'f files::Relation,
}

impl Relation<'_> {
    fn ids(&self) -> [MaterialId; 2] {
        self.typed.material_ids_list
    }

    fn at(&self) -> DeckSource {
        DeckSource::field(self.file, format!("material_relations[{}]", self.index))
    }

    /// Where its variable `key` is.
    fn variable_path(&self, key: &str) -> String {
        format!("material_relations[{}].Variables.{key}", self.index)
    }

    /// The relation's constitutive law, if the harness steps it.
    fn law(&self) -> Result<SteppedLaw, DeckError> {
        const KEY: &str = "DEM_DISCONTINUUM_CONSTITUTIVE_LAW_NAME";
        match &self.typed.variables.law {
            Some(LawName::Stepped(law)) => Ok(*law),
            Some(LawName::Other(name)) => Err(DeckError::unsupported(
                DeckSource::field(self.file, self.variable_path(KEY)),
                format!("{name}, a law whose force the harness does not step"),
                LAWS,
            )),
            None => Err(missing(
                self.file,
                self.variable_path(KEY),
                KEY,
                &format!("a constitutive law: {LAWS}"),
            )),
        }
    }
}

/// How often Kratos looks for new contacts, and how far.
#[derive(Clone, Debug)]
struct Search {
    frequency: f64,
    from: String,
    particles: f64,
    walls: f64,
    absolute: bool,
}

impl Search {
    /// The trap of a pair (against a wall or not) at time step `dt`.
    fn trap(&self, wall: bool, dt: f64) -> String {
        let (key, tolerance) = if wall {
            ("search_tolerance_against_walls", self.walls)
        } else {
            ("SearchTolerance", self.particles)
        };
        let n = self.frequency;
        let speed = if self.absolute {
            format!(
                ", so an approach faster than {key} / ({n} Δt) = {} m/s can overlap without force until the next",
                sig(tolerance / (n * dt))
            )
        } else {
            String::new()
        };
        format!(
            "neighbour search: NeighbourSearchFrequency {n} ({}) with {key} {tolerance} m: Kratos finds a new contact only at a search{speed} (measured at 50 without tolerance: COR 0.711 for 0.694); the impacts search every step",
            self.from
        )
    }
}

/// A figure to four significant digits.
fn sig(x: f64) -> String {
    format!("{}", format!("{x:.3e}").parse::<f64>().unwrap_or(x))
}

/// The settings of `ProjectParametersDEM.json` the check uses, with Kratos' defaults.
#[derive(Clone, Debug)]
struct Project {
    timestep: f64,
    timestep_from: String,
    global_damping: Option<(f64, DeckSource)>,
    search: Option<Search>,
    problem_name: Option<String>,
    folder: PathBuf,
    left_out: Vec<String>,
}

impl Project {
    fn read(path: &Path, file: &ProjectFile) -> Result<(Self, PathBuf), DeckError> {
        let folder = path.parent().unwrap_or(Path::new("")).to_path_buf();
        let refuse = |key: &str, found: String, supported: &str| {
            DeckError::unsupported(DeckSource::field(path, key), found, supported)
        };
        let number = |value: Option<Number>, default: f64| value.map_or(default, |n| n.0);
        let dimension = number(file.dimension, 3.0);
        if !(2.5..=3.5).contains(&dimension) {
            return Err(refuse(
                "Dimension",
                format!("{dimension}"),
                "3 (the 2D laws are not read)",
            ));
        }
        let element = file
            .element_type
            .as_deref()
            .unwrap_or("SphericPartDEMElement3D");
        if element != "SphericPartDEMElement3D" {
            return Err(refuse(
                "ElementType",
                element.to_string(),
                "SphericPartDEMElement3D (discontinuum spheres)",
            ));
        }
        let strategy = file
            .solver_settings
            .strategy
            .as_deref()
            .unwrap_or("sphere_strategy");
        if strategy != "sphere_strategy" {
            return Err(refuse(
                "solver_settings.strategy",
                strategy.to_string(),
                "sphere_strategy (discontinuum spheres)",
            ));
        }
        let scheme = file
            .translational_scheme
            .as_deref()
            .unwrap_or("Symplectic_Euler");
        if scheme != SCHEME {
            return Err(refuse(
                "TranslationalIntegrationScheme",
                format!("{scheme}, a scheme whose stepping the harness does not model"),
                "Symplectic_Euler (Kratos' default, a leap-frog; Forward_Euler gains energy: an elastic impact rebounds at 1.0056 with 1000 steps per contact)",
            ));
        }
        let mass_factor = number(file.virtual_mass_coefficient, 1.0);
        #[allow(clippy::float_cmp)] // 1.0 is Kratos' default and its only neutral value
        if mass_factor != 1.0 {
            return Err(refuse(
                "VirtualMassCoefficient",
                format!("{mass_factor}, which scales the mass Kratos integrates with"),
                "1.0",
            ));
        }
        let timestep = number(file.max_time_step, DEFAULT_MAX_TIME_STEP);
        if timestep <= 0.0 {
            return Err(refuse(
                "MaxTimeStep",
                format!("{timestep}"),
                "a positive time step, s",
            ));
        }
        let timestep_from = match file.max_time_step {
            Some(_) => DeckSource::field(path, "MaxTimeStep").to_string(),
            None => format!("Kratos' default MaxTimeStep: {} sets none", path.display()),
        };
        let mut left_out = Vec::new();
        if file.automatic_timestep == Some(true) {
            left_out.push(format!(
                "AutomaticTimestep true ({}): Kratos 10.4.4 reads it nowhere (its stage steps by MaxTimeStep); the impacts run at MaxTimeStep",
                path.display()
            ));
        }
        let global_damping = file
            .global_damping
            .filter(|g| g.0 != 0.0)
            .map(|g| (g.0, DeckSource::field(path, "GlobalDamping")));
        if let Some((g, at)) = &global_damping {
            left_out.push(format!(
                "GlobalDamping {g} ({at}): Kratos damps every particle's total force by it; the impacts check the contact alone, without it"
            ));
        }
        let frequency = number(
            file.neighbour_search_frequency,
            DEFAULT_NEIGHBOUR_SEARCH_FREQUENCY,
        );
        let search = (frequency > 1.0).then(|| Search {
            frequency,
            from: match file.neighbour_search_frequency {
                Some(_) => DeckSource::field(path, "NeighbourSearchFrequency").to_string(),
                None => format!("Kratos' default: {} sets none", path.display()),
            },
            particles: number(file.search_tolerance, 0.0),
            walls: number(file.search_tolerance_against_walls, 0.0),
            absolute: file.delta_option.as_deref().is_none_or(|o| o == "Absolute"),
        });
        left_out.push(format!(
            "gravity, rotation, bounding box, output and the run's length ({}): the impact is one free normal impact",
            path.display()
        ));
        let materials = folder.join(
            file.solver_settings
                .material_import_settings
                .materials_filename
                .as_deref()
                .unwrap_or(MATERIALS_FILE),
        );
        Ok((
            Project {
                timestep,
                timestep_from,
                global_damping,
                search,
                problem_name: file.problem_name.clone(),
                folder,
                left_out,
            },
            materials,
        ))
    }
}

/// The parts of a `.mdpa` file the check reads: the spheres' nodes and radii and the
/// sub-model parts with their elements and data.
#[derive(Debug, Default)]
struct Mdpa {
    radius: BTreeMap<u64, f64>,
    element_node: BTreeMap<u64, u64>,
    parts: BTreeMap<String, MdpaPart>,
}

#[derive(Debug, Default)]
struct MdpaPart {
    elements: Vec<u64>,
    data: BTreeMap<String, String>,
    line: usize,
}

/// The blocks of an `.mdpa` whose lines the check reads.
#[derive(Clone, Debug, PartialEq)]
enum Block {
    Elements,
    Radius,
    Part(String),
    PartData(String),
    PartElements(String),
    Other,
}

impl Mdpa {
    fn read(path: &Path) -> Result<Self, DeckError> {
        let text = std::fs::read_to_string(path).map_err(|source| DeckError::Read {
            path: path.to_path_buf(),
            source,
        })?;
        let mut mdpa = Mdpa::default();
        let mut stack: Vec<Block> = Vec::new();
        for (index, raw) in text.lines().enumerate() {
            let at = SourceLine {
                file: path.to_path_buf(),
                line: index + 1,
            };
            let line = raw.split("//").next().unwrap_or("").trim();
            let words: Vec<&str> = line.split_whitespace().collect();
            let id = |w: &str| -> Result<u64, DeckError> {
                w.parse().map_err(|_| {
                    DeckError::unsupported(&at, format!("`{w}` is not an id"), "whole numbers")
                })
            };
            match words.as_slice() {
                [] => {}
                ["Begin", kind, rest @ ..] => {
                    let parent = stack.iter().rev().find_map(|b| match b {
                        Block::Part(name) => Some(name.clone()),
                        _ => None,
                    });
                    let block = match (*kind, rest.first()) {
                        ("Elements", _) => Block::Elements,
                        ("NodalData", Some(&"RADIUS")) => Block::Radius,
                        ("SubModelPart", Some(name)) => {
                            let full =
                                parent.map_or((*name).to_string(), |p| format!("{p}.{name}"));
                            mdpa.parts.entry(full.clone()).or_default().line = index + 1;
                            Block::Part(full)
                        }
                        ("SubModelPartData", _) => parent.map_or(Block::Other, Block::PartData),
                        ("SubModelPartElements", _) => {
                            parent.map_or(Block::Other, Block::PartElements)
                        }
                        _ => Block::Other,
                    };
                    stack.push(block);
                }
                ["End", ..] => {
                    stack.pop();
                }
                _ => match stack.last() {
                    Some(Block::Elements) => {
                        let node = words.get(2).ok_or_else(|| {
                            DeckError::unsupported(
                                &at,
                                format!("`{line}`: an element without its node"),
                                "ID PROPERTIES NODE",
                            )
                        })?;
                        mdpa.element_node.insert(id(words[0])?, id(node)?);
                    }
                    Some(Block::Radius) => {
                        let value = words
                            .last()
                            .and_then(|w| w.parse::<f64>().ok())
                            .filter(|r| *r > 0.0);
                        let value = value.ok_or_else(|| {
                            DeckError::unsupported(
                                &at,
                                format!("`{line}`: no positive radius"),
                                "NODE FIXED RADIUS",
                            )
                        })?;
                        mdpa.radius.insert(id(words[0])?, value);
                    }
                    Some(Block::PartData(part)) => {
                        let part = part.clone();
                        mdpa.parts
                            .entry(part)
                            .or_default()
                            .data
                            .insert(words[0].to_string(), words[1..].join(" "));
                    }
                    Some(Block::PartElements(part)) => {
                        let part = part.clone();
                        for w in &words {
                            let e = id(w)?;
                            mdpa.parts.entry(part.clone()).or_default().elements.push(e);
                        }
                    }
                    _ => {}
                },
            }
        }
        Ok(mdpa)
    }

    /// The radii of the spheres of `part` (a sub-model part's name below the root, or `None`
    /// for the whole file), each with how many spheres have it.
    fn radii(
        &self,
        path: &Path,
        part: Option<&str>,
    ) -> Result<BTreeMap<u64, (f64, usize)>, DeckError> {
        let elements: Vec<u64> = match part {
            None => self.element_node.keys().copied().collect(),
            Some(name) => self
                .parts
                .iter()
                .filter(|(p, _)| *p == name || p.starts_with(&format!("{name}.")))
                .flat_map(|(_, p)| p.elements.iter().copied())
                .collect(),
        };
        let mut radii = BTreeMap::new();
        for e in elements {
            let radius = self
                .element_node
                .get(&e)
                .and_then(|n| self.radius.get(n))
                .ok_or_else(|| DeckError::Lacking {
                    file: path.to_path_buf(),
                    what: format!("element {e} has no nodal RADIUS"),
                    supported: "a `Begin NodalData RADIUS` block with every sphere's node".into(),
                })?;
            radii.entry(radius.to_bits()).or_insert((*radius, 0)).1 += 1;
        }
        Ok(radii)
    }
}

/// Where a model part of the assignation table lives (clusters are left out before it is asked).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Root {
    Spheres,
    Inlet,
    Walls,
}

/// A model part of the assignation table: its name, where it lives, its entry's index.
#[derive(Clone, Debug)]
struct Assigned {
    name: String,
    root: Root,
    index: usize,
}

fn split_part(name: &str) -> (&str, Option<&str>) {
    match name.split_once('.') {
        Some((root, rest)) => (root, Some(rest)),
        None => (name, None),
    }
}

/// The other side of a pair: a particle (its material, radius, mass) or a wall's material.
enum Side<'m, 'a> {
    Particle(&'m Material<'a>, f64, f64),
    Wall(&'m Material<'a>, &'m str),
}

/// The law a relation makes Kratos integrate between a particle and its partner.
fn pair_law(
    relation: &Relation<'_>,
    own: (&Material<'_>, f64, f64),
    other: &Side<'_, '_>,
) -> Result<PairLaw, DeckError> {
    let vars = &relation.typed.variables;
    let law_name = relation.law()?;
    let name = law_name.name().to_string();
    let entered = entered_restitution(relation)?;
    let (material, radius, mass) = own;
    let (radius_star, mass_star, other_material) = match other {
        Side::Particle(m, r, m2) => (radius * r / (radius + r), 1.0 / (1.0 / mass + 1.0 / m2), *m),
        Side::Wall(m, _) => (radius, mass, *m),
    };
    let at_wall = matches!(other, Side::Wall(..));
    let mut traps = Vec::new();
    let elastic = "YOUNG_MODULUS and POISSON_RATIO (the law mixes both materials' into E*)";
    let modulus = || -> Result<(f64, f64), DeckError> {
        let (e1, nu1) = (
            material.variable(MaterialVariable::YoungModulus, elastic)?,
            material.variable(MaterialVariable::PoissonRatio, elastic)?,
        );
        let (e2, nu2) = (
            other_material.variable(MaterialVariable::YoungModulus, elastic)?,
            other_material.variable(MaterialVariable::PoissonRatio, elastic)?,
        );
        Ok((mixed_modulus(e1, nu1, e2, nu2), e1 / (1.0 - nu1 * nu1)))
    };
    let wall_trap = |e_star: f64, rigid: f64| -> Result<String, DeckError> {
        Ok(format!(
            "wall modulus: the wall's material {} is mixed into E* = {e_star:.4e} Pa (E = {:e} Pa, ν = {}), {:.3e} of the particle's own E/(1−ν²) = {rigid:.4e} Pa against a rigid wall",
            other_material.label(),
            other_material.variable(MaterialVariable::YoungModulus, elastic)?,
            other_material.variable(MaterialVariable::PoissonRatio, elastic)?,
            e_star / rigid
        ))
    };
    let law = match law_name {
        SteppedLaw::HertzViscousCoulomb => {
            let (e_star, rigid) = modulus()?;
            if at_wall {
                traps.push(wall_trap(e_star, rigid)?);
            }
            let stiffness = 4.0 / 3.0 * e_star * radius_star.sqrt();
            let gamma = hertz_damping_gamma(entered);
            traps.push(hertz_trap(entered, gamma));
            DashpotLaw {
                mass: mass_star,
                stiffness,
                exponent: 1.5,
                damping: 2.0 * gamma * (1.5 * mass_star * stiffness).sqrt(),
                damping_exponent: 0.25,
                clamp_attractive: true,
            }
        }
        linear => {
            let stiffness = if linear == SteppedLaw::LinearViscousCoulomb {
                let (e_star, rigid) = modulus()?;
                let modified = radius_star * LINEAR_RADIUS_FACTOR;
                let k = if at_wall {
                    traps.push(wall_trap(e_star, rigid)?);
                    e_star * std::f64::consts::PI * modified
                } else {
                    LINEAR_PARTICLE_FACTOR * e_star * std::f64::consts::PI * modified
                };
                traps.push(format!(
                    "linear stiffness from E*: DEM_D_Linear_viscous_Coulomb takes k = {} π E* (0.31225 R*) = {k:.4e} N/m{}",
                    if at_wall { "1.0 ×" } else { "1.432 ×" },
                    if at_wall {
                        " at a wall: 1.432 times softer than between two particles of the same E* and R*"
                    } else {
                        " between particles (1.432 times what the same E* and R* give at a wall)"
                    }
                ));
                k
            } else {
                let k = custom_stiffness(relation)?;
                traps.push(format!(
                    "stiffness: K_NORMAL = {k:e} N/m from the relation, whatever the sizes and moduli (the contact time is π sqrt(M/k) for every radius)"
                ));
                k
            };
            let gamma = linear_damping_gamma(entered);
            traps.push(linear_damping_trap(entered, gamma));
            DashpotLaw {
                mass: mass_star,
                stiffness,
                exponent: 1.0,
                damping: 2.0 * gamma * (mass_star * stiffness).sqrt(),
                damping_exponent: 0.0,
                clamp_attractive: true,
            }
        }
    };
    traps.push("clamped: Kratos sets a negative (attractive) total normal force to zero at the end of contact: the COR is the clamped law's".into());
    let tangential = vars.tangential();
    if !tangential.is_empty() {
        traps.push(format!(
            "{} act on no head-on impact: kept, and they change nothing here",
            tangential.join(", ")
        ));
    }
    if let Side::Wall(_, parts) = other {
        traps.push(format!(
            "wall: {parts} met as a flat RigidFace3D3N plane (R* = R)"
        ));
    }
    Ok(PairLaw::new(name, law, Some(entered), traps).set_by([relation.at()]))
}

/// The relation's `COEFFICIENT_OF_RESTITUTION`, refused where missing (Kratos reads it as 0)
/// or outside (0, 1].
fn entered_restitution(relation: &Relation<'_>) -> Result<f64, DeckError> {
    const COR: &str = "COEFFICIENT_OF_RESTITUTION";
    let entered = relation.typed.variables.restitution.map(|n| n.0).ok_or_else(|| {
        missing(
            relation.file,
            relation.variable_path(COR),
            COR,
            "COEFFICIENT_OF_RESTITUTION (Kratos reads a missing one as 0 and damps as at 0.001)",
        )
    })?;
    if !(entered > 0.0 && entered <= 1.0) {
        return Err(DeckError::unsupported(
            DeckSource::field(relation.file, relation.variable_path(COR)),
            format!("{entered}"),
            "a restitution in (0, 1]",
        ));
    }
    Ok(entered)
}

/// `DEM_D_Linear_Custom_Constants`' stiffness, N/m: the relation's `K_NORMAL`, refused where
/// missing or not positive.
fn custom_stiffness(relation: &Relation<'_>) -> Result<f64, DeckError> {
    let k = relation
        .typed
        .variables
        .k_normal
        .map(|n| n.0)
        .ok_or_else(|| {
            missing(
                relation.file,
                relation.variable_path("K_NORMAL"),
                "K_NORMAL",
                "K_NORMAL, the normal stiffness in N/m, for DEM_D_Linear_Custom_Constants",
            )
        })?;
    if k <= 0.0 {
        return Err(DeckError::unsupported(
            DeckSource::field(relation.file, relation.variable_path("K_NORMAL")),
            format!("{k}"),
            "a positive stiffness, N/m",
        ));
    }
    Ok(k)
}

/// The trap of Kratos' linear damping: γ solved by bisection to 1e-4, and its cut-offs.
fn linear_damping_trap(entered: f64, gamma: f64) -> String {
    format!(
        "damping ratio by bisection: Kratos solves γ from COEFFICIENT_OF_RESTITUTION {entered} on the clamped linear dashpot only to 1e-4 in γ (RootByBisection): γ = {gamma}{}",
        if entered > UNDAMPED_ABOVE {
            " (above 0.999 it takes γ = 0: an elastic contact)"
        } else if entered < LOWEST_RESTITUTION {
            " (below 0.001 it solves for 0.001)"
        } else {
            ""
        }
    )
}

/// The trap of Kratos' Hertz damping: Thornton's fit, its cut-offs, and the restitution to
/// enter for the law to realise the one meant.
fn hertz_trap(entered: f64, gamma: f64) -> String {
    let cut = if entered > UNDAMPED_ABOVE {
        " (above 0.999 it takes γ = 0: an elastic contact)"
    } else if entered < LOWEST_RESTITUTION {
        " (below 0.001 it takes the fit at 0.001)"
    } else {
        ""
    };
    let compensation = match hertz_input_restitution(entered) {
        Some(en) => format!("; the clamped law realises {entered} when given {en:.6}"),
        None => "; no restitution Kratos can be given realises it (the fit keeps some damping up to 0.999)".into(),
    };
    format!(
        "damping ratio from Thornton's fit: Kratos turns COEFFICIENT_OF_RESTITUTION {entered} into γ = {gamma:.6} (GammaForHertzThornton){cut}, a fit, not the law's exact inverse{compensation}"
    )
}

/// The files of a setup: the materials (its path and value, or `None` when the project was
/// named and the materials are to be read from the file it names), and the project's.
struct SetupFiles {
    materials: Option<(PathBuf, Value)>,
    project: (PathBuf, Value),
}

impl KratosDeck {
    /// The materials and the project of the file named, whichever of the two it is.
    fn files(path: &Path, named: Value) -> Result<SetupFiles, DeckError> {
        match kind_of(&named) {
            Some(FileKind::Materials) => {
                let folder = path.parent().unwrap_or(Path::new(""));
                let project_path = folder.join(PROJECT_FILE);
                if !project_path.is_file() {
                    return Err(DeckError::Lacking {
                        file: path.to_path_buf(),
                        what: format!("no {PROJECT_FILE} beside it (the time step MaxTimeStep, the scheme and the .mdpa's problem_name are there)"),
                        supported: format!("put {PROJECT_FILE} beside it, or name the project parameters file"),
                    });
                }
                let project = read_json(&project_path)?;
                Ok(SetupFiles {
                    materials: Some((path.to_path_buf(), named)),
                    project: (project_path, project),
                })
            }
            Some(FileKind::Project) => Ok(SetupFiles {
                materials: None,
                project: (path.to_path_buf(), named),
            }),
            None => Err(DeckError::Lacking {
                file: path.to_path_buf(),
                what: "neither a MaterialsDEM.json (materials, material_relations) nor a ProjectParametersDEM.json (MaxTimeStep, solver_settings)".into(),
                supported: "a Kratos DEM materials or project parameters file".into(),
            }),
        }
    }
}

/// The deck's particle sizes of one material: `(radius, from)`.
fn sizes_of(
    material: &Material<'_>,
    parts: &[(&str, Root)],
    mdpa: &mut Option<(PathBuf, Option<Mdpa>)>,
    inlet: &mut Option<(PathBuf, Option<Mdpa>)>,
) -> Result<Vec<(f64, String)>, DeckError> {
    let mut sizes = Vec::new();
    for (name, root) in parts {
        let (_, sub) = split_part(name);
        let slot = match root {
            Root::Spheres => &mut *mdpa,
            Root::Inlet => &mut *inlet,
            _ => continue,
        };
        let Some((file, loaded)) = slot.as_mut() else {
            continue;
        };
        if loaded.is_none() {
            if !file.is_file() {
                continue;
            }
            *loaded = Some(Mdpa::read(file)?);
        }
        let Some(m) = loaded.as_ref() else { continue };
        match root {
            Root::Spheres => {
                let radii = m.radii(file, sub)?;
                if radii.len() > MAX_SIZES {
                    let (lo, hi) = (
                        radii.values().map(|r| r.0).fold(f64::INFINITY, f64::min),
                        radii.values().map(|r| r.0).fold(0.0, f64::max),
                    );
                    return Err(DeckError::Lacking {
                        file: file.clone(),
                        what: format!(
                            "{name} (material {}) has {} radii from {lo} to {hi} m",
                            material.label(),
                            radii.len()
                        ),
                        supported: format!(
                            "at most {MAX_SIZES} are checked one by one: give the sizes to check with --particle {}:RADIUS:DENSITY",
                            material.id()
                        ),
                    });
                }
                for (radius, count) in radii.values() {
                    sizes.push((
                        *radius,
                        format!(
                            "nodal RADIUS of {count} spheres of {name} ({})",
                            file.display()
                        ),
                    ));
                }
            }
            _ => {
                let part = sub
                    .and_then(|s| m.parts.get(s))
                    .ok_or_else(|| DeckError::Lacking {
                        file: file.clone(),
                        what: format!("no SubModelPart {} for the inlet {name}", sub.unwrap_or("")),
                        supported: format!(
                            "the inlet's RADIUS, or --particle {}:RADIUS:DENSITY",
                            material.id()
                        ),
                    })?;
                let at = SourceLine {
                    file: file.clone(),
                    line: part.line,
                };
                let radius = part
                    .data
                    .get("RADIUS")
                    .and_then(|r| r.parse::<f64>().ok())
                    .filter(|r| *r > 0.0)
                    .ok_or_else(|| {
                        DeckError::unsupported(
                            &at,
                            format!("the inlet {name} has no positive RADIUS"),
                            "RADIUS R in its SubModelPartData",
                        )
                    })?;
                let spread = part
                    .data
                    .get("STANDARD_DEVIATION")
                    .and_then(|s| s.parse::<f64>().ok())
                    .unwrap_or(0.0);
                let from = if spread > 0.0 {
                    format!(
                        "the mean RADIUS of the inlet {name} ({at}; a {} distribution of standard deviation {spread}: other sizes with --particle {}:RADIUS:DENSITY)",
                        part.data
                            .get("PROBABILITY_DISTRIBUTION")
                            .map_or("normal", String::as_str),
                        material.id()
                    )
                } else {
                    format!("the RADIUS of the inlet {name} ({at})")
                };
                sizes.push((radius, from));
            }
        }
    }
    Ok(sizes)
}

/// The materials file read: its materials and relations, each with where it is, and the model
/// parts each material is assigned to (particles or walls).
struct MaterialsSetup<'f> {
    path: &'f Path,
    materials: Vec<Material<'f>>,
    relations: Vec<Relation<'f>>,
    assigned: BTreeMap<MaterialId, Vec<Assigned>>,
}

impl<'f> MaterialsSetup<'f> {
    /// Read `file` (at `path`): one material per id, every assignation naming a material and a
    /// model part the check knows (clusters are left out, with a line in `left_out`), and every
    /// relation of a pair that meets naming a law the check steps, before any size is looked
    /// for.
    fn read(
        path: &'f Path,
        file: &'f MaterialsFile,
        left_out: &mut Vec<String>,
    ) -> Result<Self, DeckError> {
        let materials: Vec<Material<'f>> = file
            .materials
            .iter()
            .enumerate()
            .map(|(index, typed)| Material {
                file: path,
                index,
                typed,
            })
            .collect();
        for (k, m) in materials.iter().enumerate() {
            if let Some(first) = materials[..k].iter().find(|o| o.id() == m.id()) {
                return Err(DeckError::unsupported(
                    DeckSource::field(path, format!("materials[{k}].material_id")),
                    format!("{}, which materials[{}] has already", m.id(), first.index),
                    "one material per material_id",
                ));
            }
        }
        let relations: Vec<Relation<'f>> = file
            .material_relations
            .iter()
            .enumerate()
            .map(|(index, typed)| Relation {
                file: path,
                index,
                typed,
            })
            .collect();
        let assigned = assign_parts(path, file, &materials, left_out)?;
        let setup = MaterialsSetup {
            path,
            materials,
            relations,
            assigned,
        };
        let role = |id: MaterialId, wall: bool| {
            setup
                .assigned
                .get(&id)
                .is_some_and(|ps| ps.iter().any(|p| (p.root == Root::Walls) == wall))
        };
        for r in &setup.relations {
            let [a, b] = r.ids();
            if (role(a, false) && (role(b, false) || role(b, true)))
                || (role(b, false) && role(a, true))
            {
                r.law()?;
            }
        }
        Ok(setup)
    }

    /// The material of `id` (every assigned id has one: [`assign_parts`] checked it).
    fn material(&self, id: MaterialId) -> &Material<'f> {
        self.materials
            .iter()
            .find(|m| m.id() == id)
            .expect("assigned materials exist")
    }

    /// The relation of the materials `a` and `b`, in either order.
    fn relation(&self, a: MaterialId, b: MaterialId) -> Result<&Relation<'f>, DeckError> {
        self.relations
            .iter()
            .find(|r| r.ids() == [a, b] || r.ids() == [b, a])
            .ok_or_else(|| DeckError::Lacking {
                file: self.path.to_path_buf(),
                what: format!(
                    "no material_relations entry for the materials {} and {}",
                    self.material(a).label(),
                    self.material(b).label()
                ),
                supported: "a relation (law, COEFFICIENT_OF_RESTITUTION) for every pair of \
                            materials that meet, as Kratos needs"
                    .into(),
            })
    }

    /// Each `--particle` names a particle material, with the density Kratos forms its mass
    /// from.
    fn check_given(&self, options: &DeckOptions) -> Result<(), DeckError> {
        for p in &options.particles {
            let parts = self.assigned.get(&p.type_id).filter(|ps| {
                ps.iter()
                    .any(|part| matches!(part.root, Root::Spheres | Root::Inlet))
            });
            if parts.is_none() {
                return Err(DeckError::Lacking {
                    file: self.path.to_path_buf(),
                    what: format!(
                        "--particle {}:{}:{}: material {} is assigned to no particles (SpheresPart, DEMInletPart)",
                        p.type_id, p.radius, p.density, p.type_id
                    ),
                    supported: "the material id of a particle material of the assignation table"
                        .into(),
                });
            }
            let material = self.material(p.type_id);
            let density =
                material.variable(MaterialVariable::ParticleDensity, "PARTICLE_DENSITY, kg/m³")?;
            #[allow(clippy::float_cmp)] // the density given must be the material's, bit for bit
            if p.density != density {
                return Err(DeckError::Lacking {
                    file: self.path.to_path_buf(),
                    what: format!(
                        "--particle {}:{}:{}: material {} has PARTICLE_DENSITY {density}, and Kratos forms the mass from it",
                        p.type_id,
                        p.radius,
                        p.density,
                        material.label()
                    ),
                    supported: format!("--particle {}:{}:{density}", p.type_id, p.radius),
                });
            }
        }
        Ok(())
    }

    /// One body per particle material and size: the sizes given with `--particle`, else those
    /// of the project's `.mdpa` files (spheres and inlets); a particle material with no size is
    /// refused, naming where it was looked for.
    fn bodies(&self, project: &Project, options: &DeckOptions) -> Result<Vec<DeckBody>, DeckError> {
        let problem = project.problem_name.clone().unwrap_or_default();
        let mut mdpa = Some((project.folder.join(format!("{problem}DEM.mdpa")), None));
        let mut inlet = Some((
            project.folder.join(format!("{problem}DEM_Inlet.mdpa")),
            None,
        ));
        let given: BTreeSet<MaterialId> = options.particles.iter().map(|p| p.type_id).collect();
        let mut bodies: Vec<DeckBody> = Vec::new();
        for (id, parts) in &self.assigned {
            let particles: Vec<(&str, Root)> = parts
                .iter()
                .filter(|p| matches!(p.root, Root::Spheres | Root::Inlet))
                .map(|p| (p.name.as_str(), p.root))
                .collect();
            if particles.is_empty() {
                continue;
            }
            let material = self.material(*id);
            let density = material.variable(
                MaterialVariable::ParticleDensity,
                "PARTICLE_DENSITY, kg/m³ (a particle material's)",
            )?;
            let e = material.variable(MaterialVariable::YoungModulus, "YOUNG_MODULUS, Pa")?;
            let nu = material.variable(MaterialVariable::PoissonRatio, "POISSON_RATIO")?;
            let sizes: Vec<(f64, String)> = if given.contains(id) {
                options
                    .particles
                    .iter()
                    .filter(|p| p.type_id == *id)
                    .map(|p| (p.radius, "--particle".to_string()))
                    .collect()
            } else {
                sizes_of(material, &particles, &mut mdpa, &mut inlet)?
            };
            if sizes.is_empty() {
                let names: Vec<&str> = particles.iter().map(|p| p.0).collect();
                return Err(DeckError::Lacking {
                    file: self.path.to_path_buf(),
                    what: format!(
                        "no radius for material {} ({}): no sphere of it in {} nor an inlet RADIUS in {}",
                        material.label(),
                        names.join(", "),
                        mdpa.as_ref()
                            .map_or(String::new(), |m| m.0.display().to_string()),
                        inlet
                            .as_ref()
                            .map_or(String::new(), |m| m.0.display().to_string())
                    ),
                    supported: format!("give its size with --particle {id}:RADIUS:{density}"),
                });
            }
            for (radius, from) in sizes {
                #[allow(clippy::float_cmp)] // the same radius read twice is the same number
                let known = bodies
                    .iter()
                    .any(|b| b.type_id == *id && b.radius == radius);
                if !known {
                    bodies.push(DeckBody {
                        type_id: *id,
                        radius,
                        density,
                        mass: particle_mass(radius, density),
                        youngs_modulus: Some(e),
                        poisson_ratio: Some(nu),
                        from,
                    });
                }
            }
        }
        if bodies.is_empty() {
            return Err(DeckError::Lacking {
                file: self.path.to_path_buf(),
                what: "no particle material in the material_assignation_table (SpheresPart, DEMInletPart)".into(),
                supported: "assign a material to the particles' model part".into(),
            });
        }
        Ok(bodies)
    }

    /// One wall per material assigned to rigid faces, its parts named together.
    fn walls(&self) -> Vec<DeckWall> {
        let mut walls = Vec::new();
        for (id, parts) in &self.assigned {
            let names: Vec<&str> = parts
                .iter()
                .filter(|p| p.root == Root::Walls)
                .map(|p| p.name.as_str())
                .collect();
            if names.is_empty() {
                continue;
            }
            let material = self.material(*id);
            walls.push(DeckWall {
                name: names.join(", "),
                type_id: Some(*id),
                youngs_modulus: material.typed.variables.get(MaterialVariable::YoungModulus),
                poisson_ratio: material.typed.variables.get(MaterialVariable::PoissonRatio),
                from: material.at(),
            });
        }
        walls
    }

    /// Every pair of bodies and every body against every wall, each with its relation's law;
    /// and the indices of the relations used.
    fn contacts(
        &self,
        project: &Project,
        bodies: &[DeckBody],
        walls: &[DeckWall],
    ) -> Result<(Vec<DeckContact>, BTreeSet<usize>), DeckError> {
        let mut extra_traps: Vec<String> = Vec::new();
        if let Some((g, at)) = &project.global_damping {
            extra_traps.push(format!("GlobalDamping {g} ({at}) is left out: in the simulation it also damps each particle's motion, so its rebounds are lower than the COR here"));
        }
        let mut used_relations = BTreeSet::new();
        // Each pair's law with the traps of the project's search and damping.
        let mut with_project = |relation: &Relation<'_>, mut pl: PairLaw, at_wall: bool| {
            used_relations.insert(relation.index);
            let search = project.search.as_ref();
            pl.traps
                .extend(search.map(|s| s.trap(at_wall, project.timestep)));
            pl.traps.extend(extra_traps.iter().cloned());
            pl
        };
        let mut contacts = body_contacts(bodies, |body, other| {
            let relation = self.relation(body.type_id, other.type_id)?;
            let own = (self.material(body.type_id), body.radius, body.mass);
            let side = Side::Particle(self.material(other.type_id), other.radius, other.mass);
            Ok(with_project(
                relation,
                pair_law(relation, own, &side)?,
                false,
            ))
        })?;
        contacts.extend(wall_contacts(
            bodies,
            walls,
            WallOrder::ByWall,
            |wall, body| {
                let wall_id = wall.type_id.unwrap_or_default();
                let relation = self.relation(body.type_id, wall_id)?;
                let side = Side::Wall(self.material(wall_id), &wall.name);
                let own = (self.material(body.type_id), body.radius, body.mass);
                Ok(with_project(
                    relation,
                    pair_law(relation, own, &side)?,
                    true,
                ))
            },
        )?);
        Ok((contacts, used_relations))
    }

    /// The materials file reduced to the materials in use and the relations checked, as
    /// written in `value`; the relations no checked pair uses are listed in `left_out`.
    fn written_back(
        &self,
        value: &Value,
        used: &BTreeSet<MaterialId>,
        used_relations: &BTreeSet<usize>,
        left_out: &mut Vec<String>,
    ) -> Result<String, DeckError> {
        let written = |key: &str, index: usize| value[key][index].clone();
        let reduced = serde_json::json!({
            "materials": self.materials.iter().filter(|m| used.contains(&m.id())).map(|m| written("materials", m.index)).collect::<Vec<_>>(),
            "material_relations": self.relations.iter().filter(|r| used_relations.contains(&r.index)).map(|r| written("material_relations", r.index)).collect::<Vec<_>>(),
        });
        let unused: Vec<String> = self
            .relations
            .iter()
            .filter(|r| !used_relations.contains(&r.index))
            .map(|r| {
                let law = r
                    .typed
                    .variables
                    .law
                    .as_ref()
                    .map_or("no law", LawName::name);
                format!("material_relations[{}] ({law})", r.index)
            })
            .collect();
        if !unused.is_empty() {
            left_out.push(format!(
                "relations no checked pair uses ({}: {})",
                self.path.display(),
                unused.join(", ")
            ));
        }
        serde_json::to_string_pretty(&reduced).map_err(|e| DeckError::Lacking {
            file: self.path.to_path_buf(),
            what: format!("its materials cannot be written back as JSON: {e}"),
            supported: "plain JSON values".into(),
        })
    }
}

/// Which model parts are particles and which walls, each with its material: the assignation
/// table read, a material named by name or id, clusters left out with a line in `left_out`.
fn assign_parts(
    path: &Path,
    file: &MaterialsFile,
    materials: &[Material<'_>],
    left_out: &mut Vec<String>,
) -> Result<BTreeMap<MaterialId, Vec<Assigned>>, DeckError> {
    let parts_supported = "SpheresPart, DEMInletPart and RigidFacePart (ClusterPart is left out), or their sub-model parts";
    let mut assigned: BTreeMap<MaterialId, Vec<Assigned>> = BTreeMap::new();
    for (index, entry) in file.material_assignation_table.iter().enumerate() {
        let entry_at =
            |k: usize| DeckSource::field(path, format!("material_assignation_table[{index}][{k}]"));
        let material = match &entry.material {
            MaterialRef::Name(n) => materials
                .iter()
                .find(|m| m.typed.material_name.as_deref() == Some(n.as_str()))
                .map(Material::id)
                .ok_or_else(|| {
                    DeckError::unsupported(
                        entry_at(1),
                        format!("material `{n}` is in no material_name"),
                        "the name or id of a material of the file",
                    )
                })?,
            MaterialRef::Id(id) => *id,
        };
        if !materials.iter().any(|m| m.id() == material) {
            return Err(DeckError::unsupported(
                entry_at(1),
                format!("material {material} is in no material_id"),
                "the name or id of a material of the file",
            ));
        }
        let root = match split_part(&entry.part).0 {
            "SpheresPart" => Root::Spheres,
            "DEMInletPart" => Root::Inlet,
            "RigidFacePart" => Root::Walls,
            "ClusterPart" => {
                left_out.push(format!(
                    "clusters ({}, {}): particles of several spheres are not checked",
                    entry.part,
                    DeckSource::field(path, format!("material_assignation_table[{index}]"))
                ));
                continue;
            }
            other => {
                return Err(DeckError::unsupported(
                    entry_at(0),
                    format!("model part `{other}`"),
                    parts_supported,
                ));
            }
        };
        assigned.entry(material).or_default().push(Assigned {
            name: entry.part.clone(),
            root,
            index,
        });
    }
    Ok(assigned)
}

impl DeckDialect for KratosDeck {
    fn recognises(&self, path: &Path, text: &str) -> bool {
        let looks_like =
            path.extension().is_some_and(|e| e == "json") || text.trim_start().starts_with('{');
        looks_like
            && serde_json::from_str::<Value>(text)
                .ok()
                .as_ref()
                .and_then(kind_of)
                .is_some()
    }

    fn reads(&self) -> &'static str {
        "Kratos DEM MaterialsDEM.json or ProjectParametersDEM.json"
    }

    fn read(&self, path: &Path, options: &DeckOptions) -> Result<UserDeck, DeckError> {
        if let Some((name, _)) = options.variables.first() {
            return Err(DeckError::Lacking {
                file: path.to_path_buf(),
                what: format!("--var {name}: a Kratos setup has no variables"),
                supported: "leave --var out (it sets LIGGGHTS and LAMMPS variables)".into(),
            });
        }
        let files = Self::files(path, read_json(path)?)?;
        let (project_path, project_value) = files.project;
        let project_file: ProjectFile = files::typed(&project_path, &project_value)?;
        let (project, named_by_project) = Project::read(&project_path, &project_file)?;
        let (materials_path, materials_value) = match files.materials {
            None => {
                let value = read_json(&named_by_project)?;
                (named_by_project, value)
            }
            Some((named, value)) => {
                let same = std::fs::canonicalize(&named_by_project).ok()
                    == std::fs::canonicalize(&named).ok();
                if !same {
                    return Err(DeckError::Lacking {
                        file: path.to_path_buf(),
                        what: format!(
                            "the {PROJECT_FILE} beside it names the materials file {}",
                            named_by_project.display()
                        ),
                        supported: format!(
                            "name {} instead, or make its materials_filename name this file",
                            project_path.display()
                        ),
                    });
                }
                (named, value)
            }
        };
        let file: MaterialsFile = files::typed(&materials_path, &materials_value)?;
        let mut left_out = project.left_out.clone();
        let setup = MaterialsSetup::read(&materials_path, &file, &mut left_out)?;
        setup.check_given(options)?;
        let bodies = setup.bodies(&project, options)?;
        let walls = setup.walls();
        let (contacts, used_relations) = setup.contacts(&project, &bodies, &walls)?;
        let used: BTreeSet<MaterialId> = bodies
            .iter()
            .map(|b| b.type_id)
            .chain(walls.iter().filter_map(|w| w.type_id))
            .collect();
        let common = setup.written_back(&materials_value, &used, &used_relations, &mut left_out)?;
        let particle_types = u32::try_from(
            bodies
                .iter()
                .map(|b| b.type_id)
                .collect::<BTreeSet<_>>()
                .len(),
        )
        .unwrap_or(u32::MAX);
        let written = |key: &str, index: usize| materials_value[key][index].clone();
        Ok(UserDeck {
            path: path.to_path_buf(),
            timestep: project.timestep,
            timestep_from: project.timestep_from,
            bodies,
            walls,
            contacts,
            representative_velocity: None,
            left_out,
            transplant: Transplant {
                before_box: Vec::new(),
                common: common.lines().map(str::to_string).collect(),
                walls: setup
                    .assigned
                    .values()
                    .flatten()
                    .filter(|p| p.root == Root::Walls)
                    .map(|p| written("material_assignation_table", p.index).to_string())
                    .collect(),
                types: particle_types,
            },
        })
    }

    fn input(&self, deck: &UserDeck, plan: ImpactPlan<'_>) -> Result<DeckImpactInput, CodeError> {
        let (body, other, (v1, v2)) = (plan.body, plan.other, plan.velocities);
        let other_material = match plan.contact.partner {
            Partner::Body(o) => deck.bodies[o].type_id,
            Partner::Wall(w) => deck.walls[w].type_id.unwrap_or_default(),
        };
        // The script starts the bodies one ulp apart (`math.nextafter`), as the driver does.
        let start_gap = plan.reach.next_up() - plan.reach;
        let num = exact_number;
        let materials = serde_json::to_string(&deck.transplant.common.join("\n")).map_err(|e| {
            CodeError::Unsupported {
                code: "kratos".into(),
                case: plan.setup.case_name.clone(),
                reason: e.to_string(),
            }
        })?;
        let values = [
            ("scene", plan.setup.scene.name().to_string()),
            ("timestep", num(deck.timestep)),
            ("steps", plan.steps.to_string()),
            ("material", body.type_id.to_string()),
            ("radius", num(body.radius)),
            ("velocity", num(v1)),
            ("other_material", other_material.to_string()),
            ("other_radius", num(other.map_or(0.0, |o| o.radius))),
            ("other_velocity", num(v2)),
            ("scheme", SCHEME.to_string()),
            // Last: the user's text is filled in after every placeholder.
            ("materials", materials),
        ];
        let text = fill_template(&super::with_common(TEMPLATE), &values).map_err(|e| {
            CodeError::Unsupported {
                code: "kratos".into(),
                case: plan.setup.case_name.clone(),
                reason: e.to_string(),
            }
        })?;
        Ok(DeckImpactInput {
            input: RenderedInput {
                file_name: SCRIPT.to_string(),
                text,
                args: vec![SCRIPT.to_string()],
            },
            setup: plan.setup,
            start_gap,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Kratos 10.4.4 logged these DAMPING_GAMMA values for COEFFICIENT_OF_RESTITUTION 0.5 and 1.0
    /// with DEM_D_Linear_viscous_Coulomb and DEM_D_Linear_Custom_Constants.
    #[allow(clippy::float_cmp)]
    #[test]
    fn the_linear_gamma_is_kratos_bisection_bit_for_bit() {
        assert_eq!(linear_damping_gamma(0.5), 0.255279541015625);
        assert_eq!(linear_damping_gamma(1.0), 0.0);
        assert_eq!(linear_damping_gamma(0.9995), 0.0);
        assert_eq!(linear_damping_gamma(0.0), linear_damping_gamma(0.001));
        // Within the bisection's 1e-4 of the exact clamped ratio.
        for e in [0.2, 0.3, 0.5, 0.7, 0.9] {
            let exact = crate::codes::damping::clamped_linear_damping_ratio(e).unwrap();
            assert!((linear_damping_gamma(e) - exact).abs() < 1e-4, "{e}");
        }
    }

    /// The laws named in messages are the ones the typed reader takes.
    #[test]
    fn the_laws_named_are_the_laws_read() {
        let names: Vec<&str> = SteppedLaw::ALL.iter().map(|l| l.name()).collect();
        assert_eq!(names.join(", "), LAWS);
    }

    #[test]
    fn mdpa_parts_radii_and_inlet_data_are_read() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("xDEM.mdpa");
        std::fs::write(
            &path,
            "Begin Properties 0\nEnd Properties\nBegin Nodes\n 1 0 0 0\n 2 1 0 0\n 3 2 0 0\nEnd Nodes\n\
Begin Elements SphericParticle3D // the balls\n 1 0 1\n 2 0 2\n 3 0 3\nEnd Elements\n\
Begin NodalData RADIUS\n 1 0 0.03\n 2 0 0.03\n 3 0 0.02\nEnd NodalData\n\
Begin SubModelPart Big\n Begin SubModelPartData\n  RADIUS 0.5\n End SubModelPartData\n Begin SubModelPartElements\n  1 2\n End SubModelPartElements\n\
 Begin SubModelPart Inner\n  Begin SubModelPartElements\n   3\n  End SubModelPartElements\n End SubModelPart\nEnd SubModelPart\n",
        )
        .unwrap();
        let m = Mdpa::read(&path).unwrap();
        let radii =
            |part| -> Vec<(f64, usize)> { m.radii(&path, part).unwrap().into_values().collect() };
        assert_eq!(radii(None).len(), 2);
        // A part holds its own elements and its sub-parts'.
        assert_eq!(radii(Some("Big")).iter().map(|r| r.1).sum::<usize>(), 3);
        assert_eq!(radii(Some("Big.Inner")), [(0.02, 1)]);
        assert_eq!(m.parts["Big"].data["RADIUS"], "0.5");
        assert_eq!(m.parts["Big.Inner"].line, 25);
    }
}
