//! `millimpact deck` reading a YADE script from the recorded dump of its set-up (no YADE starts):
//! the mill example with its match maker and p-wave step, a user's script as YADE holds it after
//! its set-up, the ViscEl and FrictPhys forms as their laws, and a script read up to its first step.

// A value read from a deck is the number written in it, bit for bit: compared exactly.
#![allow(clippy::float_cmp)]

mod common;

use common::deck::{YADE_MILL, relative, yade_case, yade_read};
use common::root;
use millimpact::codes::deck::{DeckOptions, TypeRef};

/// YADE's `E*` of two materials.
fn mixed(e1: f64, n1: f64, e2: f64, n2: f64) -> f64 {
    e1 * e2 / ((1.0 - n1 * n1) * e2 + (1.0 - n2 * n2) * e1)
}

#[test]
fn the_yade_mill_script_is_read_with_its_match_maker_and_p_wave_step() {
    use millimpact::codes::yade::thornton_damping_ratio;
    std::env::set_current_dir(root()).unwrap();
    let deck = yade_read(YADE_MILL, "mill.dump.json", &DeckOptions::default()).unwrap();
    // R_ALUMINA = R_STEEL * 0.625, as YADE holds it.
    let sizes: Vec<(u32, f64, f64)> = deck
        .bodies
        .iter()
        .map(|b| (b.type_id, b.radius, b.density))
        .collect();
    assert_eq!(sizes, [(0, 0.02, 7850.0), (1, 0.02 * 0.625, 3950.0)]);
    // O.dt = 0.2 * PWaveTimeStep(): YADE's own O.dt for this script, as it printed it.
    assert_eq!(deck.timestep, 2.5830790342723347e-07);
    assert!(
        deck.timestep_from
            .starts_with("examples/decks/yade-mill/mill.py:47, `O.dt = 0.2 * PWaveTimeStep()`"),
        "{}",
        deck.timestep_from
    );
    assert_eq!(deck.walls.len(), 1);
    assert_eq!(deck.walls[0].name, "facetCylinder:22");
    assert_eq!(deck.walls[0].type_id, Some(2));
    use TypeRef::{Type, Wall};
    let pairs: Vec<([TypeRef; 2], Option<f64>)> = deck
        .contacts
        .iter()
        .map(|c| (c.types, c.cor_entered))
        .collect();
    // The en of each pair from the MatchMaker, as YADE evaluates it for the materials' ids.
    assert_eq!(
        pairs,
        [
            ([Type(0), Type(0)], Some(0.8)),
            ([Type(0), Type(1)], Some(0.75)),
            ([Type(1), Type(1)], Some(0.7)),
            ([Type(0), Wall], Some(0.6)),
            ([Type(1), Wall], Some(0.55))
        ]
    );
    // Steel on alumina: Hertz of the mixed E*, R* and reduced mass; β_n of Thornton's fit.
    let (steel, alumina) = (&deck.bodies[0], &deck.bodies[1]);
    let m = steel.mass * alumina.mass / (steel.mass + alumina.mass);
    let r: f64 = 0.02 * 0.0125 / 0.0325;
    let k = 4.0 / 3.0 * mixed(2.1e11, 0.3, 3.7e11, 0.22) * r.sqrt();
    let law = deck.contacts[1]
        .law
        .dashpot()
        .copied()
        .expect("a spring–dashpot law");
    assert!(relative(law.stiffness, k) < 1e-14 && relative(law.mass, m) < 1e-14);
    // YADE's masses: 4/3 π R³ ρ.
    assert!(
        relative(
            steel.mass,
            4.0 / 3.0 * std::f64::consts::PI * 0.02f64.powi(3) * 7850.0
        ) < 1e-14
    );
    let c = 2.0 * thornton_damping_ratio(0.75) * (1.5 * m * k).sqrt();
    assert!(relative(law.damping, c) < 1e-14);
    assert_eq!((law.exponent, law.damping_exponent), (1.5, 0.25));
    assert!(law.clamp_attractive);
    // Alumina on the drum's facets: the facet's radius is 2R, so R* = 2R/3; the liner mixed in.
    let wall = deck.contacts[4]
        .law
        .dashpot()
        .copied()
        .expect("a spring–dashpot law");
    let k = 4.0 / 3.0 * mixed(3.7e11, 0.22, 2e11, 0.29) * (2.0 * 0.0125 / 3.0f64).sqrt();
    assert!(relative(wall.stiffness, k) < 1e-14 && relative(wall.mass, alumina.mass) < 1e-14);
    assert!(
        deck.contacts[4]
            .traps
            .iter()
            .any(|t| t.starts_with("wall radius"))
    );
    // What the script set, carried into every impact: its materials and functors.
    let common = deck.transplant.common.join("\n");
    assert!(
        common.contains("O.materials.append(FrictMat(frictionAngle=3.490658503988659e-1, young=2.1e11, poisson=3e-1, label=\"steel\", density=7.85e3))"),
        "{common}"
    );
    assert!(
        common.contains("IP2 = [Ip2_FrictMat_FrictMat_MindlinPhys(en=MatchMaker(matches=[(0, 0, 8e-1), (0, 1, 7.5e-1), (1, 1, 7e-1), (0, 2, 6e-1), (1, 2, 5.5e-1)], algo=\"val\", val=7e-1), es=MatchMaker(matches=[], algo=\"val\", val=7e-1))]"),
        "{common}"
    );
    assert!(
        common.contains("IG2 = [Ig2_Sphere_Sphere_ScGeom(), Ig2_Facet_Sphere_ScGeom()]"),
        "{common}"
    );
    for (left, line) in [
        ("gravity", "mill.py:44"),
        ("output and control", "mill.py:45"),
        ("the run itself", "mill.py:49"),
        ("the walls' shapes", "mill.py:22"),
        ("wall and particle motion", "mill.py:43"),
        ("the force reset and the collider", "mill.py:36,37"),
    ] {
        assert!(
            deck.left_out
                .iter()
                .any(|l| l.starts_with(left) && l.ends_with(line)),
            "{left}: {:?}",
            deck.left_out
        );
    }
}

