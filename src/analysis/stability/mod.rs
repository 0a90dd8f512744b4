//! `millimpact stability`: a built-in grid of stiff and extreme cases by every integrating
//! method, and the stability limit of the fixed-step methods at a step given in seconds.
//!
//! The grid spans E from 1e5 to 1e15 Pa, R from 1e-6 to 1 m, v0 from 1e-8 to 1e3 m/s, η from 0
//! to 0.999999, ball–ball mass ratios down to 1e-6 and rod aspect ratios (length/diameter)
//! from 1 to 1000. Many of these are physically absurd (a 1 m ball of E = 1e5 Pa at 1 km/s
//! "deforms" by metres): the point is the arithmetic, which must not care, since every method
//! integrates the dimensionless form of physics.md §3.
//!
//! What passes:
//!
//! - rk4-event and dopri5 (`pass`): the run ends, every figure is finite, the COR is in
//!   [0, 1], and the relative errors of COR, peak deformation and contact time are all at most
//!   1e-9. Any failure here makes the command exit 1.
//! - rk4 (the paper's) and verlet (`pass`): the run ends within a work bound fixed in advance
//!   from the exact contact time, and every figure is finite. Their COR is *not* guaranteed to
//!   be in [0, 1] nor accurate: at η near 1 the sign(ẏ) switch is evaluated inside a step
//!   (verlet with the half-step velocity), so the tiny restitution force is applied with the
//!   wrong sign over part of a step and the COR error can exceed 100 % of a COR that is itself
//!   ~1e-3. Their accuracy is a separate flag, `accurate`, against the tolerance `verify`
//!   states for them (1e-3 on COR and peak, one step on the contact time).
//! - η → 1: every run, by every method, must end in bounded work with the COR near 0.

use std::time::Instant;

use rayon::prelude::*;

use serde::ser::SerializeMap;
use serde::{Serialize, Serializer};

use super::run::RunReport;
use super::tolerance::{Differences, Tolerance};
use crate::model::case::{Case, ContactKind};
use crate::model::count::ceil_count;
use crate::model::exact;
use crate::model::figures::{Checked, Figures, quantity, suffix};
use crate::model::scene::{Ball, Material, Plate, Rod, Scene, StiffnessConvention};
use crate::output::{Section, Summary};
use crate::solve::paper::{self, Settings};
use crate::solve::steppers::{State, rk4_step, verlet_step};
use crate::solve::{Method, SolveError};

#[cfg(test)]
mod tests;

/// The methods the grid runs, in report order.
pub(crate) const METHODS: [Method; 4] = [
    Method::Rk4,
    Method::Rk4Event,
    Method::Dopri5,
    Method::Verlet,
];

/// The error rk4-event and dopri5 must meet on every grid case.
pub(crate) const ACCURATE_TOLERANCE: f64 = 1e-9;

/// The largest loss coefficient of the grid.
pub(crate) const ETA_MAX: f64 = 0.999999;

/// One case of the grid, with the parameters it was built from.
#[derive(Clone, Debug)]
pub(crate) struct GridCase {
    /// Which part of the grid it belongs to.
    pub family: &'static str,
    /// The case.
    pub case: Case,
    /// Young's modulus of the (first) body, Pa.
    pub youngs_modulus: f64,
    /// Ball radius or rod diameter, m.
    pub size: f64,
    /// ball_ball: m2/m1.
    pub mass_ratio: Option<f64>,
    /// rod_end: length/diameter.
    pub aspect_ratio: Option<f64>,
}

fn material(e: f64) -> Material {
    Material {
        youngs_modulus: e,
        poisson_ratio: 0.3,
    }
}

fn ball(radius: f64, density: f64, e: f64) -> Ball {
    Ball {
        radius,
        density,
        material: material(e),
    }
}

fn make_case(name: String, scene: Scene, v0: f64, eta: f64) -> Case {
    Case {
        path: format!("(grid)/{name}").into(),
        name,
        scene,
        impact_velocity: v0,
        loss_coefficient: eta,
        stiffness: StiffnessConvention::Hertz,
        contact: ContactKind::Unilateral,
        oblique: None,
    }
}

