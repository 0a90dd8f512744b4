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
//!
//! YADE's objects (materials, functors, kinds of wall) are in `objects.rs`, what is taken from
//! the dump in `reading.rs`, `ViscElMat`'s arithmetic in `viscel.rs`; here are the bodies, each
//! pair's law, the contacts and the impact rendered.

use std::f64::consts::PI;
use std::path::Path;

use super::dump::{Dump, READ_TIME_LIMIT, dump_script, line_text, parse_dump};
use super::objects::{Class, FUNCTORS, Functor, Material, WallKind, edit_traps};
use super::reading::{
    Reading, WallRead, common_lines, lacking, left_out_lines, refuse_before_reading,
};
use super::viscel::{series, viscel_cn_from_en, viscel_en_from_cn};
use super::{HERTZIAN_WALL_RADIUS_FACTOR, TRAJECTORY_FILE, thornton_damping_ratio};
use crate::codes::CodeError;
use crate::codes::damping::hertz_input_restitution;
use crate::codes::deck::{
    DeckBody, DeckContact, DeckDialect, DeckError, DeckImpactInput, DeckOptions, DeckSource,
    DeckWall, ImpactPlan, PairLaw, Partner, SourceLine, Transplant, TypeRef, UserDeck, WallOrder,
};
use crate::codes::template::{exact_number, fill_template};
use crate::model::law::DashpotLaw;
use crate::model::scene::{pair_radius, reduced_mass};
use crate::solve::dashpot::accurate_metrics;

const TEMPLATE: &str = include_str!("deck.py");
const SCRIPT: &str = "impact.py";

/// YADE's deck reader.
pub struct YadeDeck;

/// Whether the script's physics functors can form a contact of the materials `a`, `b`.
fn formed(r: &Reading, a: u32, b: u32) -> bool {
    r.physics.iter().all(|f| f.evaluates(a, b))
}

/// The pairs of the bodies' materials (and of a body's with a wall's) the script's
/// `MatchMaker`s give YADE no value for: left out, as the script never lets them meet.
fn unformed(r: &Reading, bodies: &[DeckBody]) -> Option<String> {
    let mut types: Vec<u32> = bodies.iter().map(|b| b.type_id).collect();
    types.sort_unstable();
    types.dedup();
    let mut pairs = Vec::new();
    for (k, a) in types.iter().enumerate() {
        for b in &types[k..] {
            if !formed(r, *a, *b) {
                pairs.push(format!("{a}–{b}"));
            }
        }
        for w in &r.walls {
            if !formed(r, *a, w.material) {
                pairs.push(format!("{a}–{}", w.name));
            }
        }
    }
    pairs.dedup();
    (!pairs.is_empty()).then(|| {
        format!(
            "pairs the script's MatchMaker gives YADE no value for, so that they never meet (YADE stops at a contact it cannot evaluate): {}",
            pairs.join(", ")
        )
    })
}

/// The deck's own impact speed: the first moving sphere's `state.vel` as the set-up leaves
/// it (m/s), with where it was made.
fn deck_speed(path: &Path, dump: &Dump) -> Option<(f64, String)> {
    dump.bodies.iter().find_map(|b| {
        let v = b.vel.as_ref()?;
        let speed = v
            .iter()
            .map(|x| x.unwrap_or(0.0).powi(2))
            .sum::<f64>()
            .sqrt();
        (b.dynamic && speed > 0.0 && speed.is_finite()).then(|| {
            let at = b.line.map_or(format!("O.bodies[{}]", b.id), |l| {
                format!("{}:{l}", path.display())
            });
            (speed, format!("state.vel ({at})"))
        })
    })
}

