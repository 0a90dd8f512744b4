//! YADE's objects as the deck reader takes them from the dump (`super::dump`): the materials of
//! `O.materials`, the `InteractionLoop`'s functors (a `MatchMaker` evaluated per pair of
//! materials), the kinds of wall, the engines and functors the check knows, where in the script
//! each was made, and each object written back as Python for an impact's script.

use std::collections::BTreeMap;
use std::path::Path;

use super::dump::{Attribute, FunctorDump, MaterialDump, line_text};
use crate::codes::deck::{DeckError, DeckSource, SourceLine};
use crate::codes::template::exact_number;

/// The functors whose laws the check knows.
pub(super) const FUNCTORS: &str = "Ig2_Sphere_Sphere_ScGeom(6D), Ig2_Wall_Sphere_ScGeom, Ig2_Facet_Sphere_ScGeom(6D), Ig2_Box_Sphere_ScGeom(6D); Ip2_FrictMat_FrictMat_MindlinPhys with Law2_ScGeom_MindlinPhys_Mindlin, Ip2_FrictMat_FrictMat_FrictPhys with Law2_ScGeom_FrictPhys_CundallStrack, Ip2_ViscElMat_ViscElMat_ViscElPhys with Law2_ScGeom_ViscElPhys_Basic";

/// A material class the check knows.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Class {
    Frict,
    ViscEl,
}

impl Class {
    /// The class's name in YADE.
    pub(super) fn name(self) -> &'static str {
        match self {
            Class::Frict => "FrictMat",
            Class::ViscEl => "ViscElMat",
        }
    }
}

/// A Python literal of a value YADE holds, to carry it into the impact's script; `None` for an
/// object the impact cannot rebuild.
fn python(value: &Attribute) -> Option<String> {
    Some(match value {
        Attribute::Null => "None".into(),
        Attribute::Flag(b) => if *b { "True" } else { "False" }.into(),
        Attribute::Number(x) => exact_number(*x),
        Attribute::Text(t) => format!("{t:?}"),
        Attribute::List(items) => {
            let items: Option<Vec<String>> = items.iter().map(python).collect();
            let items = items?;
            if items.len() == 3 {
                format!("Vector3({})", items.join(", "))
            } else {
                format!("[{}]", items.join(", "))
            }
        }
        Attribute::MatchMaker { match_maker: m } => {
            let mut matches = Vec::new();
            for triple in &m.matches {
                let [Some(a), Some(b), Some(x)] = triple.as_slice() else {
                    return None;
                };
                // The ids are whole numbers YADE keeps as floats: written as ids.
                matches.push(format!("({a}, {b}, {})", exact_number(*x)));
            }
            let val = m
                .val
                .map_or(String::new(), |v| format!(", val={}", exact_number(v)));
            format!(
                "MatchMaker(matches=[{}], algo={:?}{val})",
                matches.join(", "),
                m.algo
            )
        }
        Attribute::Object { .. } => return None,
    })
}

/// A material of `O.materials`, as YADE holds it after the set-up.
#[derive(Clone, Debug)]
pub(super) struct Material {
    pub(super) class: Class,
    values: BTreeMap<String, Attribute>,
    /// What the script set (the attributes that differ from a fresh instance's).
    changed: Vec<String>,
    /// Attributes that differ from their values when the material was appended: the name, the
    /// value then and after the set-up.
    edited: Vec<(String, String, String)>,
    pub(super) at: DeckSource,
}

impl Material {
    /// The material `m` of the dump of the script at `path`; a class the check does not know
    /// is refused.
    pub(super) fn from_dump(path: &Path, m: &MaterialDump) -> Result<Self, DeckError> {
        let at = source(path, m.line, || format!("O.materials[{}]", m.id));
        let class = class_of(&m.class).ok_or_else(|| {
            at.refuse(
                format!("material class `{}` (O.materials[{}])", m.class, m.id),
                "FrictMat, ViscElMat",
            )
        })?;
        let shown = |a: Option<&Attribute>| {
            a.and_then(python)
                .unwrap_or_else(|| "(not set)".to_string())
        };
        let edited = m
            .appended
            .as_ref()
            .map(|then| {
                m.attributes
                    .iter()
                    .filter(|(k, now)| then.get(*k) != Some(*now))
                    .map(|(k, now)| (k.clone(), shown(then.get(k)), shown(Some(now))))
                    .collect()
            })
            .unwrap_or_default();
        Ok(Material {
            class,
            values: m.attributes.clone(),
            changed: m.changed.clone(),
            edited,
            at,
        })
    }

