//! The mill's part of the report (`report --mill DECK`) without a code: drawn from the runs
//! recorded in `tests/data/mill/` (snapshot of the part as the pages render it, its data files
//! as `mill` exports them), and the book's figures of the example mill drawn from its stored
//! run, `examples/mill/stored-run.json` (what `millimpact mill examples/mill/in.mill --format
//! json` printed; the live tier checks a fresh run gives the same).

mod common;

use common::mill::{EXAMPLE, recorded};
use common::{codes_hidden, millimpact, root};
use millimpact::analysis::mill::MillReport;
use millimpact::analysis::report::{Report, mill_part};
use millimpact::codes::CodeName;
use millimpact::codes::liggghts::mill::MillLaw;
use millimpact::output::report_page::render_pages;
use millimpact::output::{Format, export};

fn page(part: millimpact::analysis::report::ReportPart) -> String {
    let report = Report {
        title: "report".into(),
        parts: vec![part],
        appendix: vec![],
        data: vec![],
        failures: vec![],
    };
    render_pages(&report).unwrap().1
}

#[test]
fn the_mill_part_has_power_spectra_and_profile_figures_and_the_mills_tables() {
    let mill = recorded();
    assert_eq!(
        mill.reproduce,
        "millimpact mill examples/mill/in.mill --time 0.05 --spectra-time 0.0003 --contact-every 10"
    );
    let (part, data) = mill_part(1, &mill).unwrap();
    let figures: Vec<&str> = part.figures.iter().map(|f| f.id.as_str()).collect();
    assert_eq!(
        figures,
        [
            "mill-1-power",
            "mill-1-impact-energy",
            "mill-1-peak-force",
            "mill-1-charge"
        ]
    );
    let tables: Vec<&str> = part.tables.iter().map(|t| t.id.as_str()).collect();
    assert_eq!(tables, ["mill-1-figures", "mill-1-spectra", "mill-1-runs"]);
    for f in &part.figures {
        assert_eq!(f.command, mill.reproduce);
        assert!(f.svg.starts_with("<svg"), "{}", f.id);
    }
    // The power figure holds, per run, both routes at every stretch of the trace that has them.
    let power = &part.figures[0].csv;
    for law in ["hertz (liggghts)", "paper (liggghts-paper)"] {
        for route in ["torque on the meshes", "the weight's torque"] {
            let rows = power
                .lines()
                .filter(|l| l.starts_with(&format!("{law}: {route},")))
                .count();
            assert!(rows > 10, "{law}: {route}: {rows} rows\n{power}");
        }
    }
    // The spectra figures sum the table's bins: between particles and against the liner.
    let energy = &part.figures[1].csv;
    let total = |liner: bool, law: &str| -> f64 {
        energy
            .lines()
            .filter(|l| l.contains(law) && l.contains("against the liner") == liner)
            .map(|l| l.rsplit(',').next().unwrap().parse::<f64>().unwrap())
            .sum()
    };
    let from_table = |liner: bool| -> f64 {
        mill.spectra
            .iter()
            .filter(|s| s.spectrum == "impact_energy" && s.pair.ends_with("-wall") == liner)
            .map(|s| s.written.mean)
            .sum()
    };
    for liner in [false, true] {
        let (drawn, table) = (total(liner, "model hertz"), from_table(liner));
        assert!(
            (drawn - table).abs() <= 1e-9 * table && table > 0.0,
            "{drawn} {table}"
        );
    }
    // The profile: every particle of each law's run, and the circle through the outermost.
    let charge = &part.figures[3].csv;
    for (law, run) in [
        ("model hertz", &mill.runs[0]),
        ("model paper", &mill.runs[1]),
    ] {
        let rows = charge.lines().filter(|l| l.starts_with(law)).count();
        assert_eq!(rows, run.profile.len());
        assert_eq!(rows, 100, "the example's 100 balls");
    }
    let names: Vec<&str> = data.iter().map(|d| d.name.as_str()).collect();
    assert_eq!(names, ["mill-1.json", "mill-1.csv"]);
    assert_eq!(data[0].text, export(&mill, Format::Json).unwrap());
    assert_eq!(data[1].text, export(&mill, Format::Csv).unwrap());
    insta::assert_snapshot!("mill_report_part", page(part));
}

