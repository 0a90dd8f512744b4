//! A LAMMPS user's deck (`millimpact deck`): `pair_style granular` with its `pair_coeff` lines,
//! `fix wall/gran granular` (and `wall/gran/region`), `timestep`, particles from `create_atoms`
//! and `set … diameter … density|mass`, read through `include`s and variables; and the impact of
//! one pair rendered with those lines transplanted, the wall made the plane `zplane 0 NULL`.
//!
//! The law each line makes a build integrate follows that build's conventions as its probe
//! measured them ([`super::probe`]): the wall's effective modulus, what `damping tsuji` applies
//! (the √2), whether `damping coeff_restitution` exists, whether touching is contact;
//! `reference/lammps/CONVENTIONS.md` has the measurements.

use std::collections::{BTreeMap, HashMap};
use std::path::Path;

use super::conventions::{Conventions, WallModulus, exact_hertz_alpha};
use super::{Build, INPUT_FILE, LOG_FILE, TRAJECTORY_FILE};
use crate::codes::deck::{
    DeckBody, DeckContact, DeckError, DeckImpactInput, DeckOptions, DeckReader, DeckWall,
    Partner, SourceLine, Transplant, TypeRef, UserDeck, sphere_mass,
};
use crate::codes::script::{Command, ScriptReader};
use crate::codes::template::exact_number;
use crate::codes::{CodeDriver, CodeError, CodeSetup, CodeSphere, RenderedInput};
use crate::model::law::DashpotLaw;
use crate::model::scene::{SceneKind, pair_radius, reduced_mass};

/// The deck reader of one LAMMPS build, with the driver that probes it.
pub struct LammpsDeck(pub &'static Build, pub &'static dyn CodeDriver);

/// A `pair_coeff` or `fix wall/gran granular` contact model as read.
#[derive(Clone, Debug, PartialEq)]
struct GranularModel {
    normal: String,
    /// `k` (hooke, hertz) or `E` (hertz/material), and `d`, and `ν` (hertz/material).
    values: Vec<f64>,
    damping: String,
    limit_damping: bool,
    tangential: String,
    /// The model's words as written (the transplanted line keeps them).
    words: Vec<String>,
}

const NORMAL: &str = "hooke k d, hertz k d, hertz/material E d nu";
const DAMPING: &str = "damping velocity, mass_velocity, viscoelastic, tsuji, coeff_restitution (a build from 2023 on)";

/// Read a granular model from `words[start..]`, up to the first word of `stop` (a wall style).
fn read_model(c: &Command, start: usize, stop: &[&str]) -> Result<(GranularModel, usize), DeckError> {
    let normal = c.word(start, "a normal model")?.to_string();
    let n = match normal.as_str() {
        "hooke" | "hertz" => 2,
        "hertz/material" => 3,
        other => {
            return Err(DeckError::unsupported(&c.at, format!("normal model `{other}`"), NORMAL));
        }
    };
    let values = (start + 1..start + 1 + n).map(|k| c.number(k, &normal)).collect::<Result<Vec<_>, _>>()?;
    let mut model = GranularModel {
        normal,
        values,
        damping: "viscoelastic".into(),
        limit_damping: false,
        tangential: String::new(),
        words: Vec::new(),
    };
    let mut k = start + 1 + n;
    while let Some(word) = c.words.get(k) {
        if stop.contains(&word.as_str()) {
            break;
        }
        match word.as_str() {
            "damping" => {
                model.damping = c.word(k + 1, "a damping model")?.to_string();
                k += 2;
            }
            "limit_damping" => {
                model.limit_damping = true;
                k += 1;
            }
            "tangential" | "rolling" | "twisting" => {
                let style = c.word(k + 1, word)?.to_string();
                let args = match (word.as_str(), style.as_str()) {
                    ("tangential", "linear_nohistory") => 2,
                    ("tangential", _) => 3,
                    ("rolling", "sds") => 3,
                    ("twisting", "marshall") => 0,
                    ("twisting", "sds") => 3,
                    _ => 0,
                };
                if word == "tangential" {
                    model.tangential = style.clone();
                }
                k += 2 + args;
            }
            "heat" | "synchronized_verlet" => k += 2,
            other => {
                return Err(DeckError::unsupported(
                    &c.at,
                    format!("`{other}` in a granular model"),
                    &format!("{NORMAL}; {DAMPING}; tangential, rolling, twisting; limit_damping"),
                ));
            }
        }
    }
    let known = ["velocity", "mass_velocity", "viscoelastic", "tsuji", "coeff_restitution"];
    if !known.contains(&model.damping.as_str()) {
        return Err(DeckError::unsupported(&c.at, format!("damping {}", model.damping), DAMPING));
    }
    model.words = c.words[start..k].to_vec();
    Ok((model, k))
}

