//! `millimpact deck` reading a Kratos DEM setup, no Kratos started: the mill example from either
//! of its files, the laws Kratos integrates, Kratos' own damping ratios bit for bit, and custom
//! constants with the sizes taken from an inlet or from the command line.

// A value read from a deck is the number written in it, bit for bit: compared exactly.
#![allow(clippy::float_cmp)]

mod common;

use common::deck::{KRATOS_MILL, KRATOS_PROJECT, json, kratos_deck, read, relative};
use common::root;
use millimpact::analysis::deck::read_deck;
use millimpact::codes::CodeName;
use millimpact::codes::deck::{DeckOptions, GivenParticle, TypeRef, UserDeck};

/// The DAMPING_GAMMA Kratos 10.4.4 wrote into the example's sub-properties when it ran the
/// example's own project (its DEMAnalysisStage, 100 steps): Thornton's fit for the Hertz
/// relations at 0.7 and 0.65, the bisection for the linear ones at 0.6.
const KRATOS_LOGGED_GAMMA: [(f64, f64); 3] = [
    (0.7, 0.111_675_654_969_499_98),
    (0.65, 0.136_969_229_119_020_37),
    (0.6, 0.180_877_685_546_875),
];

#[test]
fn the_kratos_mill_is_read_from_either_of_its_files() {
    let (code, deck) = read_deck(&root().join(KRATOS_MILL), None, &DeckOptions::default()).unwrap();
    assert_eq!(code, CodeName::Kratos);
    let (code, by_project) =
        read_deck(&root().join(KRATOS_PROJECT), None, &DeckOptions::default()).unwrap();
    assert_eq!(code, CodeName::Kratos);
    assert_eq!(
        UserDeck {
            path: deck.path.clone(),
            ..by_project
        },
        deck
    );
    assert_eq!(deck.timestep, 2e-6);
    assert!(
        deck.timestep_from
            .ends_with("ProjectParametersDEM.json: MaxTimeStep"),
        "{}",
        deck.timestep_from
    );
    // The radii from the DEM .mdpa's nodal RADIUS of each material's sub-model part.
    let sizes: Vec<(u32, f64, f64)> = deck
        .bodies
        .iter()
        .map(|b| (b.type_id, b.radius, b.density))
        .collect();
    assert_eq!(sizes, [(1, 0.03, 7800.0), (2, 0.02, 7600.0)]);
    assert!(
        deck.bodies[0]
            .from
            .starts_with("nodal RADIUS of 3 spheres of SpheresPart.DEMParts_SteelBalls"),
        "{}",
        deck.bodies[0].from
    );
    assert_eq!(deck.walls.len(), 1);
    let wall = &deck.walls[0];
    assert_eq!(wall.name, "RigidFacePart.DEM-FEM-Wall_Liner");
    assert_eq!(
        (wall.type_id, wall.youngs_modulus, wall.poisson_ratio),
        (Some(3), Some(5e7), Some(0.45))
    );
    assert!(
        wall.from
            .to_string()
            .ends_with("MaterialsDEM.json: materials[2]")
    );
    use TypeRef::{Type, Wall};
    let types: Vec<[TypeRef; 2]> = deck.contacts.iter().map(|c| c.types).collect();
    assert_eq!(
        types,
        [
            [Type(1), Type(1)],
            [Type(1), Type(2)],
            [Type(2), Type(2)],
            [Type(1), Wall],
            [Type(2), Wall]
        ]
    );
    // What each impact carries: the file's materials and the relations checked, as written.
    let carried: serde_json::Value =
        serde_json::from_str(&deck.transplant.common.join("\n")).unwrap();
    let file = json(&root().join(KRATOS_MILL));
    assert_eq!(carried["materials"], file["materials"]);
    assert_eq!(carried["material_relations"], file["material_relations"]);
    assert!(carried.get("material_assignation_table").is_none());
    assert!(
        deck.left_out
            .iter()
            .any(|l| l.starts_with("gravity, rotation")),
        "{:?}",
        deck.left_out
    );
}

