//! A YADE user's script (`millimpact deck`): the materials (`FrictMat`, `ViscElMat`) appended
//! to `O.materials`, the `InteractionLoop`'s functors, `O.dt` (a number, or a multiple of
//! `PWaveTimeStep()`), the spheres of `sphere(…)` calls with their radii and materials, and the
//! walls (`wall`, `facet` and the `geom.facet…` shapes, fixed `box`es) with theirs; and the
//! impact of one pair rendered with those materials and functors transplanted.
//!
//! A Python script cannot be read in general: [`super::python`] reads its literal values and
//! module-level numeric assignments and executes nothing. What a check needs and the reader
//! cannot resolve is refused with its file and line; what the check does not need is listed.
//!
//! The law each functor makes YADE 2023.02a integrate follows its sources
//! (`pkg/dem/HertzMindlin.cpp`, `pkg/dem/ViscoelasticPM.cpp`, `pkg/dem/ElasticContactLaw.cpp`)
//! and the radii its geometry functors give a wall, as measured and listed in
//! `reference/yade/CONVENTIONS.md`; the live test checks every pair of the example against it.

use std::collections::BTreeMap;
use std::f64::consts::PI;
use std::path::Path;

use super::python::{Call, Expr, Known, Module, Unresolved, Value, show};
use super::{HERTZIAN_WALL_RADIUS_FACTOR, TRAJECTORY_FILE, thornton_damping_ratio};
use crate::codes::damping::hertz_input_restitution;
use crate::codes::deck::{
    DeckBody, DeckContact, DeckError, DeckImpactInput, DeckOptions, DeckReader, DeckSource,
    DeckWall, Partner, SourceLine, Transplant, TypeRef, UserDeck, sphere_mass,
};
use crate::codes::template::{exact_number, fill_template};
use crate::codes::{CodeError, CodeSetup, CodeSphere, RenderedInput};
use crate::model::law::DashpotLaw;
use crate::model::scene::{SceneKind, pair_radius, reduced_mass};
use crate::solve::dashpot::accurate_metrics;

const TEMPLATE: &str = include_str!("deck.py");
const SCRIPT: &str = "impact.py";

/// The functors whose laws the check knows.
const FUNCTORS: &str = "Ig2_Sphere_Sphere_ScGeom(6D), Ig2_Wall_Sphere_ScGeom, Ig2_Facet_Sphere_ScGeom(6D), Ig2_Box_Sphere_ScGeom(6D); Ip2_FrictMat_FrictMat_MindlinPhys with Law2_ScGeom_MindlinPhys_Mindlin, Ip2_FrictMat_FrictMat_FrictPhys with Law2_ScGeom_FrictPhys_CundallStrack, Ip2_ViscElMat_ViscElMat_ViscElPhys with Law2_ScGeom_ViscElPhys_Basic";
/// What a value of the script may be.
const LITERAL: &str = "a literal number, a name assigned one at module level, or arithmetic of them (math functions included)";

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

/// A material appended to `O.materials`, its values resolved.
#[derive(Clone, Debug)]
struct Material {
    class: Class,
    values: Vec<(String, Value)>,
    at: SourceLine,
}

impl Material {
    fn get(&self, key: &str) -> Option<f64> {
        self.values
            .iter()
            .rev()
            .find(|(k, _)| k == key)
            .and_then(|(_, v)| v.number())
    }

    /// A value with the class's default (`ElastMat`: density 1000, young 1e9, poisson 0.25;
    /// `ViscElMat`'s own: NaN, "not given").
    fn value(&self, key: &str) -> f64 {
        self.get(key).unwrap_or(match key {
            "density" => 1000.0,
            "young" => 1e9,
            "poisson" => 0.25,
            "mRtype" => 1.0,
            _ => f64::NAN,
        })
    }

    fn label(&self) -> Option<String> {
        self.values
            .iter()
            .find(|(k, _)| k == "label")
            .and_then(|(_, v)| match v {
                Value::Str(s) => Some(s.clone()),
                _ => None,
            })
    }

    fn python(&self) -> String {
        let args: Vec<String> = self
            .values
            .iter()
            .map(|(k, v)| format!("{k}={}", v.python()))
            .collect();
        format!("{}({})", self.class.name(), args.join(", "))
    }
}

/// A functor's parameter: a value, or a `MatchMaker` of per-material-pair values.
#[derive(Clone, Debug, PartialEq)]
enum Param {
    Value(Value),
    Match {
        matches: Vec<(i64, i64, f64)>,
        algo: String,
        val: Option<f64>,
    },
}

impl Param {
    fn python(&self) -> String {
        match self {
            Param::Value(v) => v.python(),
            Param::Match { matches, algo, val } => {
                let m: Vec<String> = matches
                    .iter()
                    .map(|(a, b, x)| format!("({a}, {b}, {})", exact_number(*x)))
                    .collect();
                let val = val.map_or(String::new(), |v| format!(", val={}", exact_number(v)));
                format!(
                    "MatchMaker(matches=({},), algo='{algo}'{val})",
                    m.join(", ")
                )
            }
        }
    }
}

/// A functor of the `InteractionLoop`.
#[derive(Clone, Debug)]
struct Functor {
    class: String,
    params: Vec<(String, Param)>,
    at: SourceLine,
}

impl Functor {
    fn param(&self, key: &str) -> Option<&Param> {
        self.params
            .iter()
            .rev()
            .find(|(k, _)| k == key)
            .map(|(_, p)| p)
    }

    fn number(&self, key: &str) -> Option<f64> {
        match self.param(key) {
            Some(Param::Value(v)) => v.number(),
            _ => None,
        }
    }

    fn flag(&self, key: &str) -> bool {
        matches!(self.param(key), Some(Param::Value(Value::Bool(true))))
    }

