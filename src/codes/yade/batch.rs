//! YADE batches: many impacts in one process, in any scene. Impacts run side by side in one
//! scene, in groups of at most [`GROUP`] (one after another, `O.reset()` between groups), each
//! built as its single script builds it: the same materials, bodies, masses, velocities and
//! functors, its own wall, and the same rows recorded. What differs is only where it is: impact
//! `j` of a group is moved across the line of approach by `j` spacings, so every difference of
//! positions the contact reads is the single run's to the last bit (the coordinate across is the
//! same for both bodies of an impact, and a wall reads only the coordinate along its axis), and
//! each impact's bodies carry a mask bit of their own, so that a sphere meets its own wall only
//! (walls are infinite planes). A ball's restitution against its partner comes from a
//! `MatchMaker` keyed by their two materials. Each impact records the rows its single run
//! records (its own iterations, then its state after them), so it gives its single run's
//! trajectory to the last bit (tested for every scene).
//!
//! Side by side rather than one after another: YADE's start-up costs about a second and each
//! `O.step()` called from Python a fixed overhead, which impacts side by side share.
//!
//! Started lighter than a single run: YADE's launcher (`yade`, a Python script) loads the
//! library and then IPython for its interactive shell, builds the shell and opens its remote
//! prompts before it runs a script, even with `-x`. A batch is run by the launcher's own
//! Python instead ([`launcher_python`]: the interpreter and library folder the launcher names),
//! importing the same YADE library (`import yade`, with the launcher's one thread) without
//! IPython: about 0.7 s of CPU instead of 1.2 s. The same library runs the same steps: the
//! batch still equals its single runs, which the launcher runs, to the last bit (tested live).
//! A launcher that is not such a script (a wrapper, say) runs the batch itself.

use std::ffi::OsString;
use std::path::{Path, PathBuf};

use crate::codes::batch::parse_marked_batch;
use crate::codes::batch_fns::{BatchFns, check_batch_size};
use crate::codes::template::exact_number;
use crate::codes::yade::{Yade, script_input};
use crate::codes::{BatchError, CodeSetup, Executable, Launch, RenderedInput};
use crate::model::scene::SceneKind;

/// Most impacts in one batch.
pub(crate) const MAX_BATCH: usize = 256;

/// Impacts whose steps cost what one start of YADE does: the start (importing the library)
/// takes about 0.7 s of CPU, an impact of a ball scene at 200 steps per contact about 2 ms of
/// its batch (recording included), measured on the Debian build.
pub(crate) const IMPACTS_PER_START: usize = 350;

/// Most impacts side by side in one scene: each has a bit of the body mask (an `int`) to itself.
pub(crate) const GROUP: usize = 30;

/// The batch script.
pub(crate) const BATCH_SCRIPT: &str = "batch.py";

/// The batch script's start: YADE's library, loaded by the launcher or, run by its Python
/// alone, by the script.
pub(super) const PREAMBLE: &str = include_str!("preamble.py");

/// The batch script after its list of impacts and groups: the single script's scene, for each
/// impact of a group at once.
const SCRIPT: &str = include_str!("batch.py");

/// The impacts' groups: consecutive impacts of one scene and one time step, at most [`GROUP`]
/// each.
pub(crate) fn groups(setups: &[CodeSetup]) -> Vec<Vec<usize>> {
    let mut groups: Vec<Vec<usize>> = Vec::new();
    for (i, s) in setups.iter().enumerate() {
        let joins = groups.last().is_some_and(|g| {
            let first = &setups[g[0]];
            g.len() < GROUP
                && first.scene == s.scene
                && first.timestep.to_bits() == s.timestep.to_bits()
        });
        match groups.last_mut() {
            Some(g) if joins => g.push(i),
            _ => groups.push(vec![i]),
        }
    }
    groups
}

