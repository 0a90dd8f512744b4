//! `millimpact deck` without a code: the deck readers (each construct, includes and variables,
//! every refusal naming its file and line, exit 2 with nothing run), and snapshots of every
//! format from the runs `tests/deck_live.rs` recorded in the real codes.

// A value read from a deck is the number written in it, bit for bit: compared exactly.
#![allow(clippy::float_cmp)]

mod common;

use std::path::{Path, PathBuf};

use common::{millimpact, root};
use millimpact::analysis::deck::{RecordedRuns, check_deck, read_deck};
use millimpact::codes::CodeName;
use millimpact::codes::deck::{DeckOptions, GivenParticle, Partner, TypeRef, UserDeck};
use millimpact::codes::yade::deck::YadeDeck;
use millimpact::model::law::DashpotLaw;
use millimpact::output::{Format, export};

const MILL: &str = "examples/decks/liggghts-mill/in.mill";

fn read(path: &Path) -> UserDeck {
    read_deck(path, None, &DeckOptions::default())
        .unwrap_or_else(|e| panic!("{e}"))
        .1
}

/// A deck in a fresh folder: `files` are (name, text); the first is the deck.
fn deck_files(files: &[(&str, &str)]) -> (tempfile::TempDir, PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    for (name, text) in files {
        std::fs::write(dir.path().join(name), text).unwrap();
    }
    let path = dir.path().join(files[0].0);
    (dir, path)
}

/// The lines every small deck below shares: two steel types, a wall type, COR 0.5.
const HEAD: &str = "units si\natom_style granular\nhard_particles yes\ncreate_box 3 box\n\
fix m1 all property/global youngsModulus peratomtype 2e11 2e11 2e11\n\
fix m2 all property/global poissonsRatio peratomtype 0.3 0.3 0.3\n\
fix m3 all property/global coefficientRestitution peratomtypepair 3 0.5 0.5 0.5 0.5 0.5 0.5 0.5 0.5 0.5\n";

fn relative(a: f64, b: f64) -> f64 {
    ((a - b) / b).abs()
}

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

/// Each deck with one bad line, and what its error must say besides its file and line.
#[test]
fn bad_lines_are_refused_with_their_file_line_and_what_is_supported() {
    let atoms = "pair_coeff * *\ncreate_atoms 1 single 0 0 0\nset atom 1 diameter 0.02 density 7800\ntimestep 1e-7\n";
    let cases: [(&str, String, usize, &str); 10] = [
        (
            "normal model",
            format!("{HEAD}pair_style gran model edinburgh\n{atoms}"),
            8,
            "supported: model hertz, hooke",
        ),
        (
            "cohesion",
            format!("{HEAD}pair_style gran model hertz cohesion sjkr\n{atoms}"),
            8,
            "supported: cohesion off",
        ),
        (
            "pair style",
            format!("{HEAD}pair_style lj/cut 2.5\n{atoms}"),
            8,
            "supported: pair_style gran",
        ),
        (
            "unknown variable",
            format!("{HEAD}pair_style gran model hertz\ntimestep ${{dt}}\n"),
            9,
            "`dt` is not defined",
        ),
        (
            "running value",
            format!(
                "{HEAD}variable t equal step*2\npair_style gran model hertz\ntimestep ${{t}}\n"
            ),
            10,
            "thermo keyword",
        ),
        (
            "units",
            format!(
                "units cgs\n{}pair_style gran model hertz\n{atoms}",
                &HEAD[9..]
            ),
            1,
            "supported: units si",
        ),
        (
            "soft limit",
            format!(
                "{}pair_style gran model hertz\n{atoms}",
                HEAD.replace("hard_particles yes\n", "")
            ),
            4,
            "hard_particles yes",
        ),
        (
            "integrator",
            format!("{HEAD}pair_style gran model hertz\nfix i all nve/limit 0.1\n{atoms}"),
            9,
            "supported: fix nve/sphere",
        ),
        (
            "template",
            format!(
                "{HEAD}pair_style gran model hertz\nfix p all particletemplate/sphere 1 atom_type 1 density constant 7800 radius gaussian 0.01 0.001\ntimestep 1e-7\n"
            ),
            9,
            "--particle 1:RADIUS:DENSITY",
        ),
        (
            "multisphere",
            format!(
                "{HEAD}pair_style gran model hertz\nfix p all particletemplate/multisphere 1 atom_type 1\n"
            ),
            9,
            "supported: particletemplate/sphere",
        ),
    ];
    for (what, text, line, says) in cases {
        let (_d, path) = deck_files(&[("in.bad", &text)]);
        let e = read_deck(&path, None, &DeckOptions::default())
            .unwrap_err()
            .to_string();
        let at = format!("{}:{line}: ", path.display());
        assert!(e.starts_with(&at) && e.contains(says), "{what}: {e}");
    }
}

#[test]
fn an_included_file_names_its_own_lines_and_a_missing_one_is_named() {
    let (_d, path) = deck_files(&[
        ("in.main", &format!("{HEAD}include more.in\n")),
        (
            "more.in",
            "# the pair line\n\npair_style gran model luding\n",
        ),
    ]);
    let e = read_deck(&path, None, &DeckOptions::default())
        .unwrap_err()
        .to_string();
    assert!(e.contains("more.in:3: normal model `luding`"), "{e}");
    let (_d, path) = deck_files(&[("in.main", &format!("{HEAD}include nowhere.in\n"))]);
    let e = read_deck(&path, None, &DeckOptions::default())
        .unwrap_err()
        .to_string();
    assert!(
        e.starts_with("cannot read ") && e.contains("nowhere.in"),
        "{e}"
    );
}

#[test]
fn the_command_refuses_a_bad_deck_in_one_line_with_exit_2_and_runs_nothing() {
    let (_d, path) = deck_files(&[(
        "in.bad",
        &format!("{HEAD}pair_style gran model hertz cohesion sjkr\n"),
    )]);
    let out = millimpact()
        .args(["deck", path.to_str().unwrap()])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(out.stdout.is_empty());
    let err = String::from_utf8(out.stderr).unwrap();
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(
        err.starts_with("error: ") && err.contains("in.bad:8: cohesion sjkr"),
        "{err}"
    );
    // A file no reader takes.
    let (_d, path) = deck_files(&[("notes.txt", "a list of groceries\n")]);
    let out = millimpact()
        .args(["deck", path.to_str().unwrap()])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8(out.stderr).unwrap();
    assert!(
        err.contains("not a deck of any code this build reads; supported: liggghts:"),
        "{err}"
    );
}

