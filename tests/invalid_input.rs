//! Every class of invalid input: one line on stderr naming the file, the key, the value and
//! what is allowed; exit code 2; no file written.

mod common;

use std::path::{Path, PathBuf};

use common::{case_path, millimpact, shipped, write};
use millimpact::solve::Method;
use millimpact::solve::paper::{self, Settings, angular_frequency, stability_limit};
use tempfile::TempDir;

const ROD: &str = r#"scene = "rod_end"
impact_velocity = 2.0
loss_coefficient = 0.35

[rod]
diameter = 0.03
length = 0.5
density = 7800.0
youngs_modulus = 2.0e11
"#;

const BALL_PLATE: &str = r#"scene = "ball_plate"
impact_velocity = 2.0
loss_coefficient = 0.35

[ball]
radius = 0.02
density = 7800.0
youngs_modulus = 2.0e11
poisson_ratio = 0.3

[plate]
rigid = false
youngs_modulus = 2.0e11
poisson_ratio = 0.3
"#;

const BALL_BALL: &str = r#"scene = "ball_ball"
impact_velocity = 2.0
loss_coefficient = 0.35

[ball]
radius = 0.02
density = 7800.0
youngs_modulus = 2.0e11
poisson_ratio = 0.3
"#;

/// Replace exactly one occurrence of `from` in `text`.
fn edit(text: &str, from: &str, to: &str) -> String {
    assert_eq!(text.matches(from).count(), 1, "{from:?} must occur once");
    text.replacen(from, to, 1)
}

/// Run `millimpact <args> --trajectory OUT.csv` and check the rejection: exit 2, nothing on
/// stdout, one line on stderr holding every fragment, and OUT.csv not written.
#[track_caller]
fn rejected(dir: &Path, args: &[&str], fragments: &[&str]) -> String {
    let out_csv = dir.join("OUT.csv");
    let mut cmd = millimpact();
    cmd.current_dir(dir).args(args);
    if args[0] == "run" {
        cmd.arg("--trajectory").arg(&out_csv);
    }
    let output = cmd.output().unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr).into_owned();
    assert_eq!(
        output.status.code(),
        Some(2),
        "{args:?}: exit code {:?}, stderr {stderr}",
        output.status.code()
    );
    assert!(output.stdout.is_empty(), "{args:?}: wrote to stdout");
    let line = stderr.strip_suffix('\n').unwrap_or(&stderr);
    assert!(
        !line.is_empty() && !line.contains('\n'),
        "{args:?}: not one line: {stderr:?}"
    );
    for fragment in fragments {
        assert!(
            line.contains(fragment),
            "{args:?}: {line:?} does not contain {fragment:?}"
        );
    }
    assert!(!out_csv.exists(), "{args:?}: OUT.csv was written");
    line.to_string()
}

/// A case file with `text` is rejected, the message naming the file, `key`, `value` and
/// `allowed`.
#[track_caller]
fn bad_case(name: &str, text: &str, key: &str, value: &str, allowed: &str) {
    let dir = TempDir::new().unwrap();
    let path = write(dir.path(), &format!("{name}.toml"), text);
    let file = path.display().to_string();
    let line = rejected(
        dir.path(),
        &["run", &file],
        &[&file, &format!("{key} = {value}: "), allowed],
    );
    // The same text is what the library reports.
    let error = millimpact::model::case::Case::load(&path).unwrap_err();
    assert_eq!(error.key, key);
    assert_eq!(error.value, value);
    assert!(line.ends_with(&error.to_string()), "{line} vs {error}");
    // And sweep rejects the same file the same way.
    rejected(
        dir.path(),
        &["sweep", &file, "--loss-coefficient", "0:0.5:0.1"],
        &[&file, &format!("{key} = {value}: ")],
    );
}

