//! The paper plugin's coefficients as a deck writes them (`pair_coeff` of `pair_style paper`
//! and `paper/linear`, `fix wall/paper hertz|linear`, each with an optional
//! `tangential mindlin MU` or `tangential linear KT MU`), read as the plugin reads them, and the
//! paper's law each gives a pair.

use crate::codes::deck::{DeckError, PairLaw, SourceLine};
use crate::codes::script::Command;
use crate::model::exact;
use crate::model::law::{CodeLaw, PaperLaw};

/// The contact stiffness a line of the paper plugin gives.
#[derive(Clone, Copy, Debug)]
pub(super) enum PaperStiffness {
    /// `pair_style paper`, `wall/paper hertz`: `C = (4/3) E* sqrt(R*)` with this E*, Pa.
    Hertz(f64),
    /// `pair_style paper/linear`, `wall/paper linear`: `C = kn`, N/m.
    Linear(f64),
}

/// The plugin's optional tangential force: a history spring bounded by Coulomb on the whole
/// normal force.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum PaperTangential {
    /// `tangential mindlin MU`: `k_t = 8 G* sqrt(R* δ)` from the materials.
    Mindlin { friction: f64 },
    /// `tangential linear KT MU`: `k_t` constant, N/m.
    Linear { stiffness: f64, friction: f64 },
}

/// What a `pair_coeff` or `fix wall/paper` line of the paper plugin sets: η, the stiffness and
/// the tangential force if any.
#[derive(Clone, Copy, Debug)]
pub(super) struct PaperCoeff {
    pub(super) eta: f64,
    pub(super) stiffness: PaperStiffness,
    pub(super) tangential: Option<PaperTangential>,
}

/// Read `tangential mindlin MU` or `tangential linear KT MU` from `c.words[start..end]`
/// (`words[start]` is `tangential`), checked as the plugin checks them; `mindlin` only where the
/// line carries the materials (`!linear`).
fn paper_tangential(
    c: &Command,
    start: usize,
    end: usize,
    linear: bool,
) -> Result<PaperTangential, DeckError> {
    let form = "tangential mindlin MU, or tangential linear KT MU";
    let words = &c.words[start..end];
    let count_error = || {
        c.refuse(
            format!("`{}` ({} words)", words.join(" "), words.len()),
            form,
        )
    };
    let tangential = match words.get(1).map(String::as_str) {
        Some("mindlin") if linear => {
            return Err(c.refuse(
                "tangential mindlin on a linear normal law (the line has no E and nu)",
                "tangential linear KT MU (the plugin stops the run otherwise)",
            ));
        }
        Some("mindlin") if words.len() == 3 => PaperTangential::Mindlin {
            friction: c.number(start + 2, "tangential MU")?,
        },
        Some("linear") if words.len() == 4 => {
            let stiffness = c.number(start + 2, "tangential KT")?;
            if stiffness.is_nan() || stiffness <= 0.0 {
                return Err(c.refuse(
                    format!("tangential KT = {stiffness}"),
                    "KT > 0, N/m (the plugin stops the run otherwise)",
                ));
            }
            PaperTangential::Linear {
                stiffness,
                friction: c.number(start + 3, "tangential MU")?,
            }
        }
        Some("mindlin" | "linear") => return Err(count_error()),
        Some(other) => {
            return Err(c.refuse(format!("tangential model `{other}`"), form));
        }
        None => return Err(count_error()),
    };
    let (PaperTangential::Mindlin { friction } | PaperTangential::Linear { friction, .. }) =
        tangential;
    if !(friction >= 0.0 && friction.is_finite()) {
        return Err(c.refuse(
            format!("tangential MU = {friction}"),
            "a finite MU >= 0 (the plugin stops the run otherwise)",
        ));
    }
    Ok(tangential)
}

