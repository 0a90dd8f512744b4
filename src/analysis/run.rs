//! What a run reports, and the text forms it is printed in (table, JSON, CSV, Markdown).
//! Field names are a contract with the tools that read them: extend, do not rename.

use serde::Serialize;

use std::path::{Path, PathBuf};

use thiserror::Error;

use crate::error::{Blame, UserError};
use crate::model::case::{Case, ContactKind};
use crate::model::exact::{self, ImpactFigures};
use crate::model::figures::{Checked, Elastic, Exact, Figures, Quantity, quantity, suffix};
use crate::model::tangential::{ClosedFormKind, TangentialBodies, TangentialLaw, normalised_angle};
use crate::output::{Section, Summary, sci, seconds, signed};
use crate::solve::paper::{self, Outcome, Sample, Settings};
use crate::solve::tangential::{ObliqueOutcome, closed_form, solve_oblique};
use crate::solve::{Knob, Method, SolveError, Stats};

/// The quantities of the closed forms a run is printed beside.
pub(crate) const REPORTED_EXACT: u8 =
    quantity::COR | quantity::PEAK_DEFORMATION | quantity::PEAK_FORCE | quantity::CONTACT_TIME;

/// The closed-form figures a run is compared with.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct ExactFigures {
    /// COR, peak deformation (m), peak force (N), contact time (s).
    #[serde(flatten)]
    pub figures: Figures<f64, REPORTED_EXACT>,
    /// Absorbed energy, J.
    pub absorbed_energy: f64,
}

/// Relative errors `(run - exact) / exact` of the checked quantities.
pub(crate) type RelativeErrors = Checked;

/// One impact by one method: everything `millimpact run` prints.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RunReport {
    /// Case name.
    pub case: String,
    /// Scene name.
    pub scene: &'static str,
    /// Method name.
    pub method: &'static str,
    /// Unilateral or bilateral.
    pub contact: &'static str,
    /// Loss coefficient η.
    pub loss_coefficient: f64,
    /// Impact speed, m/s.
    pub impact_velocity: f64,
    /// Reduced mass, kg.
    pub mass: f64,
    /// Contact stiffness C, N/m^n.
    pub stiffness: f64,
    /// How C was computed for a ball scene: "hertz" (`(4/3) E* sqrt(R*)`) or "paper" (the
    /// paper's printed `a E sqrt(R) / (1 - ν²)`); "rod" for the rod's `π D² E / (4H)`.
    pub stiffness_convention: StiffnessOrigin,
    /// Exponent n.
    pub exponent: f64,
    /// COR, peak deformation (m), peak force (N), contact time (s) and its compression and
    /// restitution parts (s).
    #[serde(flatten)]
    pub figures: Exact,
    /// Absorbed energy, J.
    pub absorbed_energy: f64,
    /// Absorbed energy as a fraction of the impact energy `½ M v0²`: `1 − e²`.
    pub absorbed_fraction: f64,
    /// Accepted steps.
    pub steps: u64,
    /// Right-hand-side evaluations.
    pub rhs_evaluations: u64,
    /// Wall time of the integration, s.
    pub wall_time: f64,
    /// Fixed step, s (fixed-step methods).
    pub timestep: Option<f64>,
    /// Closed forms.
    pub exact: ExactFigures,
    /// Relative errors against the closed forms.
    pub error: RelativeErrors,
    /// Elastic Hertz figures (ball scenes).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub hertz_elastic: Option<Elastic>,
    /// Bilateral contact: speed at each passage through zero approach, m/s.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub crossing_speeds: Vec<f64>,
    /// Where the run leaves the range its model or method is valid in (see [`warnings`]);
    /// a warning does not change the exit code.
    pub warnings: Vec<String>,
    /// The tangential half of an oblique or spinning case (absent for a normal one, whose
    /// output is what it always was).
    #[serde(flatten)]
    pub tangential: Option<TangentialReport>,
}