#[test]
fn the_templates_are_valid() {
    let dir = TempDir::new().unwrap();
    for (name, text) in [
        ("rod", ROD),
        ("ball_plate", BALL_PLATE),
        ("ball_ball", BALL_BALL),
    ] {
        let path = write(dir.path(), &format!("{name}.toml"), text);
        millimpact::model::case::Case::load(&path).unwrap();
    }
}

#[test]
fn zero_or_negative_sizes_densities_moduli_and_speed() {
    let positive = "must be a finite number > 0";
    for (from, to, key, value) in [
        ("diameter = 0.03", "diameter = 0.0", "rod.diameter", "0"),
        ("length = 0.5", "length = -0.5", "rod.length", "-0.5"),
        ("density = 7800.0", "density = 0", "rod.density", "0"),
        (
            "youngs_modulus = 2.0e11",
            "youngs_modulus = -2.0e11",
            "rod.youngs_modulus",
            "-200000000000",
        ),
        (
            "impact_velocity = 2.0",
            "impact_velocity = 0.0",
            "impact_velocity",
            "0",
        ),
        (
            "impact_velocity = 2.0",
            "impact_velocity = -2.0",
            "impact_velocity",
            "-2",
        ),
    ] {
        bad_case("rod", &edit(ROD, from, to), key, value, positive);
    }
    for (from, to, key, value) in [
        ("radius = 0.02", "radius = -0.02", "ball.radius", "-0.02"),
        ("density = 7800.0", "density = -1.0", "ball.density", "-1"),
        (
            "rigid = false\nyoungs_modulus = 2.0e11",
            "rigid = false\nyoungs_modulus = 0.0",
            "plate.youngs_modulus",
            "0",
        ),
    ] {
        bad_case(
            "ball_plate",
            &edit(BALL_PLATE, from, to),
            key,
            value,
            positive,
        );
    }
    let other = format!("{BALL_BALL}\n[other_ball]\nradius = -0.01\n");
    bad_case("ball_ball", &other, "other_ball.radius", "-0.01", positive);
}

#[test]
fn poisson_ratio_outside_open_interval() {
    let ball_nu = "2.0e11\npoisson_ratio = 0.3\n\n[plate]";
    let plate_nu = "rigid = false\nyoungs_modulus = 2.0e11\npoisson_ratio = 0.3";
    for nu in ["0.5", "-1", "0.7", "-1.5"] {
        let text = edit(
            BALL_PLATE,
            ball_nu,
            &ball_nu.replace("= 0.3", &format!("= {nu}")),
        );
        bad_case("ball_plate", &text, "ball.poisson_ratio", nu, "(-1, 0.5)");
        let text = edit(
            BALL_PLATE,
            plate_nu,
            &plate_nu.replace("= 0.3", &format!("= {nu}")),
        );
        bad_case("ball_plate", &text, "plate.poisson_ratio", nu, "(-1, 0.5)");
        let text = format!("{BALL_BALL}\n[other_ball]\npoisson_ratio = {nu}\n");
        bad_case(
            "ball_ball",
            &text,
            "other_ball.poisson_ratio",
            nu,
            "(-1, 0.5)",
        );
    }
}

#[test]
fn loss_coefficient_outside_zero_one() {
    for eta in ["1", "1.5", "-0.1"] {
        let text = edit(
            ROD,
            "loss_coefficient = 0.35",
            &format!("loss_coefficient = {eta}"),
        );
        bad_case("rod", &text, "loss_coefficient", eta, "[0, 1)");
    }
}

#[test]
fn restitution_outside_zero_one() {
    for e in ["0", "-0.5", "1.1"] {
        let text = edit(
            ROD,
            "loss_coefficient = 0.35",
            &format!("restitution = {e}"),
        );
        bad_case("rod", &text, "restitution", e, "(0, 1]");
    }
    // A positive e so small that η = (1-e²)/(1+e²) rounds to 1: no impact would ever end.
    let text = edit(ROD, "loss_coefficient = 0.35", "restitution = 1e-9");
    bad_case("rod", &text, "restitution", "0.000000001", "(0, 1]");
}

