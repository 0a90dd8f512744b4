//! A LIGGGHTS user's deck (`millimpact deck`): the granular `pair_style gran` and `fix wall/gran`
//! lines, the `fix property/global` materials, `timestep`, the particles from
//! `particletemplate/sphere` or `create_atoms` and `set`, read through `include`s and variables;
//! and the impact of one pair rendered with those lines transplanted, a mesh or primitive wall
//! made the flat plane `primitive type T zplane 0.0` (a wall's `R*` is the particle's radius in
//! LIGGGHTS whatever its shape).
//!
//! What each model integrates is read from the 3.8.0 sources (`normal_model_hertz.h`,
//! `normal_model_hooke.h`, `normal_model_hertz_stiffness.h`, `normal_model_hooke_stiffness.h`,
//! `global_properties.cpp`) and confirmed by the live tests; `reference/liggghts/CONVENTIONS.md`
//! has the measurements.

use std::collections::HashMap;
use std::path::Path;

use super::gran::{
    GranModel, MODEL_KEYWORDS, PAPER_MODELS, WallFix, read_model, read_settings, read_wall,
    type_number,
};
use super::{Liggghts, TRAJECTORY_FILE};
use crate::codes::deck::{
    AtomSyntax, Bodies, DeckBody, DeckDialect, DeckError, DeckImpactInput, DeckOptions, DeckWall,
    ImpactPlan, NEIGHBOURS, PairLaw, Partner, ScriptReading, SourceLine, Transplant, TypeRef,
    UserDeck, WallOrder, body_contacts, every_refusal, named_file, wall_contacts, with_includes,
};
use crate::codes::script::{Command, ScriptReader, check_si_units};
use crate::codes::template::{exact_number, fill_template};
use crate::codes::{CodeDriver, CodeError};
use crate::model::exact;
use crate::model::law::{CodeLaw, DashpotLaw, PaperLaw};
use crate::model::scene::{pair_radius, reduced_mass};

const TEMPLATE: &str = include_str!("deck.in");

/// LIGGGHTS's deck reader.
pub(crate) struct LiggghtsDeck;

/// A `fix property/global` table.
#[derive(Clone, Debug)]
struct Property {
    values: Vec<f64>,
    columns: usize,
    at: SourceLine,
}

impl Property {
    fn of_type(&self, name: &str, t: u32) -> Result<f64, DeckError> {
        let k = t as usize - 1;
        self.values.get(k).copied().ok_or_else(|| {
            self.at.refuse(
                format!("{name} has {} values, none for type {t}", self.values.len()),
                "one value per atom type (peratomtype)",
            )
        })
    }

    fn of_pair(&self, name: &str, i: u32, j: u32) -> Result<f64, DeckError> {
        let (i, j) = (i as usize - 1, j as usize - 1);
        if self.columns == 0 {
            return Err(self.at.refuse(
                format!("{name} is not a table of type pairs"),
                "peratomtypepair N v11 v12 … vNN",
            ));
        }
        self.values
            .get(i * self.columns + j)
            .copied()
            .ok_or_else(|| {
                self.at.refuse(
                    format!("{name} has no value for the types {} and {}", i + 1, j + 1),
                    "peratomtypepair N with N×N values",
                )
            })
    }

    fn scalar(&self, name: &str) -> Result<f64, DeckError> {
        self.values
            .first()
            .copied()
            .ok_or_else(|| self.at.refuse(format!("{name} has no value"), "scalar V"))
    }
}

/// Everything the reader gathers in one pass.
#[derive(Default)]
struct Reading {
    script: ScriptReading,
    before_box: Vec<String>,
    properties: HashMap<String, Property>,
    property_lines: Vec<String>,
    pair: Option<(GranModel, Command)>,
    pair_coeffs: Vec<Command>,
    walls: Vec<WallFix>,
    meshes: HashMap<String, (u32, SourceLine)>,
    templates: Vec<(u32, Option<f64>, Option<f64>, Command)>,
    hard_particles: bool,
    soft_particles: bool,
}

/// LIGGGHTS 3.8's atom commands; its `set`: diameter and density, and `type`, `type/fraction` (no `type/ratio`,
/// `type/subset`: "Illegal set command").
const SYNTAX: AtomSyntax = AtomSyntax {
    whole: |t, c, _| type_number(t, c),
    type_label: "the atom type",
    mass: false,
    makes: &["type", "type/fraction"],
    refuses: |c, word| match word {
        "type/ratio" | "type/subset" => Err(c.refuse(
            format!(
                "set … {word}: LIGGGHTS 3.8 has no such keyword (it stops: \"Illegal set command\")"
            ),
            "set … type N, or type/fraction N FRACTION SEED",
        )),
        _ => Ok(()),
    },
};

