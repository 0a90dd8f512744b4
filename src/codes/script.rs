//! The input language LIGGGHTS and LAMMPS share, read the way they read it: lines continued by a
//! trailing `&`, `#` comments, quoted words, `include`, and variables (`variable NAME equal …`,
//! `index`, `string`, `loop`, `world`, `internal`) substituted as `${NAME}`, `$N` and `$(…)`
//! before a line is split into words. A user's deck is read with it (`millimpact deck`); what
//! only a running simulation knows (a thermo keyword, an atom's position) cannot be resolved
//! and is named with its file and line.
//!
//! The equal-style formulas are evaluated here, not by an expression crate: LAMMPS's grammar
//! has its own precedence (unary minus binds tighter than `^`, and `^` is left-associative, so
//! `-2^2` is 4 and `2^3^2` is 64), its own function names (`ln`, `log` = log10, `PI`) and
//! `v_NAME` references, and every number form `atof` reads (`1.5E+2`).

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use super::deck::{DataFile, DeckError, SourceLine};

/// One command of a script after substitution: its words and where it was written.
#[derive(Clone, Debug, PartialEq)]
pub struct Command {
    /// The file and line (the first line of a continued command).
    pub at: SourceLine,
    /// The words, quotes removed, variables substituted.
    pub words: Vec<String>,
    /// The line as the code reads it (continuations joined, comment cut, variables
    /// substituted): what a transplanted deck writes.
    pub text: String,
}

impl Command {
    /// The command's name (its first word).
    pub fn name(&self) -> &str {
        &self.words[0]
    }

    /// An error at this command's line: `what` it holds that is not `supported`.
    pub(crate) fn refuse(&self, what: impl Into<String>, supported: &str) -> DeckError {
        self.at.refuse(what, supported)
    }

    /// Word `k` (0 is the command), or an error naming the line and what was expected there.
    pub(crate) fn word(&self, k: usize, expected: &str) -> Result<&str, DeckError> {
        self.words.get(k).map(String::as_str).ok_or_else(|| {
            self.at
                .refuse(format!("`{}`: missing {expected}", self.text), expected)
        })
    }

    /// Word `k` read as a number (as `atof` reads it), or an error naming the line.
    pub(crate) fn number(&self, k: usize, what: &str) -> Result<f64, DeckError> {
        let word = self.word(k, what)?;
        parse_number(word).ok_or_else(|| {
            self.at.refuse(
                format!("{what} `{word}` is not a number"),
                "a number, or a variable that resolves to one",
            )
        })
    }
}

/// Refuse a script whose `units` line is not `si` (`code`'s default, `lj`, where it has none).
pub(crate) fn check_si_units(
    units: Option<&Command>,
    path: &Path,
    code: &str,
) -> Result<(), DeckError> {
    match units {
        Some(c) if c.words.get(1).is_some_and(|u| u == "si") => Ok(()),
        Some(c) => Err(c.refuse(
            format!("units {}", c.words.get(1).map_or("", String::as_str)),
            "units si",
        )),
        None => Err(DeckError::Lacking {
            file: path.to_path_buf(),
            what: format!("no `units` line ({code}'s default is lj)"),
            supported: "units si".into(),
        }),
    }
}

/// The script's time step, s, with where it is set; refused where it is missing or not
/// positive.
pub(crate) fn checked_timestep(
    timestep: Option<&(f64, SourceLine)>,
    path: &Path,
) -> Result<(f64, SourceLine), DeckError> {
    let (timestep, timestep_at) = timestep.cloned().ok_or_else(|| DeckError::Lacking {
        file: path.to_path_buf(),
        what: "no timestep".into(),
        supported: "timestep DT (s)".into(),
    })?;
    if timestep.is_nan() || timestep <= 0.0 {
        return Err(timestep_at.refuse(format!("timestep {timestep}"), "a positive time step, s"));
    }
    Ok((timestep, timestep_at))
}

/// A number as LAMMPS's `numeric()` accepts it (no trailing text).
pub(crate) fn parse_number(word: &str) -> Option<f64> {
    word.trim().parse::<f64>().ok().filter(|x| x.is_finite())
}

/// What a variable holds.
#[derive(Clone, Debug, PartialEq)]
enum Variable {
    /// A formula evaluated each time it is used (`equal`), with where it was defined.
    Formula(String, SourceLine),
    /// A text (`index`, `string`, `loop`, `world`, `internal`: the first value).
    Text(String),
    /// A style whose value only the running code knows (`atom`, `vector`, `python`, …), with
    /// where it was defined: left alone until a line the check reads uses it.
    Running(String, SourceLine),
}

/// The simulation box as `create_box` makes it from a `block` region: `xlo xhi ylo yhi zlo
/// zhi`, m.
type SimulationBox = [f64; 6];

/// A line that could not be read, with the number of commands read before it.
pub(crate) type Unread = (usize, DeckError);