/// Every format of the mill deck's check, from the runs recorded in LIGGGHTS.
#[test]
fn snapshots_of_the_mill_deck_in_every_format() {
    std::env::set_current_dir(root()).unwrap();
    let runs: RecordedRuns = serde_json::from_str(
        &std::fs::read_to_string(root().join("tests/data/deck/liggghts-mill.runs.json")).unwrap(),
    )
    .unwrap();
    let (code, deck) = read_deck(Path::new(MILL), None, &DeckOptions::default()).unwrap();
    assert_eq!(code, CodeName::Liggghts);
    let report = check_deck(code, &deck, (vec![4.0], "given".into()), &runs).unwrap();
    assert!(report.impacts.iter().all(|i| i.failure.is_none()));
    for format in Format::ALL {
        let text = export(&report, format).unwrap();
        insta::assert_snapshot!(format!("deck_liggghts_mill_{format}"), text);
    }
}

/// `report --deck` reads its decks before any work: a bad one is the same one line, exit 2,
/// and no report folder.
#[test]
fn the_report_refuses_a_bad_deck_before_any_work() {
    let (dir, path) = deck_files(&[(
        "in.bad",
        &format!("{HEAD}pair_style gran model hertz cohesion sjkr\n"),
    )]);
    let out_dir = dir.path().join("report");
    let out = millimpact()
        .current_dir(root())
        .args(["report", "--deck", path.to_str().unwrap(), "--out"])
        .arg(&out_dir)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(out.stdout.is_empty());
    let err = String::from_utf8(out.stderr).unwrap();
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(
        err.starts_with("error: ") && err.contains("in.bad:8: cohesion sjkr"),
        "{err}"
    );
    assert!(!out_dir.exists(), "no report written");
}

/// The mill deck's part of `report --deck`, from the runs recorded in LIGGGHTS: its tables as
/// the pages render them, and the whole check beside it as JSON and CSV.
#[test]
fn snapshot_of_the_mill_deck_s_part_of_the_report() {
    std::env::set_current_dir(root()).unwrap();
    let runs: RecordedRuns = serde_json::from_str(
        &std::fs::read_to_string(root().join("tests/data/deck/liggghts-mill.runs.json")).unwrap(),
    )
    .unwrap();
    let (code, deck) = read_deck(Path::new(MILL), None, &DeckOptions::default()).unwrap();
    let check = check_deck(code, &deck, (vec![4.0], "given".into()), &runs).unwrap();
    let (part, data) = millimpact::analysis::report::deck_part(1, &check).unwrap();
    let names: Vec<&str> = data.iter().map(|d| d.name.as_str()).collect();
    assert_eq!(names, ["deck-1.json", "deck-1.csv"]);
    assert_eq!(data[0].text, export(&check, Format::Json).unwrap());
    assert_eq!(data[1].text, export(&check, Format::Csv).unwrap());
    // Every pair at the speed, and the wall's traps, warnings and what was left out.
    assert_eq!(part.tables[0].rows.len(), check.impacts.len());
    let ids: Vec<&str> = part.tables.iter().map(|t| t.id.as_str()).collect();
    assert_eq!(
        ids,
        [
            "deck-1-pairs",
            "deck-1-traps",
            "deck-1-warnings",
            "deck-1-left-out"
        ]
    );
    let report = millimpact::analysis::report::Report {
        title: "report".into(),
        parts: vec![part],
        appendix: vec![],
        data,
        failures: vec![],
    };
    let (_, markdown) = millimpact::output::report_page::render_pages(&report).unwrap();
    insta::assert_snapshot!("deck_liggghts_mill_report_part", markdown);
}

/// The worked example of `docs/src/commands/deck.md` is the table of the recorded check.
#[test]
fn the_books_worked_example_is_the_recorded_check() {
    std::env::set_current_dir(root()).unwrap();
    let runs: RecordedRuns = serde_json::from_str(
        &std::fs::read_to_string(root().join("tests/data/deck/liggghts-mill.runs.json")).unwrap(),
    )
    .unwrap();
    let (code, deck) = read_deck(Path::new(MILL), None, &DeckOptions::default()).unwrap();
    let report = check_deck(code, &deck, (vec![4.0], "given".into()), &runs).unwrap();
    let table = export(&report, Format::Table).unwrap();
    assert_eq!(book_example("<!-- deck example:"), table);
}

/// The text block after `marker` in `docs/src/commands/deck.md`, up to its end marker.
fn book_example(marker: &str) -> String {
    let page = std::fs::read_to_string(root().join("docs/src/commands/deck.md")).unwrap();
    let start = page.find(marker).expect("the example's marker");
    let block = &page[start..];
    block[block.find("```text\n").unwrap() + 8..block.find("```\n<!-- end of ").unwrap()]
        .to_string()
}

const GRANULAR: &str = "examples/decks/lammps-granular/in.granular";

/// As on a machine without the codes: a LAMMPS deck is read with the build's fallback
/// conventions (no probe starts).
fn hide_codes() {
    for (variable, missing) in common::codes_hidden() {
        // SAFETY: every test of this file that sets them sets the same values, before reading.
        unsafe { std::env::set_var(variable, missing) };
    }
}

#[test]
fn the_lammps_deck_is_read_with_the_builds_conventions() {
    hide_codes();
    let (code, deck) = read_deck(&root().join(GRANULAR), None, &DeckOptions::default()).unwrap();
    assert_eq!(code, CodeName::Lammps);
    let sizes: Vec<(u32, f64, f64, Option<f64>)> = deck
        .bodies
        .iter()
        .map(|b| (b.type_id, b.radius, b.density, b.youngs_modulus))
        .collect();
    assert_eq!(
        sizes,
        [
            (1, 0.005, 2500.0, Some(6.3e10)),
            (2, 0.0025, 2500.0, Some(6.3e10))
        ]
    );
    assert_eq!(
        deck.transplant.walls,
        [
            "fix floor all wall/gran granular hertz/material 63000000000 0.7 0.22 damping tsuji tangential mindlin NULL 1.0 0.5 limit_damping zplane 0 NULL"
        ]
    );
    // The ball on the floor: the 2021 wall's E/(2(1−ν)), R* = R, m* = m, tsuji's α(e_in), clamped.
    let wall = &deck.contacts[3];
    let body = &deck.bodies[0];
    let k = 4.0 / 3.0 * 6.3e10 / (2.0 * (1.0 - 0.22)) * 0.005f64.sqrt();
    let alpha = millimpact::codes::lammps::tsuji_alpha(0.7);
    assert!(
        relative(
            wall.law.dashpot().expect("a spring–dashpot law").stiffness,
            k
        ) < 1e-14
    );
    assert!(
        relative(
            wall.law.dashpot().expect("a spring–dashpot law").damping,
            alpha * (body.mass * k).sqrt()
        ) < 1e-14
    );
    assert!(
        wall.law
            .dashpot()
            .expect("a spring–dashpot law")
            .clamp_attractive
    );
    assert_eq!(wall.cor_entered, Some(0.7));
    // Two beads: the pair's E/(2(1−ν²)), not clamped.
    let pair = &deck.contacts[0];
    let k = 4.0 / 3.0 * 6.3e10 / (2.0 * (1.0 - 0.22 * 0.22)) * 0.0025f64.sqrt();
    assert!(
        relative(
            pair.law.dashpot().expect("a spring–dashpot law").stiffness,
            k
        ) < 1e-14
            && !pair
                .law
                .dashpot()
                .expect("a spring–dashpot law")
                .clamp_attractive
    );
}