impl Reading {
    fn leave_out(&mut self, what: &str, command: &Command) {
        self.script.leave_out(what, command);
    }

    fn property(&self, name: &str, file: &Path, needed_by: &str) -> Result<&Property, DeckError> {
        self.properties.get(name).ok_or_else(|| DeckError::Lacking {
            file: file.to_path_buf(),
            what: format!(
                "{needed_by} needs the material property {name}, which no fix property/global sets"
            ),
            supported: format!("add `fix ID all property/global {name} …` as LIGGGHTS requires"),
        })
    }
}

/// `key constant VALUE` in a particle template (`density constant 7800`).
fn constant_after(command: &Command, key: &str) -> Result<Option<f64>, DeckError> {
    let Some(k) = command.words.iter().position(|w| w == key) else {
        return Ok(None);
    };
    match command.words.get(k + 1).map(String::as_str) {
        Some("constant") => command.number(k + 2, key).map(Some),
        _ => Ok(None),
    }
}

impl LiggghtsDeck {
    fn gather(path: &Path, options: &DeckOptions) -> Result<Reading, DeckError> {
        let (commands, unread) =
            ScriptReader::read_each(path, &options.variables, ("LIGGGHTS 3.8", &["ternary"]))?;
        let mut r = Reading::default();
        let mut refused = Vec::new();
        for (k, c) in commands.iter().enumerate() {
            if let Err(e) = Self::command(c, &mut r) {
                refused.push((k, e));
            }
        }
        let units = check_si_units(r.script.units.as_ref(), path, "LIGGGHTS").err();
        every_refusal(units, unread, refused)?;
        Ok(r)
    }

    fn command(c: &Command, r: &mut Reading) -> Result<(), DeckError> {
        if r.script.command(c, &SYNTAX)? {
            return Ok(());
        }
        match c.name() {
            "atom_style" => r.before_box.push(c.text.clone()),
            "hard_particles" => {
                r.hard_particles = c.word(1, "yes or no")? == "yes";
                r.before_box.push(c.text.clone());
            }
            "soft_particles" => {
                r.soft_particles = c.word(1, "yes or no")? == "yes";
                r.before_box.push(c.text.clone());
            }
            "pair_style" => {
                if c.word(1, "a pair style")? != "gran" {
                    return Err(c.refuse(
                        format!("pair_style {}", c.words[1]),
                        "pair_style gran model …",
                    ));
                }
                let (mut model, k) = read_model(c, 2)?;
                read_settings(c, k, &mut model)?;
                r.pair = Some((model, c.clone()));
            }
            "pair_coeff" => r.pair_coeffs.push(c.clone()),
            "fix" => Self::fix(c, r)?,
            "region" => r.leave_out("regions (the mill's geometry)", c),
            "communicate" | "modify_timing" => r.leave_out(NEIGHBOURS, c),
            "unfix" | "group" | "velocity" | "delete_atoms" | "displace_atoms" | "change_box" => {
                r.leave_out("changes to the running simulation", c)
            }
            "pair_modify" | "mass" | "dimension" | "lattice" | "reset_timestep" | "run_style"
            | "atom_style_modify" => r.leave_out("other settings", c),
            _ => {
                return Err(ScriptReading::unknown(
                    c,
                    "the LIGGGHTS commands of a granular deck (units, atom_style, create_box, region, fix, pair_style gran, pair_coeff, timestep, create_atoms, set, include, variable, output and run commands)",
                ));
            }
        }
        Ok(())
    }

