//! `millimpact deck` drops nothing and ignores nothing without a word: types made by `set …
//! type/fraction` get their rows, a `--var` the code would refuse is refused, a speed the law
//! cannot take is refused before anything runs, a failed run shows no figures, and the table
//! fits the width it is given. No code starts here: every code is hidden, and the checks that
//! would run one read recorded runs.

// A value read from a deck is the number written in it, bit for bit: compared exactly.
#![allow(clippy::float_cmp)]

mod common;

use std::path::{Path, PathBuf};

use common::{millimpact, root};
use millimpact::analysis::deck::{RecordedRuns, check_deck, read_deck};
use millimpact::codes::CodeName;
use millimpact::codes::deck::{DeckOptions, TypeRef, UserDeck};
use millimpact::output::{Format, export, table_at_width};
use millimpact::solve::dashpot::accurate_metrics;

const FRACTION: &str = "tests/data/deck/liggghts-fraction.in";
const MILL: &str = "examples/decks/liggghts-mill/in.mill";

/// A deck in a fresh folder.
fn deck_file(name: &str, text: &str) -> (tempfile::TempDir, PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join(name);
    std::fs::write(&path, text).unwrap();
    (dir, path)
}

/// As on a machine without the codes: a code that starts fails the test.
fn hide_codes() {
    for (variable, missing) in common::codes_hidden() {
        // SAFETY: every test of this file that sets them sets the same values, before reading.
        unsafe { std::env::set_var(variable, missing) };
    }
}

fn read(path: &Path, code: Option<CodeName>, options: &DeckOptions) -> UserDeck {
    hide_codes();
    read_deck(path, code, options)
        .unwrap_or_else(|e| panic!("{e}"))
        .1
}

fn read_error(path: &Path, code: Option<CodeName>, options: &DeckOptions) -> String {
    hide_codes();
    match read_deck(path, code, options) {
        Ok(_) => panic!("{} was read", path.display()),
        Err(e) => e.to_string(),
    }
}

/// The deck command with every code hidden: (exit code, stdout, stderr).
fn deck_command(args: &[&str]) -> (Option<i32>, String, String) {
    let mut command = millimpact();
    for (variable, missing) in common::codes_hidden() {
        command.env(variable, missing);
    }
    let out = command.arg("deck").args(args).output().unwrap();
    (
        out.status.code(),
        String::from_utf8(out.stdout).unwrap(),
        String::from_utf8(out.stderr).unwrap(),
    )
}

fn pairs(deck: &UserDeck) -> Vec<[TypeRef; 2]> {
    deck.contacts.iter().map(|c| c.types).collect()
}

#[test]
fn a_type_made_by_set_type_fraction_gets_its_rows_with_the_density_it_keeps() {
    let deck = read(&root().join(FRACTION), None, &DeckOptions::default());
    let sizes: Vec<(u32, f64, f64)> = deck
        .bodies
        .iter()
        .map(|b| (b.type_id, b.radius, b.density))
        .collect();
    // Type 2's atoms were type 1's (density 2500) and were given a diameter of their own.
    assert_eq!(sizes, [(1, 0.005, 2500.0), (2, 0.002, 2500.0)]);
    use TypeRef::{Type, Wall};
    assert_eq!(
        pairs(&deck),
        [
            [Type(1), Type(1)],
            [Type(1), Type(2)],
            [Type(2), Type(2)],
            [Type(1), Wall],
            [Type(2), Wall]
        ]
    );
    assert!(
        deck.bodies[1].from.ends_with("liggghts-fraction.in:30)"),
        "{}",
        deck.bodies[1].from
    );
}