    /// The parameter's value for the materials `a`, `b` (a `MatchMaker` looked up by id, as
    /// YADE does), or `None` where it is not given.
    fn pair_value(&self, key: &str, a: u32, b: u32) -> Result<Option<f64>, DeckError> {
        match self.param(key) {
            None | Some(Param::Value(Value::NoneValue)) => Ok(None),
            Some(Param::Value(v)) => v.number().map(Some).ok_or_else(|| {
                DeckError::unsupported(
                    &self.at,
                    format!("{}'s {key} = {}", self.class, v.python()),
                    "a number or a MatchMaker",
                )
            }),
            Some(Param::Match { matches, algo, val }) => {
                let (a, b) = (i64::from(a), i64::from(b));
                if let Some((_, _, x)) = matches
                    .iter()
                    .find(|(i, j, _)| (*i == a && *j == b) || (*i == b && *j == a))
                {
                    return Ok(Some(*x));
                }
                match (algo.as_str(), val) {
                    ("val", Some(v)) => Ok(Some(*v)),
                    _ => Err(DeckError::unsupported(
                        &self.at,
                        format!(
                            "{}'s {key}: its MatchMaker has no match for the materials {a} and {b} and no fallback YADE can compute without the materials' own values (algo '{algo}')",
                            self.class
                        ),
                        "a match for every pair in use, or algo='val' with val=X",
                    )),
                }
            }
        }
    }

    fn python(&self) -> String {
        let args: Vec<String> = self
            .params
            .iter()
            .map(|(k, p)| format!("{k}={}", p.python()))
            .collect();
        format!("{}({})", self.class, args.join(", "))
    }
}

/// What a wall is in YADE, which decides the radius its geometry functor gives it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
enum WallKind {
    /// `wall(…)`: `Ig2_Wall_Sphere_ScGeom`.
    Plane,
    /// `facet(…)` and the `geom.facet…`, `ymport` meshes: `Ig2_Facet_Sphere_ScGeom`.
    Facet,
    /// A fixed `box(…)`: `Ig2_Box_Sphere_ScGeom`.
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
}

/// A wall as read: its kind, material and (a box's) mass.
#[derive(Clone, Debug)]
struct WallRead {
    name: String,
    kind: WallKind,
    material: u32,
    /// A fixed box's mass, kg (its volume times its material's density), where its extents are
    /// literal; walls and facets have none.
    mass: Result<f64, Unresolved>,
    at: SourceLine,
    lines: Vec<usize>,
}

/// A sphere as read.
#[derive(Clone, Debug)]
struct SphereRead {
    material: u32,
    radius: Result<f64, Unresolved>,
    at: SourceLine,
}

/// Everything read from the script.
#[derive(Default)]
struct Reading {
    materials: Vec<Material>,
    /// `O.materials.append` calls (by where they start) and the ids they return.
    appended: BTreeMap<(usize, usize), Vec<u32>>,
    /// Names of material instances appended by name (`O.materials.append(steel)`).
    named: BTreeMap<String, u32>,
    spheres: Vec<SphereRead>,
    walls: Vec<WallRead>,
    geometry: Vec<Functor>,
    physics: Vec<Functor>,
    laws: Vec<Functor>,
    loop_at: Option<SourceLine>,
    newton: Option<SourceLine>,
    timestep: Option<(Expr, SourceLine)>,
    left_out: BTreeMap<String, Vec<usize>>,
}

impl Reading {
    fn leave_out(&mut self, what: &str, line: usize) {
        let lines = self.left_out.entry(what.to_string()).or_default();
        if !lines.contains(&line) {
            lines.push(line);
        }
    }
}

/// The reader's own values: the ids `O.materials.append` returns, and `PWaveTimeStep()`.
struct Knowledge<'a> {
    appended: &'a BTreeMap<(usize, usize), Vec<u32>>,
    pwave: Option<f64>,
}

impl Known for Knowledge<'_> {
    fn call(&self, call: &Call) -> Option<Result<Value, Unresolved>> {
        if call.func == "O.materials.append" {
            return Some(match self.appended.get(&call.at).map(Vec::as_slice) {
                Some([id]) => Ok(Value::Int(i64::from(*id))),
                _ => Err(Unresolved(format!(
                    "`{}` appends no single material",
                    show(&Expr::Call(call.clone()))
                ))),
            });
        }
        (call.name() == "PWaveTimeStep").then(|| {
            self.pwave.map(Value::Float).ok_or_else(|| {
                Unresolved(
                    "PWaveTimeStep() has no sphere of known size before it (YADE would return 1 s)"
                        .into(),
                )
            })
        })
    }
}

/// Where the script's names resolve: a deck file and its module.
struct Script<'a> {
    path: &'a Path,
    module: &'a Module,
}

impl Script<'_> {
    fn at(&self, line: usize) -> SourceLine {
        SourceLine {
            file: self.path.to_path_buf(),
            line,
        }
    }

    /// The value of `expr` (the argument `what` of a call on `line`), or the error naming it.
    fn value(
        &self,
        expr: &Expr,
        line: usize,
        known: &dyn Known,
        what: &str,
    ) -> Result<Value, DeckError> {
        self.module.value(expr, line, known).map_err(|e| {
            DeckError::unsupported(
                self.at(line),
                format!("{what} `{}`: {e}", show(expr)),
                LITERAL,
            )
        })
    }

    fn number(
        &self,
        expr: &Expr,
        line: usize,
        known: &dyn Known,
        what: &str,
    ) -> Result<f64, DeckError> {
        let v = self.value(expr, line, known, what)?;
        v.number().ok_or_else(|| {
            DeckError::unsupported(
                self.at(line),
                format!("{what} `{}` is {}, not a number", show(expr), v.python()),
                LITERAL,
            )
        })
    }

    /// The expression a name is bound to, or the expression itself.
    fn through_name(&self, expr: &Expr, line: usize) -> Expr {
        match expr {
            Expr::Name(n) => self
                .module
                .binding(n, line)
                .map_or_else(|_| expr.clone(), |(_, e)| e),
            other => other.clone(),
        }
    }
}