#[test]
fn nan_and_infinity() {
    for (from, to, key, value) in [
        (
            "impact_velocity = 2.0",
            "impact_velocity = nan",
            "impact_velocity",
            "NaN",
        ),
        (
            "impact_velocity = 2.0",
            "impact_velocity = inf",
            "impact_velocity",
            "inf",
        ),
        (
            "loss_coefficient = 0.35",
            "loss_coefficient = nan",
            "loss_coefficient",
            "NaN",
        ),
        (
            "loss_coefficient = 0.35",
            "restitution = nan",
            "restitution",
            "NaN",
        ),
        ("diameter = 0.03", "diameter = +inf", "rod.diameter", "inf"),
        ("length = 0.5", "length = -inf", "rod.length", "-inf"),
        ("density = 7800.0", "density = nan", "rod.density", "NaN"),
        (
            "youngs_modulus = 2.0e11",
            "youngs_modulus = inf",
            "rod.youngs_modulus",
            "inf",
        ),
    ] {
        bad_case("rod", &edit(ROD, from, to), key, value, "finite");
    }
    let text = edit(
        BALL_PLATE,
        "2.0e11\npoisson_ratio = 0.3\n\n[plate]",
        "2.0e11\npoisson_ratio = nan\n\n[plate]",
    );
    bad_case("ball_plate", &text, "ball.poisson_ratio", "NaN", "finite");
}

#[test]
fn both_or_neither_of_loss_coefficient_and_restitution() {
    let both = edit(
        ROD,
        "loss_coefficient = 0.35",
        "loss_coefficient = 0.35\nrestitution = 0.7",
    );
    bad_case("rod", &both, "loss_coefficient", "0.35", "exactly one");
    let neither = edit(ROD, "loss_coefficient = 0.35\n", "");
    bad_case(
        "rod",
        &neither,
        "loss_coefficient",
        "(missing)",
        "exactly one",
    );
}

#[test]
fn unknown_scene() {
    let text = edit(ROD, "\"rod_end\"", "\"rod_side\"");
    bad_case("rod", &text, "scene", "\"rod_side\"", "\"rod_end\"");
    let text = edit(ROD, "scene = \"rod_end\"\n", "");
    bad_case("rod", &text, "scene", "(missing)", "\"ball_plate\"");
}

#[test]
fn tables_and_keys_the_scene_does_not_use() {
    let plate = format!("{ROD}\n[plate]\nrigid = true\n");
    bad_case("rod", &plate, "[plate]", "(table)", "[rod]");
    let other = format!("{BALL_PLATE}\n[other_ball]\nradius = 0.01\n");
    bad_case(
        "ball_plate",
        &other,
        "[other_ball]",
        "(table)",
        "[ball] and [plate]",
    );
    let plate_in_balls = format!("{BALL_BALL}\n[plate]\nrigid = true\n");
    bad_case(
        "ball_ball",
        &plate_in_balls,
        "[plate]",
        "(table)",
        "[other_ball]",
    );
    let nu_in_rod = format!("{ROD}poisson_ratio = 0.3\n");
    bad_case(
        "rod",
        &nu_in_rod,
        "rod.poisson_ratio",
        "0.3",
        "[rod] takes diameter",
    );
    let misspelt = edit(ROD, "diameter", "diamter");
    bad_case(
        "rod",
        &misspelt,
        "rod.diamter",
        "0.03",
        "[rod] takes diameter",
    );
    let top = format!("impact_speed = 2.0\n{ROD}");
    bad_case("rod", &top, "impact_speed", "2.0", "allowed at top level");
    let stiffness = format!("stiffness = \"paper\"\n{ROD}");
    bad_case(
        "rod",
        &stiffness,
        "stiffness",
        "\"paper\"",
        "not used by scene \"rod_end\"",
    );
    let rigid_with_modulus = edit(BALL_PLATE, "rigid = false", "rigid = true");
    bad_case(
        "ball_plate",
        &rigid_with_modulus,
        "plate.poisson_ratio",
        "0.3",
        "[plate] takes rigid",
    );
    let bad_convention = format!("stiffness = \"soft\"\n{BALL_BALL}");
    bad_case(
        "ball_ball",
        &bad_convention,
        "stiffness",
        "\"soft\"",
        "\"paper\"",
    );
    let bad_contact = format!("contact = \"sideways\"\n{ROD}");
    bad_case(
        "rod",
        &bad_contact,
        "contact",
        "\"sideways\"",
        "\"bilateral\"",
    );
}

