//! A LAMMPS user's deck (`millimpact deck`): `pair_style granular` with its `pair_coeff` lines,
//! `fix wall/gran granular` (and `wall/gran/region`), `timestep`, particles from `create_atoms`
//! and `set … diameter … density|mass`, read through `include`s and variables; and the impact of
//! one pair rendered with those lines transplanted, the wall made the plane `zplane 0 NULL`.
//!
//! The law each line makes a build integrate follows that build's conventions as its probe
//! measured them ([`super::probe`]): the wall's effective modulus, what `damping tsuji` applies
//! (the √2), whether `damping coeff_restitution` exists, whether touching is contact;
//! `reference/lammps/CONVENTIONS.md` has the measurements. A pair of types no `pair_coeff`
//! sets is mixed from the types' own lines as the build mixes it ([`super::mixing`]), and
//! what LAMMPS refuses (lines of different forms to mix, a type without its own line, in the
//! 2021 build `pair_coeff J I` with `J > I`) is refused with its lines.
//!
//! A deck that selects the paper's law through its plugin (`pair_style paper` or
//! `paper/linear`, `fix wall/paper`; the driver `lammps-paper`) is read with the plugin's own rules
//! (`LammpsDeck::read_paper`): each pair's law is the paper's, with η and the materials (or
//! `kn`) of its `pair_coeff`, every pair of types must have one, and the impacts run in
//! lammps-paper.

use std::path::Path;

use super::conventions::{Conventions, exact_hertz_alpha};
use super::granular::{CLASSIC, classic_model, dashpot_only, friction, model_name, read_model};
use super::mixing::{Coefficients, GranularModel, PairMixing};
use super::oblique::{oblique_lines, undamped_wall};
use super::plugin_coeffs::{PaperCoeff, PaperWall, paper_coeff, paper_law};
use super::{Build, TRAJECTORY_FILE};
use crate::codes::deck::{
    AtomSyntax, Bodies, BodyElasticity, DeckBody, DeckContact, DeckDialect, DeckError,
    DeckImpactInput, DeckOptions, DeckWall, ImpactPlan, NEIGHBOURS, OUTPUT, PairLaw, Partner,
    ScriptReading, SourceLine, Transplant, TypeRef, UserDeck, WallOrder, body_contacts,
    every_refusal, wall_contacts, whole_number, with_includes,
};
use crate::codes::script::{Command, ScriptReader, check_si_units};
use crate::codes::template::exact_number;
use crate::codes::{CodeDriver, CodeError};
use crate::model::law::DashpotLaw;
use crate::model::scene::{pair_radius, reduced_mass};
use crate::solve::dashpot::accurate_metrics;

/// The deck reader of one LAMMPS build, with the driver that probes it.
pub(crate) struct LammpsDeck(pub &'static Build, pub &'static dyn CodeDriver);

/// A deck's wall as the impact meets it: the plane `zplane 0 NULL`, with no material of its
/// own (the granular model or the plugin's coefficients carry the wall's).
fn plane_wall(id: &str, at: &SourceLine) -> DeckWall {
    DeckWall {
        name: id.to_string(),
        type_id: None,
        youngs_modulus: None,
        poisson_ratio: None,
        from: at.clone().into(),
    }
}

/// The trap every wall's contact carries: its geometry met as a flat plane.
fn plane_trap(geometry: &str) -> String {
    format!("wall: `{geometry}` met as the plane zplane 0 NULL (R* = R at a flat wall)")
}

/// A wall fix as read.
#[derive(Clone, Debug)]
struct WallFix {
    id: String,
    group: String,
    model: GranularModel,
    at: SourceLine,
    geometry: String,
    /// The classic model's words as the deck has them (`hooke/history Kn Kt γn γt μ flag`),
    /// for a wall of a classic style.
    classic: Option<String>,
}

/// A deck's bodies, walls, pairs, the lines every impact carries and each wall's line.
type Pairs = (
    Vec<DeckBody>,
    Vec<DeckWall>,
    Vec<DeckContact>,
    Vec<String>,
    Vec<String>,
);

#[derive(Default)]
struct Reading {
    script: ScriptReading,
    atom_style: Option<Command>,
    pair: Option<Command>,
    coeffs: Vec<(String, String, GranularModel, Command)>,
    walls: Vec<WallFix>,
    /// `pair_style paper` (`Some(false)`) or `paper/linear` (`Some(true)`).
    paper_linear: Option<bool>,
    paper_coeffs: Vec<(String, String, PaperCoeff, Command)>,
    paper_walls: Vec<PaperWall>,
    /// The classic style of `pair_style gran/…`, as the granular model it equals.
    classic: Option<GranularModel>,
    /// Whether the pair style was refused (its `pair_coeff` lines are then not read).
    pair_refused: bool,
}

impl Reading {
    fn leave_out(&mut self, what: &str, c: &Command) {
        self.script.leave_out(what, c);
    }
}

fn whole(x: f64, c: &Command, what: &str) -> Result<u32, DeckError> {
    whole_number(x, &c.at, what, "a whole number from 1")
}

