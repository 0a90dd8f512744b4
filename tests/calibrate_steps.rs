//! `calibrate`'s recommended steps, in the fast tier: the process runs with no DEM code found
//! (each build's `MILLIMPACT_<CODE>_BINARY` names a missing file), so no LAMMPS build is probed
//! and the cards are planned with the drivers' fallback conventions, as on a machine without
//! the codes. tests/calibrate_live.rs checks the same with the installed builds probed.

mod common;

#[test]
fn a_cards_step_is_the_largest_within_the_tolerance_without_the_codes() {
    for (variable, missing) in common::codes_hidden() {
        // SAFETY: this file's only test sets the variables before anything reads them, and
        // nothing else runs in this process meanwhile.
        unsafe { std::env::set_var(variable, missing) };
    }
    common::calibrate::a_cards_step_is_the_largest_within_the_tolerance();
}