/// The tangential half of an oblique or spinning impact: the inputs, what the run gives, the
/// closed form where one holds. Velocities along the contact plane's axis `t`, spins with the
/// sign of the case (positive: rolling towards `+t`); angles in degrees from the normal.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct TangentialReport {
    /// The ball's centre velocity along the plane at first contact, m/s.
    pub tangential_velocity: f64,
    /// The ball's spin at first contact, rad/s.
    pub angular_velocity: f64,
    /// Coulomb's μ.
    pub friction_coefficient: f64,
    /// The tangential law (`spring`, its constant, `damping_ratio`).
    pub tangential_law: TangentialLaw,
    /// The ball's centre velocity along the plane at separation, m/s.
    pub tangential_velocity_out: f64,
    /// The ball's spin at separation, rad/s.
    pub angular_velocity_out: f64,
    /// Ball–ball: the other ball's centre velocity at separation, m/s.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub other_tangential_velocity_out: Option<f64>,
    /// Ball–ball: the other ball's spin at separation, rad/s.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub other_angular_velocity_out: Option<f64>,
    /// The slip of the contact point at first contact and at separation, m/s.
    pub slip_velocity_in: f64,
    /// See `slip_velocity_in`.
    pub slip_velocity_out: f64,
    /// Angle of the incident relative centre velocity from the normal, degrees:
    /// `atan2(v_t, v_n)`.
    pub incident_angle: f64,
    /// Angle of the rebound relative centre velocity from the normal, degrees:
    /// `atan2(v_t', e v_n)` with this run's normal COR `e`.
    pub rebound_angle: f64,
    /// Tangential COR of the contact point, `slip_out / slip_in` (−1: the slip reversed whole,
    /// 0: rolling); absent without slip.
    pub tangential_restitution: Option<f64>,
    /// Thornton's normalised incident angle `ψ = 2 slip_in / (μ (1+e) v_n)`; absent at μ = 0.
    pub normalised_incident_angle: Option<f64>,
    /// Thornton's normalised rebound angle `ψ' = 2 slip_out / (μ (1+e) v_n)`; in gross sliding
    /// `ψ' = ψ − 7`.
    pub normalised_rebound_angle: Option<f64>,
    /// Whether the force stayed on the Coulomb bound the whole contact.
    pub slid_throughout: bool,
    /// Changes of the tangential regime (inside the bound, on it).
    pub regime_changes: u32,
    /// Kinetic energy of the tangential motion (translation along the plane and spin) at
    /// first contact and at separation, J.
    pub tangential_energy_in: f64,
    /// See `tangential_energy_in`.
    pub tangential_energy_out: f64,
    /// Steps and right-hand-side evaluations of the coupled integration.
    pub tangential_steps: u64,
    /// See `tangential_steps`.
    pub tangential_rhs_evaluations: u64,
    /// The closed form, where one holds for the case (gross sliding, the stick reversal).
    pub tangential_exact: Option<TangentialExact>,
}

/// A tangential closed form beside the run.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct TangentialExact {
    /// Which closed form.
    pub kind: ClosedFormKind,
    /// The ball's centre velocity at separation, m/s.
    pub tangential_velocity_out: f64,
    /// The ball's spin at separation, rad/s.
    pub angular_velocity_out: f64,
    /// Relative error of the run's `tangential_velocity_out`.
    pub tangential_velocity_error: f64,
    /// Relative error of the run's `angular_velocity_out`.
    pub angular_velocity_error: f64,
}

impl TangentialReport {
    /// The report of `outcome` for `case`, oblique.
    fn new(case: &Case, outcome: &ObliqueOutcome) -> Option<TangentialReport> {
        let oblique = case.oblique.as_ref()?;
        let bodies = TangentialBodies::of(&case.scene, oblique)?;
        let v_n = case.impact_velocity;
        let e = outcome.restitution;
        let mu = oblique.friction_coefficient;
        let relative_in = oblique.tangential_velocity
            - bodies.other.map_or(0.0, |(_, _, m)| m.tangential_velocity);
        let relative_out =
            outcome.ball.tangential_velocity - outcome.other.map_or(0.0, |m| m.tangential_velocity);
        let exact = closed_form(case).map(|form| {
            let (ball, _) = bodies.after(form.impulse);
            TangentialExact {
                kind: form.kind,
                tangential_velocity_out: ball.tangential_velocity,
                angular_velocity_out: ball.angular_velocity,
                tangential_velocity_error: relative(
                    outcome.ball.tangential_velocity,
                    ball.tangential_velocity,
                ),
                angular_velocity_error: relative(
                    outcome.ball.angular_velocity,
                    ball.angular_velocity,
                ),
            }
        });
        Some(TangentialReport {
            tangential_velocity: oblique.tangential_velocity,
            angular_velocity: oblique.angular_velocity,
            friction_coefficient: mu,
            tangential_law: oblique.law,
            tangential_velocity_out: outcome.ball.tangential_velocity,
            angular_velocity_out: outcome.ball.angular_velocity,
            other_tangential_velocity_out: outcome.other.map(|m| m.tangential_velocity),
            other_angular_velocity_out: outcome.other.map(|m| m.angular_velocity),
            slip_velocity_in: outcome.slip_in,
            slip_velocity_out: outcome.slip_out,
            incident_angle: relative_in.atan2(v_n).to_degrees(),
            rebound_angle: relative_out.atan2(e * v_n).to_degrees(),
            tangential_restitution: (outcome.slip_in != 0.0)
                .then(|| outcome.slip_out / outcome.slip_in),
            normalised_incident_angle: normalised_angle(outcome.slip_in, v_n, mu, e),
            normalised_rebound_angle: normalised_angle(outcome.slip_out, v_n, mu, e),
            slid_throughout: outcome.slid_throughout,
            regime_changes: outcome.regime_changes,
            tangential_energy_in: outcome.tangential_energy_in,
            tangential_energy_out: outcome.tangential_energy_out,
            tangential_steps: outcome.stats.steps,
            tangential_rhs_evaluations: outcome.stats.rhs_evaluations,
            tangential_exact: exact,
        })
    }