/// A wall fix as read.
#[derive(Clone, Debug)]
struct WallFix {
    id: String,
    group: String,
    model: GranularModel,
    at: SourceLine,
    geometry: String,
}

#[derive(Default)]
struct Reading {
    units: Option<Command>,
    atom_style: Option<Command>,
    types: Option<u32>,
    pair: Option<Command>,
    coeffs: Vec<(String, String, GranularModel, Command)>,
    walls: Vec<WallFix>,
    atoms_of_type: BTreeMap<u32, SourceLine>,
    atom_types: Vec<u32>,
    set_type: HashMap<u32, [Option<f64>; 3]>,
    set_atom: HashMap<usize, [Option<f64>; 3]>,
    timestep: Option<(f64, SourceLine)>,
    left_out: BTreeMap<String, (std::path::PathBuf, Vec<usize>)>,
}

impl Reading {
    fn leave_out(&mut self, what: &str, c: &Command) {
        self.left_out
            .entry(what.to_string())
            .or_insert_with(|| (c.at.file.clone(), Vec::new()))
            .1
            .push(c.at.line);
    }
}

fn whole(x: f64, c: &Command, what: &str) -> Result<u32, DeckError> {
    if x >= 1.0 && x.fract() == 0.0 && x <= f64::from(u32::MAX) {
        // A positive whole number below u32::MAX: the conversion is exact.
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        Ok(x as u32)
    } else {
        Err(DeckError::unsupported(&c.at, format!("{what} `{x}`"), "a whole number from 1"))
    }
}

/// Whether pair_coeff's `I`/`J` (a number or `*`, `n*`, `*n`, `m*n`) covers type `t`.
fn covers(range: &str, t: u32, types: u32) -> bool {
    let parse = |s: &str, default: u32| if s.is_empty() { Some(default) } else { s.parse().ok() };
    match range.split_once('*') {
        None => range.parse::<u32>().is_ok_and(|x| x == t),
        Some((lo, hi)) => match (parse(lo, 1), parse(hi, types)) {
            (Some(lo), Some(hi)) => (lo..=hi).contains(&t),
            _ => false,
        },
    }
}