#[test]
fn a_lammps_line_the_build_lacks_or_a_pair_without_coefficients_is_refused() {
    hide_codes();
    let head = "units si\natom_style sphere\ncreate_box 2 box\ncreate_atoms 1 single 0 0 0\ncreate_atoms 2 single 1 0 0\nset type 1 diameter 0.01 density 2500\nset type 2 diameter 0.01 density 2500\ntimestep 1e-6\npair_style granular\n";
    let (_d, path) = deck_files(&[(
        "in.cr",
        &format!(
            "{head}pair_coeff * * hertz/material 1e9 0.5 0.3 damping coeff_restitution tangential linear_nohistory 0 0\n"
        ),
    )]);
    let e = read_deck(&path, Some(CodeName::Lammps), &DeckOptions::default())
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("in.cr:10: damping coeff_restitution: this build (probed) has none")
            && e.contains("--code lammps-2025"),
        "{e}"
    );
    // A pair_coeff without its tangential model, which both builds refuse.
    let (_d, path) = deck_files(&[(
        "in.tangential",
        &format!("{head}pair_coeff * * hertz/material 1e9 0.5 0.3 damping tsuji\n"),
    )]);
    let e = read_deck(&path, None, &DeckOptions::default())
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("in.tangential:10: a pair_coeff without a tangential model"),
        "{e}"
    );
    let (_d, path) = deck_files(&[(
        "in.dmt",
        &format!("{head}pair_coeff * * dmt 1e9 0.5 0.3 0.1\n"),
    )]);
    let e = read_deck(&path, None, &DeckOptions::default())
        .unwrap_err()
        .to_string();
    assert!(
        e.contains(
            "in.dmt:10: normal model `dmt`; supported: hooke k d, hertz k d, hertz/material E d nu"
        ),
        "{e}"
    );
}

#[test]
fn snapshots_of_the_lammps_deck_in_every_format() {
    hide_codes();
    std::env::set_current_dir(root()).unwrap();
    let runs: RecordedRuns = serde_json::from_str(
        &std::fs::read_to_string(root().join("tests/data/deck/lammps-granular.runs.json")).unwrap(),
    )
    .unwrap();
    let (code, deck) = read_deck(Path::new(GRANULAR), None, &DeckOptions::default()).unwrap();
    let report = check_deck(code, &deck, (vec![4.0], "given".into()), &runs).unwrap();
    assert!(report.impacts.iter().all(|i| i.failure.is_none()));
    for format in Format::ALL {
        let text = export(&report, format).unwrap();
        insta::assert_snapshot!(format!("deck_lammps_granular_{format}"), text);
    }
}

const KRATOS_MILL: &str = "examples/decks/kratos-mill/MaterialsDEM.json";
const KRATOS_PROJECT: &str = "examples/decks/kratos-mill/ProjectParametersDEM.json";

/// The DAMPING_GAMMA Kratos 10.4.4 wrote into the example's sub-properties when it ran the
/// example's own project (its DEMAnalysisStage, 100 steps): Thornton's fit for the Hertz
/// relations at 0.7 and 0.65, the bisection for the linear ones at 0.6.
const KRATOS_LOGGED_GAMMA: [(f64, f64); 3] = [
    (0.7, 0.111_675_654_969_499_98),
    (0.65, 0.136_969_229_119_020_37),
    (0.6, 0.180_877_685_546_875),
];

