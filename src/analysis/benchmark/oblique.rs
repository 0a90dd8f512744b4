//! Chung & Ooi's oblique and spinning tests 4–8, run by the harness's own sources: the
//! tangential solver (`rk4-event` and `dopri5`) at every point of each test's sweep, held to
//! the closed form where one is exact (Coulomb sliding throughout, and test 7's contact that
//! never slips) and to each other everywhere.
//!
//! The set-ups are the published ones as the codes' own Chung & Ooi scripts give them (YADE's
//! 2023 scripts, Kratos' DEM benchmarks, PySPH's DEM examples); the book's benchmark page names
//! the source of every number and where they disagree. Each test sweeps the same grid the
//! Kratos benchmark does, at 10° steps: the incident angle θ from 5° to 85°, and in tests 5–8
//! the tangential speed or spin that gives the contact point the slip `v_n tan θ`.

use serde::Serialize;

use super::{BenchmarkError, BenchmarkRow, Plane, Quantity};
use crate::analysis::source::Source;
use crate::codes::CodeName;
use crate::model::case::{Case, CaseError};
use crate::model::exact;
use crate::model::tangential::{ClosedFormKind, TangentialBodies, normalised_angle};
use crate::solve::paper::Settings;
use crate::solve::tangential::{closed_form, solve_oblique};
use crate::solve::{Method, SolveError};

/// The largest difference, scaled by `max(|reference|, 1)`, between a solver's figure and the
/// closed form, or between the two solvers.
pub(crate) const OBLIQUE_TOLERANCE: f64 = 1e-6;

/// The incident angles of every sweep, degrees from the normal: 5° to 85° at 10° steps.
pub(crate) const INCIDENT_ANGLES: [f64; 9] = [5.0, 15.0, 25.0, 35.0, 45.0, 55.0, 65.0, 75.0, 85.0];

/// What a test sweeps.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub(crate) enum Swept {
    /// The incident angle of a constant resultant speed, degrees from the normal (test 4).
    IncidentAngle,
    /// The ball's tangential speed at a constant normal speed, m/s (test 5).
    TangentialVelocity,
    /// The ball's spin at a constant normal speed, rad/s (tests 6–8).
    AngularVelocity,
}

impl Swept {
    /// The column heading of the swept value.
    pub(crate) fn label(self) -> &'static str {
        match self {
            Swept::IncidentAngle => "incident angle (°)",
            Swept::TangentialVelocity => "tangential velocity (m/s)",
            Swept::AngularVelocity => "angular velocity (rad/s)",
        }
    }
}

/// One material of one oblique test.
#[derive(Clone, Copy, Debug)]
pub(crate) struct ObliqueImpact {
    /// The test's number (4 to 8).
    pub test: u8,
    /// The material, as the paper names it.
    pub material: &'static str,
    /// The shipped case (`cases/benchmarks/<name>.toml`), at one point of the sweep.
    pub case: &'static str,
    /// Its text, built in.
    text: &'static str,
    /// What the test sweeps.
    pub swept: Swept,
}