#[test]
fn the_report_refuses_a_bad_mill_option_before_any_work() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("report");
    for (args, says) in [
        (
            &["--mill-seeds", "17"][..],
            "--mill-seeds = 17: examples/mill/in.mill: 1 to 16 runs per law",
        ),
        (
            &["--mill-time", "5"][..],
            "--mill-time = 5: examples/mill/in.mill: a rotation time",
        ),
    ] {
        let output = millimpact()
            .envs(codes_hidden())
            .current_dir(root())
            .args(["report", "cases/ball_plate.toml", "--mill", EXAMPLE])
            .args(args)
            .arg("--out")
            .arg(&out)
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert_eq!(output.status.code(), Some(2), "{stderr}");
        assert_eq!(stderr.lines().count(), 1, "{stderr}");
        assert!(stderr.contains(says), "{stderr}");
        assert!(!out.exists(), "no report written");
    }
    // A deck that is not a mill: the mill's own refusal.
    let output = millimpact()
        .envs(codes_hidden())
        .current_dir(root())
        .args([
            "report",
            "cases/ball_plate.toml",
            "--mill",
            "tests/data/deck/liggghts-no-friction.in",
        ])
        .arg("--out")
        .arg(&out)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(2), "{stderr}");
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(stderr.contains("rotate"), "{stderr}");
    assert!(!out.exists());
}

/// The example mill's stored run, as `millimpact mill examples/mill/in.mill --format json`
/// printed it.
fn stored_example() -> MillReport {
    let path = root().join("examples/mill/stored-run.json");
    serde_json::from_str(&std::fs::read_to_string(&path).unwrap())
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// The book's figures of the example mill are the report's, drawn from its stored run; the
/// book's table of that run is its Markdown export.
#[test]
fn the_books_mill_figures_are_drawn_from_the_stored_example_run() {
    let mill = stored_example();
    assert_eq!(mill.reproduce, "millimpact mill examples/mill/in.mill");
    assert_eq!(mill.written_law, MillLaw::Hertz);
    assert_eq!(mill.runs[0].code, CodeName::Liggghts.name());
    let (part, _) = mill_part(1, &mill).unwrap();
    let update = std::env::var_os("UPDATE_BOOK").is_some();
    for f in &part.figures {
        let path = root().join(format!("docs/src/figures/{}.svg", f.id));
        if std::fs::read_to_string(&path).ok().as_deref() == Some(f.svg.as_str()) {
            continue;
        }
        assert!(
            update,
            "{} differs from what `millimpact report --mill examples/mill/in.mill` draws from examples/mill/stored-run.json; rerun with UPDATE_BOOK=1 and review it",
            path.display()
        );
        std::fs::write(&path, &f.svg).unwrap();
    }
    let table = export(&mill, Format::Markdown).unwrap();
    let page_path = root().join("docs/src/commands/mill.md");
    let page = std::fs::read_to_string(&page_path).unwrap();
    let (start, end) = (
        "<!-- mill example: begin -->\n",
        "<!-- mill example: end -->",
    );
    let from = page.find(start).expect("the example's begin marker") + start.len();
    let to = page.find(end).expect("the example's end marker");
    if page[from..to] != table {
        assert!(
            update,
            "docs/src/commands/mill.md: the example's table is not the stored run's; rerun with UPDATE_BOOK=1"
        );
        std::fs::write(
            &page_path,
            format!("{}{table}{}", &page[..from], &page[to..]),
        )
        .unwrap();
    }
}

/// The spectra's note names the wall fix LIGGGHTS records only where the spectra have wall
/// rows: a mill whose wall spectra were left out (its mesh walls come after its first run) says
/// nothing of a wall it did not record.
#[test]
fn the_spectra_note_names_the_wall_only_where_wall_rows_are() {
    let mut mill = stored_example();
    let wall_note = "the wall is the last mesh wall/gran fix";
    assert!(mill.spectra.iter().any(|s| s.pair.ends_with("-wall")));
    assert!(export(&mill, Format::Table).unwrap().contains(wall_note));
    mill.spectra.retain(|s| !s.pair.ends_with("-wall"));
    assert!(!mill.spectra.is_empty());
    assert!(!export(&mill, Format::Table).unwrap().contains(wall_note));
}