/// The built-in grid.
pub(crate) fn grid() -> Vec<GridCase> {
    let mut out = Vec::new();
    const STEEL: f64 = 7800.0;
    // Dimensional extremes of a ball on a plate of its own material.
    for e in [1e5, 1e10, 1e15] {
        for r in [1e-6, 1e-3, 1.0] {
            for v0 in [1e-8, 1e-2, 1e3] {
                for eta in [0.0, 0.35, ETA_MAX] {
                    let b = ball(r, STEEL, e);
                    let scene = Scene::BallPlate {
                        ball: b,
                        plate: Plate::Elastic(material(e)),
                    };
                    out.push(GridCase {
                        family: "ball_plate extremes",
                        case: make_case(
                            format!("bp E{e:e} R{r:e} v{v0:e} eta{eta}"),
                            scene,
                            v0,
                            eta,
                        ),
                        youngs_modulus: e,
                        size: r,
                        mass_ratio: None,
                        aspect_ratio: None,
                    });
                }
            }
        }
    }
    // η from 0 to 1 on the three scenes at canonical sizes.
    let etas = [
        0.0, 1e-12, 1e-9, 1e-6, 1e-3, 0.1, 0.35, 0.5, 0.9, 0.99, 0.999, 0.99999, ETA_MAX,
    ];
    for eta in etas {
        let steel = ball(0.02, STEEL, 2e11);
        let rod = Rod {
            diameter: 0.03,
            length: 0.5,
            density: STEEL,
            youngs_modulus: 2e11,
        };
        let scenes = [
            (
                "rigid",
                Scene::BallPlate {
                    ball: steel,
                    plate: Plate::Rigid,
                },
            ),
            (
                "balls",
                Scene::BallBall {
                    ball: steel,
                    other: steel,
                },
            ),
            ("rod", Scene::RodEnd { rod }),
        ];
        for (label, scene) in scenes {
            let (mass_ratio, aspect_ratio) = match label {
                "balls" => (Some(1.0), None),
                "rod" => (None, Some(rod.length / rod.diameter)),
                _ => (None, None),
            };
            out.push(GridCase {
                family: "loss coefficient",
                case: make_case(format!("{label} eta{eta}"), scene, 2.0, eta),
                youngs_modulus: 2e11,
                size: if label == "rod" { 0.03 } else { 0.02 },
                mass_ratio,
                aspect_ratio,
            });
        }
    }
    // Ball on ball, the second ever lighter: by density, and by radius (m ∝ R³).
    let ratios: [(&str, f64); 6] = [
        ("density", 1.0),
        ("density", 1e-2),
        ("density", 1e-4),
        ("density", 1e-6),
        ("radius", 1e-3),
        ("radius", 1e-6),
    ];
    for (how, ratio) in ratios {
        for v0 in [1e-8, 1.0, 1e3] {
            for eta in [0.0, 0.35, ETA_MAX] {
                let first = ball(0.02, STEEL, 2e11);
                let other = if how == "density" {
                    ball(0.02, STEEL * ratio, 2e11)
                } else {
                    ball(0.02 * ratio.cbrt(), STEEL, 2e11)
                };
                let scene = Scene::BallBall { ball: first, other };
                out.push(GridCase {
                    family: "ball_ball mass ratio",
                    case: make_case(
                        format!("bb {how} m2/m1 {ratio:e} v{v0:e} eta{eta}"),
                        scene,
                        v0,
                        eta,
                    ),
                    youngs_modulus: 2e11,
                    size: 0.02,
                    mass_ratio: Some(other.mass() / first.mass()),
                    aspect_ratio: None,
                });
            }
        }
    }
    // Rods from squat to slender, soft to stiff.
    for aspect in [1.0, 10.0, 100.0, 1000.0] {
        for e in [1e5, 1e10, 1e15] {
            for v0 in [1e-8, 1.0, 1e3] {
                for eta in [0.0, 0.35, ETA_MAX] {
                    let rod = Rod {
                        diameter: 0.03,
                        length: 0.03 * aspect,
                        density: STEEL,
                        youngs_modulus: e,
                    };
                    out.push(GridCase {
                        family: "rod aspect ratio",
                        case: make_case(
                            format!("rod L/D{aspect} E{e:e} v{v0:e} eta{eta}"),
                            Scene::RodEnd { rod },
                            v0,
                            eta,
                        ),
                        youngs_modulus: e,
                        size: 0.03,
                        mass_ratio: None,
                        aspect_ratio: Some(aspect),
                    });
                }
            }
        }
    }
    out
}