impl LammpsDeck {
    fn gather(path: &Path, options: &DeckOptions) -> Result<Reading, DeckError> {
        let commands = ScriptReader::read(path, &options.variables)?;
        let mut r = Reading::default();
        for c in &commands {
            match c.name() {
                "units" => r.units = Some(c.clone()),
                "atom_style" => r.atom_style = Some(c.clone()),
                "create_box" => r.types = Some(whole(c.number(1, "the number of atom types")?, c, "create_box")?),
                "timestep" => r.timestep = Some((c.number(1, "the time step")?, c.at.clone())),
                "pair_style" => {
                    if c.word(1, "a pair style")? != "granular" {
                        return Err(DeckError::unsupported(&c.at, format!("pair_style {}", c.words[1]), "pair_style granular"));
                    }
                    r.pair = Some(c.clone());
                }
                "pair_coeff" => {
                    let (model, k) = read_model(c, 3, &[])?;
                    if k != c.words.len() {
                        return Err(DeckError::unsupported(&c.at, format!("`{}`", c.text), "pair_coeff I J MODEL …"));
                    }
                    r.coeffs.push((c.words[1].clone(), c.words[2].clone(), model, c.clone()));
                }
                "fix" => match c.word(3, "the fix style")? {
                    "wall/gran" | "wall/gran/region" => {
                        if c.word(4, "granular")? != "granular" {
                            return Err(DeckError::unsupported(&c.at, format!("fix {} {}", c.words[3], c.words[4]), "fix ID group wall/gran granular MODEL … WALLSTYLE ARGS"));
                        }
                        let stops = ["xplane", "yplane", "zplane", "zcylinder", "region"];
                        let (model, k) = read_model(c, 5, &stops)?;
                        if k >= c.words.len() {
                            return Err(DeckError::unsupported(&c.at, "a wall without its style".into(), "xplane, yplane, zplane, zcylinder, region"));
                        }
                        r.walls.push(WallFix {
                            id: c.words[1].clone(),
                            group: c.words[2].clone(),
                            model,
                            at: c.at.clone(),
                            geometry: c.words[k..].join(" "),
                        });
                    }
                    "nve/sphere" => r.leave_out("the integrator (the impact runs fix nve/sphere, as the deck)", c),
                    "nve" | "nve/limit" | "nvt/sphere" | "nve/asphere" | "rigid" | "rigid/small" => {
                        return Err(DeckError::unsupported(&c.at, format!("fix {}: an integrator whose step the harness does not model", c.words[3]), "fix nve/sphere"));
                    }
                    "gravity" => r.leave_out("gravity (the impact is a free normal impact)", c),
                    "pour" | "deposit" => r.leave_out("particle insertion (give the sizes with --particle TYPE:RADIUS:DENSITY)", c),
                    _ => r.leave_out("other fixes (no part of a contact)", c),
                },
                "create_atoms" => {
                    let t = whole(c.number(1, "the atom type")?, c, "type")?;
                    r.atoms_of_type.entry(t).or_insert_with(|| c.at.clone());
                    if c.words.get(2).is_some_and(|w| w == "single") {
                        r.atom_types.push(t);
                    }
                }
                "set" => {
                    let pick = |key: &str| -> Result<Option<f64>, DeckError> {
                        match c.words.iter().position(|w| w == key) {
                            Some(k) => c.number(k + 1, key).map(Some),
                            None => Ok(None),
                        }
                    };
                    let values = [pick("diameter")?, pick("density")?, pick("mass")?];
                    let merge = |slot: &mut [Option<f64>; 3]| {
                        for (s, v) in slot.iter_mut().zip(values) {
                            *s = v.or(*s);
                        }
                    };
                    match c.word(1, "atom or type")? {
                        "type" => merge(r.set_type.entry(whole(c.number(2, "the type")?, c, "type")?).or_default()),
                        "atom" => merge(r.set_atom.entry(whole(c.number(2, "the atom id")?, c, "atom")? as usize).or_default()),
                        _ => r.leave_out("set commands on groups or regions", c),
                    }
                }
                "region" | "lattice" => r.leave_out("regions (the geometry)", c),
                "read_data" | "read_restart" | "read_dump" => r.leave_out("particles read from a file (give their sizes with --particle TYPE:RADIUS:DENSITY)", c),
                "neighbor" | "neigh_modify" | "comm_modify" | "comm_style" | "newton" | "processors" | "boundary" | "atom_modify" | "dimension" => {
                    r.leave_out("neighbour lists, communication and domain settings (the impact sets its own)", c)
                }
                "dump" | "dump_modify" | "undump" | "thermo" | "thermo_style" | "thermo_modify" | "compute" | "compute_modify" | "uncompute" | "print" | "write_restart" | "restart" | "write_data" | "write_dump" | "echo" | "log" | "shell" | "label" | "jump" | "next" | "if" | "clear" | "quit" | "info" => {
                    r.leave_out("output and control", c)
                }
                "run" | "rerun" | "minimize" => r.leave_out("the run itself", c),
                "unfix" | "group" | "velocity" | "delete_atoms" | "displace_atoms" | "change_box" | "reset_timestep" | "run_style" | "mass" | "pair_modify" | "special_bonds" => {
                    r.leave_out("other settings", c)
                }
                other => {
                    return Err(DeckError::unsupported(
                        &c.at,
                        format!("command `{other}`"),
                        "the LAMMPS commands of a granular deck (units, atom_style, create_box, region, pair_style granular, pair_coeff, fix, timestep, create_atoms, set, include, variable, output and run commands)",
                    ));
                }
            }
        }
        Ok(r)
    }

