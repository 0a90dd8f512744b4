//! The `model …` words of LIGGGHTS' granular pair style and wall fixes (`pair_style gran`,
//! `fix wall/gran`), with their settings and walls, as LIGGGHTS 3.8 reads them: what the deck
//! check and the mill both read a deck's contact lines with.

use std::collections::HashMap;

use crate::codes::deck::{DeckError, SourceLine, whole_number};
use crate::codes::script::Command;

/// The normal models whose law the harness knows.
const NORMAL_MODELS: &str = "model hertz, hooke, hertz/stiffness, hooke/stiffness, paper, paper/linear (the last two run in liggghts-paper)";

/// The paper's normal models (`scripts/liggghts-paper/normal_model_paper.h`), built into
/// liggghts-paper only.
pub(super) const PAPER_MODELS: [&str; 2] = ["paper", "paper/linear"];

/// A `model …` specification of `pair_style gran` or `fix wall/gran`, with its settings.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct GranModel {
    pub(super) normal: String,
    pub(super) tangential: String,
    pub(super) cohesion: String,
    pub(super) rolling: String,
    pub(super) surface: String,
    /// The words of the model specification (`model hertz tangential history …`).
    pub(super) spec: Vec<String>,
    /// `key value` settings after the wall or pair arguments.
    pub(super) settings: Vec<(String, String)>,
}

impl GranModel {
    pub(super) fn setting(&self, key: &str) -> Option<&str> {
        self.settings
            .iter()
            .rev()
            .find(|(k, _)| k == key)
            .map(|(_, v)| v.as_str())
    }

    pub(super) fn on(&self, key: &str) -> bool {
        self.setting(key) == Some("on")
    }

    /// The trap of the tangential and rolling models, which act on no head-on impact.
    pub(super) fn idle_trap(&self) -> Option<String> {
        (self.tangential != "no_history" || self.rolling != "off").then(|| format!(
            "tangential {} and rolling_friction {} act on no head-on impact: kept, and they change nothing here",
            self.tangential, self.rolling
        ))
    }
}

/// A wall fix as read.
#[derive(Clone, Debug)]
pub(super) struct WallFix {
    pub(super) id: String,
    pub(super) group: String,
    pub(super) model: GranModel,
    pub(super) wall_type: u32,
    pub(super) at: SourceLine,
    /// What of the wall's definition the plane leaves out.
    pub(super) geometry: String,
    /// The mesh/surface fixes it meets (none for a primitive wall).
    pub(super) meshes: Vec<String>,
}

/// The model keywords of LIGGGHTS's model selector, in the order it reads them.
pub(super) const MODEL_KEYWORDS: [&str; 5] = [
    "model",
    "tangential",
    "cohesion",
    "rolling_friction",
    "surface",
];

/// Read `model X [tangential Y] [cohesion Z] [rolling_friction R] [surface S]` from
/// `words[start..]`; returns the model and the index after it.
pub(super) fn read_model(command: &Command, start: usize) -> Result<(GranModel, usize), DeckError> {
    let mut k = start;
    let mut model = GranModel {
        normal: String::new(),
        tangential: "no_history".into(),
        cohesion: "off".into(),
        rolling: "off".into(),
        surface: "default".into(),
        spec: Vec::new(),
        settings: Vec::new(),
    };
    while let Some(key) = command
        .words
        .get(k)
        .filter(|w| MODEL_KEYWORDS.contains(&w.as_str()))
    {
        let value = command
            .word(k + 1, &format!("a value after {key}"))?
            .to_string();
        match key.as_str() {
            "model" => model.normal = value.clone(),
            "tangential" => model.tangential = value.clone(),
            "cohesion" => model.cohesion = value.clone(),
            "rolling_friction" => model.rolling = value.clone(),
            _ => model.surface = value.clone(),
        }
        model.spec.push(key.clone());
        model.spec.push(value);
        k += 2;
    }
    check_known_words(command, &model)?;
    if model.normal.is_empty() {
        return Err(command.refuse(
            format!("`{}`: no `model` keyword", command.text),
            "LIGGGHTS 3.x granular lines: `model M [tangential T] [cohesion C] [rolling_friction R] [surface S]`",
        ));
    }
    let supported = ["hertz", "hooke", "hertz/stiffness", "hooke/stiffness"];
    if !supported.contains(&model.normal.as_str()) && !PAPER_MODELS.contains(&model.normal.as_str())
    {
        return Err(command.refuse(format!("normal model `{}`", model.normal), NORMAL_MODELS));
    }
    if model.cohesion != "off" {
        return Err(command.refuse(
            format!(
                "cohesion {}: it adds a normal force the impact check does not model",
                model.cohesion
            ),
            "cohesion off",
        ));
    }
    if model.surface != "default" {
        return Err(command.refuse(
            format!("surface {}", model.surface),
            "surface default (spheres)",
        ));
    }
    Ok((model, k))
}

