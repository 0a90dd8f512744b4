//! The paper plugin's coefficients as a deck writes them (`pair_coeff` of `pair_style paper`
//! and `paper/linear`, `fix wall/paper hertz|linear`), read as the plugin reads them, and the
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

/// What a `pair_coeff` or `fix wall/paper` line of the paper plugin sets: η and the stiffness.
#[derive(Clone, Copy, Debug)]
pub(super) struct PaperCoeff {
    pub(super) eta: f64,
    pub(super) stiffness: PaperStiffness,
}

/// Read the plugin's coefficients from `c.words[start..end]`: `eta E nu [E2 nu2]` (Hertz,
/// `E2 nu2` allowed where `two_materials`) or `eta kn` (linear), checked as the plugin checks
/// them.
pub(super) fn paper_coeff(
    c: &Command,
    start: usize,
    end: usize,
    linear: bool,
    two_materials: bool,
) -> Result<PaperCoeff, DeckError> {
    let form = match (linear, two_materials) {
        (true, _) => "eta kn",
        (false, true) => "eta E nu [E2 nu2]",
        (false, false) => "eta E nu Ewall nuwall",
    };
    let counts: &[usize] = match (linear, two_materials) {
        (true, _) => &[2],
        (false, true) => &[3, 5],
        (false, false) => &[5],
    };
    if !counts.contains(&(end.saturating_sub(start))) {
        return Err(DeckError::unsupported(
            &c.at,
            format!("`{}`", c.text),
            &format!("the paper plugin's {form}"),
        ));
    }
    let values = (start..end)
        .map(|k| c.number(k, form))
        .collect::<Result<Vec<_>, _>>()?;
    let eta = values[0];
    if !(0.0..1.0).contains(&eta) {
        return Err(DeckError::unsupported(
            &c.at,
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
    Ok(PaperCoeff { eta, stiffness })
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
    let traps = std::iter::once(eta_trap).chain(traps).collect();
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