fn json(path: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

/// The example's files in a fresh folder, its materials and project edited by `materials`
/// and `project`; the path of the materials file.
fn kratos_deck(
    materials: impl Fn(&mut serde_json::Value),
    project: impl Fn(&mut serde_json::Value),
) -> (tempfile::TempDir, PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    let example = root().join("examples/decks/kratos-mill");
    for (name, edit) in [
        (
            "MaterialsDEM.json",
            &materials as &dyn Fn(&mut serde_json::Value),
        ),
        ("ProjectParametersDEM.json", &project),
    ] {
        let mut value = json(&example.join(name));
        edit(&mut value);
        std::fs::write(
            dir.path().join(name),
            serde_json::to_string_pretty(&value).unwrap(),
        )
        .unwrap();
    }
    std::fs::copy(
        example.join("millDEM.mdpa"),
        dir.path().join("millDEM.mdpa"),
    )
    .unwrap();
    let path = dir.path().join("MaterialsDEM.json");
    (dir, path)
}

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

/// Each Kratos setup with one bad field, and what its error must say after its file and field.
#[test]
fn bad_kratos_fields_are_refused_with_their_path_and_what_is_supported() {
    type Edit = Box<dyn Fn(&mut serde_json::Value)>;
    let none = || -> Edit { Box::new(|_| {}) };
    let cases: Vec<(&str, Edit, Edit, &str, &str)> = vec![
        (
            "law",
            Box::new(|m| {
                m["material_relations"][3]["Variables"]["DEM_DISCONTINUUM_CONSTITUTIVE_LAW_NAME"] =
                    "DEM_D_Linear_classic".into()
            }),
            none(),
            "MaterialsDEM.json: material_relations[3].Variables.DEM_DISCONTINUUM_CONSTITUTIVE_LAW_NAME: ",
            "supported: DEM_D_Hertz_viscous_Coulomb, DEM_D_Linear_viscous_Coulomb, DEM_D_Linear_Custom_Constants",
        ),
        (
            "restitution as text",
            Box::new(|m| {
                m["material_relations"][0]["Variables"]["COEFFICIENT_OF_RESTITUTION"] = "0.7".into()
            }),
            none(),
            "MaterialsDEM.json: material_relations[0].Variables.COEFFICIENT_OF_RESTITUTION: ",
            "found \"0.7\"; supported: a number",
        ),
        (
            "restitution above 1",
            Box::new(|m| {
                m["material_relations"][1]["Variables"]["COEFFICIENT_OF_RESTITUTION"] = 1.5.into()
            }),
            none(),
            "MaterialsDEM.json: material_relations[1].Variables.COEFFICIENT_OF_RESTITUTION: ",
            "supported: a restitution in (0, 1]",
        ),
        (
            "K_NORMAL missing",
            Box::new(|m| {
                m["material_relations"][4]["Variables"]["DEM_DISCONTINUUM_CONSTITUTIVE_LAW_NAME"] =
                    "DEM_D_Linear_Custom_Constants".into()
            }),
            none(),
            "MaterialsDEM.json: material_relations[4].Variables.K_NORMAL: ",
            "no K_NORMAL",
        ),
        (
            "density missing",
            Box::new(|m| {
                m["materials"][0]["Variables"]
                    .as_object_mut()
                    .unwrap()
                    .remove("PARTICLE_DENSITY");
            }),
            none(),
            "MaterialsDEM.json: materials[0].Variables.PARTICLE_DENSITY: ",
            "no PARTICLE_DENSITY",
        ),
        (
            "material name",
            Box::new(|m| m["material_assignation_table"][0][1] = "steel".into()),
            none(),
            "MaterialsDEM.json: material_assignation_table[0][1]: ",
            "material `steel` is in no material_name",
        ),
        (
            "model part",
            Box::new(|m| m["material_assignation_table"][2][0] = "FEMPart.Liner".into()),
            none(),
            "MaterialsDEM.json: material_assignation_table[2][0]: ",
            "supported: SpheresPart, DEMInletPart and RigidFacePart",
        ),
        (
            "scheme",
            none(),
            Box::new(|p| p["TranslationalIntegrationScheme"] = "Forward_Euler".into()),
            "ProjectParametersDEM.json: TranslationalIntegrationScheme: ",
            "supported: Symplectic_Euler",
        ),
        (
            "virtual mass",
            none(),
            Box::new(|p| p["VirtualMassCoefficient"] = 0.9.into()),
            "ProjectParametersDEM.json: VirtualMassCoefficient: ",
            "supported: 1.0",
        ),
        (
            "continuum",
            none(),
            Box::new(|p| p["ElementType"] = "SphericContPartDEMElement3D".into()),
            "ProjectParametersDEM.json: ElementType: ",
            "supported: SphericPartDEMElement3D",
        ),
    ];
    for (what, materials, project, at, says) in cases {
        let (dir, path) = kratos_deck(materials, project);
        let e = read_deck(&path, None, &DeckOptions::default())
            .unwrap_err()
            .to_string();
        let at = format!("{}{at}", dir.path().display().to_string() + "/");
        assert!(e.starts_with(&at) && e.contains(says), "{what}: {e}");
    }
}

#[test]
fn a_kratos_setup_lacking_a_part_says_what_and_how_to_give_it() {
    let (_d, path) = kratos_deck(
        |m| {
            m["material_relations"].as_array_mut().unwrap().remove(2);
        },
        |_| {},
    );
    let e = read_deck(&path, None, &DeckOptions::default())
        .unwrap_err()
        .to_string();
    assert!(e.contains("no material_relations entry for the materials 2 (high_chrome_iron) and 2 (high_chrome_iron)"), "{e}");
    // No .mdpa to take the radii from: named, with the flag that gives them.
    let (_d, path) = kratos_deck(|_| {}, |p| p["problem_name"] = "elsewhere".into());
    let e = read_deck(&path, None, &DeckOptions::default())
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("no radius for material 1 (forged_steel)")
            && e.contains("elsewhereDEM.mdpa")
            && e.ends_with("--particle 1:RADIUS:7800"),
        "{e}"
    );
    // A distribution in the .mdpa: more radii than are checked one by one.
    let (dir, path) = kratos_deck(|_| {}, |_| {});
    let mdpa = std::fs::read_to_string(dir.path().join("millDEM.mdpa")).unwrap();
    let mdpa = mdpa
        .replace("    2   0   0.03\n", "    2   0   0.031\n")
        .replace("    3   0   0.03\n", "    3   0   0.032\n")
        .replace("    1   0   0.03\n", "    1   0   0.029\n");
    let mdpa = mdpa.replace("    4   0   0.02\n", "    4   0   0.021\n");
    let mdpa = mdpa.replace(
        "Begin SubModelPartElements\n        1\n",
        "Begin SubModelPartElements\n        1\n        4\n",
    );
    std::fs::write(dir.path().join("millDEM.mdpa"), mdpa).unwrap();
    let e = read_deck(&path, None, &DeckOptions::default())
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("SpheresPart.DEMParts_SteelBalls (material 1 (forged_steel)) has 4 radii from 0.021 to 0.032 m") && e.contains("--particle 1:RADIUS:DENSITY"),
        "{e}"
    );
    // A project beside it that names another materials file.
    let (_d, path) = kratos_deck(
        |_| {},
        |p| {
            p["solver_settings"]["material_import_settings"]["materials_filename"] =
                "Other.json".into()
        },
    );
    let e = read_deck(&path, None, &DeckOptions::default())
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("names the materials file")
            && e.contains("Other.json")
            && e.contains("name ")
            && e.contains("ProjectParametersDEM.json instead"),
        "{e}"
    );
    // A materials file alone: the project with the time step is missing.
    let (dir, path) = kratos_deck(|_| {}, |_| {});
    std::fs::remove_file(dir.path().join("ProjectParametersDEM.json")).unwrap();
    let e = read_deck(&path, None, &DeckOptions::default())
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("no ProjectParametersDEM.json beside it") && e.contains("MaxTimeStep"),
        "{e}"
    );
}

#[test]
fn a_kratos_setup_with_an_unsupported_law_exits_2_naming_the_field_and_runs_nothing() {
    let (_d, path) = kratos_deck(
        |m| {
            m["material_relations"][0]["Variables"]["DEM_DISCONTINUUM_CONSTITUTIVE_LAW_NAME"] =
                "DEM_D_Conical_damage".into()
        },
        |_| {},
    );
    let out = millimpact()
        .args(["deck", path.to_str().unwrap()])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(out.stdout.is_empty());
    let err = String::from_utf8(out.stderr).unwrap();
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(
        err.starts_with("error: ")
            && err.contains("MaterialsDEM.json: material_relations[0].Variables.DEM_DISCONTINUUM_CONSTITUTIVE_LAW_NAME: DEM_D_Conical_damage")
            && err.contains("supported: DEM_D_Hertz_viscous_Coulomb"),
        "{err}"
    );
}