    fn fix(c: &Command, r: &mut Reading) -> Result<(), DeckError> {
        let style = c.word(3, "the fix style")?;
        match style {
            "property/global" => {
                let name = c.word(4, "the property's name")?.to_string();
                let data = c.word(5, "the property's style")?;
                let (columns, first) = match data {
                    "scalar" | "vector" | "peratomtype" | "atomtype" => (0, 6),
                    "peratomtypepair" | "atomtypepair" | "matrix" => {
                        let n = c.number(6, "the number of columns")?;
                        (type_number(n, c)? as usize, 7)
                    }
                    other => {
                        return Err(c.refuse(
                            format!("property/global style {other}"),
                            "scalar, vector, peratomtype, peratomtypepair, matrix",
                        ));
                    }
                };
                let values = (first..c.words.len())
                    .map(|k| c.number(k, &name))
                    .collect::<Result<Vec<_>, _>>()?;
                r.properties.insert(
                    name,
                    Property {
                        values,
                        columns,
                        at: c.at.clone(),
                    },
                );
                r.property_lines.push(c.text.clone());
            }
            "wall/gran" => {
                let wall = read_wall(c, &r.meshes)?;
                r.walls.push(wall);
            }
            "mesh/surface"
            | "mesh/surface/stress"
            | "mesh/surface/planar"
            | "mesh/surface/stress/servo" => {
                let k = c.words.iter().position(|w| w == "type").ok_or_else(|| {
                    c.refuse(
                        format!("fix {style} without `type`"),
                        "fix ID group mesh/surface file F type T …",
                    )
                })?;
                let t = type_number(c.number(k + 1, "the mesh's type")?, c)?;
                r.meshes.insert(c.words[1].clone(), (t, c.at.clone()));
                r.leave_out(
                    "mesh walls' geometry (each wall/gran wall is met as a flat plane)",
                    c,
                );
                // LIGGGHTS stops at a mesh it cannot open ("Cannot open mesh file"); the mesh
                // is known all the same, so the walls that name it are read on.
                if let Some(f) = c.words.iter().position(|w| w == "file") {
                    named_file(c, f + 1, "mesh file")?;
                }
            }
            "particletemplate/sphere" => {
                let k = c.words.iter().position(|w| w == "atom_type").ok_or_else(|| {
                    c.refuse("particletemplate/sphere without atom_type", "particletemplate/sphere SEED atom_type T density constant RHO radius constant R")
                })?;
                let t = type_number(c.number(k + 1, "the template's atom type")?, c)?;
                let density = constant_after(c, "density")?;
                let radius = constant_after(c, "radius")?;
                r.templates.push((t, radius, density, c.clone()));
                r.script.atoms.made_elsewhere(t);
            }
            "particletemplate/multisphere" | "particletemplate/superquadric" => {
                return Err(c.refuse(
                    format!("fix {style}: a non-spherical particle"),
                    "particletemplate/sphere",
                ));
            }
            "nve/sphere" => r.leave_out(
                "the integrator (the impact runs fix nve/sphere, as the deck)",
                c,
            ),
            "nve" | "nve/limit" | "nve/sphere/limit" | "nve/asphere" | "nvt" | "rigid"
            | "multisphere" => {
                return Err(c.refuse(
                    format!("fix {style}: an integrator whose step the harness does not model"),
                    "fix nve/sphere",
                ));
            }
            "gravity" => r.leave_out("gravity (the impact is a free normal impact)", c),
            "coarsegraining" => {
                return Err(c.refuse(
                    "fix coarsegraining: it scales the contact law",
                    "decks without coarse-graining",
                ));
            }
            "particledistribution/discrete"
            | "particledistribution/discrete/numberbased"
            | "particledistribution/discrete/massbased"
            | "insert/pack"
            | "insert/stream"
            | "insert/rate/region"
            | "insert/pack/dense" => {
                if let Some(k) = c.words.iter().position(|w| w == "vel")
                    && c.words.get(k + 1).is_some_and(|w| w == "constant")
                {
                    r.script.speed_of(c, k + 2, "insertion vel");
                }
                r.leave_out("particle insertion", c);
            }
            "move/mesh" | "move" | "rotate" => r.leave_out("wall and particle motion", c),
            _ => r.leave_out("other fixes (no part of a contact)", c),
        }
        Ok(())
    }

    fn bodies(r: &Reading, path: &Path, options: &DeckOptions) -> Result<Vec<DeckBody>, DeckError> {
        let mut bodies = Bodies::new(path, options)?;
        for (t, radius, density, c) in &r.templates {
            if bodies.given(*t) {
                continue;
            }
            let (Some(radius), Some(density)) = (radius, density) else {
                return Err(c.refuse(
                    format!(
                        "the template {} has no constant radius and density",
                        c.words[1]
                    ),
                    &format!(
                        "`radius constant R` and `density constant RHO`, or --particle {t}:RADIUS:DENSITY"
                    ),
                ));
            };
            bodies.push(*t, *radius, *density, format!("{} ({})", c.words[1], c.at));
        }
        bodies.push_atoms(&r.script.atoms, "")?;
        bodies.finish(
            path,
            "no particle sizes (no particletemplate/sphere, no create_atoms with set diameter and density)",
        )
    }
}