#[test]
fn a_users_yade_script_is_read_as_yade_holds_it_after_its_set_up() {
    let deck = yade_case("users").unwrap();
    // glass's young edited by its index after the loop appended it, the plate's through the
    // object appended: YADE's values, and the edit said.
    let glass: Vec<&millimpact::codes::deck::DeckBody> =
        deck.bodies.iter().filter(|b| b.type_id == 0).collect();
    assert_eq!(glass.len(), 2);
    assert!(glass.iter().all(|b| b.youngs_modulus == Some(1e7)));
    assert_eq!(deck.walls[0].youngs_modulus, Some(5e10));
    // O.dt = 0.3 * PWaveTimeStep() of the edited glass, as the plain YADE run printed it.
    assert_eq!(deck.timestep, 2.900123150094541e-07);
    let radii: Vec<(u32, f64)> = deck.bodies.iter().map(|b| (b.type_id, b.radius)).collect();
    assert_eq!(radii, [(0, 0.006), (0, 0.004), (1, 0.005)]);
    let glass_pair = &deck.contacts[0];
    assert!(
        glass_pair.traps.iter().any(|t| t
            == "young of glass (tests/data/deck/yade/users.py:16) was 6.5e10 when appended and is 1e7 after the set-up: the check takes 1e7, as YADE does"),
        "{:?}",
        glass_pair.traps
    );
    // The MatchMaker built from a dict: glass–steel 0.8, steel–steel 0.7, the wall its val.
    let en: Vec<(String, Option<f64>)> = deck
        .contacts
        .iter()
        .map(|c| (format!("{}-{}", c.types[0], c.types[1]), c.cor_entered))
        .collect();
    for (pair, e) in [("0-0", 0.9), ("0-1", 0.8), ("1-1", 0.7), ("1-wall", 0.6)] {
        assert!(en.contains(&(pair.to_string(), Some(e))), "{pair}: {en:?}");
    }
    assert!(
        deck.left_out
            .iter()
            .any(|l| l.starts_with("the run itself") && l.ends_with("users.py:52")),
        "{:?}",
        deck.left_out
    );
}

