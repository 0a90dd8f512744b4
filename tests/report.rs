//! `millimpact report` from the stored references: written in under a minute, every figure
//! present, and (live: it needs Chromium) the page opens in headless Chromium with no console
//! error, no broken image and no missing figure.

use std::path::Path;
use std::process::Command;
use std::time::Instant;

mod common;

fn chromium() -> &'static str {
    for name in ["chromium", "chromium-browser"] {
        if Command::new(name)
            .arg("--version")
            .output()
            .is_ok_and(|o| o.status.success())
        {
            return name;
        }
    }
    panic!("headless Chromium is needed (Debian package `chromium`; scripts/test.sh installs it)");
}

/// Write the report from the stored references into a new folder and check what it holds:
/// every figure inline with its SVG and CSV beside it, every code's stored run in the
/// work–precision diagram, every local link resolving. Returns the folder and the figures' ids.
/// With `codes_hidden`, `report` finds no DEM code (so probes none), as on a machine without
/// them; else it probes the installed LAMMPS builds for its cards.
fn write_and_check_the_report(codes_hidden: bool) -> (tempfile::TempDir, Vec<String>) {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let out = tempfile::tempdir().unwrap();
    let mut command = assert_cmd::Command::cargo_bin("millimpact").unwrap();
    if codes_hidden {
        command.envs(common::codes_hidden());
    }
    let started = Instant::now();
    let run = command
        .current_dir(root)
        .args(["report", "--out"])
        .arg(out.path())
        .output()
        .unwrap();
    let elapsed = started.elapsed().as_secs_f64();
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    assert!(elapsed < 60.0, "the report took {elapsed:.1} s");
    let html = std::fs::read_to_string(out.path().join("index.html")).unwrap();
    let md = std::fs::read_to_string(out.path().join("index.md")).unwrap();
    // Every figure is inline in the page, and its SVG and CSV are beside it.
    let ids: Vec<String> = html
        .split("<figure id=\"")
        .skip(1)
        .map(|s| s[..s.find('"').unwrap()].to_string())
        .collect();
    for expected in [
        "fig2-displacement",
        "fig2-velocity",
        "fig3-cor-vs-eta",
        "force-overlap-ball_plate",
        "force-time-rod_end",
        "model-by-e-ball_plate",
        "realised-vs-requested",
        "work-precision",
        "stability-map",
    ] {
        assert!(
            ids.iter().any(|id| id == expected),
            "figure {expected} missing"
        );
    }
    for id in &ids {
        let block = html.split(&format!("<figure id=\"{id}\"")).nth(1).unwrap();
        let block = &block[..block.find("</figure>").unwrap()];
        assert!(block.contains("<svg"), "{id}: no inline SVG");
        for ext in ["svg", "csv"] {
            assert!(
                out.path().join(format!("{id}.{ext}")).is_file(),
                "{id}.{ext}"
            );
        }
        assert!(md.contains(&format!("({id}.svg)")), "index.md lacks {id}");
    }
    // The work–precision diagram has a point for every registered code's stored run, beside the
    // methods' sweeps.
    let work_precision = std::fs::read_to_string(out.path().join("work-precision.csv")).unwrap();
    for code in millimpact::codes::CodeName::names() {
        assert!(
            work_precision.contains(&format!("\"{code} (stored run)\"")),
            "no {code} point in work-precision.csv"
        );
    }
    // Every local link resolves; nothing is fetched from the network.
    for link in html
        .split("href=\"")
        .skip(1)
        .map(|s| &s[..s.find('"').unwrap()])
    {
        if link.starts_with('#') {
            continue;
        }
        assert!(!link.contains("://"), "network link {link}");
        assert!(out.path().join(link).is_file(), "broken link {link}");
    }
    assert!(!html.contains("<img"), "figures are inline, not images");
    (out, ids)
}

/// The fast tier's report: written without the codes (the LAMMPS builds are not probed).
#[test]
fn the_report_is_written_with_every_figure() {
    write_and_check_the_report(true);
}

#[test]
#[ignore = "live: needs Chromium, probes LAMMPS and LAMMPS 2025 (bash scripts/test.sh)"]
fn the_report_opens_in_a_browser_with_every_figure() {
    let (out, ids) = write_and_check_the_report(false);
    let profile = tempfile::tempdir().unwrap();
    let page = format!("file://{}", out.path().join("index.html").display());
    let browser = Command::new(chromium())
        .args([
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--disable-background-networking",
            "--disable-component-update",
            "--no-first-run",
            "--enable-logging=stderr",
            "--v=0",
        ])
        .arg(format!("--user-data-dir={}", profile.path().display()))
        .arg("--dump-dom")
        .arg(&page)
        .output()
        .unwrap();
    assert!(browser.status.success());
    let dom = String::from_utf8_lossy(&browser.stdout);
    let log = String::from_utf8_lossy(&browser.stderr);
    let console: Vec<&str> = log
        .lines()
        .filter(|l| l.contains("CONSOLE") || l.contains("Uncaught"))
        .collect();
    assert!(console.is_empty(), "console errors: {console:?}");
    assert_eq!(
        dom.matches("class=\"report-figure\"").count(),
        ids.len(),
        "the browser's DOM holds every figure"
    );
    assert!(
        dom.matches("<svg").count() >= ids.len(),
        "every figure drawn"
    );
}
