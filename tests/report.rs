//! `millimpact report` from the stored references: written in under a minute, every figure
//! present, and (live: it needs Chromium) the page opens in headless Chromium with no console
//! error, no broken image and no missing figure.

use std::path::Path;
use std::process::Command;

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
    let run = command
        .current_dir(root)
        .args(["report", "--out"])
        .arg(out.path())
        .output()
        .unwrap();
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
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
        let series = format!("{code} (stored run)");
        assert!(
            csv::Reader::from_reader(work_precision.as_bytes())
                .records()
                .any(|r| r.is_ok_and(|r| r.get(0) == Some(series.as_str()))),
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
    // The tangential half: a row per stored oblique run, each build that runs one named.
    let tangential = std::fs::read_to_string(out.path().join("tangential.csv")).unwrap();
    let rows = tangential.lines().count() - 1;
    let stored: usize = std::fs::read_dir(root.join("reference/oblique"))
        .unwrap()
        .map(|d| {
            std::fs::read_dir(d.unwrap().path())
                .unwrap()
                .filter(|f| {
                    f.as_ref()
                        .unwrap()
                        .path()
                        .extension()
                        .is_some_and(|e| e == "json")
                })
                .count()
        })
        .sum();
    assert_eq!(rows, stored, "{tangential}");
    for code in millimpact::codes::CodeName::oblique_builds() {
        assert!(
            csv::Reader::from_reader(tangential.as_bytes())
                .records()
                .any(|r| r
                    .is_ok_and(|r| r.get(0).is_some_and(|b| b.starts_with(&format!("{code} "))))),
            "no {code} row: {tangential}"
        );
    }
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

/// `report CASE --out DIR` run from `cwd`, as on a machine without the codes (a report that
/// is written needs the project's root as `cwd`, where it finds its canonical cases).
fn report_into(cwd: &Path, out: &Path) -> std::process::Output {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    assert_cmd::Command::cargo_bin("millimpact")
        .unwrap()
        .envs(common::codes_hidden())
        .current_dir(cwd)
        .arg("report")
        .arg(root.join("cases/ball_plate.toml"))
        .arg("--reference")
        .arg(root.join("reference"))
        .arg("--out")
        .arg(out)
        .output()
        .unwrap()
}

/// The names in `dir`, hidden ones too, sorted.
fn names(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

#[test]
fn a_folder_of_someone_elses_files_is_refused_and_left_as_it_was() {
    let parent = tempfile::tempdir().unwrap();
    let theirs = parent.path().join("site");
    std::fs::create_dir(&theirs).unwrap();
    std::fs::write(theirs.join("index.html"), "<p>my own page</p>").unwrap();
    std::fs::write(theirs.join("notes.md"), "mine").unwrap();
    let run = report_into(parent.path(), &theirs);
    assert_eq!(run.status.code(), Some(2), "{run:?}");
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert_eq!(
        stderr,
        format!(
            "error: --out = {}: a folder that is not empty and holds no earlier report (no \
             .millimpact-report in it); name a new folder, or an empty one, or one an earlier \
             report wrote\n",
            theirs.display()
        )
    );
    assert_eq!(names(&theirs), ["index.html", "notes.md"]);
    assert_eq!(
        std::fs::read_to_string(theirs.join("index.html")).unwrap(),
        "<p>my own page</p>"
    );
    assert_eq!(names(parent.path()), ["site"], "nothing written beside it");
}

#[test]
fn an_earlier_report_is_replaced_whole() {
    let parent = tempfile::tempdir().unwrap();
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let out = parent.path().join("report");
    let first = report_into(root, &out);
    assert!(first.status.success(), "{first:?}");
    let written = names(&out);
    assert!(written.contains(&".millimpact-report".to_string()));
    assert!(written.contains(&"index.html".to_string()));
    // A file the earlier report had (a figure since dropped, say) does not survive.
    std::fs::write(out.join("figure-since-dropped.svg"), "<svg/>").unwrap();
    let second = report_into(root, &out);
    assert!(second.status.success(), "{second:?}");
    assert_eq!(names(&out), written);
    assert_eq!(names(parent.path()), ["report"], "no temporary folder left");
    // An empty folder is written into as a new one.
    let empty = parent.path().join("empty");
    std::fs::create_dir(&empty).unwrap();
    assert!(report_into(root, &empty).status.success());
    assert_eq!(names(&empty), written);
}

#[test]
fn out_dot_in_a_project_root_is_refused() {
    // A project's root as a user has it: its manifest, cases and sources.
    let project = tempfile::tempdir().unwrap();
    std::fs::write(
        project.path().join("Cargo.toml"),
        "[package]\nname = \"mine\"\n",
    )
    .unwrap();
    std::fs::create_dir(project.path().join("src")).unwrap();
    std::fs::write(project.path().join("src/main.rs"), "fn main() {}\n").unwrap();
    let before = names(project.path());
    for out in [".", "..", "src"] {
        let run = report_into(project.path(), Path::new(out));
        assert_eq!(run.status.code(), Some(2), "--out {out}: {run:?}");
        let stderr = String::from_utf8_lossy(&run.stderr);
        assert_eq!(stderr.lines().count(), 1, "{stderr}");
        assert!(
            stderr.starts_with(&format!("error: --out = {out}: ")),
            "{stderr}"
        );
        assert_eq!(
            names(project.path()),
            before,
            "--out {out}: nothing written"
        );
    }
    // Even when the working directory is an earlier report: it is not replaced from inside.
    let report = project.path().join("report");
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    assert!(report_into(root, &report).status.success());
    let run = report_into(&report, Path::new("."));
    assert_eq!(run.status.code(), Some(2), "{run:?}");
    assert!(
        String::from_utf8_lossy(&run.stderr).contains("the working directory"),
        "{run:?}"
    );
}