    /// A finite number the material holds under `key`.
    pub(super) fn get(&self, key: &str) -> Option<f64> {
        self.values
            .get(key)
            .and_then(Attribute::number)
            .filter(|x| x.is_finite())
    }

    /// A value as YADE holds it (NaN where it is "not given").
    pub(super) fn value(&self, key: &str) -> f64 {
        self.get(key).unwrap_or(f64::NAN)
    }

    /// Its Young's modulus and Poisson's ratio, or neither for a ViscElMat whose kn, cn or tc, en
    /// form uses no modulus.
    pub(super) fn moduli(&self) -> (Option<f64>, Option<f64>) {
        match self.class {
            Class::ViscEl if self.get("kn").is_some() || self.get("tc").is_some() => (None, None),
            _ => (Some(self.value("young")), Some(self.value("poisson"))),
        }
    }

    /// The material's label, where the script gave one.
    pub(super) fn label(&self) -> Option<String> {
        match self.values.get("label") {
            Some(Attribute::Text(s)) if !s.is_empty() => Some(s.clone()),
            _ => None,
        }
    }

    /// The material as the script set it (its attributes that differ from a fresh instance's);
    /// an object the impact cannot rebuild is refused.
    pub(super) fn python(&self) -> Result<String, DeckError> {
        let mut args = Vec::new();
        for key in self.changed.iter().filter(|k| *k != "id") {
            // A dump that names a set attribute without its value was not written by the
            // reading script (it writes both from one object): refused, not indexed blindly.
            let Some(value) = self.values.get(key) else {
                return Err(self.at.refuse(
                    format!(
                        "{}'s {key}: set in the dump but given no value",
                        self.class.name()
                    ),
                    "a dump as YADE's reading script writes it (every attribute it sets has a value)",
                ));
            };
            let literal = python(value).ok_or_else(|| {
                self.at.refuse(
                    format!(
                        "{}'s {key}: an object the impact cannot carry",
                        self.class.name()
                    ),
                    "numbers, flags and strings",
                )
            })?;
            args.push(format!("{key}={literal}"));
        }
        Ok(format!("{}({})", self.class.name(), args.join(", ")))
    }
}

/// A functor of the `InteractionLoop`, as YADE holds it.
#[derive(Clone, Debug)]
pub(super) struct Functor {
    pub(super) class: String,
    pub(super) dump: FunctorDump,
    pub(super) at: DeckSource,
}

impl Functor {
    /// A parameter that holds a value (not `None`, not NaN).
    pub(super) fn param(&self, key: &str) -> Option<&Attribute> {
        self.dump
            .attributes
            .get(key)
            .filter(|a| !matches!(a, Attribute::Null))
    }

    /// A parameter's number.
    pub(super) fn number(&self, key: &str) -> Option<f64> {
        self.param(key).and_then(Attribute::number)
    }

    /// Whether a flag parameter is set.
    pub(super) fn flag(&self, key: &str) -> bool {
        matches!(self.param(key), Some(Attribute::Flag(true)))
    }

    /// Whether YADE can form a contact of the materials `a`, `b` with this functor: each of
    /// its `MatchMaker`s gives a number for them (YADE stops at a contact one cannot
    /// evaluate, so a script that runs never lets such a pair meet).
    pub(super) fn evaluates(&self, a: u32, b: u32) -> bool {
        self.dump.attributes.iter().all(|(key, attribute)| {
            !matches!(attribute, Attribute::MatchMaker { .. })
                || self.dump.per_pair.get(key).is_none_or(|table| {
                    table
                        .iter()
                        .any(|(i, j, x)| *i == i64::from(a) && *j == i64::from(b) && x.is_some())
                })
        })
    }