    fn bodies(r: &Reading, path: &Path, options: &DeckOptions) -> Result<Vec<DeckBody>, DeckError> {
        let mut bodies: Vec<DeckBody> = Vec::new();
        if let Some(p) = options.particles.iter().find(|p| p.type_id == 0) {
            return Err(DeckError::Lacking { file: path.to_path_buf(), what: format!("--particle {}:{}:{}: atom types count from 1", p.type_id, p.radius, p.density), supported: "--particle TYPE:RADIUS:DENSITY with TYPE an atom type of the deck".into() });
        }
        let given: Vec<u32> = options.particles.iter().map(|p| p.type_id).collect();
        let mut push = |t: u32, radius: f64, density: f64, from: String| {
            // The same size read twice is the same number, bit for bit.
            #[allow(clippy::float_cmp)]
            let known = bodies.iter().any(|b| b.type_id == t && b.radius == radius && b.density == density);
            if !known {
                bodies.push(DeckBody { type_id: t, radius, density, mass: sphere_mass(radius, density), youngs_modulus: None, poisson_ratio: None, from });
            }
        };
        for (t, at) in &r.atoms_of_type {
            if given.contains(t) {
                continue;
            }
            let of_type = r.set_type.get(t).copied().unwrap_or_default();
            let mut found = false;
            let size = |own: [Option<f64>; 3]| -> Option<(f64, f64)> {
                let d = own[0].or(of_type[0])?;
                let r = d / 2.0;
                let density = own[1].or(of_type[1]).or_else(|| own[2].or(of_type[2]).map(|m| m / sphere_mass(r, 1.0)))?;
                Some((r, density))
            };
            for (index, atom_type) in r.atom_types.iter().enumerate() {
                if atom_type == t
                    && let Some((radius, density)) = size(r.set_atom.get(&(index + 1)).copied().unwrap_or_default())
                {
                    push(*t, radius, density, format!("atom {} ({at})", index + 1));
                    found = true;
                }
            }
            if !found {
                let (radius, density) = size([None; 3]).ok_or_else(|| {
                    DeckError::unsupported(at, format!("atoms of type {t} are created without a diameter and density (or mass) set for them"), &format!("`set type {t} diameter D density RHO`, or --particle {t}:RADIUS:DENSITY"))
                })?;
                push(*t, radius, density, format!("set type {t} ({at})"));
            }
        }
        for p in &options.particles {
            push(p.type_id, p.radius, p.density, format!("--particle {}:{}:{}", p.type_id, p.radius, p.density));
        }
        if bodies.is_empty() {
            return Err(DeckError::Lacking {
                file: path.to_path_buf(),
                what: "no particle sizes (no create_atoms with set diameter and density)".into(),
                supported: "give them with --particle TYPE:RADIUS:DENSITY".into(),
            });
        }
        Ok(bodies)
    }