/// LIGGGHTS header of the small decks below: three types, type 3 the wall's.
const HEAD: &str = "units si\natom_style granular\nhard_particles yes\ncreate_box 3 box\n\
fix m1 all property/global youngsModulus peratomtype 2e11 2e11 2e11\n\
fix m2 all property/global poissonsRatio peratomtype 0.3 0.3 0.3\n\
fix m3 all property/global coefficientRestitution peratomtypepair 3 0.5 0.5 0.5 0.5 0.5 0.5 0.5 0.5 0.5\n\
pair_style gran model hertz\npair_coeff * *\ntimestep 1e-6\ncreate_atoms 1 region box\n";

#[test]
fn a_type_made_before_its_own_set_line_keeps_the_size_of_the_atoms_it_took() {
    // `set type 2 diameter …` before any atom is of type 2 sets none: type 2 takes type 1's.
    let (_d, path) = deck_file(
        "in.before",
        &format!(
            "{HEAD}set type 1 diameter 0.01 density 7800\nset type 2 diameter 0.004\n\
set type 1 type 2\n"
        ),
    );
    let deck = read(&path, None, &DeckOptions::default());
    let sizes: Vec<(u32, f64, f64)> = deck
        .bodies
        .iter()
        .map(|b| (b.type_id, b.radius, b.density))
        .collect();
    assert_eq!(sizes, [(1, 0.005, 7800.0), (2, 0.005, 7800.0)]);
}

#[test]
fn a_group_of_known_atoms_sets_their_sizes_as_the_code_does() {
    // `set group all`: every atom there is, so type 1's; the fraction made type 2 keeps it.
    let (_d, path) = deck_file(
        "in.all",
        &format!(
            "{HEAD}set group all diameter 0.01 density 7800\nset group all type/fraction 2 0.3 32452843\n"
        ),
    );
    let deck = read(&path, None, &DeckOptions::default());
    let sizes: Vec<(u32, f64, f64)> = deck
        .bodies
        .iter()
        .map(|b| (b.type_id, b.radius, b.density))
        .collect();
    assert_eq!(sizes, [(1, 0.005, 7800.0), (2, 0.005, 7800.0)]);
    // A group of types: `group heavy type 2` after the atoms of type 2 are made.
    let (_d, path) = deck_file(
        "in.types",
        &format!(
            "{HEAD}create_atoms 2 region box\ngroup heavy type 2\nset group heavy diameter 0.02 density 2500\nset type 1 diameter 0.01 density 7800\n"
        ),
    );
    let deck = read(&path, None, &DeckOptions::default());
    let sizes: Vec<(u32, f64, f64)> = deck
        .bodies
        .iter()
        .map(|b| (b.type_id, b.radius, b.density))
        .collect();
    assert_eq!(sizes, [(1, 0.005, 7800.0), (2, 0.01, 2500.0)]);
}

#[test]
fn a_type_whose_size_cannot_be_known_is_named_with_its_line_and_what_to_give() {
    // A region's atoms made type 2: the reader cannot know which atoms, so which size.
    let (_d, path) = deck_file(
        "in.group",
        &format!(
            "{HEAD}set type 1 diameter 0.01 density 7800\ngroup lower region box\nset group lower type/fraction 2 0.3 32452843\n"
        ),
    );
    let e = read_error(&path, None, &DeckOptions::default());
    assert_eq!(
        e,
        format!(
            "{}:14: atoms of type 2 come from `set group lower type/fraction 2 0.3 32452843` without a diameter and density the reader can know for them; supported: `set type 2 diameter D density RHO`, or --particle 2:RADIUS:DENSITY",
            path.display()
        )
    );
    let (status, stdout, stderr) = deck_command(&[path.to_str().unwrap()]);
    assert_eq!(status, Some(2));
    assert!(stdout.is_empty());
    assert_eq!(stderr, format!("error: {e}\n"));
    // Given on the command line, it has its rows.
    let options = DeckOptions {
        particles: vec![millimpact::codes::deck::GivenParticle {
            type_id: 2,
            radius: 0.002,
            density: 2500.0,
        }],
        ..DeckOptions::default()
    };
    let deck = read(&path, None, &options);
    assert!(pairs(&deck).contains(&[TypeRef::Type(2), TypeRef::Type(2)]));
    // LIGGGHTS 3.8 has no type/ratio: it stops, and so does the reader.
    let (_d, path) = deck_file(
        "in.ratio",
        &format!(
            "{HEAD}set type 1 diameter 0.01 density 7800\nset type 1 type/ratio 2 0.5 32452843\n"
        ),
    );
    assert_eq!(
        read_error(&path, None, &DeckOptions::default()),
        format!(
            "{}:13: set … type/ratio: LIGGGHTS 3.8 has no such keyword (it stops: \"Illegal set command\"); supported: set … type N, or type/fraction N FRACTION SEED",
            path.display()
        )
    );
}