    /// The parameter's value for the materials `a`, `b` (a `MatchMaker` as YADE evaluates it
    /// for their ids), or `None` where it is not given.
    pub(super) fn pair_value(&self, key: &str, a: u32, b: u32) -> Result<Option<f64>, DeckError> {
        match self.param(key) {
            None => Ok(None),
            Some(Attribute::Number(x)) => Ok(Some(*x)),
            Some(Attribute::MatchMaker { match_maker }) => {
                let value = self.dump.per_pair.get(key).and_then(|table| {
                    table
                        .iter()
                        .find(|(i, j, _)| *i == i64::from(a) && *j == i64::from(b))
                        .and_then(|(_, _, x)| *x)
                });
                value.map(Some).ok_or_else(|| {
                    self.at.refuse(
                        format!(
                            "{}'s {key}: its MatchMaker gives YADE no number for the materials {a} and {b} (no match, algo '{}')",
                            self.class, match_maker.algo
                        ),
                        "a match for every pair in use, or algo='val' with val=X",
                    )
                })
            }
            Some(other) => Err(self.at.refuse(
                format!(
                    "{}'s {key} = {}",
                    self.class,
                    python(other).unwrap_or_else(|| "an object".into())
                ),
                "a number or a MatchMaker",
            )),
        }
    }

    /// The functor as the script set it (its attributes that differ from a fresh instance's).
    pub(super) fn python(&self) -> Result<String, DeckError> {
        let mut args = Vec::new();
        for key in &self.dump.changed {
            let Some(value) = self.dump.attributes.get(key) else {
                return Err(self.at.refuse(
                    format!("{}'s {key}: set in the dump but given no value", self.class),
                    "a dump as YADE's reading script writes it (every attribute it sets has a value)",
                ));
            };
            if matches!(value, Attribute::Null) {
                continue;
            }
            let literal = python(value).ok_or_else(|| {
                self.at.refuse(
                    format!("{}'s {key}: an object the impact cannot carry", self.class),
                    "numbers, flags, MatchMakers",
                )
            })?;
            args.push(format!("{key}={literal}"));
        }
        Ok(format!("{}({})", self.class, args.join(", ")))
    }
}

/// What a wall is in YADE, which decides the radius its geometry functor gives it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub(super) enum WallKind {
    /// A `Wall` (`utils.wall`): `Ig2_Wall_Sphere_ScGeom`.
    Plane,
    /// A `Facet` (`facet`, the `geom.facet…` shapes, `ymport` meshes): `Ig2_Facet_Sphere_ScGeom`.
    Facet,
    /// A fixed `Box` (`utils.box`): `Ig2_Box_Sphere_ScGeom`.
    Box,
    /// A sphere YADE does not move (`fixed=True`, or every translation in `blockedDOFs`):
    /// `Ig2_Sphere_Sphere_ScGeom` with its own radius, so `R*` is of both radii.
    Sphere,
}

impl WallKind {
    /// The geometry functors that take a sphere against this kind (ScGeom, ScGeom6D).
    pub(super) fn geometry(self) -> [&'static str; 2] {
        match self {
            WallKind::Plane => ["Ig2_Wall_Sphere_ScGeom", "Ig2_Wall_Sphere_ScGeom"],
            WallKind::Facet => ["Ig2_Facet_Sphere_ScGeom", "Ig2_Facet_Sphere_ScGeom6D"],
            WallKind::Box => ["Ig2_Box_Sphere_ScGeom", "Ig2_Box_Sphere_ScGeom6D"],
            WallKind::Sphere => ["Ig2_Sphere_Sphere_ScGeom", "Ig2_Sphere_Sphere_ScGeom6D"],
        }
    }

    /// The kind of a body of YADE's `shape`; `None` for a shape that is no wall.
    pub(super) fn of_shape(shape: &str) -> Option<Self> {
        match shape {
            "Wall" => Some(WallKind::Plane),
            "Facet" => Some(WallKind::Facet),
            "Box" => Some(WallKind::Box),
            _ => None,
        }
    }
}

/// The functors of one of the InteractionLoop's lists (`list`, at `what` in `O.engines`), each
/// with its line; one the check does not know is refused.
pub(super) fn known_functors(
    path: &Path,
    text: &str,
    engine_line: Option<usize>,
    list: &[FunctorDump],
    what: &str,
) -> Result<Vec<Functor>, DeckError> {
    list.iter()
        .enumerate()
        .map(|(i, f)| {
            let here = source(path, line_of(text, engine_line, &f.class), || {
                format!("{what}[{i}]")
            });
            if !KNOWN_FUNCTORS.contains(&f.class.as_str()) {
                return Err(here.refuse(format!("functor {}", f.class), FUNCTORS));
            }
            Ok(Functor {
                class: f.class.clone(),
                dump: f.clone(),
                at: here,
            })
        })
        .collect()
}

/// The class the check knows of YADE's class `name`.
fn class_of(name: &str) -> Option<Class> {
    match name {
        "FrictMat" => Some(Class::Frict),
        "ViscElMat" => Some(Class::ViscEl),
        _ => None,
    }
}