fn class_of(func: &str) -> Option<Class> {
    match func.rsplit('.').next()? {
        "FrictMat" => Some(Class::Frict),
        "ViscElMat" => Some(Class::ViscEl),
        _ => None,
    }
}

/// Material-like class names (YADE's materials end in `Mat`).
fn is_material_class(func: &str) -> bool {
    let name = func.rsplit('.').next().unwrap_or(func);
    name.ends_with("Mat") && name.chars().next().is_some_and(char::is_uppercase)
}

fn wall_kind(call: &Call) -> Option<(WallKind, Option<usize>)> {
    let name = call.name();
    let prefix = call.func.strip_suffix(name).unwrap_or("");
    let utils = matches!(prefix, "" | "utils." | "yade.utils.");
    match name {
        "wall" if utils => Some((WallKind::Plane, Some(4))),
        "facet" if utils => Some((WallKind::Facet, Some(7))),
        "box" if utils => Some((WallKind::Box, Some(8))),
        _ if name.starts_with("facet")
            && matches!(prefix, "" | "geom." | "yade.geom." | "utils.") =>
        {
            Some((WallKind::Facet, None))
        }
        "stl" | "gmsh" | "gts" | "unv" if prefix.ends_with("ymport.") => {
            Some((WallKind::Facet, None))
        }
        _ => None,
    }
}

fn is_sphere(call: &Call) -> bool {
    matches!(
        call.func.as_str(),
        "sphere" | "utils.sphere" | "yade.utils.sphere"
    )
}

const GENERATORS: [&str; 10] = [
    "makeCloud",
    "randomDensePack",
    "regularHexa",
    "regularOrtho",
    "randomPeriPack",
    "toSimulation",
    "filterSpherePack",
    "text",
    "textExt",
    "textClumps",
];

/// Engines whose settings the impact replaces with its own.
fn engine_left_out(name: &str) -> Option<&'static str> {
    Some(match name {
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
        _ if name.ends_with("Engine") || name.ends_with("Controller") => {
            "wall and particle motion and other engines (no part of a contact)"
        }
        _ => return None,
    })
}

impl YadeDeck {
    /// Resolve the material a body call names (`material=`, default the last appended).
    fn material_ref(
        s: &Script,
        r: &mut Reading,
        call: &Call,
        position: Option<usize>,
    ) -> Result<u32, DeckError> {
        let at = s.at(call.line);
        let count = r.materials.len();
        let by_index = |k: i64, r: &Reading| -> Result<u32, DeckError> {
            let n = i64::try_from(r.materials.len()).unwrap_or(i64::MAX);
            let id = if k < 0 { n + k } else { k };
            u32::try_from(id)
                .ok()
                .filter(|id| (*id as usize) < r.materials.len())
                .ok_or_else(|| {
                    DeckError::unsupported(
                        &at,
                        format!(
                            "material {k} of `{}`: O.materials holds {n} materials there",
                            call.func
                        ),
                        "an id or label of a material appended to O.materials before the body",
                    )
                })
        };
        let Some(expr) = call.arg("material", position) else {
            if count == 0 {
                // utils.defaultMaterial(), appended as O.materials[0] by the first body.
                r.materials.push(Material {
                    class: Class::Frict,
                    values: vec![
                        ("density".into(), Value::Float(1e3)),
                        ("young".into(), Value::Float(1e7)),
                        ("poisson".into(), Value::Float(0.3)),
                        ("frictionAngle".into(), Value::Float(0.5)),
                        ("label".into(), Value::Str("defaultMat".into())),
                    ],
                    at: at.clone(),
                });
            }
            return by_index(-1, r);
        };
        let bound = s.through_name(expr, call.line);
        if let Expr::Call(c) = &bound {
            if c.func == "O.materials.append" {
                return match r.appended.get(&c.at).map(Vec::as_slice) {
                    Some([id]) => Ok(*id),
                    _ => Err(DeckError::unsupported(
                        &at,
                        format!("material `{}`", show(expr)),
                        "one material's id",
                    )),
                };
            }
            if is_material_class(&c.func) {
                // An instance: appended under its name before, or not at all (YADE gives it id −1).
                let appended = match expr {
                    Expr::Name(n) => r.named.get(n).copied(),
                    _ => None,
                };
                return appended.ok_or_else(|| DeckError::unsupported(&at, format!("material `{}` is not appended to O.materials (YADE gives it id −1; the check numbers types by their O.materials ids)", show(expr)), "O.materials.append(MATERIAL) before the body, and material=its id, label or name"));
            }
        }
        let known = Knowledge {
            appended: &r.appended,
            pwave: None,
        };
        match s.value(expr, call.line, &known, "material")? {
            Value::Int(k) => by_index(k, r),
            Value::Str(label) => r
                .materials
                .iter()
                .position(|m| m.label().as_deref() == Some(label.as_str()))
                .and_then(|k| u32::try_from(k).ok())
                .ok_or_else(|| {
                    DeckError::unsupported(
                        &at,
                        format!("material '{label}': no material of that label in O.materials"),
                        "the label of a material appended before the body",
                    )
                }),
            other => Err(DeckError::unsupported(
                &at,
                format!("material = {}", other.python()),
                "an O.materials id, a label, or a name bound to an appended material",
            )),
        }
    }

    /// A material constructor's values.
    fn material(s: &Script, call: &Call, known: &dyn Known) -> Result<Material, DeckError> {
        let at = s.at(call.line);
        let class = class_of(&call.func).ok_or_else(|| {
            DeckError::unsupported(
                &at,
                format!("material class `{}`", call.func),
                "FrictMat, ViscElMat",
            )
        })?;
        if !call.args.is_empty() {
            return Err(DeckError::unsupported(
                &at,
                format!("positional arguments to {}", call.func),
                "keyword arguments (young=…, poisson=…, density=…)",
            ));
        }
        let values = call
            .kwargs
            .iter()
            .map(|(k, e)| {
                Ok((
                    k.clone(),
                    s.value(e, call.line, known, &format!("{}'s {k}", class.name()))?,
                ))
            })
            .collect::<Result<Vec<_>, DeckError>>()?;
        Ok(Material { class, values, at })
    }

