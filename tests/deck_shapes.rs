//! The corpus of decks in the shapes users write (`tests/data/deck/shapes/`, listed with their
//! outcomes in its `manifest.csv`): every deck is read with no code started and gives the
//! pairs recorded, or the refusal recorded (each fragment, in order); the live test runs every
//! deck that gives rows and checks each row's COR against the law's own.

mod common;

use std::path::{Path, PathBuf};

use common::deck::hide_codes;
use common::{codes_hidden, millimpact, root};
use millimpact::analysis::deck::read_deck;
use millimpact::codes::CodeName;
use millimpact::codes::deck::{DeckOptions, DeckReader, UserDeck};
use millimpact::codes::yade::deck::YadeDeck;

const SHAPES: &str = "tests/data/deck/shapes";

/// One row of the manifest.
struct Shape {
    deck: PathBuf,
    code: String,
    rows: bool,
    expect: String,
}

fn manifest() -> Vec<Shape> {
    let dir = root().join(SHAPES);
    let text = std::fs::read_to_string(dir.join("manifest.csv")).unwrap();
    let mut lines = text.lines();
    assert_eq!(lines.next(), Some("deck,code,outcome,expect"));
    lines
        .filter(|l| !l.trim().is_empty())
        .map(|l| {
            let mut fields = l.splitn(4, ',');
            let mut next = || fields.next().unwrap_or_else(|| panic!("short row `{l}`"));
            let (deck, code, outcome, expect) = (next(), next(), next(), next());
            assert!(matches!(outcome, "rows" | "refused"), "{l}");
            Shape {
                deck: PathBuf::from(SHAPES).join(deck),
                code: code.to_string(),
                rows: outcome == "rows",
                expect: expect.to_string(),
            }
        })
        .collect()
}

/// The pairs of a deck as the manifest writes them: `1-1 1-wall`.
fn pairs(deck: &UserDeck) -> String {
    let pairs: Vec<String> = deck
        .contacts
        .iter()
        .map(|c| format!("{}-{}", c.types[0], c.types[1]))
        .collect();
    pairs.join(" ")
}

/// What tells which construct a deck stands for: its first line (a script's), or its
/// folder's `about.txt` (Kratos' JSON files have no comments).
fn construct(deck: &Path) -> String {
    let about = match deck.extension().and_then(|e| e.to_str()) {
        Some("json") => deck.parent().unwrap().join("about.txt"),
        _ => deck.to_path_buf(),
    };
    let text = std::fs::read_to_string(root().join(about)).unwrap();
    text.lines().next().unwrap_or_default().to_string()
}

#[test]
fn the_corpus_covers_every_code_with_thirty_decks_or_more_each_saying_its_construct() {
    let shapes = manifest();
    assert!(shapes.len() >= 30, "{} decks", shapes.len());
    for code in ["liggghts", "lammps", "yade", "kratos"] {
        let n = shapes.iter().filter(|s| s.code == code).count();
        assert!(n >= 4, "{code}: {n} decks");
    }
    for s in &shapes {
        let first = construct(&s.deck);
        assert!(
            first.starts_with("# ") && first.len() > 20,
            "{}: first line `{first}`",
            s.deck.display()
        );
    }
    // Every deck of the folder is in the manifest (a deck's own included or data files are
    // named by their deck, not listed).
    let listed: Vec<PathBuf> = shapes.iter().map(|s| s.deck.clone()).collect();
    for entry in std::fs::read_dir(root().join(SHAPES)).unwrap() {
        let name = entry.unwrap().file_name().into_string().unwrap();
        let is_deck = Path::new(&name)
            .extension()
            .is_some_and(|e| e == "in" || e == "py");
        if is_deck {
            assert!(
                listed.contains(&PathBuf::from(SHAPES).join(&name)),
                "{name} is not in the manifest"
            );
        }
    }
}