/// The name of the call on a wall's line that made it (`facetCylinder`, `wall`, `stl`), else
/// its shape's.
pub(super) fn wall_name(path: &Path, line: Option<usize>, kind: WallKind) -> String {
    let fallback = match kind {
        WallKind::Plane => "wall",
        WallKind::Facet => "facet",
        WallKind::Box => "box",
        WallKind::Sphere => "sphere",
    };
    let called = line.and_then(|l| line_text(path, l)).and_then(|text| {
        text.split(|c: char| !(c.is_alphanumeric() || c == '_'))
            .find(|word| {
                text.contains(&format!("{word}("))
                    && (word.starts_with("facet")
                        || matches!(
                            *word,
                            "wall" | "box" | "stl" | "gmsh" | "gts" | "unv" | "sphere"
                        ))
            })
            .map(str::to_string)
    });
    format!(
        "{}:{}",
        called.as_deref().unwrap_or(fallback),
        line.map_or("?".into(), |l| l.to_string())
    )
}

/// Engines whose settings the impact replaces with its own.
pub(super) fn engine_left_out(name: &str) -> &'static str {
    match name {
        "ForceResetter"
        | "InsertionSortCollider"
        | "SpatialQuickSortCollider"
        | "PersistentTriangulationCollider" => {
            "the force reset and the collider (the impact sets its own)"
        }
        "GravityEngine" | "CentralGravityEngine" | "AxialGravityEngine" => {
            "gravity (the impact is a free normal impact)"
        }
        "PyRunner"
        | "VTKRecorder"
        | "SnapshotEngine"
        | "TorqueRecorder"
        | "ForceRecorder"
        | "PositionRecorder"
        | "TriaxialStateRecorder" => "output and control",
        _ => "wall and particle motion and other engines (no part of a contact)",
    }
}

/// The functors the check knows.
const KNOWN_FUNCTORS: [&str; 13] = [
    "Ig2_Sphere_Sphere_ScGeom",
    "Ig2_Sphere_Sphere_ScGeom6D",
    "Ig2_Wall_Sphere_ScGeom",
    "Ig2_Facet_Sphere_ScGeom",
    "Ig2_Facet_Sphere_ScGeom6D",
    "Ig2_Box_Sphere_ScGeom",
    "Ig2_Box_Sphere_ScGeom6D",
    "Ip2_FrictMat_FrictMat_MindlinPhys",
    "Ip2_FrictMat_FrictMat_FrictPhys",
    "Ip2_ViscElMat_ViscElMat_ViscElPhys",
    "Law2_ScGeom_MindlinPhys_Mindlin",
    "Law2_ScGeom_FrictPhys_CundallStrack",
    "Law2_ScGeom_ViscElPhys_Basic",
];

/// The first line from `from` on (from 1) of the script `text` that calls `class` (`class(`):
/// where an engine or functor set on the `O.engines` line of `from` is written; `from` itself
/// where none is.
pub(super) fn line_of(text: &str, from: Option<usize>, class: &str) -> Option<usize> {
    let from = from?;
    let call = format!("{class}(");
    let found = text
        .lines()
        .enumerate()
        .skip(from.saturating_sub(1))
        .find(|(_, line)| {
            line.match_indices(&call).any(|(at, _)| {
                !line[..at]
                    .chars()
                    .next_back()
                    .is_some_and(|c| c.is_alphanumeric() || c == '_')
            })
        })
        .map(|(i, _)| i + 1);
    Some(found.unwrap_or(from))
}

/// A line of the script, or a field of what YADE holds where no line made it.
pub(super) fn source(
    path: &Path,
    line: Option<usize>,
    field: impl FnOnce() -> String,
) -> DeckSource {
    match line {
        Some(line) => DeckSource::Line(SourceLine {
            file: path.to_path_buf(),
            line,
        }),
        None => DeckSource::field(path, field()),
    }
}

/// A trap line for each attribute of `m` the script changed after appending it.
pub(super) fn edit_traps(m: &Material) -> Vec<String> {
    m.edited
        .iter()
        .map(|(key, then, now)| {
            format!(
                "{key} of {} ({}) was {then} when appended and is {now} after the set-up: the check takes {now}, as YADE does",
                m.label().unwrap_or_else(|| m.class.name().to_string()),
                m.at
            )
        })
        .collect()
}
