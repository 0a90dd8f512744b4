//! `millimpact calibrate`: from a measured COR to the paper's η, the energy an impact absorbs,
//! and a card per DEM code: the settings that realise that COR on the case, the COR the code
//! will realise at a time step (its own law, stepped as it steps), the step that keeps the
//! offset below a tolerance, and the traps the card avoids.

use serde::Serialize;

use super::compare::phase::Range;
use super::store::{CodeLawError, own_law_exact, prepare};
use crate::codes::{CodeName, setup::elastic_contact_time};
use crate::model::case::Case;
use crate::model::exact;
use crate::model::law::CodeLaw;
use crate::model::trajectory::trajectory_metrics;
use crate::output::invocation::Invocation;
use crate::output::{Section, Summary, joules, sci, signed};
use crate::solve::dashpot::CodeStepping;

/// Start phases sampled when a card predicts a stepped COR.
pub(crate) const CARD_PHASES: usize = 16;
/// Fewest steps per elastic contact time a card recommends.
pub(crate) const FEWEST_STEPS_PER_CONTACT: u32 = 10;
/// Most steps per elastic contact time a card searches.
pub(crate) const MOST_STEPS_PER_CONTACT: u32 = 163_840;

/// How to calibrate.
#[derive(Clone, Debug, PartialEq)]
pub struct CalibrateOptions {
    /// The CORs to realise (one, or the ends of a measured range).
    pub restitutions: Vec<f64>,
    /// The codes' time step, s (default: the elastic contact time / 1000, as the drivers run).
    pub timestep: Option<f64>,
    /// The largest relative COR offset from the target a card's time step may leave.
    pub tolerance: f64,
}

/// One code's card for one COR.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Card {
    /// The code.
    pub code: CodeName,
    /// The lines to type into the code, as the driver renders them for this case and COR.
    pub settings: Vec<String>,
    /// Why the code cannot realise the COR on this case, if it cannot.
    pub unsupported: Option<String>,
    /// The law the code integrates with those settings.
    pub law: Option<CodeLaw>,
    /// That law's COR at zero step error.
    pub law_cor: f64,
    /// `law_cor − target`, relative to the target (a fit's residual where the code's damping
    /// comes from a fit).
    pub fit_error: f64,
    /// The time step the prediction is for, s.
    pub timestep: f64,
    /// The COR the code will realise at that step, started at touch as the drivers start it.
    pub realised_cor: f64,
    /// Its range over where the first contact falls within a step.
    pub realised_band: Range,
    /// The time step of the fewest steps per elastic contact time (from
    /// `FEWEST_STEPS_PER_CONTACT`) whose COR stays within the tolerance of the target over
    /// every start phase, s: one step per contact fewer leaves it (found by doubling, then
    /// bisection).
    pub timestep_for_tolerance: Option<f64>,
    /// Steps per elastic contact time at that step.
    pub steps_per_contact: Option<u32>,
    /// The traps the card avoids.
    pub traps: Vec<String>,
}

/// Everything for one COR.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Target {
    /// The COR asked for.
    pub restitution: f64,
    /// The paper's η that gives it: `(1 − e²)/(1 + e²)`.
    pub loss_coefficient: f64,
    /// Kinetic energy absorbed per impact, J.
    pub absorbed_energy: f64,
    /// Its share of the impact energy, `1 − e²`.
    pub absorbed_fraction: f64,
    /// One card per code.
    pub cards: Vec<Card>,
}

/// What `calibrate` reports.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Calibration {
    /// Case name.
    pub case: String,
    /// The case file.
    pub path: String,
    /// Impact energy `½ M v0²`, J.
    pub impact_energy: f64,
    /// The relative COR tolerance the cards' time steps keep.
    pub tolerance: f64,
    /// One entry per COR asked for.
    pub targets: Vec<Target>,
}

fn stepped_cor(
    law: &CodeLaw,
    v0: f64,
    dt: f64,
    steps: u64,
    stepping: &CodeStepping,
    phi: f64,
) -> f64 {
    trajectory_metrics(&stepping.trajectory(law, v0, dt, steps, phi * v0 * dt))
        .map_or(f64::NAN, |m| m.cor)
}

fn band(law: &CodeLaw, v0: f64, dt: f64, steps: u64, stepping: &CodeStepping) -> Range {
    let cors: Vec<f64> = (0..CARD_PHASES)
        .map(|k| stepped_cor(law, v0, dt, steps, stepping, k as f64 / CARD_PHASES as f64))
        .collect();
    Range {
        min: cors.iter().cloned().fold(f64::INFINITY, f64::min),
        max: cors.iter().cloned().fold(f64::NEG_INFINITY, f64::max),
    }
}

