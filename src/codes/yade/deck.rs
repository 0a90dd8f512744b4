//! A YADE user's script (`millimpact deck`), read as YADE holds it after the script's set-up
//! (`super::dump`: the script run by YADE's own Python with its stepping disarmed, then
//! dumped): the materials of `O.materials` with every attribute after any later edit, the
//! `InteractionLoop`'s functors with each `MatchMaker` evaluated per pair of materials,
//! `O.dt`, and the bodies: spheres with their radii, materials and masses; walls, facets and
//! fixed boxes with their materials. Then the impact of one pair rendered with those materials
//! and functors transplanted.
//!
//! What the check cannot take from what YADE holds (a material class, a functor or a law it
//! does not model, a free box) is refused in one line; what it leaves out (other body shapes,
//! clumps, gravity, motion engines, the run) is listed, each with its lines.
//!
//! The law each functor makes YADE 2023.02a integrate follows its sources
//! (`pkg/dem/HertzMindlin.cpp`, `pkg/dem/ViscoelasticPM.cpp`, `pkg/dem/ElasticContactLaw.cpp`)
//! and the radii its geometry functors give a wall, as measured and listed in
//! `reference/yade/CONVENTIONS.md`; the live test checks every pair of the example against it.

use std::collections::BTreeMap;
use std::f64::consts::PI;
use std::path::Path;

use super::dump::{
    Attribute, BodyDump, Dump, EngineDump, FunctorDump, MaterialDump, READ_TIME_LIMIT, dump_script,
    line_text, parse_dump,
};
use super::{HERTZIAN_WALL_RADIUS_FACTOR, TRAJECTORY_FILE, thornton_damping_ratio};
use crate::codes::damping::hertz_input_restitution;
use crate::codes::deck::{
    DeckBody, DeckContact, DeckDialect, DeckError, DeckImpactInput, DeckOptions, DeckSource,
    DeckWall, ImpactPlan, PairLaw, Partner, SourceLine, Transplant, TypeRef, UserDeck, WallOrder,
};
use crate::codes::template::{exact_number, fill_template};
use crate::codes::{CodeError, RenderedInput};
use crate::model::law::DashpotLaw;
use crate::model::scene::{pair_radius, reduced_mass};
use crate::solve::dashpot::accurate_metrics;

const TEMPLATE: &str = include_str!("deck.py");
const SCRIPT: &str = "impact.py";

/// The functors whose laws the check knows.
const FUNCTORS: &str = "Ig2_Sphere_Sphere_ScGeom(6D), Ig2_Wall_Sphere_ScGeom, Ig2_Facet_Sphere_ScGeom(6D), Ig2_Box_Sphere_ScGeom(6D); Ip2_FrictMat_FrictMat_MindlinPhys with Law2_ScGeom_MindlinPhys_Mindlin, Ip2_FrictMat_FrictMat_FrictPhys with Law2_ScGeom_FrictPhys_CundallStrack, Ip2_ViscElMat_ViscElMat_ViscElPhys with Law2_ScGeom_ViscElPhys_Basic";

/// YADE's deck reader.
pub struct YadeDeck;

/// A material class the check knows.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Class {
    Frict,
    ViscEl,
}

impl Class {
    fn name(self) -> &'static str {
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
struct Material {
    class: Class,
    values: BTreeMap<String, Attribute>,
    /// What the script set (the attributes that differ from a fresh instance's).
    changed: Vec<String>,
    /// Attributes that differ from their values when the material was appended: the name, the
    /// value then and after the set-up.
    edited: Vec<(String, String, String)>,
    at: DeckSource,
}

impl Material {
    fn get(&self, key: &str) -> Option<f64> {
        self.values
            .get(key)
            .and_then(Attribute::number)
            .filter(|x| x.is_finite())
    }

    /// A value as YADE holds it (NaN where it is "not given").
    fn value(&self, key: &str) -> f64 {
        self.get(key).unwrap_or(f64::NAN)
    }

    fn label(&self) -> Option<String> {
        match self.values.get("label") {
            Some(Attribute::Text(s)) if !s.is_empty() => Some(s.clone()),
            _ => None,
        }
    }