    fn append(s: &Script, r: &mut Reading, call: &Call) -> Result<(), DeckError> {
        let Some(arg) = call.args.first() else {
            return Ok(());
        };
        // A name stays written as it is: an instance appended by name is known by it.
        let items = match (arg, s.through_name(arg, call.line)) {
            (_, Expr::Seq(items)) => items,
            (written, _) => vec![written.clone()],
        };
        let mut ids = Vec::new();
        for written in items {
            let item = s.through_name(&written, call.line);
            let Expr::Call(c) = &item else {
                return Err(DeckError::unsupported(
                    s.at(call.line),
                    format!("O.materials.append({})", show(arg)),
                    "O.materials.append(FrictMat(…)) or ViscElMat(…), or of a name assigned one at module level",
                ));
            };
            let known = Knowledge {
                appended: &r.appended,
                pwave: None,
            };
            let material = Self::material(s, c, &known)?;
            let id = u32::try_from(r.materials.len()).unwrap_or(u32::MAX);
            if let Expr::Name(n) = &written {
                r.named.insert(n.clone(), id);
            }
            ids.push(id);
            r.materials.push(material);
        }
        r.appended.insert(call.at, ids);
        Ok(())
    }

    fn functors(s: &Script, r: &Reading, call: &Call, k: usize) -> Result<Vec<Functor>, DeckError> {
        let at = s.at(call.line);
        let Some(arg) = call.args.get(k) else {
            return Err(DeckError::unsupported(
                &at,
                "InteractionLoop without its three functor lists".into(),
                "InteractionLoop([Ig2…], [Ip2…], [Law2…])",
            ));
        };
        let Expr::Seq(items) = s.through_name(arg, call.line) else {
            return Err(DeckError::unsupported(
                &at,
                format!("functor list `{}`", show(arg)),
                "a list of functor constructors written in the InteractionLoop, or a name assigned one",
            ));
        };
        let known = Knowledge {
            appended: &r.appended,
            pwave: None,
        };
        items
            .iter()
            .map(|item| {
                let Expr::Call(f) = item else {
                    return Err(DeckError::unsupported(
                        &at,
                        format!("functor `{}`", show(item)),
                        "a functor constructor, Name(key=value, …)",
                    ));
                };
                let here = s.at(f.line);
                let params = f
                    .kwargs
                    .iter()
                    .map(|(key, e)| {
                        let param = match s.through_name(e, f.line) {
                            Expr::Call(m) if m.name() == "MatchMaker" => {
                                Self::match_maker(s, &m, &known)?
                            }
                            _ => Param::Value(s.value(
                                e,
                                f.line,
                                &known,
                                &format!("{}'s {key}", f.func),
                            )?),
                        };
                        Ok((key.clone(), param))
                    })
                    .collect::<Result<Vec<_>, DeckError>>()?;
                if !f.args.is_empty() {
                    return Err(DeckError::unsupported(
                        &here,
                        format!("positional arguments to {}", f.func),
                        "keyword arguments",
                    ));
                }
                Ok(Functor {
                    class: f.name().to_string(),
                    params,
                    at: here,
                })
            })
            .collect()
    }

    fn match_maker(s: &Script, m: &Call, known: &dyn Known) -> Result<Param, DeckError> {
        let at = s.at(m.line);
        let mut matches = Vec::new();
        let mut algo = "avg".to_string();
        let mut val = None;
        for (key, e) in &m.kwargs {
            let v = s.value(e, m.line, known, &format!("MatchMaker's {key}"))?;
            match (key.as_str(), v) {
                ("matches", Value::Seq(items)) => {
                    for item in items {
                        match item {
                            Value::Seq(t) if t.len() == 3 => match (&t[0], &t[1], t[2].number()) {
                                (Value::Int(a), Value::Int(b), Some(x)) => {
                                    matches.push((*a, *b, x))
                                }
                                _ => {
                                    return Err(DeckError::unsupported(
                                        &at,
                                        format!("MatchMaker match {}", Value::Seq(t).python()),
                                        "(id1, id2, value), ids whole numbers",
                                    ));
                                }
                            },
                            other => {
                                return Err(DeckError::unsupported(
                                    &at,
                                    format!("MatchMaker match {}", other.python()),
                                    "(id1, id2, value)",
                                ));
                            }
                        }
                    }
                }
                ("algo", Value::Str(a)) => algo = a,
                ("val", v) if v.number().is_some() => val = v.number(),
                (key, v) => {
                    return Err(DeckError::unsupported(
                        &at,
                        format!("MatchMaker {key}={}", v.python()),
                        "MatchMaker(matches=((id1, id2, value), …), algo='val', val=X)",
                    ));
                }
            }
        }
        Ok(Param::Match { matches, algo, val })
    }