    /// The rows of the human table.
    fn rows(&self) -> Vec<Vec<String>> {
        let exact = self.tangential_exact;
        let row = |name: &str, run: f64, exact: Option<f64>| {
            vec![
                name.to_string(),
                sci(run),
                exact.map(sci).unwrap_or_default(),
                exact.map(|x| signed(relative(run, x))).unwrap_or_default(),
            ]
        };
        vec![
            row(
                "tangential velocity out (m/s)",
                self.tangential_velocity_out,
                exact.map(|x| x.tangential_velocity_out),
            ),
            row(
                "angular velocity out (rad/s)",
                self.angular_velocity_out,
                exact.map(|x| x.angular_velocity_out),
            ),
            row("slip velocity out (m/s)", self.slip_velocity_out, None),
            row("rebound angle (°)", self.rebound_angle, None),
        ]
    }

    /// The notes of the human table.
    fn notes(&self) -> Vec<String> {
        let psi = match (
            self.normalised_incident_angle,
            self.normalised_rebound_angle,
        ) {
            (Some(a), Some(b)) => format!(", Thornton's ψ = {} → ψ' = {}", sci(a), sci(b)),
            _ => String::new(),
        };
        vec![
            format!(
                "tangential: v_t = {} m/s, ω = {} rad/s, μ = {}, law {}; {}, {} regime changes{psi}",
                self.tangential_velocity,
                self.angular_velocity,
                self.friction_coefficient,
                law_name(&self.tangential_law),
                if self.slid_throughout {
                    "slid throughout"
                } else {
                    "not sliding throughout"
                },
                self.regime_changes
            ),
            match self.tangential_exact {
                Some(x) => format!(
                    "tangential closed form: {}",
                    ClosedFormKind::describe(x.kind)
                ),
                None => "tangential closed form: none holds for this case (partial slip)".into(),
            },
        ]
    }
}

/// The law as the human table names it.
fn law_name(law: &TangentialLaw) -> String {
    use crate::model::tangential::TangentialSpring;
    let spring = match law.spring {
        TangentialSpring::Mindlin => "history, Mindlin spring 8 G* sqrt(R* δ)".to_string(),
        TangentialSpring::Linear { stiffness } => {
            format!("history, linear spring {} N/m", sci(stiffness))
        }
        TangentialSpring::Proportional { ratio } => {
            format!("history, spring {ratio} × the normal secant stiffness")
        }
    };
    if law.damping_ratio > 0.0 {
        format!("{spring}, damping ratio {}", law.damping_ratio)
    } else {
        spring
    }
}

/// Largest peak deformation, as a fraction of the effective radius R*, inside Hertz's
/// small-strain range. Hertz theory assumes a contact radius `a = sqrt(R* δ)` small against R*;
/// `a/R* ≤ 0.1` (Johnson, *Contact Mechanics*, 1985, §4.2 and §5.1, where the elastic
/// half-space idealisation is taken to hold) is `δ/R* ≤ 0.01`.
pub(crate) const HERTZ_MAX_STRAIN: f64 = 0.01;

/// Smallest rod length in diameters for the rod-end law: the rod's spring `π D² E / (4H)` is a
/// uniform bar in plane compression, which needs a slender rod (Saint-Venant: the end zone where
/// the contact stress spreads over the section is about one diameter long).
pub(crate) const ROD_MIN_SLENDERNESS: f64 = 5.0;

