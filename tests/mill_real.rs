//! `millimpact mill` on what real decks contain, read and rendered with no code started: what
//! only observes (an atom-style variable, a compute that reduces it, a `thermo_style` that
//! prints it) left as written; the particle–wall spectra left out where LIGGGHTS cannot record
//! them (no mesh `wall/gran` fix before the first run); `run N upto` as LIGGGHTS reads it; a
//! move before the rotation run as written; `model hooke` refused for the reason it cannot be
//! switched.

mod common;

use std::path::{Path, PathBuf};

use common::mill::{EXAMPLE, small_plan};
use common::{codes_hidden, millimpact, root};
use millimpact::codes::liggghts::mill::{MillDeck, MillLaw};

/// A copy of the example in a fresh folder, `edit` applied to its deck.
fn edited(edit: impl Fn(String) -> String) -> (tempfile::TempDir, PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir(dir.path().join("meshes")).unwrap();
    std::fs::copy(
        root().join("examples/mill/meshes/drum.stl"),
        dir.path().join("meshes/drum.stl"),
    )
    .unwrap();
    let text = std::fs::read_to_string(root().join(EXAMPLE)).unwrap();
    let path = dir.path().join("in.mill");
    let changed = edit(text.clone());
    assert_ne!(changed, text, "the edit changed nothing");
    std::fs::write(&path, changed).unwrap();
    (dir, path)
}

/// Run `mill` with no code findable; require exit 2, nothing on stdout and one line on
/// stderr holding every piece of `expected`.
fn refused(path: &Path, expected: &[&str]) {
    let output = millimpact()
        .arg("mill")
        .arg(path)
        .envs(codes_hidden())
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(2), "{stderr}");
    assert!(output.stdout.is_empty());
    assert_eq!(stderr.trim().lines().count(), 1, "{stderr}");
    for piece in expected {
        assert!(stderr.contains(piece), "`{piece}` not in {stderr}");
    }
}

fn read(path: &Path) -> MillDeck {
    MillDeck::read(path).unwrap_or_else(|e| panic!("{e}"))
}

/// The index of the first rendered line that starts with `start`.
fn position(lines: &[&str], start: &str) -> usize {
    lines
        .iter()
        .position(|l| l.starts_with(start))
        .unwrap_or_else(|| panic!("no line starting `{start}`"))
}

const WATCHING: [&str; 3] = [
    "variable        pe atom mass*9.81*z",
    "compute         pe all reduce sum v_pe",
    "thermo_style    custom step atoms ke c_rke c_pe",
];

#[test]
fn a_deck_that_watches_its_charges_potential_energy_is_read_and_its_watch_kept() {
    let (_dir, path) = edited(|t| {
        t.replace(
            "thermo_style    custom step atoms ke c_rke\n",
            &(WATCHING.join("\n") + "\n"),
        )
    });
    let deck = read(&path);
    assert_eq!(deck.rotation_steps, 600_000);
    for law in [MillLaw::Hertz, MillLaw::Paper] {
        let text = deck.render(law, &small_plan());
        let lines: Vec<&str> = text.lines().collect();
        for watch in WATCHING {
            assert!(lines.contains(&watch), "{law}: `{watch}` not kept");
        }
        // In the order written, before the first run.
        let run = position(&lines, "run");
        assert!(position(&lines, "variable        pe") < position(&lines, "compute         pe"));
        assert!(position(&lines, "thermo_style") < run);
    }
}

#[test]
fn a_running_variable_used_where_a_number_is_needed_is_still_refused() {
    let (_dir, path) = edited(|t| {
        t.replace(
            "timestep        1.5e-6",
            "variable        pe atom mass*9.81*z\ntimestep        ${pe}",
        )
    });
    refused(&path, &[&format!("{}:38", path.display()), "variable pe"]);
}