/// The card of `code` for `case` (already at the COR's η); it fails when the run cannot be
/// sized or the code's own law not integrated.
pub fn card(
    code: CodeName,
    case: &Case,
    timestep: Option<f64>,
    tolerance: f64,
) -> Result<Card, CodeLawError> {
    let driver = code.driver();
    let target = case.restitution();
    let v0 = case.impact_velocity;
    let setup = prepare(code, case, None, timestep, false)?;
    let law = driver.law(&setup);
    let stepping = driver.stepping(&setup);
    let (settings, unsupported) = match driver.render(&setup) {
        Ok(input) => {
            let keys = driver
                .card()
                .map_or(&[][..], |card| card.setting_keys(case.scene.kind()));
            let lines = input
                .text
                .lines()
                .map(str::trim)
                .filter(|l| !l.starts_with('#') && keys.iter().any(|k| l.contains(k)))
                .map(String::from)
                .collect();
            (lines, None)
        }
        Err(e) => (Vec::new(), Some(e.to_string())),
    };
    let exact = own_law_exact(code, &law, v0, 1e-12)?;
    // A step too small to count in u64 cannot be run either: saturate, the run refuses it.
    let steps_for = |dt: f64| {
        crate::model::count::ceil_count(1.05 * exact.contact_time / dt)
            .map_or(u64::MAX, |n| n.saturating_add(4))
    };
    let dt = setup.timestep;
    let realised_cor = stepped_cor(&law, v0, dt, steps_for(dt), &stepping, 0.0);
    let realised_band = band(&law, v0, dt, steps_for(dt), &stepping);
    let tc = elastic_contact_time(case);
    let within = |r: &Range| {
        (r.min - target).abs() <= tolerance * target && (r.max - target).abs() <= tolerance * target
    };
    let mut found = None;
    if unsupported.is_none() {
        let passes = |n: u32| {
            let h = tc / n as f64;
            // The frame's start is the run's at its own step; at another step, from touch.
            let at_h = CodeStepping {
                frame: None,
                ..stepping
            };
            within(&band(&law, v0, h, steps_for(h), &at_h))
        };
        // Doubling finds the first count that passes; bisection between it and the one before
        // finds the fewest steps per contact that pass, not a power of two.
        let mut hi = FEWEST_STEPS_PER_CONTACT;
        while hi <= MOST_STEPS_PER_CONTACT && !passes(hi) {
            hi *= 2;
        }
        if hi <= MOST_STEPS_PER_CONTACT {
            let mut lo = if hi == FEWEST_STEPS_PER_CONTACT {
                hi
            } else {
                hi / 2
            };
            while hi - lo > 1 {
                let mid = lo + (hi - lo) / 2;
                if passes(mid) {
                    hi = mid;
                } else {
                    lo = mid;
                }
            }
            found = Some((tc / hi as f64, hi));
        }
    }
    Ok(Card {
        code,
        settings,
        unsupported,
        law: Some(law),
        law_cor: exact.cor,
        fit_error: (exact.cor - target) / target,
        timestep: dt,
        realised_cor,
        realised_band,
        timestep_for_tolerance: found.map(|f| f.0),
        steps_per_contact: found.map(|f| f.1),
        traps: driver
            .card()
            .map(|card| card.traps(&setup))
            .unwrap_or_default(),
    })
}

/// Calibrate `case` for every COR in the options.
pub fn calibrate(case: &Case, options: &CalibrateOptions) -> Result<Calibration, CodeLawError> {
    let law = case.law();
    let v0 = case.impact_velocity;
    let impact_energy = 0.5 * law.mass * v0 * v0;
    let mut targets = Vec::new();
    for &e in &options.restitutions {
        let eta = exact::loss_coefficient(e);
        let at = case.with_loss_coefficient(eta);
        let cards = CodeName::ALL
            .iter()
            .map(|&code| card(code, &at, options.timestep, options.tolerance))
            .collect::<Result<_, _>>()?;
        targets.push(Target {
            restitution: e,
            loss_coefficient: eta,
            absorbed_energy: impact_energy * (1.0 - e * e),
            absorbed_fraction: 1.0 - e * e,
            cards,
        });
    }
    Ok(Calibration {
        case: case.name.clone(),
        path: case.path.display().to_string(),
        impact_energy,
        tolerance: options.tolerance,
        targets,
    })
}