    /// The law `model` makes the build integrate between a particle (radius, mass) and a
    /// partner (`Some((radius, mass))`, or `None` for a wall), with its entered COR and traps.
    fn law(&self, conventions: &Conventions, model: &GranularModel, (radius, mass): (f64, f64), partner: Option<(f64, f64)>, at: &SourceLine) -> Result<(DashpotLaw, Option<f64>, Vec<String>), DeckError> {
        let r_star = partner.map_or(radius, |(r2, _)| pair_radius(radius, r2));
        let m_star = partner.map_or(mass, |(_, m2)| reduced_mass(mass, m2));
        let mut traps = Vec::new();
        let v = &model.values;
        let d = v[1];
        let (stiffness, exponent) = match model.normal.as_str() {
            "hooke" => (v[0], 1.0),
            "hertz" => (v[0] * r_star.sqrt(), 1.5),
            _ => {
                let (e, nu) = (v[0], v[2]);
                let e_star = match (partner, conventions.wall_modulus) {
                    (Some(_), _) | (None, WallModulus::HalfOverOneMinusNuSquared) => e / (2.0 * (1.0 - nu * nu)),
                    (None, WallModulus::HalfOverOneMinusNu) => {
                        traps.push(format!("wall modulus: in this build fix wall/gran hertz/material reads E* = E/(2(1−ν)) = {:.4e} Pa, not E/(2(1−ν²)) = {:.4e} Pa (the particle's material on both sides): {:+.1} % stiffer", e / (2.0 * (1.0 - nu)), e / (2.0 * (1.0 - nu * nu)), 100.0 * nu));
                        e / (2.0 * (1.0 - nu))
                    }
                };
                if partner.is_none() {
                    traps.push(format!("wall modulus: the wall's E and ν are the particle's material on both sides (E* = {e_star:.4e} Pa): a wall meant rigid or of another material needs another E"));
                }
                (4.0 / 3.0 * e_star * r_star.sqrt(), 1.5)
            }
        };
        let hertz = exponent > 1.0;
        let (damping, damping_exponent, entered) = match model.damping.as_str() {
            "velocity" => (d, 0.0, None),
            "mass_velocity" => (d * m_star, 0.0, None),
            "viscoelastic" => (d * m_star * r_star.sqrt(), 0.5, None),
            "tsuji" => {
                let alpha = conventions.tsuji_fit.alpha(d);
                let exact = exact_hertz_alpha(d);
                traps.push(format!(
                    "damping tsuji takes e_in, not e: this build applies α = {alpha:.6} for e_in = {d}, where the law that realises e = {d} needs √5 β(e) = {exact:.6}{}",
                    if conventions.tsuji_fit.factor() > 1.0 { "" } else { " (the fit is √2 short: the COR comes out higher)" }
                ));
                (alpha * (m_star * stiffness).sqrt(), if hertz { 0.25 } else { 0.0 }, Some(d))
            }
            _ => {
                if !conventions.coeff_restitution {
                    return Err(DeckError::unsupported(at, "damping coeff_restitution: this build (probed) has none".into(), "damping velocity, mass_velocity, viscoelastic, tsuji in this build; --code lammps-2025 has coeff_restitution"));
                }
                if !(d > 0.0 && d <= 1.0) {
                    return Err(DeckError::unsupported(at, format!("damping coeff_restitution with e = {d}"), "0 < e <= 1 (the build runs e = 0 as NaN and e > 1 as energy gain without a word)"));
                }
                if hertz {
                    (exact_hertz_alpha(d) * (m_star * stiffness).sqrt(), 0.25, Some(d))
                } else {
                    (DashpotLaw::linear(m_star, stiffness, d).damping, 0.0, Some(d))
                }
            }
        };
        let mut law = DashpotLaw { mass: m_star, stiffness, exponent, damping, damping_exponent, clamp_attractive: false };
        if model.limit_damping {
            traps.push("limit_damping: the attractive tail at the end of contact is cut, and the COR rises (Schwager & Pöschel; 0.5 → 0.550)".into());
            law = law.clamped();
        }
        if !model.tangential.is_empty() {
            traps.push(format!("tangential {} acts on no head-on impact: kept, and it changes nothing here", model.tangential));
        }
        Ok((law, entered, traps))
    }
}

impl DeckReader for LammpsDeck {
    fn recognises(&self, _path: &Path, text: &str) -> bool {
        text.lines().any(|l| {
            let w: Vec<&str> = l.split_whitespace().collect();
            matches!(w.as_slice(), ["pair_style", "granular", ..])
                || (w.first() == Some(&"fix") && w.get(3).is_some_and(|s| s.starts_with("wall/gran")) && w.get(4) == Some(&"granular"))
        })
    }