#[test]
fn a_mesh_wall_fix_only_after_the_first_run_leaves_the_wall_spectra_out() {
    // LIGGGHTS defines wall/gran/local only before the first run and only after a mesh
    // wall/gran fix: a deck whose mesh wall comes after its first run cannot have it.
    let wall = "fix             walls all wall/gran model hertz tangential history rolling_friction cdt mesh n_meshes 1 meshes drum\n";
    let (_dir, path) = edited(|t| {
        t.replace(wall, "").replace(
            "fix             integr all nve/sphere\n",
            &format!("fix             integr all nve/sphere\nrun             1\n{wall}"),
        )
    });
    let deck = read(&path);
    assert!(deck.recorded_wall_meshes.is_empty());
    assert!(
        deck.left_out.iter().any(|l| l
            .contains("particle–wall collision spectra of fix             walls")
            && l.contains(&format!("{}:53", path.display()))),
        "{:?}",
        deck.left_out
    );
    for law in [MillLaw::Hertz, MillLaw::Paper] {
        let text = deck.render(law, &small_plan());
        let lines: Vec<&str> = text.lines().collect();
        assert!(!text.contains("millimpact_walls"), "{law}: {text}");
        // The pairs' compute before the first run, the wall fix (switched) after it.
        let pairs = position(&lines, "compute millimpact_pairs all pair/gran/local");
        let first_run = position(&lines, "run");
        let fix = lines
            .iter()
            .position(|l| l.starts_with("fix") && l.contains(" walls all wall/gran "))
            .expect("the wall fix");
        assert!(pairs < first_run && first_run < fix, "{law}");
    }
    // The example's wall fix is before the first run: its compute stays beside the pairs'.
    let example = read(Path::new(EXAMPLE)).render(MillLaw::Hertz, &small_plan());
    let lines: Vec<&str> = example.lines().collect();
    assert_eq!(
        position(&lines, "compute millimpact_walls"),
        position(&lines, "compute millimpact_pairs") + 1
    );
}

#[test]
fn run_upto_runs_until_its_step() {
    let (_dir, path) = edited(|t| {
        t.replace("run             100000", "run             100000 upto")
            .replace("run             600000", "run             700000 upto")
    });
    let deck = read(&path);
    assert_eq!(deck.settling_steps, 100_000);
    assert_eq!(deck.rotation_steps, 600_000);
    let text = deck.render(MillLaw::Hertz, &small_plan());
    let runs: Vec<&str> = text.lines().filter(|l| l.starts_with("run")).collect();
    // The settling run as written; the rotation cut to the plan's 1000 steps.
    assert_eq!(runs, ["run             100000 upto", "run 800", "run 200"]);
    // Reset, the counter starts again.
    let (_dir, path) = edited(|t| {
        t.replace(
            "run             600000",
            "reset_timestep  0\nrun             250000 upto",
        )
    });
    assert_eq!(read(&path).rotation_steps, 250_000);
    // Before the step reached, LIGGGHTS stops.
    let (_dir, path) =
        edited(|t| t.replace("run             600000", "run             50000 upto"));
    refused(
        &path,
        &[
            &format!("{}:63", path.display()),
            "run 50000 upto at step 100000",
        ],
    );
}

#[test]
fn a_move_before_the_rotation_runs_as_written() {
    let shift = "fix             shift all move/mesh mesh drum linear 0. 0. 0.01\nrun             2000\nunfix           shift\n";
    let (_dir, path) = edited(|t| {
        t.replace(
            "\n# 75 % of the critical speed",
            &format!("\n{shift}# 75 % of the critical speed"),
        )
    });
    let deck = read(&path);
    assert_eq!(deck.settling_steps, 102_000);
    assert_eq!(deck.rotation_steps, 600_000);
    assert_eq!(deck.rotating.len(), 1);
    assert_eq!(deck.rotating[0].mesh, "drum");
    let text = deck.render(MillLaw::Paper, &small_plan());
    for line in shift.lines() {
        assert!(text.lines().any(|l| l == line), "`{line}` not as written");
    }
    // Still moving when the drum turns: its power would not be measured.
    let (_dir, path) = edited(|t| {
        t.replace(
            "\n# 75 % of the critical speed",
            "\nfix             shift all move/mesh mesh drum linear 0. 0. 0.01\n# 75 % of the critical speed",
        )
    });
    refused(
        &path,
        &[
            &format!("{}:61", path.display()),
            "move/mesh linear still moves its mesh",
            "unfix",
        ],
    );
}

#[test]
fn model_hooke_is_refused_for_its_linear_spring() {
    let (_dir, path) = edited(|t| {
        t.replace("model hertz", "model hooke").replace(
            "fix             m5",
            "fix             m6 all property/global characteristicVelocity scalar 1.0\nfix             m5",
        )
    });
    refused(
        &path,
        &[
            &format!("{}:35", path.display()),
            "model hooke: a linear spring",
            "characteristicVelocity",
        ],
    );
}