/// The figures a grid case writes beside its errors: the COR, which the pass criteria bound.
pub(crate) const WRITTEN: u8 = quantity::COR;

/// One grid case by one method.
#[derive(Clone, Debug, Serialize)]
pub(crate) struct CaseResult {
    /// Case label.
    pub case: String,
    /// Part of the grid.
    pub family: &'static str,
    /// Scene.
    pub scene: &'static str,
    /// Method.
    pub method: Method,
    /// Young's modulus, Pa.
    pub youngs_modulus: f64,
    /// Ball radius or rod diameter, m.
    pub size: f64,
    /// Impact speed, m/s.
    pub impact_velocity: f64,
    /// Loss coefficient.
    pub loss_coefficient: f64,
    /// ball_ball: m2/m1.
    pub mass_ratio: Option<f64>,
    /// rod_end: length/diameter.
    pub aspect_ratio: Option<f64>,
    /// The run's figures that are written (`cor`; NaN if the run failed).
    #[serde(flatten)]
    pub figures: Figures<f64, WRITTEN>,
    /// The closed forms of the same figures (`cor_exact`).
    #[serde(flatten, serialize_with = "suffix::exact")]
    pub exact: Figures<f64, WRITTEN>,
    /// |relative error| of the checked quantities (`cor_error`, …; NaN if the run failed).
    #[serde(flatten, serialize_with = "suffix::error")]
    pub errors: Checked,
    /// Accepted steps.
    pub steps: u64,
    /// Right-hand-side evaluations.
    pub rhs_evaluations: u64,
    /// Every figure is finite.
    pub finite: bool,
    /// The COR is in [0, 1].
    pub cor_in_range: bool,
    /// The run ended within the work bound (see [`work_bound`]).
    pub bounded_work: bool,
    /// Within the method's stated tolerance (1e-9 for rk4-event and dopri5; `verify`'s 1e-3
    /// and one step for rk4 and verlet).
    pub accurate: bool,
    /// The method's pass criterion (see the module documentation).
    pub pass: bool,
    /// Why the run failed, if it did.
    pub error: Option<String>,
}

/// The most steps a run of `method` may take on a contact of exact duration `contact_time`
/// (s) at fixed step `timestep` (s): twice the steps the exact contact needs, plus the event
/// and series steps; for dopri5, a fixed 10⁵ (it takes ~10³ at rtol 1e-12 on any case).
pub(crate) fn work_bound(method: Method, contact_time: f64, timestep: Option<f64>) -> u64 {
    match (method, timestep) {
        (Method::Dopri5, _) | (_, None) => 100_000,
        // A step so small that the bound passes u64 is no bound at all.
        (_, Some(h)) => {
            ceil_count(2.0 * contact_time / h).map_or(u64::MAX, |n| n.saturating_add(100))
        }
    }
}

/// Run one grid case by one method at the solver's defaults (1000 steps per period, rtol
/// 1e-12).
pub(crate) fn run_one(grid_case: &GridCase, method: Method) -> CaseResult {
    let case = &grid_case.case;
    let law = case.law();
    let v0 = case.impact_velocity;
    let exact_figures = exact::paper_impact(&law, v0);
    let settings = Settings {
        method,
        contact: case.contact,
        ..Settings::default()
    };
    let mut result = CaseResult {
        case: case.name.clone(),
        family: grid_case.family,
        scene: case.scene.kind().name(),
        method,
        youngs_modulus: grid_case.youngs_modulus,
        size: grid_case.size,
        impact_velocity: v0,
        loss_coefficient: case.loss_coefficient,
        mass_ratio: grid_case.mass_ratio,
        aspect_ratio: grid_case.aspect_ratio,
        figures: Figures::splat(f64::NAN),
        exact: exact_figures.select(),
        errors: Checked::splat(f64::NAN),
        steps: 0,
        rhs_evaluations: 0,
        finite: false,
        cor_in_range: false,
        bounded_work: false,
        accurate: false,
        pass: false,
        error: None,
    };
    let outcome = match paper::solve(&law, v0, &settings) {
        Ok(outcome) => outcome,
        Err(e) => {
            result.error = Some(e.to_string());
            return result;
        }
    };
    let f = &outcome.figures;
    let run_report = RunReport::new(case, method, &outcome);
    result.figures = run_report.figures.select();
    result.errors = run_report.error.map(|_, e| e.abs());
    result.steps = outcome.stats.steps;
    result.rhs_evaluations = outcome.stats.rhs_evaluations;
    result.finite = (run_report.figures.iter())
        .chain(result.errors.iter())
        .map(|(_, x)| *x)
        .chain([f.absorbed_energy])
        .all(f64::is_finite);
    result.cor_in_range = (0.0..=1.0).contains(&f.cor);
    result.bounded_work =
        outcome.stats.steps <= work_bound(method, exact_figures.contact_time, outcome.timestep);
    let differences: Differences = result.errors;
    let tolerance = Tolerance::for_method(
        method,
        run_report.timestep,
        run_report.exact.figures.contact_time,
    );
    result.accurate = result.finite && tolerance.admits(&differences);
    let accurate_everywhere = Tolerance::splat(ACCURATE_TOLERANCE);
    result.pass = if method.held_accurate() {
        result.finite
            && result.cor_in_range
            && result.bounded_work
            && accurate_everywhere.admits(&differences)
    } else {
        result.finite && result.bounded_work
    };
    result
}