#[test]
fn lammps_types_made_by_type_ratio_and_type_subset_get_their_rows() {
    let (_d, path) = deck_file(
        "in.beads",
        "units si\natom_style sphere\ncreate_box 3 box\ncreate_atoms 1 random 600 12345 box\n\
set type 1 diameter 0.01 mass 1.3e-3\nset type 1 type/ratio 2 0.3 4567\nset type 1 type/subset 3 100 890\n\
set type 3 diameter 0.004 density 7800\ntimestep 1e-6\npair_style granular\n\
pair_coeff * * hertz/material 6.3e10 0.8 0.22 damping tsuji tangential linear_nohistory 0 0\n",
    );
    let deck = read(&path, Some(CodeName::Lammps), &DeckOptions::default());
    let types: Vec<u32> = deck.bodies.iter().map(|b| b.type_id).collect();
    assert_eq!(types, [1, 2, 3]);
    // Type 2 keeps type 1's diameter and mass; type 3 was given its own.
    assert_eq!(deck.bodies[1].radius, 0.005);
    assert!((deck.bodies[1].mass - 1.3e-3).abs() < 1e-15);
    assert_eq!(
        (deck.bodies[2].radius, deck.bodies[2].density),
        (0.002, 7800.0)
    );
    assert_eq!(deck.contacts.len(), 6);
}

/// `variable dt equal …` in the deck: LIGGGHTS and LAMMPS stop when `-var dt …` made it an
/// index variable first, and so does the check.
#[test]
fn a_var_on_a_variable_the_code_will_not_redefine_is_refused_with_exit_2() {
    let (_d, path) = deck_file(
        "in.dt",
        &HEAD
            .replace(
                "timestep 1e-6\n",
                "variable dt equal 1e-6\ntimestep ${dt}\n",
            )
            .replace(
                "create_atoms 1 region box\n",
                "create_atoms 1 region box\nset type 1 diameter 0.01 density 7800\n",
            ),
    );
    let (status, stdout, stderr) = deck_command(&[path.to_str().unwrap(), "--var", "dt=5e-7"]);
    assert_eq!(status, Some(2));
    assert!(stdout.is_empty());
    assert_eq!(
        stderr,
        format!(
            "error: {}:10: variable dt equal: --var dt=5e-7 made `dt` an index variable (as -var does), and LIGGGHTS and LAMMPS stop at this line (\"Cannot redefine variable as a different style\"); supported: --var only for a variable the deck defines as `variable dt index …` (or does not define): change this line to `variable dt index VALUE`, or leave out --var dt and edit the value here\n",
            path.display()
        )
    );
    // An index variable takes the command line's value, as -var gives it.
    let (_d, path) = deck_file(
        "in.index",
        &HEAD
            .replace(
                "timestep 1e-6\n",
                "variable dt index 1e-6\ntimestep ${dt}\n",
            )
            .replace(
                "create_atoms 1 region box\n",
                "create_atoms 1 region box\nset type 1 diameter 0.01 density 7800\n",
            ),
    );
    let options = DeckOptions {
        variables: vec![("dt".into(), "5e-7".into())],
        ..DeckOptions::default()
    };
    assert_eq!(read(&path, None, &options).timestep, 5e-7);
    // The deck's own redefinition in another style stops the codes too.
    let (_d, path) = deck_file(
        "in.twice",
        &format!("variable r equal 0.01\nvariable r string 0.02\n{HEAD}"),
    );
    assert_eq!(
        read_error(&path, None, &DeckOptions::default()),
        format!(
            "{0}:2: variable r string: `r` is already a equal variable ({0}:1), and LIGGGHTS and LAMMPS stop at this line (\"Cannot redefine variable as a different style\"); supported: a variable redefined in its own style (equal), or `variable r delete` before it",
            path.display()
        )
    );
}

