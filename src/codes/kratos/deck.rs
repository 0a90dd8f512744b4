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
//!
//! The project is read in `project.rs`, the materials file in `materials.rs`, the `.mdpa` files
//! in `mdpa.rs`; here are the bodies, walls and contacts, each pair's law, and the impact
//! rendered.

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

use serde_json::Value;

use super::files::{
    self, LawName, MaterialId, MaterialVariable, MaterialsFile, ProjectFile, SteppedLaw,
};
use super::materials::{Material, MaterialsSetup, Relation, Root, missing};
use super::mdpa::Mdpa;
use super::project::{PROJECT_FILE, Project, SetupFiles, kind_of, read_json};
use super::{
    LOWEST_RESTITUTION, SCHEME, SCRIPT, UNDAMPED_ABOVE, hertz_damping_gamma, linear_damping_gamma,
    mixed_modulus, particle_mass,
};
use crate::codes::CodeError;
use crate::codes::damping::hertz_input_restitution;
use crate::codes::deck::{
    DeckBody, DeckContact, DeckDialect, DeckError, DeckImpactInput, DeckOptions, DeckSource,
    DeckWall, ImpactPlan, PairLaw, Partner, SourceLine, Transplant, UserDeck, WallOrder,
    body_contacts, wall_contacts,
};
use crate::codes::template::{exact_number, fill_template};
use crate::model::law::DashpotLaw;

/// The Python template of one impact with a user's materials.
pub(super) const TEMPLATE: &str = include_str!("deck.py");

/// Most radii one material's particles may have in the `.mdpa` for each to be checked; a
/// distribution of more is given with `--particle`.
pub(crate) const MAX_SIZES: usize = 3;

/// `DEM_D_Linear_viscous_Coulomb`'s stiffness factor between particles (`beta`), absent at a
/// wall.
pub(crate) const LINEAR_PARTICLE_FACTOR: f64 = 1.432;
/// `DEM_D_Linear_viscous_Coulomb`'s "modified radius" over the contact radius.
pub(crate) const LINEAR_RADIUS_FACTOR: f64 = 0.31225;

/// Kratos' deck reader.
pub(crate) struct KratosDeck;

/// A model part's name split at its first dot: the root part and the sub-model part below it.
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
                        at.refuse(
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

impl<'f> MaterialsSetup<'f> {
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
        let files = SetupFiles::read(path, read_json(path)?)?;
        let (project_path, project_value) = files.project;
        let project_file: ProjectFile = files::typed(&project_path, &project_value)?;
        let (project, named_by_project) = Project::read(&project_path, &project_file)?;
        // Kratos reads the spheres' model part before anything runs, and stops where it is
        // not there: so does the check, naming the field its name comes from.
        let spheres_name = format!(
            "{}DEM.mdpa",
            project.problem_name.as_deref().unwrap_or_default()
        );
        let spheres = project.folder.join(&spheres_name);
        if !spheres.is_file() {
            return Err(DeckError::missing(
                DeckSource::field(&project_path, "problem_name"),
                "the spheres' model part (problem_name + \"DEM.mdpa\")",
                &spheres_name,
                &spheres,
            ));
        }
        let (materials_path, materials_value) = match files.materials {
            None => {
                if !named_by_project.is_file() {
                    return Err(DeckError::missing(
                        DeckSource::field(
                            &project_path,
                            "solver_settings.material_import_settings.materials_filename",
                        ),
                        "the materials file",
                        &named_by_project
                            .file_name()
                            .map_or(String::new(), |n| n.to_string_lossy().into_owned()),
                        &named_by_project,
                    ));
                }
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
        let materials = serde_json::to_string(&deck.transplant.common.join("\n"))
            .map_err(|e| plan.setup.unsupported("kratos", e.to_string()))?;
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
        let text = fill_template(&super::with_common(TEMPLATE), &values)
            .map_err(|e| plan.setup.unsupported("kratos", e.to_string()))?;
        Ok(DeckImpactInput {
            input: super::script_input(SCRIPT, text),
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
}
