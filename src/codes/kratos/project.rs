//! A Kratos DEM project (`ProjectParametersDEM.json`) as the deck reader takes it, from the
//! typed records of `files.rs`: the time step, the scheme and the other settings the check
//! refuses or leaves out, the neighbour search, the `.mdpa` files' problem name and the
//! materials file it names, all with Kratos 10.4.4's defaults; and which of a setup's files a
//! JSON file the user names is.

use std::path::{Path, PathBuf};

use serde_json::Value;

use super::SCHEME;
use super::files::{Number, ProjectFile};
use crate::codes::deck::{DeckError, DeckSource, SourceLine};

/// The project parameters file a materials file is read with, in its folder.
pub(crate) const PROJECT_FILE: &str = "ProjectParametersDEM.json";

/// The materials file a project names when it names none (`sphere_strategy.py`'s default).
pub(crate) const MATERIALS_FILE: &str = "MaterialsDEM.json";

/// Kratos 10.4.4's own defaults for what a project may leave out
/// (`dem_default_input_parameters.py`): the step, the scheme, the search frequency, gravity.
const DEFAULT_MAX_TIME_STEP: f64 = 5e-5;
const DEFAULT_NEIGHBOUR_SEARCH_FREQUENCY: f64 = 50.0;

/// Read a JSON file, or say where it is not JSON.
pub(super) fn read_json(path: &Path) -> Result<Value, DeckError> {
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
pub(super) enum FileKind {
    Materials,
    Project,
}

/// Which of a setup's files `value` is, by the keys only that file has.
pub(super) fn kind_of(value: &Value) -> Option<FileKind> {
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

/// How often Kratos looks for new contacts, and how far.
#[derive(Clone, Debug)]
pub(super) struct Search {
    frequency: f64,
    from: String,
    particles: f64,
    walls: f64,
    absolute: bool,
}

impl Search {
    /// The trap of a pair (against a wall or not) at time step `dt`.
    pub(super) fn trap(&self, wall: bool, dt: f64) -> String {
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
pub(super) struct Project {
    pub(super) timestep: f64,
    pub(super) timestep_from: String,
    pub(super) global_damping: Option<(f64, DeckSource)>,
    pub(super) search: Option<Search>,
    pub(super) problem_name: Option<String>,
    pub(super) folder: PathBuf,
    pub(super) left_out: Vec<String>,
}

impl Project {
    /// The settings of the project `file` (at `path`), refused where the check cannot model
    /// them, and the path of the materials file it names.
    pub(super) fn read(path: &Path, file: &ProjectFile) -> Result<(Self, PathBuf), DeckError> {
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
        // Kratos' default element and strategy are the only ones of discontinuum spheres.
        let spheres_only = |key: &str, value: Option<&str>, only: &str| {
            let given = value.unwrap_or(only);
            if given == only {
                return Ok(());
            }
            let supported = format!("{only} (discontinuum spheres)");
            Err(refuse(key, given.to_string(), &supported))
        };
        let element = file.element_type.as_deref();
        spheres_only("ElementType", element, "SphericPartDEMElement3D")?;
        let strategy = file.solver_settings.strategy.as_deref();
        spheres_only("solver_settings.strategy", strategy, "sphere_strategy")?;
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

/// The files of a setup: the materials (its path and value, or `None` when the project was
/// named and the materials are to be read from the file it names), and the project's.
pub(super) struct SetupFiles {
    pub(super) materials: Option<(PathBuf, Value)>,
    pub(super) project: (PathBuf, Value),
}

impl SetupFiles {
    /// The materials and the project of the file named, whichever of the two it is.
    pub(super) fn read(path: &Path, named: Value) -> Result<Self, DeckError> {
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
