//! Helpers shared by every integration test: the crate's folders, the shipped cases, the
//! binary, cases built in code, and relative comparisons.
#![allow(dead_code)]

use std::path::{Path, PathBuf};

use assert_cmd::Command;

use millimpact::model::case::Case;
use millimpact::model::case::ContactKind;
use millimpact::model::scene::{Ball, Material, Plate, Rod, Scene, StiffnessConvention};

/// The crate's root folder.
pub fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// A shipped case file.
pub fn case_path(name: &str) -> PathBuf {
    root().join("cases").join(format!("{name}.toml"))
}

/// A shipped case, loaded through the validating reader.
pub fn shipped(name: &str) -> Case {
    Case::load(&case_path(name)).unwrap_or_else(|e| panic!("{name}: {e}"))
}

/// The `millimpact` binary, run from the crate's root (so `cases/` and `reference/` resolve).
pub fn millimpact() -> Command {
    let mut cmd = Command::cargo_bin("millimpact").unwrap();
    cmd.current_dir(root());
    cmd
}

/// Run `cmd`, require exit 0, and return its standard output.
#[track_caller]
pub fn stdout(cmd: &mut Command) -> String {
    let output = cmd.output().unwrap();
    assert!(
        output.status.success(),
        "exit {:?}: {}",
        output.status.code(),
        String::from_utf8_lossy(&output.stderr)
    );
    String::from_utf8(output.stdout).unwrap()
}

/// Steel: E = 200 GPa, ν = 0.3.
pub fn steel() -> Material {
    Material {
        youngs_modulus: 2.0e11,
        poisson_ratio: 0.3,
    }
}

/// A ball of radius `r` (m), density `rho` and modulus `e` (ν = 0.3).
pub fn ball(r: f64, rho: f64, e: f64) -> Ball {
    Ball {
        radius: r,
        density: rho,
        material: Material {
            youngs_modulus: e,
            poisson_ratio: 0.3,
        },
    }
}

/// A case built in code, without a file.
pub fn case(name: &str, scene: Scene, v0: f64, eta: f64) -> Case {
    Case {
        name: name.to_string(),
        path: PathBuf::from(format!("{name}.toml")),
        scene,
        impact_velocity: v0,
        loss_coefficient: eta,
        stiffness: StiffnessConvention::Hertz,
        contact: ContactKind::Unilateral,
        oblique: None,
    }
}

/// The three scenes at a given size `r` (m) and modulus `e` (Pa), steel density.
pub fn scenes(r: f64, e: f64) -> Vec<(&'static str, Scene)> {
    let b = ball(r, 7800.0, e);
    vec![
        (
            "ball_plate",
            Scene::BallPlate {
                ball: b,
                plate: Plate::Elastic(b.material),
            },
        ),
        (
            "ball_ball",
            Scene::BallBall {
                ball: b,
                other: ball(0.5 * r, 7800.0, 0.7 * e),
            },
        ),
        (
            "rod_end",
            Scene::RodEnd {
                rod: Rod {
                    diameter: 1.5 * r,
                    length: 25.0 * r,
                    density: 7800.0,
                    youngs_modulus: e,
                },
            },
        ),
    ]
}

/// Relative difference `|a - b| / |b|`.
pub fn rel(a: f64, b: f64) -> f64 {
    ((a - b) / b).abs()
}

/// Assert `|a - b| <= tol |b|` with a message naming what was compared.
#[track_caller]
pub fn assert_rel(what: &str, a: f64, b: f64, tol: f64) {
    let r = rel(a, b);
    assert!(
        r <= tol,
        "{what}: got {a:.17e}, expected {b:.17e}, relative error {r:.3e} > {tol:e}"
    );
}

/// Write `text` to `dir/name` and return the path.
pub fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}
pub mod calibrate;
pub mod codes;
pub mod deck;
pub mod mill;
pub mod oblique;
pub mod paper_build;

/// For every registered build, its `MILLIMPACT_<CODE>_BINARY` naming a file that does not
/// exist: with these set, no DEM code is found, so none is probed or run, as on a machine
/// without the codes (the drivers' fallback conventions plan the setups).
pub fn codes_hidden() -> Vec<(String, PathBuf)> {
    millimpact::codes::CodeName::ALL
        .iter()
        .map(|code| {
            (
                millimpact::codes::runner::binary_override_variable(code.name()),
                PathBuf::from(format!("/nonexistent/millimpact-fast-tier/{}", code.name())),
            )
        })
        .collect()
}