    fn gather(s: &Script, options: &DeckOptions) -> Result<Reading, DeckError> {
        let mut r = Reading::default();
        let calls = s.module.calls();
        let given: Vec<u32> = options.particles.iter().map(|p| p.type_id).collect();
        for call in &calls {
            let at = s.at(call.line);
            let name = call.name();
            if call.func == "O.materials.append" {
                Self::append(s, &mut r, call)?;
            } else if is_sphere(call) {
                let material = Self::material_ref(s, &mut r, call, Some(7))?;
                let known = Knowledge {
                    appended: &r.appended,
                    pwave: None,
                };
                let radius = call
                    .arg("radius", Some(1))
                    .ok_or_else(|| Unresolved("no radius".into()))
                    .and_then(|e| s.module.value(e, call.line, &known))
                    .and_then(|v| {
                        v.number()
                            .ok_or_else(|| Unresolved(format!("{} is not a number", v.python())))
                    });
                if call
                    .arg("fixed", Some(2))
                    .is_some_and(|e| *e == Expr::Bool(true))
                {
                    r.leave_out("fixed spheres, checked as free ones", call.line);
                }
                r.leave_out(
                    "the bodies' positions (the impact places its own)",
                    call.line,
                );
                r.spheres.push(SphereRead {
                    material,
                    radius,
                    at,
                });
            } else if let Some((kind, position)) = wall_kind(call) {
                if kind == WallKind::Box {
                    let fixed = call
                        .arg("fixed", Some(4))
                        .is_some_and(|e| *e == Expr::Bool(true))
                        || call
                            .arg("dynamic", Some(3))
                            .is_some_and(|e| *e == Expr::Bool(false));
                    if !fixed {
                        return Err(DeckError::unsupported(
                            &at,
                            format!(
                                "a free `{}(…)`: a box that moves is a particle the check does not model",
                                call.func
                            ),
                            "box(…, fixed=True) as a wall",
                        ));
                    }
                }
                let material = Self::material_ref(s, &mut r, call, position)?;
                let known = Knowledge {
                    appended: &r.appended,
                    pwave: None,
                };
                let mass = match kind {
                    WallKind::Box => {
                        let density = r.materials[material as usize].value("density");
                        call.arg("extents", Some(1))
                            .ok_or_else(|| Unresolved("the box has no extents".into()))
                            .and_then(|e| s.module.value(e, call.line, &known))
                            .and_then(|v| match v {
                                Value::Seq(x)
                                    if x.len() == 3 && x.iter().all(|v| v.number().is_some()) =>
                                {
                                    Ok(8.0
                                        * x.iter().filter_map(Value::number).product::<f64>()
                                        * density)
                                }
                                other => Err(Unresolved(format!(
                                    "its extents {} are not three half-sizes",
                                    other.python()
                                ))),
                            })
                    }
                    _ => Ok(0.0),
                };
                if !matches!(name, "wall" | "facet" | "box") {
                    r.leave_out(
                        "the walls' shapes (each met as a flat face of its kind)",
                        call.line,
                    );
                }
                r.leave_out(
                    "the bodies' positions (the impact places its own)",
                    call.line,
                );
                // Walls of one kind and material (and mass) are one wall to the check.
                let same = r.walls.iter_mut().find(|w| {
                    w.kind == kind
                        && w.material == material
                        && w.mass.as_ref().ok() == mass.as_ref().ok()
                });
                match same {
                    Some(w) => w.lines.push(call.line),
                    None => r.walls.push(WallRead {
                        name: format!("{name}:{}", call.line),
                        kind,
                        material,
                        mass,
                        at,
                        lines: vec![call.line],
                    }),
                }
            } else if name == "InteractionLoop" {
                if let Some(first) = &r.loop_at {
                    return Err(DeckError::unsupported(
                        &at,
                        format!(
                            "a second InteractionLoop (the first at line {})",
                            first.line
                        ),
                        "one InteractionLoop",
                    ));
                }
                r.geometry = Self::functors(s, &r, call, 0)?;
                r.physics = Self::functors(s, &r, call, 1)?;
                r.laws = Self::functors(s, &r, call, 2)?;
                r.loop_at = Some(at);
            } else if name == "NewtonIntegrator" {
                let known = Knowledge {
                    appended: &r.appended,
                    pwave: None,
                };
                let damping = match call.arg("damping", None) {
                    Some(e) => s.number(e, call.line, &known, "NewtonIntegrator's damping")?,
                    None => 0.2,
                };
                if damping != 0.0 {
                    let e = ((1.0 - damping) / (1.0 + damping)).sqrt();
                    return Err(DeckError::unsupported(
                        &at,
                        format!(
                            "NewtonIntegrator damping = {damping}{}: YADE's local damping scales every body's force by 1 ∓ {damping} against its own velocity, on top of the contact law (alone it makes a Hertz impact on a fixed wall rebound at {e:.4}, and between two moving balls it depends on their absolute velocities): the check models contact laws",
                            if call.arg("damping", None).is_none() {
                                " (its default)"
                            } else {
                                ""
                            }
                        ),
                        "NewtonIntegrator(damping=0) (give it to check the contacts alone)",
                    ));
                }
                if call.arg("gravity", None).is_some() {
                    r.leave_out("gravity (the impact is a free normal impact)", call.line);
                }
                r.newton = Some(at);
            } else if name.ends_with("TimeStepper") {
                return Err(DeckError::unsupported(
                    &at,
                    format!("{name}: the time step is set while the script runs"),
                    "O.dt = NUMBER or O.dt = FACTOR * PWaveTimeStep(), without a time stepper in O.engines",
                ));
            } else if let Some(what) = engine_left_out(name) {
                r.leave_out(what, call.line);
            } else if GENERATORS.contains(&name) {
                r.leave_out("spheres made at run time (give their sizes with --particle TYPE:RADIUS:DENSITY, TYPE the material's O.materials id)", call.line);
            } else if matches!(call.func.as_str(), "O.run" | "O.wait" | "O.stopAtIter") {
                r.leave_out("the run itself", call.line);
            } else if call.func.starts_with("plot.")
                || call.func.starts_with("qt.")
                || call.func.starts_with("O.save")
                || call.func.starts_with("O.load")
            {
                r.leave_out("output and control", call.line);
            }
        }
        for (index, st) in s.module.statements.iter().enumerate() {
            let t = super::python::text(&st.tokens);
            let changed_in_place = t.starts_with("O.dt ")
                && !t.starts_with("O.dt =")
                && st.tokens.get(3).is_some_and(
                    |x| matches!(x.tok, super::python::Tok::Op(o) if o.ends_with('=') && o != "=="),
                );
            if changed_in_place {
                return Err(DeckError::unsupported(
                    s.at(st.line),
                    format!("`{t}`: the time step changed in place"),
                    "O.dt = NUMBER or O.dt = FACTOR * PWaveTimeStep()",
                ));
            }
            if t.starts_with("O.dt =") {
                if st.indent > 0 {
                    return Err(DeckError::unsupported(
                        s.at(st.line),
                        format!("`{t}` inside a block: the time step is set while the script runs"),
                        "O.dt = … at module level",
                    ));
                }
                let expr = super::python::expression(&st.tokens[4..], index);
                r.timestep = Some((expr, s.at(st.line)));
            }
        }
        // A sphere whose size is given on the command line needs none of its own.
        r.spheres.retain(|sp| !given.contains(&sp.material));
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
        let mut push = |t: u32, radius: f64, density: f64, from: String| {
            // The same size read twice is the same number, bit for bit.
            #[allow(clippy::float_cmp)]
            let known = bodies
                .iter()
                .any(|b| b.type_id == t && b.radius == radius && b.density == density);
            if !known {
                let (youngs_modulus, poisson_ratio) = elastic(&r.materials[t as usize]);
                bodies.push(DeckBody {
                    type_id: t,
                    radius,
                    density,
                    mass: sphere_mass(radius, density),
                    youngs_modulus,
                    poisson_ratio,
                    from,
                });
            }
        };
        for sp in &r.spheres {
            let m = &r.materials[sp.material as usize];
            let radius = sp.radius.clone().map_err(|e| {
                DeckError::unsupported(
                    &sp.at,
                    format!("the radius of this sphere: {e}"),
                    &format!(
                        "{LITERAL}; or give the size with --particle {}:RADIUS:DENSITY",
                        sp.material
                    ),
                )
            })?;
            if !(radius > 0.0 && radius.is_finite()) {
                return Err(DeckError::unsupported(
                    &sp.at,
                    format!("sphere radius {radius}"),
                    "a positive radius, m",
                ));
            }
            let label = m.label().map_or(String::new(), |l| format!("{l}, "));
            push(
                sp.material,
                radius,
                m.value("density"),
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
            push(p.type_id, p.radius, p.density, format!("{label}--particle"));
        }
        if bodies.is_empty() {
            return Err(DeckError::Lacking { file: path.to_path_buf(), what: "no sphere of known size (no sphere(center, radius, …) call with a literal radius)".into(), supported: "give the sizes with --particle TYPE:RADIUS:DENSITY, TYPE the material's O.materials id".into() });
        }
        Ok(bodies)
    }
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

/// The pair's law, entered COR, model name and traps.
struct PairLaw {
    law: DashpotLaw,
    entered: Option<f64>,
    model: String,
    traps: Vec<String>,
}

impl YadeDeck {
    /// The `Ip2` functor YADE's dispatcher picks for two material classes, and its `Law2`.
    fn functors_for<'a>(
        r: &'a Reading,
        a: Class,
        b: Class,
        at: &SourceLine,
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
                        "{} and {} (line {}) both take FrictMat pairs",
                        g.class, f.class, f.at.line
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
            .params
            .iter()
            .map(|(k, _)| k.as_str())
            .filter(|k| {
                matches!(
                    *k,
                    "es" | "betas" | "eta" | "krot" | "ktwist" | "frictAngle" | "ks" | "et"
                )
            })
            .collect();
        let wall_radius_trap = |traps: &mut Vec<String>, model: &str| {
            let Some((kind, w)) = wall else { return };
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
        };
        let mut out = match ip2.class.as_str() {
            "Ip2_FrictMat_FrictMat_MindlinPhys" => {
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
                PairLaw {
                    law,
                    entered: en,
                    model: format!(
                        "Hertz–Mindlin{}",
                        if en.is_some() {
                            " en"
                        } else if betan.is_some() {
                            " betan"
                        } else {
                            ""
                        }
                    ),
                    traps,
                }
            }
            "Ip2_FrictMat_FrictMat_FrictPhys" => {
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
                PairLaw {
                    law,
                    entered: None,
                    model: "FrictPhys linear".into(),
                    traps,
                }
            }
            _ => Self::viscel_law(ip2, a, b, wall, mass)?,
        };
        if !ignored.is_empty() {
            out.traps.push(format!("{} of {} (tangential, rolling and friction settings) act on no head-on impact: kept, and they change nothing here", ignored.join(", "), ip2.class));
        }
        let model = out.model.clone();
        wall_radius_trap(&mut out.traps, &model);
        Ok(out)
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
                        "ViscElMat without {key}, met by the ViscElMat of line {} that has it (YADE stops: \"Both materials should have the same defined set of variables\")",
                        given.at.line
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
                Some((WallKind::Box, w)) => traps.push(format!("the fixed box's own mass ({:.4e} kg) enters the tuning: kn, cn are set for the reduced mass {mass_r:.6e} kg of the ball and the box, not for the ball's {mass:.6e} kg that moves ({:+.2e} relative)", w.mass.as_ref().map_or(f64::NAN, |m| *m), mass_r / mass - 1.0)),
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
        Ok(PairLaw {
            law,
            entered,
            model,
            traps,
        })
    }
}

impl DeckReader for YadeDeck {
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
        "YADE scripts (FrictMat/ViscElMat materials, InteractionLoop functors, O.dt, sphere/wall/facet/box calls)"
    }

