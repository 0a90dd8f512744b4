//! A user's YADE script as YADE holds it after its set-up: the script run by YADE's own Python
//! (the launcher's interpreter, as a batch runs, `super::batch::launch`) in a scratch folder,
//! under a time limit, in its own process group, with everything that advances the simulation
//! disarmed (`read.py`), and what YADE then holds dumped as JSON and read here into typed
//! structs.
//!
//! The first call that would step the simulation (`O.run`, `O.step`, `O.wait`, `O.runEngine`)
//! ends the reading: the set-up up to that call is what is dumped, and the call's line is named.
//! `O.save` writes nothing. An exception of the script is the user's error, with YADE's own
//! message and the script's line.

use std::collections::BTreeMap;
use std::ffi::OsString;
use std::path::{Path, PathBuf};
use std::time::Duration;

use serde::Deserialize;

use super::Yade;
use crate::codes::deck::{DeckError, DeckSource, SourceLine};
use crate::codes::runner::process::{LOG_FILE, Process, Step};
use crate::codes::{CodeError, RenderedInput};

/// The dumper, run by YADE's Python.
const READER: &str = include_str!("read.py");

/// The dumper's file name in the scratch folder.
pub(crate) const READER_FILE: &str = "read.py";

/// The dump's file name in the scratch folder.
pub(crate) const DUMP_FILE: &str = "dump.json";

/// How long the set-up of a script may take before the reading is stopped, where no time limit
/// is given (`deck --timeout` gives one): a script's set-up (bodies made, packings generated)
/// takes seconds; one stuck in a loop of its own is ended.
pub const READ_TIME_LIMIT: Duration = Duration::from_secs(120);

/// The prefix of the line the dumper prints for an exception of the script.
const RAISED: &str = "MILLIMPACT raised line=";

/// What YADE holds after a script's set-up.
#[derive(Clone, Debug, Deserialize, PartialEq)]
pub struct Dump {
    /// YADE's version.
    pub version: String,
    /// The call that ended the reading, where one did.
    pub stopped: Option<Stopped>,
    /// The lines of the `O.save` calls, which wrote nothing.
    pub saved: Vec<Option<usize>>,
    /// `O.dt`, s.
    pub dt: Option<f64>,
    /// The line that last set `O.dt`, where the script set it.
    pub dt_line: Option<usize>,
    /// `O.dynDt`: whether a time stepper may change the step while the simulation runs.
    pub dyn_dt: bool,
    /// The line that last set `O.engines`.
    pub engines_line: Option<usize>,
    /// `O.materials`, in order of their ids.
    pub materials: Vec<MaterialDump>,
    /// `O.engines`, in order.
    pub engines: Vec<EngineDump>,
    /// `O.bodies`.
    pub bodies: Vec<BodyDump>,
}

/// The call that ended the reading.
#[derive(Clone, Debug, Deserialize, PartialEq)]
pub struct Stopped {
    /// `O.run`, `O.step`, `O.wait` or `O.runEngine`.
    pub call: String,
    /// Its line in the script.
    pub line: Option<usize>,
}

/// A material of `O.materials`.
#[derive(Clone, Debug, Deserialize, PartialEq)]
pub struct MaterialDump {
    /// Its id (its index in `O.materials`).
    pub id: i64,
    /// Its class (`FrictMat`, `ViscElMat`, …).
    pub class: String,
    /// Every attribute, after any edit of the set-up.
    pub attributes: BTreeMap<String, Attribute>,
    /// The attributes whose values differ from a fresh instance's (what the script set).
    pub changed: Vec<String>,
    /// Its attributes when it was appended, where `O.materials.append` appended it.
    pub appended: Option<BTreeMap<String, Attribute>>,
    /// The line that appended it.
    pub line: Option<usize>,
}

/// An engine of `O.engines`.
#[derive(Clone, Debug, Deserialize, PartialEq)]
pub struct EngineDump {
    /// Its class.
    pub class: String,
    /// Its attributes (none for an `InteractionLoop`, whose functors are listed instead).
    pub attributes: BTreeMap<String, Attribute>,
    /// The attributes whose values differ from a fresh instance's.
    pub changed: Vec<String>,
    /// An `InteractionLoop`'s functors.
    pub functors: Option<LoopFunctors>,
}