struct Materials<'a> {
    r: &'a Reading,
    path: &'a Path,
}

impl Materials<'_> {
    fn modulus(&self, t: u32, needed_by: &str) -> Result<(f64, f64, SourceLine), DeckError> {
        let e = self.r.property("youngsModulus", self.path, needed_by)?;
        let nu = self.r.property("poissonsRatio", self.path, needed_by)?;
        let (ev, nuv) = (
            e.of_type("youngsModulus", t)?,
            nu.of_type("poissonsRatio", t)?,
        );
        if !(0.0..=0.5).contains(&nuv) {
            return Err(nu.at.refuse(
                format!("poissonsRatio {nuv} of type {t}"),
                "0 <= poissonsRatio <= 0.5 (LIGGGHTS stops otherwise)",
            ));
        }
        if ev > 1e9 && !self.r.hard_particles {
            return Err(e.at.refuse(
                format!("youngsModulus {ev} of type {t} without `hard_particles yes`"),
                "youngsModulus <= 1e9, or hard_particles yes (LIGGGHTS stops otherwise)",
            ));
        }
        if ev < 5e6 && !self.r.soft_particles {
            return Err(e.at.refuse(
                format!("youngsModulus {ev} of type {t} without `soft_particles yes`"),
                "youngsModulus >= 5e6, or soft_particles yes (LIGGGHTS stops otherwise)",
            ));
        }
        Ok((ev, nuv, e.at.clone()))
    }

    /// `E*` of the types `i` and `j`, Pa, the line of their moduli added to `lines`; at a
    /// wall (of type `j`), the trap of the wall's own modulus added to `traps`.
    fn y_star(
        &self,
        (i, j): (u32, u32),
        needed_by: &str,
        wall: bool,
        traps: &mut Vec<String>,
        lines: &mut Vec<SourceLine>,
    ) -> Result<f64, DeckError> {
        let (e1, nu1, e_at) = self.modulus(i, needed_by)?;
        let (e2, nu2, _) = self.modulus(j, needed_by)?;
        let y_star = 1.0 / ((1.0 - nu1 * nu1) / e1 + (1.0 - nu2 * nu2) / e2);
        lines.push(e_at);
        if wall {
            traps.push(wall_modulus_trap(j, (e1, nu1), (e2, nu2), y_star));
        }
        Ok(y_star)
    }

    fn restitution(&self, i: u32, j: u32, needed_by: &str) -> Result<(f64, SourceLine), DeckError> {
        let p = self
            .r
            .property("coefficientRestitution", self.path, needed_by)?;
        let e = p.of_pair("coefficientRestitution", i, j)?;
        if !(e > 0.05 && e <= 1.0) {
            return Err(p.at.refuse(
                format!("coefficientRestitution {e} for the types {i} and {j}"),
                "0.05 < coefficientRestitution <= 1 (LIGGGHTS stops otherwise)",
            ));
        }
        Ok((e, p.at.clone()))
    }

    /// The law LIGGGHTS integrates between a particle of type `i` (radius, mass) and a partner
    /// of type `j` (`Some((radius, mass))` for a particle, `None` for a wall).
    fn pair_law(
        &self,
        model: &GranModel,
        (i, radius, mass): (u32, f64, f64),
        j: u32,
        partner: Option<(f64, f64)>,
        at: &SourceLine,
    ) -> Result<PairLaw, DeckError> {
        if PAPER_MODELS.contains(&model.normal.as_str()) {
            return self.paper_law(model, (i, radius, mass), j, partner, at);
        }
        let needed_by = format!("model {}", model.normal);
        let r_star = partner.map_or(radius, |(r2, _)| pair_radius(radius, r2));
        let m_star = partner.map_or(mass, |(_, m2)| reduced_mass(mass, m2));
        let mut traps = Vec::new();
        let mut lines = vec![at.clone()];
        let (law, cor_entered) = match model.normal.as_str() {
            "hertz" | "hooke" => {
                let wall = partner.is_none();
                let y_star = self.y_star((i, j), &needed_by, wall, &mut traps, &mut lines)?;
                let (e, e_line) = self.restitution(i, j, &needed_by)?;
                lines.push(e_line);
                if model.normal == "hertz" {
                    let k = 4.0 / 3.0 * y_star * r_star.sqrt();
                    (DashpotLaw::damped_hertz(m_star, k, e), Some(e))
                } else {
                    let v_prop =
                        self.r
                            .property("characteristicVelocity", self.path, &needed_by)?;
                    let v = v_prop.scalar("characteristicVelocity")?;
                    if v < 1e-2 {
                        return Err(v_prop.at.refuse(
                            format!("characteristicVelocity {v}"),
                            "characteristicVelocity >= 1e-2 (LIGGGHTS stops otherwise)",
                        ));
                    }
                    lines.push(v_prop.at.clone());
                    let s = r_star.sqrt();
                    let kn = 16.0 / 15.0
                        * s
                        * y_star
                        * (15.0 * m_star * v * v / (16.0 * s * y_star)).powf(0.2);
                    traps.push(format!(
                        "model hooke: its spring kn = {kn:.4e} N/m is Hertz's at characteristicVelocity {v} m/s only: at another speed the contact time and overlap are not Hertz's (the COR is)"
                    ));
                    (DashpotLaw::linear(m_star, kn, e), Some(e))
                }
            }
            "hooke/stiffness" => {
                let kn_p = self.r.property("kn", self.path, &needed_by)?;
                let kn = kn_p.of_pair("kn", i, j)?;
                let absolute = model.on("absolute_damping");
                let name = if absolute { "gamman_abs" } else { "gamman" };
                let g = self.r.property(name, self.path, &needed_by)?;
                let gamma = g.of_pair(name, i, j)?;
                lines.push(kn_p.at.clone());
                lines.push(g.at.clone());
                let damping = if absolute { gamma } else { gamma * m_star };
                if !absolute {
                    traps.push(format!("gamman is per unit mass: the dashpot is gamman × m* = {damping:.4e} N·s/m here (absolute_damping on takes N·s/m)"));
                }
                (
                    DashpotLaw {
                        mass: m_star,
                        stiffness: kn,
                        exponent: 1.0,
                        damping,
                        damping_exponent: 0.0,
                        clamp_attractive: false,
                    },
                    None,
                )
            }
            _ => {
                // hertz/stiffness: kn and gamman scaled by sqrt(R* δ), gamman per unit mass.
                let kn_p = self.r.property("kn", self.path, &needed_by)?;
                let g = self.r.property("gamman", self.path, &needed_by)?;
                let kn = kn_p.of_pair("kn", i, j)?;
                let gamma = g.of_pair("gamman", i, j)?;
                lines.push(kn_p.at.clone());
                lines.push(g.at.clone());
                let s = r_star.sqrt();
                (
                    DashpotLaw {
                        mass: m_star,
                        stiffness: kn * s,
                        exponent: 1.5,
                        damping: gamma * m_star * s,
                        damping_exponent: 0.5,
                        clamp_attractive: false,
                    },
                    None,
                )
            }
        };
        let law = if model.on("limitForce") {
            traps.push("limitForce on: the attractive tail at the end of contact is cut, and the COR rises above the entered one (Schwager & Pöschel; 0.7128 for 0.6939 with hertz)".into());
            law.clamped()
        } else {
            law
        };
        traps.extend(model.idle_trap());
        Ok(PairLaw::new(&model.normal, law, cor_entered, traps).set_by(lines))
    }

    /// The paper's law LIGGGHTS integrates under `model paper` (`C = (4/3) E* sqrt(R*)`, formed
    /// as `model hertz` forms its stiffness, n = 1.5) or `model paper/linear` (`C = kn` of the
    /// type pair, n = 1), with the pair's `lossCoefficient` η; the COR it is built to realise,
    /// `sqrt((1 − η)/(1 + η))`, stands as the one entered (the deck gives η, not a COR).
    fn paper_law(
        &self,
        model: &GranModel,
        (i, radius, mass): (u32, f64, f64),
        j: u32,
        partner: Option<(f64, f64)>,
        at: &SourceLine,
    ) -> Result<PairLaw, DeckError> {
        let needed_by = format!("model {}", model.normal);
        let r_star = partner.map_or(radius, |(r2, _)| pair_radius(radius, r2));
        // LIGGGHTS's `meff`: the pair's reduced mass, the particle's own at a wall.
        let m_star = partner.map_or(mass, |(_, m2)| reduced_mass(mass, m2));
        let mut traps = vec![
            "lossCoefficient is η itself, not a COR: the law realises sqrt((1 − η)/(1 + η)) whatever the size, mass, material and speed".to_string(),
        ];
        let mut lines = vec![at.clone()];
        let (stiffness, exponent) = if model.normal == "paper" {
            let wall = partner.is_none();
            let y_star = self.y_star((i, j), &needed_by, wall, &mut traps, &mut lines)?;
            (4.0 / 3.0 * y_star * r_star.sqrt(), 1.5)
        } else {
            let kn_p = self.r.property("kn", self.path, &needed_by)?;
            let kn = kn_p.of_pair("kn", i, j)?;
            // LIGGGHTS stops without kt: the style hands it to the tangential model.
            let kt_p = self.r.property("kt", self.path, &needed_by)?;
            kt_p.of_pair("kt", i, j)?;
            if kn.is_nan() || kn <= 0.0 {
                return Err(kn_p.at.refuse(
                    format!("kn {kn} for the types {i} and {j}"),
                    "a positive stiffness kn, N/m",
                ));
            }
            lines.push(kn_p.at.clone());
            (kn, 1.0)
        };
        let eta_p = self.r.property("lossCoefficient", self.path, &needed_by)?;
        let eta = eta_p.of_pair("lossCoefficient", i, j)?;
        // liggghts-paper checks every type pair of the table when it sets the model up, not
        // only the pairs that meet.
        let columns = eta_p.columns.max(1);
        if let Some((k, bad)) = eta_p
            .values
            .iter()
            .enumerate()
            .find(|(_, v)| !(0.0..1.0).contains(*v))
        {
            return Err(eta_p.at.refuse(
                format!(
                    "lossCoefficient {bad} for the types {} and {}",
                    k / columns + 1,
                    k % columns + 1
                ),
                "0 <= lossCoefficient < 1 for every type pair (η: liggghts-paper stops otherwise; η >= 1 never separates the bodies, η < 0 creates energy)",
            ));
        }
        lines.push(eta_p.at.clone());
        traps.extend(model.idle_trap());
        let law = PaperLaw {
            mass: m_star,
            stiffness,
            exponent,
            loss_coefficient: eta,
        };
        Ok(PairLaw::new(
            &model.normal,
            CodeLaw::Paper(law),
            Some(exact::restitution(eta)),
            traps,
        )
        .set_by(lines))
    }
}