/// Tests 4–8, two materials each.
pub(crate) const OBLIQUE_TESTS: [ObliqueImpact; 10] = [
    ObliqueImpact {
        test: 4,
        material: "aluminium oxide",
        case: "chung_ooi_4_alumina",
        text: include_str!("../../../cases/benchmarks/chung_ooi_4_alumina.toml"),
        swept: Swept::IncidentAngle,
    },
    ObliqueImpact {
        test: 4,
        material: "aluminium alloy",
        case: "chung_ooi_4_aluminium",
        text: include_str!("../../../cases/benchmarks/chung_ooi_4_aluminium.toml"),
        swept: Swept::IncidentAngle,
    },
    ObliqueImpact {
        test: 5,
        material: "steel",
        case: "chung_ooi_5_steel",
        text: include_str!("../../../cases/benchmarks/chung_ooi_5_steel.toml"),
        swept: Swept::TangentialVelocity,
    },
    ObliqueImpact {
        test: 5,
        material: "polyethylene",
        case: "chung_ooi_5_polyethylene",
        text: include_str!("../../../cases/benchmarks/chung_ooi_5_polyethylene.toml"),
        swept: Swept::TangentialVelocity,
    },
    ObliqueImpact {
        test: 6,
        material: "aluminium alloy",
        case: "chung_ooi_6_aluminium",
        text: include_str!("../../../cases/benchmarks/chung_ooi_6_aluminium.toml"),
        swept: Swept::AngularVelocity,
    },
    ObliqueImpact {
        test: 6,
        material: "nylon",
        case: "chung_ooi_6_nylon",
        text: include_str!("../../../cases/benchmarks/chung_ooi_6_nylon.toml"),
        swept: Swept::AngularVelocity,
    },
    ObliqueImpact {
        test: 7,
        material: "aluminium alloy",
        case: "chung_ooi_7_aluminium",
        text: include_str!("../../../cases/benchmarks/chung_ooi_7_aluminium.toml"),
        swept: Swept::AngularVelocity,
    },
    ObliqueImpact {
        test: 7,
        material: "copper",
        case: "chung_ooi_7_copper",
        text: include_str!("../../../cases/benchmarks/chung_ooi_7_copper.toml"),
        swept: Swept::AngularVelocity,
    },
    ObliqueImpact {
        test: 8,
        material: "aluminium alloy",
        case: "chung_ooi_8_aluminium",
        text: include_str!("../../../cases/benchmarks/chung_ooi_8_aluminium.toml"),
        swept: Swept::AngularVelocity,
    },
    ObliqueImpact {
        test: 8,
        material: "nylon",
        case: "chung_ooi_8_nylon",
        text: include_str!("../../../cases/benchmarks/chung_ooi_8_nylon.toml"),
        swept: Swept::AngularVelocity,
    },
];

/// A test whose DEM code rows are absent, and why.
#[derive(Clone, Debug, Serialize)]
pub(crate) struct PendingCodes {
    /// The test.
    pub test: u8,
    /// The builds that are to run it.
    pub builds: Vec<CodeName>,
    /// Why their rows are absent.
    pub reason: &'static str,
}

impl PendingCodes {
    /// The one line of the report that says so.
    pub(crate) fn line(&self) -> String {
        let builds: Vec<&str> = self.builds.iter().map(|b| b.name()).collect();
        format!(
            "test {}: no DEM code rows yet; {} are to run it and do not yet ({})",
            self.test,
            builds.join(", "),
            self.reason
        )
    }
}

/// The pending line of every oblique test.
pub(crate) fn pending_codes() -> Vec<PendingCodes> {
    let mut tests: Vec<u8> = OBLIQUE_TESTS.iter().map(|t| t.test).collect();
    tests.dedup();
    tests
        .into_iter()
        .map(|test| PendingCodes {
            test,
            // The builds that run an oblique impact are to run tests 4–8.
            builds: CodeName::ALL
                .iter()
                .copied()
                .filter(|c| c.driver().runs_oblique())
                .collect(),
            reason: if test >= 7 {
                "two balls: the drivers refuse an oblique pair, whose contact normal turns"
            } else {
                "each runs a point of it by `millimpact reference --code CODE`, against Coulomb's \
                 closed form at the run's COR; the sweep's rows need each code's own tangential \
                 law stepped, since a damped code's bound jumps at first touch and its spring \
                 starts inside it, which the closed form of the paper's law does not have"
            },
        })
        .collect()
}

impl ObliqueImpact {
    /// The case, read from this build.
    pub fn case(&self) -> Result<Case, CaseError> {
        Case::parse(
            self.text,
            &std::path::Path::new("cases/benchmarks").join(format!("{}.toml", self.case)),
        )
    }

    /// The plane struck (tests 4–6), `None` for two spheres (tests 7 and 8).
    pub(crate) fn plane(&self) -> Option<Plane> {
        (self.test <= 6).then_some(Plane::Rigid)
    }