#[test]
fn the_kratos_mill_laws_are_the_ones_kratos_integrates() {
    let deck = read(&root().join(KRATOS_MILL));
    let gamma = |e: f64| {
        KRATOS_LOGGED_GAMMA
            .iter()
            .find(|(cor, _)| *cor == e)
            .unwrap()
            .1
    };
    let mixed = |e1: f64, n1: f64, e2: f64, n2: f64| {
        e1 * e2 / (e2 * (1.0 - n1 * n1) + e1 * (1.0 - n2 * n2))
    };
    let (steel, chrome) = (&deck.bodies[0], &deck.bodies[1]);
    // Steel on chrome iron: Hertz, E* of both, R* and m* of the pair, γ of Thornton's fit.
    let pair = &deck.contacts[1];
    assert_eq!(pair.model, "DEM_D_Hertz_viscous_Coulomb");
    let k = 4.0 / 3.0 * mixed(2.1e11, 0.3, 1.8e11, 0.28) * (0.03f64 * 0.02 / 0.05).sqrt();
    let m = steel.mass * chrome.mass / (steel.mass + chrome.mass);
    assert!(
        relative(
            pair.law.dashpot().expect("a spring–dashpot law").stiffness,
            k
        ) < 1e-14
    );
    assert!(relative(pair.law.dashpot().expect("a spring–dashpot law").mass, m) < 1e-14);
    let c = 2.0 * gamma(0.7) * (1.5 * m * k).sqrt();
    assert!(relative(pair.law.dashpot().expect("a spring–dashpot law").damping, c) < 1e-14);
    assert_eq!(
        (
            pair.law.dashpot().expect("a spring–dashpot law").exponent,
            pair.law
                .dashpot()
                .expect("a spring–dashpot law")
                .damping_exponent
        ),
        (1.5, 0.25)
    );
    assert!(
        pair.law
            .dashpot()
            .expect("a spring–dashpot law")
            .clamp_attractive
    );
    let both = &deck.contacts[2];
    assert!(
        relative(
            both.law.dashpot().expect("a spring–dashpot law").damping
                / (1.5
                    * both.law.dashpot().expect("a spring–dashpot law").mass
                    * both.law.dashpot().expect("a spring–dashpot law").stiffness)
                    .sqrt(),
            2.0 * gamma(0.65)
        ) < 1e-14
    );
    // Chrome iron on the liner: linear, k = π E* (0.31225 R) without the 1.432 of two
    // particles, the ball's own mass, γ of Kratos' bisection.
    let wall = &deck.contacts[4];
    assert_eq!(wall.model, "DEM_D_Linear_viscous_Coulomb");
    let k = std::f64::consts::PI * mixed(1.8e11, 0.28, 5e7, 0.45) * 0.31225 * 0.02;
    assert!(
        relative(
            wall.law.dashpot().expect("a spring–dashpot law").stiffness,
            k
        ) < 1e-14
    );
    assert!(
        relative(
            wall.law.dashpot().expect("a spring–dashpot law").mass,
            chrome.mass
        ) < 1e-14
    );
    assert!(
        relative(
            wall.law.dashpot().expect("a spring–dashpot law").damping,
            2.0 * gamma(0.6) * (chrome.mass * k).sqrt()
        ) < 1e-14
    );
    assert_eq!(
        (
            wall.law.dashpot().expect("a spring–dashpot law").exponent,
            wall.law
                .dashpot()
                .expect("a spring–dashpot law")
                .damping_exponent
        ),
        (1.0, 0.0)
    );
    assert!(
        wall.law
            .dashpot()
            .expect("a spring–dashpot law")
            .clamp_attractive
    );
    assert_eq!(wall.cor_entered, Some(0.6));
    for trap in [
        "wall modulus",
        "linear stiffness from E*",
        "damping ratio by bisection",
        "clamped",
        "wall: RigidFacePart.DEM-FEM-Wall_Liner met as a flat RigidFace3D3N plane",
        "neighbour search: NeighbourSearchFrequency 20",
    ] {
        assert!(
            wall.traps.iter().any(|t| t.starts_with(trap)),
            "{trap}: {:?}",
            wall.traps
        );
    }
    // The neighbour search's speed: search_tolerance_against_walls / (20 Δt).
    assert!(wall.traps.iter().any(|t| t.contains("= 2.5 m/s")));
    // The Hertz trap names the restitution that realises the one entered.
    let en = millimpact::codes::damping::hertz_input_restitution(0.7).unwrap();
    assert!(
        pair.traps
            .iter()
            .any(|t| t.contains(&format!("when given {en:.6}")))
    );
}