/// Read the plugin's coefficients from `c.words[start..end]`: `eta E nu [E2 nu2]` (Hertz,
/// `E2 nu2` allowed where `two_materials`) or `eta kn` (linear), then the optional tangential
/// words, checked as the plugin checks them.
pub(super) fn paper_coeff(
    c: &Command,
    start: usize,
    end: usize,
    linear: bool,
    two_materials: bool,
) -> Result<PaperCoeff, DeckError> {
    let tangential_at = (start..end).find(|&k| c.words[k] == "tangential");
    let tangential = tangential_at
        .map(|k| paper_tangential(c, k, end, linear))
        .transpose()?;
    let end = tangential_at.unwrap_or(end);
    let form = match (linear, two_materials) {
        (true, _) => "eta kn [tangential linear KT MU]",
        (false, true) => "eta E nu [E2 nu2] [tangential mindlin MU | tangential linear KT MU]",
        (false, false) => "eta E nu Ewall nuwall [tangential mindlin MU | tangential linear KT MU]",
    };
    let counts: &[usize] = match (linear, two_materials) {
        (true, _) => &[2],
        (false, true) => &[3, 5],
        (false, false) => &[5],
    };
    if !counts.contains(&(end.saturating_sub(start))) {
        return Err(c.refuse(
            format!("`{}`", c.text),
            &format!("the paper plugin's {form}"),
        ));
    }
    let values = (start..end)
        .map(|k| c.number(k, form))
        .collect::<Result<Vec<_>, _>>()?;
    let eta = values[0];
    if !(0.0..1.0).contains(&eta) {
        return Err(c.refuse(
            format!("eta = {eta}"),
            "0 <= eta < 1 (the plugin stops the run otherwise: eta >= 1 never separates the bodies, eta < 0 creates energy)",
        ));
    }
    let stiffness = if linear {
        PaperStiffness::Linear(values[1])
    } else {
        let (e1, nu1) = (values[1], values[2]);
        let (e2, nu2) = if values.len() == 5 {
            (values[3], values[4])
        } else {
            (e1, nu1)
        };
        PaperStiffness::Hertz(super::paper_plugin_modulus(e1, nu1, e2, nu2))
    };
    Ok(PaperCoeff {
        eta,
        stiffness,
        tangential,
    })
}

/// The paper's law the plugin's coefficients give a pair of `R*` and mass `(r_star, mass)`: its
/// η, the COR it is built to realise entered, a trap saying so first among `traps`.
pub(super) fn paper_law(
    model: &str,
    coeff: &PaperCoeff,
    (r_star, mass): (f64, f64),
    traps: Vec<String>,
) -> PairLaw {
    let (stiffness, exponent) = match coeff.stiffness {
        PaperStiffness::Hertz(modulus) => (4.0 / 3.0 * modulus * r_star.sqrt(), 1.5),
        PaperStiffness::Linear(kn) => (kn, 1.0),
    };
    let law = PaperLaw {
        mass,
        stiffness,
        exponent,
        loss_coefficient: coeff.eta,
    };
    let e = exact::restitution(coeff.eta);
    let eta_trap = format!(
        "eta is η itself, not a COR: {} gives e = sqrt((1 − η)/(1 + η)) = {e:.6}",
        coeff.eta
    );
    let tangential = coeff.tangential.map(|t| {
        let spring = match t {
            PaperTangential::Mindlin { friction } => {
                format!("tangential mindlin {friction}: k_t = 8 G* sqrt(R* δ)")
            }
            PaperTangential::Linear {
                stiffness,
                friction,
            } => format!("tangential linear {stiffness} {friction}: k_t = {stiffness} N/m"),
        };
        format!(
            "{spring} with the Coulomb bound on the whole normal force (dashpot branch included), \
             no tangential damping; the rows here check the normal half"
        )
    });
    let traps = std::iter::once(eta_trap)
        .chain(tangential)
        .chain(traps)
        .collect();
    PairLaw::new(model, CodeLaw::Paper(law), Some(e), traps)
}

/// A `fix wall/paper` as read.
#[derive(Clone, Debug)]
pub(super) struct PaperWall {
    pub(super) id: String,
    pub(super) coeff: PaperCoeff,
    /// The model's words (`hertz eta E nu Ewall nuwall`, `linear eta kn`).
    pub(super) model: Vec<String>,
    pub(super) at: SourceLine,
    pub(super) geometry: String,
}