    /// The figures the paper plots for this test, in the order of their rows.
    pub(crate) fn quantities(&self) -> &'static [Quantity] {
        match self.test {
            4 | 5 => &[
                Quantity::NormalisedReboundAngle,
                Quantity::TangentialCor,
                Quantity::ReboundSpin,
            ],
            7 => &[
                Quantity::ReboundTangentialVelocity,
                Quantity::ReboundSpin,
                Quantity::OtherReboundTangentialVelocity,
                Quantity::OtherReboundSpin,
            ],
            6 => &[
                Quantity::NormalisedReboundAngle,
                Quantity::ContactTangentialCor,
                Quantity::ReboundSpin,
            ],
            _ => &[
                Quantity::NormalisedReboundAngle,
                Quantity::ContactTangentialCor,
                Quantity::ReboundSpin,
                Quantity::OtherReboundSpin,
            ],
        }
    }

    /// The case at incident angle `angle` (degrees) and the swept value there: test 4 splits
    /// the case's resultant speed at the angle; tests 5–8 keep the normal speed and give the
    /// contact point the slip `v_n tan θ`, by the tangential speed (5) or the spin (6–8, with
    /// the shipped spin's sign).
    pub(crate) fn at(&self, base: &Case, angle: f64) -> (Case, f64) {
        let mut case = base.clone();
        let theta = angle.to_radians();
        let Some(oblique) = case.oblique.as_mut() else {
            return (case, angle);
        };
        let value = match self.swept {
            Swept::IncidentAngle => {
                let speed = base.impact_velocity.hypot(oblique.tangential_velocity);
                case.impact_velocity = speed * theta.cos();
                oblique.tangential_velocity = speed * theta.sin();
                angle
            }
            Swept::TangentialVelocity => {
                oblique.tangential_velocity = base.impact_velocity * theta.tan();
                oblique.tangential_velocity
            }
            Swept::AngularVelocity => {
                let radius = match &base.scene {
                    crate::model::scene::Scene::BallPlate { ball, .. }
                    | crate::model::scene::Scene::BallBall { ball, .. } => ball.radius,
                    crate::model::scene::Scene::RodEnd { .. } => 1.0,
                };
                // Test 7's balls meet at ±v_n/2 each: the spin gives each surface v_n/2 tan θ.
                let normal = if self.test == 7 {
                    base.impact_velocity / 2.0
                } else {
                    base.impact_velocity
                };
                let sign = if oblique.angular_velocity < 0.0 {
                    -1.0
                } else {
                    1.0
                };
                oblique.angular_velocity = sign * normal * theta.tan() / radius;
                oblique.angular_velocity
            }
        };
        (case, value)
    }
}

/// The figures of one impact, from the tangential impulse on the ball.
struct Rebound {
    values: Vec<f64>,
}

/// The values of `quantities` for `case` after the tangential impulse `impulse` (N·s on the
/// ball), its normal COR taken as the case's (the normalisation's convention).
fn rebound(case: &Case, impulse: f64, quantities: &[Quantity]) -> Option<Rebound> {
    let oblique = case.oblique.as_ref()?;
    let bodies = TangentialBodies::of(&case.scene, oblique)?;
    let (ball, other) = bodies.after(impulse);
    let after = TangentialBodies {
        ball: (bodies.ball.0, bodies.ball.1, ball),
        other: bodies.other.zip(other).map(|((m, r, _), o)| (m, r, o)),
    };
    let e = exact::restitution(case.loss_coefficient);
    let v_n = case.impact_velocity;
    let mu = oblique.friction_coefficient;
    let values = quantities
        .iter()
        .map(|q| match q {
            Quantity::NormalisedReboundAngle => {
                normalised_angle(after.slip(), v_n, mu, e).unwrap_or(f64::NAN)
            }
            Quantity::TangentialCor => ball.tangential_velocity / oblique.tangential_velocity,
            Quantity::ContactTangentialCor => -after.slip() / bodies.slip(),
            Quantity::ReboundSpin => ball.angular_velocity,
            Quantity::ReboundTangentialVelocity => ball.tangential_velocity,
            Quantity::OtherReboundSpin => other.map_or(f64::NAN, |o| o.angular_velocity),
            Quantity::OtherReboundTangentialVelocity => {
                other.map_or(f64::NAN, |o| o.tangential_velocity)
            }
            _ => f64::NAN,
        })
        .collect();
    Some(Rebound { values })
}

/// The closed form's tangential impulse for `case`, where one is exact: Coulomb sliding
/// throughout (the condition of [`crate::model::tangential::gross_sliding_holds`]), or a
/// contact that does not slip at first touch (test 7's mirrored spins), whose history spring
/// never stretches: no impulse.
pub(crate) fn closed_form_impulse(case: &Case) -> Option<f64> {
    let oblique = case.oblique.as_ref()?;
    let bodies = TangentialBodies::of(&case.scene, oblique)?;
    if bodies.slip() == 0.0 {
        return Some(0.0);
    }
    closed_form(case)
        .filter(|f| f.kind == ClosedFormKind::GrossSliding)
        .map(|f| f.impulse)
}