#[test]
fn each_reader_recognises_its_own_files_only() {
    let text = |p: &str| std::fs::read_to_string(root().join(p)).unwrap();
    let kratos = CodeName::Kratos.driver().deck().unwrap();
    let liggghts = CodeName::Liggghts.driver().deck().unwrap();
    let lammps = CodeName::Lammps.driver().deck().unwrap();
    for json in [KRATOS_MILL, KRATOS_PROJECT] {
        assert!(kratos.recognises(Path::new(json), &text(json)), "{json}");
        assert!(!liggghts.recognises(Path::new(json), &text(json)), "{json}");
        assert!(!lammps.recognises(Path::new(json), &text(json)), "{json}");
    }
    for script in [MILL, GRANULAR] {
        assert!(
            !kratos.recognises(Path::new(script), &text(script)),
            "{script}"
        );
    }
    // JSON of something else is no Kratos setup.
    let (_d, path) = deck_files(&[("settings.json", "{\"theme\": \"dark\"}\n")]);
    let e = read_deck(&path, None, &DeckOptions::default())
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("not a deck of any code this build reads")
            && e.contains("kratos: Kratos DEM MaterialsDEM.json or ProjectParametersDEM.json"),
        "{e}"
    );
}

/// Every format of the Kratos mill's check, from the runs recorded in Kratos.
#[test]
fn snapshots_of_the_kratos_mill_in_every_format() {
    let report = kratos_report();
    assert!(report.impacts.iter().all(|i| i.failure.is_none()));
    for format in Format::ALL {
        let text = export(&report, format).unwrap();
        insta::assert_snapshot!(format!("deck_kratos_mill_{format}"), text);
    }
}

fn kratos_report() -> millimpact::analysis::deck::DeckReport {
    std::env::set_current_dir(root()).unwrap();
    let runs: RecordedRuns = serde_json::from_str(
        &std::fs::read_to_string(root().join("tests/data/deck/kratos-mill.runs.json")).unwrap(),
    )
    .unwrap();
    let (code, deck) = read_deck(Path::new(KRATOS_MILL), None, &DeckOptions::default()).unwrap();
    check_deck(code, &deck, (vec![4.0], "given".into()), &runs).unwrap()
}

/// The Kratos example of `docs/src/commands/deck.md` is the table of the recorded check.
#[test]
fn the_books_kratos_example_is_the_recorded_check() {
    let table = export(&kratos_report(), Format::Table).unwrap();
    assert_eq!(book_example("<!-- kratos deck example:"), table);
}

const YADE_MILL: &str = "examples/decks/yade-mill/mill.py";

/// The YADE script at `script` (from the project's root) read from the recorded dump of its
/// set-up `dump` (under `tests/data/deck/yade/`, recorded as its README says): no YADE starts.
fn yade_read(script: &str, dump: &str, options: &DeckOptions) -> Result<UserDeck, String> {
    let text = std::fs::read_to_string(root().join("tests/data/deck/yade").join(dump)).unwrap();
    YadeDeck::read_dump(Path::new(script), &text, options).map_err(|e| e.to_string())
}

/// A script of `tests/data/deck/yade/` read from its recorded dump.
fn yade_case(name: &str) -> Result<UserDeck, String> {
    std::env::set_current_dir(root()).unwrap();
    yade_read(
        &format!("tests/data/deck/yade/{name}.py"),
        &format!("{name}.dump.json"),
        &DeckOptions::default(),
    )
}

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

/// Each script of `tests/data/deck/yade/` that YADE sets up but the check cannot take: its
/// line (0: the file alone) and what its error must say.
#[test]
fn yade_set_ups_the_check_cannot_take_are_refused_with_their_line_and_what_is_supported() {
    let cases: [(&str, usize, &str); 10] = [
        (
            "refuse-law",
            9,
            "functor Law2_ScGeom_MindlinPhys_HertzWithLinearShear; supported: Ig2_Sphere_Sphere_ScGeom",
        ),
        (
            "refuse-no-law",
            8,
            "without Law2_ScGeom_FrictPhys_CundallStrack",
        ),
        ("refuse-local-damping", 10, "damping = 0.2 (its default)"),
        (
            "refuse-time-stepper",
            6,
            "GlobalStiffnessTimeStepper: the time step is set while the script runs",
        ),
        (
            "refuse-material-class",
            2,
            "material class `CohFrictMat` (O.materials[0]); supported: FrictMat, ViscElMat",
        ),
        (
            "refuse-free-box",
            4,
            "supported: box(…, fixed=True) as a wall",
        ),
        (
            "refuse-match-maker",
            8,
            "its MatchMaker gives YADE no number for the materials 0 and 0",
        ),
        (
            "refuse-no-geometry",
            4,
            "no Ig2_Wall_Sphere_ScGeom in the InteractionLoop",
        ),
        (
            "refuse-not-appended",
            3,
            "a Sphere whose material is not in O.materials (its id is -1",
        ),
        ("refuse-no-step", 0, "the script sets no O.dt"),
    ];
    for (name, line, says) in cases {
        let e = yade_case(name).unwrap_err();
        let at = match line {
            0 => format!("tests/data/deck/yade/{name}.py: "),
            _ => format!("tests/data/deck/yade/{name}.py:{line}: "),
        };
        assert!(e.starts_with(&at) && e.contains(says), "{name}: {e}");
    }
    // The radius given on the command line replaces the type's, by its O.materials id.
    let options = DeckOptions {
        particles: vec![GivenParticle {
            type_id: 0,
            radius: 0.02,
            density: 7800.0,
        }],
        ..DeckOptions::default()
    };
    let deck = yade_read("tests/data/deck/yade/base.py", "base.dump.json", &options).unwrap();
    let radii: Vec<f64> = deck.bodies.iter().map(|b| b.radius).collect();
    assert_eq!(radii, [0.02]);
    // A LIGGGHTS deck takes no type 0.
    let e = read_deck(&root().join(MILL), None, &options)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("--particle 0:0.02:7800: atom types count from 1"),
        "{e}"
    );
    // --var names nothing in a YADE script.
    let options = DeckOptions {
        variables: vec![("E".into(), "1e7".into())],
        ..DeckOptions::default()
    };
    let e = yade_read("tests/data/deck/yade/base.py", "base.dump.json", &options).unwrap_err();
    assert!(
        e.contains("--var E: a YADE script's names are its own"),
        "{e}"
    );
}

