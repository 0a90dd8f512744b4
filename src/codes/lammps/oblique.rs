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

/// A wall's line (`fix ID GROUP wall/gran STYLE …`, as the impact carries it) with its
/// tangential damping off: a classic style's dampflag, a granular model's tangential damping
/// coefficient (`linear_nohistory γt μ`, the others `kt γt μ`) made 0. Coulomb's closed form
/// holds for a force on its bound throughout; a damped history spring lags its bound by what
/// the build's own damping decides (at e 0.7 the same `tangential mindlin NULL 1.0 0.3` line
/// delivers 94 % of Coulomb's friction in the 2021 build and 99 % in the 2025 one, both 102 %
/// undamped), so the check runs the bound undamped.
pub(super) fn undamped_wall(line: &str) -> String {
    let mut words: Vec<&str> = line.split_whitespace().collect();
    let Some(style) = words.iter().position(|w| *w == "wall/gran").map(|g| g + 1) else {
        return line.to_string();
    };
    let damping = if words.get(style) == Some(&"granular") {
        words[style..]
            .iter()
            .position(|w| *w == "tangential")
            .map(|k| style + k)
            .map(|k| match words.get(k + 1) {
                Some(&"linear_nohistory") => k + 2,
                _ => k + 3,
            })
    } else {
        // STYLE Kn Kt gamma_n gamma_t xmu dampflag
        Some(style + 6)
    };
    if let Some(slot) = damping.and_then(|k| words.get_mut(k)) {
        *slot = "0";
    }
    words.join(" ")
}

#[cfg(test)]
mod tests {
    use super::undamped_wall;

    #[test]
    fn the_tangential_damping_is_turned_off_and_nothing_else() {
        assert_eq!(
            undamped_wall(
                "fix floor all wall/gran hooke/history 2e5 NULL 2000 NULL 0.4 1 zplane 0 NULL"
            ),
            "fix floor all wall/gran hooke/history 2e5 NULL 2000 NULL 0.4 0 zplane 0 NULL"
        );
        assert_eq!(
            undamped_wall(
                "fix w all wall/gran granular hertz/material 2e11 0.9 0.3 damping tsuji tangential mindlin NULL 1.0 0.4 zplane 0 NULL"
            ),
            "fix w all wall/gran granular hertz/material 2e11 0.9 0.3 damping tsuji tangential mindlin NULL 0 0.4 zplane 0 NULL"
        );
        assert_eq!(
            undamped_wall(
                "fix w all wall/gran granular hooke 1e5 0.5 tangential linear_nohistory 1.0 0.3 zplane 0 NULL"
            ),
            "fix w all wall/gran granular hooke 1e5 0.5 tangential linear_nohistory 0 0.3 zplane 0 NULL"
        );
    }
}