#[test]
fn yade_viscel_and_frictphys_forms_give_their_laws() {
    let pi2 = std::f64::consts::PI * std::f64::consts::PI;
    let deck = yade_case("viscel-tc-en").unwrap();
    let mass = |t: u32| deck.bodies.iter().find(|b| b.type_id == t).unwrap().mass;
    let (m1, m2) = (mass(0), mass(1));
    let tuned = |c: usize, m_r: f64, tc: f64, en: f64| {
        let law = deck.contacts[c]
            .law
            .dashpot()
            .copied()
            .expect("a spring–dashpot law");
        let kn = m_r * (pi2 + en.ln().powi(2)) / (tc * tc);
        let cn = -2.0 * en.ln() * m_r / tc;
        assert!(
            relative(law.stiffness, kn) < 1e-14,
            "{c}: {} {kn}",
            law.stiffness
        );
        assert!(
            relative(law.damping, cn) < 1e-14,
            "{c}: {} {cn}",
            law.damping
        );
        assert!(law.clamp_attractive && law.exponent == 1.0);
    };
    let m_r = m1 * m2 / (m1 + m2);
    tuned(1, m_r, 3e-5, 0.7);
    assert_eq!(deck.contacts[1].cor_entered, Some(0.7));
    // The ball on the wall: tuned for m/2, while m moves.
    tuned(3, m1 / 2.0, 2e-5, 0.8);
    assert!(
        relative(
            deck.contacts[3]
                .law
                .dashpot()
                .expect("a spring–dashpot law")
                .mass,
            m1
        ) < 1e-14
    );
    assert!(
        deck.contacts[3]
            .traps
            .iter()
            .any(|t| t.starts_with("a wall's mass is 0"))
    );
    // The ball on the fixed box: its own mass as YADE holds it, 8 · 0.5 · 0.5 · 0.01 · 1100 kg.
    let m_box = 8.0 * 0.5 * 0.5 * 0.01 * 1100.0;
    tuned(5, m1 * m_box / (m1 + m_box), 3e-5, 0.7);
    // kn, cn in series; FrictPhys's linear spring; young and en through YADE's Newton iteration.
    let law = yade_case("viscel-kn-cn").unwrap().contacts[0]
        .law
        .dashpot()
        .copied()
        .expect("a spring–dashpot law");
    assert_eq!((law.stiffness, law.damping), (1e6, 20.0));
    let deck = yade_case("frict").unwrap();
    // kn = 2 E1 R1 E2 R2/(E1 R1 + E2 R2): E R between two balls and at a wall (refR = R).
    for c in &deck.contacts {
        assert!(
            relative(
                c.law.dashpot().expect("a spring–dashpot law").stiffness,
                2e11 * 0.01
            ) < 1e-14
        );
        assert_eq!(
            (
                c.law.dashpot().expect("a spring–dashpot law").damping,
                c.cor_entered
            ),
            (0.0, None)
        );
    }
    let deck = yade_case("viscel-young").unwrap();
    let law = deck.contacts[0]
        .law
        .dashpot()
        .copied()
        .expect("a spring–dashpot law");
    assert!(relative(law.stiffness, 1e8 * 0.01) < 1e-14);
    // Within 1 % of en on the mass it is tuned for (m/2 between two equal balls).
    let m = deck.bodies[0].mass / 2.0;
    let zeta = law.damping / (2.0 * (m * law.stiffness).sqrt());
    let x = zeta / (1.0 - zeta * zeta).sqrt();
    let e = (-x * (std::f64::consts::PI - 2.0 * x.atan())).exp();
    assert!(relative(e, 0.5) <= 1e-2 && relative(e, 0.5) > 1e-6, "{e}");
}

#[test]
fn a_yade_script_that_steps_in_a_loop_is_read_up_to_its_first_step() {
    let deck = yade_case("steps-in-loop").unwrap();
    // The edit after the loop is never run: the modulus is the one set up.
    assert_eq!(deck.bodies[0].youngs_modulus, Some(2e11));
    assert!(
        deck.left_out.iter().any(|l| l
            == "the run itself (the reading stops at the first call that steps the simulation, O.step; the lines after it are not read): tests/data/deck/yade/steps-in-loop.py:16"),
        "{:?}",
        deck.left_out
    );
}
