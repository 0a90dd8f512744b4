//! The deck check's report from the runs `tests/deck_live.rs` recorded in the real codes: every
//! format of each code's example (snapshots), the mill's part of `report --deck`, and the worked
//! examples of `docs/src/commands/deck.md` as the recorded checks' tables.

// A value read from a deck is the number written in it, bit for bit: compared exactly.
#![allow(clippy::float_cmp)]

mod common;

use std::path::Path;

use common::deck::{GRANULAR, KRATOS_MILL, MILL, MIXED, YADE_MILL, hide_codes, yade_read};
use common::root;
use millimpact::analysis::deck::{RecordedRuns, check_deck, read_deck};
use millimpact::codes::CodeName;
use millimpact::codes::deck::DeckOptions;
use millimpact::output::{Format, export};

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