/// The ways a run leaves its valid range: a peak deformation beyond Hertz's small-strain range
/// (`HERTZ_MAX_STRAIN`), a rod too short for the bar spring (`ROD_MIN_SLENDERNESS`), and a
/// fixed-step result outside what the law allows (COR outside [0, 1], energy created), which is
/// the method's step error at a coarse step, not physics.
pub fn warnings(case: &Case, method: Method, figures: &ImpactFigures) -> Vec<String> {
    let mut out = Vec::new();
    if let Some(radius) = case.scene.effective_radius() {
        let strain = figures.peak_deformation / radius;
        if strain > HERTZ_MAX_STRAIN {
            out.push(format!(
                "{}: peak deformation {:.3e} m is {:.3} of the effective radius {:.3e} m, beyond \
                 Hertz's small-strain range (δ/R* ≤ {HERTZ_MAX_STRAIN}, contact radius ≤ 0.1 R*)",
                case.path.display(),
                figures.peak_deformation,
                strain,
                radius
            ));
        }
    }
    if let crate::model::scene::Scene::RodEnd { rod } = &case.scene {
        let slenderness = rod.length / rod.diameter;
        if slenderness < ROD_MIN_SLENDERNESS {
            out.push(format!(
                "{}: rod length {} m is {slenderness:.3} diameters; the rod-end law's bar spring \
                 π D² E / (4H) needs a rod of at least {ROD_MIN_SLENDERNESS} diameters",
                case.path.display(),
                rod.length
            ));
        }
    }
    if !(0.0..=1.0).contains(&figures.cor) || figures.absorbed_energy < 0.0 {
        out.push(format!(
            "{}: {method} gives a COR of {} (absorbed energy {:.3e} J): outside [0, 1]: the \
             method's step error at this step exceeds the loss (the exact COR is {}); a smaller \
             step shrinks it",
            case.path.display(),
            figures.cor,
            figures.absorbed_energy,
            exact::paper_impact(&case.law(), case.impact_velocity).cor
        ));
    }
    out
}

fn relative(value: f64, reference: f64) -> f64 {
    (value - reference) / reference
}

/// The relative errors `(value - reference) / reference` of each quantity of `Q`.
pub(crate) fn relative_errors<const Q: u8>(
    value: &Figures<f64, Q>,
    reference: &Figures<f64, Q>,
) -> Figures<f64, Q> {
    value.map(|q, v| relative(*v, *reference.get(q)))
}

impl RunReport {
    /// Assemble the report of `outcome` for `case` by `method`.
    pub(crate) fn new(case: &Case, method: Method, outcome: &Outcome) -> RunReport {
        RunReport::with_tangential(case, method, outcome, None)
    }

    /// [`RunReport::new`] with the tangential half of an oblique case.
    pub(crate) fn with_tangential(
        case: &Case,
        method: Method,
        outcome: &Outcome,
        oblique: Option<&ObliqueOutcome>,
    ) -> RunReport {
        let law = case.law();
        let exact = exact::paper_impact(&law, case.impact_velocity);
        let f = &outcome.figures;
        let figures = f.figures;
        let exact_figures = exact.figures;
        let hertz_elastic = match (
            case.scene.effective_modulus(),
            case.scene.effective_radius(),
        ) {
            (Some(e), Some(r)) => Some(exact::hertz_elastic(law.mass, e, r, case.impact_velocity)),
            _ => None,
        };
        let Stats {
            steps,
            rhs_evaluations,
            ..
        } = outcome.stats;
        RunReport {
            case: case.name.clone(),
            scene: case.scene.kind().name(),
            method: method.name(),
            contact: match case.contact {
                crate::model::case::ContactKind::Unilateral => "unilateral",
                crate::model::case::ContactKind::Bilateral => "bilateral",
            },
            loss_coefficient: law.loss_coefficient,
            impact_velocity: case.impact_velocity,
            mass: law.mass,
            stiffness: law.stiffness,
            stiffness_convention: match (case.scene.kind(), case.stiffness) {
                (crate::model::scene::SceneKind::RodEnd, _) => StiffnessOrigin::Rod,
                (_, crate::model::scene::StiffnessConvention::Hertz) => StiffnessOrigin::Hertz,
                (_, crate::model::scene::StiffnessConvention::Paper) => StiffnessOrigin::Paper,
            },
            exponent: law.exponent,
            figures,
            absorbed_energy: f.absorbed_energy,
            absorbed_fraction: 1.0 - f.cor * f.cor,
            steps,
            rhs_evaluations,
            wall_time: outcome.wall_time,
            timestep: outcome.timestep,
            exact: ExactFigures {
                figures: exact_figures.select(),
                absorbed_energy: exact.absorbed_energy,
            },
            error: relative_errors(&figures.select(), &exact_figures.select()),
            hertz_elastic,
            crossing_speeds: outcome.crossing_speeds.clone(),
            warnings: warnings(case, method, f),
            tangential: oblique.and_then(|o| TangentialReport::new(case, o)),
        }
    }