/// Every grid case by every method in [`METHODS`], on two threads (the machine is shared).
pub(crate) fn run_grid() -> Vec<CaseResult> {
    let jobs: Vec<(GridCase, Method)> = grid()
        .into_iter()
        .flat_map(|g| METHODS.map(|m| (g.clone(), m)))
        .collect();
    let run = |job: &(GridCase, Method)| run_one(&job.0, job.1);
    match rayon::ThreadPoolBuilder::new().num_threads(2).build() {
        Ok(pool) => pool.install(|| jobs.par_iter().map(run).collect()),
        Err(_) => jobs.iter().map(run).collect(),
    }
}

/// What the solver did with a step in seconds.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(tag = "verdict", content = "reason", rename_all = "snake_case")]
pub(crate) enum SolverVerdict {
    /// It integrated.
    Ran,
    /// It refused the step as beyond the stability limit.
    Refused(String),
    /// It failed otherwise.
    Failed(String),
}

impl std::fmt::Display for SolverVerdict {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            SolverVerdict::Ran => f.write_str("ran"),
            SolverVerdict::Refused(_) => f.write_str("refused (Unstable)"),
            SolverVerdict::Failed(reason) => write!(f, "failed: {reason}"),
        }
    }
}

/// The stability check of a fixed-step method at a step in seconds, just below or just above
/// its limit.
#[derive(Clone, Debug, Serialize)]
pub(crate) struct LimitCheck {
    /// Method.
    pub method: Method,
    /// The method's limit on `ω Δt`.
    pub limit: f64,
    /// The `ω Δt` tried.
    pub omega_dt: f64,
    /// What `paper::solve` did with that step on the bilateral, undamped rod (n = 1).
    pub solver: SolverVerdict,
    /// `paper::solve` ran: the largest speed at a zero crossing over the run, over `v0`.
    pub solver_max_crossing_speed: Option<f64>,
    /// The method's own step map on `y'' = -ω² y`: the largest `|(ωy, v)|` over the last tenth
    /// of `LIMIT_STEPS` steps over that over the first tenth.
    pub growth: f64,
    /// Whether the growth is bounded (at most 1.5).
    pub bounded: bool,
}

/// Steps of the direct check of the step map (about 400 periods at `ω Δt` near the limit).
pub(crate) const LIMIT_STEPS: usize = 1000;

/// How far below and above the limit the checks step, relative.
pub(crate) const LIMIT_MARGIN: f64 = 0.01;

/// Growth of the largest `|(y, v)|` of `method`'s fixed-step map on `y'' = -y` at step `z`
/// (so `ω Δt = z`), the last tenth of `LIMIT_STEPS` over the first tenth. RK4 is the
/// crate's own step; Verlet is the solver's kick–drift–kick.
pub(crate) fn step_map_growth(method: Method, z: f64) -> f64 {
    let rhs = |s: &State| State::new(s[1], -s[0]);
    let mut s = State::new(0.0, 1.0);
    let tenth = LIMIT_STEPS / 10;
    let (mut first, mut last) = (0.0f64, 0.0f64);
    for k in 0..LIMIT_STEPS {
        s = match method {
            Method::Verlet => verlet_step(&|y| -y, &s, z),
            _ => rk4_step(&rhs, &s, &rhs(&s), z),
        };
        let size = s.norm();
        if k < tenth {
            first = first.max(size);
        }
        if k >= LIMIT_STEPS - tenth {
            last = last.max(size);
        }
    }
    last / first
}