/// One card as a CSV row.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct CardRecord {
    /// Case name.
    pub case: String,
    /// The COR asked for.
    pub restitution: f64,
    /// η.
    pub loss_coefficient: f64,
    /// Absorbed energy per impact, J.
    pub absorbed_energy: f64,
    /// Its share of the impact energy.
    pub absorbed_fraction: f64,
    /// The code.
    pub code: CodeName,
    /// The settings, joined by ` | `.
    pub settings: String,
    /// The law's COR at zero step error.
    pub law_cor: f64,
    /// Its relative residual from the target.
    pub fit_error: f64,
    /// The time step of the prediction, s.
    pub timestep: f64,
    /// The COR realised at that step.
    pub realised_cor: f64,
    /// Smallest over the start phase.
    pub realised_cor_min: f64,
    /// Largest over the start phase.
    pub realised_cor_max: f64,
    /// The step that keeps the offset within the tolerance, s.
    pub timestep_for_tolerance: Option<f64>,
    /// Steps per elastic contact time at that step.
    pub steps_per_contact: Option<u32>,
    /// Why the code cannot, if it cannot.
    pub unsupported: Option<String>,
}

impl Summary for Calibration {
    type Record = CardRecord;

    fn records(&self) -> Vec<CardRecord> {
        self.targets
            .iter()
            .flat_map(|t| {
                t.cards.iter().map(|c| CardRecord {
                    case: self.case.clone(),
                    restitution: t.restitution,
                    loss_coefficient: t.loss_coefficient,
                    absorbed_energy: t.absorbed_energy,
                    absorbed_fraction: t.absorbed_fraction,
                    code: c.code,
                    settings: c.settings.join(" | "),
                    law_cor: c.law_cor,
                    fit_error: c.fit_error,
                    timestep: c.timestep,
                    realised_cor: c.realised_cor,
                    realised_cor_min: c.realised_band.min,
                    realised_cor_max: c.realised_band.max,
                    timestep_for_tolerance: c.timestep_for_tolerance,
                    steps_per_contact: c.steps_per_contact,
                    unsupported: c.unsupported.clone(),
                })
            })
            .collect()
    }

    fn sections(&self) -> Vec<Section> {
        let mut out = Vec::new();
        for t in &self.targets {
            let mut s = Section::new(
                Some(format!(
                    "{}: COR {} → η = {:.6}; absorbed per impact {} = {:.1} % of the impact energy {}",
                    self.case,
                    t.restitution,
                    t.loss_coefficient,
                    joules(t.absorbed_energy),
                    100.0 * t.absorbed_fraction,
                    joules(self.impact_energy)
                )),
                &[
                    "code",
                    "law's COR (fit error)",
                    "Δt (s)",
                    "COR realised at Δt [start-phase band]",
                    &format!("Δt for |ΔCOR| ≤ {:e}", self.tolerance),
                ],
            );
            for c in &t.cards {
                s.rows.push(vec![
                    c.code.to_string(),
                    format!("{:.6} ({})", c.law_cor, signed(c.fit_error)),
                    sci(c.timestep),
                    format!(
                        "{:.6} [{:.6}, {:.6}]",
                        c.realised_cor, c.realised_band.min, c.realised_band.max
                    ),
                    match (c.timestep_for_tolerance, c.steps_per_contact) {
                        (Some(h), Some(n)) => format!("{} ({n} steps per contact)", sci(h)),
                        _ => "none found".into(),
                    },
                ]);
            }
            out.push(s);
            for c in &t.cards {
                let mut lines = vec![format!("{} card (COR {}):", c.code, t.restitution)];
                if let Some(why) = &c.unsupported {
                    lines.push(format!("  cannot: {why}"));
                }
                lines.extend(c.settings.iter().map(|l| format!("    {l}")));
                lines.extend(c.traps.iter().map(|l| format!("  avoids: {l}")));
                out.push(Section::text(lines));
            }
        }
        out
    }

    fn footer(&self) -> Vec<String> {
        let cors: Vec<String> = self
            .targets
            .iter()
            .map(|t| t.restitution.to_string())
            .collect();
        let command = if cors.len() == 1 {
            Invocation::new("calibrate").option("--cor", &cors[0])
        } else {
            Invocation::new("calibrate").option("--cor-range", cors.join(":"))
        };
        vec![format!(
            "reproduce: {} --tolerance {:e}",
            command.arg(&self.path),
            self.tolerance
        )]
    }
}