/// Every deck LIGGGHTS, LAMMPS and Kratos read gives the pairs recorded or the refusal
/// recorded, with no code started; each YADE deck (which YADE itself sets up: the live test
/// reads it) is taken by the YADE reader and no other.
#[test]
fn every_deck_of_the_corpus_reads_to_its_recorded_outcome_with_no_code_started() {
    hide_codes();
    std::env::set_current_dir(root()).unwrap();
    let mut failures = Vec::new();
    for s in manifest() {
        if s.code == "yade" {
            let text = std::fs::read_to_string(&s.deck).unwrap();
            assert!(YadeDeck.recognises(&s.deck, &text), "{}", s.deck.display());
            continue;
        }
        match (read_deck(&s.deck, None, &DeckOptions::default()), s.rows) {
            (Ok((code, deck)), true) => {
                if code.name() != s.code || pairs(&deck) != s.expect {
                    failures.push(format!(
                        "{}: read by {} with pairs `{}`, recorded {} `{}`",
                        s.deck.display(),
                        code.name(),
                        pairs(&deck),
                        s.code,
                        s.expect
                    ));
                }
            }
            (Ok((code, deck)), false) => failures.push(format!(
                "{}: read by {} with pairs `{}`, recorded as refused",
                s.deck.display(),
                code.name(),
                pairs(&deck)
            )),
            (Err(e), true) => failures.push(format!("{}: refused: {e}", s.deck.display())),
            (Err(e), false) => {
                let text = e.to_string();
                let mut from = 0;
                for fragment in s.expect.split('|') {
                    match text[from..].find(fragment) {
                        Some(k) => from += k + fragment.len(),
                        None => {
                            failures.push(format!(
                                "{}: `{fragment}` not (in order) in: {text}",
                                s.deck.display()
                            ));
                            break;
                        }
                    }
                }
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// The command line refuses each refused deck with exit 2 and nothing run (the codes are
/// hidden: a code that started would fail it).
#[test]
fn each_refused_deck_exits_2_with_its_lines_and_nothing_on_stdout() {
    for s in manifest().iter().filter(|s| !s.rows && s.code != "yade") {
        let out = millimpact()
            .current_dir(root())
            .args(["deck", s.deck.to_str().unwrap()])
            .envs(codes_hidden())
            .output()
            .unwrap();
        assert_eq!(out.status.code(), Some(2), "{}", s.deck.display());
        assert!(out.stdout.is_empty(), "{}", s.deck.display());
        let err = String::from_utf8(out.stderr).unwrap();
        let fragments = s.expect.split('|').count();
        assert_eq!(
            err.lines().count(),
            fragments,
            "{}: {err}",
            s.deck.display()
        );
    }
}

/// Every deck that gives rows, run in its code: each row's realised COR is the law's own
/// (integrated exactly, independently of the code) to within the step's own band.
#[test]
#[ignore = "live: runs LIGGGHTS, LAMMPS, YADE and Kratos on every deck of the corpus that gives rows"]
fn every_deck_that_gives_rows_realises_its_laws_cor_within_the_steps_band() {
    let mut checked = 0;
    for s in manifest() {
        let out = millimpact()
            .current_dir(root())
            .args([
                "deck",
                s.deck.to_str().unwrap(),
                "--code",
                &s.code,
                "--impact-velocity",
                "1",
                "--format",
                "json",
            ])
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr);
        if !s.rows {
            assert_eq!(out.status.code(), Some(2), "{}: {stderr}", s.deck.display());
            assert!(
                stderr.contains(s.expect.split('|').next().unwrap()),
                "{}: {stderr}",
                s.deck.display()
            );
            continue;
        }
        assert_eq!(out.status.code(), Some(0), "{}: {stderr}", s.deck.display());
        let report: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        let impacts = report["impacts"].as_array().unwrap();
        let pairs: Vec<String> = impacts
            .iter()
            // By types, as the manifest records them (a label names a size class's radius).
            .map(|i| {
                let side = |v: &serde_json::Value| match v.as_str() {
                    Some(wall) => wall.to_string(),
                    None => v.to_string(),
                };
                format!("{}-{}", side(&i["types"][0]), side(&i["types"][1]))
            })
            .collect();
        assert_eq!(pairs.join(" "), s.expect, "{}", s.deck.display());
        for i in impacts {
            let realised = i["cor_realised"].as_f64().unwrap();
            let law = i["cor_law"].as_f64().unwrap();
            let (lo, hi) = (
                i["integration_band"]["min"].as_f64().unwrap(),
                i["integration_band"]["max"].as_f64().unwrap(),
            );
            // The run's one phase lies in the band of all phases; 1e-9 is the trajectory's
            // printed precision on the COR.
            let d = realised - law;
            assert!(
                d >= lo - 1e-9 && d <= hi + 1e-9,
                "{} {}: realised {realised} − law {law} = {d:e} outside [{lo:e}, {hi:e}]",
                s.deck.display(),
                i["pair"]
            );
            checked += 1;
        }
    }
    assert!(checked > 30, "{checked} rows checked");
}

#[test]
fn the_book_lists_every_deck_of_the_corpus_with_its_outcome() {
    let book = std::fs::read_to_string(root().join("docs/src/deck-shapes.md")).unwrap();
    for s in manifest() {
        let name = s.deck.strip_prefix(SHAPES).unwrap().display().to_string();
        let name = name.trim_start_matches('/');
        let row = book
            .lines()
            .find(|l| l.starts_with(&format!("| `{name}` |")))
            .unwrap_or_else(|| panic!("{name} is not in docs/src/deck-shapes.md"));
        let outcome = if s.rows {
            format!("rows {}", s.expect)
        } else {
            "refused".to_string()
        };
        assert!(row.contains(&outcome), "{name}: {row}");
    }
    let code_name = |c: &str| CodeName::ALL.iter().any(|n| n.name() == c);
    assert!(manifest().iter().all(|s| code_name(&s.code)));
}