#[test]
fn a_yade_script_that_runs_before_its_engines_are_set_is_refused_naming_that_line() {
    let e = yade_case("runs-early").unwrap_err();
    assert_eq!(
        e,
        "tests/data/deck/yade/runs-early.py: the script sets no O.engines before the reading stopped at its first step (O.run, line 7): YADE's default engines are no contact law of the script's; O.engines = [..., InteractionLoop([Ig2…], [Ip2…], [Law2…]), NewtonIntegrator(damping=0)] before the first O.run"
    );
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

#[test]
fn a_yade_dump_that_does_not_read_names_its_field() {
    let e = YadeDeck::read_dump(
        Path::new("s.py"),
        "{\"version\": 1}",
        &DeckOptions::default(),
    )
    .unwrap_err()
    .to_string();
    assert!(
        e.starts_with("s.py: the dump: YADE's dump of the set-up does not read: "),
        "{e}"
    );
}

#[test]
fn a_yade_script_with_an_unsupported_functor_is_refused_naming_its_line() {
    std::env::set_current_dir(root()).unwrap();
    let e = yade_read(
        "tests/data/deck/yade-capillary.py",
        "capillary.dump.json",
        &DeckOptions::default(),
    )
    .unwrap_err();
    assert!(
        e.starts_with("tests/data/deck/yade-capillary.py:14: functor Ip2_FrictMat_FrictMat_CapillaryPhys; supported: "),
        "{e}"
    );
}

fn yade_report() -> millimpact::analysis::deck::DeckReport {
    std::env::set_current_dir(root()).unwrap();
    let runs: RecordedRuns = serde_json::from_str(
        &std::fs::read_to_string(root().join("tests/data/deck/yade-mill.runs.json")).unwrap(),
    )
    .unwrap();
    let deck = yade_read(YADE_MILL, "mill.dump.json", &DeckOptions::default()).unwrap();
    let report = check_deck(CodeName::Yade, &deck, (vec![4.0], "given".into()), &runs).unwrap();
    assert!(report.impacts.iter().all(|i| i.failure.is_none()));
    report
}

/// Every format of the YADE mill's check, from the runs recorded in YADE.
#[test]
fn snapshots_of_the_yade_mill_script_in_every_format() {
    let report = yade_report();
    for format in Format::ALL {
        let text = export(&report, format).unwrap();
        insta::assert_snapshot!(format!("deck_yade_mill_{format}"), text);
    }
}

/// The YADE example of `docs/src/commands/deck.md` is the table of the recorded check.
#[test]
fn the_books_yade_example_is_the_recorded_check() {
    let table = export(&yade_report(), Format::Table).unwrap();
    let page = std::fs::read_to_string(root().join("docs/src/commands/deck.md")).unwrap();
    let start = page
        .find("<!-- yade deck example:")
        .expect("the example's marker");
    let block = &page[start..];
    let body = &block[block.find("```text\n").unwrap() + 8
        ..block
            .find("```\n<!-- end of yade deck example -->")
            .unwrap()];
    assert_eq!(body, table);
}

const MIXED: &str = "examples/decks/lammps-mixed/in.mixed";
const MIXED_HERTZ: &str = "tests/data/deck/lammps-mixed-hertz.in";

/// tsuji's fit as both builds apply it (their probes measure no √2), evaluated at run time as
/// the reader evaluates it: near e = 0.9 its terms (up to 18) cancel to 0.05, and
/// the compiler's folding of a constant argument rounds them otherwise (by 2e-14).
fn poly(e: f64) -> f64 {
    millimpact::codes::lammps::tsuji_alpha(std::hint::black_box(e))
}

/// Read `path` with the reader of `code` (the build's fallback conventions: no code runs).
fn read_with(code: CodeName, path: &Path) -> UserDeck {
    hide_codes();
    read_deck(path, Some(code), &DeckOptions::default())
        .unwrap_or_else(|e| panic!("{e}"))
        .1
}

/// Two bead types, each with lines of its own only: the pair 1 2 is LAMMPS's to mix.
fn two_types(lines: &str) -> String {
    format!(
        "units si\natom_style sphere\ncreate_box 2 box\ncreate_atoms 1 single 0 0 0\ncreate_atoms 2 single 1 0 0\n\
set type 1 diameter 0.004 density 2500\nset type 2 diameter 0.006 density 7800\ntimestep 1e-7\npair_style granular\n{lines}"
    )
}

/// The glass–steel pair of the mixed example, as each build mixes it from `pair_coeff 1 1`
/// and `2 2`: the 2025 build Hertz with the two materials' E* and tsuji's α of √(e₁e₂), the
/// 2021 build a linear spring of √(k₁k₂) and a dashpot of √(α₁α₂), whatever the lines say.
#[test]
fn each_build_mixes_the_pair_of_two_bead_types_as_its_source_does() {
    let path = root().join(MIXED);
    let (e1, nu1, c1, e2, nu2, c2): (f64, f64, f64, f64, f64, f64) =
        (6.3e10, 0.22, 0.9, 2.0e11, 0.3, 0.6);
    let new = read_with(CodeName::Lammps2025, &path);
    let (glass, steel) = (&new.bodies[0], &new.bodies[1]);
    let r: f64 = glass.radius * steel.radius / (glass.radius + steel.radius);
    let m = glass.mass * steel.mass / (glass.mass + steel.mass);
    let types: Vec<[TypeRef; 2]> = new.contacts.iter().map(|c| c.types).collect();
    assert_eq!(types[1], [TypeRef::Type(1), TypeRef::Type(2)]);
    let pair = &new.contacts[1];
    let e_star = 1.0 / ((1.0 - nu1 * nu1) / e1 + (1.0 - nu2 * nu2) / e2);
    let k = 4.0 / 3.0 * e_star * r.sqrt();
    let alpha = poly((c1 * c2).sqrt());
    let law = pair.law.dashpot().copied().expect("a spring–dashpot law");
    assert!(relative(law.stiffness, k) < 1e-14, "{} {k}", law.stiffness);
    assert!(relative(law.damping, alpha * (m * k).sqrt()) < 1e-14);
    assert!(relative(law.mass, m) < 1e-14);
    assert_eq!((law.exponent, law.damping_exponent), (1.5, 0.25));
    assert!(!law.clamp_attractive);
    // The damping is converted after mixing: √(α₁α₂) would be 25 % weaker.
    assert!(alpha / (poly(c1) * poly(c2)).sqrt() > 1.3);
    // No COR is entered for a mixed pair; its lines are both types' own.
    assert_eq!(pair.cor_entered, None);
    let lines: Vec<usize> = pair
        .lines
        .iter()
        .map(|l| match l {
            millimpact::codes::deck::DeckSource::Line(l) => l.line,
            other => panic!("{other}"),
        })
        .collect();
    assert_eq!(lines, [29, 30]);
    assert!(
        pair.traps[0].starts_with("mixed: no pair_coeff sets the types 1 and 2"),
        "{:?}",
        pair.traps
    );
    assert!(
        pair.traps.iter().any(|t| t.starts_with(
            "COR of the mixed pair: none entered (the lines have e = 0.9 in 1 1, e = 0.6 in 2 2)"
        )),
        "{:?}",
        pair.traps
    );
    // The types' own pairs are their own lines.
    assert_eq!(new.contacts[0].cor_entered, Some(c1));
    assert_eq!(new.contacts[2].cor_entered, Some(c2));

    let old = read_with(CodeName::Lammps, &path);
    let pair = &old.contacts[1];
    let stored = |e: f64, nu: f64| 4.0 / 3.0 * e / (2.0 * (1.0 - nu * nu));
    let k = (stored(e1, nu1) * stored(e2, nu2)).sqrt();
    let d = (poly(c1) * poly(c2)).sqrt();
    let law = pair.law.dashpot().copied().expect("a spring–dashpot law");
    assert!(relative(law.stiffness, k) < 1e-14, "{} {k}", law.stiffness);
    assert!(relative(law.damping, d) < 1e-14, "{} {d}", law.damping);
    assert_eq!((law.exponent, law.damping_exponent), (1.0, 0.0));
    assert!(!law.clamp_attractive);
    assert_eq!(pair.cor_entered, None);
    assert!(
        pair.traps
            .iter()
            .any(|t| t.starts_with("mixed pair's model left unset")),
        "{:?}",
        pair.traps
    );
    // The own pairs read the same in both builds.
    assert_eq!(old.contacts[0].law, new.contacts[0].law);
}

/// hertz with damping velocity: the 2025 build keeps the form with √(k₁k₂) and √(d₁d₂); the
/// 2021 build runs those numbers as hooke.
#[test]
fn a_hertz_pair_is_mixed_whole_in_2025_and_as_hooke_in_2021() {
    let path = root().join(MIXED_HERTZ);
    let new = read_with(CodeName::Lammps2025, &path);
    let (a, b) = (&new.bodies[0], &new.bodies[1]);
    let r: f64 = a.radius * b.radius / (a.radius + b.radius);
    let k = (4e10f64 * 1.3e11).sqrt();
    let d = 3f64.sqrt();
    let law = new.contacts[1]
        .law
        .dashpot()
        .copied()
        .expect("a spring–dashpot law");
    assert!(relative(law.stiffness, k * r.sqrt()) < 1e-14);
    assert!(relative(law.damping, d) < 1e-14);
    assert_eq!((law.exponent, law.damping_exponent), (1.5, 0.0));
    // limit_damping of type 2's line: on in the 2025 pair, not in the 2021 one.
    assert!(law.clamp_attractive);
    let law = read_with(CodeName::Lammps, &path).contacts[1]
        .law
        .dashpot()
        .copied()
        .expect("a spring–dashpot law");
    assert!(relative(law.stiffness, k) < 1e-14);
    assert!(relative(law.damping, d) < 1e-14);
    assert_eq!((law.exponent, law.damping_exponent), (1.0, 0.0));
    assert!(!law.clamp_attractive);
}

/// limit_damping on one type's line: the 2025 pair takes it, the 2021 pair does not; and
/// coeff_restitution mixed in 2025 realises the geometric mean of the two e's exactly.
#[test]
fn limit_damping_and_coeff_restitution_reach_the_mixed_pair_as_each_build_has_it() {
    let tsuji = two_types(
        "pair_coeff 1 1 hertz/material 6.3e10 0.9 0.22 damping tsuji tangential linear_nohistory 0 0 limit_damping\n\
pair_coeff 2 2 hertz/material 2e11 0.6 0.3 damping tsuji tangential linear_nohistory 0 0\n",
    );
    let (_d, path) = deck_files(&[("in.ld", &tsuji)]);
    let new = read_with(CodeName::Lammps2025, &path);
    assert!(
        new.contacts[1]
            .law
            .dashpot()
            .expect("a spring–dashpot law")
            .clamp_attractive
    );
    assert!(
        new.contacts[1]
            .traps
            .iter()
            .any(|t| t.starts_with("limit_damping is on in pair_coeff 1 1 only"))
    );
    let old = read_with(CodeName::Lammps, &path);
    assert!(
        !old.contacts[1]
            .law
            .dashpot()
            .expect("a spring–dashpot law")
            .clamp_attractive
    );
    assert!(
        old.contacts[1]
            .traps
            .iter()
            .any(|t| t.starts_with("limit_damping of the lines does not reach the mixed pair"))
    );
    // The own pair 1 1 keeps its clamp in both.
    assert!(
        new.contacts[0]
            .law
            .dashpot()
            .expect("a spring–dashpot law")
            .clamp_attractive
            && old.contacts[0]
                .law
                .dashpot()
                .expect("a spring–dashpot law")
                .clamp_attractive
    );

    let restitution = two_types(
        "pair_coeff 1 1 hertz/material 6.3e10 0.9 0.22 damping coeff_restitution tangential linear_nohistory 0 0\n\
pair_coeff 2 2 hertz/material 2e11 0.4 0.3 damping coeff_restitution tangential linear_nohistory 0 0\n",
    );
    let (_d, path) = deck_files(&[("in.cr", &restitution)]);
    let law = read_with(CodeName::Lammps2025, &path).contacts[1]
        .law
        .dashpot()
        .copied()
        .expect("a spring–dashpot law");
    let cor = millimpact::solve::dashpot::accurate_metrics(&law, 2.0, 1e-12)
        .unwrap()
        .cor;
    assert!((cor - 0.6).abs() < 1e-9, "{cor}");
}

/// What LAMMPS refuses, refused with the lines: two own lines of different forms to mix, a
/// type without its own line, and (in the 2021 build) `pair_coeff J I` with `J > I`.
#[test]
fn a_pair_lammps_cannot_mix_is_refused_with_both_lines() {
    let forms = two_types(
        "pair_coeff 1 1 hertz/material 6.3e10 0.9 0.22 damping tsuji tangential linear_nohistory 0 0\n\
pair_coeff 2 2 hooke 1e6 0.5 damping velocity tangential linear_nohistory 0 0\n",
    );
    let (_d, path) = deck_files(&[("in.forms", &forms)]);
    let at = |line: usize| format!("{}:{line}", path.display());
    for code in [CodeName::Lammps, CodeName::Lammps2025] {
        hide_codes();
        let e = read_deck(&path, Some(code), &DeckOptions::default())
            .unwrap_err()
            .to_string();
        assert!(
            e.starts_with(&format!("{}: no pair_coeff sets the types 1 and 2, and LAMMPS refuses to mix them from pair_coeff 1 1 ({}: hertz/material damping tsuji tangential linear_nohistory) and 2 2 (here: hooke damping velocity tangential linear_nohistory)", at(11), at(10)))
                && e.contains("supported: a pair_coeff 1 2 of its own"),
            "{code}: {e}"
        );
    }
    // A tangential model of another name is another form too.
    let tangential = two_types(
        "pair_coeff 1 1 hertz/material 6.3e10 0.9 0.22 damping tsuji tangential mindlin NULL 1.0 0.3\n\
pair_coeff 2 2 hertz/material 2e11 0.6 0.3 damping tsuji tangential linear_nohistory 0 0\n",
    );
    let (_d, path) = deck_files(&[("in.tangential", &tangential)]);
    hide_codes();
    let e = read_deck(&path, Some(CodeName::Lammps2025), &DeckOptions::default())
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("in.tangential:11: no pair_coeff sets the types 1 and 2")
            && e.contains("tangential mindlin"),
        "{e}"
    );
    // Its own line for every type of the box, in use or not.
    let three = two_types(
        "pair_coeff 1 1 hertz/material 6.3e10 0.9 0.22 damping tsuji tangential linear_nohistory 0 0\n\
pair_coeff 2 2 hertz/material 2e11 0.6 0.3 damping tsuji tangential linear_nohistory 0 0\n",
    )
    .replace("create_box 2 box", "create_box 3 box");
    let (_d, path) = deck_files(&[("in.three", &three)]);
    hide_codes();
    let e = read_deck(&path, None, &DeckOptions::default())
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("in.three: no pair_coeff sets the type 3 with itself")
            && e.contains("All pair coeffs are not set"),
        "{e}"
    );
    // pair_coeff 2 1: the 2021 build sets nothing and refuses it; the 2025 build reads 1 2.
    let swapped = two_types(
        "pair_coeff 1 1 hooke 1e6 0.5 damping velocity tangential linear_nohistory 0 0\n\
pair_coeff 2 2 hooke 4e6 2.0 damping velocity tangential linear_nohistory 0 0\n\
pair_coeff 2 1 hooke 9e6 0.1 damping velocity tangential linear_nohistory 0 0\n",
    );
    let (_d, path) = deck_files(&[("in.swapped", &swapped)]);
    hide_codes();
    let e = read_deck(&path, Some(CodeName::Lammps), &DeckOptions::default())
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("in.swapped:12: pair_coeff 2 1: this build sets no pair for J < I")
            && e.contains("supported: pair_coeff 1 2"),
        "{e}"
    );
    let law = read_with(CodeName::Lammps2025, &path).contacts[1]
        .law
        .dashpot()
        .copied()
        .expect("a spring–dashpot law");
    assert_eq!((law.stiffness, law.damping), (9e6, 0.1));
}