/// The tangential impulse `method` gives for `case`.
fn solved_impulse(case: &Case, method: Method) -> Result<f64, BenchmarkError> {
    let settings = Settings {
        method,
        ..Settings::default()
    };
    let solve_error = |source: SolveError| BenchmarkError::Solve {
        case: case.name.clone(),
        source,
    };
    let outcome = solve_oblique(case, &settings).map_err(solve_error)?;
    outcome
        .map(|o| o.impulse)
        .ok_or_else(|| BenchmarkError::NotOblique {
            case: case.name.clone(),
        })
}

/// `(value − reference) / max(|reference|, 1)`.
pub(crate) fn scaled_difference(value: f64, reference: f64) -> f64 {
    (value - reference) / reference.abs().max(1.0)
}

/// The solvers that run tests 4–8.
pub(crate) const OBLIQUE_METHODS: [Method; 2] = [Method::Rk4Event, Method::Dopri5];

/// Every row of tests 4–8: per material, per point of its sweep, per figure, one row for each
/// solver.
pub(crate) fn oblique_rows() -> Result<Vec<BenchmarkRow>, BenchmarkError> {
    let mut rows = Vec::new();
    for impact in &OBLIQUE_TESTS {
        let base = impact.case()?;
        let quantities = impact.quantities();
        for angle in INCIDENT_ANGLES {
            let (case, swept_value) = impact.at(&base, angle);
            let closed = closed_form_impulse(&case).and_then(|j| rebound(&case, j, quantities));
            let mut solved = Vec::new();
            for method in OBLIQUE_METHODS {
                let impulse = solved_impulse(&case, method)?;
                if let Some(r) = rebound(&case, impulse, quantities) {
                    solved.push((method, r));
                }
            }
            let cor_set = exact::restitution(case.loss_coefficient);
            for (i, (method, figures)) in solved.iter().enumerate() {
                let other = &solved[(i + 1) % solved.len()].1;
                for (k, &quantity) in quantities.iter().enumerate() {
                    let value = figures.values[k];
                    let closed_form = closed.as_ref().map(|c| c.values[k]);
                    let closed_form_difference = closed_form.map(|c| scaled_difference(value, c));
                    let method_difference = scaled_difference(value, other.values[k]);
                    let pass = value.is_finite()
                        && method_difference.abs() <= OBLIQUE_TOLERANCE
                        && closed_form_difference.is_none_or(|d| d.abs() <= OBLIQUE_TOLERANCE);
                    rows.push(BenchmarkRow {
                        test: impact.test,
                        material: impact.material,
                        source: Source::Method(*method),
                        quantity,
                        cor_set,
                        published: None,
                        value,
                        relative_difference: None,
                        tolerance: OBLIQUE_TOLERANCE,
                        pass,
                        expected_pass: true,
                        plane: impact.plane(),
                        case: impact.case,
                        closed_form,
                        closed_form_difference,
                        swept: Some(impact.swept),
                        swept_value: Some(swept_value),
                        method_difference: Some(method_difference),
                    });
                }
            }
        }
    }
    Ok(rows)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::scene::{Plate, Scene};
    use crate::model::tangential::OtherBallMotion;

    /// Every shipped set-up reads as published. The numbers and their sources (the book's
    /// benchmark page gives the same list):
    /// - test 4: R 2.5 mm, 3.9 m/s, μ 0.092, e 0.98, rigid plane; aluminium oxide E 380 GPa,
    ///   ν 0.23, ρ 4000 (YADE 2023 `Test4.py`, Kratos `test4_data/Materials4.json`); aluminium
    ///   alloy E 70 GPa, ν 0.33, ρ 2700 (YADE `Test4.py`; Kratos' test 6–8 meshes).
    /// - test 5: R 10 µm, v_n 5 m/s, μ 0.3, e 1, rigid plane; steel E 208 GPa, ν 0.30,
    ///   ρ 7850 (Kratos `benchmark5DEM.mdpa`, PySPH test 5); polyethylene E 1 GPa, ν 0.40,
    ///   ρ 1400 (PySPH test 5).
    /// - test 6: R 0.1 m, v_n 0.2 m/s, μ 0.4, e 0.5, rigid plane; aluminium alloy as above
    ///   (Kratos `benchmark6DEM.mdpa`); nylon E 2.5 GPa, ν 0.40, ρ 1000 (PySPH test 8).
    /// - test 7: R 0.1 m each, ±0.2 m/s, opposite spins, μ 0.4, e 0.5; aluminium alloy
    ///   (Kratos `benchmark7DEM.mdpa`; PySPH test 7 has E 700 GPa, a tenfold slip against its
    ///   own test 8 and Kratos); copper E 120 GPa, ν 0.35, ρ 8900 (PySPH test 7).
    /// - test 8: R 0.1 m at 0.2 m/s with spin against R 0.5 m at rest, density and E 1000
    ///   times the ball's (Kratos `benchmark8DEM.mdpa`; PySPH test 8 scales the density and,
    ///   in its case A, the shear modulus), μ 0.4, e 0.5.
    #[test]
    fn the_set_ups_read_as_published() {
        // (case, radius, density, E, ν, μ, e, normal speed).
        let expected = [
            (
                "chung_ooi_4_alumina",
                0.0025,
                4000.0,
                3.8e11,
                0.23,
                0.092,
                0.98,
                None,
            ),
            (
                "chung_ooi_4_aluminium",
                0.0025,
                2700.0,
                7.0e10,
                0.33,
                0.092,
                0.98,
                None,
            ),
            (
                "chung_ooi_5_steel",
                1e-5,
                7850.0,
                2.08e11,
                0.30,
                0.3,
                1.0,
                Some(5.0),
            ),
            (
                "chung_ooi_5_polyethylene",
                1e-5,
                1400.0,
                1e9,
                0.40,
                0.3,
                1.0,
                Some(5.0),
            ),
            (
                "chung_ooi_6_aluminium",
                0.1,
                2700.0,
                7.0e10,
                0.33,
                0.4,
                0.5,
                Some(0.2),
            ),
            (
                "chung_ooi_6_nylon",
                0.1,
                1000.0,
                2.5e9,
                0.40,
                0.4,
                0.5,
                Some(0.2),
            ),
            (
                "chung_ooi_7_aluminium",
                0.1,
                2700.0,
                7.0e10,
                0.33,
                0.4,
                0.5,
                Some(0.4),
            ),
            (
                "chung_ooi_7_copper",
                0.1,
                8900.0,
                1.2e11,
                0.35,
                0.4,
                0.5,
                Some(0.4),
            ),
            (
                "chung_ooi_8_aluminium",
                0.1,
                2700.0,
                7.0e10,
                0.33,
                0.4,
                0.5,
                Some(0.2),
            ),
            (
                "chung_ooi_8_nylon",
                0.1,
                1000.0,
                2.5e9,
                0.40,
                0.4,
                0.5,
                Some(0.2),
            ),
        ];
        assert_eq!(expected.len(), OBLIQUE_TESTS.len());
        for (impact, (name, radius, density, modulus, nu, mu, e, v_n)) in
            OBLIQUE_TESTS.iter().zip(expected)
        {
            assert_eq!(impact.case, name);
            let case = impact.case().unwrap();
            let (ball, other) = match &case.scene {
                Scene::BallPlate { ball, plate } => {
                    assert_eq!(*plate, Plate::Rigid, "{name}");
                    (ball, None)
                }
                Scene::BallBall { ball, other } => (ball, Some(other)),
                Scene::RodEnd { .. } => panic!("{name} is a ball scene"),
            };
            let close = |a: f64, b: f64| (a / b - 1.0).abs() < 1e-12;
            assert!(close(ball.radius, radius), "{name} radius");
            assert!(close(ball.density, density), "{name} density");
            assert!(close(ball.material.youngs_modulus, modulus), "{name} E");
            assert!(close(ball.material.poisson_ratio, nu), "{name} ν");
            let oblique = case.oblique.unwrap();
            assert!(close(oblique.friction_coefficient, mu), "{name} μ");
            assert!(
                (exact::restitution(case.loss_coefficient) - e).abs() < 1e-9,
                "{name} e"
            );
            match v_n {
                // Test 4: 3.9 m/s at 45°.
                None => {
                    assert!(close(
                        case.impact_velocity.hypot(oblique.tangential_velocity),
                        3.9
                    ));
                    assert!(close(case.impact_velocity, oblique.tangential_velocity));
                }
                Some(v) => assert!(close(case.impact_velocity, v), "{name} v_n"),
            }
            match impact.test {
                7 => {
                    assert_eq!(oblique.other_ball, OtherBallMotion::Mirrored);
                    assert_eq!(other.unwrap(), ball, "{name}: identical spheres");
                }
                8 => {
                    let other = other.unwrap();
                    assert_eq!(oblique.other_ball, OtherBallMotion::AtRest);
                    assert!(close(other.radius, 5.0 * radius), "{name} R2");
                    assert!(close(other.density, 1000.0 * density), "{name} ρ2");
                    assert!(close(other.material.youngs_modulus, 1000.0 * modulus));
                    assert!(close(other.material.poisson_ratio, nu));
                }
                _ => assert!(other.is_none()),
            }
        }
    }

    /// Test 4's sweep keeps the resultant 3.9 m/s; the others keep the normal speed and give
    /// the contact point the slip v_n tan θ (test 7's each ball half the relative speed).
    #[test]
    fn the_sweeps_give_the_published_slips() {
        for impact in &OBLIQUE_TESTS {
            let base = impact.case().unwrap();
            for angle in INCIDENT_ANGLES {
                let (case, _) = impact.at(&base, angle);
                let oblique = case.oblique.unwrap();
                let bodies = TangentialBodies::of(&case.scene, &oblique).unwrap();
                let tan = angle.to_radians().tan();
                match impact.test {
                    4 => {
                        let speed = case.impact_velocity.hypot(oblique.tangential_velocity);
                        assert!((speed - 3.9).abs() < 1e-12);
                        assert!((bodies.slip() / case.impact_velocity - tan).abs() < 1e-12);
                    }
                    7 => {
                        assert!(bodies.slip().abs() < 1e-15, "{}", impact.case);
                        let (_, r, m) = bodies.ball;
                        let surface = r * m.angular_velocity;
                        assert!((surface / (case.impact_velocity / 2.0) - tan).abs() < 1e-12);
                    }
                    _ => {
                        assert!(
                            (bodies.slip() / case.impact_velocity - tan).abs() < 1e-12,
                            "{} {angle}",
                            impact.case
                        );
                    }
                }
            }
        }
    }

    /// Where Coulomb sliding holds throughout, both solvers meet the closed form to 1e-6:
    /// |Δv_t| = μ(1+e)v_n and |Δω| = 5μ(1+e)v_n/(2R) on the plane; and every test has points in
    /// gross sliding (test 7 none slips: its closed form is no impulse at every point).
    #[test]
    fn the_solvers_meet_the_closed_form_where_gross_sliding_holds() {
        let rows = oblique_rows().unwrap();
        for test in 4..=8u8 {
            let with_closed: Vec<&BenchmarkRow> = rows
                .iter()
                .filter(|r| r.test == test && r.closed_form.is_some())
                .collect();
            assert!(!with_closed.is_empty(), "test {test}");
            for r in with_closed {
                assert!(
                    r.closed_form_difference.unwrap().abs() <= 1e-6,
                    "{} {:?} {:?} {}: {} against {:?}",
                    r.case,
                    r.source,
                    r.quantity,
                    r.swept_value.unwrap(),
                    r.value,
                    r.closed_form
                );
            }
        }
        // The sliding formulas themselves, on test 4's alumina at 85°.
        let impact = &OBLIQUE_TESTS[0];
        let (case, _) = impact.at(&impact.case().unwrap(), 85.0);
        let oblique = case.oblique.unwrap();
        let j = closed_form_impulse(&case).expect("85° slides throughout");
        let Scene::BallPlate { ball, .. } = &case.scene else {
            panic!()
        };
        let e = exact::restitution(case.loss_coefficient);
        let scale = oblique.friction_coefficient * (1.0 + e) * case.impact_velocity;
        let dv = j / ball.mass();
        assert!((dv.abs() / scale - 1.0).abs() < 1e-12);
        let (after, _) = TangentialBodies::of(&case.scene, &oblique)
            .unwrap()
            .after(j);
        let dw = after.angular_velocity - oblique.angular_velocity;
        assert!((dw.abs() / (5.0 * scale / (2.0 * ball.radius)) - 1.0).abs() < 1e-12);
    }

    #[test]
    fn every_oblique_row_passes_and_every_test_has_rows() {
        let rows = oblique_rows().unwrap();
        let failed: Vec<&BenchmarkRow> = rows.iter().filter(|r| !r.pass).collect();
        assert!(failed.is_empty(), "{failed:#?}");
        for impact in &OBLIQUE_TESTS {
            let n = rows.iter().filter(|r| r.case == impact.case).count();
            assert_eq!(
                n,
                INCIDENT_ANGLES.len() * impact.quantities().len() * OBLIQUE_METHODS.len()
            );
        }
    }
}
