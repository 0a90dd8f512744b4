//! `deck --impact-velocity A:B:N` run in LAMMPS: a deck with `damping viscoelastic` (whose COR
//! depends on the speed) realises, at each speed asked, the COR of the harness's own
//! integration of its law, within the step's band; Müller & Pöschel's closed form lies beside
//! it. `UPDATE_DECK_RUNS=1 cargo test --release --test deck_speed_live -- --ignored` also writes
//! the runs to `tests/data/deck/lammps-viscoelastic.runs.json` (read by `tests/deck_speed.rs`).

mod common;

use std::path::Path;

use millimpact::analysis::deck::{LiveRunner, Recording, check_deck, read_deck};
use millimpact::analysis::store::verify::REMAINDER_TOLERANCE;
use millimpact::codes::CodeName;
use millimpact::codes::deck::DeckOptions;

/// The deck, and the speeds its check is recorded at (`0.5:8:5`).
pub const DECK: &str = "tests/data/deck/lammps-viscoelastic.in";
const SPEEDS: [f64; 5] = [0.5, 1.0, 2.0, 4.0, 8.0];

#[test]
#[ignore = "live: runs LAMMPS (the Debian build) on tests/data/deck/lammps-viscoelastic.in"]
fn a_viscoelastic_deck_realises_its_law_at_every_speed_asked() {
    std::env::set_current_dir(common::root()).unwrap();
    // The speeds as the command line makes them of `0.5:8:5`.
    let output = common::millimpact()
        .args([
            "deck",
            DECK,
            "--impact-velocity",
            "0.5:8:5",
            "--format",
            "json",
        ])
        .output()
        .unwrap();
    assert_eq!(
        output.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let json: serde_json::Value = serde_json::from_slice(&output.stdout).unwrap();
    let given: Vec<f64> = json["velocities"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    assert_eq!(given.len(), SPEEDS.len());
    for (a, b) in given.iter().zip(SPEEDS) {
        assert!((a / b - 1.0).abs() < 1e-15, "{given:?}");
    }

    let (code, deck) = read_deck(Path::new(DECK), None, &DeckOptions::default()).unwrap();
    assert_eq!(code, CodeName::Lammps);
    let live = LiveRunner::default();
    let recording = Recording {
        inner: &live,
        runs: Default::default(),
    };
    let report = check_deck(code, &deck, (given, "given".into()), &recording).unwrap();
    // The bead pair and the bead on the floor, at five speeds each.
    assert_eq!(report.impacts.len(), 2 * SPEEDS.len());
    for i in &report.impacts {
        let at = format!("{} at {} m/s", i.pair, i.impact_velocity);
        assert_eq!(i.failure, None, "{at}");
        assert!(
            (i.remainder / i.cor_law_stepped).abs() <= REMAINDER_TOLERANCE,
            "{at}: remainder {:e}",
            i.remainder
        );
        // The realised COR is the law's exact one moved by the step, inside its band.
        let offset = i.realised.cor - i.cor_law;
        assert!(
            offset >= i.integration_band.min - REMAINDER_TOLERANCE
                && offset <= i.integration_band.max + REMAINDER_TOLERANCE,
            "{at}: {offset:e} outside [{:e}, {:e}]",
            i.integration_band.min,
            i.integration_band.max
        );
        assert!(offset.abs() < 5e-4, "{at}: {offset:e}");
        assert!(
            i.traps
                .iter()
                .any(|t| t.starts_with("the COR of this law depends on the impact speed")),
            "{at}: {:?}",
            i.traps
        );
    }
    assert_eq!(report.cor_against_speed.len(), 2);
    for curve in &report.cor_against_speed {
        assert!(curve.depends_on_speed && curve.spread > 0.05, "{curve:?}");
        // The COR falls as the speed rises, in the run as in the law.
        assert!(
            curve.cor_realised.windows(2).all(|w| w[1] < w[0]),
            "{curve:?}"
        );
        // limit_damping clamps the law, as Müller & Pöschel's series assumes: their closed
        // form is the law's exact COR to 1e-5 at these CORs (0.65–0.85).
        let closed = curve.cor_closed_form.as_ref().expect("a viscoelastic law");
        for (c, l) in closed.iter().zip(&curve.cor_law) {
            assert!((c - l).abs() < 1e-5, "{}: {c} against {l}", curve.pair);
        }
    }
    if std::env::var_os("UPDATE_DECK_RUNS").is_some() {
        let runs = recording.runs.into_inner().unwrap();
        std::fs::write(
            "tests/data/deck/lammps-viscoelastic.runs.json",
            serde_json::to_string_pretty(&runs).unwrap() + "\n",
        )
        .unwrap();
    }
}
