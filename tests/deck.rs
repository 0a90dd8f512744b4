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
        common.contains("youngsModulus peratomtype 2e11 2e11 5e7"),
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
    let law = deck.contacts[1].law;
    assert!(relative(law.stiffness, expected.stiffness) < 1e-14);
    assert!(relative(law.damping, expected.damping) < 1e-14);
    assert!(relative(law.mass, expected.mass) < 1e-14);
    assert!(!law.clamp_attractive);
    // Ball on the rubber liner: the liner's E and ν mixed in, R* = R, m* = m.
    let y_wall = 1.0 / ((1.0 - 0.09) / 2e11 + (1.0 - 0.45 * 0.45) / 5e7);
    let wall = &deck.contacts[3];
    assert_eq!(wall.partner, Partner::Wall(0));
    assert_eq!(wall.cor_entered, Some(0.6));
    assert!(relative(wall.law.stiffness, 4.0 / 3.0 * y_wall * 0.03f64.sqrt()) < 1e-14);
    assert!(relative(wall.law.mass, big.mass) < 1e-14);
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
    let law = deck.contacts[0].law;
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
    let law = deck.contacts[0].law;
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
    let law = read(&path).contacts[0].law;
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
    assert!(deck.contacts[1].law.clamp_attractive && !deck.contacts[0].law.clamp_attractive);
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
    let page = std::fs::read_to_string(root().join("docs/src/commands/deck.md")).unwrap();
    let start = page
        .find("<!-- deck example:")
        .expect("the example's marker");
    let block = &page[start..];
    let body = &block[block.find("```text\n").unwrap() + 8
        ..block.find("```\n<!-- end of deck example -->").unwrap()];
    assert_eq!(body, table);
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
            "fix floor all wall/gran granular hertz/material 6.3e10 7e-1 2.2e-1 damping tsuji tangential mindlin NULL 1.0 0.5 limit_damping zplane 0 NULL"
        ]
    );
    // The ball on the floor: the 2021 wall's E/(2(1−ν)), R* = R, m* = m, tsuji's α(e_in), clamped.
    let wall = &deck.contacts[3];
    let body = &deck.bodies[0];
    let k = 4.0 / 3.0 * 6.3e10 / (2.0 * (1.0 - 0.22)) * 0.005f64.sqrt();
    let alpha = millimpact::codes::lammps::tsuji_alpha(0.7);
    assert!(relative(wall.law.stiffness, k) < 1e-14);
    assert!(relative(wall.law.damping, alpha * (body.mass * k).sqrt()) < 1e-14);
    assert!(wall.law.clamp_attractive);
    assert_eq!(wall.cor_entered, Some(0.7));
    // Two beads: the pair's E/(2(1−ν²)), not clamped.
    let pair = &deck.contacts[0];
    let k = 4.0 / 3.0 * 6.3e10 / (2.0 * (1.0 - 0.22 * 0.22)) * 0.0025f64.sqrt();
    assert!(relative(pair.law.stiffness, k) < 1e-14 && !pair.law.clamp_attractive);
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
    let law = pair.law;
    assert!(relative(law.stiffness, k) < 1e-14, "{} {k}", law.stiffness);
    assert!(relative(law.damping, alpha * (m * k).sqrt()) < 1e-14);
    assert!(relative(law.mass, m) < 1e-14);
    assert_eq!((law.exponent, law.damping_exponent), (1.5, 0.25));
    assert!(!law.clamp_attractive);
    // The damping is converted after mixing: √(α₁α₂) would be 25 % weaker.
    assert!(alpha / (poly(c1) * poly(c2)).sqrt() > 1.3);
    // No COR is entered for a mixed pair; its lines are both types' own.
    assert_eq!(pair.cor_entered, None);
    let lines: Vec<usize> = pair.lines.iter().map(|l| l.line).collect();
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
    let law = pair.law;
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
    let law = new.contacts[1].law;
    assert!(relative(law.stiffness, k * r.sqrt()) < 1e-14);
    assert!(relative(law.damping, d) < 1e-14);
    assert_eq!((law.exponent, law.damping_exponent), (1.5, 0.0));
    let law = read_with(CodeName::Lammps, &path).contacts[1].law;
    assert!(relative(law.stiffness, k) < 1e-14);
    assert!(relative(law.damping, d) < 1e-14);
    assert_eq!((law.exponent, law.damping_exponent), (1.0, 0.0));
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
    assert!(new.contacts[1].law.clamp_attractive);
    assert!(
        new.contacts[1]
            .traps
            .iter()
            .any(|t| t.starts_with("limit_damping is on in pair_coeff 1 1 only"))
    );
    let old = read_with(CodeName::Lammps, &path);
    assert!(!old.contacts[1].law.clamp_attractive);
    assert!(
        old.contacts[1]
            .traps
            .iter()
            .any(|t| t.starts_with("limit_damping of the lines does not reach the mixed pair"))
    );
    // The own pair 1 1 keeps its clamp in both.
    assert!(new.contacts[0].law.clamp_attractive && old.contacts[0].law.clamp_attractive);

    let restitution = two_types(
        "pair_coeff 1 1 hertz/material 6.3e10 0.9 0.22 damping coeff_restitution tangential linear_nohistory 0 0\n\
pair_coeff 2 2 hertz/material 2e11 0.4 0.3 damping coeff_restitution tangential linear_nohistory 0 0\n",
    );
    let (_d, path) = deck_files(&[("in.cr", &restitution)]);
    let law = read_with(CodeName::Lammps2025, &path).contacts[1].law;
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
    let law = read_with(CodeName::Lammps2025, &path).contacts[1].law;
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
    let zeta = deck.contacts[1].law.never_separates().unwrap();
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
    assert!(row.cor_realised.is_nan() && row.steps == 0);
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
    let law = read_with(CodeName::Lammps2025, &path).contacts[1].law;
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