/// LAMMPS's atom commands; its `set`: diameter, density or mass, and the four keywords that make types.
const SYNTAX: AtomSyntax = AtomSyntax {
    whole,
    type_label: "the type",
    mass: true,
    makes: &["type", "type/fraction", "type/ratio", "type/subset"],
    refuses: |_, _| Ok(()),
};

/// Whether pair_coeff's `I`/`J` (a number or `*`, `n*`, `*n`, `m*n`) covers type `t`.
fn covers(range: &str, t: u32, types: u32) -> bool {
    let parse = |s: &str, default: u32| {
        if s.is_empty() {
            Some(default)
        } else {
            s.parse().ok()
        }
    };
    match range.split_once('*') {
        None => range.parse::<u32>().is_ok_and(|x| x == t),
        Some((lo, hi)) => match (parse(lo, 1), parse(hi, types)) {
            (Some(lo), Some(hi)) => (lo..=hi).contains(&t),
            _ => false,
        },
    }
}

/// The deck's `pair_coeff` lines of `pair_style granular`, each `I J` as the build reads it.
struct PairCoeffLines<'a> {
    lines: Vec<(&'a str, &'a str, &'a GranularModel, &'a Command)>,
    /// The number of atom types of the box.
    types: u32,
}

impl<'a> PairCoeffLines<'a> {
    /// Each line's I J as the build reads them: J < I swapped where the build reorders, else
    /// refused (the build sets no pair for it).
    fn as_the_build_reads(
        r: &'a Reading,
        mixing: PairMixing,
        types: u32,
    ) -> Result<Self, DeckError> {
        let mut lines = Vec::new();
        for (a, b, model, c) in &r.coeffs {
            match (a.parse::<u32>(), b.parse::<u32>()) {
                (Ok(i), Ok(j)) if j < i => {
                    if !mixing.reorders_types() {
                        return Err(c.refuse(
                            format!(
                                "pair_coeff {a} {b}: this build sets no pair for J < I (LAMMPS: \"Incorrect args for pair coefficients\")"
                            ),
                            &format!("pair_coeff {b} {a}"),
                        ));
                    }
                    lines.push((b.as_str(), a.as_str(), model, c));
                }
                _ => lines.push((a.as_str(), b.as_str(), model, c)),
            }
        }
        Ok(Self { lines, types })
    }

    /// The line that sets the pair i, j: the last whose I holds the smaller type and whose J
    /// the larger (LAMMPS sets [i][j] for i in I and i ≤ j in J).
    fn for_pair(&self, i: u32, j: u32) -> Option<(&'a GranularModel, &'a Command)> {
        let (p, q) = (i.min(j), i.max(j));
        self.lines
            .iter()
            .rev()
            .find(|(a, b, _, _)| covers(a, p, self.types) && covers(b, q, self.types))
            .map(|&(_, _, m, c)| (m, c))
    }

    /// What LAMMPS refuses before it runs: a type without its own line, two lines of
    /// different forms to mix. Every type of the box counts, in use or not.
    fn check_every_pair_is_set(&self, path: &Path) -> Result<(), DeckError> {
        let types = self.types;
        for t in 1..=types {
            if self.for_pair(t, t).is_none() {
                return Err(DeckError::lacking(
                    path,
                    &format!("no pair_coeff sets the type {t} with itself"),
                    &format!(
                        "a pair_coeff {t} {t} (LAMMPS refuses a deck that leaves one unset: \"All pair coeffs are not set\"), or * *"
                    ),
                ));
            }
        }
        for i in 1..=types {
            for j in i + 1..=types {
                if self.for_pair(i, j).is_some() {
                    continue;
                }
                if let (Some((a, at_a)), Some((b, at_b))) =
                    (self.for_pair(i, i), self.for_pair(j, j))
                    && a.form() != b.form()
                {
                    return Err(at_b.at.refuse(
                        format!(
                            "no pair_coeff sets the types {i} and {j}, and LAMMPS refuses to mix them from pair_coeff {i} {i} ({}: {}) and {j} {j} (here: {}): their functional forms differ (\"Granular pair style functional forms are different\")",
                            at_a.at,
                            a.form(),
                            b.form()
                        ),
                        &format!(
                            "a pair_coeff {i} {j} of its own, or the same normal, damping, tangential, rolling and twisting models in {i} {i} and {j} {j}"
                        ),
                    ));
                }
            }
        }
        Ok(())
    }

    /// A type's material, where its own pair_coeff gives one (hertz/material E d ν).
    fn give_materials(&self, bodies: &mut [DeckBody]) {
        for b in bodies {
            if let Some((m, _)) = self
                .for_pair(b.type_id, b.type_id)
                .filter(|(m, _)| m.normal == "hertz/material")
            {
                b.youngs_modulus = Some(m.values[0]);
                b.poisson_ratio = Some(m.values[2]);
            }
        }
    }
}