/// The three functor lists of an `InteractionLoop`.
#[derive(Clone, Debug, Deserialize, PartialEq)]
pub struct LoopFunctors {
    /// The `Ig2` functors.
    pub geometry: Vec<FunctorDump>,
    /// The `Ip2` functors.
    pub physics: Vec<FunctorDump>,
    /// The `Law2` functors.
    pub laws: Vec<FunctorDump>,
}

/// A functor.
#[derive(Clone, Debug, Deserialize, PartialEq)]
pub struct FunctorDump {
    /// Its class.
    pub class: String,
    /// Every attribute.
    pub attributes: BTreeMap<String, Attribute>,
    /// The attributes whose values differ from a fresh instance's.
    pub changed: Vec<String>,
    /// Each `MatchMaker` attribute evaluated for every ordered pair of material ids, as the
    /// functor evaluates it (`(*en)(mat1->id, mat2->id)`): `[id1, id2, value]`, `null` where
    /// YADE gives no number.
    pub per_pair: BTreeMap<String, Vec<(i64, i64, Option<f64>)>>,
}

/// A value YADE holds.
#[derive(Clone, Debug, Deserialize, PartialEq)]
#[serde(untagged)]
pub enum Attribute {
    /// `None`, or a number YADE leaves at NaN ("not given").
    Null,
    /// A flag.
    Flag(bool),
    /// A number.
    Number(f64),
    /// A string.
    Text(String),
    /// A list or a vector.
    List(Vec<Attribute>),
    /// A `MatchMaker`.
    MatchMaker {
        /// Its settings.
        match_maker: MatchMakerDump,
    },
    /// Any other object.
    Object {
        /// Its class and attributes.
        object: ObjectDump,
    },
}

/// A `MatchMaker`'s settings.
#[derive(Clone, Debug, Deserialize, PartialEq)]
pub struct MatchMakerDump {
    /// `(id1, id2, value)` triples.
    pub matches: Vec<Vec<Option<f64>>>,
    /// The fallback algorithm.
    pub algo: String,
    /// The fallback value of `algo='val'`.
    pub val: Option<f64>,
}

/// An object YADE holds, by its class.
#[derive(Clone, Debug, Deserialize, PartialEq)]
pub struct ObjectDump {
    /// Its class.
    pub class: String,
    /// Its attributes.
    pub attributes: BTreeMap<String, Attribute>,
}

/// A body of `O.bodies`.
#[derive(Clone, Debug, Deserialize, PartialEq)]
pub struct BodyDump {
    /// Its id.
    pub id: i64,
    /// Its shape's class (`Sphere`, `Wall`, `Facet`, `Box`, …).
    pub shape: Option<String>,
    /// Its material's id (−1 for a material not in `O.materials`).
    pub material: Option<i64>,
    /// Its mass, kg.
    pub mass: Option<f64>,
    /// Whether YADE moves it.
    pub dynamic: bool,
    /// Its blocked degrees of freedom.
    pub blocked: String,
    /// Whether it is a clump or a clump's member.
    pub clump: bool,
    /// The line that appended it.
    pub line: Option<usize>,
    /// A sphere's radius, m.
    pub radius: Option<f64>,
    /// A box's half-sizes, m.
    pub extents: Option<Vec<Option<f64>>>,
    /// A sphere's velocity as the set-up leaves it (`state.vel`), m/s; none in a dump of a
    /// reader that did not record it.
    #[serde(default)]
    pub vel: Option<Vec<Option<f64>>>,
}

impl Attribute {
    /// The number it holds.
    pub(crate) fn number(&self) -> Option<f64> {
        match self {
            Attribute::Number(x) => Some(*x),
            _ => None,
        }
    }
}

/// Read a dump's JSON text (of the script at `script`), naming the field that is not as the
/// dumper writes it.
pub fn parse_dump(script: &Path, text: &str) -> Result<Dump, DeckError> {
    let bad = |field: String, e: serde_json::Error| {
        DeckError::unsupported(
            DeckSource::field(script, field),
            format!("YADE's dump of the set-up does not read: {e}"),
            "the dump src/codes/yade/read.py writes",
        )
    };
    let value: serde_json::Value =
        serde_json::from_str(text).map_err(|e| bad("the dump".into(), e))?;
    // Section by section, then item by item, so that an error names its field's path.
    if let serde_json::Value::Object(fields) = &value {
        for (section, items) in fields {
            if let serde_json::Value::Array(items) = items {
                for (i, item) in items.iter().enumerate() {
                    let path = format!("{section}[{i}]");
                    let checked = match section.as_str() {
                        "materials" => MaterialDump::deserialize(item).map(drop),
                        "engines" => EngineDump::deserialize(item).map(drop),
                        "bodies" => BodyDump::deserialize(item).map(drop),
                        _ => Ok(()),
                    };
                    checked.map_err(|e| bad(path, e))?;
                }
            }
        }
    }
    Dump::deserialize(&value).map_err(|e| bad("the dump".into(), e))
}