    /// The flat row of a sweep (one line of CSV).
    pub(crate) fn row(&self) -> RunRecord {
        RunRecord {
            case: self.case.clone(),
            method: self.method,
            loss_coefficient: self.loss_coefficient,
            figures: self.figures,
            exact: self.exact.figures.select(),
            error: self.error,
            absorbed_energy: self.absorbed_energy,
            absorbed_fraction: self.absorbed_fraction,
            steps: self.steps,
            rhs_evaluations: self.rhs_evaluations,
            wall_time: self.wall_time,
        }
    }

    /// The human table: the run beside the closed forms, then the work and the notes.
    pub(crate) fn sections(&self) -> Vec<Section> {
        let mut t = Section::new(
            Some(format!(
                "{} ({}, {}): method {}, η = {}, M = {} kg, C = {}, n = {}",
                self.case,
                self.scene,
                self.contact,
                self.method,
                self.loss_coefficient,
                sci(self.mass),
                sci(self.stiffness),
                self.exponent
            )),
            &["figure", "run", "exact", "relative error"],
        );
        // The closed forms' quantities, each with its relative error, then the energy and the
        // compression time, which have no error of their own.
        let compared = self.exact.figures.iter().map(|(q, &exact)| {
            let run = *self.figures.get(q);
            (label(q), run, exact, Some(relative(run, exact)))
        });
        let rest = [
            (
                "absorbed energy (J)",
                self.absorbed_energy,
                self.exact.absorbed_energy,
                None,
            ),
            (
                "absorbed share of the impact energy",
                self.absorbed_fraction,
                1.0 - self.exact.figures.cor * self.exact.figures.cor,
                None,
            ),
            (
                label(Quantity::CompressionTime),
                self.figures.compression_time,
                f64::NAN,
                None,
            ),
        ];
        let rows = compared.chain(rest);
        let tangential_rows = self
            .tangential
            .as_ref()
            .map(|t| t.rows())
            .unwrap_or_default();
        for (name, run, exact, error) in rows {
            t.rows.push(vec![
                name.to_string(),
                sci(run),
                if exact.is_nan() {
                    "".into()
                } else {
                    sci(exact)
                },
                error.map(signed).unwrap_or_default(),
            ]);
        }
        t.rows.extend(tangential_rows);
        let mut text = format!(
            "steps {}, rhs evaluations {}, wall time {}",
            self.steps,
            self.rhs_evaluations,
            seconds(self.wall_time)
        );
        if let Some(dt) = self.timestep {
            text += &format!(", Δt = {} s", sci(dt));
        }
        let mut notes = vec![text];
        if self.stiffness_convention == StiffnessOrigin::Paper {
            notes.push("stiffness: the paper's printed coefficient a E sqrt(R) / (1 - ν²), not Hertz's (4/3) E* sqrt(R*)".to_string());
        }
        if let Some(h) = &self.hertz_elastic {
            notes.push(format!(
                "elastic Hertz: peak deformation {} m, contact time {} s",
                sci(h.peak_deformation),
                sci(h.contact_time)
            ));
        }
        if !self.crossing_speeds.is_empty() {
            let speeds: Vec<String> = self.crossing_speeds.iter().map(|s| sci(*s)).collect();
            notes.push(format!(
                "speeds through zero approach (m/s): {}",
                speeds.join(", ")
            ));
        }
        if let Some(tangential) = &self.tangential {
            notes.extend(tangential.notes());
        }
        t.notes = notes;
        vec![t]
    }
}

/// The row name of a quantity in the human table, with its unit.
fn label(q: Quantity) -> &'static str {
    match q {
        Quantity::Cor => "COR",
        Quantity::PeakDeformation => "peak deformation (m)",
        Quantity::PeakForce => "peak force (N)",
        Quantity::ContactTime => "contact time (s)",
        Quantity::ForceContactTime => "force contact time (s)",
        Quantity::CompressionTime => "compression time (s)",
        Quantity::RestitutionTime => "restitution time (s)",
    }
}