/// What a mixed pair's law realises, against the e each type's own line typed (where its
/// damping takes one) and the e the build mixed from them (`mixed_e`, where it mixes one).
fn mixed_cor(
    law: &DashpotLaw,
    mixed_e: Option<f64>,
    [i, j]: [u32; 2],
    models: [Option<&GranularModel>; 2],
) -> String {
    let typed: Vec<String> = [i, j]
        .into_iter()
        .zip(models)
        .filter_map(|(t, m)| {
            m.filter(|m| matches!(m.damping.as_str(), "tsuji" | "coeff_restitution"))
                .map(|m| format!("e = {} in {t} {t}", m.values[1]))
        })
        .collect();
    let typed = if typed.is_empty() {
        String::new()
    } else {
        format!(" (the lines have {})", typed.join(", "))
    };
    // F = k δ^n + d δ^m δ̇ has a COR free of the speed when m = (n − 1)/2 (linear, tsuji):
    // then one number says what the pair realises.
    let free_of_speed = ((law.exponent - 1.0) / 2.0 - law.damping_exponent).abs() < 1e-12;
    if let Some(zeta) = law.never_separates() {
        return format!(
            "COR of the mixed pair: none entered{typed}; its law is damped beyond critical (ζ = {zeta:.4e}): the bodies never separate, COR 0"
        );
    }
    let realised = free_of_speed
        .then(|| accurate_metrics(law, 1.0, 1e-12).ok())
        .flatten();
    match realised {
        Some(m) => format!(
            "COR of the mixed pair: none entered{typed}; its law realises {:.6} at every speed{}{}",
            m.cor,
            if typed.is_empty() {
                ""
            } else {
                ", neither type's e"
            },
            mixed_e.map_or(String::new(), |e| format!(
                ", against the e = {e:.6} the build mixed"
            ))
        ),
        None => format!(
            "COR of the mixed pair: none entered{typed}; its law's COR depends on the speed (the table gives it at each)"
        ),
    }
}

