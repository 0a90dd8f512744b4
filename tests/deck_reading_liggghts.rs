//! `millimpact deck` reading a LIGGGHTS deck, no code started: the mill example through its
//! include and variables and the laws it gives, each normal model and setting as its law, atoms
//! set by type, continued lines, and variables and particles given on the command line.

// A value read from a deck is the number written in it, bit for bit: compared exactly.
#![allow(clippy::float_cmp)]

mod common;

use common::deck::{HEAD, MILL, deck_files, read, relative};
use common::root;
use millimpact::analysis::deck::read_deck;
use millimpact::codes::deck::{DeckOptions, GivenParticle, Partner, TypeRef};
use millimpact::model::law::DashpotLaw;

#[test]
fn the_mill_deck_is_read_through_its_include_and_variables() {
    let deck = read(&root().join(MILL));
    assert_eq!(deck.timestep, 2e-6);
    assert!(
        deck.timestep_from.ends_with("in.mill:28"),
        "{}",
        deck.timestep_from
    );
    let sizes: Vec<(u32, f64, f64)> = deck
        .bodies
        .iter()
        .map(|b| (b.type_id, b.radius, b.density))
        .collect();
    // r_small = v_r_big/2 with r_big = 0.06/2: a formula through another variable.
    assert_eq!(sizes, [(1, 0.03, 7800.0), (2, 0.015, 7800.0)]);
    assert_eq!(deck.walls.len(), 1);
    assert_eq!(deck.walls[0].type_id, Some(3));
    assert_eq!(deck.walls[0].youngs_modulus, Some(5e7));
    // Three ball pairs, two ball–wall pairs.
    let types: Vec<[TypeRef; 2]> = deck.contacts.iter().map(|c| c.types).collect();
    use TypeRef::{Type, Wall};
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
    // The include's property lines, variables substituted; the mesh wall made a plane.
    let common = deck.transplant.common.join("\n");
    assert!(
        common.contains("youngsModulus peratomtype 200000000000 200000000000 50000000"),
        "{common}"
    );
    assert!(
        common.contains("pair_style      gran model hertz tangential history rolling_friction cdt"),
        "{common}"
    );
    assert_eq!(
        deck.transplant.walls,
        [
            "fix walls all wall/gran model hertz tangential history rolling_friction cdt primitive type 3 zplane 0.0"
        ]
    );
    assert_eq!(deck.transplant.types, 3);
    for left in [
        "gravity",
        "mesh walls",
        "particle insertion",
        "the run itself",
    ] {
        assert!(
            deck.left_out.iter().any(|l| l.starts_with(left)),
            "{left}: {:?}",
            deck.left_out
        );
    }
}

#[test]
fn the_mill_decks_laws_are_liggghts_hertz_with_its_mixed_modulus() {
    let deck = read(&root().join(MILL));
    let big = &deck.bodies[0];
    let small = &deck.bodies[1];
    // Ball on ball (types 1 and 2): Y* of two steels, R* = R1 R2/(R1+R2), m* reduced.
    let y = 2e11 / (2.0 * (1.0 - 0.09));
    let r: f64 = 0.03 * 0.015 / 0.045;
    let m = big.mass * small.mass / (big.mass + small.mass);
    let expected = DashpotLaw::damped_hertz(m, 4.0 / 3.0 * y * r.sqrt(), 0.7);
    let law = deck.contacts[1]
        .law
        .dashpot()
        .copied()
        .expect("a spring–dashpot law");
    assert!(relative(law.stiffness, expected.stiffness) < 1e-14);
    assert!(relative(law.damping, expected.damping) < 1e-14);
    assert!(relative(law.mass, expected.mass) < 1e-14);
    assert!(!law.clamp_attractive);
    // Ball on the rubber liner: the liner's E and ν mixed in, R* = R, m* = m.
    let y_wall = 1.0 / ((1.0 - 0.09) / 2e11 + (1.0 - 0.45 * 0.45) / 5e7);
    let wall = &deck.contacts[3];
    assert_eq!(wall.partner, Partner::Wall(0));
    assert_eq!(wall.cor_entered, Some(0.6));
    assert!(
        relative(
            wall.law.dashpot().expect("a spring–dashpot law").stiffness,
            4.0 / 3.0 * y_wall * 0.03f64.sqrt()
        ) < 1e-14
    );
    assert!(
        relative(
            wall.law.dashpot().expect("a spring–dashpot law").mass,
            big.mass
        ) < 1e-14
    );
    assert!(
        wall.traps.iter().any(|t| t.starts_with("wall modulus")),
        "{:?}",
        wall.traps
    );
}

