//! The held-out oblique cases run through `millimpact reference` in a DEM code: what each
//! build's live oblique test asserts.
#![allow(dead_code)]

use serde_json::Value;

use super::{millimpact, root};

/// The held-out oblique ball-on-plate cases the codes run: gross sliding, and backspin.
pub const HELD_OUT: [&str; 2] = ["ball_plate_sliding", "ball_plate_spin"];

/// `millimpact reference --code CODE cases/oblique/CASE.toml --format json` (exit 0 required),
/// its `tangential` object.
pub fn reference_tangential(code: &str, case: &str) -> Value {
    reference_tangential_with(code, case, &[])
}

/// [`reference_tangential`] with more options (`--clamp`, a step).
pub fn reference_tangential_with(code: &str, case: &str, options: &[&str]) -> Value {
    let path = root().join(format!("cases/oblique/{case}.toml"));
    let text = super::stdout(
        millimpact()
            .args(["reference", "--code", code, "--format", "json"])
            .args(options)
            .arg(path),
    );
    let record: Value = serde_json::from_str(&text).unwrap();
    record["tangential"].clone()
}

/// The case's run in `code` meets Coulomb's closed form: the changes of velocity along the
/// plane and of spin within the allowed share of the closed form's (1 % and the attractive
/// tail's friction), the spin changed the way the closed form's does, and the closed form is
/// the one the case was written for. Returns the two change errors.
#[track_caller]
pub fn assert_meets_closed_form(code: &str, case: &str) -> (f64, f64) {
    let t = reference_tangential(code, case);
    assert_eq!(t["closed_form"], "gross_sliding", "{code} {case}: {t}");
    let number = |key: &str| {
        t[key]
            .as_f64()
            .unwrap_or_else(|| panic!("{code} {case}: {key} in {t}"))
    };
    let allowed = number("allowed_change_error");
    assert!((0.01..0.03).contains(&allowed), "{code} {case}: {t}");
    let (v, w) = (
        number("tangential_change_error"),
        number("spin_change_error"),
    );
    assert!(
        v.abs() <= allowed && w.abs() <= allowed,
        "{code} {case}: changes off by {v:+e} and {w:+e}, allowed {allowed:e}: {t}"
    );
    let spin_change = number("angular_velocity_out") - number("angular_velocity");
    let closed_change = number("angular_velocity_closed_form") - number("angular_velocity");
    assert!(
        spin_change * closed_change > 0.0,
        "{code} {case}: spin changed by {spin_change}, the closed form by {closed_change}"
    );
    eprintln!("{code} {case}: change errors v_t {v:+.3e}, ω {w:+.3e}, allowed {allowed:.3e}");
    (v, w)
}
