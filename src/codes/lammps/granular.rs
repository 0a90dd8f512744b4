//! The contact model words of `pair_coeff` (`pair_style granular`) and `fix wall/gran granular`,
//! read as LAMMPS's granular model reads them: a normal model and its coefficients, then the
//! damping, tangential, rolling, twisting, heat and `synchronized_verlet` keywords with theirs;
//! and the classic styles (`pair_style gran/…`, `fix wall/gran hooke…`) as the granular models
//! they equal.

use super::mixing::GranularModel;
use crate::codes::deck::{DeckError, DeckFriction};
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
            return Err(c.refuse(
                format!(
                    "normal model `{adhesive}`: an adhesive force the impact check does not model"
                ),
                NORMAL,
            ));
        }
        other => {
            return Err(c.refuse(
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
                    return Err(c.refuse(
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
                return Err(c.refuse(
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
        return Err(c.refuse(format!("damping {}", model.damping), DAMPING));
    }
    // A model whose last keyword lacks its arguments ends at the line's end: the build refuses
    // such a line itself, with its own words, and the check never reads past it.
    let k = k.min(c.words.len());
    model.words = c.words[start..k].to_vec();
    Ok((model, k))
}

/// The classic granular styles (`pair_style gran/…`, `fix wall/gran …`).
pub(super) const CLASSIC: [&str; 3] = ["hooke", "hooke/history", "hertz/history"];

/// A classic style's words from `c.words[k..]`: `STYLE Kn Kt γn γt μ dampflag [limit_damping]`
/// (`STYLE` `gran/hooke` … on a pair_style line, `hooke` … on a wall), read as the granular
/// model LAMMPS documents it to equal (`src/GRANULAR/pair_gran_hooke_history.cpp`,
/// `pair_gran_hertz_history.cpp`, `fix_wall_gran.cpp`): the normal force of `hooke` and
/// `hooke/history` is `Kn δ − m* γn δ̇` (`hooke Kn γn damping mass_velocity`), that of
/// `hertz/history` is `sqrt(R* δ) (Kn δ − m* γn δ̇)` (`hertz Kn γn damping viscoelastic`);
/// `Kt`, `γt`, μ and dampflag are tangential. Returns the model and the index after it.
pub(super) fn classic_model(c: &Command, k: usize) -> Result<(GranularModel, usize), DeckError> {
    let written = c.word(k, "a classic style")?;
    let style = written.strip_prefix("gran/").unwrap_or(written);
    let form = "STYLE Kn Kt gamma_n gamma_t xmu dampflag [limit_damping] (Kt, gamma_t may be NULL)";
    if !CLASSIC.contains(&style) {
        return Err(c.refuse(
            format!(
                "`{written}`: LAMMPS has no such classic granular style and stops at this line"
            ),
            "pair_style gran/hooke, gran/hooke/history, gran/hertz/history; fix wall/gran hooke, hooke/history, hertz/history; or granular",
        ));
    }
    let kn = c.number(k + 1, "Kn")?;
    let gamma_n = c.number(k + 3, "gamma_n")?;
    for (j, what) in [(k + 2, "Kt"), (k + 4, "gamma_t")] {
        if c.word(j, what)? != "NULL" {
            c.number(j, what)?;
        }
    }
    c.number(k + 5, "xmu")?;
    let flag = c.number(k + 6, "dampflag")?;
    #[allow(clippy::float_cmp)] // a flag is written 0 or 1
    if flag != 0.0 && flag != 1.0 {
        return Err(c.refuse(
            format!("dampflag {flag}"),
            &format!("dampflag 0 or 1 ({form})"),
        ));
    }
    if kn <= 0.0 || gamma_n < 0.0 {
        return Err(c.refuse(
            format!("Kn {kn}, gamma_n {gamma_n}"),
            "Kn > 0 and gamma_n >= 0 (LAMMPS stops otherwise: \"Illegal pair_style command\")",
        ));
    }
    let mut end = k + 7;
    let limit_damping = c.words.get(end).is_some_and(|w| w == "limit_damping");
    if limit_damping {
        end += 1;
    }
    let hertz = style == "hertz/history";
    let model = GranularModel {
        normal: if hertz { "hertz" } else { "hooke" }.into(),
        values: vec![kn, gamma_n],
        damping: if hertz {
            "viscoelastic"
        } else {
            "mass_velocity"
        }
        .into(),
        limit_damping,
        tangential: format!("classic {style}"),
        rolling: String::new(),
        twisting: String::new(),
        words: c.words[k..end].to_vec(),
    };
    Ok((model, end))
}

/// A model as the table names it: the classic style by its own name and the granular model
/// it equals, a granular model by its normal and damping models.
pub(super) fn model_name(model: &GranularModel) -> String {
    match model.tangential.strip_prefix("classic ") {
        Some(style) => format!("{style} (= {} damping {})", model.normal, model.damping),
        None => format!("{} damping {}", model.normal, model.damping),
    }
}

/// The friction a model's words give: a classic style's `xmu` (with its dampflag, as written),
/// a granular model's `tangential STYLE …` whose last coefficient is μ (`linear_nohistory γt μ`,
/// the others `kt γt μ`, as `gran_sub_mod_tangential.cpp` reads them); `None` for a model
/// without one or with μ = 0 (no friction to check).
pub(super) fn friction(model: &GranularModel) -> Option<DeckFriction> {
    if dashpot_only(model) {
        return None;
    }
    let words = &model.words;
    let (coefficient, written, damping) = if model.tangential.starts_with("classic ") {
        let (xmu, flag) = (words.get(5)?, words.get(6)?);
        let damping = (flag != "0").then(|| format!("dampflag {flag}"));
        (
            xmu,
            format!("{}: xmu {xmu}, dampflag {flag}", words[0]),
            damping,
        )
    } else {
        let k = words.iter().position(|w| w == "tangential")?;
        let style = words.get(k + 1)?;
        let args = if style == "linear_nohistory" { 2 } else { 3 };
        let mu = words.get(k + 1 + args)?;
        let damp = words.get(k + args)?;
        let damping =
            (damp.parse::<f64>().ok() != Some(0.0)).then(|| format!("damping coefficient {damp}"));
        (mu, words[k..=k + 1 + args].join(" "), damping)
    };
    let coefficient: f64 = coefficient.parse().ok()?;
    (coefficient > 0.0).then_some(DeckFriction {
        coefficient,
        model: written,
        damping,
    })
}

/// Whether a model's tangential force is its dashpot alone (the classic `hooke`, granular
/// `linear_nohistory`): bounded by μ F_n, its impulse is what its damping coefficient decides
/// (none at dampflag 0), so Coulomb's closed form does not hold and its friction is not checked.
pub(super) fn dashpot_only(model: &GranularModel) -> bool {
    match model.tangential.strip_prefix("classic ") {
        Some(style) => style == "hooke",
        None => {
            let words = &model.words;
            words
                .iter()
                .position(|w| w == "tangential")
                .and_then(|k| words.get(k + 1))
                .is_some_and(|style| style == "linear_nohistory")
        }
    }
}
