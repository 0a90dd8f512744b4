//! A Kratos DEM setup's JSON files as typed serde structs: the parts of `MaterialsDEM.json`
//! and `ProjectParametersDEM.json` the deck check reads. Fields the check does not read are
//! let through, as Kratos lets them through; a field read but of the wrong type is refused in
//! one line naming the file, the field's path, the value found and what is allowed
//! (`MaterialsDEM.json: materials[1].Variables.YOUNG_MODULUS: found "abc"; supported: a number`).
//! Whether a field may be missing depends on its use (a wall's material has no density), so
//! such fields are `Option`s, required where the check uses them.

use std::fmt;
use std::path::Path;

use serde::Deserialize;
use serde::de::{self, Deserializer, IgnoredAny, SeqAccess, Unexpected, Visitor};
use serde_json::Value;

use crate::codes::deck::{DeckError, DeckSource};

/// A finite number, as Kratos reads a double.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Number(pub f64);

impl<'de> Deserialize<'de> for Number {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let value = Value::deserialize(deserializer)?;
        value
            .as_f64()
            .filter(|x| x.is_finite())
            .map(Number)
            .ok_or_else(|| refuse(&value, &"a number"))
    }
}

/// A material's id: `material_id`, an entry of `material_ids_list` or of the assignation table.
pub(crate) type MaterialId = u32;

/// What a material id must be, in an error.
const MATERIAL_ID: &str = "a material id (a whole number from 0)";

/// A material id, read as Kratos reads an int.
fn material_id<'de, D: Deserializer<'de>>(deserializer: D) -> Result<MaterialId, D::Error> {
    let value = Value::deserialize(deserializer)?;
    value
        .as_u64()
        .and_then(|x| u32::try_from(x).ok())
        .ok_or_else(|| refuse(&value, &MATERIAL_ID))
}

/// The error of a value that is not `expected` (its text is the path's value, looked up again
/// by [`field_error`]).
fn refuse<E: de::Error>(value: &Value, expected: &dyn de::Expected) -> E {
    let unexpected = match value {
        Value::Null => Unexpected::Unit,
        Value::Bool(b) => Unexpected::Bool(*b),
        Value::Number(n) => n
            .as_f64()
            .map_or(Unexpected::Other("a number"), Unexpected::Float),
        Value::String(s) => Unexpected::Str(s),
        Value::Array(_) => Unexpected::Seq,
        Value::Object(_) => Unexpected::Map,
    };
    E::invalid_type(unexpected, expected)
}

/// `MaterialsDEM.json`: the materials, their relations and which model part has which.
#[derive(Clone, Debug, Deserialize)]
#[serde(
    expecting = "a Kratos DEM materials file (materials, material_relations, material_assignation_table)"
)]
pub(crate) struct MaterialsFile {
    /// The materials.
    pub materials: Vec<Material>,
    /// The contact settings of pairs of materials.
    pub material_relations: Vec<Relation>,
    /// Which model part is made of which material.
    pub material_assignation_table: Vec<Assignment>,
}

/// A material: its id, name and `Variables`.
#[derive(Clone, Debug, Deserialize)]
#[serde(expecting = "a material (material_id, material_name, Variables)")]
pub(crate) struct Material {
    /// Its id.
    #[serde(deserialize_with = "material_id")]
    pub material_id: MaterialId,
    /// Its name, by which the assignation table may name it.
    #[serde(default)]
    pub material_name: Option<String>,
    /// Its variables (a wall's material has no density).
    #[serde(rename = "Variables", default)]
    pub variables: MaterialVariables,
}

/// The variables of a material the check reads.
#[derive(Clone, Debug, Default, Deserialize)]
#[serde(expecting = "a material's Variables (PARTICLE_DENSITY, YOUNG_MODULUS, POISSON_RATIO)")]
pub(crate) struct MaterialVariables {
    /// `PARTICLE_DENSITY`, kg/m³.
    #[serde(rename = "PARTICLE_DENSITY", default)]
    pub particle_density: Option<Number>,
    /// `YOUNG_MODULUS`, Pa.
    #[serde(rename = "YOUNG_MODULUS", default)]
    pub young_modulus: Option<Number>,
    /// `POISSON_RATIO`.
    #[serde(rename = "POISSON_RATIO", default)]
    pub poisson_ratio: Option<Number>,
}