#[test]
fn wrong_types() {
    let text = edit(ROD, "impact_velocity = 2.0", "impact_velocity = \"fast\"");
    bad_case(
        "rod",
        &text,
        "impact_velocity",
        "\"fast\"",
        "must be a number",
    );
    let text = edit(BALL_PLATE, "rigid = false", "rigid = \"no\"");
    bad_case(
        "ball_plate",
        &text,
        "plate.rigid",
        "\"no\"",
        "true or false",
    );
}

#[test]
fn missing_file_and_invalid_toml() {
    let dir = TempDir::new().unwrap();
    let missing = dir.path().join("nowhere.toml");
    let file = missing.display().to_string();
    rejected(
        dir.path(),
        &["run", &file],
        &[&file, "(file) = (unreadable)", "cannot read"],
    );
    let broken = write(dir.path(), "broken.toml", &format!("{ROD}density =\n"));
    let file = broken.display().to_string();
    rejected(
        dir.path(),
        &["run", &file],
        &[&file, "(file) = (not TOML)", "invalid TOML at line 10"],
    );
}

#[test]
fn bad_loss_coefficient_ranges() {
    let dir = TempDir::new().unwrap();
    let file = case_path("rod_end").display().to_string();
    for range in [
        "0:1:0.1",
        "0.5:0.1:0.1",
        "-0.1:0.5:0.1",
        "0:0.5:0",
        "0:0.5",
        "a:b:c",
        "0:nan:0.1",
    ] {
        rejected(
            dir.path(),
            &["sweep", &file, &format!("--loss-coefficient={range}")],
            &[
                &file,
                &format!("--loss-coefficient = {range}: "),
                "START:STOP:STEP",
            ],
        );
    }
}

#[test]
fn timestep_with_an_adaptive_method() {
    let dir = TempDir::new().unwrap();
    let file = case_path("rod_end").display().to_string();
    rejected(
        dir.path(),
        &["run", &file, "--method", "dopri5", "--timestep", "1e-7"],
        &[
            &file,
            "--timestep = 0.0000001: ",
            "rk4, rk4-event and verlet",
        ],
    );
    rejected(
        dir.path(),
        &["run", &file, "--method", "rk4", "--timestep=-1e-7"],
        &[&file, "--timestep = -0.0000001: ", "> 0"],
    );
}

fn temp_out(dir: &Path) -> PathBuf {
    dir.join("OUT.csv")
}