/// The trap of a wall's own modulus, which LIGGGHTS mixes into `E*` (`y_star`, Pa) with the
/// particle's (`own`: its E and ν) as if the wall were a body of type `j` (`wall`: its E and ν).
fn wall_modulus_trap(j: u32, own: (f64, f64), wall: (f64, f64), y_star: f64) -> String {
    let ((e1, nu1), (e2, nu2)) = (own, wall);
    let own = e1 / (1.0 - nu1 * nu1);
    format!(
        "wall modulus: the wall's type {j} (E = {e2:e} Pa, ν = {nu2}) is mixed into E* = {y_star:.4e} Pa, {:.3e} of the particle's own E/(1−ν²) = {own:.4e} Pa against a rigid wall{}",
        y_star / own,
        if y_star < 0.99 * own {
            " (a wall meant rigid needs a far larger E: LIGGGHTS has no rigid wall)"
        } else {
            ""
        }
    )
}

impl DeckDialect for LiggghtsDeck {
    fn recognises(&self, path: &Path, text: &str) -> bool {
        with_includes(path, text).lines().map(str::trim).any(|l| {
            let words: Vec<&str> = l.split_whitespace().collect();
            matches!(words.as_slice(), ["pair_style", "gran", "model", ..])
                || (words.first() == Some(&"fix")
                    && words.get(3) == Some(&"wall/gran")
                    && words.get(4) == Some(&"model"))
                || matches!(words.as_slice(), ["atom_style", "granular", ..])
        })
    }

