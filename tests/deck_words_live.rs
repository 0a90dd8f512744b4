//! The words of `millimpact deck` against the real codes: the reader's variables and formulas
//! are the values LAMMPS (2021) and LIGGGHTS print for them; a type made by `set type/fraction`
//! gets its rows, run in LIGGGHTS; a run LIGGGHTS stops carries LIGGGHTS's own ERROR line and
//! no figures.

mod common;

use std::collections::BTreeMap;
use std::path::Path;

use common::{millimpact, root};
use millimpact::analysis::deck::{LiveRunner, check_deck, read_deck};
use millimpact::analysis::store::verify::REMAINDER_TOLERANCE;
use millimpact::codes::CodeName;
use millimpact::codes::deck::{DeckOptions, TypeRef};
use millimpact::codes::script::ScriptReader;

const VARIABLES: &str = "tests/data/deck/variables.in";

/// `NAME=VALUE` of every `print NAME=VALUE` line in `text`.
fn printed(text: &str) -> BTreeMap<String, f64> {
    text.lines()
        .filter_map(|l| l.trim().split_once('='))
        .filter(|(name, _)| name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_'))
        .filter_map(|(name, value)| Some((name.to_string(), value.trim().parse().ok()?)))
        .collect()
}

/// What `code` prints for the variables script, run in a scratch folder.
fn code_prints(code: CodeName) -> BTreeMap<String, f64> {
    let executable = code
        .driver()
        .locate()
        .unwrap_or_else(|e| panic!("{code}: {e}"));
    let dir = tempfile::tempdir().unwrap();
    let out = executable
        .command()
        .args(["-in"])
        .arg(root().join(VARIABLES))
        .args(["-log", "none", "-echo", "none"])
        .current_dir(dir.path())
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&out.stdout).into_owned();
    assert!(out.status.success(), "{code}: {text}");
    printed(&text)
}

#[test]
#[ignore = "live: runs LAMMPS 2021 and LIGGGHTS"]
fn the_readers_variables_are_the_values_the_codes_print() {
    let commands = ScriptReader::read(&root().join(VARIABLES), &[]).unwrap();
    let read: BTreeMap<String, f64> = printed(
        &commands
            .iter()
            .filter(|c| c.name() == "print")
            .map(|c| c.words[1..].join(" "))
            .collect::<Vec<_>>()
            .join("\n"),
    );
    assert_eq!(read.len(), 21, "{read:?}");
    for code in [CodeName::Lammps, CodeName::Liggghts] {
        let prints = code_prints(code);
        assert_eq!(
            prints.keys().collect::<Vec<_>>(),
            read.keys().collect::<Vec<_>>(),
            "{code}"
        );
        for (name, value) in &read {
            let theirs = prints[name];
            let relative = ((value - theirs) / theirs).abs();
            assert!(
                relative <= 1e-12,
                "{code}: {name}: read {value}, printed {theirs} ({relative:e})"
            );
        }
    }
}

/// The deck whose type 2 exists only through `set type 1 type/fraction 2 …`: its pairs with
/// type 2 are run in LIGGGHTS and agree with their own law as every deck's pairs do.
#[test]
#[ignore = "live: runs LIGGGHTS"]
fn the_type_fraction_decks_type_2_is_run_in_liggghts() {
    std::env::set_current_dir(root()).unwrap();
    let (code, deck) = read_deck(
        Path::new("tests/data/deck/liggghts-fraction.in"),
        None,
        &DeckOptions::default(),
    )
    .unwrap();
    assert_eq!(code, CodeName::Liggghts);
    let report = check_deck(
        code,
        &deck,
        (vec![2.0], "given".into()),
        &LiveRunner::default(),
    )
    .unwrap();
    use TypeRef::{Type, Wall};
    for pair in [[Type(1), Type(2)], [Type(2), Type(2)], [Type(2), Wall]] {
        let i = report
            .impacts
            .iter()
            .find(|i| i.types == pair)
            .unwrap_or_else(|| panic!("no row for {pair:?}"));
        assert_eq!(i.failure, None, "{}", i.pair);
        assert!(i.realised.cor > 0.5 && i.realised.cor < 1.0, "{}", i.pair);
        assert!(
            (i.remainder / i.cor_law_stepped).abs() < REMAINDER_TOLERANCE,
            "{}: remainder {}",
            i.pair,
            i.remainder
        );
    }
}

/// A deck LIGGGHTS stops on (its tangential model needs a coefficientFriction the deck lacks):
/// every row carries LIGGGHTS's own ERROR line and no figures, and the command exits 1.
#[test]
#[ignore = "live: runs LIGGGHTS"]
fn a_run_liggghts_stops_carries_its_error_line_and_no_figures() {
    let out = millimpact()
        .args([
            "deck",
            "tests/data/deck/liggghts-no-friction.in",
            "--impact-velocity",
            "2",
            "--format",
            "json",
        ])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1));
    let report: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let impacts = report["impacts"].as_array().unwrap();
    assert_eq!(impacts.len(), 5);
    for i in impacts {
        let failure = i["failure"].as_str().unwrap();
        assert!(
            failure.contains(
                "saying `ERROR: Could not locate a fix/property storing value(s) for coefficientFriction as requested by tangential_model history."
            ),
            "{failure}"
        );
        for figure in [
            "cor_realised",
            "cor_law_stepped",
            "integration_difference",
            "remainder",
            "contact_time",
        ] {
            assert!(i[figure].is_null(), "{figure}: {}", i[figure]);
        }
        assert!(i["integration_band"]["min"].is_null());
    }
    let stderr = String::from_utf8(out.stderr).unwrap();
    assert!(
        stderr.starts_with("error: deck: 5 of 5 impacts failed"),
        "{stderr}"
    );
}

/// A fault LIGGGHTS finds on one process (`error->one`, here a `create_atoms … random` seed it
/// refuses) ends it with MPI_Abort, which drops its buffered screen output and writes no log:
/// the deck's runs keep the ERROR line all the same, and the failure carries it.
#[test]
#[ignore = "live: runs LIGGGHTS"]
fn an_error_liggghts_finds_on_one_process_reaches_the_failure() {
    use millimpact::analysis::deck::ImpactRunner;
    use millimpact::codes::CodeError;
    std::env::set_current_dir(root()).unwrap();
    let (code, deck) = read_deck(
        Path::new("tests/data/deck/liggghts-fraction.in"),
        None,
        &DeckOptions::default(),
    )
    .unwrap();
    let reader = code.driver().deck().unwrap();
    let mut impact = reader.render(&deck, 0, 2.0, 100).unwrap();
    let at = impact.input.text.find("create_atoms").unwrap();
    impact
        .input
        .text
        .insert_str(at, "create_atoms    1 random 10 42 NULL\n");
    let error = LiveRunner::default()
        .run(code, &impact, &deck.contacts[0].law)
        .unwrap_err();
    match &error {
        CodeError::Crashed { said, .. } => assert_eq!(
            said.as_deref(),
            Some(
                "ERROR on proc 0: Random number generation: It is required that the random seed value is > 10000 and a prime number."
            ),
            "{error}"
        ),
        other => panic!("{other}"),
    }
}