    fn reads(&self) -> &'static str {
        "LAMMPS inputs (pair_style granular, fix wall/gran granular)"
    }

    fn read(&self, path: &Path, options: &DeckOptions) -> Result<UserDeck, DeckError> {
        let r = Self::gather(path, options)?;
        let lacking = |what: &str, supported: &str| DeckError::Lacking { file: path.to_path_buf(), what: what.into(), supported: supported.into() };
        match &r.units {
            Some(c) if c.words.get(1).is_some_and(|u| u == "si") => {}
            Some(c) => return Err(DeckError::unsupported(&c.at, format!("units {}", c.words.get(1).map_or("", String::as_str)), "units si")),
            None => return Err(lacking("no `units` line (LAMMPS's default is lj)", "units si")),
        }
        let types = r.types.ok_or_else(|| lacking("no create_box (the number of atom types)", "create_box N REGION"))?;
        let (timestep, timestep_at) = r.timestep.clone().ok_or_else(|| lacking("no timestep", "timestep DT (s)"))?;
        if timestep.is_nan() || timestep <= 0.0 {
            return Err(DeckError::unsupported(&timestep_at, format!("timestep {timestep}"), "a positive time step, s"));
        }
        // The conventions of the build that will run it: its probe, else its fallback.
        let conventions = self.1.measured_conventions().ok().flatten().unwrap_or(self.0.fallback);
        let mut bodies = Self::bodies(&r, path, options)?;
        let coeff_for = |i: u32, j: u32| {
            r.coeffs.iter().rev().find(|(a, b, _, _)| (covers(a, i, types) && covers(b, j, types)) || (covers(a, j, types) && covers(b, i, types)))
        };
        // A type's material, where its own pair_coeff gives one (hertz/material E d ν).
        for b in &mut bodies {
            if let Some((_, _, m, _)) = coeff_for(b.type_id, b.type_id).filter(|(_, _, m, _)| m.normal == "hertz/material") {
                b.youngs_modulus = Some(m.values[0]);
                b.poisson_ratio = Some(m.values[2]);
            }
        }
        let mut contacts = Vec::new();
        for (a, body) in bodies.iter().enumerate() {
            for (b, other) in bodies.iter().enumerate().skip(a) {
                let (_, _, model, c) = coeff_for(body.type_id, other.type_id).ok_or_else(|| {
                    lacking(&format!("no pair_coeff covers the types {} and {}", body.type_id, other.type_id), "a pair_coeff for every pair of types in use, or * * (LAMMPS would mix the pair from I I and J J; the check does not)")
                })?;
                let (law, entered, traps) = self.law(&conventions, model, (body.radius, body.mass), Some((other.radius, other.mass)), &c.at)?;
                contacts.push(DeckContact { body: a, partner: Partner::Body(b), types: [TypeRef::Type(body.type_id), TypeRef::Type(other.type_id)], model: format!("{} damping {}", model.normal, model.damping), cor_entered: entered, law, traps, lines: vec![c.at.clone().into()] });
            }
        }
        let mut walls = Vec::new();
        let mut wall_lines = Vec::new();
        for (w, wall) in r.walls.iter().enumerate() {
            walls.push(DeckWall { name: wall.id.clone(), type_id: None, youngs_modulus: None, poisson_ratio: None, from: wall.at.clone().into() });
            wall_lines.push(format!("fix {} {} wall/gran granular {} zplane 0 NULL", wall.id, wall.group, wall.model.words.join(" ")));
            for (a, body) in bodies.iter().enumerate() {
                let (law, entered, mut traps) = self.law(&conventions, &wall.model, (body.radius, body.mass), None, &wall.at)?;
                traps.push(format!("wall: `{}` met as the plane zplane 0 NULL (R* = R at a flat wall)", wall.geometry));
                contacts.push(DeckContact { body: a, partner: Partner::Wall(w), types: [TypeRef::Type(body.type_id), TypeRef::Wall], model: format!("{} damping {}", wall.model.normal, wall.model.damping), cor_entered: entered, law, traps, lines: vec![wall.at.clone().into()] });
            }
        }
        let left_out = r.left_out.iter().map(|(what, (file, lines))| {
            let lines: Vec<String> = lines.iter().map(usize::to_string).collect();
            format!("{what}: {}:{}", file.display(), lines.join(","))
        }).collect();
        let mut common = Vec::new();
        if let Some(c) = &r.pair {
            common.push(c.text.clone());
        }
        common.extend(r.coeffs.iter().map(|x| x.3.text.clone()));
        Ok(UserDeck {
            path: path.to_path_buf(),
            timestep,
            timestep_from: timestep_at.to_string(),
            bodies,
            walls,
            contacts,
            representative_velocity: None,
            left_out,
            transplant: Transplant { before_box: r.atom_style.iter().map(|c| c.text.clone()).collect(), common, walls: wall_lines, types },
        })
    }

    fn render(&self, deck: &UserDeck, contact: usize, velocity: f64, steps: u64) -> Result<DeckImpactInput, CodeError> {
        let c = &deck.contacts[contact];
        let body = &deck.bodies[c.body];
        let sphere = |b: &DeckBody| CodeSphere { radius: b.radius, density: b.density, mass: b.mass, youngs_modulus: f64::NAN, poisson_ratio: None };
        let (scene, other) = match c.partner {
            Partner::Body(o) => (SceneKind::BallBall, Some(&deck.bodies[o])),
            Partner::Wall(_) => (SceneKind::BallPlate, None),
        };
        let conventions = self.1.measured_conventions().ok().flatten();
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
            conventions,
        };
        setup.effective_radius = Some(setup.pair_radius());
        // A build that counts touching as contact starts a hair before touch, as its driver does.
        let gap = self.0.start_gap(&setup);
        let (v1, v2) = setup.centre_of_mass_velocities();
        let t = |x: TypeRef| match x {
            TypeRef::Type(t) => t,
            TypeRef::Wall => 1,
        };
        let r1 = body.radius;
        let reach = r1 + other.map_or(0.0, |o| o.radius);
        let h = exact_number(4.0 * reach + velocity * setup.duration() + gap);
        let mut lines = vec![
            "# millimpact deck: one normal impact with the contact lines of a user's deck (its time step;".to_string(),
            format!("# its lines between the markers, variables substituted). {} at {velocity} m/s, {}.", format_args!("{} on {}", c.types[0], c.types[1]), deck.path.display()),
            "units           si".into(),
        ];
        lines.extend(deck.transplant.before_box.iter().cloned());
        if deck.transplant.before_box.is_empty() {
            lines.push("atom_style      sphere".into());
        }
        lines.extend([
            "atom_modify     map array".to_string(),
            "dimension       3".into(),
            "boundary        f f f".into(),
            "comm_modify     vel yes".into(),
            format!("region          box block -{h} {h} -{h} {h} -{h} {h} units box"),
            format!("create_box      {} box", deck.transplant.types),
        ]);
        let (overlap, approach, force) = match other {
            Some(o) => {
                lines.push(format!("create_atoms    {} single {} 0 0 units box", t(c.types[0]), exact_number(-r1 - gap)));
                lines.push(format!("create_atoms    {} single {} 0 0 units box", t(c.types[1]), exact_number(o.radius)));
                for (id, b, v) in [(1, body, v1), (2, o, v2)] {
                    lines.push(format!("set             atom {id} diameter {} density {} vx {}", exact_number(2.0 * b.radius), exact_number(b.density), exact_number(v)));
                }
                (format!("({})-(x[2]-x[1])", exact_number(r1 + o.radius)), "vx[1]-vx[2]".to_string(), "fx[2]".to_string())
            }
            None => {
                lines.push(format!("create_atoms    {} single 0 0 {} units box", t(c.types[0]), exact_number(r1 + gap)));
                lines.push(format!("set             atom 1 diameter {} density {} vz {}", exact_number(2.0 * r1), exact_number(body.density), exact_number(-v1)));
                (format!("({})-z[1]", exact_number(r1)), "-vz[1]".to_string(), "fz[1]".to_string())
            }
        };
        lines.push("# --- the deck's lines ---".into());
        lines.extend(deck.transplant.common.iter().cloned());
        if let Partner::Wall(w) = c.partner {
            lines.push(deck.transplant.walls[w].clone());
        }
        lines.push("# --- end of the deck's lines ---".into());
        lines.extend([
            "fix             integrate all nve/sphere".to_string(),
            format!("timestep        {}", exact_number(deck.timestep)),
            "variable        t equal time".into(),
            format!("variable        overlap equal {overlap}"),
            format!("variable        approach equal {approach}"),
            format!("variable        force equal {force}"),
            format!("fix             trajectory all print 1 \"${{t}} ${{overlap}} ${{approach}} ${{force}}\" file {TRAJECTORY_FILE} screen no title \"# time overlap approach_velocity normal_force\""),
            "thermo_style    custom step".into(),
            "thermo          0".into(),
            format!("run             {steps}"),
        ]);
        Ok(DeckImpactInput {
            input: RenderedInput {
                file_name: INPUT_FILE.into(),
                text: lines.join("\n") + "\n",
                args: ["-in", INPUT_FILE, "-log", LOG_FILE, "-nocite", "-echo", "none"].map(String::from).to_vec(),
            },
            setup,
            start_gap: gap,
        })
    }
}