/// The command refuses the unmixable deck in one line naming it, exit 2, and runs nothing.
#[test]
fn the_command_refuses_a_pair_lammps_cannot_mix_with_exit_2() {
    hide_codes();
    let forms = two_types(
        "pair_coeff 1 1 hertz/material 6.3e10 0.9 0.22 damping tsuji tangential linear_nohistory 0 0\n\
pair_coeff 2 2 hertz 1e9 0.5 damping tsuji tangential linear_nohistory 0 0\n",
    );
    let (_d, path) = deck_files(&[("in.forms", &forms)]);
    for code in ["lammps", "lammps-2025"] {
        let out = millimpact()
            .args(["deck", path.to_str().unwrap(), "--code", code])
            .output()
            .unwrap();
        assert_eq!(out.status.code(), Some(2));
        assert!(out.stdout.is_empty());
        let err = String::from_utf8(out.stderr).unwrap();
        assert_eq!(err.lines().count(), 1, "{err}");
        assert!(
            err.starts_with("error: ")
                && err.contains("in.forms:11: no pair_coeff sets the types 1 and 2")
                && err.contains("in.forms:10: hertz/material"),
            "{err}"
        );
    }
}

/// A mixed pair the 2021 build damps beyond critical (viscoelastic numbers run as a velocity
/// dashpot) never separates: its row says so, and no run is started for it.
#[test]
fn a_mixed_pair_that_never_separates_is_reported_not_run() {
    let sticky = two_types(
        "pair_coeff 1 1 hertz 4e10 5e8 damping viscoelastic tangential linear_nohistory 0 0\n\
pair_coeff 2 2 hertz 1.3e11 8e8 damping viscoelastic tangential linear_nohistory 0 0\n",
    );
    let (_d, path) = deck_files(&[("in.sticky", &sticky)]);
    let deck = read_with(CodeName::Lammps, &path);
    let zeta = deck.contacts[1]
        .law
        .dashpot()
        .expect("a spring–dashpot law")
        .never_separates()
        .unwrap();
    assert!(zeta > 1e5, "{zeta}");
    assert!(
        deck.contacts[1]
            .traps
            .iter()
            .any(|t| t.contains("the bodies never separate, COR 0")),
        "{:?}",
        deck.contacts[1].traps
    );
    let report = check_deck(
        CodeName::Lammps,
        &deck,
        (vec![2.0], "given".into()),
        &RecordedRuns::default(),
    )
    .unwrap();
    let row = &report.impacts[1];
    assert_eq!(row.pair, "1–2");
    assert_eq!(row.cor_law, 0.0);
    assert!(row.realised.cor.is_nan() && row.steps == 0);
    assert!(row.failure.as_deref().unwrap().starts_with("not run: the law these lines make the code integrate is a linear spring with a dashpot of damping ratio"), "{:?}", row.failure);
    // The own pairs went to the runner (here: none recorded).
    assert!(
        report.impacts[0]
            .failure
            .as_deref()
            .unwrap()
            .contains("no recorded run")
    );
    // In the 2025 build the pair stays viscoelastic Hertz, and separates.
    let law = read_with(CodeName::Lammps2025, &path).contacts[1]
        .law
        .dashpot()
        .copied()
        .expect("a spring–dashpot law");
    assert_eq!(law.never_separates(), None);
}

/// The mixed example's check in each build, from runs recorded in it: the table and JSON.
#[test]
fn snapshots_of_the_mixed_deck_in_each_build() {
    hide_codes();
    std::env::set_current_dir(root()).unwrap();
    for (code, runs) in [
        (CodeName::Lammps, "lammps-mixed"),
        (CodeName::Lammps2025, "lammps-mixed-2025"),
    ] {
        let runs: RecordedRuns = serde_json::from_str(
            &std::fs::read_to_string(root().join(format!("tests/data/deck/{runs}.runs.json")))
                .unwrap(),
        )
        .unwrap();
        let (code, deck) =
            read_deck(Path::new(MIXED), Some(code), &DeckOptions::default()).unwrap();
        let report = check_deck(code, &deck, (vec![4.0], "given".into()), &runs).unwrap();
        assert!(report.impacts.iter().all(|i| i.failure.is_none()));
        for format in [Format::Table, Format::Json] {
            let text = export(&report, format).unwrap();
            insta::assert_snapshot!(format!("deck_lammps_mixed_{code}_{format}"), text);
        }
    }
}