/// A variable of a material the check reads.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum MaterialVariable {
    /// `PARTICLE_DENSITY`, kg/m³.
    ParticleDensity,
    /// `YOUNG_MODULUS`, Pa.
    YoungModulus,
    /// `POISSON_RATIO`.
    PoissonRatio,
}

impl MaterialVariable {
    /// Kratos' name of the variable.
    pub(crate) fn name(self) -> &'static str {
        match self {
            MaterialVariable::ParticleDensity => "PARTICLE_DENSITY",
            MaterialVariable::YoungModulus => "YOUNG_MODULUS",
            MaterialVariable::PoissonRatio => "POISSON_RATIO",
        }
    }
}

impl MaterialVariables {
    /// The value of `variable`, if the material has it.
    pub(crate) fn get(&self, variable: MaterialVariable) -> Option<f64> {
        match variable {
            MaterialVariable::ParticleDensity => self.particle_density,
            MaterialVariable::YoungModulus => self.young_modulus,
            MaterialVariable::PoissonRatio => self.poisson_ratio,
        }
        .map(|n| n.0)
    }
}

/// A material relation: the contact settings of two materials.
#[derive(Clone, Debug, Deserialize)]
#[serde(expecting = "a material relation (material_ids_list, Variables)")]
pub(crate) struct Relation {
    /// The two materials.
    #[serde(deserialize_with = "id_pair")]
    pub material_ids_list: [MaterialId; 2],
    /// Its law, restitution and friction.
    #[serde(rename = "Variables")]
    pub variables: RelationVariables,
}

/// `material_ids_list`: two material ids.
fn id_pair<'de, D: Deserializer<'de>>(deserializer: D) -> Result<[MaterialId; 2], D::Error> {
    struct Pair;
    impl<'de> Visitor<'de> for Pair {
        type Value = [MaterialId; 2];
        fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
            f.write_str("two material ids [ID, ID]")
        }
        fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Self::Value, A::Error> {
            let mut ids = [0; 2];
            for (k, id) in ids.iter_mut().enumerate() {
                *id = seq
                    .next_element::<Id>()?
                    .ok_or_else(|| de::Error::invalid_length(k, &self))?
                    .0;
            }
            if seq.next_element::<IgnoredAny>()?.is_some() {
                return Err(de::Error::invalid_length(3, &self));
            }
            Ok(ids)
        }
    }
    deserializer.deserialize_seq(Pair)
}

/// A material id inside a list.
struct Id(MaterialId);

impl<'de> Deserialize<'de> for Id {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        material_id(deserializer).map(Id)
    }
}

/// The variables of a relation the check reads.
#[derive(Clone, Debug, Deserialize)]
#[serde(expecting = "a relation's Variables (its law and restitution)")]
pub(crate) struct RelationVariables {
    /// `DEM_DISCONTINUUM_CONSTITUTIVE_LAW_NAME`.
    #[serde(rename = "DEM_DISCONTINUUM_CONSTITUTIVE_LAW_NAME", default)]
    pub law: Option<LawName>,
    /// `COEFFICIENT_OF_RESTITUTION`.
    #[serde(rename = "COEFFICIENT_OF_RESTITUTION", default)]
    pub restitution: Option<Number>,
    /// `K_NORMAL`, N/m (`DEM_D_Linear_Custom_Constants`).
    #[serde(rename = "K_NORMAL", default)]
    pub k_normal: Option<Number>,
    /// `STATIC_FRICTION`.
    #[serde(rename = "STATIC_FRICTION", default)]
    pub static_friction: Option<Number>,
    /// `DYNAMIC_FRICTION`.
    #[serde(rename = "DYNAMIC_FRICTION", default)]
    pub dynamic_friction: Option<Number>,
    /// `ROLLING_FRICTION`.
    #[serde(rename = "ROLLING_FRICTION", default)]
    pub rolling_friction: Option<Number>,
    /// `ROLLING_FRICTION_WITH_WALLS`.
    #[serde(rename = "ROLLING_FRICTION_WITH_WALLS", default)]
    pub rolling_friction_with_walls: Option<Number>,
}

impl RelationVariables {
    /// The tangential variables set to something other than zero, by name.
    pub(crate) fn tangential(&self) -> Vec<&'static str> {
        [
            ("STATIC_FRICTION", self.static_friction),
            ("DYNAMIC_FRICTION", self.dynamic_friction),
            ("ROLLING_FRICTION", self.rolling_friction),
            (
                "ROLLING_FRICTION_WITH_WALLS",
                self.rolling_friction_with_walls,
            ),
        ]
        .into_iter()
        .filter(|(_, v)| v.is_some_and(|x| x.0 != 0.0))
        .map(|(name, _)| name)
        .collect()
    }
}