/// Just below the stability limit a fixed step integrates; just above, the run is refused
/// with the limit in the message.
#[test]
fn timestep_at_the_stability_limit() {
    for name in ["rod_end", "ball_plate"] {
        let mut c = shipped(name);
        if name == "rod_end" {
            // The undamped linear oscillator, where ω = sqrt(C/M) exactly.
            c = c.with_loss_coefficient(0.0);
        }
        let dir = TempDir::new().unwrap();
        let file = write(dir.path(), "case.toml", &case_text(&c, name));
        let file = file.display().to_string();
        let law = c.law();
        let omega = angular_frequency(&law, c.impact_velocity);
        if name == "rod_end" {
            common::assert_rel("ω", omega, (law.stiffness / law.mass).sqrt(), 1e-14);
        }
        for (method, limit) in [
            (Method::Rk4, 2.0 * 2f64.sqrt()),
            (Method::Rk4Event, 2.0 * 2f64.sqrt()),
            (Method::Verlet, 2.0),
        ] {
            assert_eq!(stability_limit(method), Some(limit));
            let below = 0.999 * limit / omega;
            let above = 1.001 * limit / omega;
            let out = temp_out(dir.path());
            millimpact()
                .args(["run", &file, "--method", method.name(), "--format", "json"])
                .arg("--timestep")
                .arg(below.to_string())
                .arg("--trajectory")
                .arg(&out)
                .assert()
                .success();
            assert!(out.exists());
            std::fs::remove_file(&out).unwrap();
            let line = rejected(
                dir.path(),
                &[
                    "run",
                    &file,
                    "--method",
                    method.name(),
                    "--timestep",
                    &above.to_string(),
                ],
                &[&file, "--timestep", "stability limit"],
            );
            assert!(
                line.contains(&limit.to_string()),
                "{line} does not give the limit {limit}"
            );
            assert!(line.contains("use Δt <"), "{line}");
        }
    }
}

/// The limits themselves: RK4's amplification factor on `y'' = -ω² y` reaches 1 at
/// `ω Δt = 2√2`, velocity Verlet's at 2; and the solver, two-sided and undamped for many periods
/// just below the limit, does not grow.
#[test]
fn stability_limits_are_where_the_methods_turn_unstable() {
    let rk4_gain = |z: f64| {
        // R(iz) of classical RK4.
        let re = 1.0 - z * z / 2.0 + z.powi(4) / 24.0;
        let im = z - z.powi(3) / 6.0;
        (re * re + im * im).sqrt()
    };
    let verlet_gain = |z: f64| {
        // Eigenvalues of the velocity-Verlet map: λ² - (2 - z²) λ + 1 = 0.
        let b = 2.0 - z * z;
        let disc = b * b - 4.0;
        if disc <= 0.0 {
            1.0
        } else {
            (b.abs() + disc.sqrt()) / 2.0
        }
    };
    let rk4 = stability_limit(Method::Rk4).unwrap();
    let verlet = stability_limit(Method::Verlet).unwrap();
    assert!(rk4_gain(rk4 * 0.999) < 1.0 && rk4_gain(rk4 * 1.001) > 1.0);
    assert!(verlet_gain(verlet * 0.999) <= 1.0 && verlet_gain(verlet * 1.001) > 1.0);

    let mut c = shipped("rod_end_bilateral").with_loss_coefficient(0.0);
    c.contact = millimpact::model::case::ContactKind::Bilateral;
    let law = c.law();
    let omega = angular_frequency(&law, c.impact_velocity);
    for method in [Method::Rk4, Method::Verlet] {
        let dt = 0.999 * stability_limit(method).unwrap() / omega;
        let settings = Settings {
            method,
            timestep: Some(dt),
            contact: c.contact,
            periods: 200.0,
            record: true,
            ..Settings::default()
        };
        let out = paper::solve(&law, c.impact_velocity, &settings).unwrap();
        let energy: Vec<f64> = out
            .trajectory
            .iter()
            .map(|s| 0.5 * law.mass * s.v * s.v + 0.5 * law.stiffness * s.y * s.y)
            .collect();
        let initial = 0.5 * law.mass * c.impact_velocity * c.impact_velocity;
        let largest = energy.iter().cloned().fold(0.0, f64::max);
        assert!(energy.len() > 200, "{}", energy.len());
        // A bounded map can stretch the energy by a fixed factor near its limit, never without
        // bound: 200 periods at a growth of even 1.001 per step would exceed 1e3.
        assert!(
            largest < 1e3 * initial,
            "{}: energy grew to {largest} from {initial}",
            method.name()
        );
    }
}