impl LammpsDeck {
    fn gather(&self, path: &Path, options: &DeckOptions) -> Result<Reading, DeckError> {
        // The 2021 build has no ternary() (it came in 2022).
        let lacking: (&'static str, &'static [&'static str]) =
            if self.0.name == super::DEBIAN_2021.name {
                ("LAMMPS 2021", &["ternary"])
            } else {
                ("", &[])
            };
        let (commands, unread) = ScriptReader::read_each(path, &options.variables, lacking)?;
        let mut r = Reading::default();
        let mut refused = Vec::new();
        for (k, c) in commands.iter().enumerate() {
            if let Err(e) = Self::command(c, &mut r) {
                refused.push((k, e));
            }
        }
        let units = check_si_units(r.script.units.as_ref(), path, "LAMMPS").err();
        every_refusal(units, unread, refused)?;
        // The oblique impact runs against each wall only: the pairs' friction is not checked.
        let pairs: Vec<Command> = r
            .coeffs
            .iter()
            .filter(|x| friction(&x.2).is_some())
            .map(|x| x.3.clone())
            .chain(
                r.classic
                    .as_ref()
                    .filter(|m| friction(m).is_some())
                    .and_then(|_| r.pair.clone()),
            )
            .collect();
        for c in &pairs {
            r.leave_out(
                "the pairs' friction (the oblique impact runs against each wall only)",
                c,
            );
        }
        for wall in r.walls.iter().filter(|w| dashpot_only(&w.model)) {
            r.script.left_out.leave_out("a wall's friction that is its tangential dashpot alone (classic hooke, linear_nohistory: its impulse is what its damping decides, no closed form), not checked", &wall.at);
        }
        Ok(r)
    }

    fn command(c: &Command, r: &mut Reading) -> Result<(), DeckError> {
        if r.script.command(c, &SYNTAX)? {
            return Ok(());
        }
        match c.name() {
            "atom_style" => r.atom_style = Some(c.clone()),
            "plugin" => r.leave_out(
                "plugin commands (the impact loads the paper plugin itself)",
                c,
            ),
            "pair_style" if matches!(c.word(1, "a pair style")?, "paper" | "paper/linear") => {
                r.paper_linear = Some(c.words[1] == "paper/linear");
                r.pair = Some(c.clone());
            }
            "pair_coeff" if r.paper_linear.is_some() => {
                let linear = r.paper_linear == Some(true);
                let coeff = paper_coeff(c, 3, c.words.len(), linear, true)?;
                r.paper_coeffs.push((
                    c.word(1, "I")?.to_string(),
                    c.word(2, "J")?.to_string(),
                    coeff,
                    c.clone(),
                ));
            }
            "pair_style" if c.word(1, "a pair style")?.starts_with("gran/") => {
                r.pair = Some(c.clone());
                r.pair_refused = true;
                r.classic = Some(classic_model(c, 1)?.0);
            }
            "pair_coeff" if r.classic.is_some() => {
                let model = r.classic.clone().unwrap_or_else(|| unreachable!());
                if c.words.len() != 3 {
                    return Err(c.refuse(
                        format!("`{}`", c.text),
                        "pair_coeff I J with no coefficients (the classic styles take theirs on the pair_style line)",
                    ));
                }
                r.coeffs
                    .push((c.words[1].clone(), c.words[2].clone(), model, c.clone()));
            }
            "pair_style" => {
                if c.word(1, "a pair style")? != "granular" {
                    r.pair_refused = true;
                    return Err(c.refuse(
                        format!("pair_style {}", c.words[1]),
                        "pair_style granular, or paper and paper/linear of the paper plugin",
                    ));
                }
                r.pair = Some(c.clone());
            }
            // The coefficients of a refused pair style are not read: the style's refusal says it.
            "pair_coeff" if r.pair_refused => {}
            "pair_coeff" => {
                let (model, k) = read_model(c, 3, &[])?;
                if k != c.words.len() {
                    return Err(c.refuse(format!("`{}`", c.text), "pair_coeff I J MODEL …"));
                }
                if !c.words[3..].iter().any(|w| w == "tangential") {
                    return Err(c.refuse("a pair_coeff without a tangential model (LAMMPS refuses it: \"must specify … tangential\")", "pair_coeff I J NORMAL … tangential STYLE …, e.g. tangential linear_nohistory 0 0"));
                }
                r.coeffs
                    .push((c.words[1].clone(), c.words[2].clone(), model, c.clone()));
            }
            "fix" => match c.word(3, "the fix style")? {
                "wall/paper" => {
                    let planes = ["xplane", "yplane", "zplane"];
                    let k = c.words.iter().position(|w| planes.contains(&w.as_str())).ok_or_else(|| {
                        c.refuse("a wall/paper without its plane", "fix ID group wall/paper hertz eta E nu Ewall nuwall PLANE lo hi, or linear eta kn PLANE lo hi")
                    })?;
                    let linear = match c.word(4, "hertz or linear")? {
                        "hertz" => false,
                        "linear" => true,
                        other => {
                            return Err(
                                c.refuse(format!("wall/paper model `{other}`"), "hertz, linear")
                            );
                        }
                    };
                    r.paper_walls.push(PaperWall {
                        id: c.words[1].clone(),
                        coeff: paper_coeff(c, 5, k, linear, false)?,
                        model: c.words[4..k].to_vec(),
                        at: c.at.clone(),
                        geometry: c.words[k..].join(" "),
                    });
                }
                "wall/gran" | "wall/gran/region"
                    if CLASSIC.contains(&c.word(4, "a wall model")?) =>
                {
                    let (model, k) = classic_model(c, 4)?;
                    let geometry = &c.words[k..];
                    if geometry.iter().any(|w| w == "limit_damping") {
                        return Err(c.refuse(
                            "limit_damping after the wall's style: LAMMPS stops at it (\"Illegal fix wall/gran command\")",
                            "fix ID group wall/gran STYLE Kn Kt gamma_n gamma_t xmu dampflag limit_damping WALLSTYLE ARGS",
                        ));
                    }
                    if geometry.is_empty() {
                        return Err(c.refuse(
                            "a wall without its style",
                            "xplane, yplane, zplane, zcylinder, region",
                        ));
                    }
                    r.walls.push(WallFix {
                        id: c.words[1].clone(),
                        group: c.words[2].clone(),
                        model,
                        at: c.at.clone(),
                        geometry: geometry.join(" "),
                        classic: Some(c.words[4..k].join(" ")),
                    });
                }
                "wall/gran" | "wall/gran/region" => {
                    if c.word(4, "granular")? != "granular" {
                        return Err(c.refuse(
                            format!("fix {} {}", c.words[3], c.words[4]),
                            "fix ID group wall/gran granular MODEL … WALLSTYLE ARGS",
                        ));
                    }
                    let stops = ["xplane", "yplane", "zplane", "zcylinder", "region"];
                    let (model, k) = read_model(c, 5, &stops)?;
                    if k >= c.words.len() {
                        return Err(c.refuse(
                            "a wall without its style",
                            "xplane, yplane, zplane, zcylinder, region",
                        ));
                    }
                    r.walls.push(WallFix {
                        id: c.words[1].clone(),
                        group: c.words[2].clone(),
                        model,
                        at: c.at.clone(),
                        geometry: c.words[k..].join(" "),
                        classic: None,
                    });
                }
                "nve/sphere" => r.leave_out(
                    "the integrator (the impact runs fix nve/sphere, as the deck)",
                    c,
                ),
                "nve" | "nve/limit" | "nvt/sphere" | "nve/asphere" | "rigid" | "rigid/small" => {
                    return Err(c.refuse(
                        format!(
                            "fix {}: an integrator whose step the harness does not model",
                            c.words[3]
                        ),
                        "fix nve/sphere",
                    ));
                }
                "gravity" => r.leave_out("gravity (the impact is a free normal impact)", c),
                "pour" | "deposit" => Self::inserts(c, r)?,
                _ => r.leave_out("other fixes (no part of a contact)", c),
            },
            "region" | "lattice" => r.leave_out("regions (the geometry)", c),
            "comm_style" | "dimension" => r.leave_out(NEIGHBOURS, c),
            "info" => r.leave_out(OUTPUT, c),
            "unfix" | "group" | "velocity" | "delete_atoms" | "displace_atoms" | "change_box"
            | "reset_timestep" | "run_style" | "mass" | "pair_modify" | "special_bonds" => {
                r.leave_out("other settings", c)
            }
            _ => {
                return Err(ScriptReading::unknown(
                    c,
                    "the LAMMPS commands of a granular deck (units, atom_style, create_box, region, pair_style granular, pair_coeff, fix, timestep, create_atoms, set, include, variable, output and run commands)",
                ));
            }
        }
        Ok(())
    }

    /// `fix ID group pour N TYPE SEED …` and `fix ID group deposit N TYPE M SEED …` make atoms
    /// of TYPE: a pour of one diameter (`diam one D`, LAMMPS's default 1) and one density
    /// (`dens RHO RHO`, default 1) gives the type its size; a range of either, or a deposit
    /// (whose atoms take LAMMPS's defaults), leaves it to `--particle`.
    fn inserts(c: &Command, r: &mut Reading) -> Result<(), DeckError> {
        r.leave_out("particle insertion (the types it makes are read)", c);
        let t = whole(c.number(5, "the inserted atom type")?, c, "type")?;
        if c.words[3] != "pour" {
            r.script.atoms.insert(t, c, None, None);
            return Ok(());
        }
        let position = |key: &str| c.words.iter().position(|w| w == key);
        let diameter = match position("diam") {
            None => Some(1.0),
            Some(k) if c.words.get(k + 1).is_some_and(|w| w == "one") => {
                Some(c.number(k + 2, "diam one")?)
            }
            Some(_) => None,
        };
        let density = match position("dens") {
            None => Some(1.0),
            Some(k) => {
                let (lo, hi) = (c.number(k + 1, "dens")?, c.number(k + 2, "dens")?);
                // One density only when both bounds are the same number.
                #[allow(clippy::float_cmp)]
                (lo == hi).then_some(lo)
            }
        };
        r.script.atoms.insert(t, c, diameter, density);
        Ok(())
    }

    fn bodies(r: &Reading, path: &Path, options: &DeckOptions) -> Result<Vec<DeckBody>, DeckError> {
        let mut bodies = Bodies::new(path, options)?;
        bodies.push_atoms(&r.script.atoms, " (or mass)")?;
        bodies.finish(
            path,
            "no particle sizes (no create_atoms with set diameter and density)",
        )
    }

    /// The law the coefficients `c` make the build integrate between a particle (radius, mass)
    /// and a partner (`Some((radius, mass))`, or `None` for a wall), with the COR the damping
    /// number stands for (`tsuji`, `coeff_restitution`) and the traps.
    fn law(
        &self,
        conventions: &Conventions,
        c: &Coefficients,
        (radius, mass): (f64, f64),
        partner: Option<(f64, f64)>,
        at: &SourceLine,
    ) -> Result<(DashpotLaw, Option<f64>, Vec<String>), DeckError> {
        let r_star = partner.map_or(radius, |(r2, _)| pair_radius(radius, r2));
        let m_star = partner.map_or(mass, |(_, m2)| reduced_mass(mass, m2));
        let mut traps = Vec::new();
        let d = c.damping_number;
        let (stiffness, exponent) = c.normal.stiffness(r_star);
        let hertz = exponent > 1.0;
        let (damping, damping_exponent, entered) = match c.damping.as_str() {
            "velocity" => (d, 0.0, None),
            "mass_velocity" => (d * m_star, 0.0, None),
            "viscoelastic" => (d * m_star * r_star.sqrt(), 0.5, None),
            "tsuji" => {
                let alpha = conventions.tsuji_fit.alpha(d);
                let exact = exact_hertz_alpha(d);
                // A number as typed where it is short, else to six decimals (a mixed e).
                let e_in = if d.to_string().len() <= 8 {
                    d.to_string()
                } else {
                    format!("{d:.6}")
                };
                traps.push(format!(
                    "damping tsuji takes e_in, not e: this build applies α = {alpha:.6} for e_in = {e_in}, where the law that realises e = {e_in} needs √5 β(e) = {exact:.6}{}",
                    if conventions.tsuji_fit.factor() > 1.0 { "" } else { " (the fit is √2 short: the COR comes out higher)" }
                ));
                (
                    alpha * (m_star * stiffness).sqrt(),
                    if hertz { 0.25 } else { 0.0 },
                    Some(d),
                )
            }
            _ => {
                if !conventions.coeff_restitution {
                    return Err(at.refuse(
                        "damping coeff_restitution: this build (probed) has none",
                        "damping velocity, mass_velocity, viscoelastic, tsuji in this build; --code lammps-2025 has coeff_restitution",
                    ));
                }
                if !(d > 0.0 && d <= 1.0) {
                    return Err(at.refuse(
                        format!("damping coeff_restitution with e = {d}"),
                        "0 < e <= 1 (the build runs e = 0 as NaN and e > 1 as energy gain without a word)",
                    ));
                }
                if hertz {
                    (
                        exact_hertz_alpha(d) * (m_star * stiffness).sqrt(),
                        0.25,
                        Some(d),
                    )
                } else {
                    (
                        DashpotLaw::linear(m_star, stiffness, d).damping,
                        0.0,
                        Some(d),
                    )
                }
            }
        };
        let mut law = DashpotLaw {
            mass: m_star,
            stiffness,
            exponent,
            damping,
            damping_exponent,
            clamp_attractive: false,
        };
        if c.limit_damping {
            traps.push("limit_damping: the attractive tail at the end of contact is cut, and the COR rises (Schwager & Pöschel; 0.5 → 0.550)".into());
            law = law.clamped();
        }
        if !c.tangential.is_empty() {
            traps.push(format!(
                "tangential {} acts on no head-on impact: kept, and it changes nothing here",
                c.tangential
            ));
        }
        Ok((law, entered, traps))
    }
}

impl LammpsDeck {
    /// The law of a pair of bodies: its `pair_coeff` line's, or the one the build mixes from
    /// the two types' own lines.
    fn body_law(
        &self,
        conventions: &Conventions,
        coeffs: &PairCoeffLines<'_>,
        path: &Path,
        body: &DeckBody,
        other: &DeckBody,
    ) -> Result<PairLaw, DeckError> {
        let (i, j) = (body.type_id, other.type_id);
        let (coefficients, model, mut traps, lines, at, mixed) = match coeffs.for_pair(i, j) {
            Some((model, c)) => {
                let (coefficients, traps) = model.coefficients(conventions, false);
                (
                    coefficients,
                    model_name(model),
                    traps,
                    vec![c.at.clone()],
                    &c.at,
                    false,
                )
            }
            None => {
                let own = |t: u32| {
                    coeffs.for_pair(t, t).ok_or_else(|| DeckError::lacking(path, &format!("no pair_coeff sets the types {i} and {j}, nor {t} {t} to mix them from"), "a pair_coeff for every pair of types in use, or I I and J J to mix it from, or * *"))
                };
                let ((ma, ca), (mb, cb)) = (own(i.min(j))?, own(i.max(j))?);
                let pair = self.0.mixing.mix(
                    conventions,
                    (i.min(j), ma, &ca.at.to_string()),
                    (i.max(j), mb, &cb.at.to_string()),
                );
                (
                    pair.coefficients,
                    pair.model,
                    pair.traps,
                    vec![ca.at.clone(), cb.at.clone()],
                    &cb.at,
                    true,
                )
            }
        };
        let (law, entered, law_traps) = self.law(
            conventions,
            &coefficients,
            (body.radius, body.mass),
            Some((other.radius, other.mass)),
            at,
        )?;
        traps.extend(law_traps);
        // A mixed pair has no COR of its own: what it realises is said in its traps.
        let entered = if mixed {
            traps.push(mixed_cor(
                &law,
                entered,
                [i, j],
                [coeffs.for_pair(i, i), coeffs.for_pair(j, j)].map(|o| o.map(|(m, _)| m)),
            ));
            None
        } else {
            entered
        };
        Ok(PairLaw::new(model, law, entered, traps).set_by(lines))
    }

    /// The law of a body against a `fix wall/gran granular` wall, met as the plane
    /// `zplane 0 NULL`.
    fn wall_law(
        &self,
        conventions: &Conventions,
        wall: &WallFix,
        body: &DeckBody,
    ) -> Result<PairLaw, DeckError> {
        let (coefficients, mut traps) = wall.model.coefficients(conventions, true);
        let (law, entered, law_traps) = self.law(
            conventions,
            &coefficients,
            (body.radius, body.mass),
            None,
            &wall.at,
        )?;
        traps.extend(law_traps);
        traps.push(plane_trap(&wall.geometry));
        let model = match &wall.classic {
            Some(_) => format!("wall/gran {}", model_name(&wall.model)),
            None => model_name(&wall.model),
        };
        Ok(PairLaw::new(model, law, entered, traps)
            .set_by([&wall.at])
            .with_friction(friction(&wall.model)))
    }

    /// A deck of the paper plugin: each pair of particle types by its `pair_coeff` (every pair
    /// of the box's types must have one, as the plugin requires: η has no mixing rule), each
    /// type against each `fix wall/paper`; the law the paper's with the plugin's stiffness
    /// (`(4/3) E* sqrt(R*)` or `kn`), the reduced mass and η, the COR entered its closed form.
    fn read_paper(
        r: &Reading,
        path: &Path,
        options: &DeckOptions,
        types: u32,
    ) -> Result<Pairs, DeckError> {
        if let Some((_, _, _, c)) = r.coeffs.first() {
            return Err(c.refuse(
                "granular lines beside the paper plugin's",
                "one contact law per deck: pair_style paper with fix wall/paper, or pair_style granular with fix wall/gran granular",
            ));
        }
        if let Some(w) = r.walls.first() {
            return Err(w.at.refuse(
                "fix wall/gran beside the paper plugin's styles",
                "fix wall/paper with pair_style paper",
            ));
        }
        let lacking = |what: String, supported: &str| DeckError::Lacking {
            file: path.to_path_buf(),
            what,
            supported: supported.into(),
        };
        // The line that sets the pair i ≤ j: the last whose I holds i and whose J holds j, as
        // the plugin sets [i][j] for i in I and i ≤ j in J.
        let coeff_for = |i: u32, j: u32| {
            r.paper_coeffs
                .iter()
                .rev()
                .find(|(a, b, _, _)| covers(a, i, types) && covers(b, j, types))
        };
        if r.paper_linear.is_some() {
            for i in 1..=types {
                for j in i..=types {
                    if coeff_for(i, j).is_none() {
                        return Err(lacking(
                            format!("no pair_coeff for atom types {i} {j}"),
                            "a pair_coeff for every pair of types, I <= J (the plugin stops otherwise: eta has no mixing rule)",
                        ));
                    }
                }
            }
        }
        let bodies = Self::bodies(r, path, options)?;
        let mut contacts = Vec::new();
        if let Some(linear) = r.paper_linear {
            contacts = body_contacts(&bodies, |body, other| {
                let (i, j) = (body.type_id, other.type_id);
                let Some((_, _, coeff, c)) = coeff_for(i.min(j), i.max(j)) else {
                    unreachable!("every pair of types was checked above")
                };
                let pair = (
                    pair_radius(body.radius, other.radius),
                    reduced_mass(body.mass, other.mass),
                );
                let model = if linear { "paper/linear" } else { "paper" };
                Ok(paper_law(model, coeff, pair, vec![]).set_by([&c.at]))
            })?;
        }
        contacts.extend(wall_contacts(
            &bodies,
            &r.paper_walls,
            WallOrder::ByWall,
            |wall, body| {
                let model = format!("wall/paper {}", wall.model[0]);
                let plane = vec![plane_trap(&wall.geometry)];
                Ok(
                    paper_law(&model, &wall.coeff, (body.radius, body.mass), plane)
                        .set_by([&wall.at]),
                )
            },
        )?);
        let walls = r
            .paper_walls
            .iter()
            .map(|w| plane_wall(&w.id, &w.at))
            .collect();
        // The impact's sphere is in group all; the wall acts on it whatever the deck's group.
        let wall_lines = r
            .paper_walls
            .iter()
            .map(|wall| {
                format!(
                    "fix {} all wall/paper {} zplane 0 NULL",
                    wall.id,
                    wall.model.join(" ")
                )
            })
            .collect();
        let mut common = vec![format!("plugin          load {}", super::PAPER_PLUGIN_FILE)];
        common.extend(r.pair.iter().map(|c| c.text.clone()));
        common.extend(r.paper_coeffs.iter().map(|x| x.3.text.clone()));
        Ok((bodies, walls, contacts, common, wall_lines))
    }

    /// A deck of `pair_style granular`: each pair of bodies by its `pair_coeff` or as the
    /// build mixes it, each body against each `fix wall/gran granular`, by the conventions of
    /// the build that will run it.
    fn read_granular(
        &self,
        r: &Reading,
        path: &Path,
        options: &DeckOptions,
        types: u32,
    ) -> Result<Pairs, DeckError> {
        let coeffs = PairCoeffLines::as_the_build_reads(r, self.0.mixing, types)?;
        if r.pair.is_some() {
            coeffs.check_every_pair_is_set(path)?;
        }
        // The conventions of the build that will run it: its probe, else its fallback.
        let conventions = self
            .1
            .measured_conventions()
            .ok()
            .flatten()
            .unwrap_or(self.0.fallback);
        let mut bodies = Self::bodies(r, path, options)?;
        coeffs.give_materials(&mut bodies);
        let mut contacts = body_contacts(&bodies, |body, other| {
            self.body_law(&conventions, &coeffs, path, body, other)
        })?;
        contacts.extend(wall_contacts(
            &bodies,
            &r.walls,
            WallOrder::ByWall,
            |wall, body| self.wall_law(&conventions, wall, body),
        )?);
        let walls = r.walls.iter().map(|w| plane_wall(&w.id, &w.at)).collect();
        let wall_lines = r
            .walls
            .iter()
            .map(|wall| match &wall.classic {
                // The classic wall as the deck has it.
                Some(words) => format!(
                    "fix {} {} wall/gran {words} zplane 0 NULL",
                    wall.id, wall.group
                ),
                None => format!(
                    "fix {} {} wall/gran granular {} zplane 0 NULL",
                    wall.id,
                    wall.group,
                    wall.model.words.join(" ")
                ),
            })
            .collect();
        let mut common = Vec::new();
        if let Some(c) = &r.pair {
            common.push(c.text.clone());
        }
        common.extend(r.coeffs.iter().map(|x| x.3.text.clone()));
        Ok((bodies, walls, contacts, common, wall_lines))
    }
}

impl DeckDialect for LammpsDeck {
    fn renders_oblique(&self) -> bool {
        true
    }

    fn setup_basis(&self) -> (BodyElasticity, Option<Conventions>) {
        let conventions = self.1.measured_conventions().ok().flatten();
        (BodyElasticity::Withheld, conventions)
    }

    fn recognises(&self, path: &Path, text: &str) -> bool {
        with_includes(path, text).lines().any(|l| {
            let w: Vec<&str> = l.split_whitespace().collect();
            matches!(
                w.as_slice(),
                ["pair_style", "granular" | "paper" | "paper/linear", ..]
            ) || (w.first() == Some(&"pair_style")
                && w.get(1).is_some_and(|s| s.starts_with("gran/")))
                || (w.first() == Some(&"fix") && w.get(3) == Some(&"wall/paper"))
                || (w.first() == Some(&"fix")
                    && w.get(3).is_some_and(|s| s.starts_with("wall/gran"))
                    && w.get(4)
                        .is_some_and(|m| *m == "granular" || CLASSIC.contains(m)))
        })
    }

    fn reads(&self) -> &'static str {
        "LAMMPS inputs (pair_style granular, fix wall/gran granular; the paper plugin's pair_style paper, paper/linear and fix wall/paper)"
    }

    fn read(&self, path: &Path, options: &DeckOptions) -> Result<UserDeck, DeckError> {
        let r = self.gather(path, options)?;
        let (types, timestep, timestep_at) = r.script.checked(path, "LAMMPS")?;
        let (bodies, walls, contacts, common, wall_lines) =
            if r.paper_linear.is_some() || !r.paper_walls.is_empty() {
                Self::read_paper(&r, path, options, types)?
            } else {
                self.read_granular(&r, path, options, types)?
            };
        Ok(UserDeck {
            path: path.to_path_buf(),
            timestep,
            timestep_from: timestep_at.to_string(),
            bodies,
            walls,
            contacts,
            representative_velocity: r.script.impact_speed.clone(),
            left_out: r.script.left_out.lines(),
            transplant: Transplant {
                before_box: r.atom_style.iter().map(|c| c.text.clone()).collect(),
                common,
                walls: wall_lines,
                types,
            },
        })
    }

    fn input(&self, deck: &UserDeck, plan: ImpactPlan<'_>) -> Result<DeckImpactInput, CodeError> {
        let (c, body, other, (v1, v2)) = (plan.contact, plan.body, plan.other, plan.velocities);
        // A build that counts touching as contact starts a hair before touch, as its driver does.
        let gap = self.0.start_gap(&plan.setup);
        let t = |x: TypeRef| match x {
            TypeRef::Type(t) => t,
            TypeRef::Wall => 1,
        };
        let r1 = body.radius;
        // The box holds the bodies' whole travel, along the plane too in an oblique impact.
        let travel = plan.velocity + plan.tangential_velocity.map_or(0.0, f64::abs);
        let h = exact_number(4.0 * plan.reach + travel * plan.setup.duration() + gap);
        let mut lines = vec![
            "# millimpact deck: one normal impact with the contact lines of a user's deck (its time step;".to_string(),
            format!("# its lines between the markers, variables substituted). {} at {} m/s, {}.", format_args!("{} on {}", c.types[0], c.types[1]), plan.velocity, deck.path.display()),
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
                lines.push(format!(
                    "create_atoms    {} single {} 0 0 units box",
                    t(c.types[0]),
                    exact_number(-r1 - gap)
                ));
                lines.push(format!(
                    "create_atoms    {} single {} 0 0 units box",
                    t(c.types[1]),
                    exact_number(o.radius)
                ));
                // Along the plane (y) the bodies move as along the normal: the centre of mass
                // at rest, the slip split by the masses.
                let share = |v: f64| plan.tangential_velocity.map(|s| s * v / (v1 - v2));
                for (id, b, v) in [(1, body, v1), (2, o, v2)] {
                    lines.push(format!(
                        "set             atom {id} diameter {} density {} vx {}{}",
                        exact_number(2.0 * b.radius),
                        exact_number(b.density),
                        exact_number(v),
                        share(v).map_or(String::new(), |t| format!(" vy {}", exact_number(t)))
                    ));
                }
                (
                    format!("({})-(x[2]-x[1])", exact_number(r1 + o.radius)),
                    "vx[1]-vx[2]".to_string(),
                    "fx[2]".to_string(),
                )
            }
            None => {
                lines.push(format!(
                    "create_atoms    {} single 0 0 {} units box",
                    t(c.types[0]),
                    exact_number(r1 + gap)
                ));
                lines.push(format!(
                    "set             atom 1 diameter {} density {} vz {}{}",
                    exact_number(2.0 * r1),
                    exact_number(body.density),
                    exact_number(-v1),
                    plan.tangential_velocity
                        .map_or(String::new(), |t| format!(" vx {}", exact_number(t)))
                ));
                (
                    format!("({})-z[1]", exact_number(r1)),
                    "-vz[1]".to_string(),
                    "fz[1]".to_string(),
                )
            }
        };
        lines.push("# --- the deck's lines ---".into());
        lines.extend(deck.transplant.common.iter().cloned());
        if let Partner::Wall(w) = c.partner {
            let line = &deck.transplant.walls[w];
            lines.push(match plan.tangential_velocity {
                Some(_) => undamped_wall(line),
                None => line.clone(),
            });
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
        ]);
        match plan.tangential_velocity {
            None => lines.extend([
                "thermo_style    custom step".to_string(),
                "thermo          0".into(),
                format!("run             {}", plan.steps),
            ]),
            Some(_) => lines.extend(oblique_lines(other.is_some(), plan.steps)),
        }
        Ok(DeckImpactInput {
            input: super::deck_input(lines.join("\n") + "\n"),
            setup: plan.setup,
            start_gap: gap,
        })
    }
}
