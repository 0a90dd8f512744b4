//! The contact model words of `pair_coeff` (`pair_style granular`) and `fix wall/gran granular`,
//! read as LAMMPS's granular model reads them: a normal model and its coefficients, then the
//! damping, tangential, rolling, twisting, heat and `synchronized_verlet` keywords with theirs.

use super::mixing::GranularModel;
use crate::codes::deck::DeckError;
use crate::codes::script::Command;

const NORMAL: &str = "hooke k d, hertz k d, hertz/material E d nu";
/// The tangential models of LAMMPS' granular styles (`*_classic` from 2025 on).
const TANGENTIAL: [&str; 8] = [
    "linear_nohistory",
    "linear_history",
    "linear_history_classic",
    "mindlin",
    "mindlin_rescale",
    "mindlin/force",
    "mindlin_rescale/force",
    "mindlin_classic",
];

const DAMPING: &str = "damping velocity, mass_velocity, viscoelastic, tsuji, coeff_restitution (a build from 2023 on)";

/// Read a granular model from `words[start..]`, up to the first word of `stop` (a wall style).
pub(super) fn read_model(
    c: &Command,
    start: usize,
    stop: &[&str],
) -> Result<(GranularModel, usize), DeckError> {
    let normal = c.word(start, "a normal model")?.to_string();
    let n = match normal.as_str() {
        "hooke" | "hertz" => 2,
        "hertz/material" => 3,
        adhesive @ ("dmt" | "jkr") => {
            return Err(DeckError::unsupported(
                &c.at,
                format!(
                    "normal model `{adhesive}`: an adhesive force the impact check does not model"
                ),
                NORMAL,
            ));
        }
        other => {
            return Err(DeckError::unsupported(
                &c.at,
                format!(
                    "normal model `{other}`: LAMMPS has no such normal model and stops at this line"
                ),
                NORMAL,
            ));
        }
    };
    let values = (start + 1..start + 1 + n)
        .map(|k| c.number(k, &normal))
        .collect::<Result<Vec<_>, _>>()?;
    let mut model = GranularModel {
        normal,
        values,
        damping: "viscoelastic".into(),
        limit_damping: false,
        tangential: String::new(),
        rolling: String::new(),
        twisting: String::new(),
        words: Vec::new(),
    };
    let mut k = start + 1 + n;
    while let Some(word) = c.words.get(k) {
        if stop.contains(&word.as_str()) {
            break;
        }
        match word.as_str() {
            "damping" => {
                model.damping = c.word(k + 1, "a damping model")?.to_string();
                k += 2;
            }
            "limit_damping" => {
                model.limit_damping = true;
                k += 1;
            }
            "tangential" | "rolling" | "twisting" => {
                let style = c.word(k + 1, word)?.to_string();
                let args = match (word.as_str(), style.as_str()) {
                    ("tangential", "linear_nohistory") => 2,
                    ("tangential", _) => 3,
                    ("rolling", "sds") => 3,
                    ("twisting", "marshall") => 0,
                    ("twisting", "sds") => 3,
                    _ => 0,
                };
                let known: &[&str] = match word.as_str() {
                    "tangential" => &TANGENTIAL,
                    "rolling" => &["none", "sds"],
                    _ => &["none", "marshall", "sds"],
                };
                if !known.contains(&style.as_str()) {
                    return Err(DeckError::unsupported(
                        &c.at,
                        format!(
                            "{word} `{style}`: LAMMPS has no such {word} model and stops at this line"
                        ),
                        &format!("{word} {}", known.join(", ")),
                    ));
                }
                let named = if style == "none" {
                    String::new()
                } else {
                    style.clone()
                };
                match word.as_str() {
                    "tangential" => model.tangential = named,
                    "rolling" => model.rolling = named,
                    _ => model.twisting = named,
                }
                k += 2 + args;
            }
            // LAMMPS' own reading: `synchronized_verlet` is a flag; `heat none` has no
            // coefficient, `heat area K` and `heat radius K` one.
            "synchronized_verlet" => k += 1,
            "heat" => {
                k += if c.words.get(k + 1).is_some_and(|m| m == "none") {
                    2
                } else {
                    3
                }
            }
            other => {
                return Err(DeckError::unsupported(
                    &c.at,
                    format!("`{other}` in a granular model"),
                    &format!("{NORMAL}; {DAMPING}; tangential, rolling, twisting; limit_damping"),
                ));
            }
        }
    }
    let known = [
        "velocity",
        "mass_velocity",
        "viscoelastic",
        "tsuji",
        "coeff_restitution",
    ];
    if !known.contains(&model.damping.as_str()) {
        return Err(DeckError::unsupported(
            &c.at,
            format!("damping {}", model.damping),
            DAMPING,
        ));
    }
    // A model whose last keyword lacks its arguments ends at the line's end: the build refuses
    // such a line itself, with its own words, and the check never reads past it.
    let k = k.min(c.words.len());
    model.words = c.words[start..k].to_vec();
    Ok((model, k))
}