    fn reads(&self) -> &'static str {
        "LIGGGHTS inputs (pair_style gran model …)"
    }

    fn read(&self, path: &Path, options: &DeckOptions) -> Result<UserDeck, DeckError> {
        let r = Self::gather(path, options)?;
        let (types, timestep, timestep_at) = r.script.checked(path, "LIGGGHTS")?;
        let (pair_model, pair_command) = r.pair.clone().ok_or_else(|| DeckError::Lacking {
            file: path.to_path_buf(),
            what: "no pair_style gran line".into(),
            supported: "pair_style gran model …".into(),
        })?;
        check_types_declared(&r, types, path)?;
        let mut bodies = Self::bodies(&r, path, options)?;
        let materials = Materials { r: &r, path };
        if uses_modulus(&pair_model) || r.walls.iter().any(|w| uses_modulus(&w.model)) {
            for b in &mut bodies {
                let (e, nu, _) =
                    materials.modulus(b.type_id, &format!("model {}", pair_model.normal))?;
                b.youngs_modulus = Some(e);
                b.poisson_ratio = Some(nu);
            }
        }
        let (walls, wall_lines) = deck_walls(&r, &materials)?;
        let mut contacts = body_contacts(&bodies, |body, other| {
            materials.pair_law(
                &pair_model,
                (body.type_id, body.radius, body.mass),
                other.type_id,
                Some((other.radius, other.mass)),
                &pair_command.at,
            )
        })?;
        contacts.extend(wall_contacts(
            &bodies,
            &r.walls,
            WallOrder::ByBody,
            |wall, body| {
                let mut pl = materials.pair_law(
                    &wall.model,
                    (body.type_id, body.radius, body.mass),
                    wall.wall_type,
                    None,
                    &wall.at,
                )?;
                pl.traps.push(format!(
                    "wall: {} met as a flat plane (LIGGGHTS takes R* = R at any wall)",
                    wall.geometry
                ));
                Ok(pl)
            },
        )?);
        // The deck's own impact speed, else the speed its Hooke model is set for.
        let representative_velocity = r.script.impact_speed.clone().or_else(|| {
            r.properties.get("characteristicVelocity").and_then(|p| {
                p.values
                    .first()
                    .map(|v| (*v, format!("characteristicVelocity ({})", p.at)))
            })
        });
        let left_out = r.script.left_out.lines();
        let mut common = r.property_lines.clone();
        common.push(pair_command.text.clone());
        common.extend(r.pair_coeffs.iter().map(|c| c.text.clone()));
        Ok(UserDeck {
            path: path.to_path_buf(),
            timestep,
            timestep_from: timestep_at.to_string(),
            bodies,
            walls,
            contacts,
            representative_velocity,
            left_out,
            transplant: Transplant {
                before_box: r.before_box.clone(),
                common,
                walls: wall_lines,
                types,
            },
        })
    }

    fn input(&self, deck: &UserDeck, plan: ImpactPlan<'_>) -> Result<DeckImpactInput, CodeError> {
        let (c, body, other) = (plan.contact, plan.body, plan.other);
        let (v1, v2) = plan.velocities;
        let wall_line = match c.partner {
            Partner::Body(_) => None,
            Partner::Wall(w) => Some(deck.transplant.walls[w].clone()),
        };
        let gap = super::contact_gap(&plan.setup);
        let r1 = body.radius;
        let type_of = |t: TypeRef| match t {
            TypeRef::Type(t) => t,
            TypeRef::Wall => 0,
        };
        let atom = |id: u32, t: u32, z: f64, b: &DeckBody, vz: f64| {
            format!(
                "create_atoms    {t} single 0 0 {} units box\nset             atom {id} diameter {} density {} vz {}",
                exact_number(z),
                exact_number(2.0 * b.radius),
                exact_number(b.density),
                exact_number(vz)
            )
        };
        let mut atoms = atom(1, type_of(c.types[0]), r1 + gap, body, -v1);
        let (overlap, approach) = match other {
            Some(other) => {
                atoms.push('\n');
                atoms.push_str(&atom(2, type_of(c.types[1]), -other.radius, other, -v2));
                (
                    format!("{}-(z[1]-z[2])", exact_number(plan.reach)),
                    "vz[2]-vz[1]".to_string(),
                )
            }
            None => (format!("{}-z[1]", exact_number(r1)), "-vz[1]".to_string()),
        };
        let half = 4.0 * plan.reach + plan.velocity * plan.setup.duration() + gap;
        let h = exact_number(half);
        let mut lines = deck.transplant.common.clone();
        lines.extend(wall_line);
        // LIGGGHTS stops unless the lowest type in use (by an atom or a wall) is 1: a pair of
        // higher types gets a plane of type 1 beyond the neighbour distance of both bodies,
        // which nothing ever touches.
        let in_use = c.types.iter().map(|&t| type_of(t)).chain(match c.partner {
            Partner::Wall(w) => deck.walls[w].type_id,
            Partner::Body(_) => None,
        });
        if in_use.filter(|&t| t > 0).min().is_some_and(|t| t > 1) {
            let spec = lowest_type_spec(&deck.transplant.common);
            lines.push(format!(
                "fix             lowest_type all wall/gran {spec} primitive type 1 zplane {} # untouched: type 1 in use",
                exact_number(-0.9 * half)
            ));
        }
        let values = [
            ("deck", deck.path.display().to_string()),
            ("pair", format!("{} on {}", c.types[0], c.types[1])),
            ("velocity", exact_number(plan.velocity)),
            ("before_box", deck.transplant.before_box.join("\n")),
            ("domain", format!("-{h} {h} -{h} {h} -{h} {h}")),
            ("types", deck.transplant.types.to_string()),
            ("skin", exact_number(plan.reach)),
            ("deck_lines", lines.join("\n")),
            ("timestep", exact_number(deck.timestep)),
            ("atoms", atoms),
            ("overlap", overlap),
            ("approach", approach),
            ("steps", plan.steps.to_string()),
            ("trajectory", TRAJECTORY_FILE.to_string()),
        ];
        let text = fill_template(TEMPLATE, &values)
            .map_err(|e| plan.setup.unsupported(Liggghts.name(), e.to_string()))?;
        Ok(DeckImpactInput {
            input: super::input_file(text),
            setup: plan.setup,
            start_gap: gap,
        })
    }
}