#[test]
fn a_speed_the_law_cannot_take_is_refused_before_anything_runs() {
    let deck = root().join(FRACTION);
    let (status, stdout, stderr) =
        deck_command(&[deck.to_str().unwrap(), "--impact-velocity", "1e9"]);
    assert_eq!(status, Some(2));
    assert!(stdout.is_empty());
    assert_eq!(
        stderr,
        format!(
            "error: --impact-velocity = 1000000000 m/s: the law of 1–1 presses the surfaces {} m together at this speed, beyond the radius 0.005 m (the peak overlap {} × R); it takes at most {} m/s: give a slower --impact-velocity\n",
            "1.586e2", "3.172e4", "2.362e3"
        )
    );
    // The speed it names is where the law's own peak overlap is the radius.
    let law = read(&deck, None, &DeckOptions::default()).contacts[0]
        .law
        .dashpot()
        .copied()
        .expect("a spring–dashpot law");
    let peak = accurate_metrics(&law, 2.362e3, 1e-10)
        .unwrap()
        .peak_deformation;
    assert!((peak / 0.005 - 1.0).abs() < 1e-3, "{peak}");
    let peak = accurate_metrics(&law, 1e9, 1e-10).unwrap().peak_deformation;
    assert!((peak / 1.586e2 - 1.0).abs() < 1e-3, "{peak}");
    // So slow that the contact needs more steps than the check runs.
    let (status, stdout, stderr) =
        deck_command(&[deck.to_str().unwrap(), "--impact-velocity", "1e-30"]);
    assert_eq!(status, Some(2));
    assert!(stdout.is_empty());
    assert_eq!(
        stderr,
        "error: --impact-velocity = 0.000000000000000000000000000001 m/s: the contact of 1–1 at this speed lasts 3.191517e1 s, 3.19e7 steps of the deck's Δt = 1e-6 s, beyond the check's limit of 20000000 steps; give a faster --impact-velocity\n"
    );
}

#[test]
fn a_failed_run_shows_no_figures() {
    std::env::set_current_dir(root()).unwrap();
    hide_codes();
    let (code, deck) = read_deck(Path::new(FRACTION), None, &DeckOptions::default()).unwrap();
    // No run recorded: every run fails, as a run the code stops does.
    let report = check_deck(
        code,
        &deck,
        (vec![2.0], "given".into()),
        &RecordedRuns::default(),
    )
    .unwrap();
    assert_eq!(report.impacts.len(), 5);
    for i in &report.impacts {
        assert!(i.failure.is_some());
        for (figure, value) in [
            ("COR realised", i.realised.cor),
            ("law stepped", i.cor_law_stepped),
            ("integration", i.integration_difference),
            ("band", i.integration_band.min),
            ("band", i.integration_band.max),
            ("remainder", i.remainder),
            ("contact time", i.realised.contact_time),
        ] {
            assert!(value.is_nan(), "{}: {figure} {value}", i.pair);
        }
    }
    for format in Format::ALL {
        let text = export(&report, format).unwrap();
        insta::assert_snapshot!(format!("deck_fraction_failed_{format}"), text);
    }
    let table = export(&report, Format::Table).unwrap();
    let row = table.lines().find(|l| l.contains("2–wall")).unwrap();
    assert_eq!(
        row,
        "│ 2–wall ┆ 2        ┆ 0.7         ┆ failed (see warnings)               ┆ —                               ┆ —                ┆ —                                   ┆ —                ┆ —                  ┆ —         │"
    );
}