/// The batch script for `setups`, or why they cannot run as one.
pub(crate) fn render_batch(setups: &[CodeSetup]) -> Result<RenderedInput, BatchError> {
    check_batch_size(setups, MAX_BATCH, "the batch script's size")?;
    let mut impacts = String::new();
    for s in setups {
        // The single script's values, as Python literals (the scene's name quoted); `en` for
        // the ball scenes only (a rod's contact is kn and cn: its inversion would be wasted).
        let mut values = Yade.script_values(s)?;
        if s.scene != SceneKind::RodEnd {
            values.push(("restitution", exact_number(Yade::input_restitution(s))));
        }
        let fields: Vec<String> = values
            .into_iter()
            .map(|(key, value)| match key {
                "scene" => format!("\"{key}\": \"{value}\""),
                _ => format!("\"{key}\": {value}"),
            })
            .collect();
        impacts += &format!("    {{{}}},\n", fields.join(", "));
    }
    // Far enough apart that no two impacts' bodies ever meet (masks keep walls to their own).
    let reach = setups
        .iter()
        .map(|s| s.sphere.radius + s.other_sphere.map_or(0.0, |o| o.radius))
        .fold(0.0f64, f64::max);
    let groups: Vec<String> = groups(setups)
        .iter()
        .map(|g| {
            let ids: Vec<String> = g.iter().map(usize::to_string).collect();
            format!("[{}]", ids.join(", "))
        })
        .collect();
    let text = format!(
        "# millimpact: {} impacts in one YADE run, side by side in groups (src/codes/yade/batch.rs).\n{PREAMBLE}\nSPACING = {}\n# Each impact's values, as its single script is filled with them.\nIMPACTS = [\n{impacts}]\nGROUPS = [{}]\n{SCRIPT}",
        setups.len(),
        exact_number(8.0 * reach),
        groups.join(", "),
    );
    Ok(script_input(BATCH_SCRIPT, text))
}

/// YADE's launcher read as a Python script: the interpreter its first line names (with that
/// line's arguments) and the folder of YADE's Python library it puts on the module path
/// (`sys.path.insert(1,'…/py')`, as the Debian build and a build from source write it).
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct LauncherPython {
    /// The interpreter's program and its arguments from the `#!` line.
    pub interpreter: Vec<String>,
    /// The folder that holds the `yade` package.
    pub library: PathBuf,
}

/// The Python of the launcher at `launcher` and its library folder, if the launcher is such a
/// script and the folder holds the `yade` package; `None` otherwise (a wrapper, a binary).
pub(crate) fn launcher_python(launcher: &Path) -> Option<LauncherPython> {
    let text = std::fs::read(launcher).ok()?;
    let text = String::from_utf8_lossy(&text);
    let interpreter: Vec<String> = text
        .lines()
        .next()?
        .strip_prefix("#!")?
        .split_whitespace()
        .map(str::to_string)
        .collect();
    let looks_like_python = interpreter.iter().any(|word| {
        Path::new(word)
            .file_name()
            .and_then(|name| name.to_str())
            .is_some_and(|name| name.starts_with("python"))
    });
    if !looks_like_python {
        return None;
    }
    let library = text.lines().find_map(|line| {
        let inserted = line.trim().strip_prefix("sys.path.insert(1,")?;
        let quoted = inserted.trim().strip_suffix(')')?.trim();
        let folder = quoted
            .strip_prefix('\'')
            .and_then(|q| q.strip_suffix('\''))
            .or_else(|| quoted.strip_prefix('"').and_then(|q| q.strip_suffix('"')))?;
        Some(PathBuf::from(folder))
    })?;
    library
        .join("yade")
        .join("__init__.py")
        .is_file()
        .then_some(LauncherPython {
            interpreter,
            library,
        })
}

