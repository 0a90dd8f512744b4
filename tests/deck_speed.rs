//! `deck --impact-velocity A:B:N` in the fast tier: the check of a viscoelastic LAMMPS deck at
//! five speeds from the runs recorded by `tests/deck_speed_live.rs`, in every format, and the
//! values the option refuses.

mod common;

use std::path::Path;

use millimpact::analysis::deck::{RecordedRuns, check_deck, read_deck};
use millimpact::codes::CodeName;
use millimpact::codes::deck::DeckOptions;
use millimpact::output::{Format, export};

const DECK: &str = "tests/data/deck/lammps-viscoelastic.in";

/// Every format of the viscoelastic deck's check at 0.5, 1, 2, 4 and 8 m/s: per pair its COR
/// against the speed, the law's exact curve, Müller & Pöschel's closed form, and the trap line
/// with the spread.
#[test]
fn snapshots_of_the_cor_against_speed_in_every_format() {
    std::env::set_current_dir(common::root()).unwrap();
    // The build is read with its recorded conventions: no probe of a LAMMPS starts here.
    for (variable, missing) in common::codes_hidden() {
        // SAFETY: this file's tests set only these variables, each to the same value.
        unsafe { std::env::set_var(variable, missing) };
    }
    let runs: RecordedRuns = serde_json::from_str(
        &std::fs::read_to_string("tests/data/deck/lammps-viscoelastic.runs.json").unwrap(),
    )
    .unwrap();
    let (code, deck) = read_deck(Path::new(DECK), None, &DeckOptions::default()).unwrap();
    assert_eq!(code, CodeName::Lammps);
    let speeds = vec![0.5, 1.0, 2.0, 4.0, 8.0];
    let report = check_deck(code, &deck, (speeds, "given".into()), &runs).unwrap();
    assert!(report.impacts.iter().all(|i| i.failure.is_none()));
    assert_eq!(report.cor_against_speed.len(), 2);
    for curve in &report.cor_against_speed {
        assert!(curve.depends_on_speed, "{curve:?}");
        let trap = curve.trap().unwrap();
        assert!(
            trap.contains(&format!("spread {:.3e}", curve.spread)),
            "{trap}"
        );
    }
    for format in Format::ALL {
        let text = export(&report, format).unwrap();
        insta::assert_snapshot!(format!("deck_lammps_viscoelastic_speeds_{format}"), text);
    }
}

/// Bad `--impact-velocity` values: one line naming the value and what is allowed, exit 2,
/// nothing on standard output, no code started.
#[test]
fn bad_speed_ranges_are_refused_in_one_line() {
    for (value, says) in [
        ("0:1:3", "A of A:B:N is `0`"),
        ("-1:1:3", "A of A:B:N is `-1`"),
        ("2:1:3", "B = 1 m/s is not above A = 2 m/s"),
        ("1:1:3", "B = 1 m/s is not above A = 1 m/s"),
        ("1:2:1", "N of A:B:N is `1`"),
        ("1:2:x", "N of A:B:N is `x`"),
        ("1:2:2.5", "N of A:B:N is `2.5`"),
        ("1:inf:3", "B of A:B:N is `inf`"),
        ("a:2:3", "A of A:B:N is `a`"),
        ("1:2", "allowed: a positive speed, m/s, or A:B:N"),
        ("1:2:3:4", "allowed: a positive speed, m/s, or A:B:N"),
        ("fast", "allowed: a positive speed, m/s, or A:B:N"),
    ] {
        let output = common::millimpact()
            .envs(common::codes_hidden())
            .args(["deck", DECK, &format!("--impact-velocity={value}")])
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert_eq!(output.status.code(), Some(2), "{value}: {stderr}");
        assert!(output.stdout.is_empty(), "{value}");
        assert_eq!(stderr.lines().count(), 1, "{value}: {stderr}");
        assert!(
            stderr.contains("--impact-velocity") && stderr.contains(says),
            "{value}: {stderr}"
        );
    }
}

/// The report's part on a deck checked at several speeds draws each pair's realised COR against
/// the speed beside its law's exact curve and Müller & Pöschel's closed form, from the check's
/// own figures (the CSV beside the figure holds them), and says that the COR depends on speed.
#[test]
fn the_reports_deck_part_draws_the_cor_against_speed() {
    std::env::set_current_dir(common::root()).unwrap();
    for (variable, missing) in common::codes_hidden() {
        // SAFETY: this file's tests set only these variables, each to the same value.
        unsafe { std::env::set_var(variable, missing) };
    }
    let runs: RecordedRuns = serde_json::from_str(
        &std::fs::read_to_string("tests/data/deck/lammps-viscoelastic.runs.json").unwrap(),
    )
    .unwrap();
    let (code, deck) = read_deck(Path::new(DECK), None, &DeckOptions::default()).unwrap();
    let speeds = vec![0.5, 1.0, 2.0, 4.0, 8.0];
    let report = check_deck(code, &deck, (speeds.clone(), "given".into()), &runs).unwrap();
    let (part, _) = millimpact::analysis::report::deck_part(1, &report).unwrap();
    let [figure] = part.figures.as_slice() else {
        panic!(
            "one figure: {:?}",
            part.figures.iter().map(|f| &f.id).collect::<Vec<_>>()
        );
    };
    assert_eq!(figure.id, "deck-1-cor-against-speed");
    assert!(figure.svg.starts_with("<svg"), "{}", &figure.svg[..40]);
    assert!(figure.caption.contains("spread"), "{}", figure.caption);
    let mut rows = csv::Reader::from_reader(figure.csv.as_bytes());
    let rows: Vec<(String, f64, f64)> = rows.deserialize().map(Result::unwrap).collect();
    for curve in &report.cor_against_speed {
        let drawn = |suffix: &str| -> Vec<(f64, f64)> {
            rows.iter()
                .filter(|(name, ..)| name == &format!("{}: {suffix}", curve.pair))
                .map(|(_, v, e)| (*v, *e))
                .collect()
        };
        let realised = drawn(&format!("realised in {code}"));
        assert_eq!(realised.len(), speeds.len(), "{}", curve.pair);
        for ((v, e), (&speed, &cor)) in realised
            .iter()
            .zip(curve.speeds.iter().zip(&curve.cor_realised))
        {
            assert_eq!((v.to_bits(), e.to_bits()), (speed.to_bits(), cor.to_bits()));
        }
        assert_eq!(drawn("its law, exact").len(), speeds.len());
        assert_eq!(drawn("Müller & Pöschel's closed form").len(), speeds.len());
    }
}
