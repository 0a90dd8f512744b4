//! The end of the input of a deck's oblique impact (LAMMPS): the run, then one line with the
//! bodies' motion along the contact plane, which the live runner reads from the log.

use crate::codes::deck::TANGENTIAL_LINE;

/// The end of an oblique impact's input: its steps, then the line [`TANGENTIAL_LINE`] with the
/// ball's velocity along the plane and its spin (and the partner's, for a `pair`). At a wall
/// the plane's axis is x and the spin the ball's ω_y (its surface at the contact, −z from its
/// centre, moves at v_x − R ω_y); between two balls on the x axis it is y and the spin −ω_z.
/// A spin is read through a reduce over a group of the one atom (the 2025 build refuses a
/// per-atom vector's element in an equal-style variable), evaluated by the thermo output of
/// the last step so that it is current after the run.
pub(super) fn oblique_lines(pair: bool, steps: u64) -> Vec<String> {
    let (velocity, spin, sign) = if pair {
        ("vy", "omegaz", "-")
    } else {
        ("vx", "omegay", "")
    };
    let ids: &[u32] = if pair { &[1, 2] } else { &[1] };
    let mut lines = vec![format!(
        "compute         millimpact_spin all property/atom {spin}"
    )];
    let mut printed = Vec::new();
    let mut thermo = vec!["thermo_style    custom step".to_string()];
    for id in ids {
        lines.extend([
            format!("group           millimpact_{id} id {id}"),
            format!(
                "compute         millimpact_spin_{id} millimpact_{id} reduce sum c_millimpact_spin"
            ),
            format!("variable        millimpact_vt_{id} equal {velocity}[{id}]"),
            format!("variable        millimpact_w_{id} equal {sign}c_millimpact_spin_{id}"),
        ]);
        thermo.push(format!("v_millimpact_vt_{id} v_millimpact_w_{id}"));
        printed.push(format!("${{millimpact_vt_{id}}} ${{millimpact_w_{id}}}"));
    }
    lines.extend([
        thermo.join(" "),
        "thermo          0".into(),
        format!("run             {steps}"),
        format!(
            "print           \"{TANGENTIAL_LINE} {}\"",
            printed.join(" ")
        ),
    ]);
    lines
}