/// The stability-limit checks: rk4 and verlet, just below and just above their limits, on the
/// bilateral undamped linear contact (whose eigenvalues `±iω` lie on the imaginary axis, so the
/// limit is where each method's stability region meets that axis: `2√2` for RK4, 2 for
/// Verlet).
pub(crate) fn limit_checks() -> Vec<LimitCheck> {
    let rod = Rod {
        diameter: 0.03,
        length: 0.5,
        density: 7800.0,
        youngs_modulus: 2e11,
    };
    let mut case = make_case("rod bilateral".to_string(), Scene::RodEnd { rod }, 2.0, 0.0);
    case.contact = ContactKind::Bilateral;
    let law = case.law();
    let omega = paper::angular_frequency(&law, case.impact_velocity);
    let mut out = Vec::new();
    for method in [Method::Rk4, Method::Verlet] {
        let limit = paper::stability_limit(method).expect("a fixed-step method");
        for factor in [1.0 - LIMIT_MARGIN, 1.0 + LIMIT_MARGIN] {
            let z = factor * limit;
            let settings = Settings {
                method,
                timestep: Some(z / omega),
                contact: ContactKind::Bilateral,
                periods: 100.0,
                ..Settings::default()
            };
            let (solver, solver_max_crossing_speed) =
                match paper::solve(&law, case.impact_velocity, &settings) {
                    Ok(outcome) => (
                        SolverVerdict::Ran,
                        Some(
                            outcome.crossing_speeds.iter().cloned().fold(0.0, f64::max)
                                / case.impact_velocity,
                        ),
                    ),
                    Err(e @ SolveError::Unstable { .. }) => {
                        (SolverVerdict::Refused(e.to_string()), None)
                    }
                    Err(e) => (SolverVerdict::Failed(e.to_string()), None),
                };
            let growth = step_map_growth(method, z);
            out.push(LimitCheck {
                method,
                limit,
                omega_dt: z,
                solver,
                solver_max_crossing_speed,
                growth,
                bounded: growth.is_finite() && growth <= 1.5,
            });
        }
    }
    out
}

/// Per-method totals of the grid.
#[derive(Clone, Debug, Serialize)]
pub(crate) struct MethodSummary {
    /// Method.
    pub method: Method,
    /// Cases run.
    pub cases: usize,
    /// Cases that pass.
    pub passed: usize,
    /// Cases within the method's stated tolerance.
    pub accurate: usize,
    /// Cases with the COR in [0, 1].
    pub cor_in_range: usize,
    /// Largest relative error of each checked quantity over the grid (`max_cor_error`, …).
    #[serde(flatten, serialize_with = "max_error_names")]
    pub max_error: Checked,
    /// Most steps in one case.
    pub max_steps: u64,
    /// At η = [`ETA_MAX`]: the largest COR (the exact one is 7.07e-4).
    pub max_cor_at_eta_max: f64,
}

/// Writes [`MethodSummary::max_error`] flattened, each quantity as `max_{quantity}_error`.
fn max_error_names<S: Serializer>(max_error: &Checked, serializer: S) -> Result<S::Ok, S::Error> {
    let mut map = serializer.serialize_map(Some(Checked::<f64>::quantities().count()))?;
    for (q, value) in max_error.iter() {
        map.serialize_entry(&format!("max_{q}_error"), value)?;
    }
    map.end()
}

/// Everything `millimpact stability` reports.
#[derive(Clone, Debug, Serialize)]
pub(crate) struct StabilityReport {
    /// Every case by every method.
    pub cases: Vec<CaseResult>,
    /// Totals per method.
    pub summary: Vec<MethodSummary>,
    /// The fixed-step stability limits, just below and just above.
    pub stability_limits: Vec<LimitCheck>,
    /// Wall time of the whole grid, s.
    pub wall_time_s: f64,
}