/// The TOML text of a case made from a shipped one at another η.
fn case_text(c: &millimpact::model::case::Case, name: &str) -> String {
    let text = std::fs::read_to_string(case_path(name)).unwrap();
    let mut out = String::new();
    for line in text.lines() {
        if line.starts_with("loss_coefficient") {
            out += &format!("loss_coefficient = {:?}\n", c.loss_coefficient);
        } else {
            out += line;
            out.push('\n');
        }
    }
    out
}

#[test]
fn command_line_usage_errors_are_one_line_too() {
    let dir = TempDir::new().unwrap();
    let case = case_path("ball_plate");
    let case = case.to_str().unwrap();
    rejected(
        dir.path(),
        &["run", case, "--method", "rk5"],
        &[
            "'rk5'",
            "--method",
            "possible values: rk4, rk4-event, dopri5, verlet, exact",
        ],
    );
    rejected(
        dir.path(),
        &["run", case, "--rtol", "tight"],
        &["'tight'", "--rtol"],
    );
    rejected(
        dir.path(),
        &["run", case, "--steps-per-period", "2"],
        &["'2'", "--steps-per-period"],
    );
    // A bilateral run past 1000 periods is unbounded work, not a check.
    rejected(
        dir.path(),
        &["run", case, "--periods", "1e9"],
        &["'1e9'", "--periods", "(0, 1000]"],
    );
    // A code run at one step per contact reports a COR of 18.7: refused before any code starts.
    rejected(
        dir.path(),
        &[
            "reference",
            "--code",
            "lammps",
            case,
            "--steps-per-contact",
            "1",
        ],
        &["'1'", "--steps-per-contact", "20"],
    );
}

/// A case must be a regular file of a case's size, and its numbers must give representable
/// derived quantities; each refusal is one line, exit 2, at once (no hang, no growth).
#[test]
fn unreadable_and_unrepresentable_cases_are_refused() {
    let dir = tempfile::TempDir::new().unwrap();
    let fifo = dir.path().join("fifo.toml");
    assert!(
        std::process::Command::new("mkfifo")
            .arg(&fifo)
            .status()
            .unwrap()
            .success()
    );
    let big = dir.path().join("big.toml");
    std::fs::write(&big, "#".repeat(70_000)).unwrap();
    let shipped = std::fs::read_to_string(common::case_path("ball_plate")).unwrap();
    let huge = dir.path().join("huge.toml");
    std::fs::write(&huge, shipped.replace("radius = 0.02", "radius = 1e308")).unwrap();
    let light = dir.path().join("light.toml");
    std::fs::write(
        &light,
        shipped.replace("density = 7800.0", "density = 1e-308"),
    )
    .unwrap();
    for (path, expected) in [
        (Path::new("/dev/zero"), "not a regular file"),
        (fifo.as_path(), "not a regular file"),
        (big.as_path(), "at most 65536 bytes"),
        (huge.as_path(), "mass = inf"),
        (light.as_path(), "mass = 3.35"),
    ] {
        let out = common::millimpact()
            .arg("run")
            .arg(path)
            .timeout(std::time::Duration::from_secs(20))
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{}: {stderr}", path.display());
        assert!(stderr.contains(expected), "{}: {stderr}", path.display());
        assert_eq!(stderr.lines().count(), 1, "{stderr}");
    }
}

