//! Oblique impacts in the YADE driver: the rendered script of the held-out cases (friction,
//! the ball's motion along the plane, the printed line), the laws it refuses, and live runs
//! through `millimpact reference` against the closed form of Coulomb sliding.

use std::path::Path;

use millimpact::codes::deck::TANGENTIAL_LINE;
use millimpact::codes::yade::Yade;
use millimpact::codes::{CodeDriver, CodeError, CodeSetup, prepare_with};
use millimpact::model::case::Case;
use millimpact::model::tangential::TangentialSpring;

mod common;

use common::{case_path, millimpact};

const CASES: [&str; 2] = ["oblique/ball_plate_sliding", "oblique/ball_plate_spin"];

fn setup_of(case: &Case) -> CodeSetup {
    prepare_with(&Yade, case, None, None, false, None).unwrap()
}

fn held_out(name: &str) -> CodeSetup {
    let case = Case::load(&case_path(name)).unwrap_or_else(|e| panic!("{name}: {e}"));
    let setup = setup_of(&case);
    assert!(setup.oblique.is_some(), "{name} is an oblique case");
    setup
}

/// The script text of `setup` as the driver renders it.
fn rendered(setup: &CodeSetup) -> String {
    Yade.render(setup).unwrap().text
}

/// The number a line `NAME = value` of the script gives.
fn assigned(text: &str, name: &str) -> f64 {
    let prefix = format!("{name} = ");
    let line = text
        .lines()
        .find_map(|l| l.strip_prefix(&prefix))
        .unwrap_or_else(|| panic!("no `{name} = ` line"));
    line.trim()
        .parse()
        .unwrap_or_else(|e| panic!("{name}: {line}: {e}"))
}

// The script must give YADE the case's numbers to the last bit.
#[allow(clippy::float_cmp)]
#[test]
fn the_oblique_script_gives_the_ball_its_motion_the_friction_and_prints_the_line() {
    for name in CASES {
        let setup = held_out(name);
        let oblique = setup.oblique.unwrap();
        let text = rendered(&setup);
        assert_eq!(
            assigned(&text, "MU"),
            oblique.friction_coefficient,
            "{name}"
        );
        assert_eq!(
            assigned(&text, "VT"),
            oblique.ball.tangential_velocity,
            "{name}"
        );
        assert_eq!(
            assigned(&text, "W"),
            oblique.ball.angular_velocity,
            "{name}"
        );
        for line in [
            "mat1.frictionAngle = math.atan(MU)",
            "mat2.frictionAngle = math.atan(MU)",
            "phys_functor.es = 1.0",
            "O.bodies[b1].state.vel = Vector3(VT, 0.0, V1)",
            // The ball is below the wall: its surface at the contact moves at v_x + R ω_y.
            "O.bodies[b1].state.angVel = Vector3(0.0, -W, 0.0)",
            "O.bodies[b1].state.blockedDOFs = \"yXZ\"",
        ] {
            assert!(text.lines().any(|l| l == line), "{name}: no `{line}`");
        }
        // The set-up comes before the steps and after what it changes; the line after them.
        let at = |what: &str| {
            text.find(what)
                .unwrap_or_else(|| panic!("{name}: no `{what}`"))
        };
        assert!(at("phys_functor = ") < at("phys_functor.es"), "{name}");
        assert!(
            at("O.bodies[b1].state.blockedDOFs = \"XYZ\"") < at("\"yXZ\""),
            "{name}"
        );
        assert!(at("\"yXZ\"") < at("for _ in range(STEPS)"), "{name}");
        let last = text.lines().last().unwrap();
        assert_eq!(
            last,
            format!(
                "print(\"{TANGENTIAL_LINE} %r %r\" % (O.bodies[b1].state.vel[0], -O.bodies[b1].state.angVel[1]))"
            ),
            "{name}"
        );
        assert!(at("for _ in range(STEPS)") < at(TANGENTIAL_LINE), "{name}");
    }
}

#[test]
fn a_normal_impact_renders_as_before_and_the_oblique_one_only_adds_lines() {
    for name in CASES {
        let setup = held_out(name);
        let oblique = rendered(&setup);
        let normal = rendered(&CodeSetup {
            oblique: None,
            ..setup.clone()
        });
        for word in [
            TANGENTIAL_LINE,
            "MU =",
            "frictionAngle = math.atan",
            "es = 1.0",
        ] {
            assert!(
                !normal.contains(word),
                "{name}: `{word}` in a normal impact"
            );
        }
        // Every line of the normal script is in the oblique one, in order.
        let mut lines = oblique.lines();
        for line in normal.lines() {
            assert!(
                lines.any(|l| l == line),
                "{name}: `{line}` missing from the oblique script"
            );
        }
        assert!(oblique.len() > normal.len());
    }
}