/// A relation's constitutive law: one whose force the harness steps, or another, named as
/// written (refused where a checked pair uses it, reported where none does).
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) enum LawName {
    /// A law the harness steps.
    Stepped(SteppedLaw),
    /// Any other name.
    Other(String),
}

/// The constitutive laws whose force the harness steps.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum SteppedLaw {
    /// `DEM_D_Hertz_viscous_Coulomb`.
    HertzViscousCoulomb,
    /// `DEM_D_Linear_viscous_Coulomb`.
    LinearViscousCoulomb,
    /// `DEM_D_Linear_Custom_Constants`.
    LinearCustomConstants,
}

impl SteppedLaw {
    /// Every law the harness steps.
    pub(crate) const ALL: [SteppedLaw; 3] = [
        SteppedLaw::HertzViscousCoulomb,
        SteppedLaw::LinearViscousCoulomb,
        SteppedLaw::LinearCustomConstants,
    ];

    /// Kratos' name of the law.
    pub(crate) fn name(self) -> &'static str {
        match self {
            SteppedLaw::HertzViscousCoulomb => "DEM_D_Hertz_viscous_Coulomb",
            SteppedLaw::LinearViscousCoulomb => "DEM_D_Linear_viscous_Coulomb",
            SteppedLaw::LinearCustomConstants => "DEM_D_Linear_Custom_Constants",
        }
    }
}

impl LawName {
    /// Kratos' name of the law, as written.
    pub(crate) fn name(&self) -> &str {
        match self {
            LawName::Stepped(law) => law.name(),
            LawName::Other(name) => name,
        }
    }
}

impl<'de> Deserialize<'de> for LawName {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let value = Value::deserialize(deserializer)?;
        let name = value
            .as_str()
            .ok_or_else(|| refuse(&value, &"a constitutive law's name"))?;
        Ok(SteppedLaw::ALL
            .into_iter()
            .find(|law| law.name() == name)
            .map_or_else(|| LawName::Other(name.to_string()), LawName::Stepped))
    }
}

/// An entry of the assignation table: a model part and its material.
#[derive(Clone, Debug)]
pub(crate) struct Assignment {
    /// The model part (`SpheresPart.Balls`).
    pub part: String,
    /// Its material.
    pub material: MaterialRef,
}

/// A material as the assignation table names it.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) enum MaterialRef {
    /// By its `material_name`.
    Name(String),
    /// By its `material_id`.
    Id(MaterialId),
}

impl<'de> Deserialize<'de> for MaterialRef {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let value = Value::deserialize(deserializer)?;
        match &value {
            Value::String(name) => Ok(MaterialRef::Name(name.clone())),
            _ => value
                .as_u64()
                .and_then(|x| u32::try_from(x).ok())
                .map(MaterialRef::Id)
                .ok_or_else(|| refuse(&value, &"a material's material_name or material_id")),
        }
    }
}

impl<'de> Deserialize<'de> for Assignment {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct Entry;
        impl<'de> Visitor<'de> for Entry {
            type Value = Assignment;
            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str("a [MODEL PART, MATERIAL] pair")
            }
            fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Assignment, A::Error> {
                let part = seq
                    .next_element::<String>()?
                    .ok_or_else(|| de::Error::invalid_length(0, &self))?;
                let material = seq
                    .next_element::<MaterialRef>()?
                    .ok_or_else(|| de::Error::invalid_length(1, &self))?;
                if seq.next_element::<IgnoredAny>()?.is_some() {
                    return Err(de::Error::invalid_length(3, &self));
                }
                Ok(Assignment { part, material })
            }
        }
        deserializer.deserialize_seq(Entry)
    }
}