fn mill_report() -> millimpact::analysis::deck::DeckReport {
    std::env::set_current_dir(root()).unwrap();
    let runs: RecordedRuns = serde_json::from_str(
        &std::fs::read_to_string(root().join("tests/data/deck/liggghts-mill.runs.json")).unwrap(),
    )
    .unwrap();
    let (code, deck) = read_deck(Path::new(MILL), None, &DeckOptions::default()).unwrap();
    check_deck(code, &deck, (vec![4.0], "given".into()), &runs).unwrap()
}

#[test]
fn the_table_fits_the_width_it_is_given() {
    let report = mill_report();
    let full = export(&report, Format::Table).unwrap();
    let widest = |text: &str| text.lines().map(|l| l.chars().count()).max().unwrap();
    assert!(widest(&full) > 150, "{}", widest(&full));
    // The footer is the command that reproduces the check: left whole, to be copied.
    let footer = full.lines().last().unwrap();
    assert!(footer.starts_with("reproduce: millimpact deck"), "{footer}");
    for width in [80, 100, 120] {
        let text = table_at_width(&report, width).unwrap();
        let (body, last) = text.trim_end().rsplit_once('\n').unwrap();
        assert!(widest(body) <= usize::from(width), "{width}: {text}");
        assert_eq!(last, footer, "{width}");
        // Every pair's row is in every table the columns were split into, and every figure
        // of the full table is in the narrow one.
        for i in &report.impacts {
            assert!(
                text.contains(&format!("│ {:<6} ┆ 4  ", i.pair)),
                "{}",
                i.pair
            );
            assert!(text.contains(&format!("{:.6}", i.realised.cor)));
            assert!(text.contains(&format!("{:.6}", i.paper_loss_coefficient)));
        }
        // The text under the tables is the same words, wrapped.
        let words = |t: &str| -> Vec<String> {
            t.lines()
                .filter(|l| !l.starts_with(['│', '┌', '└', '╞', '├']))
                .flat_map(|l| l.split_whitespace().map(String::from).collect::<Vec<_>>())
                .collect()
        };
        assert_eq!(words(&text), words(&full), "{width}");
    }
    insta::assert_snapshot!(
        "deck_liggghts_mill_table_at_100",
        table_at_width(&report, 100).unwrap()
    );
    // Wide enough, it is the full table.
    assert_eq!(table_at_width(&report, 400).unwrap(), full);
}

/// `ternary()` came to LAMMPS in 2022: LIGGGHTS 3.8 and the 2021 build stop at it, and so does
/// the check; the 2025 build evaluates it.
#[test]
fn ternary_is_refused_where_the_code_has_none() {
    let (_d, path) = deck_file(
        "in.ternary",
        &HEAD.replace(
            "timestep 1e-6\n",
            "variable dt equal ternary(1>2,1e-6,2e-6)\ntimestep ${dt}\n",
        ),
    );
    assert_eq!(
        read_error(&path, None, &DeckOptions::default()),
        format!(
            "{}:11: `ternary()` in `ternary(1>2,1e-6,2e-6)`: LIGGGHTS 3.8 has no such function (it stops: \"Invalid math/group/special function\"); supported: numbers, PI, v_NAME of numeric variables, ( ), unary - and !, ^, * / %, + -, < <= > >= == !=, && ||, and sqrt, exp, ln, log, abs, sin, cos, tan, asin, acos, atan, atan2, ceil, floor, round, ternary (LAMMPS from 2022)",
            path.display()
        )
    );
    let lammps = |lines: &str| {
        format!(
            "units si\natom_style sphere\ncreate_box 1 box\ncreate_atoms 1 single 0 0 0\n\
set type 1 diameter 0.004 density 2500\n{lines}pair_style granular\n\
pair_coeff * * hertz/material 6.3e10 0.8 0.22 damping tsuji tangential linear_nohistory 0 0\n"
        )
    };
    let (_d, path) = deck_file(
        "in.lammps",
        &lammps("variable dt equal ternary(1>2,1e-6,2e-6)\ntimestep ${dt}\n"),
    );
    let e = read_error(&path, Some(CodeName::Lammps), &DeckOptions::default());
    assert!(
        e.starts_with(&format!(
            "{}:7: `ternary()` in `ternary(1>2,1e-6,2e-6)`: LAMMPS 2021 has no such function",
            path.display()
        )),
        "{e}"
    );
    let deck = read(&path, Some(CodeName::Lammps2025), &DeckOptions::default());
    assert_eq!(deck.timestep, 2e-6);
}