/// Run the script at `path` in YADE up to the end of its set-up and return the dump's JSON
/// text. The script's own error is [`DeckError::Raised`]; YADE missing, crashing or past
/// `time_limit` is [`DeckError::Reader`].
pub fn dump_script(path: &Path, time_limit: Duration) -> Result<String, DeckError> {
    let fault = |source: CodeError| DeckError::Reader {
        path: path.to_path_buf(),
        code: "yade".into(),
        source: Box::new(source),
    };
    let executable = crate::codes::runner::locate(&Yade).map_err(fault)?;
    let script = std::fs::canonicalize(path).map_err(|source| DeckError::Read {
        path: path.to_path_buf(),
        source,
    })?;
    let script_arg = script.display().to_string();
    let input = RenderedInput {
        file_name: READER_FILE.into(),
        text: READER.into(),
        args: ["-j1", "-n", "-x", READER_FILE, &script_arg, DUMP_FILE]
            .map(String::from)
            .to_vec(),
    };
    let mut launch = super::batch::launch(executable, &input);
    if launch.args != input.args {
        // Run by the launcher's Python: the dumper's own arguments follow it.
        launch
            .args
            .extend([script_arg.clone(), DUMP_FILE.to_string()]);
    }
    let ran = Process::new(
        &launch.executable,
        &launch.args,
        (READER_FILE, READER),
        time_limit,
        "millimpact-yade-read-",
    )
    .linking(script_folder_links(&script))
    .run()
    .map_err(|e| {
        fault(e.code_error_saying("yade", |step| match step {
            Step::Input => Some("writing the reader"),
            Step::Start => Some("starting YADE"),
            Step::Wait => Some("waiting for YADE"),
            _ => None,
        }))
    })?;
    let Some(status) = ran.status else {
        return Err(fault(ran.timed_out("yade")));
    };
    let log = ran.log().map_err(|e| fault(e.code_error("yade")))?;
    if let Some((line, message)) = raised(&log) {
        let at = match line {
            Some(line) => DeckSource::Line(SourceLine {
                file: path.to_path_buf(),
                line,
            }),
            None => DeckSource::field(path, "(no line of the script)"),
        };
        return Err(DeckError::Raised {
            at,
            code: "yade".into(),
            message,
        });
    }
    if !status.success() {
        let said = log
            .lines()
            .rev()
            .find(|l| !l.trim().is_empty())
            .map(str::to_string);
        return Err(fault(ran.crashed("yade", status, said)));
    }
    match std::fs::read_to_string(ran.folder().join(DUMP_FILE)) {
        Ok(text) => Ok(text),
        Err(source) => Err(fault(ran.unparsable(
            "yade",
            crate::codes::ParseError::Read {
                path: PathBuf::from(DUMP_FILE),
                source,
            },
        ))),
    }
}

/// The script's line and YADE's message of the exception the dumper printed.
fn raised(log: &str) -> Option<(Option<usize>, String)> {
    log.lines().find_map(|l| {
        let rest = l.trim().strip_prefix(RAISED)?;
        let (line, message) = rest.split_once(' ').unwrap_or((rest, ""));
        Some((line.parse().ok(), message.trim().to_string()))
    })
}

/// Every entry of the script's folder, to be linked into the scratch folder (its name there,
/// what it leads to), so that the files the script reads by relative paths (meshes, packings)
/// are found while what it writes lands in the scratch folder. An entry that cannot be linked
/// is left out: the script then says which file it misses.
fn script_folder_links(script: &Path) -> Vec<(OsString, PathBuf)> {
    // A script named without a folder is in the working folder; the links must point at
    // absolute paths, since they are read from the scratch folder.
    let folder = match script.parent() {
        Some(parent) if !parent.as_os_str().is_empty() => parent,
        _ => Path::new("."),
    };
    let Ok(folder) = std::fs::canonicalize(folder) else {
        return Vec::new();
    };
    let Ok(entries) = std::fs::read_dir(&folder) else {
        return Vec::new();
    };
    entries
        .flatten()
        .map(|entry| (entry.file_name(), entry.path()))
        .filter(|(name, _)| {
            ![READER_FILE, DUMP_FILE, LOG_FILE]
                .iter()
                .any(|own| name == *own)
        })
        .collect()
}