/// One rule for each count and tolerance, in the library as on the command line: steps per
/// period in 4..=1e8, a relative tolerance no finer than the spacing of doubles, a trajectory of
/// at most 1e6 rows (checked before the run), and an output file's directory must exist.
#[test]
fn counts_tolerances_and_output_directories_are_bounded_before_any_work() {
    let dir = TempDir::new().unwrap();
    let case = case_path("ball_plate");
    let case = case.to_str().unwrap();
    rejected(
        dir.path(),
        &["run", case, "--method", "dopri5", "--rtol", "1e-300"],
        &["'1e-300'", "--rtol", "[2.220446049250313e-16, 1)"],
    );
    rejected(
        dir.path(),
        &[
            "run",
            case,
            "--method",
            "rk4",
            "--steps-per-period",
            "100000000",
        ],
        &["--steps-per-period = 100000000", "1e6"],
    );
    rejected(
        dir.path(),
        &["run", case, "--method", "verlet", "--timestep", "1e-12"],
        &["--timestep = 0.000000000001", "rows"],
    );
    // Without a trajectory the same fine step is only work, and is run.
    millimpact()
        .args([
            "run",
            case,
            "--method",
            "rk4",
            "--steps-per-period",
            "4000000",
        ])
        .assert()
        .success();
    let missing = dir.path().join("no-such-dir").join("t.csv");
    let out = millimpact()
        .args(["run", case, "--trajectory"])
        .arg(&missing)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("its directory does not exist"), "{stderr}");
    assert!(!dir.path().join("no-such-dir").exists());
    // The library refuses what the command line refuses.
    let c = common::shipped("ball_plate");
    for options in [
        millimpact::analysis::run::IntegrationOptions {
            method: Method::Rk4,
            steps_per_period: Some(1),
            ..Default::default()
        },
        millimpact::analysis::run::IntegrationOptions {
            method: Method::Dopri5,
            rtol: Some(1e-300),
            ..Default::default()
        },
    ] {
        assert!(options.settings(&c, false).is_err(), "{options:?}");
    }
}

/// A run outside its valid range says so on standard error and in the JSON, and still exits 0:
/// Hertz beyond small strain, a stubby rod, and a fixed step so coarse that the COR leaves
/// [0, 1].
#[test]
fn validity_warnings_go_to_stderr_and_the_json() {
    let dir = TempDir::new().unwrap();
    let soft = write(
        dir.path(),
        "soft.toml",
        &edit(
            BALL_PLATE,
            "youngs_modulus = 2.0e11\npoisson_ratio = 0.3\n\n[plate]",
            "youngs_modulus = 1.0e6\npoisson_ratio = 0.3\n\n[plate]",
        ),
    );
    let stubby = write(
        dir.path(),
        "stubby.toml",
        &edit(ROD, "length = 0.5", "length = 0.02"),
    );
    let steel = case_path("ball_plate");
    for (path, extra, expected) in [
        (&soft, &[][..], "beyond Hertz's small-strain range"),
        (&stubby, &[][..], "needs a rod of at least 5 diameters"),
        (
            &steel,
            &["--method", "verlet", "--timestep", "5.38e-5"][..],
            "outside [0, 1]",
        ),
    ] {
        let out = millimpact()
            .arg("run")
            .arg(path)
            .args(extra)
            .args(["--format", "json"])
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(0), "{stderr}");
        assert!(
            stderr.starts_with("warning: ") && stderr.contains(expected),
            "{stderr}"
        );
        let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        let warnings = json["warnings"].as_array().unwrap();
        assert_eq!(warnings.len(), 1, "{warnings:?}");
        assert!(warnings[0].as_str().unwrap().contains(expected));
    }
    // The shipped cases are inside every range: no warning.
    for name in ["ball_plate", "ball_ball", "rod_end"] {
        let out = millimpact()
            .arg("run")
            .arg(case_path(name))
            .output()
            .unwrap();
        assert!(out.status.success());
        assert!(
            out.stderr.is_empty(),
            "{name}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
    }
}

/// A value written as a TOML multi-line string (or a quoted key with a line break) is refused on
/// one line, its breaks written `\n` (the case reader's fuzz target found the break printed).
#[test]
fn a_value_with_line_breaks_is_refused_on_one_line() {
    let dir = TempDir::new().unwrap();
    let text = "scene = \"\"\"ball\nplate\"\"\"\nimpact_velocity = 2.0\nloss_coefficient = 0.35\n";
    let path = write(dir.path(), "multiline.toml", text);
    let file = path.display().to_string();
    rejected(
        dir.path(),
        &["run", &file],
        &[&file, "scene = \"ball\\nplate\""],
    );
}
