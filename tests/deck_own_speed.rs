//! The deck's own impact speed as the default: an insertion's `vel` (LIGGGHTS), `velocity …
//! set` (LIGGGHTS, LAMMPS), YADE's `state.vel` (live: YADE sets the script up), taken where
//! the deck gives one and said in the table's title; a zero speed or a value only the run
//! knows gives none, and the default speeds stay.

mod common;

use common::deck::{deck_files, hide_codes};
use common::{millimpact, root};
use millimpact::analysis::deck::{read_deck, velocities};
use millimpact::codes::deck::DeckOptions;

fn read(path: &std::path::Path) -> millimpact::codes::deck::UserDeck {
    hide_codes();
    read_deck(path, None, &DeckOptions::default())
        .unwrap_or_else(|e| panic!("{e}"))
        .1
}

#[test]
fn an_insertion_vel_or_a_velocity_set_is_the_decks_own_speed() {
    std::env::set_current_dir(root()).unwrap();
    let deck = read(std::path::Path::new(
        "tests/data/deck/shapes/lg-hertz-primitive.in",
    ));
    let (v, from) = deck.representative_velocity.clone().unwrap();
    // `vel constant 0. 0. -1.5`: its length.
    assert_eq!(v.to_bits(), 1.5f64.to_bits());
    assert_eq!(
        from,
        "insertion vel (tests/data/deck/shapes/lg-hertz-primitive.in:24)"
    );
    let (speeds, said) = velocities(&deck, &[]);
    assert_eq!(speeds, [0.75, 1.5, 3.0]);
    assert!(said.contains("insertion vel"), "{said}");
    let deck = read(std::path::Path::new(
        "tests/data/deck/shapes/lg-create-atoms-set.in",
    ));
    let (v, from) = deck.representative_velocity.unwrap();
    assert_eq!(v.to_bits(), 1.2f64.to_bits());
    assert!(
        from.starts_with("velocity set (") && from.ends_with(":22)"),
        "{from}"
    );
    // Its own speed wins over the speed the Hooke model is set for.
    let deck = read(std::path::Path::new(
        "tests/data/deck/shapes/lg-hooke-charvel.in",
    ));
    assert!(
        deck.representative_velocity
            .unwrap()
            .1
            .starts_with("insertion vel")
    );
}

#[test]
fn a_lammps_velocity_set_is_its_speed_and_a_zero_or_running_value_is_none() {
    let head = "units si\natom_style sphere\natom_modify map array\ncomm_modify vel yes\n\
region box block -1 1 -1 1 0 1 units box\ncreate_box 1 box\ncreate_atoms 1 single 0 0 0.5\n\
set type 1 diameter 0.01 density 2500\npair_style granular\n\
pair_coeff * * hooke 1e5 0.5 tangential linear_nohistory 0 0\n\
fix floor all wall/gran granular hooke 1e5 0.5 tangential linear_nohistory 0 0 zplane 0 NULL\n\
timestep 1e-6\n";
    let (_d, path) = deck_files(&[("in.v", &format!("{head}velocity all set 0.6 NULL -0.8\n"))]);
    let deck = read(&path);
    let (v, _) = deck.representative_velocity.unwrap();
    assert!((v - 1.0).abs() < 1e-15, "{v}");
    for line in [
        "velocity all set 0 0 0\n",
        "velocity all set v_vx 0 0\n",
        "velocity all create 300 4928\n",
    ] {
        let (_d, path) = deck_files(&[("in.v", &format!("{head}{line}"))]);
        let deck = read(&path);
        assert_eq!(deck.representative_velocity, None, "{line}");
        assert_eq!(velocities(&deck, &[]).0, [1.0, 2.0, 4.0]);
    }
}

/// YADE's `state.vel` as the set-up leaves it, named in the table's title.
#[test]
#[ignore = "live: runs YADE to set up a script whose sphere has a state.vel"]
fn a_yade_state_vel_is_the_decks_own_speed() {
    let out = millimpact()
        .current_dir(root())
        .args(["deck", "tests/data/deck/shapes/yade-viscel.py"])
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    let title = stdout.lines().next().unwrap_or_default();
    assert!(
        title.contains("impact speeds 0.75, 1.5, 3 m/s (around the deck's state.vel (tests/data/deck/shapes/yade-viscel.py:"),
        "{title}"
    );
}
