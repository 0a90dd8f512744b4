//! What a reader keeps as it goes through a deck beside what the impact carries: the lines it
//! leaves out, by kind, said back to the user with where they stand.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use super::bodies::{AtomSyntax, Atoms};
use super::data::DataFile;
use super::{DeckError, SourceLine};
use crate::codes::script::{Command, check_si_units, checked_timestep, parse_number};

/// The lines of a deck the impacts leave out, by what they are (the mill's geometry, output,
/// the run itself), each kind with the file of its first line and the lines.
#[derive(Debug, Default)]
pub(crate) struct LeftOut(BTreeMap<String, (PathBuf, Vec<usize>)>);

impl LeftOut {
    /// Leave out the line `at`, of the kind `what`.
    pub(crate) fn leave_out(&mut self, what: &str, at: &SourceLine) {
        self.0
            .entry(what.to_string())
            .or_insert_with(|| (at.file.clone(), Vec::new()))
            .1
            .push(at.line);
    }

    /// One line per kind: `what: file:line,line,…`.
    pub(crate) fn lines(&self) -> Vec<String> {
        self.0
            .iter()
            .map(|(what, (file, lines))| {
                let lines: Vec<String> = lines.iter().map(usize::to_string).collect();
                format!("{what}: {}:{}", file.display(), lines.join(","))
            })
            .collect()
    }
}

/// The file word `k` of `c` names (`what`: a data file, a mesh file), found as the code finds
/// it where the user runs the deck from its own folder: beside the file of the line. A file
/// that is not there is refused at the line, as the code stops there.
pub(crate) fn named_file(c: &Command, k: usize, what: &str) -> Result<PathBuf, DeckError> {
    let name = c.word(k, what)?;
    let path = if Path::new(name).is_absolute() {
        PathBuf::from(name)
    } else {
        c.at.file.parent().unwrap_or(Path::new(".")).join(name)
    };
    if path.is_file() {
        Ok(path)
    } else {
        Err(DeckError::missing(&c.at, what, name, &path))
    }
}

/// Every line of a script the check cannot honour, found in one pass, as one error: the
/// units' refusal first (a deck in other units is refused whatever else it holds), then the
/// lines in the order the code reads them (`read`: the lines the reader could not read, each
/// with the number of commands before it; `taken`: the commands it could not take, each with
/// its index among the commands).
pub(crate) fn every_refusal(
    units: Option<DeckError>,
    read: Vec<(usize, DeckError)>,
    taken: Vec<(usize, DeckError)>,
) -> Result<(), DeckError> {
    // A line that could not be read comes before the command at its place: (place, 0) sorts
    // before (place, 1).
    let mut all: Vec<((usize, u8), DeckError)> = read
        .into_iter()
        .map(|(k, e)| ((k, 0), e))
        .chain(taken.into_iter().map(|(k, e)| ((k, 1), e)))
        .collect();
    all.sort_by_key(|(k, _)| *k);
    DeckError::all(
        units
            .into_iter()
            .chain(all.into_iter().map(|(_, e)| e))
            .collect(),
    )
}

/// A script's text with the text of the files its `include` lines name (found beside the
/// including file, as the reader finds them; three levels deep, unreadable ones skipped):
/// what tells whose deck it is may stand in an included file.
pub(crate) fn with_includes(path: &Path, text: &str) -> String {
    fn gather(path: &Path, text: &str, depth: usize, all: &mut String) {
        all.push_str(text);
        all.push('\n');
        if depth == 0 {
            return;
        }
        for line in text.lines() {
            let mut words = line.split_whitespace();
            if words.next() == Some("include")
                && let Some(name) = words.next()
            {
                let included = path.parent().unwrap_or(Path::new(".")).join(name);
                if let Ok(inner) = std::fs::read_to_string(&included) {
                    gather(&included, &inner, depth - 1, all);
                }
            }
        }
    }
    let mut all = String::new();
    gather(path, text, 3, &mut all);
    all
}

/// The kind of left-out line of a script's neighbour, communication and domain settings.
pub(crate) const NEIGHBOURS: &str =
    "neighbour lists, communication and domain settings (the impact sets its own)";

/// The kind of left-out line of a script's output and flow control.
pub(crate) const OUTPUT: &str = "output and control";

/// What a reader of a LAMMPS-family script (LAMMPS, LIGGGHTS) gathers from the commands the
/// two read alike: the units, the box's types, the time step, the atoms and the lines left out.
#[derive(Debug, Default)]
pub(crate) struct ScriptReading {
    /// The `units` line.
    pub units: Option<Command>,
    /// The number of atom types `create_box` declares.
    pub types: Option<u32>,
    /// The time step, s, and where it is set.
    pub timestep: Option<(f64, SourceLine)>,
    /// The atoms the script makes.
    pub atoms: Atoms,
    /// The lines the impacts leave out.
    pub left_out: LeftOut,
    /// The deck's own impact speed, m/s, and what sets it (`velocity … set`, an insertion's
    /// `vel`): the first that gives a speed.
    pub impact_speed: Option<(f64, String)>,
}