/// The one line of the refusal of `setup`, or a panic when it renders.
fn refusal(setup: &CodeSetup) -> String {
    match Yade.render(setup) {
        Err(e @ CodeError::Unsupported { .. }) => {
            let line = e.to_string();
            assert!(!line.contains('\n'), "{line}");
            line
        }
        Err(e) => panic!("not a refusal: {e}"),
        Ok(_) => panic!("rendered a law YADE cannot run"),
    }
}

#[test]
fn laws_yade_cannot_render_are_refused_naming_the_law() {
    let setup = held_out(CASES[0]);
    let with = |spring: TangentialSpring, damping_ratio: f64| {
        let mut s = setup.clone();
        let o = s.oblique.as_mut().unwrap();
        o.law.spring = spring;
        o.law.damping_ratio = damping_ratio;
        s
    };
    let linear = refusal(&with(TangentialSpring::Linear { stiffness: 2.5e5 }, 0.0));
    assert!(
        linear.contains("constant tangential stiffness (250000 N/m)"),
        "{linear}"
    );
    assert!(linear.contains("Mindlin"), "{linear}");
    let proportional = refusal(&with(TangentialSpring::Proportional { ratio: 0.25 }, 0.0));
    assert!(proportional.contains("ratio 0.25"), "{proportional}");
    let damped = refusal(&with(TangentialSpring::Mindlin, 0.3));
    assert!(damped.contains("tangential damping ratio 0.3"), "{damped}");
    assert!(damped.contains("outside the Coulomb bound"), "{damped}");
    assert!(Yade.runs_oblique());
}

/// The `tangential` section of `reference --code yade CASE --format json`, checked for the
/// exit status the verdict implies.
fn reference(case: &Path) -> serde_json::Value {
    let output = millimpact()
        .args(["reference", "--code", "yade"])
        .arg(case)
        .args(["--format", "json"])
        .output()
        .unwrap();
    let json: serde_json::Value = serde_json::from_slice(&output.stdout).unwrap_or_else(|e| {
        panic!(
            "{}: {e}: {}",
            case.display(),
            String::from_utf8_lossy(&output.stderr)
        )
    });
    json["tangential"].clone()
}

fn number(section: &serde_json::Value, key: &str) -> f64 {
    section[key]
        .as_f64()
        .unwrap_or_else(|| panic!("no number `{key}` in {section}"))
}

/// Both change errors within the allowed one, and the changes of v_t and ω in the closed
/// form's senses.
fn assert_meets_closed_form(what: &str, t: &serde_json::Value) {
    assert_eq!(t["closed_form"], "gross_sliding", "{what}: {t}");
    let allowed = number(t, "allowed_change_error");
    for key in ["tangential_change_error", "spin_change_error"] {
        let error = number(t, key);
        assert!(error.abs() <= allowed, "{what}: {key} {error} > {allowed}");
    }
    for (start, out, closed) in [
        (
            "tangential_velocity",
            "tangential_velocity_out",
            "tangential_velocity_closed_form",
        ),
        (
            "angular_velocity",
            "angular_velocity_out",
            "angular_velocity_closed_form",
        ),
    ] {
        let change = number(t, out) - number(t, start);
        let expected = number(t, closed) - number(t, start);
        assert!(
            change.signum() == expected.signum() && expected != 0.0,
            "{what}: {out} changes by {change}, the closed form by {expected}"
        );
    }
}

#[test]
#[ignore = "live: needs yade (bash scripts/test.sh)"]
fn the_held_out_cases_meet_coulomb_sliding_in_yade() {
    for name in CASES {
        let t = reference(&case_path(name));
        assert_meets_closed_form(name, &t);
    }
}

// The sign of the spin in YADE's frame: a ball spinning without moving along the plate is
// driven along +t by a positive spin (its surface slips towards −t), and loses spin.
#[test]
#[ignore = "live: needs yade (bash scripts/test.sh)"]
fn a_spin_only_start_turns_the_way_the_closed_form_does() {
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(case_path(CASES[1]))
        .unwrap()
        .replace("tangential_velocity = 0.5", "tangential_velocity = 0.0")
        .replace("angular_velocity = -300.0", "angular_velocity = 300.0");
    let case = common::write(dir.path(), "spin_only.toml", &text);
    let t = reference(&case);
    assert!(number(&t, "tangential_velocity") == 0.0, "{t}");
    assert!(number(&t, "tangential_velocity_out") > 0.0, "{t}");
    assert!(number(&t, "angular_velocity_out") < 300.0, "{t}");
    assert_meets_closed_form("spin only", &t);
}