/// How a case's contact stiffness `C` was formed (in JSON, its lowercase name).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum StiffnessOrigin {
    /// Hertz's `(4/3) E* sqrt(R*)`, for a ball scene.
    Hertz,
    /// The paper's printed `a E sqrt(R) / (1 - ν²)`, for a ball scene.
    Paper,
    /// The rod's `π D² E / (4H)`.
    Rod,
}

/// One case by one method, with the exact figures beside: a row of `millimpact run --format
/// csv` and of a case's η sweep (`millimpact sweep CASE`).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RunRecord {
    /// Case name.
    pub case: String,
    /// Method.
    pub method: &'static str,
    /// η.
    pub loss_coefficient: f64,
    /// The run's figures (`cor`, `peak_deformation`, …).
    #[serde(flatten)]
    pub figures: Exact,
    /// The closed forms of the checked quantities (`cor_exact`, …).
    #[serde(flatten, serialize_with = "suffix::exact")]
    pub exact: Checked,
    /// Relative errors of the checked quantities (`cor_error`, …).
    #[serde(flatten, serialize_with = "suffix::error")]
    pub error: Checked,
    /// Absorbed energy, J.
    pub absorbed_energy: f64,
    /// Absorbed energy as a fraction of the impact energy.
    pub absorbed_fraction: f64,
    /// Steps.
    pub steps: u64,
    /// RHS evaluations.
    pub rhs_evaluations: u64,
    /// Wall time, s.
    pub wall_time: f64,
}

/// One row of a trajectory file.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub(crate) struct TrajectoryRow {
    /// Time, s.
    pub t: f64,
    /// Approach, m.
    pub y: f64,
    /// Approach rate, m/s.
    #[serde(rename = "y_dot")]
    pub v: f64,
    /// Elastic force, N.
    pub elastic_force: f64,
    /// Dissipative force, N.
    pub dissipative_force: f64,
    /// Mechanical energy (kinetic plus elastic), J.
    pub energy: f64,
}

/// The trajectory as rows: time (s), approach (m), approach rate (m/s), elastic force (N),
/// dissipative force (N) and mechanical energy (J, kinetic plus elastic).
pub(crate) fn trajectory_rows(case: &Case, samples: &[Sample]) -> Vec<TrajectoryRow> {
    let law = case.law();
    let bilateral = case.contact == ContactKind::Bilateral;
    samples
        .iter()
        .map(|s| {
            let in_contact = s.y > 0.0 || (bilateral && s.y != 0.0);
            let elastic = if in_contact {
                law.stiffness * s.y.abs().powf(law.exponent) * s.y.signum()
            } else {
                0.0
            };
            let direction = (s.y * s.v).signum();
            // Out of contact there is no force at all (not a negative zero).
            let dissipative = if elastic == 0.0 {
                0.0
            } else {
                law.loss_coefficient * elastic * direction
            };
            let potential = if in_contact {
                law.stiffness * s.y.abs().powf(law.exponent + 1.0) / (law.exponent + 1.0)
            } else {
                0.0
            };
            TrajectoryRow {
                t: s.t,
                y: s.y,
                v: s.v,
                elastic_force: elastic,
                dissipative_force: dissipative,
                energy: 0.5 * law.mass * s.v * s.v + potential,
            }
        })
        .collect()
}

impl Summary for RunReport {
    type Record = RunRecord;

    fn records(&self) -> Vec<RunRecord> {
        vec![self.row()]
    }

    fn sections(&self) -> Vec<Section> {
        RunReport::sections(self)
    }
}

/// Fewest steps per undamped period a fixed-step method is run at: below it RK4 gives a COR
/// above 1 at η = 0 and the contact is one or two steps.
pub(crate) const MIN_STEPS_PER_PERIOD: u32 = 4;

/// Most steps per undamped period (about 5e7 steps in a contact, seconds of work).
pub(crate) const MAX_STEPS_PER_PERIOD: u32 = 100_000_000;

/// Smallest relative tolerance of the adaptive method: the spacing of doubles near 1 (below it a
/// step can never meet the tolerance and the step size underflows).
pub(crate) const MIN_RTOL: f64 = f64::EPSILON;

/// Most rows a trajectory may have (about 200 MB of CSV): checked before the run, from the
/// steps the method will take.
pub(crate) const MAX_TRAJECTORY_ROWS: f64 = 1e6;