/// Run the grid and the limit checks.
pub(crate) fn stability_report() -> StabilityReport {
    let started = Instant::now();
    let cases = run_grid();
    let summary = METHODS
        .iter()
        .map(|m| {
            let own: Vec<&CaseResult> = cases.iter().filter(|c| c.method == *m).collect();
            MethodSummary {
                method: *m,
                cases: own.len(),
                passed: own.iter().filter(|c| c.pass).count(),
                accurate: own.iter().filter(|c| c.accurate).count(),
                cor_in_range: own.iter().filter(|c| c.cor_in_range).count(),
                max_error: Checked::from_fn(|q| {
                    own.iter().map(|c| *c.errors.get(q)).fold(0.0, f64::max)
                }),
                max_steps: own.iter().map(|c| c.steps).max().unwrap_or(0),
                max_cor_at_eta_max: own
                    .iter()
                    .filter(|c| c.loss_coefficient == ETA_MAX)
                    .map(|c| c.figures.cor)
                    .fold(0.0, f64::max),
            }
        })
        .collect();
    StabilityReport {
        cases,
        summary,
        stability_limits: limit_checks(),
        wall_time_s: started.elapsed().as_secs_f64(),
    }
}

impl StabilityReport {
    /// The cases that fail of the methods held accurate everywhere (rk4-event, dopri5).
    pub(crate) fn accurate_method_failures(&self) -> Vec<&CaseResult> {
        self.cases
            .iter()
            .filter(|c| c.method.held_accurate() && !c.pass)
            .collect()
    }
}

impl Summary for StabilityReport {
    type Record = CaseResult;

    fn records(&self) -> Vec<CaseResult> {
        self.cases.clone()
    }

    fn sections(&self) -> Vec<Section> {
        let mut t = Section::new(
            Some(format!(
                "stability grid: {} cases × {} methods in {:.2} s",
                self.cases.len() / METHODS.len(),
                METHODS.len(),
                self.wall_time_s
            )),
            &[
                "method",
                "cases",
                "pass",
                "accurate",
                "COR in [0,1]",
                "max COR err",
                "max peak err",
                "max time err",
                "max steps",
                "max COR at η=0.999999",
            ],
        );
        for s in &self.summary {
            let mut row = vec![
                s.method.to_string(),
                s.cases.to_string(),
                s.passed.to_string(),
                s.accurate.to_string(),
                s.cor_in_range.to_string(),
            ];
            row.extend(s.max_error.iter().map(|(_, e)| format!("{e:.2e}")));
            row.extend([
                s.max_steps.to_string(),
                format!("{:.3e}", s.max_cor_at_eta_max),
            ]);
            t.rows.push(row);
        }
        t.notes.push(
            "pass: rk4-event and dopri5 — finite, COR in [0,1], every error ≤ 1e-9; rk4 and \
             verlet — finite figures in bounded work (their accuracy is `accurate`: 1e-3 on \
             COR and peak, one step on the contact time; near η = 1 their COR is not \
             guaranteed, since the sign(ẏ) switch falls inside a step)"
                .to_string(),
        );
        let mut l = Section::new(
            Some(
                "fixed step in seconds at the stability limit (bilateral undamped rod)".to_string(),
            ),
            &[
                "method",
                "limit ω·Δt",
                "ω·Δt tried",
                "paper::solve",
                "max crossing speed / v0",
                "step-map growth",
                "bounded",
            ],
        );
        for c in &self.stability_limits {
            l.rows.push(vec![
                c.method.to_string(),
                format!("{:.6}", c.limit),
                format!("{:.6}", c.omega_dt),
                c.solver.to_string(),
                c.solver_max_crossing_speed
                    .map_or_else(String::new, |s| format!("{s:.6}")),
                format!("{:.3e}", c.growth),
                c.bounded.to_string(),
            ]);
        }
        let failures = self.accurate_method_failures();
        let mut f = Section::new(
            Some(if failures.is_empty() {
                "every rk4-event and dopri5 case passes".to_string()
            } else {
                "FAILING rk4-event and dopri5 cases".to_string()
            }),
            &["case", "method", "COR err", "peak err", "time err", "error"],
        );
        for c in failures {
            let mut row = vec![c.case.clone(), c.method.to_string()];
            row.extend(c.errors.iter().map(|(_, e)| format!("{e:.2e}")));
            row.push(c.error.clone().unwrap_or_default());
            f.rows.push(row);
        }
        if f.rows.is_empty() {
            f.headers.clear();
        }
        vec![t, l, f]
    }

    fn footer(&self) -> Vec<String> {
        vec!["reproduce: millimpact stability".to_string()]
    }
}