    fn read(&self, path: &Path, options: &DeckOptions) -> Result<UserDeck, DeckError> {
        let source = std::fs::read_to_string(path).map_err(|source| DeckError::Read {
            path: path.to_path_buf(),
            source,
        })?;
        let module = Module::read(&source, &options.variables).map_err(|e| {
            DeckError::unsupported(
                &SourceLine {
                    file: path.to_path_buf(),
                    line: e.line,
                },
                e.what,
                "Python that scans: closed strings and brackets",
            )
        })?;
        let s = Script {
            path,
            module: &module,
        };
        let r = Self::gather(&s, options)?;
        let lacking = |what: &str, supported: &str| DeckError::Lacking {
            file: path.to_path_buf(),
            what: what.into(),
            supported: supported.into(),
        };
        let loop_at = r.loop_at.clone().ok_or_else(|| {
            lacking(
                "no InteractionLoop",
                "O.engines with InteractionLoop([Ig2…], [Ip2…], [Law2…])",
            )
        })?;
        if r.newton.is_none() {
            return Err(lacking(
                "no NewtonIntegrator in O.engines: nothing moves",
                "NewtonIntegrator(damping=0)",
            ));
        }
        for f in r.geometry.iter().chain(&r.physics).chain(&r.laws) {
            let known = [
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
            if !known.contains(&f.class.as_str()) {
                return Err(DeckError::unsupported(
                    &f.at,
                    format!("functor {}", f.class),
                    FUNCTORS,
                ));
            }
        }
        let mut bodies = Self::bodies(&r, path, options)?;
        bodies.sort_by(|a, b| {
            a.type_id
                .cmp(&b.type_id)
                .then(b.radius.total_cmp(&a.radius))
        });
        // The time step, with PWaveTimeStep() over the spheres made before it.
        let (dt_expr, dt_at) = r.timestep.clone().ok_or_else(|| {
            lacking(
                "no `O.dt = …` (YADE's default step is 1e-8 s)",
                "O.dt = NUMBER or O.dt = FACTOR * PWaveTimeStep()",
            )
        })?;
        let mut pwave: Option<(f64, String)> = None;
        let mut consider = |radius: f64, m: &Material, density: f64, from: String| {
            // In YADE's operations: utils.sphere's mass (4/3 π r³ ρ), the density Shop::PWaveTimeStep
            // forms back from it, and r / sqrt(E/ρ): the step to the last bit.
            let volume = 4.0 / 3.0 * PI * radius.powf(3.0);
            let density = volume * density / (4.0 / 3.0 * PI * radius.powf(3.0));
            let t = radius / (m.value("young") / density).sqrt();
            if pwave.as_ref().is_none_or(|(best, _)| t < *best) {
                pwave = Some((t, from));
            }
        };
        for sp in r.spheres.iter().filter(|sp| sp.at.line < dt_at.line) {
            if let Ok(radius) = sp.radius {
                let m = &r.materials[sp.material as usize];
                consider(
                    radius,
                    m,
                    m.value("density"),
                    format!("R {radius} at {}", sp.at),
                );
            }
        }
        for p in &options.particles {
            consider(
                p.radius,
                &r.materials[p.type_id as usize],
                p.density,
                format!("R {} of --particle {}", p.radius, p.type_id),
            );
        }
        let known = Knowledge {
            appended: &r.appended,
            pwave: pwave.as_ref().map(|p| p.0),
        };
        let timestep = s.number(&dt_expr, dt_at.line, &known, "O.dt")?;
        if !(timestep > 0.0 && timestep.is_finite()) {
            return Err(DeckError::unsupported(
                &dt_at,
                format!("O.dt = {timestep}"),
                "a positive time step, s",
            ));
        }
        let uses_pwave = show(&dt_expr).contains("PWaveTimeStep");
        let timestep_from = match &pwave {
            Some((t, from)) if uses_pwave => {
                let viscel_default = r
                    .materials
                    .iter()
                    .any(|m| m.class == Class::ViscEl && m.get("young").is_none());
                format!(
                    "{dt_at}, {}; PWaveTimeStep() = {} s, R/sqrt(E/ρ) of the sphere of {from}{}",
                    show(&dt_expr),
                    exact_number(*t),
                    if viscel_default {
                        "; a ViscElMat's young there is its default 1e9 Pa, which its tc or kn do not use"
                    } else {
                        ""
                    }
                )
            }
            _ => dt_at.to_string(),
        };
        // Contacts: each pair of bodies, then each body against each wall.
        let geometry_for = |names: [&str; 2], at: &SourceLine| {
            r.geometry.iter().find(|f| names.contains(&f.class.as_str())).ok_or_else(|| {
                DeckError::unsupported(at, format!("no {} in the InteractionLoop (line {}): YADE would make no contact here", names[0], loop_at.line), FUNCTORS)
            })
        };
        let mut contacts = Vec::new();
        for (i, body) in bodies.iter().enumerate() {
            for (j, other) in bodies.iter().enumerate().skip(i) {
                let m_a = &r.materials[body.type_id as usize];
                let m_b = &r.materials[other.type_id as usize];
                let geometry = geometry_for(
                    ["Ig2_Sphere_Sphere_ScGeom", "Ig2_Sphere_Sphere_ScGeom6D"],
                    &loop_at,
                )?;
                let a = Side {
                    id: body.type_id,
                    material: m_a,
                    radius: body.radius,
                    mass: body.mass,
                };
                let b = Side {
                    id: other.type_id,
                    material: m_b,
                    radius: other.radius,
                    mass: other.mass,
                };
                let pair = Self::pair_law(
                    &r,
                    &a,
                    &b,
                    None,
                    reduced_mass(body.mass, other.mass),
                    geometry,
                )?;
                let mut lines = vec![m_a.at.clone(), m_b.at.clone(), loop_at.clone()];
                lines.dedup();
                contacts.push(DeckContact {
                    body: i,
                    partner: Partner::Body(j),
                    types: [TypeRef::Type(body.type_id), TypeRef::Type(other.type_id)],
                    model: pair.model,
                    cor_entered: pair.entered,
                    law: pair.law,
                    traps: pair.traps,
                    lines: lines.into_iter().map(DeckSource::from).collect(),
                });
            }
        }
        let mut walls = Vec::new();
        let mut wall_lines = Vec::new();
        for (w, wall) in r.walls.iter().enumerate() {
            let m_w = &r.materials[wall.material as usize];
            let geometry = geometry_for(wall.kind.geometry(), &wall.at)?;
            let factor = match wall.kind {
                WallKind::Plane | WallKind::Facet if geometry.flag("hertzian") => {
                    HERTZIAN_WALL_RADIUS_FACTOR
                }
                WallKind::Facet => 2.0,
                _ => 1.0,
            };
            let (young, poisson) = match m_w.class {
                Class::ViscEl if m_w.get("kn").is_some() || m_w.get("tc").is_some() => (None, None),
                _ => (Some(m_w.value("young")), Some(m_w.value("poisson"))),
            };
            walls.push(DeckWall {
                name: wall.name.clone(),
                type_id: Some(wall.material),
                youngs_modulus: young,
                poisson_ratio: poisson,
                from: wall.at.clone().into(),
            });
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
                    wall.mass.as_ref().ok().copied(),
                ),
            };
            let mut snippet = format!("b2 = O.bodies.append({placement})");
            if let Some(m) = mass {
                snippet.push_str(&format!("\nO.bodies[b2].state.mass = {}  # the script's box: its extents times its density", exact_number(m)));
            }
            wall_lines.push(snippet);
            for (i, body) in bodies.iter().enumerate() {
                let m_a = &r.materials[body.type_id as usize];
                let needs_mass = m_w.class == Class::ViscEl && m_a.class == Class::ViscEl;
                let wall_mass = match (&wall.mass, needs_mass) {
                    (Ok(m), _) => *m,
                    (Err(_), false) => 0.0,
                    (Err(e), true) => {
                        return Err(DeckError::unsupported(
                            &wall.at,
                            format!("a fixed box whose mass ViscElPhys's tuning needs: {e}"),
                            "literal extents",
                        ));
                    }
                };
                let a = Side {
                    id: body.type_id,
                    material: m_a,
                    radius: body.radius,
                    mass: body.mass,
                };
                let b = Side {
                    id: wall.material,
                    material: m_w,
                    radius: factor * body.radius,
                    mass: wall_mass,
                };
                let pair =
                    Self::pair_law(&r, &a, &b, Some((wall.kind, wall)), body.mass, geometry)?;
                let mut traps = pair.traps;
                if wall.lines.len() > 1 {
                    traps.push(format!(
                        "{} bodies of this kind and material (lines {}) are one wall here",
                        wall.lines.len(),
                        wall.lines
                            .iter()
                            .map(usize::to_string)
                            .collect::<Vec<_>>()
                            .join(", ")
                    ));
                }
                contacts.push(DeckContact {
                    body: i,
                    partner: Partner::Wall(w),
                    types: [TypeRef::Type(body.type_id), TypeRef::Wall],
                    model: pair.model,
                    cor_entered: pair.entered,
                    law: pair.law,
                    traps,
                    lines: [&m_a.at, &wall.at, &loop_at]
                        .into_iter()
                        .map(DeckSource::from)
                        .collect(),
                });
            }
        }
        let left_out = r
            .left_out
            .iter()
            .map(|(what, lines)| {
                let lines: Vec<String> = lines.iter().map(usize::to_string).collect();
                format!("{what}: {}:{}", path.display(), lines.join(","))
            })
            .collect();
        let mut common: Vec<String> = r
            .materials
            .iter()
            .map(|m| format!("O.materials.append({})", m.python()))
            .collect();
        for (name, list) in [("IG2", &r.geometry), ("IP2", &r.physics), ("LAW2", &r.laws)] {
            let items: Vec<String> = list.iter().map(Functor::python).collect();
            common.push(format!("{name} = [{}]", items.join(", ")));
        }
        Ok(UserDeck {
            path: path.to_path_buf(),
            timestep,
            timestep_from,
            bodies,
            walls,
            contacts,
            representative_velocity: None,
            left_out,
            transplant: Transplant {
                before_box: Vec::new(),
                common,
                walls: wall_lines,
                types: u32::try_from(r.materials.len()).unwrap_or(u32::MAX),
            },
        })
    }

    fn render(
        &self,
        deck: &UserDeck,
        contact: usize,
        velocity: f64,
        steps: u64,
    ) -> Result<DeckImpactInput, CodeError> {
        let c = &deck.contacts[contact];
        let body = &deck.bodies[c.body];
        let sphere = |b: &DeckBody| CodeSphere {
            radius: b.radius,
            density: b.density,
            mass: b.mass,
            youngs_modulus: b.youngs_modulus.unwrap_or(f64::NAN),
            poisson_ratio: b.poisson_ratio,
        };
        let (scene, other) = match c.partner {
            Partner::Body(o) => (SceneKind::BallBall, Some(&deck.bodies[o])),
            Partner::Wall(_) => (SceneKind::BallPlate, None),
        };
        let mut setup = CodeSetup {
            case_name: format!("deck-{contact}-{}-{}", c.types[0], c.types[1]),
            scene,
            sphere: sphere(body),
            other_sphere: other.map(sphere),
            plate_material: None,
            effective_modulus: None,
            effective_radius: None,
            reduced_mass: c.law.mass,
            stiffness: c.law.stiffness,
            exponent: c.law.exponent,
            impact_velocity: velocity,
            target_restitution: c.cor_entered.unwrap_or(f64::NAN),
            loss_coefficient: None,
            timestep: deck.timestep,
            steps,
            clamp_attractive: c.law.clamp_attractive,
            conventions: None,
        };
        setup.effective_radius = Some(setup.pair_radius());
        let (v1, v2) = setup.centre_of_mass_velocities();
        // The script starts the bodies one ulp apart (YADE's laws act at zero overlap).
        let next_up = |x: f64| f64::from_bits(x.to_bits() + 1);
        let (placement, gap) = match c.partner {
            Partner::Body(o) => {
                let reach = body.radius + deck.bodies[o].radius;
                (String::new(), next_up(reach) - reach)
            }
            Partner::Wall(w) => (
                deck.transplant.walls[w].clone(),
                next_up(body.radius) - body.radius,
            ),
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
            ("speed", velocity.to_string()),
            (
                "scene",
                if other.is_some() { "ball_ball" } else { "wall" }.to_string(),
            ),
            ("timestep", exact_number(deck.timestep)),
            ("steps", steps.to_string()),
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
            case: setup.case_name.clone(),
            reason: e.to_string(),
        })?;
        Ok(DeckImpactInput {
            input: RenderedInput {
                file_name: SCRIPT.into(),
                text,
                args: ["-j1", "-n", "-x", SCRIPT].map(String::from).to_vec(),
            },
            setup,
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