impl ScriptReading {
    /// Read `c` where it is one of the commands both codes read alike; whether it was.
    pub(crate) fn command(&mut self, c: &Command, syntax: &AtomSyntax) -> Result<bool, DeckError> {
        match c.name() {
            "units" => self.units = Some(c.clone()),
            "create_box" => {
                let n = c.number(1, "the number of atom types")?;
                self.types = Some((syntax.whole)(n, c, "create_box")?);
            }
            "timestep" => self.timestep = Some((c.number(1, "the time step")?, c.at.clone())),
            "create_atoms" => {
                let t = (syntax.whole)(c.number(1, "the atom type")?, c, "type")?;
                let single = c.words.get(2).is_some_and(|w| w == "single");
                self.atoms.create(t, &c.at, single);
            }
            // The speed a deck gives its particles is its impacts' speed; the line is the
            // dialect's to leave out.
            "velocity" => {
                if c.words.get(2).is_some_and(|w| w == "set") {
                    self.speed_of(c, 3, "velocity set");
                }
                return Ok(false);
            }
            // The group is known for a later `set group`; the line is the dialect's to leave out.
            "group" => {
                self.atoms.group(c);
                return Ok(false);
            }
            "set" => {
                if !self.atoms.set(c, syntax)? {
                    self.leave_out("set commands on groups or regions", c);
                }
            }
            "read_data" => {
                let path = named_file(c, 1, "data file")?;
                let data = DataFile::read(&path, &c.at)?;
                if let Some(n) = data.types {
                    self.types = Some(n);
                }
                let append = c.words.iter().any(|w| w == "add");
                self.atoms.read_data(&data.atoms, &c.at, append);
                self.leave_out(
                    "the data file's positions and box (its atoms' sizes are read)",
                    c,
                );
            }
            "read_restart" | "read_dump" => {
                named_file(c, 1, "data file")?;
                self.leave_out(
                "particles read from a file (give their sizes with --particle TYPE:RADIUS:DENSITY)",
                c,
                );
            }
            "run" | "rerun" | "minimize" => self.leave_out("the run itself", c),
            "neighbor" | "neigh_modify" | "comm_modify" | "newton" | "processors" | "boundary"
            | "atom_modify" | "balance" => self.leave_out(NEIGHBOURS, c),
            "dump" | "dump_modify" | "undump" | "thermo" | "thermo_style" | "thermo_modify"
            | "compute" | "compute_modify" | "uncompute" | "print" | "write_restart"
            | "restart" | "write_data" | "write_dump" | "echo" | "log" | "shell" | "label"
            | "jump" | "next" | "if" | "clear" | "quit" => self.leave_out(OUTPUT, c),
            _ => return Ok(false),
        }
        Ok(true)
    }

    /// The speed `vx vy vz` at `c.words[k..k + 3]` gives (a `NULL` or a variable the code
    /// evaluates at run time adds nothing), kept as the deck's impact speed (`what` sets it)
    /// where none is yet and it is not zero.
    pub(crate) fn speed_of(&mut self, c: &Command, k: usize, what: &str) {
        if self.impact_speed.is_some() {
            return;
        }
        let speed = (k..k + 3)
            .filter_map(|j| c.words.get(j).and_then(|w| parse_number(w)))
            .map(|x| x * x)
            .sum::<f64>()
            .sqrt();
        if speed > 0.0 && speed.is_finite() {
            self.impact_speed = Some((speed, format!("{what} ({})", c.at)));
        }
    }

    /// The error of a command the code's reader does not take (`supported`: those it does).
    pub(crate) fn unknown(c: &Command, supported: &str) -> DeckError {
        c.refuse(format!("command `{}`", c.name()), supported)
    }

    /// Leave out the command `c`, of the kind `what`.
    pub(crate) fn leave_out(&mut self, what: &str, c: &Command) {
        self.left_out.leave_out(what, &c.at);
    }

    /// The number of atom types and the time step with where it is set, once the units are
    /// checked to be SI (`code`: whose default they are otherwise); what lacks is refused.
    pub(crate) fn checked(
        &self,
        path: &Path,
        code: &str,
    ) -> Result<(u32, f64, SourceLine), DeckError> {
        check_si_units(self.units.as_ref(), path, code)?;
        let types = self.types.ok_or_else(|| {
            DeckError::lacking(
                path,
                "no create_box (the number of atom types)",
                "create_box N REGION",
            )
        })?;
        let (timestep, at) = checked_timestep(self.timestep.as_ref(), path)?;
        Ok((types, timestep, at))
    }
}