/// `ProjectParametersDEM.json`: the settings the check reads; a missing one is Kratos'
/// default.
#[derive(Clone, Debug, Default, Deserialize)]
#[serde(expecting = "Kratos DEM project parameters (an object)")]
pub(crate) struct ProjectFile {
    /// `Dimension`.
    #[serde(rename = "Dimension", default)]
    pub dimension: Option<Number>,
    /// `ElementType`.
    #[serde(rename = "ElementType", default)]
    pub element_type: Option<String>,
    /// `solver_settings`.
    #[serde(default)]
    pub solver_settings: SolverSettings,
    /// `TranslationalIntegrationScheme`.
    #[serde(rename = "TranslationalIntegrationScheme", default)]
    pub translational_scheme: Option<String>,
    /// `VirtualMassCoefficient`.
    #[serde(rename = "VirtualMassCoefficient", default)]
    pub virtual_mass_coefficient: Option<Number>,
    /// `MaxTimeStep`, s.
    #[serde(rename = "MaxTimeStep", default)]
    pub max_time_step: Option<Number>,
    /// `AutomaticTimestep`.
    #[serde(rename = "AutomaticTimestep", default)]
    pub automatic_timestep: Option<bool>,
    /// `GlobalDamping`.
    #[serde(rename = "GlobalDamping", default)]
    pub global_damping: Option<Number>,
    /// `NeighbourSearchFrequency`, steps.
    #[serde(rename = "NeighbourSearchFrequency", default)]
    pub neighbour_search_frequency: Option<Number>,
    /// `SearchTolerance`, m between particles.
    #[serde(rename = "SearchTolerance", default)]
    pub search_tolerance: Option<Number>,
    /// `search_tolerance_against_walls`, m.
    #[serde(default)]
    pub search_tolerance_against_walls: Option<Number>,
    /// `DeltaOption` (`Absolute` makes the tolerances lengths).
    #[serde(rename = "DeltaOption", default)]
    pub delta_option: Option<String>,
    /// `problem_name`, the stem of the `.mdpa` files.
    #[serde(default)]
    pub problem_name: Option<String>,
}

/// `solver_settings`.
#[derive(Clone, Debug, Default, Deserialize)]
#[serde(expecting = "the solver settings (an object)")]
pub(crate) struct SolverSettings {
    /// `strategy`.
    #[serde(default)]
    pub strategy: Option<String>,
    /// `material_import_settings`.
    #[serde(default)]
    pub material_import_settings: MaterialImportSettings,
}

/// `solver_settings.material_import_settings`.
#[derive(Clone, Debug, Default, Deserialize)]
#[serde(expecting = "the material import settings (an object)")]
pub(crate) struct MaterialImportSettings {
    /// `materials_filename`, beside the project.
    #[serde(default)]
    pub materials_filename: Option<String>,
}

/// `value` (a whole file as JSON) read as `T`, or the one-line error of its first field that
/// is not what `T` allows.
pub(crate) fn typed<T: de::DeserializeOwned>(file: &Path, value: &Value) -> Result<T, DeckError> {
    serde_path_to_error::deserialize(value).map_err(|e| field_error(file, value, &e))
}

/// A typed read's error as the deck reports it: the field's path, what is there, what is
/// allowed.
fn field_error(
    file: &Path,
    root: &Value,
    error: &serde_path_to_error::Error<serde_json::Error>,
) -> DeckError {
    let mut path = error.path().to_string();
    let message = error.inner().to_string();
    // A field every file (or entry) must have.
    if let Some(field) = message
        .strip_prefix("missing field `")
        .and_then(|m| m.strip_suffix('`'))
    {
        path = if path == "." {
            field.to_string()
        } else {
            format!("{path}.{field}")
        };
        return DeckError::unsupported(
            DeckSource::field(file, path),
            format!("no {field}"),
            &format!("{field}, which Kratos requires there"),
        );
    }
    let mut found = root;
    for segment in error.path() {
        let next = match segment {
            serde_path_to_error::Segment::Seq { index } => found.get(index),
            serde_path_to_error::Segment::Map { key } => found.get(key.as_str()),
            _ => None,
        };
        match next {
            Some(v) => found = v,
            None => break,
        }
    }
    // serde says `invalid type: …, expected X` and `invalid length N, expected X`.
    let allowed = message
        .rsplit_once(", expected ")
        .map_or(message.as_str(), |(_, expected)| expected)
        .replace("a sequence", "a list")
        .replace("a map", "an object");
    if path == "." {
        path = "the file's top level".to_string();
    }
    DeckError::unsupported(
        DeckSource::field(file, path),
        format!("found {}", shown(found)),
        &allowed,
    )
}

/// A JSON value as the error shows it: its text, cut after 60 characters.
fn shown(value: &Value) -> String {
    let text = value.to_string();
    match text.char_indices().nth(60) {
        Some((at, _)) => format!("{}…", &text[..at]),
        None => text,
    }
}
