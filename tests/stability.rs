//! `millimpact stability`: the extreme-case grid through the command line. The fixed-step
//! stability limits are the module's own unit tests.

mod common;

use common::millimpact;
use serde_json::Value;

/// The grid's largest loss coefficient, as the command's page states it (η from 0 to 0.999999).
const ETA_MAX: f64 = 0.999999;

/// The whole grid through the command line: exit 0, the documented shape, every rk4-event and
/// dopri5 case within 1e-9, every run finite and bounded, and COR → 0 as η → 1.
#[test]
fn every_grid_case_passes() {
    let out = millimpact()
        .args(["stability", "--format", "json"])
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    let doc: Value = serde_json::from_slice(&out).unwrap();
    let cases = doc["cases"].as_array().unwrap();
    assert!(cases.len() >= 4 * 200, "{} runs", cases.len());
    for c in cases {
        let method = c["method"].as_str().unwrap();
        let pass = c["pass"].as_bool().unwrap();
        assert!(pass, "{method} fails {}", c["case"]);
        assert!(c["finite"].as_bool().unwrap() && c["bounded_work"].as_bool().unwrap());
        if method == "rk4-event" || method == "dopri5" {
            for key in ["cor_error", "peak_deformation_error", "contact_time_error"] {
                let e = c[key].as_f64().unwrap();
                assert!(e <= 1e-9, "{method} {}: {key} = {e}", c["case"]);
            }
            let cor = c["cor"].as_f64().unwrap();
            assert!((0.0..=1.0).contains(&cor));
        }
        if c["loss_coefficient"].as_f64().unwrap() == ETA_MAX {
            // e(0.999999) = 7.07e-4; even verlet's wrong-signed half step stays below 1e-2.
            let cor = c["cor"].as_f64().unwrap();
            assert!(cor < 1e-2, "{method} {}: COR {cor} at η → 1", c["case"]);
        }
    }
    // The grid spans what it claims.
    let span = |key: &str| {
        let v: Vec<f64> = cases.iter().filter_map(|c| c[key].as_f64()).collect();
        (
            v.iter().cloned().fold(f64::MAX, f64::min),
            v.iter().cloned().fold(f64::MIN, f64::max),
        )
    };
    assert_eq!(span("youngs_modulus"), (1e5, 1e15));
    assert_eq!(span("impact_velocity"), (1e-8, 1e3));
    assert_eq!(span("loss_coefficient"), (0.0, ETA_MAX));
    assert_eq!(span("aspect_ratio"), (1.0, 1000.0));
    assert!((span("mass_ratio").0 / 1e-6 - 1.0).abs() < 1e-9);
    let size = span("size");
    assert!(size.0 <= 1e-6 && size.1 >= 1.0);
}