/// Integration options as a user gives them: a method and at most the knob that method has.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct IntegrationOptions {
    /// The method.
    pub method: Method,
    /// Fixed-step methods: steps per undamped period (default 1000).
    pub steps_per_period: Option<u32>,
    /// Fixed-step methods: a step in seconds instead.
    pub timestep: Option<f64>,
    /// Adaptive methods: relative tolerance (default 1e-12).
    pub rtol: Option<f64>,
    /// Bilateral contact: undamped periods to follow.
    pub periods: f64,
}

impl Default for IntegrationOptions {
    fn default() -> Self {
        let settings = Settings::default();
        IntegrationOptions {
            method: settings.method,
            steps_per_period: None,
            timestep: None,
            rtol: None,
            periods: settings.periods,
        }
    }
}

impl IntegrationOptions {
    /// Validate the options for `case` and turn them into solver settings; a knob the method
    /// does not have is refused, not ignored.
    pub fn settings(&self, case: &Case, record: bool) -> Result<Settings, UserError> {
        let refuse = |option: &str, value: String, allowed: String| UserError::CaseArgument {
            case: case.path.display().to_string(),
            option: option.to_string(),
            value,
            allowed,
        };
        let defaults = Settings::default();
        let method = self.method;
        let knob = method.descriptor().knob;
        if let Some(n) = self.steps_per_period
            && knob != Knob::StepsPerPeriod
        {
            return Err(refuse(
                "--steps-per-period",
                n.to_string(),
                format!("{method} has no steps per period; it applies to the fixed-step methods"),
            ));
        }
        if let Some(rtol) = self.rtol {
            if knob != Knob::Rtol {
                return Err(refuse(
                    "--rtol",
                    rtol.to_string(),
                    format!("{method} has no tolerance; it applies to the adaptive methods"),
                ));
            }
            if !(MIN_RTOL..1.0).contains(&rtol) {
                return Err(refuse(
                    "--rtol",
                    rtol.to_string(),
                    format!("must be in [{MIN_RTOL:e}, 1) (the spacing of doubles near 1 and up)"),
                ));
            }
        }
        if let Some(dt) = self.timestep {
            if !(dt.is_finite() && dt > 0.0) {
                return Err(refuse(
                    "--timestep",
                    dt.to_string(),
                    "must be a finite number > 0 (seconds)".into(),
                ));
            }
            if !method.is_fixed_step() {
                return Err(refuse(
                    "--timestep",
                    dt.to_string(),
                    "applies to the fixed-step methods rk4, rk4-event and verlet only".into(),
                ));
            }
        }
        if !(self.periods.is_finite() && self.periods > 0.0) {
            return Err(refuse(
                "--periods",
                self.periods.to_string(),
                "must be a finite number > 0".into(),
            ));
        }
        if let Some(n) = self.steps_per_period
            && !(MIN_STEPS_PER_PERIOD..=MAX_STEPS_PER_PERIOD).contains(&n)
        {
            return Err(refuse(
                "--steps-per-period",
                n.to_string(),
                format!("must be in {MIN_STEPS_PER_PERIOD}..={MAX_STEPS_PER_PERIOD}"),
            ));
        }
        let steps_per_period = self.steps_per_period.unwrap_or(defaults.steps_per_period);
        if record && method.is_fixed_step() {
            let rows = self.trajectory_rows_bound(case, steps_per_period);
            if rows > MAX_TRAJECTORY_ROWS {
                let (option, value) = match self.timestep {
                    Some(dt) => ("--timestep", dt.to_string()),
                    None => ("--steps-per-period", steps_per_period.to_string()),
                };
                return Err(refuse(
                    option,
                    value,
                    format!(
                        "with --trajectory this run would write about {rows:.2e} rows, more than \
                         {MAX_TRAJECTORY_ROWS:e}; use a coarser step or no trajectory"
                    ),
                ));
            }
        }
        Ok(Settings {
            method,
            steps_per_period,
            timestep: self.timestep,
            rtol: self.rtol.unwrap_or(defaults.rtol),
            contact: case.contact,
            periods: self.periods,
            record,
        })
    }
}