/// How the launcher at `executable` runs a batch `input`: by its Python with YADE's library
/// on the module path (first, as the launcher puts it) and the launcher's one thread, or by
/// the launcher itself when it is not a Python script that names its library.
pub(crate) fn launch(executable: Executable, input: &RenderedInput) -> Launch {
    let module_path = launcher_python(&executable.program).and_then(|python| {
        let mut folders = vec![python.library.clone()];
        folders.extend(
            std::env::var_os("PYTHONPATH")
                .map_or_else(Vec::new, |p| std::env::split_paths(&p).collect::<Vec<_>>()),
        );
        // A folder whose name holds the path separator cannot be put on the path.
        std::env::join_paths(folders)
            .ok()
            .map(|joined| (python, joined))
    });
    let Some((python, module_path)) = module_path else {
        return Launch {
            executable,
            args: input.args.clone(),
        };
    };
    let mut env = executable.env;
    // What `yade -j1` sets before it loads the library.
    env.push(("OMP_NUM_THREADS", OsString::from("1")));
    env.push(("PYTHONPATH", module_path));
    let mut words = python.interpreter.into_iter();
    let program = words.next().map(PathBuf::from).unwrap_or_default();
    let mut args: Vec<String> = words.collect();
    args.push(input.file_name.clone());
    Launch {
        executable: Executable { program, env },
        args,
    }
}

/// YADE's batches: many impacts in one process, side by side in groups.
pub(crate) static YADE_BATCH: BatchFns = BatchFns::new(MAX_BATCH, render_batch, parse_marked_batch)
    .costing(IMPACTS_PER_START)
    .launched_by(launch);

#[cfg(test)]
mod tests {
    use super::*;
    use crate::codes::CodeName;
    use crate::codes::batch::marked_trajectory_file as batch_trajectory_file;
    use crate::codes::setup::shipped_setup;

    #[test]
    fn groups_hold_one_scene_and_step_and_at_most_a_mask_each() {
        let mut setups: Vec<CodeSetup> = (0..65)
            .map(|i| shipped_setup(CodeName::Yade, "ball_plate", i as f64 / 100.0))
            .collect();
        setups.push(shipped_setup(CodeName::Yade, "rod_end", 0.3));
        setups.push(shipped_setup(CodeName::Yade, "rod_end", 0.4));
        let mut finer = shipped_setup(CodeName::Yade, "rod_end", 0.5);
        finer.timestep /= 2.0;
        setups.push(finer);
        let g = groups(&setups);
        let sizes: Vec<usize> = g.iter().map(Vec::len).collect();
        assert_eq!(sizes, [30, 30, 5, 2, 1]);
        assert_eq!(g.concat(), (0..setups.len()).collect::<Vec<_>>());
    }

    #[test]
    fn the_script_lists_each_impact_with_its_single_scripts_values() {
        let setups = [
            shipped_setup(CodeName::Yade, "ball_ball", 0.1),
            shipped_setup(CodeName::Yade, "ball_ball", 0.7),
        ];
        let text = render_batch(&setups).unwrap().text;
        for s in &setups {
            let mut values = Yade.script_values(s).unwrap();
            values.push(("restitution", exact_number(Yade::input_restitution(s))));
            for (key, value) in values {
                let cell = match key {
                    "scene" => format!("\"{key}\": \"{value}\""),
                    _ => format!("\"{key}\": {value}"),
                };
                assert!(text.contains(&cell), "{cell}");
            }
        }
        assert!(text.contains("GROUPS = [[0, 1]]"));
        // A rod's contact is kn and cn: its `en` is not inverted for a batch.
        let rod = render_batch(&[shipped_setup(CodeName::Yade, "rod_end", 0.3)])
            .unwrap()
            .text;
        assert!(!rod.contains("\"restitution\": "), "{rod}");
    }

    #[test]
    fn each_impact_reads_its_own_loop_time() {
        let dir = tempfile::tempdir().unwrap();
        let setups = [
            shipped_setup(CodeName::Yade, "rod_end", 0.1),
            shipped_setup(CodeName::Yade, "rod_end", 0.2),
        ];
        for i in 0..2 {
            std::fs::write(
                dir.path().join(batch_trajectory_file(i)),
                "iter,time,overlap,approach_velocity,normal_force\n0,0.0,0.0,1.0,0.0\n1,1e-6,1e-6,1.0,2.0\n",
            )
            .unwrap();
        }
        let log = "MILLIMPACT version=2023.02a\nMILLIMPACT impact=1 loop_time=0.25\nMILLIMPACT impact=2 loop_time=0.5\n";
        let runs = parse_marked_batch(&setups, dir.path(), log);
        let times: Vec<Option<f64>> = runs.iter().map(|r| r.as_ref().unwrap().loop_time).collect();
        assert_eq!(times, [Some(0.25), Some(0.5)]);
        assert_eq!(
            runs[0].as_ref().unwrap().version.as_deref(),
            Some("2023.02a")
        );
    }