/// A LAMMPS type made by `fix pour` of one size and density gets its rows; a pour over a range
/// of sizes is named with what to give.
#[test]
fn lammps_types_poured_get_their_rows_or_a_line() {
    let deck = |pour: &str| {
        format!(
            "units si\natom_style sphere\ncreate_box 2 box\ncreate_atoms 1 single 0 0 0\n\
set type 1 diameter 0.01 density 2500\nregion hopper block 0 1 0 1 0 1 units box\n{pour}\ntimestep 1e-6\n\
pair_style granular\npair_coeff * * hertz/material 6.3e10 0.8 0.22 damping tsuji tangential linear_nohistory 0 0\n"
        )
    };
    let (_d, path) = deck_file(
        "in.pour",
        &deck("fix ins all pour 500 2 4767548 region hopper diam one 0.004 dens 7800 7800"),
    );
    let read_deck = read(&path, Some(CodeName::Lammps), &DeckOptions::default());
    let sizes: Vec<(u32, f64, f64)> = read_deck
        .bodies
        .iter()
        .map(|b| (b.type_id, b.radius, b.density))
        .collect();
    assert_eq!(sizes, [(1, 0.005, 2500.0), (2, 0.002, 7800.0)]);
    let (_d, path) = deck_file(
        "in.range",
        &deck("fix ins all pour 500 2 4767548 region hopper diam range 0.003 0.005 dens 7800 7800"),
    );
    assert_eq!(
        read_error(&path, Some(CodeName::Lammps), &DeckOptions::default()),
        format!(
            "{}:7: atoms of type 2 come from `fix ins all pour 500 2 4767548 region hopper diam range 0.003 0.005 dens 7800 7800` without a diameter and density (or mass) the reader can know for them; supported: --particle 2:RADIUS:DENSITY (atoms inserted during the run take no `set`)",
            path.display()
        )
    );
}

/// A build that reads no decks (its law is a hook the harness adds), named with `--code`: one
/// line saying so and naming the builds that read decks, exit 2, before anything is read or run
/// (not "not a deck of any code", which a deck of its own code would wrongly be told).
#[test]
fn a_build_that_reads_no_decks_is_named_as_such() {
    for (deck, code) in [
        ("examples/decks/yade-mill/mill.py", "yade-paper"),
        (
            "examples/decks/kratos-mill/MaterialsDEM.json",
            "kratos-paper",
        ),
    ] {
        let path = root().join(deck);
        let (status, stdout, stderr) = deck_command(&[path.to_str().unwrap(), "--code", code]);
        assert_eq!(status, Some(2), "{stderr}");
        assert!(stdout.is_empty(), "{stdout}");
        assert_eq!(stderr.lines().count(), 1, "{stderr}");
        assert!(
            stderr.contains(&format!("--code {code} reads no decks")),
            "{stderr}"
        );
        let readers = stderr
            .rsplit_once("the builds that read decks: ")
            .unwrap()
            .1
            .trim();
        let named: Vec<&str> = readers.split(", ").collect();
        assert!(
            named.contains(&"yade") && named.contains(&"kratos"),
            "{readers}"
        );
        assert!(!named.contains(&code), "{readers}");
    }
}
