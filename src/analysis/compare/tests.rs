//! The whole comparison: both contact times, the compression time and the peak force, pinned
//! against the closed forms (the paper's law) and against an independent integration (the
//! codes' damped laws); the start-phase band against the stepped law.

use std::path::Path;

use crate::analysis::compare::phase::{self, DEFAULT_PHASES, start_phase_band};
use crate::analysis::compare::{RESTITUTIONS, model_by_restitution};
use crate::analysis::store;
use crate::codes::CodeName;
use crate::model::case::Case;
use crate::model::exact;
use crate::model::law::DashpotLaw;
use crate::model::trajectory::{CodeTrajectory, trajectory_metrics};
use crate::solve::Method;
use crate::solve::dashpot::{accurate_metrics, own_law_metrics};
use crate::solve::paper::{self, Settings};

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

fn case(name: &str) -> Case {
    Case::load(&root().join("cases").join(format!("{name}.toml"))).unwrap()
}

/// Each `(figure, value, reference)` within `tol` of its reference, relatively.
fn assert_within(what: &str, tol: f64, figures: &[(&str, f64, f64)]) {
    for &(figure, value, reference) in figures {
        assert!(
            rel(value, reference) < tol,
            "{what}: {figure} {value} vs {reference}"
        );
    }
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

/// The paper's law, integrated by rk4-event and read as a code's trajectory is read, gives
/// both contact times (equal: its force is repulsive until the overlap closes), the
/// compression time and the peak force of the closed forms.
#[test]
fn the_paper_law_read_as_a_trajectory_gives_the_closed_forms() {
    for name in ["ball_plate", "rod_end"] {
        let case = case(name);
        let law = case.law();
        let v0 = case.impact_velocity;
        let settings = Settings {
            method: Method::Rk4Event,
            steps_per_period: 4000,
            record: true,
            ..Settings::default()
        };
        let out = paper::solve(&law, v0, &settings).unwrap();
        let samples = &out.trajectory;
        let trajectory = CodeTrajectory {
            time: samples.iter().map(|s| s.t).collect(),
            overlap: samples.iter().map(|s| s.y).collect(),
            approach_velocity: samples.iter().map(|s| s.v).collect(),
            normal_force: samples.iter().map(|s| law.force(s.y, s.v)).collect(),
        };
        let m = trajectory_metrics(&trajectory).unwrap();
        let e = exact::paper_impact(&law, v0);
        // Linear interpolation of the crossings and the sampled peak: O(h²) with h = T/4000.
        let tol = 1e-5;
        assert_within(
            name,
            tol,
            &[
                ("overlap time", m.contact_time, e.contact_time),
                ("force time", m.force_contact_time, e.contact_time),
                ("compression", m.compression_time, e.compression_time),
                ("peak force", m.peak_force, e.peak_force),
            ],
        );
        // The closed forms the comparison uses for the paper's law agree with the integration.
        let p = e.metrics();
        assert!(
            rel(p.force_contact_time, m.force_contact_time) < tol,
            "{name}"
        );
        assert!(rel(p.peak_force, m.peak_force) < tol, "{name}");
    }
}

/// Figures of a damped law by classical RK4 at a tiny fixed step, every event found by
/// linear interpolation between steps: independent of the event-locating integration.
struct Reference {
    cor: f64,
    peak_force: f64,
    contact_time: f64,
    force_contact_time: f64,
    compression_time: f64,
}

fn rk4_reference(law: &DashpotLaw, v0: f64, h: f64) -> Reference {
    // The law continued smoothly past y = 0 (the linear law's `k y + c ẏ` is not continuous at
    // touch), so that a step straddling the start or the end stays smooth; the crossing is
    // interpolated inside the step.
    let force = |y: f64, v: f64| {
        let linear = law.exponent < 1.25 && law.damping_exponent.abs() < 1e-12;
        let f = if linear {
            law.stiffness * y + law.damping * v
        } else {
            let y = y.max(0.0);
            law.stiffness * y.powf(law.exponent) + law.damping * y.powf(law.damping_exponent) * v
        };
        if law.clamp_attractive { f.max(0.0) } else { f }
    };
    let acc = |y: f64, v: f64| -force(y, v) / law.mass;
    let (mut t, mut y, mut v) = (0.0f64, 0.0f64, v0);
    let mut peak_force: f64 = 0.0;
    let (mut force_end, mut turn) = (f64::NAN, f64::NAN);
    let mut f_prev = 0.0;
    let mut pushed = false;
    loop {
        let (k1y, k1v) = (v, acc(y, v));
        let (k2y, k2v) = (v + 0.5 * h * k1v, acc(y + 0.5 * h * k1y, v + 0.5 * h * k1v));
        let (k3y, k3v) = (v + 0.5 * h * k2v, acc(y + 0.5 * h * k2y, v + 0.5 * h * k2v));
        let (k4y, k4v) = (v + h * k3v, acc(y + h * k3y, v + h * k3v));
        let y1 = y + h / 6.0 * (k1y + 2.0 * k2y + 2.0 * k3y + k4y);
        let v1 = v + h / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
        // The unclamped force, so that its zero is a sign change.
        let f1 = DashpotLaw {
            clamp_attractive: false,
            ..*law
        }
        .force(y1, v1);
        peak_force = peak_force.max(f1);
        if f1 > 0.0 {
            pushed = true;
        }
        if pushed && force_end.is_nan() && f1 <= 0.0 {
            force_end = t + h * f_prev / (f_prev - f1);
        }
        if turn.is_nan() && v1 <= 0.0 {
            turn = t + h * v / (v - v1);
        }
        if y1 <= 0.0 && t > 0.0 {
            let end = t + h * y / (y - y1);
            let v_end = v + (v1 - v) * (end - t) / h;
            return Reference {
                cor: -v_end / v0,
                peak_force,
                contact_time: end,
                force_contact_time: force_end,
                compression_time: turn,
            };
        }
        (t, y, v, f_prev) = (t + h, y1, v1, f1);
    }
}

#[test]
fn damped_laws_event_figures_match_an_independent_integration() {
    let case = case("ball_plate");
    let law = case.law();
    let v0 = case.impact_velocity;
    let e = exact::restitution(case.loss_coefficient);
    let hertz = DashpotLaw::damped_hertz(law.mass, law.stiffness, e);
    let rod = case_rod();
    for (what, l, v) in [
        ("damped Hertz", hertz, v0),
        ("damped Hertz, clamped", hertz.clamped(), v0),
        ("linear", rod.0, rod.1),
        ("linear, clamped", rod.0.clamped(), rod.1),
    ] {
        let m = accurate_metrics(&l, v, 1e-12).unwrap();
        let h = m.contact_time / 400_000.0;
        let r = rk4_reference(&l, v, h);
        let tol = 1e-7;
        assert_within(
            what,
            tol,
            &[
                ("COR", m.cor, r.cor),
                ("peak force", m.peak_force, r.peak_force),
                ("overlap time", m.contact_time, r.contact_time),
                ("force time", m.force_contact_time, r.force_contact_time),
                ("compression", m.compression_time, r.compression_time),
            ],
        );
        // The force ends well before the overlap: the model difference the old figures hid.
        assert!(m.force_contact_time < 0.95 * m.contact_time, "{what}");
    }
}

fn case_rod() -> (DashpotLaw, f64) {
    let rod = case("rod_end");
    let law = rod.law();
    (
        DashpotLaw::linear(law.mass, law.stiffness, rod.restitution()),
        rod.impact_velocity,
    )
}

/// The peak-force gap at η = 0.35 is the largest of the model differences, and every
/// difference shrinks as e → 1; a code with the paper's law built in has none at any e.
#[test]
fn model_differences_shrink_towards_the_elastic_limit() {
    let all = model_by_restitution(&case("ball_plate"), &RESTITUTIONS).unwrap();
    // One point per restitution and code.
    assert_eq!(all.len(), RESTITUTIONS.len() * CodeName::ALL.len());
    // The builds with the paper's law are those given η itself.
    let paper_builds = CodeName::ALL
        .iter()
        .filter(|c| c.driver().takes_loss_coefficient())
        .count();
    assert!(
        paper_builds >= 3,
        "liggghts-paper, yade-paper and lammps-paper at least"
    );
    let (paper, points): (Vec<_>, Vec<_>) = all
        .into_iter()
        .partition(|p| p.code.driver().takes_loss_coefficient());
    assert_eq!(paper.len(), RESTITUTIONS.len() * paper_builds);
    for p in &paper {
        let o = &p.offsets;
        // Its own law is the paper's, at the case's η itself, with the build's E* and mass
        // (equal to the case's to rounding): the COR exactly, the rest to rounding.
        assert_eq!(o.cor.to_bits(), 0f64.to_bits(), "{p:?}");
        for d in [
            o.peak_deformation,
            o.peak_force,
            o.contact_time,
            o.force_contact_time,
        ] {
            assert!(d.abs() < 1e-15, "{p:?}");
        }
    }
    for p in &points {
        assert!((p.law_cor - p.restitution).abs() < 1e-3, "{p:?}");
        assert!(
            p.offsets.peak_force.abs() > p.offsets.peak_deformation.abs(),
            "{p:?}"
        );
        assert!(
            p.offsets.force_contact_time < p.offsets.contact_time,
            "{p:?}"
        );
    }
    let at = |e: f64| {
        points
            .iter()
            .filter(move |p| (p.restitution - e).abs() < 1e-12)
    };
    for (lo, hi) in at(0.6).zip(at(0.95)) {
        assert!(hi.offsets.peak_force.abs() < lo.offsets.peak_force.abs());
        assert!(hi.offsets.contact_time.abs() < lo.offsets.contact_time.abs());
    }
}

/// Each stored run's integration offset (its own law stepped from touch, as stored) lies in
/// the band the start-phase sweep gives, and a start one whole step early repeats the run.
#[test]
fn stored_runs_lie_in_their_start_phase_band() {
    let files = store::stored_files(&root().join("reference")).unwrap();
    assert!(!files.is_empty());
    let mut checked = 0;
    for path in files {
        for r in store::load(&path).unwrap().runs {
            let exact = own_law_metrics(&r.law, r.setup.impact_velocity, 1e-13).unwrap();
            let band = start_phase_band(&r, &exact, DEFAULT_PHASES).unwrap();
            let p = &r.paper_exact;
            let s = &r.law_at_step;
            let slack = 1e-12;
            let what = format!("{} {} η={}", r.code, r.case, r.loss_coefficient);
            assert!(
                band.ranges.cor.contains((s.cor - exact.cor) / p.cor, slack),
                "{what}: {:?}",
                band.ranges.cor
            );
            assert!(
                band.ranges.peak_deformation.contains(
                    (s.peak_deformation - exact.peak_deformation) / p.peak_deformation,
                    slack
                ),
                "{what}"
            );
            assert!(
                band.ranges.contact_time.contains(
                    (s.contact_time - exact.contact_time) / p.contact_time,
                    slack
                ),
                "{what}"
            );
            assert!(
                band.ranges.cor.max > band.ranges.cor.min,
                "{what}: the band has width"
            );
            let zero = phase::stepped_at_phase(&r, 0.0).unwrap();
            let one = phase::stepped_at_phase(&r, 1.0).unwrap();
            assert!(rel(one.cor, zero.cor) < 1e-12, "{what}");
            assert!(rel(one.contact_time, zero.contact_time) < 1e-9, "{what}");
            checked += 1;
        }
    }
    assert!(checked >= 9, "{checked} stored runs checked");
}