/// The text of line `line` (from 1) of the script at `path`, trimmed, where it can be read.
pub(crate) fn line_text(path: &Path, line: usize) -> Option<String> {
    let text = std::fs::read_to_string(path).ok()?;
    text.lines()
        .nth(line.checked_sub(1)?)
        .map(|l| l.trim().to_string())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_exception_line_gives_its_line_and_yades_message() {
        let log = "Using python version: 3.11\nMILLIMPACT version=2023.02a\nMILLIMPACT raised line=7 NameError: name 'E' is not defined\n";
        assert_eq!(
            raised(log),
            Some((Some(7), "NameError: name 'E' is not defined".to_string()))
        );
        assert_eq!(raised("MILLIMPACT dumped\n"), None);
    }

    #[test]
    fn a_dump_field_that_does_not_read_is_named_by_its_path() {
        let text = r#"{"version": "x", "stopped": null, "saved": [], "dt": 1e-7, "dt_line": 3, "dyn_dt": false, "engines_line": null,
            "materials": [], "engines": [], "bodies": [{"id": 0, "shape": "Sphere", "material": "steel"}]}"#;
        let e = parse_dump(Path::new("s.py"), text).unwrap_err().to_string();
        assert!(e.starts_with("s.py: bodies[0]: "), "{e}");
    }

    /// The YADE scripts of `tests/data/deck/yade/` and the shipped example, each with the dump of
    /// its set-up `tests/deck_reading_yade.rs` reads.
    fn yade_scripts_with_dumps() -> Vec<(std::path::PathBuf, std::path::PathBuf)> {
        let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
        let data = root.join("tests/data/deck/yade");
        let mut pairs = vec![
            (
                root.join("examples/decks/yade-mill/mill.py"),
                data.join("mill.dump.json"),
            ),
            (
                root.join("tests/data/deck/yade-capillary.py"),
                data.join("capillary.dump.json"),
            ),
        ];
        let mut scripts: Vec<_> = std::fs::read_dir(&data)
            .unwrap()
            .map(|e| e.unwrap().path())
            .filter(|p| p.extension().is_some_and(|x| x == "py"))
            .collect();
        scripts.sort();
        for script in scripts {
            let dump = script.with_extension("dump.json");
            if dump.exists() || std::env::var_os("UPDATE_DECK_RUNS").is_some() {
                pairs.push((script, dump));
            }
        }
        pairs
    }

    /// The recorded dumps the fast tier reads are what YADE dumps of their scripts now;
    /// `UPDATE_DECK_RUNS=1` records them again (a script whose set-up YADE refuses has none).
    #[test]
    #[ignore = "live: runs the set-up of every YADE script of tests/data/deck/yade in YADE"]
    fn the_recorded_yade_dumps_are_what_yade_dumps_now() {
        let pairs = yade_scripts_with_dumps();
        assert!(pairs.len() > 10, "{pairs:?}");
        for (script, dump) in pairs {
            let live = match dump_script(&script, READ_TIME_LIMIT) {
                Ok(text) => text,
                Err(e) => {
                    // Only a script YADE cannot set up has no dump.
                    assert!(!dump.exists(), "{}: {e}", script.display());
                    continue;
                }
            };
            if std::env::var_os("UPDATE_DECK_RUNS").is_some() {
                std::fs::write(&dump, &live).unwrap();
            }
            let recorded = std::fs::read_to_string(&dump).unwrap();
            let (live, recorded) = (
                parse_dump(&script, &live).unwrap(),
                parse_dump(&script, &recorded).unwrap(),
            );
            // Part by part, so that a difference names its part.
            let at = script.display();
            assert_eq!(live.materials, recorded.materials, "{at}: materials");
            assert_eq!(live.engines, recorded.engines, "{at}: engines");
            assert_eq!(live.bodies, recorded.bodies, "{at}: bodies");
            assert_eq!(live, recorded, "{at}");
        }
    }
}