/// The words LIGGGHTS 3.8 knows after each model keyword (its `style_*_model.h` tables, with
/// the `off`/`default` it takes for none), and the paper's models of liggghts-paper.
const KNOWN_MODELS: [(&str, &[&str]); 5] = [
    (
        "model",
        &[
            "hooke",
            "hooke/stiffness",
            "hooke/hysteresis",
            "hertz",
            "hertz/stiffness",
            "thornton_ning",
            "edinburgh",
            "edinburgh/stiffness",
            "luding",
            "paper",
            "paper/linear",
        ],
    ),
    ("tangential", &["no_history", "history", "tan_luding"]),
    (
        "cohesion",
        &[
            "off",
            "sjkr",
            "sjkr2",
            "easo/capillary/viscous",
            "washino/capillary/viscous",
        ],
    ),
    (
        "rolling_friction",
        &["off", "cdt", "epsd", "epsd2", "epsd3", "luding"],
    ),
    ("surface", &["default", "multicontact", "superquadric"]),
];

/// The on/off and number settings LIGGGHTS 3.8's contact models register (a word none of them
/// knows stops it: "Unknown argument or wrong keyword order").
const KNOWN_SETTINGS: [&str; 20] = [
    "absolute_damping",
    "computeDissipatedEnergy",
    "computeElasticPotential",
    "disableNormalWhenBonded",
    "disableTangentialWhenBonded",
    "fixKc",
    "heating_normal_hertz",
    "heating_normal_hooke",
    "heating_tangential_history",
    "heating_tracking",
    "ktToKnUser",
    "limitForce",
    "limitLiquidContent",
    "modifyLbVolume",
    "tangential_damping",
    "tangential_reduce",
    "torsion",
    "torsionTorque",
    "viscous",
    "curvatureLimitFactor",
];

/// A model word LIGGGHTS does not know (a typo: `tangential histroy`) is refused with the
/// line and the words it accepts there, as LIGGGHTS stops at it.
fn check_known_words(command: &Command, model: &GranModel) -> Result<(), DeckError> {
    for pair in model.spec.chunks(2) {
        let [key, value] = pair else { continue };
        let Some((_, known)) = KNOWN_MODELS.iter().find(|(k, _)| k == key) else {
            continue;
        };
        if !known.contains(&value.as_str()) {
            return Err(command.refuse(
                format!("{key} `{value}`: LIGGGHTS 3.8 has no such model and stops at this line"),
                &format!("{key} {}", known.join(", ")),
            ));
        }
    }
    Ok(())
}

/// Read `key value` settings from `words[start..]` into `model`.
pub(super) fn read_settings(
    command: &Command,
    start: usize,
    model: &mut GranModel,
) -> Result<(), DeckError> {
    // A keyword's arguments cut short at the line's end leave `start` past it: no settings.
    let words = command.words.get(start..).unwrap_or_default();
    if PAPER_MODELS.contains(&model.normal.as_str())
        && let Some(key) = words.first()
    {
        return Err(command.refuse(
            format!(
                "`{key}` after model {}: the paper's styles take no settings (liggghts-paper stops: \"Unknown argument or wrong keyword order\")",
                model.normal
            ),
            "model paper or paper/linear without limitForce, tangential_damping or other settings (the force never attracts)",
        ));
    }
    if !words.len().is_multiple_of(2) {
        return Err(command.refuse(
            format!("`{}`: a setting without its value", command.text),
            "settings as `key on|off` pairs (limitForce on, tangential_damping off, …)",
        ));
    }
    for pair in words.chunks(2) {
        let (key, value) = (&pair[0], &pair[1]);
        if !KNOWN_SETTINGS.contains(&key.as_str()) {
            let model_words = KNOWN_MODELS.map(|(k, _)| k).join(", ");
            return Err(command.refuse(
                format!(
                    "`{key} {value}`: LIGGGHTS 3.8 knows no such model keyword or setting and stops at this line (\"Unknown argument or wrong keyword order\")"
                ),
                &format!(
                    "the model keywords {model_words} (in that order), then settings {}",
                    KNOWN_SETTINGS.join(", ")
                ),
            ));
        }
        let switch = value == "on";
        match key.as_str() {
            "viscous" | "disableNormalWhenBonded" if switch => {
                return Err(command.refuse(
                    format!("{key} on: a normal force the impact check does not model"),
                    &format!("{key} off"),
                ));
            }
            _ => model.settings.push((key.clone(), value.clone())),
        }
    }
    Ok(())
}