    /// A launcher as YADE's build writes it, in `dir`, naming `library` as its module folder.
    fn launcher(dir: &Path, first_line: &str, library: &Path) -> PathBuf {
        let path = dir.join("yade-double");
        std::fs::write(
            &path,
            format!(
                "{first_line}\n# encoding: utf-8\nimport sys,os\n\nsys.path.insert(1,'{}')\n",
                library.display()
            ),
        )
        .unwrap();
        path
    }

    fn library_in(dir: &Path) -> PathBuf {
        let library = dir.join("py");
        std::fs::create_dir_all(library.join("yade")).unwrap();
        std::fs::write(library.join("yade").join("__init__.py"), "").unwrap();
        library
    }

    #[test]
    fn a_python_launcher_names_its_interpreter_and_library() {
        let dir = tempfile::tempdir().unwrap();
        let library = library_in(dir.path());
        let found = launcher_python(&launcher(dir.path(), "#!/usr/bin/python3.11", &library));
        assert_eq!(
            found,
            Some(LauncherPython {
                interpreter: vec!["/usr/bin/python3.11".into()],
                library: library.clone(),
            })
        );
        let through_env =
            launcher_python(&launcher(dir.path(), "#!/usr/bin/env python3", &library));
        assert_eq!(
            through_env.map(|p| p.interpreter),
            Some(vec!["/usr/bin/env".to_string(), "python3".to_string()])
        );
    }

    #[test]
    fn what_is_not_such_a_launcher_names_nothing() {
        let dir = tempfile::tempdir().unwrap();
        let library = library_in(dir.path());
        // A wrapper, a launcher whose library folder holds no `yade`, a missing file.
        assert_eq!(
            launcher_python(&launcher(dir.path(), "#!/bin/sh", &library)),
            None
        );
        let empty = dir.path().join("empty");
        std::fs::create_dir_all(&empty).unwrap();
        assert_eq!(
            launcher_python(&launcher(dir.path(), "#!/usr/bin/python3", &empty)),
            None
        );
        let wrapper = dir.path().join("wrapper");
        std::fs::write(
            &wrapper,
            "#!/usr/bin/python3\nimport os\nos.execvp('yade', ['yade'])\n",
        )
        .unwrap();
        assert_eq!(launcher_python(&wrapper), None);
        assert_eq!(launcher_python(&dir.path().join("absent")), None);
    }

    #[test]
    fn a_batch_runs_by_the_launcher_s_python_or_else_by_the_launcher() {
        let dir = tempfile::tempdir().unwrap();
        let library = library_in(dir.path());
        let input = render_batch(&[
            shipped_setup(CodeName::Yade, "rod_end", 0.3),
            shipped_setup(CodeName::Yade, "rod_end", 0.4),
        ])
        .unwrap();
        let python = launch(
            Executable::plain(launcher(dir.path(), "#!/usr/bin/python3.11", &library)),
            &input,
        );
        assert_eq!(python.executable.program, Path::new("/usr/bin/python3.11"));
        assert_eq!(python.args, [BATCH_SCRIPT]);
        let env: std::collections::HashMap<_, _> = python.executable.env.iter().cloned().collect();
        assert_eq!(env["OMP_NUM_THREADS"], "1");
        let module_path: Vec<PathBuf> = std::env::split_paths(&env["PYTHONPATH"]).collect();
        assert_eq!(module_path.first(), Some(&library));
        // Not a Python launcher: the launcher itself, with the launcher's arguments.
        let wrapper = Executable::plain(launcher(dir.path(), "#!/bin/sh", &library));
        let itself = launch(wrapper.clone(), &input);
        assert_eq!(itself.executable, wrapper);
        assert_eq!(itself.args, ["-j1", "-n", "-x", BATCH_SCRIPT]);
    }
}