/// Kratos' own derivations of γ, bit for bit as 10.4.4 logged them.
#[test]
fn kratos_damping_ratios_are_kratos_own_bits() {
    use millimpact::codes::kratos::{hertz_damping_gamma, linear_damping_gamma};
    let [(e1, g1), (e2, g2), (e3, g3)] = KRATOS_LOGGED_GAMMA;
    assert_eq!(hertz_damping_gamma(e1), g1);
    assert_eq!(hertz_damping_gamma(e2), g2);
    assert_eq!(linear_damping_gamma(e3), g3);
}

#[test]
fn kratos_custom_constants_take_k_normal_and_sizes_come_from_an_inlet_or_flags() {
    // The liner's relations with DEM_D_Linear_Custom_Constants and K_NORMAL; the steel balls
    // from an inlet instead of the .mdpa.
    let (dir, path) = kratos_deck(
        |m| {
            for r in [3, 4] {
                let v = &mut m["material_relations"][r]["Variables"];
                v["DEM_DISCONTINUUM_CONSTITUTIVE_LAW_NAME"] =
                    "DEM_D_Linear_Custom_Constants".into();
                v["K_NORMAL"] = 2e6.into();
            }
            m["material_assignation_table"][0][0] = "DEMInletPart.Inlet_Steel".into();
        },
        |_| {},
    );
    std::fs::write(
        dir.path().join("millDEM_Inlet.mdpa"),
        "Begin SubModelPart Inlet_Steel // Group Steel\n  Begin SubModelPartData\n    RADIUS 0.025\n    PROBABILITY_DISTRIBUTION normal\n    STANDARD_DEVIATION 0.002\n  End SubModelPartData\nEnd SubModelPart\n",
    )
    .unwrap();
    let deck = read(&path);
    let steel = &deck.bodies[0];
    assert_eq!((steel.type_id, steel.radius), (1, 0.025));
    assert!(
        steel
            .from
            .contains("the mean RADIUS of the inlet DEMInletPart.Inlet_Steel")
            && steel.from.contains("standard deviation 0.002"),
        "{}",
        steel.from
    );
    let wall = deck
        .contacts
        .iter()
        .find(|c| c.types == [TypeRef::Type(1), TypeRef::Wall])
        .unwrap();
    assert_eq!(
        wall.law.dashpot().expect("a spring–dashpot law").stiffness,
        2e6
    );
    let gamma = millimpact::codes::kratos::linear_damping_gamma(0.6);
    assert!(
        relative(
            wall.law.dashpot().expect("a spring–dashpot law").damping,
            2.0 * gamma * (steel.mass * 2e6).sqrt()
        ) < 1e-14
    );
    // Flags replace a material's sizes; their density must be the material's.
    let options = DeckOptions {
        particles: vec![GivenParticle {
            type_id: 2,
            radius: 0.05,
            density: 7600.0,
        }],
        ..DeckOptions::default()
    };
    let (_, deck) = read_deck(&path, None, &options).unwrap();
    let chrome: Vec<(f64, &str)> = deck
        .bodies
        .iter()
        .filter(|b| b.type_id == 2)
        .map(|b| (b.radius, b.from.as_str()))
        .collect();
    assert_eq!(chrome, [(0.05, "--particle")]);
    let options = DeckOptions {
        particles: vec![GivenParticle {
            type_id: 2,
            radius: 0.05,
            density: 7800.0,
        }],
        ..DeckOptions::default()
    };
    let e = read_deck(&path, None, &options).unwrap_err().to_string();
    assert!(
        e.contains("material 2 (high_chrome_iron) has PARTICLE_DENSITY 7600")
            && e.ends_with("--particle 2:0.05:7600"),
        "{e}"
    );
}