/// Read `fix ID group wall/gran …`.
pub(super) fn read_wall(
    command: &Command,
    meshes: &HashMap<String, (u32, SourceLine)>,
) -> Result<WallFix, DeckError> {
    let (mut model, mut k) = read_model(command, 4)?;
    let mut wall_type = None;
    let mut geometry = String::new();
    let mut mesh_names: Vec<String> = Vec::new();
    while let Some(word) = command.words.get(k) {
        match word.as_str() {
            "primitive" => {
                if command.word(k + 1, "`type` after primitive")? != "type" {
                    return Err(
                        command.refuse("primitive without `type`", "primitive type T STYLE ARGS")
                    );
                }
                let t = command.number(k + 2, "the wall's type")?;
                wall_type = Some(type_number(t, command)?);
                let style = command.word(k + 3, "the primitive's style")?;
                let args = match style {
                    "xplane" | "yplane" | "zplane" => 1,
                    "xcylinder" | "ycylinder" | "zcylinder" => 3,
                    other => {
                        return Err(command.refuse(
                            format!("primitive {other}"),
                            "primitive xplane, yplane, zplane, xcylinder, ycylinder, zcylinder",
                        ));
                    }
                };
                geometry = format!("primitive {style}");
                k += 4 + args;
            }
            "mesh" => k += 1,
            "n_meshes" => k += 2,
            "meshes" => {
                let n = command.words[k + 1..]
                    .iter()
                    .take_while(|w| meshes.contains_key(w.as_str()))
                    .count();
                if n == 0 {
                    return Err(command.refuse(
                        format!(
                            "`meshes` names no mesh/surface fix defined before: `{}`",
                            command.text
                        ),
                        "meshes ID… of fix mesh/surface lines above",
                    ));
                }
                mesh_names.extend(command.words[k + 1..k + 1 + n].iter().cloned());
                k += 1 + n;
            }
            "store_force"
            | "store_force_contact"
            | "store_force_contact_every"
            | "allow_special_domain_periodic"
            | "store_force_contact_stress"
            | "temperature"
            | "track_energy" => k += if word == "track_energy" { 1 } else { 2 },
            "shear" => {
                geometry.push_str(" (its shear motion)");
                k += 3;
            }
            "contact_area" => {
                k += if command.words.get(k + 1).is_some_and(|w| w == "constant") {
                    3
                } else {
                    2
                }
            }
            _ => break,
        }
    }
    read_settings(command, k, &mut model)?;
    if !mesh_names.is_empty() {
        let types: Vec<u32> = mesh_names.iter().map(|m| meshes[m].0).collect();
        if types.iter().any(|t| *t != types[0]) {
            return Err(command.refuse(
                format!(
                    "the meshes {} have different types {types:?}",
                    mesh_names.join(", ")
                ),
                "one wall/gran fix per wall material (meshes of one type)",
            ));
        }
        wall_type = Some(types[0]);
        geometry = format!("mesh {}", mesh_names.join(", "));
    }
    let wall_type = wall_type.ok_or_else(|| {
        command.refuse(
            format!("`{}`: no primitive or mesh wall", command.text),
            "primitive type T STYLE ARGS, or mesh n_meshes N meshes ID…",
        )
    })?;
    Ok(WallFix {
        id: command.words[1].clone(),
        group: command.words[2].clone(),
        model,
        wall_type,
        at: command.at.clone(),
        geometry,
        meshes: mesh_names,
    })
}

/// An atom type as LIGGGHTS takes it: a whole number from 1.
pub(super) fn type_number(t: f64, command: &Command) -> Result<u32, DeckError> {
    whole_number(t, &command.at, "type", "a whole atom type from 1")
}