#[test]
fn each_normal_model_and_setting_gives_its_law() {
    let atoms =
        "create_atoms 1 single 0 0 0\nset atom 1 diameter 0.02 density 7800\ntimestep 1e-7\n";
    let mass = 4.0 / 3.0 * std::f64::consts::PI * 0.01f64.powi(3) * 7800.0;
    // hooke: kn from characteristicVelocity, the linear dashpot of the entered COR.
    let hooke = format!(
        "{HEAD}fix v all property/global characteristicVelocity scalar 2.0\npair_style gran model hooke\npair_coeff * *\n{atoms}"
    );
    let (_d, path) = deck_files(&[("in.hooke", &hooke)]);
    let deck = read(&path);
    let (y, r, m): (f64, f64, f64) = (2e11 / (2.0 * 0.91), 0.005, mass / 2.0);
    let kn = 16.0 / 15.0 * r.sqrt() * y * (15.0 * m * 4.0 / (16.0 * r.sqrt() * y)).powf(0.2);
    let law = deck.contacts[0]
        .law
        .dashpot()
        .copied()
        .expect("a spring–dashpot law");
    assert!(
        relative(law.stiffness, kn) < 1e-13,
        "{} {kn}",
        law.stiffness
    );
    assert!(relative(law.damping, DashpotLaw::linear(m, kn, 0.5).damping) < 1e-13);
    assert_eq!(
        deck.representative_velocity.as_ref().map(|v| v.0),
        Some(2.0)
    );
    // hooke/stiffness with absolute damping, and limitForce on: a clamped linear law.
    let stiff = "units si\natom_style granular\ncreate_box 1 box\n\
fix k all property/global kn peratomtypepair 1 1e6\nfix kt all property/global kt peratomtypepair 1 0\n\
fix g all property/global gamman_abs peratomtypepair 1 25\nfix gt all property/global gammat_abs peratomtypepair 1 0\n\
pair_style gran model hooke/stiffness absolute_damping on limitForce on\npair_coeff * *\n";
    let (_d, path) = deck_files(&[("in.stiff", &format!("{stiff}{atoms}"))]);
    let deck = read(&path);
    let law = deck.contacts[0]
        .law
        .dashpot()
        .copied()
        .expect("a spring–dashpot law");
    assert_eq!(
        (
            law.stiffness,
            law.damping,
            law.exponent,
            law.damping_exponent
        ),
        (1e6, 25.0, 1.0, 0.0)
    );
    assert!(law.clamp_attractive);
    assert_eq!(deck.contacts[0].cor_entered, None);
    assert!(
        deck.contacts[0]
            .traps
            .iter()
            .any(|t| t.starts_with("limitForce on"))
    );
    // hertz/stiffness: kn and gamman (per mass) scaled by sqrt(R* δ).
    let hs = "units si\natom_style granular\ncreate_box 1 box\n\
fix k all property/global kn peratomtypepair 1 1e9\nfix g all property/global gamman peratomtypepair 1 100\n\
pair_style gran model hertz/stiffness\npair_coeff * *\n";
    let (_d, path) = deck_files(&[("in.hs", &format!("{hs}{atoms}"))]);
    let law = read(&path).contacts[0]
        .law
        .dashpot()
        .copied()
        .expect("a spring–dashpot law");
    assert!(relative(law.stiffness, 1e9 * r.sqrt()) < 1e-14);
    assert!(relative(law.damping, 100.0 * m * r.sqrt()) < 1e-14);
    assert_eq!((law.exponent, law.damping_exponent), (1.5, 0.5));
}

#[test]
fn atoms_set_by_type_continuations_and_command_line_variables_are_read() {
    let text = format!(
        "variable r index 0.01\nvariable rho string 7800\n{HEAD}pair_style gran &\n  model hertz\npair_coeff * *\n\
create_atoms 2 region everywhere\nset type 2 diameter $(2*v_r) density ${{rho}}\nvariable q equal 1e-6\ntimestep $q\n\
fix w all wall/gran model hertz primitive type 3 zplane 0.0 limitForce on\n"
    );
    let (_d, path) = deck_files(&[("in.deck", &text)]);
    let options = DeckOptions {
        variables: vec![("r".into(), "0.02".into())],
        ..DeckOptions::default()
    };
    let (_, deck) = read_deck(&path, None, &options).unwrap();
    // The command line's r wins over the deck's index variable, as -var does.
    assert_eq!(deck.bodies[0].radius, 0.02);
    assert_eq!(deck.bodies[0].type_id, 2);
    assert_eq!(deck.timestep, 1e-6);
    assert_eq!(
        deck.transplant.walls,
        ["fix w all wall/gran model hertz primitive type 3 zplane 0.0 limitForce on"]
    );
    // The wall's own settings: clamped at the wall, not between the balls.
    assert!(
        deck.contacts[1]
            .law
            .dashpot()
            .expect("a spring–dashpot law")
            .clamp_attractive
            && !deck.contacts[0]
                .law
                .dashpot()
                .expect("a spring–dashpot law")
                .clamp_attractive
    );
    // Particles given on the command line replace the deck's sizes of their type.
    let options = DeckOptions {
        particles: vec![GivenParticle {
            type_id: 2,
            radius: 0.05,
            density: 1000.0,
        }],
        ..DeckOptions::default()
    };
    let (_, deck) = read_deck(&path, None, &options).unwrap();
    assert_eq!(deck.bodies.len(), 1);
    assert_eq!(
        (deck.bodies[0].radius, deck.bodies[0].density),
        (0.05, 1000.0)
    );
}