    fn python(&self) -> Result<String, DeckError> {
        let mut args = Vec::new();
        for key in self.changed.iter().filter(|k| *k != "id") {
            let value = &self.values[key];
            let literal = python(value).ok_or_else(|| {
                DeckError::unsupported(
                    self.at.clone(),
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
struct Functor {
    class: String,
    dump: FunctorDump,
    at: DeckSource,
}

impl Functor {
    /// A parameter that holds a value (not `None`, not NaN).
    fn param(&self, key: &str) -> Option<&Attribute> {
        self.dump
            .attributes
            .get(key)
            .filter(|a| !matches!(a, Attribute::Null))
    }

    fn number(&self, key: &str) -> Option<f64> {
        self.param(key).and_then(Attribute::number)
    }

    fn flag(&self, key: &str) -> bool {
        matches!(self.param(key), Some(Attribute::Flag(true)))
    }

    /// The parameter's value for the materials `a`, `b` (a `MatchMaker` as YADE evaluates it
    /// for their ids), or `None` where it is not given.
    fn pair_value(&self, key: &str, a: u32, b: u32) -> Result<Option<f64>, DeckError> {
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
                    DeckError::unsupported(
                        self.at.clone(),
                        format!(
                            "{}'s {key}: its MatchMaker gives YADE no number for the materials {a} and {b} (no match, algo '{}')",
                            self.class, match_maker.algo
                        ),
                        "a match for every pair in use, or algo='val' with val=X",
                    )
                })
            }
            Some(other) => Err(DeckError::unsupported(
                self.at.clone(),
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
    fn python(&self) -> Result<String, DeckError> {
        let mut args = Vec::new();
        for key in &self.dump.changed {
            let value = &self.dump.attributes[key];
            if matches!(value, Attribute::Null) {
                continue;
            }
            let literal = python(value).ok_or_else(|| {
                DeckError::unsupported(
                    self.at.clone(),
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
enum WallKind {
    /// A `Wall` (`utils.wall`): `Ig2_Wall_Sphere_ScGeom`.
    Plane,
    /// A `Facet` (`facet`, the `geom.facet…` shapes, `ymport` meshes): `Ig2_Facet_Sphere_ScGeom`.
    Facet,
    /// A fixed `Box` (`utils.box`): `Ig2_Box_Sphere_ScGeom`.
    Box,
}

impl WallKind {
    fn geometry(self) -> [&'static str; 2] {
        match self {
            WallKind::Plane => ["Ig2_Wall_Sphere_ScGeom", "Ig2_Wall_Sphere_ScGeom"],
            WallKind::Facet => ["Ig2_Facet_Sphere_ScGeom", "Ig2_Facet_Sphere_ScGeom6D"],
            WallKind::Box => ["Ig2_Box_Sphere_ScGeom", "Ig2_Box_Sphere_ScGeom6D"],
        }
    }

    fn of_shape(shape: &str) -> Option<Self> {
        match shape {
            "Wall" => Some(WallKind::Plane),
            "Facet" => Some(WallKind::Facet),
            "Box" => Some(WallKind::Box),
            _ => None,
        }
    }
}

/// Walls of one kind, material and mass: one wall to the check.
#[derive(Clone, Debug)]
struct WallRead {
    name: String,
    kind: WallKind,
    material: u32,
    /// Its mass as YADE holds it, kg (a fixed box's volume times its density; 0 for walls and
    /// facets).
    mass: f64,
    at: DeckSource,
    lines: Vec<usize>,
}

/// A sphere as YADE holds it.
#[derive(Clone, Debug)]
struct SphereRead {
    material: u32,
    radius: f64,
    mass: f64,
    at: DeckSource,
}

/// Everything taken from the dump.
#[derive(Default)]
struct Reading {
    materials: Vec<Material>,
    spheres: Vec<SphereRead>,
    walls: Vec<WallRead>,
    geometry: Vec<Functor>,
    physics: Vec<Functor>,
    laws: Vec<Functor>,
    loop_at: Option<DeckSource>,
    left_out: BTreeMap<String, Vec<usize>>,
}

impl Reading {
    fn leave_out(&mut self, what: &str, line: Option<usize>) {
        let lines = self.left_out.entry(what.to_string()).or_default();
        if let Some(line) = line.filter(|l| !lines.contains(l)) {
            lines.push(line);
        }
    }

    /// Take the InteractionLoop's functors from the engines, refuse what changes the contact
    /// law or the step (local damping, a time stepper), and leave out the rest with its line.
    fn take_engines(&mut self, path: &Path, dump: &Dump) -> Result<(), DeckError> {
        let engines_at = dump.engines_line;
        let text = std::fs::read_to_string(path).unwrap_or_default();
        let newton = dump.engines.iter().any(|e| e.class == "NewtonIntegrator");
        for (k, engine) in dump.engines.iter().enumerate() {
            let engine_line = line_of(&text, engines_at, &engine.class);
            let at = source(path, engine_line, || format!("O.engines[{k}]"));
            if let Some(functors) = &engine.functors {
                if let Some(first) = &self.loop_at {
                    return Err(DeckError::unsupported(
                        at,
                        format!("a second InteractionLoop (O.engines[{k}]; the first: {first})"),
                        "one InteractionLoop",
                    ));
                }
                let take = |list: &[FunctorDump], what: &str| {
                    known_functors(
                        path,
                        &text,
                        engine_line,
                        list,
                        &format!("O.engines[{k}].{what}"),
                    )
                };
                self.geometry = take(&functors.geometry, "geomDispatcher.functors")?;
                self.physics = take(&functors.physics, "physDispatcher.functors")?;
                self.laws = take(&functors.laws, "lawDispatcher.functors")?;
                self.loop_at = Some(at);
            } else if engine.class == "NewtonIntegrator" {
                self.take_newton(engine, at, engine_line)?;
            } else if engine.class.ends_with("TimeStepper") {
                return Err(DeckError::unsupported(
                    at,
                    format!(
                        "{}: the time step is set while the script runs",
                        engine.class
                    ),
                    "a fixed O.dt, without a time stepper in O.engines",
                ));
            } else {
                self.leave_out(engine_left_out(&engine.class), engine_line);
            }
        }
        if self.loop_at.is_some() && !newton {
            return Err(DeckError::Lacking {
                file: path.to_path_buf(),
                what: "no NewtonIntegrator in O.engines: nothing moves".into(),
                supported: "NewtonIntegrator(damping=0)".into(),
            });
        }
        Ok(())
    }

    /// Refuse a NewtonIntegrator with local damping; leave its gravity out.
    fn take_newton(
        &mut self,
        engine: &EngineDump,
        at: DeckSource,
        engine_line: Option<usize>,
    ) -> Result<(), DeckError> {
        let damping = engine
            .attributes
            .get("damping")
            .and_then(Attribute::number)
            .unwrap_or(0.0);
        if damping != 0.0 {
            let e = ((1.0 - damping) / (1.0 + damping)).sqrt();
            return Err(DeckError::unsupported(
                at,
                format!(
                    "NewtonIntegrator damping = {damping}{}: YADE's local damping scales every body's force by 1 ∓ {damping} against its own velocity, on top of the contact law (alone it makes a Hertz impact on a fixed wall rebound at {e:.4}, and between two moving balls it depends on their absolute velocities): the check models contact laws",
                    if engine.changed.iter().any(|c| c == "damping") {
                        ""
                    } else {
                        " (its default)"
                    }
                ),
                "NewtonIntegrator(damping=0) (give it to check the contacts alone)",
            ));
        }
        let gravity = match engine.attributes.get("gravity") {
            Some(Attribute::List(g)) => g.iter().any(|x| x.number() != Some(0.0)),
            _ => false,
        };
        if gravity {
            self.leave_out("gravity (the impact is a free normal impact)", engine_line);
        }
        Ok(())
    }

    /// Take one body: a sphere (unless its material's size is `given`), or a wall of one kind,
    /// material and mass; clumps and other shapes are left out with their line.
    fn take_body(&mut self, path: &Path, body: &BodyDump, given: &[u32]) -> Result<(), DeckError> {
        let at = source(path, body.line, || format!("O.bodies[{}]", body.id));
        let shape = body.shape.as_deref().unwrap_or("no shape");
        if body.clump {
            self.leave_out(
                "clumps and their members (a clump moves as one body, which one impact of two spheres does not model)",
                body.line,
            );
            return Ok(());
        }
        let kind = WallKind::of_shape(shape);
        if shape != "Sphere" && kind.is_none() {
            self.leave_out(
                &format!("bodies of shape {shape} (no contact of the check takes them)"),
                body.line,
            );
            return Ok(());
        }
        let material = body
            .material
            .and_then(|m| u32::try_from(m).ok())
            .filter(|m| (*m as usize) < self.materials.len())
            .ok_or_else(|| {
                DeckError::unsupported(
                    at.clone(),
                    format!(
                        "a {shape} whose material is not in O.materials (its id is {}; the check numbers types by their O.materials ids)",
                        body.material.map_or("none".into(), |m| m.to_string())
                    ),
                    "O.materials.append(MATERIAL) before the body, and material=its id, label or the material",
                )
            })?;
        self.leave_out(
            "the bodies' positions (the impact places its own)",
            body.line,
        );
        let mass = body.mass.unwrap_or(0.0);
        match kind {
            None => {
                if !body.dynamic {
                    self.leave_out("fixed spheres, checked as free ones", body.line);
                }
                let radius = body.radius.filter(|r| *r > 0.0).ok_or_else(|| {
                    DeckError::unsupported(
                        at.clone(),
                        format!(
                            "a sphere of radius {}",
                            body.radius.map_or("NaN".into(), |r| r.to_string())
                        ),
                        "a positive radius, m",
                    )
                })?;
                if !given.contains(&material) {
                    self.spheres.push(SphereRead {
                        material,
                        radius,
                        mass,
                        at,
                    });
                }
            }
            Some(kind) => self.take_wall(path, body, kind, material, at)?,
        }
        Ok(())
    }

    /// Take a wall body: walls of one kind, material and mass (the same number, bit for bit)
    /// are one wall; a box that moves is refused.
    fn take_wall(
        &mut self,
        path: &Path,
        body: &BodyDump,
        kind: WallKind,
        material: u32,
        at: DeckSource,
    ) -> Result<(), DeckError> {
        let mass = body.mass.unwrap_or(0.0);
        if kind == WallKind::Box && body.dynamic {
            return Err(DeckError::unsupported(
                at,
                "a free box: a box that moves is a particle the check does not model".into(),
                "box(…, fixed=True) as a wall",
            ));
        }
        let name = wall_name(path, body.line, kind);
        if !(name.starts_with("wall:") || name.starts_with("facet:") || name.starts_with("box:")) {
            self.leave_out(
                "the walls' shapes (each met as a flat face of its kind)",
                body.line,
            );
        }
        let same = self.walls.iter_mut().find(|w| {
            w.kind == kind && w.material == material && w.mass.to_bits() == mass.to_bits()
        });
        match same {
            Some(w) => {
                if let Some(line) = body.line.filter(|l| !w.lines.contains(l)) {
                    w.lines.push(line);
                }
            }
            None => self.walls.push(WallRead {
                name,
                kind,
                material,
                mass,
                at,
                lines: body.line.into_iter().collect(),
            }),
        }
        Ok(())
    }
}

/// The functors of one of the InteractionLoop's lists (`list`, at `what` in `O.engines`), each
/// with its line; one the check does not know is refused.
fn known_functors(
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
                return Err(DeckError::unsupported(
                    here,
                    format!("functor {}", f.class),
                    FUNCTORS,
                ));
            }
            Ok(Functor {
                class: f.class.clone(),
                dump: f.clone(),
                at: here,
            })
        })
        .collect()
}

fn class_of(name: &str) -> Option<Class> {
    match name {
        "FrictMat" => Some(Class::Frict),
        "ViscElMat" => Some(Class::ViscEl),
        _ => None,
    }
}

/// The name of the call on a wall's line that made it (`facetCylinder`, `wall`, `stl`), else
/// its shape's.
fn wall_name(path: &Path, line: Option<usize>, kind: WallKind) -> String {
    let fallback = match kind {
        WallKind::Plane => "wall",
        WallKind::Facet => "facet",
        WallKind::Box => "box",
    };
    let called = line.and_then(|l| line_text(path, l)).and_then(|text| {
        text.split(|c: char| !(c.is_alphanumeric() || c == '_'))
            .find(|word| {
                text.contains(&format!("{word}("))
                    && (word.starts_with("facet")
                        || matches!(*word, "wall" | "box" | "stl" | "gmsh" | "gts" | "unv"))
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
fn engine_left_out(name: &str) -> &'static str {
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
fn line_of(text: &str, from: Option<usize>, class: &str) -> Option<usize> {
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
fn source(path: &Path, line: Option<usize>, field: impl FnOnce() -> String) -> DeckSource {
    match line {
        Some(line) => DeckSource::Line(SourceLine {
            file: path.to_path_buf(),
            line,
        }),
        None => DeckSource::field(path, field()),
    }
}

impl YadeDeck {
    fn material(path: &Path, m: &MaterialDump) -> Result<Material, DeckError> {
        let at = source(path, m.line, || format!("O.materials[{}]", m.id));
        let class = class_of(&m.class).ok_or_else(|| {
            DeckError::unsupported(
                at.clone(),
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

    /// Take the materials, engines, functors and bodies from YADE's dump.
    fn gather(path: &Path, dump: &Dump, options: &DeckOptions) -> Result<Reading, DeckError> {
        let mut r = Reading::default();
        for (k, m) in dump.materials.iter().enumerate() {
            if usize::try_from(m.id).ok() != Some(k) {
                return Err(DeckError::unsupported(
                    DeckSource::field(path, format!("O.materials[{k}]")),
                    format!("a material whose id is {}", m.id),
                    "materials numbered by their place in O.materials, as O.materials.append numbers them",
                ));
            }
            r.materials.push(Self::material(path, m)?);
        }
        r.take_engines(path, dump)?;
        let given: Vec<u32> = options.particles.iter().map(|p| p.type_id).collect();
        for body in &dump.bodies {
            r.take_body(path, body, &given)?;
        }
        if let Some(stopped) = &dump.stopped {
            r.leave_out(
                &format!(
                    "the run itself (the reading stops at the first call that steps the simulation, {}; the lines after it are not read)",
                    stopped.call
                ),
                stopped.line,
            );
        }
        for line in &dump.saved {
            r.leave_out("O.save (it writes nothing while the script is read)", *line);
        }
        Ok(r)
    }

    /// The bodies: one per size of each material, the given ones replacing their type's.
    fn bodies(r: &Reading, path: &Path, options: &DeckOptions) -> Result<Vec<DeckBody>, DeckError> {
        let mut bodies: Vec<DeckBody> = Vec::new();
        let elastic = |m: &Material| match m.class {
            // The young a ViscElMat's kn/cn or tc/en form does not use is no modulus of it.
            Class::ViscEl if m.get("kn").is_some() || m.get("tc").is_some() => (None, None),
            _ => (Some(m.value("young")), Some(m.value("poisson"))),
        };
        let mut push = |t: u32, radius: f64, density: f64, mass: f64, from: String| {
            // The same size read twice is the same number, bit for bit.
            let known = bodies.iter().any(|b| {
                b.type_id == t
                    && b.radius.to_bits() == radius.to_bits()
                    && b.density.to_bits() == density.to_bits()
            });
            if !known {
                let (youngs_modulus, poisson_ratio) = elastic(&r.materials[t as usize]);
                bodies.push(DeckBody {
                    type_id: t,
                    radius,
                    density,
                    mass,
                    youngs_modulus,
                    poisson_ratio,
                    from,
                });
            }
        };
        for sp in &r.spheres {
            let m = &r.materials[sp.material as usize];
            let label = m.label().map_or(String::new(), |l| format!("{l}, "));
            push(
                sp.material,
                sp.radius,
                m.value("density"),
                sp.mass,
                format!("{label}{}", sp.at),
            );
        }
        for p in &options.particles {
            let Some(m) = r.materials.get(p.type_id as usize) else {
                return Err(DeckError::Lacking {
                    file: path.to_path_buf(),
                    what: format!(
                        "--particle {}: no material {} in O.materials ({} appended)",
                        p.type_id,
                        p.type_id,
                        r.materials.len()
                    ),
                    supported: "TYPE is the material's O.materials id, from 0".into(),
                });
            };
            let label = m.label().map_or(String::new(), |l| format!("{l}, "));
            push(
                p.type_id,
                p.radius,
                p.density,
                crate::codes::deck::sphere_mass(p.radius, p.density),
                format!("{label}--particle"),
            );
        }
        if bodies.is_empty() {
            return Err(DeckError::Lacking {
                file: path.to_path_buf(),
                what: "no sphere in O.bodies after the set-up".into(),
                supported: "give the sizes with --particle TYPE:RADIUS:DENSITY, TYPE the material's O.materials id".into(),
            });
        }
        Ok(bodies)
    }

    /// The deck YADE's dump `dump_text` (of the script at `path`) describes: what
    /// [`DeckReader::read`](crate::codes::deck::DeckReader::read) returns once YADE has run
    /// the script's set-up. The fast tests read recorded dumps with it.
    pub fn read_dump(
        path: &Path,
        dump_text: &str,
        options: &DeckOptions,
    ) -> Result<UserDeck, DeckError> {
        let dump = parse_dump(path, dump_text)?;
        Self::from_dump(path, &dump, options)
    }
}

/// The trap of a wall whose geometry functor gives it a radius `b.radius` (a multiple of the
/// ball's), not a flat face's, for a law of `model`.
fn wall_radius_trap(
    traps: &mut Vec<String>,
    model: &str,
    (kind, w): (WallKind, &WallRead),
    a: &Side,
    b: &Side,
    geometry: &Functor,
) {
    let factor = b.radius / a.radius;
    // A hertzian wall's 1e8 R is a flat face to 1e-8; tc, en or kn, cn take no radius.
    if factor >= 1e3 || matches!(model, "ViscEl tc, en" | "ViscEl kn, cn") {
        return;
    }
    let hertz = if model.starts_with("Hertz") {
        format!(
            ": a Hertz contact {:.1} % longer than on a flat face",
            100.0 * ((1.0 + factor) / factor).powf(0.2) - 100.0
        )
    } else {
        String::new()
    };
    traps.push(format!(
        "wall radius: {} gives {} ({}) the radius {factor} R, so R* = {:.4} R, not a flat face's R{hertz}{}",
        geometry.class,
        w.name,
        match kind { WallKind::Plane => "a wall", WallKind::Facet => "a facet", WallKind::Box => "a box" },
        factor / (1.0 + factor),
        if kind == WallKind::Box { "" } else { " (hertzian=True gives it 1e8 R)" }
    ));
}

/// `contactParameterCalculation` of ViscoelasticPM.cpp: two values in series, a zero one left out.
fn series(a: f64, b: f64) -> f64 {
    let inverse = (if a != 0.0 { 1.0 / a } else { 0.0 }) + (if b != 0.0 { 1.0 / b } else { 0.0 });
    if inverse != 0.0 { 1.0 / inverse } else { 0.0 }
}

/// `Ip2_ViscElMat_ViscElMat_ViscElPhys::epsilon`.
const VISCEL_EPSILON: f64 = 1e-8;

/// `get_en_from_cn` of ViscoelasticPM.cpp: the COR of the clamped linear dashpot `cn` on mass
/// `m` and stiffness `kn`, in YADE's own operations.
// The equality branch is YADE's: it steps off the two points its formulas divide by zero at.
#[allow(clippy::float_cmp)]
fn viscel_en_from_cn(cn: f64, m: f64, kn: f64) -> f64 {
    let beta = 0.5 * cn / m;
    let omega0 = (kn / m).sqrt();
    let omega = (omega0 * omega0 - beta * beta).sqrt();
    let big = (beta * beta - omega0 * omega0).sqrt();
    let root2 = 2f64.sqrt();
    if beta < omega0 / root2 {
        (-beta / omega * (PI - (2.0 * beta * omega / (omega * omega - beta * beta)).atan())).exp()
    } else if beta > omega0 / root2 && beta < omega0 {
        (-beta / omega * (-2.0 * beta * omega / (omega * omega - beta * beta)).atan()).exp()
    } else if beta > omega0 {
        (-beta / big * ((beta + big) / (beta - big)).ln()).exp()
    } else if beta == omega0 / root2 || beta == omega0 {
        viscel_en_from_cn(cn + VISCEL_EPSILON, m, kn)
    } else {
        0.0
    }
}

/// `find_cn_from_en` of ViscoelasticPM.cpp: YADE's Newton iteration for the `cn` whose clamped
/// law rebounds at `en`, stopped once within 1 % of it (at most 15 steps; then `cn = 0`, and
/// `None` here).
fn viscel_cn_from_en(en: f64, m: f64, kn: f64) -> Option<f64> {
    let eps = VISCEL_EPSILON;
    let mut cn = eps;
    let mut en_temp = viscel_en_from_cn(cn, m, kn);
    let mut i = 0;
    let mut error = 1.0 / eps;
    while error > 1.0e-2 || error.is_nan() {
        if i > 15 {
            return None;
        }
        i += 1;
        let deriv = (viscel_en_from_cn(cn - eps, m, kn) - viscel_en_from_cn(cn + eps, m, kn))
            / (-2.0 * eps);
        let deriv = if deriv.abs() > 1e-15 { deriv } else { 1e-15 };
        cn -= (en_temp - en) / deriv;
        en_temp = viscel_en_from_cn(cn, m, kn);
        error = (en_temp - en).abs() / en;
    }
    Some(cn)
}

/// `E*` as `Ip2_FrictMat_FrictMat_MindlinPhys` mixes two materials.
fn mixed_modulus(a: &Material, b: &Material) -> f64 {
    let (e1, n1, e2, n2) = (
        a.value("young"),
        a.value("poisson"),
        b.value("young"),
        b.value("poisson"),
    );
    e1 * e2 / ((1.0 - n1 * n1) * e2 + (1.0 - n2 * n2) * e1)
}

/// One side of a pair as the functors see it.
struct Side<'a> {
    id: u32,
    material: &'a Material,
    /// The radius the geometry functor gives it (`refR`).
    radius: f64,
    /// Its mass as YADE holds it (0 for a wall or facet).
    mass: f64,
}

impl YadeDeck {
    /// The `Ip2` functor YADE's dispatcher picks for two material classes, and its `Law2`.
    fn functors_for<'a>(
        r: &'a Reading,
        a: Class,
        b: Class,
        at: &DeckSource,
    ) -> Result<(&'a Functor, &'a Functor), DeckError> {
        let takes = |f: &&Functor| match f.class.as_str() {
            "Ip2_ViscElMat_ViscElMat_ViscElPhys" => a == Class::ViscEl && b == Class::ViscEl,
            _ => true,
        };
        let candidates: Vec<&Functor> = r.physics.iter().filter(takes).collect();
        // The dispatcher takes the most specialised functor: ViscElMat's own before FrictMat's.
        let exact = candidates
            .iter()
            .find(|f| f.class == "Ip2_ViscElMat_ViscElMat_ViscElPhys");
        let general: Vec<&&Functor> = candidates
            .iter()
            .filter(|f| f.class != "Ip2_ViscElMat_ViscElMat_ViscElPhys")
            .collect();
        let ip2 = match (exact, general.as_slice()) {
            (Some(f), _) => *f,
            (None, [f]) => **f,
            (None, []) => {
                return Err(DeckError::unsupported(
                    at,
                    format!(
                        "no Ip2 functor in the InteractionLoop takes {}–{}: YADE would make no contact of this pair",
                        a.name(),
                        b.name()
                    ),
                    FUNCTORS,
                ));
            }
            (None, [f, g, ..]) => {
                return Err(DeckError::unsupported(
                    &g.at,
                    format!(
                        "{} and {} ({}) both take FrictMat pairs",
                        g.class, f.class, f.at
                    ),
                    "one Ip2 functor for FrictMat pairs",
                ));
            }
        };
        let law = match ip2.class.as_str() {
            "Ip2_FrictMat_FrictMat_MindlinPhys" => "Law2_ScGeom_MindlinPhys_Mindlin",
            "Ip2_FrictMat_FrictMat_FrictPhys" => "Law2_ScGeom_FrictPhys_CundallStrack",
            _ => "Law2_ScGeom_ViscElPhys_Basic",
        };
        let law2 = r.laws.iter().find(|f| f.class == law).ok_or_else(|| {
            DeckError::unsupported(&ip2.at, format!("{} without {law} in the InteractionLoop: YADE would leave its contacts without a force", ip2.class), FUNCTORS)
        })?;
        Ok((ip2, law2))
    }

    /// The law of `a` against `b` (a ball, or a wall of `wall_kind`), with the dynamic mass
    /// `mass` (reduced for two balls, the ball's at a wall).
    fn pair_law(
        r: &Reading,
        a: &Side,
        b: &Side,
        wall: Option<(WallKind, &WallRead)>,
        mass: f64,
        geometry: &Functor,
    ) -> Result<PairLaw, DeckError> {
        let loop_at = r.loop_at.clone().unwrap_or_else(|| a.material.at.clone());
        let (ip2, law2) = Self::functors_for(r, a.material.class, b.material.class, &loop_at)?;
        let r_star = pair_radius(a.radius, b.radius);
        let ignored: Vec<&str> = ip2
            .dump
            .changed
            .iter()
            .map(String::as_str)
            .filter(|k| {
                matches!(
                    *k,
                    "es" | "betas" | "eta" | "krot" | "ktwist" | "frictAngle" | "ks" | "et"
                )
            })
            .collect();
        let mut out = match ip2.class.as_str() {
            "Ip2_FrictMat_FrictMat_MindlinPhys" => {
                Self::mindlin_law(ip2, law2, a, b, wall, mass, r_star)?
            }
            "Ip2_FrictMat_FrictMat_FrictPhys" => Self::frict_law(ip2, a, b, mass)?,
            _ => Self::viscel_law(ip2, a, b, wall, mass)?,
        };
        if !ignored.is_empty() {
            out.traps.push(format!("{} of {} (tangential, rolling and friction settings) act on no head-on impact: kept, and they change nothing here", ignored.join(", "), ip2.class));
        }
        let model = out.model.clone();
        if let Some(wall) = wall {
            wall_radius_trap(&mut out.traps, &model, wall, a, b, geometry);
        }
        Ok(out)
    }

    /// Hertz–Mindlin (`Ip2_FrictMat_FrictMat_MindlinPhys`): `(4/3) E* sqrt(R*)`, damped by
    /// `betan` or by `en` through Thornton's fit, clamped; what YADE refuses or the check does
    /// not model (adhesion, `nothing`) is refused.
    fn mindlin_law(
        ip2: &Functor,
        law2: &Functor,
        a: &Side,
        b: &Side,
        wall: Option<(WallKind, &WallRead)>,
        mass: f64,
        r_star: f64,
    ) -> Result<PairLaw, DeckError> {
        if ip2.number("gamma").is_some_and(|g| g != 0.0) && law2.flag("includeAdhesion") {
            return Err(DeckError::unsupported(&law2.at, "includeAdhesion=True with the Ip2's gamma: an adhesive force the check does not model".into(), "includeAdhesion=False, or gamma=0"));
        }
        if law2.flag("nothing") {
            return Err(DeckError::unsupported(
                &law2.at,
                "nothing=True: the law computes no force".into(),
                "nothing=False",
            ));
        }
        let e_star = mixed_modulus(a.material, b.material);
        let kno = 4.0 / 3.0 * e_star * r_star.sqrt();
        let en = ip2.pair_value("en", a.id, b.id)?;
        let betan = ip2.pair_value("betan", a.id, b.id)?;
        let beta = match (en, betan) {
            (Some(_), Some(_)) => {
                return Err(DeckError::unsupported(
                    &ip2.at,
                    "both en and betan".into(),
                    "one of en, betan (YADE refuses both)",
                ));
            }
            (Some(e), None) => {
                if !(e > 0.0 && e <= 1.0) {
                    return Err(DeckError::unsupported(
                        &ip2.at,
                        format!("en = {e}"),
                        "0 < en <= 1",
                    ));
                }
                thornton_damping_ratio(e)
            }
            (None, Some(b)) => b,
            (None, None) => 0.0,
        };
        let law = DashpotLaw {
            mass,
            stiffness: kno,
            exponent: 1.5,
            damping: 2.0 * beta * (1.5 * mass * kno).sqrt(),
            damping_exponent: 0.25,
            clamp_attractive: true,
        };
        let mut traps = Vec::new();
        if let Some(e) = en {
            let cor = accurate_metrics(&law, 1.0, 1e-12).map_or(f64::NAN, |m| m.cor);
            let fix = match hertz_input_restitution(e) {
                Some(x) => format!("the en that realises {e} is {x:.6}"),
                None => format!(
                    "no en below 1 realises {e} (the fit's damping does not vanish as en → 1)"
                ),
            };
            traps.push(format!("en → β_n through Thornton et al.'s fit (2013, for the clamped law): en = {e} gives β_n = {beta:.6}, whose law realises {cor:.6} ({:+.2e}); {fix}", cor - e));
        }
        if betan.is_some() {
            traps.push(format!("betan given: c = 2 β_n sqrt(1.5 M k) with β_n = {beta} (the ratio to the tangent stiffness's critical damping, not to a linear spring's)"));
        }
        traps.push("the normal force is cut at zero: it never attracts (YADE's clamped damping), so the COR is higher than the same dashpot's without the cut".into());
        traps.push(match wall {
            Some((_, w)) => format!("E* = {e_star:.4e} Pa: the wall's material ({}: E = {:e} Pa, ν = {}) is mixed in, E1 E2/((1−ν1²) E2 + (1−ν2²) E1); a wall meant rigid needs a far larger young", w.name, b.material.value("young"), b.material.value("poisson")),
            None => format!("E* = {e_star:.4e} Pa = E1 E2/((1−ν1²) E2 + (1−ν2²) E1) of the two materials"),
        });
        let model = format!(
            "Hertz–Mindlin{}",
            if en.is_some() {
                " en"
            } else if betan.is_some() {
                " betan"
            } else {
                ""
            }
        );
        Ok(PairLaw::new(model, law, en, traps))
    }

    /// `Ip2_FrictMat_FrictMat_FrictPhys`: a linear spring from the materials' moduli and the
    /// radii, undamped, clamped.
    fn frict_law(ip2: &Functor, a: &Side, b: &Side, mass: f64) -> Result<PairLaw, DeckError> {
        let (ea, eb) = (a.material.value("young"), b.material.value("young"));
        let (ra, rb) = (a.radius, b.radius);
        let kn = match ip2.pair_value("kn", a.id, b.id)? {
            Some(k) => k,
            None => 2.0 * ea * ra * eb * rb / (ea * ra + eb * rb),
        };
        let law = DashpotLaw {
            mass,
            stiffness: kn,
            exponent: 1.0,
            damping: 0.0,
            damping_exponent: 0.0,
            clamp_attractive: true,
        };
        let traps = vec![
            format!("FrictPhys is a linear spring, kn = 2 E1 R1 E2 R2/(E1 R1 + E2 R2) = {kn:.4e} N/m from the materials' young and the radii the geometry gives them (not Hertz: its stiffness does not grow with the overlap)"),
            "no contact damping: the contact is elastic and its COR departs from 1 by the step alone (YADE dissipates here only through NewtonIntegrator's damping, 0 in this script)".into(),
        ];
        Ok(PairLaw::new("FrictPhys linear", law, None, traps))
    }

    // Two materials' values are compared exactly: YADE averages what differs, and mRtype is a
    // whole number.
    #[allow(clippy::float_cmp)]
    fn viscel_law(
        ip2: &Functor,
        a: &Side,
        b: &Side,
        wall: Option<(WallKind, &WallRead)>,
        mass: f64,
    ) -> Result<PairLaw, DeckError> {
        let (m1, m2) = (a.material, b.material);
        for key in ["kn", "ks", "cn", "cs", "tc", "en", "et"] {
            if m1.value(key).is_finite() != m2.value(key).is_finite() {
                let (given, lacking) = if m1.value(key).is_finite() {
                    (m1, m2)
                } else {
                    (m2, m1)
                };
                return Err(DeckError::unsupported(
                    &lacking.at,
                    format!(
                        "ViscElMat without {key}, met by the ViscElMat of {} that has it (YADE stops: \"Both materials should have the same defined set of variables\")",
                        given.at
                    ),
                    "the same set of tc, en, et, kn, cn, ks, cs on every ViscElMat",
                ));
            }
        }
        if m1.value("mRtype") != m2.value("mRtype") {
            return Err(DeckError::unsupported(
                &m2.at,
                "mRtype differs from the other material's (YADE stops)".into(),
                "the same mRtype, 1 or 2",
            ));
        }
        // The wall's mass 0 becomes the sphere's, as YADE substitutes it.
        let (mass1, mass2) = match (a.mass, b.mass) {
            (x, y) if x == 0.0 && y > 0.0 => (y, y),
            (x, y) if y == 0.0 && x > 0.0 => (x, x),
            other => other,
        };
        let mass_r = mass1 * mass2 / (mass1 + mass2);
        let mut traps = Vec::new();
        let averaged = |key: &str| -> Result<(f64, bool), DeckError> {
            Ok(match ip2.pair_value(key, a.id, b.id)? {
                Some(x) => (x, false),
                None => (
                    (m1.value(key) + m2.value(key)) / 2.0,
                    m1.value(key) != m2.value(key),
                ),
            })
        };
        let functor_form = ["tc", "en", "et"].iter().all(|k| ip2.param(k).is_some());
        let (kn, cn, entered, model) = if (m1.value("tc").is_finite()
            && m1.value("en").is_finite()
            && m1.value("et").is_finite())
            || functor_form
        {
            let (tc, tc_mixed) = averaged("tc")?;
            let (en, en_mixed) = averaged("en")?;
            let kn1 = 1.0 / tc / tc * (PI * PI + en.ln().powi(2)) * mass_r * 2.0;
            let cn1 = -2.0 / tc * en.ln() * mass_r * 2.0;
            if en_mixed || tc_mixed {
                traps.push(format!("YADE averages the two materials' values: en = ({} + {})/2 = {en}, tc = ({:e} + {:e})/2 = {tc:e} s", m1.value("en"), m2.value("en"), m1.value("tc"), m2.value("tc")));
            }
            traps.push(format!("tc, en set kn, cn of the linear oscillator that rebounds at en = {en} unclamped; the force is cut at zero (YADE's clamped damping), so the COR comes out higher"));
            (
                series(kn1, kn1),
                series(cn1, cn1),
                Some(en),
                "ViscEl tc, en".to_string(),
            )
        } else if ["kn", "ks", "cn", "cs"]
            .iter()
            .all(|k| m1.value(k).is_finite())
        {
            traps.push(format!("kn, cn of the two materials in series, 1/(1/a + 1/b): kn = {:.4e} N/m, cn = {:.4e} N·s/m (each material carries twice a like pair's value)", series(m1.value("kn"), m2.value("kn")), series(m1.value("cn"), m2.value("cn"))));
            traps.push(
                "the force is cut at zero: it never attracts (YADE's clamped damping)".into(),
            );
            (
                series(m1.value("kn"), m2.value("kn")),
                series(m1.value("cn"), m2.value("cn")),
                None,
                "ViscEl kn, cn".to_string(),
            )
        } else {
            let kn1 = 2.0 * m1.value("young") * a.radius;
            let kn2 = 2.0 * m2.value("young") * b.radius;
            let kn = series(kn1, kn2);
            traps.push(format!("kn = 2 E1 R1 and 2 E2 R2 in series = {kn:.4e} N/m, from the materials' young (ViscElMat's default 1e9 Pa where not given) and the radii the geometry gives them"));
            if m1.value("cn").is_finite() && m1.value("cs").is_finite() {
                (
                    kn,
                    series(m1.value("cn"), m2.value("cn")),
                    None,
                    "ViscEl young, cn".to_string(),
                )
            } else if m1.value("en").is_finite() {
                let (en, en_mixed) = averaged("en")?;
                if en_mixed {
                    traps.push(format!(
                        "YADE averages the two materials' en: ({} + {})/2 = {en}",
                        m1.value("en"),
                        m2.value("en")
                    ));
                }
                let c = viscel_cn_from_en(en, mass_r, kn).ok_or_else(|| DeckError::unsupported(&m1.at, format!("en = {en}: YADE's Newton iteration for cn does not converge in 15 steps (it then runs cn = 0, an elastic contact)"), "an en the iteration reaches, or tc, en, et"))?;
                let realised = viscel_en_from_cn(c, mass_r, kn);
                traps.push(format!("cn from en by YADE's Newton iteration, stopped within 1 % of en: cn = {c:.6e} N·s/m, whose clamped law realises {realised:.6} on the mass it is tuned for"));
                (
                    kn,
                    series(2.0 * c, 2.0 * c),
                    Some(en),
                    "ViscEl young, en".to_string(),
                )
            } else {
                return Err(DeckError::unsupported(
                    &m1.at,
                    "a ViscElMat with neither tc, en, et nor kn, ks, cn, cs nor en or cn, cs"
                        .into(),
                    "tc, en, et; or kn, ks, cn, cs; or young with en or with cn, cs (YADE: \"Inconsistent material constants\")",
                ));
            }
        };
        let tuned_mass = matches!(model.as_str(), "ViscEl tc, en" | "ViscEl young, en");
        if tuned_mass {
            match wall {
                Some((WallKind::Box, w)) => traps.push(format!("the fixed box's own mass ({:.4e} kg) enters the tuning: kn, cn are set for the reduced mass {mass_r:.6e} kg of the ball and the box, not for the ball's {mass:.6e} kg that moves ({:+.2e} relative)", w.mass, mass_r / mass - 1.0)),
                Some(_) => traps.push(format!("a wall's mass is 0, and YADE takes the sphere's for it: kn, cn are tuned for m/2 = {mass_r:.4e} kg while the ball's {mass:.4e} kg moves, so the contact lasts √2 longer and its damping ratio is 1/√2 of the one tuned")),
                None => {}
            }
        }
        let law = DashpotLaw {
            mass,
            stiffness: kn,
            exponent: 1.0,
            damping: cn,
            damping_exponent: 0.0,
            clamp_attractive: true,
        };
        Ok(PairLaw::new(model, law, entered, traps))
    }
}

impl YadeDeck {
    fn from_dump(path: &Path, dump: &Dump, options: &DeckOptions) -> Result<UserDeck, DeckError> {
        refuse_before_reading(path, dump, options)?;
        let r = Self::gather(path, dump, options)?;
        let loop_at = r.loop_at.clone().ok_or_else(|| {
            lacking(
                path,
                "no InteractionLoop in O.engines after the set-up",
                "O.engines with InteractionLoop([Ig2…], [Ip2…], [Law2…])",
            )
        })?;
        let mut bodies = Self::bodies(&r, path, options)?;
        bodies.sort_by(|a, b| {
            a.type_id
                .cmp(&b.type_id)
                .then(b.radius.total_cmp(&a.radius))
        });
        let (timestep, timestep_from) = dump_timestep(path, dump)?;
        // Contacts: each pair of bodies, then each body against each wall.
        let mut contacts = Self::body_contacts(&r, &bodies, &loop_at)?;
        let (walls, wall_lines) = Self::wall_contacts(&r, &bodies, &loop_at, &mut contacts)?;
        Ok(UserDeck {
            path: path.to_path_buf(),
            timestep,
            timestep_from,
            bodies,
            walls,
            contacts,
            representative_velocity: None,
            left_out: left_out_lines(&r, path),
            transplant: Transplant {
                before_box: Vec::new(),
                common: common_lines(&r)?,
                walls: wall_lines,
                types: u32::try_from(r.materials.len()).unwrap_or(u32::MAX),
            },
        })
    }

    /// Each pair of bodies with the law YADE's functors give their two materials.
    fn body_contacts(
        r: &Reading,
        bodies: &[DeckBody],
        loop_at: &DeckSource,
    ) -> Result<Vec<DeckContact>, DeckError> {
        crate::codes::deck::body_contacts(bodies, |body, other| {
            let m_a = &r.materials[body.type_id as usize];
            let m_b = &r.materials[other.type_id as usize];
            let geometry = geometry_for(
                r,
                ["Ig2_Sphere_Sphere_ScGeom", "Ig2_Sphere_Sphere_ScGeom6D"],
                loop_at,
                loop_at,
            )?;
            let (a, b) = (Self::side(body, m_a), Self::side(other, m_b));
            let mass = reduced_mass(body.mass, other.mass);
            let mut pair = Self::pair_law(r, &a, &b, None, mass, geometry)?;
            pair.traps.extend(edit_traps(m_a));
            if body.type_id != other.type_id {
                pair.traps.extend(edit_traps(m_b));
            }
            let mut lines = vec![m_a.at.clone(), m_b.at.clone(), loop_at.clone()];
            lines.dedup();
            Ok(pair.set_by(lines))
        })
    }

    /// A ball of `material` as the functors see it.
    fn side<'a>(body: &DeckBody, material: &'a Material) -> Side<'a> {
        Side {
            id: body.type_id,
            material,
            radius: body.radius,
            mass: body.mass,
        }
    }

    /// The script's walls, with each body's contact against each pushed onto `contacts`; the
    /// walls and the Python each impact carries to place its wall.
    fn wall_contacts(
        r: &Reading,
        bodies: &[DeckBody],
        loop_at: &DeckSource,
        contacts: &mut Vec<DeckContact>,
    ) -> Result<(Vec<DeckWall>, Vec<String>), DeckError> {
        let mut walls = Vec::new();
        for wall in &r.walls {
            let m_w = &r.materials[wall.material as usize];
            let (young, poisson) = match m_w.class {
                Class::ViscEl if m_w.get("kn").is_some() || m_w.get("tc").is_some() => (None, None),
                _ => (Some(m_w.value("young")), Some(m_w.value("poisson"))),
            };
            walls.push(DeckWall {
                name: wall.name.clone(),
                type_id: Some(wall.material),
                youngs_modulus: young,
                poisson_ratio: poisson,
                from: wall.at.clone(),
            });
        }
        let order = WallOrder::ByWall;
        let laws = crate::codes::deck::wall_contacts(bodies, &r.walls, order, |wall, body| {
            let m_w = &r.materials[wall.material as usize];
            let geometry = geometry_for(r, wall.kind.geometry(), &wall.at, loop_at)?;
            let factor = match wall.kind {
                WallKind::Plane | WallKind::Facet if geometry.flag("hertzian") => {
                    HERTZIAN_WALL_RADIUS_FACTOR
                }
                WallKind::Facet => 2.0,
                _ => 1.0,
            };
            let m_a = &r.materials[body.type_id as usize];
            let a = Self::side(body, m_a);
            let b = Side {
                id: wall.material,
                material: m_w,
                radius: factor * body.radius,
                mass: wall.mass,
            };
            let mut pair = Self::pair_law(r, &a, &b, Some((wall.kind, wall)), body.mass, geometry)?;
            if wall.lines.len() > 1 {
                pair.traps.push(format!(
                    "{} bodies of this kind and material (lines {}) are one wall here",
                    wall.lines.len(),
                    wall.lines
                        .iter()
                        .map(usize::to_string)
                        .collect::<Vec<_>>()
                        .join(", ")
                ));
            }
            pair.traps.extend(edit_traps(m_a));
            if wall.material != body.type_id {
                pair.traps.extend(edit_traps(m_w));
            }
            Ok(pair.set_by([m_a.at.clone(), wall.at.clone(), loop_at.clone()]))
        })?;
        contacts.extend(laws);
        Ok((walls, r.walls.iter().map(wall_placement).collect()))
    }
}

/// The error of a script that lacks `what`, naming what is `supported`.
fn lacking(path: &Path, what: &str, supported: &str) -> DeckError {
    DeckError::Lacking {
        file: path.to_path_buf(),
        what: what.into(),
        supported: supported.into(),
    }
}

/// Refuse what no reading of the dump can mend: `--var` (a script's names are its own) and a
/// script that sets no engines before its first step.
fn refuse_before_reading(path: &Path, dump: &Dump, options: &DeckOptions) -> Result<(), DeckError> {
    if let Some((name, _)) = options.variables.first() {
        return Err(lacking(
            path,
            &format!("--var {name}: a YADE script's names are its own, set in the script"),
            "--var for LIGGGHTS and LAMMPS decks; for YADE, edit the script",
        ));
    }
    if dump.engines_line.is_none() {
        let before = match &dump.stopped {
            Some(stop) => format!(
                " before the reading stopped at its first step ({}, line {})",
                stop.call,
                stop.line.map_or("?".into(), |l| l.to_string())
            ),
            None => String::new(),
        };
        return Err(lacking(
            path,
            &format!(
                "the script sets no O.engines{before}: YADE's default engines are no contact law of the script's"
            ),
            "O.engines = [..., InteractionLoop([Ig2…], [Ip2…], [Law2…]), NewtonIntegrator(damping=0)] before the first O.run",
        ));
    }
    Ok(())
}

/// `O.dt` as YADE holds it after the set-up, s, and where the script sets it; refused where
/// the script sets none or it is not positive.
fn dump_timestep(path: &Path, dump: &Dump) -> Result<(f64, String), DeckError> {
    let dt_line = dump.dt_line.ok_or_else(|| {
        lacking(
            path,
            "the script sets no O.dt (YADE would step at its default)",
            "O.dt = NUMBER or O.dt = FACTOR * PWaveTimeStep()",
        )
    })?;
    let dt_at = SourceLine {
        file: path.to_path_buf(),
        line: dt_line,
    };
    let timestep = dump.dt.unwrap_or(f64::NAN);
    if !(timestep > 0.0 && timestep.is_finite()) {
        return Err(DeckError::unsupported(
            &dt_at,
            format!("O.dt = {timestep} after the set-up"),
            "a positive time step, s",
        ));
    }
    let timestep_from = match line_text(path, dt_line) {
        Some(text) => format!("{dt_at}, `{text}`; O.dt as YADE holds it after the set-up"),
        None => format!("{dt_at}; O.dt as YADE holds it after the set-up"),
    };
    Ok((timestep, timestep_from))
}

/// The InteractionLoop's geometry functor of one of `names` (the first one named in the error),
/// for a contact defined `at`.
fn geometry_for<'r>(
    r: &'r Reading,
    names: [&str; 2],
    at: &DeckSource,
    loop_at: &DeckSource,
) -> Result<&'r Functor, DeckError> {
    r.geometry
        .iter()
        .find(|f| names.contains(&f.class.as_str()))
        .ok_or_else(|| {
            DeckError::unsupported(
                at.clone(),
                format!(
                    "no {} in the InteractionLoop ({loop_at}): YADE would make no contact here",
                    names[0]
                ),
                FUNCTORS,
            )
        })
}

/// A trap line for each attribute of `m` the script changed after appending it.
fn edit_traps(m: &Material) -> Vec<String> {
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

/// The Python that places `wall` in an impact's script (a box with its mass as YADE holds it).
fn wall_placement(wall: &WallRead) -> String {
    let (placement, mass) = match wall.kind {
        WallKind::Plane => (
            format!(
                "utils.wall(0.0, axis=2, sense=0, material={})",
                wall.material
            ),
            None,
        ),
        WallKind::Facet => (
            format!(
                "utils.facet([(-100.0 * R1, -100.0 * R1, 0.0), (100.0 * R1, -100.0 * R1, 0.0), (0.0, 100.0 * R1, 0.0)], material={})",
                wall.material
            ),
            None,
        ),
        WallKind::Box => (
            format!(
                "utils.box((0.0, 0.0, -100.0 * R1), (100.0 * R1, 100.0 * R1, 100.0 * R1), fixed=True, material={})",
                wall.material
            ),
            Some(wall.mass),
        ),
    };
    let mut snippet = format!("b2 = O.bodies.append({placement})");
    if let Some(m) = mass {
        snippet.push_str(&format!(
            "\nO.bodies[b2].state.mass = {}  # the script's box, as YADE holds it",
            exact_number(m)
        ));
    }
    snippet
}

/// What the script holds that the impacts leave out, one line per kind with its lines.
fn left_out_lines(r: &Reading, path: &Path) -> Vec<String> {
    r.left_out
        .iter()
        .map(|(what, lines)| {
            if lines.is_empty() {
                return format!("{what}: {}", path.display());
            }
            let lines: Vec<String> = lines.iter().map(usize::to_string).collect();
            format!("{what}: {}:{}", path.display(), lines.join(","))
        })
        .collect()
}

/// The script's materials and functors as the Python each impact's script starts from.
fn common_lines(r: &Reading) -> Result<Vec<String>, DeckError> {
    let mut common = Vec::new();
    for m in &r.materials {
        common.push(format!("O.materials.append({})", m.python()?));
    }
    for (name, list) in [("IG2", &r.geometry), ("IP2", &r.physics), ("LAW2", &r.laws)] {
        let items = list
            .iter()
            .map(Functor::python)
            .collect::<Result<Vec<_>, _>>()?;
        common.push(format!("{name} = [{}]", items.join(", ")));
    }
    Ok(common)
}

impl DeckDialect for YadeDeck {
    fn recognises(&self, _path: &Path, text: &str) -> bool {
        text.contains("O.engines")
            || text.contains("O.bodies.append")
            || text.contains("O.materials.append")
            || text.lines().any(|l| {
                let l = l.trim_start();
                l.starts_with("from yade") || l.starts_with("import yade")
            })
    }

    fn reads(&self) -> &'static str {
        "YADE scripts, set up by YADE and read as it then holds them (FrictMat/ViscElMat materials, InteractionLoop functors, O.dt, spheres, walls, facets, fixed boxes)"
    }

    fn read(&self, path: &Path, options: &DeckOptions) -> Result<UserDeck, DeckError> {
        let dump = dump_script(path, options.time_limit.unwrap_or(READ_TIME_LIMIT))?;
        Self::read_dump(path, &dump, options)
    }

    fn input(&self, deck: &UserDeck, plan: ImpactPlan<'_>) -> Result<DeckImpactInput, CodeError> {
        let (c, body, other) = (plan.contact, plan.body, plan.other);
        let (v1, v2) = plan.velocities;
        // The script starts the bodies one ulp apart (YADE's laws act at zero overlap).
        let gap = f64::from_bits(plan.reach.to_bits() + 1) - plan.reach;
        let placement = match c.partner {
            Partner::Body(_) => String::new(),
            Partner::Wall(w) => deck.transplant.walls[w].clone(),
        };
        let t = |x: TypeRef| match x {
            TypeRef::Type(t) => t.to_string(),
            TypeRef::Wall => "0".into(),
        };
        let other_material = match c.partner {
            Partner::Body(o) => deck.bodies[o].type_id.to_string(),
            Partner::Wall(_) => "None".into(),
        };
        let values = [
            ("source", deck.path.display().to_string()),
            ("trajectory", TRAJECTORY_FILE.to_string()),
            ("pair", format!("{} on {}", c.types[0], c.types[1])),
            ("speed", plan.velocity.to_string()),
            (
                "scene",
                if other.is_some() { "ball_ball" } else { "wall" }.to_string(),
            ),
            ("timestep", exact_number(deck.timestep)),
            ("steps", plan.steps.to_string()),
            ("radius", exact_number(body.radius)),
            ("mass", exact_number(body.mass)),
            ("material", t(c.types[0])),
            ("velocity", exact_number(v1)),
            (
                "other_radius",
                exact_number(other.map_or(0.0, |o| o.radius)),
            ),
            ("other_mass", exact_number(other.map_or(0.0, |o| o.mass))),
            ("other_material", other_material),
            ("other_velocity", exact_number(v2)),
            ("deck_lines", deck.transplant.common.join("\n")),
            (
                "wall",
                if placement.is_empty() {
                    "pass".to_string()
                } else {
                    placement.replace('\n', "\n    ")
                },
            ),
        ];
        let text = fill_template(TEMPLATE, &values).map_err(|e| CodeError::Unsupported {
            code: "yade".into(),
            case: plan.setup.case_name.clone(),
            reason: e.to_string(),
        })?;
        Ok(DeckImpactInput {
            input: RenderedInput {
                file_name: SCRIPT.into(),
                text,
                args: ["-j1", "-n", "-x", SCRIPT].map(String::from).to_vec(),
            },
            setup: plan.setup,
            start_gap: gap,
        })
    }
}

#[cfg(test)]
mod tests {
    // series() of exact inputs is exact.
    #![allow(clippy::float_cmp)]
    use super::*;

    #[test]
    fn yades_newton_iteration_lands_within_one_percent_of_en() {
        let (m, kn) = (0.5, 1e6);
        for en in [0.3, 0.5, 0.7, 0.9] {
            let cn = viscel_cn_from_en(en, m, kn).unwrap();
            let realised = viscel_en_from_cn(cn, m, kn);
            assert!(((realised - en) / en).abs() <= 1e-2, "{en}: {realised}");
            // get_en_from_cn is the clamped linear dashpot's COR (the closed form of damping.rs).
            let zeta = crate::codes::damping::clamped_linear_damping_ratio(realised).unwrap();
            let c = 2.0 * zeta * (m * kn).sqrt();
            assert!(((c - cn) / cn).abs() < 1e-9, "{en}: {c} {cn}");
        }
    }

    #[test]
    fn values_in_series_leave_a_zero_out() {
        assert_eq!(series(2.0, 2.0), 1.0);
        assert_eq!(series(0.0, 3.0), 3.0);
        assert_eq!(series(0.0, 0.0), 0.0);
    }
}