impl IntegrationOptions {
    /// An upper estimate of the steps (trajectory rows) a fixed-step run takes: the loading
    /// quarter-period and the unloading one, which lasts `1/sqrt(1 − η)` times longer at the
    /// paper's unloading stiffness (RK4 with events steps it at its own period), or the
    /// periods followed in bilateral contact.
    fn trajectory_rows_bound(&self, case: &Case, steps_per_period: u32) -> f64 {
        let law = case.law();
        let period = 4.0 * exact::j_integral(law.exponent) * law.elastic_peak(case.impact_velocity)
            / case.impact_velocity;
        let per_period = match self.timestep {
            Some(dt) => period / dt,
            None => f64::from(steps_per_period),
        };
        let periods = match case.contact {
            ContactKind::Bilateral => self.periods,
            ContactKind::Unilateral if self.method == Method::Rk4Event => 1.0,
            ContactKind::Unilateral => 0.5 + 0.25 / (1.0 - law.loss_coefficient).sqrt(),
        };
        per_period * periods
    }
}

/// The arguments that repeat a run of `case` with `settings`.
pub(crate) fn reproduce_arguments(case: &Case, settings: &Settings) -> String {
    let method = settings.method;
    let mut text = format!("{} --method {method}", case.path.display());
    match (method.descriptor().knob, settings.timestep) {
        (_, Some(dt)) => text += &format!(" --timestep {dt:e}"),
        (Knob::Rtol, None) => text += &format!(" --rtol {:e}", settings.rtol),
        (Knob::StepsPerPeriod, None) => {
            text += &format!(" --steps-per-period {}", settings.steps_per_period)
        }
        (Knob::None, None) => {}
    }
    if case.contact == ContactKind::Bilateral {
        text += &format!(" --periods {}", settings.periods);
    }
    text
}

/// Why a case could not be integrated.
#[derive(Debug, Error)]
pub enum RunError {
    /// The step asked is beyond the method's stability limit: the user's (exit 2).
    #[error("{}: --timestep: {source}", case.display())]
    Unsolvable {
        /// The case file.
        case: PathBuf,
        /// The solver's refusal.
        source: SolveError,
    },
    /// A fixed step (from `--timestep` or `--steps-per-period`) beyond the method's stability
    /// limit on the tangential spring of an oblique case: the user's (exit 2).
    #[error("{}: the tangential spring: {source}", case.display())]
    TangentialUnstable {
        /// The case file.
        case: PathBuf,
        /// The solver's refusal.
        source: SolveError,
    },
    /// `--method exact` on an oblique case that no tangential closed form covers: the user's.
    #[error(
        "{}: --method exact: no tangential closed form holds for this oblique case (gross sliding needs |slip| >= 3.5 μ (1+e) v_n and a history spring that reaches the bound at once; the stick reversal a proportional spring of ratio 2/7, η = 0 and no damping); use an integrating method",
        case.display()
    )]
    NoClosedForm {
        /// The case file.
        case: PathBuf,
    },
    /// The integration failed for another reason.
    #[error("{}: integration failed", case.display())]
    Failed {
        /// The case file.
        case: PathBuf,
        /// Why.
        source: SolveError,
    },
}

impl Blame for RunError {
    fn is_user_error(&self) -> bool {
        matches!(
            self,
            RunError::Unsolvable { .. }
                | RunError::NoClosedForm { .. }
                | RunError::TangentialUnstable { .. }
        )
    }
}

/// Integrate `case` with `settings` and report against the closed forms.
pub fn run_case(case: &Case, settings: &Settings) -> Result<(RunReport, Outcome), RunError> {
    let outcome = paper::solve(&case.law(), case.impact_velocity, settings)
        .map_err(|e| solve_failure(&case.path, e))?;
    if case.oblique.is_none() {
        return Ok((RunReport::new(case, settings.method, &outcome), outcome));
    }
    let oblique = solve_oblique(case, settings)
        .map_err(|source| match source {
            SolveError::Unstable { .. } => RunError::TangentialUnstable {
                case: case.path.clone(),
                source,
            },
            source => solve_failure(&case.path, source),
        })?
        .ok_or_else(|| RunError::NoClosedForm {
            case: case.path.clone(),
        })?;
    Ok((
        RunReport::with_tangential(case, settings.method, &outcome, Some(&oblique)),
        outcome,
    ))
}

/// The error of a solve of the case read from `path` that failed: a step beyond the
/// stability limit is the user's (exit 2), any other failure the integration's.
pub(crate) fn solve_failure(path: &Path, source: SolveError) -> RunError {
    let case = path.to_path_buf();
    match source {
        SolveError::Unstable { .. } => RunError::Unsolvable { case, source },
        source => RunError::Failed { case, source },
    }
}