/// Refuse a type that a template, an atom or a wall uses beyond the `types` create_box
/// declares.
fn check_types_declared(r: &Reading, types: u32, path: &Path) -> Result<(), DeckError> {
    for t in r
        .templates
        .iter()
        .map(|x| x.0)
        .chain(r.script.atoms.of_type.keys().copied())
        .chain(r.walls.iter().map(|w| w.wall_type))
    {
        if t > types {
            return Err(DeckError::Lacking {
                file: path.to_path_buf(),
                what: format!("type {t} is used but create_box declares {types} types"),
                supported: "types from 1 to create_box's N".into(),
            });
        }
    }
    Ok(())
}

/// Whether a normal model takes its stiffness from the types' Young's moduli.
fn uses_modulus(m: &GranModel) -> bool {
    m.normal == "hertz" || m.normal == "hooke" || m.normal == "paper"
}

/// The deck's walls, with their materials where their model uses one, and the line each
/// impact carries for its wall (met as the plane `zplane 0.0`).
fn deck_walls(
    r: &Reading,
    materials: &Materials<'_>,
) -> Result<(Vec<DeckWall>, Vec<String>), DeckError> {
    let mut walls = Vec::new();
    let mut wall_lines = Vec::new();
    for w in &r.walls {
        let (e, nu) = if uses_modulus(&w.model) {
            let (e, nu, _) =
                materials.modulus(w.wall_type, &format!("model {}", w.model.normal))?;
            (Some(e), Some(nu))
        } else {
            (None, None)
        };
        walls.push(DeckWall {
            name: w.id.clone(),
            type_id: Some(w.wall_type),
            youngs_modulus: e,
            poisson_ratio: nu,
            from: w.at.clone().into(),
        });
        let settings: Vec<String> = w
            .model
            .settings
            .iter()
            .flat_map(|(k, v)| [k.clone(), v.clone()])
            .collect();
        wall_lines.push(
            format!(
                "fix {} {} wall/gran {} primitive type {} zplane 0.0 {}",
                w.id,
                w.group,
                w.model.spec.join(" "),
                w.wall_type,
                settings.join(" ")
            )
            .trim_end()
            .to_string(),
        );
    }
    Ok((walls, wall_lines))
}

/// The model specification of the deck's `pair_style gran` line (`model hertz tangential …`),
/// for a wall that must exist but never be touched.
fn lowest_type_spec(common: &[String]) -> String {
    let Some(line) = common
        .iter()
        .find(|l| l.trim_start().starts_with("pair_style"))
    else {
        return "model hertz".into();
    };
    let words: Vec<&str> = line.split_whitespace().skip(2).collect();
    let mut spec = Vec::new();
    for pair in words.chunks(2) {
        match pair {
            [key, value] if MODEL_KEYWORDS.contains(key) => spec.extend([*key, *value]),
            _ => break,
        }
    }
    spec.join(" ")
}