impl YadeDeck {
    /// The bodies: one per size of each material, the given ones replacing their type's.
    fn bodies(r: &Reading, path: &Path, options: &DeckOptions) -> Result<Vec<DeckBody>, DeckError> {
        let mut bodies: Vec<DeckBody> = Vec::new();
        let mut push = |t: u32, radius: f64, density: f64, mass: f64, from: String| {
            // The same size read twice is the same number, bit for bit.
            let known = bodies.iter().any(|b| {
                b.type_id == t
                    && b.radius.to_bits() == radius.to_bits()
                    && b.density.to_bits() == density.to_bits()
            });
            if !known {
                let (youngs_modulus, poisson_ratio) = r.materials[t as usize].moduli();
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
        match kind { WallKind::Plane => "a wall", WallKind::Facet => "a facet", WallKind::Box => "a box", WallKind::Sphere => "a fixed sphere" },
        factor / (1.0 + factor),
        if matches!(kind, WallKind::Box | WallKind::Sphere) { "" } else { " (hertzian=True gives it 1e8 R)" }
    ));
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
                return Err(at.refuse(
                    format!(
                        "no Ip2 functor in the InteractionLoop takes {}–{}: YADE would make no contact of this pair",
                        a.name(),
                        b.name()
                    ),
                    FUNCTORS,
                ));
            }
            (None, [f, g, ..]) => {
                return Err(g.at.refuse(
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
            ip2.at.refuse(format!("{} without {law} in the InteractionLoop: YADE would leave its contacts without a force", ip2.class), FUNCTORS)
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
            return Err(law2.at.refuse(
                "includeAdhesion=True with the Ip2's gamma: an adhesive force the check does not model",
                "includeAdhesion=False, or gamma=0",
            ));
        }
        if law2.flag("nothing") {
            return Err(law2
                .at
                .refuse("nothing=True: the law computes no force", "nothing=False"));
        }
        let e_star = mixed_modulus(a.material, b.material);
        let kno = 4.0 / 3.0 * e_star * r_star.sqrt();
        let en = ip2.pair_value("en", a.id, b.id)?;
        let betan = ip2.pair_value("betan", a.id, b.id)?;
        let beta = match (en, betan) {
            (Some(_), Some(_)) => {
                return Err(ip2
                    .at
                    .refuse("both en and betan", "one of en, betan (YADE refuses both)"));
            }
            (Some(e), None) => {
                if !(e > 0.0 && e <= 1.0) {
                    return Err(ip2.at.refuse(format!("en = {e}"), "0 < en <= 1"));
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
                return Err(lacking.at.refuse(
                    format!(
                        "ViscElMat without {key}, met by the ViscElMat of {} that has it (YADE stops: \"Both materials should have the same defined set of variables\")",
                        given.at
                    ),
                    "the same set of tc, en, et, kn, cn, ks, cs on every ViscElMat",
                ));
            }
        }
        if m1.value("mRtype") != m2.value("mRtype") {
            return Err(m2.at.refuse(
                "mRtype differs from the other material's (YADE stops)",
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
                let c = viscel_cn_from_en(en, mass_r, kn).ok_or_else(|| m1.at.refuse(format!("en = {en}: YADE's Newton iteration for cn does not converge in 15 steps (it then runs cn = 0, an elastic contact)"), "an en the iteration reaches, or tc, en, et"))?;
                let realised = viscel_en_from_cn(c, mass_r, kn);
                traps.push(format!("cn from en by YADE's Newton iteration, stopped within 1 % of en: cn = {c:.6e} N·s/m, whose clamped law realises {realised:.6} on the mass it is tuned for"));
                (
                    kn,
                    series(2.0 * c, 2.0 * c),
                    Some(en),
                    "ViscEl young, en".to_string(),
                )
            } else {
                return Err(m1.at.refuse(
                    "a ViscElMat with neither tc, en, et nor kn, ks, cn, cs nor en or cn, cs",
                    "tc, en, et; or kn, ks, cn, cs; or young with en or with cn, cs (YADE: \"Inconsistent material constants\")",
                ));
            }
        };
        let tuned_mass = matches!(model.as_str(), "ViscEl tc, en" | "ViscEl young, en");
        if tuned_mass {
            match wall {
                Some((WallKind::Sphere, w)) => traps.push(format!("the fixed sphere's own mass ({:.4e} kg) enters the tuning: kn, cn are set for the reduced mass {mass_r:.6e} kg of the two spheres, not for the ball's {mass:.6e} kg that moves ({:+.2e} relative)", w.mass, mass_r / mass - 1.0)),
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
        let r = Reading::gather(path, dump, options)?;
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
        let mut contacts = Self::body_contacts(&r, &bodies, &loop_at, false)?;
        let (walls, wall_lines) = Self::wall_contacts(&r, &bodies, &loop_at, &mut contacts, false)?;
        if contacts.is_empty() {
            // No pair the script could let meet: what YADE says of the first is the refusal.
            Self::body_contacts(&r, &bodies, &loop_at, true)?;
            Self::wall_contacts(&r, &bodies, &loop_at, &mut contacts, true)?;
        }
        let unformed_pairs = unformed(&r, &bodies);
        Ok(UserDeck {
            path: path.to_path_buf(),
            timestep,
            timestep_from,
            bodies,
            walls,
            contacts,
            representative_velocity: deck_speed(path, dump),
            left_out: left_out_lines(&r, path)
                .into_iter()
                .chain(unformed_pairs)
                .collect(),
            transplant: Transplant {
                before_box: Vec::new(),
                common: common_lines(&r)?,
                walls: wall_lines,
                types: u32::try_from(r.materials.len()).unwrap_or(u32::MAX),
            },
        })
    }

    /// Each pair of bodies with the law YADE's functors give their two materials: the pairs
    /// the script can let meet, or `every` pair.
    fn body_contacts(
        r: &Reading,
        bodies: &[DeckBody],
        loop_at: &DeckSource,
        every: bool,
    ) -> Result<Vec<DeckContact>, DeckError> {
        let formed = |a: &DeckBody, b: &DeckBody| every || formed(r, a.type_id, b.type_id);
        crate::codes::deck::body_contacts_formed(bodies, formed, |body, other| {
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

    /// The script's walls, with each body's contact against each (that the script can let
    /// meet, or `every` one) pushed onto `contacts`; the walls and the Python each impact
    /// carries to place its wall.
    fn wall_contacts(
        r: &Reading,
        bodies: &[DeckBody],
        loop_at: &DeckSource,
        contacts: &mut Vec<DeckContact>,
        every: bool,
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
        let formed = |w: &WallRead, b: &DeckBody| every || formed(r, b.type_id, w.material);
        let laws = crate::codes::deck::wall_contacts_formed(
            bodies,
            &r.walls,
            order,
            formed,
            |wall, body| {
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
                    // A fixed sphere keeps its own radius: R* is of both radii.
                    radius: match wall.kind {
                        WallKind::Sphere => wall.radius,
                        _ => factor * body.radius,
                    },
                    mass: wall.mass,
                };
                let mut pair =
                    Self::pair_law(r, &a, &b, Some((wall.kind, wall)), body.mass, geometry)?;
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
            },
        )?;
        contacts.extend(laws);
        Ok((walls, r.walls.iter().map(wall_placement).collect()))
    }
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
        return Err(dt_at.refuse(
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
            at.refuse(
                format!(
                    "no {} in the InteractionLoop ({loop_at}): YADE would make no contact here",
                    names[0]
                ),
                FUNCTORS,
            )
        })
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
        // Its top at the face z = 0 the ball meets, centres on the line of the impact.
        WallKind::Sphere => (
            format!(
                "utils.sphere((0.0, 0.0, -{r}), {r}, fixed=True, material={})",
                wall.material,
                r = exact_number(wall.radius)
            ),
            Some(wall.mass),
        ),
    };
    let mut snippet = format!("b2 = O.bodies.append({placement})");
    if let Some(m) = mass {
        let what = if wall.kind == WallKind::Sphere {
            "sphere"
        } else {
            "box"
        };
        snippet.push_str(&format!(
            "\nO.bodies[b2].state.mass = {}  # the script's {what}, as YADE holds it",
            exact_number(m)
        ));
    }
    snippet
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
        let text = fill_template(TEMPLATE, &values)
            .map_err(|e| plan.setup.unsupported("yade", e.to_string()))?;
        Ok(DeckImpactInput {
            input: super::script_input(SCRIPT, text),
            setup: plan.setup,
            start_gap: gap,
        })
    }
}
