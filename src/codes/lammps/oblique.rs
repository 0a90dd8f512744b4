//! The end of the input of a deck's oblique impact (LAMMPS): the run, then one line with the
//! bodies' motion along the contact plane, which the live runner reads from the log.

use crate::codes::deck::TANGENTIAL_LINE;
use crate::codes::template::exact_number;
use crate::codes::{CodeError, CodeSetup};
use crate::model::tangential::TangentialSpring;

/// Where a wall's tangential words go in a normal impact's input.
pub(super) enum TangentialSlot<'a> {
    /// In place of these words (a stock build's `tangential linear_nohistory 0 0`).
    Replace(&'a str),
    /// Before ` zplane` on the wall's line (the plugin's `fix wall/paper`, which has none).
    BeforePlane,
}

/// The input of `setup`'s oblique impact at a wall, from its normal impact's input `text`
/// (rendered by `code` from its wall template): the ball's velocity along x and its spin ω_y
/// set beside its vz, the wall's `tangential` words, and the run's end of [`oblique_lines`].
/// `text` itself for a normal setup.
pub(super) fn oblique_wall_input(
    code: &str,
    setup: &CodeSetup,
    text: String,
    slot: TangentialSlot,
    tangential: &str,
) -> Result<String, CodeError> {
    let Some(oblique) = setup.oblique else {
        return Ok(text);
    };
    let ours = |what: &str| setup.unsupported(code, format!("the wall template has no {what}"));
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    let velocity = lines
        .iter_mut()
        .find(|l| l.starts_with("set ") && l.contains(" vz "))
        .ok_or_else(|| ours("`set … vz` line"))?;
    velocity.push_str(&format!(
        " vx {} omega 0 {} 0",
        exact_number(oblique.ball.tangential_velocity),
        exact_number(oblique.ball.angular_velocity)
    ));
    let wall = lines
        .iter_mut()
        .find(|l| l.starts_with("fix ") && l.contains(" zplane "))
        .ok_or_else(|| ours("wall line"))?;
    *wall = match slot {
        TangentialSlot::Replace(words) if wall.contains(words) => {
            wall.replacen(words, tangential, 1)
        }
        TangentialSlot::Replace(words) => return Err(ours(words)),
        TangentialSlot::BeforePlane => {
            wall.replacen(" zplane ", &format!(" {tangential} zplane "), 1)
        }
    };
    // The template ends with the run: thermo_style, thermo, run.
    let run_start = lines
        .iter()
        .rposition(|l| l.starts_with("thermo_style"))
        .ok_or_else(|| ours("run at its end"))?;
    lines.truncate(run_start);
    lines.extend(oblique_lines(false, setup.steps));
    Ok(lines.join("\n") + "\n")
}

/// A stock build's `tangential` words of `setup`'s law at a wall of `fix wall/gran granular`:
/// Mindlin's spring as `mindlin 8G* 0 μ` (the code scales k_t by the contact radius
/// `a = sqrt(R* δ)`, so `8 G* a` is the case's spring with the case's own G*, not the one the
/// code would mix from the `E = 2E*, ν = 0` its normal model is given), a constant spring as
/// `linear_history k_t 0 μ`, the proportional one as `mindlin ratio·C/sqrt(R*) 0 μ` (`k_t a`
/// is then `ratio C sqrt(δ)`); the tangential damping off (`x_γ,t = 0`). A case's dashpot is
/// refused: the code's tangential damping is a multiple of its normal one, not a ratio of
/// `k_t`.
pub(super) fn granular_tangential(code: &str, setup: &CodeSetup) -> Result<String, CodeError> {
    let Some(oblique) = setup.oblique else {
        return Ok(String::new());
    };
    refuse_damped(code, setup)?;
    let mu = exact_number(oblique.friction_coefficient);
    Ok(match oblique.law.spring {
        TangentialSpring::Mindlin => {
            let g = setup.effective_shear_modulus().ok_or_else(|| {
                setup.unsupported(code, "Mindlin's spring needs both bodies' E and ν")
            })?;
            format!("tangential mindlin {} 0 {mu}", exact_number(8.0 * g))
        }
        TangentialSpring::Linear { stiffness } => {
            format!(
                "tangential linear_history {} 0 {mu}",
                exact_number(stiffness)
            )
        }
        TangentialSpring::Proportional { ratio } => format!(
            "tangential mindlin {} 0 {mu}",
            exact_number(ratio * setup.stiffness / setup.pair_radius().sqrt())
        ),
    })
}

/// The plugin's `tangential` words of `setup`'s law: `mindlin μ` (its G* from the bodies' E
/// and ν, as the case forms it) or `linear k_t μ`; it has no proportional spring and no
/// dashpot.
pub(super) fn plugin_tangential(code: &str, setup: &CodeSetup) -> Result<String, CodeError> {
    let Some(oblique) = setup.oblique else {
        return Ok(String::new());
    };
    refuse_damped(code, setup)?;
    let mu = exact_number(oblique.friction_coefficient);
    match oblique.law.spring {
        TangentialSpring::Mindlin => Ok(format!("tangential mindlin {mu}")),
        TangentialSpring::Linear { stiffness } => {
            Ok(format!("tangential linear {} {mu}", exact_number(stiffness)))
        }
        TangentialSpring::Proportional { .. } => Err(setup.unsupported(
            code,
            "[tangential] spring = \"proportional\": the plugin's springs are `mindlin` and `linear`",
        )),
    }
}

fn refuse_damped(code: &str, setup: &CodeSetup) -> Result<(), CodeError> {
    match setup.oblique {
        Some(o) if o.law.damping_ratio != 0.0 => Err(setup.unsupported(
            code,
            format!(
                "[tangential] damping_ratio = {}: this build's tangential dashpot is not a ratio of k_t; the case's law runs undamped only",
                o.law.damping_ratio
            ),
        )),
        _ => Ok(()),
    }
}

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
/// holds for a force on its bound throughout; with a dashpot, the history stored against it at
/// the bound makes the force point forward in the first steps of the contact, for as long as
/// the spring's stiffness against the normal one decides (at e 0.7 the same `tangential mindlin
/// NULL 1.0 0.3` line delivers 94 % of Coulomb's friction in the 2021 build, whose wall forms a
/// softer `NULL` spring, and 99 % in the 2025 one, both 102 % undamped:
/// `tests/lammps_wall_mindlin.rs`), so the check runs the bound undamped.
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