/// Reads a script and its includes.
#[derive(Debug, Default)]
pub struct ScriptReader {
    variables: HashMap<String, Variable>,
    /// Each variable's style and where it was defined (`None`: on the command line).
    styles: HashMap<String, (String, Option<SourceLine>)>,
    /// The code's name and the formula functions it lacks (see [`ScriptReader::read_for`]).
    lacking: (&'static str, &'static [&'static str]),
    commands: Vec<Command>,
    depth: usize,
    /// Whether `variable` lines are kept among the commands (a whole deck written out again
    /// needs them: `v_NAME` references are resolved by the code at run time).
    keep_variables: bool,
    /// Whether a line that cannot be read is kept in `errors` and the reading goes on (so
    /// that one pass names every such line), rather than ending the reading.
    go_on: bool,
    /// The lines that could not be read, each with the number of commands read before it.
    errors: Vec<Unread>,
    /// The `block` regions defined so far, by ID.
    regions: HashMap<String, SimulationBox>,
    /// The box once `create_box` has made it from a block region (its bounds are what
    /// `xlo` … `zhi` give a formula from then on).
    simulation_box: Option<SimulationBox>,
}

/// Most nested includes followed (a file that includes itself stops here).
const MAX_INCLUDE_DEPTH: usize = 16;

/// The variable styles a deck may use.
const SUPPORTED_STYLES: &str = "variable styles equal, index, string, loop, world, internal";

impl ScriptReader {
    /// Read `path` with the variables `preset` defined first (as `-var NAME VALUE` on the
    /// command line defines them), following `include`s.
    pub fn read(path: &Path, preset: &[(String, String)]) -> Result<Vec<Command>, DeckError> {
        Self::read_for(path, preset, ("", &[]))
    }

    /// [`ScriptReader::read`] for a code (its name) that lacks some formula functions (the
    /// 2021 LAMMPS and LIGGGHTS 3.8 have no `ternary()`): a formula that calls one is refused,
    /// as the code stops at it.
    pub(crate) fn read_for(
        path: &Path,
        preset: &[(String, String)],
        lacking: (&'static str, &'static [&'static str]),
    ) -> Result<Vec<Command>, DeckError> {
        let mut reader = ScriptReader {
            lacking,
            ..ScriptReader::default()
        };
        reader.preset(preset);
        reader.file(path)?;
        Ok(reader.commands)
    }

    /// [`ScriptReader::read_for`] that reads on past a line it cannot read: the commands
    /// read, and each line that could not be, with the number of commands read before it
    /// (where it stands among them). Only a deck that cannot be opened ends the reading.
    pub(crate) fn read_each(
        path: &Path,
        preset: &[(String, String)],
        lacking: (&'static str, &'static [&'static str]),
    ) -> Result<(Vec<Command>, Vec<Unread>), DeckError> {
        let mut reader = ScriptReader {
            lacking,
            go_on: true,
            ..ScriptReader::default()
        };
        reader.preset(preset);
        reader.file(path)?;
        Ok((reader.commands, reader.errors))
    }

    /// Define the variables `preset` as `-var NAME VALUE` on the command line defines them.
    fn preset(&mut self, preset: &[(String, String)]) {
        for (name, value) in preset {
            self.variables
                .insert(name.clone(), Variable::Text(value.clone()));
            // `-var` makes an index-style variable.
            self.styles.insert(name.clone(), ("index".into(), None));
        }
    }

    /// [`ScriptReader::read_for`] keeping the `variable` lines among the commands (with their
    /// `${…}` substituted as the code substitutes them when it reads the line), so that the
    /// commands written out in order are the deck the code reads.
    pub(crate) fn read_whole(
        path: &Path,
        lacking: (&'static str, &'static [&'static str]),
    ) -> Result<Vec<Command>, DeckError> {
        let mut reader = ScriptReader {
            lacking,
            keep_variables: true,
            ..ScriptReader::default()
        };
        reader.file(path)?;
        Ok(reader.commands)
    }

    fn file(&mut self, path: &Path) -> Result<(), DeckError> {
        let text = std::fs::read_to_string(path).map_err(|source| DeckError::Read {
            path: path.to_path_buf(),
            source,
        })?;
        let mut pending = String::new();
        let mut first_line = 0;
        for (index, raw) in text.lines().enumerate() {
            if pending.is_empty() {
                first_line = index + 1;
            }
            let trimmed = raw.trim_end();
            if let Some(head) = trimmed.strip_suffix('&') {
                pending.push_str(head);
                pending.push(' ');
                continue;
            }
            pending.push_str(trimmed);
            let line = std::mem::take(&mut pending);
            let at = SourceLine {
                file: path.to_path_buf(),
                line: first_line,
            };
            let read = self.line(&line, at, path);
            self.went_on(read)?;
        }
        if !pending.is_empty() {
            let at = SourceLine {
                file: path.to_path_buf(),
                line: first_line,
            };
            let read = self.line(&pending, at, path);
            self.went_on(read)?;
        }
        Ok(())
    }

    /// A line's reading: its error kept where the reading goes on past it, else returned.
    fn went_on(&mut self, read: Result<(), DeckError>) -> Result<(), DeckError> {
        match read {
            Err(e) if self.go_on => {
                self.errors.push((self.commands.len(), e));
                Ok(())
            }
            other => other,
        }
    }

    fn line(&mut self, raw: &str, at: SourceLine, path: &Path) -> Result<(), DeckError> {
        let text = self.substitute(&strip_comment(raw), &at)?;
        let words = split_words(&text, &at)?;
        if words.is_empty() {
            return Ok(());
        }
        match words[0].as_str() {
            "include" => {
                let name = words
                    .get(1)
                    .ok_or_else(|| at.refuse("include without a file", "include FILE"))?;
                if self.depth >= MAX_INCLUDE_DEPTH {
                    return Err(at.refuse(
                        format!("include {name}: more than {MAX_INCLUDE_DEPTH} nested includes"),
                        "includes that end",
                    ));
                }
                let included = resolve_include(path, name);
                // The code stops at an include it cannot open: so does the check, at its line.
                if !included.is_file() {
                    return Err(DeckError::missing(&at, "include", name, &included));
                }
                self.depth += 1;
                let result = self.file(&included);
                self.depth -= 1;
                result
            }
            "variable" => {
                self.define(&words, &at)?;
                if self.keep_variables {
                    self.commands.push(Command {
                        at,
                        words,
                        text: text.trim().to_string(),
                    });
                }
                Ok(())
            }
            _ => {
                self.box_of(&words, path);
                self.commands.push(Command {
                    at,
                    words,
                    text: text.trim().to_string(),
                });
                Ok(())
            }
        }
    }

    /// Keep the bounds a `region ID block …` gives, and the box `create_box N ID` makes of
    /// one: a formula after it may use `xlo` … `zhi`, `lx`, `ly`, `lz`, `vol` as LAMMPS's do.
    fn box_of(&mut self, words: &[String], from: &Path) {
        match (
            words.first().map(String::as_str),
            words.get(2).map(String::as_str),
        ) {
            (Some("region"), Some("block")) if words.len() >= 9 => {
                let bounds: Option<Vec<f64>> =
                    words[3..9].iter().map(|w| parse_number(w)).collect();
                if let Some(b) = bounds.and_then(|b| <[f64; 6]>::try_from(b).ok()) {
                    self.regions.insert(words[1].clone(), b);
                } else {
                    self.regions.remove(&words[1]);
                }
            }
            (Some("create_box"), Some(region)) => {
                self.simulation_box = self.regions.get(region).copied();
            }
            (Some("read_data"), _) => {
                if let Some(name) = words.get(1) {
                    let file = resolve_include(from, name);
                    if let Some(b) = DataFile::header_box(&file) {
                        self.simulation_box = Some(b);
                    }
                }
            }
            _ => {}
        }
    }

    fn define(&mut self, words: &[String], at: &SourceLine) -> Result<(), DeckError> {
        let (Some(name), Some(style)) = (words.get(1), words.get(2)) else {
            return Err(at.refuse("variable without a name and style", SUPPORTED_STYLES));
        };
        let values = &words[3..];
        let first = || {
            values.first().cloned().ok_or_else(|| {
                at.refuse(
                    format!("variable {name} {style} without a value"),
                    SUPPORTED_STYLES,
                )
            })
        };
        if self.refuse_restyling(name, style, at)? {
            return Ok(());
        }
        match style.as_str() {
            "delete" => {
                self.variables.remove(name);
                self.styles.remove(name);
            }
            // Defined once: a second definition is ignored (as LAMMPS does, so that `-var`
            // on the command line wins).
            "index" | "loop" | "world" | "universe" | "uloop" => {
                if !self.variables.contains_key(name) {
                    let value = if style == "loop" && values.len() == 1 {
                        "1".to_string()
                    } else {
                        first()?
                    };
                    self.variables.insert(name.clone(), Variable::Text(value));
                }
            }
            "string" | "internal" => {
                let value = first()?;
                self.variables.insert(name.clone(), Variable::Text(value));
            }
            "equal" => {
                let formula = values.join(" ");
                if formula.is_empty() {
                    return Err(at.refuse(
                        format!("variable {name} equal without a formula"),
                        SUPPORTED_STYLES,
                    ));
                }
                self.variables
                    .insert(name.clone(), Variable::Formula(formula, at.clone()));
            }
            // A value only the running code knows: refused where a line the check reads
            // uses it, not here (a deck that only watches its charge through it is read).
            other => {
                self.variables.insert(
                    name.clone(),
                    Variable::Running(other.to_string(), at.clone()),
                );
            }
        }
        if style != "delete" {
            self.styles
                .entry(name.clone())
                .or_insert_with(|| (style.clone(), Some(at.clone())));
        }
        Ok(())
    }

    /// LAMMPS and LIGGGHTS ignore a second definition of a variable in the styles that keep
    /// their first (`index`, `loop`, `world`, `universe`, `uloop`, `file`, `format`: so that
    /// `-var` wins), and stop at one in another style unless the variable already has it
    /// ("Cannot redefine variable as a different style"): `-var` makes an index variable, so
    /// `--var dt=…` on a deck's `variable dt equal …` stops the code.
    /// Whether the definition is ignored (the variable exists and the style keeps the first).
    fn refuse_restyling(
        &self,
        name: &str,
        style: &str,
        at: &SourceLine,
    ) -> Result<bool, DeckError> {
        const KEEP_FIRST: [&str; 7] = [
            "index", "loop", "world", "universe", "uloop", "file", "format",
        ];
        let Some((first, defined)) = self.styles.get(name) else {
            return Ok(false);
        };
        if KEEP_FIRST.contains(&style) {
            return Ok(true);
        }
        if first == style || style == "delete" {
            return Ok(false);
        }
        let (what, supported) = match defined {
            None => {
                let value = match self.variables.get(name) {
                    Some(Variable::Text(text)) => text.clone(),
                    _ => String::new(),
                };
                (
                    format!(
                        "variable {name} {style}: --var {name}={value} made `{name}` an index variable (as -var does), and LIGGGHTS and LAMMPS stop at this line (\"Cannot redefine variable as a different style\")"
                    ),
                    format!(
                        "--var only for a variable the deck defines as `variable {name} index …` (or does not define): change this line to `variable {name} index VALUE`, or leave out --var {name} and edit the value here"
                    ),
                )
            }
            Some(line) => (
                format!(
                    "variable {name} {style}: `{name}` is already a {first} variable ({line}), and LIGGGHTS and LAMMPS stop at this line (\"Cannot redefine variable as a different style\")"
                ),
                format!(
                    "a variable redefined in its own style ({first}), or `variable {name} delete` before it"
                ),
            ),
        };
        Err(at.refuse(what, &supported))
    }

    /// The text of variable `name`, used at `at`: a formula evaluated now, written to 15
    /// significant digits as `${NAME}` writes it.
    fn value(&self, name: &str, at: &SourceLine) -> Result<String, DeckError> {
        match self.variables.get(name) {
            Some(Variable::Text(text)) => Ok(text.clone()),
            Some(Variable::Formula(..)) => Ok(fifteen_digits(self.evaluate_variable(name, at, 0)?)),
            Some(Variable::Running(style, defined)) => Err(running(name, style, defined, at)),
            None => Err(at.refuse(
                format!("variable `{name}` is not defined"),
                "variables defined in the deck before their use, or given with --var NAME=VALUE",
            )),
        }
    }

    fn evaluate_variable(
        &self,
        name: &str,
        at: &SourceLine,
        depth: usize,
    ) -> Result<f64, DeckError> {
        if depth > 64 {
            return Err(at.refuse(
                format!("variable `{name}` refers to itself"),
                "variables that resolve to numbers",
            ));
        }
        match self.variables.get(name) {
            Some(Variable::Formula(formula, _)) => {
                let lookup = |v: &str| self.evaluate_variable(v, at, depth + 1);
                Expression::new(formula, at, &lookup)
                    .lacking(self.lacking)
                    .in_box(self.simulation_box)
                    .evaluate()
            }
            Some(Variable::Running(style, defined)) => Err(running(name, style, defined, at)),
            Some(Variable::Text(text)) => parse_number(text).ok_or_else(|| {
                at.refuse(
                    format!("variable `{name}` = `{text}` is not a number"),
                    "numeric variables in formulas",
                )
            }),
            None => Err(at.refuse(
                format!("variable `{name}` is not defined"),
                "variables defined in the deck before their use, or given with --var NAME=VALUE",
            )),
        }
    }

    /// Replace `${NAME}`, `$N` (one character) and `$(formula)` outside quotes.
    fn substitute(&self, line: &str, at: &SourceLine) -> Result<String, DeckError> {
        let mut out = String::with_capacity(line.len());
        let chars: Vec<char> = line.chars().collect();
        let (mut single, mut double) = (false, false);
        let mut i = 0;
        while i < chars.len() {
            let c = chars[i];
            if c == '$' && !single && !double && i + 1 < chars.len() {
                let (value, next) = match chars[i + 1] {
                    '{' => {
                        let end = find(&chars, i + 2, '}')
                            .ok_or_else(|| at.refuse("`${` without `}`", "${NAME}"))?;
                        let name: String = chars[i + 2..end].iter().collect();
                        (self.value(&name, at)?, end + 1)
                    }
                    '(' => {
                        let end = matching_paren(&chars, i + 1)
                            .ok_or_else(|| at.refuse("`$(` without `)`", "$(formula)"))?;
                        let inner: String = chars[i + 2..end].iter().collect();
                        // `$(formula:format)`: the format only changes how it is written.
                        let formula = inner.split(':').next().unwrap_or_default();
                        let lookup = |v: &str| self.evaluate_variable(v, at, 1);
                        let x = Expression::new(formula, at, &lookup)
                            .lacking(self.lacking)
                            .in_box(self.simulation_box)
                            .evaluate()?;
                        (printf_g(x, 20), end + 1)
                    }
                    name => (self.value(&name.to_string(), at)?, i + 2),
                };
                out.push_str(&value);
                i = next;
                continue;
            }
            if c == '"' && !single {
                double = !double;
            } else if c == '\'' && !double {
                single = !single;
            }
            out.push(c);
            i += 1;
        }
        Ok(out)
    }
}

fn find(chars: &[char], from: usize, c: char) -> Option<usize> {
    (from..chars.len()).find(|&k| chars[k] == c)
}

fn matching_paren(chars: &[char], open: usize) -> Option<usize> {
    let mut depth = 0;
    for (k, &c) in chars.iter().enumerate().skip(open) {
        match c {
            '(' => depth += 1,
            ')' => {
                depth -= 1;
                if depth == 0 {
                    return Some(k);
                }
            }
            _ => {}
        }
    }
    None
}

/// The error of a variable of a running-only style used where the check must know its value.
fn running(name: &str, style: &str, defined: &SourceLine, at: &SourceLine) -> DeckError {
    at.refuse(
        format!(
            "variable {name} ({style}, {defined}): a style whose value only the running code knows, used where the check needs a number"
        ),
        SUPPORTED_STYLES,
    )
}

/// An included file: relative names are found beside the including file (where the user runs
/// the deck from, in the usual layout).
fn resolve_include(from: &Path, name: &str) -> PathBuf {
    let path = Path::new(name);
    if path.is_absolute() {
        path.to_path_buf()
    } else {
        from.parent().unwrap_or(Path::new(".")).join(path)
    }
}

/// The line up to a `#` outside quotes.
fn strip_comment(line: &str) -> String {
    let (mut single, mut double) = (false, false);
    for (k, c) in line.char_indices() {
        match c {
            '"' if !single => double = !double,
            '\'' if !double => single = !single,
            '#' if !single && !double => return line[..k].to_string(),
            _ => {}
        }
    }
    line.to_string()
}

/// Split a line into words; a quoted span (single, double or triple quotes) is one word.
fn split_words(line: &str, at: &SourceLine) -> Result<Vec<String>, DeckError> {
    let mut words = Vec::new();
    let mut rest = line.trim_start();
    while !rest.is_empty() {
        let (word, tail) = if let Some(inner) = rest.strip_prefix("\"\"\"") {
            let end = inner.find("\"\"\"").ok_or_else(|| unclosed(at))?;
            (inner[..end].to_string(), &inner[end + 3..])
        } else if let Some(quote) = rest.chars().next().filter(|c| *c == '"' || *c == '\'') {
            let inner = &rest[1..];
            let end = inner.find(quote).ok_or_else(|| unclosed(at))?;
            (inner[..end].to_string(), &inner[end + 1..])
        } else {
            let end = rest.find(char::is_whitespace).unwrap_or(rest.len());
            (rest[..end].to_string(), &rest[end..])
        };
        words.push(word);
        rest = tail.trim_start();
    }
    Ok(words)
}

fn unclosed(at: &SourceLine) -> DeckError {
    at.refuse(
        "a quote that is not closed",
        "quoted words closed on their line",
    )
}

/// A value as C's `printf("%.{precision}g")` writes it: `precision` significant digits, in
/// fixed notation unless the exponent is below −4 or at least `precision`, trailing zeros left
/// out. What the codes write for `${NAME}` (`%.15g`) and `$(formula)` (`%.20g`), and so what
/// they read back: a `run ${n}` of 150000 is `run 150000`, where `1.5e5` would run one step.
pub(crate) fn printf_g(x: f64, precision: usize) -> String {
    if !x.is_finite() {
        return if x.is_nan() {
            "nan".into()
        } else if x > 0.0 {
            "inf".into()
        } else {
            "-inf".into()
        };
    }
    let precision = precision.max(1);
    let scientific = format!("{x:.*e}", precision - 1);
    let Some((mantissa, exponent)) = scientific.split_once('e') else {
        return scientific;
    };
    let exponent: i64 = exponent.parse().unwrap_or(0);
    let trim = |digits: &str| -> String {
        if digits.contains('.') {
            digits
                .trim_end_matches('0')
                .trim_end_matches('.')
                .to_string()
        } else {
            digits.to_string()
        }
    };
    let limit = i64::try_from(precision).unwrap_or(i64::MAX);
    if exponent < -4 || exponent >= limit {
        let sign = if exponent < 0 { '-' } else { '+' };
        format!("{}e{sign}{:02}", trim(mantissa), exponent.abs())
    } else {
        // At most `precision` + 4 decimals here.
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let decimals = (limit - 1 - exponent) as usize;
        trim(&format!("{x:.decimals$}"))
    }
}

/// A value as `${NAME}` of an equal-style variable writes it (`%.15g`).
pub(crate) fn fifteen_digits(x: f64) -> String {
    printf_g(x, 15)
}

/// The names a formula may call, with their argument counts.
const FUNCTIONS: &str = "sqrt, exp, ln, log, abs, sin, cos, tan, asin, acos, atan, atan2, ceil, floor, round, ternary (LAMMPS from 2022)";

/// What a formula may hold.
const FORMULA_SUPPORTED: &str = "numbers, PI, v_NAME of numeric variables, ( ), unary - and !, ^, * / %, + -, < <= > >= == !=, && ||, and sqrt, exp, ln, log, abs, sin, cos, tan, asin, acos, atan, atan2, ceil, floor, round, ternary (LAMMPS from 2022)";

/// A formula of an equal-style variable, evaluated by precedence climbing with LAMMPS's
/// precedences (`||` 1, `&&` 2, `== !=` 3, `< <= > >=` 4, `+ -` 5, `* / %` 6, `^` 7, unary 8,
/// every binary operator left-associative).
struct Expression<'a> {
    chars: Vec<char>,
    at: usize,
    text: &'a str,
    line: &'a SourceLine,
    lookup: &'a dyn Fn(&str) -> Result<f64, DeckError>,
    lacking: (&'static str, &'static [&'static str]),
    simulation_box: Option<SimulationBox>,
}

impl<'a> Expression<'a> {
    fn new(
        text: &'a str,
        line: &'a SourceLine,
        lookup: &'a dyn Fn(&str) -> Result<f64, DeckError>,
    ) -> Self {
        Expression {
            chars: text.chars().collect(),
            at: 0,
            text,
            line,
            lookup,
            lacking: ("", &[]),
            simulation_box: None,
        }
    }

    /// The box's bounds, where `create_box` has made it.
    fn in_box(mut self, simulation_box: Option<SimulationBox>) -> Self {
        self.simulation_box = simulation_box;
        self
    }

    /// A thermo keyword of the box (`xlo` … `zhi`, `lx`, `ly`, `lz`, `vol`), once it is made.
    fn box_keyword(&self, name: &str) -> Option<f64> {
        let [xlo, xhi, ylo, yhi, zlo, zhi] = self.simulation_box?;
        Some(match name {
            "xlo" => xlo,
            "xhi" => xhi,
            "ylo" => ylo,
            "yhi" => yhi,
            "zlo" => zlo,
            "zhi" => zhi,
            "lx" => xhi - xlo,
            "ly" => yhi - ylo,
            "lz" => zhi - zlo,
            "vol" => (xhi - xlo) * (yhi - ylo) * (zhi - zlo),
            _ => return None,
        })
    }

    /// The code (its name) lacks these functions.
    fn lacking(mut self, lacking: (&'static str, &'static [&'static str])) -> Self {
        self.lacking = lacking;
        self
    }

    fn evaluate(mut self) -> Result<f64, DeckError> {
        let value = self.binary(1)?;
        self.skip_space();
        if self.at < self.chars.len() {
            return Err(self.fail(format!(
                "cannot read `{}` in `{}`",
                self.chars[self.at..].iter().collect::<String>(),
                self.text
            )));
        }
        Ok(value)
    }

    fn fail(&self, what: String) -> DeckError {
        self.line.refuse(what, FORMULA_SUPPORTED)
    }

    fn skip_space(&mut self) {
        while self.at < self.chars.len() && self.chars[self.at].is_whitespace() {
            self.at += 1;
        }
    }

    fn peek_operator(&mut self) -> Option<(&'static str, u8)> {
        self.skip_space();
        let rest: String = self.chars[self.at..].iter().take(2).collect();
        const OPERATORS: [(&str, u8); 14] = [
            ("||", 1),
            ("&&", 2),
            ("==", 3),
            ("!=", 3),
            ("<=", 4),
            (">=", 4),
            ("<", 4),
            (">", 4),
            ("+", 5),
            ("-", 5),
            ("*", 6),
            ("/", 6),
            ("%", 6),
            ("^", 7),
        ];
        OPERATORS.into_iter().find(|(op, _)| rest.starts_with(op))
    }

    fn binary(&mut self, min: u8) -> Result<f64, DeckError> {
        let mut left = self.unary()?;
        while let Some((op, precedence)) = self.peek_operator() {
            if precedence < min {
                break;
            }
            self.at += op.len();
            let right = self.binary(precedence + 1)?;
            left = self.apply(op, left, right)?;
        }
        Ok(left)
    }

    fn apply(&self, op: &str, a: f64, b: f64) -> Result<f64, DeckError> {
        let truth = |x: bool| if x { 1.0 } else { 0.0 };
        Ok(match op {
            "||" => truth(a != 0.0 || b != 0.0),
            "&&" => truth(a != 0.0 && b != 0.0),
            "==" => truth((a - b).abs() == 0.0),
            "!=" => truth((a - b).abs() != 0.0),
            "<=" => truth(a <= b),
            ">=" => truth(a >= b),
            "<" => truth(a < b),
            ">" => truth(a > b),
            "+" => a + b,
            "-" => a - b,
            "*" => a * b,
            "/" if b == 0.0 => return Err(self.fail(format!("divide by zero in `{}`", self.text))),
            "/" => a / b,
            "%" if b == 0.0 => return Err(self.fail(format!("modulo zero in `{}`", self.text))),
            "%" => a % b,
            // LAMMPS: x^0 is 1 whatever x.
            "^" if b == 0.0 => 1.0,
            "^" => a.powf(b),
            _ => unreachable!("an operator of the table"),
        })
    }

    fn unary(&mut self) -> Result<f64, DeckError> {
        self.skip_space();
        match self.chars.get(self.at) {
            Some('-') => {
                self.at += 1;
                Ok(-self.unary()?)
            }
            Some('!') if self.chars.get(self.at + 1) != Some(&'=') => {
                self.at += 1;
                Ok(if self.unary()? == 0.0 { 1.0 } else { 0.0 })
            }
            _ => self.primary(),
        }
    }

    fn primary(&mut self) -> Result<f64, DeckError> {
        self.skip_space();
        let Some(&c) = self.chars.get(self.at) else {
            return Err(self.fail(format!("`{}` ends where a value is expected", self.text)));
        };
        if c == '(' {
            self.at += 1;
            let value = self.binary(1)?;
            self.skip_space();
            if self.chars.get(self.at) != Some(&')') {
                return Err(self.fail(format!("unbalanced parentheses in `{}`", self.text)));
            }
            self.at += 1;
            return Ok(value);
        }
        if c.is_ascii_digit() || c == '.' {
            return self.number();
        }
        if c.is_ascii_alphabetic() || c == '_' {
            let start = self.at;
            while self.at < self.chars.len()
                && (self.chars[self.at].is_ascii_alphanumeric() || self.chars[self.at] == '_')
            {
                self.at += 1;
            }
            let name: String = self.chars[start..self.at].iter().collect();
            self.skip_space();
            if self.chars.get(self.at) == Some(&'(') {
                return self.call(&name);
            }
            if self.chars.get(self.at) == Some(&'[') {
                return Err(self.fail(format!(
                    "`{name}[…]` in `{}` is a value only the running code knows",
                    self.text
                )));
            }
            if name == "PI" {
                return Ok(std::f64::consts::PI);
            }
            if let Some(variable) = name.strip_prefix("v_") {
                return (self.lookup)(variable);
            }
            if let Some(value) = self.box_keyword(&name) {
                return Ok(value);
            }
            return Err(self.fail(format!(
                "`{name}` in `{}` is a thermo keyword or a name this reader does not know: a value only the running code knows",
                self.text
            )));
        }
        Err(self.fail(format!("unexpected `{c}` in `{}`", self.text)))
    }

    fn number(&mut self) -> Result<f64, DeckError> {
        let start = self.at;
        let digits = |s: &mut Self| {
            while s.at < s.chars.len() && s.chars[s.at].is_ascii_digit() {
                s.at += 1;
            }
        };
        digits(self);
        if self.chars.get(self.at) == Some(&'.') {
            self.at += 1;
            digits(self);
        }
        if matches!(self.chars.get(self.at), Some('e' | 'E')) {
            let mark = self.at;
            self.at += 1;
            if matches!(self.chars.get(self.at), Some('+' | '-')) {
                self.at += 1;
            }
            let before = self.at;
            digits(self);
            if before == self.at {
                self.at = mark;
            }
        }
        let text: String = self.chars[start..self.at].iter().collect();
        text.parse()
            .map_err(|_| self.fail(format!("`{text}` in `{}` is not a number", self.text)))
    }

    fn call(&mut self, name: &str) -> Result<f64, DeckError> {
        // The functions of one argument, by name (`ln` is e-based, `log` 10-based).
        type OneArgument = fn(f64) -> f64;
        const ONE: [(&str, OneArgument); 14] = [
            ("sqrt", f64::sqrt),
            ("exp", f64::exp),
            ("ln", f64::ln),
            ("log", f64::log10),
            ("abs", f64::abs),
            ("sin", f64::sin),
            ("cos", f64::cos),
            ("tan", f64::tan),
            ("asin", f64::asin),
            ("acos", f64::acos),
            ("atan", f64::atan),
            ("ceil", f64::ceil),
            ("floor", f64::floor),
            ("round", f64::round),
        ];
        let one = ONE
            .iter()
            .find(|(known, _)| *known == name)
            .map(|&(_, f)| f);
        if name == "min" || name == "max" {
            // Not the smaller of two numbers: LAMMPS and LIGGGHTS stop at `min(3,4)` ("Invalid
            // special function").
            return Err(self.fail(format!(
                "`{name}()` in `{}`: in LAMMPS and LIGGGHTS {name}() reduces a compute's, fix's or vector variable's values, a value only the running code knows (the codes stop at {name} of numbers: \"Invalid special function\")",
                self.text
            )));
        }
        let (code, lacks) = self.lacking;
        if lacks.contains(&name) {
            return Err(self.fail(format!(
                "`{name}()` in `{}`: {code} has no such function (it stops: \"Invalid math/group/special function\")",
                self.text
            )));
        }
        if one.is_none() && name != "atan2" && name != "ternary" {
            return Err(self.fail(format!(
                "`{name}()` in `{}`: a function this reader does not evaluate (one of {FUNCTIONS} is)",
                self.text
            )));
        }
        // At the opening parenthesis.
        self.at += 1;
        let mut args = Vec::new();
        loop {
            args.push(self.binary(1)?);
            self.skip_space();
            match self.chars.get(self.at) {
                Some(',') => self.at += 1,
                Some(')') => {
                    self.at += 1;
                    break;
                }
                _ => return Err(self.fail(format!("unbalanced parentheses in `{}`", self.text))),
            }
        }
        let value = match (one, name, &args[..]) {
            (Some(f), _, [x]) => f(*x),
            (Some(_), ..) => {
                return Err(self.fail(format!("{name}() takes one argument in `{}`", self.text)));
            }
            (_, "atan2", [y, x]) => y.atan2(*x),
            (_, "atan2", _) => {
                return Err(self.fail(format!("{name}() takes two arguments in `{}`", self.text)));
            }
            // `ternary`, the one function left.
            (_, _, [c, a, b]) => {
                if *c != 0.0 {
                    *a
                } else {
                    *b
                }
            }
            _ => {
                return Err(self.fail(format!(
                    "ternary() takes three arguments in `{}`",
                    self.text
                )));
            }
        };
        if value.is_finite() {
            Ok(value)
        } else {
            Err(self.fail(format!("`{}` is not a finite number", self.text)))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn eval(text: &str) -> Result<f64, DeckError> {
        let at = SourceLine {
            file: "in".into(),
            line: 1,
        };
        let lookup = |name: &str| match name {
            "r" => Ok(0.5),
            _ => Err(at.refuse(format!("no {name}"), "")),
        };
        Expression::new(text, &at, &lookup).evaluate()
    }

    // Each formula's value is exact in binary floating point.
    #[allow(clippy::float_cmp)]
    #[test]
    fn formulas_follow_lammps_precedence() {
        assert_eq!(eval("-2^2").unwrap(), 4.0);
        assert_eq!(eval("2^3^2").unwrap(), 64.0);
        assert_eq!(eval("1 + 2*3 - 4/2").unwrap(), 5.0);
        assert_eq!(eval("1.5E+2 * 2e-1").unwrap(), 30.0);
        assert_eq!(eval("2*v_r").unwrap(), 1.0);
        assert_eq!(eval("ternary(1 > 2, 3, 4) + (1 == 1) + !0").unwrap(), 6.0);
        assert_eq!(eval("sqrt(16) + log(100) + abs(-1)").unwrap(), 7.0);
        assert_eq!(eval("0^0").unwrap(), 1.0);
        assert_eq!(eval("7 % 4 && 1").unwrap(), 1.0);
    }

    #[test]
    fn formulas_with_running_values_are_refused() {
        for (text, word) in [
            ("step*2", "step"),
            ("x[1]", "x[…]"),
            ("count(all)", "count()"),
            ("1/0", "divide by zero"),
            ("(1+2", "unbalanced"),
            ("v_nope", "no nope"),
            ("min(3,4)", "min() reduces a compute's"),
            ("max(1,2)", "max() reduces a compute's"),
        ] {
            let e = eval(text).unwrap_err().to_string();
            assert!(e.contains(word) && e.starts_with("in:1:"), "{text}: {e}");
        }
    }

    #[test]
    fn fifteen_digits_reads_back_as_lammps_writes_it() {
        let third = 1.0 / 3.0;
        let x: f64 = fifteen_digits(third).parse().unwrap();
        assert!((x - third).abs() < 1e-15 && (x - third).abs() > 0.0);
        assert_eq!(fifteen_digits(2e11), "200000000000");
        assert_eq!(fifteen_digits(0.25), "0.25");
        // A step count stays a whole number in digits (LIGGGHTS runs `1.5e5` as one step).
        assert_eq!(fifteen_digits(0.15 / 1e-6), "150000");
        assert_eq!(fifteen_digits(1e15), "1e+15");
        assert_eq!(fifteen_digits(123456789012345.0), "123456789012345");
        assert_eq!(fifteen_digits(-2.5e-5), "-2.5e-05");
        assert_eq!(fifteen_digits(1e-4), "0.0001");
        assert_eq!(fifteen_digits(0.0), "0");
        // Rounding that carries into the next power of ten changes the notation, as in C.
        assert_eq!(fifteen_digits(999_999_999_999_999.9), "1e+15");
        assert_eq!(printf_g(0.1, 20), "0.10000000000000000555");
        assert_eq!(printf_g(150000.0, 20), "150000");
    }

    #[test]
    fn words_comments_and_quotes_are_split_as_the_codes_split_them() {
        let at = SourceLine {
            file: "in".into(),
            line: 3,
        };
        assert_eq!(
            strip_comment("fix a all print \"#x\" # note"),
            "fix a all print \"#x\" "
        );
        let words = split_words("print \"a b\" 'c d' \"\"\"e \"f\" g\"\"\" h", &at).unwrap();
        assert_eq!(words, ["print", "a b", "c d", "e \"f\" g", "h"]);
        assert!(split_words("print \"a", &at).is_err());
    }
}
